//! `vrep-maze solve`: the solution as data, the same path `render --solution` draws.

use std::collections::BTreeSet;
use std::path::Path;

use predicates::prelude::*;
use predicates::str::contains;
use serde_json::Value;

use crate::support::bin;

fn golden(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("mazes")
        .join(name)
        .display()
        .to_string()
}

fn stdout(args: &[&str]) -> String {
    let out = bin()
        .args(args)
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    String::from_utf8(out).unwrap()
}

/// The cells the ASCII picture marks as on the path (`.`, and `S`/`E` at its ends).
fn drawn_path(ascii: &str) -> BTreeSet<(u64, u64)> {
    let rows: Vec<&str> = ascii.lines().collect();
    let height = (rows.len() as u64 - 1) / 2;
    let mut cells = BTreeSet::new();
    for (i, row) in rows.iter().enumerate().filter(|(i, _)| i % 2 == 1) {
        let y = height - 1 - (i as u64 - 1) / 2;
        for (x, mark) in row.chars().skip(2).step_by(4).enumerate() {
            if matches!(mark, '.' | 'S' | 'E') {
                cells.insert((x as u64, y));
            }
        }
    }
    cells
}

fn solved_cells(report: &Value) -> BTreeSet<(u64, u64)> {
    report["cells"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| (c[0].as_u64().unwrap(), c[1].as_u64().unwrap()))
        .collect()
}

#[test]
fn solve_and_render_solution_show_the_same_path() {
    for name in [
        "dfs-9x9-seed42.json",
        "prim-9x9-seed42-braid0.5.json",
        "prim-20x15-seed7.json",
        "dfs-9x9-seed42-walls.json",
    ] {
        let file = golden(name);
        let report: Value = serde_json::from_str(&stdout(&["solve", &file])).unwrap();
        let picture = stdout(&["render", &file, "--solution"]);
        assert_eq!(solved_cells(&report), drawn_path(&picture), "{name}");
        let layout: Value = serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
        let cells = report["cells"].as_array().unwrap().len() as u64;
        assert_eq!(cells, layout["metrics"]["solution_cells"], "{name}");
        assert_eq!(
            report["turns"], layout["metrics"]["solution_turns"],
            "{name}"
        );
        assert_eq!(report["waypoints"][0]["x"], layout["start"]["pose"]["x"]);
    }
}

#[test]
fn a_braided_maze_gives_a_shortest_path() {
    // prim braided by half has loops: the path is as short as the metrics say, and no
    // cell is visited twice.
    let file = golden("prim-9x9-seed42-braid0.5.json");
    let report: Value = serde_json::from_str(&stdout(&["solve", &file])).unwrap();
    let cells = report["cells"].as_array().unwrap();
    assert_eq!(solved_cells(&report).len(), cells.len());
    assert_eq!(report["length"].as_f64().unwrap(), (cells.len() - 1) as f64);
}

#[test]
fn csv_rows_are_timed_at_the_given_speed() {
    let file = golden("dfs-9x9-seed42.json");
    let report: Value = serde_json::from_str(&stdout(&["solve", &file])).unwrap();
    let csv = stdout(&["solve", &file, "--format", "csv", "--speed", "0.5"]);
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("t,x,y,yaw"));
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    let waypoints = report["waypoints"].as_array().unwrap();
    assert_eq!(rows.len(), waypoints.len());
    for (row, w) in rows.iter().zip(waypoints) {
        assert_eq!(row[0], w["distance"].as_f64().unwrap() / 0.5);
        assert_eq!(
            row[1..],
            [
                w["x"].as_f64().unwrap(),
                w["y"].as_f64().unwrap(),
                w["yaw"].as_f64().unwrap()
            ]
        );
    }
    assert!(rows.windows(2).all(|r| r[1][0] >= r[0][0]));
    assert_eq!(
        rows.last().unwrap()[0],
        report["length"].as_f64().unwrap() / 0.5
    );
}

#[test]
fn another_start_and_bad_input_are_named() {
    let file = golden("dfs-9x9-seed42.json");
    let report: Value = serde_json::from_str(&stdout(&["solve", &file, "--from", "8,8"])).unwrap();
    assert_eq!(report["from"], serde_json::json!([8, 8]));
    assert_eq!(report["cells"][0], serde_json::json!([8, 8]));
    bin()
        .args(["solve", &file, "--from", "9,0"])
        .assert()
        .code(2)
        .stderr(contains("from cell (9,0) is off the 9x9 grid"));
    bin()
        .args(["solve", &file, "--from", "a"])
        .assert()
        .code(2)
        .stderr(contains("not a cell x,y"));
    bin()
        .arg("solve")
        .assert()
        .code(2)
        .stderr(contains("not provided: <FILE>"))
        .stderr(contains("serve").not());
}

#[test]
fn writing_a_file_says_what_was_written() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("path.csv");
    bin()
        .args([
            "solve",
            &golden("dfs-9x9-seed42.json"),
            "--format",
            "csv",
            "-o",
        ])
        .arg(&out)
        .assert()
        .success()
        .stdout("")
        .stderr(contains("wrote").and(contains("turns")));
    assert!(
        std::fs::read_to_string(&out)
            .unwrap()
            .starts_with("t,x,y,yaw\n")
    );
}
