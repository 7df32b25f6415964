//! The skidding level (physics.md §5.2) through the component and the model API.

use raceway::component::{variables, Component};

fn vr(name: &str) -> u32 {
    variables::by_name(name).unwrap().vr
}

#[test]
#[ignore]
fn explore() {
    let text = std::fs::read_to_string("examples/scenes/6012-skidding.toml").unwrap();
    let mut c = Component::from_text(&text).unwrap();
    let h = 1e-3;
    for i in 0..200 {
        c.do_step(i as f64 * h, h).unwrap();
        if i % 10 == 9 {
            println!(
                "t {:.3} fy {:.1} cage {:.3} slip {:.4} torque {:.4e} loaded {} stats {:?}",
                c.time(),
                c.get_real(vr("force.y")).unwrap(),
                c.get_real(vr("cage.omega")).unwrap(),
                c.get_real(vr("cage.slip")).unwrap(),
                c.get_real(vr("torque.z")).unwrap(),
                c.get_real(vr("balls.loaded")).unwrap(),
                c.stats()
            );
        }
    }
}
