//! Layout JSON, version 1: everything needed to draw, check, render and share one maze.
//!
//! `generate` writes it, `validate`, `render` and `apply` read it. The README documents
//! the schema; `schema/layout-v1.schema.json` is generated from these types. All lengths
//! are metres and all angles radians, in the frame of the scene's `Floor` object.

pub mod block_grid;
pub mod build;
pub mod endpoints;
pub mod geometry;
pub mod import;
pub mod json;
pub mod limits;
pub mod micromouse;
pub mod passages;
pub mod runs;
pub mod sizes;
pub mod solution;
pub mod walls;

use std::collections::BTreeMap;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::maze::Metrics;

pub use build::{FloorSize, GenerateSpec, build_layout};
pub use endpoints::EndpointSpec;
pub use geometry::Geometry;
pub use json::{read_layout, write_layout};

/// The value of the `format` field.
pub const FORMAT: &str = "vrep-maze/layout";
/// The layout version this build reads and writes.
pub const VERSION: u32 = 1;

/// One maze, ready to draw: the root of layout v1.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Layout {
    /// Always `"vrep-maze/layout"`.
    pub format: String,
    /// Layout version: 1.
    pub version: u32,
    /// How the maze is drawn: absent for lines (v1's original style), `"walls"` for walls.
    #[serde(default, skip_serializing_if = "Style::is_lines")]
    pub style: Style,
    /// How the maze was made: enough to make it again.
    pub generator: GeneratorInfo,
    /// The cell grid and where it lies on the floor.
    pub grid: GridSpec,
    /// The floor the maze must fit on.
    pub floor: FloorSpec,
    /// The line template (`Line`) every segment is a copy of.
    pub line: LineSpec,
    /// Wall style only: the wall template (`Wall`, a cuboid) every wall is a copy of, and
    /// the gaps left in the outer boundary.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub wall: Option<WallSpec>,
    /// Wall style with posts only: the post template (`Post`, a square cuboid as high as the
    /// walls) every post is a copy of.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub post: Option<PostSpec>,
    /// Where the robot starts (`Start` marker).
    pub start: Endpoint,
    /// Where the robot must arrive (`End` marker).
    pub end: Endpoint,
    /// What the maze is like; `metrics.loops` declares the loops the passages may form.
    pub metrics: Metrics,
    /// Always [`passages::ENCODING`]: says how to read `passages`.
    pub passage_encoding: String,
    /// The open passages, one string per row: `passages[0]` is row 0 (the south row);
    /// character `x` of a row is the open-passage hex digit of cell (x, row).
    pub passages: Vec<String>,
    /// The line segments to draw, one per copy of `Line` (the template itself is the first);
    /// empty in a wall layout.
    pub segments: Vec<Pose>,
    /// Wall style only: one pose (the cuboid's centre) per copy of `Wall`, every copy a
    /// child of `Maze`; the template itself is not drawn.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    #[schemars(with = "Vec<WallPose>")]
    pub walls: Vec<Pose>,
    /// Wall style with posts only: one pose (the cuboid's centre) per copy of `Post`, one at
    /// every lattice corner, every copy a child of `Maze`; the template itself is not drawn.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    #[schemars(with = "Vec<WallPose>")]
    pub posts: Vec<Pose>,
}

/// A wall's or a post's pose as the schema describes it: a [`Pose`] whose `z`, the centre
/// of the cuboid, is half the wall's height (so up to half of [`walls::HEIGHT`]'s maximum).
#[derive(Debug, Clone, Copy, PartialEq, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct WallPose {
    /// Metres, on the floor.
    #[schemars(range(min = limits::ORIGIN.min, max = limits::ORIGIN.max))]
    pub x: f64,
    /// Metres, on the floor.
    #[schemars(range(min = limits::ORIGIN.min, max = limits::ORIGIN.max))]
    pub y: f64,
    /// Metres above the floor: half the wall's height (a post is as high as the walls).
    #[schemars(range(min = 0.0, max = 50.0))]
    pub z: f64,
    /// Rotation about z, radians in (-pi, pi].
    #[schemars(range(min = limits::YAW.min, max = limits::YAW.max))]
    pub yaw: f64,
}

/// How a maze is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum Style {
    /// Lines on the floor along the passages, for line-following robots (`Line` copies in
    /// `segments`).
    #[default]
    Lines,
    /// Walls on every closed side between cells and around the grid, for robots that
    /// navigate by proximity sensors, lidar or camera (`Wall` copies in `walls`).
    Walls,
}

impl Style {
    /// Both styles, lines first.
    pub const ALL: [Style; 2] = [Style::Lines, Style::Walls];

    /// `true` for [`Style::Lines`] (the field is then left out of the layout).
    pub fn is_lines(&self) -> bool {
        *self == Style::Lines
    }

    /// The style's name in the layout and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Style::Lines => "lines",
            Style::Walls => "walls",
        }
    }
}

/// The wall template's size, and the gaps in the outer boundary.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct WallSpec {
    /// Length along the template's own x axis (along the cell side), metres.
    #[serde(serialize_with = "json::micrometres")]
    #[schemars(range(min = limits::LENGTH.min, max = limits::LENGTH.max))]
    pub length: f64,
    /// Thickness along its y axis, metres.
    #[serde(serialize_with = "json::micrometres")]
    #[schemars(range(min = limits::LENGTH.min, max = limits::LENGTH.max))]
    pub thickness: f64,
    /// Height along its z axis, metres; every wall stands on the floor (centre at half
    /// the height).
    #[serde(serialize_with = "json::micrometres")]
    #[schemars(range(min = walls::HEIGHT.min, max = walls::HEIGHT.max))]
    pub height: f64,
    /// Sides of the outer boundary left open (entrance and exit), in the order given.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub openings: Vec<Opening>,
}

/// The post template's size: a cuboid with a square footprint, as high as the walls
/// (`wall.height`), standing at every lattice corner so the walls' joints are closed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct PostSpec {
    /// Side of the square footprint, metres: at least the wall thickness and less than the
    /// cell; the walls fill the `cell_size - size` between two posts.
    #[serde(serialize_with = "json::micrometres")]
    #[schemars(range(min = limits::LENGTH.min, max = limits::LENGTH.max))]
    pub size: f64,
}

/// A side of the outer boundary left without a wall.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Opening {
    /// Column and row of the boundary cell.
    pub cell: [u32; 2],
    /// Which of its sides is open: it must face out of the grid.
    pub side: Side,
}

/// A side of a cell, by compass name (north is +y).
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Serialize, Deserialize, JsonSchema,
)]
#[serde(rename_all = "lowercase")]
pub enum Side {
    /// -y.
    South,
    /// -x.
    West,
    /// +y.
    North,
    /// +x.
    East,
}

impl Side {
    /// The passage direction through this side.
    pub fn direction(self) -> crate::maze::Direction {
        use crate::maze::Direction;
        match self {
            Side::South => Direction::South,
            Side::West => Direction::West,
            Side::North => Direction::North,
            Side::East => Direction::East,
        }
    }

    /// The side's name in the layout.
    pub fn name(self) -> &'static str {
        match self {
            Side::South => "south",
            Side::West => "west",
            Side::North => "north",
            Side::East => "east",
        }
    }
}

impl Layout {
    /// A copy of everything but the segments (left empty): what a reader or writer that
    /// streams the segments works with.
    pub fn without_segments(&self) -> Layout {
        Layout {
            format: self.format.clone(),
            version: self.version,
            generator: self.generator.clone(),
            grid: self.grid.clone(),
            floor: self.floor.clone(),
            line: self.line.clone(),
            start: self.start.clone(),
            end: self.end.clone(),
            metrics: self.metrics.clone(),
            passage_encoding: self.passage_encoding.clone(),
            passages: self.passages.clone(),
            segments: Vec::new(),
            style: self.style,
            wall: self.wall.clone(),
            walls: self.walls.clone(),
            post: self.post.clone(),
            posts: self.posts.clone(),
        }
    }
}

/// How a layout was generated.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct GeneratorInfo {
    /// Version of vrep-maze that wrote the layout.
    pub crate_version: String,
    /// The `--algo` value.
    pub algorithm: String,
    /// The seed (given, or drawn from the OS and recorded here).
    pub seed: u64,
    /// Algorithm options (name to value), empty when the algorithm has none.
    pub options: BTreeMap<String, String>,
}

/// The grid of cells in the floor frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct GridSpec {
    /// Cells along the maze's x axis.
    pub columns: u32,
    /// Cells along the maze's y axis.
    pub rows: u32,
    /// Side of a square cell, metres.
    #[serde(serialize_with = "json::micrometres")]
    #[schemars(range(min = limits::LENGTH.min, max = limits::LENGTH.max))]
    pub cell_size: f64,
    /// Floor coordinates (x, y) of the centre of cell (0, 0).
    #[serde(serialize_with = "json::micrometres_pair")]
    #[schemars(inner(range(min = limits::ORIGIN.min, max = limits::ORIGIN.max)))]
    pub origin: [f64; 2],
    /// Rotation of the maze about the floor's z axis, radians, counter-clockwise.
    #[serde(serialize_with = "json::micrometres")]
    #[schemars(range(min = limits::ROTATION.min, max = limits::ROTATION.max))]
    pub rotation: f64,
}

/// The floor, centred on the floor frame's origin.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct FloorSpec {
    /// Extent along x and y, metres.
    #[serde(serialize_with = "json::micrometres_pair")]
    #[schemars(inner(range(min = limits::FLOOR.min, max = limits::FLOOR.max)))]
    pub size: [f64; 2],
}

/// The line template's size and height.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct LineSpec {
    /// Length along the template's own x axis, metres.
    #[serde(serialize_with = "json::micrometres")]
    #[schemars(range(min = limits::LENGTH.min, max = limits::LENGTH.max))]
    pub length: f64,
    /// Width along its y axis, metres.
    #[serde(serialize_with = "json::micrometres")]
    #[schemars(range(min = limits::LENGTH.min, max = limits::LENGTH.max))]
    pub width: f64,
    /// Height of every segment above the floor, metres.
    #[serde(serialize_with = "json::micrometres")]
    #[schemars(range(min = limits::HEIGHT.min, max = limits::HEIGHT.max))]
    pub z: f64,
}

/// A marked cell (start or end) and where its marker goes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Endpoint {
    /// Column and row of the cell.
    pub cell: [u32; 2],
    /// The marker's pose: the cell centre, at marker height.
    pub pose: Pose,
    /// End only, optional: a goal region, connected cells that `cell` belongs to; reaching
    /// any of them solves the maze, and `cell` is the one nearest the start.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub region: Vec<[u32; 2]>,
}

/// A position and a heading in the floor frame (roll and pitch are always 0).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct Pose {
    /// Metres, on the floor.
    #[serde(serialize_with = "json::micrometres")]
    #[schemars(range(min = limits::ORIGIN.min, max = limits::ORIGIN.max))]
    pub x: f64,
    /// Metres, on the floor.
    #[serde(serialize_with = "json::micrometres")]
    #[schemars(range(min = limits::ORIGIN.min, max = limits::ORIGIN.max))]
    pub y: f64,
    /// Metres above the floor.
    #[serde(serialize_with = "json::micrometres")]
    #[schemars(range(min = limits::HEIGHT.min, max = limits::HEIGHT.max))]
    pub z: f64,
    /// Rotation about z, radians in (-pi, pi].
    #[serde(serialize_with = "json::micrometres")]
    #[schemars(range(min = limits::YAW.min, max = limits::YAW.max))]
    pub yaw: f64,
}
