//! `schema/layout-v1.schema.json` is generated from the layout types; this test keeps the
//! checked-in file equal to what the types say (re-bless with `VREP_MAZE_BLESS=1`).

use std::fs;
use std::path::Path;

use vrep_maze::layout::Layout;

#[test]
fn the_checked_in_schema_matches_the_types() {
    let schema = schemars::schema_for!(Layout);
    let text = serde_json::to_string_pretty(&schema).unwrap() + "\n";
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("schema/layout-v1.schema.json");
    if std::env::var_os("VREP_MAZE_BLESS").is_some() {
        fs::create_dir_all(path.parent().unwrap()).unwrap();
        fs::write(&path, &text).unwrap();
        return;
    }
    let checked_in = fs::read_to_string(&path).unwrap_or_default();
    assert!(
        checked_in == text,
        "{} is out of date: re-bless with VREP_MAZE_BLESS=1 cargo test --test it schema",
        path.display()
    );
    assert!(text.contains("\"segments\""));
}

#[test]
fn every_golden_layout_satisfies_the_schema() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let schema: serde_json::Value = serde_json::from_str(
        &fs::read_to_string(root.join("schema/layout-v1.schema.json")).unwrap(),
    )
    .unwrap();
    let validator = jsonschema::validator_for(&schema).expect("a valid JSON Schema");
    let mut checked = 0;
    for entry in fs::read_dir(root.join("mazes")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().and_then(|e| e.to_str()) != Some("json") {
            continue;
        }
        let layout: serde_json::Value =
            serde_json::from_str(&fs::read_to_string(&path).unwrap()).unwrap();
        let errors: Vec<String> = validator
            .iter_errors(&layout)
            .map(|e| e.to_string())
            .collect();
        assert!(errors.is_empty(), "{}: {errors:?}", path.display());
        checked += 1;
    }
    assert!(checked >= 7, "only {checked} golden layouts");
    // The schema is strict enough to refuse a broken layout.
    let mut broken: serde_json::Value =
        serde_json::from_str(&fs::read_to_string(root.join("mazes/dfs-9x9-seed42.json")).unwrap())
            .unwrap();
    broken["grid"]["columns"] = serde_json::json!("nine");
    broken["surprise"] = serde_json::json!(1);
    assert!(validator.iter_errors(&broken).count() >= 2);
}

/// The checked-in schema of every `--json` report equals what its type says (re-bless with
/// `VREP_MAZE_BLESS=1 cargo test --test it schema`).
#[test]
fn the_checked_in_report_schemas_match_the_types() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("schema");
    for (name, schema) in vrep_maze::cli::reports::schemas() {
        let text = serde_json::to_string_pretty(&schema).unwrap() + "\n";
        let path = root.join(name);
        if std::env::var_os("VREP_MAZE_BLESS").is_some() {
            fs::write(&path, &text).unwrap();
            continue;
        }
        let checked_in = fs::read_to_string(&path).unwrap_or_default();
        assert!(
            checked_in == text,
            "{} is out of date: re-bless with VREP_MAZE_BLESS=1 cargo test --test it schema",
            path.display()
        );
    }
}

mod json_output {
    use std::fs;
    use std::path::Path;

    use serde_json::Value;

    use crate::support::bin;
    use crate::support::cli::{Serve, generate};

    /// Runs `vrep-maze args`, expecting exit `code`; its standard output must be exactly one
    /// JSON document that satisfies `schema/<schema>`; returns it.
    fn document(args: &[&str], code: i32, schema: &str) -> Value {
        let out = bin().args(args).assert().code(code).get_output().clone();
        let stdout = String::from_utf8(out.stdout).unwrap();
        assert_eq!(
            stdout.lines().count(),
            1,
            "one document on one line: {stdout}"
        );
        let value: Value = serde_json::from_str(&stdout).unwrap();
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("schema")
            .join(schema);
        let schema: Value = serde_json::from_str(&fs::read_to_string(path).unwrap()).unwrap();
        let validator = jsonschema::validator_for(&schema).expect("a valid JSON Schema");
        let errors: Vec<String> = validator
            .iter_errors(&value)
            .map(|e| e.to_string())
            .collect();
        assert!(errors.is_empty(), "{args:?}: {errors:?}\n{value}");
        value
    }

    #[test]
    fn validate_solve_and_batch_print_documents_that_satisfy_their_schemas() {
        let dir = tempfile::tempdir().unwrap();
        let good = generate(dir.path(), "3", "prim");
        let bad = dir.path().join("bad.json");
        let mut layout: Value = serde_json::from_str(&fs::read_to_string(&good).unwrap()).unwrap();
        layout["line"]["z"] = serde_json::json!(-1.0);
        fs::write(&bad, layout.to_string()).unwrap();
        let missing = dir.path().join("missing.json");
        let v = document(
            &[
                "validate",
                "--json",
                &good,
                bad.to_str().unwrap(),
                missing.to_str().unwrap(),
            ],
            1,
            "validate-v1.schema.json",
        );
        assert_eq!(v["valid"], false);
        assert_eq!(v["files"][0]["valid"], true);
        assert_eq!(v["files"][0]["metrics"]["cells"], 81);
        assert_eq!(v["files"][1]["valid"], false);
        assert!(v["files"][1]["problem_count"].as_u64().unwrap() >= 1);
        assert!(
            v["files"][1]["problems"][0]
                .as_str()
                .unwrap()
                .contains("line.z")
        );
        assert!(v["files"][2]["error"].as_str().is_some());
        let ok = document(&["validate", "--json", &good], 0, "validate-v1.schema.json");
        assert_eq!(ok["valid"], true);

        let s = document(&["solve", "--json", &good], 0, "solve-v1.schema.json");
        assert_eq!(s["format"], "vrep-maze/solve");
        let plain: Value = serde_json::from_str(
            &String::from_utf8(
                bin()
                    .args(["solve", &good])
                    .assert()
                    .success()
                    .get_output()
                    .stdout
                    .clone(),
            )
            .unwrap(),
        )
        .unwrap();
        assert_eq!(s, plain, "--json is --format json");

        let out = dir.path().join("set");
        let batch = [
            "batch",
            "--json",
            "--seeds",
            "0..4",
            "--size",
            "5x5",
            "--out-dir",
            out.to_str().unwrap(),
        ];
        let b = document(&batch, 0, "batch-v1.schema.json");
        assert_eq!(
            (b["seeds"].as_u64(), b["written"].as_u64()),
            (Some(4), Some(4))
        );
        let again = document(&batch, 0, "batch-v1.schema.json");
        assert_eq!(again["unchanged"], 4);
    }

    #[test]
    fn apply_and_clear_print_documents_that_satisfy_their_schemas_on_both_apis() {
        let dir = tempfile::tempdir().unwrap();
        let m = generate(dir.path(), "42", "prim");
        let s = Serve::start(
            &[
                "--api",
                "both",
                "--listen",
                "127.0.0.1:0",
                "--zmq-listen",
                "127.0.0.1:0",
            ],
            2,
        );
        for (api, port) in [("legacy", s.ports[0]), ("zmq", s.ports[1])] {
            let port = port.to_string();
            let a = document(
                &["apply", &m, "--json", "--api", api, "--port", &port],
                0,
                "apply-v1.schema.json",
            );
            assert_eq!(a["lines"], 160, "{api}");
            assert_eq!(a["verified"], true);
            let n = |key: &str| a[key].as_u64().unwrap();
            assert_eq!(
                n("unchanged") + n("placed") + n("pasted"),
                160,
                "{api}: {a}"
            );
            assert_eq!(
                n("markers_unchanged") + n("markers_placed"),
                2,
                "{api}: {a}"
            );
            let dry = document(
                &[
                    "apply",
                    &m,
                    "--json",
                    "--dry-run",
                    "--api",
                    api,
                    "--port",
                    &port,
                ],
                0,
                "apply-v1.schema.json",
            );
            assert_eq!(
                (&dry["nothing_to_do"], &dry["unchanged"], &dry["verified"]),
                (&true.into(), &160.into(), &false.into()),
                "{api}: {dry}"
            );
            // a mesh drawing's document has the same schema
            let mesh = document(
                &[
                    "apply", &m, "--json", "--draw", "mesh", "--api", api, "--port", &port,
                ],
                0,
                "apply-v1.schema.json",
            );
            // counted in runs (one rectangle each) and meshes, not in copies
            assert_eq!(mesh["verified"], true, "{api}: {mesh}");
            assert_eq!(
                mesh["pasted"], 1,
                "{api}: one mesh of the 9x9's runs: {mesh}"
            );
            assert_eq!(mesh["removed"], 159, "{api}: the copies went: {mesh}");
            // and back to copies for the clear below
            let back = document(
                &["apply", &m, "--json", "--api", api, "--port", &port],
                0,
                "apply-v1.schema.json",
            );
            assert_eq!(back["lines"], 160, "{api}: {back}");
            // the same layout again: over ZeroMQ every kept copy's pose is sent unread
            // (reading costs what setting does), over legacy every pose is read first
            let again = document(
                &["apply", &m, "--json", "--api", api, "--port", &port],
                0,
                "apply-v1.schema.json",
            );
            let (placed, unread) = (&again["placed"], &again["placed_unread"]);
            match api {
                "zmq" => assert!(
                    unread.as_u64() > Some(0) && unread == placed,
                    "zmq: {again}"
                ),
                _ => assert_eq!((placed, unread), (&0.into(), &0.into()), "legacy: {again}"),
            }
            let c = document(
                &["clear", "--json", "--api", api, "--port", &port],
                0,
                "clear-v1.schema.json",
            );
            assert_eq!(c["removed"].as_array().unwrap().len(), 159, "{api}");
        }
    }

    #[test]
    fn quiet_means_nothing_but_errors() {
        let dir = tempfile::tempdir().unwrap();
        let m = generate(dir.path(), "42", "prim");
        let s = Serve::start(&["--listen", "127.0.0.1:0"], 1);
        let port = s.port();
        for args in [
            vec!["-q", "apply", &m, "--port", &port],
            vec!["-q", "clear", "--port", &port],
            vec!["-q", "validate", &m],
        ] {
            bin().args(&args).assert().success().stdout("").stderr("");
        }
        let out = dir.path().join("set");
        bin()
            .args(["-q", "batch", "--seeds", "0..2", "--out-dir"])
            .arg(&out)
            .assert()
            .success()
            .stdout("")
            .stderr("");
        // errors still show
        bin()
            .args(["-q", "validate", "nope.json"])
            .assert()
            .failure()
            .stderr(predicates::str::contains("nope.json"));
    }
}
