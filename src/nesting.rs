//! How deeply a scene text nests, measured before any parser sees it.
//!
//! The TOML and JSON parsers and the schema walk recurse once per level of nesting, so a
//! short text of deeply nested inline tables, arrays or dotted keys can overflow a small
//! thread stack (a host's worker thread of 64 KiB) before any check runs. A scene needs a
//! handful of levels (`[effects]` → `[[effects.defects]]` → a table in it); this scan counts
//! the levels of a text with a bounded loop and no recursion, and the text is refused,
//! naming line and column, when it nests deeper than [`MAX_NESTING`].
//!
//! What counts as a level: each `[`/`{` open at that point; in TOML also each part of the
//! current table header (`[a.b.c]` is three, `[[a.b]]` three: the array adds one) and each
//! dot of a dotted key (`a.b.c = 1` adds two). Strings (basic, literal and the multi-line
//! forms; JSON strings with escapes) and comments are skipped. The count errs on the high
//! side (dotted keys of sibling entries in one inline table add up), which only matters far
//! above what a scene uses.

/// The deepest nesting a scene may have. Every shipped scene stays within 6 levels (the
/// test `every_shipped_scene_is_far_inside_the_limit`); 16 leaves room for any hand-written
/// layout. It was 32 until the fuzzer on a 64 KiB thread found `bearing` as 31 nested
/// inline tables overflowing it: the serde walk of a bearing table takes about 1.5 KiB of
/// stack per level (60 KiB at 31); at 16 it takes under 48 KiB (`tests/small_stack.rs`).
pub const MAX_NESTING: usize = 16;

/// Where a text first nests deeper than the limit: 1-based line and column, and the depth
/// reached there.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TooDeep {
    /// Line, from 1.
    pub line: usize,
    /// Column in characters, from 1.
    pub column: usize,
    /// The depth reached.
    pub depth: usize,
}

impl std::fmt::Display for TooDeep {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "nested {} levels deep at line {}, column {}: a scene may nest at most {} levels \
             (tables, arrays and dotted-key parts together)",
            self.depth, self.line, self.column, MAX_NESTING
        )
    }
}

impl std::error::Error for TooDeep {}

/// Check a scene text, TOML or JSON (JSON when its first non-blank character is `{`).
pub fn check(text: &str) -> Result<(), TooDeep> {
    if text.trim_start().starts_with('{') {
        check_json(text, MAX_NESTING)
    } else {
        check_toml(text, MAX_NESTING)
    }
}

/// Line and column (1-based, in characters) of byte offset `at`.
fn place(text: &str, at: usize) -> (usize, usize) {
    let before = &text[..at.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let start = before.rfind('\n').map_or(0, |i| i + 1);
    (line, before[start..].chars().count() + 1)
}

fn too_deep(text: &str, at: usize, depth: usize) -> TooDeep {
    let (line, column) = place(text, at);
    TooDeep {
        line,
        column,
        depth,
    }
}

/// JSON: `{` and `[` outside strings.
pub fn check_json(text: &str, max: usize) -> Result<(), TooDeep> {
    let b = text.as_bytes();
    let mut depth = 0usize;
    let mut i = 0;
    while i < b.len() {
        match b[i] {
            b'"' => {
                i += 1;
                while i < b.len() && b[i] != b'"' {
                    i += if b[i] == b'\\' { 2 } else { 1 };
                }
            }
            b'{' | b'[' => {
                depth += 1;
                if depth > max {
                    return Err(too_deep(text, i, depth));
                }
            }
            b'}' | b']' => depth = depth.saturating_sub(1),
            _ => {}
        }
        i += 1;
    }
    Ok(())
}

/// Skip a TOML string starting at `i` (at its first quote); returns the index after it.
fn skip_toml_string(b: &[u8], mut i: usize) -> usize {
    let q = b[i];
    let triple = b.len() >= i + 3 && b[i + 1] == q && b[i + 2] == q;
    if triple {
        i += 3;
        while i < b.len() {
            if q == b'"' && b[i] == b'\\' {
                i += 2;
                continue;
            }
            if b.len() >= i + 3 && b[i] == q && b[i + 1] == q && b[i + 2] == q {
                // Up to two more quotes may belong to the content ("""a"""" is legal).
                let mut j = i + 3;
                while j < b.len() && b[j] == q && j < i + 5 {
                    j += 1;
                }
                return j;
            }
            i += 1;
        }
        return i;
    }
    let start = i;
    i += 1;
    while i < b.len() && b[i] != q && b[i] != b'\n' {
        i += if q == b'"' && b[i] == b'\\' { 2 } else { 1 };
    }
    if i >= b.len() || b[i] != q {
        // Unterminated on its line: the parser recovers and reads on (a stray quote in a
        // key, `step"s = { x = { ...`, overflowed a 64 KiB stack when its brackets were
        // skipped as string content), so only the quote itself is skipped.
        return start + 1;
    }
    i + 1
}

/// TOML: brackets and braces outside strings and comments, header parts, dotted-key parts.
pub fn check_toml(text: &str, max: usize) -> Result<(), TooDeep> {
    let b = text.as_bytes();
    // Open brackets, innermost last (`[` or `{`).
    let mut open: Vec<u8> = Vec::new();
    let mut header = 0usize; // levels of the current table header
    let mut dots = 0usize; // dotted-key parts of the current statement
    let mut in_key = true; // reading a key (line start at top level, after `{` or `,` in a table)
    let mut line_start = true;
    let mut prev = b'\n'; // the last byte read that is not a blank
    let mut i = 0;
    let depth = |open: &Vec<u8>, header: usize, dots: usize| open.len() + header + dots;
    while i < b.len() {
        let c = b[i];
        match c {
            b'\n' => {
                if open.is_empty() {
                    dots = 0;
                    in_key = true;
                }
                line_start = true;
                prev = c;
                i += 1;
                continue;
            }
            b' ' | b'\t' | b'\r' => {
                i += 1;
                continue;
            }
            b'#' => {
                while i < b.len() && b[i] != b'\n' {
                    i += 1;
                }
                continue;
            }
            b'"' | b'\'' if prev.is_ascii_alphanumeric() || prev == b'_' || prev == b'-' => {
                // A quote right after a bare key or a value (`cau"ality = { ...`) starts no
                // string for the parser, which recovers and reads the brackets after it
                // (found by the fuzzer: they overflowed a 64 KiB stack when a later quote
                // closed this "string" over them): only the quote is skipped.
                prev = c;
                line_start = false;
                i += 1;
                continue;
            }
            b'"' | b'\'' => {
                i = skip_toml_string(b, i);
                prev = c;
                line_start = false;
                continue;
            }
            b'[' if line_start && open.is_empty() => {
                // A table header `[a.b]` or `[[a.b]]`: its parts replace the previous ones.
                let array = b.get(i + 1) == Some(&b'[');
                let mut j = i + if array { 2 } else { 1 };
                let mut parts = 1usize;
                while j < b.len() && b[j] != b']' && b[j] != b'\n' {
                    match b[j] {
                        b'"' | b'\'' => {
                            j = skip_toml_string(b, j);
                            continue;
                        }
                        b'.' => {
                            parts += 1;
                            if parts + usize::from(array) > max {
                                return Err(too_deep(text, j, parts + usize::from(array)));
                            }
                        }
                        _ => {}
                    }
                    j += 1;
                }
                header = parts + usize::from(array);
                dots = 0;
                while j < b.len() && b[j] == b']' {
                    j += 1;
                }
                i = j;
                prev = b']';
                line_start = false;
                in_key = true;
                continue;
            }
            b'[' | b'{' => {
                open.push(c);
                in_key = c == b'{';
                if depth(&open, header, dots) > max {
                    return Err(too_deep(text, i, depth(&open, header, dots)));
                }
            }
            b']' | b'}' => {
                open.pop();
                in_key = false;
            }
            b',' => in_key = open.last() == Some(&b'{'),
            b'=' => in_key = false,
            b'.' if in_key => {
                dots += 1;
                if depth(&open, header, dots) > max {
                    return Err(too_deep(text, i, depth(&open, header, dots)));
                }
            }
            _ => {}
        }
        prev = c;
        line_start = false;
        i += 1;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn inline_tables(n: usize) -> String {
        format!("a = {}1{}\n", "{ b = ".repeat(n), " }".repeat(n))
    }

    #[test]
    fn an_unterminated_string_hides_no_brackets() {
        // Found by the fuzzer on a 64 KiB thread (issue #38): the stray quote opened a
        // "string" to the end of the line and the 300 tables after it were not counted.
        let t = format!(
            "[run]\nstep\"s = {}1{}\n",
            "{ x = ".repeat(300),
            " }".repeat(300)
        );
        let e = check_toml(&t, MAX_NESTING).unwrap_err();
        assert_eq!((e.depth, e.line), (MAX_NESTING + 1, 2));
        // Nor does a quote inside a key that a later quote closes (fuzzer, again).
        let t = format!(
            "[model]\ncau\"ality = {}\"motion\"{}\n",
            "{ x = ".repeat(300),
            " }".repeat(300)
        );
        assert_eq!(check_toml(&t, MAX_NESTING).unwrap_err().line, 2);
        // A closed string still hides what is in it.
        assert!(check_toml(&format!("a = \"{}\"\n", "{".repeat(300)), MAX_NESTING).is_ok());
    }

    #[test]
    fn counts_each_kind_of_level() {
        assert_eq!(check_toml(&inline_tables(5), 4).unwrap_err().depth, 5);
        assert!(check_toml(&inline_tables(5), 5).is_ok());
        let arrays = format!("a = {}1{}\n", "[".repeat(7), "]".repeat(7));
        assert!(check_toml(&arrays, 7).is_ok());
        assert_eq!(check_toml(&arrays, 6).unwrap_err().depth, 7);
        let header = "[a.b.c.d]\nx = 1\n";
        assert!(check_toml(header, 4).is_ok());
        assert_eq!(check_toml(header, 3).unwrap_err().depth, 4);
        assert_eq!(check_toml("[[a.b.c]]\n", 3).unwrap_err().depth, 4);
        let dotted = "[t]\nx.y.z = 1\n";
        assert!(check_toml(dotted, 3).is_ok());
        assert_eq!(check_toml(dotted, 2).unwrap_err().depth, 3);
        let json = format!("{}1{}", "{\"a\":".repeat(9), "}".repeat(9));
        assert!(check_json(&json, 9).is_ok());
        assert_eq!(check_json(&json, 8).unwrap_err().depth, 9);
    }

    /// Brackets, dots and quotes inside strings, comments and values do not count; a
    /// header's parts are replaced by the next header's, not added.
    #[test]
    fn strings_comments_and_values_do_not_count() {
        let t = "# [[[[[[ {{{{ a.b.c.d\n\
                 [effects.thermal]\n\
                 name = \"[[[[{{{{.....\"\n\
                 lit = '[[[[.....'\n\
                 multi = \"\"\"\n[[[[\n{{{{\n\"\"\"\n\
                 x = 1.5e-3\n\
                 [a.b]\n\
                 \"quoted.key.with.dots\" = [1.0, 2.5]\n";
        assert!(check_toml(t, 3).is_ok());
        let j = r#"{"a": "{{{{[[[[\"{{{{", "b": [1.5, {"c": 2}]}"#;
        assert!(check_json(j, 3).is_ok());
    }

    #[test]
    fn every_shipped_scene_is_far_inside_the_limit() {
        let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/scenes");
        let mut n = 0;
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            if p.extension().is_some_and(|x| x == "toml") {
                let text = std::fs::read_to_string(&p).unwrap();
                assert!(check_toml(&text, 6).is_ok(), "{}", p.display());
                n += 1;
            }
        }
        assert!(n > 10);
    }

    #[test]
    fn the_place_is_line_and_column() {
        let t = "x = 1\ny = [[[[\n";
        let e = check_toml(t, 3).unwrap_err();
        assert_eq!((e.line, e.column, e.depth), (2, 8, 4));
    }
}
