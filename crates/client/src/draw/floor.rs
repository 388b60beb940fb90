//! The floor's size before `apply --resize-floor` grew it to a layout's: recorded in the
//! scene (integer signals, as the line template's home is, [`super::home`]) before the
//! first resize, so that `clear` scales the floor back. Scaling needs the ZeroMQ remote API
//! (`sim.scaleObject`); the legacy remote API has no call that resizes an object.

use super::backend::Backend;
use super::error::BackendError;
use super::error::DrawError;
use super::extent::{FloorShort, Resize, extents, object_kind};
use super::signals::FLOOR_SIZE as FLOOR_SIGNALS;
use super::tolerance::SIZE_TOLERANCE;
use vrep_maze_core::coppelia::OBJECT_SHAPE_TYPE;
use vrep_maze_core::wording::{Message, Opt, Value};

/// A floor's size before the first `apply --resize-floor`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FloorRecord {
    /// The floor it is the size of.
    pub handle: i32,
    /// Extent along x and y, metres.
    pub size: [f64; 2],
}

impl FloorRecord {
    /// The signal values (`None` when a size does not fit: such a size is not recorded).
    fn encode(&self) -> Option<[i32; 3]> {
        let fixed = |v: f64| {
            let scaled = (v * 1e3).round();
            (scaled.is_finite() && scaled > 0.0 && scaled < i32::MAX as f64)
                .then_some(scaled as i32)
        };
        Some([self.handle, fixed(self.size[0])?, fixed(self.size[1])?])
    }

    /// The record from the signal values, `None` unless all are set.
    fn decode(values: &[Option<i32>]) -> Option<FloorRecord> {
        match values {
            [Some(handle), Some(x), Some(y)] => Some(FloorRecord {
                handle: *handle,
                size: [f64::from(*x) / 1e3, f64::from(*y) / 1e3],
            }),
            _ => None,
        }
    }
}

/// Reads the record; `None` if there is none.
pub fn read(scene: &mut dyn Backend) -> Result<Option<FloorRecord>, BackendError> {
    Ok(FloorRecord::decode(&scene.int_signals(&FLOOR_SIGNALS)?))
}

/// Deletes the record.
fn forget(scene: &mut dyn Backend) -> Result<(), BackendError> {
    let signals: Vec<(&str, Option<i32>)> = FLOOR_SIGNALS.iter().map(|n| (*n, None)).collect();
    scene.set_int_signals(&signals)
}

/// Grows the floor (`floor`: its handle and, as the survey read it, its type) named `name`
/// to the layout's size ([`FloorShort::resized`]): refused unless it is a shape (a dummy
/// scales alike along x, y and z), its size before is recorded first unless a record of it
/// exists (an earlier resize), then it is scaled and its size read back: the report says
/// what the simulator reads, and a floor that did not grow to the layout's size is refused
/// as a short one. With `dry_run` nothing is sent. Returns the report's line.
pub fn resize(
    scene: &mut dyn Backend,
    (floor, kind): (i32, Option<i32>),
    name: &str,
    short: &FloorShort,
    dry_run: bool,
) -> Result<String, DrawError> {
    let refused = |short: FloorShort, resize| DrawError::Floor {
        floor: name.to_string(),
        short,
        resize,
    };
    let factors = short
        .factors()
        .ok_or_else(|| refused(*short, Resize::NoExtent))?;
    if let Some(kind) = kind.filter(|k| *k != OBJECT_SHAPE_TYPE) {
        return Err(refused(*short, Resize::NotAShape { kind }));
    }
    if scene.authoring().is_none() {
        return Err(refused(*short, Resize::NoApi));
    }
    let was = extents(&short.have);
    if dry_run {
        return Ok(format!(
            "would resize `{name}` from {was} m to {} m (clear puts it back)",
            extents(&short.resized())
        ));
    }
    let record = FloorRecord {
        handle: floor,
        size: short.have,
    };
    if read(scene)?.is_none_or(|r| r.handle != floor)
        && let Some(values) = record.encode()
    {
        let signals: Vec<(&str, Option<i32>)> = FLOOR_SIGNALS
            .iter()
            .zip(values)
            .map(|(n, v)| (*n, Some(v)))
            .collect();
        scene.set_int_signals(&signals)?;
    }
    if let Some(authoring) = scene.authoring() {
        authoring.scale(floor, factors)?;
    }
    let Some(now) = floor_size(scene, floor)? else {
        return Ok(format!(
            "resized `{name}` from {was} m towards {} m, a size the simulator did not read back (clear puts it back)",
            extents(&short.resized())
        ));
    };
    let grown = FloorShort {
        have: now,
        need: short.need,
    };
    if (0..2).any(|k| now[k] + SIZE_TOLERANCE < short.need[k]) {
        return Err(refused(grown, Resize::DidNotGrow));
    }
    Ok(format!(
        "resized `{name}` from {was} m to {} m (clear puts it back)",
        extents(&now)
    ))
}

/// The floor's extent along x and y as the simulator reads it now, `None` if it does not
/// give it.
fn floor_size(scene: &mut dyn Backend, floor: i32) -> Result<Option<[f64; 2]>, BackendError> {
    let size = scene.sizes(&[floor])?.first().copied().flatten();
    Ok(size
        .map(|s| [s[0], s[1]])
        .filter(|s| s.iter().all(|v| v.is_finite())))
}

/// Puts the floor (`floor`: its handle and, as the survey read it, its type) named `name`
/// back to its size before the first `apply --resize-floor`, if a record of it exists, and
/// deletes the record; the line says the size the simulator reads after the scale. A floor
/// that is no shape is left as it is (only an older version resized one: a dummy scales
/// alike along x, y and z, so no scale gives it back its x and y), the record deleted. Over
/// the legacy remote API, which cannot resize, says how to instead and keeps the record.
/// With `dry_run` nothing is sent. Returns the report's line, `None` without a record.
pub fn restore(
    scene: &mut dyn Backend,
    (floor, kind): (i32, Option<i32>),
    name: &str,
    dry_run: bool,
) -> Result<Option<Message>, DrawError> {
    let Some(record) = read(scene)?.filter(|r| r.handle == floor) else {
        return Ok(None);
    };
    let was = extents(&record.size);
    if let Some(kind) = kind.filter(|k| *k != OBJECT_SHAPE_TYPE) {
        if !dry_run {
            forget(scene)?;
        }
        return Ok(Some(
            Message::text(format!(
                "left `{name}` as it is: it is {}, not a shape, so no scale puts it back to {was} m",
                object_kind(kind)
            ))
            .and_message(before_resize())
            .and("; resize it in CoppeliaSim"),
        ));
    }
    if scene.authoring().is_none() {
        return Ok(Some(
            Message::text(format!("left `{name}` as it is: apply "))
                .and_setting(Opt::ResizeFloor, Value::On)
                .and(format!(" grew it from {was} m, and the legacy remote API cannot resize it back; run clear over the ZeroMQ remote API ("))
                .and_setting(Opt::Api, Value::word("zmq"))
                .and(") to restore it"),
        ));
    }
    let now = floor_size(scene, floor)?;
    let factors = now.and_then(|now| {
        let f = [record.size[0] / now[0], record.size[1] / now[1], 1.0];
        f.iter().all(|x| x.is_finite() && *x > 0.0).then_some(f)
    });
    let Some(factors) = factors else {
        return Ok(Some(
            Message::text(format!(
                "left `{name}` as it is: the simulator did not give its size, so it cannot be put back to {was} m"
            ))
            .and_message(before_resize()),
        ));
    };
    if dry_run {
        return Ok(Some(
            Message::text(format!("would put `{name}` back to {was} m"))
                .and_message(before_resize()),
        ));
    }
    if factors.iter().any(|f| (f - 1.0).abs() > 1e-9)
        && let Some(authoring) = scene.authoring()
    {
        authoring.scale(floor, factors)?;
    }
    forget(scene)?;
    let back = floor_size(scene, floor)?;
    Ok(Some(match back {
        Some(back) if (0..2).all(|k| (back[k] - record.size[k]).abs() <= SIZE_TOLERANCE) => {
            Message::text(format!("put `{name}` back to {} m", extents(&back)))
                .and_message(before_resize())
        }
        Some(back) => Message::text(format!("scaled `{name}` back towards {was} m"))
            .and_message(before_resize())
            .and(format!(
                ", but it reads {} m now: resize it in CoppeliaSim",
                extents(&back)
            )),
        None => Message::text(format!("scaled `{name}` back to {was} m"))
            .and_message(before_resize())
            .and(", a size the simulator did not read back"),
    }))
}

/// ", its size before apply --resize-floor".
fn before_resize() -> Message {
    Message::text(", its size before apply ").and_setting(Opt::ResizeFloor, Value::On)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_record_round_trips_to_the_millimetre_and_a_bad_size_is_not_kept() {
        let record = FloorRecord {
            handle: 7,
            size: [10.0, 4.5],
        };
        let values = record.encode().unwrap().map(Some);
        assert_eq!(FloorRecord::decode(&values), Some(record));
        assert_eq!(FloorRecord::decode(&[Some(7), None, Some(1)]), None);
        for bad in [f64::NAN, 0.0, -1.0, 3e6] {
            let bad = FloorRecord {
                size: [bad, 1.0],
                ..record
            };
            assert_eq!(bad.encode(), None);
        }
        assert!(FLOOR_SIGNALS.iter().all(|n| {
            n.chars()
                .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '.')
        }));
    }
}
