//! `vrep-maze export -o maze.pointmaze.json` end to end: a W x H maze becomes Gymnasium-
//! Robotics' 2H+1 by 2W+1 `maze_map` with one `"r"` and one `"g"`, and the block size keeps the
//! cell size. The Python tests (python/tests/test_rl.py) load it into PointMaze.

use crate::support::bin;
use std::fs;
use tempfile::TempDir;

#[test]
fn a_five_by_four_maze_is_nine_rows_of_eleven_blocks() {
    let dir = TempDir::new().unwrap();
    let layout = dir.path().join("m.json");
    bin()
        .args([
            "generate",
            "-q",
            "--seed",
            "9",
            "--size",
            "5x4",
            "--cell-size",
            "0.5",
        ])
        .args(["--line-length", "0.3", "--line-width", "0.05"])
        .arg("-o")
        .arg(&layout)
        .assert()
        .success();
    let out = dir.path().join("m.pointmaze.json");
    bin()
        .arg("export")
        .arg(&layout)
        .arg("-o")
        .arg(&out)
        .assert()
        .success();
    let value: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(&out).unwrap()).unwrap();
    let rows = value["maze_map"].as_array().unwrap();
    assert_eq!(rows.len(), 9);
    assert!(rows.iter().all(|r| r.as_array().unwrap().len() == 11));
    let blocks: Vec<&serde_json::Value> = rows.iter().flat_map(|r| r.as_array().unwrap()).collect();
    assert_eq!(blocks.iter().filter(|b| **b == "r").count(), 1);
    assert_eq!(blocks.iter().filter(|b| **b == "g").count(), 1);
    assert_eq!(value["maze_size_scaling"], 0.25);
}
