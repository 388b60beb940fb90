//! Segment checks: every passage is covered without gaps, no segment lies off a passage
//! (over a wall, between rows, off the grid), and no segment is drawn twice.
//!
//! Work happens in the maze frame, where every segment lies on a row (along x) or a
//! column (along y), so each check is one-dimensional: intervals along one grid line.

use std::collections::BTreeMap;

use nalgebra::Point2;

use super::Problems;
use crate::layout::Layout;
use crate::layout::geometry::{Geometry, normalize_angle};
use crate::layout::limits;
use crate::maze::{Cell, Direction, Maze};

/// Position tolerance in the maze frame: see [`limits::SEGMENT_TOLERANCE`].
const TOLERANCE: f64 = limits::SEGMENT_TOLERANCE;
/// Heading tolerance, radians.
const YAW_TOLERANCE: f64 = 1e-4;

/// Which way a grid line runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Axis {
    /// A row: along the maze's x.
    Row,
    /// A column: along the maze's y.
    Column,
}

/// A stretch `lo..hi` along one grid line, and the segment that draws it.
#[derive(Debug, Clone, Copy)]
struct Span {
    lo: f64,
    hi: f64,
    segment: usize,
}

/// Runs every segment check on `layout`, whose passages are `maze`.
pub(super) fn check(layout: &Layout, maze: &Maze, geometry: &Geometry, problems: &mut Problems) {
    let lines = place_segments(layout, maze, geometry, problems);
    let grid = maze.grid();
    let c = geometry.cell_size;
    let half_width = geometry.line_width / 2.0;
    for (axis, count, length) in [
        (Axis::Row, grid.height(), grid.width()),
        (Axis::Column, grid.width(), grid.height()),
    ] {
        for line in 0..count {
            let open: Vec<(u32, (f64, f64))> = (0..length.saturating_sub(1))
                .filter(|&k| maze.is_open(grid.index(cell_on(axis, line, k)), forward(axis)))
                .map(|k| {
                    let k_f = f64::from(k);
                    (k, (k_f * c - half_width, (k_f + 1.0) * c + half_width))
                })
                .collect();
            let spans = lines.get(&(axis, line)).map(Vec::as_slice).unwrap_or(&[]);
            check_line(axis, line, &open, spans, layout, c, problems);
        }
    }
}

/// Puts every segment on its grid line, reporting those that fit no line.
fn place_segments(
    layout: &Layout,
    maze: &Maze,
    geometry: &Geometry,
    problems: &mut Problems,
) -> BTreeMap<(Axis, u32), Vec<Span>> {
    let grid = maze.grid();
    let to_maze = geometry.maze_to_floor().inverse();
    let c = geometry.cell_size;
    let half_length = layout.line.length / 2.0;
    let mut lines: BTreeMap<(Axis, u32), Vec<Span>> = BTreeMap::new();
    for (index, pose) in layout.segments.iter().enumerate() {
        let location = format!("segments[{index}]");
        let local = to_maze * Point2::new(pose.x, pose.y);
        let yaw = normalize_angle(pose.yaw - geometry.rotation);
        let axis = if yaw.sin().abs() < YAW_TOLERANCE {
            Axis::Row
        } else if yaw.cos().abs() < YAW_TOLERANCE {
            Axis::Column
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
        let (across, along, count, noun) = match axis {
            Axis::Row => (local.y, local.x, grid.height(), "row"),
            Axis::Column => (local.x, local.y, grid.width(), "column"),
        };
        let line = (across / c).round();
        if (across - line * c).abs() > TOLERANCE {
            problems.add(
                location,
                format!(
                    "at ({}, {}) lies between two {noun}s of cell centres",
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
            lo: along - half_length,
            hi: along + half_length,
            segment: index,
        });
    }
    lines
}

/// Checks one grid line: `open` holds (passage index, interval to cover) per passage.
fn check_line(
    axis: Axis,
    line: u32,
    open: &[(u32, (f64, f64))],
    spans: &[Span],
    layout: &Layout,
    c: f64,
    problems: &mut Problems,
) {
    let allowed = merge(open.iter().map(|&(_, iv)| iv));
    let mut sorted = spans.to_vec();
    sorted.sort_by(|a, b| a.lo.total_cmp(&b.lo).then(a.segment.cmp(&b.segment)));
    for pair in sorted.windows(2) {
        if (pair[0].lo - pair[1].lo).abs() < TOLERANCE
            && (pair[0].hi - pair[1].hi).abs() < TOLERANCE
        {
            problems.add(
                format!("segments[{}]", pair[1].segment),
                format!(
                    "duplicates segments[{}]: the same line drawn twice",
                    pair[0].segment
                ),
            );
        }
    }
    for span in &sorted {
        let inside = allowed
            .iter()
            .any(|&(lo, hi)| span.lo >= lo - TOLERANCE && span.hi <= hi + TOLERANCE);
        if !inside {
            let pose = &layout.segments[span.segment];
            let stray = first_uncovered(span.lo, span.hi, &allowed);
            let k = (stray / c).floor();
            let (last, noun) = match axis {
                Axis::Row => (layout.grid.columns, "east"),
                Axis::Column => (layout.grid.rows, "north"),
            };
            let message = if k < 0.0 || k >= f64::from(last - 1) {
                format!(
                    "at ({}, {}) sticks out past the edge of the grid",
                    pose.x, pose.y
                )
            } else {
                let cell = cell_on(axis, line, k as u32);
                format!(
                    "at ({}, {}) draws over a wall: there is no passage {noun} of cell {cell}",
                    pose.x, pose.y
                )
            };
            problems.add(format!("segments[{}]", span.segment), message);
        }
    }
    let drawn = merge(sorted.iter().map(|s| (s.lo, s.hi)));
    for &(k, (lo, hi)) in open {
        let covered = drawn
            .iter()
            .any(|&(a, b)| a <= lo + TOLERANCE && b >= hi - TOLERANCE);
        if !covered {
            let from = cell_on(axis, line, k);
            let to = cell_on(axis, line, k + 1);
            let gap = first_uncovered(lo, hi, &drawn);
            problems.add(
                format!("passage {from}-{to}"),
                format!(
                    "is not covered gap-free by segments: nothing drawn {:.3} m past the centre of {from}",
                    gap - f64::from(k) * c
                ),
            );
        }
    }
}

/// The cell at position `k` along grid line `line`.
fn cell_on(axis: Axis, line: u32, k: u32) -> Cell {
    match axis {
        Axis::Row => Cell::new(k, line),
        Axis::Column => Cell::new(line, k),
    }
}

/// The direction a grid line runs in.
fn forward(axis: Axis) -> Direction {
    match axis {
        Axis::Row => Direction::East,
        Axis::Column => Direction::North,
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
