//! Stages and zips the four FMUs (motion- and load-driven, FMI 2 and FMI 3) and regenerates
//! the variable table of `docs/fmi.md`, all from `raceway::component::variables`. The four carry the same binary: the GUID a host
//! instantiates with tells it which variant it is.
//!
//! ```text
//! raceway-fmu-pack --lib <libraceway_fmu.so> --out <dir> [--lib-win64 <raceway_fmu.dll>]
//!                  [--scene <scene.toml>] [--update-doc <docs/fmi.md>] [--check-doc <docs/fmi.md>]
//! ```
//!
//! Writes `<dir>/stage/<name>/` for each archive name (`raceway-fmi2`, `raceway-fmi3`,
//! `raceway-load-fmi2`, `raceway-load-fmi3`: modelDescription.xml, binaries/<platform>/
//! raceway.so (`--lib`, this machine's platform) and, with `--lib-win64`, the Windows x86_64
//! library cross-built by `scripts/build-windows` as binaries/win64/raceway.dll (FMI 2) or
//! binaries/x86_64-windows/raceway.dll (FMI 3), documentation/index.html (listing the
//! platforms packed), documentation/licenses/ (license.txt, the two licence texts and the
//! third-party notices),
//! resources/scene.toml when `--scene` is given, in the two archives of the scene's
//! causality), zips each into `<dir>/<name>.fmu` and writes `<dir>/variables.md`.

use raceway_core::fmi::model_description as md;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// The licence texts and the third-party notices, in every FMU's `documentation/licenses/`.
const LICENSE_FILES: [(&str, &str); 3] = [
    ("LICENSE-MIT", include_str!("../../../LICENSE-MIT")),
    ("LICENSE-APACHE", include_str!("../../../LICENSE-APACHE")),
    (
        "THIRD-PARTY-NOTICES.md",
        include_str!("../../../THIRD-PARTY-NOTICES.md"),
    ),
];

/// (FMI 2 folder, FMI 3 platform tuple, library extension) of one platform.
type Platform = (&'static str, &'static str, &'static str);

/// Windows x86_64: FMI 2.0.4 §2.3 names the folder `win64`, FMI 3.0 §2.5 the platform tuple
/// `x86_64-windows`; the library is `<modelIdentifier>.dll` in both.
const WIN64: Platform = ("win64", "x86_64-windows", "dll");

/// This machine's platform (the one `--lib` was built for); spec2 2_3, spec3 2_5.
fn platforms() -> Result<Platform, String> {
    match (std::env::consts::ARCH, std::env::consts::OS) {
        ("x86_64", "linux") => Ok(("linux64", "x86_64-linux", "so")),
        ("aarch64", "linux") => Ok(("aarch64-linux", "aarch64-linux", "so")),
        ("x86_64", "macos") => Ok(("darwin64", "x86_64-darwin", "dylib")),
        ("aarch64", "macos") => Ok(("aarch64-darwin", "aarch64-darwin", "dylib")),
        ("x86_64", "windows") => Ok(WIN64),
        (a, o) => Err(format!("no FMI platform name for {a}-{o}")),
    }
}

fn write(path: &Path, bytes: &[u8]) -> Result<(), String> {
    if let Some(d) = path.parent() {
        std::fs::create_dir_all(d).map_err(|e| format!("{}: {e}", d.display()))?;
    }
    std::fs::write(path, bytes).map_err(|e| format!("{}: {e}", path.display()))
}

/// The files below `dir`, depth first as `os.walk` with sorted names gives them: a folder's
/// files before its subfolders.
fn files_below(dir: &Path) -> Result<Vec<PathBuf>, String> {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .and_then(|rd| rd.collect::<Result<Vec<_>, _>>())
        .map_err(|e| format!("{}: {e}", dir.display()))?;
    entries.sort_by_key(|e| e.file_name());
    let (mut files, mut dirs) = (Vec::new(), Vec::new());
    for e in entries {
        let path = e.path();
        if path.is_dir() {
            dirs.push(path);
        } else {
            files.push(path);
        }
    }
    for d in dirs {
        files.extend(files_below(&d)?);
    }
    Ok(files)
}

/// Zips the staged folder `root` into `fmu` (through `fmu.tmp`, renamed when complete):
/// deflate, names relative to `root` with forward slashes, a fixed timestamp (1980-01-01)
/// and mode 0644, so no path or time of this machine is in the archive (spec2 2_3).
fn zip_folder(root: &Path, fmu: &Path) -> Result<(), String> {
    let tmp = fmu.with_extension("fmu.tmp");
    let err = |e: &dyn std::fmt::Display| format!("{}: {e}", tmp.display());
    let file = std::fs::File::create(&tmp).map_err(|e| err(&e))?;
    let mut z = zip::ZipWriter::new(std::io::BufWriter::new(file));
    let options = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated)
        .last_modified_time(zip::DateTime::default())
        .unix_permissions(0o644);
    for path in files_below(root)? {
        let rel = path.strip_prefix(root).map_err(|e| err(&e))?;
        let name: Vec<_> = rel.iter().map(|c| c.to_string_lossy()).collect();
        let bytes = std::fs::read(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        z.start_file(name.join("/"), options).map_err(|e| err(&e))?;
        z.write_all(&bytes).map_err(|e| err(&e))?;
    }
    z.finish()
        .map_err(|e| err(&e))?
        .flush()
        .map_err(|e| err(&e))?;
    std::fs::rename(&tmp, fmu).map_err(|e| format!("{}: {e}", fmu.display()))
}

fn run() -> Result<(), String> {
    let mut args = std::env::args().skip(1);
    let (mut lib, mut out, mut scene, mut update, mut check) = (None, None, None, None, None);
    let mut lib_win64 = None;
    while let Some(a) = args.next() {
        let mut val = || {
            args.next()
                .map(PathBuf::from)
                .ok_or(format!("{a} needs a value"))
        };
        match a.as_str() {
            "--lib" => lib = Some(val()?),
            "--lib-win64" => lib_win64 = Some(val()?),
            "--out" => out = Some(val()?),
            "--scene" => scene = Some(val()?),
            "--update-doc" => update = Some(val()?),
            "--check-doc" => check = Some(val()?),
            _ => return Err(format!("unknown argument `{a}`")),
        }
    }
    let out = out.ok_or("--out is required")?;
    let table = md::markdown_table();
    write(&out.join("variables.md"), table.as_bytes())?;
    if lib.is_none() && lib_win64.is_some() {
        return Err("--lib-win64 needs --lib (this machine's library) beside it".into());
    }
    if let Some(lib) = lib {
        let read = |p: &Path| std::fs::read(p).map_err(|e| format!("{}: {e}", p.display()));
        // (platform, library bytes) for every platform packed, this machine's first
        let mut libs = vec![(platforms()?, read(&lib)?)];
        if let Some(dll) = &lib_win64 {
            let bytes = read(dll)?;
            // a PE image starts with "MZ": catches a Linux .so passed by mistake
            if !bytes.starts_with(b"MZ") {
                return Err(format!("{}: not a Windows DLL", dll.display()));
            }
            if libs[0].0 != WIN64 {
                libs.push((WIN64, bytes));
            }
        }
        let names: Vec<(&str, &str)> = libs.iter().map(|((p2, p3, _), _)| (*p2, *p3)).collect();
        let scene_text = match &scene {
            Some(s) => {
                let t = std::fs::read_to_string(s).map_err(|e| format!("{}: {e}", s.display()))?;
                // refuse a broken scene at packing time rather than in the host
                let c = raceway_core::Component::from_text(&t)
                    .map_err(|e| format!("{}: {e}", s.display()))?;
                Some((t, c.causality()))
            }
            None => None,
        };
        let stage = out.join("stage");
        if stage.exists() {
            std::fs::remove_dir_all(&stage).map_err(|e| format!("{}: {e}", stage.display()))?;
        }
        for c in md::VARIANTS {
            // the scene goes into the FMUs of its own causality, whose inputs' start values
            // are its initial values
            let own = scene_text
                .as_ref()
                .filter(|(_, sc)| *sc == c)
                .map(|(t, _)| t.as_str());
            let xmls = [
                ("fmi2", md::fmi2_with(c, own)?),
                ("fmi3", md::fmi3_with(c, own)?),
            ];
            for (version, xml) in xmls {
                let name = md::archive_name(c, version);
                let root = stage.join(name.trim_end_matches(".fmu"));
                write(&root.join("modelDescription.xml"), xml.as_bytes())?;
                for ((p2, p3, ext), bytes) in &libs {
                    let folder = if version == "fmi2" { p2 } else { p3 };
                    let file = format!("{}.{ext}", md::MODEL_IDENTIFIER);
                    write(&root.join("binaries").join(folder).join(file), bytes)?;
                }
                let docs = root.join("documentation");
                write(
                    &docs.join("index.html"),
                    md::documentation_html_on(c, &names).as_bytes(),
                )?;
                write(
                    &docs.join("licenses").join("license.txt"),
                    md::license_text().as_bytes(),
                )?;
                for (name, text) in LICENSE_FILES {
                    write(&docs.join("licenses").join(name), text.as_bytes())?;
                }
                if let Some(t) = own {
                    write(&root.join("resources").join("scene.toml"), t.as_bytes())?;
                }
                let fmu = out.join(&name);
                zip_folder(&root, &fmu)?;
                println!("{}", fmu.display());
            }
        }
    }
    for (path, fix) in [(update, true), (check, false)] {
        let Some(path) = path else { continue };
        let doc = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let new = md::update_doc(&doc).ok_or(format!(
            "{}: the markers `{}` / `{}` are missing",
            path.display(),
            md::DOC_BEGIN,
            md::DOC_END
        ))?;
        if new != doc {
            if fix {
                write(&path, new.as_bytes())?;
                eprintln!("updated the variable table in {}", path.display());
            } else {
                return Err(format!(
                    "{}: the variable table is out of date; run scripts/build-fmu",
                    path.display()
                ));
            }
        }
    }
    Ok(())
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("raceway-fmu-pack: {e}");
            ExitCode::FAILURE
        }
    }
}
