//! Checking a layout: is it well formed, solvable, a tree (or honest about its loops),
//! drawn gap-free, and on the floor? Every problem found is reported, each naming what
//! and where.

mod coverage;
mod goal;
mod walls;

use std::fmt;

use nalgebra::Point2;

use crate::generate::Algorithm;
use crate::layout::build::{extent_needed, fits_within};
use crate::layout::geometry::{Geometry, rectangle_corners};
use crate::layout::limits::{self, Naming, show};
use crate::layout::micromouse::Preset;
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
    check_generator(layout, &mut problems);
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
        if layout.style.is_lines() {
            coverage::check(layout, maze, &geometry, &mut problems);
        }
        walls::check_walls(layout, maze, &geometry, &mut problems);
        goal::check_goal(layout, maze, &mut problems);
    }
    check_floor(layout, grid, &geometry, &mut problems);
    Report {
        problems: problems.0,
        metrics,
    }
}

/// The generator section names a known algorithm with options it takes.
fn check_generator(layout: &Layout, problems: &mut Problems) {
    let generator = &layout.generator;
    let pairs = generator
        .options
        .iter()
        .map(|(k, v)| (k.as_str(), v.as_str()));
    let imported = generator.algorithm == crate::layout::import::ALGORITHM;
    if let Err(e) = Algorithm::from_name_and_pairs(&generator.algorithm, pairs)
        && !imported
    {
        problems.add("generator", e);
    }
    for (key, value) in &generator.options {
        match key.as_str() {
            "preset" if Preset::from_name(value).is_none() => problems.add(
                "generator.options.preset",
                format!("'{value}' is not a preset: micromouse or micromouse-half"),
            ),
            "source" if !imported => problems.add(
                "generator.options.source",
                "only an imported layout (generator.algorithm \"import\") names a source file",
            ),
            "growing" | "bias" | "preset" | "source" => {}
            "braid" => {
                if !value
                    .parse::<f64>()
                    .is_ok_and(|v| limits::BRAID.contains(v))
                {
                    problems.add(
                        "generator.options.braid",
                        format!("'{value}' is not a share from 0 to 1"),
                    );
                }
            }
            _ => problems.add(
                format!("generator.options.{key}"),
                "is not an option vrep-maze knows",
            ),
        }
    }
}

/// Every number in the range [`limits`] documents (the same `generate` checks its
/// options against); the geometry they make, unless one it depends on is out of range.
/// Heights and poses are checked too but do not stop the rest of the validation.
fn check_numbers(layout: &Layout, problems: &mut Problems) -> Option<Geometry> {
    let geometry = Geometry {
        cell_size: layout.grid.cell_size,
        origin: layout.grid.origin,
        rotation: layout.grid.rotation,
        line_length: layout.line.length,
        line_width: layout.line.width,
        line_z: layout.line.z,
        marker_z: layout.start.pose.z,
    };
    let mut blocking = false;
    for v in limits::check_template(&geometry, Naming::Layout) {
        // Heights do not change where anything lies; keep checking the rest.
        blocking |= v.name != "line.z" && v.name != "start.pose.z";
        problems.add(v.name, v.message);
    }
    for v in limits::check_placement(&geometry, Naming::Layout)
        .into_iter()
        .chain(limits::check_floor(layout.floor.size, Naming::Layout))
    {
        blocking = true;
        problems.add(v.name, v.message);
    }
    if let Some(v) = limits::check_range("end.pose.z", layout.end.pose.z, limits::HEIGHT) {
        problems.add(v.name, v.message);
    } else if limits::HEIGHT.contains(layout.line.z) && layout.end.pose.z <= layout.line.z {
        problems.add(
            "end.pose.z",
            format!(
                "{} m is not above line.z {} m: the markers must lie on top of the lines",
                show(layout.end.pose.z),
                show(layout.line.z)
            ),
        );
    }
    for (which, pose) in [("start", &layout.start.pose), ("end", &layout.end.pose)] {
        for (field, value) in [("x", pose.x), ("y", pose.y)] {
            if !value.is_finite() {
                blocking = true;
                problems.add(
                    format!("{which}.pose.{field}"),
                    format!("must be a finite number, not {}", show(value)),
                );
            }
        }
        if let Some(v) = limits::check_range(&format!("{which}.pose.yaw"), pose.yaw, limits::YAW) {
            problems.add(v.name, v.message);
        }
    }
    for (index, pose) in layout.segments.iter().enumerate() {
        if ![pose.x, pose.y, pose.z, pose.yaw]
            .iter()
            .all(|v| v.is_finite())
        {
            blocking = true;
            problems.add(
                format!("segments[{index}]"),
                "has a coordinate that is not a finite number",
            );
            continue;
        }
        if let Some(v) =
            limits::check_range(&format!("segments[{index}].yaw"), pose.yaw, limits::YAW)
        {
            problems.add(v.name, v.message);
        }
        if !limits::HEIGHT.contains(layout.line.z) {
            // line.z itself is reported; judge the segment by the range alone.
            if let Some(v) =
                limits::check_range(&format!("segments[{index}].z"), pose.z, limits::HEIGHT)
            {
                problems.add(v.name, v.message);
            }
        } else if (pose.z - layout.line.z).abs() > 2.0 * limits::ROUNDING {
            problems.add(
                format!("segments[{index}].z"),
                format!(
                    "{} m is not line.z {} m: every segment lies at the height of the lines",
                    show(pose.z),
                    show(layout.line.z)
                ),
            );
        }
    }
    (!blocking).then_some(geometry)
}

/// The endpoint's cell is on the grid and its marker sits on the cell centre: compared
/// in the maze frame, within what the writer's rounding can move it
/// ([`limits::marker_tolerance`]).
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
    let centre = geometry.local_centre(cell);
    let local = geometry.maze_to_floor().inverse() * Point2::new(pose.x, pose.y);
    let off = (local - centre).norm();
    if off > limits::marker_tolerance(centre.coords.norm()) {
        let floor = geometry.cell_centre(cell);
        problems.add(
            format!("{which}.pose"),
            format!(
                "marker at ({}, {}) is not on the centre ({:.6}, {:.6}) of cell {cell}: {} m off",
                pose.x,
                pose.y,
                floor.x,
                floor.y,
                show(off)
            ),
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

/// The maze and every segment lie on the declared floor, within what the writer's
/// rounding can move them ([`limits::floor_tolerance`]).
fn check_floor(layout: &Layout, grid: Grid, geometry: &Geometry, problems: &mut Problems) {
    let size = layout.floor.size;
    let tolerance = limits::floor_tolerance(geometry, grid);
    let need = extent_needed(&geometry.grid_corners(grid));
    if !fits_within(need, size, tolerance) {
        problems.add(
            "floor.size",
            format!(
                "the maze needs {:.3} m x {:.3} m but the floor is {} m x {} m",
                need[0],
                need[1],
                show(size[0]),
                show(size[1])
            ),
        );
    }
    for (index, pose) in layout.segments.iter().enumerate() {
        let corners = rectangle_corners(pose, layout.line.length, layout.line.width);
        if !fits_within(extent_needed(&corners), size, tolerance) {
            problems.add(
                format!("segments[{index}]"),
                format!(
                    "at ({}, {}) reaches off the {} m x {} m floor",
                    pose.x,
                    pose.y,
                    show(size[0]),
                    show(size[1])
                ),
            );
        }
    }
}

/// The most problems an error shows: the first ones say what is wrong, and a broken layout
/// can have millions.
pub const MAX_SHOWN: usize = 20;

/// A layout that failed [`validate`]. Every consumer of layouts (drawing, rendering, writing
/// a dataset) passes [`checked`] first and refuses with this, so nothing is ever drawn,
/// rendered or written from a layout that `vrep-maze validate` rejects.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("invalid layout ({} problem(s); `vrep-maze validate` lists them)", .problems.len())]
pub struct Invalid {
    /// Everything wrong, in the order [`validate`] found it.
    pub problems: Vec<Problem>,
}

impl Invalid {
    /// The first [`MAX_SHOWN`] problems, one per line, then how many more there are.
    pub fn shown(&self) -> Vec<String> {
        let mut lines: Vec<String> = self
            .problems
            .iter()
            .take(MAX_SHOWN)
            .map(Problem::to_string)
            .collect();
        if self.problems.len() > MAX_SHOWN {
            lines.push(format!(
                "... and {} more problem(s)",
                self.problems.len() - MAX_SHOWN
            ));
        }
        lines
    }
}

/// The one gate every consumer of a layout passes: `Ok` when [`validate`] finds nothing.
pub fn checked(layout: &Layout) -> Result<(), Invalid> {
    let report = validate(layout);
    if report.is_ok() {
        Ok(())
    } else {
        Err(Invalid {
            problems: report.problems,
        })
    }
}
