//! Draw a [`Drawing`]: remove the surplus, reuse earlier copies, paste only the missing ones
//! (batched doubling), place each round's copies before the next, in requests of bounded
//! server time, then verify. A wall maze with posts is drawn in two parts, walls then posts,
//! each from its own template in the same way.

use std::collections::HashMap;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use super::fit;
use super::home;
use super::lease::{Claim, claimed};
use super::plan::{self, foreign_copies, maze_lines, paste_round, pose_differences, world_frame};
use super::{
    Backend, BackendError, DrawError, Drawing, Edit, Handles, IdleRates, ObjectInfo, ObjectNames,
    Pose, Survey, TemplateUse, resolve_handles, verify,
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
    /// Set by a Ctrl-C handler: the run stops after the request in flight, restores the
    /// idle rate and fails with [`DrawError::Interrupted`].
    pub interrupt: Option<Arc<AtomicBool>>,
    /// Grow a floor smaller than the layout's to its size ([`super::floor::resize`]; the
    /// ZeroMQ API only) instead of refusing with [`DrawError::Floor`].
    pub resize_floor: bool,
}

impl Default for ApplyOptions {
    fn default() -> Self {
        ApplyOptions {
            names: ObjectNames::default(),
            stop_simulation: false,
            dry_run: false,
            paste_blocks_per_round: 16,
            interrupt: None,
            resize_floor: false,
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
    /// Lines placed so far (parent and pose sent, or found in place) / in all.
    Placing {
        /// Lines (or walls and posts) placed so far.
        done: usize,
        /// Lines (or walls and posts) in the drawing.
        total: usize,
    },
    /// The work planned, before any change: [`super::estimate::copies_draw`] prices it.
    Planned(super::estimate::CopiesWork),
    /// Reading back.
    Verifying,
}

/// What [`apply`] did. In copies mode the counts add up: `lines + posts` = `unchanged +
/// placed + pasted` (the drawing's lines and posts), and `unchanged + placed` = `reused`,
/// plus the template itself in a line maze with lines; the markers are counted apart.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ApplyReport {
    /// Lines or walls: what `lines` counts.
    pub style: super::Style,
    /// Lines drawn (template included), or walls.
    pub lines: usize,
    /// Posts drawn (a wall maze with posts), else 0.
    pub posts: usize,
    /// Mesh mode (`--draw mesh`): the meshes the maze is drawn as (then `lines` and `posts`
    /// count rectangles and boxes, `reused` meshes kept, `pasted` meshes created); 0 in
    /// copies mode.
    pub meshes: usize,
    /// Earlier copies reused (kept), the template not counted.
    pub reused: usize,
    /// Copies pasted.
    pub pasted: usize,
    /// Earlier copies removed (the surplus, another style's copies); mesh mode: the
    /// earlier meshes and copies removed.
    pub removed: usize,
    /// Copies mode: the objects of an earlier mesh maze removed (its meshes and their
    /// holder), counted apart from the copies.
    pub removed_meshes: usize,
    /// Lines and posts kept (the template, reused copies) that were already in place: no
    /// edit sent. Mesh mode: the meshes kept.
    pub unchanged: usize,
    /// Lines and posts kept whose pose (or parent) was sent: found elsewhere, or a pose the
    /// backend had not read (ZeroMQ sends a reused copy's pose rather than read it first).
    pub placed: usize,
    /// Of `placed`: poses sent unread, perhaps in place already (ZeroMQ reads a copy's pose
    /// no more cheaply than it sets it, one round trip each, so it sets it unread).
    pub unread: usize,
    /// Markers already in place: `Start`, `End` and the line template where it is not a
    /// line (hidden under `Start` in a one-cell maze; in mesh mode, on the first line).
    pub markers_unchanged: usize,
    /// Markers whose pose was sent (or, on a dry run, would be).
    pub markers_placed: usize,
    /// Edits sent.
    pub edits: usize,
    /// Round trips.
    pub round_trips: usize,
    /// Wall time.
    pub elapsed: Duration,
    /// The simulation was running when the scene was read.
    pub simulation_running: bool,
    /// The simulation was stopped first.
    pub stopped_simulation: bool,
    /// Dry run: nothing was changed.
    pub dry_run: bool,
    /// What the user should know: markers larger than a cell, sizes not read
    /// ([`super::fit::check_sizes`]).
    pub warnings: Vec<String>,
    /// The floor grown to the layout's (`--resize-floor`, [`super::floor::resize`]): one
    /// line saying from what size to what.
    pub floor: Option<String>,
    /// The user's objects under the maze dummy (and root objects named like copies of a
    /// template but of another type): left alone ([`plan::sort_out`]).
    pub left_alone: Vec<String>,
}

impl ApplyReport {
    /// `true` when the scene already shows the drawing: nothing to paste, remove or place,
    /// and no simulation to stop (on a dry run: nothing a real run would change).
    pub fn nothing_to_do(&self) -> bool {
        self.pasted == 0
            && self.removed == 0
            && self.removed_meshes == 0
            && self.placed == 0
            && self.markers_placed == 0
            && !self.simulation_running
            && self.floor.is_none()
    }
}

impl std::fmt::Display for ApplyReport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let posts = if self.posts > 0 {
            format!(" and {} posts", self.posts)
        } else {
            String::new()
        };
        let cost = format!(
            "{} round trip(s), {:.2} s",
            self.round_trips,
            self.elapsed.as_secs_f64()
        );
        if self.dry_run && self.nothing_to_do() {
            let what = if self.meshes > 0 {
                format!("{} mesh(es)", self.meshes)
            } else {
                format!("{} {}{posts}", self.lines, self.style.name())
            };
            return write!(
                f,
                "nothing to do: the scene already shows this layout ({what}, markers in place); {cost}"
            );
        }
        let verb = if self.dry_run { "would draw" } else { "drew" };
        // Start and End, and the line template where it is no line of copies (on the first
        // line of a mesh maze, under `Start` in a one-cell maze): counted with them
        let what = if self.markers_unchanged + self.markers_placed > 2 {
            "Start, End and the line template"
        } else {
            "markers"
        };
        let markers = format!(
            "{what}: {} already in place, {} placed",
            self.markers_unchanged, self.markers_placed
        );
        if self.meshes > 0 {
            return write!(
                f,
                "{verb} {} {} runs{posts} as {} mesh(es): {} kept, {} created; {markers}; {} earlier object(s) removed; {cost}",
                self.lines,
                self.style.name().trim_end_matches('s'),
                self.meshes,
                self.reused,
                self.pasted,
                self.removed,
            );
        }
        let kept = self.unchanged + self.placed;
        let template = kept > self.reused;
        let of = match (template, self.reused) {
            (_, _) if kept == 0 => String::new(),
            (true, 0) => "the template: ".to_string(),
            (true, n) => format!("the template and {n} earlier copies: "),
            (false, n) => format!("{n} earlier copies: "),
        };
        let kept = if kept == 0 {
            "0 kept".to_string()
        } else {
            let unread = if self.unread > 0 {
                format!(
                    ", {} set unread, as reading costs what setting does",
                    self.unread
                )
            } else {
                String::new()
            };
            format!(
                "{kept} kept ({of}{} already in place, {} placed{unread})",
                self.unchanged,
                self.placed - self.unread
            )
        };
        let meshes = if self.removed_meshes > 0 {
            format!(
                "; {} object(s) of an earlier mesh maze removed",
                self.removed_meshes
            )
        } else {
            String::new()
        };
        write!(
            f,
            "{verb} {} {}{posts}: {kept}, {} pasted; {markers}; {} earlier copies removed{meshes}; {cost}",
            self.lines,
            self.style.name(),
            self.pasted,
            self.removed,
        )
    }
}

/// Draws `drawing` into `scene` and verifies it. The idle rate is raised (idle fps 0) before
/// the scene is read and restored afterwards, also on error or interrupt. The run claims the
/// scene first ([`super::lease`]) and fails with [`DrawError::Concurrent`] if another run
/// takes it over.
pub fn apply(
    scene: &mut dyn Backend,
    drawing: &Drawing,
    opts: &ApplyOptions,
    progress: &mut dyn FnMut(Stage),
) -> Result<ApplyReport, DrawError> {
    // two roles on one object: refused before anything is sent
    opts.names.check_roles()?;
    raised_and_claimed(scene, opts.dry_run, |scene, claim| {
        apply_claimed(scene, drawing, opts, progress, claim)
    })
}

/// Runs a draw's `work` as every draw runs ([`apply`], [`super::mesh::apply()`]): with the
/// idle rate raised ([`raised`]) and the scene claimed ([`claimed`]), counting its round
/// trips and wall time into the report it returns.
pub(crate) fn raised_and_claimed(
    scene: &mut dyn Backend,
    dry_run: bool,
    work: impl FnOnce(&mut dyn Backend, &Claim) -> Result<ApplyReport, DrawError>,
) -> Result<ApplyReport, DrawError> {
    let started = Instant::now();
    let rt0 = scene.round_trips();
    // the rate first: every call before it waits for an idle pass (the claim too)
    let (mut report, _) = raised(scene, dry_run, |scene| {
        claimed(scene, dry_run, |scene, claim| {
            let mut report = work(scene, claim)?;
            report
                .warnings
                .splice(0..0, claim.warning().map(str::to_string));
            Ok(report)
        })
    })?;
    report.round_trips = scene.round_trips() - rt0;
    report.elapsed = started.elapsed();
    Ok(report)
}

/// Reads the scene for drawing what `asks` says (with `posts`: the post template too): the
/// survey and the handles of the named objects, or [`DrawError::Missing`] whose hints give
/// the layout's sizes.
pub fn surveyed(
    scene: &mut dyn Backend,
    names: &ObjectNames,
    asks: &TemplateUse<'_>,
    posts: bool,
) -> Result<(Survey, Handles), DrawError> {
    let survey = scene.survey(&names.survey(asks.style))?;
    let h = resolve_handles(names, asks.style, &survey, posts, Some(asks.sizes))?;
    Ok((survey, h))
}

/// Deals with a simulation the survey found `running` before anything is changed: refuses
/// it ([`DrawError::SimulationRunning`]) unless `stop` is asked, then stops it unless
/// `dry_run`. Returns whether it was stopped.
pub(crate) fn stop_running_simulation(
    scene: &mut dyn Backend,
    running: bool,
    stop: bool,
    dry_run: bool,
) -> Result<bool, DrawError> {
    if !running {
        return Ok(false);
    }
    if !stop {
        return Err(DrawError::SimulationRunning);
    }
    if !dry_run {
        scene.stop_simulation()?;
        return Ok(true);
    }
    Ok(false)
}

impl ApplyOptions {
    /// Whether Ctrl-C asked the run to stop ([`ApplyOptions::interrupt`]).
    pub fn interrupted(&self) -> bool {
        self.interrupt
            .as_ref()
            .is_some_and(|flag| flag.load(Ordering::SeqCst))
    }
}

/// Runs `work` with the idle rate raised to 0 (unless `dry_run`), so that reading and
/// drawing are not paced by CoppeliaSim's idle main loop (8 passes a second by default: a
/// ZeroMQ call then takes 93-125 ms instead of 0.45 ms, `../shared/spec/real-coppeliasim-4.5.1.md`),
/// and restores the user's rate afterwards, whatever `work` returned. The user's rate is
/// recorded in the scene while it is raised, so an interrupted run is repaired by the next.
/// Returns `work`'s value and the rates found.
pub(crate) fn raised<T>(
    scene: &mut dyn Backend,
    dry_run: bool,
    work: impl FnOnce(&mut dyn Backend) -> Result<T, DrawError>,
) -> Result<(T, IdleRates), DrawError> {
    let rates = scene.idle_rates()?;
    // an interrupted earlier run may have left the rate at 0 and recorded the user's value
    let user_fps = rates.saved.unwrap_or(rates.current);
    let raise = !dry_run && (user_fps != 0 || rates.saved.is_some());
    raised_from(scene, rates, raise.then_some(user_fps), work)
}

/// [`raised`] for a run that only reads (`vrep-maze inspect`): the user's rate is raised and
/// restored as a draw does it, but a rate an interrupted run left at 0 with its record is
/// left exactly as found (reads are fast at 0 already; `clear` or the next apply repairs it,
/// and the report says so). Returns `work`'s value and the rates found.
pub fn raised_to_read<T, E: From<BackendError>>(
    scene: &mut dyn Backend,
    work: impl FnOnce(&mut dyn Backend) -> Result<T, E>,
) -> Result<(T, IdleRates), E> {
    let rates = scene.idle_rates()?;
    let raise = rates.saved.is_none() && rates.current != 0;
    raised_from(scene, rates, raise.then_some(rates.current), work)
}

/// Runs `work` with the idle rate at 0 when `user_fps` is given (recorded in the scene while
/// raised), restoring it to `user_fps` afterwards whatever `work` returned.
fn raised_from<T, E: From<BackendError>>(
    scene: &mut dyn Backend,
    rates: IdleRates,
    user_fps: Option<i32>,
    work: impl FnOnce(&mut dyn Backend) -> Result<T, E>,
) -> Result<(T, IdleRates), E> {
    if let Some(fps) = user_fps {
        scene.set_idle_fps(0, Some(fps))?;
    }
    let result = work(scene);
    let restored = match user_fps {
        Some(fps) => scene.set_idle_fps(fps, None),
        None => Ok(()),
    };
    let value = result?;
    restored?;
    Ok((value, rates))
}

/// [`apply`] under `claim`, with the idle rate raised.
fn apply_claimed(
    scene: &mut dyn Backend,
    drawing: &Drawing,
    opts: &ApplyOptions,
    progress: &mut dyn FnMut(Stage),
    claim: &Claim,
) -> Result<ApplyReport, DrawError> {
    let style = drawing.style;
    let names = &opts.names;
    let posts = !drawing.posts.is_empty();
    let counts = ApplyReport {
        style,
        lines: drawing.lines.len(),
        posts: drawing.posts.len(),
        ..Default::default()
    };
    let Begun {
        survey,
        h,
        mut report,
        objects,
    } = begin(
        scene,
        opts,
        &drawing.template_use(),
        posts,
        counts,
        progress,
    )?;
    let objects = &objects;
    let others = names.others(style);
    // an earlier mesh maze (`--draw mesh`) goes whole, and none of it is reused as a copy
    let leftovers = super::mesh::leftovers(scene, names, &h, &survey.objects)?;
    report
        .left_alone
        .extend(leftovers.left_alone.iter().cloned());
    let meshes: Vec<i32> = leftovers.ours.iter().map(|(x, _)| *x).collect();
    // the holder, ours or the user's, is never a line
    let mesh_maze = |x: &i32| meshes.contains(x) || Some(*x) == leftovers.holder;
    let mut existing = maze_lines(objects, &h, names.template(style), &others);
    existing.retain(|x| !mesh_maze(x));
    let earlier = EarlierLines::of(
        match style {
            super::Style::Lines => !existing.is_empty(),
            super::Style::Walls => has_line_copies(objects, &h, &names.line),
        },
        leftovers.ours.iter().map(|(_, name)| name.as_str()),
    );
    let copies_needed = drawing
        .lines
        .len()
        .saturating_sub(usize::from(drawing.template_drawn()));
    let mut parts = vec![Part {
        template: h.line,
        template_drawn: drawing.template_drawn(),
        poses: &drawing.lines,
        plan: plan::plan(&existing, copies_needed),
    }];
    if let Some(template) = h.post.filter(|_| posts) {
        let existing = foreign_copies(objects, &h, &[&names.post]);
        parts.push(Part {
            template,
            template_drawn: false,
            poses: &drawing.posts,
            plan: plan::plan(&existing, drawing.posts.len()),
        });
    }
    // an earlier maze of the other style goes (a wall is no line, nor a line a wall), and
    // its posts unless this maze has posts too
    let mut foreign = foreign_copies(objects, &h, &names.foreign(style, posts));
    foreign.retain(|x| !mesh_maze(x));
    report.removed_meshes = meshes.len();
    foreign.extend(meshes);
    if !drawing.template_drawn() {
        let floor = objects
            .iter()
            .find(|o| o.handle == h.floor)
            .map(world_frame)
            .unwrap_or_default();
        let mut templates = vec![(names.template(style), h.line)];
        templates.extend(h.post.filter(|_| posts).map(|p| (names.post.as_str(), p)));
        report.warnings.extend(plan::templates_on_the_maze(
            drawing, objects, &floor, &templates,
        ));
    }
    for part in &parts {
        report.reused += part.plan.reuse.len();
        report.removed += part.plan.remove.len();
        report.pasted += part.plan.paste;
    }
    report.removed += foreign.len() - report.removed_meshes;
    let kept: usize = parts.iter().map(|part| part.plan.reuse.len()).sum();
    progress(Stage::Planned(super::estimate::CopiesWork {
        objects: survey.objects.len(),
        removed: report.removed + report.removed_meshes,
        placed: kept + usize::from(drawing.template_drawn()) + 2,
        pasted: report.pasted,
        kept_children: kept,
        blocks_per_round: opts.paste_blocks_per_round,
    }));
    if opts.dry_run {
        // what a real run would place: compared as it compares, with every pose read (a
        // backend may not have read the copies' poses in the survey), nothing written
        let unread = objects
            .iter()
            .any(|o| o.position.iter().any(|x| x.is_nan()));
        let read;
        let objects = if unread {
            read = plan::sort_out(&scene.objects()?, &h, &names.templates(), &survey.traits);
            &read.objects
        } else {
            objects
        };
        placements(&parts, drawing, &h, objects, &mut report);
        return Ok(report);
    }
    let line_template = survey.handles.get(5).copied().flatten();
    keep_home(
        scene,
        claim.signals_kept(),
        drawing.template_drawn(),
        &h,
        objects,
        earlier,
        line_template,
        names,
        &mut report,
    )?;
    let mut run = Drawer {
        scene,
        drawing,
        opts,
        h: &h,
        claim,
        progress,
        report: &mut report,
        objects_in_scene: survey.objects.len(),
        placed: 0,
        traits: &survey.traits,
        holder: leftovers.holder,
    };
    run.draw(objects, &parts, &foreign)?;
    Ok(report)
}

/// The kept objects' places: the edits that put each part's template (a line maze's) and
/// reused copies, and the markers, where `drawing` wants them (relative to the floor),
/// leaving out those `objects` shows there already; counted into `report`.
struct Placements {
    /// The edits to send.
    edits: Vec<Edit>,
    /// The objects drawn so far per part, `drawn[p][i]` for `parts[p].poses[i]`: a line
    /// maze starts with the template itself, walls and posts with copies only.
    drawn: Vec<Vec<i32>>,
    /// Lines and posts kept (in place or placed).
    kept: usize,
}

/// Decides [`Placements`] for `parts` from the scene's `objects`, counting the kept lines
/// and markers found in place or placed into `report`; sends nothing.
fn placements(
    parts: &[Part<'_>],
    drawing: &Drawing,
    h: &Handles,
    objects: &[ObjectInfo],
    report: &mut ApplyReport,
) -> Placements {
    let by_handle: HashMap<i32, &ObjectInfo> = objects.iter().map(|o| (o.handle, o)).collect();
    let known = |handle: i32| by_handle.get(&handle).copied();
    let floor = known(h.floor).map(world_frame).unwrap_or_default();
    let mut out = Placements {
        edits: Vec::new(),
        drawn: Vec::with_capacity(parts.len()),
        kept: 0,
    };
    let mut markers = Vec::new();
    for part in parts {
        let mut copies = if part.template_drawn {
            vec![part.template]
        } else {
            vec![]
        };
        copies.extend(&part.plan.reuse);
        for (i, (&handle, want)) in copies.iter().zip(part.poses).enumerate() {
            let parent = (i > 0 || !part.template_drawn).then_some(h.parent);
            let current = known(handle);
            let edits = place(current, &floor, h.floor, handle, want, parent);
            if edits.is_empty() {
                report.unchanged += 1;
            } else {
                report.placed += 1;
                if current.is_some_and(|o| o.position.iter().any(|x| x.is_nan())) {
                    report.unread += 1;
                }
            }
            out.edits.extend(edits);
            out.kept += 1;
        }
        if part.poses.is_empty() && part.template_drawn {
            // no segment (a 1-cell maze): the template goes below the floor, out of
            // every camera's sight, rather than lie on the maze
            markers.push((
                part.template,
                home::Home::hidden(drawing.start.x, drawing.start.y),
            ));
        }
        out.drawn.push(copies);
    }
    markers.push((h.start, drawing.start));
    markers.push((h.end, drawing.end));
    for (handle, want) in markers {
        let edits = place(known(handle), &floor, h.floor, handle, &want, None);
        if edits.is_empty() {
            report.markers_unchanged += 1;
        } else {
            report.markers_placed += 1;
        }
        out.edits.extend(edits);
    }
    out
}

/// The edits that put `handle` at `want` (relative to the floor, under `parent`), none if
/// `current` shows it there already.
fn place(
    current: Option<&ObjectInfo>,
    floor: &vrep_maze_core::coppelia::frame::Frame,
    floor_handle: i32,
    handle: i32,
    want: &Pose,
    parent: Option<i32>,
) -> Vec<Edit> {
    let parent_ok = parent.is_none_or(|p| current.is_some_and(|o| o.parent == Some(p)));
    let pose_ok = current.is_some_and(|o| pose_differences(floor, o, want).is_none());
    let mut edits = Vec::new();
    if parent_ok && pose_ok {
        return edits;
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
        relative_to: floor_handle,
        position: crate::draw::position(want),
        orientation: crate::draw::euler(want),
    });
    edits
}

/// The earlier line maze a drawing finds, which tells whether the line template already lies
/// on one of its lines ([`keep_home`]). A wall maze never moves the line template, so an
/// earlier wall maze is none.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum EarlierLines {
    /// No line maze: the template stands where the user put it.
    None,
    /// Copies of the line template under the maze dummy.
    Copies,
    /// A line maze drawn as meshes (`--draw mesh`, or loaded from `export -o
    /// x.simscene.xml`, which puts the template on the first line, under a mesh).
    Meshes,
}

impl EarlierLines {
    /// What `line_copies` (copies of the line template under the maze dummy) and the names
    /// of an earlier mesh maze's objects say.
    pub fn of<'a>(line_copies: bool, meshes: impl IntoIterator<Item = &'a str>) -> Self {
        let line_meshes = meshes.into_iter().any(|name| {
            super::mesh::parse_mesh_name(name)
                .is_some_and(|(kind, _)| kind == super::mesh::MeshKind::Lines)
        });
        match (line_copies, line_meshes) {
            (true, _) => EarlierLines::Copies,
            (false, true) => EarlierLines::Meshes,
            (false, false) => EarlierLines::None,
        }
    }
}

/// Whether copies of the line template (`line`) lie under the maze dummy: an earlier line
/// maze a wall maze replaces.
pub(crate) fn has_line_copies(objects: &[ObjectInfo], h: &Handles, line: &str) -> bool {
    objects
        .iter()
        .any(|o| o.parent == Some(h.parent) && plan::is_copy_name(&o.name, line))
}

/// Keeps the line template's home ([`home`]) before a drawing moves it: a line maze
/// records where the template stands now, unless a record of it exists. If an earlier line
/// maze exists without a record, the template already lies on its first line, so its home is
/// taken to be below the floor: said in a warning for copies (a maze drawn by an older
/// version, or a scene saved and loaded again: the record is kept in signals, which a scene
/// file does not hold), silently for meshes (only this version draws them, and our
/// `.simscene.xml` export puts the template there, under a mesh). A wall maze hides the line
/// template ([`hide_line_template`]). Nothing where the simulator keeps no signals
/// (`signals_kept` false: the claim's warning says `clear` cannot put the template back).
#[allow(clippy::too_many_arguments)]
pub(crate) fn keep_home(
    scene: &mut dyn Backend,
    signals_kept: bool,
    template_drawn: bool,
    h: &Handles,
    objects: &[ObjectInfo],
    earlier: EarlierLines,
    line_template: Option<i32>,
    names: &ObjectNames,
    report: &mut ApplyReport,
) -> Result<(), DrawError> {
    if !signals_kept {
        return Ok(());
    }
    let (record, old) = home::read(scene)?.unzip();
    let floor = objects
        .iter()
        .find(|o| o.handle == h.floor)
        .map(world_frame)
        .unwrap_or_default();
    // an older version's record moves to the new names
    if let (Some(home), Some(true)) = (record, old) {
        home::write(scene, &home)?;
    }
    if !template_drawn {
        return hide_line_template(
            scene,
            h,
            &floor,
            objects,
            earlier,
            line_template,
            &names.line,
            record,
        );
    }
    if record.is_some_and(|r| r.handle == h.line) {
        return Ok(());
    }
    let Some(template) = objects.iter().find(|o| o.handle == h.line) else {
        return Ok(());
    };
    let (position, orientation) = plan::relative_pose(&floor, template);
    let home = if on_an_earlier_maze(scene, h, objects, template, &names.line, &floor, earlier)? {
        if earlier == EarlierLines::Copies {
            report.warnings.push(format!(
                "no record of where `{}` stood before the first apply (a maze drawn by an older vrep-maze, or a scene saved and loaded again): `clear` will put it below the floor, out of sight",
                names.line
            ));
        }
        let hidden = home::Home::hidden(position[0], position[1]);
        home::Home {
            handle: h.line,
            position: crate::draw::position(&hidden),
            orientation: crate::draw::euler(&hidden),
        }
    } else {
        home::Home {
            handle: h.line,
            position,
            orientation,
        }
    };
    home::write(scene, &home)?;
    Ok(())
}

/// Whether the line template (`template`, named `line`) lies on the earlier line maze
/// `earlier` says there is, as its first line: always on a mesh maze's (only our export puts
/// it there), on a maze of copies only if one of the copies under the maze dummy touches it
/// as a maze's lines do ([`super::first_line::lies_on_a_maze`]; its length read for it), so
/// that a user's copy of `Line` under `Maze` does not make the template's own pose a guess.
pub(crate) fn on_an_earlier_maze(
    scene: &mut dyn Backend,
    h: &Handles,
    objects: &[ObjectInfo],
    template: &ObjectInfo,
    line: &str,
    floor: &vrep_maze_core::coppelia::frame::Frame,
    earlier: EarlierLines,
) -> Result<bool, DrawError> {
    match earlier {
        EarlierLines::None => Ok(false),
        EarlierLines::Meshes => Ok(true),
        EarlierLines::Copies => {
            let copies: Vec<&ObjectInfo> = objects
                .iter()
                .filter(|o| o.parent == Some(h.parent) && plan::is_copy_name(&o.name, line))
                .collect();
            let length = scene.sizes(&[template.handle])?.first().copied().flatten();
            // a length not read: no evidence either way, so taken to be on it as before
            Ok(length.is_none_or(|size| {
                super::first_line::lies_on_a_maze(template, &copies, floor, size[0])
            }))
        }
    }
}

/// A wall maze has no line, so the line template (`line_template`, if the scene has one)
/// must not lie on its floor as a stray line for a camera to see (the course scene keeps it
/// at the floor's centre, `../shared/spec/course-scene.md`): it goes below the floor under
/// where it stood, its home recorded first unless a record exists (the first line of a line
/// maze it replaces: below the floor if that maze has no record), so that `clear`, or the
/// next line maze, puts it back.
#[allow(clippy::too_many_arguments)]
fn hide_line_template(
    scene: &mut dyn Backend,
    h: &Handles,
    floor: &vrep_maze_core::coppelia::frame::Frame,
    objects: &[ObjectInfo],
    earlier: EarlierLines,
    line_template: Option<i32>,
    line_name: &str,
    record: Option<home::Home>,
) -> Result<(), DrawError> {
    let Some(template) = line_template.and_then(|t| objects.iter().find(|o| o.handle == t)) else {
        return Ok(());
    };
    let (position, orientation) = plan::relative_pose(floor, template);
    let home = match record.filter(|r| r.handle == template.handle) {
        Some(home) => home,
        None => {
            let on_maze =
                on_an_earlier_maze(scene, h, objects, template, line_name, floor, earlier)?;
            let home = if !on_maze {
                home::Home {
                    handle: template.handle,
                    position,
                    orientation,
                }
            } else {
                let below = home::Home::hidden(position[0], position[1]);
                home::Home {
                    handle: template.handle,
                    position: crate::draw::position(&below),
                    orientation: crate::draw::euler(&below),
                }
            };
            home::write(scene, &home)?;
            home
        }
    };
    let hidden = home::Home::hidden(home.position[0], home.position[1]);
    let want = crate::draw::position(&hidden);
    if (0..3).any(|k| (position[k] - want[k]).abs() > plan::POSITION_TOLERANCE) {
        scene.edit(&[Edit::SetPose {
            handle: template.handle,
            relative_to: h.floor,
            position: want,
            orientation: crate::draw::euler(&hidden),
        }])?;
    }
    Ok(())
}

/// What a draw of either mode knows once it has looked at the scene.
pub(crate) struct Begun {
    /// The survey of the style's names.
    pub survey: Survey,
    /// The named objects' handles.
    pub h: Handles,
    /// The report so far: the counts given, the size warnings, the simulation state, the
    /// user's objects left alone.
    pub report: ApplyReport,
    /// The survey's objects without the user's ([`plan::sort_out`]).
    pub objects: Vec<ObjectInfo>,
}

/// The start both draw modes share: survey the scene, refuse templates or markers whose
/// sizes contradict what the drawing asks of them (`asks`), report the survey done, refuse
/// (or stop, as `opts` says) a running simulation, and set the user's objects apart: only
/// the templates' copies are the maze's. `counts` is the report's start (style and sizes).
pub(crate) fn begin(
    scene: &mut dyn Backend,
    opts: &ApplyOptions,
    asks: &TemplateUse<'_>,
    posts: bool,
    counts: ApplyReport,
    progress: &mut dyn FnMut(Stage),
) -> Result<Begun, DrawError> {
    let names = &opts.names;
    let (survey, h) = surveyed(scene, names, asks, posts)?;
    let sizes = sizes_of(scene, asks, names, &h)?;
    let short = sizes.floor.filter(|_| sizes.refusals.is_empty());
    if let Some(refused) = sizes.refused(names) {
        return Err(refused);
    }
    if let Some(short) = short.filter(|_| !opts.resize_floor) {
        let resize = if short.factors().is_none() {
            super::floor::Resize::NoExtent
        } else if scene.authoring().is_none() {
            super::floor::Resize::NoApi
        } else {
            super::floor::Resize::Offered
        };
        return Err(DrawError::Floor {
            floor: names.floor.clone(),
            short,
            resize,
        });
    }
    progress(Stage::Surveyed);
    let mut report = ApplyReport {
        dry_run: opts.dry_run,
        warnings: sizes.warnings,
        simulation_running: survey.simulation_running,
        ..counts
    };
    report.stopped_simulation = stop_running_simulation(
        scene,
        survey.simulation_running,
        opts.stop_simulation,
        opts.dry_run,
    )?;
    if let Some(short) = short {
        report.floor = Some(super::floor::resize(
            scene,
            h.floor,
            &names.floor,
            &short,
            opts.dry_run,
        )?);
    }
    let sorted = plan::sort_out(&survey.objects, &h, &names.templates(), &survey.traits);
    report.left_alone = sorted.strangers;
    Ok(Begun {
        survey,
        h,
        report,
        objects: sorted.objects,
    })
}

/// Reads the sizes of the template, start, end, floor and post template (if the drawing
/// has posts) ([`Backend::sizes`]: legacy in one request) and compares them with the
/// drawing's ([`fit::check_sizes`]).
pub(crate) fn sizes_of(
    scene: &mut dyn Backend,
    drawing: &TemplateUse<'_>,
    names: &ObjectNames,
    h: &Handles,
) -> Result<fit::SizeCheck, DrawError> {
    let post = h.post.filter(|_| drawing.posts);
    let mut asked = vec![h.line, h.start, h.end, h.floor];
    asked.extend(post);
    let sizes = scene.sizes(&asked)?;
    let get = |k: usize| sizes.get(k).copied().flatten();
    Ok(fit::check_sizes(
        drawing,
        names,
        &fit::Measured {
            template: get(0),
            start: get(1),
            end: get(2),
            floor: get(3),
            post: post.and_then(|_| get(4)),
        },
    ))
}

/// One template's copies in a drawing: the style's (lines or walls), or the posts.
struct Part<'a> {
    /// The template copied.
    template: i32,
    /// The template itself is the first copy (lines), else every copy is pasted.
    template_drawn: bool,
    /// Where the copies go.
    poses: &'a [Pose],
    /// The earlier copies reused and removed, and how many to paste.
    plan: plan::Plan,
}

/// One apply's drawing state: what is sent, in requests of bounded server time.
struct Drawer<'a, 'p> {
    scene: &'a mut dyn Backend,
    drawing: &'a Drawing,
    opts: &'a ApplyOptions,
    h: &'a Handles,
    claim: &'a Claim,
    progress: &'p mut dyn FnMut(Stage),
    report: &'a mut ApplyReport,
    /// Objects in the scene now (the simulator's per-object costs grow with it).
    objects_in_scene: usize,
    /// Lines whose place has been sent (or found right).
    placed: usize,
    /// What the survey read of copies and the user's objects ([`plan::sort_out`]).
    traits: &'a plan::Traits,
    /// The holder of a mesh maze the user keeps (their objects under it): no line.
    holder: Option<i32>,
}

impl Drawer<'_, '_> {
    /// Removes the surplus (each part's and the `foreign` copies), places each part's
    /// template, reused copies and the markers, then pastes each part's missing copies round
    /// by round, placing each round's copies before pasting the next (so few copies are
    /// ever parentless, which the simulator pays for per object), and verifies.
    fn draw(
        &mut self,
        objects: &[ObjectInfo],
        parts: &[Part<'_>],
        foreign: &[i32],
    ) -> Result<(), DrawError> {
        let floor = objects
            .iter()
            .find(|o| o.handle == self.h.floor)
            .map(world_frame)
            .unwrap_or_default();
        let (h, drawing) = (self.h, self.drawing);
        // the surplus goes first: fewer objects make every later copy cheaper
        let removals: Vec<Edit> = parts
            .iter()
            .flat_map(|part| &part.plan.remove)
            .chain(foreign)
            .map(|&r| Edit::Remove(r))
            .collect();
        self.send(&removals, 0)?;
        self.objects_in_scene = self.objects_in_scene.saturating_sub(removals.len());
        // the templates, reused copies and markers, where they differ, go with the first
        // round of copies (or alone, if nothing is pasted)
        let Placements {
            mut edits,
            mut drawn,
            kept: mut placed_now,
        } = placements(parts, drawing, h, objects, self.report);
        let to_paste: usize = parts.iter().map(|part| part.plan.paste).sum();
        let mut pasted = 0;
        let mut short = None;
        for (part, copies) in parts.iter().zip(&mut drawn) {
            let mut done = 0;
            // what is pasted from: only the template and the copies this run pasted from
            // it, never an earlier copy (a user's recoloured look-alike would spread)
            let mut sources = vec![part.template];
            while done < part.plan.paste {
                self.checkpoint("while pasting the lines")?;
                let budget = self.scene.lines_per_request(self.objects_in_scene).max(1);
                let groups = paste_round(
                    &sources,
                    (part.plan.paste - done).min(budget),
                    self.opts.paste_blocks_per_round,
                );
                if groups.is_empty() {
                    break;
                }
                let carried = std::mem::take(&mut placed_now);
                let mut new_lines = 0;
                for new in self.scene.copy_paste(&groups)? {
                    sources.extend(&new);
                    for handle in new {
                        if let Some(want) = part.poses.get(copies.len()) {
                            edits.extend(place(
                                None,
                                &floor,
                                h.floor,
                                handle,
                                want,
                                Some(h.parent),
                            ));
                            new_lines += 1;
                        }
                        copies.push(handle);
                        done += 1;
                        pasted += 1;
                    }
                }
                self.objects_in_scene += new_lines;
                (self.progress)(Stage::Pasting {
                    done: pasted,
                    total: to_paste,
                });
                self.send(&std::mem::take(&mut edits), carried + new_lines)?;
            }
            if done < part.plan.paste {
                short.get_or_insert((done, part.plan.paste));
            }
            copies.truncate(part.poses.len().max(usize::from(part.template_drawn)));
        }
        self.send(&edits, placed_now)?;
        if let Some((done, wanted)) = short {
            return Err(super::BackendError::Remote(format!(
                "copy-paste produced {done} of {wanted} copies"
            ))
            .into());
        }
        (self.progress)(Stage::Verifying);
        self.claim.check(self.scene, "before verifying")?;
        let after = if self.claim.contended() {
            self.scene.objects_from_scene()?
        } else {
            self.scene.objects()?
        };
        self.claim.check(self.scene, "while verifying")?;
        let mut after =
            plan::sort_out(&after, h, &self.opts.names.templates(), self.traits).objects;
        after.retain(|o| Some(o.handle) != self.holder);
        let drawn_of = |p: usize| {
            let poses = parts.get(p).map_or(0, |part| part.poses.len());
            drawn.get(p).map_or(&[][..], |d| &d[..poses.min(d.len())])
        };
        let problems = verify::check(
            &after,
            h,
            &self.opts.names,
            drawn_of(0),
            drawn_of(1),
            drawing,
        );
        if problems.is_empty() {
            Ok(())
        } else {
            Err(DrawError::Verify(problems))
        }
    }

    /// Sends `edits`, which place `lines` lines, in requests the simulator finishes in
    /// bounded time ([`Backend::lines_per_request`], about two edits a line) and the lease
    /// checks between them.
    fn send(&mut self, edits: &[Edit], lines: usize) -> Result<(), DrawError> {
        if edits.is_empty() {
            self.placed += lines;
            return Ok(());
        }
        self.report.edits += edits.len();
        let per_request = self
            .scene
            .lines_per_request(self.objects_in_scene)
            .saturating_mul(2)
            .min(self.claim.edits_per_check())
            .max(1);
        let mut sent = 0;
        for chunk in edits.chunks(per_request) {
            self.checkpoint("while placing the lines")?;
            self.scene.edit(chunk)?;
            sent += chunk.len();
            let done = self.placed + lines * sent / edits.len().max(1);
            (self.progress)(Stage::Placing {
                done: done.min(self.drawing.copies()),
                total: self.drawing.copies(),
            });
        }
        self.placed += lines;
        Ok(())
    }

    /// Stops here if the user interrupted or another run took the scene over.
    fn checkpoint(&mut self, phase: &'static str) -> Result<(), DrawError> {
        if self.opts.interrupted() {
            return Err(DrawError::Interrupted {
                placed: self.placed,
                total: self.drawing.copies(),
            });
        }
        self.claim.check(self.scene, phase)
    }
}
