//! Unit tests of the translation layer (run with `cargo test --features fmi --lib fmi::`;
//! the host-level tests are in `tests/python/`).

use super::instance::{uri_to_path, Instance, Logger, Snapshot, Status};
use super::model_description::{self as md, base_unit, GUID, GUID_LOAD};
use super::params::{self, ParamValue};
use crate::component::scene::{BearingRef, InputRule, Level};
use crate::component::variables::{Causality, PARAMETERS};

const M: Causality = Causality::Motion;

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
    for c in md::VARIANTS {
        let (x2, x3) = (md::fmi2(c), md::fmi3(c));
        assert!(x2.contains(md::guid(c)) && x3.contains(md::guid(c)));
        let outputs = md::outputs(c).count();
        assert_eq!(x2.matches("<Unknown index=").count(), 2 * outputs);
        assert_eq!(x3.matches("<Output valueReference=").count(), outputs);
    }
    assert_eq!(md::inputs(M).count(), 11);
    // load-driven: loads and speed in, the ring's motion out
    let load_in: Vec<&str> = md::inputs(Causality::Load).map(|v| v.name).collect();
    assert_eq!(
        load_in,
        [
            "shaft.omega",
            "load.x",
            "load.y",
            "load.z",
            "load.mx",
            "load.my"
        ]
    );
    assert!(md::outputs(Causality::Load).any(|v| v.name == "shaft.y"));
    assert_ne!(GUID, GUID_LOAD);
    assert_eq!(md::variant_of(GUID_LOAD), Some(Causality::Load));
    assert_eq!(md::variant_of("{x}"), None);
}

#[test]
fn counts_are_integers_and_choices_enumerations_in_both_versions() {
    for c in md::VARIANTS {
        let (x2, x3) = (md::fmi2(c), md::fmi3(c));
        assert!(x2.contains(
            "name=\"balls.loaded\" valueReference=\"109\" causality=\"output\" \
             variability=\"discrete\""
        ));
        assert!(x2.contains("<Integer/></ScalarVariable>"));
        assert!(x3.contains("<Int32 name=\"balls.loaded\" valueReference=\"109\""));
        assert!(x3.contains("<Int32 name=\"warnings.active\""));
        assert!(x2.contains("<SimpleType name=\"Level\">"));
        assert!(x2.contains("<Item name=\"ring\" value=\"3\"/>"));
        assert!(x2.contains("<Enumeration declaredType=\"Level\" start=\"0\"/>"));
        assert!(x3.contains("<EnumerationType name=\"InputRule\">"));
        assert!(x3.contains("declaredType=\"InputRule\" start=\"0\"/>"));
        assert!(x2.contains("<Boolean start=\"false\"/>"));
        assert!(x3.contains("<Boolean name=\"override_clearance\""));
        // no sentinel: the clearance's start is inside its range
        assert!(x3.contains("<Float64 name=\"clearance\""));
        assert!(!x2.contains("start=\"-1\""));
    }
    // the items after `scene` are the scene's spellings
    assert_eq!(
        &crate::component::variables::LEVEL_ITEMS[1..],
        &Level::NAMES
    );
    for rule in &crate::component::variables::INPUT_RULE_ITEMS[1..] {
        let r: InputRule =
            serde_json::from_value(serde_json::Value::String(rule.to_string())).unwrap();
        assert_eq!(serde_json::to_value(r).unwrap(), *rule);
    }
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
    let item = |p: &str, x: &str| {
        let items: &[&str] = if p == "level" {
            &crate::component::variables::LEVEL_ITEMS
        } else {
            &crate::component::variables::INPUT_RULE_ITEMS
        };
        ParamValue::Int(items.iter().position(|i| *i == x).unwrap() as i64)
    };
    let sc = |v: &params::ParamValues, tol, res| params::scene(v, tol, res, M, &[]);
    let v = values(&[
        ("bearing", s("6205")),
        ("level", item("level", "linear")),
        ("input_rule", item("input_rule", "derivatives")),
        ("clearance", ParamValue::Real(12e-6)),
        ("override_clearance", ParamValue::Bool(true)),
        ("rtol", ParamValue::Real(1e-8)),
    ]);
    let (scene, source) = sc(&v, Some(1e-3), None).unwrap();
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
    let (scene, _) = sc(&params::unset(), Some(1e-4), None).unwrap();
    assert_eq!(scene.solver.rtol, 1e-4);
    let (scene, _) = sc(&params::unset(), Some(0.5), None).unwrap();
    assert_eq!(
        scene.solver.rtol,
        crate::component::scene::SolverSpec::default().rtol
    );
    // an empty string and item 0 (`scene`) are "not set"
    assert!(sc(&values(&[("bearing", s(""))]), None, None).is_ok());
    let (kept, _) = sc(&values(&[("level", ParamValue::Int(0))]), None, None).unwrap();
    assert_eq!(
        kept.model.level,
        crate::component::Scene::default_scene().model.level
    );
    // every level is an item
    for (l, name) in crate::component::Level::ALL
        .iter()
        .zip(crate::component::Level::NAMES)
    {
        let (s, _) = sc(&values(&[("level", item("level", name))]), None, None).unwrap();
        assert_eq!(s.model.level, *l);
    }
    let e = sc(
        &values(&[
            ("clearance", ParamValue::Real(-0.5)),
            ("override_clearance", ParamValue::Bool(true)),
        ]),
        None,
        None,
    )
    .unwrap_err();
    assert!(e.contains("clearance"), "{e}");
    // without override_clearance the clearance parameter changes nothing
    let (kept, _) = sc(
        &values(&[("clearance", ParamValue::Real(5e-6))]),
        None,
        None,
    )
    .unwrap();
    assert_eq!(kept.bearing, raceway_default_bearing());
    let resource = Ok("bearing = ".to_string());
    let e = sc(&params::unset(), None, Some(&resource)).unwrap_err();
    assert!(e.starts_with("resources/scene.toml"), "{e}");
    // the variant decides the causality: a load scene is refused by the motion FMU; the
    // load FMU runs the default scene load-driven with the host's loads as start values
    let load_scene = "bearing = \"6205\"\n[model]\ncausality = \"load\"\n";
    let e = sc(&values(&[("scene", s(load_scene))]), None, None).unwrap_err();
    assert!(e.contains("load-driven FMU"), "{e}");
    let (ls, _) = params::scene(
        &params::unset(),
        None,
        None,
        Causality::Load,
        &[("load.y", -500.0)],
    )
    .unwrap();
    assert_eq!(ls.model.causality, Causality::Load);
    assert_eq!(ls.inputs.initial.get("load.y"), Some(&-500.0));
    assert!(!ls.inputs.initial.contains_key("shaft.y"));
}

pub(super) fn instance() -> Instance {
    Instance::new(
        2,
        M,
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
    a.set_integer(1003, 1, "Integer").unwrap(); // hold
    a.exit_initialization().unwrap();
    a.mode = super::instance::STEP;
    a.do_step(0.0, 1e-4).unwrap();
    let bytes = a.snapshot().to_bytes();
    let back = Snapshot::from_bytes(&bytes, M).unwrap();
    assert_eq!(back.to_bytes(), bytes);
    // another instance with other parameters takes everything from the state
    let mut b = instance();
    b.restore(&back).unwrap();
    assert_eq!(b.get_integer(1003, "Integer").unwrap(), 1);
    assert_eq!(b.time, a.time);
    assert_eq!(
        b.get_real(101).unwrap().to_bits(),
        a.get_real(101).unwrap().to_bits()
    );
    for cut in [0, 4, 20, bytes.len() - 1] {
        assert!(Snapshot::from_bytes(&bytes[..cut], M).is_err(), "{cut}");
    }
    let mut other = bytes.clone();
    other[20] ^= 1; // inside the GUID
    let err = Snapshot::from_bytes(&other, M).err().expect("refused");
    assert!(err.contains("this instance is"), "{err}");
    // a motion-driven state is refused by a load-driven instance, in bytes and in memory
    let err = Snapshot::from_bytes(&bytes, Causality::Load)
        .err()
        .expect("refused");
    assert!(err.contains("load-driven"), "{err}");
    let mut l = Instance::new(
        2,
        Causality::Load,
        "l",
        Logger::Fmi2(None, std::ptr::null_mut()),
        false,
        None::<&std::path::Path>,
    );
    let e = l.restore(&back).unwrap_err();
    assert!(e.msg.contains("motion-driven FMU"), "{}", e.msg);
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
    let (x2, x3) = (md::fmi2(M), md::fmi3(M));
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
    let html = md::documentation_html(M);
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

/// A panic inside a call poisons that instance only: every later call on it is refused
/// (its state may be half-updated), another instance goes on; a freed or made-up handle
/// is refused, never dereferenced.
#[test]
fn a_panic_poisons_its_instance_and_freed_handles_are_refused() {
    use super::instance::{guard, ANY};
    let a = instance().into_raw();
    let b = instance().into_raw();
    let ok = |_: &mut Instance| Ok(Status::Ok);
    assert_eq!(unsafe { guard(a, "t", ANY, ok) }, Status::Ok);
    let boom = |_: &mut Instance| -> super::instance::Outcome { panic!("boom") };
    assert_eq!(unsafe { guard(a, "t", ANY, boom) }, Status::Error);
    assert_eq!(unsafe { guard(a, "t", ANY, ok) }, Status::Error);
    assert_eq!(unsafe { guard(b, "t", ANY, ok) }, Status::Ok);
    Instance::free(a);
    Instance::free(a); // a second free is ignored
    assert_eq!(unsafe { guard(a, "t", ANY, ok) }, Status::Error);
    assert_eq!(
        unsafe { guard(0x1234_5670 as *mut std::ffi::c_void, "t", ANY, ok) },
        Status::Error
    );
    Instance::free(b);
}

#[test]
fn a_start_time_no_step_could_leave_is_refused_at_set_up_by_name() {
    // Issue #38 item 9: startTime = 1e300 was accepted, then every step was refused.
    let mut a = instance();
    let e = a.setup(None, 1e300, None).expect_err("1e300 refused");
    assert!(
        e.msg.contains("startTime") && e.msg.contains("[-5e8, 5e8] s"),
        "{}",
        e.msg
    );
    assert_eq!(a.start_time, 0.0, "the refusal keeps the old start");
    // The far end of the range that message gives can be met: set up there and step.
    a.setup(None, -5e8, None).unwrap();
    a.set_real(2, -1e-5).unwrap();
    a.set_real(11, 183.26).unwrap();
    a.exit_initialization().unwrap();
    a.do_step(-5e8, 0.2).map_err(|(_, f)| f.msg).unwrap();
    assert!((a.time - (-5e8 + 0.2)).abs() < 1e-6);
}

/// A bad scene through the FMU (the `scene` parameter or resources/scene.toml) is reported
/// as `raceway scene --check` reports it: every problem with its line:column and the
/// nearest known name, the parse problems and the library's own refusals alike.
#[test]
fn scene_errors_carry_line_column_and_suggestions() {
    let s = |t: &str| ParamValue::Str(t.to_string());
    let sc = |v: &params::ParamValues, res| params::scene(v, None, res, M, &[]);
    let typo = "bearing = \"6205\"\n[model]\nlevl = \"ring\"\n[solver]\nrtol = 0.5\n";
    let e = sc(&values(&[("scene", s(typo))]), None).unwrap_err();
    assert!(e.starts_with("parameter `scene`: 2 problem(s)"), "{e}");
    assert!(
        e.contains("3:1: `model.levl`: unknown key `levl`; did you mean `level`?"),
        "{e}"
    );
    assert!(e.contains("5:8: `solver.rtol`"), "{e}");
    let resource = Ok(typo.to_string());
    let e = sc(&params::unset(), Some(&resource)).unwrap_err();
    assert!(e.starts_with("resources/scene.toml: 2 problem(s)"), "{e}");
    // A scene that parses but that the library refuses: located by its field path.
    let old = "bearing = \"6205\"\n[inputs]\ninitial = { \"shaft.omega\" = 183.26 }\n";
    let v = values(&[("scene", s(old))]);
    let scene = sc(&v, None).unwrap();
    let e = params::component(&v, None, scene).map(|_| ()).unwrap_err();
    assert!(e.contains("3:13: `inputs.initial.shaft.omega`"), "{e}");
    assert!(e.contains("did you mean `speed_rpm`?"), "{e}");
}

fn param_vr(name: &str) -> u32 {
    PARAMETERS.iter().find(|p| p.name == name).unwrap().vr
}

/// force.y after initialisation of an instance prepared by `setup`, with `scene` (if any)
/// as its `scene` parameter.
fn force_y(scene: Option<&str>, setup: &dyn Fn(&mut Instance)) -> f64 {
    let mut a = instance();
    if let Some(s) = scene {
        a.set_string(param_vr("scene"), Some(s.to_string()))
            .unwrap();
    }
    setup(&mut a);
    a.exit_initialization().unwrap();
    a.get_real(102).unwrap()
}

/// The named parameters `clearance_um`, `speed_rpm` and `solver` act exactly as the same
/// edit of the scene does, override the scene string's field, and carry the row's unit,
/// range and description into both model descriptions; an out-of-range value is refused
/// naming the parameter and the range, and changes nothing.
#[test]
fn named_parameters_act_as_the_same_scene_edit() {
    use crate::component::scene::DEFAULT_SCENE;
    let edit = |um: f64| {
        DEFAULT_SCENE.replace(
            "bearing = \"6205\"",
            &format!("bearing = {{ preset = \"6205\", clearance_um = {um:?} }}"),
        )
    };
    assert_ne!(edit(20.0), DEFAULT_SCENE);
    let base = force_y(None, &|_| {});
    let by_scene = force_y(Some(&edit(20.0)), &|_| {});
    let by_param = force_y(None, &|a| {
        a.set_real(param_vr("clearance_um"), 20.0).unwrap()
    });
    assert_eq!(
        by_param.to_bits(),
        by_scene.to_bits(),
        "{by_param} vs {by_scene}"
    );
    assert!(
        (by_param - base).abs() > 1.0,
        "20 µm of clearance changes the force: {base} -> {by_param}"
    );
    // over the scene string: the parameter wins
    let over = force_y(Some(&edit(5.0)), &|a| {
        a.set_real(param_vr("clearance_um"), 20.0).unwrap()
    });
    assert_eq!(over.to_bits(), by_scene.to_bits());
    // out of range: refused by name with the range, the value kept
    let mut a = instance();
    let e = a.set_real(param_vr("clearance_um"), 2000.0).unwrap_err();
    assert!(
        e.msg.contains("`clearance_um`") && e.msg.contains("[-1000, 1000]"),
        "{}",
        e.msg
    );
    a.exit_initialization().unwrap();
    assert_eq!(a.get_real(102).unwrap().to_bits(), base.to_bits());
    // speed_rpm and solver reach the same scene fields as the scene text
    let sc = |v: &params::ParamValues| params::scene(v, None, None, M, &[]).unwrap().0;
    let s = sc(&values(&[("speed_rpm", ParamValue::Real(3000.0))]));
    assert_eq!(s.inputs.speed_rpm, 3000.0);
    let k = crate::component::variables::SOLVER_ITEMS
        .iter()
        .position(|i| *i == "rosenbrock")
        .unwrap() as i64;
    let s = sc(&values(&[("solver", ParamValue::Int(k))]));
    assert_eq!(s.solver.method, crate::component::scene::Method::Rosenbrock);
    let kept = sc(&values(&[("solver", ParamValue::Int(0))]));
    assert_eq!(
        kept.solver.method,
        crate::component::Scene::default_scene().solver.method
    );
    let e = params::scene(
        &values(&[("speed_rpm", ParamValue::Real(1e9))]),
        None,
        None,
        M,
        &[],
    )
    .unwrap_err();
    assert!(e.contains("`speed_rpm`") && e.contains("rpm"), "{e}");
    // the model descriptions: the row's unit (a scaled unit), range and description
    let row = crate::component::fields::find(crate::geometry::BearingSpec::FIELDS, "clearance_um");
    for x in [md::fmi2(M), md::fmi3(M)] {
        assert!(x.contains("name=\"clearance_um\""), "clearance_um declared");
        assert!(x.contains(row.description));
        assert!(x.contains("unit=\"µm\"") && x.contains("min=\"-1000\" max=\"1000\""));
        assert!(x.contains("factor=\"1e-6\""), "µm is 1e-6 m");
        assert!(x.contains("name=\"speed_rpm\"") && x.contains("unit=\"rpm\""));
        assert!(x.contains("name=\"solver\"") && x.contains("\"rosenbrock\""));
    }
}
