//! `apply --draw mesh`: the maze as a few mesh shapes, drawn, verified, replaced by copies
//! and back, cleared, for each API that can draw meshes; and the meshes of every golden line
//! layout cover exactly the cells' passages.

use vrep_maze::draw::mesh::{self, HOLDER, MeshMaze, parse_mesh_name};
use vrep_maze::draw::{self, ApplyOptions, Backend, DrawError, Drawing, ObjectNames};
use vrep_maze::generate::Algorithm;
use vrep_maze::layout::walls::{WallOptions, into_walls, length_between_posts};
use vrep_maze::layout::{Layout, passages, read_layout};
use vrep_maze::maze::Grid;
use vrep_maze::sim::{Mesh, Scene};

use crate::support::backend::{Kind, Server};
use crate::support::backend_tests;
use crate::support::layouts::course_layout;

// every API draws meshes: the legacy API through an XML model loaded from a temporary
// file, ZeroMQ protocols 1 and 2 with one Lua program per batch of meshes
backend_tests!(
    line_maze_draws_verifies_keeps_replaces_and_clears,
    wall_maze_with_posts_draws_boxes_that_copies_replace,
    verify_finds_a_changed_mesh_and_a_stray_copy,
    ctrl_c_stops_before_the_next_mesh_with_the_idle_rate_restored,
    the_users_objects_under_the_maze_outlive_a_mesh_maze,
    every_mesh_is_read_back_in_one_request,
    zeromq_makes_each_batch_of_meshes_in_one_request,
);

/// The user's objects under `Maze` (a dummy, a cuboid, a 1 m plane, a dummy and a 1 m plane
/// named like copies of `Line`) are no part of a mesh maze: drawing it over copies, and
/// clearing it, leaves them where they are and names them; verification passes beside
/// them.
fn the_users_objects_under_the_maze_outlive_a_mesh_maze(kind: Kind) {
    let k = kind.name();
    let (mut scene, mut mine) = crate::trust_draw::scene_with_the_users_objects();
    let maze = scene.resolve("Maze").unwrap();
    scene.add(
        "Line3",
        vrep_maze::sim::NewObject {
            kind: vrep_maze::sim::ObjectType::Shape,
            parent: Some(maze),
            position: [4.0, 4.0, 0.001],
            orientation: [0.0; 3],
            size: [1.0, 1.0, 0.0],
            colour: [0, 255, 0],
        },
    );
    mine.push("Line3");
    let s = kind.serve(scene, 0);
    let snapshot = |s: &Server| {
        let all = s.snapshot();
        mine.iter()
            .map(|n| {
                all.iter()
                    .find(|o| o.0 == *n)
                    .cloned()
                    .expect("still there")
            })
            .collect::<Vec<_>>()
    };
    let before = snapshot(&s);
    let mut b = s.connect();
    let layout = course_layout(Algorithm::Prim, 5, 5, 42);
    apply_copies(&mut b, &layout);
    let m = MeshMaze::try_from(&layout).unwrap();
    let r = apply_mesh(&mut b, &m).unwrap_or_else(|e| panic!("{k}: {e}"));
    for name in &mine {
        assert!(r.left_alone.iter().any(|n| n == name), "{k}: {name}: {r:?}");
    }
    verify_mesh(&mut b, &m).unwrap_or_else(|e| panic!("{k}: {e}"));
    let cleared = draw::clear(&mut *b, &Default::default()).unwrap();
    assert!(
        cleared.removed.iter().all(|n| !mine.contains(&n.as_str())),
        "{k}: {cleared:?}"
    );
    assert_eq!(snapshot(&s), before, "{k}: the user's objects untouched");
    drop(b);
    s.shutdown();
}

fn no_progress(_: draw::Stage) {}

fn apply_mesh(b: &mut Box<dyn Backend>, m: &MeshMaze) -> Result<draw::ApplyReport, DrawError> {
    mesh::apply(&mut **b, m, &ApplyOptions::default(), &mut no_progress)
}

fn apply_copies(b: &mut Box<dyn Backend>, layout: &Layout) -> draw::ApplyReport {
    let d = Drawing::try_from(layout).unwrap();
    draw::apply(&mut **b, &d, &ApplyOptions::default(), &mut no_progress).unwrap()
}

fn verify_mesh(b: &mut Box<dyn Backend>, m: &MeshMaze) -> Result<(), DrawError> {
    mesh::verify(&mut **b, m, &ObjectNames::default())
}

/// The meshes of ours in the scene: (name, parent's alias, colour).
fn meshes(s: &Server) -> Vec<(String, String, [u8; 3])> {
    s.with_sim(|sim| {
        sim.scene
            .objects()
            .filter(|o| parse_mesh_name(&o.alias).is_some())
            .map(|o| {
                let parent = o
                    .parent
                    .map(|p| sim.scene.get(p).unwrap().alias.clone())
                    .unwrap_or_default();
                (o.alias.clone(), parent, o.colour)
            })
            .collect()
    })
}

/// Objects under `Maze` (all depths), the holder included.
fn under_maze(s: &Server) -> usize {
    s.with_sim(|sim| {
        let maze = sim.scene.resolve("Maze").unwrap();
        sim.scene.subtree(maze).len() - 1
    })
}

/// Where `Line` stands, rounded to 0.1 mm.
fn line_home(s: &Server) -> [i64; 3] {
    s.with_sim(|sim| {
        let o = sim.scene.objects().find(|o| o.alias == "Line").unwrap();
        o.position.map(|x| (x * 1e4).round() as i64)
    })
}

fn line_maze_draws_verifies_keeps_replaces_and_clears(kind: Kind) {
    let s = kind.serve(Scene::course(), 8);
    let home = line_home(&s);
    let mut b = s.connect();
    let layout = course_layout(Algorithm::Prim, 9, 9, 42);
    let m = MeshMaze::try_from(&layout).unwrap();
    let r = apply_mesh(&mut b, &m).unwrap();
    assert_eq!(
        (r.meshes, r.pasted, r.reused, r.removed),
        (1, 1, 0, 0),
        "{r:?}"
    );
    assert_eq!(s.idle_fps(), 8, "user's idle rate restored");
    let found = meshes(&s);
    assert_eq!(found.len(), 1);
    assert_eq!(found[0].1, HOLDER);
    assert_eq!(found[0].2, [0, 255, 0], "coloured like the template");
    verify_mesh(&mut b, &m).unwrap();
    // the mesh holds the runs' rectangles, in the Floor frame
    let (triangles, bottom) = s.with_sim(|sim| {
        let o = sim
            .scene
            .objects()
            .find(|o| parse_mesh_name(&o.alias).is_some())
            .unwrap();
        let mesh: &Mesh = o.mesh.as_ref().unwrap();
        (mesh.triangles(), o.bounding_box().0[2])
    });
    assert_eq!(triangles, m.pieces() * 2);
    assert!((bottom - 0.001).abs() < 1e-6);
    // the same layout again: found in place, nothing created
    let again = apply_mesh(&mut b, &m).unwrap();
    assert_eq!(
        (again.pasted, again.reused, again.removed),
        (0, 1, 0),
        "{again:?}"
    );
    // copies replace the meshes, and meshes the copies
    let copies = apply_copies(&mut b, &layout);
    assert_eq!(copies.pasted, 159, "{copies:?}");
    assert!(meshes(&s).is_empty());
    assert_eq!(under_maze(&s), 159, "the copies only: no holder left");
    let other = MeshMaze::try_from(&course_layout(Algorithm::Prim, 9, 9, 7)).unwrap();
    let r = apply_mesh(&mut b, &other).unwrap();
    assert_eq!(r.removed, 159, "{r:?}");
    assert_eq!(s.line_count(), 1, "only the template is left of the copies");
    assert_eq!(under_maze(&s), 2, "the holder and one mesh");
    // another mesh maze replaces this one
    let r = apply_mesh(&mut b, &m).unwrap();
    assert_eq!((r.pasted, r.removed), (1, 1), "{r:?}");
    assert!(matches!(
        verify_mesh(&mut b, &other),
        Err(DrawError::Verify(_))
    ));
    let c = draw::clear(&mut *b, &draw::ClearOptions::default()).unwrap();
    assert!(c.removed.is_empty(), "{:?}", c.removed);
    assert_eq!(c.removed_meshes.len(), 2, "{:?}", c.removed_meshes);
    // the template, which lay on the first line, is back where it stood before
    assert!(
        c.template
            .as_ref()
            .is_some_and(|t| t.contains("back where it stood")),
        "{c:?}"
    );
    assert_eq!(line_home(&s), home);
    assert_eq!(under_maze(&s), 0);
    assert!(meshes(&s).is_empty());
    b.close().unwrap();
    s.shutdown();
}

/// The course maze of `seed` with walls and posts.
fn post_layout(n: u64, seed: u64) -> Layout {
    let mut layout = course_layout(Algorithm::Prim, n, n, seed);
    let grid = Grid::new(n, n).unwrap();
    let maze = passages::decode(grid, &layout.passages).unwrap();
    let options = WallOptions {
        length: length_between_posts(1.0, 0.05),
        posts: Some(0.05),
        ..WallOptions::default()
    };
    into_walls(&mut layout, &maze, &options, true).unwrap();
    layout
}

fn wall_maze_with_posts_draws_boxes_that_copies_replace(kind: Kind) {
    let s = kind.serve(Scene::course_walls(), 8);
    let mut b = s.connect();
    let layout = post_layout(9, 3);
    let m = MeshMaze::try_from(&layout).unwrap();
    // 100 posts of 10 triangles (no bottom) fill one mesh besides the walls'
    assert_eq!(
        m.meshes
            .iter()
            .filter(|x| x.kind == mesh::MeshKind::Posts)
            .count(),
        1
    );
    let r = apply_mesh(&mut b, &m).unwrap();
    assert_eq!(
        (r.meshes, r.pasted, r.posts),
        (m.meshes.len(), m.meshes.len(), 100),
        "{r:?}"
    );
    verify_mesh(&mut b, &m).unwrap();
    let found = meshes(&s);
    assert!(
        found
            .iter()
            .all(|(_, parent, colour)| parent == HOLDER && *colour == [77, 77, 77])
    );
    // respondable and static, like the templates
    s.with_sim(|sim| {
        let o = sim
            .scene
            .objects()
            .find(|o| parse_mesh_name(&o.alias).is_some())
            .unwrap();
        let (min, max) = o.bounding_box();
        assert!(
            (max[2] - min[2] - 0.2).abs() < 1e-6,
            "boxes as high as the walls"
        );
    });
    let copies = apply_copies(&mut b, &layout);
    assert!(copies.pasted > 100, "{copies:?}");
    assert!(meshes(&s).is_empty());
    let r = apply_mesh(&mut b, &m).unwrap();
    assert_eq!(r.removed, copies.pasted, "{r:?}");
    let c = draw::clear(&mut *b, &draw::ClearOptions::default()).unwrap();
    assert!(c.removed.is_empty(), "{:?}", c.removed);
    assert_eq!(c.removed_meshes.len(), m.meshes.len() + 1);
    assert_eq!(under_maze(&s), 0);
    b.close().unwrap();
    s.shutdown();
}

fn verify_finds_a_changed_mesh_and_a_stray_copy(kind: Kind) {
    let s = kind.serve(Scene::course(), 0);
    let mut b = s.connect();
    let m = MeshMaze::try_from(&course_layout(Algorithm::Dfs, 6, 5, 1)).unwrap();
    apply_mesh(&mut b, &m).unwrap();
    s.with_sim(|sim| {
        let h = sim
            .scene
            .objects()
            .find(|o| parse_mesh_name(&o.alias).is_some())
            .unwrap()
            .handle;
        // the mesh stretched by 1 cm along x (its largest x moved): ZeroMQ reads the
        // vertices, the legacy API the box's size (CoppeliaSim gives no box position)
        let mut mesh = sim.scene.get(h).unwrap().mesh.clone().unwrap();
        let right = mesh
            .vertices
            .iter()
            .step_by(3)
            .fold(f32::NEG_INFINITY, |a, &b| a.max(b));
        for v in mesh.vertices.iter_mut().step_by(3) {
            if *v == right {
                *v += 0.01;
            }
        }
        sim.scene.set_mesh(h, mesh).unwrap();
    });
    let Err(DrawError::Verify(problems)) = verify_mesh(&mut b, &m) else {
        panic!("moved vertices went unnoticed")
    };
    let wanted = if kind == Kind::Legacy {
        "bounding box"
    } else {
        "no vertex"
    };
    assert!(
        problems.iter().any(|p| p.to_string().contains(wanted)),
        "{problems:?}"
    );
    // the next apply notices (issue 38: a kept mesh is checked as a new one is) and
    // replaces the changed mesh; a stray copy of the template under Maze is removed
    s.with_sim(|sim| {
        let line = sim.scene.resolve("Line").unwrap();
        let maze = sim.scene.resolve("Maze").unwrap();
        let copy = sim.scene.copy_paste(&[line]).unwrap()[0];
        sim.scene.set_parent(copy, Some(maze), true).unwrap();
    });
    let Err(DrawError::Verify(problems)) = verify_mesh(&mut b, &m) else {
        panic!("a stray copy went unnoticed")
    };
    assert!(
        problems.iter().any(|p| p.to_string().contains("stray")),
        "{problems:?}"
    );
    let r = apply_mesh(&mut b, &m).unwrap();
    assert_eq!((r.removed, r.pasted, r.reused), (2, 1, 0), "{r:?}");
    assert!(
        r.warnings.iter().any(|w| w.starts_with("replaced mesh `")),
        "{r:?}"
    );
    assert_eq!(s.line_count(), 1);
    verify_mesh(&mut b, &m).unwrap();
    b.close().unwrap();
    s.shutdown();
}

/// The meshes come back in one request, the same as one at a time: over ZeroMQ their
/// triangles (one `sim.executeLuaCode`, `vrep_maze::coppelia::lua`, the same as one
/// `sim.getShapeMesh` each), over the legacy API their boxes and poses (one message).
fn every_mesh_is_read_back_in_one_request(kind: Kind) {
    let s = kind.serve(crate::support::layouts::big_course(), 0);
    let mut b = s.connect();
    let m = MeshMaze::try_from(&course_layout(Algorithm::Dfs, 30, 30, 3)).unwrap();
    assert!(m.meshes.len() >= 2, "{} meshes", m.meshes.len());
    apply_mesh(&mut b, &m).unwrap();
    let handles: Vec<i32> = s.with_sim(|sim| {
        sim.scene
            .objects()
            .filter(|o| parse_mesh_name(&o.alias).is_some())
            .map(|o| o.handle)
            .collect()
    });
    assert_eq!(handles.len(), m.meshes.len());
    let before = b.round_trips();
    let together = b.meshes().unwrap().read_shapes(&handles).unwrap();
    let requests = b.round_trips() - before;
    let one_by_one: Vec<_> = handles
        .iter()
        .map(|&h| b.meshes().unwrap().read_shape(h).unwrap())
        .collect();
    assert_eq!(together, one_by_one);
    assert_eq!(requests, 1, "{kind:?}");
    b.close().unwrap();
    s.shutdown();
}

/// Over ZeroMQ, each batch of meshes `apply` creates is made and dressed by one request (one
/// `sim.executeLuaCode`, `vrep_maze::coppelia::lua::create`), priced by its triangles, its
/// vertices and the steps of the search for coincident vertices in what was sent, and no mesh
/// by a `sim.createShape` of its own; the legacy API loads a model.
fn zeromq_makes_each_batch_of_meshes_in_one_request(kind: Kind) {
    use vrep_maze::coppelia::vertex_merge::merge_steps;
    use vrep_maze::sim::cost::Op;
    let s = kind.serve(crate::support::layouts::big_course(), 0);
    let mut b = s.connect();
    let m = MeshMaze::try_from(&course_layout(Algorithm::Dfs, 100, 100, 5)).unwrap();
    assert!(m.meshes.len() > 8, "{} meshes", m.meshes.len());
    s.with_sim(|sim| sim.ledger = Some(vec![]));
    apply_mesh(&mut b, &m).unwrap();
    let ledger = s.with_sim(|sim| sim.ledger.take()).unwrap();
    let ops = || ledger.iter().flat_map(|c| &c.ops);
    let packed: Vec<(usize, usize, u64)> = ops()
        .filter_map(|op| match *op {
            Op::CreateMeshesPacked {
                triangles,
                vertices,
                merge_steps,
            } => Some((triangles, vertices, merge_steps)),
            _ => None,
        })
        .collect();
    let one_by_one = ops()
        .filter(|op| matches!(op, Op::CreateMesh { .. }))
        .count();
    assert_eq!(one_by_one, 0, "{kind:?}");
    if kind == Kind::Legacy {
        assert!(packed.is_empty());
    } else {
        assert_eq!(packed.len(), m.meshes.len().div_ceil(8), "{kind:?}");
        let triangles: usize = m.meshes.iter().map(|x| x.triangles()).sum();
        let vertices: usize = m.meshes.iter().map(|x| x.vertices.len() / 3).sum();
        assert_eq!(packed.iter().map(|p| p.0).sum::<usize>(), triangles);
        assert_eq!(packed.iter().map(|p| p.1).sum::<usize>(), vertices);
        let steps: u64 = m.meshes.iter().map(|x| merge_steps(&x.vertices)).sum();
        assert_eq!(packed.iter().map(|p| p.2).sum::<u64>(), steps);
    }
    b.close().unwrap();
    s.shutdown();
}

/// Cells of 1 cm covered by the rectangles `rects` (floor-frame corners, axis-aligned),
/// counted by their centres.
fn raster(rects: impl Iterator<Item = [[f64; 2]; 4]>) -> std::collections::HashSet<(i64, i64)> {
    let mut cells = std::collections::HashSet::new();
    for corners in rects {
        let (mut x0, mut y0, mut x1, mut y1) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
        for [x, y] in corners {
            (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
        }
        // centres of 1 cm cells strictly inside (a rectangle's edges lie on whole cm here)
        let first = |v: f64| (v * 100.0 - 1e-6).ceil() as i64;
        let last = |v: f64| (v * 100.0 + 1e-6).floor() as i64;
        for i in first(x0 - 0.005 + 1e-9)..=last(x1 - 0.005) {
            for j in first(y0 - 0.005 + 1e-9)..=last(y1 - 0.005) {
                cells.insert((i, j));
            }
        }
    }
    cells
}

#[test]
fn meshes_of_every_golden_line_layout_cover_exactly_the_copies() {
    let mut checked = 0;
    for entry in std::fs::read_dir("mazes").unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "json") {
            continue;
        }
        let layout = read_layout(&path).unwrap();
        if layout.style != vrep_maze::layout::Style::Lines || layout.grid.rotation != 0.0 {
            continue;
        }
        let m = MeshMaze::try_from(&layout).unwrap();
        let by_mesh = raster(m.meshes.iter().flat_map(|x| &x.pieces).map(|p| p.corners));
        let (l, w) = (layout.line.length / 2.0, layout.line.width / 2.0);
        let by_copies = raster(layout.segments.iter().map(|s| {
            let (c, si) = (s.yaw.cos().round(), s.yaw.sin().round());
            let (dx, dy) = (l * c.abs() + w * si.abs(), l * si.abs() + w * c.abs());
            [
                [s.x - dx, s.y - dy],
                [s.x + dx, s.y - dy],
                [s.x + dx, s.y + dy],
                [s.x - dx, s.y + dy],
            ]
        }));
        assert_eq!(by_mesh.len(), by_copies.len(), "{}", path.display());
        assert!(
            by_mesh == by_copies,
            "{}: the meshes cover other cells",
            path.display()
        );
        assert!(!by_mesh.is_empty() || layout.segments.is_empty());
        checked += 1;
    }
    assert!(checked >= 15, "{checked} golden line layouts");
}

/// To a simulator on another machine the legacy mesh model is sent with `simxTransferFile`
/// under a `REMOTE_API_TEMPFILE_` name ending in `.simmodel.xml`, loaded and erased: the
/// maze draws and verifies, and the server's folder keeps no file.
#[test]
fn legacy_sends_the_mesh_model_with_transfer_file_to_a_remote_simulator() {
    let s = Kind::Legacy.serve(Scene::course(), 0);
    let dir = tempfile::tempdir().unwrap();
    s.with_sim(|sim| sim.temp_dir = dir.path().to_path_buf());
    let timeout = std::time::Duration::from_secs(10);
    let mut b: Box<dyn Backend> = Box::new(
        vrep_maze::legacy::LegacyBackend::connect("127.0.0.1", s.addr().port(), timeout)
            .unwrap()
            .transferring_models(),
    );
    let m = MeshMaze::try_from(&course_layout(Algorithm::Prim, 9, 9, 42)).unwrap();
    let r = apply_mesh(&mut b, &m).unwrap();
    assert_eq!((r.meshes, r.pasted), (1, 1), "{r:?}");
    verify_mesh(&mut b, &m).unwrap();
    assert_eq!(meshes(&s).len(), 1);
    assert_eq!(
        std::fs::read_dir(dir.path()).unwrap().count(),
        0,
        "the transferred model is erased"
    );
    b.close().unwrap();
    s.shutdown();
}

fn ctrl_c_stops_before_the_next_mesh_with_the_idle_rate_restored(kind: Kind) {
    use std::sync::Arc;
    use std::sync::atomic::AtomicBool;
    let s = kind.serve(crate::support::layouts::big_course(), 8);
    let mut b = s.connect();
    let m = MeshMaze::try_from(&course_layout(Algorithm::Prim, 20, 20, 1)).unwrap();
    let opts = ApplyOptions {
        interrupt: Some(Arc::new(AtomicBool::new(true))),
        ..Default::default()
    };
    let result = mesh::apply(&mut *b, &m, &opts, &mut no_progress);
    assert!(
        matches!(result, Err(DrawError::Interrupted { placed: 0, total }) if total == m.pieces()),
        "{result:?}"
    );
    assert_eq!(s.idle_fps(), 8, "user's idle rate restored");
    assert!(meshes(&s).is_empty(), "nothing created after the interrupt");
    // the same apply again finishes the maze
    apply_mesh(&mut b, &m).unwrap();
    assert_eq!(meshes(&s).len(), m.meshes.len());
    b.close().unwrap();
    s.shutdown();
}
