//! The command line under generated abuse: every subcommand driven with a few hundred
//! argument lists drawn from extreme values (NaN, 1e308, negatives, huge strings, special
//! files) and mutated layout files. Whatever the input: no panic (exit 101), a short error
//! (a few KB at most), one of the documented exit codes, and no invalid layout accepted
//! (a zero exit from `validate`, `render`, `apply` or `generate` means the layout is valid).
//! The scene holds objects that are not the maze's (a dummy, a cuboid, a plane and a dummy
//! named like a copy under `Maze`): every `apply` and `clear` leaves them where they were,
//! and a successful one names them.
//! The draws are seeded, so a failure repeats.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use tempfile::TempDir;
use vrep_maze::layout::read_layout;
use vrep_maze::rng::MazeRng;
use vrep_maze::validate::validate;

use crate::support::bin;
use crate::support::cli::Serve;

/// Runs per subcommand family; the whole test stays within a few seconds per hundred.
const RUNS: usize = 240;
/// The most stderr a refusal may print.
const MAX_STDERR: usize = 4096;
/// Stop drawing new cases after this long (a slow machine runs fewer, never longer).
const TIME_BUDGET: Duration = Duration::from_secs(60);

fn pick<'a>(rng: &mut MazeRng, items: &[&'a str]) -> &'a str {
    items[rng.index(items.len())]
}

/// Values that broke earlier versions, and ordinary ones.
const NUMBERS: &[&str] = &[
    "0",
    "1",
    "-1",
    "-0.5",
    "0.5",
    "3",
    "1e308",
    "-1e308",
    "1e-300",
    "1e-9",
    "nan",
    "inf",
    "-inf",
    "18446744073709551616",
    "0.001",
    "10000",
    "360",
    "-720",
    "",
];
const SIZES: &[&str] = &[
    "9x9", "1x1", "0x5", "4097x1", "3x-2", "x", "2x3", "1x12", "nanxnan",
];
const ENDPOINTS: &[&str] = &[
    "sw",
    "ne",
    "farthest",
    "farthest-pair",
    "4,4",
    "9,9",
    "-1,0",
    "a,b",
];
const ALGOS: &[&str] = &[
    "dfs",
    "prim",
    "kruskal",
    "wilson",
    "binary-tree",
    "nope",
    "",
];

/// A layout file with one random change: a number made extreme, a key removed, a type
/// swapped, or the text cut short.
fn mutated_layout(rng: &mut MazeRng, golden: &serde_json::Value, dir: &Path, n: usize) -> PathBuf {
    let mut v = golden.clone();
    let fields: &[&[&str]] = &[
        &["grid", "cell_size"],
        &["grid", "columns"],
        &["grid", "rotation"],
        &["grid", "origin"],
        &["floor", "size"],
        &["line", "z"],
        &["line", "length"],
        &["line", "width"],
        &["start", "cell"],
        &["end", "pose"],
        &["metrics", "loops"],
        &["passages"],
        &["segments"],
        &["version"],
        &["generator", "seed"],
    ];
    let path = fields[rng.index(fields.len())];
    let replacement = match rng.below(7) {
        0 => serde_json::json!(1e308),
        1 => serde_json::json!(-1),
        2 => serde_json::Value::Null,
        3 => serde_json::json!("zzz"),
        4 => serde_json::json!([]),
        5 => serde_json::json!(0),
        _ => serde_json::json!({"x": 1e300, "y": -5, "z": 0, "yaw": 1e308}),
    };
    let mut target = &mut v;
    for key in &path[..path.len() - 1] {
        target = &mut target[*key];
    }
    let last = path[path.len() - 1];
    if rng.chance(1, 5) {
        if let Some(map) = target.as_object_mut() {
            map.remove(last);
        }
    } else {
        target[last] = replacement;
    }
    if let Some(segments) = v["segments"].as_array_mut()
        && !segments.is_empty()
        && rng.chance(1, 4)
    {
        let i = rng.index(segments.len());
        segments[i]["x"] = serde_json::json!(0.123);
    }
    let mut text = v.to_string();
    if rng.chance(1, 10) {
        text.truncate(rng.index(text.len()));
    }
    let file = dir.join(format!("mutant-{n}.json"));
    std::fs::write(&file, text).unwrap();
    file
}

/// One argument list for `command`, given files to draw from, and the layout file it reads
/// (if any).
fn arguments(
    rng: &mut MazeRng,
    command: &str,
    files: &[String],
    port: &str,
) -> (Vec<String>, Option<String>) {
    let long = "L".repeat(20_000);
    let mut args = vec![command.to_string()];
    let file = |rng: &mut MazeRng| files[rng.index(files.len())].clone();
    let options: &[(&str, &[&str])] = match command {
        "generate" | "batch" => &[
            ("--seed", NUMBERS),
            ("--algo", ALGOS),
            ("--size", SIZES),
            ("--start", ENDPOINTS),
            ("--end", ENDPOINTS),
            ("--braid", NUMBERS),
            ("--cell-size", NUMBERS),
            ("--line-length", NUMBERS),
            ("--line-width", NUMBERS),
            ("--line-z", NUMBERS),
            ("--marker-z", NUMBERS),
            ("--rotation", NUMBERS),
            ("--origin", &["0,0", "1e308,0", "nan,1", "5,5", "x"]),
            ("--floor-size", &["10x10", "1e308x1", "0x0", "25x25"]),
            ("--growing", &["newest", "mix:0.5", "mix:2", "bogus"]),
            ("--bias", &["ne", "sw", "up"]),
        ],
        "render" => &[
            ("--format", &["ascii", "svg", "png", "jpg"]),
            ("--solution", &[]),
        ],
        "apply" | "clear" => &[
            ("--timeout", &["0.3", "0", "-1", "1e308", "nan"]),
            ("--api", &["legacy", "zmq", "auto", "bogus"]),
            ("--line", &["Line", "Nope", "", "Maze", "MySensor", "Line9"]),
            ("--parent", &["Maze", "Floor", "Box"]),
            ("--wall", &["Wall", "Line", "Box"]),
            ("--start", &["Start", "End", "BigPlane"]),
            ("--dry-run", &[]),
            ("--stop-simulation", &[]),
        ],
        _ => &[],
    };
    // a third of the runs take no option, so success paths are reached too
    let count = if options.is_empty() || rng.chance(1, 3) {
        0
    } else {
        1 + rng.below(4)
    };
    for _ in 0..count {
        let (name, values) = options[rng.index(options.len())];
        args.push(name.to_string());
        if !values.is_empty() {
            args.push(if rng.chance(1, 30) {
                long.clone()
            } else {
                pick(rng, values).to_string()
            });
        }
    }
    let mut layout = None;
    match command {
        "validate" | "render" | "apply" => {
            let f = file(rng);
            layout = Some(f.clone());
            args.push(f);
        }
        "completions" => args.push(pick(rng, &["bash", "zsh", "fish", "nosh"]).into()),
        "batch" => {
            args.extend([
                "--seeds".into(),
                pick(rng, &["0..3", "5", "3..3", "x"]).into(),
            ]);
            args.extend(["--out-dir".into(), format!("{}-dataset", files[0])]);
        }
        _ => {}
    }
    if matches!(command, "apply" | "clear") {
        args.extend([
            "--port".into(),
            port.into(),
            "--timeout".into(),
            "0.5".into(),
        ]);
    }
    if command == "generate" && rng.chance(1, 2) {
        args.extend(["-o".into(), format!("{}-out.json", files[0])]);
    }
    if command == "render" && rng.chance(1, 2) {
        let ext = pick(rng, &["svg", "png", "txt", "jpg", ""]);
        args.extend(["-o".into(), format!("{}-picture.{ext}", files[0])]);
    }
    (args, layout)
}

/// Handle, name, parent and world pose of each of the `names` in the scene served at `port`.
fn users_objects(port: &str, names: &[&str]) -> Vec<vrep_maze::draw::ObjectInfo> {
    let mut b = vrep_maze::legacy::LegacyBackend::connect(
        "127.0.0.1",
        port.parse().unwrap(),
        Duration::from_secs(5),
    )
    .unwrap();
    let objects = vrep_maze::draw::Backend::objects(&mut b).unwrap();
    names
        .iter()
        .map(|n| {
            let o = objects
                .iter()
                .find(|o| o.name == *n)
                .unwrap_or_else(|| panic!("{n} is still in the scene"));
            o.clone()
        })
        .collect()
}

/// `true` if `path` reads as a layout that `validate` accepts.
fn valid(path: &str) -> bool {
    read_layout(Path::new(path)).is_ok_and(|l| validate(&l).is_ok())
}

#[test]
fn no_input_makes_the_command_line_panic_flood_or_accept_an_invalid_layout() {
    let dir = TempDir::new().unwrap();
    let golden_path = concat!(env!("CARGO_MANIFEST_DIR"), "/mazes/kruskal-9x9-seed42.json");
    let golden: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(golden_path).unwrap()).unwrap();
    let mut rng = MazeRng::from_seed(0xF022);
    let base = dir.path().join("base").display().to_string();
    // the golden layout often, so drawing and rendering succeed too
    let mut files = vec![base.clone()];
    files.extend(std::iter::repeat_n(golden_path.to_string(), 12));
    files.extend(["/dev/null", "/nonexistent.json", "-"].map(String::from));
    files.push(dir.path().display().to_string());
    for n in 0..60 {
        files.push(
            mutated_layout(&mut rng, &golden, dir.path(), n)
                .display()
                .to_string(),
        );
    }
    let (scene, users) = crate::trust_draw::scene_with_the_users_objects();
    let scene_file = dir.path().join("scene.json");
    std::fs::write(&scene_file, scene.to_json().to_string()).unwrap();
    let scene_arg = scene_file.display().to_string();
    let serve = Serve::start(
        &[
            "--listen",
            "127.0.0.1:0",
            "--idle-fps",
            "0",
            "--scene",
            &scene_arg,
        ],
        1,
    );
    let port = serve.port();
    let users_before = users_objects(&port, &users);
    let commands = [
        "generate",
        "validate",
        "render",
        "batch",
        "apply",
        "clear",
        "completions",
    ];
    let started = Instant::now();
    let mut runs = 0;
    let mut accepted_layouts = 0;
    let mut codes = [0usize; 3];
    while runs < RUNS && started.elapsed() < TIME_BUDGET {
        let command = commands[runs % commands.len()];
        let (args, layout) = arguments(&mut rng, command, &files, &port);
        runs += 1;
        let out = bin().args(&args).write_stdin("").output().unwrap();
        let shown: Vec<String> = args
            .iter()
            .map(|a| {
                if a.len() > 40 {
                    format!("<{} chars>", a.len())
                } else {
                    a.clone()
                }
            })
            .collect();
        let stderr = String::from_utf8_lossy(&out.stderr);
        let code = out.status.code();
        assert!(
            matches!(code, Some(0..=2)),
            "{shown:?}: exit {code:?}\n{stderr}"
        );
        assert!(!stderr.contains("panicked"), "{shown:?}: {stderr}");
        assert!(
            stderr.len() <= MAX_STDERR,
            "{shown:?}: {} bytes on stderr",
            stderr.len()
        );
        codes[code.unwrap_or(1) as usize] += 1;
        if code != Some(0) {
            continue;
        }
        if matches!(command, "apply" | "clear") && !args.iter().any(|a| a == "--parent") {
            let stdout = String::from_utf8_lossy(&out.stdout);
            assert!(
                stdout.contains("left alone")
                    && users
                        .iter()
                        .filter(|u| !args.iter().any(|a| a == *u))
                        .all(|u| stdout.contains(u)),
                "{shown:?}: the user's objects are named\n{stdout}"
            );
        }
        match command {
            "validate" | "render" | "apply" => {
                if let Some(path) = layout.filter(|p| p != "-") {
                    accepted_layouts += 1;
                    assert!(valid(&path), "{shown:?} accepted an invalid layout");
                }
            }
            "batch" => {
                let out_dir = format!("{}-dataset", files[0]);
                for entry in std::fs::read_dir(&out_dir).into_iter().flatten() {
                    let path = entry.unwrap().path();
                    if path.extension().is_some_and(|e| e == "json") {
                        accepted_layouts += 1;
                        let path = path.display().to_string();
                        assert!(valid(&path), "{shown:?} wrote an invalid layout {path}");
                    }
                }
            }
            "generate" => {
                let written = args.iter().position(|a| a == "-o").map(|i| &args[i + 1]);
                if let Some(path) = written {
                    accepted_layouts += 1;
                    assert!(valid(path), "{shown:?} wrote an invalid layout");
                } else {
                    accepted_layouts += 1;
                    let text = String::from_utf8_lossy(&out.stdout);
                    let layout = vrep_maze::layout::json::parse_layout(&text, "stdout").unwrap();
                    assert!(
                        validate(&layout).is_ok(),
                        "{shown:?} printed an invalid layout"
                    );
                }
            }
            _ => {}
        }
    }
    eprintln!(
        "cli fuzz: {runs} runs: {} exit 0, {} exit 1, {} exit 2; {accepted_layouts} accepted layouts checked",
        codes[0], codes[1], codes[2]
    );
    assert_eq!(
        users_objects(&port, &users),
        users_before,
        "the user's objects under Maze never moved, changed parent or went"
    );
    assert!(runs >= 100, "only {runs} runs in the time budget");
    assert!(
        accepted_layouts > 0,
        "the draws never reached a success path"
    );
}

/// Where standard output goes in [`outputs_that_cannot_be_written_and_inputs_that_never_end`].
#[derive(Debug, Clone, Copy)]
enum Sink {
    /// `> /dev/full`: every write fails (ENOSPC).
    Full,
    /// `>&-`: closed.
    Closed,
    /// A pipe whose reader has gone (`| head -c0`): the run ends quietly, exit 0.
    GonePipe,
}

/// Runs `vrep-maze args` with standard output at `sink` and no input; exit code and stderr.
fn run_into(args: &[String], sink: Sink) -> (Option<i32>, String) {
    use std::process::{Command, Stdio};
    let bin = assert_cmd::cargo::cargo_bin("vrep-maze");
    let mut command = Command::new(&bin);
    command
        .envs(crate::support::cli::away_from_defaults())
        .args(args)
        .stdin(Stdio::null())
        .stderr(Stdio::piped());
    match sink {
        Sink::Full => {
            command.stdout(std::fs::File::create("/dev/full").unwrap());
        }
        // the shell's `>&-`: the child starts with descriptor 1 closed
        Sink::Closed => {
            let mut shell = Command::new("sh");
            shell
                .arg("-c")
                .arg("exec \"$0\" \"$@\" >&-")
                .arg(&bin)
                .args(args)
                .stdin(Stdio::null())
                .stderr(Stdio::piped());
            command = shell;
        }
        Sink::GonePipe => {
            command.stdout(Stdio::piped());
        }
    }
    let mut child = command.spawn().unwrap();
    // a reader that leaves at once: the pipe's read end is closed before anything is read
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Runs `vrep-maze args` reading from `/dev/zero`-like endless `input` on standard input
/// (written until the command stops reading); exit code and stderr.
fn run_endless(args: &[&str], input: &'static [u8], head: &'static [u8]) -> (Option<i32>, String) {
    use std::io::Write;
    use std::process::{Command, Stdio};
    let mut child = Command::new(assert_cmd::cargo::cargo_bin("vrep-maze"))
        .envs(crate::support::cli::away_from_defaults())
        .args(args)
        .stdin(Stdio::piped())
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut stdin = child.stdin.take().unwrap();
    let writer = std::thread::spawn(move || {
        let _ = stdin.write_all(head);
        let block = input.repeat((1 << 16) / input.len().max(1) + 1);
        // endless for the reader: at most 4 GiB, far beyond every bound it has
        for _ in 0..(4usize << 30) / block.len() {
            if stdin.write_all(&block).is_err() {
                return;
            }
        }
    });
    let out = child.wait_with_output().unwrap();
    writer.join().unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn outputs_that_cannot_be_written_and_inputs_that_never_end() {
    let dir = TempDir::new().unwrap();
    let golden = concat!(env!("CARGO_MANIFEST_DIR"), "/mazes/kruskal-9x9-seed42.json");
    let drawing = concat!(env!("CARGO_MANIFEST_DIR"), "/mazes/drawn-4x4.txt");
    // every command that writes to standard output, and writers of files
    let to_stdout: Vec<Vec<String>> = [
        vec!["validate", golden],
        vec!["render", golden],
        vec!["render", golden, "--format", "svg"],
        vec!["generate", "--seed", "1"],
        vec!["generate", "--style", "walls", "--seed", "2"],
        vec!["import", drawing],
        vec!["completions", "bash"],
        vec!["completions", "fish"],
        vec!["demo"],
        vec!["--help"],
        vec!["--version"],
        vec!["generate", "--help"],
        vec!["apply", "--help"],
    ]
    .into_iter()
    .map(|a| a.into_iter().map(String::from).collect())
    .collect();
    let mut rng = MazeRng::from_seed(0xF011);
    let mut cases = 0;
    for args in &to_stdout {
        for sink in [Sink::Full, Sink::Closed, Sink::GonePipe] {
            let (code, stderr) = run_into(args, sink);
            cases += 1;
            assert!(!stderr.contains("panicked"), "{args:?} {sink:?}: {stderr}");
            match sink {
                Sink::GonePipe => assert_eq!(code, Some(0), "{args:?} {sink:?}: {stderr}"),
                Sink::Full | Sink::Closed => {
                    assert_eq!(code, Some(1), "{args:?} {sink:?}: {stderr}");
                    let errors: Vec<&str> =
                        stderr.lines().filter(|l| l.starts_with("error:")).collect();
                    assert_eq!(errors.len(), 1, "{args:?} {sink:?}: {stderr}");
                    assert!(
                        errors[0].contains("cannot write to standard output"),
                        "{args:?} {sink:?}: {stderr}"
                    );
                }
            }
        }
    }
    // files that cannot be written: a full device, a place that takes no file, a missing
    // folder, a folder; a random writer each time
    let places = ["/dev/full", "/proc/vrep-maze.svg", "/nonexistent/m.svg"];
    for place in places.iter().chain([&dir.path().to_str().unwrap()]) {
        for _ in 0..3 {
            let writers: [Vec<&str>; 4] = [
                vec!["generate", "--seed", "3", "-o", place],
                vec!["render", golden, "-o", place, "--format", "svg"],
                vec!["import", drawing, "-o", place],
                vec!["batch", "--seeds", "1..3", "--out-dir", place],
            ];
            // a folder is where batch writes: the others only
            let usable = if place.starts_with('/') && Path::new(place).is_dir() {
                3
            } else {
                4
            };
            let args = &writers[rng.index(usable)];
            let output = bin().args(args).output().unwrap();
            let stderr = String::from_utf8_lossy(&output.stderr);
            cases += 1;
            assert_eq!(output.status.code(), Some(1), "{args:?}: {stderr}");
            assert_eq!(
                stderr.lines().filter(|l| l.starts_with("error:")).count(),
                1,
                "{args:?}: {stderr}"
            );
            assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
        }
    }
    // inputs that never end: files and standard input, for every reader
    for reader in [
        vec!["validate"],
        vec!["render"],
        vec!["import"],
        vec!["apply", "--port", "9", "--connect-timeout", "0.5"],
    ] {
        let (code, stderr) = {
            let output = bin().args(&reader).arg("/dev/zero").output().unwrap();
            (
                output.status.code(),
                String::from_utf8_lossy(&output.stderr).into_owned(),
            )
        };
        cases += 1;
        assert_eq!(code, Some(1), "{reader:?} /dev/zero: {stderr}");
        assert!(
            stderr.contains("NUL") || stderr.contains("0x00"),
            "{reader:?} /dev/zero: {stderr}"
        );
        if reader[0] == "import" {
            continue;
        }
        let mut with_stdin = reader.clone();
        with_stdin.push("-");
        let layout_head: &'static [u8] = Box::leak(
            std::fs::read_to_string(golden)
                .unwrap()
                .split("\"segments\": [")
                .next()
                .map(|head| format!("{head}\"segments\": [\n"))
                .unwrap()
                .into_bytes()
                .into_boxed_slice(),
        );
        for (head, endless, says) in [
            (&b""[..], &b"\0"[..], "control character 0x00"),
            (&b""[..], &b" "[..], "KiB of white space"),
            (
                layout_head,
                &b"{\"x\": 0.25, \"y\": 0, \"z\": 0.001, \"yaw\": 0},\n"[..],
                "segments: no layout of this grid holds more",
            ),
            (layout_head, &b"\0"[..], "KiB"),
        ] {
            let (code, stderr) = run_endless(&with_stdin, endless, head);
            cases += 1;
            assert_eq!(
                code,
                Some(1),
                "{with_stdin:?} endless {endless:?}: {stderr}"
            );
            assert!(
                stderr.contains(says),
                "{with_stdin:?} endless {endless:?}: {stderr}"
            );
            assert!(!stderr.contains("panicked"), "{stderr}");
        }
    }
    // an endless string reads 64 MiB before it is refused: once is enough
    let (code, stderr) = run_endless(&["validate", "-"], b"a", b"{\"a\": \"");
    cases += 1;
    assert_eq!(code, Some(1), "{stderr}");
    assert!(stderr.contains("more than 64 MiB"), "{stderr}");
    eprintln!("cli fuzz, unwritable outputs and endless inputs: {cases} cases");
}
