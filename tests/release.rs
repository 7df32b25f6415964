//! What a release carries, checked against the numbers that must stay true: the licence
//! texts, the citation file's version and the changelog's, all from `Cargo.toml`.

use std::path::Path;

fn read(name: &str) -> String {
    std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join(name))
        .unwrap_or_else(|e| panic!("{name}: {e}"))
}

#[test]
fn licence_texts_match_the_manifest() {
    assert_eq!(env!("CARGO_PKG_LICENSE"), "MIT OR Apache-2.0");
    assert!(read("LICENSE-MIT").contains("Permission is hereby granted, free of charge"));
    let apache = read("LICENSE-APACHE");
    assert!(apache.contains("Apache License") && apache.contains("Version 2.0, January 2004"));
}

#[test]
fn citation_and_changelog_carry_the_manifest_version() {
    let version = env!("CARGO_PKG_VERSION");
    let cff = read("CITATION.cff");
    assert!(cff.starts_with("cff-version: 1.2.0\n"), "CFF 1.2.0");
    let line = cff
        .lines()
        .find(|l| l.starts_with("version:"))
        .expect("a version line");
    assert_eq!(line, format!("version: \"{version}\""));
    for l in ["MIT", "Apache-2.0"] {
        assert!(cff.contains(&format!("  - {l}\n")), "licence {l}");
    }
    let changelog = read("CHANGELOG.md");
    assert!(changelog.contains("## [Unreleased]"));
    assert!(changelog.contains(&format!("## [{version}]")), "{version}");
}
