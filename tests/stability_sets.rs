//! The stability campaign's set cells (heavy preload, lift-off under axial load, high
//! speed; quasi-static and ring levels): each gives finite outputs that converge under
//! refinement or a clean error, never a panic or a NaN; the lift-off cell does lift a row
//! off and the heavy-preload cell carries its preload.

use raceway::component::variables::by_name;
use raceway::report::stability::{sets, Outcome};
use raceway::Component;

#[test]
fn set_cells_are_finite_or_clean_errors() {
    let res = sets::run(0.002, false);
    assert_eq!(res.len(), sets::cells().len());
    for (c, o) in &res {
        assert!(o.passed(), "{}: {o:?}", c.name);
        // Every cell is a meaningful case: none is refused.
        assert!(matches!(o, Outcome::Converged { .. }), "{}: {o:?}", c.name);
    }
    let page = sets::markdown(&res, 0.002);
    assert!(page.contains("heavy preload") && !page.contains("FAILED"));
    // The lift-off cell lifts the row facing -z off; the heavy cell's rows carry 3 kN.
    let get = |c: &mut Component, n: &str| c.get_real(by_name(n).unwrap().vr).unwrap();
    let cell = |name: &str| {
        sets::cells()
            .into_iter()
            .find(|c| c.name.starts_with(name))
            .unwrap()
    };
    let mut c =
        Component::from_text(&cell("lift-off under thrust (60 µm axial), qs").scene(1e-6)).unwrap();
    c.do_step(0.0, 1e-4).unwrap();
    assert_eq!(get(&mut c, "row1.lift_off"), 1.0);
    assert_eq!(get(&mut c, "row0.lift_off"), 0.0);
    assert_eq!(get(&mut c, "row1.force.z"), 0.0);
    assert!(get(&mut c, "force.z") < -1000.0);
    let mut c = Component::from_text(&cell("heavy preload 3 kN, ring").scene(1e-6)).unwrap();
    c.do_step(0.0, 1e-4).unwrap();
    let (f0, f1) = (get(&mut c, "row0.force.z"), get(&mut c, "row1.force.z"));
    // The 500 N thrust shifts load between the rows around the 3 kN preload.
    assert!((f0 + f1 + 500.0).abs() < 0.05 * 500.0, "{f0} {f1}");
    assert!(f1 > 2000.0 && -f0 > 2000.0, "{f0} {f1}");
}
