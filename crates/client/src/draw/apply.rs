//! Draw a [`Drawing`]: remove the surplus, reuse earlier copies, paste only the missing ones
//! (batched doubling), place each round's copies before the next, in requests of bounded
//! server time, then verify. A wall maze with posts is drawn in two parts, walls then posts,
//! each from its own template in the same way.

use std::collections::HashMap;

use super::backend::{Backend, Edit, ObjectInfo, Survey};
use super::drawing::Drawing;
use super::error::{BackendError, DrawError};
use super::home;
use super::lease::Claim;
use super::names::{Handles, ObjectNames};
use super::options::ApplyOptions;
use super::ownership::{self, foreign_copies, maze_pieces};
use super::paste::{self, paste_round};
use super::pose::{self, floor_frame, pose_differences};
use super::report::{ApplyReport, Stage};
use super::session::{Begun, EarlierLines, begin, has_line_copies, keep_home, raised_and_claimed};
use super::survey::Traits;
use super::verify;
use vrep_maze_core::coppelia::frame::Frame;
use vrep_maze_core::layout::{Pose, Style};

/// Draws `drawing` into `scene` and verifies it. The idle rate is raised (idle fps 0) before
/// the scene is read and restored afterwards, also on error or interrupt. The run claims the
/// scene first ([`lease`](super::lease)) and fails with [`DrawError::Concurrent`] if another run
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

/// [`apply`] under `claim`, with the idle rate raised.
fn apply_claimed(
    scene: &mut dyn Backend,
    drawing: &Drawing,
    opts: &ApplyOptions,
    progress: &mut dyn FnMut(Stage),
    claim: &Claim,
) -> Result<ApplyReport, DrawError> {
    let names = &opts.names;
    let Begun {
        survey,
        h,
        mut report,
        objects,
    } = begin_drawing(scene, drawing, opts, progress)?;
    let objects = &objects;
    let Planned {
        parts,
        foreign,
        earlier,
        holder,
    } = plan(scene, drawing, names, &survey, &h, objects, &mut report)?;
    count_plan(
        &parts,
        &foreign,
        drawing,
        &survey,
        opts,
        &mut report,
        progress,
    );
    if opts.dry_run {
        // what a real run would place: compared as it compares, nothing written
        let read = all_poses_read(scene, &h, objects, names, &survey.traits)?;
        placements(
            &parts,
            drawing,
            &h,
            read.as_deref().unwrap_or(objects),
            &mut report,
        );
        return Ok(report);
    }
    let line_template = survey.handles.other_template;
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
    // where Start and End stand before they move, for `clear`: unless an earlier maze holds
    // them already
    if claim.signals_kept() {
        let earlier = parts.iter().any(|p| !p.plan.reuse.is_empty())
            || report.removed + report.removed_meshes > 0;
        super::markers_home::record(scene, &h, objects, earlier)?;
    }
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
        holder,
    };
    run.draw(objects, &parts, &foreign)?;
    Ok(report)
}

/// [`begin`] for `drawing`: surveys the scene, checks the templates and markers against
/// what the drawing asks of them and sets the user's objects apart.
fn begin_drawing(
    scene: &mut dyn Backend,
    drawing: &Drawing,
    opts: &ApplyOptions,
    progress: &mut dyn FnMut(Stage),
) -> Result<Begun, DrawError> {
    let style = drawing.style;
    let posts = !drawing.posts.is_empty();
    let counts = ApplyReport {
        style,
        pieces: drawing.pieces.len(),
        posts: drawing.posts.len(),
        ..Default::default()
    };
    begin(
        scene,
        opts,
        &drawing.template_use(),
        posts,
        counts,
        progress,
    )
}

/// What [`plan`] decided.
struct Planned<'a> {
    /// Each template's copies: reused, removed and pasted.
    parts: Vec<Part<'a>>,
    /// What else goes: an earlier maze of another style, a mesh maze, spoiled copies.
    foreign: Vec<i32>,
    /// What an earlier maze held, for [`keep_home`].
    earlier: EarlierLines,
    /// The holder of a mesh maze the user keeps (their objects under it): no line.
    holder: Option<i32>,
}

/// Plans the copies of `drawing` from the scene's `objects`: which earlier copies are
/// reused and which go (a mesh maze, copies the user spoiled, an earlier maze of the
/// other style), how many are pasted; the objects left alone and the meshes removed are
/// counted into `report`, and the warnings of spoiled copies and of templates on the maze
/// added to it.
fn plan<'a>(
    scene: &mut dyn Backend,
    drawing: &'a Drawing,
    names: &ObjectNames,
    survey: &Survey,
    h: &Handles,
    objects: &[ObjectInfo],
    report: &mut ApplyReport,
) -> Result<Planned<'a>, DrawError> {
    let style = drawing.style;
    let posts = !drawing.posts.is_empty();
    let others = names.others(style);
    // an earlier mesh maze (`--draw mesh`) goes whole, and none of it is reused as a copy
    let leftovers = super::mesh::leftovers(scene, names, h, &survey.objects)?;
    report
        .left_alone
        .extend(leftovers.left_alone.iter().cloned());
    let meshes: Vec<i32> = leftovers.ours.iter().map(|(x, _)| *x).collect();
    // the holder, ours or the user's, is never a line
    let mesh_maze = |x: &i32| meshes.contains(x) || Some(*x) == leftovers.holder;
    let mut existing = maze_pieces(objects, h, names.template(style), &others);
    existing.retain(|x| !mesh_maze(x));
    // a copy of ours the user scaled or recoloured is pasted anew, never reused as it is
    let spoiled = spoiled_copies(objects, &survey.traits, report);
    existing.retain(|x| !spoiled.contains(x));
    let earlier = EarlierLines::of(
        match style {
            Style::Lines => !existing.is_empty(),
            Style::Walls => has_line_copies(objects, h, &names.line),
        },
        leftovers.ours.iter().map(|(_, name)| name.as_str()),
    );
    let copies_needed = drawing
        .pieces
        .len()
        .saturating_sub(usize::from(drawing.template_drawn()));
    let mut parts = vec![Part {
        template: h.template,
        template_drawn: drawing.template_drawn(),
        poses: &drawing.pieces,
        plan: paste::plan(&existing, copies_needed),
    }];
    if let Some(template) = h.post.filter(|_| posts) {
        let mut existing = foreign_copies(objects, h, &[&names.post]);
        existing.retain(|x| !spoiled.contains(x));
        parts.push(Part {
            template,
            template_drawn: false,
            poses: &drawing.posts,
            plan: paste::plan(&existing, drawing.posts.len()),
        });
    }
    // an earlier maze of the other style goes (a wall is no line, nor a line a wall), and
    // its posts unless this maze has posts too
    let mut foreign = foreign_copies(objects, h, &names.foreign(style, posts));
    foreign.retain(|x| !mesh_maze(x));
    report.removed_meshes = meshes.len();
    foreign.extend(meshes);
    foreign.extend(&spoiled);
    if !drawing.template_drawn() {
        warn_templates_on_the_maze(drawing, objects, h, names, report);
    }
    Ok(Planned {
        parts,
        foreign,
        earlier,
        holder: leftovers.holder,
    })
}

/// Warns in `report` of templates standing on the maze `drawing` draws (they are not
/// part of it: every copy is pasted).
fn warn_templates_on_the_maze(
    drawing: &Drawing,
    objects: &[ObjectInfo],
    h: &Handles,
    names: &ObjectNames,
    report: &mut ApplyReport,
) {
    let style = drawing.style;
    let posts = !drawing.posts.is_empty();
    let floor = floor_frame(objects, h.floor).unwrap_or_default();
    let mut templates = vec![(names.template(style), h.template)];
    templates.extend(h.post.filter(|_| posts).map(|p| (names.post.as_str(), p)));
    report.warnings.extend(pose::templates_on_the_maze(
        drawing, objects, &floor, &templates,
    ));
}

/// Counts the plan of `parts` and `foreign` into `report` and tells `progress` the work
/// ahead.
fn count_plan(
    parts: &[Part<'_>],
    foreign: &[i32],
    drawing: &Drawing,
    survey: &Survey,
    opts: &ApplyOptions,
    report: &mut ApplyReport,
    progress: &mut dyn FnMut(Stage),
) {
    for part in parts {
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
}

/// The scene's objects read again with every pose, the user's set apart, when a pose of
/// `objects` is unread (a backend may not have read the copies' poses in the survey);
/// `None` when `objects` hold every pose.
fn all_poses_read(
    scene: &mut dyn Backend,
    h: &Handles,
    objects: &[ObjectInfo],
    names: &ObjectNames,
    traits: &Traits,
) -> Result<Option<Vec<ObjectInfo>>, DrawError> {
    let unread = objects
        .iter()
        .any(|o| o.position.iter().any(|x| x.is_nan()));
    if !unread {
        return Ok(None);
    }
    let read = ownership::sort_out(&scene.objects()?, h, &names.templates(), traits);
    Ok(Some(read.objects))
}

/// The copies of ours among `objects` that the user scaled or recoloured
/// (`Traits::spoiled`), in handle order: removed and pasted anew, each named in
/// a warning of `report` with what differs.
fn spoiled_copies(
    objects: &[ObjectInfo],
    traits: &crate::draw::survey::Traits,
    report: &mut ApplyReport,
) -> Vec<i32> {
    let mut spoiled: Vec<(i32, &str, &str)> = objects
        .iter()
        .filter_map(|o| {
            Some((
                o.handle,
                o.name.as_str(),
                traits.spoiled.get(&o.handle)?.as_str(),
            ))
        })
        .collect();
    spoiled.sort_unstable_by_key(|s| s.0);
    const NAMED: usize = 3;
    if !spoiled.is_empty() {
        let named: Vec<String> = spoiled
            .iter()
            .take(NAMED)
            .map(|(_, name, why)| format!("`{name}` {why}"))
            .collect();
        let more = match spoiled.len().saturating_sub(NAMED) {
            0 => String::new(),
            n => format!("; ... ({n} more)"),
        };
        report.warnings.push(format!(
            "replaced {} copy(ies) that no longer looked like their template: {}{more}",
            spoiled.len(),
            named.join("; ")
        ));
    }
    spoiled.into_iter().map(|s| s.0).collect()
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
    let floor = floor_frame(objects, h.floor).unwrap_or_default();
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
        position: pose::position(want),
        orientation: pose::euler(want),
    });
    edits
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
    plan: paste::Plan,
}

/// The edits and counts carried from one round of pasting to the next.
struct Pasting {
    /// Edits not sent yet.
    edits: Vec<Edit>,
    /// Pieces those edits place that no round has counted yet.
    placed_now: usize,
    /// Copies pasted so far, all parts.
    pasted: usize,
    /// Copies to paste, all parts.
    to_paste: usize,
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
    /// What the survey read of copies and the user's objects ([`ownership::sort_out`]).
    traits: &'a Traits,
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
        let floor = floor_frame(objects, self.h.floor).unwrap_or_default();
        self.remove_surplus(parts, foreign)?;
        // the templates, reused copies and markers, where they differ, go with the first
        // round of copies (or alone, if nothing is pasted)
        let Placements {
            edits,
            mut drawn,
            kept,
        } = placements(parts, self.drawing, self.h, objects, self.report);
        let mut pasting = Pasting {
            edits,
            placed_now: kept,
            pasted: 0,
            to_paste: parts.iter().map(|part| part.plan.paste).sum(),
        };
        let mut short = None;
        for (part, copies) in parts.iter().zip(&mut drawn) {
            let done = self.paste_part(part, copies, &floor, &mut pasting)?;
            if done < part.plan.paste {
                short.get_or_insert((done, part.plan.paste));
            }
            copies.truncate(part.poses.len().max(usize::from(part.template_drawn)));
        }
        self.send(&pasting.edits, pasting.placed_now, false)?;
        if let Some((done, wanted)) = short {
            return Err(BackendError::Remote(format!(
                "copy-paste produced {done} of {wanted} copies"
            ))
            .into());
        }
        self.verify(parts, &drawn)
    }

    /// Removes each part's surplus copies and the `foreign` ones, first: fewer objects
    /// make every later copy cheaper.
    fn remove_surplus(&mut self, parts: &[Part<'_>], foreign: &[i32]) -> Result<(), DrawError> {
        let removals: Vec<Edit> = parts
            .iter()
            .flat_map(|part| &part.plan.remove)
            .chain(foreign)
            .map(|&r| Edit::Remove(r))
            .collect();
        self.send(&removals, 0, true)?;
        self.objects_in_scene = self.objects_in_scene.saturating_sub(removals.len());
        Ok(())
    }

    /// Pastes `part`'s missing copies round by round onto `copies`, sending each round's
    /// places (with the edits `pasting` holds) before pasting the next; how many were
    /// pasted (fewer than planned if a round pasted none).
    fn paste_part(
        &mut self,
        part: &Part<'_>,
        copies: &mut Vec<i32>,
        floor: &Frame,
        pasting: &mut Pasting,
    ) -> Result<usize, DrawError> {
        let h = self.h;
        let mut done = 0;
        // what is pasted from: only the template and the copies this run pasted from
        // it, never an earlier copy (a user's recoloured look-alike would spread)
        let mut sources = vec![part.template];
        while done < part.plan.paste {
            self.checkpoint("while pasting the lines")?;
            let budget = self.scene.pieces_per_request(self.objects_in_scene).max(1);
            let groups = paste_round(
                &sources,
                (part.plan.paste - done).min(budget),
                self.opts.paste_blocks_per_round,
            );
            if groups.is_empty() {
                break;
            }
            let carried = std::mem::take(&mut pasting.placed_now);
            let mut new_pieces = 0;
            for new in self.scene.copy_paste(&groups)? {
                sources.extend(&new);
                for handle in new {
                    if let Some(want) = part.poses.get(copies.len()) {
                        pasting.edits.extend(place(
                            None,
                            floor,
                            h.floor,
                            handle,
                            want,
                            Some(h.parent),
                        ));
                        new_pieces += 1;
                    }
                    copies.push(handle);
                    done += 1;
                    pasting.pasted += 1;
                }
            }
            self.objects_in_scene += new_pieces;
            (self.progress)(Stage::Pasting {
                done: pasting.pasted,
                total: pasting.to_paste,
            });
            self.send(
                &std::mem::take(&mut pasting.edits),
                carried + new_pieces,
                false,
            )?;
        }
        Ok(done)
    }

    /// Reads the scene back (lease checked before, and after by the release) and checks that it holds
    /// the drawing: `drawn[p]` the objects drawn for `parts[p]`.
    fn verify(&mut self, parts: &[Part<'_>], drawn: &[Vec<i32>]) -> Result<(), DrawError> {
        let h = self.h;
        (self.progress)(Stage::Verifying);
        self.claim.check(self.scene, "before verifying")?;
        let after = if self.claim.contended() {
            self.scene.objects_from_scene()?
        } else {
            self.scene.objects()?
        };
        // the run's last read: the release's read of the lease checks it
        self.claim.check_at_release("while verifying");
        let mut after =
            ownership::sort_out(&after, h, &self.opts.names.templates(), self.traits).objects;
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
            self.drawing,
        );
        if problems.is_empty() {
            Ok(())
        } else {
            Err(DrawError::Verify(problems))
        }
    }

    /// Sends `edits`, which place `pieces` pieces, in requests the simulator finishes in
    /// bounded time ([`Backend::pieces_per_request`], about two edits a piece) and the lease
    /// checks between them. An interrupt stops it between two requests only when
    /// `interruptible`: the places of copies already pasted are always sent, so an
    /// interrupted apply leaves no copy unplaced and its count is what the scene holds.
    fn send(
        &mut self,
        edits: &[Edit],
        pieces: usize,
        interruptible: bool,
    ) -> Result<(), DrawError> {
        if edits.is_empty() {
            self.placed += pieces;
            return Ok(());
        }
        self.report.edits += edits.len();
        let per_request = self
            .scene
            .pieces_per_request(self.objects_in_scene)
            .saturating_mul(2)
            .min(self.claim.edits_per_check())
            .max(1);
        let mut sent = 0;
        for chunk in edits.chunks(per_request) {
            if interruptible {
                self.checkpoint("while removing the old maze's surplus")?;
            } else {
                self.claim.check(self.scene, "while placing the lines")?;
            }
            self.scene.edit(chunk)?;
            sent += chunk.len();
            let done = self.placed + pieces * sent / edits.len().max(1);
            (self.progress)(Stage::Placing {
                done: done.min(self.drawing.copies()),
                total: self.drawing.copies(),
            });
        }
        self.placed += pieces;
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
