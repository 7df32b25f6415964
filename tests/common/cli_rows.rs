//! The force of the default scene's first two rows of `raceway run` (t = 0 and t = one
//! step of 1e-4 s), the reference of the unset-inputs test on every face.

/// `[[force.x, force.y] at t = 0, at t = 1e-4 s]` from `raceway run`'s series.csv.
pub fn default_scene_first_rows() -> [[f64; 2]; 2] {
    let dir = std::env::temp_dir().join(format!(
        "raceway-first-rows-{}-{:?}",
        std::process::id(),
        std::thread::current().id()
    ));
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_raceway"))
        .args(["run", "-q", "--duration", "0.0002", "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let csv = std::fs::read_to_string(dir.join("series.csv")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let mut lines = csv.lines();
    let head: Vec<&str> = lines.next().unwrap().split(',').collect();
    let col = |name: &str| head.iter().position(|h| *h == name).unwrap();
    let (t, fx, fy) = (col("t [s]"), col("force.x [N]"), col("force.y [N]"));
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!((rows[0][t], rows[1][t]), (0.0, 1e-4));
    [[rows[0][fx], rows[0][fy]], [rows[1][fx], rows[1][fy]]]
}
