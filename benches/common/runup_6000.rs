//! The skidding benches' scene: `examples/scenes/7008ce-runup.toml` started at 6000 rpm
//! (a fresh component at that speed starts at the kinematic speeds). A bench mounts it
//! with `#[path = "common/runup_6000.rs"] mod runup_6000;`.

/// The scene text.
pub fn scene() -> String {
    let text = include_str!("../../examples/scenes/7008ce-runup.toml");
    let omega = 6000.0 * std::f64::consts::PI / 30.0;
    text.replace(
        "\"shaft.omega\" = 0.0",
        &format!("\"shaft.omega\" = {omega}"),
    )
}
