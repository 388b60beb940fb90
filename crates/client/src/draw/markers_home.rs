//! Where the start and end markers stood before the first `apply`, so that `clear` puts them
//! back, as it puts the line template back ([`super::home`]). Kept the same way: integer
//! signals ([`super::signals::START_HOME`], [`super::signals::END_HOME`]) holding each marker's handle and
//! its pose in the floor frame in micrometres and microradians, which survive between runs
//! but not in a scene file.

use super::backend::{Backend, ObjectInfo};
use super::error::BackendError;
use super::home::Home;
use super::names::{Handles, ObjectNames};
use super::pose::{floor_frame, relative_pose};
use super::signals::{END_HOME, START_HOME};

/// Every signal name of both records: the start marker's, then the end marker's.
fn all_names() -> Vec<&'static str> {
    START_HOME.into_iter().chain(END_HOME).collect()
}

/// The records of the start and end markers, each `None` when there is none.
pub fn read(scene: &mut dyn Backend) -> Result<[Option<Home>; 2], BackendError> {
    let values = scene.int_signals(&all_names())?;
    let (start, end) = values.split_at(START_HOME.len());
    Ok([Home::decode(start), Home::decode(end)])
}

/// Records where the markers (`h.start`, `h.end`) stand now, before a drawing moves them,
/// each unless it is recorded already. Nothing when `earlier` says the scene holds an
/// earlier maze: without a record, the markers stand on its cells, not where the user put
/// them (`clear` then says it has no record and leaves them). A pose not read, or out of
/// range, is not recorded.
pub fn record(
    scene: &mut dyn Backend,
    h: &Handles,
    objects: &[ObjectInfo],
    earlier: bool,
) -> Result<(), BackendError> {
    if earlier {
        // nothing is written then, so the records need not be read (one request a reset)
        return Ok(());
    }
    let recorded = read(scene)?;
    let floor = floor_frame(objects, h.floor).unwrap_or_default();
    let mut writes = Vec::new();
    for ((handle, names), have) in [(h.start, START_HOME), (h.end, END_HOME)]
        .into_iter()
        .zip(recorded)
    {
        if have.is_some_and(|r| r.handle == handle) {
            continue;
        }
        let Some(marker) = objects.iter().find(|o| o.handle == handle) else {
            continue;
        };
        let (position, orientation) = relative_pose(&floor, marker);
        let home = Home {
            handle,
            position,
            orientation,
        };
        if let Some(values) = home.encode() {
            writes.extend(names.into_iter().zip(values.map(Some)));
        }
    }
    if writes.is_empty() {
        return Ok(());
    }
    scene.set_int_signals(&writes)
}

/// Puts the markers back where their records say they stood before the first `apply`, and
/// deletes the records; says what it did (with `dry_run`, would do). Without a record, when
/// `drawn` (a maze was there to remove), says that the markers are left where they are.
pub fn restore(
    scene: &mut dyn Backend,
    h: &Handles,
    drawn: bool,
    names: &ObjectNames,
    dry_run: bool,
) -> Result<Option<String>, BackendError> {
    let recorded = read(scene)?;
    let markers = [(h.start, &names.start), (h.end, &names.end)];
    let mut back = Vec::new();
    let mut unknown = Vec::new();
    let mut edits = Vec::new();
    for ((handle, name), home) in markers.into_iter().zip(recorded) {
        match home.filter(|r| r.handle == handle) {
            Some(home) => {
                back.push(format!("`{name}`"));
                edits.push(home.edit(h.floor));
            }
            None => unknown.push(format!("`{name}`")),
        }
    }
    if !dry_run {
        if !edits.is_empty() {
            scene.edit(&edits)?;
        }
        if recorded.iter().any(Option::is_some) {
            let forget: Vec<_> = all_names().into_iter().map(|n| (n, None)).collect();
            scene.set_int_signals(&forget)?;
        }
    }
    let verb = if dry_run { "would put" } else { "put" };
    let mut said = Vec::new();
    if !back.is_empty() {
        said.push(format!(
            "{verb} {} back where {} stood before the first apply",
            back.join(" and "),
            if back.len() == 1 { "it" } else { "they" }
        ));
    }
    if drawn && !unknown.is_empty() {
        said.push(format!(
            "no record of where {} stood before the first apply (the record lives in the scene's signals, which a scene file does not keep: a scene saved and loaded again, or a maze drawn by an older vrep-maze): left where {} {}",
            unknown.join(" and "),
            if unknown.len() == 1 { "it" } else { "they" },
            if unknown.len() == 1 { "is" } else { "are" },
        ));
    }
    Ok((!said.is_empty()).then(|| said.join("; ")))
}
