//! Draw a [`Drawing`]: reuse earlier copies, paste only the missing ones (batched doubling),
//! set every parent and pose in one batch, remove the surplus, verify.

use std::time::{Duration, Instant};

use super::lease::Claim;
use super::plan::{self, maze_lines, paste_round, pose_differences, world_frame};
use super::{
    Backend, DrawError, Drawing, Edit, Handles, ObjectInfo, ObjectNames, resolve_handles, verify,
};

/// Options of [`apply`].
#[derive(Debug, Clone)]
pub struct ApplyOptions {
    /// Names of the scene objects the drawing uses.
    pub names: ObjectNames,
    /// Stop a running simulation instead of refusing.
    pub stop_simulation: bool,
    /// Only survey and plan; change nothing.
    pub dry_run: bool,
    /// Copy-paste commands per round trip (each copies the whole current set of lines).
    pub paste_blocks_per_round: usize,
}

impl Default for ApplyOptions {
    fn default() -> Self {
        ApplyOptions {
            names: ObjectNames::default(),
            stop_simulation: false,
            dry_run: false,
            paste_blocks_per_round: 16,
        }
    }
}

/// Progress of [`apply`], for a progress display.
#[derive(Debug, Clone, PartialEq)]
pub enum Stage {
    /// The scene has been read (names resolved, objects listed).
    Surveyed,
    /// Copies pasted so far / to paste.
    Pasting {
        /// Copies pasted so far.
        done: usize,
        /// Copies this apply pastes in all.
        total: usize,
    },
    /// Setting parents and poses.
    Placing,
    /// Reading back.
    Verifying,
}

/// What [`apply`] did.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ApplyReport {
    /// Lines drawn (template included).
    pub lines: usize,
    /// Earlier copies reused.
    pub reused: usize,
    /// Copies pasted.
    pub pasted: usize,
    /// Earlier copies removed.
    pub removed: usize,
    /// Objects already in place (no edit sent).
    pub unchanged: usize,
    /// Edits sent.
    pub edits: usize,
    /// Round trips.
    pub round_trips: usize,
    /// Wall time.
    pub elapsed: Duration,
    /// The simulation was stopped first.
    pub stopped_simulation: bool,
    /// Dry run: nothing was changed.
    pub dry_run: bool,
}

impl std::fmt::Display for ApplyReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let verb = if self.dry_run { "would draw" } else { "drew" };
        write!(
            f,
            "{verb} {} lines: {} reused, {} pasted, {} removed, {} already in place; {} round trip(s), {:.2} s",
            self.lines,
            self.reused,
            self.pasted,
            self.removed,
            self.unchanged,
            self.round_trips,
            self.elapsed.as_secs_f64()
        )
    }
}

/// Draws `drawing` into `scene` and verifies it. The idle rate is raised (idle fps 0) while
/// drawing and restored afterwards, also on error. The run claims the scene first
/// ([`super::lease`]) and fails with [`DrawError::Concurrent`] if another run takes it over.
pub fn apply(
    scene: &mut dyn Backend,
    drawing: &Drawing,
    opts: &ApplyOptions,
    progress: &mut dyn FnMut(Stage),
) -> Result<ApplyReport, DrawError> {
    let started = Instant::now();
    let rt0 = scene.round_trips();
    if opts.dry_run {
        return apply_claimed(scene, drawing, opts, progress, &Claim::none(), started, rt0);
    }
    let claim = Claim::take(scene)?;
    let result = apply_claimed(scene, drawing, opts, progress, &claim, started, rt0);
    let released = claim.release(scene);
    let mut report = result?;
    released?;
    report.round_trips = scene.round_trips() - rt0;
    Ok(report)
}

/// [`apply`] under `claim`.
#[allow(clippy::too_many_arguments)]
fn apply_claimed(
    scene: &mut dyn Backend,
    drawing: &Drawing,
    opts: &ApplyOptions,
    progress: &mut dyn FnMut(Stage),
    claim: &Claim,
    started: Instant,
    rt0: usize,
) -> Result<ApplyReport, DrawError> {
    let survey = scene.survey(&opts.names.all())?;
    let h = resolve_handles(&opts.names, &survey)?;
    progress(Stage::Surveyed);
    let mut report = ApplyReport {
        lines: drawing.lines.len(),
        dry_run: opts.dry_run,
        ..Default::default()
    };
    if survey.simulation_running {
        if !opts.stop_simulation {
            return Err(DrawError::SimulationRunning);
        }
        if !opts.dry_run {
            scene.stop_simulation()?;
            report.stopped_simulation = true;
        }
    }
    let existing = maze_lines(&survey.objects, &h, &opts.names.line);
    let copies_needed = drawing.lines.len().saturating_sub(1);
    let p = plan::plan(&existing, copies_needed);
    report.reused = p.reuse.len();
    report.removed = p.remove.len();
    report.pasted = p.paste;
    if opts.dry_run {
        report.round_trips = scene.round_trips() - rt0;
        report.elapsed = started.elapsed();
        return Ok(report);
    }
    // an interrupted earlier run may have left the rate at 0 and recorded the user's value
    let user_fps = survey.saved_idle_fps.unwrap_or(survey.idle_fps);
    let raise = user_fps != 0 || survey.saved_idle_fps.is_some();
    if raise {
        scene.set_idle_fps(0, Some(user_fps))?;
    }
    let result = draw(
        scene,
        drawing,
        opts,
        &h,
        &survey.objects,
        p,
        &mut report,
        progress,
        claim,
    );
    let restored = if raise {
        scene.set_idle_fps(user_fps, None)
    } else {
        Ok(())
    };
    result?;
    restored?;
    report.round_trips = scene.round_trips() - rt0;
    report.elapsed = started.elapsed();
    Ok(report)
}

#[allow(clippy::too_many_arguments)]
fn draw(
    scene: &mut dyn Backend,
    drawing: &Drawing,
    opts: &ApplyOptions,
    h: &Handles,
    objects: &[ObjectInfo],
    p: plan::Plan,
    report: &mut ApplyReport,
    progress: &mut dyn FnMut(Stage),
    claim: &Claim,
) -> Result<(), DrawError> {
    // lines in segment order: template first, then reused copies, then pasted ones
    let mut lines = vec![h.line];
    lines.extend(&p.reuse);
    let mut pasted = 0;
    while pasted < p.paste {
        claim.check(scene, "while pasting the lines")?;
        let groups = paste_round(&lines, p.paste - pasted, opts.paste_blocks_per_round);
        if groups.is_empty() {
            break;
        }
        for new in scene.copy_paste(&groups)? {
            pasted += new.len();
            lines.extend(new);
        }
        progress(Stage::Pasting {
            done: pasted,
            total: p.paste,
        });
    }
    if pasted < p.paste {
        return Err(super::BackendError::Remote(format!(
            "copy-paste produced {pasted} of {} copies",
            p.paste
        ))
        .into());
    }
    lines.truncate(drawing.lines.len().max(1));
    progress(Stage::Placing);
    let floor = objects
        .iter()
        .find(|o| o.handle == h.floor)
        .map(world_frame)
        .unwrap_or_default();
    let by_handle = |handle: i32| objects.iter().find(|o| o.handle == handle);
    let mut edits = Vec::new();
    let mut place =
        |edits: &mut Vec<Edit>, handle: i32, want: &super::Pose, parent: Option<i32>| {
            let current = by_handle(handle);
            let parent_ok = parent.is_none_or(|p| current.is_some_and(|o| o.parent == Some(p)));
            let pose_ok = current.is_some_and(|o| pose_differences(&floor, o, want).is_none());
            if parent_ok && pose_ok {
                report.unchanged += 1;
                return;
            }
            if let Some(p) = parent
                && !parent_ok
            {
                edits.push(Edit::SetParent {
                    handle,
                    parent: Some(p),
                    keep_in_place: false,
                });
            }
            edits.push(Edit::SetPose {
                handle,
                relative_to: h.floor,
                position: crate::draw::position(want),
                orientation: crate::draw::euler(want),
            });
        };
    for (i, (handle, want)) in lines.iter().zip(&drawing.lines).enumerate() {
        place(&mut edits, *handle, want, (i > 0).then_some(h.parent));
    }
    if drawing.lines.is_empty() {
        // no segment (a 1-cell maze): hide the template under Start rather than leave it lying
        let hidden = super::Pose {
            z: (drawing.start.z - 0.001).max(0.0),
            yaw: drawing.start.yaw,
            ..drawing.start
        };
        place(&mut edits, h.line, &hidden, None);
    }
    place(&mut edits, h.start, &drawing.start, None);
    place(&mut edits, h.end, &drawing.end, None);
    edits.extend(p.remove.iter().map(|&r| Edit::Remove(r)));
    report.edits = edits.len();
    for chunk in edits.chunks(claim.edits_per_check()) {
        claim.check(scene, "while placing the lines")?;
        scene.edit(chunk)?;
    }
    progress(Stage::Verifying);
    claim.check(scene, "before verifying")?;
    let after = scene.objects()?;
    claim.check(scene, "while verifying")?;
    let problems = verify::check(
        &after,
        h,
        &opts.names.line,
        &lines[..drawing.lines.len().min(lines.len())],
        drawing,
    );
    if problems.is_empty() {
        Ok(())
    } else {
        Err(DrawError::Verify(problems))
    }
}
