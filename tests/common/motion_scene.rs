//! A motion-driven scene for the integration tests of the skidding and full levels.
//! Mount with `#[path = "common/motion_scene.rs"] mod motion_scene;`.

/// A motion-driven scene of `bearing` at `level`: shaft displacement `q` (x, y, z m; rx, ry
/// rad), shaft speed `omega` (rad/s), no shaft velocity, solver rtol 1e-5 and atol 1e-9 m,
/// input rule `derivatives`; `extra` are lines of the `[model.<level>]` table.
pub fn motion_scene(bearing: &str, level: &str, q: [f64; 5], omega: f64, extra: &str) -> String {
    let rpm = omega * 30.0 / std::f64::consts::PI;
    format!(
        r#"
bearing = "{bearing}"
[model]
level = "{level}"
[model.{level}]
{extra}
[solver]
rtol = 1e-5
atol_m = 1e-9
[inputs]
rule = "derivatives"
speed_rpm = {rpm:e}
initial = {{ "shaft.x" = {:e}, "shaft.y" = {:e}, "shaft.z" = {:e}, "shaft.rx" = {:e}, "shaft.ry" = {:e},
            "shaft.vx" = 0.0, "shaft.vy" = 0.0, "shaft.vz" = 0.0, "shaft.wx" = 0.0, "shaft.wy" = 0.0 }}
"#,
        q[0], q[1], q[2], q[3], q[4]
    )
}
