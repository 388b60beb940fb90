//! From a maze and the generate options to a complete layout.

use std::collections::BTreeMap;

use nalgebra::Point2;

use super::endpoints::{self, EndpointSpec, resolve};
use super::geometry::{Geometry, course, round_um};
use super::limits::{self, Name, Naming};
use super::{
    Endpoint, FORMAT, FloorSpec, GeneratorInfo, GridSpec, Layout, LineSpec, Pose, VERSION, passages,
};
use crate::generate::{Algorithm, generate_braided};
use crate::maze::{Cell, Grid, Maze, Metrics};
use crate::wording::{Message, Opt, Value};

/// The floor a maze is placed on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum FloorSize {
    /// The course floor (10 m x 10 m), grown in whole 5 m panels until the maze fits.
    Auto,
    /// This size (x, y) in metres; the maze must fit.
    Fixed([f64; 2]),
}

/// Everything `generate` needs to make a layout.
#[derive(Debug, Clone, PartialEq)]
pub struct GenerateSpec {
    /// The grid.
    pub grid: Grid,
    /// The algorithm.
    pub algorithm: Algorithm,
    /// The seed.
    pub seed: u64,
    /// Share of dead ends to braid away (0 keeps the maze perfect).
    pub braid: f64,
    /// How to pick the start cell.
    pub start: EndpointSpec,
    /// How to pick the end cell.
    pub end: EndpointSpec,
    /// Where things go on the floor.
    pub geometry: Geometry,
    /// The floor.
    pub floor: FloorSize,
}

impl GenerateSpec {
    /// The course defaults on `grid`: start in the south-west corner, end farthest away.
    pub fn course(grid: Grid, algorithm: Algorithm, seed: u64) -> Self {
        Self {
            grid,
            algorithm,
            seed,
            braid: 0.0,
            start: EndpointSpec::Corner(super::endpoints::Corner::SouthWest),
            end: EndpointSpec::Farthest,
            geometry: Geometry::course(grid),
            floor: FloorSize::Auto,
        }
    }
}

impl GenerateSpec {
    /// Checks every number and option against [`limits`] before anything is allocated:
    /// the braid share, the line template against the cell, the rotation, the size of the
    /// maze against the largest floor, the origin, the floor, the start and end, the
    /// number of segments, and that the maze fits the floor. The error is one line naming
    /// the option, the value and the range.
    pub fn check(&self) -> Result<(), Message> {
        self.check_on(self.grid).map(|_| ())
    }

    /// [`GenerateSpec::check`] on `grid`; the geometry as the layout will store it.
    fn check_on(&self, grid: Grid) -> Result<Geometry, Message> {
        if let Some(v) = limits::check_braid(self.braid) {
            return Err(v.line());
        }
        first(limits::check_template(&self.geometry, Naming::Options))?;
        let placement = limits::check_placement(&self.geometry, Naming::Options);
        first(
            placement
                .iter()
                .filter(|v| v.name == Name::Opt(Opt::Rotation))
                .cloned(),
        )?;
        let geometry = self.geometry.rounded();
        check_span(grid, &geometry)?;
        first(placement)?;
        if let FloorSize::Fixed(size) = self.floor {
            first(limits::check_floor(size, Naming::Options))?;
        }
        endpoints::check(grid, self.start, self.end)?;
        let per_passage = geometry.segments_per_passage();
        let bound = limits::segments_bound(grid, self.braid > 0.0, per_passage);
        if bound > limits::MAX_SEGMENTS {
            return Err(Message::text(format!(
                "a {grid} maze with {per_passage} line copies a passage could need {bound} segments, more than the {} a layout may hold: use a smaller ",
                limits::MAX_SEGMENTS
            ))
            .and_opt(Opt::Size)
            .and(" or a longer ")
            .and_opt(Opt::LineLength));
        }
        floor_for(grid, &geometry, self.floor)?;
        Ok(geometry)
    }
}

/// The first violation, as an error.
fn first(violations: impl IntoIterator<Item = limits::Violation>) -> Result<(), Message> {
    match violations.into_iter().next() {
        Some(v) => Err(v.line()),
        None => Ok(()),
    }
}

/// The maze itself (cells times cell size, turned by the rotation) fits the largest
/// floor; checked before the origin, which by default centres the maze.
fn check_span(grid: Grid, geometry: &Geometry) -> Result<(), Message> {
    let (w, h) = (
        f64::from(grid.width()) * geometry.cell_size,
        f64::from(grid.height()) * geometry.cell_size,
    );
    let (cos, sin) = (geometry.rotation.cos().abs(), geometry.rotation.sin().abs());
    let span = [cos * w + sin * h, sin * w + cos * h];
    let tolerance = limits::floor_tolerance(geometry, grid);
    if span.iter().any(|&s| s > limits::MAX_FLOOR + tolerance) {
        return Err(Message::text(format!("the {grid} maze with "))
            .and_setting(
                Opt::CellSize,
                Value::number(limits::show(geometry.cell_size)),
            )
            .and(format!(
                " spans {:.3} m x {:.3} m on the floor: more than the largest floor, {} m x {} m",
                span[0],
                span[1],
                limits::MAX_FLOOR,
                limits::MAX_FLOOR
            )));
    }
    Ok(())
}

/// Generates the maze `spec` describes and lays it out; every option is checked first
/// ([`GenerateSpec::check`]), so a refused spec allocates nothing.
pub fn build_layout(spec: &GenerateSpec) -> Result<Layout, Message> {
    plan_layout(spec).map(Planned::into_layout)
}

/// [`build_layout`] without computing the segments: they come from the maze when asked,
/// so a big layout can be written without its segment list in memory.
pub fn plan_layout(spec: &GenerateSpec) -> Result<Planned, Message> {
    spec.check()?;
    let maze = generate_braided(spec.grid, spec.algorithm, spec.seed, spec.braid);
    plan_maze(maze, spec)
}

/// A layout whose segments are computed from its maze when asked.
#[derive(Debug, Clone)]
pub struct Planned {
    /// Everything but the segments (left empty).
    pub head: Layout,
    maze: Maze,
    geometry: Geometry,
    offsets: Vec<f64>,
}

impl Planned {
    /// How many segments the layout has.
    pub fn segment_count(&self) -> usize {
        self.maze.passage_count() * self.offsets.len()
    }

    /// The segments, in layout order: passage by passage, each passage's copies in turn.
    pub fn segments(&self) -> impl Iterator<Item = Pose> + '_ {
        let placer = self.geometry.passage_placer(&self.offsets);
        self.maze
            .passages()
            .flat_map(move |(cell, dir)| placer.segments(cell, dir))
    }

    /// This layout drawn with walls instead of lines: `draw` turns the head into a wall
    /// layout (see [`walls::into_walls`](super::walls::into_walls)) for the maze; no
    /// segments are left to compute.
    pub fn with_walls(
        mut self,
        draw: impl FnOnce(&mut Layout, &Maze) -> Result<(), Message>,
    ) -> Result<Planned, Message> {
        draw(&mut self.head, &self.maze)?;
        self.offsets.clear();
        Ok(self)
    }

    /// The whole layout, segments and all.
    pub fn into_layout(self) -> Layout {
        let segments = self.segments().collect();
        Layout {
            segments,
            ..self.head
        }
    }
}

/// Lays out an already generated `maze` as `spec` says. Everything is computed from the
/// geometry as the layout stores it (micrometres, microradians), so `validate` finds
/// what was drawn.
pub fn plan_maze(maze: Maze, spec: &GenerateSpec) -> Result<Planned, Message> {
    let grid = maze.grid();
    let geometry = spec.check_on(grid)?;
    let (start, end, from_start) = resolve(&maze, spec.start, spec.end)?;
    let metrics = Metrics::measure_from(&maze, &from_start, grid.index(end))
        .ok_or_else(|| format!("end {end} cannot be reached from start {start}"))?;
    let floor = floor_for(grid, &geometry, spec.floor)?;
    let head = Layout {
        format: FORMAT.to_string(),
        version: VERSION,
        generator: GeneratorInfo {
            crate_version: env!("CARGO_PKG_VERSION").to_string(),
            algorithm: spec.algorithm.name().to_string(),
            seed: spec.seed,
            options: options(spec),
        },
        grid: GridSpec {
            columns: grid.width(),
            rows: grid.height(),
            cell_size: geometry.cell_size,
            origin: geometry.origin,
            rotation: geometry.rotation,
        },
        floor: FloorSpec { size: floor },
        line: LineSpec {
            length: geometry.line_length,
            width: geometry.line_width,
            z: geometry.line_z,
        },
        start: endpoint(&geometry, start),
        end: endpoint(&geometry, end),
        metrics,
        passage_encoding: passages::ENCODING.to_string(),
        passages: passages::encode(&maze),
        segments: Vec::new(),
        style: super::Style::Lines,
        wall: None,
        walls: Vec::new(),
        post: None,
        posts: Vec::new(),
    };
    let offsets = geometry.segment_offsets();
    Ok(Planned {
        head,
        maze,
        geometry,
        offsets,
    })
}

/// The generator options a layout records: only those that change the maze.
fn options(spec: &GenerateSpec) -> BTreeMap<String, String> {
    let mut options: BTreeMap<String, String> = spec
        .algorithm
        .option_pairs()
        .into_iter()
        .map(|(name, value)| (name.to_string(), value))
        .collect();
    if spec.braid > 0.0 {
        options.insert("braid".to_string(), spec.braid.to_string());
    }
    options
}

fn endpoint(geometry: &Geometry, cell: Cell) -> Endpoint {
    Endpoint {
        cell: [cell.x, cell.y],
        pose: geometry.marker_pose(cell),
        region: Vec::new(),
    }
}

/// The floor size for `grid`: checked when fixed, grown in panels when automatic, never
/// beyond the largest floor. The tolerance covers the writer's rounding
/// ([`limits::floor_tolerance`]), so rounding never makes a maze miss its floor.
fn floor_for(grid: Grid, geometry: &Geometry, floor: FloorSize) -> Result<[f64; 2], Message> {
    let need = extent_needed(&geometry.grid_corners(grid));
    let tolerance = limits::floor_tolerance(geometry, grid);
    match floor {
        FloorSize::Fixed(size) if fits_within(need, size, tolerance) => Ok(size.map(round_um)),
        FloorSize::Fixed(size) => Err(Message::text(format!(
            "the maze needs a floor of {:.3} m x {:.3} m (centred on the floor origin) but ",
            need[0], need[1],
        ))
        .and_opt(Opt::FloorSize)
        .and(format!(
            " is {} m x {} m",
            limits::show(size[0]),
            limits::show(size[1])
        ))),
        FloorSize::Auto => {
            let size = need.map(|n| {
                let panels = ((n - tolerance) / course::FLOOR_PANEL - 1e-9).ceil();
                (panels * course::FLOOR_PANEL).max(course::FLOOR_SIZE)
            });
            if size.iter().any(|&s| s > limits::MAX_FLOOR) {
                return Err(Message::text(format!(
                    "the maze needs a floor of {:.3} m x {:.3} m (centred on the floor origin), more than the largest floor, {} m x {} m: move ",
                    need[0],
                    need[1],
                    limits::MAX_FLOOR,
                    limits::MAX_FLOOR
                ))
                .and_opt(Opt::Origin)
                .and(" towards 0,0"));
            }
            Ok(size)
        }
    }
}

/// The size (x, y) of the floor, centred on the floor origin, that holds all `points`.
pub fn extent_needed(points: &[Point2<f64>]) -> [f64; 2] {
    let half = |f: fn(&Point2<f64>) -> f64| points.iter().map(|p| f(p).abs()).fold(0.0, f64::max);
    [2.0 * half(|p| p.x), 2.0 * half(|p| p.y)]
}

/// `true` if an extent fits a floor size (micrometre tolerance).
pub fn fits(need: [f64; 2], size: [f64; 2]) -> bool {
    fits_within(need, size, 2e-6)
}

/// `true` if an extent fits a floor size, `tolerance` metres to spare on each axis.
pub fn fits_within(need: [f64; 2], size: [f64; 2], tolerance: f64) -> bool {
    need[0] <= size[0] + tolerance && need[1] <= size[1] + tolerance
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::wording::testing::dashed;

    #[test]
    fn course_layout_matches_the_handout() {
        let spec = GenerateSpec::course(Grid::new(9, 9).unwrap(), Algorithm::Dfs, 42);
        let layout = build_layout(&spec).unwrap();
        assert_eq!(layout.floor.size, [10.0, 10.0]);
        assert_eq!(layout.segments.len(), 2 * 80);
        assert_eq!(layout.start.cell, [0, 0]);
        assert_eq!((layout.start.pose.x, layout.start.pose.y), (-4.0, -4.0));
        assert_eq!(layout.start.pose.z, 0.002);
        assert_eq!(layout.metrics.loops, 0);
        assert!(layout.segments.iter().all(|s| s.z == 0.001));
    }

    #[test]
    fn braided_layouts_declare_their_loops() {
        let mut spec = GenerateSpec::course(Grid::new(12, 12).unwrap(), Algorithm::Prim, 5);
        spec.braid = 0.5;
        let layout = build_layout(&spec).unwrap();
        assert!(layout.metrics.loops > 0);
        assert_eq!(
            layout.generator.options.get("braid").map(String::as_str),
            Some("0.5")
        );
        assert!(crate::validate::validate(&layout).is_ok());
    }

    #[test]
    fn floors_grow_in_panels_or_refuse() {
        let grid = Grid::new(20, 15).unwrap();
        let mut spec = GenerateSpec::course(grid, Algorithm::Prim, 1);
        assert_eq!(build_layout(&spec).unwrap().floor.size, [25.0, 15.0]);
        spec.floor = FloorSize::Fixed([10.0, 10.0]);
        let err = build_layout(&spec).unwrap_err();
        let err = dashed(&err);
        assert!(err.contains("--floor-size is 10 m x 10 m"), "{err}");
    }
}
