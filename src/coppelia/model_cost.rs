//! The modeled server work of loading an XML model (`simxLoadModel`, `sim.loadModel`): a pure
//! function of the triangles it holds, fitted to the one measured figure of
//! `../shared/spec/real-coppeliasim-4.5.1.md` ("One object instead of thousands"): a model
//! holding one mesh of 20,000 rectangles (40,000 triangles, 7 MB of XML) loaded through the
//! legacy API in 3.7 s at idle fps 8. A blocking legacy call at idle fps 8 takes one
//! main-loop pass, 125 ms ("Pacing"), which the servers already wait; the rest, about
//! 3.58 s, is the loader's work, about 89 µs per triangle (parsing the text, building the
//! mesh and its normals and edges). The cost is put on triangles rather than bytes because
//! our files write numbers more compactly than CoppeliaSim's own `%.4e`.

use std::time::Duration;

/// Server work per triangle of a loaded model: (3.7 s - one 125 ms pass) / 40,000 triangles.
pub const PER_TRIANGLE: Duration = Duration::from_nanos(89_375);

/// How long a real CoppeliaSim 4.5.1 works to load a model of `triangles` triangles.
pub fn model_load(triangles: usize) -> Duration {
    PER_TRIANGLE.saturating_mul(u32::try_from(triangles).unwrap_or(u32::MAX))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_model_of_20000_rectangles_loads_in_the_measured_3_7_s() {
        // 20,000 rectangles = 40,000 triangles, plus the one pass at idle fps 8 (125 ms)
        // the blocking call waits for.
        let modeled = model_load(40_000) + Duration::from_millis(125);
        let ratio = modeled.as_secs_f64() / 3.7;
        assert!((0.75..=1.33).contains(&ratio), "{modeled:?} vs 3.7 s");
        assert!(
            model_load(2) < Duration::from_millis(1),
            "a small model is quick"
        );
        assert_eq!(model_load(0), Duration::ZERO);
    }
}
