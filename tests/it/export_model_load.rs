//! A CoppeliaSim model exported from a golden layout, loaded by the emulator's XML model
//! loader as `simxLoadModel` / `sim.loadModel` load it: every mesh, every triangle.

use vrep_maze::coppelia::xml::{FileKind, read};
use vrep_maze::draw::mesh::MeshMaze;
use vrep_maze::export::{Format, export};
use vrep_maze::layout::{Layout, read_layout};
use vrep_maze::sim::{Scene, model};

fn golden(name: &str) -> Layout {
    read_layout(
        &std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("mazes")
            .join(name),
    )
    .unwrap()
}

fn exported(format: Format, layout: &Layout) -> String {
    let mut out = Vec::new();
    export(format, layout, &mut out).unwrap();
    String::from_utf8(out).unwrap()
}

#[test]
fn the_emulator_loads_the_exported_model_with_every_triangle() {
    let layout = golden("dfs-9x9-seed42.json");
    let maze = MeshMaze::try_from(&layout).unwrap();
    let text = exported(Format::CoppeliaModel, &layout);
    assert_eq!(
        text,
        exported(Format::CoppeliaModel, &layout),
        "deterministic"
    );
    let doc = read(&text).unwrap();
    assert_eq!(doc.kind, FileKind::Model);
    let mut scene = Scene::course();
    let loaded = model::load(&mut scene, &doc).unwrap();
    let base = scene.get(loaded.base).unwrap();
    assert_eq!((base.alias.as_str(), base.name.as_str()), ("Maze", "Maze0"));
    let triangles: usize = maze.meshes.iter().map(|m| m.triangles()).sum();
    assert_eq!(loaded.triangles, triangles);
    assert_eq!(loaded.handles.len(), 2 + maze.meshes.len());
    for (m, h) in maze.meshes.iter().zip(&loaded.handles[2..]) {
        let o = scene.get(*h).unwrap();
        assert_eq!(o.alias, m.name());
        let mesh = o.mesh.as_ref().unwrap();
        assert_eq!(mesh.indices, m.indices);
        let off = mesh
            .vertices
            .iter()
            .zip(&m.vertices)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0f32, f32::max);
        assert!(off < 1e-6, "vertices back within float precision: {off}");
    }
}
