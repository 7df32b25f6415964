//! series.csv carries the outputs a run's level and effects set (issue #40, item 4): the
//! registry's claim (`levels::outputs_set`, the groups tagged in the variable table) is
//! checked against what each level really writes. Every shipped scene steps a few times and
//! every output left out of its series must hold the value no level sets: 0 (the cage's
//! speed ratio 1 - slip: 1, the cage running at its kinematic speed).

use raceway::component::variables::{self, Role};
use raceway::component::Scene;
use raceway::runner::{self, Record};

#[test]
fn outputs_left_out_of_a_series_are_never_set_by_its_level() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/scenes");
    let mut files: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    assert!(files.len() >= 20);
    let mut left_out = 0;
    for path in &files {
        let scene = Scene::from_text(&std::fs::read_to_string(path).unwrap()).unwrap();
        let kept: Vec<&str> = runner::recorded(&scene, Record::default())
            .iter()
            .map(|v| v.name)
            .collect();
        let mut c = runner::prepare(&scene).unwrap();
        let h = scene.run.step_s;
        for i in 0..3 {
            c.do_step(i as f64 * h, h)
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            for v in variables::SCALARS {
                if v.role != Role::Output || kept.contains(&v.name) {
                    continue;
                }
                left_out += 1;
                let unset = if v.name == "cage.speed_ratio" {
                    1.0
                } else {
                    0.0
                };
                let x = c.get_real(v.vr).unwrap();
                assert_eq!(
                    x,
                    unset,
                    "{}: {} = {x} is set by level {} but left out of its series",
                    path.display(),
                    v.name,
                    scene.model.level.name()
                );
            }
        }
    }
    assert!(left_out > 100, "{left_out}");
}
