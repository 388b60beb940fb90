//! apply over the legacy backend only: its round-trip bound on a big maze, and scenes
//! named the CoppeliaSim 4.x hash way (`Line#3`). The scenarios every backend shares are
//! in `draw`.

use vrep_maze::draw::{self, ApplyOptions, ObjectNames};
use vrep_maze::sim::{NamingMode, Scene};

use crate::support::backend::Kind;
use crate::support::layouts::drawing;

fn no_progress(_: draw::Stage) {}

#[test]
fn legacy_apply_round_trips_30x30() {
    let s = Kind::Legacy.serve(crate::support::layouts::big_course(), 0);
    let mut sc = s.connect();
    let d = drawing(30, 7);
    let r = draw::apply(&mut *sc, &d, &ApplyOptions::default(), &mut no_progress).unwrap();
    assert_eq!(r.pieces, 1798);
    let bound = Kind::Legacy.apply_round_trip_bound(30).unwrap();
    assert_eq!(bound, 20);
    assert!(
        r.round_trips <= bound,
        "30x30 took {} round trips",
        r.round_trips
    );
    drop(sc);
    s.shutdown();
}

#[test]
fn legacy_apply_works_with_hash_names_and_repairs_parentless_copies() {
    let mut scene = Scene::course();
    scene.naming = NamingMode::Hash;
    let line = scene.resolve("Line").unwrap();
    // an interrupted run: copies pasted but never re-parented
    for _ in 0..3 {
        scene.copy_paste(&[line]).unwrap();
    }
    let s = Kind::Legacy.serve(scene, 0);
    let mut sc = s.connect();
    let d = drawing(2, 5);
    let r = draw::apply(&mut *sc, &d, &ApplyOptions::default(), &mut no_progress).unwrap();
    assert_eq!((r.reused, r.pasted, r.removed), (3, d.pieces.len() - 4, 0));
    let names: Vec<String> =
        s.with_sim(|sim| sim.scene.objects().map(|o| o.name.clone()).collect());
    assert!(names.iter().any(|n| n == "Line#3"), "{names:?}");
    draw::verify(&mut *sc, &d, &ObjectNames::default()).unwrap();
    drop(sc);
    s.shutdown();
}
