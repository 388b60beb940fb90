//! The modeled server work of loading an XML model (`simxLoadModel`, `sim.loadModel`): a pure
//! function of the triangles it holds. Fitted to the models `apply --draw mesh` loads over the
//! legacy API on a real CoppeliaSim 4.5.1 (`docs/measurements.md` "Loading our XML models
//! over the legacy API"): a 100x100 line maze drawn by two `simxLoadModel` calls of about
//! 8,000 and 2,680 triangles (8 meshes, then 3), answered in 69.6 and 19.5 ms at idle fps 0, of which a 2 ms
//! pass ([`crate::coppelia::cost::CostModel::legacy_pass_floor`]): 8.5 and 6.5 µs per triangle.
//!
//! `../shared/spec/real-coppeliasim-4.5.1.md` ("One object instead of thousands") loaded a
//! model of 20,000 rectangles that CoppeliaSim itself had saved (7 MB of XML, with normals
//! and edges) in 3.7 s, 89 µs a triangle: our files, about 90 bytes a triangle, load ten
//! times faster, and the model prices ours.

use std::time::Duration;

/// Server work per triangle of a loaded model: (69.6 + 19.5 ms - two 2 ms passes) / 10,680
/// triangles.
pub const PER_TRIANGLE: Duration = Duration::from_nanos(8_000);

/// How long a real CoppeliaSim 4.5.1 works to load a model of `triangles` triangles.
pub fn model_load(triangles: usize) -> Duration {
    PER_TRIANGLE.saturating_mul(u32::try_from(triangles).unwrap_or(u32::MAX))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_models_of_a_100x100_load_in_the_measured_time() {
        // docs/measurements.md: 69.6 ms and 19.5 ms a call, with a 2 ms pass each
        for (triangles, measured) in [(8_000, 0.0676), (2_680, 0.0175)] {
            let ratio = model_load(triangles).as_secs_f64() / measured;
            assert!((0.75..=1.33).contains(&ratio), "{triangles}: x{ratio:.2}");
        }
        assert!(
            model_load(2) < Duration::from_millis(1),
            "a small model is quick"
        );
        assert_eq!(model_load(0), Duration::ZERO);
    }
}
