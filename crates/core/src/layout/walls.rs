//! Wall style: a `Wall` cuboid copy on every closed side between cells and on the outer
//! boundary, except the openings asked for; with posts, a `Post` cuboid at every lattice
//! corner as well.
//!
//! The sides lie on the lattice lines between cell centres, in the maze frame: lattice
//! line `j` along x at `y = (j - 1/2) * cell` (`j = 0..=rows`, south of row `j`), lattice
//! line `i` along y at `x = (i - 1/2) * cell` (`i = 0..=columns`, west of column `i`).
//! Side `k` of a line spans one cell. Without posts, a closed side takes
//! `n = ceil(cell / length)` copies spread evenly from one lattice corner to the next, so
//! walls meet end to end along a line: no gap a robot could pass.
//!
//! With posts (as in micromouse mazes, whose 16x16 lattice holds all 289 posts), lattice
//! corner `(i, j)`, where line `i` along y crosses line `j` along x (the south-west corner
//! of cell `(i, j)`), holds a post of side `p`, every corner of the lattice whether or not a
//! wall meets there. A closed side then takes `n = ceil((cell - p) / length)` copies spread
//! evenly between the faces of its two posts: walls and posts cover the side gap-free, the
//! walls never reach into a post, and the posts close the joints where walls meet.

use std::f64::consts::PI;
use std::fmt;
use std::str::FromStr;

use nalgebra::Point2;

use super::build::{extent_needed, fits_within};
use super::geometry::{Geometry, course, rectangle_corners, round_um};
use super::limits::{self, Name, Naming, Range, Violation, show};
use super::{Layout, Opening, Pose, PostSpec, Side, Style, WallSpec};
use crate::maze::{Cell, Grid, Maze};
use crate::wording::{Message, Opt, Value};

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

/// The `--openings` values: for completions.
pub const OPENINGS_WORDS: [&str; 4] = ["none", "start", "end", "start,end"];

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
    /// Side of the `Post` at every lattice corner, metres; `None` for no posts.
    pub posts: Option<f64>,
}

impl Default for WallOptions {
    fn default() -> Self {
        Self {
            length: defaults::LENGTH,
            thickness: defaults::THICKNESS,
            height: defaults::HEIGHT,
            openings: Openings::default(),
            posts: None,
        }
    }
}

/// The wall length that fills the space between two posts of side `post` on a side of
/// `cell_size`: one wall a side, computed from the values as the layout stores them
/// (micrometres), so exactly one copy fits.
pub fn length_between_posts(cell_size: f64, post: f64) -> f64 {
    round_um(round_um(cell_size) - round_um(post))
}

/// Which way a lattice line runs, in the maze frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum WallAxis {
    /// Along x: the line between two rows.
    AlongX,
    /// Along y: the line between two columns.
    AlongY,
}

/// Checks the wall template (and the post template, side `post`) against `cell_size`:
/// each number in range, the thickness less than the cell (thicker walls close the
/// passages), the length at most the stretch a side leaves for walls (the cell, or the
/// cell less one post: a longer copy reaches into the next side, which may be open, or
/// into a post) and at least that stretch / [`limits::MAX_SEGMENTS_PER_PASSAGE`]. A post
/// is at least as thick as the walls (their ends would show beside it) and leaves at least
/// [`limits::MIN_LENGTH`] of the side for walls.
pub fn check_template(
    cell_size: f64,
    length: f64,
    thickness: f64,
    height: f64,
    post: Option<f64>,
    naming: Naming,
) -> Vec<Violation> {
    let (l, t, h, p) = template_names(naming);
    let mut out: Vec<Violation> = [
        limits::check_range(l.clone(), length, limits::LENGTH),
        limits::check_range(t.clone(), thickness, limits::LENGTH),
        limits::check_range(h, height, HEIGHT),
        post.and_then(|size| limits::check_range(p.clone(), size, limits::LENGTH)),
    ]
    .into_iter()
    .flatten()
    .collect();
    if !out.is_empty() || !limits::LENGTH.contains(cell_size) {
        return out;
    }
    if thickness >= cell_size {
        out.push(starting_with_value(
            &t,
            thickness,
            format!(
                "m is not less than the cell size {} m: the walls would close the passages",
                show(cell_size)
            ),
        ));
    }
    let Some((span, bound)) = wall_span(cell_size, thickness, post, &p, &mut out) else {
        return out;
    };
    check_length(length, span, &bound, post.is_some(), &l, &mut out);
    out
}

/// The names of the wall length, thickness, height and post size in `naming`.
fn template_names(naming: Naming) -> (Name, Name, Name, Name) {
    match naming {
        Naming::Options => (
            Name::Opt(Opt::WallLength),
            Name::Opt(Opt::WallThickness),
            Name::Opt(Opt::WallHeight),
            Name::Opt(Opt::PostSize),
        ),
        Naming::Layout => (
            "wall.length".into(),
            "wall.thickness".into(),
            "wall.height".into(),
            "post.size".into(),
        ),
    }
}

/// A violation of `name`, whose message starts with the value: `0.2 m is longer than ...`.
fn starting_with_value(name: &Name, value: f64, message: String) -> Violation {
    Violation {
        name: name.clone(),
        value: Some(show(value)),
        message: message.into(),
    }
}

/// The stretch of a side the walls fill, and what bounds it in messages: the cell, or
/// with a post of side `post` (named `p`) the cell less the post. `None` (with the
/// violations added to `out`) when the post is thinner than the walls or leaves no room
/// for one.
fn wall_span(
    cell_size: f64,
    thickness: f64,
    post: Option<f64>,
    p: &Name,
    out: &mut Vec<Violation>,
) -> Option<(f64, String)> {
    let Some(size) = post else {
        return Some((cell_size, format!("the cell size {} m", show(cell_size))));
    };
    let mut fits = true;
    if size < thickness - limits::ROUNDING * 2.0 {
        out.push(starting_with_value(
            p,
            size,
            format!(
                "m is thinner than the walls ({} m): their ends would show beside the posts",
                show(thickness)
            ),
        ));
        fits = false;
    }
    if cell_size - size < limits::MIN_LENGTH - limits::ROUNDING * 2.0 {
        out.push(starting_with_value(
            p,
            size,
            format!(
                "m leaves less than {} m between two posts of a {} m cell: no room for a wall",
                limits::MIN_LENGTH,
                show(cell_size)
            ),
        ));
        fits = false;
    }
    if !fits {
        return None;
    }
    let span = round_um(cell_size - size);
    Some((
        span,
        format!(
            "the {} m between two posts (cell {} m - post {} m)",
            show(span),
            show(cell_size),
            show(size)
        ),
    ))
}

/// Checks the wall `length` (named `l`) against the `span` a side leaves for walls
/// (`bound` in messages): at most the span, at least the span /
/// [`limits::MAX_SEGMENTS_PER_PASSAGE`].
fn check_length(
    length: f64,
    span: f64,
    bound: &str,
    posts: bool,
    l: &Name,
    out: &mut Vec<Violation>,
) {
    if length > span + limits::ROUNDING * 2.0 {
        let into = if posts {
            "a post"
        } else {
            "the next side, which may be open"
        };
        out.push(starting_with_value(
            l,
            length,
            format!("m is longer than {bound}: a wall would reach into {into}",),
        ));
    }
    let shortest = span / limits::MAX_SEGMENTS_PER_PASSAGE as f64;
    if length < shortest - limits::ROUNDING * 2.0 {
        let over = if posts {
            format!("(cell - post) {}", show(span))
        } else {
            "cell".to_string()
        };
        out.push(starting_with_value(
            l,
            length,
            format!(
                "m is shorter than {over} / {} = {} m: a side may take at most {} copies",
                limits::MAX_SEGMENTS_PER_PASSAGE,
                show(shortest),
                limits::MAX_SEGMENTS_PER_PASSAGE
            ),
        ));
    }
}

/// Copies of `Wall` per stretch `cell_size` long: `ceil(cell / length)`, at least 1.
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

/// Offsets of the wall copies' centres along a closed side, from its first lattice corner:
/// [`copy_offsets`] over the whole side, or with posts of side `post`, over the stretch
/// between the posts' faces.
pub fn side_offsets(cell_size: f64, length: f64, post: Option<f64>) -> Vec<f64> {
    match post {
        None => copy_offsets(cell_size, length),
        Some(size) => copy_offsets(cell_size - size, length)
            .into_iter()
            .map(|t| t + size / 2.0)
            .collect(),
    }
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
) -> Result<Vec<Opening>, Message> {
    let mut out: Vec<Opening> = Vec::new();
    let ends = [
        (openings.start, "start", Opt::Start, start),
        (openings.end, "end", Opt::End, end),
    ];
    for (wanted, which, option, cell) in ends {
        if !wanted {
            continue;
        }
        let side = outer_side(grid, cell).ok_or_else(|| {
            Message::setting(Opt::Openings, Value::word(openings))
                .and(format!(
                    ": the {which} cell {cell} is not on the edge of the {grid} grid, so no gap can lead to it; choose "
                ))
                .and_opt(option)
                .and(format!(" on the edge or leave {which} out of "))
                .and_opt(Opt::Openings)
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
/// to east), then along y (west to east, each south to north); with posts of side `post`,
/// between the posts.
pub fn wall_poses(
    maze: &Maze,
    geometry: &Geometry,
    spec: &WallSpec,
    post: Option<f64>,
) -> Vec<Pose> {
    let grid = maze.grid();
    let iso = geometry.maze_to_floor();
    let c = geometry.cell_size;
    let offsets = side_offsets(c, spec.length, post);
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

/// Floor poses of the posts of a `grid`, one per lattice corner: corner `(i, j)` (the
/// south-west corner of cell `(i, j)`) at index `j * (columns + 1) + i`, each standing on
/// the floor at half the walls' `height`, square to the maze.
pub fn post_poses(grid: Grid, geometry: &Geometry, height: f64) -> Vec<Pose> {
    let iso = geometry.maze_to_floor();
    let c = geometry.cell_size;
    let z = round_um(height / 2.0);
    let mut poses = Vec::with_capacity(post_count(grid) as usize);
    for j in 0..=grid.height() {
        for i in 0..=grid.width() {
            let p = iso * Point2::new((f64::from(i) - 0.5) * c, (f64::from(j) - 0.5) * c);
            poses.push(Pose::rounded(p.x, p.y, z, geometry.rotation));
        }
    }
    poses
}

/// Lattice corners of `grid`, one post each: `(columns + 1) * (rows + 1)`.
pub fn post_count(grid: Grid) -> u64 {
    (u64::from(grid.width()) + 1) * (u64::from(grid.height()) + 1)
}

/// The floor-frame corners of the rectangle the walls (and posts) cover: the grid plus
/// `thickness / 2` all round (pass the thicker of walls and posts).
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

/// `true` if the footprint of a post of `spec` at `pose` lies on a floor of `size`
/// (centred on the floor origin), within `tolerance`.
pub fn post_on_floor(pose: &Pose, spec: &PostSpec, size: [f64; 2], tolerance: f64) -> bool {
    let corners = rectangle_corners(pose, spec.size, spec.size);
    fits_within(extent_needed(&corners), size, tolerance)
}

/// Turns the line layout of `maze` into a wall layout: the wall template and openings in
/// `wall`, one pose per wall in `walls`, with posts the post template in `post` and one
/// pose per lattice corner in `posts`, no line segments. The floor grows in whole
/// panels when `auto_floor` and the boundary walls reach past it; otherwise a floor they
/// reach past is refused.
pub fn into_walls(
    layout: &mut Layout,
    maze: &Maze,
    options: &WallOptions,
    auto_floor: bool,
) -> Result<(), Message> {
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
) -> Result<(), Message> {
    let grid = maze.grid();
    if let Some(o) = openings.iter().find(|o| opening_side(grid, o).is_none()) {
        return Err(format!(
            "the {} side of cell ({},{}) is not on the outer boundary of the {grid} grid",
            o.side.name(),
            o.cell[0],
            o.cell[1]
        )
        .into());
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
        options.posts,
        Naming::Options,
    )
    .into_iter()
    .next()
    {
        return Err(v.line());
    }
    let post = options.posts.map(|size| PostSpec {
        size: round_um(size),
    });
    let post_size = post.as_ref().map(|p| p.size);
    let span = geometry.cell_size - post_size.unwrap_or(0.0);
    check_wall_count(grid, span, options)?;
    let spec = WallSpec {
        length: round_um(options.length),
        thickness: round_um(options.thickness),
        height: round_um(options.height),
        openings,
    };
    let reach = spec.thickness.max(post_size.unwrap_or(0.0));
    fit_floor(layout, grid, &geometry, reach, auto_floor)?;
    layout.walls = wall_poses(maze, &geometry, &spec, post_size);
    layout.posts = match post_size {
        Some(_) => post_poses(grid, &geometry, spec.height),
        None => Vec::new(),
    };
    layout.style = Style::Walls;
    layout.wall = Some(spec);
    layout.post = post;
    layout.segments.clear();
    Ok(())
}

/// Refuses walls of `options` that, `span` of each side theirs to fill, could need more
/// copies (walls and posts) than a layout may hold.
fn check_wall_count(grid: Grid, span: f64, options: &WallOptions) -> Result<(), Message> {
    let per_side = copies_per_side(span, round_um(options.length)) as u64;
    let sides = u64::from(grid.width()) * (u64::from(grid.height()) + 1)
        + u64::from(grid.height()) * (u64::from(grid.width()) + 1);
    let posts = if options.posts.is_some() {
        post_count(grid)
    } else {
        0
    };
    if sides * per_side + posts > limits::MAX_SEGMENTS {
        return Err(Message::text(format!(
            "a {grid} maze with {per_side} wall copies a side could need {} walls{}, more than the {} copies a layout may hold: use a smaller ",
            sides * per_side,
            if posts > 0 {
                format!(" and {posts} posts")
            } else {
                String::new()
            },
            limits::MAX_SEGMENTS
        ))
        .and_opt(Opt::Size)
        .and(" or a longer ")
        .and_opt(Opt::WallLength));
    }
    Ok(())
}

/// Makes the layout's floor hold walls reaching `reach` past the lattice lines: refused
/// when it is too small and `auto_floor` is off, else grown in whole panels (at most to
/// the largest floor).
fn fit_floor(
    layout: &mut Layout,
    grid: Grid,
    geometry: &Geometry,
    reach: f64,
    auto_floor: bool,
) -> Result<(), Message> {
    let need = extent_needed(&wall_extent_corners(grid, geometry, reach));
    let tolerance = limits::floor_tolerance(geometry, grid);
    if !fits_within(need, layout.floor.size, tolerance) {
        if !auto_floor {
            return Err(Message::text(format!(
                "the walls need a floor of {:.3} m x {:.3} m (centred on the floor origin) but ",
                need[0], need[1],
            ))
            .and_opt(Opt::FloorSize)
            .and(format!(
                " is {} m x {} m",
                show(layout.floor.size[0]),
                show(layout.floor.size[1])
            )));
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
            )
            .into());
        }
        layout.floor.size = size;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::Algorithm;
    use crate::layout::{GenerateSpec, build_layout, passages};
    use crate::wording::testing::dashed;

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
            err.to_string()
                .contains("the end cell (2,2) is not on the edge"),
            "{err}"
        );
    }

    #[test]
    fn posts_stand_at_every_corner_and_the_walls_between_them() {
        let spec = GenerateSpec::course(Grid::new(3, 2).unwrap(), Algorithm::Dfs, 1);
        let mut layout = build_layout(&spec).unwrap();
        let maze = passages::decode(Grid::new(3, 2).unwrap(), &layout.passages).unwrap();
        let options = WallOptions {
            length: length_between_posts(1.0, 0.05),
            posts: Some(0.05),
            ..WallOptions::default()
        };
        into_walls(&mut layout, &maze, &options, true).unwrap();
        assert_eq!(layout.post, Some(PostSpec { size: 0.05 }));
        assert_eq!(layout.wall.as_ref().unwrap().length, 0.95);
        // every corner of the 4 x 3 lattice, the closed sides one wall each as before
        assert_eq!(layout.posts.len(), 12);
        assert_eq!(layout.walls.len(), 17 - 5);
        assert_eq!(layout.posts[0], Pose::rounded(-1.5, -0.5, 0.1, 0.0));
        assert_eq!(layout.posts[11], Pose::rounded(1.5, 1.5, 0.1, 0.0));
        // a wall still centred on its side, now between the posts' faces
        assert_eq!(layout.walls[0], Pose::rounded(-1.0, -0.5, 0.1, 0.0));
        let offsets = side_offsets(1.0, 0.475, Some(0.05));
        assert_eq!(offsets.len(), 2);
        assert!((offsets[0] - 0.2625).abs() < 1e-12 && (offsets[1] - 0.7375).abs() < 1e-12);
        // without posts the options leave the layout without them
        let (plain, _) = walled(Openings::default());
        assert!(plain.post.is_none() && plain.posts.is_empty());
    }

    #[test]
    fn the_post_template_must_fit_the_walls_and_the_cell() {
        let v = check_template(0.18, 0.168, 0.012, 0.05, Some(0.01), Naming::Options);
        assert!(
            dashed(&v[0].line())
                .starts_with("--post-size 0.01 m is thinner than the walls (0.012 m)"),
            "{v:?}"
        );
        let v = check_template(0.18, 0.168, 0.012, 0.05, Some(0.18), Naming::Layout);
        assert!(
            v[0].to_string()
                .starts_with("post.size 0.18 m leaves less than 0.001 m between two posts"),
            "{v:?}"
        );
        let v = check_template(0.18, 0.18, 0.012, 0.05, Some(0.012), Naming::Layout);
        assert_eq!(
            v[0].to_string(),
            "wall.length 0.18 m is longer than the 0.168 m between two posts (cell 0.18 m - post 0.012 m): a wall would reach into a post"
        );
        assert!(check_template(0.18, 0.168, 0.012, 0.05, Some(0.012), Naming::Layout).is_empty());
        assert!(check_template(0.18, 0.084, 0.012, 0.05, Some(0.012), Naming::Layout).is_empty());
    }

    #[test]
    fn options_parse_and_copies_spread() {
        assert_eq!("none".parse::<Openings>().unwrap(), Openings::default());
        assert!("start,exit".parse::<Openings>().is_err());
        assert_eq!(copies_per_side(1.0, 1.0), 1);
        assert_eq!(copy_offsets(1.0, 0.4), vec![0.2, 0.5, 0.8]);
        let v = check_template(0.18, 0.2, 0.012, 0.05, None, Naming::Options);
        assert!(
            dashed(&v[0].line()).starts_with("--wall-length 0.2 m is longer"),
            "{v:?}"
        );
        let v = check_template(0.18, 0.18, 0.2, 0.05, None, Naming::Layout);
        assert!(v[0].to_string().starts_with("wall.thickness"), "{v:?}");
    }
}
