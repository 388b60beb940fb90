//! `vrep-maze export` to the robot simulators' formats (MJCF, SDF, URDF, Webots), end to
//! end: a line maze and a wall maze with posts in every format and ending, same seed same
//! bytes, and the bad inputs (a bare `.xml`, a layout that fails validation). The real
//! parsers read these files in `tests/conformance/run-export.sh`.

use crate::support::bin;
use predicates::str::contains;
use std::fs;
use std::path::{Path, PathBuf};
use tempfile::TempDir;

const ENDINGS: [&str; 6] = [".mjcf", ".mujoco.xml", ".sdf", ".world", ".urdf", ".wbt"];

fn generate(dir: &Path, name: &str, args: &[&str]) -> PathBuf {
    let path = dir.join(name);
    bin()
        .args(["generate", "-q", "--seed", "9", "--size", "5x4"])
        .args(["--rotation", "20"])
        .args(args)
        .arg("-o")
        .arg(&path)
        .assert()
        .success();
    path
}

fn export(layout: &Path, out: &Path) -> String {
    bin()
        .arg("export")
        .arg(layout)
        .arg("-o")
        .arg(out)
        .assert()
        .success();
    fs::read_to_string(out).unwrap()
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn a_wall_maze_with_posts_in_every_format_collides_once_per_run_and_post() {
    let dir = TempDir::new().unwrap();
    let layout = generate(dir.path(), "w.json", &["--style", "walls", "--posts"]);
    let posts = json(&layout)["posts"].as_array().unwrap().len();
    assert_eq!(posts, 6 * 5);
    let text = |ending: &str| export(&layout, &dir.path().join(format!("w{ending}")));

    let mjcf = text(".mjcf");
    assert_eq!(mjcf, text(".mujoco.xml"));
    let runs = mjcf.matches("<geom name=\"wall_").count();
    assert!(runs > 0);
    assert_eq!(mjcf.matches("<geom name=\"post_").count(), posts);
    assert!(!mjcf.contains("contype"), "every wall and post collides");
    assert!(mjcf.contains("<site name=\"start\"") && mjcf.contains("<site name=\"end\""));
    assert!(
        mjcf.contains("euler=\"0 0 0.349066\""),
        "the maze's 20 degrees"
    );

    let sdf = text(".sdf");
    assert_eq!(sdf, text(".world"));
    assert!(sdf.contains("<model name=\"ground_plane\">"));
    assert!(sdf.contains("<model name=\"maze\">\n      <static>true</static>"));
    // the ground plane's collision, then one per run and post
    assert_eq!(sdf.matches("<collision ").count(), 1 + runs + posts);
    assert!(sdf.contains("<visual name=\"start\">") && sdf.contains("<visual name=\"end\">"));

    let urdf = text(".urdf");
    assert_eq!(urdf.matches("<link ").count(), 2);
    assert!(urdf.contains("type=\"fixed\""));
    assert_eq!(urdf.matches("<collision ").count(), runs + posts);
    assert_eq!(urdf.matches("<visual ").count(), runs + posts + 3);

    let wbt = text(".wbt");
    assert!(wbt.starts_with("#VRML_SIM R2023b utf8\n"));
    assert_eq!(wbt.matches("boundingObject Group").count(), 1);
    assert_eq!(wbt.matches("Box {").count(), 2 * (runs + posts) + 2);
}

#[test]
fn a_line_maze_in_every_format_is_paint_that_touches_nothing() {
    let dir = TempDir::new().unwrap();
    let layout = generate(dir.path(), "l.json", &[]);
    for ending in ENDINGS {
        let text = export(&layout, &dir.path().join(format!("l{ending}")));
        assert!(text.contains("line_0"), "{ending}");
        assert!(!text.contains("wall_"), "{ending}");
        match ending {
            ".mjcf" | ".mujoco.xml" => assert_eq!(
                text.matches("<geom name=\"line_").count(),
                text.matches("contype=\"0\" conaffinity=\"0\"").count()
            ),
            ".sdf" | ".world" => assert_eq!(text.matches("<collision ").count(), 1),
            ".urdf" => assert!(!text.contains("<collision")),
            _ => assert!(!text.contains("boundingObject Group")),
        }
    }
}

#[test]
fn the_same_seed_exports_the_same_bytes() {
    let dir = TempDir::new().unwrap();
    let a = generate(dir.path(), "a.json", &["--style", "walls", "--posts"]);
    let b = generate(dir.path(), "b.json", &["--style", "walls", "--posts"]);
    for ending in ENDINGS {
        let one = export(&a, &dir.path().join(format!("a{ending}")));
        let two = export(&b, &dir.path().join(format!("b{ending}")));
        assert_eq!(one, two, "{ending}");
    }
}

#[test]
fn a_bare_xml_is_ambiguous_and_an_invalid_layout_writes_nothing() {
    let dir = TempDir::new().unwrap();
    let layout = generate(dir.path(), "w.json", &["--style", "walls", "--posts"]);
    let bare = dir.path().join("maze.xml");
    bin()
        .arg("export")
        .arg(&layout)
        .arg("-o")
        .arg(&bare)
        .assert()
        .code(2)
        .stderr(contains("ambiguous"))
        .stderr(contains(".mjcf, .mujoco.xml, .sdf, .world, .urdf, .wbt"));
    assert!(!bare.exists());

    let text = fs::read_to_string(&layout).unwrap();
    let broken = dir.path().join("broken.json");
    fs::write(
        &broken,
        text.replacen("\"height\": 0.2", "\"height\": -0.2", 1),
    )
    .unwrap();
    for ending in ENDINGS {
        let out = dir.path().join(format!("old{ending}"));
        fs::write(&out, "old").unwrap();
        bin()
            .arg("export")
            .arg(&broken)
            .arg("-o")
            .arg(&out)
            .assert()
            .code(1)
            .stderr(contains("nothing was exported"));
        assert_eq!(fs::read_to_string(&out).unwrap(), "old", "{ending}");
    }
}
