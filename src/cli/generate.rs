//! `vrep-maze generate`: make a maze and write its layout.

use std::path::PathBuf;
use std::process::ExitCode;
use std::str::FromStr;

use anyhow::Result;
use clap::Args;

use super::listed::listed;
use super::output::write_output;
use super::progress::{Progress, Unit};
use super::usage::usage;
use super::values::{
    parse_finite, parse_floor, parse_metres, parse_point, parse_share, parse_size,
};
use crate::generate::{Algorithm, Bias, GrowingMode};
use crate::layout::build::{Planned, plan_layout};
use crate::layout::endpoints::{END_WORDS, ENDPOINT_HELP, START_WORDS};
use crate::layout::geometry::course;
use crate::layout::json::write_layout_parts;
use crate::layout::limits;
use crate::layout::micromouse::{self, Preset};
use crate::layout::walls::{self, OPENINGS_WORDS, Openings, WallOptions};
use crate::layout::{EndpointSpec, FloorSize, GenerateSpec, Geometry, Layout, Style};
use crate::maze::Grid;
use crate::rng::os_seed;

/// Options of `generate`.
#[derive(Debug, Clone, Args)]
#[command(
    after_help = "Examples:\n  vrep-maze generate --seed 42 --algo prim -o maze.json\n  vrep-maze generate --size 20x15 --start nw --end se --seed 7 > big.json\n  vrep-maze generate --cell-size 0.5 --line-length 0.3 --line-width 0.05 --seed 1\n  vrep-maze generate --style walls --openings start,end --end ne --seed 42 -o walls.json\n  vrep-maze generate --style walls --posts --seed 42 -o posts.json\n  vrep-maze generate --preset micromouse --posts --seed 3 -o mouse.json"
)]
pub struct GenerateArgs {
    /// Seed of the random stream; without it one is drawn from the OS and recorded in the
    /// layout (and printed), so the maze can be made again.
    #[arg(long, allow_hyphen_values = true)]
    pub seed: Option<u64>,
    /// What maze to make and how it is drawn.
    #[command(flatten)]
    pub layout: LayoutArgs,
    /// Write the layout here (atomically) instead of standard output.
    #[arg(short, long)]
    pub output: Option<PathBuf>,
}

/// Every option of `generate` but the seed and the output: what maze to make and how it is
/// drawn. `batch` flattens the same struct, so the two commands cannot drift apart.
#[derive(Debug, Clone, Args)]
pub struct LayoutArgs {
    /// What maze to make.
    #[command(flatten)]
    pub maze: MazeArgs,
    /// How the maze is drawn.
    #[command(flatten)]
    pub style: StyleArgs,
}

impl LayoutArgs {
    /// The layout these options describe for `seed`, its segments (if lines) still to be
    /// computed.
    pub fn plan(&self, seed: u64) -> Result<Planned> {
        let spec = self.maze.spec(seed)?;
        plan(&spec, &self.style, self.maze.origin)
    }

    /// Every option checked, as [`LayoutArgs::plan`] checks them, without making a maze
    /// (what is left to refuse depends on the maze: its start and end).
    pub fn check(&self) -> Result<()> {
        let spec = self.maze.spec(0)?;
        match self.style.preset {
            Some(preset) => {
                let cell_size = preset.spec(spec, self.maze.origin).geometry.cell_size;
                self.style
                    .posts(preset.walls(None).thickness, cell_size)
                    .map(drop)
            }
            None => self.style.walls(spec.geometry.cell_size).map(drop),
        }
    }

    /// The file `batch` writes the maze of `seed` to: `<algo>-<W>x<H>[-braid<P>]-seed<N>`,
    /// then `-walls` (and `-posts`) for a wall maze, or `<algo>-<preset>[-posts]-seed<N>`
    /// for a preset; `.json`.
    pub fn file_name(&self, seed: u64) -> Result<String> {
        let spec = self.maze.spec(seed)?;
        let posts = if self.style.posts { "-posts" } else { "" };
        if let Some(preset) = self.style.preset {
            return Ok(format!(
                "{}-{}{posts}-seed{seed}.json",
                spec.algorithm.name(),
                preset.name()
            ));
        }
        let name = crate::batch::file_name(&spec);
        Ok(match self.style.style {
            Style::Lines => name,
            Style::Walls => format!("{}-walls{posts}.json", name.trim_end_matches(".json")),
        })
    }
}

/// The maze options `generate` and `batch` share: everything but the seed.
#[derive(Debug, Clone, Args)]
pub struct MazeArgs {
    /// Algorithm: dfs, prim, kruskal, aldous-broder, wilson, hunt-and-kill, growing-tree,
    /// eller, sidewinder, binary-tree, recursive-division (textures in the README).
    #[arg(
        long,
        default_value = "dfs",
        value_parser = listed(Algorithm::from_str, Algorithm::ALL.map(Algorithm::name)),
        hide_possible_values = true
    )]
    pub algo: Algorithm,
    /// Growing tree only: which cell grows next, newest|oldest|random|middle|mix:P
    /// (newest with probability P, else random) [default: newest].
    #[arg(long, value_parser = listed(growing_mode, GrowingMode::WORDS), hide_possible_values = true)]
    pub growing: Option<GrowingMode>,
    /// Binary tree only: the two directions every cell opens towards, ne|nw|se|sw
    /// [default: ne].
    #[arg(long, value_parser = listed(Bias::parse, Bias::ALL.map(Bias::name)), hide_possible_values = true)]
    pub bias: Option<Bias>,
    /// Braid: share (0 to 1) of dead ends to open into loops, so wall-following fails;
    /// 0 keeps the maze perfect.
    #[arg(long, default_value_t = 0.0, value_parser = parse_share, allow_hyphen_values = true)]
    pub braid: f64,
    /// Grid size in cells, WxH (at most 4096x4096 cells in all).
    #[arg(long, default_value = "9x9", value_parser = parse_size, allow_hyphen_values = true)]
    pub size: (u64, u64),
    /// Start cell: a cell 'x,y', a corner 'sw|se|nw|ne', or 'farthest-pair' (both ends of the longest path; then no --end).
    #[arg(long, default_value = "sw", value_parser = listed(parse_endpoint, START_WORDS), hide_possible_values = true)]
    pub start: EndpointSpec,
    /// End cell: a cell 'x,y', a corner, or 'farthest' (farthest from the start along the maze).
    #[arg(long, default_value = "farthest", value_parser = listed(parse_endpoint, END_WORDS), hide_possible_values = true)]
    pub end: EndpointSpec,
    /// Side of a cell, metres: 0.001..10000, and at least line length - line width.
    #[arg(long, default_value_t = course::CELL_SIZE, value_parser = parse_metres, allow_hyphen_values = true)]
    pub cell_size: f64,
    /// Length of the Line template, metres: 0.001..10000, and at most 64 copies a passage.
    #[arg(long, default_value_t = course::LINE_LENGTH, value_parser = parse_metres, allow_hyphen_values = true)]
    pub line_length: f64,
    /// Width of the Line template, metres: 0.001..10000, and less than the cell size.
    #[arg(long, default_value_t = course::LINE_WIDTH, value_parser = parse_metres, allow_hyphen_values = true)]
    pub line_width: f64,
    /// Height of the lines above the floor, metres: 0.000001..0.05.
    #[arg(long, default_value_t = course::LINE_Z, value_parser = parse_finite, allow_hyphen_values = true)]
    pub line_z: f64,
    /// Height of the Start and End markers, metres: 0.000001..0.05, above the lines.
    #[arg(long, default_value_t = course::MARKER_Z, value_parser = parse_finite, allow_hyphen_values = true)]
    pub marker_z: f64,
    /// Floor position x,y of cell (0,0)'s centre before any --rotation, each -5000..5000 [default: the maze centred on the floor origin].
    #[arg(long, value_parser = parse_point, allow_hyphen_values = true)]
    pub origin: Option<[f64; 2]>,
    /// Rotation of the maze about its own centre (a vertical axis through the middle of its
    /// cells, which stays where --origin puts it), degrees counter-clockwise: any finite angle.
    #[arg(long, default_value_t = 0.0, value_parser = parse_finite, allow_hyphen_values = true)]
    pub rotation: f64,
    /// Floor size XxY in metres the maze must fit, each side 0.001..10000 [default: 10x10, grown in 5 m panels to fit].
    #[arg(long, value_parser = parse_floor, allow_hyphen_values = true)]
    pub floor_size: Option<[f64; 2]>,
}

/// How `generate` draws the maze: lines or walls, and the micromouse presets.
#[derive(Debug, Clone, Args)]
pub struct StyleArgs {
    /// lines (Line copies on the floor, for line followers) or walls (a Wall cuboid on
    /// every closed side and around the grid, for robots that sense walls).
    #[arg(long, default_value = "lines", value_parser = listed(parse_style, Style::ALL.map(Style::name)), hide_possible_values = true)]
    pub style: Style,
    /// Walls only: length of the Wall template, metres, at most the cell size [default: 1].
    #[arg(long, value_parser = parse_metres, allow_hyphen_values = true)]
    pub wall_length: Option<f64>,
    /// Walls only: thickness of the Wall template, metres, less than the cell size [default: 0.05].
    #[arg(long, value_parser = parse_metres, allow_hyphen_values = true)]
    pub wall_thickness: Option<f64>,
    /// Walls only: height of the Wall template, metres, 0.001..100 [default: 0.2].
    #[arg(long, value_parser = parse_metres, allow_hyphen_values = true)]
    pub wall_height: Option<f64>,
    /// Walls only: gaps in the outer wall beside the start and/or end cell: none, start,
    /// end or start,end (the cell must be on the edge) [default: none].
    #[arg(long, value_parser = listed(parse_openings, OPENINGS_WORDS), hide_possible_values = true)]
    pub openings: Option<Openings>,
    /// Walls only (with --style walls or a --preset): a Post cuboid at every lattice corner,
    /// as high as the walls, so their joints are closed; the walls then fill the space
    /// between two posts (default length: cell size - post size).
    #[arg(long)]
    pub posts: bool,
    /// With --posts: side of the square Post, metres, at least the wall thickness and less
    /// than the cell size [default: the wall thickness].
    #[arg(long, value_parser = parse_metres, allow_hyphen_values = true)]
    pub post_size: Option<f64>,
    /// A micromouse maze: micromouse (16x16 cells of 0.18 m, walls 0.012 m thick, 0.05 m
    /// high) or micromouse-half (32x32 of 0.09 m); start in the south-west corner opening
    /// one way, goal the 2x2 centre with a single entrance. With --posts, posts as thick as
    /// the walls and walls between them (0.168 m in the classic), as in competition mazes.
    #[arg(long, value_parser = listed(parse_preset, Preset::ALL.map(Preset::name)), hide_possible_values = true, conflicts_with_all = [
        "size", "cell_size", "start", "end", "braid", "line_length", "line_width",
        "style", "wall_length", "wall_thickness", "wall_height", "openings",
    ])]
    pub preset: Option<Preset>,
}

fn parse_style(s: &str) -> Result<Style, String> {
    match s {
        "lines" => Ok(Style::Lines),
        "walls" => Ok(Style::Walls),
        _ => Err(format!("'{s}' is not a style: use lines or walls")),
    }
}

fn parse_openings(s: &str) -> Result<Openings, String> {
    s.parse()
}

fn parse_preset(s: &str) -> Result<Preset, String> {
    Preset::from_name(s)
        .ok_or_else(|| format!("'{s}' is not a preset: use micromouse or micromouse-half"))
}

impl StyleArgs {
    /// The wall options asked for on cells of `cell_size`, `None` for lines; wall options
    /// without `--style walls` are refused.
    fn walls(&self, cell_size: f64) -> Result<Option<WallOptions>> {
        if self.style == Style::Lines {
            let given = [
                ("--wall-length", self.wall_length.is_some()),
                ("--wall-thickness", self.wall_thickness.is_some()),
                ("--wall-height", self.wall_height.is_some()),
                ("--openings", self.openings.is_some()),
                ("--posts", self.posts),
                ("--post-size", self.post_size.is_some()),
            ];
            if let Some((name, _)) = given.iter().find(|(_, g)| *g) {
                return Err(usage(format!(
                    "{name} shapes walls: add --style walls (the maze is drawn with lines)"
                )));
            }
            return Ok(None);
        }
        let d = WallOptions::default();
        let thickness = self.wall_thickness.unwrap_or(d.thickness);
        let posts = self.posts(thickness, cell_size)?;
        let length = match posts {
            Some(size) => walls::length_between_posts(cell_size, size),
            None => d.length,
        };
        Ok(Some(WallOptions {
            length: self.wall_length.unwrap_or(length),
            thickness,
            height: self.wall_height.unwrap_or(d.height),
            openings: self.openings.unwrap_or(d.openings),
            posts,
        }))
    }

    /// The side of the posts asked for (`--post-size`, else `thickness`), `None` without
    /// `--posts`; a size without `--posts` is refused, and so is one that leaves the walls
    /// between posts on cells of `cell_size` (when their length is not given) too short:
    /// the message names the option the user gave (`--post-size` or `--wall-thickness`),
    /// not the wall length derived from it.
    fn posts(&self, thickness: f64, cell_size: f64) -> Result<Option<f64>> {
        if !self.posts && self.post_size.is_some() {
            return Err(usage(
                "--post-size shapes posts: add --posts (the maze has no posts)",
            ));
        }
        let size = self.post_size.unwrap_or(thickness);
        if self.posts
            && self.wall_length.is_none()
            && limits::LENGTH.contains(size)
            && limits::LENGTH.contains(cell_size)
            && walls::length_between_posts(cell_size, size) < limits::LENGTH.min
        {
            let given = if self.post_size.is_some() {
                "--post-size"
            } else {
                "--wall-thickness (the posts' side unless --post-size is given)"
            };
            return Err(usage(format!(
                "{given} {} m leaves no room for the walls between the posts on {} m cells: at most {} m",
                limits::show(size),
                limits::show(cell_size),
                limits::show(cell_size - limits::LENGTH.min)
            )));
        }
        Ok(self.posts.then(|| self.post_size.unwrap_or(thickness)))
    }
}

impl GenerateArgs {
    /// The layout these options describe for `seed` (the caller's: given, or drawn), its
    /// segments (if lines) still to be computed: what `generate` writes, for programs that
    /// embed the command line (the Python package's `generate`).
    pub fn plan(&self, seed: u64) -> Result<Planned> {
        self.layout.plan(seed)
    }
}

/// The layout `spec` and the style options describe, its segments (if lines) still to be
/// computed.
fn plan(spec: &GenerateSpec, style: &StyleArgs, origin: Option<[f64; 2]>) -> Result<Planned> {
    if let Some(preset) = style.preset {
        let mut spec = preset.spec(spec.clone(), origin);
        spec.geometry = spec.geometry.turned_about_centre(spec.grid);
        let posts = style.posts(preset.walls(None).thickness, spec.geometry.cell_size)?;
        return micromouse::plan(preset, &spec, posts).map_err(usage);
    }
    let walls = style.walls(spec.geometry.cell_size)?;
    let planned = plan_layout(spec).map_err(usage)?;
    match walls {
        Some(options) => {
            let auto_floor = spec.floor == FloorSize::Auto;
            planned
                .with_walls(|head, maze| walls::into_walls(head, maze, &options, auto_floor))
                .map_err(usage)
        }
        None => Ok(planned),
    }
}

/// A `--growing` value, refused in the command line's words.
fn growing_mode(s: &str) -> Result<GrowingMode, String> {
    GrowingMode::parse(s).map_err(|e| super::wording::worded(&e))
}

fn parse_endpoint(s: &str) -> Result<EndpointSpec, String> {
    s.parse()
        .map_err(|e: String| format!("{e}; use {ENDPOINT_HELP}"))
}

impl MazeArgs {
    /// The generate spec these options describe (`seed` decided by the caller), every
    /// value checked against the layout limits before anything is allocated.
    pub fn spec(&self, seed: u64) -> Result<GenerateSpec> {
        let grid =
            Grid::new(self.size.0, self.size.1).map_err(|e| usage(format!("--size: {e}")))?;
        let algorithm = self
            .algo
            .with_options(self.growing, self.bias)
            .map_err(usage)?;
        let cell_size = self.cell_size;
        // Any finite angle: whole turns beyond one are dropped (exactly, in degrees), so
        // every angle a user could mean within a turn is kept as given.
        let rotation = if self.rotation.abs() > 360.0 {
            self.rotation % 360.0
        } else {
            self.rotation
        };
        let spec = GenerateSpec {
            grid,
            algorithm,
            seed,
            braid: self.braid,
            start: self.start,
            end: self.end,
            geometry: Geometry {
                cell_size,
                origin: self
                    .origin
                    .unwrap_or_else(|| Geometry::centred_origin(grid, cell_size)),
                rotation: rotation.to_radians(),
                line_length: self.line_length,
                line_width: self.line_width,
                line_z: self.line_z,
                marker_z: self.marker_z,
            }
            .turned_about_centre(grid),
            floor: self.floor_size.map_or(FloorSize::Auto, FloorSize::Fixed),
        };
        spec.check().map_err(usage)?;
        Ok(spec)
    }
}

/// Segments written between two updates of the bar.
const BAR_STEP: usize = 1 << 16;

/// Runs `generate`: the segments are written as they are computed, never held as a list.
pub fn run(args: GenerateArgs, progress: Progress) -> Result<ExitCode> {
    let drawn = args.seed.is_none();
    // Check every option before drawing a seed, so a refused run prints nothing else.
    let grid = args.layout.maze.spec(0)?.grid;
    let seed = args.seed.unwrap_or_else(os_seed);
    // Options are checked; what is left to refuse depends on them too (start and end).
    let spinner = progress.spinner(format!("generating a {grid} maze"));
    let planned = args.plan(seed);
    spinner.finish_and_clear();
    let planned = planned?;
    let layout = &planned.head;
    if layout.start.cell == layout.end.cell {
        eprintln!(
            "note: start and end are the same cell ({},{}); allowed, the robot is already there",
            layout.start.cell[0], layout.start.cell[1]
        );
    }
    let count = planned.segment_count();
    let bar = progress.bar("writing the layout", count as u64, Unit::Items("segments"));
    let segments = planned.segments().enumerate().map(|(i, pose)| {
        if i % BAR_STEP == 0 {
            bar.set_position(i as u64);
        }
        pose
    });
    let written = write_output(args.output.as_deref(), |w| {
        write_layout_parts(layout, segments, w)
    });
    bar.finish_and_clear();
    written?;
    if drawn {
        eprintln!(
            "seed {seed} (drawn from the OS; recorded in the layout; pass --seed {seed} to make this maze again)"
        );
    }
    let floor = FloorNote::of(&args.layout, seed, layout);
    if let Some(path) = &args.output {
        eprintln!(
            "wrote {}: {}, solution {} cells{}",
            super::escape::escaped(&path.display().to_string()),
            super::validate::describe(layout, count),
            layout.metrics.solution_cells,
            floor
                .as_ref()
                .map_or(String::new(), |f| format!("; {}", f.size))
        );
    } else if let Some(f) = &floor {
        eprintln!("note: {}", f.size);
    }
    if let Some(hint) = floor.and_then(|f| f.hint) {
        eprintln!("  hint: {hint}");
    }
    Ok(ExitCode::SUCCESS)
}

/// What `generate` says of a floor that is not the course's (10 m x 10 m), where the size
/// is decided rather than at `apply`: the size, and for a larger floor what draws it.
struct FloorNote {
    /// `floor 35 m x 35 m, larger than the course's 10 m x 10 m`.
    size: String,
    /// `--resize-floor`, and a smaller `--cell-size` where one fits the course's floor.
    hint: Option<String>,
}

impl FloorNote {
    /// The note for `layout`, made from `args` and `seed`; `None` on the course's floor.
    fn of(args: &LayoutArgs, seed: u64, layout: &Layout) -> Option<FloorNote> {
        let [x, y] = layout.floor.size;
        let course = course::FLOOR_SIZE;
        if x == course && y == course {
            return None;
        }
        let shown = format!("{} m x {} m", limits::show(x), limits::show(y));
        let larger = x > course || y > course;
        if !larger {
            return Some(FloorNote {
                size: format!("floor {shown}"),
                hint: None,
            });
        }
        let resize = format!(
            "the course scene's floor is {course} m x {course} m: draw it with `apply --resize-floor` (clear puts the floor back)"
        );
        let hint = match fitting_cell_size(args, seed) {
            Some(cell) => format!(
                "{resize}, or generate it with --cell-size {} to fit that floor",
                limits::show(cell)
            ),
            None => resize,
        };
        Some(FloorNote {
            size: format!("floor {shown}, larger than the course's {course} m x {course} m"),
            hint: Some(hint),
        })
    }
}

/// The largest cell side, in whole centimetres, at which the maze `args` describe fits the
/// course's floor, the other options as given (the line template must still fit a cell);
/// `None` where none does (a preset's cells, a fixed floor, a line template longer than such
/// a cell, an origin that keeps the maze off that floor).
fn fitting_cell_size(args: &LayoutArgs, seed: u64) -> Option<f64> {
    if args.style.preset.is_some() || args.maze.floor_size.is_some() {
        return None;
    }
    let spec = args.maze.spec(seed).ok()?;
    let need = crate::layout::build::extent_needed(&spec.geometry.grid_corners(spec.grid));
    let need = need[0].max(need[1]);
    let cell = (spec.geometry.cell_size * course::FLOOR_SIZE / need * 100.0).floor() / 100.0;
    if cell <= 0.0 {
        return None;
    }
    let mut smaller = args.clone();
    smaller.maze.cell_size = cell;
    let planned = smaller.plan(seed).ok()?;
    let fits = planned
        .head
        .floor
        .size
        .iter()
        .all(|&s| s <= course::FLOOR_SIZE);
    fits.then_some(cell)
}
