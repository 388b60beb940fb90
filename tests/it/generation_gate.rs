//! The generation gate: `generate` can never write a layout that `validate` rejects, and
//! `validate` rejects the physically absurd. Random option combinations (extreme,
//! negative, tiny, huge, every rotation) are either refused cleanly or validate; each
//! case from the "trust at every edge" issue is pinned at the command line, with exit
//! code 2 for a refused option (clap's usage code) and 1 for an invalid layout or a
//! failure.

use std::f64::consts::TAU;
use std::fs;
use std::path::Path;
use std::sync::OnceLock;

use assert_cmd::Command;
use proptest::prelude::*;
use serde_json::{Value, json};
use tempfile::TempDir;
use vrep_maze::generate::Algorithm;
use vrep_maze::layout::endpoints::Corner;
use vrep_maze::layout::json::{parse_layout, to_string};
use vrep_maze::layout::{EndpointSpec, FloorSize, GenerateSpec, Geometry, build_layout};
use vrep_maze::maze::{Cell, Grid};
use vrep_maze::validate::validate;

/// A change made to a spec or a layout.
type Edit<T> = fn(&mut T);

fn bin() -> Command {
    Command::cargo_bin("vrep-maze").expect("binary built")
}

/// The checked-in layout schema, which carries the same ranges.
fn schema() -> &'static jsonschema::Validator {
    static SCHEMA: OnceLock<jsonschema::Validator> = OnceLock::new();
    SCHEMA.get_or_init(|| {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("schema/layout-v1.schema.json");
        let schema: Value = serde_json::from_str(&fs::read_to_string(path).unwrap()).unwrap();
        jsonschema::validator_for(&schema).expect("a valid JSON Schema")
    })
}

/// Builds `spec`: a refusal must be one line; a layout must validate, also after a
/// trip through its JSON text, which holds no `null` and satisfies the schema.
fn gate(spec: &GenerateSpec) -> Result<(), String> {
    match build_layout(spec) {
        Err(message) => {
            let message = vrep_maze::cli::wording::worded(&message);
            assert!(
                !message.is_empty() && !message.contains('\n'),
                "{message:?}"
            );
            Err(message)
        }
        Ok(layout) => {
            let report = validate(&layout);
            assert!(report.is_ok(), "{spec:?}: {:?}", report.problems);
            let text = to_string(&layout);
            assert!(!text.contains("null"), "{spec:?}: {text}");
            let json: Value = serde_json::from_str(&text).unwrap();
            let errors: Vec<String> = schema().iter_errors(&json).map(|e| e.to_string()).collect();
            assert!(errors.is_empty(), "{spec:?}: the schema says {errors:?}");
            let read = parse_layout(&text, "gate.json").expect("written layouts parse");
            let report = validate(&read);
            assert!(report.is_ok(), "{spec:?} after JSON: {:?}", report.problems);
            Ok(())
        }
    }
}

/// Numbers from the absurd to the ordinary, weighted towards the edges.
fn number(ordinary: std::ops::Range<f64>) -> impl Strategy<Value = f64> {
    prop_oneof![
        3 => ordinary,
        1 => proptest::sample::select(vec![
            0.0,
            -0.0,
            -1.0,
            -5.0,
            1e-300,
            1e-9,
            1e-6,
            0.001,
            0.4,
            1.5,
            999.0,
            1000.0,
            10000.0,
            10000.001,
            1e308,
            -1e308,
            f64::MIN_POSITIVE,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ]),
        1 => any::<f64>(),
    ]
}

fn endpoint() -> impl Strategy<Value = EndpointSpec> {
    prop_oneof![
        proptest::sample::select(vec![
            EndpointSpec::Corner(Corner::SouthWest),
            EndpointSpec::Corner(Corner::NorthEast),
            EndpointSpec::Farthest,
            EndpointSpec::FarthestPair,
        ]),
        (0u32..8, 0u32..8).prop_map(|(x, y)| EndpointSpec::Cell(Cell::new(x, y))),
    ]
}

prop_compose! {
    fn spec()(
        w in 1u64..=6,
        h in 1u64..=6,
        algorithm in proptest::sample::select(Algorithm::ALL.to_vec()),
        seed in any::<u64>(),
        braid in number(0.0..1.0),
        cell_size in number(0.05..3.0),
        line_length in number(0.01..3.0),
        line_width in number(0.001..0.5),
        line_z in number(0.0..0.01),
        marker_z in number(0.0..0.02),
        rotation in prop_oneof![3 => -TAU..TAU, 1 => number(-1e6..1e6)],
        origin in proptest::option::of((number(-20.0..20.0), number(-20.0..20.0))),
        floor in proptest::option::of((number(1.0..40.0), number(1.0..40.0))),
        start in endpoint(),
        end in endpoint(),
    ) -> GenerateSpec {
        let grid = Grid::new(w, h).unwrap();
        GenerateSpec {
            grid,
            algorithm,
            seed,
            braid,
            start,
            end,
            geometry: Geometry {
                cell_size,
                origin: origin.map_or_else(|| Geometry::centred_origin(grid, cell_size), |(x, y)| [x, y]),
                rotation,
                line_length,
                line_width,
                line_z,
                marker_z,
            },
            floor: floor.map_or(FloorSize::Auto, |(x, y)| FloorSize::Fixed([x, y])),
        }
    }
}

/// In-range, consistent geometry, and whether to centre the maze.
fn ordinary_geometry() -> impl Strategy<Value = (Geometry, bool)> {
    (0.05..3.0f64)
        .prop_flat_map(|cell| (Just(cell), 0.001..cell * 0.9))
        .prop_flat_map(|(cell, width)| {
            (
                Just((cell, width)),
                ((cell + width) / 60.0).max(width + 1e-4)..(cell + width),
                -1e6..1e6f64,
                proptest::option::of((-20.0..20.0f64, -20.0..20.0f64)),
                1e-6..0.01f64,
                1e-5..0.04f64,
            )
        })
        .prop_map(
            |((cell_size, line_width), line_length, rotation, origin, line_z, lift)| {
                (
                    Geometry {
                        cell_size,
                        origin: origin.map_or([0.0, 0.0], |(x, y)| [x, y]),
                        rotation,
                        line_length,
                        line_width,
                        line_z,
                        marker_z: line_z + lift,
                    },
                    origin.is_none(),
                )
            },
        )
}

prop_compose! {
    fn ordinary_spec()(
        w in 1u64..=6,
        h in 1u64..=6,
        algorithm in proptest::sample::select(Algorithm::ALL.to_vec()),
        seed in any::<u64>(),
        braid in 0.0..=1.0f64,
        (mut geometry, centred) in ordinary_geometry(),
        end in proptest::sample::select(vec![EndpointSpec::Farthest, EndpointSpec::Corner(Corner::SouthEast)]),
    ) -> GenerateSpec {
        let grid = Grid::new(w, h).unwrap();
        if centred {
            geometry.origin = Geometry::centred_origin(grid, geometry.cell_size);
        }
        GenerateSpec {
            grid,
            algorithm,
            seed,
            braid,
            start: EndpointSpec::Corner(Corner::SouthWest),
            end,
            geometry,
            floor: FloorSize::Auto,
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    #[test]
    fn any_options_are_refused_or_validate(spec in spec()) {
        let _ = gate(&spec);
    }

    #[test]
    fn ordinary_options_validate(spec in ordinary_spec()) {
        // In range and consistent: the gate must let every one of these through.
        prop_assert!(gate(&spec).is_ok(), "{:?}: {:?}", spec, gate(&spec));
    }

    #[test]
    fn any_rotation_of_a_sane_maze_validates(
        degrees in prop_oneof![-360.0..360.0f64, -1e12..1e12f64],
        w in 1u64..=12,
        h in 1u64..=12,
        seed in any::<u64>(),
    ) {
        let mut spec = GenerateSpec::course(Grid::new(w, h).unwrap(), Algorithm::Prim, seed);
        spec.geometry.rotation = degrees.to_radians();
        prop_assert!(gate(&spec).is_ok());
    }
}

#[test]
fn a_sweep_of_rotations_all_validate() {
    for k in -75..75 {
        let mut spec = GenerateSpec::course(Grid::new(9, 9).unwrap(), Algorithm::Dfs, 42);
        spec.geometry.rotation = (f64::from(k) * 2.4 + 0.3).to_radians();
        gate(&spec).unwrap_or_else(|e| panic!("{k}: {e}"));
    }
}

#[test]
fn a_25_m_maze_fits_a_25_m_floor_at_every_right_angle() {
    for degrees in [0.0, 90.0, 180.0, 270.0, -90.0, -180.0, 360.0, 450.0] {
        let mut spec = GenerateSpec::course(Grid::new(25, 25).unwrap(), Algorithm::Kruskal, 7);
        let rotation = f64::to_radians(degrees);
        // Turn the maze about cell (0, 0) and put that cell where the turned maze is
        // centred on the floor.
        let (sin, cos) = (rotation.sin().round(), rotation.cos().round());
        spec.geometry.rotation = rotation;
        spec.geometry.origin = [-(cos * 12.0 - sin * 12.0), -(sin * 12.0 + cos * 12.0)];
        spec.floor = FloorSize::Fixed([25.0, 25.0]);
        gate(&spec).unwrap_or_else(|e| panic!("{degrees}: {e}"));
        spec.floor = FloorSize::Auto;
        assert_eq!(build_layout(&spec).unwrap().floor.size, [25.0, 25.0]);
    }
    // The case: the default 9x9 turned 180 degrees about cell (0, 0) reaches
    // 12.5 m from the floor origin, and gets (and fits) a 25 m floor.
    let mut spec = GenerateSpec::course(Grid::new(9, 9).unwrap(), Algorithm::Dfs, 42);
    spec.geometry.rotation = std::f64::consts::PI;
    assert_eq!(build_layout(&spec).unwrap().floor.size, [25.0, 25.0]);
    gate(&spec).unwrap();
}

#[test]
fn the_library_refuses_before_allocating() {
    let course = || GenerateSpec::course(Grid::new(50, 50).unwrap(), Algorithm::Dfs, 1);
    let cases: [(Edit<GenerateSpec>, &str); 6] = [
        (
            |s| s.geometry.cell_size = 1e308,
            "--cell-size 1e308 is out of range",
        ),
        (
            |s| s.geometry.line_width = 1e308,
            "--line-width 1e308 is out of range",
        ),
        (
            |s| s.geometry.line_length = 1e-300,
            "--line-length 1e-300 is out of range",
        ),
        (
            |s| s.geometry.line_length = 1e-9,
            "--line-length 1e-9 is out of range",
        ),
        (
            |s| s.geometry.rotation = f64::NAN,
            "--rotation NaN rad is not a finite angle",
        ),
        (|s| s.braid = -0.5, "--braid -0.5 is out of range 0..1"),
    ];
    for (edit, needle) in cases {
        let mut spec = course();
        edit(&mut spec);
        let err = vrep_maze::cli::wording::worded(&build_layout(&spec).unwrap_err());
        assert!(err.contains(needle), "{needle}: {err}");
    }
    let mut huge = GenerateSpec::course(Grid::new(4096, 4096).unwrap(), Algorithm::Dfs, 1);
    huge.geometry.cell_size = 0.2;
    huge.geometry.origin = Geometry::centred_origin(huge.grid, 0.2);
    huge.geometry.line_length = 0.06;
    huge.geometry.line_width = 0.05;
    let err = build_layout(&huge).unwrap_err().to_string();
    assert!(
        err.contains("more than the 67108864 a layout may hold"),
        "{err}"
    );
    let mut far = course();
    far.geometry.cell_size = 300.0;
    far.geometry.line_length = 180.0;
    far.geometry.line_width = 30.0;
    let err = build_layout(&far).unwrap_err().to_string();
    assert!(
        err.contains("more than the largest floor, 10000 m x 10000 m"),
        "{err}"
    );
}

// ---- the command line ------------------------------------------------------------------

/// `generate args` must be refused: exit 2, nothing on stdout, one line naming `needle`.
fn refused(args: &[&str], needle: &str) {
    let output = bin().arg("generate").args(args).output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(2), "{args:?}: {stderr}");
    assert!(output.stdout.is_empty(), "{args:?} wrote a layout");
    assert!(
        stderr.contains(needle),
        "{args:?}: expected {needle:?} in {stderr}"
    );
    assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
    assert_eq!(
        stderr.lines().count(),
        1,
        "{args:?}: one line, not {stderr}"
    );
}

/// `generate args` must succeed, and `validate` must accept what it wrote.
fn accepted(args: &[&str]) -> String {
    let dir = TempDir::new().unwrap();
    let path = dir.path().join("maze.json");
    let output = bin()
        .arg("generate")
        .args(args)
        .arg("-o")
        .arg(&path)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(0), "{args:?}: {stderr}");
    let validated = bin().arg("validate").arg(&path).output().unwrap();
    assert_eq!(
        validated.status.code(),
        Some(0),
        "{args:?}: {}",
        String::from_utf8_lossy(&validated.stderr)
    );
    let text = fs::read_to_string(&path).unwrap();
    assert!(!text.contains("null"), "{args:?}: {text}");
    text
}

#[test]
fn cells_too_small_for_the_line_are_refused() {
    refused(
        &["--cell-size", "0.4"],
        "--cell-size 0.4 m is too small for the line template",
    );
    refused(
        &["--cell-size", "0.001", "--size", "50x50"],
        "--line-width 0.1 m is not narrower than --cell-size 0.001 m",
    );
    refused(
        &["--line-width", "1.5"],
        "--line-width 1.5 m is not narrower than --cell-size 1 m",
    );
    // The exact fit is fine: one 0.6 m copy covers a 0.5 m passage plus the line width.
    accepted(&["--cell-size", "0.5", "--seed", "3"]);
    accepted(&[
        "--cell-size",
        "0.5",
        "--line-length",
        "0.3",
        "--line-width",
        "0.05",
        "--seed",
        "1",
    ]);
}

#[test]
fn every_rotation_validates() {
    for degrees in ["90", "180", "-90", "270", "33.3", "1e308", "-1e308", "720"] {
        accepted(&["--rotation", degrees, "--seed", "5", "--size", "12x7"]);
    }
    // the maze turns about its centre, which stays where --origin puts it (here the floor
    // origin): a 25 m maze turned half a turn still fits a 25 m floor
    let text = accepted(&[
        "--rotation",
        "180",
        "--origin",
        "-12,-12",
        "--size",
        "25x25",
        "--floor-size",
        "25x25",
        "--seed",
        "1",
    ]);
    assert!(text.contains("\"origin\": [12.0, 12.0]"), "{text}");
    // on the course, a quarter or half turn keeps the 10 m floor; 45 degrees needs 12.73 m
    for degrees in ["90", "180", "-90"] {
        let text = accepted(&["--rotation", degrees, "--seed", "1"]);
        assert!(text.contains("\"size\": [10.0, 10.0]"), "{degrees}: {text}");
    }
    let text = accepted(&["--rotation", "45", "--seed", "1"]);
    assert!(text.contains("\"size\": [15.0, 15.0]"), "{text}");
    refused(
        &["--rotation", "45", "--floor-size", "12x12", "--seed", "1"],
        "the maze needs a floor of 12.728 m x 12.728 m",
    );
}

#[test]
fn huge_values_are_refused_not_written_as_null() {
    refused(
        &["--origin", "1e308,0"],
        "--origin x 1e308 is out of range -5000..5000 m",
    );
    refused(
        &["--floor-size", "1e308x10"],
        "--floor-size x 1e308 is out of range",
    );
    refused(
        &["--line-length", "1e308"],
        "--line-length 1e308 is out of range",
    );
    refused(
        &["--line-z", "1e308"],
        "--line-z 1e308 is out of range 1e-6..0.05 m",
    );
    refused(&["--marker-z", "1e308"], "--marker-z 1e308 is out of range");
    refused(&["--line-z", "-5"], "--line-z -5 is out of range");
    refused(
        &["--marker-z", "0.0005"],
        "--marker-z 0.0005 m is not above --line-z 0.001 m",
    );
    refused(&["--size", "16000x1"], "more than the largest floor");
    refused(
        &[
            "--size",
            "16000x1",
            "--cell-size",
            "0.5",
            "--origin",
            "-5001,0",
        ],
        "--origin x -5001 is out of range -5000..5000 m",
    );
    // The largest grid at the course's cell size still fits the largest floor.
    let largest = GenerateSpec::course(Grid::new(4096, 4096).unwrap(), Algorithm::Dfs, 1);
    assert!(largest.check().is_ok(), "{:?}", largest.check());
}

#[test]
fn former_panics_are_clean_refusals() {
    refused(
        &["--cell-size", "1e308"],
        "--cell-size 1e308 is out of range 0.001..10000 m",
    );
    refused(
        &["--line-width", "1e308"],
        "--line-width 1e308 is out of range",
    );
    refused(
        &["--line-length", "1e-300"],
        "--line-length 1e-300 is out of range",
    );
    refused(
        &["--line-length", "1e-9"],
        "--line-length 1e-9 is out of range",
    );
    refused(
        &["--line-length", "0.002"],
        "a passage would take 550 copies of the line",
    );
}

#[test]
fn negative_numbers_parse_and_are_refused_by_range() {
    refused(&["--braid", "-0.5"], "--braid -0.5 is out of range 0..1");
    refused(&["--braid", "1.5"], "--braid 1.5 is out of range 0..1");
    refused(&["--braid", "NaN"], "--braid NaN is out of range 0..1");
}

#[test]
fn farthest_pair_refuses_an_explicit_end() {
    refused(
        &["--start", "farthest-pair", "--end", "ne"],
        "--end ne conflicts with --start farthest-pair",
    );
    accepted(&["--start", "farthest-pair", "--seed", "2"]);
    accepted(&[
        "--start",
        "farthest-pair",
        "--end",
        "farthest",
        "--seed",
        "2",
    ]);
}

#[test]
fn exit_codes_tell_usage_from_failure() {
    // clap's own refusal of a malformed value: 2.
    let output = bin()
        .args(["generate", "--cell-size", "abc"])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(2));
    // A refused combination of well-formed values: 2 as well.
    refused(&["--floor-size", "5x5"], "--floor-size is 5 m x 5 m");
    refused(&["--start", "9,0"], "--start 9,0 is off the 9x9 grid");
    refused(&["--size", "0x5"], "--size");
    // A failure to do what was asked: 1.
    let output = bin()
        .args([
            "generate",
            "--seed",
            "1",
            "-o",
            "/nonexistent/dir/maze.json",
        ])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
}

// ---- validate --------------------------------------------------------------------------

fn good_layout() -> Value {
    let output = bin()
        .args(["generate", "--seed", "42", "--size", "5x5"])
        .output()
        .unwrap();
    assert!(output.status.success());
    serde_json::from_slice(&output.stdout).unwrap()
}

/// Validates `layout` at the command line: exit 1 and every needle on stderr.
fn invalid(dir: &Path, layout: &Value, needles: &[&str]) -> String {
    let path = dir.join("bad.json");
    fs::write(&path, serde_json::to_string_pretty(layout).unwrap()).unwrap();
    let output = bin().arg("validate").arg(&path).output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr).to_string();
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    for needle in needles {
        assert!(stderr.contains(needle), "expected {needle:?} in {stderr}");
    }
    assert!(!stderr.contains("panicked"), "{stderr}");
    stderr
}

#[test]
fn validate_rejects_the_physically_absurd() {
    let dir = TempDir::new().unwrap();
    let good = good_layout();
    let edits: [(&str, Edit<Value>, &[&str]); 9] = [
        (
            "line.z huge",
            |v| v["line"]["z"] = json!(1e308),
            &["line.z: 1e308 is out of range"],
        ),
        (
            "line.z below the floor",
            |v| v["line"]["z"] = json!(-5.0),
            &["line.z: -5 is out of range"],
        ),
        (
            "segment z",
            |v| v["segments"][3]["z"] = json!(1e308),
            &["segments[3].z: 1e308 m is not line.z 0.001 m"],
        ),
        (
            "marker yaw",
            |v| v["start"]["pose"]["yaw"] = json!(1e308),
            &["start.pose.yaw: 1e308 is out of range"],
        ),
        (
            "marker under the lines",
            |v| v["end"]["pose"]["z"] = json!(0.0005),
            &["end.pose.z: 0.0005 m is not above line.z 0.001 m"],
        ),
        (
            "huge floor",
            |v| v["floor"]["size"] = json!([1e308, 10.0]),
            &["floor.size[0]: 1e308 is out of range 0.001..10000 m"],
        ),
        (
            "huge origin",
            |v| v["grid"]["origin"] = json!([0.0, -1e308]),
            &["grid.origin[1]: -1e308 is out of range -5000..5000 m"],
        ),
        (
            "huge rotation",
            |v| v["grid"]["rotation"] = json!(1e308),
            &["grid.rotation: 1e308 is out of range"],
        ),
        (
            "green floor",
            |v| v["line"]["width"] = json!(1.5),
            &["line.width: 1.5 m is not narrower than grid.cell_size 1 m"],
        ),
    ];
    for (what, edit, needles) in edits {
        let mut layout = good.clone();
        edit(&mut layout);
        let stderr = invalid(dir.path(), &layout, needles);
        assert!(stderr.lines().count() <= 22, "{what}: {stderr}");
    }
}

#[test]
fn validate_prints_at_most_20_problems() {
    let dir = TempDir::new().unwrap();
    let mut layout = good_layout();
    let segments = layout["segments"].as_array_mut().unwrap();
    let count = segments.len();
    assert!(count > 30);
    for segment in segments.iter_mut() {
        segment["z"] = json!(0.5);
    }
    let stderr = invalid(
        dir.path(),
        &layout,
        &[&format!("... and {} more problem(s)", count - 20)],
    );
    let problems = stderr
        .lines()
        .filter(|l| l.starts_with("error: ") && !l.contains("more problem(s)"))
        .count();
    assert_eq!(problems, 20, "{stderr}");
    assert!(stderr.contains("INVALID "), "{stderr}");
    assert!(stderr.contains(&format!("{count} problem(s)")), "{stderr}");
}
