//! Wall checks: the style's fields are consistent, the wall template fits the cell, every
//! closed side is covered gap-free by walls, no wall stands in an open passage or an
//! opening, no wall is drawn twice, and every wall stands on the floor. With posts: the
//! post template fits the walls and the cell, a post stands at every lattice corner (none
//! missing, none doubled, none elsewhere), each on the floor, and the walls fill every
//! closed side between its posts without reaching into one.
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
    post_on_floor,
};
use crate::layout::{Layout, Pose, PostSpec, Style, WallSpec};
use crate::maze::{Grid, Maze};

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
    let Some(spec) = wall_template(layout, problems) else {
        return;
    };
    if layout.post.is_none() && !layout.posts.is_empty() {
        problems.add(
            "post",
            "missing: a layout with posts needs its post template",
        );
        return;
    }
    let post = layout.post.as_ref();
    let template = check_template(
        geometry.cell_size,
        spec.length,
        spec.thickness,
        spec.height,
        post.map(|p| p.size),
        Naming::Layout,
    );
    let bad_template = !template.is_empty();
    for v in template {
        problems.violation(&v);
    }
    let grid = maze.grid();
    check_openings(spec, grid, problems);
    if bad_template {
        return;
    }
    let lines = place_walls(layout, spec, maze, geometry, problems);
    // with posts, the walls fill each closed side between the faces of its two posts
    let inset = post.map_or(0.0, |p| p.size / 2.0);
    check_lines(
        layout,
        spec,
        maze,
        geometry.cell_size,
        inset,
        &lines,
        problems,
    );
    check_walls_on_floor(layout, spec, geometry, grid, problems);
    if let Some(post) = post {
        check_posts(layout, spec, post, grid, geometry, problems);
    }
}

/// The wall template of a wall layout, or `None` (with the problem added) when the style
/// and the wall fields disagree; a line layout must carry no wall, post or walls field.
fn wall_template<'a>(layout: &'a Layout, problems: &mut Problems) -> Option<&'a WallSpec> {
    match (layout.style, &layout.wall) {
        (Style::Lines, None) => {
            if !layout.walls.is_empty() {
                problems.add("walls", "only a layout with style \"walls\" has walls");
            }
            if layout.post.is_some() {
                problems.add(
                    "post",
                    "only a layout with style \"walls\" has a post template",
                );
            } else if !layout.posts.is_empty() {
                problems.add("posts", "only a layout with style \"walls\" has posts");
            }
            None
        }
        (Style::Lines, Some(_)) => {
            problems.add(
                "wall",
                "only a layout with style \"walls\" has a wall template",
            );
            None
        }
        (Style::Walls, None) => {
            problems.add(
                "wall",
                "missing: a layout with style \"walls\" needs its wall template",
            );
            None
        }
        (Style::Walls, Some(spec)) => Some(spec),
    }
}

/// Checks that every opening of `spec` is on the outer boundary of `grid` and none is
/// listed twice.
fn check_openings(spec: &WallSpec, grid: Grid, problems: &mut Problems) {
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
}

/// Runs [`check_line`] on every lattice line of both axes, the walls placed on them in
/// `lines`; `cell` is the cell size and `inset` half a post's side (0 without posts).
fn check_lines(
    layout: &Layout,
    spec: &WallSpec,
    maze: &Maze,
    cell: f64,
    inset: f64,
    lines: &BTreeMap<(WallAxis, u32), Vec<Span>>,
    problems: &mut Problems,
) {
    let grid = maze.grid();
    for axis in [WallAxis::AlongX, WallAxis::AlongY] {
        let (count, sides) = lattice(grid, axis);
        for line in 0..count {
            let closed: Vec<(u32, (f64, f64))> = (0..sides)
                .filter(|&k| is_closed(maze, &spec.openings, axis, line, k))
                .map(|k| {
                    let from = (f64::from(k) - 0.5) * cell;
                    (k, (from + inset, from + cell - inset))
                })
                .collect();
            let spans = lines.get(&(axis, line)).map(Vec::as_slice).unwrap_or(&[]);
            let on_line = Line {
                axis,
                index: line,
                cell,
                inset,
            };
            check_line(layout, maze, on_line, &closed, spans, problems);
        }
    }
}

/// Checks that no wall reaches off the floor.
fn check_walls_on_floor(
    layout: &Layout,
    spec: &WallSpec,
    geometry: &Geometry,
    grid: Grid,
    problems: &mut Problems,
) {
    let tolerance = limits::floor_tolerance(geometry, grid);
    for (index, pose) in layout.walls.iter().enumerate() {
        if !on_floor(pose, spec, layout.floor.size, tolerance) {
            problems.add(
                format!("walls[{index}]"),
                off_floor(pose, layout.floor.size),
            );
        }
    }
}

/// Checks what every wall and post pose must be, adding problems at `location`: finite,
/// its yaw in range, its centre at half of `height` (`rule` says so in the message).
/// `false` when a coordinate is not a number and nothing more can be checked.
fn stands_on_floor(
    location: &str,
    pose: &Pose,
    height: f64,
    rule: &str,
    problems: &mut Problems,
) -> bool {
    if ![pose.x, pose.y, pose.z, pose.yaw]
        .iter()
        .all(|v| v.is_finite())
    {
        problems.add(location, "has a coordinate that is not a finite number");
        return false;
    }
    if let Some(v) = limits::check_range(format!("{location}.yaw"), pose.yaw, limits::YAW) {
        problems.violation(&v);
    }
    if (pose.z - height / 2.0).abs() > 2.0 * limits::ROUNDING {
        problems.add(
            format!("{location}.z"),
            format!(
                "{} m is not half of wall.height {} m: {rule}",
                show(pose.z),
                show(height)
            ),
        );
    }
    true
}

/// Checks the posts of `post`: one at every lattice corner of `grid`, standing on the
/// floor at half the walls' height, square to the maze, none doubled, none elsewhere.
fn check_posts(
    layout: &Layout,
    spec: &WallSpec,
    post: &PostSpec,
    grid: Grid,
    geometry: &Geometry,
    problems: &mut Problems,
) {
    let columns = grid.width() as usize + 1;
    // the post found at each lattice corner, corner (i, j) at j * columns + i (`NONE`: no
    // post yet); four bytes a corner, as a big grid has millions
    const NONE: u32 = u32::MAX;
    let mut at_corner: Vec<u32> = vec![NONE; columns * (grid.height() as usize + 1)];
    for index in 0..layout.posts.len() {
        let Some((i, j)) = post_corner(layout, spec, post, grid, geometry, index, problems) else {
            continue;
        };
        match &mut at_corner[j * columns + i] {
            empty if *empty == NONE => *empty = u32::try_from(index).unwrap_or(NONE - 1),
            first => problems.add(
                format!("posts[{index}]"),
                format!("duplicates posts[{first}]: two posts stand at lattice corner ({i},{j})"),
            ),
        }
    }
    for (corner, &found) in at_corner.iter().enumerate() {
        if found == NONE {
            problems.add(
                format!(
                    "posts (lattice corner ({},{}))",
                    corner % columns,
                    corner / columns
                ),
                "missing: every lattice corner takes a post, and none stands here",
            );
        }
    }
}

/// Checks post `index` of the layout: on the floor, square to the maze, on a lattice
/// corner of `grid`. The corner `(i, j)` it stands at, or `None` when it stands at none
/// (or a coordinate is not a number).
fn post_corner(
    layout: &Layout,
    spec: &WallSpec,
    post: &PostSpec,
    grid: Grid,
    geometry: &Geometry,
    index: usize,
    problems: &mut Problems,
) -> Option<(usize, usize)> {
    let location = format!("posts[{index}]");
    let location = location.as_str();
    let pose = &layout.posts[index];
    if !stands_on_floor(
        location,
        pose,
        spec.height,
        "every post stands on the floor, as high as the walls",
        problems,
    ) {
        return None;
    }
    // a square turned a quarter is the same square
    if (2.0 * (pose.yaw - geometry.rotation)).sin().abs() > 2.0 * YAW_TOLERANCE {
        problems.add(
            location,
            format!(
                "at ({}, {}) has yaw {} rad: it is not square to the maze axes",
                pose.x, pose.y, pose.yaw
            ),
        );
    }
    let tolerance = limits::floor_tolerance(geometry, grid);
    if !post_on_floor(pose, post, layout.floor.size, tolerance) {
        problems.add(location, off_floor(pose, layout.floor.size));
    }
    let c = geometry.cell_size;
    let local = geometry.maze_to_floor().inverse() * Point2::new(pose.x, pose.y);
    let (i, j) = ((local.x / c + 0.5).round(), (local.y / c + 0.5).round());
    if (local.x - (i - 0.5) * c).abs() > TOLERANCE || (local.y - (j - 0.5) * c).abs() > TOLERANCE {
        problems.add(
            location,
            format!(
                "at ({}, {}) does not stand on a lattice corner, where the sides of the cells meet",
                pose.x, pose.y
            ),
        );
        return None;
    }
    if i < 0.0 || j < 0.0 || i > f64::from(grid.width()) || j > f64::from(grid.height()) {
        problems.add(
            location,
            format!("at ({}, {}) lies off the grid", pose.x, pose.y),
        );
        return None;
    }
    Some((i as usize, j as usize))
}

/// A lattice line, as [`check_line`] needs it.
#[derive(Debug, Clone, Copy)]
struct Line {
    axis: WallAxis,
    /// Which line of `axis` it is.
    index: u32,
    /// The cell size.
    cell: f64,
    /// Half a post's side (0 without posts): how far from each lattice corner the walls
    /// begin.
    inset: f64,
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
    let mut lines: BTreeMap<(WallAxis, u32), Vec<Span>> = BTreeMap::new();
    for (index, pose) in layout.walls.iter().enumerate() {
        let location = format!("walls[{index}]");
        if !stands_on_floor(
            &location,
            pose,
            spec.height,
            "every wall stands on the floor",
            problems,
        ) {
            continue;
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

/// Checks one lattice line: `closed` holds (side index, interval the walls cover) per
/// closed side.
fn check_line(
    layout: &Layout,
    maze: &Maze,
    on: Line,
    closed: &[(u32, (f64, f64))],
    spans: &[Span],
    problems: &mut Problems,
) {
    let grid = maze.grid();
    let allowed = merge(closed.iter().map(|&(_, iv)| iv));
    let mut sorted = spans.to_vec();
    sorted.sort_by(|a, b| a.lo.total_cmp(&b.lo).then(a.wall.cmp(&b.wall)));
    check_duplicates(&sorted, problems);
    for span in &sorted {
        let inside = allowed
            .iter()
            .any(|&(lo, hi)| span.lo >= lo - TOLERANCE && span.hi <= hi + TOLERANCE);
        if inside {
            continue;
        }
        let pose = &layout.walls[span.wall];
        let stray = first_uncovered(span.lo, span.hi, &allowed);
        problems.add(
            format!("walls[{}]", span.wall),
            stray_message(grid, on, pose, stray),
        );
    }
    let drawn = merge(sorted.iter().map(|s| (s.lo, s.hi)));
    for &(k, (lo, hi)) in closed {
        let covered = drawn
            .iter()
            .any(|&(a, b)| a <= lo + TOLERANCE && b >= hi - TOLERANCE);
        if !covered {
            add_gap(grid, on, k, lo, first_uncovered(lo, hi, &drawn), problems);
        }
    }
}

/// Reports every wall of `sorted` (spans sorted by start) that stands where an earlier one
/// does.
fn check_duplicates(sorted: &[Span], problems: &mut Problems) {
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
}

/// What is wrong with the wall at `pose` on line `on` whose point `stray` (along the line)
/// no closed side holds: it reaches into a post, past the grid, or into a passage or an
/// opening.
fn stray_message(grid: Grid, on: Line, pose: &Pose, stray: f64) -> String {
    let (axis, line, c) = (on.axis, on.index, on.cell);
    let (_, sides) = lattice(grid, axis);
    let k = (stray / c + 0.5).floor();
    // with posts: the lattice corner nearest the stray point, along the line
    let corner = (stray / c + 0.5).round();
    if on.inset > 0.0
        && (stray - (corner - 0.5) * c).abs() <= on.inset + TOLERANCE
        && corner >= 0.0
        && corner <= f64::from(sides)
    {
        let (i, j) = match axis {
            WallAxis::AlongX => (corner as u32, line),
            WallAxis::AlongY => (line, corner as u32),
        };
        format!(
            "at ({}, {}) reaches into the post at lattice corner ({i},{j})",
            pose.x, pose.y
        )
    } else if k < 0.0 || k >= f64::from(sides) {
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
    }
}

/// Reports closed side `k` of line `on`, its walls' interval starting at `lo`, as not
/// covered gap-free: nothing stands at `gap`.
fn add_gap(grid: Grid, on: Line, k: u32, lo: f64, gap: f64, problems: &mut Problems) {
    let axis = on.axis;
    // the posts cover the first `inset` of the side
    let end = lo - on.inset;
    let what = match cells_beside(grid, axis, on.index, k) {
        (Some(a), Some(b)) => format!("the side between cells {a} and {b}"),
        (Some(cell), None) | (None, Some(cell)) => format!("the outer side of cell {cell}"),
        (None, None) => unreachable!("a lattice side has a cell on one side at least"),
    };
    let between = if on.inset > 0.0 {
        " between its posts"
    } else {
        ""
    };
    problems.add(
        format!("walls ({what})"),
        format!(
            "is closed but not covered gap-free by walls{between}: nothing stands {:.3} m from its {} end",
            gap - end,
            match axis {
                WallAxis::AlongX => "west",
                WallAxis::AlongY => "south",
            }
        ),
    );
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

/// The problem of a wall or post at `pose` that reaches off a floor of `size` metres.
fn off_floor(pose: &Pose, size: [f64; 2]) -> String {
    format!(
        "at ({}, {}) reaches off the {} m x {} m floor",
        pose.x,
        pose.y,
        show(size[0]),
        show(size[1])
    )
}

#[cfg(test)]
mod tests {
    use crate::generate::Algorithm;
    use crate::layout::walls::{WallOptions, into_walls, length_between_posts};
    use crate::layout::{GenerateSpec, Layout, PostSpec, build_layout, passages};
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

    /// The 4x3 course maze (Prim, seed 9) in walls with posts of `size`.
    fn post_layout(size: f64) -> Layout {
        let grid = Grid::new(4, 3).unwrap();
        let mut layout = build_layout(&GenerateSpec::course(grid, Algorithm::Prim, 9)).unwrap();
        let maze = passages::decode(grid, &layout.passages).unwrap();
        let options = WallOptions {
            length: length_between_posts(1.0, size),
            posts: Some(size),
            ..WallOptions::default()
        };
        into_walls(&mut layout, &maze, &options, true).unwrap();
        layout
    }

    #[test]
    fn a_generated_post_layout_is_valid() {
        let layout = post_layout(0.05);
        assert_eq!(layout.posts.len(), 5 * 4);
        assert_eq!(problems(&layout), Vec::<String>::new());
        assert_eq!(problems(&post_layout(0.2)), Vec::<String>::new());
    }

    #[test]
    fn a_missing_post_is_named_by_its_corner() {
        let mut layout = post_layout(0.05);
        layout.posts.remove(6); // corner (1,1): 5 corners a row
        assert_eq!(
            problems(&layout),
            [
                "posts (lattice corner (1,1)): missing: every lattice corner takes a post, and none stands here"
            ]
        );
        layout.posts.clear();
        assert_eq!(problems(&layout).len(), 20);
    }

    #[test]
    fn an_extra_post_off_the_corners_or_the_grid_is_named() {
        let mut layout = post_layout(0.05);
        let mut inside = layout.posts[6];
        inside.x += 0.5; // the middle of a side
        let mut beyond = layout.posts[4]; // corner (4,0), the south-east one
        beyond.x += 1.0;
        layout.posts.extend([inside, beyond]);
        let found = problems(&layout);
        assert_eq!(found.len(), 2, "{found:?}");
        assert!(
            found[0].starts_with("posts[20]: at (")
                && found[0].ends_with(
                    "does not stand on a lattice corner, where the sides of the cells meet"
                ),
            "{found:?}"
        );
        assert!(
            found[1].starts_with("posts[21]: at (") && found[1].ends_with("lies off the grid"),
            "{found:?}"
        );
    }

    #[test]
    fn a_duplicate_post_is_named() {
        let mut layout = post_layout(0.05);
        let again = layout.posts[7];
        layout.posts.push(again);
        assert_eq!(
            problems(&layout),
            ["posts[20]: duplicates posts[7]: two posts stand at lattice corner (2,1)"]
        );
    }

    #[test]
    fn a_post_off_the_floor_or_the_ground_is_named() {
        // the grid spans x -1.5..2.5, y -1.5..1.5: walls 0.05 m thick fit a floor 5.1 m x
        // 3.1 m (centred on the floor origin), posts of 0.2 m do not
        let mut layout = post_layout(0.2);
        layout.floor.size = [5.1, 3.1];
        let found = problems(&layout);
        // the 12 corners on the south, east and north edges reach past the floor
        assert_eq!(found.len(), 12, "{found:?}");
        assert!(
            found[0].starts_with("posts[0]: at (-1.5, -1.5)")
                && found[0].ends_with("reaches off the 5.1 m x 3.1 m floor"),
            "{found:?}"
        );
        let mut layout = post_layout(0.05);
        layout.posts[3].z = 0.2;
        layout.posts[5].yaw = 0.3;
        let found = problems(&layout);
        assert_eq!(found.len(), 2, "{found:?}");
        assert!(
            found[0].starts_with("posts[3].z: 0.2 m is not half of wall.height 0.2 m"),
            "{found:?}"
        );
        assert!(
            found[1].starts_with("posts[5]: at (")
                && found[1].ends_with("it is not square to the maze axes"),
            "{found:?}"
        );
        // a quarter turn is the same square
        let mut layout = post_layout(0.05);
        layout.posts[5].yaw = crate::layout::geometry::round_um(std::f64::consts::FRAC_PI_2);
        assert_eq!(problems(&layout), Vec::<String>::new());
    }

    #[test]
    fn a_bad_post_template_or_a_wall_into_a_post_is_named() {
        let mut layout = post_layout(0.05);
        layout.post = Some(PostSpec { size: 0.04 });
        assert_eq!(
            problems(&layout),
            [
                "post.size: 0.04 m is thinner than the walls (0.05 m): their ends would show beside the posts"
            ]
        );
        let mut layout = post_layout(0.05);
        layout.post = Some(PostSpec { size: 1.0 });
        assert!(
            problems(&layout)[0]
                .starts_with("post.size: 1 m leaves less than 0.001 m between two posts"),
            "{:?}",
            problems(&layout)
        );
        let mut layout = post_layout(0.05);
        layout.post = Some(PostSpec { size: 0.0 });
        assert!(
            problems(&layout)[0].starts_with("post.size: 0 is out of range"),
            "{:?}",
            problems(&layout)
        );
        // the walls of a layout without posts are a post too long
        let mut layout = wall_layout();
        layout.post = Some(PostSpec { size: 0.05 });
        assert!(
            problems(&layout)[0]
                .starts_with("wall.length: 1 m is longer than the 0.95 m between two posts"),
            "{:?}",
            problems(&layout)
        );
        // a wall moved along its side reaches into a post, and leaves a gap behind
        let mut layout = post_layout(0.05);
        layout.walls[0].x += 0.03;
        let found = problems(&layout);
        assert_eq!(found.len(), 2, "{found:?}");
        assert!(
            found[0].starts_with("walls[0]: at (")
                && found[0].ends_with("reaches into the post at lattice corner (1,0)"),
            "{found:?}"
        );
        assert!(
            found[1].contains("is closed but not covered gap-free by walls between its posts: nothing stands 0.025 m from its west end"),
            "{found:?}"
        );
    }

    #[test]
    fn post_fields_belong_to_wall_layouts_with_a_post_template() {
        let mut layout = post_layout(0.05);
        layout.post = None;
        assert_eq!(
            problems(&layout),
            ["post: missing: a layout with posts needs its post template"]
        );
        let grid = Grid::new(4, 3).unwrap();
        let mut lines = build_layout(&GenerateSpec::course(grid, Algorithm::Prim, 9)).unwrap();
        lines.posts = post_layout(0.05).posts;
        assert_eq!(
            problems(&lines),
            ["posts: only a layout with style \"walls\" has posts"]
        );
        lines.post = Some(PostSpec { size: 0.05 });
        assert_eq!(
            problems(&lines),
            ["post: only a layout with style \"walls\" has a post template"]
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
