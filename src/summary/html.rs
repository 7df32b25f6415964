//! `report.html`: one self-contained page per run (no network, no script): the scene and its
//! provenance, the summary as tables, every plot inline as SVG and the characteristic lines
//! with their evidence. It renders what [`summary_of`](super::summary_of) computed and what
//! the plots drew; it computes nothing itself.

use super::{Ctx, Summary};
use crate::analysis::FoundPeak;
use serde_json::Value;
use std::fmt::Write as _;

/// Where a run came from: what the page states beside the scene.
#[derive(Debug, Clone, Default)]
pub struct Provenance {
    /// The program's version.
    pub version: String,
    /// The command line as given.
    pub command: String,
    /// Path of the scene file (or "default" for the embedded scene).
    pub scene_file: String,
}

/// One plot of the run: its file name (e.g. `spectrum.png`) and its drawing as SVG text.
#[derive(Debug, Clone)]
pub struct Figure {
    /// File name of the PNG beside the page.
    pub file: String,
    /// The same drawing as SVG.
    pub svg: String,
}

/// FNV-1a (64 bit) of the scene as run (overrides applied, defaults filled), in the
/// canonical JSON of its serde form: two runs with the same hash ran the same scene.
pub fn scene_hash(scene: &crate::component::Scene) -> String {
    let text = serde_json::to_string(scene).unwrap_or_default();
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in text.bytes() {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    format!("{h:016x}")
}

/// Escape text for HTML.
pub fn esc(s: &str) -> String {
    let mut o = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => o.push_str("&amp;"),
            '<' => o.push_str("&lt;"),
            '>' => o.push_str("&gt;"),
            '"' => o.push_str("&quot;"),
            '\'' => o.push_str("&#39;"),
            c => o.push(c),
        }
    }
    o
}

/// A number for a table: four significant digits, plain between 1e-3 and 1e6.
pub(super) fn num(v: f64) -> String {
    if !v.is_finite() {
        return "–".into();
    }
    if v == 0.0 {
        return "0".into();
    }
    let a = v.abs();
    if !(1e-3..1e6).contains(&a) {
        return format!("{v:.3e}");
    }
    let digits = (3 - a.log10().floor() as i32).max(0) as usize;
    let s = format!("{v:.digits$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// A JSON value as table-cell HTML: numbers formatted, lists joined, objects as a nested
/// table.
fn cell(v: &Value) -> String {
    match v {
        Value::Null => "–".into(),
        Value::Bool(b) => b.to_string(),
        Value::Number(n) => n.as_f64().map(num).unwrap_or_else(|| n.to_string()),
        Value::String(s) => esc(s),
        Value::Array(a) if a.iter().all(|x| !x.is_object() && !x.is_array()) => {
            a.iter().map(cell).collect::<Vec<_>>().join(", ")
        }
        Value::Array(a) => a.iter().map(cell).collect::<Vec<_>>().join("<br>"),
        Value::Object(m) => kv_table(m.iter()),
    }
}

/// What a summary key means, where its name alone does not say (the ratings' fields), with
/// its unit from the label (`P [N]` → `equivalent dynamic load P (N)`; docs/columns.md).
fn key_label(k: &str) -> String {
    let known = [
        ("P", "equivalent dynamic load P"),
        ("P0", "equivalent static load P0"),
        ("C", "basic dynamic load rating C"),
        ("C0", "basic static load rating C0"),
        ("Cu", "fatigue load limit Cu"),
        ("S0", "static safety factor S0"),
        ("a_ISO", "life modification factor a_ISO"),
        ("peak_pressure", "peak Hertz pressure"),
        ("L10", "basic rating life L10"),
        ("L10r", "reference rating life L10r"),
        ("L10mr", "modified reference rating life L10mr"),
        ("life_inner", "inner raceway life"),
        ("life_outer", "outer raceway life"),
        ("kappa", "viscosity ratio kappa"),
    ];
    let (name, unit) = crate::units::split_label(k);
    let text = known
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, l)| l.to_string())
        .unwrap_or_else(|| name.replace('_', " "));
    match unit {
        Some("1") | None => text,
        Some(u) => format!(
            "{text} ({})",
            u.replace("mm2/s", "mm²/s").replace("N.m", "N m")
        ),
    }
}

/// Key–value rows.
fn kv_table<'a>(rows: impl Iterator<Item = (&'a String, &'a Value)>) -> String {
    let mut t = String::from("<table class=\"kv\">");
    for (k, v) in rows {
        let _ = write!(
            t,
            "<tr><th>{}</th><td>{}</td></tr>",
            esc(&key_label(k)),
            cell(v)
        );
    }
    t + "</table>"
}

/// The summary's sections: heading and the JSON keys (or key prefixes ending in `*`) it
/// shows. Keys no section claims go to "Other results", so nothing computed is left out.
const SECTIONS: [(&str, &[&str]); 10] = [
    (
        "Run",
        &["scene", "level", "duration [s]", "cpu [s]", "load_average"],
    ),
    ("Bearing", &["bearing"]),
    ("Operating point", &["operating_point"]),
    (
        "Loads and pressures",
        &[
            "peak_force [N]",
            "peak_contact_load [N]",
            "peak_pressure [Pa]",
            "start_*",
        ],
    ),
    ("Lubricant film", &["film"]),
    ("Friction and power", &["friction"]),
    ("Temperatures and clearance", &["thermal"]),
    (
        "Cage",
        &[
            "final_cage_slip",
            "cage_*",
            "peak_pocket_force [N]",
            "peak_guide_force [N]",
        ],
    ),
    ("Ratings, life and safety", &["rating"]),
    ("Bearing set: rows rated on their own loads", &["set"]),
];

/// Keys shown in their own section (the lines and warnings).
const OWN: [&str; 3] = ["frequencies", "envelope_frequencies", "warnings"];

fn claims(pattern: &str, key: &str) -> bool {
    match pattern.strip_suffix('*') {
        Some(p) => key.starts_with(p),
        None => key == pattern,
    }
}

/// The found-lines table of one spectrum: what was expected, the tolerance, the nearest
/// peak, its distance and height over the local floor, and the verdict.
fn lines_table(found: &[FoundPeak], scale: f64) -> String {
    let mut t = String::from(
        "<table class=\"lines\"><tr><th>line</th><th>expected (Hz)</th><th>tolerance (± Hz)</th>\
         <th>nearest peak (Hz)</th><th>deviation (Hz)</th><th>over floor</th><th>verdict</th></tr>",
    );
    for p in found {
        let _ = write!(
            t,
            "<tr class=\"{}\"><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>",
            if p.is_found() { "found" } else { "missing" },
            esc(&p.label),
            num(p.expected),
            num(p.tol_hz),
            num(p.found),
            num(p.deviation()),
            if p.found.is_finite() { num(p.over_floor) } else { "–".into() },
            esc(&p.verdict_text(scale))
        );
    }
    t + "</table>"
}

const STYLE: &str = "body{font-family:sans-serif;margin:1.5em auto;max-width:1100px;color:#222;padding:0 1em}\
h1{font-size:1.5em;margin-bottom:.2em}h2{font-size:1.2em;border-bottom:1px solid #ccc;margin-top:1.6em}\
h3{font-size:1.05em}table{border-collapse:collapse;margin:.4em 0}th,td{border:1px solid #ddd;padding:.2em .5em;\
text-align:left;vertical-align:top}table.kv th{background:#f4f4f4;font-weight:normal;width:22em}\
table.kv table.kv th{width:auto}table.lines td:nth-child(n+2):nth-child(-n+6){text-align:right;\
font-variant-numeric:tabular-nums}tr.found td:first-child{color:#060;font-weight:bold}\
tr.missing td{color:#666}.warn{color:#a00}figure{margin:1em 0}figure svg{width:100%;height:auto;\
border:1px solid #eee}figcaption{font-size:.9em;color:#555}pre{background:#f7f7f7;padding:.6em;\
overflow-x:auto;font-size:.85em}.prov td,.prov th{font-size:.95em}";

/// The page of a run: `sm` the summary [`summary_of`](super::summary_of) made of `c`,
/// `figures` the run's plots.
pub fn report_html(c: &Ctx, sm: &Summary, figures: &[Figure], prov: &Provenance) -> String {
    let mut h = String::new();
    let title = format!("raceway run: {} ({})", c.name, c.scene.title);
    let _ = writeln!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\
         <title>{}</title><style>{STYLE}</style></head><body>\n<h1>{}</h1>",
        esc(&title),
        esc(&title)
    );
    // Provenance.
    let _ = writeln!(
        h,
        "<table class=\"kv prov\"><tr><th>program</th><td>raceway {}</td></tr>\
         <tr><th>scene file</th><td>{}</td></tr><tr><th>scene hash (FNV-1a of the scene as run)</th><td><code>{}</code></td></tr>\
         <tr><th>command</th><td><code>{}</code></td></tr>\
         <tr><th>thread CPU of the run</th><td>{} s</td></tr><tr><th>load average (1, 5, 15 min)</th><td>{}</td></tr>\
         <tr><th>level, driven by</th><td>{}, {:?}</td></tr></table>",
        esc(&prov.version),
        esc(&prov.scene_file),
        scene_hash(c.scene),
        esc(&prov.command),
        num(c.cpu_s),
        esc(sm.json.get("load_average").and_then(Value::as_str).unwrap_or("unknown")),
        esc(c.scene.model.level.name()),
        c.scene.model.causality
    );
    // Warnings first: what the reader must not miss.
    if let Some(Value::Array(w)) = sm.json.get("warnings") {
        h += "<h2>Warnings</h2>";
        if w.is_empty() {
            h += "<p>none</p>\n";
        } else {
            h += "<ul class=\"warn\">";
            for x in w {
                let _ = write!(h, "<li>{}</li>", cell(x));
            }
            h += "</ul>\n";
        }
    }
    h += "<h2>Summary</h2>\n";
    for (head, keys) in SECTIONS {
        let rows: Vec<(&String, &Value)> = sm
            .json
            .iter()
            .filter(|(k, _)| keys.iter().any(|p| claims(p, k)))
            .collect();
        if rows.is_empty() {
            continue;
        }
        let _ = write!(h, "<h3>{}</h3>", esc(head));
        // A section of one object shows the object's fields.
        match rows.as_slice() {
            [(k, v)] if k.as_str() == "set" => h += &super::sets::html_table(v),
            [(_, Value::Object(m))] => h += &kv_table(m.iter()),
            _ => h += &kv_table(rows.into_iter()),
        }
        h.push('\n');
    }
    let other: Vec<(&String, &Value)> = sm
        .json
        .iter()
        .filter(|(k, _)| {
            !OWN.contains(&k.as_str())
                && !SECTIONS
                    .iter()
                    .any(|(_, keys)| keys.iter().any(|p| claims(p, k)))
        })
        .collect();
    if !other.is_empty() {
        h += "<h3>Other results</h3>";
        h += &kv_table(other.into_iter());
        h.push('\n');
    }
    // Lines with their evidence.
    let scale = c.record_scale();
    let _ = writeln!(
        h,
        "<h2>Characteristic lines</h2>\n<p>Spectrum of <code>{}</code> ({}) over the second half of the run \
         (Hann window, bins {} Hz). A line is found when a peak (interpolated between bins) lies within the \
         tolerance of the expected frequency and stands at least {} times above the median floor in [f/2, 2f].</p>",
        esc(c.signal.0),
        esc(c.signal.1),
        num(c.spec.resolution()),
        crate::analysis::FOUND_OVER_FLOOR
    );
    h += &lines_table(&c.found, scale);
    if let Some((_, band, found)) = &c.envelope {
        let _ = writeln!(
            h,
            "<h3>Envelope spectrum (defect scene; band {})</h3>",
            band.map_or("whole signal".to_string(), |(lo, hi)| format!(
                "{lo:.0}–{hi:.0} Hz"
            ))
        );
        h += &lines_table(found, scale);
    }
    // Plots.
    h += "<h2>Plots</h2>\n";
    if figures.is_empty() {
        h += "<p>no plots were made (see the warnings of the run)</p>\n";
    }
    for f in figures {
        // The SVG's own XML prologue (if any) is dropped: inline SVG starts at <svg.
        let svg = f.svg.find("<svg").map_or(f.svg.as_str(), |i| &f.svg[i..]);
        let _ = writeln!(
            h,
            "<figure id=\"{}\">{svg}<figcaption>{} (also <a href=\"{}\">PNG</a>)</figcaption></figure>",
            esc(f.file.trim_end_matches(".png")),
            esc(&f.file),
            esc(&f.file)
        );
    }
    // The scene as run and the text summary.
    let toml = toml::to_string_pretty(c.scene).unwrap_or_else(|e| format!("(not shown: {e})"));
    let _ = writeln!(
        h,
        "<h2>Scene as run</h2>\n<pre>{}</pre>\n<h2>Text summary</h2>\n<pre>{}</pre>\n</body></html>",
        esc(&toml),
        esc(&sm.text)
    );
    h
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn escapes_markup_and_formats_numbers() {
        assert_eq!(esc("<a & \"b\">"), "&lt;a &amp; &quot;b&quot;&gt;");
        assert_eq!(num(1234.5678), "1235");
        assert_eq!(num(0.012345), "0.01235");
        assert_eq!(num(2.0), "2");
        assert_eq!(num(1.5e9), "1.500e9");
        assert_eq!(num(f64::NAN), "–");
    }

    #[test]
    fn scene_hash_tells_scenes_apart() {
        let a = crate::component::Scene::default_scene();
        let mut b = a.clone();
        assert_eq!(scene_hash(&a), scene_hash(&b));
        b.run.duration_s *= 2.0;
        assert_ne!(scene_hash(&a), scene_hash(&b));
    }
}
