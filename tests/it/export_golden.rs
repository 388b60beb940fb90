//! Golden exports: `tests/fixtures/export/` pins the exact bytes `export` writes in the
//! MJCF, SDF, URDF and Webots formats for a line maze and a wall maze with posts, so a
//! rewrite of a writer (e.g. onto `quick_xml::Writer`) cannot change a user's file
//! unnoticed. (The CoppeliaSim formats carry meshes, hundreds of kilobytes: their bytes are
//! checked by the simulator suites instead.)
//!
//! Re-bless (after a deliberate change, explained in the issue note) with
//! `VREP_MAZE_BLESS=1 cargo test --test it export_golden`.

use std::fs;
use std::path::{Path, PathBuf};

use crate::support::bin;

/// Environment variable that rewrites the golden files instead of comparing them.
const BLESS: &str = "VREP_MAZE_BLESS";

/// The formats pinned here, by their `--format` names (also the golden files' endings).
const FORMATS: [&str; 4] = ["mjcf", "sdf", "urdf", "webots"];

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

/// The layouts exported: a golden line maze and a small wall maze with posts.
fn layouts() -> [PathBuf; 2] {
    [
        root().join("mazes/kruskal-1x12-seed42.json"),
        root().join("tests/fixtures/export/walls-posts-3x2.json"),
    ]
}

#[test]
fn exports_are_byte_identical_to_the_golden_files() {
    let dir = tempfile::tempdir().unwrap();
    let bless = std::env::var_os(BLESS).is_some();
    for layout in layouts() {
        let stem = layout.file_stem().unwrap().to_str().unwrap();
        for format in FORMATS {
            let name = format!("{stem}.{format}");
            let written = dir.path().join(&name);
            bin()
                .arg("export")
                .arg(&layout)
                .arg("-o")
                .arg(&written)
                .args(["--format", format, "-q"])
                .assert()
                .success();
            let bytes = fs::read(&written).unwrap();
            let golden = root().join("tests/fixtures/export").join(&name);
            if bless {
                fs::write(&golden, &bytes).unwrap();
                continue;
            }
            let expected = fs::read(&golden)
                .unwrap_or_else(|e| panic!("{}: {e} (bless with {BLESS}=1)", golden.display()));
            assert!(
                bytes == expected,
                "{name} differs from {}: export changed the bytes it writes",
                golden.display()
            );
        }
    }
}
