//! `schema/layout-v1.schema.json` is generated from the layout types; this test keeps the
//! checked-in file equal to what the types say (re-bless with `VREP_MAZE_BLESS=1`).

use std::fs;
use std::path::Path;

use vrep_maze::layout::Layout;

#[test]
fn the_checked_in_schema_matches_the_types() {
    let schema = schemars::schema_for!(Layout);
    let text = serde_json::to_string_pretty(&schema).unwrap() + "\n";
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("schema/layout-v1.schema.json");
    if std::env::var_os("VREP_MAZE_BLESS").is_some() {
        fs::create_dir_all(path.parent().unwrap()).unwrap();
        fs::write(&path, &text).unwrap();
        return;
    }
    let checked_in = fs::read_to_string(&path).unwrap_or_default();
    assert!(
        checked_in == text,
        "{} is out of date: re-bless with VREP_MAZE_BLESS=1 cargo test --test it schema",
        path.display()
    );
    assert!(text.contains("\"segments\""));
}

#[test]
fn every_golden_layout_satisfies_the_schema() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let schema: serde_json::Value = serde_json::from_str(
        &fs::read_to_string(root.join("schema/layout-v1.schema.json")).unwrap(),
    )
    .unwrap();
    let validator = jsonschema::validator_for(&schema).expect("a valid JSON Schema");
    let mut checked = 0;
    for entry in fs::read_dir(root.join("mazes")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) != Some("json") {
            continue;
        }
        let layout: serde_json::Value =
            serde_json::from_str(&fs::read_to_string(&path).unwrap()).unwrap();
        let errors: Vec<String> = validator
            .iter_errors(&layout)
            .map(|e| e.to_string())
            .collect();
        assert!(errors.is_empty(), "{}: {errors:?}", path.display());
        checked += 1;
    }
    assert!(checked >= 7, "only {checked} golden layouts");
    // The schema is strict enough to refuse a broken layout.
    let mut broken: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(root.join("mazes/dfs-9x9-seed42.json")).unwrap())
            .unwrap();
    broken["grid"]["columns"] = serde_json::json!("nine");
    broken["surprise"] = serde_json::json!(1);
    assert!(validator.iter_errors(&broken).count() >= 2);
}
