//! Goal region checks: `end.region` (optional) holds distinct cells on the grid, joined
//! side by side into one piece, among them `end.cell`, which is the region cell nearest
//! the start (so the stored solution and metrics, measured to `end.cell`, reach the
//! region as soon as any path can). `start` has no region.

use super::Problems;
use crate::layout::Layout;
use crate::maze::analysis::{UNREACHED, distances_from};
use crate::maze::{Cell, Maze};

/// Runs the goal region checks on `layout`, whose passages are `maze`.
pub(super) fn check_goal(layout: &Layout, maze: &Maze, problems: &mut Problems) {
    if !layout.start.region.is_empty() {
        problems.add("start.region", "only the end may be a region");
    }
    let region = &layout.end.region;
    if region.is_empty() {
        return;
    }
    let grid = maze.grid();
    let mut cells: Vec<Cell> = Vec::with_capacity(region.len());
    for (index, &[x, y]) in region.iter().enumerate() {
        let cell = Cell::new(x, y);
        if !grid.contains(cell) {
            problems.add(
                format!("end.region[{index}]"),
                format!("{cell} is off the {grid} grid"),
            );
            return;
        }
        if cells.contains(&cell) {
            problems.add(
                format!("end.region[{index}]"),
                format!("{cell} is listed twice"),
            );
            return;
        }
        cells.push(cell);
    }
    let end = Cell::new(layout.end.cell[0], layout.end.cell[1]);
    if !cells.contains(&end) {
        problems.add("end.region", format!("does not hold end.cell {end}"));
        return;
    }
    // side by side into one piece: grow from the first cell through grid neighbours
    let mut reached = vec![cells[0]];
    let mut next = 0;
    while next < reached.len() {
        let here = reached[next];
        next += 1;
        for &other in &cells {
            let touching = here.x.abs_diff(other.x) + here.y.abs_diff(other.y) == 1;
            if touching && !reached.contains(&other) {
                reached.push(other);
            }
        }
    }
    if reached.len() != cells.len() {
        problems.add(
            "end.region",
            format!(
                "falls apart: {} of its {} cells do not touch the rest side by side",
                cells.len() - reached.len(),
                cells.len()
            ),
        );
        return;
    }
    let start = Cell::new(layout.start.cell[0], layout.start.cell[1]);
    if !grid.contains(start) {
        return; // reported with the start
    }
    let dist = distances_from(maze, grid.index(start));
    let nearest = cells
        .iter()
        .map(|&c| dist[grid.index(c)])
        .min()
        .unwrap_or(UNREACHED);
    if nearest != UNREACHED && dist[grid.index(end)] != nearest {
        problems.add(
            "end.cell",
            format!(
                "{end} is {} steps from the start but another cell of end.region is {nearest}: end.cell must be the region cell the robot reaches first",
                dist[grid.index(end)]
            ),
        );
    }
}
