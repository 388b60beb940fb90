//! `draw::Session`: one connection, many jobs. A training loop's resets (a new mesh maze,
//! then another, then a wall maze, then clear) each leave the scene as a separate run would:
//! the maze verified, the user's idle rate and object count as before, and the session
//! still usable; after `close` every call says so.

use vrep_maze::draw::{ApplyOptions, ClearOptions, DrawMode, Job, Picture, Session};
use vrep_maze::generate::Algorithm;
use vrep_maze::layout::Layout;
use vrep_maze::sim::Scene;

use crate::support::backend::Kind;
use crate::support::backend_tests;
use crate::support::layouts::course_layout;

backend_tests!(one_session_replaces_mazes_as_separate_runs_would);

/// `layout` drawn as meshes, nothing created, the scene not saved.
fn mesh_job(layout: &Layout) -> Job<'_> {
    Job {
        layout,
        picture: Picture::of(layout, DrawMode::Mesh).unwrap(),
        options: ApplyOptions::default(),
        create_missing: false,
        save_scene: None,
    }
}

fn one_session_replaces_mazes_as_separate_runs_would(kind: Kind) {
    let k = kind.name();
    let s = kind.serve(Scene::course(), 8);
    let objects = |s: &crate::support::backend::Server| s.snapshot().len();
    let before = objects(&s);
    let mut session = Session::new(s.connect());
    let mut counts = vec![];
    let mut user_fps = 8;
    for seed in [1, 2, 3, 4] {
        let layout = course_layout(Algorithm::Prim, 9, 9, seed);
        let job = mesh_job(&layout);
        let r = session.apply(&job, &mut |_| {}).unwrap();
        assert_eq!(r.drawn.meshes, 1, "{k}: {r:?}");
        assert_eq!(
            s.idle_fps(),
            user_fps,
            "{k}: the user's rate restored after each call"
        );
        counts.push(objects(&s));
        // the scene changed between calls (the user moved the idle rate): surveyed again
        user_fps -= 1;
        s.set_idle_fps(user_fps);
        session
            .verify(&job.picture, &job.options.names)
            .unwrap_or_else(|e| panic!("{k}: {e}"));
        assert_eq!(s.idle_fps(), user_fps, "{k}");
    }
    assert!(
        counts.windows(2).all(|w| w[0] == w[1]),
        "{k}: object count flat over resets: {counts:?}"
    );
    let cleared = session.clear(&ClearOptions::default()).unwrap();
    assert!(!cleared.removed_meshes.is_empty(), "{k}: {cleared:?}");
    assert_eq!(objects(&s), before, "{k}: clear leaves the scene as it was");
    session.close().unwrap();
    assert!(session.is_closed());
    let e = session.clear(&ClearOptions::default()).unwrap_err();
    assert_eq!(e.to_string(), "the session is closed: connect again", "{k}");
}

backend_tests!(a_call_that_lost_the_connection_leaves_the_next_to_connect_again);

/// A session opened with a way to reconnect: the call that meets a dead simulator fails with
/// the connection lost, and the next connects again and draws on the new simulator (here a
/// second server, as a restarted CoppeliaSim would be).
fn a_call_that_lost_the_connection_leaves_the_next_to_connect_again(kind: Kind) {
    let k = kind.name();
    let short = std::time::Duration::from_millis(500);
    let (first, again) = (
        kind.serve(Scene::course(), 0),
        kind.serve(Scene::course(), 0),
    );
    let port = again.addr().port();
    let backend = kind.connect(first.addr().port(), short).unwrap();
    let reconnect = Box::new(move || kind.connect(port, short));
    let mut session = Session::reconnecting(backend, reconnect);
    let layout = course_layout(Algorithm::Prim, 9, 9, 1);
    let job = mesh_job(&layout);
    session.apply(&job, &mut |_| {}).unwrap();
    first.shutdown();
    let lost = session.apply(&job, &mut |_| {}).unwrap_err();
    assert!(lost.lost_connection(), "{k}: {lost}");
    let r = session
        .apply(&job, &mut |_| {})
        .unwrap_or_else(|e| panic!("{k}: {e}"));
    assert_eq!((r.drawn.meshes, r.drawn.pasted), (1, 1), "{k}: {r:?}");
    assert!(again.snapshot().len() > Scene::course().len(), "{k}");
    session.close().unwrap();
    again.shutdown();
}
