//! `modelDescription.xml` (FMI 2.0 and 3.0), the documentation table and the GUID, all
//! generated from the one variable table in [`crate::component::variables`].
//!
//! Layout and rules: spec2 `2_2_common_schema.adoc`, `4_3_co-simulation_schema.adoc`;
//! spec3 `2_4_common_schema.adoc`, `4_4_co-simulation_schema.adoc`; the checks of
//! `fmpy.validation` (every output in `<Outputs>`, the exact `<InitialUnknowns>` set,
//! start values on inputs, every unit defined, exactly one independent variable in FMI 3).

use crate::component::variables::{
    self, Causality, ParamType, Parameter, Role, VarType, Variable, DAMPING, DISPLAY_UNITS,
    PARAMETERS, RANGES, SCALARS, STIFFNESS,
};
use std::fmt::Write;

/// The model identifier: the shared library's base name inside the FMUs.
pub const MODEL_IDENTIFIER: &str = "raceway";

/// Value reference of the independent variable `time` (FMI 3 only).
pub const VR_TIME: u32 = 0;

/// Bump when the generated XML changes in a way the variable table does not show.
const GENERATOR_FORMAT: &str = "raceway-fmi-model-description/1";

const fn fnv(mut h: u64, bytes: &[u8]) -> u64 {
    let mut i = 0;
    while i < bytes.len() {
        h ^= bytes[i] as u64;
        h = h.wrapping_mul(0x0100_0000_01b3);
        i += 1;
    }
    // field separator, so that ("ab", "c") and ("a", "bc") differ
    h ^= 0xff;
    h.wrapping_mul(0x0100_0000_01b3)
}

const fn hash_variable(mut h: u64, v: &Variable) -> u64 {
    h = fnv(h, v.name.as_bytes());
    h = fnv(h, &v.vr.to_le_bytes());
    h = fnv(h, v.unit.as_bytes());
    h = fnv(h, &[v.role as u8, v.ty as u8]);
    fnv(h, v.description.as_bytes())
}

const fn hash_parameter(mut h: u64, p: &Parameter) -> u64 {
    h = fnv(h, p.name.as_bytes());
    h = fnv(h, &p.vr.to_le_bytes());
    h = fnv(h, &[p.ty.tag()]);
    if let ParamType::Enumeration { type_name, items } = p.ty {
        h = fnv(h, type_name.as_bytes());
        let mut i = 0;
        while i < items.len() {
            h = fnv(h, items[i].as_bytes());
            i += 1;
        }
    }
    h = fnv(h, p.unit.as_bytes());
    h = fnv(h, p.start.as_bytes());
    fnv(h, p.description.as_bytes())
}

/// FNV-1a over the whole variable table, the crate version, the generator format and the
/// variant's causality, from a given offset basis (two bases give the 128 bits of the GUID).
const fn table_hash(basis: u64, causality: Causality) -> u64 {
    let mut h = fnv(basis, GENERATOR_FORMAT.as_bytes());
    h = fnv(h, variant_name(causality).as_bytes());
    h = fnv(h, env!("CARGO_PKG_VERSION").as_bytes());
    let mut i = 0;
    while i < SCALARS.len() {
        h = hash_variable(h, &SCALARS[i]);
        i += 1;
    }
    let mut r = 0;
    while r < 5 {
        let mut c = 0;
        while c < 5 {
            h = hash_variable(h, &STIFFNESS[r][c]);
            h = hash_variable(h, &DAMPING[r][c]);
            c += 1;
        }
        r += 1;
    }
    let mut p = 0;
    while p < PARAMETERS.len() {
        h = hash_parameter(h, &PARAMETERS[p]);
        p += 1;
    }
    let mut d = 0;
    while d < DISPLAY_UNITS.len() {
        h = fnv(h, DISPLAY_UNITS[d].0.as_bytes());
        h = fnv(h, DISPLAY_UNITS[d].1.as_bytes());
        h = fnv(h, &DISPLAY_UNITS[d].2.to_bits().to_le_bytes());
        d += 1;
    }
    let mut r = 0;
    while r < RANGES.len() {
        h = fnv(h, RANGES[r].0.as_bytes());
        h = fnv(h, &RANGES[r].1.to_bits().to_le_bytes());
        h = fnv(h, &RANGES[r].2.to_bits().to_le_bytes());
        r += 1;
    }
    h
}

const fn guid_bytes(causality: Causality) -> [u8; 38] {
    const HEX: &[u8; 16] = b"0123456789abcdef";
    let a = table_hash(0xcbf2_9ce4_8422_2325, causality);
    let b = table_hash(0x6c62_272e_07bb_0142, causality);
    let mut nibbles = [0u8; 32];
    let mut i = 0;
    while i < 16 {
        nibbles[i] = HEX[((a >> (60 - 4 * i)) & 0xf) as usize];
        nibbles[16 + i] = HEX[((b >> (60 - 4 * i)) & 0xf) as usize];
        i += 1;
    }
    let mut out = [0u8; 38];
    out[0] = b'{';
    out[37] = b'}';
    let mut k = 0;
    let mut o = 1;
    while k < 32 {
        if k == 8 || k == 12 || k == 16 || k == 20 {
            out[o] = b'-';
            o += 1;
        }
        out[o] = nibbles[k];
        o += 1;
        k += 1;
    }
    out
}

const GUID_BYTES: [u8; 38] = guid_bytes(Causality::Motion);
const GUID_LOAD_BYTES: [u8; 38] = guid_bytes(Causality::Load);

/// The FMI 2 `guid` and FMI 3 `instantiationToken` of the motion-driven FMU: a hash of the
/// variable table, the crate version, the XML generator's format and the variant,
/// evaluated at compile time. The binary checks it at instantiation; the packer writes the
/// same constant into both model descriptions.
pub const GUID: &str = match core::str::from_utf8(&GUID_BYTES) {
    Ok(s) => s,
    Err(_) => panic!("GUID is ASCII"),
};

/// The GUID / instantiation token of the load-driven FMU (see [`GUID`]).
pub const GUID_LOAD: &str = match core::str::from_utf8(&GUID_LOAD_BYTES) {
    Ok(s) => s,
    Err(_) => panic!("GUID is ASCII"),
};

/// The two FMUs built from one binary: motion-driven (shaft motion in, forces out) and
/// load-driven (loads in, ring motion and forces out). The GUID a host passes at
/// instantiation decides which one an instance is.
pub const VARIANTS: [Causality; 2] = [Causality::Motion, Causality::Load];

/// `motion` or `load`.
pub const fn variant_name(c: Causality) -> &'static str {
    match c {
        Causality::Motion => "motion",
        Causality::Load => "load",
    }
}

/// The GUID / instantiation token of a variant.
pub const fn guid(c: Causality) -> &'static str {
    match c {
        Causality::Motion => GUID,
        Causality::Load => GUID_LOAD,
    }
}

/// The variant a GUID / instantiation token belongs to.
pub fn variant_of(guid_or_token: &str) -> Option<Causality> {
    VARIANTS.into_iter().find(|&c| guid(c) == guid_or_token)
}

/// The archive's file name: `raceway-fmi2.fmu`, `raceway-load-fmi3.fmu`, ...
pub fn archive_name(c: Causality, fmi: &str) -> String {
    match c {
        Causality::Motion => format!("raceway-{fmi}.fmu"),
        Causality::Load => format!("raceway-load-{fmi}.fmu"),
    }
}

/// The model name of a variant.
pub const fn model_name(c: Causality) -> &'static str {
    match c {
        Causality::Motion => "raceway",
        Causality::Load => "raceway_load",
    }
}

/// The variables an FMU of causality `c` shows (inputs and outputs), in table order.
pub fn io_variables(c: Causality) -> impl Iterator<Item = &'static Variable> {
    variables::all().filter(move |v| v.is_input(c) || v.is_output(c))
}

/// The inputs of the FMU of causality `c`, in table order.
pub fn inputs(c: Causality) -> impl Iterator<Item = &'static Variable> {
    variables::all().filter(move |v| v.is_input(c))
}

/// The outputs of the FMU of causality `c`, in table order.
pub fn outputs(c: Causality) -> impl Iterator<Item = &'static Variable> {
    variables::all().filter(move |v| v.is_output(c))
}

/// The inputs output `v` depends on directly at a communication point (`<Outputs>`
/// dependencies). Motion-driven: every input (the forces follow the motion at once).
/// Load-driven: the ring's motion is a state, so it depends on no input; the other outputs
/// follow that state and the speed, and the loads act only through the ring's acceleration.
pub fn direct_dependencies(c: Causality, v: &Variable) -> Vec<&'static Variable> {
    match c {
        Causality::Motion => inputs(c).collect(),
        Causality::Load if v.role == Role::Motion => Vec::new(),
        Causality::Load => inputs(c).filter(|i| i.role == Role::Speed).collect(),
    }
}

/// Exponents (kg, m, s, rad) of one factor of a unit spelling such as `N.m.s/rad`.
fn factor(f: &str) -> Option<[i32; 4]> {
    Some(match f {
        "1" => [0, 0, 0, 0],
        // Millions of revolutions: a count, dimensionless.
        "Mrev" => [0, 0, 0, 0],
        // Scaled units of the named parameters ([`unit_factor`]).
        "µm" => [0, 1, 0, 0],
        "rpm" => [0, 0, -1, 1],
        "kg" => [1, 0, 0, 0],
        "m" => [0, 1, 0, 0],
        "s" => [0, 0, 1, 0],
        "rad" => [0, 0, 0, 1],
        "N" => [1, 1, -2, 0],
        "Pa" => [1, -1, -2, 0],
        "W" => [1, 2, -3, 0],
        _ => return None,
    })
}

/// The factor of a scaled unit to its SI base units (`value in SI = factor × value`):
/// `µm` 1e-6 m, `rpm` pi/30 rad/s; 1 for the others (FMI `BaseUnit factor`).
pub fn unit_factor(unit: &str) -> f64 {
    match unit {
        "µm" => 1e-6,
        "rpm" => std::f64::consts::PI / 30.0,
        _ => 1.0,
    }
}

/// SI base-unit exponents of a unit spelling of the table (`.` multiplies, one `/`).
pub fn base_unit(unit: &str) -> Option<[i32; 4]> {
    let (num, den) = match unit.split_once('/') {
        Some((n, d)) => (n, Some(d)),
        None => (unit, None),
    };
    let mut e = [0; 4];
    for f in num.split('.') {
        let x = factor(f)?;
        (0..4).for_each(|i| e[i] += x[i]);
    }
    if let Some(den) = den {
        for f in den.split('.') {
            let x = factor(f)?;
            (0..4).for_each(|i| e[i] -= x[i]);
        }
    }
    Some(e)
}

fn units(c: Causality) -> Vec<&'static str> {
    let mut u: Vec<&str> = std::iter::once("s")
        .chain(
            io_variables(c)
                .filter(|v| v.ty == VarType::Real)
                .map(|v| v.unit),
        )
        .chain(PARAMETERS.iter().map(|p| p.unit).filter(|u| !u.is_empty()))
        .collect();
    u.sort_unstable();
    u.dedup();
    u
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

fn unit_definitions(x: &mut String, c: Causality) {
    x.push_str("  <UnitDefinitions>\n");
    for u in units(c) {
        let e = base_unit(u).unwrap_or_else(|| panic!("unit `{u}` has no base-unit rule"));
        let mut attrs = String::new();
        for (name, k) in ["kg", "m", "s", "rad"].iter().zip(e) {
            if k != 0 {
                let _ = write!(attrs, " {name}=\"{k}\"");
            }
        }
        let f = unit_factor(u);
        if f != 1.0 {
            let _ = write!(attrs, " factor=\"{f:e}\"");
        }
        let mut body = String::new();
        if !attrs.is_empty() {
            let _ = write!(body, "<BaseUnit{attrs}/>");
        }
        for (_, d, f) in DISPLAY_UNITS.iter().filter(|(si, _, _)| *si == u) {
            let _ = write!(body, "<DisplayUnit name=\"{}\" factor=\"{f}\"/>", esc(d));
        }
        if body.is_empty() {
            let _ = writeln!(x, "    <Unit name=\"{}\"/>", esc(u));
        } else {
            let _ = writeln!(x, "    <Unit name=\"{}\">{body}</Unit>", esc(u));
        }
    }
    x.push_str("  </UnitDefinitions>\n");
}

/// The log categories the binary uses (`instance::category`).
pub const LOG_CATEGORIES: [(&str, &str); 5] = [
    ("logStatusWarning", "warnings"),
    ("logStatusDiscard", "discarded steps"),
    ("logStatusError", "errors"),
    ("logStatusFatal", "fatal errors"),
    ("logAll", "debug messages (only with debug logging on)"),
];

fn log_categories(x: &mut String) {
    x.push_str("  <LogCategories>\n");
    for (name, d) in LOG_CATEGORIES {
        let _ = writeln!(x, "    <Category name=\"{name}\" description=\"{d}\"/>");
    }
    x.push_str("  </LogCategories>\n");
}

/// One line on what a variant does.
pub const fn description(c: Causality) -> &'static str {
    match c {
        Causality::Motion => {
            "Ball bearing (raceway): forces, moments, stiffness and damping from the shaft's motion"
        }
        Causality::Load => {
            "Ball bearing (raceway), load-driven: the inner ring's motion and the bearing's forces from the loads on the ring"
        }
    }
}

const DEFAULT_EXPERIMENT: &str =
    "  <DefaultExperiment startTime=\"0\" stopTime=\"0.1\" stepSize=\"0.0001\"/>\n";

fn param_start(p: &Parameter) -> String {
    esc(p.start)
}

/// `unit="…"`, the display unit, the range and the start of a real parameter (both
/// versions).
fn real_param_attrs(p: &Parameter) -> String {
    format!(
        "unit=\"{}\"{}{} start=\"{}\"",
        esc(p.unit),
        display_attr(p.unit),
        range_attr(p.name),
        param_start(p)
    )
}

/// A number as people write it: plain between 1e-4 and 1e6, else in exponent form
/// (`1e-14`, not `0.00000000000001`); both are valid `xs:double` and round-trip exactly.
pub(crate) fn num(x: f64) -> String {
    if x == 0.0 || (1e-4..1e6).contains(&x.abs()) {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// ` displayUnit="…"` for a variable of SI unit `unit` that has one, else "".
fn display_attr(unit: &str) -> String {
    variables::display_unit(unit).map_or(String::new(), |(d, _)| {
        format!(" displayUnit=\"{}\"", esc(d))
    })
}

/// ` min="…" max="…"` for an input or parameter with a declared range, else "".
fn range_attr(name: &str) -> String {
    variables::range(name).map_or(String::new(), |(lo, hi)| {
        format!(" min=\"{}\" max=\"{}\"", num(lo), num(hi))
    })
}

/// The enumeration types of the parameters (name, items), in table order.
fn enumerations() -> impl Iterator<Item = (&'static str, &'static [&'static str])> {
    PARAMETERS.iter().filter_map(|p| match p.ty {
        ParamType::Enumeration { type_name, items } => Some((type_name, items)),
        _ => None,
    })
}

/// `<TypeDefinitions>` of both versions (FMI 2 `SimpleType`/`Enumeration`, FMI 3
/// `EnumerationType`).
fn type_definitions(x: &mut String, fmi3: bool) {
    x.push_str("  <TypeDefinitions>\n");
    for (name, items) in enumerations() {
        if fmi3 {
            let _ = writeln!(x, "    <EnumerationType name=\"{name}\">");
        } else {
            let _ = writeln!(x, "    <SimpleType name=\"{name}\">\n      <Enumeration>");
        }
        for (k, item) in items.iter().enumerate() {
            let d = if k == 0 { "as the scene has it" } else { "" };
            let _ = writeln!(
                x,
                "      {}<Item name=\"{}\" value=\"{k}\"{}/>",
                if fmi3 { "" } else { "  " },
                esc(item),
                if d.is_empty() {
                    String::new()
                } else {
                    format!(" description=\"{d}\"")
                }
            );
        }
        if fmi3 {
            x.push_str("    </EnumerationType>\n");
        } else {
            x.push_str("      </Enumeration>\n    </SimpleType>\n");
        }
    }
    x.push_str("  </TypeDefinitions>\n");
}

/// What both versions write before the variables: the version's `<fmiModelDescription>`
/// with its `<CoSimulation>`, then the units, the types, the log categories, the default
/// experiment and the opening `<ModelVariables>`.
fn preamble(c: Causality, fmi3: bool) -> String {
    let (name, guid, desc) = (model_name(c), guid(c), esc(description(c)));
    let ver = env!("CARGO_PKG_VERSION");
    let mut x = String::new();
    let _ = if fmi3 {
        write!(
            x,
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n\
             <fmiModelDescription fmiVersion=\"3.0\" modelName=\"{name}\" \
             instantiationToken=\"{guid}\"\n  description=\"{desc}\"\n  \
             version=\"{ver}\" generationTool=\"raceway {ver}\" variableNamingConvention=\"structured\">\n  \
             <CoSimulation modelIdentifier=\"{MODEL_IDENTIFIER}\" \
             canHandleVariableCommunicationStepSize=\"true\"\n    maxOutputDerivativeOrder=\"1\" \
             canGetAndSetFMUState=\"true\" canSerializeFMUState=\"true\"\n    \
             providesDirectionalDerivatives=\"true\" providesAdjointDerivatives=\"false\" \
             hasEventMode=\"false\"\n    canBeInstantiatedOnlyOncePerProcess=\"false\"/>\n",
        )
    } else {
        write!(
            x,
            "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n\
             <fmiModelDescription fmiVersion=\"2.0\" modelName=\"{name}\" guid=\"{guid}\"\n  \
             description=\"{desc}\"\n  version=\"{ver}\" generationTool=\"raceway {ver}\" \
             variableNamingConvention=\"structured\" numberOfEventIndicators=\"0\">\n  \
             <CoSimulation modelIdentifier=\"{MODEL_IDENTIFIER}\" \
             canHandleVariableCommunicationStepSize=\"true\" canInterpolateInputs=\"true\"\n    \
             maxOutputDerivativeOrder=\"1\" canRunAsynchronuously=\"false\" \
             canBeInstantiatedOnlyOncePerProcess=\"false\"\n    \
             canNotUseMemoryManagementFunctions=\"true\" canGetAndSetFMUstate=\"true\" \
             canSerializeFMUstate=\"true\"\n    providesDirectionalDerivative=\"true\"/>\n",
        )
    };
    unit_definitions(&mut x, c);
    type_definitions(&mut x, fmi3);
    log_categories(&mut x);
    x.push_str(DEFAULT_EXPERIMENT);
    x.push_str("  <ModelVariables>\n");
    x
}

/// The `start` of each input of the FMU of causality `c` carrying `scene` as
/// `resources/scene.toml` (`None`: none, the default scene), in [`inputs`] order: the
/// scene's initial value, which the FMU holds until the host sets the input
/// ([`crate::component::scene::InputSpec::initial_value`]). The error names the scene's
/// problem.
pub fn input_starts(c: Causality, scene: Option<&str>) -> Result<Vec<f64>, String> {
    let resource = scene.map(|t| Ok(t.to_string()));
    super::params::input_starts(&super::params::unset(), resource.as_ref(), c)
}

/// ` min=… max=… start=…` of input `v` with start value `start`.
fn input_attrs(v: &Variable, start: f64) -> String {
    format!("{} start=\"{}\"", range_attr(v.name), num(start))
}

/// FMI 2.0 co-simulation `modelDescription.xml` of the variant of causality `c` without a
/// scene of its own (the inputs' start values are the default scene's).
pub fn fmi2(c: Causality) -> String {
    fmi2_with(c, None).expect("the default scene builds")
}

/// FMI 3.0 co-simulation `modelDescription.xml` of the variant of causality `c` without a
/// scene of its own (the inputs' start values are the default scene's).
pub fn fmi3(c: Causality) -> String {
    fmi3_with(c, None).expect("the default scene builds")
}

/// FMI 2.0 co-simulation `modelDescription.xml` of the variant of causality `c` carrying
/// `scene` (its inputs' `start` from [`input_starts`]).
pub fn fmi2_with(c: Causality, scene: Option<&str>) -> Result<String, String> {
    let starts = input_starts(c, scene)?;
    let mut x = preamble(c, false);
    // 1-based indices, needed by <ModelStructure>
    let mut index = 0usize;
    let mut input_idx = Vec::new();
    let mut outputs = Vec::new();
    let mut param_idx = Vec::new();
    // No `time` variable in FMI 2: an independent variable has no start value (spec2
    // 2_2_3), which the FMI Library (libcosim) nevertheless reports as an error.
    for v in io_variables(c) {
        index += 1;
        let input = v.is_input(c);
        let (caus, init, start) = if input {
            input_idx.push((index, v.vr));
            ("input", "", input_attrs(v, starts[input_idx.len() - 1]))
        } else {
            outputs.push((index, v));
            ("output", " initial=\"calculated\"", String::new())
        };
        let (variability, ty) = match v.ty {
            VarType::Real => (
                "continuous",
                format!(
                    "<Real unit=\"{}\"{}{start}/>",
                    esc(v.unit),
                    display_attr(v.unit)
                ),
            ),
            VarType::Integer => ("discrete", format!("<Integer{start}/>")),
        };
        let _ = writeln!(
            x,
            "    <!-- {index} --><ScalarVariable name=\"{}\" valueReference=\"{}\" \
             causality=\"{caus}\" variability=\"{variability}\"{init} description=\"{}\">\
             {ty}</ScalarVariable>",
            esc(v.name),
            v.vr,
            esc(v.description),
        );
    }
    for p in PARAMETERS {
        index += 1;
        param_idx.push(index);
        let ty = match p.ty {
            ParamType::Real => format!("<Real {}/>", real_param_attrs(p)),
            ParamType::String => format!("<String start=\"{}\"/>", param_start(p)),
            ParamType::Boolean => format!("<Boolean start=\"{}\"/>", param_start(p)),
            ParamType::Enumeration { type_name, .. } => format!(
                "<Enumeration declaredType=\"{type_name}\" start=\"{}\"/>",
                param_start(p)
            ),
        };
        let _ = writeln!(
            x,
            "    <!-- {index} --><ScalarVariable name=\"{}\" valueReference=\"{}\" \
             causality=\"parameter\" variability=\"fixed\" initial=\"exact\" \
             description=\"{}\">{ty}</ScalarVariable>",
            esc(p.name),
            p.vr,
            esc(p.description)
        );
    }
    x.push_str("  </ModelVariables>\n  <ModelStructure>\n    <Outputs>\n");
    let join = |v: &[usize]| {
        v.iter()
            .map(|i| i.to_string())
            .collect::<Vec<_>>()
            .join(" ")
    };
    let all_inputs: Vec<usize> = input_idx.iter().map(|&(i, _)| i).collect();
    let init_deps = join(&[all_inputs, param_idx.clone()].concat());
    for (i, v) in &outputs {
        let deps: Vec<usize> = direct_dependencies(c, v)
            .iter()
            .filter_map(|d| input_idx.iter().find(|(_, vr)| *vr == d.vr).map(|p| p.0))
            .collect();
        let _ = writeln!(
            x,
            "      <Unknown index=\"{i}\" dependencies=\"{}\"/>",
            join(&deps)
        );
    }
    x.push_str("    </Outputs>\n    <InitialUnknowns>\n");
    for (i, _) in &outputs {
        let _ = writeln!(
            x,
            "      <Unknown index=\"{i}\" dependencies=\"{init_deps}\"/>"
        );
    }
    x.push_str("    </InitialUnknowns>\n  </ModelStructure>\n</fmiModelDescription>\n");
    Ok(x)
}

/// FMI 3.0 co-simulation `modelDescription.xml` of the variant of causality `c` carrying
/// `scene` (its inputs' `start` from [`input_starts`]).
pub fn fmi3_with(c: Causality, scene: Option<&str>) -> Result<String, String> {
    let starts = input_starts(c, scene)?;
    let mut starts_iter = starts.iter();
    let mut x = preamble(c, true);
    let _ = writeln!(
        x,
        "    <Float64 name=\"time\" valueReference=\"{VR_TIME}\" causality=\"independent\" \
         variability=\"continuous\" description=\"simulation time\" unit=\"s\"/>"
    );
    for v in io_variables(c) {
        let input = v.is_input(c);
        let (caus, extra) = if input {
            let start = *starts_iter.next().expect("one start per input");
            ("input", input_attrs(v, start))
        } else {
            ("output", " initial=\"calculated\"".to_string())
        };
        let (elem, variability, unit) = match v.ty {
            VarType::Real => (
                "Float64",
                "continuous",
                format!(" unit=\"{}\"{}", esc(v.unit), display_attr(v.unit)),
            ),
            VarType::Integer => ("Int32", "discrete", String::new()),
        };
        let _ = writeln!(
            x,
            "    <{elem} name=\"{}\" valueReference=\"{}\" causality=\"{caus}\" \
             variability=\"{variability}\" description=\"{}\"{unit}{extra}/>",
            esc(v.name),
            v.vr,
            esc(v.description),
        );
    }
    for p in PARAMETERS {
        let head = format!(
            "name=\"{}\" valueReference=\"{}\" causality=\"parameter\" variability=\"fixed\" \
             initial=\"exact\" description=\"{}\"",
            esc(p.name),
            p.vr,
            esc(p.description)
        );
        let _ = match p.ty {
            ParamType::Real => writeln!(x, "    <Float64 {head} {}/>", real_param_attrs(p)),
            ParamType::String => writeln!(
                x,
                "    <String {head}><Start value=\"{}\"/></String>",
                param_start(p)
            ),
            ParamType::Boolean => writeln!(x, "    <Boolean {head} start=\"{}\"/>", param_start(p)),
            ParamType::Enumeration { type_name, .. } => writeln!(
                x,
                "    <Enumeration {head} declaredType=\"{type_name}\" start=\"{}\"/>",
                param_start(p)
            ),
        };
    }
    x.push_str("  </ModelVariables>\n  <ModelStructure>\n");
    let vrs =
        |it: &mut dyn Iterator<Item = u32>| it.map(|v| v.to_string()).collect::<Vec<_>>().join(" ");
    let init_deps = vrs(&mut inputs(c)
        .map(|v| v.vr)
        .chain(PARAMETERS.iter().map(|p| p.vr)));
    for v in outputs(c) {
        let deps = vrs(&mut direct_dependencies(c, v).into_iter().map(|d| d.vr));
        let _ = writeln!(
            x,
            "    <Output valueReference=\"{}\" dependencies=\"{deps}\"/>",
            v.vr
        );
    }
    for v in outputs(c) {
        let _ = writeln!(
            x,
            "    <InitialUnknown valueReference=\"{}\" dependencies=\"{init_deps}\"/>",
            v.vr
        );
    }
    x.push_str("  </ModelStructure>\n</fmiModelDescription>\n");
    Ok(x)
}

/// The platforms the FMUs carry binaries for (FMI 2 folder, FMI 3 tuple). Other targets
/// need toolchains this build machine does not have.
pub const PLATFORMS: &[(&str, &str)] = &[("linux64", "x86_64-linux")];

/// Cells of the variable table, one row per variable of either variant.
type Row = [String; 10];

/// Causality of `v` in the FMU of causality `c` ("—" when that FMU does not show it).
fn causality_cell(c: Causality, v: &Variable) -> String {
    if v.is_input(c) {
        "input".into()
    } else if v.is_output(c) {
        "output".into()
    } else {
        "—".into()
    }
}

/// The variable table (both variants): name, value reference, type, causality in the
/// motion-driven and in the load-driven FMU, unit, display unit, range, start,
/// description (the cells as plain text).
fn rows() -> Vec<Row> {
    let shown = |u: &str| {
        variables::display_unit(u).map_or(String::new(), |(d, f)| format!("{d} (× {})", num(f)))
    };
    let range = |n: &str| {
        variables::range(n).map_or(String::new(), |(lo, hi)| {
            format!("[{}, {}]", num(lo), num(hi))
        })
    };
    let mut r = vec![[
        "time (FMI 3 only)".to_string(),
        VR_TIME.to_string(),
        "Float64".into(),
        "independent".into(),
        "independent".into(),
        "s".into(),
        String::new(),
        String::new(),
        String::new(),
        "simulation time".into(),
    ]];
    for v in variables::all() {
        let input = VARIANTS.iter().any(|&c| v.is_input(c));
        let ty = match v.ty {
            VarType::Real => "Real / Float64",
            VarType::Integer => "Integer / Int32",
        };
        let unit = match v.ty {
            VarType::Real => v.unit,
            VarType::Integer => "",
        };
        r.push([
            v.name.into(),
            v.vr.to_string(),
            ty.into(),
            causality_cell(Causality::Motion, v),
            causality_cell(Causality::Load, v),
            unit.into(),
            shown(unit),
            range(v.name),
            if input { "0".into() } else { String::new() },
            v.description.into(),
        ]);
    }
    for p in PARAMETERS {
        let (ty, start) = match p.ty {
            ParamType::Real => ("Real / Float64".to_string(), p.start.to_string()),
            ParamType::String => ("String".to_string(), format!("\"{}\"", p.start)),
            ParamType::Boolean => ("Boolean".to_string(), p.start.to_string()),
            ParamType::Enumeration { type_name, items } => (
                format!(
                    "Enumeration {type_name}: {}",
                    items
                        .iter()
                        .enumerate()
                        .map(|(k, i)| format!("{k} {i}"))
                        .collect::<Vec<_>>()
                        .join(", ")
                ),
                format!(
                    "{} ({})",
                    p.start,
                    p.start
                        .parse::<usize>()
                        .ok()
                        .and_then(|k| items.get(k))
                        .unwrap_or(&"?")
                ),
            ),
        };
        r.push([
            p.name.into(),
            p.vr.to_string(),
            ty,
            "parameter (fixed)".into(),
            "parameter (fixed)".into(),
            p.unit.into(),
            shown(p.unit),
            range(p.name),
            start,
            p.description.into(),
        ]);
    }
    r
}

const HEADER: [&str; 10] = [
    "name",
    "value reference",
    "type",
    "causality (motion-driven FMU)",
    "causality (load-driven FMU)",
    "unit",
    "display unit (× factor)",
    "range (SI)",
    "start",
    "description",
];

fn platform_line() -> String {
    platform_line_on(PLATFORMS)
}

fn platform_line_on(platforms: &[(&str, &str)]) -> String {
    let list: Vec<String> = platforms
        .iter()
        .map(|(a, b)| format!("{a} (FMI 2) / {b} (FMI 3)"))
        .collect();
    format!(
        "Platforms with a binary in the FMUs: {}. Other platforms need a build of the \
         library there (`scripts/build-fmu`).",
        list.join(", ")
    )
}

/// The Markdown variable table of `docs/fmi.md` (between the `BEGIN/END generated` markers).
pub fn markdown_table() -> String {
    let mut t = String::new();
    t.push_str("| FMU | archives | GUID / instantiationToken of this build |\n|---|---|---|\n");
    for c in VARIANTS {
        let _ = writeln!(
            t,
            "| {}-driven | `{}`, `{}` | `{}` |",
            variant_name(c),
            archive_name(c, "fmi2"),
            archive_name(c, "fmi3"),
            guid(c)
        );
    }
    let _ = writeln!(t, "\n{}\n", platform_line());
    let _ = writeln!(t, "| {} |", HEADER.join(" | "));
    let _ = writeln!(t, "|{}", "---|".repeat(HEADER.len()));
    for mut row in rows() {
        row[0] = match row[0].split_once(' ') {
            Some((name, note)) => format!("`{name}` {note}"),
            None => format!("`{}`", row[0]),
        };
        let cells: Vec<String> = row.iter().map(|c| c.replace('|', "\\|")).collect();
        let _ = writeln!(t, "| {} |", cells.join(" | "));
    }
    t
}

/// What the host does with a variant (for its documentation page).
const fn usage(c: Causality) -> &'static str {
    match c {
        Causality::Motion => {
            "Co-simulation, motion-driven: the host sets the shaft's motion \
             (<code>shaft.*</code>) and speed and reads the bearing's forces, moments, \
             stiffness <code>K.i.j</code> and damping <code>C.i.j</code>."
        }
        Causality::Load => {
            "Co-simulation, load-driven: the host sets the loads on the inner ring \
             (<code>load.*</code>) and the shaft speed; the ring (its mass plus \
             <code>model.attached_mass_kg</code>) moves inside the FMU, which returns its \
             motion (<code>shaft.*</code>) and the bearing's forces, moments, \
             <code>K.i.j</code> and <code>C.i.j</code>. By default the ring starts in static \
             equilibrium under the loads set before initialisation ends."
        }
    }
}

/// `documentation/index.html` of the FMU of causality `c`: what it is, its platforms and
/// the variable table, generated like the model descriptions.
pub fn documentation_html(c: Causality) -> String {
    documentation_html_on(c, PLATFORMS)
}

/// [`documentation_html`] for an FMU carrying binaries for `platforms` (FMI 2 folder, FMI 3
/// tuple), e.g. `linux64` and `win64` when `scripts/build-fmu --win64` packs both.
pub fn documentation_html_on(c: Causality, platforms: &[(&str, &str)]) -> String {
    let mut h = String::new();
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head><meta charset=\"utf-8\">\
         <title>{name} {ver}</title>\n<style>body{{font-family:sans-serif;max-width:70em}}\
         table{{border-collapse:collapse}}td,th{{border:1px solid #999;padding:2px 6px;\
         text-align:left;vertical-align:top}}</style></head>\n<body>\n<h1>{name} {ver}</h1>\n\
         <p>{}.</p>\n<p>{} Outputs are valid from the end of initialisation on. Units are \
         SI; the display units are those people read.</p>\n\
         <p>{}</p>\n<p>GUID / instantiationToken: <code>{}</code>. License: \
         <a href=\"licenses/license.txt\">licenses/license.txt</a>.</p>\n<table>\n<tr>",
        esc(description(c)),
        usage(c),
        esc(&platform_line_on(platforms)),
        guid(c),
        name = model_name(c),
        ver = env!("CARGO_PKG_VERSION")
    );
    for col in HEADER {
        let _ = write!(h, "<th>{}</th>", esc(col));
    }
    h.push_str("</tr>\n");
    for row in rows() {
        h.push_str("<tr>");
        for (i, cell) in row.iter().enumerate() {
            if i == 0 {
                let _ = write!(h, "<td><code>{}</code></td>", esc(cell));
            } else {
                let _ = write!(h, "<td>{}</td>", esc(cell));
            }
        }
        h.push_str("</tr>\n");
    }
    h.push_str("</table>\n</body>\n</html>\n");
    h
}

/// `documentation/licenses/license.txt` of the FMUs (the crate's license).
pub fn license_text() -> String {
    format!(
        "raceway {} is licensed under {} (SPDX), at your option:\n\
         the MIT license or the Apache License, Version 2.0.\n\n\
         The FMU's binary contains raceway and the Rust crates it depends on, each under its \
         own permissive license (MIT, Apache-2.0 or compatible).\n",
        env!("CARGO_PKG_VERSION"),
        env!("CARGO_PKG_LICENSE")
    )
}

/// Marker lines around the generated table in `docs/fmi.md`.
pub const DOC_BEGIN: &str =
    "<!-- BEGIN generated variable table (scripts/build-fmu regenerates it) -->";
/// See [`DOC_BEGIN`].
pub const DOC_END: &str = "<!-- END generated variable table -->";

/// `doc` with the text between the markers replaced by [`markdown_table`]; `None` when the
/// markers are missing.
pub fn update_doc(doc: &str) -> Option<String> {
    let b = doc.find(DOC_BEGIN)? + DOC_BEGIN.len();
    let e = doc[b..].find(DOC_END)? + b;
    Some(format!(
        "{}\n\n{}\n{}",
        &doc[..b],
        markdown_table(),
        &doc[e..]
    ))
}
