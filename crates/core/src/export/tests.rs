//! Exports of the golden layouts: structure against the files a real CoppeliaSim 4.5.1
//! wrote (`tests/it/export_model_load.rs` loads them into the emulator).

use std::path::Path;

use super::*;
use crate::coppelia::xml::tests::structure;
use crate::coppelia::xml::{Body, read};

const COURSE: &str = include_str!("../../../../tests/coppeliasim-xml/course-4.5.1.simscene.xml");
const TWO_RECTS: &str =
    include_str!("../../../../tests/coppeliasim-xml/mesh-two-rects-4.5.1.simmodel.xml");

fn golden(name: &str) -> Layout {
    crate::layout::read_layout(
        &Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../mazes")
            .join(name),
    )
    .unwrap()
}

fn exported(format: Format, layout: &Layout) -> String {
    let mut out = Vec::new();
    export(format, layout, &mut out).unwrap();
    String::from_utf8(out).unwrap()
}

/// The structure of a file cut into its header (everything outside objects) and the
/// structure of each object, keyed by its type (`shape`, `dummy`).
fn parts(text: &str) -> (Vec<String>, Vec<(String, Vec<String>)>) {
    let mut header = Vec::new();
    let mut objects: Vec<(String, Vec<String>)> = Vec::new();
    for path in structure(text) {
        match path.strip_prefix("CoppeliaSim/sceneObject") {
            Some("") => objects.push((String::new(), Vec::new())),
            Some(rest) => {
                let last = objects.last_mut().expect("inside an object");
                if last.0.is_empty() {
                    last.0 = rest.trim_start_matches('/').to_string();
                }
                last.1.push(rest.to_string());
            }
            None => header.push(path),
        }
    }
    (header, objects)
}

#[test]
fn endings_choose_the_format() {
    let of = |name: &str| Format::from_path(Path::new(name));
    assert_eq!(of("maze.simmodel.xml"), Some(Format::CoppeliaModel));
    assert_eq!(of("dir/MAZE.SimScene.xml"), Some(Format::CoppeliaScene));
    assert_eq!(of("maze.xml"), None);
    assert_eq!(of(".simmodel.xml"), None);
    assert_eq!(of("maze.ttm"), None);
    assert_eq!(of("m.mjcf"), Some(Format::Mjcf));
    assert_eq!(of("m.MuJoCo.XML"), Some(Format::Mjcf));
    assert_eq!(of("m.sdf"), Some(Format::Sdf));
    assert_eq!(of("dir/m.world"), Some(Format::Sdf));
    assert_eq!(of("m.urdf"), Some(Format::Urdf));
    assert_eq!(of("m.wbt"), Some(Format::Webots));
    assert_eq!(of("m.PointMaze.json"), Some(Format::PointMaze));
    assert_eq!(of("m.json"), None);
    assert_eq!(of(".urdf"), None);
    assert_eq!(
        Format::endings(),
        ".simmodel.xml, .simscene.xml, .mjcf, .mujoco.xml, .sdf, .world, .urdf, .wbt, .pointmaze.json, .yaml, .yml"
    );
}

#[test]
fn every_format_same_layout_same_bytes_and_invalid_layouts_write_nothing() {
    use super::solids::tests::{line_layout, post_layout};
    for layout in [line_layout(17.0), post_layout(-40.0)] {
        for format in Format::ALL {
            let (mut a, mut b) = (Vec::new(), Vec::new());
            export(format, &layout, &mut a).unwrap();
            export(format, &layout.clone(), &mut b).unwrap();
            assert_eq!(a, b, "{format:?}");
            assert!(!a.is_empty());
        }
    }
    let mut bad = post_layout(0.0);
    bad.grid.cell_size = -1.0;
    for format in Format::ALL {
        let mut out = Vec::new();
        assert!(export(format, &bad, &mut out).is_err());
        assert!(out.is_empty());
    }
}

#[test]
fn every_object_has_the_structure_coppeliasim_writes_for_its_type() {
    let (_, reference_shapes) = parts(TWO_RECTS);
    let (course_header, course_objects) = parts(COURSE);
    let shape = &reference_shapes[0].1;
    let dummy = &course_objects.iter().find(|(k, _)| k == "dummy").unwrap().1;
    for (name, format) in [
        ("dfs-9x9-seed42.json", Format::CoppeliaModel),
        ("dfs-9x9-seed42-walls.json", Format::CoppeliaModel),
        ("dfs-9x9-seed42.json", Format::CoppeliaScene),
        ("dfs-9x9-seed42-walls.json", Format::CoppeliaScene),
    ] {
        let text = exported(format, &golden(name));
        let (header, objects) = parts(&text);
        let want_header = match format {
            Format::CoppeliaModel => parts(TWO_RECTS).0,
            Format::CoppeliaScene => course_header.clone(),
            _ => unreachable!("only CoppeliaSim formats are listed"),
        };
        assert_eq!(header, want_header, "{name} {format:?}");
        for (kind, s) in &objects {
            let want = if kind == "shape" { shape } else { dummy };
            assert_eq!(s, want, "{name} {format:?}: a {kind}");
        }
        assert!(objects.iter().any(|(k, _)| k == "shape"));
    }
}

#[test]
fn the_exported_scene_holds_floor_maze_meshes_markers_and_template() {
    let layout = golden("dfs-9x9-seed42.json");
    let doc = read(&exported(Format::CoppeliaScene, &layout)).unwrap();
    let aliases: Vec<&str> = doc.objects.iter().map(|o| o.alias.as_str()).collect();
    assert_eq!(&aliases[..3], ["Floor", "Maze", "MazeMeshes"]);
    assert_eq!(&aliases[aliases.len() - 3..], ["Start", "End", "Line"]);
    let start = &doc.objects[aliases.len() - 3];
    assert_eq!(
        start.position,
        [
            layout.start.pose.x,
            layout.start.pose.y,
            layout.start.pose.z
        ]
    );
    assert!(matches!(&start.body, Body::Shape(s) if s.colour == [0.0, 0.0, 1.0]));
}

#[test]
fn a_layout_that_fails_validation_writes_nothing() {
    let mut layout = golden("dfs-9x9-seed42.json");
    layout.passages[0] = "zzz".to_string();
    let mut out = Vec::new();
    assert!(export(Format::CoppeliaModel, &layout, &mut out).is_err());
    assert!(out.is_empty());
}
