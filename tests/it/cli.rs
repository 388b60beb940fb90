//! The command line, end to end: generate, validate, render, demo, and every bad input
//! the core issue lists. Bad input must give one clear error line and a non-zero exit.

use crate::support::bin;
use predicates::prelude::*;
use predicates::str::contains;
use std::fs;
use std::path::Path;
use tempfile::TempDir;

fn generate_to(dir: &TempDir, name: &str, args: &[&str]) -> std::path::PathBuf {
    let path = dir.path().join(name);
    bin()
        .arg("generate")
        .args(args)
        .arg("-o")
        .arg(&path)
        .assert()
        .success();
    path
}

#[test]
fn generate_prints_a_valid_v1_layout() {
    let out = bin()
        .args(["generate", "--seed", "42", "--algo", "prim"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let text = String::from_utf8(out).unwrap();
    assert!(text.starts_with("{\n  \"format\": \"vrep-maze/layout\",\n  \"version\": 1,"));
    bin()
        .args(["validate", "-"])
        .write_stdin(text)
        .assert()
        .success()
        .stdout(contains("OK -: 9x9 prim seed 42, 160 segments"))
        .stdout(contains("dead ends"));
}

#[test]
fn the_same_seed_gives_the_same_bytes_across_processes() {
    let run = || {
        bin()
            .args([
                "generate", "--seed", "1234", "--algo", "kruskal", "--size", "17x11",
            ])
            .assert()
            .success()
            .get_output()
            .stdout
            .clone()
    };
    let first = run();
    assert_eq!(first, run());
    let other = bin()
        .args([
            "generate", "--seed", "1235", "--algo", "kruskal", "--size", "17x11",
        ])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    assert_ne!(first, other);
}

#[test]
fn a_missing_seed_is_drawn_recorded_and_reproducible() {
    let dir = TempDir::new().unwrap();
    let path = dir.path().join("m.json");
    let assert = bin().args(["generate", "-o"]).arg(&path).assert().success();
    let stderr = String::from_utf8(assert.get_output().stderr.clone()).unwrap();
    let seed: u64 = stderr
        .split_whitespace()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("no seed in {stderr}"));
    let text = fs::read_to_string(&path).unwrap();
    assert!(text.contains(&format!("\"seed\": {seed},")));
    let again = bin()
        .args(["generate", "--seed", &seed.to_string()])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    assert_eq!(String::from_utf8(again).unwrap(), text);
}

#[test]
fn render_draws_ascii_and_svg() {
    let dir = TempDir::new().unwrap();
    let maze = generate_to(&dir, "m.json", &["--seed", "5", "--size", "4x3"]);
    bin()
        .arg("render")
        .arg(&maze)
        .arg("--solution")
        .assert()
        .success()
        .stdout(contains("+---+---+---+---+\n"))
        .stdout(contains(" S "))
        .stdout(contains(" E "));
    let svg = dir.path().join("m.svg");
    bin()
        .arg("render")
        .arg(&maze)
        .arg("-o")
        .arg(&svg)
        .assert()
        .success();
    let text = fs::read_to_string(svg).unwrap();
    assert!(text.starts_with("<svg ") && text.contains("#00ff00"));
}

#[test]
fn demo_runs_the_whole_job() {
    bin()
        .arg("demo")
        .assert()
        .success()
        .stdout(contains("OK 9x9 dfs seed 42, 160 segments"))
        .stdout(contains(" S "))
        .stdout(contains(
            "drew 160 lines: 1 kept (the template: 0 already in place, 1 placed), 159 pasted",
        ))
        .stdout(contains("verified: the scene holds 160 green lines"));
}

#[test]
fn every_command_has_an_example_in_its_help() {
    for command in [
        "generate",
        "validate",
        "render",
        "demo",
        "batch",
        "completions",
    ] {
        bin()
            .args([command, "--help"])
            .assert()
            .success()
            .stdout(contains("vrep-maze ").and(contains("Example")));
    }
}

/// Runs `generate` with `args` and expects a one-line error containing `needle`.
fn generate_fails(args: &[&str], needle: &str) {
    let assert = bin().arg("generate").args(args).assert().failure();
    let output = assert.get_output();
    assert!(output.stdout.is_empty(), "nothing on stdout for {args:?}");
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(stderr.contains(needle), "{args:?}: {stderr}");
    assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
}

#[test]
fn bad_generate_options_are_refused_by_name() {
    generate_fails(&["--size", "0x5"], "both sides need at least 1 cell");
    generate_fails(
        &["--size", "100000x100000"],
        "the limit is 16777216 cells (4096x4096)",
    );
    generate_fails(&["--size", "-3x3"], "is not WxH");
    generate_fails(&["--algo", "mazeomatic"], "unknown algorithm 'mazeomatic'");
    generate_fails(&["--start", "9,0"], "--start 9,0 is off the 9x9 grid");
    generate_fails(&["--end", "0,9"], "--end 0,9 is off the 9x9 grid");
    generate_fails(&["--start", "middle"], "is not a cell 'x,y'");
    generate_fails(&["--cell-size", "-1"], "positive, finite number of metres");
    generate_fails(&["--cell-size", "NaN"], "positive, finite number of metres");
    generate_fails(&["--line-width", "0"], "positive, finite number of metres");
    generate_fails(&["--origin", "1,inf"], "not a finite number");
    generate_fails(&["--floor-size", "5x5"], "--floor-size is 5 m x 5 m");
    generate_fails(&["--seed", "-1"], "--seed");
    generate_fails(&["--braid", "1.5"], "is not a number from 0 to 1");
}

#[test]
fn one_by_one_is_allowed_and_says_start_is_end() {
    bin()
        .args(["generate", "--size", "1x1", "--seed", "1"])
        .assert()
        .success()
        .stderr(contains("start and end are the same cell (0,0)"))
        .stdout(contains("\"segments\": []"));
}

/// Validates `text` (as a file) and expects failure with `needle` on stderr.
fn validate_fails(text: &str, needle: &str) {
    let dir = TempDir::new().unwrap();
    let path = dir.path().join("bad.json");
    fs::write(&path, text).unwrap();
    let assert = bin().arg("validate").arg(&path).assert().failure();
    let stderr = String::from_utf8_lossy(&assert.get_output().stderr).to_string();
    assert!(stderr.contains(needle), "expected {needle:?} in: {stderr}");
    assert!(stderr.contains("bad.json"), "names the file: {stderr}");
    assert!(!stderr.contains("panicked"), "{stderr}");
}

fn good_text() -> String {
    let out = bin()
        .args(["generate", "--seed", "42", "--size", "5x5"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    String::from_utf8(out).unwrap()
}

#[test]
fn bad_layout_files_are_refused_with_line_and_column() {
    let good = good_text();
    validate_fails(
        "{\"format\": \"vrep-maze/layout\",\n \"version\": 1,,}",
        "bad.json:2:15: key must be a string",
    );
    validate_fails(&good[..good.len() / 2], "EOF while parsing");
    validate_fails(
        &good.replacen("\"version\": 1,", "\"version\": 2,", 1),
        "layout version 2 is not supported (this vrep-maze reads version 1)",
    );
    validate_fails(
        &good.replacen("vrep-maze/layout", "something-else", 1),
        "not a vrep-maze layout",
    );
    validate_fails(
        &good.replacen("\"cell_size\": 1.0", "\"cell_size\": -1.0", 1),
        "grid.cell_size: must be a positive number of metres, not -1",
    );
    validate_fails(
        &good.replacen("\"columns\": 5", "\"columns\": 6", 1),
        "passages[0] has 5 characters but grid.columns is 6",
    );
    validate_fails("", "EOF while parsing");
    bin()
        .args(["validate", "/nonexistent/m.json"])
        .assert()
        .failure()
        .stderr(contains("/nonexistent/m.json: No such file"));
}

#[test]
fn validate_accepts_a_fresh_layout() {
    let dir = TempDir::new().unwrap();
    let path = dir.path().join("ok.json");
    fs::write(&path, good_text()).unwrap();
    bin()
        .arg("validate")
        .arg(&path)
        .assert()
        .success()
        .stdout(contains("OK "))
        .stdout(contains("loops 0"));
}

#[test]
fn batch_writes_a_dataset_and_skips_what_is_there() {
    let dir = TempDir::new().unwrap();
    let out = dir.path().join("set");
    let run = || {
        bin()
            .args([
                "batch",
                "--algo",
                "kruskal",
                "--size",
                "6x6",
                "--seeds",
                "0..=9",
                "--out-dir",
            ])
            .arg(&out)
            .assert()
            .success()
    };
    run().stderr(contains("10 mazes: 10 written, 0 unchanged"));
    run().stderr(contains("10 mazes: 0 written, 10 unchanged"));
    let manifest = fs::read_to_string(out.join("manifest.jsonl")).unwrap();
    assert_eq!(manifest.lines().count(), 10);
    let single = bin()
        .args([
            "generate", "--algo", "kruskal", "--size", "6x6", "--seed", "3",
        ])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    assert_eq!(
        fs::read(out.join("kruskal-6x6-seed3.json")).unwrap(),
        single
    );
    bin()
        .args(["batch", "--seeds", "5..5", "--out-dir"])
        .arg(&out)
        .assert()
        .failure()
        .stderr(contains("'5..5' is an empty range"));
}

#[test]
fn completions_cover_every_command() {
    for shell in ["bash", "zsh", "fish"] {
        let out = bin()
            .args(["completions", shell])
            .assert()
            .success()
            .get_output()
            .stdout
            .clone();
        let script = String::from_utf8(out).unwrap();
        for command in ["generate", "validate", "render", "batch", "demo"] {
            assert!(script.contains(command), "{shell} lacks {command}");
        }
    }
    bin().args(["completions", "tcsh"]).assert().failure();
}

/// Every `--help` example that makes files runs as printed (through `sh`, in a scratch
/// folder with `HOME` pointing there) and makes them: a help example that makes nothing,
/// like the old batch example whose filter refused every maze, fails here. Examples that
/// need a running simulator (apply, clear, serve) are left to the drawing tests.
#[test]
fn help_examples_that_make_files_make_them() {
    let dir = tempfile::TempDir::new().unwrap();
    let home = dir.path();
    for sub in [
        ".local/share/bash-completion/completions",
        ".zfunc",
        ".config/fish/completions",
    ] {
        std::fs::create_dir_all(home.join(sub)).unwrap();
    }
    std::os::unix::fs::symlink(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("mazes"),
        home.join("mazes"),
    )
    .unwrap();
    let exe = assert_cmd::cargo::cargo_bin("vrep-maze");
    let path = format!(
        "{}:{}",
        exe.parent().unwrap().display(),
        std::env::var("PATH").unwrap_or_default()
    );
    let mut ran = 0;
    for command in ["generate", "validate", "render", "batch", "completions"] {
        let help = bin().args([command, "--help"]).output().unwrap();
        let help = String::from_utf8(help.stdout).unwrap();
        let examples = help
            .lines()
            .skip_while(|l| !l.starts_with("Example"))
            .filter_map(|l| l.trim().strip_prefix("vrep-maze ").map(|_| l.trim()));
        for example in examples {
            let out = std::process::Command::new("sh")
                .args(["-c", example])
                .current_dir(home)
                .env("HOME", home)
                .env("PATH", &path)
                .output()
                .unwrap();
            assert!(
                out.status.success(),
                "`{example}` failed: {}",
                String::from_utf8_lossy(&out.stderr)
            );
            ran += 1;
            let words: Vec<&str> = example.split_whitespace().collect();
            for (i, w) in words.iter().enumerate() {
                let Some(target) = words.get(i + 1) else {
                    continue;
                };
                let target = target.replace('~', &home.display().to_string());
                let made = home.join(&target);
                match *w {
                    "-o" | ">" => assert!(
                        std::fs::metadata(&made).is_ok_and(|m| m.len() > 0),
                        "`{example}` made no {target}"
                    ),
                    "--out-dir" => {
                        let layouts = std::fs::read_dir(&made)
                            .unwrap()
                            .filter(|e| e.as_ref().unwrap().file_name() != "manifest.jsonl")
                            .count();
                        assert!(layouts > 0, "`{example}` made no layout in {target}");
                    }
                    _ => {}
                }
            }
        }
    }
    assert!(ran >= 12, "only {ran} examples found");
}

#[test]
fn export_writes_coppeliasim_models_and_scenes_chosen_by_the_ending() {
    let dir = TempDir::new().unwrap();
    let maze = generate_to(&dir, "m.json", &["--seed", "5", "--size", "4x3"]);
    for (name, filetype) in [
        ("m.simmodel.xml", "exhaustiveModel"),
        ("m.simscene.xml", "exhaustiveScene"),
    ] {
        let out = dir.path().join(name);
        bin()
            .arg("export")
            .arg(&maze)
            .arg("-o")
            .arg(&out)
            .assert()
            .success()
            // said as render says what it wrote
            .stderr(contains(format!(
                "wrote {}: a CoppeliaSim XML {} of 4x3",
                out.display(),
                if filetype == "exhaustiveModel" {
                    "model"
                } else {
                    "scene"
                }
            )));
        let text = fs::read_to_string(&out).unwrap();
        assert!(text.contains(&format!("<filetype>{filetype}</filetype>")));
        assert!(text.contains("<alias>MazeMesh_l_"), "{name}");
    }
    let unknown = dir.path().join("m.ttm");
    bin()
        .arg("export")
        .arg(&maze)
        .arg("-o")
        .arg(&unknown)
        .assert()
        .code(2)
        .stderr(contains(".simmodel.xml, .simscene.xml"));
    assert!(!unknown.exists());
}

#[test]
fn export_format_overrides_the_ending_and_a_bare_xml_without_it_is_refused() {
    let dir = TempDir::new().unwrap();
    let maze = generate_to(&dir, "m.json", &["--seed", "5", "--size", "4x3"]);
    let bare = dir.path().join("m.xml");
    bin()
        .arg("export")
        .arg(&maze)
        .arg("-o")
        .arg(&bare)
        .assert()
        .code(2)
        .stderr(contains("a bare .xml is ambiguous"))
        .stderr(contains("--format"));
    assert!(!bare.exists());
    for (format, marker) in [
        ("coppelia-scene", "<filetype>exhaustiveScene</filetype>"),
        ("mjcf", "<mujoco"),
    ] {
        bin()
            .arg("export")
            .arg(&maze)
            .arg("-o")
            .arg(&bare)
            .args(["--format", format])
            .assert()
            .success();
        let text = fs::read_to_string(&bare).unwrap();
        assert!(text.contains(marker), "{format}: {text:.200}");
    }
    // the format wins over an ending that names another one
    let urdf = dir.path().join("m.urdf");
    bin()
        .arg("export")
        .arg(&maze)
        .arg("-o")
        .arg(&urdf)
        .args(["--format", "webots"])
        .assert()
        .success();
    assert!(fs::read_to_string(&urdf).unwrap().starts_with("#VRML_SIM"));
    bin()
        .arg("export")
        .arg(&maze)
        .arg("-o")
        .arg(&bare)
        .args(["--format", "ttm"])
        .assert()
        .code(2)
        .stderr(contains("coppelia-model"));
}

#[test]
fn export_of_a_layout_that_fails_validation_writes_nothing() {
    let dir = TempDir::new().unwrap();
    let maze = generate_to(&dir, "m.json", &["--seed", "5", "--size", "4x3"]);
    let text = fs::read_to_string(&maze).unwrap();
    let broken = dir.path().join("broken.json");
    fs::write(
        &broken,
        text.replacen("\"cell_size\": 1.0", "\"cell_size\": 0.01", 1),
    )
    .unwrap();
    let out = dir.path().join("m.simmodel.xml");
    fs::write(&out, "old").unwrap();
    bin()
        .arg("export")
        .arg(&broken)
        .arg("-o")
        .arg(&out)
        .assert()
        .code(1)
        .stderr(contains("nothing was exported"));
    assert_eq!(
        fs::read_to_string(&out).unwrap(),
        "old",
        "the old file stays"
    );
}

#[test]
fn batch_makes_every_style_byte_for_byte_as_generate_does() {
    let dir = TempDir::new().unwrap();
    for (sub, args, file) in [
        (
            "w",
            &[
                "--style",
                "walls",
                "--posts",
                "--size",
                "5x4",
                "--openings",
                "start",
            ][..],
            "dfs-5x4-seed1-walls-posts.json",
        ),
        (
            "m",
            &["--preset", "micromouse-half", "--algo", "prim"][..],
            "prim-micromouse-half-seed1.json",
        ),
        (
            "l",
            &["--size", "6x6", "--braid", "0.5"][..],
            "dfs-6x6-braid0.5-seed1.json",
        ),
    ] {
        let out = dir.path().join(sub);
        bin()
            .args(["batch", "--seeds", "0..3", "--out-dir"])
            .arg(&out)
            .args(args)
            .assert()
            .success()
            .stderr(contains("3 mazes: 3 written"));
        let made = fs::read(out.join(file)).unwrap();
        let generated = bin()
            .args(["generate", "--seed", "1"])
            .args(args)
            .assert()
            .success()
            .get_output()
            .stdout
            .clone();
        assert!(made == generated, "{file}");
    }
    bin()
        .args(["batch", "--seeds", "0..3", "--posts", "--out-dir"])
        .arg(dir.path().join("x"))
        .assert()
        .code(2)
        .stderr(contains("--posts shapes walls"));
    assert!(
        !dir.path().join("x").exists(),
        "a refused batch makes nothing"
    );
}
