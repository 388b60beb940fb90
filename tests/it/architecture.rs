//! ARCHITECTURE.md stays true to the tree: every file or folder of this repository it names
//! (in backticks, from the top: `crates/...`, `src/...`, `tests/...`, ...) exists, so a
//! newcomer following it, or its first-change recipes, never looks for a path that moved.

use std::path::Path;

/// Where a repository path starts.
const TOPS: &[&str] = &[
    "crates/", "src/", "tests/", "python/", "docs/", "mazes/", "schema/", "benches/", "bench/",
    ".ci/",
];

/// The repository paths `text` names in backticks.
fn named_paths(text: &str) -> Vec<&str> {
    text.split('`')
        .skip(1)
        .step_by(2)
        .filter(|t| TOPS.iter().any(|top| t.starts_with(top)))
        .filter(|t| !t.contains(' ') && !t.contains('*'))
        .collect()
}

/// The recipes' example names: a file a recipe creates (`generate/foo.rs`, `render/pdf.rs`).
const PLACEHOLDERS: &[&str] = &["foo", "pdf"];

/// What must exist for `path` to be true: the path, or for a file a recipe creates, its
/// folder.
fn to_check(path: &str) -> &str {
    let path = path.trim_end_matches('/');
    let name = path.rsplit('/').next().unwrap_or(path);
    if PLACEHOLDERS.iter().any(|p| name.contains(p)) {
        path.rsplit_once('/').map_or(path, |(folder, _)| folder)
    } else {
        path
    }
}

#[test]
fn every_path_the_architecture_names_exists() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(root.join("ARCHITECTURE.md")).unwrap();
    let paths = named_paths(&text);
    assert!(paths.len() > 30, "only {} paths named", paths.len());
    let missing: Vec<&str> = paths
        .into_iter()
        .filter(|p| !root.join(to_check(p)).exists())
        .collect();
    assert!(
        missing.is_empty(),
        "ARCHITECTURE.md names paths that do not exist: {missing:?}"
    );
}

#[test]
fn a_recipes_new_file_needs_its_folder() {
    assert_eq!(
        to_check("crates/core/src/render/pdf.rs"),
        "crates/core/src/render"
    );
    assert_eq!(
        to_check("crates/core/src/mesh.rs"),
        "crates/core/src/mesh.rs"
    );
    assert_eq!(to_check("tests/it/"), "tests/it");
}

#[test]
fn the_checker_finds_paths_and_leaves_other_code_alone() {
    assert_eq!(
        named_paths("see `crates/core/src/mesh.rs`, `draw::run`, `src/` and `cargo test`"),
        ["crates/core/src/mesh.rs", "src/"]
    );
}
