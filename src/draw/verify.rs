//! Compare a scene with a drawing: every line, `Start` and `End` in place (1e-4 m, 1e-4 rad),
//! copies parented to the maze dummy, and no other maze lines.

use super::plan::{maze_lines, pose_differences, world_frame};
use super::{Backend, DrawError, Drawing, Handles, ObjectInfo, ObjectNames, resolve_handles};

/// Differences between `objects` and `drawing`, where `lines[i]` is the object drawn for
/// `drawing.lines[i]` (`lines[0]` is the template). Empty when the scene matches.
pub fn check(
    objects: &[ObjectInfo],
    h: &Handles,
    template: &str,
    lines: &[i32],
    drawing: &Drawing,
) -> Vec<String> {
    let mut problems = Vec::new();
    let Some(floor) = objects
        .iter()
        .find(|o| o.handle == h.floor)
        .map(world_frame)
    else {
        return vec!["the floor object disappeared".into()];
    };
    let get = |handle: i32| objects.iter().find(|o| o.handle == handle);
    if lines.len() != drawing.lines.len() {
        problems.push(format!(
            "{} line objects for {} segments",
            lines.len(),
            drawing.lines.len()
        ));
    }
    for (i, (&handle, want)) in lines.iter().zip(&drawing.lines).enumerate() {
        match get(handle) {
            None => problems.push(format!("line {i} (handle {handle}) is missing")),
            Some(o) => {
                if let Some(d) = pose_differences(&floor, o, want) {
                    problems.push(format!("line {i} `{}` {d}", o.name));
                }
                if i > 0 && o.parent != Some(h.parent) {
                    problems.push(format!(
                        "line {i} `{}` has parent {:?}, expected {}",
                        o.name, o.parent, h.parent
                    ));
                }
            }
        }
    }
    for (what, handle, want) in [
        ("start", h.start, &drawing.start),
        ("end", h.end, &drawing.end),
    ] {
        match get(handle) {
            None => problems.push(format!("the {what} marker is missing")),
            Some(o) => {
                if let Some(d) = pose_differences(&floor, o, want) {
                    problems.push(format!("{what} `{}` {d}", o.name));
                }
            }
        }
    }
    let mut expected: Vec<i32> = lines.iter().skip(1).copied().collect();
    expected.sort_unstable();
    let mut found = maze_lines(objects, h, template);
    found.sort_unstable();
    if found != expected {
        let stray: Vec<String> = found
            .iter()
            .filter(|x| !expected.contains(x))
            .filter_map(|x| get(*x).map(|o| o.name.clone()))
            .collect();
        if !stray.is_empty() {
            problems.push(format!(
                "{} stray maze object(s): {}",
                stray.len(),
                stray.join(", ")
            ));
        }
    }
    problems
}

/// Verifies a scene against a drawing without knowing which copy is which line: every
/// segment must be covered by a distinct maze line in place (the template may cover any
/// segment), copies must be children of the maze dummy, no other maze line may exist, and
/// `Start`/`End` must be in place. One round trip.
pub fn verify(
    scene: &mut dyn Backend,
    drawing: &Drawing,
    names: &ObjectNames,
) -> Result<(), DrawError> {
    let survey = scene.survey(&names.all())?;
    let h = resolve_handles(names, &survey)?;
    let objects = &survey.objects;
    let floor = objects
        .iter()
        .find(|o| o.handle == h.floor)
        .map(world_frame)
        .unwrap_or_default();
    let get = |handle: i32| objects.iter().find(|o| o.handle == handle);
    let mut pool: Vec<i32> = vec![h.line];
    pool.extend(maze_lines(objects, &h, &names.line));
    let mut problems = Vec::new();
    for (i, want) in drawing.lines.iter().enumerate() {
        let hit = pool
            .iter()
            .position(|&c| get(c).is_some_and(|o| pose_differences(&floor, o, want).is_none()));
        match hit {
            Some(k) => {
                let c = pool.remove(k);
                if c != h.line && get(c).and_then(|o| o.parent) != Some(h.parent) {
                    problems.push(format!(
                        "line {i} `{}` is not a child of `{}`",
                        get(c).map(|o| o.name.as_str()).unwrap_or("?"),
                        names.parent
                    ));
                }
            }
            None => problems.push(format!(
                "no line at ({:.3}, {:.3}, {:.3}) yaw {:.4}",
                want.x, want.y, want.z, want.yaw
            )),
        }
    }
    let stray: Vec<&str> = pool
        .iter()
        .filter(|&&c| c != h.line)
        .filter_map(|&c| get(c).map(|o| o.name.as_str()))
        .collect();
    if !stray.is_empty() {
        problems.push(format!(
            "{} stray maze object(s): {}",
            stray.len(),
            stray.join(", ")
        ));
    }
    for (what, handle, want) in [
        ("start", h.start, &drawing.start),
        ("end", h.end, &drawing.end),
    ] {
        if let Some(d) = get(handle).and_then(|o| pose_differences(&floor, o, want)) {
            problems.push(format!("{what} {d}"));
        }
    }
    if problems.is_empty() {
        Ok(())
    } else {
        Err(DrawError::Verify(problems))
    }
}
