//! Remove a drawn maze: every child of the maze dummy except the templates, and parentless
//! copies of the line template left by an interrupted run. Templates stay where they are.

use super::lease::Claim;
use super::plan::maze_lines;
use super::{Backend, DrawError, Edit, ObjectNames, resolve_handles};

/// What [`clear`] removed.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ClearReport {
    /// Names of the removed objects.
    pub removed: Vec<String>,
    /// Messages exchanged with the simulator.
    pub round_trips: usize,
    /// Idle rate restored (it had been left at 0 by an interrupted `apply`).
    pub restored_idle_fps: Option<i32>,
    /// The simulation was running and [`ClearOptions::stop_simulation`] stopped it first.
    pub stopped_simulation: bool,
}

/// How [`clear`] runs.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct ClearOptions {
    /// Names of the scene objects.
    pub names: ObjectNames,
    /// Stop a running simulation first; without it a running simulation is refused, since
    /// CoppeliaSim undoes every removal when the simulation stops.
    pub stop_simulation: bool,
    /// Only list what would be removed.
    pub dry_run: bool,
}

/// Removes the maze lines (idempotent) and restores an idle rate left at 0 by an
/// interrupted `apply`. Refuses a running simulation as [`super::apply()`] does.
pub fn clear(scene: &mut dyn Backend, opts: &ClearOptions) -> Result<ClearReport, DrawError> {
    let rt0 = scene.round_trips();
    let claim = if opts.dry_run {
        Claim::none()
    } else {
        Claim::take(scene)?
    };
    let result = clear_claimed(scene, opts, &claim);
    let released = claim.release(scene);
    let mut report = result?;
    released?;
    report.round_trips = scene.round_trips() - rt0;
    Ok(report)
}

/// [`clear`] under `claim`.
fn clear_claimed(
    scene: &mut dyn Backend,
    opts: &ClearOptions,
    claim: &Claim,
) -> Result<ClearReport, DrawError> {
    let (names, dry_run) = (&opts.names, opts.dry_run);
    let survey = scene.survey(&names.all())?;
    let h = resolve_handles(names, &survey)?;
    let mut stopped_simulation = false;
    if survey.simulation_running {
        if !opts.stop_simulation {
            return Err(DrawError::SimulationRunning);
        }
        if !dry_run {
            scene.stop_simulation()?;
            stopped_simulation = true;
        }
    }
    let doomed = maze_lines(&survey.objects, &h, &names.line);
    let removed = doomed
        .iter()
        .filter_map(|d| {
            survey
                .objects
                .iter()
                .find(|o| o.handle == *d)
                .map(|o| o.name.clone())
        })
        .collect();
    claim.check(scene, "before removing the lines")?;
    if !doomed.is_empty() && !dry_run {
        scene.edit(&doomed.iter().map(|&d| Edit::Remove(d)).collect::<Vec<_>>())?;
    }
    let restored_idle_fps = match survey.saved_idle_fps {
        Some(fps) if !dry_run => {
            scene.set_idle_fps(fps, None)?;
            Some(fps)
        }
        _ => None,
    };
    Ok(ClearReport {
        removed,
        round_trips: 0,
        restored_idle_fps,
        stopped_simulation,
    })
}
