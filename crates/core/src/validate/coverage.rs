//! Segment checks against the maze: every passage is covered without gaps, no segment
//! lies off a passage (over a wall, between rows, off the grid), and no segment is drawn
//! twice.
//!
//! Work happens in the maze frame, where every segment lies on a row (along x) or a
//! column (along y), so each check is one-dimensional: intervals along one grid line.
//! Segments are placed as they arrive and a stray one is reported at once; what needs
//! all of a line (duplicates, gaps) is checked at the end, from 12 bytes kept per segment
//! (its start along the line and its index), in lists sized from the passages up front.

use std::f64::consts::{FRAC_PI_2, PI};

use nalgebra::{Isometry2, Point2};

use super::Problems;
use crate::layout::Pose;
use crate::layout::geometry::{Geometry, normalize_angle};
use crate::layout::limits;
use crate::maze::{Cell, Direction, Grid, Maze};

/// Position tolerance in the maze frame: see [`limits::SEGMENT_TOLERANCE`].
const TOLERANCE: f64 = limits::SEGMENT_TOLERANCE;
/// Heading tolerance, radians.
const YAW_TOLERANCE: f64 = 1e-4;

/// Which way a grid line runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Axis {
    /// A row: along the maze's x.
    Row,
    /// A column: along the maze's y.
    Column,
}

impl Axis {
    /// The cell at position `k` along grid line `line`.
    fn cell(self, line: u32, k: u32) -> Cell {
        match self {
            Axis::Row => Cell::new(k, line),
            Axis::Column => Cell::new(line, k),
        }
    }

    /// The direction the line runs in.
    fn forward(self) -> Direction {
        match self {
            Axis::Row => Direction::East,
            Axis::Column => Direction::North,
        }
    }
}

/// The segments placed on one grid line: where each starts along it, and its index.
#[derive(Debug, Default)]
struct Line {
    starts: Vec<f64>,
    segments: Vec<u32>,
}

/// The segments placed so far, line by line.
pub(super) struct Coverage {
    maze: Maze,
    to_maze: Isometry2<f64>,
    rotation: f64,
    cell: f64,
    half_width: f64,
    length: f64,
    /// Rows (`0..height`), then columns.
    lines: Vec<Line>,
}

impl Coverage {
    /// Ready to place the segments of a layout whose passages are `maze`.
    pub fn new(maze: Maze, geometry: &Geometry, length: f64) -> Self {
        let grid = maze.grid();
        let per_passage = geometry.segments_per_passage();
        let mut open = vec![0usize; (grid.height() + grid.width()) as usize];
        for (cell, dir) in maze.passages() {
            match dir {
                Direction::East => open[cell.y as usize] += 1,
                Direction::North => open[(grid.height() + cell.x) as usize] += 1,
                _ => {}
            }
        }
        let lines = open
            .into_iter()
            .map(|passages| Line {
                starts: Vec::with_capacity(passages * per_passage),
                segments: Vec::with_capacity(passages * per_passage),
            })
            .collect();
        Self {
            to_maze: geometry.maze_to_floor().inverse(),
            rotation: geometry.rotation,
            cell: geometry.cell_size,
            half_width: geometry.line_width / 2.0,
            length,
            maze,
            lines,
        }
    }

    fn grid(&self) -> Grid {
        self.maze.grid()
    }

    /// Puts segment `index` on its grid line, or reports why it fits none or lies off the
    /// passages.
    pub fn place(&mut self, index: usize, pose: &Pose, problems: &mut Problems) {
        let location = || format!("segments[{index}]");
        let local = self.to_maze * Point2::new(pose.x, pose.y);
        let yaw = normalize_angle(pose.yaw - self.rotation).abs();
        let axis = if yaw < YAW_TOLERANCE || PI - yaw < YAW_TOLERANCE {
            Axis::Row
        } else if (yaw - FRAC_PI_2).abs() < YAW_TOLERANCE {
            Axis::Column
        } else {
            problems.add(
                location(),
                format!(
                    "at ({}, {}) has yaw {} rad: it runs along neither maze axis",
                    pose.x, pose.y, pose.yaw
                ),
            );
            return;
        };
        let grid = self.grid();
        let (across, along, count, noun) = match axis {
            Axis::Row => (local.y, local.x, grid.height(), "row"),
            Axis::Column => (local.x, local.y, grid.width(), "column"),
        };
        let c = self.cell;
        let line = (across / c).round();
        if (across - line * c).abs() > TOLERANCE {
            problems.add(
                location(),
                format!(
                    "at ({}, {}) lies between two {noun}s of cell centres",
                    pose.x, pose.y
                ),
            );
            return;
        }
        if line < 0.0 || line >= f64::from(count) {
            problems.add(
                location(),
                format!("at ({}, {}) lies off the grid", pose.x, pose.y),
            );
            return;
        }
        let line = line as u32;
        let start = along - self.length / 2.0;
        if let Some(message) = self.stray(axis, line, start, start + self.length) {
            problems.add(location(), format!("at ({}, {}) {message}", pose.x, pose.y));
            return;
        }
        let slot = match axis {
            Axis::Row => line,
            Axis::Column => grid.height() + line,
        };
        let placed = &mut self.lines[slot as usize];
        placed.starts.push(start);
        placed.segments.push(index as u32);
    }

    /// Why `lo..hi` on grid line `line` is not within its open passages, if it is not.
    /// Passage `k` (cell `k` to `k + 1`) may be drawn over `k·c − w/2 .. (k+1)·c + w/2`.
    fn stray(&self, axis: Axis, line: u32, lo: f64, hi: f64) -> Option<String> {
        let (c, hw) = (self.cell, self.half_width);
        let passages = match axis {
            Axis::Row => i64::from(self.grid().width()) - 1,
            Axis::Column => i64::from(self.grid().height()) - 1,
        };
        let open = |k: i64| {
            (0..passages).contains(&k) && {
                let cell = axis.cell(line, k as u32);
                self.maze.is_open(self.grid().index(cell), axis.forward())
            }
        };
        // The first passage whose stretch can hold `lo`, the last that `hi` needs.
        let first = ((lo + hw + TOLERANCE) / c).floor() as i64;
        let last = ((hi - hw - TOLERANCE) / c).ceil() as i64 - 1;
        let blocked = if first > last {
            // Around the centre of cell `first`: either passage beside it will do.
            (!open(first - 1) && !open(first)).then_some(first - 1)
        } else {
            (first..=last).find(|&k| !open(k))
        }?;
        Some(if blocked < 0 || blocked >= passages {
            "sticks out past the edge of the grid".to_string()
        } else {
            let noun = match axis {
                Axis::Row => "east",
                Axis::Column => "north",
            };
            format!(
                "draws over a wall: there is no passage {noun} of cell {}",
                axis.cell(line, blocked as u32)
            )
        })
    }

    /// The checks that need whole lines: no segment drawn twice, every passage covered.
    pub fn finish(mut self, problems: &mut Problems) {
        let grid = self.grid();
        let mut merged = Vec::new();
        let lines = std::mem::take(&mut self.lines);
        for (slot, placed) in lines.into_iter().enumerate() {
            let slot = slot as u32;
            let (axis, line) = if slot < grid.height() {
                (Axis::Row, slot)
            } else {
                (Axis::Column, slot - grid.height())
            };
            let placed = sorted(placed);
            self.duplicates(&placed, problems);
            merged.clear();
            for &lo in &placed.starts {
                let hi = lo + self.length;
                match merged.last_mut() {
                    Some((_, end)) if lo <= *end + TOLERANCE => *end = f64::max(*end, hi),
                    _ => merged.push((lo, hi)),
                }
            }
            self.gaps(axis, line, &merged, problems);
        }
    }

    /// Pairs of segments drawing the same stretch.
    fn duplicates(&self, placed: &Line, problems: &mut Problems) {
        for k in 1..placed.starts.len() {
            if (placed.starts[k] - placed.starts[k - 1]).abs() < TOLERANCE {
                problems.add(
                    format!("segments[{}]", placed.segments[k]),
                    format!(
                        "duplicates segments[{}]: the same line drawn twice",
                        placed.segments[k - 1]
                    ),
                );
            }
        }
    }

    /// Open passages on the line that `drawn` (sorted, merged) does not cover.
    fn gaps(&self, axis: Axis, line: u32, drawn: &[(f64, f64)], problems: &mut Problems) {
        let grid = self.grid();
        let (c, hw) = (self.cell, self.half_width);
        let length = match axis {
            Axis::Row => grid.width(),
            Axis::Column => grid.height(),
        };
        let mut j = 0;
        for k in 0..length.saturating_sub(1) {
            let from = axis.cell(line, k);
            if !self.maze.is_open(grid.index(from), axis.forward()) {
                continue;
            }
            let (lo, hi) = (f64::from(k) * c - hw, f64::from(k + 1) * c + hw);
            while j + 1 < drawn.len() && drawn[j + 1].0 <= lo + TOLERANCE {
                j += 1;
            }
            let covered = drawn
                .get(j)
                .is_some_and(|&(a, b)| a <= lo + TOLERANCE && b >= hi - TOLERANCE);
            if !covered {
                let to = axis.cell(line, k + 1);
                let gap = first_uncovered(lo, hi, drawn.get(j..).unwrap_or_default());
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
}

/// The line's segments in order along it (as this crate writes them, so usually as they
/// came), ties by index.
fn sorted(placed: Line) -> Line {
    let in_order = placed.starts.is_sorted();
    if in_order {
        return placed;
    }
    let mut pairs: Vec<(f64, u32)> = placed.starts.into_iter().zip(placed.segments).collect();
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let (starts, segments) = pairs.into_iter().unzip();
    Line { starts, segments }
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
