//! From a maze and the generate options to a complete layout.

use std::collections::BTreeMap;

use nalgebra::Point2;

use super::endpoints::{EndpointSpec, resolve};
use super::geometry::{Geometry, course, round_um};
use super::{
    Endpoint, FORMAT, FloorSpec, GeneratorInfo, GridSpec, Layout, LineSpec, VERSION, passages,
};
use crate::generate::{Algorithm, generate_braided};
use crate::maze::{Cell, Grid, Maze, Metrics};

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

/// Generates the maze `spec` describes and lays it out.
pub fn build_layout(spec: &GenerateSpec) -> Result<Layout, String> {
    let maze = generate_braided(spec.grid, spec.algorithm, spec.seed, spec.braid);
    layout_maze(&maze, spec)
}

/// Lays out an already generated `maze` as `spec` says.
pub fn layout_maze(maze: &Maze, spec: &GenerateSpec) -> Result<Layout, String> {
    let geometry = &spec.geometry;
    let grid = maze.grid();
    let (start, end) = resolve(maze, spec.start, spec.end)?;
    let metrics = Metrics::measure(maze, grid.index(start), grid.index(end))
        .ok_or_else(|| format!("end {end} cannot be reached from start {start}"))?;
    let floor = floor_for(grid, geometry, spec.floor)?;
    let offsets = geometry.segment_offsets();
    let segments = maze
        .passages()
        .flat_map(|(cell, dir)| geometry.passage_segments(cell, dir, &offsets))
        .collect();
    Ok(Layout {
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
            cell_size: round_um(geometry.cell_size),
            origin: geometry.origin.map(round_um),
            rotation: round_um(geometry.rotation),
        },
        floor: FloorSpec { size: floor },
        line: LineSpec {
            length: round_um(geometry.line_length),
            width: round_um(geometry.line_width),
            z: round_um(geometry.line_z),
        },
        start: endpoint(geometry, start),
        end: endpoint(geometry, end),
        metrics,
        passage_encoding: passages::ENCODING.to_string(),
        passages: passages::encode(maze),
        segments,
    })
}

/// The generator options a layout records: only those that change the maze.
fn options(spec: &GenerateSpec) -> BTreeMap<String, String> {
    let mut options = BTreeMap::new();
    if spec.braid > 0.0 {
        options.insert("braid".to_string(), spec.braid.to_string());
    }
    options
}

fn endpoint(geometry: &Geometry, cell: Cell) -> Endpoint {
    Endpoint {
        cell: [cell.x, cell.y],
        pose: geometry.marker_pose(cell),
    }
}

/// The floor size for `grid`: checked when fixed, grown in panels when automatic.
fn floor_for(grid: Grid, geometry: &Geometry, floor: FloorSize) -> Result<[f64; 2], String> {
    let need = extent_needed(&geometry.grid_corners(grid));
    match floor {
        FloorSize::Fixed(size) if fits(need, size) => Ok(size.map(round_um)),
        FloorSize::Fixed(size) => Err(format!(
            "the maze needs a floor of {:.3} m x {:.3} m (centred on the floor origin) but --floor-size is {} m x {} m",
            need[0], need[1], size[0], size[1]
        )),
        FloorSize::Auto => Ok(need.map(|n| {
            let panels = (n / course::FLOOR_PANEL - 1e-9).ceil() * course::FLOOR_PANEL;
            panels.max(course::FLOOR_SIZE)
        })),
    }
}

/// The size (x, y) of the floor, centred on the floor origin, that holds all `points`.
pub fn extent_needed(points: &[Point2<f64>]) -> [f64; 2] {
    let half = |f: fn(&Point2<f64>) -> f64| points.iter().map(|p| f(p).abs()).fold(0.0, f64::max);
    [2.0 * half(|p| p.x), 2.0 * half(|p| p.y)]
}

/// `true` if an extent fits a floor size (micrometre tolerance).
pub fn fits(need: [f64; 2], size: [f64; 2]) -> bool {
    need[0] <= size[0] + 2e-6 && need[1] <= size[1] + 2e-6
}

#[cfg(test)]
mod tests {
    use super::*;

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
        assert!(err.contains("--floor-size is 10 m x 10 m"), "{err}");
    }
}
