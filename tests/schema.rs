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
        "{} is out of date: re-bless with VREP_MAZE_BLESS=1 cargo test --test schema",
        path.display()
    );
    assert!(text.contains("\"segments\""));
}
