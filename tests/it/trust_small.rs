//! Issue 38's smaller rows, each as a person meets it: a floor that is a dummy (row 4), a
//! ROS map's YAML for any file name (row 5), an export written whole or not at all (row 6), a
//! raised floor (row 9), a mesh apply's hints for a missing floor (row 10), a legacy
//! connection named by its address (row 13, what a Python session's `repr` says), on `serve`
//! where a simulator is involved. Rows 12 and 13's Python halves are in `python/tests/`.

use tempfile::TempDir;
use vrep_maze::cli::remedies;
use vrep_maze::coppelia::HANDLE_WORLD;
use vrep_maze::draw::extent::Resize;
use vrep_maze::draw::{self, ApplyOptions, ClearOptions, DrawError, ObjectNames};
use vrep_maze::sim::{NewObject, ObjectType, Scene};

use crate::support::backend::Kind;
use crate::support::backend_tests;
use crate::support::bin;
use crate::support::cli::{self, Serve};
use crate::support::layouts::drawing;

backend_tests!(
    a_dummy_floor_is_never_resized_and_clear_says_what_it_reads,
    a_raised_floor_puts_line_back_where_it_stood_and_says_so,
);

/// Row 4: `--floor FD`, `FD` a 0.7231 m dummy, is too small for the course's 10 m layout.
/// `--resize-floor` once "resized" it to 15 x 15 m and verified, though a dummy scales alike
/// along x, y and z (it measured 5.46 m on the real builds, as on `serve`). It is refused
/// now, with or without `--resize-floor`, naming what it is, offering no resize, and left as
/// it is; a record of its size an older version left makes `clear` say what it did (nothing),
/// not that it put the dummy back to a size it does not have.
fn a_dummy_floor_is_never_resized_and_clear_says_what_it_reads(kind: Kind) {
    let k = kind.name();
    let mut scene = Scene::course();
    let fd = scene.add(
        "FD",
        NewObject {
            kind: ObjectType::Dummy,
            parent: None,
            position: [0.0; 3],
            orientation: [0.0; 3],
            size: [0.7231; 3],
            colour: [255, 255, 0],
        },
    );
    let s = kind.serve(scene, 0);
    let size = || s.with_sim(|sim| sim.scene.get(fd).unwrap().size);
    let names = ObjectNames {
        floor: "FD".into(),
        ..Default::default()
    };
    let d = drawing(4, 1);
    let mut b = s.connect();
    for resize_floor in [false, true] {
        let opts = ApplyOptions {
            names: names.clone(),
            resize_floor,
            ..Default::default()
        };
        let e = draw::apply(&mut *b, &d, &opts, &mut |_| {}).unwrap_err();
        assert!(
            matches!(
                e,
                DrawError::Floor {
                    resize: Resize::NotAShape { kind: 4 },
                    ..
                }
            ),
            "{k} {resize_floor}: {e:?}"
        );
        assert_eq!(
            remedies::message(&e),
            "the scene's `FD` is 0.7231 x 0.7231 m but the layout's floor is 10 x 10 m, and `FD` is a dummy, not a shape: apply resizes only a shape",
            "{k}"
        );
        let hints = remedies::hints(&e);
        assert_eq!(
            hints,
            [
                "use a plane or cuboid of at least 10 x 10 m as the floor and pass its name with --floor"
            ],
            "{k}"
        );
        assert_eq!(size(), [0.7231; 3], "{k}: left as it is");
        assert_eq!(s.line_count(), 1, "{k}: nothing drawn, the template alone");
    }
    // a comparison with the layout (`verify`, `inspect --layout`) finds the same and offers
    // the same: no `--resize-floor` for a dummy
    let e = draw::verify(&mut *b, &d, &names).unwrap_err();
    assert!(
        matches!(
            e,
            DrawError::Floor {
                resize: Resize::NotAShape { kind: 4 },
                ..
            }
        ),
        "{k} verify: {e:?}"
    );
    assert!(
        remedies::hints(&e)
            .iter()
            .all(|h| !h.contains("--resize-floor")),
        "{k} verify: {:?}",
        remedies::hints(&e)
    );
    // what an older version's `apply --resize-floor` left: the record, and the dummy scaled
    let f = 10.0 / 0.7231;
    s.with_sim(|sim| {
        sim.scene.scale(fd, [f, f, 1.0]).unwrap();
        for (name, value) in draw::signals::FLOOR_SIZE.iter().zip([fd, 723, 723]) {
            sim.int_signals.insert(name.to_string(), value);
        }
    });
    let grown = size();
    let opts = ClearOptions {
        names,
        ..Default::default()
    };
    let c = draw::clear(&mut *b, &opts).unwrap_or_else(|e| panic!("{k}: {e}"));
    assert_eq!(
        c.floor
            .as_ref()
            .map(vrep_maze::cli::wording::worded)
            .as_deref(),
        Some(
            "left `FD` as it is: it is a dummy, not a shape, so no scale puts it back to 0.723 x 0.723 m, its size before apply --resize-floor; resize it in CoppeliaSim"
        ),
        "{k}"
    );
    assert_eq!(size(), grown, "{k}: left as it is");
    let c = draw::clear(&mut *b, &opts).unwrap_or_else(|e| panic!("{k}: {e}"));
    assert_eq!(c.floor, None, "{k}: the record is gone");
    drop(b);
    s.shutdown();
}

/// Row 9: `Floor` raised to z 0.5 leaves the course's `Line` below it. Applied and cleared,
/// `Line` goes back exactly where it stood, and `clear` says that, not that it put it "below
/// the floor" where an earlier maze had left it.
fn a_raised_floor_puts_line_back_where_it_stood_and_says_so(kind: Kind) {
    let k = kind.name();
    let s = kind.serve(Scene::course(), 0);
    let (line, before) = s.with_sim(|sim| {
        let floor = sim.scene.resolve("Floor").unwrap();
        sim.scene
            .set_position(floor, HANDLE_WORLD, [0.0, 0.0, 0.5])
            .unwrap();
        let line = sim.scene.resolve("Line").unwrap();
        (line, sim.scene.pose(line, HANDLE_WORLD).unwrap())
    });
    let mut b = s.connect();
    draw::apply(
        &mut *b,
        &drawing(4, 1),
        &ApplyOptions::default(),
        &mut |_| {},
    )
    .unwrap_or_else(|e| panic!("{k}: {e}"));
    let c = draw::clear(&mut *b, &ClearOptions::default()).unwrap_or_else(|e| panic!("{k}: {e}"));
    assert_eq!(
        c.template.as_deref(),
        Some("put `Line` back where it stood before the first apply"),
        "{k}"
    );
    let after = s.with_sim(|sim| sim.scene.pose(line, HANDLE_WORLD).unwrap());
    for (a, b) in before
        .0
        .iter()
        .chain(&before.1)
        .zip(after.0.iter().chain(&after.1))
    {
        assert!((a - b).abs() < 1e-6, "{k}: {before:?} then {after:?}");
    }
    drop(b);
    s.shutdown();
}

/// Row 10: `apply --draw mesh` on a scene without `Floor` offers `--create-missing`, as a
/// copies apply does, and no `--resize-floor` for a floor that does not exist; the hint
/// followed, the maze is drawn.
#[test]
fn a_mesh_apply_without_a_floor_offers_create_missing_not_a_resize() {
    let dir = TempDir::new().unwrap();
    let mut scene = Scene::course();
    let floor = scene.resolve("Floor").unwrap();
    scene.remove(floor).unwrap();
    let file = dir.path().join("no-floor.json");
    std::fs::write(&file, scene.to_json().to_string()).unwrap();
    let file = file.display().to_string();
    let s = Serve::start(
        &["--api", "zmq", "--listen", "127.0.0.1:0", "--scene", &file],
        1,
    );
    let port = s.port();
    let layout = cli::generate(dir.path(), "3", "dfs");
    let apply = |draw: &str, more: &[&str]| {
        bin()
            .args([
                "apply", &layout, "--api", "zmq", "--port", &port, "--draw", draw,
            ])
            .args(more)
            .output()
            .unwrap()
    };
    for draw in ["copies", "mesh"] {
        let out = apply(draw, &[]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{draw}: {err}");
        assert!(err.contains("missing in the scene: Floor"), "{draw}: {err}");
        assert!(
            err.contains("hint: or pass --create-missing"),
            "{draw}: {err}"
        );
        assert!(!err.contains("resize-floor"), "{draw}: {err}");
    }
    let out = apply("mesh", &["--create-missing"]);
    let said = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(
        said.contains("created Floor") && said.contains("verified"),
        "{said}"
    );
}

/// The golden 9x9 dfs layout's path.
fn golden() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("mazes/dfs-9x9-seed42.json")
}

/// File names that YAML reads as something else when written bare: a comment, a mapping, a
/// flow sequence or mapping, an alias, an anchor, a tag, a directive, reserved indicators,
/// quotes, block scalars, a line break, a leading space, a backslash and a control sequence.
const HOSTILE_NAMES: &[&str] = &[
    "a #b",
    "c: d",
    "[e",
    "{f",
    "*g",
    "&h",
    "!i",
    "'j\"",
    "%k",
    "@l",
    "|m",
    ">n",
    "o\np",
    " q",
    "r\\s",
    "t\u{1b}[31m",
    "u\tv",
    "w\u{2028}x",
    "-",
    "~",
    "null",
    "y,z",
];

/// Row 5: `export -o NAME.yaml` names its image so that a YAML parser that is not ours
/// (yaml-rust2; PyYAML in `tests/conformance/ros_map.py`) reads back the PGM's own name, for
/// any name, and the keys after it are still read.
#[test]
fn a_ros_maps_yaml_names_its_image_for_any_file_name() {
    let dir = TempDir::new().unwrap();
    for name in HOSTILE_NAMES {
        let yaml = dir.path().join(format!("{name}.yaml"));
        bin()
            .arg("export")
            .arg(golden())
            .arg("-o")
            .arg(&yaml)
            .assert()
            .success();
        let text = std::fs::read_to_string(&yaml).unwrap();
        let docs = yaml_rust2::YamlLoader::load_from_str(&text)
            .unwrap_or_else(|e| panic!("{name:?}: {e}\n{text}"));
        let map = &docs[0];
        let image = map["image"].as_str();
        assert_eq!(image, Some(format!("{name}.pgm").as_str()), "{text}");
        assert!(dir.path().join(image.unwrap()).is_file(), "{name:?}");
        assert_eq!(map["resolution"].as_f64(), Some(0.05), "{name:?}: {text}");
        assert_eq!(map["mode"].as_str(), Some("trinary"), "{name:?}: {text}");
    }
}

/// Row 6: an export is all or nothing. `-o s.yaml`, `s.yaml` a dangling link, fails and
/// leaves no `s.pgm` (nor a temporary); an `s.pgm` already there stays as it was; the error
/// names the file that could not be written.
#[cfg(unix)]
#[test]
fn a_ros_map_export_that_fails_leaves_no_file_behind() {
    let dir = TempDir::new().unwrap();
    let yaml = dir.path().join("s.yaml");
    std::os::unix::fs::symlink(dir.path().join("gone/s.yaml"), &yaml).unwrap();
    let names = || {
        let mut names: Vec<String> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    };
    let out = bin()
        .arg("export")
        .arg(golden())
        .arg("-o")
        .arg(&yaml)
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("s.yaml: cannot write, so neither file was written"),
        "{err}"
    );
    assert_eq!(names(), ["s.yaml"], "{err}");
    std::fs::write(dir.path().join("s.pgm"), b"the user's").unwrap();
    bin()
        .arg("export")
        .arg(golden())
        .arg("-o")
        .arg(&yaml)
        .assert()
        .code(1);
    assert_eq!(names(), ["s.pgm", "s.yaml"]);
    assert_eq!(
        std::fs::read(dir.path().join("s.pgm")).unwrap(),
        b"the user's"
    );
}

/// Row 13: a legacy connection made as the command line and Python make it names where it
/// is connected, as a ZeroMQ one does (a Python session's `repr` and `description` say it):
/// not "a connected client".
#[test]
fn a_legacy_connection_names_its_host_and_port() {
    let s = Kind::Legacy.serve(Scene::course(), 0);
    let port = s.addr().port();
    // the connection keywords of Python's `connect`, read as the command line reads them
    let cli = <vrep_maze::cli::Cli as clap::Parser>::try_parse_from([
        "vrep-maze",
        "clear",
        "--api",
        "legacy",
        "--port",
        &port.to_string(),
    ])
    .unwrap();
    let vrep_maze::cli::Command::Clear(args) = cli.command else {
        panic!("clear parsed as another command");
    };
    let backend = args.scene.connect().unwrap();
    let named = format!("legacy remote API at 127.0.0.1:{port}");
    assert_eq!(backend.describe(), named);
    let mut session = draw::Session::new(backend);
    assert_eq!(session.describe().as_deref(), Some(named.as_str()));
    session.close().unwrap();
    s.shutdown();
}
