//! `modelDescription.xml` (FMI 2.0 and 3.0), the documentation table and the GUID, all
//! generated from the one variable table in [`crate::component::variables`].
//!
//! Layout and rules: spec2 `2_2_common_schema.adoc`, `4_3_co-simulation_schema.adoc`;
//! spec3 `2_4_common_schema.adoc`, `4_4_co-simulation_schema.adoc`; the checks of
//! `fmpy.validation` (every output in `<Outputs>`, the exact `<InitialUnknowns>` set,
//! start values on inputs, every unit defined, exactly one independent variable in FMI 3).

use crate::component::variables::{
    self, Causality, ParamType, Parameter, Variable, DAMPING, DISPLAY_UNITS, PARAMETERS, RANGES,
    SCALARS, STIFFNESS,
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
    h = fnv(h, &[v.role as u8]);
    fnv(h, v.description.as_bytes())
}

const fn hash_parameter(mut h: u64, p: &Parameter) -> u64 {
    h = fnv(h, p.name.as_bytes());
    h = fnv(h, &p.vr.to_le_bytes());
    h = fnv(h, &[p.ty as u8]);
    h = fnv(h, p.unit.as_bytes());
    h = fnv(h, p.start.as_bytes());
    fnv(h, p.description.as_bytes())
}

/// FNV-1a over the whole variable table, the crate version and the generator format,
/// from a given offset basis (two bases give the 128 bits of the GUID).
const fn table_hash(basis: u64) -> u64 {
    let mut h = fnv(basis, GENERATOR_FORMAT.as_bytes());
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

const fn guid_bytes() -> [u8; 38] {
    const HEX: &[u8; 16] = b"0123456789abcdef";
    let a = table_hash(0xcbf2_9ce4_8422_2325);
    let b = table_hash(0x6c62_272e_07bb_0142);
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

const GUID_BYTES: [u8; 38] = guid_bytes();

/// The FMI 2 `guid` and FMI 3 `instantiationToken`: a hash of the variable table, the crate
/// version and the XML generator's format, evaluated at compile time. The binary checks it
/// at instantiation; the packer writes the same constant into both model descriptions.
pub const GUID: &str = match core::str::from_utf8(&GUID_BYTES) {
    Ok(s) => s,
    Err(_) => panic!("GUID is ASCII"),
};

/// The variables a motion-driven FMU shows (inputs and outputs), in table order.
pub fn io_variables() -> impl Iterator<Item = &'static Variable> {
    variables::all().filter(|v| v.is_input(Causality::Motion) || v.is_output(Causality::Motion))
}

/// The inputs of the motion-driven FMU, in table order.
pub fn inputs() -> impl Iterator<Item = &'static Variable> {
    variables::all().filter(|v| v.is_input(Causality::Motion))
}

/// The outputs of the motion-driven FMU, in table order.
pub fn outputs() -> impl Iterator<Item = &'static Variable> {
    variables::all().filter(|v| v.is_output(Causality::Motion))
}

/// Exponents (kg, m, s, rad) of one factor of a unit spelling such as `N.m.s/rad`.
fn factor(f: &str) -> Option<[i32; 4]> {
    Some(match f {
        "1" => [0, 0, 0, 0],
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

fn units() -> Vec<&'static str> {
    let mut u: Vec<&str> = std::iter::once("s")
        .chain(io_variables().map(|v| v.unit))
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

fn unit_definitions(x: &mut String) {
    x.push_str("  <UnitDefinitions>\n");
    for u in units() {
        let e = base_unit(u).unwrap_or_else(|| panic!("unit `{u}` has no base-unit rule"));
        let mut attrs = String::new();
        for (name, k) in ["kg", "m", "s", "rad"].iter().zip(e) {
            if k != 0 {
                let _ = write!(attrs, " {name}=\"{k}\"");
            }
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

const DESCRIPTION: &str =
    "Ball bearing (raceway): forces, moments, stiffness and damping from the shaft's motion";
const DEFAULT_EXPERIMENT: &str =
    "  <DefaultExperiment startTime=\"0\" stopTime=\"0.1\" stepSize=\"0.0001\"/>\n";

fn param_start(p: &Parameter) -> String {
    esc(p.start)
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

/// FMI 2.0 co-simulation `modelDescription.xml`.
pub fn fmi2() -> String {
    let mut x = String::new();
    let _ = write!(
        x,
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n\
         <fmiModelDescription fmiVersion=\"2.0\" modelName=\"raceway\" guid=\"{GUID}\"\n  \
         description=\"{DESCRIPTION}\"\n  version=\"{ver}\" generationTool=\"raceway {ver}\" \
         variableNamingConvention=\"structured\" numberOfEventIndicators=\"0\">\n  \
         <CoSimulation modelIdentifier=\"{MODEL_IDENTIFIER}\" \
         canHandleVariableCommunicationStepSize=\"true\" canInterpolateInputs=\"true\"\n    \
         maxOutputDerivativeOrder=\"1\" canRunAsynchronuously=\"false\" \
         canBeInstantiatedOnlyOncePerProcess=\"false\"\n    \
         canNotUseMemoryManagementFunctions=\"true\" canGetAndSetFMUstate=\"true\" \
         canSerializeFMUstate=\"true\"\n    providesDirectionalDerivative=\"true\"/>\n",
        ver = env!("CARGO_PKG_VERSION")
    );
    unit_definitions(&mut x);
    log_categories(&mut x);
    x.push_str(DEFAULT_EXPERIMENT);
    x.push_str("  <ModelVariables>\n");
    // 1-based indices, needed by <ModelStructure>
    let mut index = 0usize;
    let mut input_idx = Vec::new();
    let mut output_idx = Vec::new();
    let mut param_idx = Vec::new();
    // No `time` variable in FMI 2: an independent variable has no start value (spec2
    // 2_2_3), which the FMI Library (libcosim) nevertheless reports as an error.
    for v in io_variables() {
        index += 1;
        let input = v.is_input(Causality::Motion);
        let (caus, init, start) = if input {
            input_idx.push(index);
            ("input", "", format!("{} start=\"0\"", range_attr(v.name)))
        } else {
            output_idx.push(index);
            ("output", " initial=\"calculated\"", String::new())
        };
        let _ = writeln!(
            x,
            "    <!-- {index} --><ScalarVariable name=\"{}\" valueReference=\"{}\" \
             causality=\"{caus}\" variability=\"continuous\"{init} description=\"{}\">\
             <Real unit=\"{}\"{}{start}/></ScalarVariable>",
            esc(v.name),
            v.vr,
            esc(v.description),
            esc(v.unit),
            display_attr(v.unit)
        );
    }
    for p in PARAMETERS {
        index += 1;
        param_idx.push(index);
        let ty = match p.ty {
            ParamType::Real => format!(
                "<Real unit=\"{}\"{}{} start=\"{}\"/>",
                esc(p.unit),
                display_attr(p.unit),
                range_attr(p.name),
                param_start(p)
            ),
            ParamType::String => format!("<String start=\"{}\"/>", param_start(p)),
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
    let deps = join(&input_idx);
    let init_deps = join(&[input_idx.clone(), param_idx.clone()].concat());
    for i in &output_idx {
        let _ = writeln!(x, "      <Unknown index=\"{i}\" dependencies=\"{deps}\"/>");
    }
    x.push_str("    </Outputs>\n    <InitialUnknowns>\n");
    for i in &output_idx {
        let _ = writeln!(
            x,
            "      <Unknown index=\"{i}\" dependencies=\"{init_deps}\"/>"
        );
    }
    x.push_str("    </InitialUnknowns>\n  </ModelStructure>\n</fmiModelDescription>\n");
    x
}

/// FMI 3.0 co-simulation `modelDescription.xml`.
pub fn fmi3() -> String {
    let mut x = String::new();
    let _ = write!(
        x,
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n\
         <fmiModelDescription fmiVersion=\"3.0\" modelName=\"raceway\" \
         instantiationToken=\"{GUID}\"\n  description=\"{DESCRIPTION}\"\n  \
         version=\"{ver}\" generationTool=\"raceway {ver}\" variableNamingConvention=\"structured\">\n  \
         <CoSimulation modelIdentifier=\"{MODEL_IDENTIFIER}\" \
         canHandleVariableCommunicationStepSize=\"true\"\n    maxOutputDerivativeOrder=\"1\" \
         canGetAndSetFMUState=\"true\" canSerializeFMUState=\"true\"\n    \
         providesDirectionalDerivatives=\"true\" providesAdjointDerivatives=\"false\" \
         hasEventMode=\"false\"\n    canBeInstantiatedOnlyOncePerProcess=\"false\"/>\n",
        ver = env!("CARGO_PKG_VERSION")
    );
    unit_definitions(&mut x);
    log_categories(&mut x);
    x.push_str(DEFAULT_EXPERIMENT);
    x.push_str("  <ModelVariables>\n");
    let _ = writeln!(
        x,
        "    <Float64 name=\"time\" valueReference=\"{VR_TIME}\" causality=\"independent\" \
         variability=\"continuous\" description=\"simulation time\" unit=\"s\"/>"
    );
    for v in io_variables() {
        let input = v.is_input(Causality::Motion);
        let (caus, extra) = if input {
            ("input", format!("{} start=\"0\"", range_attr(v.name)))
        } else {
            ("output", " initial=\"calculated\"".to_string())
        };
        let _ = writeln!(
            x,
            "    <Float64 name=\"{}\" valueReference=\"{}\" causality=\"{caus}\" \
             variability=\"continuous\" description=\"{}\" unit=\"{}\"{}{extra}/>",
            esc(v.name),
            v.vr,
            esc(v.description),
            esc(v.unit),
            display_attr(v.unit)
        );
    }
    for p in PARAMETERS {
        match p.ty {
            ParamType::Real => {
                let _ = writeln!(
                    x,
                    "    <Float64 name=\"{}\" valueReference=\"{}\" causality=\"parameter\" \
                     variability=\"fixed\" initial=\"exact\" description=\"{}\" unit=\"{}\"{}{} \
                     start=\"{}\"/>",
                    esc(p.name),
                    p.vr,
                    esc(p.description),
                    esc(p.unit),
                    display_attr(p.unit),
                    range_attr(p.name),
                    param_start(p)
                );
            }
            ParamType::String => {
                let _ = writeln!(
                    x,
                    "    <String name=\"{}\" valueReference=\"{}\" causality=\"parameter\" \
                     variability=\"fixed\" initial=\"exact\" description=\"{}\">\
                     <Start value=\"{}\"/></String>",
                    esc(p.name),
                    p.vr,
                    esc(p.description),
                    param_start(p)
                );
            }
        }
    }
    x.push_str("  </ModelVariables>\n  <ModelStructure>\n");
    let vrs =
        |it: &mut dyn Iterator<Item = u32>| it.map(|v| v.to_string()).collect::<Vec<_>>().join(" ");
    let deps = vrs(&mut inputs().map(|v| v.vr));
    let init_deps = vrs(&mut inputs()
        .map(|v| v.vr)
        .chain(PARAMETERS.iter().map(|p| p.vr)));
    for v in outputs() {
        let _ = writeln!(
            x,
            "    <Output valueReference=\"{}\" dependencies=\"{deps}\"/>",
            v.vr
        );
    }
    for v in outputs() {
        let _ = writeln!(
            x,
            "    <InitialUnknown valueReference=\"{}\" dependencies=\"{init_deps}\"/>",
            v.vr
        );
    }
    x.push_str("  </ModelStructure>\n</fmiModelDescription>\n");
    x
}

/// The platforms the FMUs carry binaries for (FMI 2 folder, FMI 3 tuple). Other targets
/// need toolchains this build machine does not have.
pub const PLATFORMS: &[(&str, &str)] = &[("linux64", "x86_64-linux")];

/// One row of the variable table: name, value reference, causality, unit, display unit,
/// range, start, description (the cells as plain text).
fn rows() -> Vec<[String; 8]> {
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
        "independent".into(),
        "s".into(),
        String::new(),
        String::new(),
        String::new(),
        "simulation time".into(),
    ]];
    for v in io_variables() {
        let (c, s) = if v.is_input(Causality::Motion) {
            ("input", "0")
        } else {
            ("output", "")
        };
        r.push([
            v.name.into(),
            v.vr.to_string(),
            c.into(),
            v.unit.into(),
            shown(v.unit),
            range(v.name),
            s.into(),
            v.description.into(),
        ]);
    }
    for p in PARAMETERS {
        let (ty, start) = match p.ty {
            ParamType::Real => ("", p.start.to_string()),
            ParamType::String => (" (string)", format!("\"{}\"", p.start)),
        };
        r.push([
            p.name.into(),
            p.vr.to_string(),
            format!("parameter (fixed){ty}"),
            p.unit.into(),
            shown(p.unit),
            range(p.name),
            start,
            p.description.into(),
        ]);
    }
    r
}

const HEADER: [&str; 8] = [
    "name",
    "value reference",
    "causality",
    "unit",
    "display unit (× factor)",
    "range (SI)",
    "start",
    "description",
];

fn platform_line() -> String {
    let list: Vec<String> = PLATFORMS
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
    let _ = writeln!(t, "GUID / instantiationToken of this build: `{GUID}`\n");
    let _ = writeln!(t, "{}\n", platform_line());
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

/// `documentation/index.html` of the FMUs: what the FMU is, its platforms and the variable
/// table, generated like the model descriptions.
pub fn documentation_html() -> String {
    let mut h = String::new();
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head><meta charset=\"utf-8\">\
         <title>raceway {ver}</title>\n<style>body{{font-family:sans-serif;max-width:70em}}\
         table{{border-collapse:collapse}}td,th{{border:1px solid #999;padding:2px 6px;\
         text-align:left;vertical-align:top}}</style></head>\n<body>\n<h1>raceway {ver}</h1>\n\
         <p>{}.</p>\n<p>Co-simulation, motion-driven: the host sets the shaft's motion \
         (<code>shaft.*</code>) and reads the bearing's forces, moments, stiffness \
         <code>K.i.j</code> and damping <code>C.i.j</code>. Outputs are valid from the end of \
         initialisation on. Units are SI; the display units are those people read.</p>\n\
         <p>{}</p>\n<p>GUID / instantiationToken: <code>{GUID}</code>. License: \
         <a href=\"licenses/license.txt\">licenses/license.txt</a>.</p>\n<table>\n<tr>",
        esc(DESCRIPTION),
        esc(&platform_line()),
        ver = env!("CARGO_PKG_VERSION")
    );
    for c in HEADER {
        let _ = write!(h, "<th>{}</th>", esc(c));
    }
    h.push_str("</tr>\n");
    for row in rows() {
        h.push_str("<tr>");
        for (i, c) in row.iter().enumerate() {
            if i == 0 {
                let _ = write!(h, "<td><code>{}</code></td>", esc(c));
            } else {
                let _ = write!(h, "<td>{}</td>", esc(c));
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
