//! Why a drawing failed ([`DrawError`]), and its lines in an adapter's words
//! ([`DrawError::message`]).

use vrep_maze_core::layout::sizes::Sizes;
use vrep_maze_core::wording::{Message, Neutral, Opt, Value, Wording};

use super::extent::{FloorShort, Resize};
use super::role::Role;

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

/// Errors of [`apply()`](super::apply()), [`clear()`](super::clear()) and [`verify()`](super::verify()).
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
    /// Two roles name one object ([`ObjectNames::check_roles`](super::names::ObjectNames::check_roles), or two names the scene
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
    /// (`fit::check_sizes`): refused before any edit, one line per template with what
    /// to change.
    #[error("{}", sizes(.0, &Neutral))]
    Sizes(Vec<Message>),
    /// The scene's floor is smaller than the layout's (`fit::SizeCheck::floor`): refused
    /// before any edit unless `apply --resize-floor` grows it ([`super::floor::resize`]).
    #[error("{}", .short.describe_resize(.floor, *.resize))]
    Floor {
        /// The floor's name.
        floor: String,
        /// Its size and the layout's.
        short: FloorShort,
        /// Whether this connection can resize it.
        resize: Resize,
    },
    /// The simulation runs; edits would be lost when it stops.
    #[error("the simulation is running: changes made now would be discarded when it stops")]
    SimulationRunning,
    /// Another `apply` or `clear` claimed the scene while this one ran ([`lease`](super::lease)).
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
        /// Lines placed before the interrupt ([`clear()`](super::clear()): objects removed).
        placed: usize,
        /// Lines in the drawing ([`clear()`](super::clear()): objects to remove).
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
        /// The connection, as [`Backend::describe`](super::backend::Backend::describe) says it.
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
