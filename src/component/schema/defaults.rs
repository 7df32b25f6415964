//! Paths and defaults of every scene field, read from serde: complete scenes for each level
//! and traction law, the schema's paths, the default of each field and which fields are
//! required.

use super::*;

// ---------------------------------------------------------------------------------------
// Paths and defaults from serde.

pub(super) fn steel_inline() -> MaterialSpec {
    MaterialSpec::Custom(Material::by_name("steel").expect("preset"))
}

/// A bearing spec with every optional field given (struct literals: a new field does not
/// compile until it is added here, and then the schema test asks for its table entry).
pub(super) fn full_bearing(materials: MaterialsSpec) -> BearingSpec {
    BearingSpec {
        name: "6205".into(),
        kind: Default::default(),
        ball_diameter_mm: 7.94,
        pitch_diameter_mm: 39.04,
        ball_count: 9,
        inner_curvature: Some(0.52),
        outer_curvature: Some(0.52),
        contact_angle_deg: Some(0.0),
        clearance_um: Some(0.0),
        bore_mm: Some(25.0),
        outer_diameter_mm: Some(52.0),
        width_mm: Some(15.0),
        inner_ring_mass_kg: Some(0.05),
        outer_ring_mass_kg: Some(0.07),
        cage: CageSpec {
            inner_diameter_mm: Some(36.3),
            outer_diameter_mm: Some(41.8),
            width_mm: Some(6.3),
            mass_kg: Some(0.01),
            inertia_kg_m2: Some(4e-6),
            pocket_clearance_mm: Some(0.16),
            guide_clearance_mm: Some(0.2),
            guidance: Default::default(),
        },
        materials,
        source: String::new(),
    }
}

/// A scene with every optional section, field, list and map filled (two list items per
/// effect would add nothing: the paths of items are normalised to `[]`). Fields with a
/// value by default come with it (`..Default::default()`); an optional field must be given
/// `Some` here, or `table_matches_schema` names its row.
pub(super) fn full_scene(bearing: BearingRef, traction: TractionLaw) -> Scene {
    let mut initial = BTreeMap::new();
    initial.insert("shaft.y".to_string(), -1e-6);
    Scene {
        title: "full".into(),
        bearing,
        model: ModelSpec {
            level: crate::component::Level::Ring,
            skidding: SkiddingSpec {
                traction,
                pocket_clearance_mm: Some(0.1),
                spin_friction: 0.02,
                ..Default::default()
            },
            full: crate::component::scene::FullSpec {
                traction,
                pocket_clearance_mm: Some(0.1),
                guide_width_mm: Some(3.0),
                guidance: Some(crate::geometry::Guidance::InnerRing),
                cage_unbalance_um: 2.0,
                ..Default::default()
            },
            start_hold: crate::models::quasi_static::hold::HoldSpec::from_edge([Some(0.0); 5]),
            ..Default::default()
        },
        solver: SolverSpec::default(),
        inputs: InputSpec {
            speed_rpm: 100.0,
            rule: Default::default(),
            initial,
        },
        effects: Effects {
            defects: vec![DefectSpec {
                race: Element::Ball,
                angle_deg: 0.0,
                width_mm: 0.5,
                depth_um: 10.0,
                ball: Some(0),
                axial_width_mm: None,
                axial_position_mm: None,
            }],
            waviness: vec![WavinessSpec {
                race: Element::Ball,
                order: 2,
                amplitude_um: 0.1,
                phase_deg: 0.0,
                ball: Some(0),
            }],
            ball_spacing: Some(SpacingSpec {
                scatter: 0.5,
                seed: 1,
            }),
            lubrication: Some(LubricationSpec {
                film: FilmKind::Ehl,
                lubricant: "study2".into(),
                viscosity_pa_s: Some(0.05),
                pressure_viscosity_m2_per_n: Some(2e-8),
                density_kg_m3: Some(870.0),
                roughness_um: Some(0.1),
                temperature_c: None,
            }),
            wear: Some(crate::models::effects::WearSpec::default()),
            thermal: Some(crate::models::effects::ThermalSpec {
                viscosity_cst: Some(30.0),
                contact_conductance_w_k: Some(1.0),
                ..Default::default()
            }),
        },
        run: RunSpec::default(),
        set: None,
    }
}

/// Full scenes of a bearing set, one per form of `[set]` (a pair preset with a spring, one
/// with an offset, rows by hand, one row by orientation): a set takes no effects and runs on the
/// 5-DOF ring.
fn set_scenes() -> Vec<Scene> {
    use crate::models::set::{Arrangement, RowFile, SetFile};
    let with = |set: SetFile| {
        let mut s = full_scene(BearingRef::Preset("7008CE".into()), TractionLaw::default());
        s.model.ring_dof = 5;
        s.effects = Effects::default();
        s.set = Some(set);
        s
    };
    let row = |z: f64, o: i32| RowFile {
        bearing: "7008CE".into(),
        position_mm: z,
        orientation: o,
    };
    vec![
        with(SetFile {
            arrangement: Some(Arrangement::Db),
            spacer_mm: 1.0,
            preload_n: Some(200.0),
            spring_n_per_um: Some(20.0),
            ..Default::default()
        }),
        with(SetFile {
            arrangement: Some(Arrangement::Df),
            preload_offset_um: Some(5.0),
            ..Default::default()
        }),
        // No preload: either orientation of either row is a set.
        with(SetFile {
            row: vec![row(-7.5, 1), row(7.5, -1)],
            ..Default::default()
        }),
        with(SetFile {
            orientation: Some(-1),
            ..Default::default()
        }),
    ]
}

pub(super) fn bearing_table(spec: &BearingSpec, preset: Option<&str>) -> toml::Table {
    let mut t = toml::Table::try_from(spec).expect("a bearing spec serialises");
    if let Some(p) = preset {
        t.insert("preset".into(), toml::Value::String(p.into()));
    }
    t
}

/// Full scenes covering every form: bearing as a table (with inline and preset
/// materials) and as a preset name, each traction law. Every one is a valid scene
/// (`tests`).
pub fn full_scenes() -> Vec<Scene> {
    let inline = MaterialsSpec {
        ball: steel_inline(),
        inner_ring: steel_inline(),
        outer_ring: steel_inline(),
        cage: MaterialSpec::Custom(Material::by_name("phenolic").expect("preset")),
    };
    let fitted = TractionLaw::Fitted {
        a: -0.01,
        b: 0.1,
        c: 10.0,
        d: 0.02,
        s_reg: 0.01,
        u_min: 0.1,
    };
    vec![
        full_scene(
            BearingRef::Table(bearing_table(&full_bearing(inline), Some("6205"))),
            TractionLaw::default(),
        ),
        full_scene(
            BearingRef::Table(bearing_table(&full_bearing(MaterialsSpec::default()), None)),
            fitted,
        ),
        full_scene(
            BearingRef::Preset("6205".into()),
            // With the optional override of the asperity share, so its rows are walked.
            TractionLaw::MixedEhl(crate::contact::traction::MixedEhl {
                fit: Some(Default::default()),
                ..Default::default()
            }),
        ),
        {
            // The 4109 law with every optional field, on MIL-L-7808 (the temperature-dependent
            // lubricant preset), so their rows are walked.
            use crate::contact::traction::{Fit4109, Oil4109};
            let mut s = full_scene(
                BearingRef::Preset("7004".into()),
                TractionLaw::Fitted4109(Fit4109 {
                    temperature_c: Some(80.0),
                    oil: Oil4109::MilL7808,
                    viscosity: Some(0.01),
                    beta: Some(0.02),
                    conductivity: Some(0.13),
                    ..Default::default()
                }),
            );
            if let Some(l) = s.effects.lubrication.as_mut() {
                l.lubricant = "mil_l_7808".into();
                l.temperature_c = Some(80.0);
                l.viscosity_pa_s = None;
            }
            s
        },
        {
            // A roller bearing's defect with its axial extent (the ring level takes defects and
            // waviness on roller bearings, nothing else), so its rows are walked. On a roller
            // (`race = "ball"`): the spellings' check reads the first full scene with a
            // spelling as a ball bearing's spec.
            let mut s = full_scene(BearingRef::Preset("NU206".into()), TractionLaw::default());
            s.effects = Effects {
                defects: vec![DefectSpec {
                    race: Element::Ball,
                    angle_deg: 270.0,
                    width_mm: 1.0,
                    depth_um: 10.0,
                    ball: None,
                    axial_width_mm: Some(4.0),
                    axial_position_mm: Some(-1.0),
                }],
                waviness: vec![WavinessSpec {
                    race: Element::Ball,
                    order: 2,
                    amplitude_um: 0.1,
                    phase_deg: 0.0,
                    ball: None,
                }],
                ..Effects::default()
            };
            s
        },
    ]
    .into_iter()
    .chain(set_scenes())
    .collect()
}

pub(super) fn walk_value(v: &toml::Value, norm: &str, out: &mut BTreeMap<String, toml::Value>) {
    match v {
        toml::Value::Table(t) => {
            for (k, c) in t {
                walk_value(c, &normalise_child(norm, k), out);
            }
        }
        toml::Value::Array(a) if a.iter().all(|x| x.is_table()) && !a.is_empty() => {
            for c in a {
                walk_value(c, &format!("{norm}[]"), out);
            }
        }
        // An empty list of tables (the effects of a set's scene, all off) names no field.
        toml::Value::Array(a) if a.is_empty() && norm.starts_with("effects.") => {}
        leaf => {
            out.entry(norm.to_string()).or_insert_with(|| leaf.clone());
        }
    }
}

/// Every leaf path of the serde schema, normalised, with the value the full scenes give
/// it (used for its TOML type).
pub fn schema_paths() -> BTreeMap<String, toml::Value> {
    let mut out = BTreeMap::new();
    for s in full_scenes() {
        let v = toml::Value::try_from(&s).expect("a scene serialises");
        walk_value(&v, "", &mut out);
    }
    out
}

/// The smallest scene serde accepts: only the required fields of the scene, of one item of
/// each effect list and of the effect tables.
pub const MINIMAL_SCENE: &str = r#"
bearing = "6205"
[effects]
defects = [{ race = "outer", width_mm = 1.0, depth_um = 1.0 }]
waviness = [{ race = "outer", order = 1, amplitude_um = 0.1 }]
ball_spacing = { scatter = 0.0 }
lubrication = {}
"#;

/// The fields a bearing table without `preset` must give, and those of an inline material
/// (required whenever a material is given as a table).
pub const MINIMAL_BEARING: &str = r#"
name = "x"
ball_diameter_mm = 1.0
pitch_diameter_mm = 10.0
ball_count = 3
materials = { ball = { name = "m", youngs_modulus = 2e11, poisson_ratio = 0.3, density = 7800.0, thermal_expansion = 0.0, conductivity = 0.0, heat_capacity = 0.0 } }
"#;

/// A field's default as documented.
#[derive(Debug, Clone, PartialEq)]
pub enum Default_ {
    /// Must be given.
    Required,
    /// Required in a bearing table without `preset` (else the preset's).
    RequiredWithoutPreset,
    /// Absent unless given (see the note for what is used then).
    Absent,
    /// The value serde fills in.
    Value(toml::Value),
}

impl Default_ {
    /// Text for the documentation.
    pub fn text(&self) -> String {
        match self {
            Default_::Required => "required".into(),
            Default_::RequiredWithoutPreset => "the preset's; required without preset".into(),
            Default_::Absent => "absent".into(),
            Default_::Value(v) => match v {
                toml::Value::String(s) => format!("\"{s}\""),
                toml::Value::Float(x) if *x != 0.0 && !(1e-3..1e5).contains(&x.abs()) => {
                    format!("{x:e}")
                }
                toml::Value::Float(x) => format!("{x:?}"),
                other => other.to_string(),
            },
        }
    }
}

/// Concrete leaf paths of a TOML text (array items as `[i]`), for removal.
pub(super) fn concrete_leaves(v: &toml::Value, path: Vec<PathSeg>, out: &mut Vec<Vec<PathSeg>>) {
    match v {
        toml::Value::Table(t) => {
            for (k, c) in t {
                let mut p = path.clone();
                p.push(PathSeg::Key(k.clone()));
                concrete_leaves(c, p, out);
            }
        }
        toml::Value::Array(a) if a.iter().all(|x| x.is_table()) && !a.is_empty() => {
            for (i, c) in a.iter().enumerate() {
                let mut p = path.clone();
                p.push(PathSeg::Index(i));
                concrete_leaves(c, p, out);
            }
        }
        _ => out.push(path),
    }
}

#[derive(Debug, Clone)]
pub(super) enum PathSeg {
    Key(String),
    Index(usize),
}

pub(super) fn remove_at(v: &mut toml::Value, path: &[PathSeg]) {
    match (path, v) {
        ([PathSeg::Key(k)], toml::Value::Table(t)) => {
            t.remove(k);
        }
        ([PathSeg::Key(k), rest @ ..], toml::Value::Table(t)) => {
            if let Some(c) = t.get_mut(k) {
                remove_at(c, rest)
            }
        }
        ([PathSeg::Index(i), rest @ ..], toml::Value::Array(a)) => {
            if let Some(c) = a.get_mut(*i) {
                remove_at(c, rest)
            }
        }
        _ => {}
    }
}

pub(super) fn norm_of(prefix: &str, path: &[PathSeg]) -> String {
    let mut n = prefix.to_string();
    for s in path {
        match s {
            PathSeg::Key(k) => n = normalise_child(&n, k),
            PathSeg::Index(_) => n.push_str("[]"),
        }
    }
    n
}

/// The leaves of a minimal text that serde cannot do without: removing one makes `parses`
/// fail. Normalised with `prefix`.
pub(super) fn required_of(
    text: &str,
    prefix: &str,
    parses: impl Fn(&toml::Value) -> bool,
) -> BTreeSet<String> {
    let v: toml::Value = toml::from_str(text).expect("minimal text parses");
    assert!(parses(&v), "the minimal text is accepted");
    let mut leaves = Vec::new();
    concrete_leaves(&v, Vec::new(), &mut leaves);
    leaves
        .into_iter()
        .filter(|p| {
            let mut w = v.clone();
            remove_at(&mut w, p);
            !parses(&w)
        })
        .map(|p| norm_of(prefix, &p))
        .collect()
}

/// The leaves serde requires in a scene, and in a bearing table without `preset`.
pub fn required_paths() -> (BTreeSet<String>, BTreeSet<String>) {
    let scene = required_of(MINIMAL_SCENE, "", |v| v.clone().try_into::<Scene>().is_ok());
    let bearing = required_of(MINIMAL_BEARING, "bearing", |v| {
        v.clone().try_into::<BearingSpec>().is_ok()
    });
    (scene, bearing)
}

/// Defaults of every path: serde's own, read back from the minimal scene and bearing;
/// required-ness from removing each field of them in turn.
pub fn defaults() -> BTreeMap<String, Default_> {
    let scene = Scene::from_text(MINIMAL_SCENE).expect("the minimal scene parses");
    let mut values = BTreeMap::new();
    walk_value(
        &toml::Value::try_from(&scene).expect("serialises"),
        "",
        &mut values,
    );
    let spec: BearingSpec = toml::from_str(MINIMAL_BEARING).expect("the minimal bearing parses");
    walk_value(
        &toml::Value::Table(bearing_table(&spec, None)),
        "bearing",
        &mut values,
    );
    let (req_scene, req_bearing) = required_paths();
    schema_paths()
        .into_keys()
        .map(|path| {
            let inline_material = path.starts_with("bearing.materials.<body>.");
            let d = if req_scene.contains(&path) || (inline_material && req_bearing.contains(&path))
            {
                Default_::Required
            } else if req_bearing.contains(&path) {
                Default_::RequiredWithoutPreset
            } else {
                values
                    .get(&path)
                    .cloned()
                    .map(Default_::Value)
                    .unwrap_or(Default_::Absent)
            };
            (path, d)
        })
        .collect()
}

/// The required fields, by normalised parent table (`""`: the scene; `bearing`: a bearing
/// table without preset). Derived once per process (a function of the compiled types
/// alone): the check asks for it at every table it visits, and deriving it serialises and
/// re-parses the minimal scene field by field (it was 55 % of a quasi-static sweep point).
pub(super) fn required() -> &'static BTreeMap<String, Vec<String>> {
    static REQUIRED: std::sync::OnceLock<BTreeMap<String, Vec<String>>> =
        std::sync::OnceLock::new();
    REQUIRED.get_or_init(derive_required)
}

fn derive_required() -> BTreeMap<String, Vec<String>> {
    let mut out: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for (p, d) in defaults() {
        if matches!(d, Default_::Required | Default_::RequiredWithoutPreset) {
            let (parent, key) = match p.rfind('.') {
                Some(i) => (p[..i].to_string(), p[i + 1..].to_string()),
                None => (String::new(), p.clone()),
            };
            out.entry(parent).or_default().push(key);
        }
    }
    out
}
