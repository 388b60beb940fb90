//! Wall style: a `Wall` cuboid copy on every closed side between cells and on the outer
//! boundary, except the openings asked for.
//!
//! The sides lie on the lattice lines between cell centres, in the maze frame: lattice
//! line `j` along x at `y = (j - 1/2) * cell` (`j = 0..=rows`, south of row `j`), lattice
//! line `i` along y at `x = (i - 1/2) * cell` (`i = 0..=columns`, west of column `i`).
//! Side `k` of a line spans one cell. A closed side takes `n = ceil(cell / length)` copies
//! spread evenly from one lattice corner to the next, so walls meet end to end along a
//! line and overlap at corners: no gap a robot could pass.

use std::f64::consts::PI;
use std::fmt;
use std::str::FromStr;

use nalgebra::Point2;

use super::build::{extent_needed, fits_within};
use super::geometry::{Geometry, course, rectangle_corners, round_um};
use super::limits::{self, Naming, Range, Violation, show};
use super::{Layout, Opening, Pose, Side, Style, WallSpec};
use crate::maze::{Cell, Grid, Maze};

/// The course defaults for walls: 1 m long (one cell side), 5 cm thick, 20 cm high.
pub mod defaults {
    /// `Wall` template length, metres.
    pub const LENGTH: f64 = 1.0;
    /// `Wall` template thickness, metres.
    pub const THICKNESS: f64 = 0.05;
    /// `Wall` template height, metres.
    pub const HEIGHT: f64 = 0.2;
}

/// Wall height: 1 mm to 100 m (walls stand on the floor; taller is not a maze).
pub const HEIGHT: Range = Range {
    min: limits::MIN_LENGTH,
    max: 100.0,
    unit: "m",
};

/// Which ends of the maze get a gap in the outer boundary (`--openings`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Openings {
    /// A gap beside the start cell.
    pub start: bool,
    /// A gap beside the end cell.
    pub end: bool,
}

/// The accepted words, for help and error texts.
pub const OPENINGS_HELP: &str = "'none', 'start', 'end' or 'start,end'";

impl FromStr for Openings {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, String> {
        let mut openings = Openings::default();
        if s.trim() == "none" {
            return Ok(openings);
        }
        for word in s.split(',') {
            match word.trim() {
                "start" => openings.start = true,
                "end" => openings.end = true,
                _ => return Err(format!("'{s}' is not {OPENINGS_HELP}")),
            }
        }
        Ok(openings)
    }
}

impl fmt::Display for Openings {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match (self.start, self.end) {
            (false, false) => "none",
            (true, false) => "start",
            (false, true) => "end",
            (true, true) => "start,end",
        })
    }
}

/// What `--style walls` asks for.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WallOptions {
    /// `Wall` length, metres.
    pub length: f64,
    /// `Wall` thickness, metres.
    pub thickness: f64,
    /// `Wall` height, metres.
    pub height: f64,
    /// Gaps beside the start and end.
    pub openings: Openings,
}

impl Default for WallOptions {
    fn default() -> Self {
        Self {
            length: defaults::LENGTH,
            thickness: defaults::THICKNESS,
            height: defaults::HEIGHT,
            openings: Openings::default(),
        }
    }
}

/// Which way a lattice line runs, in the maze frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum WallAxis {
    /// Along x: the line between two rows.
    AlongX,
    /// Along y: the line between two columns.
    AlongY,
}

/// Checks the wall template against `cell_size`: each number in range, the thickness
/// less than the cell (thicker walls close the passages), the length at most the cell
/// (a longer copy reaches into the next side, which may be open) and at least
/// cell / [`limits::MAX_SEGMENTS_PER_PASSAGE`].
pub fn check_template(
    cell_size: f64,
    length: f64,
    thickness: f64,
    height: f64,
    naming: Naming,
) -> Vec<Violation> {
    let (l, t, h) = match naming {
        Naming::Options => ("--wall-length", "--wall-thickness", "--wall-height"),
        Naming::Layout => ("wall.length", "wall.thickness", "wall.height"),
    };
    let mut out: Vec<Violation> = [
        limits::check_range(l, length, limits::LENGTH),
        limits::check_range(t, thickness, limits::LENGTH),
        limits::check_range(h, height, HEIGHT),
    ]
    .into_iter()
    .flatten()
    .collect();
    if !out.is_empty() || !limits::LENGTH.contains(cell_size) {
        return out;
    }
    let mut add = |name: &str, message: String| {
        out.push(Violation {
            name: name.to_string(),
            message,
        })
    };
    if thickness >= cell_size {
        add(
            t,
            format!(
                "{} m is not less than the cell size {} m: the walls would close the passages",
                show(thickness),
                show(cell_size)
            ),
        );
    }
    if length > cell_size + limits::ROUNDING * 2.0 {
        add(
            l,
            format!(
                "{} m is longer than the cell size {} m: a wall would reach into the next side, which may be open",
                show(length),
                show(cell_size)
            ),
        );
    }
    let shortest = cell_size / limits::MAX_SEGMENTS_PER_PASSAGE as f64;
    if length < shortest - limits::ROUNDING * 2.0 {
        add(
            l,
            format!(
                "{} m is shorter than cell / {} = {} m: a side may take at most {} copies",
                show(length),
                limits::MAX_SEGMENTS_PER_PASSAGE,
                show(shortest),
                limits::MAX_SEGMENTS_PER_PASSAGE
            ),
        );
    }
    out
}

/// Copies of `Wall` per closed side: `ceil(cell / length)`, at least 1.
pub fn copies_per_side(cell_size: f64, length: f64) -> usize {
    // the epsilon keeps an exact fit (1.0 / 1.0) from rounding up to one more
    (((cell_size / length) - 1e-9).ceil() as usize).max(1)
}

/// Offsets of the copies' centres along a side, from its first lattice corner: spread
/// evenly so they cover the side from corner to corner.
pub fn copy_offsets(cell_size: f64, length: f64) -> Vec<f64> {
    let n = copies_per_side(cell_size, length);
    if n == 1 {
        return vec![cell_size / 2.0];
    }
    let (first, last) = (length / 2.0, cell_size - length / 2.0);
    let step = (last - first) / (n - 1) as f64;
    (0..n).map(|k| first + step * k as f64).collect()
}

/// Lattice lines of `axis` on `grid` and the sides on each: (lines, sides per line).
pub fn lattice(grid: Grid, axis: WallAxis) -> (u32, u32) {
    match axis {
        WallAxis::AlongX => (grid.height() + 1, grid.width()),
        WallAxis::AlongY => (grid.width() + 1, grid.height()),
    }
}

/// The two cells side `k` of lattice line `line` lies between (`None` beyond the grid),
/// south/west one first.
pub fn cells_beside(grid: Grid, axis: WallAxis, line: u32, k: u32) -> (Option<Cell>, Option<Cell>) {
    let (count, _) = lattice(grid, axis);
    let cell = |across: u32| match axis {
        WallAxis::AlongX => Cell::new(k, across),
        WallAxis::AlongY => Cell::new(across, k),
    };
    (
        (line > 0).then(|| cell(line - 1)),
        (line + 1 < count).then(|| cell(line)),
    )
}

/// The boundary side of `cell` that `opening` names, as (axis, line, k); `None` if the side
/// does not face out of the grid.
pub fn opening_side(grid: Grid, opening: &Opening) -> Option<(WallAxis, u32, u32)> {
    let cell = Cell::new(opening.cell[0], opening.cell[1]);
    if !grid.contains(cell) {
        return None;
    }
    match opening.side {
        Side::South if cell.y == 0 => Some((WallAxis::AlongX, 0, cell.x)),
        Side::North if cell.y + 1 == grid.height() => {
            Some((WallAxis::AlongX, grid.height(), cell.x))
        }
        Side::West if cell.x == 0 => Some((WallAxis::AlongY, 0, cell.y)),
        Side::East if cell.x + 1 == grid.width() => Some((WallAxis::AlongY, grid.width(), cell.y)),
        _ => None,
    }
}

/// `true` if side `k` of lattice line `line` is closed: between two cells without a
/// passage, or on the boundary and not one of `openings`.
pub fn is_closed(maze: &Maze, openings: &[Opening], axis: WallAxis, line: u32, k: u32) -> bool {
    let grid = maze.grid();
    match cells_beside(grid, axis, line, k) {
        (Some(a), Some(_)) => {
            let dir = match axis {
                WallAxis::AlongX => crate::maze::Direction::North,
                WallAxis::AlongY => crate::maze::Direction::East,
            };
            !maze.is_open(grid.index(a), dir)
        }
        _ => !openings
            .iter()
            .any(|o| opening_side(grid, o) == Some((axis, line, k))),
    }
}

/// The first outer side of `cell` in the order south, west, north, east.
fn outer_side(grid: Grid, cell: Cell) -> Option<Side> {
    [Side::South, Side::West, Side::North, Side::East]
        .into_iter()
        .find(|&side| {
            opening_side(
                grid,
                &Opening {
                    cell: [cell.x, cell.y],
                    side,
                },
            )
            .is_some()
        })
}

/// The openings `openings` asks for beside `start` and `end`, or why one is impossible.
pub fn resolve_openings(
    grid: Grid,
    openings: Openings,
    start: Cell,
    end: Cell,
) -> Result<Vec<Opening>, String> {
    let mut out: Vec<Opening> = Vec::new();
    for (wanted, which, cell) in [(openings.start, "start", start), (openings.end, "end", end)] {
        if !wanted {
            continue;
        }
        let side = outer_side(grid, cell).ok_or_else(|| {
            format!(
                "--openings {openings}: the {which} cell {cell} is not on the edge of the {grid} grid, so no gap can lead to it; choose --{which} on the edge or leave {which} out of --openings"
            )
        })?;
        let opening = Opening {
            cell: [cell.x, cell.y],
            side,
        };
        if !out.contains(&opening) {
            out.push(opening);
        }
    }
    Ok(out)
}

/// Floor poses of the walls of `maze`: lattice lines along x (south to north, each west
/// to east), then along y (west to east, each south to north).
pub fn wall_poses(maze: &Maze, geometry: &Geometry, spec: &WallSpec) -> Vec<Pose> {
    let grid = maze.grid();
    let iso = geometry.maze_to_floor();
    let c = geometry.cell_size;
    let offsets = copy_offsets(c, spec.length);
    let z = round_um(spec.height / 2.0);
    let mut poses = Vec::new();
    for axis in [WallAxis::AlongX, WallAxis::AlongY] {
        let (lines, sides) = lattice(grid, axis);
        for line in 0..lines {
            for k in 0..sides {
                if !is_closed(maze, &spec.openings, axis, line, k) {
                    continue;
                }
                let across = (f64::from(line) - 0.5) * c;
                let from = (f64::from(k) - 0.5) * c;
                for &t in &offsets {
                    let (local, yaw) = match axis {
                        WallAxis::AlongX => (Point2::new(from + t, across), 0.0),
                        WallAxis::AlongY => (Point2::new(across, from + t), PI / 2.0),
                    };
                    let p = iso * local;
                    poses.push(Pose::rounded(p.x, p.y, z, yaw + geometry.rotation));
                }
            }
        }
    }
    poses
}

/// The floor-frame corners of the rectangle the walls cover: the grid plus half a wall
/// thickness all round.
pub fn wall_extent_corners(grid: Grid, geometry: &Geometry, thickness: f64) -> [Point2<f64>; 4] {
    let m = geometry.cell_size / 2.0 + thickness / 2.0;
    let max_x = f64::from(grid.width() - 1) * geometry.cell_size + m;
    let max_y = f64::from(grid.height() - 1) * geometry.cell_size + m;
    let iso = geometry.maze_to_floor();
    [
        iso * Point2::new(-m, -m),
        iso * Point2::new(max_x, -m),
        iso * Point2::new(max_x, max_y),
        iso * Point2::new(-m, max_y),
    ]
}

/// `true` if the footprint of a wall at `pose` lies on a floor of `size` (centred on the
/// floor origin), within `tolerance`.
pub fn on_floor(pose: &Pose, spec: &WallSpec, size: [f64; 2], tolerance: f64) -> bool {
    let corners = rectangle_corners(pose, spec.length, spec.thickness);
    fits_within(extent_needed(&corners), size, tolerance)
}

/// Turns the line layout of `maze` into a wall layout: the wall template and openings in
/// `wall`, one pose per wall in `walls`, no line segments. The floor grows in whole
/// panels when `auto_floor` and the boundary walls reach past it; otherwise a floor they
/// reach past is refused.
pub fn into_walls(
    layout: &mut Layout,
    maze: &Maze,
    options: &WallOptions,
    auto_floor: bool,
) -> Result<(), String> {
    let start = Cell::new(layout.start.cell[0], layout.start.cell[1]);
    let end = Cell::new(layout.end.cell[0], layout.end.cell[1]);
    let openings = resolve_openings(maze.grid(), options.openings, start, end)?;
    into_walls_with(layout, maze, options, openings, auto_floor)
}

/// [`into_walls`] with the outer sides to leave open given one by one (`options.openings`
/// is not used): each must face out of the grid.
pub fn into_walls_with(
    layout: &mut Layout,
    maze: &Maze,
    options: &WallOptions,
    openings: Vec<Opening>,
    auto_floor: bool,
) -> Result<(), String> {
    let grid = maze.grid();
    if let Some(o) = openings.iter().find(|o| opening_side(grid, o).is_none()) {
        return Err(format!(
            "the {} side of cell ({},{}) is not on the outer boundary of the {grid} grid",
            o.side.name(),
            o.cell[0],
            o.cell[1]
        ));
    }
    let geometry = Geometry {
        cell_size: layout.grid.cell_size,
        origin: layout.grid.origin,
        rotation: layout.grid.rotation,
        line_length: layout.line.length,
        line_width: layout.line.width,
        line_z: layout.line.z,
        marker_z: layout.start.pose.z,
    };
    if let Some(v) = check_template(
        geometry.cell_size,
        options.length,
        options.thickness,
        options.height,
        Naming::Options,
    )
    .into_iter()
    .next()
    {
        return Err(v.to_string());
    }
    let per_side = copies_per_side(geometry.cell_size, round_um(options.length)) as u64;
    let sides = u64::from(grid.width()) * (u64::from(grid.height()) + 1)
        + u64::from(grid.height()) * (u64::from(grid.width()) + 1);
    if sides * per_side > limits::MAX_SEGMENTS {
        return Err(format!(
            "a {grid} maze with {per_side} wall copies a side could need {} walls, more than the {} a layout may hold: use a smaller --size or a longer --wall-length",
            sides * per_side,
            limits::MAX_SEGMENTS
        ));
    }
    let spec = WallSpec {
        length: round_um(options.length),
        thickness: round_um(options.thickness),
        height: round_um(options.height),
        openings,
    };
    let need = extent_needed(&wall_extent_corners(grid, &geometry, spec.thickness));
    let tolerance = limits::floor_tolerance(&geometry, grid);
    if !fits_within(need, layout.floor.size, tolerance) {
        if !auto_floor {
            return Err(format!(
                "the walls need a floor of {:.3} m x {:.3} m (centred on the floor origin) but --floor-size is {} m x {} m",
                need[0],
                need[1],
                show(layout.floor.size[0]),
                show(layout.floor.size[1])
            ));
        }
        let size = need.map(|n| {
            let panels = ((n - tolerance) / course::FLOOR_PANEL - 1e-9).ceil();
            (panels * course::FLOOR_PANEL).max(course::FLOOR_SIZE)
        });
        if size.iter().any(|&s| s > limits::MAX_FLOOR) {
            return Err(format!(
                "the walls need a floor of {:.3} m x {:.3} m, more than the largest floor, {} m x {} m",
                need[0],
                need[1],
                limits::MAX_FLOOR,
                limits::MAX_FLOOR
            ));
        }
        layout.floor.size = size;
    }
    layout.walls = wall_poses(maze, &geometry, &spec);
    layout.style = Style::Walls;
    layout.wall = Some(spec);
    layout.segments.clear();
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::Algorithm;
    use crate::layout::{GenerateSpec, build_layout, passages};

    fn walled(openings: Openings) -> (Layout, Maze) {
        let spec = GenerateSpec::course(Grid::new(3, 2).unwrap(), Algorithm::Dfs, 1);
        let mut layout = build_layout(&spec).unwrap();
        let maze = passages::decode(Grid::new(3, 2).unwrap(), &layout.passages).unwrap();
        let options = WallOptions {
            openings,
            ..WallOptions::default()
        };
        into_walls(&mut layout, &maze, &options, true).unwrap();
        (layout, maze)
    }

    #[test]
    fn a_perfect_maze_has_one_wall_per_closed_side() {
        let (layout, maze) = walled(Openings::default());
        // sides: 3*3 along x + 4*2 along y = 17; passages of a perfect 6-cell maze: 5
        assert_eq!(maze.passage_count(), 5);
        assert_eq!(layout.walls.len(), 17 - 5);
        assert!(layout.segments.is_empty());
        assert_eq!(layout.style, Style::Walls);
        assert!(layout.walls.iter().all(|w| w.z == 0.1));
        // the south boundary of cell (0,0) (course origin: cell (0,0) at (-1, 0))
        assert_eq!(layout.walls[0], Pose::rounded(-1.0, -0.5, 0.1, 0.0));
    }

    #[test]
    fn openings_leave_gaps_beside_the_ends() {
        let (layout, _) = walled("start,end".parse().unwrap());
        let spec = layout.wall.as_ref().unwrap();
        assert_eq!(spec.openings.len(), 2);
        assert_eq!(spec.openings[0].side, Side::South);
        assert_eq!(layout.walls.len(), 17 - 5 - 2);
        let grid = Grid::new(5, 5).unwrap();
        let err = resolve_openings(
            grid,
            "end".parse().unwrap(),
            Cell::new(0, 0),
            Cell::new(2, 2),
        )
        .unwrap_err();
        assert!(
            err.contains("the end cell (2,2) is not on the edge"),
            "{err}"
        );
    }

    #[test]
    fn options_parse_and_copies_spread() {
        assert_eq!("none".parse::<Openings>().unwrap(), Openings::default());
        assert!("start,exit".parse::<Openings>().is_err());
        assert_eq!(copies_per_side(1.0, 1.0), 1);
        assert_eq!(copy_offsets(1.0, 0.4), vec![0.2, 0.5, 0.8]);
        let v = check_template(0.18, 0.2, 0.012, 0.05, Naming::Options);
        assert!(
            v[0].to_string()
                .starts_with("--wall-length 0.2 m is longer"),
            "{v:?}"
        );
        let v = check_template(0.18, 0.18, 0.2, 0.05, Naming::Layout);
        assert!(v[0].to_string().starts_with("wall.thickness"), "{v:?}");
    }
}
