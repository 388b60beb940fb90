//! `vrep-maze score` as a user runs it, against a `vrep-maze serve --robot` child: the
//! JSON report and its schema, the trajectory file, the exit codes of a complete, a
//! partial and a failed run.

use std::fs;
use std::path::Path;

use crate::support::bin;
use crate::support::cli::Serve;

/// The 3 x 3 course maze (DFS, seed 1): Start at floor (-1, -1), End at (1, -1); the
/// solution goes up, along the top row and down (6 m).
fn layout(dir: &Path) -> String {
    let path = dir.join("m.json").display().to_string();
    bin()
        .args([
            "generate", "--size", "3x3", "--seed", "1", "--algo", "dfs", "-o", &path,
        ])
        .assert()
        .success();
    path
}

/// A path file along floor points at 1 m/s, after half a second at the first one (so the
/// scorer, which may join a step or two after the start, sees where the robot started):
/// 0.05 m a 50 ms step, so a scorer slowed by a busy machine may miss eight steps in a row
/// (0.45 m) and still see every half cell, as `score` needs to grade the run. At 2 m/s, four
/// missed steps made a move of 0.5 m, which is not under half a cell: the full suite beside
/// other builds on a 2-core machine failed so.
fn path_file(dir: &Path, points: &[(f64, f64)]) -> String {
    let mut text = format!("t,x,y,yaw\n0,{},{},0\n", points[0].0, points[0].1);
    let mut t = 0.5;
    let mut last: Option<(f64, f64)> = None;
    for &(x, y) in points {
        if let Some((lx, ly)) = last {
            t += (x - lx).hypot(y - ly);
        }
        text += &format!("{t},{x},{y},0\n");
        last = Some((x, y));
    }
    let file = dir.join("path.csv");
    fs::write(&file, text).unwrap();
    file.display().to_string()
}

const SOLUTION: [(f64, f64); 4] = [(-1.0, -1.0), (-1.0, 1.0), (1.0, 1.0), (1.0, -1.0)];

fn serve(robot: Option<&str>, api: &str) -> Serve {
    let mut args = vec![
        "--listen",
        "127.0.0.1:0",
        "--timing",
        "instant",
        "--idle-fps",
        "0",
        "--api",
        api,
    ];
    if let Some(path) = robot {
        args.extend(["--robot", path]);
    }
    Serve::start(&args, 1)
}

fn schema_path() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("schema/score-report.schema.json")
}

/// The checked-in schema is `ScoreJson`'s (`tests/it/schema.rs` keeps every report's equal
/// to its type, and re-blesses them) and names what a grader reads.
#[test]
fn the_report_schema_is_the_score_json_type_s() {
    let (_, schema) = vrep_maze::cli::reports::schemas()
        .into_iter()
        .find(|(name, _)| *name == "score-report.schema.json")
        .expect("score's schema is one of the reports'");
    let text = serde_json::to_string_pretty(&schema).unwrap() + "\n";
    for field in [
        "reached_end",
        "time_s",
        "path_length_m",
        "shortest_length_m",
        "spl",
        "complete",
        "incomplete_reason",
        "sampling",
        "largest_jump_m",
        "jumps_over_max",
        "hints",
    ] {
        assert!(text.contains(&format!("\"{field}\"")), "{field}");
    }
    assert!(schema_path().exists());
}

#[test]
fn a_perfect_run_over_each_api_is_reported_as_json_that_satisfies_the_schema() {
    let dir = tempfile::tempdir().unwrap();
    let maze = layout(dir.path());
    let robot = path_file(dir.path(), &SOLUTION);
    let schema: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(schema_path()).unwrap()).unwrap();
    let validator = jsonschema::validator_for(&schema).unwrap();
    for api in ["legacy", "zmq"] {
        let server = serve(Some(&robot), api);
        let run = dir.path().join(format!("run-{api}.csv"));
        let out = bin()
            .args([
                "score",
                &maze,
                "--api",
                api,
                "--port",
                &server.port(),
                "--start-simulation",
                "--json",
            ])
            .args(["--timeout", "60", "--trajectory", run.to_str().unwrap()])
            .assert()
            .success()
            .get_output()
            .stdout
            .clone();
        let report: serde_json::Value = serde_json::from_slice(&out).unwrap();
        assert!(validator.is_valid(&report), "{api}: {report}");
        assert_eq!(report["complete"], true, "{api}");
        assert_eq!(report["reached_end"], true, "{api}");
        assert_eq!(report["shortest_length_m"], 6.0, "{api}");
        assert!(
            (report["spl"].as_f64().unwrap() - 1.0).abs() < 1e-9,
            "{api}: {report}"
        );
        let csv = fs::read_to_string(&run).unwrap();
        let samples = vrep_maze::score::trajectory::parse_csv(&csv).unwrap();
        assert_eq!(
            Some(samples.len() as u64),
            report["samples"].as_u64(),
            "{api}"
        );
    }
}

/// The README's pair, `drive LAYOUT --api zmq &` then `score LAYOUT --start-simulation`,
/// where the robot jumps between the samples: on a headless CoppeliaSim the simulation runs
/// far faster than `drive`'s remote calls move the robot (the issue saw 54 samples up to 7 m
/// apart, graded complete with SPL 1); `serve` runs in real time, so a fast robot makes the
/// jumps here (30 m/s: 1.5 m a 50 ms step on 1 m cells). The run is never complete, has no
/// SPL, says why and what to do, in JSON and in text, and exits 3.
#[test]
fn the_readme_pair_with_a_robot_jumping_between_samples_is_not_graded() {
    use std::io::{BufRead, BufReader};
    use std::process::Stdio;

    let dir = tempfile::tempdir().unwrap();
    let maze = layout(dir.path());
    let server = serve(None, "zmq");
    let port = server.port();
    for json in [true, false] {
        let mut driver = crate::support::cli::spawnable()
            .args(["drive", &maze, "--api", "zmq", "--port", &port])
            .args(["--speed", "30", "--run-timeout", "60"])
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // score may start the simulation once the robot stands at Start
        let mut said = String::new();
        for line in BufReader::new(driver.stderr.take().unwrap()).lines() {
            let line = line.unwrap();
            said += &line;
            if line.starts_with("waiting for the simulation") {
                break;
            }
        }
        assert!(said.contains("waiting for the simulation"), "{said}");
        let mut score = bin();
        score.args(["score", &maze, "--api", "zmq", "--port", &port]);
        score.args(["--start-simulation", "--timeout", "60"]);
        if json {
            score.arg("--json");
        }
        let out = score.assert().code(3).get_output().stdout.clone();
        assert!(driver.wait().unwrap().success(), "drive ends with the run");
        let text = String::from_utf8(out).unwrap();
        if json {
            let report: serde_json::Value = serde_json::from_str(&text).unwrap();
            let schema: serde_json::Value =
                serde_json::from_str(&fs::read_to_string(schema_path()).unwrap()).unwrap();
            assert!(jsonschema::is_valid(&schema, &report), "{report}");
            assert_eq!(report["complete"], false, "{report}");
            assert_eq!(report["spl"], serde_json::Value::Null, "{report}");
            let sampling = &report["sampling"];
            assert!(
                sampling["jumps_over_max"].as_u64().unwrap() > 0
                    && sampling["largest_jump_m"].as_f64().unwrap() > 0.5
                    && sampling["max_jump_m"] == 0.5,
                "{report}"
            );
            let why = report["incomplete_reason"].as_str().unwrap();
            assert!(why.starts_with("sampled too sparsely to grade"), "{why}");
            let hints = report["hints"].to_string();
            assert!(
                hints.contains("--real-time") && hints.contains("drive --wheels"),
                "{hints}"
            );
        } else {
            assert!(
                text.starts_with("run: INCOMPLETE (sampled too sparsely to grade: ")
                    && text.contains("SPL: none (sampled too sparsely to grade)")
                    && text.contains("hint: `vrep-maze drive` moves its robot by remote calls")
                    && text.contains("run it with --real-time"),
                "{text}"
            );
        }
    }
}

#[test]
fn a_run_cut_short_by_the_timeout_is_a_partial_report_with_exit_code_3() {
    let dir = tempfile::tempdir().unwrap();
    let maze = layout(dir.path());
    // up column 0 and stand there: End is never reached
    let robot = path_file(dir.path(), &SOLUTION[..2]);
    let server = serve(Some(&robot), "legacy");
    let out = bin()
        .args([
            "score",
            &maze,
            "--port",
            &server.port(),
            "--start-simulation",
            "--timeout",
            "1.5",
        ])
        .assert()
        .code(3)
        .get_output()
        .stdout
        .clone();
    let text = String::from_utf8(out).unwrap();
    assert!(
        text.contains("run: INCOMPLETE (the timeout of 1.5 s passed first)"),
        "{text}"
    );
    assert!(
        text.contains("reached End: no") && text.contains("SPL: 0.000"),
        "{text}"
    );
}

#[test]
fn a_missing_robot_and_a_simulation_that_never_starts_are_errors() {
    let dir = tempfile::tempdir().unwrap();
    let maze = layout(dir.path());
    let server = serve(None, "zmq");
    let port = server.port();
    bin()
        .args([
            "score",
            &maze,
            "--api",
            "zmq",
            "--port",
            &port,
            "--start-simulation",
        ])
        .assert()
        .code(1)
        .stderr(predicates::str::contains(
            "the scene has no object named `Robot`",
        ));
    // without --start-simulation too: said at once with the remedies, before any wait
    let out = bin()
        .args(["score", &maze, "--api", "zmq", "--port", &port])
        .args(["--timeout", "60"])
        .timeout(std::time::Duration::from_secs(20))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{stderr}");
    assert!(!stderr.contains("waiting for the simulation"), "{stderr}");
    assert!(
        stderr.contains("the scene has no object named `Robot`")
            && stderr.contains("hint: pass --robot NAME")
            && stderr
                .contains("hint: without a robot of your own: `vrep-maze drive LAYOUT --api zmq &` adds one named Robot"),
        "{stderr}"
    );
    bin()
        .args([
            "score",
            &maze,
            "--api",
            "zmq",
            "--port",
            &port,
            "--robot",
            "Floor",
            "--timeout",
            "0.3",
        ])
        .assert()
        .code(1)
        .stderr(predicates::str::contains(
            "the simulation did not start within 0.3 s; nothing was changed",
        ));
}

#[test]
fn render_draws_a_trajectory_as_svg_or_png_and_refuses_ascii() {
    let dir = tempfile::tempdir().unwrap();
    let maze = layout(dir.path());
    let run = dir.path().join("run.csv");
    fs::write(&run, "t,x,y,yaw\n0,-1,-1,0\n1,-1,0,0\n2,0,0,0\n").unwrap();
    let run = run.to_str().unwrap();
    for ext in ["svg", "png"] {
        let out = dir.path().join(format!("run.{ext}"));
        bin()
            .args([
                "render",
                &maze,
                "--trajectory",
                run,
                "-o",
                out.to_str().unwrap(),
            ])
            .assert()
            .success();
        let plain = dir.path().join(format!("plain.{ext}"));
        bin()
            .args(["render", &maze, "--solution", "-o", plain.to_str().unwrap()])
            .assert()
            .success();
        assert_ne!(
            fs::read(&out).unwrap(),
            fs::read(&plain).unwrap(),
            "{ext}: the run is drawn"
        );
    }
    let svg = fs::read_to_string(dir.path().join("run.svg")).unwrap();
    assert!(
        svg.contains(r#"stroke-linecap="round""#),
        "the run's polylines"
    );
    bin()
        .args(["render", &maze, "--trajectory", run])
        .assert()
        .code(2)
        .stderr(predicates::str::contains("SVG or PNG only"));
    let never = dir.path().join("never.svg");
    bin()
        .args([
            "render",
            &maze,
            "--trajectory",
            &maze,
            "-o",
            never.to_str().unwrap(),
        ])
        .assert()
        .code(1)
        .stderr(predicates::str::contains("header must be `t,x,y,yaw`"));
    assert!(!never.exists());
}
