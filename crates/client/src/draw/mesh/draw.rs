//! `apply --draw mesh`, and its `verify`: draw a [`MeshMaze`] (keep the meshes in place by
//! fingerprint, create the missing ones, remove everything else of an earlier maze, copies
//! included), place the template and markers, check; and read a drawn mesh maze back.

use std::collections::{HashMap, HashSet};

use super::compare::{bounds, mesh_differences};
use super::{
    FoundMeshes, HOLDER, Look, MazeMesh, MeshDrawing, MeshKind, MeshMaze, MeshPlace, MeshReadback,
    NewMesh,
};
use crate::draw::backend::{Backend, Edit, ObjectInfo};
use crate::draw::error::DrawError;
use crate::draw::lease::Claim;
use crate::draw::names::{Handles, ObjectNames};
use crate::draw::options::ApplyOptions;
use crate::draw::ownership::{self, foreign_copies, maze_pieces};
use crate::draw::pose::{floor_frame, pose_differences};
use crate::draw::report::{ApplyReport, DrawMode, Stage};
use crate::draw::session::{
    Begun, EarlierLines, begin, has_line_copies, keep_home, raised, raised_and_claimed, surveyed,
};
use vrep_maze_core::coppelia::{SHAPE_LAYER, SPECIAL_DETECTABLE, SPECIAL_RENDERABLE};
use vrep_maze_core::layout::{Pose, Style};
use vrep_maze_core::wording::Message;

/// Meshes created per request to [`MeshDrawing::create`], between two checks for Ctrl-C and
/// for another run (about 4,000 rectangles: 1 to 2 s on CoppeliaSim 4.5.1).
const MESHES_PER_CREATE: usize = 8;

/// The mesh capability of `scene`, or the error that says this API has none.
fn port(scene: &mut dyn Backend) -> Result<&mut dyn MeshDrawing, DrawError> {
    let api = scene.describe();
    scene.meshes().ok_or(DrawError::NoMeshes { api })
}

/// The holder of a mesh maze under the maze dummy `parent` and what it holds, found through
/// the backend's mesh capability or, without one, among `objects` (the holder by its name
/// under the maze dummy, the meshes as its children), sorted into our meshes and the user's
/// objects ([`FoundMeshes::sorted`]).
pub fn found(
    scene: &mut dyn Backend,
    names: &ObjectNames,
    parent: i32,
    objects: &[ObjectInfo],
) -> Result<FoundMeshes, DrawError> {
    Ok(found_unsorted(scene, names, parent, objects)?.sorted())
}

/// [`found`] before sorting: everything under the holder in `meshes`.
fn found_unsorted(
    scene: &mut dyn Backend,
    names: &ObjectNames,
    parent: i32,
    objects: &[ObjectInfo],
) -> Result<FoundMeshes, DrawError> {
    let holder = objects
        .iter()
        .find(|o| o.parent == Some(parent) && o.name.rsplit('/').next() == Some(HOLDER));
    if let Some(port) = scene.meshes() {
        return Ok(port.find(names, parent, holder.map(|o| o.handle))?);
    }
    Ok(FoundMeshes {
        holder: holder.map(|o| o.handle),
        meshes: holder
            .map(|holder| {
                objects
                    .iter()
                    .filter(|o| o.parent == Some(holder.handle))
                    .map(|o| super::FoundMesh {
                        handle: o.handle,
                        name: o.name.clone(),
                        parent: o.parent,
                    })
                    .collect()
            })
            .unwrap_or_default(),
        users: Vec::new(),
        elsewhere: objects
            .iter()
            .filter(|o| o.parent.is_none() && super::parse_mesh_name(&o.name).is_some())
            .map(|o| o.name.clone())
            .collect(),
    })
}

/// What a copies-mode draw or a clear finds of an earlier mesh maze ([`found`]).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Leftovers {
    /// Our meshes, then the holder if it is ours, with their names: removed. Never the
    /// templates.
    pub ours: Vec<(i32, String)>,
    /// The holder, ours or not: never a line or a copy of a template.
    pub holder: Option<i32>,
    /// The user's holder and the user's objects under it, by name: left alone.
    pub left_alone: Vec<String>,
}

/// The earlier mesh maze in the scene ([`Leftovers`]).
pub fn leftovers(
    scene: &mut dyn Backend,
    names: &ObjectNames,
    h: &Handles,
    objects: &[ObjectInfo],
) -> Result<Leftovers, DrawError> {
    let found = found(scene, names, h.parent, objects)?;
    let never_removed = h.never_removed();
    let ours = |x: &i32| !never_removed.contains(x) && Some(*x) != h.post && *x != h.floor;
    Ok(Leftovers {
        ours: found.ours().into_iter().filter(|(x, _)| ours(x)).collect(),
        holder: found.holder,
        left_alone: found.left_alone(),
    })
}

/// Draws `maze` as meshes into `scene`, as `draw::apply()` draws copies: the idle rate
/// raised, the scene claimed, Ctrl-C honoured between requests, the result checked (names,
/// parents, the template's and markers' poses; [`verify`] reads the meshes back).
pub fn apply(
    scene: &mut dyn Backend,
    maze: &MeshMaze,
    opts: &ApplyOptions,
    progress: &mut dyn FnMut(Stage),
) -> Result<ApplyReport, DrawError> {
    raised_and_claimed(scene, opts.dry_run, |scene, claim| {
        apply_claimed(scene, maze, opts, progress, claim)
    })
}

/// Pieces of `kind` in `maze`.
fn pieces_of(maze: &MeshMaze, kinds: &[MeshKind]) -> usize {
    maze.meshes
        .iter()
        .filter(|m| kinds.contains(&m.kind))
        .map(|m| m.pieces.len())
        .sum()
}

/// The special properties a mesh of `kind` gets: the template's, renderable (the robot's
/// camera sees it) and, for walls and posts, detectable by proximity sensors.
fn special(kind: MeshKind, look: &Look) -> i32 {
    let extra = if kind.respondable() {
        SPECIAL_DETECTABLE
    } else {
        0
    };
    look.special | SPECIAL_RENDERABLE | extra
}

/// What a mesh apply does with the meshes of the scene: which it keeps (`have`), which it
/// makes (`missing`, indices into the maze's meshes) and what it removes (`doomed`).
struct MeshPlan {
    /// The handle kept or made for each of the maze's meshes.
    have: Vec<Option<i32>>,
    /// The maze's meshes to make.
    missing: Vec<usize>,
    /// What goes: an earlier maze's copies, stray or duplicate meshes, kept ones that differ.
    doomed: Vec<i32>,
}

impl MeshPlan {
    /// Keeps each mesh `found` under the holder whose name (fingerprint) `maze` draws; the
    /// earlier maze's copies of any template, and every other mesh, go (the user's objects
    /// under the maze dummy stay, [`ownership::sort_out`]).
    fn of(
        maze: &MeshMaze,
        found: &FoundMeshes,
        objects: &[ObjectInfo],
        h: &Handles,
        names: &ObjectNames,
    ) -> MeshPlan {
        let others = names.others(maze.style);
        let mut doomed: Vec<i32> = maze_pieces(objects, h, names.template(maze.style), &others)
            .into_iter()
            .chain(foreign_copies(objects, h, &others))
            .filter(|x| Some(*x) != found.holder && Some(*x) != h.post)
            .collect();
        let wanted: HashMap<String, usize> = maze
            .meshes
            .iter()
            .enumerate()
            .map(|(i, m)| (m.name(), i))
            .collect();
        let mut have: Vec<Option<i32>> = vec![None; maze.meshes.len()];
        for m in &found.meshes {
            match wanted.get(&m.name) {
                Some(&i) if have[i].is_none() && m.parent == found.holder => {
                    have[i] = Some(m.handle)
                }
                _ => doomed.push(m.handle),
            }
        }
        let missing = (0..maze.meshes.len())
            .filter(|&i| have[i].is_none())
            .collect();
        MeshPlan {
            have,
            missing,
            doomed,
        }
    }

    /// The meshes kept: index into the maze's meshes and handle.
    fn kept(&self) -> Vec<(usize, i32)> {
        self.have
            .iter()
            .enumerate()
            .filter(|(i, _)| !self.missing.contains(i))
            .filter_map(|(i, h)| h.map(|h| (i, h)))
            .collect()
    }

    /// Replaces the kept mesh `i` (handle `handle`): removed, and made anew.
    fn replace(&mut self, i: usize, handle: i32) {
        self.have[i] = None;
        self.missing.push(i);
        self.doomed.push(handle);
    }
}

/// The edits that put the template and markers where `maze` wants them (those found in place
/// counted as unchanged in `report`).
fn marker_edits(
    maze: &MeshMaze,
    h: &Handles,
    objects: &[ObjectInfo],
    report: &mut ApplyReport,
) -> Vec<Edit> {
    let by_handle: HashMap<i32, &ObjectInfo> = objects.iter().map(|o| (o.handle, o)).collect();
    let floor = floor_frame(objects, h.floor).unwrap_or_default();
    let mut edits = Vec::new();
    for (handle, want) in markers(maze, h) {
        let in_place = by_handle
            .get(&handle)
            .is_some_and(|o| pose_differences(&floor, o, &want).is_none());
        if in_place {
            report.markers_unchanged += 1;
        } else {
            report.markers_placed += 1;
            edits.push(Edit::SetPose {
                handle,
                relative_to: h.floor,
                position: crate::draw::pose::position(&want),
                orientation: crate::draw::pose::euler(&want),
            });
        }
    }
    edits
}

/// How the template and the post template look (the post template's only when `posts`).
fn looks(scene: &mut dyn Backend, h: &Handles, posts: bool) -> Result<(Look, Look), DrawError> {
    let template_look = port(scene)?.look(h.template)?;
    let post_look = match h.post.filter(|_| posts) {
        Some(p) => port(scene)?.look(p)?,
        None => template_look,
    };
    Ok((template_look, post_look))
}

/// The look a mesh of `kind` has: the post template's for posts, else the template's.
fn look_of(kind: MeshKind, (template_look, post_look): (Look, Look)) -> Look {
    if kind == MeshKind::Posts {
        post_look
    } else {
        template_look
    }
}

/// Reads every mesh `plan` keeps back, in one request ([`MeshDrawing::read_all`]), and
/// replaces each that differs from what a new one would be ([`mesh_problems`]: its frame on
/// the floor, its triangles or size, its colour, its visibility), saying why in `report`.
fn check_kept(
    scene: &mut dyn Backend,
    maze: &MeshMaze,
    plan: &mut MeshPlan,
    floor: &vrep_maze_core::coppelia::frame::Frame,
    looks: (Look, Look),
    report: &mut ApplyReport,
) -> Result<(), DrawError> {
    let kept = plan.kept();
    if kept.is_empty() {
        return Ok(());
    }
    let handles: Vec<i32> = kept.iter().map(|&(_, h)| h).collect();
    let backs = port(scene)?.read_all(&handles)?;
    for (&(i, handle), back) in kept.iter().zip(&backs) {
        let mesh = &maze.meshes[i];
        let problems = mesh_problems(mesh, back, floor, look_of(mesh.kind, looks));
        if let Some(first) = problems.first() {
            report
                .warnings
                .push(format!("replaced mesh `{}`: it {first}", mesh.name()));
            plan.replace(i, handle);
        }
    }
    Ok(())
}

/// What an earlier maze in `objects` held, for [`keep_home`]: line copies (not the mesh
/// holder's or the post template), and the meshes `found`.
fn earlier_lines(
    style: Style,
    objects: &[ObjectInfo],
    h: &Handles,
    names: &ObjectNames,
    found: &FoundMeshes,
) -> EarlierLines {
    let others = names.others(style);
    EarlierLines::of(
        match style {
            Style::Lines => maze_pieces(objects, h, &names.line, &others)
                .iter()
                .any(|x| Some(*x) != found.holder && Some(*x) != h.post),
            Style::Walls => has_line_copies(objects, h, &names.line),
        },
        found.meshes.iter().map(|m| m.name.as_str()),
    )
}

fn apply_claimed(
    scene: &mut dyn Backend,
    maze: &MeshMaze,
    opts: &ApplyOptions,
    progress: &mut dyn FnMut(Stage),
    claim: &Claim,
) -> Result<ApplyReport, DrawError> {
    let (style, names) = (maze.style, &opts.names);
    let counts = ApplyReport {
        mode: DrawMode::Mesh,
        style,
        pieces: pieces_of(maze, &[MeshKind::Lines, MeshKind::Walls]),
        posts: pieces_of(maze, &[MeshKind::Posts]),
        meshes: maze.meshes.len(),
        ..Default::default()
    };
    // the line template lies on the first line: it must have the layout's line size
    let Begun {
        survey,
        h,
        mut report,
        objects,
    } = begin(scene, opts, &maze.template_use(), false, counts, progress)?;
    let found = found(scene, names, h.parent, &survey.objects)?;
    // the user's objects under the holder (and the user's holder) stay, named; meshes of
    // ours elsewhere (moved out of the holder) are the user's now, and said so
    report.left_alone.extend(found.left_alone());
    report.warnings.extend(found.elsewhere_warnings(names));
    let mut plan = MeshPlan::of(maze, &found, &objects, &h, names);
    let floor = floor_frame(&survey.objects, h.floor).unwrap_or_default();
    let edits = marker_edits(maze, &h, &survey.objects, &mut report);
    if opts.dry_run {
        report.count(maze, &plan);
        return Ok(report);
    }
    // where the line template stood before it goes onto the first line, for `clear`
    keep_home(
        scene,
        claim.signals_kept(),
        style == Style::Lines,
        &h,
        &survey.objects,
        earlier_lines(style, &objects, &h, names, &found),
        survey.handles.other_template,
        names,
        &mut report,
    )?;
    // where Start and End stand before they move, for `clear`: unless an earlier maze holds
    // them already
    if claim.signals_kept() {
        let earlier = !plan.doomed.is_empty() || !found.meshes.is_empty();
        crate::draw::markers_home::record(scene, &h, &survey.objects, earlier)?;
    }
    let posts = pieces_of(maze, &[MeshKind::Posts]) > 0;
    let looks = looks(scene, &h, posts)?;
    // a kept mesh is checked as a new one is, and replaced when it differs
    check_kept(scene, maze, &mut plan, &floor, looks, &mut report)?;
    report.count(maze, &plan);
    let mut draw = MeshDraw {
        scene,
        maze,
        opts,
        claim,
        progress,
        place: MeshPlace {
            parent: h.parent,
            holder: found.holder,
            floor: h.floor,
            floor_pose: survey
                .objects
                .iter()
                .find(|o| o.handle == h.floor)
                .map(|o| (o.position, o.orientation)),
        },
        looks,
    };
    draw.remove(&plan.doomed, survey.objects.len(), &mut report)?;
    let placed = draw.create(&mut plan)?;
    draw.checkpoint(placed, "while placing the markers")?;
    draw.scene.edit(&edits)?;
    report.edits += edits.len();
    (draw.progress)(Stage::Verifying);
    draw.verify_created(&plan)?;
    Ok(report)
}

/// One mesh apply's drawing: the removals, the meshes made, their check.
struct MeshDraw<'a, 'p> {
    scene: &'a mut dyn Backend,
    maze: &'a MeshMaze,
    opts: &'a ApplyOptions,
    claim: &'a Claim,
    progress: &'p mut dyn FnMut(Stage),
    /// Where the new meshes go (the holder once made).
    place: MeshPlace,
    /// The template's and the post template's looks.
    looks: (Look, Look),
}

impl MeshDraw<'_, '_> {
    /// Stops here if the user interrupted (`placed` pieces of the maze drawn) or another run
    /// took the scene over.
    fn checkpoint(&mut self, placed: usize, phase: &'static str) -> Result<(), DrawError> {
        if self.opts.interrupted() {
            return Err(DrawError::Interrupted {
                placed,
                total: self.maze.pieces(),
            });
        }
        self.claim.check(self.scene, phase)
    }

    /// Removes `doomed`, in requests of bounded server time.
    fn remove(
        &mut self,
        doomed: &[i32],
        objects: usize,
        report: &mut ApplyReport,
    ) -> Result<(), DrawError> {
        let per_request = self.scene.pieces_per_request(objects).max(1);
        for chunk in doomed.chunks(per_request) {
            self.checkpoint(0, "while removing the earlier maze")?;
            let removals: Vec<Edit> = chunk.iter().map(|&d| Edit::Remove(d)).collect();
            self.scene.edit(&removals)?;
            report.edits += removals.len();
        }
        Ok(())
    }

    /// Makes the meshes `plan` misses, [`MESHES_PER_CREATE`] a request; returns the pieces
    /// drawn (kept and made).
    fn create(&mut self, plan: &mut MeshPlan) -> Result<usize, DrawError> {
        let maze = self.maze;
        let mut placed = pieces_held(maze, &plan.have);
        let total = maze.pieces();
        (self.progress)(Stage::Placing {
            done: placed,
            total,
        });
        for batch in plan.missing.chunks(MESHES_PER_CREATE) {
            self.checkpoint(placed, "while creating the meshes")?;
            let names: Vec<String> = batch.iter().map(|&i| maze.meshes[i].name()).collect();
            let new: Vec<NewMesh<'_>> = batch
                .iter()
                .zip(&names)
                .map(|(&i, name)| {
                    let m = &maze.meshes[i];
                    let look = look_of(m.kind, self.looks);
                    NewMesh {
                        name,
                        vertices: &m.vertices,
                        indices: &m.indices,
                        look: Look {
                            colour: look.colour,
                            special: special(m.kind, &look),
                        },
                        respondable: m.kind.respondable(),
                    }
                })
                .collect();
            let (holder, handles) = port(self.scene)?.create(&self.place, &new)?;
            self.place.holder = Some(holder);
            for (&i, handle) in batch.iter().zip(handles) {
                plan.have[i] = Some(handle);
                placed += maze.meshes[i].pieces.len();
            }
            (self.progress)(Stage::Placing {
                done: placed,
                total,
            });
        }
        Ok(placed)
    }

    /// Reads the meshes made now back (their triangles; the colours and poses are the ones
    /// just set, acknowledged; those kept were read before) and compares them.
    fn verify_created(&mut self, plan: &MeshPlan) -> Result<(), DrawError> {
        let maze = self.maze;
        let mut problems = Vec::new();
        let created: Vec<(usize, i32)> = plan
            .missing
            .iter()
            .filter_map(|&i| {
                let handle = plan.have[i];
                if handle.is_none() {
                    problems.push(format!("mesh `{}` was not created", maze.meshes[i].name()));
                }
                Some(i).zip(handle)
            })
            .collect();
        let handles: Vec<i32> = created.iter().map(|&(_, h)| h).collect();
        let backs = port(self.scene)?.read_shapes(&handles)?;
        for (&(i, _), back) in created.iter().zip(backs) {
            let mesh = &maze.meshes[i];
            if let (Some(v), Some(t)) = (&back.vertices, &back.indices)
                && let Some(d) = mesh_differences(mesh, v, t)
            {
                problems.push(format!("mesh `{}` {d}", mesh.name()));
            }
        }
        // the run's last read: the release's read of the lease checks it
        self.claim.check_at_release("while verifying");
        if problems.is_empty() {
            Ok(())
        } else {
            Err(DrawError::Verify(
                problems.into_iter().map(Message::from).collect(),
            ))
        }
    }
}

impl ApplyReport {
    /// Counts what `plan` keeps, makes and removes of `maze`'s meshes.
    fn count(&mut self, maze: &MeshMaze, plan: &MeshPlan) {
        self.reused = maze.meshes.len() - plan.missing.len();
        self.pasted = plan.missing.len();
        self.removed = plan.doomed.len();
        self.unchanged = self.reused;
    }
}

/// Pieces held by the meshes `have` holds.
fn pieces_held(maze: &MeshMaze, have: &[Option<i32>]) -> usize {
    maze.meshes
        .iter()
        .zip(have)
        .filter(|(_, h)| h.is_some())
        .map(|(m, _)| m.pieces.len())
        .sum()
}

/// Where the template (a line maze's: on the first line, or under `Start` when there is
/// none) and the markers go.
fn markers(maze: &MeshMaze, h: &Handles) -> Vec<(i32, Pose)> {
    let mut out = Vec::new();
    if maze.style == Style::Lines {
        let hidden = Pose {
            z: (maze.start.z - 0.001).max(0.0),
            ..maze.start
        };
        out.push((h.template, maze.template.unwrap_or(hidden)));
    }
    out.push((h.start, maze.start));
    out.push((h.end, maze.end));
    out
}

/// What differs between the meshes `found` and those of `maze`, by name and parent.
fn name_problems(maze: &MeshMaze, found: &FoundMeshes) -> Vec<String> {
    let wanted: HashSet<String> = maze.meshes.iter().map(|m| m.name()).collect();
    let mut problems = Vec::new();
    let mut seen = HashSet::new();
    let mut stray = Vec::new();
    for m in &found.meshes {
        if wanted.contains(&m.name) && seen.insert(m.name.clone()) {
            if m.parent != found.holder {
                problems.push(format!("mesh `{}` is not a child of `{HOLDER}`", m.name));
            }
        } else {
            stray.push(m.name.as_str());
        }
    }
    let missing = wanted.iter().filter(|n| !seen.contains(*n)).count();
    if missing > 0 {
        problems.push(format!("{missing} of {} mesh(es) missing", wanted.len()));
    }
    if !stray.is_empty() {
        problems.push(format!(
            "{} stray object(s) under `{HOLDER}`: {}",
            stray.len(),
            stray.iter().take(5).copied().collect::<Vec<_>>().join(", ")
        ));
    }
    problems
}

/// The template's and markers' pose differences.
fn marker_problems(maze: &MeshMaze, h: &Handles, objects: &[ObjectInfo]) -> Vec<String> {
    let by_handle: HashMap<i32, &ObjectInfo> = objects.iter().map(|o| (o.handle, o)).collect();
    let floor = floor_frame(objects, h.floor).unwrap_or_default();
    markers(maze, h)
        .into_iter()
        .filter_map(|(handle, want)| {
            let what = if handle == h.start {
                "start"
            } else if handle == h.end {
                "end"
            } else {
                "the line template"
            };
            match by_handle.get(&handle) {
                None => Some(format!("{what} is missing")),
                Some(o) => pose_differences(&floor, o, &want).map(|d| format!("{what} {d}")),
            }
        })
        .collect()
}

/// Reads a mesh maze back and compares it with `maze`: every mesh by name (its fingerprint)
/// under the holder, its triangles (where the API reads them, within
/// [`super::compare::VERTEX_TOLERANCE`]) or its bounding box, its frame on the Floor's, its
/// colour the template's; nothing else under the holder or the maze dummy but the templates;
/// the template and markers in place.
pub fn verify(
    scene: &mut dyn Backend,
    maze: &MeshMaze,
    names: &ObjectNames,
) -> Result<(), DrawError> {
    raised(scene, false, |scene| verify_raised(scene, maze, names)).map(|(ok, _)| ok)
}

/// [`verify`] without touching the idle rate: only reads, for a caller that raised the rate
/// itself (what `inspect` compares with, [`crate::draw::session::raised_to_read`]).
pub fn verify_read_only(
    scene: &mut dyn Backend,
    maze: &MeshMaze,
    names: &ObjectNames,
) -> Result<(), DrawError> {
    verify_raised(scene, maze, names)
}

fn verify_raised(
    scene: &mut dyn Backend,
    maze: &MeshMaze,
    names: &ObjectNames,
) -> Result<(), DrawError> {
    let style = maze.style;
    let asks = maze.template_use();
    let (survey, h) = surveyed(scene, names, &asks, false)?;
    crate::draw::verify::refuse_size_differences(scene, &asks, names, &survey, &h)?;
    // the user's objects under the maze dummy are no stray maze objects
    let objects = ownership::sort_out(
        &scene.objects_from_scene()?,
        &h,
        &names.templates(),
        &survey.traits,
    )
    .objects;
    let found = found(scene, names, h.parent, &objects)?;
    let mut problems = name_problems(maze, &found);
    let others = names.others(style);
    let stray: Vec<String> = maze_pieces(&objects, &h, names.template(style), &others)
        .into_iter()
        .chain(foreign_copies(&objects, &h, &others))
        .filter(|x| Some(*x) != found.holder && Some(*x) != h.post)
        .filter_map(|x| objects.iter().find(|o| o.handle == x))
        .map(|o| o.name.clone())
        .collect();
    if !stray.is_empty() {
        problems.push(format!(
            "{} stray maze object(s) beside the meshes: {}",
            stray.len(),
            stray.iter().take(5).cloned().collect::<Vec<_>>().join(", ")
        ));
    }
    let floor = floor_frame(&objects, h.floor).unwrap_or_default();
    let posts = maze.meshes.iter().any(|m| m.kind == MeshKind::Posts);
    let looks = looks(scene, &h, posts)?;
    problems.extend(found_mesh_problems(scene, maze, &found, &floor, looks)?);
    problems.extend(marker_problems(maze, &h, &objects));
    if problems.is_empty() {
        Ok(())
    } else {
        Err(DrawError::Verify(
            problems.into_iter().map(Message::from).collect(),
        ))
    }
}

/// `x x y x z`, in metres to the micrometre.
fn extents(size: [f64; 3]) -> String {
    size.map(|v| format!("{:.6}", v + 0.0)).join(" x ")
}

/// Reads back the meshes of `maze` that `found` holds, in one request where the API can
/// ([`MeshDrawing::read_all`]), and compares each with what a new one would be
/// ([`mesh_problems`]; `looks`: the style's template, the post template).
fn found_mesh_problems(
    scene: &mut dyn Backend,
    maze: &MeshMaze,
    found: &FoundMeshes,
    floor: &vrep_maze_core::coppelia::frame::Frame,
    looks: (Look, Look),
) -> Result<Vec<String>, DrawError> {
    let by_name: HashMap<&str, i32> = found
        .meshes
        .iter()
        .map(|m| (m.name.as_str(), m.handle))
        .collect();
    let present: Vec<(&MazeMesh, i32)> = maze
        .meshes
        .iter()
        .filter_map(|mesh| Some(mesh).zip(by_name.get(mesh.name().as_str()).copied()))
        .collect();
    let handles: Vec<i32> = present.iter().map(|&(_, h)| h).collect();
    let backs = port(scene)?.read_all(&handles)?;
    Ok(present
        .iter()
        .zip(&backs)
        .flat_map(|(&(mesh, _), back)| {
            mesh_problems(mesh, back, floor, look_of(mesh.kind, looks))
                .into_iter()
                .map(move |p| format!("mesh `{}` {p}", mesh.name()))
        })
        .collect())
}

/// What differs between the mesh `back` read and `mesh` as a new one is made: its frame on
/// the `floor`, its triangles (where the API reads them) or its bounding box's size, its
/// colour `look`'s, and its visibility layer a new shape's ([`SHAPE_LAYER`]). Each problem
/// is said of the mesh ("is coloured ...").
fn mesh_problems(
    mesh: &MazeMesh,
    back: &MeshReadback,
    floor: &vrep_maze_core::coppelia::frame::Frame,
    look: Look,
) -> Vec<String> {
    let mut problems = Vec::new();
    let info = ObjectInfo {
        handle: 0,
        name: mesh.name(),
        parent: None,
        position: back.pose.0,
        orientation: back.pose.1,
    };
    let on_floor = Pose {
        x: 0.0,
        y: 0.0,
        z: 0.0,
        yaw: 0.0,
    };
    if let Some(d) = pose_differences(floor, &info, &on_floor) {
        problems.push(format!("has a frame that is not the floor's: {d}"));
    }
    if let (Some(v), Some(i)) = (&back.vertices, &back.indices)
        && let Some(d) = mesh_differences(mesh, v, i)
    {
        problems.push(d);
    }
    if let Some((min, max)) = back.bounding_box {
        // CoppeliaSim gives a mesh's box as half-extents about its centre, not in the
        // shape's frame (spec "Meshes on the real 4.5.1"): compare sizes, which both
        // conventions share
        let (want_min, want_max) = bounds(mesh);
        let size = [0, 1, 2].map(|k| max[k] - min[k]);
        let want = [0, 1, 2].map(|k| want_max[k] - want_min[k]);
        if size
            .iter()
            .zip(&want)
            .any(|(a, b)| (a - b).abs() > 2.0 * super::compare::VERTEX_TOLERANCE)
        {
            problems.push(format!(
                "has a bounding box of {} m, expected {} m",
                extents(size),
                extents(want)
            ));
        }
    }
    if let Some(c) = back.colour
        && c.iter().zip(look.colour).any(|(a, b)| (a - b).abs() > 0.01)
    {
        problems.push(format!("is coloured {c:?}, the template {:?}", look.colour));
    }
    if let Some(layer) = back.layer.filter(|&l| l != SHAPE_LAYER) {
        let hidden = if layer == 0 { " (hidden)" } else { "" };
        problems.push(format!(
            "is on visibility layer {layer}{hidden}, a new mesh on {SHAPE_LAYER}"
        ));
    }
    problems
}
