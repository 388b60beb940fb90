//! `vrep-maze export -o maze.yaml`: a ROS map_server map, as the command line writes it (the
//! pixels are the core module's tests; the files read by other parsers are
//! `tests/conformance/ros_map.py`'s).

use crate::support::bin;
use predicates::str::contains;
use std::fs;
use std::path::Path;

/// The golden layout `name` under `mazes/`.
fn golden(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("mazes")
        .join(name)
}

#[test]
fn a_yaml_output_writes_the_map_and_its_image_beside_it_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let yaml = dir.path().join("maze.yaml");
    bin()
        .arg("export")
        .arg(golden("dfs-9x9-seed42.json"))
        .arg("-o")
        .arg(&yaml)
        .assert()
        .success()
        .stderr(contains(
            "maze.pgm: a ROS map_server occupancy map of 9x9 dfs seed 42",
        ))
        .stderr(contains("200 x 200 px at 0.05 m a pixel"));
    let text = fs::read_to_string(&yaml).unwrap();
    assert!(text.contains("\nimage: \"maze.pgm\"\n"), "{text}");
    let pgm = fs::read(dir.path().join("maze.pgm")).unwrap();
    assert!(pgm.starts_with(b"P5\n200 200\n255\n"));
    assert_eq!(pgm.len(), "P5\n200 200\n255\n".len() + 200 * 200);
    // the same layout, the same bytes; --px-per-m sets the scale
    let again = dir.path().join("again.yml");
    bin()
        .arg("export")
        .arg(golden("dfs-9x9-seed42.json"))
        .arg("-o")
        .arg(&again)
        .args(["--px-per-m", "40"])
        .assert()
        .success();
    assert!(
        fs::read_to_string(&again)
            .unwrap()
            .contains("\nresolution: 0.025\n")
    );
    assert!(
        fs::read(dir.path().join("again.pgm"))
            .unwrap()
            .starts_with(b"P5\n400 400\n255\n")
    );
}

#[test]
fn the_map_options_are_refused_where_they_mean_nothing() {
    let dir = tempfile::tempdir().unwrap();
    bin()
        .arg("export")
        .arg(golden("dfs-9x9-seed42.json"))
        .arg("-o")
        .arg(dir.path().join("m.wbt"))
        .args(["--px-per-m", "40"])
        .assert()
        .code(2)
        .stderr(contains("shape a ROS map (-o FILE.yaml)"));
    bin()
        .arg("export")
        .arg(golden("dfs-micromouse-seed42.json"))
        .arg("-o")
        .arg(dir.path().join("m.yaml"))
        .arg("--occupied-lines")
        .assert()
        .code(2)
        .stderr(contains("--occupied-lines is for a line maze"));
    bin()
        .arg("export")
        .arg(golden("dfs-9x9-seed42.json"))
        .arg("-o")
        .arg(dir.path().join("m.yaml"))
        .args(["--px-per-m", "5000"])
        .assert()
        .code(1)
        .stderr(contains("pass a smaller --px-per-m"));
    assert_eq!(
        fs::read_dir(dir.path()).unwrap().count(),
        0,
        "nothing written"
    );
}
