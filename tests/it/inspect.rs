//! `vrep-maze inspect`: what the scene holds, over every API, and never a write.

use serde_json::{Value, json};
use vrep_maze::sim::{NewObject, ObjectType, Scene};

use crate::support::backend::{Kind, Server};
use crate::support::bin;
use crate::support::cli::generate;

/// Everything the emulator holds that a client could change: the scene (objects, names,
/// parents, poses), the idle rate, the simulation state and the signals.
fn state(server: &Server) -> String {
    server.with_sim(|sim| {
        format!(
            "{} {} {:?} {:?}",
            sim.scene.to_json(),
            sim.idle_fps,
            sim.state,
            sim.int_signals
        )
    })
}

fn api_args(kind: Kind, server: &Server) -> Vec<String> {
    let api = if kind == Kind::Legacy {
        "legacy"
    } else {
        "zmq"
    };
    vec![
        "--api".into(),
        api.into(),
        "--port".into(),
        server.addr().port().to_string(),
    ]
}

/// `inspect --json` plus `extra`, expecting exit `code`.
fn inspect(kind: Kind, server: &Server, extra: &[&str], code: i32) -> Value {
    let out = bin()
        .arg("inspect")
        .args(api_args(kind, server))
        .arg("--json")
        .args(extra)
        .assert()
        .code(code)
        .get_output()
        .stdout
        .clone();
    serde_json::from_str(&String::from_utf8(out).unwrap()).unwrap()
}

/// `inspect`'s text, expecting success.
fn inspect_text(kind: Kind, server: &Server) -> String {
    let out = bin()
        .arg("inspect")
        .args(api_args(kind, server))
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    String::from_utf8(out).unwrap()
}

/// The object of `role` in an `inspect --json` report.
fn object<'r>(report: &'r Value, role: &str) -> &'r Value {
    report["objects"]
        .as_array()
        .unwrap()
        .iter()
        .find(|o| o["role"] == role)
        .unwrap()
}

/// The validator of `schema/inspect-v1.schema.json`.
fn schema() -> jsonschema::Validator {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let schema: Value = serde_json::from_str(
        &std::fs::read_to_string(root.join("schema/inspect-v1.schema.json")).unwrap(),
    )
    .unwrap();
    jsonschema::validator_for(&schema).unwrap()
}

#[test]
fn inspect_reports_the_scene_and_changes_nothing_on_every_api() {
    let dir = tempfile::tempdir().unwrap();
    let drawn = generate(dir.path(), "42", "prim");
    let other = generate(dir.path(), "7", "dfs");
    for kind in Kind::ALL {
        let server = kind.serve(Scene::course(), 0);
        bin()
            .args(["-q", "apply", &drawn])
            .args(api_args(kind, &server))
            .assert()
            .success();
        // an object of the user's under the maze dummy
        server.with_sim(|sim| {
            let maze = sim
                .scene
                .objects()
                .find(|o| o.alias == "Maze")
                .unwrap()
                .handle;
            sim.scene.add(
                "Camera",
                NewObject {
                    kind: ObjectType::Dummy,
                    parent: Some(maze),
                    position: [0.0; 3],
                    orientation: [0.0; 3],
                    size: [0.01; 3],
                    colour: [0; 3],
                },
            );
            // named and typed like a copy of `Line`, but a 1 m plane
            sim.scene.add(
                "Line9",
                NewObject {
                    kind: ObjectType::Shape,
                    parent: Some(maze),
                    position: [4.0, -4.0, 0.001],
                    orientation: [0.0; 3],
                    size: [1.0, 1.0, 0.0],
                    colour: [0, 255, 0],
                },
            );
        });
        let before = state(&server);
        let report = inspect(kind, &server, &["--layout", &drawn], 0);
        let name = kind.name();
        assert_eq!(state(&server), before, "{name}: inspect changed the scene");
        assert_eq!(report["simulation_running"], false, "{name}");
        assert_eq!(report["idle_fps"], 0, "{name}");
        assert_eq!(
            object(&report, "line template")["position"],
            json!([-3.75, -4.0, 0.001]),
            "{name}"
        );
        assert_eq!(object(&report, "wall template")["present"], false);
        // the user's objects under the dummy are left alone: the maze still matches the layout
        let layout = &report["layout"];
        assert_eq!(layout["matches"], true, "{name}: {layout}");
        let maze = &report["maze"];
        // every API tells the maze's copies from the user's object
        assert_eq!(maze["lines"], 159, "{name}: {maze}");
        assert_eq!(maze["not_ours"], json!(["Camera", "Line9"]), "{name}");
        // without the user's objects the drawing matches; another layout does not
        server.with_sim(|sim| {
            for alias in ["Camera", "Line9"] {
                let h = sim
                    .scene
                    .objects()
                    .find(|o| o.alias == alias)
                    .unwrap()
                    .handle;
                sim.scene.remove(h).unwrap();
            }
        });
        let before = state(&server);
        let matching = inspect(kind, &server, &["--layout", &drawn], 0);
        assert_eq!(matching["layout"]["matches"], true, "{name}: {matching}");
        let differing = inspect(kind, &server, &["--layout", &other], 1);
        assert!(differing["layout"]["differences"].as_array().unwrap().len() > 1);
        assert_eq!(state(&server), before, "{name}: inspect changed the scene");
        server.shutdown();
    }
}

/// A maze drawn as meshes is the maze, not an object of the user's: inspect names its
/// meshes and compares it with a layout as `apply --draw mesh` verifies it; `clear` then
/// says it removed a mesh maze, not "copies".
#[test]
fn inspect_and_clear_know_a_mesh_maze_on_every_api() {
    let dir = tempfile::tempdir().unwrap();
    let drawn = generate(dir.path(), "42", "prim");
    let other = generate(dir.path(), "7", "dfs");
    for kind in Kind::ALL {
        let name = kind.name();
        let server = kind.serve(Scene::course(), 0);
        bin()
            .args(["-q", "apply", &drawn, "--draw", "mesh"])
            .args(api_args(kind, &server))
            .assert()
            .success();
        let before = state(&server);
        let report = inspect(kind, &server, &["--layout", &drawn], 0);
        assert_eq!(state(&server), before, "{name}: inspect changed the scene");
        let maze = &report["maze"];
        assert_eq!(maze["not_ours"], json!([]), "{name}: {maze}");
        assert_eq!(maze["style"], "lines", "{name}: {maze}");
        let meshes = maze["meshes"].as_array().unwrap();
        assert!(
            !meshes.is_empty()
                && meshes
                    .iter()
                    .all(|m| m.as_str().unwrap().starts_with("MazeMesh_l_")),
            "{name}: {maze}"
        );
        assert_eq!(report["layout"]["matches"], true, "{name}: {report}");
        let differing = inspect(kind, &server, &["--layout", &other], 1);
        assert!(
            differing["layout"]["differences"]
                .as_array()
                .unwrap()
                .iter()
                .any(|d| d.as_str().unwrap().contains("mesh")),
            "{name}: {differing}"
        );
        let out = bin()
            .arg("clear")
            .args(api_args(kind, &server))
            .arg("--json")
            .assert()
            .success()
            .get_output()
            .stdout
            .clone();
        let cleared: Value = serde_json::from_slice(&out).unwrap();
        assert_eq!(cleared["removed"], json!([]), "{name}: {cleared}");
        let mut removed_meshes: Vec<&str> = cleared["removed_meshes"]
            .as_array()
            .unwrap()
            .iter()
            .map(|m| m.as_str().unwrap())
            .collect();
        assert_eq!(
            removed_meshes.pop(),
            Some("MazeMeshes"),
            "{name}: {cleared}"
        );
        let drawn_meshes: Vec<&str> = meshes.iter().map(|m| m.as_str().unwrap()).collect();
        assert_eq!(removed_meshes, drawn_meshes, "{name}");
        server.shutdown();
    }
}

#[test]
fn the_inspect_document_satisfies_its_schema_and_the_text_names_what_is_there() {
    let server = Kind::Legacy.serve(Scene::course_walls(), 0);
    let report = inspect(Kind::Legacy, &server, &[], 0);
    let errors: Vec<String> = schema()
        .iter_errors(&report)
        .map(|e| e.to_string())
        .collect();
    assert!(errors.is_empty(), "{errors:?}");
    let text = inspect_text(Kind::Legacy, &server);
    assert!(text.contains("wall template  Wall"), "{text}");
    assert!(
        text.contains("simulation stopped; idle rate 0 fps"),
        "{text}"
    );
    assert!(text.contains("drawn: 0 lines, 0 walls, 0 posts"), "{text}");
    server.shutdown();
}

/// The templates' and markers' sizes over every API; their colours over ZeroMQ
/// (`sim.getShapeColor`), and over the legacy API, which cannot read colours, none, said in
/// the text rather than guessed. Still never a write.
#[test]
fn inspect_shows_sizes_and_colours_where_the_api_reads_them() {
    let validator = schema();
    for kind in Kind::ALL {
        let name = kind.name();
        let server = kind.serve(Scene::course_walls(), 0);
        let before = state(&server);
        let report = inspect(kind, &server, &[], 0);
        assert!(
            validator.iter_errors(&report).next().is_none(),
            "{name}: {report}"
        );
        for (role, size) in [
            ("line template", json!([0.6, 0.1, 0.0])),
            ("wall template", json!([1.0, 0.05, 0.2])),
            ("start marker", json!([1.0, 1.0, 0.0])),
        ] {
            assert_eq!(object(&report, role)["size"], size, "{name}: {role}");
        }
        let zmq = kind != Kind::Legacy;
        assert_eq!(report["colours_read"], zmq, "{name}");
        if zmq {
            for (role, colour) in [
                ("line template", json!([0.0, 1.0, 0.0])),
                ("start marker", json!([0.0, 0.0, 1.0])),
                ("end marker", json!([1.0, 0.0, 0.0])),
            ] {
                assert_eq!(object(&report, role)["colour"], colour, "{name}: {role}");
            }
        } else {
            assert!(
                report["objects"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .all(|o| o.get("colour").is_none()),
                "{name}: a colour the legacy API cannot have read: {report}"
            );
        }
        assert_eq!(
            object(&report, "maze dummy").get("colour"),
            None,
            "{name}: a dummy has none"
        );
        let text = inspect_text(kind, &server);
        assert!(text.contains("0.6 x 0.1 x 0 m"), "{name}: {text}");
        assert_eq!(text.contains("colour #00ff00"), zmq, "{name}: {text}");
        assert_eq!(
            text.contains("colours not shown: the legacy remote API cannot read them"),
            !zmq,
            "{name}: {text}"
        );
        assert_eq!(state(&server), before, "{name}: inspect changed the scene");
        server.shutdown();
    }
}

/// `inspect --layout` raises the idle rate as `apply` does, so that at the default idle fps 8
/// (a main-loop pass per paced request, `../shared/spec/real-coppeliasim-4.5.1.md` "Pacing")
/// only the requests before the rate is raised (and the last, after it is restored) wait for
/// a pass, whatever the scene holds: a maze of copies or of meshes. The rate and its record
/// are left as they were. Counted from the emulator's ledger, as
/// `draw::before_the_rate_is_raised_an_apply_waits_for_few_passes` counts apply's.
#[test]
fn inspect_raises_the_idle_rate_and_waits_for_few_passes() {
    let dir = tempfile::tempdir().unwrap();
    let drawn = generate(dir.path(), "42", "prim");
    for (kind, most) in [(Kind::Legacy, 2), (Kind::Zmq1, 2)] {
        for draw in ["copies", "mesh"] {
            let name = format!("{}, {draw}", kind.name());
            let server = kind.serve(Scene::course(), 8);
            bin()
                .args(["-q", "apply", &drawn, "--draw", draw])
                .args(api_args(kind, &server))
                .assert()
                .success();
            let before = state(&server);
            server.with_sim(|sim| sim.ledger = Some(vec![]));
            let report = inspect(kind, &server, &["--layout", &drawn], 0);
            let ledger = server.with_sim(|sim| sim.ledger.take()).unwrap();
            assert_eq!(state(&server), before, "{name}: inspect changed the scene");
            assert_eq!(
                report["idle_fps"], 8,
                "{name}: the user's rate, not the raised one"
            );
            assert_eq!(report["layout"]["matches"], true, "{name}: {report}");
            let waited: Vec<bool> = ledger.iter().map(|c| !c.queued && c.idle_fps > 0).collect();
            let before_last = &waited[..waited.len() - 1];
            assert!(
                before_last.iter().filter(|w| **w).count() <= most,
                "{name}: requests that waited for a pass, in order: {waited:?}"
            );
            server.shutdown();
        }
    }
}

/// A layout whose floor is larger than the scene's is a difference of the scene, named with
/// its remedy (the floor's, not the templates'), on every API; nothing is changed.
#[test]
fn inspect_names_a_floor_smaller_than_the_layouts() {
    let dir = tempfile::tempdir().unwrap();
    let big = dir.path().join("big.json").display().to_string();
    bin()
        .args([
            "-q", "generate", "--seed", "1", "--size", "30x30", "-o", &big,
        ])
        .assert()
        .success();
    for kind in Kind::ALL {
        let server = kind.serve(Scene::course(), 0);
        let before = state(&server);
        let report = inspect(kind, &server, &["--layout", &big], 1);
        let differences = report["layout"]["differences"].as_array().unwrap();
        assert_eq!(differences.len(), 1, "{kind:?}: {report}");
        let text = differences[0].as_str().unwrap();
        assert!(
            text.contains("`Floor` is 10 x 10 m but the layout's floor is 35 x 35 m")
                && text.contains("--resize-floor")
                && (kind != Kind::Legacy || text.contains("with --api zmq")),
            "{kind:?}: {text}"
        );
        assert_eq!(
            state(&server),
            before,
            "{kind:?}: inspect changed the scene"
        );
        server.shutdown();
    }
}

/// Issue 41 row 9: after `apply` of a 9x9 line maze, `inspect` counts the lines as `apply`
/// does (the template lies on the first line: "drew 81 lines" is "81 lines (the line
/// template and 80 copies)"), and the templates a line maze does not use are not "missing".
#[test]
fn inspect_counts_the_lines_apply_drew_and_misses_no_unused_template() {
    for kind in [Kind::Legacy, Kind::Zmq2] {
        let k = kind.name();
        let server = kind.serve(Scene::course(), 0);
        let dir = tempfile::tempdir().unwrap();
        let m = generate(dir.path(), "7", "dfs");
        let out = bin()
            .arg("apply")
            .arg(&m)
            .args(api_args(kind, &server))
            .assert()
            .success()
            .get_output()
            .stdout
            .clone();
        let applied = String::from_utf8(out).unwrap();
        let drew: usize = applied
            .split("drew ")
            .nth(1)
            .and_then(|r| r.split(' ').next())
            .and_then(|n| n.parse().ok())
            .unwrap_or_else(|| panic!("{k}: {applied}"));
        let text = inspect_text(kind, &server);
        let said = format!(
            "drawn: {drew} lines (the line template and {} copies), 0 walls, 0 posts (a line maze)",
            drew - 1
        );
        assert!(text.contains(&said), "{k}: {said}\n{text}");
        assert!(!text.contains("missing"), "{k}: {text}");
        assert!(
            text.contains("Wall     not in the scene (a line maze does not use it)"),
            "{k}: {text}"
        );
        server.shutdown();
    }
}

/// Issue 38 row 11: `inspect` of a scene with many stray copies names the first 12 and
/// counts the rest, as `apply` and `clear` do; `--json` lists every one.
#[test]
fn inspect_names_a_dozen_stray_copies_and_counts_the_rest() {
    let mut scene = Scene::course();
    let line = scene.resolve("Line").unwrap();
    for _ in 0..30 {
        scene.copy_paste(&[line]).unwrap();
    }
    let server = Kind::Legacy.serve(scene, 0);
    let text = inspect_text(Kind::Legacy, &server);
    let stray = text
        .lines()
        .find(|l| l.starts_with("stray copies outside the maze dummy: "))
        .unwrap_or_else(|| panic!("{text}"));
    assert!(stray.ends_with(", ... (18 more)"), "{stray}");
    assert_eq!(stray.matches(", ").count(), 12, "{stray}");
    let report = inspect(Kind::Legacy, &server, &[], 0);
    assert_eq!(report["maze"]["stray_copies"].as_array().unwrap().len(), 30);
    server.shutdown();
}
