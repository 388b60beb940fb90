//! Checking a layout: is it well formed, solvable, a tree (or honest about its loops),
//! drawn gap-free, and on the floor? Every problem found is reported, each naming what
//! and where.

mod coverage;

use std::fmt;

use crate::layout::build::{extent_needed, fits};
use crate::layout::geometry::{Geometry, rectangle_corners};
use crate::layout::{Layout, Pose, passages};
use crate::maze::analysis::{UNREACHED, component_count, distances_from};
use crate::maze::{Cell, Grid, Maze, Metrics};

/// One thing wrong with a layout.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Problem {
    /// The field or object concerned, e.g. `segments[12]` or `end`.
    pub location: String,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.location, self.message)
    }
}

/// The outcome of validating a layout.
#[derive(Debug, Clone, PartialEq)]
pub struct Report {
    /// Everything wrong; empty when the layout is valid.
    pub problems: Vec<Problem>,
    /// The metrics measured on the passages (when start and end could be measured).
    pub metrics: Option<Metrics>,
}

impl Report {
    /// `true` if nothing is wrong.
    pub fn is_ok(&self) -> bool {
        self.problems.is_empty()
    }
}

/// Collects problems as validation goes.
#[derive(Default)]
struct Problems(Vec<Problem>);

impl Problems {
    fn add(&mut self, location: impl Into<String>, message: impl Into<String>) {
        self.0.push(Problem {
            location: location.into(),
            message: message.into(),
        });
    }
}

/// Validates `layout` and measures it.
pub fn validate(layout: &Layout) -> Report {
    let mut problems = Problems::default();
    let Some(geometry) = check_numbers(layout, &mut problems) else {
        return Report {
            problems: problems.0,
            metrics: None,
        };
    };
    let grid = match Grid::new(layout.grid.columns.into(), layout.grid.rows.into()) {
        Ok(grid) => grid,
        Err(e) => {
            problems.add("grid", e.to_string());
            return Report {
                problems: problems.0,
                metrics: None,
            };
        }
    };
    if let Err(e) = passages::check_encoding(&layout.passage_encoding) {
        problems.add("passage_encoding", e);
    }
    let maze = match passages::decode(grid, &layout.passages) {
        Ok(maze) => Some(maze),
        Err(e) => {
            problems.add("passages", e);
            None
        }
    };
    let start = check_endpoint(
        &layout.start.cell,
        &layout.start.pose,
        "start",
        grid,
        &geometry,
        &mut problems,
    );
    let end = check_endpoint(
        &layout.end.cell,
        &layout.end.pose,
        "end",
        grid,
        &geometry,
        &mut problems,
    );
    let mut metrics = None;
    if let Some(maze) = &maze {
        check_structure(layout, maze, &mut problems);
        if let (Some(start), Some(end)) = (start, end) {
            metrics = check_route(layout, maze, start, end, &mut problems);
        }
        coverage::check(layout, maze, &geometry, &mut problems);
    }
    check_floor(layout, grid, &geometry, &mut problems);
    Report {
        problems: problems.0,
        metrics,
    }
}

/// Every length positive and finite, every coordinate finite; the geometry they make.
fn check_numbers(layout: &Layout, problems: &mut Problems) -> Option<Geometry> {
    let before = problems.0.len();
    let positive = [
        ("grid.cell_size", layout.grid.cell_size),
        ("line.length", layout.line.length),
        ("line.width", layout.line.width),
        ("floor.size[0]", layout.floor.size[0]),
        ("floor.size[1]", layout.floor.size[1]),
    ];
    for (field, value) in positive {
        if !(value.is_finite() && value > 0.0) {
            problems.add(
                field,
                format!("must be a positive number of metres, not {value}"),
            );
        }
    }
    let finite = [
        ("grid.origin[0]", layout.grid.origin[0]),
        ("grid.origin[1]", layout.grid.origin[1]),
        ("grid.rotation", layout.grid.rotation),
        ("line.z", layout.line.z),
    ];
    for (field, value) in finite {
        if !value.is_finite() {
            problems.add(field, format!("must be a finite number, not {value}"));
        }
    }
    for (index, pose) in layout.segments.iter().enumerate() {
        if ![pose.x, pose.y, pose.z, pose.yaw]
            .iter()
            .all(|v| v.is_finite())
        {
            problems.add(
                format!("segments[{index}]"),
                "has a coordinate that is not a finite number",
            );
        }
    }
    if problems.0.len() > before {
        return None;
    }
    Some(Geometry {
        cell_size: layout.grid.cell_size,
        origin: layout.grid.origin,
        rotation: layout.grid.rotation,
        line_length: layout.line.length,
        line_width: layout.line.width,
        line_z: layout.line.z,
        marker_z: layout.start.pose.z,
    })
}

/// The endpoint's cell is on the grid and its marker sits on the cell centre.
fn check_endpoint(
    cell: &[u32; 2],
    pose: &Pose,
    which: &str,
    grid: Grid,
    geometry: &Geometry,
    problems: &mut Problems,
) -> Option<usize> {
    let cell = Cell::new(cell[0], cell[1]);
    if !grid.contains(cell) {
        problems.add(
            format!("{which}.cell"),
            format!("{cell} is off the {grid} grid"),
        );
        return None;
    }
    let centre = geometry.cell_centre(cell);
    if (centre.x - pose.x).abs() > 2e-6 || (centre.y - pose.y).abs() > 2e-6 {
        problems.add(
            format!("{which}.pose"),
            format!(
                "marker at ({}, {}) is not on the centre ({:.6}, {:.6}) of cell {cell}",
                pose.x, pose.y, centre.x, centre.y
            ),
        );
    }
    if !pose.z.is_finite() || pose.z < 0.0 {
        problems.add(
            format!("{which}.pose.z"),
            format!("must be a height >= 0, not {}", pose.z),
        );
    }
    Some(grid.index(cell))
}

/// Connected, and a tree unless the layout declares its loops.
fn check_structure(layout: &Layout, maze: &Maze, problems: &mut Problems) {
    let grid = maze.grid();
    let components = component_count(maze);
    if components > 1 {
        let reached = distances_from(maze, 0)
            .iter()
            .filter(|&&d| d != UNREACHED)
            .count();
        problems.add(
            "passages",
            format!(
                "the maze falls apart into {components} pieces: {} of {} cells cannot be reached from cell (0,0)",
                grid.cell_count() - reached,
                grid.cell_count()
            ),
        );
    }
    let loops = maze.passage_count() + components - grid.cell_count();
    if loops as u64 != layout.metrics.loops {
        let message = if layout.metrics.loops == 0 {
            format!(
                "the passages form {loops} loop(s) but the layout declares a perfect maze (metrics.loops = 0)"
            )
        } else {
            format!(
                "the passages form {loops} loop(s) but metrics.loops declares {}",
                layout.metrics.loops
            )
        };
        problems.add("passages", message);
    }
}

/// A path from start to end exists; the stored metrics match the maze.
fn check_route(
    layout: &Layout,
    maze: &Maze,
    start: usize,
    end: usize,
    problems: &mut Problems,
) -> Option<Metrics> {
    let grid = maze.grid();
    let Some(measured) = Metrics::measure(maze, start, end) else {
        problems.add(
            "end",
            format!(
                "end {} cannot be reached from start {}",
                grid.cell(end),
                grid.cell(start)
            ),
        );
        return None;
    };
    let declared = &layout.metrics;
    let pairs = [
        ("cells", declared.cells, measured.cells),
        ("passages", declared.passages, measured.passages),
        (
            "solution_cells",
            declared.solution_cells,
            measured.solution_cells,
        ),
        (
            "solution_turns",
            declared.solution_turns,
            measured.solution_turns,
        ),
        (
            "decision_points",
            declared.decision_points,
            measured.decision_points,
        ),
        ("dead_ends", declared.dead_ends, measured.dead_ends),
        ("junctions", declared.junctions, measured.junctions),
        ("straights", declared.straights, measured.straights),
        (
            "diameter_cells",
            declared.diameter_cells,
            measured.diameter_cells,
        ),
    ];
    for (field, said, is) in pairs {
        if said != is {
            problems.add(
                format!("metrics.{field}"),
                format!("says {said} but the maze has {is}"),
            );
        }
    }
    Some(measured)
}

/// Every segment and both markers lie on the declared floor.
fn check_floor(layout: &Layout, grid: Grid, geometry: &Geometry, problems: &mut Problems) {
    let size = layout.floor.size;
    let need = extent_needed(&geometry.grid_corners(grid));
    if !fits(need, size) {
        problems.add(
            "floor.size",
            format!(
                "the maze needs {:.3} m x {:.3} m but the floor is {} m x {} m",
                need[0], need[1], size[0], size[1]
            ),
        );
    }
    for (index, pose) in layout.segments.iter().enumerate() {
        let corners = rectangle_corners(pose, layout.line.length, layout.line.width);
        if !fits(extent_needed(&corners), size) {
            problems.add(
                format!("segments[{index}]"),
                format!(
                    "at ({}, {}) reaches off the {} m x {} m floor",
                    pose.x, pose.y, size[0], size[1]
                ),
            );
        }
    }
}
