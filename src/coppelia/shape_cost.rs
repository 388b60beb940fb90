//! The modeled server work of mesh shapes on a real CoppeliaSim 4.5.1: creating one, merging
//! several, removing one. Pure functions; the emulated servers sleep what they return when
//! their timing is realistic. Every figure cites `../shared/spec/real-coppeliasim-4.5.1.md`,
//! "One object instead of thousands: meshes and XML models".
//!
//! `sim.createMeshShape` of one mesh of n rectangles (4 vertices, 2 triangles each), server
//! time: 100: 24 ms; 250: 121 ms; 500: 148 ms; 1,000: 428 ms; 2,000: 882 ms; 4,000: 2.2 s;
//! 20,000: 6.1 to 9.2 s (modeled at the middle, 7.65 s). The model goes through these points,
//! linearly between them, from the origin to the first, and beyond the last with the slope
//! from 4,000 to 20,000 (the figures are not one smooth curve: 250 took longer per rectangle
//! than 500).
//!
//! Not reproduced: "20,000 rectangles as 40 meshes of 500 took 2.44 s in all" from a client,
//! 61 ms a mesh, where one mesh of 500 alone took 148 ms. Both were measured; the model keeps
//! the per-mesh row, so many meshes cost more here (40 x 148 ms = 5.9 s) than in that run.
//!
//! `sim.groupShapes(handles, true)` merged those 40 meshes (20,000 rectangles) in 2.36 s:
//! 118 µs per rectangle merged. Removing a mesh of any size took under 1 ms: it costs what
//! removing any one object costs (`crate::coppelia::cost`).

use std::time::Duration;

/// (rectangles, seconds) of `sim.createMeshShape`, in order.
const CREATE: [(f64, f64); 7] = [
    (100.0, 0.024),
    (250.0, 0.121),
    (500.0, 0.148),
    (1_000.0, 0.428),
    (2_000.0, 0.882),
    (4_000.0, 2.2),
    (20_000.0, 7.65),
];

/// Seconds per rectangle merged by `sim.groupShapes` (2.36 s for 20,000).
const MERGE_PER_RECTANGLE: f64 = 2.36 / 20_000.0;

/// Server time of `sim.createMeshShape` for a mesh of `triangles` triangles (two per
/// rectangle).
pub fn create_mesh(triangles: usize) -> Duration {
    let n = triangles as f64 / 2.0;
    let mut from = (0.0, 0.0);
    for &to in &CREATE {
        if n <= to.0 {
            return seconds(from.1 + (to.1 - from.1) * (n - from.0) / (to.0 - from.0));
        }
        from = to;
    }
    let (a, b) = (CREATE[CREATE.len() - 2], CREATE[CREATE.len() - 1]);
    seconds(b.1 + (b.1 - a.1) / (b.0 - a.0) * (n - b.0))
}

/// Server time of `sim.groupShapes` merging shapes of `triangles` triangles in all.
pub fn merge_shapes(triangles: usize) -> Duration {
    seconds(MERGE_PER_RECTANGLE * triangles as f64 / 2.0)
}

fn seconds(s: f64) -> Duration {
    Duration::from_secs_f64(s.max(0.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `model` within a factor 0.75 to 1.33 of `measured` seconds.
    fn close(model: Duration, measured: f64) -> bool {
        let r = model.as_secs_f64() / measured;
        (0.75..=1.33).contains(&r)
    }

    #[test]
    fn create_mesh_follows_every_measured_row() {
        for (rectangles, measured) in [
            (100, 0.024),
            (250, 0.121),
            (500, 0.148),
            (1_000, 0.428),
            (2_000, 0.882),
            (4_000, 2.2),
            (20_000, 6.1),
            (20_000, 9.2),
        ] {
            let model = create_mesh(rectangles * 2);
            assert!(
                close(model, measured),
                "{rectangles}: {model:?} vs {measured} s"
            );
        }
        // grows with the mesh, also past the last row
        assert!(create_mesh(60_000) > create_mesh(40_000));
        assert!(create_mesh(2) > Duration::ZERO);
    }

    #[test]
    fn merging_forty_meshes_of_500_takes_what_it_took() {
        assert!(close(merge_shapes(40 * 500 * 2), 2.36));
    }
}
