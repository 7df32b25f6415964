//! Unit tests of the translation layer (run with `cargo test --features fmi --lib fmi::`;
//! the host-level tests are in `tests/python/`).

use super::instance::{uri_to_path, Instance, Logger, Snapshot, Status};
use super::model_description::{self as md, base_unit, GUID};
use super::params::{self, ParamValue};
use crate::component::scene::{BearingRef, InputRule, Level};
use crate::component::variables::PARAMETERS;

#[test]
fn resource_uris_are_percent_decoded() {
    let p = |s: &str| uri_to_path(s).map(|p| p.to_string_lossy().into_owned());
    assert_eq!(
        p("file:///tmp/a%20b/%C3%BC/resources").as_deref(),
        Some("/tmp/a b/ü/resources")
    );
    assert_eq!(p("file://localhost/tmp/x").as_deref(), Some("/tmp/x"));
    assert_eq!(p("file:/tmp/x%25y").as_deref(), Some("/tmp/x%y"));
    assert_eq!(p("file:///C:/temp/res").as_deref(), Some("C:/temp/res"));
    assert_eq!(p("/plain/path").as_deref(), Some("/plain/path"));
    assert_eq!(p("file:///bad%zz"), None);
}

#[test]
fn guid_is_a_braced_uuid_and_units_have_base_units() {
    assert_eq!(GUID.len(), 38);
    assert!(GUID.starts_with('{') && GUID.ends_with('}'));
    assert!(GUID[1..37]
        .chars()
        .all(|c| c.is_ascii_hexdigit() || c == '-'));
    assert_eq!(base_unit("N.m.s/rad"), Some([1, 2, -1, -1]));
    assert_eq!(base_unit("Pa"), Some([1, -1, -2, 0]));
    assert_eq!(base_unit("furlong"), None);
    // every unit of the table has a rule (the generators would panic otherwise)
    let (x2, x3) = (md::fmi2(), md::fmi3());
    assert!(x2.contains(GUID) && x3.contains(GUID));
    let outputs = md::outputs().count();
    assert_eq!(x2.matches("<Unknown index=").count(), 2 * outputs);
    assert_eq!(x3.matches("<Output valueReference=").count(), outputs);
    assert_eq!(md::inputs().count(), 11);
}

#[test]
fn doc_update_is_idempotent() {
    let doc = format!("# t\n\n{}\nold\n{}\ntail\n", md::DOC_BEGIN, md::DOC_END);
    let once = md::update_doc(&doc).unwrap();
    assert!(once.contains(&md::markdown_table()) && once.ends_with("tail\n"));
    assert_eq!(md::update_doc(&once).unwrap(), once);
    assert_eq!(md::update_doc("no markers"), None);
}

fn values(set: &[(&str, ParamValue)]) -> params::ParamValues {
    let mut v = params::unset();
    for (name, value) in set {
        let i = PARAMETERS.iter().position(|p| p.name == *name).unwrap();
        v[i] = Some(value.clone());
    }
    v
}

fn raceway_default_bearing() -> crate::component::scene::BearingRef {
    crate::component::Scene::default_scene().bearing
}

#[test]
fn parameters_map_onto_the_scene() {
    let s = |x: &str| ParamValue::Str(x.into());
    let v = values(&[
        ("bearing", s("6205")),
        ("level", s("linear")),
        ("input_rule", s("derivatives")),
        ("clearance", ParamValue::Real(12e-6)),
        ("rtol", ParamValue::Real(1e-8)),
    ]);
    let (scene, source) = params::scene(&v, Some(1e-3), None).unwrap();
    assert_eq!(source, "the default scene");
    assert_eq!(scene.model.level, Level::Linear);
    assert_eq!(scene.inputs.rule, InputRule::Derivatives);
    assert_eq!(scene.solver.rtol, 1e-8);
    match &scene.bearing {
        BearingRef::Table(t) => {
            assert_eq!(t["preset"].as_str(), Some("6205"));
            assert!((t["clearance_um"].as_float().unwrap() - 12.0).abs() < 1e-9);
        }
        other => panic!("{other:?}"),
    }
    // the host's tolerance is used when rtol is not set and it is in range
    let (scene, _) = params::scene(&params::unset(), Some(1e-4), None).unwrap();
    assert_eq!(scene.solver.rtol, 1e-4);
    let (scene, _) = params::scene(&params::unset(), Some(0.5), None).unwrap();
    assert_eq!(
        scene.solver.rtol,
        crate::component::scene::SolverSpec::default().rtol
    );
    // an empty string is "not set"; refusals name the parameter
    assert!(params::scene(&values(&[("level", s(""))]), None, None).is_ok());
    let e = params::scene(&values(&[("level", s("best"))]), None, None).unwrap_err();
    assert!(e.contains("parameter `level`") && e.contains("best"), "{e}");
    // every level is accepted, and the refusal and the parameter's description name them all
    let desc = crate::component::variables::PARAMETERS
        .iter()
        .find(|p| p.name == "level")
        .unwrap()
        .description;
    for (l, name) in crate::component::Level::ALL
        .iter()
        .zip(crate::component::Level::NAMES)
    {
        let (sc, _) = params::scene(&values(&[("level", s(name))]), None, None).unwrap();
        assert_eq!(sc.model.level, *l);
        assert!(
            e.contains(name) && desc.contains(name),
            "{name}: {e} / {desc}"
        );
    }
    let e = params::scene(
        &values(&[("clearance", ParamValue::Real(-0.5))]),
        None,
        None,
    )
    .unwrap_err();
    assert!(e.contains("clearance"), "{e}");
    // -1, the start value, keeps the bearing's own clearance.
    let (kept, _) = params::scene(
        &values(&[("clearance", ParamValue::Real(-1.0))]),
        None,
        None,
    )
    .unwrap();
    assert_eq!(kept.bearing, raceway_default_bearing());
    let resource = Ok("bearing = ".to_string());
    let e = params::scene(&params::unset(), None, Some(&resource)).unwrap_err();
    assert!(e.starts_with("resources/scene.toml"), "{e}");
}

pub(super) fn instance() -> Instance {
    Instance::new(
        2,
        "t",
        Logger::Fmi2(None, std::ptr::null_mut()),
        false,
        None::<&std::path::Path>,
    )
}

#[test]
fn fmu_state_bytes_round_trip_and_refuse_damage() {
    let mut a = instance();
    a.set_real(2, -2e-5).unwrap();
    a.set_string(1003, Some("hold".into())).unwrap();
    a.exit_initialization().unwrap();
    a.mode = super::instance::STEP;
    a.do_step(0.0, 1e-4).unwrap();
    let bytes = a.snapshot().to_bytes();
    let back = Snapshot::from_bytes(&bytes).unwrap();
    assert_eq!(back.to_bytes(), bytes);
    // another instance with other parameters takes everything from the state
    let mut b = instance();
    b.restore(&back).unwrap();
    assert_eq!(b.get_string(1003).unwrap(), "hold");
    assert_eq!(b.time, a.time);
    assert_eq!(
        b.get_real(101).unwrap().to_bits(),
        a.get_real(101).unwrap().to_bits()
    );
    for cut in [0, 4, 20, bytes.len() - 1] {
        assert!(Snapshot::from_bytes(&bytes[..cut]).is_err(), "{cut}");
    }
    let mut other = bytes.clone();
    other[20] ^= 1; // inside the GUID
    let err = Snapshot::from_bytes(&other).err().expect("refused");
    assert!(err.contains("this binary is"), "{err}");
}

#[test]
fn status_values_are_the_fmi_ones() {
    assert_eq!(Status::Ok as i32, 0);
    assert_eq!(Status::Discard as i32, 2);
    assert_eq!(Status::Error as i32, 3);
}

#[test]
fn outputs_are_valid_after_initialisation_restore_and_reset() {
    let mut a = instance();
    a.set_real(2, -1e-5).unwrap(); // shaft.y
    a.set_real(11, 183.26).unwrap(); // shaft.omega
    a.exit_initialization().unwrap();
    let fy = a.get_real(102).unwrap();
    assert!(fy > 100.0, "force.y at t0 = {fy} N");
    let snap = a.snapshot();
    a.set_real(2, -2e-5).unwrap();
    assert!(
        a.get_real(102).unwrap() > 2.0 * fy,
        "follows a changed input"
    );
    a.restore(&snap).unwrap();
    assert_eq!(a.get_real(102).unwrap(), fy);
    a.reset();
    a.set_real(2, -1e-5).unwrap();
    a.set_real(11, 183.26).unwrap();
    a.exit_initialization().unwrap();
    assert_eq!(a.get_real(102).unwrap(), fy);
}

#[test]
fn declared_ranges_and_display_units_are_in_the_descriptions_and_enforced() {
    let (x2, x3) = (md::fmi2(), md::fmi3());
    for x in [&x2, &x3] {
        assert!(x.contains("<DisplayUnit name=\"rpm\" factor=\"9.549296585513721\"/>"));
        assert!(x.contains("<DisplayUnit name=\"µm\" factor=\"1000000\"/>"));
        assert!(x.contains("displayUnit=\"GPa\""));
        assert!(x.contains("min=\"-0.001\" max=\"0.001\""));
        assert!(x.contains("min=\"1e-14\" max=\"0.1\""));
    }
    let mut a = instance();
    let e = a.set_real(1, 2e-3).unwrap_err();
    assert!(e.msg.contains("shaft.x") && e.msg.contains("[-0.001, 0.001]"));
    let e = a.set_real(1005, 0.5).unwrap_err();
    assert!(e.msg.contains("rtol"), "{}", e.msg);
    assert!(a.set_real(1, 1e-3).is_ok());
    let html = md::documentation_html();
    assert!(html.contains("linux64") && html.contains("<code>K.y.y</code>"));
}

#[test]
fn directional_derivatives_are_finite_or_refused_for_any_finite_seed() {
    let mut a = instance();
    a.set_real(2, -1e-5).unwrap();
    a.set_real(11, 183.26).unwrap();
    a.exit_initialization().unwrap();
    let mut out = [0.0; 1];
    a.directional_derivative(&[102], &[2], &[1e-9], &mut out)
        .unwrap();
    let small = out[0];
    assert!(small < 0.0, "dF_y/dy = -K_yy < 0: {small}");
    // A moderate huge seed scales exactly; one beyond f64 is refused, not -inf.
    a.directional_derivative(&[102], &[2], &[1e290], &mut out)
        .unwrap();
    assert!(out[0].is_finite() && (out[0] / small / 1e299 - 1.0).abs() < 1e-12);
    let e = a
        .directional_derivative(&[102], &[2], &[1e308], &mut out)
        .unwrap_err();
    assert!(e.msg.contains("seed"), "{}", e.msg);
    // Two seeds whose products overflow alone but not together.
    a.directional_derivative(&[102], &[2, 2], &[1e305, -1e305], &mut out)
        .unwrap();
    assert_eq!(out[0], 0.0);
}
