//! Remove a drawn maze, lines or walls (and posts): every child of the maze dummy except the
//! templates, and parentless copies of the templates left by an interrupted run. Templates
//! stay where they are.

use std::collections::HashMap;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use vrep_maze_core::wording::Message;

use super::backend::{Backend, Edit, ObjectInfo, Survey};
use super::error::DrawError;
use super::home;
use super::lease::{Claim, claimed};
use super::names::{Handles, ObjectNames};
use super::ownership::{self, foreign_copies, maze_pieces};
use super::pose::{floor_frame, relative_pose};
use super::session::resolve_handles;
use super::session::{EarlierLines, on_an_earlier_maze, raised, stop_running_simulation};
use vrep_maze_core::layout::Style;

/// What [`clear`] removed.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ClearReport {
    /// Names of the removed copies of the templates.
    pub removed: Vec<String>,
    /// Names of the removed objects of a mesh maze (`apply --draw mesh`): its meshes, then
    /// their holder.
    pub removed_meshes: Vec<String>,
    /// Messages exchanged with the simulator.
    pub round_trips: usize,
    /// Idle rate restored (it had been left at 0 by an interrupted `apply`).
    pub restored_idle_fps: Option<i32>,
    /// The simulation was running and [`ClearOptions::stop_simulation`] stopped it first.
    pub stopped_simulation: bool,
    /// The user's objects under the maze dummy: left alone ([`ownership::sort_out`]).
    pub left_alone: Vec<String>,
    /// Where the line template went (one line), if it moved: back home, or below the floor
    /// when its home was never recorded ([`home`]).
    pub template: Option<String>,
    /// Where the start and end markers went (one line): back where they stood before the
    /// first `apply`, or left where they are, without a record ([`super::markers_home`]).
    pub markers: Option<String>,
    /// Lines to show as warnings (the simulator did not keep the scene's signals).
    pub warnings: Vec<String>,
    /// The floor put back to its size before `apply --resize-floor` (one line), or why it
    /// was not ([`super::floor::restore`]), for an adapter to word.
    pub floor: Option<Message>,
}

/// Puts the line template back where it stood before the first `apply` ([`home`]) and
/// deletes the record. Without a record, a template that `drawn` says was the first line
/// of a maze (drawn by an older version, or on a simulator that keeps no signals: `kept`
/// false, the record is not read) goes below the floor, out of sight. Says what it did (or,
/// with `dry_run`, would do).
fn send_home(
    scene: &mut dyn Backend,
    kept: bool,
    h: &Handles,
    objects: &[ObjectInfo],
    drawn: bool,
    names: &ObjectNames,
    dry_run: bool,
) -> Result<Option<String>, DrawError> {
    let verb = if dry_run { "would put" } else { "put" };
    let template = &names.line;
    let record = if kept { home::read(scene)? } else { None };
    let record = record.map(|(home, _)| home);
    if let Some(home) = record.filter(|r| r.handle == h.template) {
        if !dry_run {
            scene.edit(&[home.edit(h.floor)])?;
            home::forget(scene)?;
        }
        // a home apply made up is where the first apply hid it, not where it stood (one
        // merely below the floor, a raised one, is where it stood)
        return Ok(Some(if home.is_hidden() {
            format!(
                "{verb} `{template}` below the floor at ({:.3}, {:.3}), out of sight, where the first apply recorded it (it lay on an earlier maze then, with no record of where it stood before); move it where you want it",
                home.position[0], home.position[1]
            )
        } else {
            format!("{verb} `{template}` back where it stood before the first apply")
        }));
    }
    let floor = floor_frame(objects, h.floor).unwrap_or_default();
    let Some((position, _)) = objects
        .iter()
        .find(|o| o.handle == h.template)
        .map(|o| relative_pose(&floor, o))
    else {
        return Ok(None);
    };
    if !drawn || position[2] < 0.0 {
        return Ok(None);
    }
    let template_info = objects.iter().find(|o| o.handle == h.template);
    if let Some(t) = template_info
        && !on_an_earlier_maze(scene, h, objects, t, template, &floor, EarlierLines::Copies)?
    {
        // it stands where the user put it: no maze's first line
        return Ok(None);
    }
    let hidden = home::Home::hidden(position[0], position[1]);
    if !dry_run {
        scene.edit(&[Edit::SetPose {
            handle: h.template,
            relative_to: h.floor,
            position: crate::draw::pose::position(&hidden),
            orientation: crate::draw::pose::euler(&hidden),
        }])?;
    }
    let why = if kept {
        "the record lives in the scene's signals, which a scene file does not keep: a scene saved and loaded again, or a maze drawn by an older vrep-maze"
    } else {
        "the simulator keeps no signals"
    };
    Ok(Some(format!(
        "no record of where `{template}` stood before the first apply ({why}): {verb} it below the floor at ({:.3}, {:.3}), out of sight; move it where you want it",
        position[0], position[1]
    )))
}

/// How [`clear`] runs.
#[derive(Debug, Clone, Default)]
pub struct ClearOptions {
    /// Names of the scene objects.
    pub names: ObjectNames,
    /// Stop a running simulation first; without it a running simulation is refused, since
    /// CoppeliaSim undoes every removal when the simulation stops.
    pub stop_simulation: bool,
    /// Only list what would be removed.
    pub dry_run: bool,
    /// Set by a Ctrl-C handler: the run stops after the request in flight.
    pub interrupt: Option<Arc<AtomicBool>>,
}

/// Removes the maze lines (idempotent) and restores an idle rate left at 0 by an
/// interrupted `apply`. Refuses a running simulation as `apply()` does.
pub fn clear(scene: &mut dyn Backend, opts: &ClearOptions) -> Result<ClearReport, DrawError> {
    opts.names.check_roles()?;
    let rt0 = scene.round_trips();
    // the rate first: every call before it waits for an idle pass (the claim too)
    let (mut report, rates) = raised(scene, opts.dry_run, |scene| {
        claimed(scene, opts.dry_run, |scene, claim| {
            clear_claimed(scene, opts, claim)
        })
    })?;
    report.round_trips = scene.round_trips() - rt0;
    // a record of the user's rate means an interrupted apply left the rate at 0: `raised`
    // restored it
    report.restored_idle_fps = rates.saved.filter(|_| !opts.dry_run);
    Ok(report)
}

/// The survey for a maze of either style, and the style: the line template is looked for
/// first, the wall template serves when the scene has no line template.
fn survey_either_style(
    scene: &mut dyn Backend,
    names: &ObjectNames,
) -> Result<(Style, Survey), DrawError> {
    let mut style = Style::Lines;
    let mut survey = scene.survey(&names.survey(style))?;
    if survey.handles.template.is_none() && survey.handles.other_template.is_some() {
        style = Style::Walls;
        survey = scene.survey(&names.survey(style))?;
    }
    Ok((style, survey))
}

/// The names of `doomed` as `objects` give them (`object 12` for one they do not hold).
fn names_of(doomed: &[i32], objects: &[ObjectInfo]) -> Vec<String> {
    let names_by_handle: HashMap<i32, &str> = objects
        .iter()
        .map(|o| (o.handle, o.name.as_str()))
        .collect();
    doomed
        .iter()
        .map(|d| {
            names_by_handle
                .get(d)
                .map_or_else(|| format!("object {d}"), |n| n.to_string())
        })
        .collect()
}

/// Removes `doomed` in requests the simulator finishes in bounded time (removal costs per
/// object, `objects_in_scene` of them), the interrupt and the lease checked before each.
fn remove(
    scene: &mut dyn Backend,
    opts: &ClearOptions,
    claim: &Claim,
    doomed: &[i32],
    objects_in_scene: usize,
) -> Result<(), DrawError> {
    let per_request = scene.pieces_per_request(objects_in_scene).max(1);
    for (i, chunk) in doomed.chunks(per_request).enumerate() {
        if opts
            .interrupt
            .as_ref()
            .is_some_and(|flag| flag.load(Ordering::SeqCst))
        {
            // `placed` counts the objects removed so far, `total` those to remove
            return Err(DrawError::Interrupted {
                placed: i * per_request,
                total: doomed.len(),
            });
        }
        claim.check(scene, "while removing the lines")?;
        scene.edit(&chunk.iter().map(|&d| Edit::Remove(d)).collect::<Vec<_>>())?;
    }
    Ok(())
}

/// Whether the maze removed was a line maze, on whose first line only the template lay:
/// `removed` holds copies of the line template, or `meshes` line meshes.
fn was_line_maze(removed: &[String], meshes: &[(i32, String)], names: &ObjectNames) -> bool {
    removed
        .iter()
        .any(|n: &String| ownership::is_copy_name(n, &names.line))
        || meshes.iter().any(|(_, n)| {
            super::mesh::parse_mesh_name(n).is_some_and(|(k, _)| k == super::mesh::MeshKind::Lines)
        })
}

/// [`clear`] under `claim`, with the idle rate raised.
fn clear_claimed(
    scene: &mut dyn Backend,
    opts: &ClearOptions,
    claim: &Claim,
) -> Result<ClearReport, DrawError> {
    let (names, dry_run) = (&opts.names, opts.dry_run);
    let (style, survey) = survey_either_style(scene, names)?;
    let h = resolve_handles(names, style, &survey, false, None)?;
    let stopped_simulation = stop_running_simulation(
        scene,
        survey.simulation_running,
        opts.stop_simulation,
        dry_run,
    )?;
    // only the templates' copies are the maze's: the user's objects stay as they are
    let sorted = ownership::sort_out(&survey.objects, &h, &names.templates(), &survey.traits);
    let others = names.others(style);
    let mut doomed = maze_pieces(&sorted.objects, &h, names.template(style), &others);
    doomed.extend(foreign_copies(&sorted.objects, &h, &others));
    // a mesh maze (`--draw mesh`): its meshes and holder, ours by name
    let leftovers = super::mesh::leftovers(scene, names, &h, &survey.objects)?;
    let meshes = &leftovers.ours;
    // the holder, ours or the user's, is never a copy
    doomed.retain(|d| !meshes.iter().any(|(m, _)| m == d) && Some(*d) != leftovers.holder);
    let removed = names_of(&doomed, &sorted.objects);
    let removed_meshes: Vec<String> = meshes.iter().map(|(_, name)| name.clone()).collect();
    doomed.extend(meshes.iter().map(|(m, _)| *m));
    if !dry_run {
        remove(scene, opts, claim, &doomed, survey.objects.len())?;
    }
    let line_maze = was_line_maze(&removed, meshes, names);
    let template = if style == Style::Lines {
        send_home(
            scene,
            claim.signals_kept(),
            &h,
            &sorted.objects,
            line_maze,
            names,
            dry_run,
        )?
    } else {
        None
    };
    let drawn = !removed.is_empty() || !removed_meshes.is_empty();
    let markers = if claim.signals_kept() {
        super::markers_home::restore(scene, &h, drawn, names, dry_run)?
    } else {
        None
    };
    let floor_kind = survey.traits.kinds.get(&h.floor).copied();
    let floor = super::floor::restore(scene, (h.floor, floor_kind), &names.floor, dry_run)?;
    Ok(ClearReport {
        template,
        markers,
        floor,
        removed,
        removed_meshes,
        round_trips: 0,
        restored_idle_fps: None,
        stopped_simulation,
        left_alone: sorted
            .strangers
            .into_iter()
            .chain(leftovers.left_alone)
            .collect(),
        warnings: claim.warning().map(str::to_string).into_iter().collect(),
    })
}
