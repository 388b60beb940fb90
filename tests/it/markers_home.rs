//! `clear` puts `Start` and `End` back where they stood before the first apply (issue 41,
//! item 4), from the record `apply` keeps in the scene's signals (`draw::markers_home`);
//! a scene without the record (saved and loaded again, drawn by an older version) keeps
//! its markers where they are, and the report says so.

use vrep_maze::draw::signals::{END_HOME, START_HOME};
use vrep_maze::draw::{self, ApplyOptions, ClearOptions};
use vrep_maze::generate::Algorithm;
use vrep_maze::sim::Scene;

use crate::support::backend::{Kind, Server};
use crate::support::backend_tests;
use crate::support::layouts::drawing_with;

backend_tests!(
    clear_puts_the_markers_back_from_their_record,
    without_a_record_clear_leaves_the_markers_and_says_so,
);

/// `Start` and `End` as (alias, parent, pose) in the server's snapshot.
fn markers(s: &Server) -> Vec<(String, Option<String>, [i64; 6])> {
    s.snapshot()
        .into_iter()
        .filter(|o| o.0 == "Start" || o.0 == "End")
        .collect()
}

fn clear_puts_the_markers_back_from_their_record(kind: Kind) {
    let k = kind.name();
    let s = kind.serve(Scene::course(), 0);
    let before = markers(&s);
    let mut b = s.connect();
    // two mazes: the record is of the first apply's markers, not the second's
    for (n, seed) in [(5, 2), (7, 3)] {
        let d = drawing_with(Algorithm::Dfs, n, seed);
        draw::apply(&mut *b, &d, &ApplyOptions::default(), &mut |_| {}).unwrap();
        assert_ne!(
            markers(&s),
            before,
            "{k}: the {n} x {n} maze moved no marker"
        );
    }
    let dry = ClearOptions {
        dry_run: true,
        ..Default::default()
    };
    let r = draw::clear(&mut *b, &dry).unwrap();
    assert_eq!(
        r.markers.as_deref(),
        Some("would put `Start` and `End` back where they stood before the first apply"),
        "{k}"
    );
    assert_ne!(markers(&s), before, "{k}: a dry run moved the markers");
    let r = draw::clear(&mut *b, &ClearOptions::default()).unwrap();
    assert_eq!(
        r.markers.as_deref(),
        Some("put `Start` and `End` back where they stood before the first apply"),
        "{k}"
    );
    assert_eq!(markers(&s), before, "{k}");
    // the record is gone with the clear
    let left = s.with_sim(|sim| {
        START_HOME
            .iter()
            .chain(&END_HOME)
            .filter(|n| sim.int_signals.contains_key(**n))
            .count()
    });
    assert_eq!(left, 0, "{k}");
    drop(b);
    s.shutdown();
}

fn without_a_record_clear_leaves_the_markers_and_says_so(kind: Kind) {
    let k = kind.name();
    let s = kind.serve(Scene::course(), 0);
    let mut b = s.connect();
    let d = drawing_with(Algorithm::Dfs, 5, 2);
    draw::apply(&mut *b, &d, &ApplyOptions::default(), &mut |_| {}).unwrap();
    // as a scene saved and loaded again: no signals
    let recorded = |s: &Server| {
        s.with_sim(|sim| {
            START_HOME
                .iter()
                .chain(&END_HOME)
                .filter(|n| sim.int_signals.contains_key(**n))
                .count()
        })
    };
    assert_eq!(recorded(&s), 14, "{k}");
    s.with_sim(|sim| {
        for name in START_HOME.iter().chain(&END_HOME) {
            sim.int_signals.remove(*name);
        }
    });
    // an apply over that maze does not take its markers' places for their home
    let e = drawing_with(Algorithm::Dfs, 7, 3);
    draw::apply(&mut *b, &e, &ApplyOptions::default(), &mut |_| {}).unwrap();
    assert_eq!(recorded(&s), 0, "{k}: recorded the earlier maze's markers");
    let drawn = markers(&s);
    let r = draw::clear(&mut *b, &ClearOptions::default()).unwrap();
    let said = r.markers.unwrap_or_default();
    assert!(
        said.starts_with("no record of where `Start` and `End` stood before the first apply")
            && said.ends_with(": left where they are"),
        "{k}: {said}"
    );
    assert_eq!(markers(&s), drawn, "{k}: the markers moved");
    drop(b);
    s.shutdown();
}
