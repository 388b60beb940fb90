//! Sizes as a message says them ([`metres`], [`extents`]) and the one size refusal with a
//! remedy of its own: a floor smaller than the layout's ([`FloorShort`]) and what stands in
//! the way of growing it ([`Resize`]).

use super::tolerance::SIZE_TOLERANCE;

/// What stands in the way of resizing a floor, for [`DrawError::Floor`](super::error::DrawError::Floor)'s remedies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Resize {
    /// The API can resize it: `--resize-floor` was not given.
    Offered,
    /// The legacy remote API answered: it cannot resize objects.
    NoApi,
    /// The floor has no extent along x or y: no scale makes it larger.
    NoExtent,
}

/// The scene's floor is smaller than the layout's along x or y.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FloorShort {
    /// The scene's floor (x, y), metres.
    pub have: [f64; 2],
    /// The layout's floor (x, y), metres.
    pub need: [f64; 2],
}

impl FloorShort {
    /// The floor after `apply --resize-floor`: the layout's size along each axis where the
    /// scene's is smaller, the scene's elsewhere (a floor is never made smaller).
    pub fn resized(&self) -> [f64; 2] {
        [0, 1].map(|k| self.have[k].max(self.need[k]))
    }

    /// The scale factors (x, y, z) from the scene's floor to [`FloorShort::resized`]; z
    /// stays. `None` for a floor without extent along x or y, which no factor makes larger.
    pub fn factors(&self) -> Option<[f64; 3]> {
        let to = self.resized();
        (self.have.iter().all(|h| *h > SIZE_TOLERANCE))
            .then(|| [to[0] / self.have[0], to[1] / self.have[1], 1.0])
    }

    /// "the scene's `Floor` is 10 x 10 m but the layout's floor is 45 x 45 m".
    pub fn describe(&self, floor: &str) -> String {
        format!(
            "the scene's `{floor}` is {} m but the layout's floor is {} m",
            extents(&self.have),
            extents(&self.need)
        )
    }
}

/// A length for messages: metres with at most 4 decimals (`0.6`, `0.05`).
pub fn metres(v: f64) -> String {
    format!("{}", (v * 1e4).round() / 1e4)
}

/// `a x b [x c]` metres.
pub fn extents(v: &[f64]) -> String {
    v.iter().map(|x| metres(*x)).collect::<Vec<_>>().join(" x ")
}
