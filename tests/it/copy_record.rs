//! The record of this tool's copies (`draw::record`, string signal `vrep-maze.copies`): a
//! re-apply over ZeroMQ reads no alias per child of `Maze` when the scene holds the record,
//! both APIs keep it true (exactly the copies in the maze), and a forged entry never makes a
//! user's object of another type ours.

use vrep_maze::draw::record::CopyRecord;
use vrep_maze::draw::signals::COPIES;
use vrep_maze::draw::{self, ApplyOptions, Drawing};
use vrep_maze::sim::{NewObject, ObjectType, Scene};

use crate::support::backend::{Kind, Server};
use crate::support::layouts::{big_course, drawing};

/// Applies `d` over a fresh connection; the round trips it took.
fn apply_fresh(s: &Server, d: &Drawing) -> usize {
    let mut b = s.connect();
    let r = draw::apply(&mut *b, d, &ApplyOptions::default(), &mut |_| {}).unwrap();
    b.close().unwrap();
    r.round_trips
}

/// The scene's record, parsed.
fn record(s: &Server) -> CopyRecord {
    s.with_sim(|sim| {
        let text = sim.string_signals.get(COPIES.name).cloned();
        CopyRecord::parse(&String::from_utf8(text.expect("a record")).unwrap())
    })
}

/// Handles of the copies of `Line` (not the template) under `Maze`.
fn copies(s: &Server) -> Vec<i32> {
    s.with_sim(|sim| {
        let maze = sim.scene.resolve("Maze").unwrap();
        let line = sim.scene.resolve("Line").unwrap();
        let mut h: Vec<i32> = sim
            .scene
            .objects()
            .filter(|o| o.alias == "Line" && o.parent == Some(maze) && o.handle != line)
            .map(|o| o.handle)
            .collect();
        h.sort_unstable();
        h
    })
}

/// The record holds every copy in the maze, as a copy of `Line`, and no other object of
/// the scene (a removed copy's handle may stay until the next run: it names nothing).
fn assert_record_is_the_copies(s: &Server, what: &str) {
    let mut r = record(s);
    r.retain(|h| s.with_sim(|sim| sim.scene.get(h).is_ok()));
    let c = copies(s);
    assert_eq!(r.len(), c.len(), "{what}: {}", r.format());
    assert!(
        c.iter().all(|h| r.get(*h) == Some("Line")),
        "{what}: {}",
        r.format()
    );
}

/// Over ZeroMQ, a re-apply over a maze this tool drew knows its copies from the record: a
/// scene without the record (an older version's maze) costs one or two more calls per
/// copy (its alias, and its size, since it is named like a copy), and that run writes the
/// record, so the next pays no more.
#[test]
fn a_reapply_over_our_maze_reads_no_alias_per_child() {
    for kind in [Kind::Zmq1, Kind::Zmq2] {
        let k = kind.name();
        let s = kind.serve(Scene::course(), 0);
        let d = drawing(9, 42);
        apply_fresh(&s, &d);
        assert_record_is_the_copies(&s, k);
        let with_record = apply_fresh(&s, &d);
        s.with_sim(|sim| sim.string_signals.remove(COPIES.name));
        let without = apply_fresh(&s, &d);
        let children = copies(&s).len();
        assert!(children > 100, "{k}: {children}");
        // at most an alias, a size and a colour a copy (the one tree call that shows
        // nothing below the copies spares one per copy), the template's size and colour once
        assert!(
            without >= with_record + children && without <= with_record + 3 * children + 5,
            "{k}: {without} round trips without the record, {with_record} with it, {children} copies"
        );
        assert_record_is_the_copies(&s, k);
        assert_eq!(apply_fresh(&s, &d), with_record, "{k}: the record is back");
        // a smaller maze removes copies; the next run drops their handles from the record
        apply_fresh(&s, &drawing(5, 1));
        assert_record_is_the_copies(&s, k);
        apply_fresh(&s, &drawing(5, 1));
        assert_eq!(
            record(&s).len(),
            copies(&s).len(),
            "{k}: {}",
            record(&s).format()
        );
        s.shutdown();
    }
}

/// The legacy API reads names in a batch and needs no record, but keeps it true for a
/// later ZeroMQ run: its pastes are recorded, its removals dropped.
#[test]
fn the_legacy_api_keeps_the_record_true() {
    let s = Kind::Legacy.serve(big_course(), 0);
    apply_fresh(&s, &drawing(9, 42));
    assert_record_is_the_copies(&s, "9x9");
    apply_fresh(&s, &drawing(12, 3));
    assert_record_is_the_copies(&s, "12x12 over it");
    apply_fresh(&s, &drawing(4, 3));
    assert_record_is_the_copies(&s, "4x4 over it");
    s.shutdown();
}

/// A record entry naming a user's dummy under `Maze` (forged, or a stale handle) does not
/// make it a copy: it is not of the template's type, so it is read, left alone and named.
#[test]
fn a_recorded_handle_of_another_type_is_still_the_users() {
    for kind in Kind::ALL {
        let k = kind.name();
        let mut scene = Scene::course();
        let maze = scene.resolve("Maze").unwrap();
        let sensor = scene.add(
            "MySensor",
            NewObject {
                kind: ObjectType::Dummy,
                parent: Some(maze),
                position: [1.0, 1.0, 0.3],
                orientation: [0.0; 3],
                size: [0.01; 3],
                colour: [0; 3],
            },
        );
        let s = kind.serve(scene, 0);
        let forged = format!("Line:{sensor}");
        s.with_sim(|sim| {
            sim.string_signals
                .insert(COPIES.name.into(), forged.into_bytes())
        });
        let mut b = s.connect();
        let r = draw::apply(
            &mut *b,
            &drawing(4, 1),
            &ApplyOptions::default(),
            &mut |_| {},
        )
        .unwrap_or_else(|e| panic!("{k}: {e}"));
        assert!(
            r.left_alone.iter().any(|n| n == "MySensor"),
            "{k}: {:?}",
            r.left_alone
        );
        b.close().unwrap();
        assert!(s.with_sim(|sim| sim.scene.get(sensor).is_ok()), "{k}: kept");
        assert_eq!(record(&s).get(sensor), None, "{k}: dropped from the record");
        s.shutdown();
    }
}
