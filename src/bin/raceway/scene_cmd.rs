//! `raceway scene --explain [--json]` documents every scene field (generated from the serde
//! schema and the one table in `raceway::component::schema`); `raceway scene --check <file>`
//! reports every problem of a scene at once, each with its place, and exits non-zero when
//! there is any.

use raceway::component::{schema, Scene};
use raceway::{Error, Result};
use std::path::PathBuf;

/// Options of `raceway scene`.
#[derive(clap::Args, Debug)]
#[command(group(clap::ArgGroup::new("what").required(true).args(["explain", "check"])))]
pub struct SceneArgs {
    /// Document every scene field: type, unit, default, allowed range, meaning.
    #[arg(long)]
    pub explain: bool,
    /// Check a scene file (TOML or JSON): every problem with its line:column.
    #[arg(long, value_name = "FILE")]
    pub check: Option<PathBuf>,
    /// Machine-readable output: the field table (--explain), or the problems (--check,
    /// on standard output; the exit status is still 1 when there is any).
    #[arg(long)]
    pub json: bool,
}

/// Run the subcommand; returns the text for standard output.
pub fn scene(a: SceneArgs) -> Result<String> {
    if a.explain {
        return Ok(schema::explain(a.json));
    }
    let path = a.check.expect("clap requires --explain or --check");
    let text = std::fs::read_to_string(&path)
        .map_err(|e| Error::Io(format!("cannot read scene `{}`: {e}", path.display())))?;
    let problems = schema::check(&text);
    if a.json {
        let out = serde_json::json!({ "ok": problems.is_empty(), "problems": problems });
        println!(
            "{}",
            serde_json::to_string_pretty(&out).expect("serialises")
        );
        return if problems.is_empty() {
            Ok(String::new())
        } else {
            Err(Error::Parse {
                what: format!("scene `{}`", path.display()),
                message: format!("{} problem(s)", problems.len()),
            })
        };
    }
    if problems.is_empty() {
        let scene = Scene::from_text(&text)?;
        return Ok(format!(
            "ok: {}: {}\n",
            path.display(),
            schema::summary(&scene)
        ));
    }
    Err(problems_error(&path.display().to_string(), &problems))
}

/// Every problem of a scene, one per line with its place: the error of `raceway scene
/// --check` and of `raceway run` alike.
pub fn problems_error(file: &str, problems: &[schema::Problem]) -> Error {
    let mut message = format!("{} problem(s)", problems.len());
    for p in problems {
        let sep = if p.line_col.is_some() { ":" } else { ": " };
        message += &format!("\n{file}{sep}{p}");
    }
    Error::Parse {
        what: format!("scene `{file}`"),
        message,
    }
}
