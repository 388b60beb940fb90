//! Issue 38's smaller rows, each as a person meets it on `serve`: a raised floor (row 9).

use vrep_maze::coppelia::HANDLE_WORLD;
use vrep_maze::draw::{self, ApplyOptions, ClearOptions};
use vrep_maze::sim::Scene;

use crate::support::backend::Kind;
use crate::support::backend_tests;
use crate::support::layouts::drawing;

backend_tests!(a_raised_floor_puts_line_back_where_it_stood_and_says_so);

/// Row 9: `Floor` raised to z 0.5 leaves the course's `Line` below it. Applied and cleared,
/// `Line` goes back exactly where it stood, and `clear` says that, not that it put it "below
/// the floor" where an earlier maze had left it.
fn a_raised_floor_puts_line_back_where_it_stood_and_says_so(kind: Kind) {
    let k = kind.name();
    let s = kind.serve(Scene::course(), 0);
    let (line, before) = s.with_sim(|sim| {
        let floor = sim.scene.resolve("Floor").unwrap();
        sim.scene
            .set_position(floor, HANDLE_WORLD, [0.0, 0.0, 0.5])
            .unwrap();
        let line = sim.scene.resolve("Line").unwrap();
        (line, sim.scene.pose(line, HANDLE_WORLD).unwrap())
    });
    let mut b = s.connect();
    draw::apply(
        &mut *b,
        &drawing(4, 1),
        &ApplyOptions::default(),
        &mut |_| {},
    )
    .unwrap_or_else(|e| panic!("{k}: {e}"));
    let c = draw::clear(&mut *b, &ClearOptions::default()).unwrap_or_else(|e| panic!("{k}: {e}"));
    assert_eq!(
        c.template.as_deref(),
        Some("put `Line` back where it stood before the first apply"),
        "{k}"
    );
    let after = s.with_sim(|sim| sim.scene.pose(line, HANDLE_WORLD).unwrap());
    for (a, b) in before
        .0
        .iter()
        .chain(&before.1)
        .zip(after.0.iter().chain(&after.1))
    {
        assert!((a - b).abs() < 1e-6, "{k}: {before:?} then {after:?}");
    }
    drop(b);
    s.shutdown();
}
