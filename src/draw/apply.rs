//! Draw a [`Drawing`]: remove the surplus, reuse earlier copies, paste only the missing ones
//! (batched doubling), place each round's copies before the next, in requests of bounded
//! server time, then verify. A wall maze with posts is drawn in two parts, walls then posts,
//! each from its own template in the same way.

use std::collections::HashMap;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use super::lease::{Claim, claimed};
use super::plan::{self, foreign_copies, maze_lines, paste_round, pose_differences, world_frame};
use super::{
    Backend, DrawError, Drawing, Edit, Handles, IdleRates, ObjectInfo, ObjectNames, Pose,
    resolve_handles, verify,
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
}

impl Default for ApplyOptions {
    fn default() -> Self {
        ApplyOptions {
            names: ObjectNames::default(),
            stop_simulation: false,
            dry_run: false,
            paste_blocks_per_round: 16,
            interrupt: None,
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
    /// Reading back.
    Verifying,
}

/// What [`apply`] did.
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
        let posts = if self.posts > 0 {
            format!(" and {} posts", self.posts)
        } else {
            String::new()
        };
        if self.meshes > 0 {
            return write!(
                f,
                "{verb} {} {} runs{posts} as {} mesh(es): {} kept, {} created, {} object(s) removed; {} round trip(s), {:.2} s",
                self.lines,
                self.style.name().trim_end_matches('s'),
                self.meshes,
                self.reused,
                self.pasted,
                self.removed,
                self.round_trips,
                self.elapsed.as_secs_f64()
            );
        }
        write!(
            f,
            "{verb} {} {}{posts}: {} reused, {} pasted, {} removed, {} already in place; {} round trip(s), {:.2} s",
            self.lines,
            self.style.name(),
            self.reused,
            self.pasted,
            self.removed,
            self.unchanged,
            self.round_trips,
            self.elapsed.as_secs_f64()
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
    let started = Instant::now();
    let rt0 = scene.round_trips();
    // the rate first: every call before it waits for an idle pass (the claim too)
    let (mut report, _) = raised(scene, opts.dry_run, |scene| {
        claimed(scene, opts.dry_run, |scene, claim| {
            apply_claimed(scene, drawing, opts, progress, claim)
        })
    })?;
    report.round_trips = scene.round_trips() - rt0;
    report.elapsed = started.elapsed();
    Ok(report)
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
    if raise {
        scene.set_idle_fps(0, Some(user_fps))?;
    }
    let result = work(scene);
    let restored = if raise {
        scene.set_idle_fps(user_fps, None)
    } else {
        Ok(())
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
    let survey = scene.survey(&names.survey(style))?;
    let h = resolve_handles(names, style, &survey, posts)?;
    progress(Stage::Surveyed);
    let mut report = ApplyReport {
        style,
        lines: drawing.lines.len(),
        posts: drawing.posts.len(),
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
    let others = names.others(style);
    // an earlier mesh maze (`--draw mesh`) goes whole, and none of it is reused as a copy
    let meshes = super::mesh::leftovers(scene, names, &h, &survey.objects)?;
    let mut existing = maze_lines(&survey.objects, &h, names.template(style), &others);
    existing.retain(|x| !meshes.contains(x));
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
        let existing = foreign_copies(&survey.objects, &h, &[&names.post]);
        parts.push(Part {
            template,
            template_drawn: false,
            poses: &drawing.posts,
            plan: plan::plan(&existing, drawing.posts.len()),
        });
    }
    // an earlier maze of the other style goes (a wall is no line, nor a line a wall), and
    // its posts unless this maze has posts too
    let mut foreign = foreign_copies(&survey.objects, &h, &names.foreign(style, posts));
    foreign.retain(|x| !meshes.contains(x));
    foreign.extend(meshes);
    for part in &parts {
        report.reused += part.plan.reuse.len();
        report.removed += part.plan.remove.len();
        report.pasted += part.plan.paste;
    }
    report.removed += foreign.len();
    if !opts.dry_run {
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
        };
        run.draw(&survey.objects, &parts, &foreign)?;
    }
    Ok(report)
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
        let by_handle: HashMap<i32, &ObjectInfo> = objects.iter().map(|o| (o.handle, o)).collect();
        let known = |handle: i32| by_handle.get(&handle).copied();
        let floor = known(self.h.floor).map(world_frame).unwrap_or_default();
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
        let mut edits: Vec<Edit> = Vec::new();
        // the objects drawn per part, `drawn[p][i]` for `parts[p].poses[i]`: a line maze
        // starts with the template itself, walls and posts with copies only
        let mut drawn: Vec<Vec<i32>> = Vec::with_capacity(parts.len());
        let mut placed_now = 0;
        for part in parts {
            let mut copies = if part.template_drawn {
                vec![part.template]
            } else {
                vec![]
            };
            copies.extend(&part.plan.reuse);
            for (i, (&handle, want)) in copies.iter().zip(part.poses).enumerate() {
                let parent = (i > 0 || !part.template_drawn).then_some(h.parent);
                self.place(&mut edits, known(handle), &floor, handle, want, parent);
                placed_now += 1;
            }
            if part.poses.is_empty() && part.template_drawn {
                // no segment (a 1-cell maze): hide the template under Start rather than
                // leave it lying
                let hidden = Pose {
                    z: (drawing.start.z - 0.001).max(0.0),
                    yaw: drawing.start.yaw,
                    ..drawing.start
                };
                let t = part.template;
                self.place(&mut edits, known(t), &floor, t, &hidden, None);
            }
            drawn.push(copies);
        }
        for (handle, want) in [(h.start, &drawing.start), (h.end, &drawing.end)] {
            self.place(&mut edits, known(handle), &floor, handle, want, None);
        }
        let to_paste: usize = parts.iter().map(|part| part.plan.paste).sum();
        let mut pasted = 0;
        let mut short = None;
        for (part, copies) in parts.iter().zip(&mut drawn) {
            let mut done = 0;
            while done < part.plan.paste {
                self.checkpoint("while pasting the lines")?;
                let budget = self.scene.lines_per_request(self.objects_in_scene).max(1);
                // with nothing drawn yet (walls, posts), the first copy is the template's
                let sources = if copies.is_empty() {
                    std::slice::from_ref(&part.template)
                } else {
                    &copies[..]
                };
                let groups = paste_round(
                    sources,
                    (part.plan.paste - done).min(budget),
                    self.opts.paste_blocks_per_round,
                );
                if groups.is_empty() {
                    break;
                }
                let carried = std::mem::take(&mut placed_now);
                let mut new_lines = 0;
                for new in self.scene.copy_paste(&groups)? {
                    for handle in new {
                        if let Some(want) = part.poses.get(copies.len()) {
                            self.place(&mut edits, None, &floor, handle, want, Some(h.parent));
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

    /// Adds the edits that put `handle` at `want` (under `parent`), unless `current` shows
    /// it there already.
    fn place(
        &mut self,
        edits: &mut Vec<Edit>,
        current: Option<&ObjectInfo>,
        floor: &crate::coppelia::frame::Frame,
        handle: i32,
        want: &Pose,
        parent: Option<i32>,
    ) {
        let parent_ok = parent.is_none_or(|p| current.is_some_and(|o| o.parent == Some(p)));
        let pose_ok = current.is_some_and(|o| pose_differences(floor, o, want).is_none());
        if parent_ok && pose_ok {
            self.report.unchanged += 1;
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
            relative_to: self.h.floor,
            position: crate::draw::position(want),
            orientation: crate::draw::euler(want),
        });
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
        if self
            .opts
            .interrupt
            .as_ref()
            .is_some_and(|flag| flag.load(Ordering::SeqCst))
        {
            return Err(DrawError::Interrupted {
                placed: self.placed,
                total: self.drawing.copies(),
            });
        }
        self.claim.check(self.scene, phase)
    }
}
