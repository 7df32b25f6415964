//! Sweep rows: one row per point (flattened summary with units in the names), their files,
//! the CSV and its exact number round trip.

use super::*;

/// The summary columns that are measurements of the machine, not results: they differ from
/// run to run; every other column is the same bit for bit whatever the threads or shards.
pub const MEASUREMENTS: [&str; 2] = ["cpu [s]", "load_average"];

/// A summary key's name and unit (`peak_force [N]` → `peak_force`, `N`;
/// [`crate::units::split_label`]).
pub(super) fn split_unit(key: &str) -> (&str, Option<&str>) {
    crate::units::split_label(key)
}

/// Flatten a summary into columns: nested keys joined by dots, the unit of a key moved to
/// the end (`peak_force [N]: [x, y, z]` → `peak_force.x [N]`, ...), arrays of labelled
/// tables by their label (`frequencies.BPFO.expected [Hz]`), arrays of strings joined by
/// `; ` (docs/columns.md).
pub fn flatten(prefix: &str, v: &Json, out: &mut Vec<(String, Json)>) {
    flatten_unit(prefix, None, v, out)
}

pub(super) fn flatten_unit(
    prefix: &str,
    unit: Option<&str>,
    v: &Json,
    out: &mut Vec<(String, Json)>,
) {
    let join = |k: &str| {
        if prefix.is_empty() {
            k.to_string()
        } else {
            format!("{prefix}.{k}")
        }
    };
    match v {
        Json::Object(m) => {
            for (k, x) in m {
                let (stem, u) = split_unit(k);
                flatten_unit(&join(stem), u.or(unit), x, out);
            }
        }
        Json::Array(a) if a.iter().all(Json::is_string) => {
            let s: Vec<&str> = a.iter().filter_map(Json::as_str).collect();
            out.push((prefix.to_string(), Json::from(s.join("; "))));
        }
        Json::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                let name = match x.get("label").and_then(Json::as_str) {
                    Some(l) => l.to_string(),
                    None if a.len() == 3 => ["x", "y", "z"][i].to_string(),
                    None => i.to_string(),
                };
                let x = match x {
                    Json::Object(m) if m.contains_key("label") => {
                        let mut m = m.clone();
                        m.remove("label");
                        Json::Object(m)
                    }
                    other => other.clone(),
                };
                flatten_unit(&join(&name), unit, &x, out);
            }
        }
        leaf => {
            let name = crate::units::label(prefix, unit.unwrap_or(""));
            out.push((name, leaf.clone()));
        }
    }
}

/// Write a file atomically ([`crate::fsutil::write_atomic`]: a temporary file in the same
/// folder, then a rename), making the folder first, so a reader (or a resumed sweep) sees the
/// whole file or none.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let io = |e: std::io::Error| Error::Io(format!("cannot write `{}`: {e}", path.display()));
    std::fs::create_dir_all(path.parent().unwrap_or(Path::new("."))).map_err(io)?;
    crate::fsutil::write_atomic(path, bytes).map_err(io)
}

/// Write one row file: its bytes to a temporary name in `rows/`, then a rename, without
/// the sync [`write_atomic`] makes. A killed process leaves the whole file or none (the
/// rename is atomic and the page cache outlives the process); after a power loss a row not
/// yet on disk may be missing or empty, and [`read_rows`] skips what does not parse, so
/// that point runs again on resume. The sync cost more than a quasi-static point's physics
/// (and grew with the disk's write-back queue). `dir/rows` must exist.
pub(super) fn write_row(path: &Path, bytes: &[u8]) -> Result<()> {
    let io = |e: std::io::Error| Error::Io(format!("cannot write `{}`: {e}", path.display()));
    let tmp = crate::fsutil::temporary_path(path);
    let done = std::fs::write(&tmp, bytes).and_then(|()| std::fs::rename(&tmp, path));
    if done.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    done.map_err(io)
}

pub(super) fn row_path(dir: &Path, index: usize) -> PathBuf {
    dir.join("rows").join(format!("{index:08}.json"))
}

/// The finished rows in `dir/rows` (unreadable files are not finished).
pub fn read_rows(dir: &Path) -> Vec<Row> {
    let mut rows: Vec<Row> = std::fs::read_dir(dir.join("rows"))
        .into_iter()
        .flatten()
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().ends_with(".json"))
        .filter(|e| !e.file_name().to_string_lossy().starts_with('.'))
        .filter_map(|e| std::fs::read(e.path()).ok())
        .filter_map(|b| serde_json::from_slice(&b).ok())
        .collect();
    rows.sort_by_key(|r| r.index);
    rows.dedup_by_key(|r| r.index);
    rows
}

pub(super) fn csv_field(v: &Json) -> String {
    let s = match v {
        Json::Null => String::new(),
        Json::Number(n) => match (n.as_i64(), n.as_f64()) {
            (Some(i), _) => i.to_string(),
            // Rust prints the shortest text that reads back to the same f64.
            (None, Some(x)) => format!("{x:?}"),
            _ => n.to_string(),
        },
        Json::Bool(b) => b.to_string(),
        Json::String(s) => s.clone(),
        other => other.to_string(),
    };
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s
    }
}

/// The CSV table of `rows` (sorted by index): `index`, the axes' columns, `error`, then the
/// summary columns in order of first appearance; an absent value is an empty field.
pub fn csv(rows: &[Row]) -> String {
    let mut cols: Vec<String> = vec!["index".into()];
    let push = |c: &str, cols: &mut Vec<String>| {
        if !cols.iter().any(|x| x == c) {
            cols.push(c.to_string());
        }
    };
    for r in rows {
        for (c, _) in &r.axes {
            push(c, &mut cols);
        }
    }
    push("error", &mut cols);
    for r in rows {
        for (c, _) in &r.summary {
            push(c, &mut cols);
        }
    }
    let mut s = cols
        .iter()
        .map(|c| csv_field(&Json::from(c.as_str())))
        .collect::<Vec<_>>()
        .join(",");
    s.push('\n');
    for r in rows {
        let mut fields = vec![String::new(); cols.len()];
        fields[0] = r.index.to_string();
        let error = r.error.clone().map(Json::from).unwrap_or(Json::Null);
        for (c, v) in r
            .axes
            .iter()
            .chain(std::iter::once(&("error".to_string(), error)))
            .chain(&r.summary)
        {
            if let Some(k) = cols.iter().position(|x| x == c) {
                fields[k] = csv_field(v);
            }
        }
        s += &fields.join(",");
        s.push('\n');
    }
    s
}
