use super::*;

#[test]
fn dotted_keys_split_like_toml() {
    assert_eq!(
        key_path("inputs.initial.\"shaft.y\"").unwrap(),
        ["inputs", "initial", "shaft.y"]
    );
    assert!(key_path("a..b").is_err());
}

#[test]
fn flattened_summary_carries_units_in_names() {
    let mut out = Vec::new();
    flatten(
        "",
        &serde_json::json!({"peak_force [N]": [1.0, 2.0, 3.0], "level": "ring",
            "frequencies": [{"label": "BPFO", "expected [Hz]": 10.0, "found [Hz]": null}],
            "rating": {"ratings": {"C [N]": 1.0}},
            "warnings": ["a", "b"]}),
        &mut out,
    );
    let names: Vec<&str> = out.iter().map(|(n, _)| n.as_str()).collect();
    for want in [
        "peak_force.x [N]",
        "peak_force.z [N]",
        "level",
        "frequencies.BPFO.expected [Hz]",
        "frequencies.BPFO.found [Hz]",
        "rating.ratings.C [N]",
        "warnings",
    ] {
        assert!(names.contains(&want), "{want} in {names:?}");
    }
}

#[test]
fn csv_numbers_round_trip_exactly() {
    let x: f64 = 0.1 + 0.2;
    let text = csv_field(&Json::from(x));
    assert_eq!(text.parse::<f64>().unwrap().to_bits(), x.to_bits());
    assert_eq!(csv_field(&Json::from("a,\"b\"")), "\"a,\"\"b\"\"\"");
}
