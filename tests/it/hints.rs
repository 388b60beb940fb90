//! Issue 30, items 2 and 7-10: a template's home is recorded only from its own pose; the templates' full sizes and the floor's are checked, and every
//! hint the tool prints is a command that works: each one here is followed as a person would
//! follow it, and the drawing then succeeds. Readers of user input are bounded, and names on
//! success paths are escaped.

use std::io::Write;
use std::process::{Command, Stdio};

use assert_cmd::cargo::CommandCargoExt;
use tempfile::TempDir;
use vrep_maze::cli::remedies;
use vrep_maze::draw::{self, ApplyOptions, Backend, ClearOptions, DrawError, Drawing, ObjectNames};
use vrep_maze::layout::read_layout;
use vrep_maze::sim::Scene;

use crate::support::backend::{Kind, Server};
use crate::support::backend_tests;
use crate::support::bin;

backend_tests!(
    a_size_hint_followed_draws_the_maze,
    a_tall_line_or_marker_is_refused_until_flat,
    a_small_floor_is_refused_with_hints_that_work,
    a_users_copy_of_line_does_not_cost_the_template_its_home,
);

/// `generate --seed 1 ARGS -o dir/name`, as a drawing.
fn generated(dir: &TempDir, name: &str, args: &[&str]) -> Drawing {
    let path = dir.path().join(name);
    bin()
        .args(["generate", "--seed", "1", "-o"])
        .arg(&path)
        .args(args)
        .assert()
        .success();
    Drawing::try_from(&read_layout(&path).unwrap()).unwrap()
}

fn apply(b: &mut dyn Backend, d: &Drawing) -> Result<draw::ApplyReport, DrawError> {
    draw::apply(b, d, &ApplyOptions::default(), &mut |_| {})
}

/// Resizes `name` in the emulated scene (what a person does in CoppeliaSim's dialog).
fn resize(s: &Server, name: &str, size: [f64; 3]) {
    s.with_sim(|sim| {
        let h = sim.scene.resolve(name).unwrap();
        sim.scene.set_size(h, size).unwrap();
    });
}

/// The options after "generate with " in a refusal, up to " (and".
fn generate_options(text: &str) -> Vec<String> {
    let from = text.find("generate with ").expect("a generate hint") + "generate with ".len();
    let to = text[from..].find(" (and").unwrap() + from;
    text[from..to].split(' ').map(String::from).collect()
}

/// A 0.3 x 0.05 m `Line` on a 1 m course layout: the refusal offers generate options;
/// generated with them, the maze draws. A template turned a quarter (0.1 x 0.6) has no
/// options `generate` takes: only the resize is offered, and after it the maze draws.
fn a_size_hint_followed_draws_the_maze(kind: Kind) {
    let k = kind.name();
    let dir = TempDir::new().unwrap();
    let s = kind.serve(Scene::course(), 0);
    let mut b = s.connect();
    let course = generated(&dir, "course.json", &["--size", "5x5"]);
    resize(&s, "Line", [0.3, 0.05, 0.0]);
    let e = apply(&mut *b, &course).unwrap_err();
    let e = vrep_maze::cli::remedies::message(&e);
    let options = generate_options(&e);
    let mut args = vec!["--size".to_string(), "5x5".into()];
    args.extend(options);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let fitted = generated(&dir, "fitted.json", &args);
    apply(&mut *b, &fitted).unwrap_or_else(|e| panic!("{k}: {e}"));
    resize(&s, "Line", [0.1, 0.6, 0.0]);
    let e = apply(&mut *b, &course).unwrap_err();
    let e = vrep_maze::cli::remedies::message(&e);
    assert!(
        !e.contains("generate with") && e.contains("resize `Line` to 0.6 x 0.1 m"),
        "{k}: {e}"
    );
    resize(&s, "Line", [0.6, 0.1, 0.0]);
    apply(&mut *b, &course).unwrap_or_else(|e| panic!("{k}: {e}"));
    drop(b);
    s.shutdown();
}

/// Issue 30 item 7: a 0.6 x 0.1 x 0.3 m cuboid `Line` would give boxes 30 cm tall, and a
/// 0.5 m tall `Start` is an obstacle: refused, and drawn once they are flat as told.
fn a_tall_line_or_marker_is_refused_until_flat(kind: Kind) {
    let k = kind.name();
    let dir = TempDir::new().unwrap();
    let s = kind.serve(Scene::course(), 0);
    let before = s.snapshot();
    let mut b = s.connect();
    let course = generated(&dir, "course.json", &["--size", "5x5"]);
    resize(&s, "Line", [0.6, 0.1, 0.3]);
    resize(&s, "Start", [1.0, 1.0, 0.5]);
    let e = apply(&mut *b, &course).unwrap_err();
    let e = vrep_maze::cli::remedies::message(&e);
    assert!(
        e.contains("`Line` is 0.3 m high")
            && e.contains("resize `Line` to 0.6 x 0.1 x 0 m")
            && e.contains("`Start` is 0.5 m high")
            && e.contains("resize `Start` to 1 x 1 x 0 m"),
        "{k}: {e}"
    );
    assert!(
        matches!(
            draw::verify(&mut *b, &course, &Default::default()),
            Err(DrawError::Sizes(_))
        ),
        "{k}: verify compares heights too"
    );
    resize(&s, "Line", [0.6, 0.1, 0.0]);
    resize(&s, "Start", [1.0, 1.0, 0.0]);
    assert_eq!(s.snapshot().len(), before.len(), "{k}: nothing drawn");
    apply(&mut *b, &course).unwrap_or_else(|e| panic!("{k}: {e}"));
    drop(b);
    s.shutdown();
}

/// Issue 30 item 7: a 9 m maze on a 4 m `Floor`, and a 12 m maze on the course's 10 m
/// floor, are refused naming both sizes. Over ZeroMQ the hint `--resize-floor` grows the
/// floor and `clear` puts it back; over legacy the hint says how instead.
fn a_small_floor_is_refused_with_hints_that_work(kind: Kind) {
    let k = kind.name();
    let dir = TempDir::new().unwrap();
    let s = kind.serve(Scene::course().with_floor([4.0, 4.0]), 0);
    let mut b = s.connect();
    let nine = generated(&dir, "nine.json", &[]);
    let e = apply(&mut *b, &nine).unwrap_err();
    assert_eq!(
        e.to_string(),
        "the scene's `Floor` is 4 x 4 m but the layout's floor is 10 x 10 m",
        "{k}"
    );
    let hints = remedies::hints(&e);
    let floor_size = |s: &Server| {
        s.with_sim(|sim| {
            let h = sim.scene.resolve("Floor").unwrap();
            sim.scene.get(h).unwrap().size
        })
    };
    // a comparison with the layout offers what this connection can do, as apply does
    let v = draw::verify(&mut *b, &nine, &ObjectNames::default()).unwrap_err();
    assert_eq!(
        remedies::hints(&v),
        hints,
        "{k}: verify's hints are apply's"
    );
    if kind == Kind::Legacy {
        assert!(hints[0].contains("--api zmq"), "{k}: {hints:?}");
        drop(b);
        s.shutdown();
        return;
    }
    assert!(
        hints[0].starts_with("pass --resize-floor"),
        "{k}: {hints:?}"
    );
    let grow = ApplyOptions {
        resize_floor: true,
        ..Default::default()
    };
    let r = draw::apply(&mut *b, &nine, &grow, &mut |_| {}).unwrap_or_else(|e| panic!("{k}: {e}"));
    assert_eq!(
        r.floor.as_deref(),
        Some("resized `Floor` from 4 x 4 m to 10 x 10 m (clear puts it back)")
    );
    assert_eq!(floor_size(&s)[..2], [10.0, 10.0], "{k}");
    // a larger maze grows it again; clear puts back the size before the first resize
    let twelve = generated(&dir, "twelve.json", &["--size", "12x12"]);
    draw::apply(&mut *b, &twelve, &grow, &mut |_| {}).unwrap_or_else(|e| panic!("{k}: {e}"));
    assert_eq!(floor_size(&s)[..2], [15.0, 15.0], "{k}");
    let c = draw::clear(&mut *b, &ClearOptions::default()).unwrap();
    assert_eq!(
        c.floor
            .as_ref()
            .map(vrep_maze::cli::wording::worded)
            .as_deref(),
        Some("put `Floor` back to 4 x 4 m, its size before apply --resize-floor")
    );
    let back = floor_size(&s);
    assert!(
        (back[0] - 4.0).abs() < 1e-6 && (back[1] - 4.0).abs() < 1e-6,
        "{k}: {back:?}"
    );
    drop(b);
    s.shutdown();
}

/// `vrep-maze apply` refuses `--resize-floor` over the legacy API before connecting.
#[test]
fn resize_floor_over_legacy_is_refused_at_once() {
    let dir = TempDir::new().unwrap();
    let layout = crate::support::cli::generate(dir.path(), "1", "dfs");
    bin()
        .args([
            "apply",
            &layout,
            "--api",
            "legacy",
            "--port",
            "9",
            "--resize-floor",
        ])
        .assert()
        .code(2)
        .stderr(predicates::str::contains(
            "--resize-floor needs the ZeroMQ remote API",
        ));
}

/// `import` of a layout names the command that draws it as text, quoted for the shell: run
/// by a shell, it works, also for a name with a space.
#[test]
fn the_import_hint_runs_as_a_shell_command() {
    let dir = TempDir::new().unwrap();
    let name = "my maze's.json";
    bin()
        .current_dir(dir.path())
        .args(["generate", "--seed", "1", "--size", "3x3", "-o", name])
        .assert()
        .success();
    let out = bin()
        .current_dir(dir.path())
        .args(["import", name])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    let from = err.find("(vrep-maze render ").expect("a render hint") + 1;
    let to = err[from..].find(" draws it").unwrap() + from;
    let hint = &err[from..to];
    let ran = Command::new("sh")
        .current_dir(dir.path())
        .arg("-c")
        .arg(hint.replacen(
            "vrep-maze",
            &format!("'{}'", env!("CARGO_BIN_EXE_vrep-maze")),
            1,
        ))
        .output()
        .unwrap();
    assert!(
        ran.status.success() && String::from_utf8_lossy(&ran.stdout).contains('+'),
        "{hint}: {}",
        String::from_utf8_lossy(&ran.stderr)
    );
}

/// Issue 30 item 8: `render --trajectory` from an endless stream stops after a bounded read
/// with an error that says why.
#[test]
fn an_endless_trajectory_is_refused_after_a_bounded_read() {
    let dir = TempDir::new().unwrap();
    let layout = crate::support::cli::generate(dir.path(), "1", "dfs");
    let svg = dir.path().join("t.svg");
    let mut child = Command::cargo_bin("vrep-maze")
        .unwrap()
        .args(["render", &layout, "--trajectory", "-", "-o"])
        .arg(&svg)
        .stdin(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stdin = child.stdin.take().unwrap();
    let rows = "0,0,0,0\n".repeat(1 << 16);
    let _ = stdin.write_all(b"t,x,y,yaw\n");
    // until the reader gives up (a broken pipe), never more than twice the bound
    for _ in 0..1100 {
        if stdin.write_all(rows.as_bytes()).is_err() {
            break;
        }
    }
    drop(stdin);
    let out = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && err.contains("more than 256 MiB: not a trajectory"),
        "{err}"
    );
}

/// Issue 30 item 9: a file name with a newline and an escape character is printed escaped on
/// the success path too.
#[test]
fn names_on_success_paths_are_escaped() {
    let dir = TempDir::new().unwrap();
    let layout = crate::support::cli::generate(dir.path(), "1", "dfs");
    let text = bin().args(["render", &layout]).output().unwrap().stdout;
    let drawing = dir.path().join("x\ny\u{1b}[2J.txt");
    std::fs::write(&drawing, text).unwrap();
    let output = dir.path().join("o\nz.json");
    let out = bin()
        .args(["import"])
        .arg(&drawing)
        .arg("-o")
        .arg(&output)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{err}");
    assert!(
        !err.contains('\u{1b}') && err.lines().count() == 1 && err.contains("o\\nz.json"),
        "{err:?}"
    );
}

/// Issue 30 item 2: a user's copy of `Line` under `Maze` (pasted from it, so at its very
/// pose) is no earlier maze: the template's home is its own pose, no "older vrep-maze" is
/// blamed, and `clear` puts it back there, saying so truly.
fn a_users_copy_of_line_does_not_cost_the_template_its_home(kind: Kind) {
    let k = kind.name();
    let dir = TempDir::new().unwrap();
    let mut scene = Scene::course();
    let (line, maze) = (
        scene.resolve("Line").unwrap(),
        scene.resolve("Maze").unwrap(),
    );
    let home = scene.get(line).unwrap().position;
    let copy = scene.copy_paste(&[line]).unwrap()[0];
    scene.set_parent(copy, Some(maze), true).unwrap();
    let s = kind.serve(scene, 0);
    let mut b = s.connect();
    let course = generated(&dir, "course.json", &[]);
    let r = apply(&mut *b, &course).unwrap_or_else(|e| panic!("{k}: {e}"));
    assert!(
        !r.warnings.iter().any(|w| w.contains("no record")),
        "{k}: {:?}",
        r.warnings
    );
    let c = draw::clear(&mut *b, &ClearOptions::default()).unwrap();
    assert_eq!(
        c.template.as_deref(),
        Some("put `Line` back where it stood before the first apply"),
        "{k}"
    );
    let now = s.with_sim(|sim| sim.scene.get(line).unwrap().position);
    assert!(
        (0..3).all(|i| (now[i] - home[i]).abs() < 1e-6),
        "{k}: {now:?}, not {home:?}"
    );
    drop(b);
    s.shutdown();
}
