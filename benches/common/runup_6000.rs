//! The skidding benches' scene: `examples/scenes/7008ce-runup.toml` started at 6000 rpm
//! (a fresh component at that speed starts at the kinematic speeds). A bench mounts it
//! with `#[path = "common/runup_6000.rs"] mod runup_6000;`.

/// The scene text.
pub fn scene() -> String {
    let text = include_str!("../../examples/scenes/7008ce-runup.toml");
    text.replace("speed_rpm = 0.0", "speed_rpm = 6000.0")
}
