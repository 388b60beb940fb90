//! The session every run stands on, whatever it draws, checks or removes: the idle rate
//! raised and restored (`raised`, [`raised_to_read`]), the scene claimed ([`super::lease`]),
//! the survey and the named handles ([`surveyed`]), the size checks (`sizes_of`), a running
//! simulation dealt with, and the line template's home kept (`keep_home`). The copies
//! (`apply()`) and mesh ([`super::mesh::apply()`]) draws, `verify()`,
//! `clear()` and `inspect` each use what they need of it; nothing here calls them.

use std::time::Instant;

use super::backend::{Backend, Edit, IdleRates, ObjectInfo, Survey};
use super::error::BackendError;
use super::error::DrawError;
use super::fit;
use super::home;
use super::lease::{Claim, claimed};
use super::names::{Handles, ObjectNames};
use super::options::ApplyOptions;
use super::ownership;
use super::pose::{self, floor_frame};
use super::report::{ApplyReport, Stage};
use super::role::Role;
use super::tolerance::POSITION_TOLERANCE;
use vrep_maze_core::layout::Style;
use vrep_maze_core::layout::sizes::Sizes;
use vrep_maze_core::layout::sizes::TemplateUse;

/// Runs a draw's `work` as every draw runs (`apply()`, [`super::mesh::apply()`]): with the
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
/// survey and the handles of the named objects, or [`DrawError::Missing`] whose remedies give
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

/// `raised` for a run that only reads (`vrep-maze inspect`): the user's rate is raised and
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
        .any(|o| o.parent == Some(h.parent) && ownership::is_copy_name(&o.name, line))
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
    let floor = floor_frame(objects, h.floor).unwrap_or_default();
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
    if record.is_some_and(|r| r.handle == h.template) {
        return Ok(());
    }
    let Some(template) = objects.iter().find(|o| o.handle == h.template) else {
        return Ok(());
    };
    let (position, orientation) = pose::relative_pose(&floor, template);
    let home = if on_an_earlier_maze(scene, h, objects, template, &names.line, &floor, earlier)? {
        if earlier == EarlierLines::Copies {
            report.warnings.push(format!(
                "no record of where `{}` stood before the first apply (a maze drawn by an older vrep-maze, or a scene saved and loaded again): `clear` will put it below the floor, out of sight",
                names.line
            ));
        }
        let hidden = home::Home::hidden(position[0], position[1]);
        home::Home {
            handle: h.template,
            position: crate::draw::pose::position(&hidden),
            orientation: crate::draw::pose::euler(&hidden),
        }
    } else {
        home::Home {
            handle: h.template,
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
                .filter(|o| o.parent == Some(h.parent) && ownership::is_copy_name(&o.name, line))
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
    let (position, orientation) = pose::relative_pose(floor, template);
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
                    position: crate::draw::pose::position(&below),
                    orientation: crate::draw::pose::euler(&below),
                }
            };
            home::write(scene, &home)?;
            home
        }
    };
    let hidden = home::Home::hidden(home.position[0], home.position[1]);
    let want = crate::draw::pose::position(&hidden);
    if (0..3).any(|k| (position[k] - want[k]).abs() > POSITION_TOLERANCE) {
        scene.edit(&[Edit::SetPose {
            handle: template.handle,
            relative_to: h.floor,
            position: want,
            orientation: crate::draw::pose::euler(&hidden),
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
    /// The survey's objects without the user's ([`ownership::sort_out`]).
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
    // the floor's type, as the survey read it: only a shape can be resized
    let floor_kind = survey.traits.kinds.get(&h.floor).copied();
    if let Some(short) = short.filter(|_| !opts.resize_floor) {
        let resize = super::fit::resize_offer(&short, floor_kind, scene.authoring().is_some());
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
    // drawn into a running simulation only when asked: its stop removes what is made now
    let running = survey.simulation_running && !opts.while_running;
    report.stopped_simulation =
        stop_running_simulation(scene, running, opts.stop_simulation, opts.dry_run)?;
    if let Some(short) = short {
        report.floor = Some(super::floor::resize(
            scene,
            (h.floor, floor_kind),
            &names.floor,
            &short,
            opts.dry_run,
        )?);
    }
    let sorted = ownership::sort_out(&survey.objects, &h, &names.templates(), &survey.traits);
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
    let mut asked = vec![h.template, h.start, h.end, h.floor];
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

/// Resolves the names of a survey (asked for `style`, [`ObjectNames::survey`]) into
/// [`Handles`] or a [`DrawError::Missing`]; `line` is then the style's template. With
/// `posts`, the post template is needed too. A missing object's remedy gives the layout's
/// `sizes` when a layout is drawn.
pub fn resolve_handles(
    names: &ObjectNames,
    style: Style,
    survey: &Survey,
    posts: bool,
    sizes: Option<&Sizes>,
) -> Result<Handles, DrawError> {
    names.check_roles()?;
    let found = survey.handles;
    let roles = ObjectNames::survey_roles(style).into_array();
    let asked = names.survey(style).into_array();
    let handles = found.into_array();
    for (i, h) in handles.iter().enumerate() {
        let Some(h) = h else { continue };
        if let Some(j) = handles[i + 1..]
            .iter()
            .position(|other| *other == Some(*h))
            .map(|k| i + 1 + k)
        {
            return Err(DrawError::SameObject {
                names: format!("`{}` and `{}`", asked[i], asked[j]),
                first: roles[i],
                second: roles[j],
            });
        }
    }
    // a name that found one of our copies: never a template or a marker
    let recorded = asked
        .iter()
        .zip(&handles)
        .zip(roles)
        .skip(2)
        .find(|((_, h), _)| h.is_some_and(|h| survey.traits.recorded.contains(&h)));
    if let Some(((name, _), role)) = recorded {
        let marker = matches!(role, Role::Start | Role::End);
        return Err(DrawError::OurCopy {
            name: name.to_string(),
            role,
            what: if marker { "a marker" } else { "the template" },
        });
    }
    let (needed, _) = found.needed_and_optional();
    let (needed_roles, _) = ObjectNames::survey_roles(style).needed_and_optional();
    let mut missing: Vec<(Role, String)> = needed_roles
        .into_iter()
        .zip(needed)
        .filter(|(_, h)| h.is_none())
        .map(|(role, _)| (role, names.name(role).to_string()))
        .collect();
    if posts && found.post.is_none() {
        missing.push((Role::Post, names.post.clone()));
    }
    if !missing.is_empty() {
        return Err(DrawError::Missing {
            objects: missing,
            sizes: sizes.cloned().map(Box::new),
        });
    }
    let h = found.map(|h| h.unwrap_or(-1));
    Ok(Handles {
        floor: h.floor,
        parent: h.parent,
        template: h.template,
        start: h.start,
        end: h.end,
        post: found.post,
    })
}
