//! Where the line template stood before the first `apply`: a line maze draws its template
//! as the first line, so `clear` puts it back there. The pose is kept in the scene (integer
//! signals [`signals::HOME`], which both APIs read and write and which survive between
//! runs), as the template's handle and its pose in the floor frame in micrometres and
//! microradians.

use super::backend::{Backend, Edit};
use super::error::BackendError;
use super::signals::{self, HOME};
use vrep_maze_core::layout::Pose;

/// How far below the floor a template no line needs is put (metres): under an opaque floor,
/// out of every camera above it.
pub const HIDDEN_DEPTH: f64 = 0.1;

/// The template's pose before the first `apply`, in the floor frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Home {
    /// The template it is the home of.
    pub handle: i32,
    /// Position, metres.
    pub position: [f64; 3],
    /// CoppeliaSim Euler angles, radians.
    pub orientation: [f64; 3],
}

impl Home {
    /// The signal values (`None` when a number does not fit: such a pose is not recorded).
    pub(crate) fn encode(&self) -> Option<[i32; 7]> {
        let fixed = |v: f64| {
            let scaled = (v * 1e6).round();
            (scaled.is_finite() && scaled.abs() < i32::MAX as f64).then_some(scaled as i32)
        };
        let p = self.position.map(fixed);
        let e = self.orientation.map(fixed);
        Some([self.handle, p[0]?, p[1]?, p[2]?, e[0]?, e[1]?, e[2]?])
    }

    /// The record from the signal values, `None` unless all seven are set.
    pub(crate) fn decode(values: &[Option<i32>]) -> Option<Home> {
        let v: Vec<i32> = values.iter().copied().collect::<Option<_>>()?;
        let real = |k: usize| v[k] as f64 / 1e6;
        (v.len() == HOME.len()).then(|| Home {
            handle: v[0],
            position: [real(1), real(2), real(3)],
            orientation: [real(4), real(5), real(6)],
        })
    }

    /// The edit that puts the template back home (pose relative to `floor`).
    pub fn edit(&self, floor: i32) -> Edit {
        Edit::SetPose {
            handle: self.handle,
            relative_to: floor,
            position: self.position,
            orientation: self.orientation,
        }
    }

    /// Whether this is a home `apply` made up rather than read ([`Home::hidden`]: the
    /// template lay on an earlier maze with no record of where it stood): exactly
    /// [`HIDDEN_DEPTH`] below the floor, turned by nothing, to the micrometre the record
    /// keeps. A home the user chose merely lies below the floor (a `Floor` raised above the
    /// template, say): it is where the template stood, and said so.
    pub fn is_hidden(&self) -> bool {
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-6;
        close(self.position[2], -HIDDEN_DEPTH) && self.orientation.iter().all(|e| close(*e, 0.0))
    }

    /// A pose below the floor under (`x`, `y`) of the floor frame ([`HIDDEN_DEPTH`]).
    pub fn hidden(x: f64, y: f64) -> Pose {
        Pose {
            x,
            y,
            z: -HIDDEN_DEPTH,
            yaw: 0.0,
        }
    }
}

/// Reads the record (under the new names, else an older version's: [`signals`]), and
/// whether it is an older version's (to be written again under the new names); `None` if
/// there is none (never recorded, or cleared).
pub fn read(scene: &mut dyn Backend) -> Result<Option<(Home, bool)>, BackendError> {
    let values = scene.int_signals(&signals::names_to_read(&HOME))?;
    let (new, old) = values.split_at(HOME.len());
    Ok(match Home::decode(new) {
        Some(home) => Some((home, false)),
        None => Home::decode(old).map(|home| (home, true)),
    })
}

/// Records `home` (nothing if its pose is not finite or out of range), removing an older
/// version's record.
pub fn write(scene: &mut dyn Backend, home: &Home) -> Result<(), BackendError> {
    let Some(values) = home.encode() else {
        return Ok(());
    };
    let set: Vec<_> = HOME.into_iter().zip(values.map(Some)).collect();
    scene.set_int_signals(&signals::int_writes(&set))
}

/// Deletes the record (an older version's too).
pub fn forget(scene: &mut dyn Backend) -> Result<(), BackendError> {
    let set: Vec<_> = HOME.into_iter().map(|s| (s, None)).collect();
    scene.set_int_signals(&signals::int_writes(&set))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_record_round_trips_to_the_micrometre() {
        let home = Home {
            handle: 12,
            position: [0.0, -5.5, 0.001],
            orientation: [0.0, 0.0, -std::f64::consts::FRAC_PI_2],
        };
        let values = home.encode().unwrap().map(Some);
        let back = Home::decode(&values).unwrap();
        assert_eq!(back.handle, 12);
        for k in 0..3 {
            assert!((back.position[k] - home.position[k]).abs() <= 5e-7);
            assert!((back.orientation[k] - home.orientation[k]).abs() <= 5e-7);
        }
        let mut partial = values;
        partial[3] = None;
        assert_eq!(Home::decode(&partial), None);
        let far = Home {
            position: [3000.0, 0.0, 0.0],
            ..home
        };
        assert_eq!(far.encode(), None);
        let nan = Home {
            orientation: [f64::NAN, 0.0, 0.0],
            ..home
        };
        assert_eq!(nan.encode(), None);
    }

    #[test]
    fn only_a_made_up_home_is_hidden_not_one_below_a_raised_floor() {
        let made_up = Home::hidden(1.5, -2.0);
        let home = Home {
            handle: 3,
            position: super::super::pose::position(&made_up),
            orientation: super::super::pose::euler(&made_up),
        };
        let values = home.encode().unwrap().map(Some);
        assert!(Home::decode(&values).unwrap().is_hidden());
        // Line where the course scene has it, under a Floor raised to z 0.5
        let below = Home {
            position: [0.0, 0.0, -0.499],
            ..home
        };
        assert!(!below.is_hidden());
        let turned = Home {
            orientation: [0.0, 0.0, 0.3],
            ..home
        };
        assert!(!turned.is_hidden());
    }
}
