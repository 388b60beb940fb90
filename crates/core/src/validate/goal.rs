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

#[cfg(test)]
mod tests {
    use crate::generate::Algorithm;
    use crate::layout::micromouse::{Preset, plan};
    use crate::layout::{GenerateSpec, Layout};
    use crate::maze::Grid;
    use crate::validate::validate;

    fn mouse() -> Layout {
        let preset = Preset::Micromouse;
        let spec = preset.spec(
            GenerateSpec::course(Grid::new(9, 9).unwrap(), Algorithm::Prim, 2),
            None,
        );
        plan(preset, &spec, None).unwrap().into_layout()
    }

    fn problems(layout: &Layout) -> Vec<String> {
        validate(layout)
            .problems
            .iter()
            .map(|p| p.to_string())
            .collect()
    }

    #[test]
    fn a_goal_region_must_hang_together_on_the_grid_and_hold_the_end() {
        assert_eq!(problems(&mouse()), Vec::<String>::new());
        let mut off = mouse();
        off.end.region.push([16, 0]);
        assert!(problems(&off).contains(&"end.region[4]: (16,0) is off the 16x16 grid".into()));
        let mut apart = mouse();
        apart.end.region.push([0, 15]);
        assert!(
            problems(&apart)
                .iter()
                .any(|p| p.starts_with("end.region: falls apart: 1 of its 5 cells")),
            "{:?}",
            problems(&apart)
        );
        let mut without = mouse();
        without.end.region.retain(|&c| c != without.end.cell);
        assert!(
            problems(&without)
                .iter()
                .any(|p| p.contains("does not hold end.cell"))
        );
        let mut start = mouse();
        start.start.region = vec![[0, 0]];
        assert!(problems(&start).contains(&"start.region: only the end may be a region".into()));
    }

    #[test]
    fn the_generator_names_a_known_preset_and_only_imports_a_source() {
        let mut bad = mouse();
        bad.generator
            .options
            .insert("preset".into(), "nanomouse".into());
        bad.generator
            .options
            .insert("source".into(), "x.txt".into());
        let found = problems(&bad);
        assert!(
            found
                .iter()
                .any(|p| p.starts_with("generator.options.preset: 'nanomouse'"))
        );
        assert!(
            found
                .iter()
                .any(|p| p.starts_with("generator.options.source: only an imported"))
        );
    }
}
