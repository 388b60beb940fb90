//! Golden layouts: `mazes/` pins the exact bytes of mazes made from fixed seeds, so no
//! code change or dependency upgrade can silently change a user's maze.
//!
//! Re-bless (after a deliberate change, explained in the issue note) with
//! `VREP_MAZE_BLESS=1 cargo test --test it golden`.

use std::fs;
use std::path::{Path, PathBuf};

use crate::support::bin;
use vrep_maze::generate::Algorithm;
use vrep_maze::layout::read_layout;
use vrep_maze::validate::validate;

/// Environment variable that rewrites the golden files instead of comparing them.
const BLESS: &str = "VREP_MAZE_BLESS";

fn mazes_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("mazes")
}

/// Every golden file and the `generate` arguments that make it.
fn golden_cases() -> Vec<(String, Vec<String>)> {
    let mut cases: Vec<(String, Vec<String>)> = Algorithm::ALL
        .iter()
        .map(|a| {
            (
                format!("{}-9x9-seed42.json", a.name()),
                vec![
                    "--algo".into(),
                    a.name().into(),
                    "--seed".into(),
                    "42".into(),
                ],
            )
        })
        .collect();
    let extra: [(&str, &[&str]); 8] = [
        (
            "growing-tree-mix0.5-9x9-seed42.json",
            &[
                "--algo",
                "growing-tree",
                "--growing",
                "mix:0.5",
                "--seed",
                "42",
            ],
        ),
        (
            "binary-tree-sw-9x9-seed42.json",
            &["--algo", "binary-tree", "--bias", "sw", "--seed", "42"],
        ),
        (
            "prim-9x9-seed42-braid0.5.json",
            &["--algo", "prim", "--seed", "42", "--braid", "0.5"],
        ),
        (
            "prim-20x15-seed7.json",
            &["--algo", "prim", "--size", "20x15", "--seed", "7"],
        ),
        ("dfs-1x1-seed42.json", &["--size", "1x1", "--seed", "42"]),
        (
            "kruskal-1x12-seed42.json",
            &["--algo", "kruskal", "--size", "1x12", "--seed", "42"],
        ),
        (
            "dfs-9x9-seed42-walls.json",
            &["--style", "walls", "--seed", "42"],
        ),
        (
            "dfs-micromouse-seed42.json",
            &["--preset", "micromouse", "--seed", "42"],
        ),
    ];
    for (name, args) in extra {
        cases.push((name.into(), args.iter().map(|s| s.to_string()).collect()));
    }
    cases
}

#[test]
fn golden_layouts_are_reproduced_byte_for_byte() {
    let bless = std::env::var_os(BLESS).is_some();
    let mut mismatched = Vec::new();
    for (name, args) in golden_cases() {
        let output = bin()
            .arg("generate")
            .args(&args)
            .assert()
            .success()
            .get_output()
            .stdout
            .clone();
        let path = mazes_dir().join(&name);
        if bless {
            fs::create_dir_all(mazes_dir()).unwrap();
            fs::write(&path, &output).unwrap();
            continue;
        }
        let golden = fs::read(&path)
            .unwrap_or_else(|e| panic!("{}: {e} (bless with {BLESS}=1)", path.display()));
        if golden != output {
            mismatched.push(format!("{name} (generate {})", args.join(" ")));
        }
    }
    assert!(
        mismatched.is_empty(),
        "generated layouts differ from mazes/: {mismatched:?}; if the change is deliberate, re-bless with {BLESS}=1 and explain it"
    );
}

#[test]
fn every_file_in_mazes_is_valid() {
    if std::env::var_os(BLESS).is_some() {
        // Blessing rewrites the files concurrently; the next plain run checks them.
        return;
    }
    let mut count = 0;
    for entry in fs::read_dir(mazes_dir()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) != Some("json") {
            continue;
        }
        let layout = read_layout(&path).unwrap_or_else(|e| panic!("{e}"));
        let report = validate(&layout);
        assert!(report.is_ok(), "{}: {:?}", path.display(), report.problems);
        bin().arg("validate").arg(&path).assert().success();
        count += 1;
    }
    assert!(count >= golden_cases().len(), "only {count} golden files");
}

/// The golden imported maze: `mazes/drawn-4x4.txt`, drawn by hand in the micromouse
/// community's text format, imported to `mazes/drawn-4x4.json`.
#[test]
fn golden_import_is_reproduced_byte_for_byte() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let output = bin()
        .current_dir(root)
        .args(["import", "mazes/drawn-4x4.txt"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let path = mazes_dir().join("drawn-4x4.json");
    if std::env::var_os(BLESS).is_some() {
        fs::write(&path, &output).unwrap();
        return;
    }
    let golden = fs::read(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (bless with {BLESS}=1)", path.display()));
    assert!(
        golden == output,
        "import mazes/drawn-4x4.txt differs from mazes/drawn-4x4.json; if deliberate, re-bless with {BLESS}=1"
    );
}
