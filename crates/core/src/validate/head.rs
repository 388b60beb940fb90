//! Checks of everything in a layout but its segments: the generator, the numbers and the
//! geometry they make, the endpoints, the maze's structure and route, the floor.

use nalgebra::Point2;

use super::Problems;
use crate::generate::Algorithm;
use crate::layout::build::{extent_needed, fits_within};
use crate::layout::geometry::Geometry;
use crate::layout::limits::{self, Naming, show};
use crate::layout::micromouse::Preset;
use crate::layout::{Layout, Pose};
use crate::maze::analysis::{UNREACHED, component_count, distances_from};
use crate::maze::{Cell, Grid, Maze, Metrics};

/// The generator section names a known algorithm with options it takes.
pub(super) fn check_generator(layout: &Layout, problems: &mut Problems) {
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
/// Heights and poses are checked too but do not stop the rest of the validation. The
/// segments' own numbers are [`super::segment`]'s.
pub(super) fn check_numbers(layout: &Layout, problems: &mut Problems) -> Option<Geometry> {
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
        blocking |= v.name != "line.z".into() && v.name != "start.pose.z".into();
        problems.violation(&v);
    }
    for v in limits::check_placement(&geometry, Naming::Layout)
        .into_iter()
        .chain(limits::check_floor(layout.floor.size, Naming::Layout))
    {
        blocking = true;
        problems.violation(&v);
    }
    if let Some(v) = limits::check_range("end.pose.z", layout.end.pose.z, limits::HEIGHT) {
        problems.violation(&v);
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
        if let Some(v) = limits::check_range(format!("{which}.pose.yaw"), pose.yaw, limits::YAW) {
            problems.violation(&v);
        }
    }
    (!blocking).then_some(geometry)
}

/// The endpoint's cell is on the grid and its marker sits on the cell centre: compared
/// in the maze frame, within what the writer's rounding can move it
/// ([`limits::marker_tolerance`]).
pub(super) fn check_endpoint(
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
pub(super) fn check_structure(declared: &Metrics, maze: &Maze, problems: &mut Problems) {
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
    if loops as u64 != declared.loops {
        let message = if declared.loops == 0 {
            format!(
                "the passages form {loops} loop(s) but the layout declares a perfect maze (metrics.loops = 0)"
            )
        } else {
            format!(
                "the passages form {loops} loop(s) but metrics.loops declares {}",
                declared.loops
            )
        };
        problems.add("passages", message);
    }
}

/// A path from start to end exists; the stored metrics match the maze.
pub(super) fn check_route(
    declared: &Metrics,
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

/// The maze lies on the declared floor, within what the writer's rounding can move it
/// ([`limits::floor_tolerance`]); each segment is checked as it arrives
/// ([`super::segment`]).
pub(super) fn check_floor(
    layout: &Layout,
    grid: Grid,
    geometry: &Geometry,
    problems: &mut Problems,
) {
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
}
