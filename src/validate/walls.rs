//! Wall checks: the style's fields are consistent, the wall template fits the cell, every
//! closed side is covered gap-free by walls, no wall stands in an open passage or an
//! opening, no wall is drawn twice, and every wall stands on the floor.
//!
//! As for lines, work happens in the maze frame, one lattice line at a time: each wall is
//! an interval along the line between two rows or two columns of cells.

use std::collections::BTreeMap;

use nalgebra::Point2;

use super::Problems;
use crate::layout::geometry::{Geometry, normalize_angle};
use crate::layout::limits::{self, Naming, show};
use crate::layout::walls::{
    WallAxis, cells_beside, check_template, is_closed, lattice, on_floor, opening_side,
};
use crate::layout::{Layout, Style, WallSpec};
use crate::maze::Maze;

/// Position tolerance in the maze frame (as for line segments).
const TOLERANCE: f64 = limits::SEGMENT_TOLERANCE;
/// Heading tolerance, radians.
const YAW_TOLERANCE: f64 = 1e-4;

/// Runs every wall check on `layout`, whose passages are `maze`; a line layout only has
/// to carry no wall fields. (That a wall layout has no segments is checked as they stream
/// past, by the validator.)
pub(super) fn check_walls(
    layout: &Layout,
    maze: &Maze,
    geometry: &Geometry,
    problems: &mut Problems,
) {
    let spec = match (layout.style, &layout.wall) {
        (Style::Lines, None) => {
            if !layout.walls.is_empty() {
                problems.add("walls", "only a layout with style \"walls\" has walls");
            }
            return;
        }
        (Style::Lines, Some(_)) => {
            problems.add(
                "wall",
                "only a layout with style \"walls\" has a wall template",
            );
            return;
        }
        (Style::Walls, None) => {
            problems.add(
                "wall",
                "missing: a layout with style \"walls\" needs its wall template",
            );
            return;
        }
        (Style::Walls, Some(spec)) => spec,
    };
    let template = check_template(
        geometry.cell_size,
        spec.length,
        spec.thickness,
        spec.height,
        Naming::Layout,
    );
    let bad_template = !template.is_empty();
    for v in template {
        problems.add(v.name, v.message);
    }
    let grid = maze.grid();
    for (index, opening) in spec.openings.iter().enumerate() {
        if opening_side(grid, opening).is_none() {
            problems.add(
                format!("wall.openings[{index}]"),
                format!(
                    "the {} side of cell ({},{}) is not on the outer boundary of the {grid} grid",
                    opening.side.name(),
                    opening.cell[0],
                    opening.cell[1]
                ),
            );
        }
        if spec.openings[..index].contains(opening) {
            problems.add(
                format!("wall.openings[{index}]"),
                "duplicates an earlier opening",
            );
        }
    }
    if bad_template {
        return;
    }
    let lines = place_walls(layout, spec, maze, geometry, problems);
    let c = geometry.cell_size;
    for axis in [WallAxis::AlongX, WallAxis::AlongY] {
        let (count, sides) = lattice(grid, axis);
        for line in 0..count {
            let closed: Vec<(u32, (f64, f64))> = (0..sides)
                .filter(|&k| is_closed(maze, &spec.openings, axis, line, k))
                .map(|k| {
                    let from = (f64::from(k) - 0.5) * c;
                    (k, (from, from + c))
                })
                .collect();
            let spans = lines.get(&(axis, line)).map(Vec::as_slice).unwrap_or(&[]);
            check_line(layout, maze, axis, line, &closed, spans, c, problems);
        }
    }
    let tolerance = limits::floor_tolerance(geometry, grid);
    for (index, pose) in layout.walls.iter().enumerate() {
        if !on_floor(pose, spec, layout.floor.size, tolerance) {
            problems.add(
                format!("walls[{index}]"),
                format!(
                    "at ({}, {}) reaches off the {} m x {} m floor",
                    pose.x,
                    pose.y,
                    show(layout.floor.size[0]),
                    show(layout.floor.size[1])
                ),
            );
        }
    }
}

/// A stretch `lo..hi` along one lattice line, and the wall that covers it.
#[derive(Debug, Clone, Copy)]
struct Span {
    lo: f64,
    hi: f64,
    wall: usize,
}

/// Puts every wall on its lattice line, reporting those that fit none or stand wrong.
fn place_walls(
    layout: &Layout,
    spec: &WallSpec,
    maze: &Maze,
    geometry: &Geometry,
    problems: &mut Problems,
) -> BTreeMap<(WallAxis, u32), Vec<Span>> {
    let grid = maze.grid();
    let to_maze = geometry.maze_to_floor().inverse();
    let c = geometry.cell_size;
    let z = spec.height / 2.0;
    let mut lines: BTreeMap<(WallAxis, u32), Vec<Span>> = BTreeMap::new();
    for (index, pose) in layout.walls.iter().enumerate() {
        let location = format!("walls[{index}]");
        if ![pose.x, pose.y, pose.z, pose.yaw]
            .iter()
            .all(|v| v.is_finite())
        {
            problems.add(location, "has a coordinate that is not a finite number");
            continue;
        }
        if let Some(v) = limits::check_range(&format!("{location}.yaw"), pose.yaw, limits::YAW) {
            problems.add(v.name, v.message);
        }
        if (pose.z - z).abs() > 2.0 * limits::ROUNDING {
            problems.add(
                format!("{location}.z"),
                format!(
                    "{} m is not half of wall.height {} m: every wall stands on the floor",
                    show(pose.z),
                    show(spec.height)
                ),
            );
        }
        let local = to_maze * Point2::new(pose.x, pose.y);
        let yaw = normalize_angle(pose.yaw - geometry.rotation);
        let axis = if yaw.sin().abs() < YAW_TOLERANCE {
            WallAxis::AlongX
        } else if yaw.cos().abs() < YAW_TOLERANCE {
            WallAxis::AlongY
        } else {
            problems.add(
                location,
                format!(
                    "at ({}, {}) has yaw {} rad: it runs along neither maze axis",
                    pose.x, pose.y, pose.yaw
                ),
            );
            continue;
        };
        let (across, along) = match axis {
            WallAxis::AlongX => (local.y, local.x),
            WallAxis::AlongY => (local.x, local.y),
        };
        let line = (across / c + 0.5).round();
        let (count, _) = lattice(grid, axis);
        if (across - (line - 0.5) * c).abs() > TOLERANCE {
            problems.add(
                location,
                format!(
                    "at ({}, {}) does not stand on a cell side: it lies inside a row or column of cells",
                    pose.x, pose.y
                ),
            );
            continue;
        }
        if line < 0.0 || line >= f64::from(count) {
            problems.add(
                location,
                format!("at ({}, {}) lies off the grid", pose.x, pose.y),
            );
            continue;
        }
        lines.entry((axis, line as u32)).or_default().push(Span {
            lo: along - spec.length / 2.0,
            hi: along + spec.length / 2.0,
            wall: index,
        });
    }
    lines
}

/// Checks one lattice line: `closed` holds (side index, interval to cover) per closed side.
#[allow(clippy::too_many_arguments)]
fn check_line(
    layout: &Layout,
    maze: &Maze,
    axis: WallAxis,
    line: u32,
    closed: &[(u32, (f64, f64))],
    spans: &[Span],
    c: f64,
    problems: &mut Problems,
) {
    let grid = maze.grid();
    let allowed = merge(closed.iter().map(|&(_, iv)| iv));
    let mut sorted = spans.to_vec();
    sorted.sort_by(|a, b| a.lo.total_cmp(&b.lo).then(a.wall.cmp(&b.wall)));
    for pair in sorted.windows(2) {
        if (pair[0].lo - pair[1].lo).abs() < TOLERANCE
            && (pair[0].hi - pair[1].hi).abs() < TOLERANCE
        {
            problems.add(
                format!("walls[{}]", pair[1].wall),
                format!(
                    "duplicates walls[{}]: the same wall stands twice",
                    pair[0].wall
                ),
            );
        }
    }
    let (_, sides) = lattice(grid, axis);
    for span in &sorted {
        let inside = allowed
            .iter()
            .any(|&(lo, hi)| span.lo >= lo - TOLERANCE && span.hi <= hi + TOLERANCE);
        if inside {
            continue;
        }
        let pose = &layout.walls[span.wall];
        let stray = first_uncovered(span.lo, span.hi, &allowed);
        let k = (stray / c + 0.5).floor();
        let message = if k < 0.0 || k >= f64::from(sides) {
            format!(
                "at ({}, {}) sticks out past the edge of the grid",
                pose.x, pose.y
            )
        } else {
            match cells_beside(grid, axis, line, k as u32) {
                (Some(a), Some(b)) => format!(
                    "at ({}, {}) stands in the open passage between cells {a} and {b}",
                    pose.x, pose.y
                ),
                (Some(cell), None) | (None, Some(cell)) => format!(
                    "at ({}, {}) stands in the opening of the outer boundary beside cell {cell}",
                    pose.x, pose.y
                ),
                (None, None) => unreachable!("a lattice side has a cell on one side at least"),
            }
        };
        problems.add(format!("walls[{}]", span.wall), message);
    }
    let drawn = merge(sorted.iter().map(|s| (s.lo, s.hi)));
    for &(k, (lo, hi)) in closed {
        let covered = drawn
            .iter()
            .any(|&(a, b)| a <= lo + TOLERANCE && b >= hi - TOLERANCE);
        if covered {
            continue;
        }
        let gap = first_uncovered(lo, hi, &drawn);
        let what = match cells_beside(grid, axis, line, k) {
            (Some(a), Some(b)) => format!("the side between cells {a} and {b}"),
            (Some(cell), None) | (None, Some(cell)) => format!("the outer side of cell {cell}"),
            (None, None) => unreachable!("a lattice side has a cell on one side at least"),
        };
        problems.add(
            format!("walls ({what})"),
            format!(
                "is closed but not covered gap-free by walls: nothing stands {:.3} m from its {} end",
                gap - lo,
                match axis {
                    WallAxis::AlongX => "west",
                    WallAxis::AlongY => "south",
                }
            ),
        );
    }
}

/// Sorted, merged union of intervals (touching or overlapping within tolerance).
fn merge(intervals: impl Iterator<Item = (f64, f64)>) -> Vec<(f64, f64)> {
    let mut all: Vec<(f64, f64)> = intervals.collect();
    all.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut merged: Vec<(f64, f64)> = Vec::with_capacity(all.len());
    for (lo, hi) in all {
        match merged.last_mut() {
            Some(last) if lo <= last.1 + TOLERANCE => last.1 = last.1.max(hi),
            _ => merged.push((lo, hi)),
        }
    }
    merged
}

/// The first point of `lo..hi` that `cover` (merged, sorted) does not contain.
fn first_uncovered(lo: f64, hi: f64, cover: &[(f64, f64)]) -> f64 {
    let mut point = lo;
    for &(a, b) in cover {
        if a > point + TOLERANCE {
            break;
        }
        if b > point {
            point = b;
        }
    }
    point.min(hi)
}

#[cfg(test)]
mod tests {
    use crate::generate::Algorithm;
    use crate::layout::walls::{WallOptions, into_walls};
    use crate::layout::{GenerateSpec, Layout, build_layout, passages};
    use crate::maze::Grid;
    use crate::validate::validate;

    fn wall_layout() -> Layout {
        let grid = Grid::new(4, 3).unwrap();
        let mut layout = build_layout(&GenerateSpec::course(grid, Algorithm::Prim, 9)).unwrap();
        let maze = passages::decode(grid, &layout.passages).unwrap();
        into_walls(&mut layout, &maze, &WallOptions::default(), true).unwrap();
        layout
    }

    fn problems(layout: &Layout) -> Vec<String> {
        validate(layout)
            .problems
            .iter()
            .map(|p| p.to_string())
            .collect()
    }

    #[test]
    fn a_generated_wall_layout_is_valid() {
        let layout = wall_layout();
        assert_eq!(problems(&layout), Vec::<String>::new());
    }

    #[test]
    fn a_missing_wall_is_a_gap() {
        let mut layout = wall_layout();
        layout.walls.remove(3);
        let found = problems(&layout);
        assert_eq!(found.len(), 1, "{found:?}");
        assert!(
            found[0].contains("is closed but not covered gap-free by walls"),
            "{found:?}"
        );
    }

    #[test]
    fn a_wall_over_a_passage_and_a_duplicate_are_named() {
        let mut layout = wall_layout();
        let first = layout.walls[0];
        layout.walls.push(first);
        let found = problems(&layout);
        assert!(
            found
                .iter()
                .any(|p| p.starts_with("walls[") && p.contains("duplicates walls[0]")),
            "{found:?}"
        );
        let mut layout = wall_layout();
        // a wall on the first open side between rows 0 and 1
        let maze = passages::decode(Grid::new(4, 3).unwrap(), &layout.passages).unwrap();
        let x = (0..4)
            .find(|&x| maze.is_open(x, crate::maze::Direction::North))
            .unwrap();
        let mut stray = layout.walls[0];
        stray.x = layout.grid.origin[0] + x as f64;
        stray.y = layout.grid.origin[1] + 0.5;
        layout.walls.push(stray);
        let found = problems(&layout);
        assert!(
            found
                .iter()
                .any(|p| p.contains("stands in the open passage between cells")),
            "{found:?}"
        );
    }

    #[test]
    fn style_fields_must_agree() {
        let mut layout = wall_layout();
        layout.segments.push(layout.start.pose);
        assert!(
            problems(&layout)
                .iter()
                .any(|p| p.starts_with("segments: has 1 line segment"))
        );
        let mut layout = wall_layout();
        layout.style = crate::layout::Style::Lines;
        assert!(
            problems(&layout)
                .iter()
                .any(|p| p.starts_with("wall: only a layout"))
        );
    }
}
