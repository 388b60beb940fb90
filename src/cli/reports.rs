//! The JSON documents that `--json` prints, one per run: their types, from which the
//! schemas in `schema/` are generated (`tests/it/schema.rs` keeps them equal). Each has a
//! `format` naming it and a `version`.

use schemars::JsonSchema;
use serde::Serialize;

use crate::layout::solution::SolveReport;
use crate::layout::{Layout, Style};
use crate::maze::Metrics;

/// Version of every report below.
pub const REPORT_VERSION: u32 = 1;

/// What `vrep-maze validate --json` prints (`schema/validate-v1.schema.json`).
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct ValidateReport {
    /// Always `"vrep-maze/validate"`.
    pub format: String,
    /// Report version: 1.
    pub version: u32,
    /// `true` if every file is a valid layout (the exit code is then 0).
    pub valid: bool,
    /// One entry per file, in the order given.
    pub files: Vec<ValidatedFile>,
}

/// One file `validate` checked.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct ValidatedFile {
    /// The file as given (`-` for standard input).
    pub file: String,
    /// `true` if it is a valid layout.
    pub valid: bool,
    /// The file could not be read as a layout at all (then no `maze`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// What the layout says it is, when it could be read.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub maze: Option<MazeSummary>,
    /// What the maze is like, when it is valid.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub metrics: Option<Metrics>,
    /// Every problem kept, `field: what is wrong` (at most 20).
    pub problems: Vec<String>,
    /// How many problems were found, kept or not.
    pub problem_count: usize,
}

/// A layout's size, maker and what it draws.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct MazeSummary {
    /// Cells along x.
    pub columns: u32,
    /// Cells along y.
    pub rows: u32,
    /// The algorithm's name.
    pub algorithm: String,
    /// The seed.
    pub seed: u64,
    /// lines or walls.
    pub style: Style,
    /// Line segments (counted as they streamed past).
    pub segments: usize,
    /// Walls.
    pub walls: usize,
    /// Posts.
    pub posts: usize,
}

impl MazeSummary {
    /// The summary of `layout`, whose `segments` were counted as they streamed past.
    pub fn of(layout: &Layout, segments: usize) -> Self {
        Self {
            columns: layout.grid.columns,
            rows: layout.grid.rows,
            algorithm: layout.generator.algorithm.clone(),
            seed: layout.generator.seed,
            style: layout.style,
            segments,
            walls: layout.walls.len(),
            posts: layout.posts.len(),
        }
    }
}

/// What `vrep-maze batch --json` prints (`schema/batch-v1.schema.json`).
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct BatchReport {
    /// Always `"vrep-maze/batch"`.
    pub format: String,
    /// Report version: 1.
    pub version: u32,
    /// Seeds asked for.
    pub seeds: usize,
    /// Layouts written (new or changed).
    pub written: usize,
    /// Layouts already on disk, byte for byte.
    pub unchanged: usize,
    /// Seeds whose maze the filter refused.
    pub filtered: usize,
    /// Seeds not made because the run was interrupted.
    pub skipped: usize,
    /// Temporary files of an earlier, killed run that were removed first.
    pub stale_removed: usize,
    /// The manifest written (one JSON line per maze kept).
    pub manifest: String,
    /// `true` if Ctrl-C stopped the run (exit code 130).
    pub interrupted: bool,
}

/// What `vrep-maze apply --json` prints (`schema/apply-v1.schema.json`).
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct ApplyJson {
    /// Always `"vrep-maze/apply"`.
    pub format: String,
    /// Report version: 1.
    pub version: u32,
    /// The layout file drawn.
    pub layout: String,
    /// Which API answered, where (and over ZeroMQ the simulator's version).
    pub connection: String,
    /// lines or walls: what `lines` counts.
    pub style: Style,
    /// What the drawing counted.
    #[serde(flatten)]
    pub counts: ApplyCounts,
    /// Wall time, seconds.
    pub seconds: f64,
    /// The simulation was stopped first.
    pub stopped_simulation: bool,
    /// Dry run: nothing was changed.
    pub dry_run: bool,
    /// Every copy, start and end was read back in place (false on a dry run).
    pub verified: bool,
    /// Scene objects created first (`--create-missing`).
    pub created: Vec<String>,
    /// Where the scene was saved (`--save-scene`), on the simulator's machine.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub saved_scene: Option<String>,
}

/// The counts of a finished apply, named as users read them: the `--json` document
/// (flattened into [`ApplyJson`]) and Python's `ApplyReport` embed this one type, made from
/// the drawing's report at the edge ([`ApplyCounts::of`]; `draw`'s `pieces` are `lines`).
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct ApplyCounts {
    /// Lines drawn (template included), or walls: with `posts`, `unchanged + placed +
    /// pasted` (`--draw mesh`: rectangles).
    pub lines: usize,
    /// Posts drawn.
    pub posts: usize,
    /// Earlier copies reused (`--draw mesh`: meshes kept).
    pub reused: usize,
    /// Copies pasted (`--draw mesh`: meshes created).
    pub pasted: usize,
    /// Earlier copies removed (`--draw mesh`: earlier meshes and copies).
    pub removed: usize,
    /// Objects of an earlier mesh maze a copies draw removed (its meshes and their holder),
    /// counted apart from `removed`.
    pub removed_meshes: usize,
    /// Lines and posts kept (the template, reused copies) already in place: no edit sent.
    pub unchanged: usize,
    /// Lines and posts kept whose pose (or parent) was sent.
    pub placed: usize,
    /// Of `placed`: poses sent without reading them first, perhaps in place already (over
    /// ZeroMQ reading a copy's pose costs a round trip as setting it does, so a re-apply
    /// sets them unread; 0 over the legacy API, which reads them all at once).
    pub placed_unread: usize,
    /// Markers (`Start`, `End`, the line template where it is not a line) already in place.
    pub markers_unchanged: usize,
    /// Markers whose pose was sent.
    pub markers_placed: usize,
    /// A dry run found that a real run would change nothing.
    pub nothing_to_do: bool,
    /// Edits sent.
    pub edits: usize,
    /// Messages exchanged with the simulator.
    pub round_trips: usize,
}

impl ApplyCounts {
    /// The counts of `report`.
    pub fn of(report: &crate::draw::ApplyReport) -> ApplyCounts {
        ApplyCounts {
            lines: report.pieces,
            posts: report.posts,
            reused: report.reused,
            pasted: report.pasted,
            removed: report.removed,
            removed_meshes: report.removed_meshes,
            unchanged: report.unchanged,
            placed: report.placed,
            placed_unread: report.unread,
            markers_unchanged: report.markers_unchanged,
            markers_placed: report.markers_placed,
            nothing_to_do: report.dry_run && report.nothing_to_do(),
            edits: report.edits,
            round_trips: report.round_trips,
        }
    }
}

/// What `vrep-maze clear --json` prints (`schema/clear-v1.schema.json`).
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct ClearJson {
    /// Always `"vrep-maze/clear"`.
    pub format: String,
    /// Report version: 1.
    pub version: u32,
    /// Which API answered, where (and over ZeroMQ the simulator's version).
    pub connection: String,
    /// Names of the copies of the templates removed (or that would be, on a dry run).
    pub removed: Vec<String>,
    /// Names of the objects of a mesh maze (`apply --draw mesh`) removed (or that would be):
    /// its meshes, then their holder `MazeMeshes`.
    pub removed_meshes: Vec<String>,
    /// Messages exchanged with the simulator.
    pub round_trips: usize,
    /// The idle rate restored (an interrupted apply had left it at 0).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub restored_idle_fps: Option<i32>,
    /// The simulation was stopped first.
    pub stopped_simulation: bool,
    /// Dry run: nothing was changed.
    pub dry_run: bool,
}

/// What `vrep-maze inspect --json` prints (`schema/inspect-v1.schema.json`).
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct InspectReport {
    /// Always `"vrep-maze/inspect"`.
    pub format: String,
    /// Report version: 1.
    pub version: u32,
    /// Which API answered, where (and over ZeroMQ the simulator's version).
    pub connection: String,
    /// The simulation is not stopped.
    pub simulation_running: bool,
    /// The idle rate now (`sim_intparam_idle_fps`).
    pub idle_fps: i32,
    /// The user's idle rate recorded by an `apply` that was interrupted (the idle rate is
    /// then its 0; `clear` restores it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub saved_idle_fps: Option<i32>,
    /// The named objects: floor, maze dummy, templates, markers.
    pub objects: Vec<SceneObject>,
    /// The API read the shapes' colours (ZeroMQ); `false` over the legacy API, which cannot
    /// read a colour, so no object has one.
    pub colours_read: bool,
    /// The maze drawn.
    pub maze: DrawnMaze,
    /// With `--layout`: whether the drawing matches it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub layout: Option<LayoutMatch>,
}

/// One of the objects vrep-maze uses, as found in the scene.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct SceneObject {
    /// What it is for: floor, maze dummy, line template, wall template, post template,
    /// start marker, end marker.
    pub role: String,
    /// Its name (the command line's `--floor`, `--line`, ...).
    pub name: String,
    /// It is in the scene.
    pub present: bool,
    /// Its handle in this scene.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub handle: Option<i32>,
    /// Position, metres: in the floor's frame (the floor's own in the world's), when read.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub position: Option<[f64; 3]>,
    /// CoppeliaSim Euler angles, radians, in the same frame (yaw last), when read.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub orientation: Option<[f64; 3]>,
    /// Bounding-box size along its own x, y, z, metres (a plane's z is 0), when the simulator
    /// gives one (float parameters 15..20; single precision, rounded to the micrometre).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub size: Option<[f64; 3]>,
    /// A shape's ambient-diffuse colour, RGB 0..1, when read (ZeroMQ `sim.getShapeColor`;
    /// never over the legacy API: see `colours_read`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub colour: Option<[f64; 3]>,
}

/// The copies under the maze dummy.
#[derive(Debug, Clone, Default, Serialize, JsonSchema)]
pub struct DrawnMaze {
    /// Copies of the line template under the maze dummy.
    pub lines: usize,
    /// Copies of the wall template under the maze dummy.
    pub walls: usize,
    /// Copies of the post template under the maze dummy.
    pub posts: usize,
    /// A mesh maze's meshes (`apply --draw mesh`): the objects under the holder
    /// `MazeMeshes`, by name.
    pub meshes: Vec<String>,
    /// lines or walls when the copies and meshes are one style's; absent when there are
    /// none, or both.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub style: Option<Style>,
    /// Children of the maze dummy whose names the API did not read (ZeroMQ, in a scene
    /// without another style's template): counted as copies of the template drawn, as
    /// `apply` treats them.
    pub names_unread: usize,
    /// Copies of a template outside the maze dummy (left by an interrupted run).
    pub stray_copies: Vec<String>,
    /// Objects under the maze dummy that vrep-maze did not draw.
    pub not_ours: Vec<String>,
}

/// Whether the drawing in the scene is a layout's.
#[derive(Debug, Clone, Serialize, JsonSchema)]
pub struct LayoutMatch {
    /// The layout file compared.
    pub file: String,
    /// Every copy, start and end in place and nothing else drawn.
    pub matches: bool,
    /// What differs (as `apply`'s verification says it).
    pub differences: Vec<String>,
}

/// Every report's schema file name (under `schema/`) and its JSON Schema.
pub fn schemas() -> Vec<(&'static str, schemars::Schema)> {
    vec![
        (
            "validate-v1.schema.json",
            schemars::schema_for!(ValidateReport),
        ),
        ("batch-v1.schema.json", schemars::schema_for!(BatchReport)),
        ("solve-v1.schema.json", schemars::schema_for!(SolveReport)),
        ("apply-v1.schema.json", schemars::schema_for!(ApplyJson)),
        ("clear-v1.schema.json", schemars::schema_for!(ClearJson)),
        (
            "inspect-v1.schema.json",
            schemars::schema_for!(InspectReport),
        ),
    ]
}
