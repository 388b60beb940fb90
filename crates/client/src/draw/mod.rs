//! Backend-neutral drawing of a maze into a CoppeliaSim scene.
//!
//! A backend ([`crate::legacy::LegacyBackend`], [`crate::zmq_api::ZmqBackend`]) implements
//! [`Backend`]: a handful of scene operations, batched where the protocol allows. [`apply()`] draws a
//! [`Drawing`] (reusing earlier copies of the `Line` template, or of `Wall` and `Post`, pasting
//! only the missing ones, removing the surplus), [`clear()`] removes a drawn maze and
//! [`verify()`] compares the scene with a drawing. The pure decisions are tested without a
//! simulator: [`ownership`] (which objects belong to the maze), [`paste`] (what to reuse,
//! paste and remove), [`pose`] (poses on the floor) and [`tolerance`] (what counts as the
//! same).

pub mod apply;
pub mod clear;
pub mod connection;
pub mod estimate;
pub mod first_line;
pub mod fit;
pub mod floor;
pub mod home;
pub mod lease;
pub mod mesh;
pub mod options;
pub mod ownership;
pub mod paste;
pub mod pose;
pub mod record;
pub mod remedy;
pub mod report;
pub mod robot;
pub mod role;
pub mod run;
pub mod session;
pub mod signals;
pub mod survey;
pub mod tolerance;
pub mod verify;

pub use apply::apply;
pub use clear::{ClearOptions, ClearReport, clear};
pub use connection::{Session, SessionError};
pub use lease::{Claimed, Lease};
pub use options::ApplyOptions;
pub use remedy::Remedy;
pub use report::{ApplyReport, Stage};
pub use role::Role;
pub use run::{DrawMode, Job, Picture, Report, RunError, run};
pub use survey::{SurveyHandles, SurveyNames, SurveyRoles};
pub use verify::verify;
pub use vrep_maze_core::layout::sizes::{Sizes, TemplateUse};
use vrep_maze_core::score::follow::Follower;
use vrep_maze_core::wording::{Message, Neutral, Opt, Value, Wording};

pub use vrep_maze_core::layout::{Pose, Style};

/// Position of a pose as an array.
pub fn position(p: &Pose) -> [f64; 3] {
    [p.x, p.y, p.z]
}

/// CoppeliaSim Euler angles of a pose (roll = pitch = 0).
pub fn euler(p: &Pose) -> [f64; 3] {
    [0.0, 0.0, p.yaw]
}

/// What to draw: one pose per copy of the style's template (`Line`: the template itself is
/// the first; `Wall`: copies only, the template stays where the scene has it), one per copy
/// of `Post` in a wall maze with posts (copies only, as walls), plus where `Start` and `End`
/// go. All in the Floor frame. Made only from a valid layout
/// (`Drawing::try_from(&layout)`), so its fields can be read but not assembled by hand.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct Drawing {
    /// Lines or walls: which template is copied.
    pub style: Style,
    /// Poses of the pieces of the maze drawn as the style's template: the line segments
    /// (`segments`, the first one the template itself) or the walls (`walls`, every one a
    /// copy), in the layout's order. The posts are apart ([`Drawing::posts`]).
    pub pieces: Vec<Pose>,
    /// Poses of the `Post` copies (`posts`): empty unless the maze has posts.
    pub posts: Vec<Pose>,
    /// Pose of the start marker.
    pub start: Pose,
    /// Pose of the end marker.
    pub end: Pose,
    /// The sizes the layout was generated for, which the templates and markers must have.
    pub sizes: Sizes,
}

/// Names of the scene objects a drawing needs.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ObjectNames {
    /// Reference frame of every coordinate (`Floor`).
    pub floor: String,
    /// Dummy every line is a child of (`Maze`).
    pub parent: String,
    /// Line template (`Line`).
    pub line: String,
    /// Start marker (`Start`).
    pub start: String,
    /// End marker (`End`).
    pub end: String,
    /// Wall template (`Wall`), the template of wall mazes.
    pub wall: String,
    /// Post template (`Post`), standing at the lattice corners of wall mazes with posts.
    pub post: String,
}

impl Drawing {
    /// What this drawing asks of the templates: the style's template is the first line (or
    /// copied for every wall) when there is any, the post template for every post.
    pub fn template_use(&self) -> TemplateUse<'_> {
        TemplateUse {
            style: self.style,
            sizes: &self.sizes,
            template: !self.pieces.is_empty(),
            posts: !self.posts.is_empty(),
        }
    }

    /// `true` when the template itself is the first copy drawn (lines); a wall template
    /// stays where the scene has it and every wall is a copy.
    pub fn template_drawn(&self) -> bool {
        self.style == Style::Lines
    }

    /// Lines, or walls and posts: the objects placed, as progress counts them.
    pub fn copies(&self) -> usize {
        self.pieces.len() + self.posts.len()
    }
}

impl Default for ObjectNames {
    fn default() -> Self {
        ObjectNames {
            floor: "Floor".into(),
            parent: "Maze".into(),
            line: "Line".into(),
            start: "Start".into(),
            end: "End".into(),
            wall: "Wall".into(),
            post: "Post".into(),
        }
    }
}

impl ObjectNames {
    /// Every template: line, wall, post ([`ownership::sort_out`] keeps their copies).
    pub fn templates(&self) -> [&str; 3] {
        [&self.line, &self.wall, &self.post]
    }

    /// The template `style` copies.
    pub fn template(&self, style: Style) -> &str {
        self.name(Role::template(style))
    }

    /// The name of `role`'s object.
    pub fn name(&self, role: Role) -> &str {
        match role {
            Role::Floor => &self.floor,
            Role::Parent => &self.parent,
            Role::Line => &self.line,
            Role::Wall => &self.wall,
            Role::Post => &self.post,
            Role::Start => &self.start,
            Role::End => &self.end,
        }
    }

    /// The templates other than `style`'s: the other style's, then the post template. Their
    /// copies in the maze are never reused as the style's (a wall is no line, a post no
    /// wall), and they themselves are never touched.
    pub fn others(&self, style: Style) -> Vec<&str> {
        match style {
            Style::Lines => vec![&self.wall, &self.post],
            Style::Walls => vec![&self.line, &self.post],
        }
    }

    /// The templates whose copies in the maze drawing `style` removes: [`ObjectNames::others`],
    /// less the post template when the drawing has `posts` (its copies are the drawing's).
    pub fn foreign(&self, style: Style, posts: bool) -> Vec<&str> {
        let mut others = self.others(style);
        if posts {
            others.truncate(1);
        }
        others
    }

    /// What [`Backend::survey`] is asked for when drawing `style`: the names of the floor,
    /// the parent, the style's template, start and end, then [`ObjectNames::others`] (the
    /// other style's template and the post template, optional).
    pub fn survey(&self, style: Style) -> SurveyNames<'_> {
        Self::survey_roles(style).map(|role| self.name(role))
    }

    /// Every role and the name of its object: floor, parent, line, wall, post, start, end.
    pub fn roles(&self) -> [(Role, &str); 7] {
        Role::ALL.map(|role| (role, self.name(role)))
    }

    /// The roles of [`ObjectNames::survey`]'s names.
    fn survey_roles(style: Style) -> SurveyRoles<Role> {
        let (template, other_template) = match style {
            Style::Lines => (Role::Line, Role::Wall),
            Style::Walls => (Role::Wall, Role::Line),
        };
        SurveyRoles {
            floor: Role::Floor,
            parent: Role::Parent,
            template,
            start: Role::Start,
            end: Role::End,
            other_template,
            post: Role::Post,
        }
    }

    /// Refuses two roles given one name (`Maze` and `/Maze` are one name: a ZeroMQ path
    /// of the scene root): one object cannot be the floor and the maze dummy, a template
    /// and a marker, ... Pure, so it is checked before anything is sent.
    pub fn check_roles(&self) -> Result<(), DrawError> {
        let roles = self.roles();
        let key = |n: &str| n.strip_prefix('/').unwrap_or(n).to_string();
        for (i, (first, a)) in roles.iter().enumerate() {
            if let Some((second, b)) = roles[i + 1..].iter().find(|(_, b)| key(a) == key(b)) {
                return Err(DrawError::SameObject {
                    names: if a == b {
                        format!("`{a}`")
                    } else {
                        format!("`{a}` and `{b}`")
                    },
                    first: *first,
                    second: *second,
                });
            }
        }
        Ok(())
    }
}

/// "left alone: N object(s) of yours under `Maze` that are no copies of a template: a, b,
/// ..." naming at most the first few, for the reports of `apply` and `clear` (`None` when
/// there are none).
pub fn left_alone_line(left_alone: &[String], parent: &str) -> Option<String> {
    const NAMED: usize = 8;
    if left_alone.is_empty() {
        return None;
    }
    let shown: Vec<&str> = left_alone.iter().take(NAMED).map(String::as_str).collect();
    let more = if left_alone.len() > NAMED {
        format!(", ... ({} more)", left_alone.len() - NAMED)
    } else {
        String::new()
    };
    Some(format!(
        "left alone: {} object(s) under `{parent}` or at the scene root that are no copies of a template (not the maze's): {}{more}",
        left_alone.len(),
        shown.join(", ")
    ))
}

/// Handles of the objects [`ObjectNames`] names, resolved in one scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Handles {
    /// The floor: every pose is relative to it.
    pub floor: i32,
    /// The dummy every maze line is a child of.
    pub parent: i32,
    /// The style's template, the one copied: `Line` (also the first line of the maze) or,
    /// for walls, `Wall`.
    pub template: i32,
    /// The start marker.
    pub start: i32,
    /// The end marker.
    pub end: i32,
    /// The post template, if the scene has one (a drawing with posts needs it).
    pub post: Option<i32>,
}

impl Handles {
    /// The objects a drawing moves but never removes: the style's template and the start
    /// and end markers.
    pub fn never_removed(&self) -> [i32; 3] {
        [self.template, self.start, self.end]
    }
}

/// One scene object as a backend reports it: world pose.
#[derive(Debug, Clone, PartialEq)]
pub struct ObjectInfo {
    /// The object's handle in this scene.
    pub handle: i32,
    /// Object name.
    pub name: String,
    /// Parent handle.
    pub parent: Option<i32>,
    /// World position.
    pub position: [f64; 3],
    /// World Euler angles.
    pub orientation: [f64; 3],
}

/// An object's bounding box in its own frame (`sim_objfloatparam_objbbox_*`, parameters
/// 15..20), as a simulator reports it: single precision, so compare sizes with
/// [`tolerance::SIZE_TOLERANCE`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoundingBox {
    /// Minimum x, y, z.
    pub min: [f64; 3],
    /// Maximum x, y, z.
    pub max: [f64; 3],
}

impl BoundingBox {
    /// Extent along x, y and z (a plane has z = 0).
    pub fn size(&self) -> [f64; 3] {
        [0, 1, 2].map(|k| self.max[k] - self.min[k])
    }
}

/// Everything [`apply()`] needs to know first, in one round trip.
#[derive(Debug, Clone, PartialEq)]
pub struct Survey {
    /// Handle of each name asked for, by role, `None` if missing.
    pub handles: SurveyHandles,
    /// The scene objects drawing needs: the named ones, the children of the maze dummy and
    /// parentless copies of the line template (a backend may list more). A pose a backend
    /// did not read is NaN: never in place, so it is set.
    pub objects: Vec<ObjectInfo>,
    /// Simulation not stopped.
    pub simulation_running: bool,
    /// What the backend read that tells a template's copy from the user's object named like
    /// one ([`ownership::Traits`]: types, and sizes and children where the name, type and copy
    /// record leave a doubt).
    pub traits: ownership::Traits,
}

/// The idle rate now and the user's rate recorded by an interrupted run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct IdleRates {
    /// Current `sim_intparam_idle_fps`.
    pub current: i32,
    /// The user's idle rate recorded by an `apply` that was interrupted before restoring it
    /// (the simulator keeps it as the integer signal [`signals::SAVED_IDLE_FPS`]).
    pub saved: Option<i32>,
}

/// A scene edit; [`Backend::edit`] applies a list of them in order, in one round trip.
#[derive(Debug, Clone, PartialEq)]
pub enum Edit {
    /// Set the parent (`None` = no parent).
    SetParent {
        /// The object to move in the hierarchy.
        handle: i32,
        /// Its new parent, `None` for the scene root.
        parent: Option<i32>,
        /// Keep the world pose (else the local pose is kept and the object moves).
        keep_in_place: bool,
    },
    /// Set position and orientation relative to another object.
    SetPose {
        /// The object to place.
        handle: i32,
        /// The object whose frame the pose is in (the floor).
        relative_to: i32,
        /// Position in that frame, metres.
        position: [f64; 3],
        /// CoppeliaSim Euler angles in that frame, radians.
        orientation: [f64; 3],
    },
    /// Remove an object.
    Remove(i32),
}

/// A failed backend operation.
#[derive(Debug, thiserror::Error)]
pub enum BackendError {
    /// Connection or protocol failure.
    #[error("{0}")]
    Transport(String),
    /// The simulator refused an operation.
    #[error("the simulator refused: {0}")]
    Remote(String),
}

impl BackendError {
    /// Whether the connection itself failed (the simulator closed or killed), not a request.
    pub fn lost_connection(&self) -> bool {
        matches!(self, BackendError::Transport(_))
    }
}

/// A connection to a simulator that can draw: the operations [`apply()`], [`clear()`] and
/// [`verify()`] need.
///
/// Contract: each operation uses as few messages as its protocol allows (the legacy API sends
/// each call as one batched request; the ZeroMQ API has one call per object, sent together
/// where they do not depend on each other's answers, `Client::call_all`, and served by one
/// main-loop pass); [`Backend::round_trips`] reports the cost so far (ZeroMQ: requests). Errors leave the
/// scene in a state that a later [`apply()`] or [`clear()`] repairs.
pub trait Backend {
    /// Reads the idle rate and the record of the user's rate ([`IdleRates`]).
    fn idle_rates(&mut self) -> Result<IdleRates, BackendError>;
    /// Resolves `names`, lists the objects drawing needs ([`Survey::objects`]) and reads the
    /// simulation state. `names` are [`ObjectNames::survey`]'s: objects are listed only
    /// when the needed ones exist ([`SurveyHandles::needed_found`]), and the maze's copies
    /// of the other templates are named after them (so [`ownership::foreign_copies`] can tell
    /// them apart).
    fn survey(&mut self, names: &SurveyNames<'_>) -> Result<Survey, BackendError>;
    /// Lists the objects drawing needs, as [`Backend::survey`] does, with every pose: a
    /// backend may give a pose it set itself, acknowledged by the simulator, without reading
    /// it back (ZeroMQ, where each read is a call).
    fn objects(&mut self) -> Result<Vec<ObjectInfo>, BackendError>;
    /// [`Backend::objects`], every pose read from the scene now.
    fn objects_from_scene(&mut self) -> Result<Vec<ObjectInfo>, BackendError> {
        self.objects()
    }
    /// The bounding boxes of `handles` ([`BoundingBox`]), in the same order, `None` for an
    /// object that has none (gone, or a simulator that does not say): legacy in one request
    /// for all, ZeroMQ one call per parameter and object, all made by one request where the
    /// simulator runs our program of several calls.
    fn bounding_boxes(&mut self, handles: &[i32])
    -> Result<Vec<Option<BoundingBox>>, BackendError>;
    /// The sizes (bounding-box extents x, y, z) of `handles`, in the same order, `None` for
    /// an object that has none; by default from [`Backend::bounding_boxes`].
    fn sizes(&mut self, handles: &[i32]) -> Result<Vec<Option<[f64; 3]>>, BackendError> {
        Ok(self
            .bounding_boxes(handles)?
            .into_iter()
            .map(|b| b.map(|b| b.size()))
            .collect())
    }
    /// The ambient-diffuse colours (RGB, 0..1) of the shapes `handles`, in the same order,
    /// `None` for one the simulator gives none of; `Ok(None)` from an API that cannot read
    /// colours (the legacy API has no call for it).
    fn shape_colours(
        &mut self,
        handles: &[i32],
    ) -> Result<Option<Vec<Option<[f64; 3]>>>, BackendError> {
        let _ = handles;
        Ok(None)
    }
    /// Reads the integer signals `names` (`None`: not set), legacy in one request.
    fn int_signals(&mut self, names: &[&str]) -> Result<Vec<Option<i32>>, BackendError>;
    /// Sets (`Some`) or clears (`None`) integer signals in order, legacy in one request.
    fn set_int_signals(&mut self, signals: &[(&str, Option<i32>)]) -> Result<(), BackendError>;
    /// Copy-pastes each group; returns the new handles of each group.
    fn copy_paste(&mut self, groups: &[Vec<i32>]) -> Result<Vec<Vec<i32>>, BackendError>;
    /// Applies edits in order.
    fn edit(&mut self, edits: &[Edit]) -> Result<(), BackendError>;
    /// Sets `sim_intparam_idle_fps` and, in the same request, records `saved` (the user's
    /// rate, so that a later run can restore it if this one is interrupted) or, with `None`,
    /// deletes the record.
    fn set_idle_fps(&mut self, fps: i32, saved: Option<i32>) -> Result<(), BackendError>;
    /// Stops the simulation and waits until it is stopped.
    fn stop_simulation(&mut self) -> Result<(), BackendError>;
    /// Messages exchanged with the simulator so far (requests with their replies).
    fn round_trips(&self) -> usize;
    /// How many pieces (lines, walls or posts: a copy, or a parent and a pose) one request
    /// may carry so that the
    /// simulator answers in bounded time, given the objects in the scene (its per-object
    /// costs grow with them). Unbounded where each call is its own request (ZeroMQ).
    fn pieces_per_request(&self, objects_in_scene: usize) -> usize {
        let _ = objects_in_scene;
        usize::MAX
    }
    /// One line naming the API, where it answered and, if known, the simulator's version.
    fn describe(&self) -> String;
    /// Which remote API this is, for [`estimate::copies_draw`]; `None` for a backend that is
    /// neither (nothing is estimated).
    fn remote_api(&self) -> Option<estimate::RemoteApi> {
        None
    }
    /// Ends the connection the way the official client does, so the simulator is ready for
    /// the next client at once. Dropping a backend closes it too, ignoring errors.
    fn close(&mut self) -> Result<(), BackendError> {
        Ok(())
    }
    /// The scene-side record that tells concurrent runs apart ([`lease`]). APIs that serve
    /// several clients at once (ZeroMQ) have one; the legacy server serves one client at a
    /// time, so it needs none.
    fn lease(&mut self) -> Option<&mut dyn Lease> {
        None
    }
    /// What this backend can do beyond drawing, if anything (the ZeroMQ API can create
    /// objects and save the scene; the legacy API cannot).
    fn authoring(&mut self) -> Option<&mut dyn Authoring> {
        None
    }
    /// Drawing a maze as mesh shapes ([`mesh::MeshDrawing`]), if this backend can.
    fn meshes(&mut self) -> Option<&mut dyn mesh::MeshDrawing> {
        None
    }
    /// A follower of a robot's run over this backend's connection, which stays open when
    /// the follower is closed (`score` in a session), if this backend can lend it.
    fn follower(&mut self) -> Option<Box<dyn Follower + '_>> {
        None
    }
    /// A driver of the scene's wheeled robot over this backend's connection, which stays
    /// open when the driver is done (`drive` in a session), if this backend can lend it.
    fn robot(&mut self) -> Option<Box<dyn crate::robot::RobotPort + '_>> {
        None
    }
    /// The bounding box, in its own frame, of the model whose base is the object `name`
    /// (an object that is no model base: its own box), for [`robot`]'s check; `None` for no
    /// such object or an API that cannot say.
    fn model_box(&mut self, name: &str) -> Result<Option<BoundingBox>, BackendError> {
        let _ = name;
        Ok(None)
    }
}

/// Scene authoring that only some APIs offer: see [`Backend::authoring`].
pub trait Authoring {
    /// Creates the objects of `names` that the scene lacks, at the layout's `sizes` (the
    /// course's colours); returns the names it created.
    fn create_missing(
        &mut self,
        names: &ObjectNames,
        sizes: &Sizes,
    ) -> Result<Vec<String>, BackendError>;
    /// Saves the scene to `path` on the simulator's machine.
    fn save_scene(&mut self, path: &str) -> Result<(), BackendError>;
    /// Scales the object `handle` by `factors` along its x, y and z (`sim.scaleObject`: a
    /// shape's mesh or primitive grows, its pose stays).
    fn scale(&mut self, handle: i32, factors: [f64; 3]) -> Result<(), BackendError>;
}

/// Creates the objects `layout` is drawn with that the scene lacks, at the layout's sizes
/// ([`Authoring::create_missing`]). Returns the names created.
pub fn create_missing_for(
    authoring: &mut dyn Authoring,
    names: &ObjectNames,
    layout: &vrep_maze_core::layout::Layout,
) -> Result<Vec<String>, BackendError> {
    authoring.create_missing(names, &Sizes::of(layout))
}

/// Errors of [`apply()`], [`clear()`] and [`verify()`].
#[derive(Debug, thiserror::Error)]
pub enum DrawError {
    /// Named objects are missing; [`DrawError::remedies`] says how to create each.
    #[error("missing in the scene: {}", missing_names(.objects))]
    Missing {
        /// The missing objects: each one's role and name.
        objects: Vec<(Role, String)>,
        /// The sizes of the layout drawn, which the objects are to have (`None` when no
        /// layout is drawn, as for `clear`).
        sizes: Option<Box<Sizes>>,
    },
    /// Two roles name one object ([`ObjectNames::check_roles`], or two names the scene
    /// resolves to one handle): refused before any edit.
    #[error("{}", two_roles(.names, .first, .second))]
    SameObject {
        /// The name, or the two names of the one object.
        names: String,
        /// The first role.
        first: Role,
        /// The second role.
        second: Role,
    },
    /// A name given for a template or a marker found one of the copies this tool pasted
    /// (the copy record holds it: `--line /Maze/Line`, `--start '/Maze/Line[3]'`): refused
    /// before any edit, since drawing would move, copy or hide a line of the maze.
    #[error("{}", our_copy(.name, .role, .what))]
    OurCopy {
        /// The name as given.
        name: String,
        /// The role it was given for.
        role: Role,
        /// What the role needs: "the template", "a marker".
        what: &'static str,
    },
    /// The scene's templates are not the size the layout was generated for
    /// ([`fit::check_sizes`]): refused before any edit, one line per template with what
    /// to change.
    #[error("{}", sizes(.0, &Neutral))]
    Sizes(Vec<Message>),
    /// The scene's floor is smaller than the layout's ([`fit::SizeCheck::floor`]): refused
    /// before any edit unless `apply --resize-floor` grows it ([`floor::resize`]).
    #[error("{}", .short.describe(.floor))]
    Floor {
        /// The floor's name.
        floor: String,
        /// Its size and the layout's.
        short: fit::FloorShort,
        /// Whether this connection can resize it.
        resize: floor::Resize,
    },
    /// The simulation runs; edits would be lost when it stops.
    #[error("the simulation is running: changes made now would be discarded when it stops")]
    SimulationRunning,
    /// Another `apply` or `clear` claimed the scene while this one ran ([`lease`]).
    #[error(
        "another apply or clear started on this scene {phase}; it may now hold parts of both mazes"
    )]
    Concurrent {
        /// When this run noticed, e.g. "before placing the lines".
        phase: &'static str,
    },
    /// Ctrl-C (or SIGTERM, SIGHUP) stopped the run between two requests; the idle rate
    /// was restored and the connection can be closed cleanly.
    #[error("interrupted with {placed} of {total} copies placed")]
    Interrupted {
        /// Lines placed before the interrupt ([`clear()`]: objects removed).
        placed: usize,
        /// Lines in the drawing ([`clear()`]: objects to remove).
        total: usize,
    },
    /// Backend failure.
    #[error(transparent)]
    Backend(#[from] BackendError),
    /// The scene does not match the drawing after drawing it (the first ten differences).
    #[error("{}", verify_failed(.0, &Neutral))]
    Verify(Vec<Message>),
    /// A mesh drawing asked of a connection without the mesh capability.
    #[error("{}", no_meshes(.api).worded(&Neutral))]
    NoMeshes {
        /// The connection, as [`Backend::describe`] says it.
        api: String,
    },
}

impl DrawError {
    /// The error's line with each role it names said by `role` (an adapter's words, which
    /// add the option that names the role's object) and each option it names by `wording`;
    /// `Display` says a role plainly ("the floor") and an option in the neutral wording.
    pub fn message(&self, role: impl Fn(Role) -> String, wording: &dyn Wording) -> String {
        match self {
            DrawError::Sizes(refusals) => sizes(refusals, wording),
            DrawError::Verify(problems) => verify_failed(problems, wording),
            DrawError::NoMeshes { api } => no_meshes(api).worded(wording),
            DrawError::SameObject {
                names,
                first,
                second,
            } => two_roles(names, role(*first), role(*second)),
            DrawError::OurCopy {
                name,
                role: given,
                what,
            } => our_copy(name, role(*given), what),
            other => other.to_string(),
        }
    }
}

/// [`DrawError::Sizes`]'s line, its refusals in `wording`'s words.
fn sizes(refusals: &[Message], wording: &dyn Wording) -> String {
    let lines: Vec<String> = refusals.iter().map(|r| r.worded(wording)).collect();
    format!(
        "the scene's templates do not fit the layout: {}",
        lines.join("; ")
    )
}

/// [`DrawError::Verify`]'s line: how many differences, the first ten in `wording`'s words.
fn verify_failed(problems: &[Message], wording: &dyn Wording) -> String {
    let first: Vec<String> = problems
        .iter()
        .take(10)
        .map(|p| p.worded(wording))
        .collect();
    format!(
        "verification failed, {} difference(s): {}",
        problems.len(),
        first.join("; ")
    )
}

/// [`DrawError::NoMeshes`]'s line: `--draw mesh is not available over this API (...)`.
fn no_meshes(api: &str) -> Message {
    Message::setting(Opt::Draw, Value::word("mesh"))
        .and(format!(" is not available over this API ({api})"))
}

/// "Floor, Line": the names of [`DrawError::Missing`]'s objects.
fn missing_names(objects: &[(Role, String)]) -> String {
    let names: Vec<&str> = objects.iter().map(|(_, name)| name.as_str()).collect();
    names.join(", ")
}

/// [`DrawError::SameObject`]'s line, its roles as said.
fn two_roles(names: &str, first: impl std::fmt::Display, second: impl std::fmt::Display) -> String {
    format!("{names} would be both {first} and {second}: one object cannot play two roles")
}

/// [`DrawError::OurCopy`]'s line, its role as said.
fn our_copy(name: &str, role: impl std::fmt::Display, what: &str) -> String {
    format!("`{name}` ({role}) is a copy vrep-maze pasted into the maze, not {what}")
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

impl TryFrom<&vrep_maze_core::layout::Layout> for Drawing {
    type Error = vrep_maze_core::validate::Invalid;

    /// The layout's segments (template first) or walls, posts, start and end poses, once
    /// the layout has passed [`vrep_maze_core::validate::checked`]: the only way to make a drawing,
    /// so nothing invalid is ever drawn.
    fn try_from(layout: &vrep_maze_core::layout::Layout) -> Result<Drawing, Self::Error> {
        vrep_maze_core::validate::checked(layout)?;
        let pieces = match layout.style {
            Style::Lines => layout.segments.clone(),
            Style::Walls => layout.walls.clone(),
        };
        Ok(Drawing {
            style: layout.style,
            pieces,
            posts: layout.posts.clone(),
            start: layout.start.pose,
            end: layout.end.pose,
            sizes: Sizes::of(layout),
        })
    }
}

/// An object named `name` at the world origin, unturned: the unit tests' scenes.
#[cfg(test)]
pub(crate) fn object_at_origin(handle: i32, name: &str, parent: Option<i32>) -> ObjectInfo {
    ObjectInfo {
        handle,
        name: name.into(),
        parent,
        position: [0.0; 3],
        orientation: [0.0; 3],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_name_in_two_roles_is_refused_naming_both() {
        assert!(ObjectNames::default().check_roles().is_ok());
        let names = ObjectNames {
            end: "/Floor".into(),
            ..Default::default()
        };
        let e = names.check_roles().unwrap_err();
        assert!(
            matches!(
                &e,
                DrawError::SameObject { names, first: Role::Floor, second: Role::End }
                    if names == "`Floor` and `/Floor`"
            ),
            "{e}"
        );
        let names = ObjectNames {
            post: "Line".into(),
            ..Default::default()
        };
        let e = names.check_roles().unwrap_err().to_string();
        assert!(
            e.starts_with("`Line` would be both the line template and the post template"),
            "{e}"
        );
    }
}
