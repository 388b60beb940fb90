//! "Verified" stays true when the user edits what we drew (issue 38): a mesh or copy that
//! `apply` keeps is checked as a new one is, and replaced when it differs; `apply` and the
//! verification `inspect --layout` makes agree; what looks like ours but is not stays, named.

use vrep_maze::draw::mesh::{self, MeshMaze, parse_mesh_name};
use vrep_maze::draw::{
    self, ApplyOptions, ApplyReport, Backend, ClearOptions, DrawError, Drawing, ObjectNames,
};
use vrep_maze::generate::Algorithm;
use vrep_maze::sim::{NewObject, ObjectType, Scene, Simulator};

use crate::support::backend::{Kind, Server};
use crate::support::backend_tests;
use crate::support::layouts::course_layout;

backend_tests!(
    a_scaled_moved_or_recoloured_mesh_is_replaced_not_kept,
    a_hidden_mesh_is_replaced_and_one_moved_to_the_root_is_named,
    a_scaled_or_recoloured_copy_is_pasted_anew,
    a_copy_with_the_users_child_is_never_reused_moved_or_removed,
);

fn no_progress(_: draw::Stage) {}

fn apply_mesh(b: &mut Box<dyn Backend>, m: &MeshMaze) -> Result<ApplyReport, DrawError> {
    mesh::apply(&mut **b, m, &ApplyOptions::default(), &mut no_progress)
}

fn verify_mesh(b: &mut Box<dyn Backend>, m: &MeshMaze) -> Result<(), DrawError> {
    mesh::verify(&mut **b, m, &ObjectNames::default())
}

/// The handle of the first mesh of ours in the scene.
fn a_mesh(sim: &Simulator) -> i32 {
    sim.scene
        .objects()
        .find(|o| parse_mesh_name(&o.alias).is_some())
        .unwrap()
        .handle
}

/// A 6x5 line maze drawn as meshes; `edit` then changes the scene; the verification finds
/// what `edit` changed (`seen`), the next apply replaces the mesh and says why, and the scene
/// verifies again.
fn edited_then_applied(kind: Kind, what: &str, seen: &str, edit: impl Fn(&mut Simulator, i32)) {
    let k = kind.name();
    let s = kind.serve(Scene::course(), 0);
    let mut b = s.connect();
    let m = MeshMaze::try_from(&course_layout(Algorithm::Dfs, 6, 5, 1)).unwrap();
    apply_mesh(&mut b, &m).unwrap();
    s.with_sim(|sim| {
        let h = a_mesh(sim);
        edit(sim, h)
    });
    let Err(DrawError::Verify(problems)) = verify_mesh(&mut b, &m) else {
        panic!("{k}: a {what} mesh verified")
    };
    assert!(
        problems.iter().any(|p| p.to_string().contains(seen)),
        "{k} {what}: {problems:?}"
    );
    let r = apply_mesh(&mut b, &m).unwrap();
    assert_eq!(
        (r.reused, r.pasted, r.removed),
        (0, 1, 1),
        "{k} {what}: {r:?}"
    );
    let why = r.warnings.iter().find(|w| w.starts_with("replaced mesh `"));
    assert!(
        why.is_some_and(|w| w.contains(seen)),
        "{k} {what}: {:?}",
        r.warnings
    );
    verify_mesh(&mut b, &m).unwrap();
    // and kept, unchanged, the next time
    let r = apply_mesh(&mut b, &m).unwrap();
    assert_eq!(
        (r.reused, r.pasted, r.removed),
        (1, 0, 0),
        "{k} {what}: {r:?}"
    );
    assert!(r.warnings.is_empty(), "{k} {what}: {:?}", r.warnings);
    b.close().unwrap();
    s.shutdown();
}

/// Row 1: scaled by 5 %, moved 5 cm, recoloured: each replaced, on every API that reads it
/// (the legacy API reads a mesh's box and pose, not its colour).
fn a_scaled_moved_or_recoloured_mesh_is_replaced_not_kept(kind: Kind) {
    let box_or_vertex = if kind == Kind::Legacy {
        "bounding box"
    } else {
        "no vertex"
    };
    edited_then_applied(kind, "scaled", box_or_vertex, |sim, h| {
        sim.scene.scale(h, [1.05; 3]).unwrap();
    });
    edited_then_applied(kind, "moved", "not the floor's", |sim, h| {
        let floor = sim.scene.resolve("Floor").unwrap();
        sim.scene.set_position(h, floor, [0.05, 0.0, 0.0]).unwrap();
    });
    if kind != Kind::Legacy {
        edited_then_applied(kind, "recoloured", "is coloured", |sim, h| {
            sim.scene.set_colour(h, [255, 0, 0]).unwrap();
        });
    }
}

/// Row 8: a mesh hidden (visibility layer 0) is replaced over ZeroMQ, which reads layers; a
/// mesh the user moved to the scene root is theirs: a new one is made under the holder, the
/// moved one is left where it is and named, by `apply` on every API.
fn a_hidden_mesh_is_replaced_and_one_moved_to_the_root_is_named(kind: Kind) {
    if kind != Kind::Legacy {
        edited_then_applied(kind, "hidden", "visibility layer 0 (hidden)", |sim, h| {
            sim.scene.set_layer(h, 0).unwrap();
        });
    }
    let k = kind.name();
    let s: Server = kind.serve(Scene::course(), 0);
    let mut b = s.connect();
    let m = MeshMaze::try_from(&course_layout(Algorithm::Dfs, 6, 5, 1)).unwrap();
    apply_mesh(&mut b, &m).unwrap();
    let moved = s.with_sim(|sim| {
        let h = a_mesh(sim);
        sim.scene.set_parent(h, None, true).unwrap();
        sim.scene.get(h).unwrap().alias.clone()
    });
    let r = apply_mesh(&mut b, &m).unwrap();
    assert_eq!((r.reused, r.pasted, r.removed), (0, 1, 0), "{k}: {r:?}");
    let named = r
        .warnings
        .iter()
        .any(|w| w.starts_with(&format!("`{moved}` at the scene root")));
    assert!(named, "{k}: {:?}", r.warnings);
    verify_mesh(&mut b, &m).unwrap();
    let at_root = s.with_sim(|sim| {
        sim.scene
            .children(None)
            .filter(|&h| sim.scene.get(h).unwrap().alias == moved)
            .count()
    });
    assert_eq!(at_root, 1, "{k}: the user's mesh stays at the root");
    b.close().unwrap();
    s.shutdown();
}

/// A user's edit of the object it is given, made in the emulated scene.
type Edit = fn(&mut Simulator, i32);

fn apply_copies(b: &mut Box<dyn Backend>, d: &Drawing) -> ApplyReport {
    draw::apply(&mut **b, d, &ApplyOptions::default(), &mut no_progress).unwrap()
}

/// A copy of `Line` under `Maze` (the maze's fourth child): its handle and alias.
fn a_copy(sim: &Simulator) -> (i32, String) {
    let maze = sim.scene.resolve("Maze").unwrap();
    let h = sim.scene.children(Some(maze)).nth(3).unwrap();
    (h, sim.scene.get(h).unwrap().name.clone())
}

/// Row 2: a drawn copy scaled 1.3x (every API), recoloured red or hidden (ZeroMQ, which
/// reads colours and layers): the verification names it, the next apply removes it and pastes a new one,
/// saying so, and the scene verifies.
fn a_scaled_or_recoloured_copy_is_pasted_anew(kind: Kind) {
    let k = kind.name();
    let d = Drawing::try_from(&course_layout(Algorithm::Dfs, 6, 5, 1)).unwrap();
    let mut edits: Vec<(&str, &str, Edit)> = vec![(
        "scaled",
        " m, the template ",
        |sim: &mut Simulator, h: i32| sim.scene.scale(h, [1.3, 1.3, 1.0]).unwrap(),
    )];
    if kind != Kind::Legacy {
        edits.push(("recoloured", "is coloured (1.00, 0.00, 0.00)", |sim, h| {
            sim.scene.set_colour(h, [255, 0, 0]).unwrap()
        }));
        edits.push(("hidden", "is on visibility layer 0 (hidden)", |sim, h| {
            sim.scene.set_layer(h, 0).unwrap()
        }));
    }
    for (what, seen, edit) in edits {
        let s = kind.serve(Scene::course(), 0);
        let mut b = s.connect();
        apply_copies(&mut b, &d);
        let (copy, name) = s.with_sim(|sim| {
            let (h, name) = a_copy(sim);
            edit(sim, h);
            (h, name)
        });
        let Err(DrawError::Verify(problems)) = draw::verify(&mut *b, &d, &ObjectNames::default())
        else {
            panic!("{k}: a {what} copy verified")
        };
        assert!(
            problems.iter().any(|p| p.to_string().contains(seen)),
            "{k} {what}: {problems:?}"
        );
        let r = apply_copies(&mut b, &d);
        assert_eq!((r.removed, r.pasted), (1, 1), "{k} {what}: {r:?}");
        let said = r.warnings.iter().any(|w| {
            w.starts_with("replaced 1 copy(ies) that no longer looked like their template")
                && w.contains(seen)
        });
        assert!(said, "{k} {what}: {:?} ({name})", r.warnings);
        assert!(s.with_sim(|sim| sim.scene.get(copy).is_err()), "{k} {what}");
        draw::verify(&mut *b, &d, &ObjectNames::default()).unwrap();
        b.close().unwrap();
        s.shutdown();
    }
}

/// Row 3: the user's dummy under a drawn copy: `apply` neither reuses, moves nor removes
/// that copy (it names it as left alone and pastes another in its place), `clear` leaves
/// it and its child where they are, and the scene verifies in between.
fn a_copy_with_the_users_child_is_never_reused_moved_or_removed(kind: Kind) {
    let k = kind.name();
    let d = Drawing::try_from(&course_layout(Algorithm::Dfs, 6, 5, 1)).unwrap();
    let other = Drawing::try_from(&course_layout(Algorithm::Dfs, 6, 5, 2)).unwrap();
    let s = kind.serve(Scene::course(), 0);
    let mut b = s.connect();
    apply_copies(&mut b, &d);
    let (copy, name, dummy) = s.with_sim(|sim| {
        let (h, name) = a_copy(sim);
        let dummy = sim.scene.add(
            "Sensor",
            NewObject {
                kind: ObjectType::Dummy,
                parent: Some(h),
                position: [0.0; 3],
                orientation: [0.0; 3],
                size: [0.01; 3],
                colour: [0, 0, 0],
            },
        );
        (h, name, dummy)
    });
    let pose = |s: &Server| s.with_sim(|sim| sim.scene.world(copy).unwrap());
    let before = pose(&s);
    // another maze: every copy moves but this one
    // named as the API names it: `Line3` (legacy), `/Line[4]` (ZeroMQ, by its alias)
    let named = |left_alone: &[String]| {
        left_alone.len() == 1 && (left_alone[0] == name || left_alone[0].starts_with("/Line["))
    };
    let r = apply_copies(&mut b, &other);
    assert!(named(&r.left_alone), "{k}: {r:?}");
    assert_eq!(r.pasted, 1, "{k}: a copy in its stead");
    draw::verify(&mut *b, &other, &ObjectNames::default()).unwrap();
    assert_eq!(pose(&s), before, "{k}: the copy with a child moved");
    let r = draw::clear(&mut *b, &ClearOptions::default()).unwrap();
    assert!(named(&r.left_alone), "{k}: {r:?}");
    s.with_sim(|sim| {
        assert_eq!(sim.scene.get(dummy).unwrap().parent, Some(copy), "{k}");
    });
    assert_eq!(pose(&s), before, "{k}: the copy with a child moved");
    b.close().unwrap();
    s.shutdown();
}
