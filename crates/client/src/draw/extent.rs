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
    /// The floor is no shape (a dummy, say: `kind` is its `sim_object_*_type` code). Only a
    /// shape scales along x and y alone; CoppeliaSim scales a dummy alike along x, y and z,
    /// so `sim.scaleObject` cannot give it the layout's size.
    NotAShape {
        /// Its object type code ([`object_kind`] says it).
        kind: i32,
    },
    /// The simulator scaled the floor but it did not grow to the layout's size (read back
    /// after the scale: `FloorShort::have` is what it reads now).
    DidNotGrow,
}

/// An object type code (`sim_object_*_type`, `../shared/spec/legacy-remote-api.md`) as a
/// message says it: "a dummy", "a camera", "an object of type 42".
pub fn object_kind(code: i32) -> String {
    let name = match code {
        0 => "a shape",
        1 => "a joint",
        2 => "a graph",
        3 => "a camera",
        4 => "a dummy",
        5 => "a proximity sensor",
        8 => "a path",
        9 => "a vision sensor",
        11 => "a mill",
        12 => "a force sensor",
        13 => "a light",
        14 => "a mirror",
        15 => "an octree",
        16 => "a point cloud",
        other => return format!("an object of type {other}"),
    };
    name.to_string()
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

    /// [`FloorShort::describe`], and why `apply` cannot grow the floor when that is not
    /// the API's doing: "..., and `FD` is a dummy, not a shape: apply resizes only a shape".
    pub fn describe_resize(&self, floor: &str, resize: Resize) -> String {
        let short = self.describe(floor);
        match resize {
            Resize::NotAShape { kind } => format!(
                "{short}, and `{floor}` is {}, not a shape: apply resizes only a shape",
                object_kind(kind)
            ),
            Resize::DidNotGrow => format!(
                "{short}, after apply scaled it (read back): the simulator did not grow it as asked"
            ),
            Resize::Offered | Resize::NoApi | Resize::NoExtent => short,
        }
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
