//! `vrep-maze inspect`: what is in a CoppeliaSim scene now, without changing it.

use std::collections::HashMap;
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};

use anyhow::{Context, Result};

use super::apply::ConnectArgs;
use super::connect::{Connected, connect};
use super::interrupt::{Interrupt, Interrupted};
use super::reports::{DrawnMaze, InspectReport, LayoutMatch, REPORT_VERSION, SceneObject};
use super::say::{self, say};
use crate::coppelia::OBJECT_SHAPE_TYPE;
use crate::coppelia::frame::Frame;
use crate::draw::mesh::{FoundMeshes, MeshKind, MeshMaze, parse_mesh_name};
use crate::draw::ownership::is_copy_of;
use crate::draw::pose::{floor_frame, relative_pose};
use crate::draw::session::raised_to_read;
use crate::draw::verify::verify_read_only;
use crate::draw::{
    Backend, BoundingBox, DrawError, Drawing, ObjectInfo, ObjectNames, Survey, SurveyHandles,
};
use crate::layout::Style;

/// Show what the scene holds (API, version, simulation state, idle rate, the templates and
/// markers, the maze drawn, objects under the maze dummy that are not ours) and, given a
/// layout, whether the drawing matches it. Only reads: the scene is left as it was (the idle
/// rate is raised while reading and restored, as apply does).
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Examples:\n  vrep-maze inspect\n  vrep-maze inspect --layout maze.json\n  vrep-maze inspect --api zmq --json"
)]
pub struct InspectArgs {
    /// Connection and object names.
    #[command(flatten)]
    pub scene: ConnectArgs,
    /// Compare the drawn maze with this layout (exit 1 if it differs).
    #[arg(long, value_name = "FILE")]
    pub layout: Option<PathBuf>,
    /// Print one JSON document on standard output (schema/inspect-v1.schema.json).
    #[arg(long)]
    pub json: bool,
}

/// Runs `inspect`.
pub fn run(args: InspectArgs) -> Result<ExitCode> {
    say::set_json(args.json);
    // two roles on one object, or a layout that cannot be drawn: refused before connecting
    args.scene.check_roles()?;
    let wanted = match &args.layout {
        Some(path) => Some(Wanted::new(
            path.display().to_string(),
            crate::layout::read_layout(path)?,
        )?),
        None => None,
    };
    let names = args.scene.names();
    let c = &args.scene;
    let interrupt = Interrupt::install()?;
    let Connected {
        mut backend,
        description,
    } = connect(
        c.api,
        &c.host,
        c.port,
        c.timeout,
        c.connect_timeout,
        Some(interrupt.flag()),
    )?;
    let read = read_report(
        backend.as_mut(),
        &names,
        description,
        wanted.as_ref(),
        interrupt.flag(),
    );
    let _ = backend.close();
    let report = read?;
    if args.json {
        say::document(&report)?;
    } else {
        show(&report, &args.scene.command("clear"))?;
    }
    let differs = report.layout.as_ref().is_some_and(|l| !l.matches);
    Ok(if differs {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    })
}

/// A layout to compare the scene with.
pub struct Wanted {
    /// Its file, as the user named it.
    file: String,
    /// Drawn as copies of the templates.
    drawing: Drawing,
    /// The layout itself (drawn as meshes when the scene holds a mesh maze).
    layout: crate::layout::Layout,
}

impl Wanted {
    /// `layout`, named `file` in the report; refused when it cannot be drawn.
    pub fn new(file: String, layout: crate::layout::Layout) -> Result<Wanted> {
        let drawing =
            Drawing::try_from(&layout).with_context(|| format!("{file}: cannot be compared"))?;
        Ok(Wanted {
            file,
            drawing,
            layout,
        })
    }
}

/// What `inspect` reports of the scene behind `backend`, described as `connection`, compared
/// with `wanted` if given. Only reads: every read paced by the idle rate costs a main-loop
/// pass (93-125 ms at the default 8 fps, `../shared/spec/real-coppeliasim-4.5.1.md`
/// "Pacing"), so the rate is raised as apply raises it and restored on every path, errors
/// and `stop` included; the report gives the rates as the user left them. Setting `stop`
/// ends the reading between two requests ([`Interrupted`]).
pub fn read_report(
    backend: &mut dyn Backend,
    names: &ObjectNames,
    connection: String,
    wanted: Option<&Wanted>,
    stop: &AtomicBool,
) -> Result<InspectReport> {
    let (mut report, rates) = raised_to_read(backend, |scene| {
        inspect(scene, names, connection, wanted, stop)
    })?;
    report.idle_fps = rates.current;
    report.saved_idle_fps = rates.saved;
    Ok(report)
}

/// Reads the scene through `scene` (reads only; the idle rates are left for the caller to
/// fill in), stopping between requests once `stop` is set.
fn inspect(
    scene: &mut dyn Backend,
    names: &ObjectNames,
    connection: String,
    wanted: Option<&Wanted>,
    stop: &AtomicBool,
) -> Result<InspectReport> {
    let (survey, surveyed) = survey(scene, names)?;
    go_on(stop)?;
    let (templates, colours_read) = named_objects(scene, &survey, names, stop)?;
    let parent = role_handle(survey.handles, names, &names.parent);
    // a mesh maze (`apply --draw mesh`): the holder under the maze dummy and its meshes
    let meshes = match parent {
        Some(parent) => crate::draw::mesh::found(scene, names, parent, &survey.objects)?,
        None => Default::default(),
    };
    go_on(stop)?;
    let maze = drawn_maze(&survey, surveyed, names, &meshes, parent);
    go_on(stop)?;
    let layout = match wanted {
        None => None,
        Some(wanted) => Some(layout_match(scene, names, wanted, &meshes)?),
    };
    Ok(InspectReport {
        format: "vrep-maze/inspect".into(),
        version: REPORT_VERSION,
        connection,
        simulation_running: survey.simulation_running,
        idle_fps: 0,
        saved_idle_fps: None,
        objects: templates,
        colours_read,
        maze,
        layout,
    })
}

/// Stops the reading once `stop` is set ([`Interrupted`]).
fn go_on(stop: &AtomicBool) -> Result<()> {
    if stop.load(Ordering::SeqCst) {
        return Err(Interrupted(
            "while reading the scene: nothing was changed, the idle rate is restored".into(),
        )
        .into());
    }
    Ok(())
}

/// The handle the survey found for `name`, one of `names` (`h` holds the handles by the
/// roles of `ObjectNames::survey(Style::Lines)`).
fn role_handle(h: SurveyHandles, names: &ObjectNames, name: &str) -> Option<i32> {
    [
        (&names.floor, h.floor),
        (&names.parent, h.parent),
        (&names.line, h.template),
        (&names.start, h.start),
        (&names.end, h.end),
        (&names.wall, h.other_template),
        (&names.post, h.post),
    ]
    .into_iter()
    .find(|(n, _)| *n == name)
    .and_then(|(_, h)| h)
}

/// The named objects as the report lists them, one a role, with their sizes and (shapes
/// only) colours read, and whether the backend reads colours at all; stopping between
/// requests once `stop` is set.
fn named_objects(
    scene: &mut dyn Backend,
    survey: &Survey,
    names: &ObjectNames,
    stop: &AtomicBool,
) -> Result<(Vec<SceneObject>, bool)> {
    let objects = &survey.objects;
    let handle = |name: &str| role_handle(survey.handles, names, name);
    let by_handle = |h: i32| objects.iter().find(|o| o.handle == h);
    let floor = survey.handles.floor.and_then(|f| floor_frame(objects, f));
    let roles = [
        ("floor", &names.floor),
        ("maze dummy", &names.parent),
        ("line template", &names.line),
        ("wall template", &names.wall),
        ("post template", &names.post),
        ("start marker", &names.start),
        ("end marker", &names.end),
    ];
    let present: Vec<i32> = roles.iter().filter_map(|(_, name)| handle(name)).collect();
    go_on(stop)?;
    let sizes: HashMap<i32, BoundingBox> = present
        .iter()
        .zip(scene.bounding_boxes(&present)?)
        .filter_map(|(&h, b)| Some((h, b?)))
        .collect();
    // colours of shapes only (a dummy has none)
    let shapes: Vec<i32> = present
        .iter()
        .copied()
        .filter(|h| survey.traits.kinds.get(h) == Some(&OBJECT_SHAPE_TYPE))
        .collect();
    go_on(stop)?;
    let colours_read = scene.shape_colours(&shapes)?;
    let colours: HashMap<i32, [f64; 3]> = match &colours_read {
        Some(colours) => shapes
            .iter()
            .zip(colours)
            .filter_map(|(&h, c)| Some((h, (*c)?)))
            .collect(),
        None => HashMap::new(),
    };
    let templates = roles
        .iter()
        .map(|(role, name)| {
            let h = handle(name);
            let object = h.and_then(by_handle);
            let mut shown = scene_object(role, name, h, object, floor.as_ref());
            shown.size = h
                .and_then(|h| sizes.get(&h))
                .map(|b| b.size().map(|v| round(v, 1e6)));
            shown.colour = h
                .and_then(|h| colours.get(&h))
                .map(|c| c.map(|v| round(v, 1e3)));
            shown
        })
        .collect();
    Ok((templates, colours_read.is_some()))
}

/// What the scene holds of a drawn maze: the copies under the maze dummy `parent` counted
/// by template, the meshes of a mesh maze, the copies left at the root, the user's objects
/// among them, and the style they make up.
fn drawn_maze(
    survey: &Survey,
    surveyed: Style,
    names: &ObjectNames,
    meshes: &FoundMeshes,
    parent: Option<i32>,
) -> DrawnMaze {
    let objects = &survey.objects;
    let handle = |name: &str| role_handle(survey.handles, names, name);
    let ours: Vec<Option<i32>> = [
        &names.floor,
        &names.line,
        &names.wall,
        &names.post,
        &names.start,
        &names.end,
    ]
    .iter()
    .map(|n| handle(n))
    .collect();
    let mut maze = DrawnMaze::default();
    let mesh_kinds: Vec<MeshKind> = meshes
        .meshes
        .iter()
        .filter_map(|m| parse_mesh_name(&m.name).map(|(kind, _)| kind))
        .collect();
    maze.meshes = meshes.meshes.iter().map(|m| m.name.clone()).collect();
    // the user's holder (a dummy of theirs named like ours) and their objects under it
    maze.not_ours.extend(meshes.left_alone());
    for o in objects.iter().filter(|o| Some(o.handle) != meshes.holder) {
        let under_maze = parent.is_some() && o.parent == parent;
        // named, typed and (where read) sized like a template's copy, as drawing judges
        let copy_of = |template: &str| is_copy_of(o, template, handle(template), &survey.traits);
        // ZeroMQ reads no names of the maze dummy's children unless another style's template
        // is in the scene; drawing treats them as copies of the surveyed template
        let unread = o
            .name
            .strip_prefix("object ")
            .is_some_and(|n| n.parse::<i32>().is_ok());
        if unread && under_maze {
            maze.names_unread += 1;
        }
        let count = if copy_of(&names.line) || unread && surveyed == Style::Lines {
            Some(&mut maze.lines)
        } else if copy_of(&names.wall) || unread && surveyed == Style::Walls {
            Some(&mut maze.walls)
        } else if copy_of(&names.post) {
            Some(&mut maze.posts)
        } else {
            None
        };
        match count {
            Some(n) if under_maze => *n += 1,
            Some(_) if o.parent.is_none() => maze.stray_copies.push(o.name.clone()),
            None if under_maze && !ours.contains(&Some(o.handle)) => {
                maze.not_ours.push(o.name.clone())
            }
            _ => {}
        }
    }
    let lines = maze.lines + mesh_kinds.iter().filter(|k| **k == MeshKind::Lines).count();
    let walls = maze.walls + mesh_kinds.iter().filter(|k| **k == MeshKind::Walls).count();
    maze.style = match (lines, walls) {
        (0, 0) => None,
        (_, 0) => Some(Style::Lines),
        (0, _) => Some(Style::Walls),
        _ => None,
    };
    maze
}

/// How the scene compares with `wanted`: its differences, worded, if any; an error other
/// than a difference is refused.
fn layout_match(
    scene: &mut dyn Backend,
    names: &ObjectNames,
    wanted: &Wanted,
    meshes: &FoundMeshes,
) -> Result<LayoutMatch> {
    let Wanted {
        file,
        drawing,
        layout,
    } = wanted;
    Ok(match compare(scene, names, drawing, layout, meshes) {
        Ok(()) => LayoutMatch {
            file: file.clone(),
            matches: true,
            differences: Vec::new(),
        },
        Err(DrawError::Verify(differences)) => LayoutMatch {
            file: file.clone(),
            matches: false,
            differences: differences.iter().map(super::wording::worded).collect(),
        },
        Err(missing @ DrawError::Missing { .. }) => LayoutMatch {
            file: file.clone(),
            matches: false,
            differences: vec![missing.to_string()],
        },
        // a floor smaller than the layout's is a difference of the scene, with its remedy
        Err(short @ DrawError::Floor { .. }) => LayoutMatch {
            file: file.clone(),
            matches: false,
            differences: vec![floor_difference(&short)],
        },
        Err(e) => return Err(anyhow::Error::new(e).context(format!("comparing {file}"))),
    })
}

/// A floor smaller than the layout's as a difference of the scene: its sizes, then what
/// fits this floor on this connection (`--resize-floor` only where it can grow it).
fn floor_difference(short: &DrawError) -> String {
    let mut line = super::remedies::message(short);
    for hint in super::remedies::hints(short) {
        line.push_str("; ");
        line.push_str(&hint);
    }
    line
}

/// Compares the scene with a layout as `apply` verifies it: as meshes when the scene holds a
/// mesh maze (`meshes`), else as copies. Only reads.
fn compare(
    scene: &mut dyn Backend,
    names: &ObjectNames,
    drawing: &Drawing,
    layout: &crate::layout::Layout,
    meshes: &FoundMeshes,
) -> Result<(), DrawError> {
    if !meshes.is_mesh_maze() {
        return verify_read_only(scene, drawing, names);
    }
    let maze =
        MeshMaze::try_from(layout).map_err(|e| DrawError::Verify(vec![e.to_string().into()]))?;
    crate::draw::mesh::verify_read_only(scene, &maze, names)
}

/// The survey of every name; a scene without the line template (a wall scene) is listed
/// through the wall template, since a backend lists objects only when the first five exist.
fn survey(scene: &mut dyn Backend, names: &ObjectNames) -> Result<(Survey, Style), DrawError> {
    let lines = scene.survey(&names.survey(Style::Lines))?;
    if lines.handles.template.is_some() || lines.handles.other_template.is_none() {
        return Ok((lines, Style::Lines));
    }
    // the wall template is the walls' template: back into the lines' roles
    let walls = scene.survey(&names.survey(Style::Walls))?;
    let h = walls.handles;
    let survey = Survey {
        handles: SurveyHandles {
            template: h.other_template,
            other_template: h.template,
            ..h
        },
        ..walls
    };
    Ok((survey, Style::Walls))
}

/// One named object as the report shows it: its pose in the floor's frame (the floor's own
/// in the world's).
fn scene_object(
    role: &str,
    name: &str,
    handle: Option<i32>,
    object: Option<&ObjectInfo>,
    floor: Option<&Frame>,
) -> SceneObject {
    let pose = object.map(|o| match floor {
        Some(floor) if role != "floor" => relative_pose(floor, o),
        _ => (o.position, o.orientation),
    });
    // to the micrometre
    let round = |v: f64| round(v, 1e6);
    SceneObject {
        role: role.into(),
        name: name.into(),
        present: handle.is_some(),
        handle,
        position: pose.map(|(p, _)| p.map(round)),
        orientation: pose.map(|(_, e)| e.map(round)),
        size: None,
        colour: None,
    }
}

/// `v` rounded to `1 / per` (1e6: the micrometre), without a negative zero.
fn round(v: f64, per: f64) -> f64 {
    (v * per).round() / per + 0.0
}

/// The report for a person; `clear` is the command that clears this scene (a hint).
fn show(r: &InspectReport, clear: &str) -> anyhow::Result<()> {
    say(format!("connected to the {}", r.connection))?;
    let saved = r
        .saved_idle_fps
        .map(|s| {
            format!(
                " (an interrupted apply left it so; your rate was {s} fps: {clear} restores it)"
            )
        })
        .unwrap_or_default();
    say(format!(
        "simulation {}; idle rate {} fps{saved}",
        if r.simulation_running {
            "running"
        } else {
            "stopped"
        },
        r.idle_fps
    ))?;
    for o in &r.objects {
        show_object(o, r.maze.style)?;
    }
    if !r.colours_read {
        say("  (colours not shown: the legacy remote API cannot read them; --api zmq can)")?;
    }
    show_maze(&r.maze)?;
    if let Some(l) = &r.layout {
        if l.matches {
            say(format!("{}: the scene matches it", l.file))?;
        } else {
            say(format!(
                "{}: the scene differs in {} way(s):",
                l.file,
                l.differences.len()
            ))?;
            for d in &l.differences {
                say(format!("  {d}"))?;
            }
        }
    }
    Ok(())
}

/// One named object's line of the report for a person: where it stands, its size and
/// colour, or that it is absent (`drawn`: the style of the maze drawn, if one is).
fn show_object(o: &SceneObject, drawn: Option<Style>) -> anyhow::Result<()> {
    let mut looks = String::new();
    if let Some(s) = o.size {
        looks += &format!("; {} x {} x {} m", s[0], s[1], s[2]);
    }
    if let Some(c) = o.colour {
        looks += &format!("; colour {}", hex(c));
    }
    match (o.position, o.orientation) {
        (Some(p), Some(e)) => say(format!(
            "  {:<14} {:<8} at {}, {}, {} m, yaw {} rad{}{looks}",
            o.role,
            o.name,
            p[0],
            p[1],
            p[2],
            e[2],
            if o.role == "floor" {
                " (world)"
            } else {
                " (floor frame)"
            }
        ))?,
        _ if o.present => say(format!("  {:<14} {:<8} present", o.role, o.name))?,
        _ => say(format!(
            "  {:<14} {:<8} {}",
            o.role,
            o.name,
            absent(&o.role, drawn)
        ))?,
    }
    Ok(())
}

/// The drawn maze's lines of the report for a person: its copies, meshes, stray copies
/// and the user's objects under the maze dummy.
fn show_maze(m: &DrawnMaze) -> anyhow::Result<()> {
    let kind = match m.style {
        Some(Style::Lines) => " (a line maze)",
        Some(Style::Walls) => " (a wall maze)",
        None if m.lines + m.walls > 0 => " (lines and walls: two mazes mixed)",
        None => "",
    };
    say(format!("drawn: {}{kind}", drawn_counts(m)))?;
    if !m.meshes.is_empty() {
        let shown = m
            .meshes
            .iter()
            .take(4)
            .cloned()
            .collect::<Vec<_>>()
            .join(", ");
        let more = if m.meshes.len() > 4 {
            format!(", ... ({} more)", m.meshes.len() - 4)
        } else {
            String::new()
        };
        say(format!(
            "drawn as meshes (apply --draw mesh): {} mesh(es) under `{}`: {shown}{more}",
            m.meshes.len(),
            crate::draw::mesh::HOLDER
        ))?;
    }
    if m.names_unread > 0 {
        say(format!(
            "  ({} of them counted by position in the tree: this API read no names of the maze dummy's children, and apply treats them as copies)",
            m.names_unread
        ))?;
    }
    if !m.stray_copies.is_empty() {
        say(format!(
            "stray copies outside the maze dummy: {}",
            first_names(&m.stray_copies)
        ))?;
    }
    if !m.not_ours.is_empty() {
        say(format!(
            "under the maze dummy but not ours: {}",
            first_names(&m.not_ours)
        ))?;
    }
    Ok(())
}

/// What `inspect` says of a template or marker the scene lacks: "missing" where a maze of
/// the `drawn` style (or any maze, when none is drawn) needs it; a template only the other
/// style uses is "not in the scene", said as no problem (a line maze uses no `Wall` or
/// `Post`).
fn absent(role: &str, drawn: Option<Style>) -> &'static str {
    match (role, drawn) {
        ("wall template", Some(Style::Lines)) => "not in the scene (a line maze does not use it)",
        ("post template", Some(Style::Lines)) => "not in the scene (a line maze does not use it)",
        ("line template", Some(Style::Walls)) => "not in the scene (a wall maze does not use it)",
        ("post template", _) => "not in the scene (only wall mazes with posts use it)",
        ("wall template", None) => "not in the scene (only wall mazes use it)",
        _ => "missing",
    }
}

/// The maze's pieces as `apply` counts them: a line maze's lines are the line template
/// (which `apply` lays on the first line) and its copies, a wall maze's walls and posts are
/// copies of their templates ("160 lines (the template and 159 copies), 0 walls, 0 posts").
fn drawn_counts(m: &DrawnMaze) -> String {
    let lines = if m.lines > 0 {
        format!(
            "{} lines (the line template and {} copies)",
            m.lines + 1,
            m.lines
        )
    } else {
        "0 lines".to_string()
    };
    let of = if m.walls + m.posts > 0 {
        " (copies of the wall and post templates)"
    } else {
        ""
    };
    format!("{lines}, {} walls, {} posts{of}", m.walls, m.posts)
}

/// The first [`NAMED`] of `names` and how many more, as `apply` and `clear` name them
/// ("a, b, ... (2858 more)"); the `--json` document lists every one.
fn first_names(names: &[String]) -> String {
    let shown = names
        .iter()
        .take(NAMED)
        .cloned()
        .collect::<Vec<_>>()
        .join(", ");
    match names.len().saturating_sub(NAMED) {
        0 => shown,
        more => format!("{shown}, ... ({more} more)"),
    }
}

/// How many names a line of `inspect` shows.
const NAMED: usize = 12;

/// An RGB colour (0..1) as `#rrggbb`.
fn hex(c: [f64; 3]) -> String {
    let byte = |v: f64| (v.clamp(0.0, 1.0) * 255.0).round() as u8;
    format!("#{:02x}{:02x}{:02x}", byte(c[0]), byte(c[1]), byte(c[2]))
}
