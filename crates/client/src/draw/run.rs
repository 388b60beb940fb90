//! One whole apply, whatever asks for it ([`run`]): create the missing objects if the
//! [`Job`] asks, draw its [`Picture`] (copies or meshes) and verify it, save the scene if
//! asked. The command line and the Python package are adapters over it: they build the job
//! from their options and tell its [`Report`] or [`RunError`] in their own words.

use vrep_maze_core::layout::Layout;
use vrep_maze_core::mesh::MeshMaze;
use vrep_maze_core::validate::Invalid;

use super::apply::apply;
use super::backend::{Backend, create_missing_for};
use super::drawing::Drawing;
use super::error::{BackendError, DrawError};
use super::mesh;
use super::options::ApplyOptions;
use super::report::{ApplyReport, DrawMode, Stage};

/// What a job draws: a layout made into copies or meshes.
#[derive(Debug, Clone)]
pub enum Picture {
    /// One copy of a template per line, wall or post.
    Copies(Drawing),
    /// A few mesh shapes.
    Mesh(MeshMaze),
}

impl Picture {
    /// `layout` drawn the `mode` way, or why it cannot be drawn.
    pub fn of(layout: &Layout, mode: DrawMode) -> Result<Picture, Invalid> {
        Ok(match mode {
            DrawMode::Copies => Picture::Copies(Drawing::try_from(layout)?),
            DrawMode::Mesh => Picture::Mesh(MeshMaze::try_from(layout)?),
        })
    }

    /// The pieces the drawing counts as it goes: copies (lines or walls, and posts), or
    /// straight runs and posts.
    pub fn pieces(&self) -> usize {
        match self {
            Picture::Copies(drawing) => drawing.copies(),
            Picture::Mesh(maze) => maze.pieces(),
        }
    }

    /// The layout's style.
    pub fn style(&self) -> vrep_maze_core::layout::Style {
        match self {
            Picture::Copies(drawing) => drawing.style,
            Picture::Mesh(maze) => maze.style,
        }
    }
}

/// One apply: what to draw and how.
#[derive(Debug, Clone)]
pub struct Job<'a> {
    /// The layout (the missing objects are made to its sizes).
    pub layout: &'a Layout,
    /// What is drawn ([`Picture::of`] the layout).
    pub picture: Picture,
    /// The object names, dry run, stopping the simulation, the floor, Ctrl-C.
    pub options: ApplyOptions,
    /// Create the missing scene objects first (ZeroMQ only; not on a dry run).
    pub create_missing: bool,
    /// Save the scene afterwards to this path on the simulator's machine (ZeroMQ only; not on
    /// a dry run).
    pub save_scene: Option<String>,
}

/// What [`run`] did.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Report {
    /// The objects created first ([`Job::create_missing`]).
    pub created: Vec<String>,
    /// The drawing's counts.
    pub drawn: ApplyReport,
    /// Where the scene was saved, if it was.
    pub saved_scene: Option<String>,
}

/// Why [`run`] failed.
#[derive(Debug, thiserror::Error)]
pub enum RunError {
    /// [`Job::create_missing`] or [`Job::save_scene`] asked of an API that cannot author
    /// scenes (the legacy API).
    #[error("the legacy API cannot create objects or save scenes ({0:?})")]
    NoAuthoring(Authored),
    /// Creating the missing objects failed.
    #[error("creating the missing scene objects: {0}")]
    Create(#[source] BackendError),
    /// The drawing failed ([`DrawError::Interrupted`] included).
    #[error(transparent)]
    Draw(#[from] DrawError),
    /// Saving the scene failed.
    #[error("saving the scene to {path}: {source}")]
    Save {
        /// Where it was to be saved.
        path: String,
        /// What the simulator answered.
        #[source]
        source: BackendError,
    },
}

/// What a job asked that only an authoring API does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Authored {
    /// [`Job::create_missing`].
    CreateMissing,
    /// [`Job::save_scene`].
    SaveScene,
}

/// Runs `job` on a connected `scene`: creates the missing objects if asked (then tells
/// `progress` [`Stage::Created`]), draws and verifies the picture, saves the scene if asked.
/// The connection stays open: a caller may run the next job on it.
pub fn run(
    scene: &mut dyn Backend,
    job: &Job<'_>,
    progress: &mut dyn FnMut(Stage),
) -> Result<Report, RunError> {
    let opts = &job.options;
    let mut created = Vec::new();
    if job.create_missing && !opts.dry_run {
        let authoring = scene
            .authoring()
            .ok_or(RunError::NoAuthoring(Authored::CreateMissing))?;
        created =
            create_missing_for(authoring, &opts.names, job.layout).map_err(RunError::Create)?;
        progress(Stage::Created(created.clone()));
    }
    let drawn = match &job.picture {
        Picture::Copies(drawing) => apply(scene, drawing, opts, progress)?,
        Picture::Mesh(maze) => mesh::apply(scene, maze, opts, progress)?,
    };
    let mut saved_scene = None;
    if let Some(path) = job.save_scene.as_deref().filter(|_| !opts.dry_run) {
        let authoring = scene
            .authoring()
            .ok_or(RunError::NoAuthoring(Authored::SaveScene))?;
        authoring
            .save_scene(path)
            .map_err(|source| RunError::Save {
                path: path.to_string(),
                source,
            })?;
        saved_scene = Some(path.to_string());
    }
    Ok(Report {
        created,
        drawn,
        saved_scene,
    })
}
