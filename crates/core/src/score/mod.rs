//! Grading a robot's run through a maze: did it reach `End`, how fast, how far it drove
//! against the shortest way, SPL (success weighted by path length, Anderson et al. 2018,
//! arXiv:1807.06757), the cells it visited, and how well it kept to the lines (line maze)
//! or clear of the walls (wall maze).
//!
//! Pure: [`Grader::grade`] reads a trajectory ([`Sample`]s in the `Floor` frame) and a
//! layout that passed [`crate::validate::checked`]; following a robot in a simulator is
//! `cli::score`'s job. The drawn lines and walls are the rectangles of
//! [`crate::layout::runs`], the same ones the pictures and meshes show.

pub mod follow;
pub mod sampling;
pub mod trajectory;

use nalgebra::{Isometry2, Point2};
use schemars::JsonSchema;
use serde::Serialize;

use crate::layout::runs::{OpenSides, for_each_run, for_each_wall_run, post_rect};
use crate::layout::{Layout, Style, passages};
use crate::maze::analysis::{Distances, UNREACHED};
use crate::maze::{Cell, Grid, Maze};

pub use sampling::Sampling;
pub use trajectory::Sample;

/// What the grade depends on besides the layout and the trajectory.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GradeOptions {
    /// The robot's radius, metres, for wall contacts (wall mazes only).
    pub robot_radius: f64,
    /// Side of the `End` marker's square footprint, metres; `None` takes the cell size
    /// (the course's 1 m marker on 1 m cells).
    pub end_size: Option<f64>,
}

impl Default for GradeOptions {
    fn default() -> Self {
        Self {
            robot_radius: DEFAULT_ROBOT_RADIUS,
            end_size: None,
        }
    }
}

/// The default robot radius, metres: about the course's small wheeled robot.
pub const DEFAULT_ROBOT_RADIUS: f64 = 0.1;

/// The grade of one run. Lengths are metres, times seconds (simulation time unless the
/// name says wall time), cells `[column, row]`.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct Report {
    /// `true` when the run was followed to its end (`End` reached with `--until end`, or
    /// the simulation stopped with `--until stop`, or a trajectory file graded whole) and
    /// sampled densely enough to grade (see `sampling`); `false` for a partial report (the
    /// simulation stopped or the connection dropped mid-run, or the timeout passed) or a
    /// run sampled too sparsely.
    pub complete: bool,
    /// Why the report is partial, when it is (several reasons joined by `; `).
    pub incomplete_reason: Option<String>,
    /// The robot's centre was inside the `End` marker's footprint (any cell of the goal
    /// region) at some sample.
    pub reached_end: bool,
    /// Simulation time of the first sample inside `End`; `null` if never reached.
    pub time_s: Option<f64>,
    /// Wall-clock seconds from the first sample to reaching `End` (or to the last sample
    /// if never reached); `null` for a graded file.
    pub wall_time_s: Option<f64>,
    /// Number of samples graded.
    pub samples: usize,
    /// Simulation time of the first sample.
    pub first_time_s: Option<f64>,
    /// Simulation time of the last sample.
    pub last_time_s: Option<f64>,
    /// Length of the polyline through all the samples.
    pub path_length_m: f64,
    /// Length of the polyline from the first sample to the first one inside `End` (the
    /// `p` of SPL); `null` if never reached.
    pub path_to_end_m: Option<f64>,
    /// The cell the robot started in (its first sample); `null` if outside the grid.
    pub start_cell: Option<[u32; 2]>,
    /// Shortest way through the maze from the centre of the start cell to the centre of
    /// the nearest goal cell: breadth-first steps over the passages times the cell size (the
    /// `l` of SPL); `null` if the robot started outside the grid.
    pub shortest_length_m: Option<f64>,
    /// SPL = S * l / max(p, l): 0 if `End` was not reached, 1 for a run no longer than the
    /// shortest way; `null` when `l` is unknown (start outside the grid) or the run was
    /// sampled too sparsely to know `p` (`sampling.jumps_over_max` above 0).
    pub spl: Option<f64>,
    /// Distinct cells the robot's centre was in.
    pub cells_visited: usize,
    /// Entries into a cell it had already been in.
    pub cells_revisited: usize,
    /// Samples whose centre lay outside the floor.
    pub samples_off_floor: usize,
    /// Samples whose centre lay outside the maze's grid of cells.
    pub samples_off_grid: usize,
    /// How far apart the samples were: a move of more than half a cell between two of
    /// them leaves the run ungraded (not `complete`, no SPL).
    pub sampling: Sampling,
    /// Line mazes: how well the robot kept to the drawn lines.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub line: Option<LineReport>,
    /// Wall mazes: how close the robot came to the walls.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub walls: Option<WallReport>,
}

impl Report {
    /// Adds how a followed run ended: `incomplete`, why it ended early (`None`: as asked),
    /// goes before any reason of the grade's own, and `wall_time_s` is set.
    pub fn followed(&mut self, incomplete: Option<String>, wall_time_s: Option<f64>) {
        if let Some(why) = incomplete {
            self.complete = false;
            self.incomplete_reason = Some(match self.incomplete_reason.take() {
                Some(own) => format!("{why}; {own}"),
                None => why,
            });
        }
        self.wall_time_s = wall_time_s;
    }
}

/// Distance of the robot's centre from the nearest drawn line (0 on the paint).
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct LineReport {
    /// Mean over the samples.
    pub mean_distance_m: f64,
    /// Largest.
    pub max_distance_m: f64,
    /// Simulation time spent more than half a line width off the paint (each sample
    /// counts until the next one).
    pub time_off_line_s: f64,
    /// The line width the layout draws.
    pub line_width_m: f64,
}

/// Clearance between the robot (a disc) and the walls and posts.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct WallReport {
    /// Smallest distance from the robot's edge to a wall or post; negative when it
    /// overlapped one (it drove into or through it).
    pub closest_approach_m: f64,
    /// Times the robot came into contact (clearance below 0 after being clear, or at
    /// the first sample).
    pub contacts: usize,
    /// The radius graded with.
    pub robot_radius_m: f64,
}

/// A layout made ready for grading: the maze, its frame and the drawn rectangles.
#[derive(Debug, Clone)]
pub struct Grader {
    maze: Maze,
    floor_to_maze: Isometry2<f64>,
    cell_size: f64,
    half_floor: [f64; 2],
    goals: Vec<Cell>,
    style: Style,
    line_width: f64,
    /// Line rectangles (line maze) or wall and post rectangles (wall maze), maze frame.
    rects: Vec<[f64; 4]>,
}

impl Grader {
    /// Prepares `layout`, which must have passed [`crate::validate::checked`].
    pub fn new(layout: &Layout) -> Result<Self, String> {
        let grid = Grid::new(layout.grid.columns.into(), layout.grid.rows.into())
            .map_err(|e| format!("grid: {e}"))?;
        let maze = passages::decode(grid, &layout.passages)?;
        let cell_size = layout.grid.cell_size;
        let mut rects = Vec::new();
        match layout.style {
            Style::Lines => {
                let Ok(()) = for_each_run::<std::convert::Infallible>(
                    &maze,
                    |run| {
                        rects.push(run.rect(cell_size, layout.line.width));
                        Ok(())
                    },
                    |_| {},
                );
            }
            Style::Walls => {
                let spec = layout.wall.as_ref().ok_or("a wall layout without `wall`")?;
                let open = OpenSides::of(&maze, &spec.openings);
                let Ok(()) = for_each_wall_run::<std::convert::Infallible>(
                    &maze,
                    &open,
                    |run| {
                        rects.push(run.rect(cell_size, spec.thickness));
                        Ok(())
                    },
                    |_| {},
                );
                if let Some(post) = &layout.post {
                    for i in 0..=grid.width() {
                        for j in 0..=grid.height() {
                            rects.push(post_rect([i, j], cell_size, post.size));
                        }
                    }
                }
            }
        }
        let region = &layout.end.region;
        let goals = if region.is_empty() {
            vec![layout.end.cell]
        } else {
            region.clone()
        };
        let maze_to_floor = Isometry2::new(
            nalgebra::Vector2::new(layout.grid.origin[0], layout.grid.origin[1]),
            layout.grid.rotation,
        );
        Ok(Self {
            maze,
            floor_to_maze: maze_to_floor.inverse(),
            cell_size,
            half_floor: layout.floor.size.map(|s| s / 2.0),
            goals: goals.into_iter().map(|[x, y]| Cell::new(x, y)).collect(),
            style: layout.style,
            line_width: layout.line.width,
            rects,
        })
    }

    /// The cell of the grid that a maze-frame point lies in, if any.
    fn cell_at(&self, p: Point2<f64>) -> Option<Cell> {
        let grid = self.maze.grid();
        let index = |v: f64, n: u32| {
            let i = (v / self.cell_size).round();
            (i >= 0.0 && i < f64::from(n)).then_some(i as u32)
        };
        Some(Cell::new(
            index(p.x, grid.width())?,
            index(p.y, grid.height())?,
        ))
    }

    /// `true` if the robot's centre at `sample` (floor frame) is inside `End`'s footprint
    /// (of `options.end_size`, else the cell size).
    pub fn in_end_at(&self, sample: &Sample, options: &GradeOptions) -> bool {
        self.in_end(
            self.floor_to_maze * Point2::new(sample.x, sample.y),
            options.end_size.unwrap_or(self.cell_size),
        )
    }

    /// `true` if a maze-frame point lies in the `End` footprint of side `size`.
    fn in_end(&self, p: Point2<f64>, size: f64) -> bool {
        let half = size / 2.0;
        self.goals.iter().any(|g| {
            let (cx, cy) = (
                f64::from(g.x) * self.cell_size,
                f64::from(g.y) * self.cell_size,
            );
            (p.x - cx).abs() <= half && (p.y - cy).abs() <= half
        })
    }

    /// Distance from a maze-frame point to the nearest drawn rectangle (0 inside one);
    /// infinite when nothing is drawn.
    fn nearest_rect(&self, p: Point2<f64>) -> f64 {
        self.rects
            .iter()
            .map(|r| point_rect(p, r))
            .fold(f64::INFINITY, f64::min)
    }

    /// Distance from the segment `a`-`b` to the nearest drawn rectangle (0 if it crosses
    /// one): a robot that passes through a thin wall between two samples touched it.
    fn nearest_rect_on_segment(&self, a: Point2<f64>, b: Point2<f64>) -> f64 {
        self.rects
            .iter()
            .map(|r| segment_rect(a, b, r))
            .fold(f64::INFINITY, f64::min)
    }

    /// Breadth-first steps from `start` to the nearest goal cell, times the cell size.
    fn shortest_from(&self, start: Cell) -> Option<f64> {
        let grid = self.maze.grid();
        let distances = Distances::from(&self.maze, grid.index(start));
        self.goals
            .iter()
            .filter(|g| grid.contains(**g))
            .map(|&g| distances.steps_to(grid.index(g)))
            .filter(|&d| d != UNREACHED)
            .min()
            .map(|steps| f64::from(steps) * self.cell_size)
    }

    /// Grades a run. The report is complete unless the samples are too sparse to grade
    /// (then it has no SPL either); the caller that followed a live run adds how the run
    /// ended with [`Report::followed`].
    pub fn grade(&self, samples: &[Sample], options: &GradeOptions) -> Report {
        let end_size = options.end_size.unwrap_or(self.cell_size);
        let local: Vec<Point2<f64>> = samples
            .iter()
            .map(|s| self.floor_to_maze * Point2::new(s.x, s.y))
            .collect();
        let mut path_length = 0.0;
        let mut reached: Option<(usize, f64)> = None;
        for (i, p) in local.iter().enumerate() {
            if i > 0 {
                path_length += (p - local[i - 1]).norm();
            }
            if reached.is_none() && self.in_end(*p, end_size) {
                reached = Some((i, path_length));
            }
        }
        let cells: Vec<Option<Cell>> = local.iter().map(|&p| self.cell_at(p)).collect();
        let (visited, revisited) = visits(&cells, self.maze.grid());
        let start_cell = cells.first().copied().flatten();
        let shortest = start_cell.and_then(|c| self.shortest_from(c));
        let times: Vec<f64> = samples.iter().map(|s| s.t).collect();
        let sampling = Sampling::of(&local, &times, self.cell_size);
        let spl = match (reached, shortest) {
            _ if !sampling.is_dense() => None,
            (None, _) => Some(0.0),
            (Some(_), None) => None,
            (Some((_, p)), Some(l)) => Some(if p.max(l) > 0.0 { l / p.max(l) } else { 1.0 }),
        };
        let off_floor = samples
            .iter()
            .filter(|s| s.x.abs() > self.half_floor[0] || s.y.abs() > self.half_floor[1])
            .count();
        let distances: Vec<f64> = local.iter().map(|&p| self.nearest_rect(p)).collect();
        let (line, walls) = match self.style {
            Style::Lines => (Some(self.line_report(samples, &distances)), None),
            Style::Walls => {
                let between: Vec<f64> = local
                    .windows(2)
                    .map(|w| self.nearest_rect_on_segment(w[0], w[1]))
                    .collect();
                (
                    None,
                    Some(wall_report(&distances, &between, options.robot_radius)),
                )
            }
        };
        Report {
            complete: sampling.is_dense(),
            incomplete_reason: sampling.too_sparse(),
            reached_end: reached.is_some(),
            time_s: reached.map(|(i, _)| samples[i].t),
            wall_time_s: None,
            samples: samples.len(),
            first_time_s: samples.first().map(|s| s.t),
            last_time_s: samples.last().map(|s| s.t),
            path_length_m: path_length,
            path_to_end_m: reached.map(|(_, p)| p),
            start_cell: start_cell.map(|c| [c.x, c.y]),
            shortest_length_m: shortest,
            spl,
            cells_visited: visited,
            cells_revisited: revisited,
            samples_off_floor: off_floor,
            samples_off_grid: cells.iter().filter(|c| c.is_none()).count(),
            sampling,
            line,
            walls,
        }
    }

    fn line_report(&self, samples: &[Sample], distances: &[f64]) -> LineReport {
        let half = self.line_width / 2.0;
        let time_off = samples
            .windows(2)
            .zip(distances)
            .filter(|(_, d)| **d > half)
            .map(|(w, _)| w[1].t - w[0].t)
            .fold(0.0, |a, b| a + b);
        let finite = |d: f64| if d.is_finite() { d } else { 0.0 };
        LineReport {
            mean_distance_m: if distances.is_empty() {
                0.0
            } else {
                distances.iter().copied().map(finite).sum::<f64>() / distances.len() as f64
            },
            max_distance_m: distances.iter().copied().map(finite).fold(0.0, f64::max),
            time_off_line_s: time_off,
            line_width_m: self.line_width,
        }
    }
}

/// Clearances from the distances of the robot's centre to the walls at each sample
/// (`at`) and along the way from each sample to the next (`between`). A contact starts
/// wherever the robot goes from clear to touching in the sequence sample, way, sample, ...
fn wall_report(at: &[f64], between: &[f64], radius: f64) -> WallReport {
    let mut contacts = 0;
    let mut touching = false;
    let mut closest = f64::INFINITY;
    let sequence = at
        .iter()
        .zip(between.iter().map(Some).chain(std::iter::repeat(None)))
        .flat_map(|(a, b)| std::iter::once(a).chain(b));
    for d in sequence {
        let clearance = d - radius;
        closest = closest.min(clearance);
        if clearance < 0.0 && !touching {
            contacts += 1;
        }
        touching = clearance < 0.0;
    }
    WallReport {
        closest_approach_m: if closest.is_finite() { closest } else { 0.0 },
        contacts,
        robot_radius_m: radius,
    }
}

/// Distance from `p` to the rectangle `[x0, y0, x1, y1]`, 0 inside it.
fn point_rect(p: Point2<f64>, &[x0, y0, x1, y1]: &[f64; 4]) -> f64 {
    let dx = (x0 - p.x).max(p.x - x1).max(0.0);
    let dy = (y0 - p.y).max(p.y - y1).max(0.0);
    dx.hypot(dy)
}

/// Distance from the segment `a`-`b` to the rectangle, 0 if they meet: the segment is
/// clipped to the rectangle (Liang-Barsky); if nothing is left, the nearest points are an
/// end of the segment or a corner of the rectangle.
fn segment_rect(a: Point2<f64>, b: Point2<f64>, rect: &[f64; 4]) -> f64 {
    let &[x0, y0, x1, y1] = rect;
    let d = b - a;
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    let mut meets = true;
    for (p, q) in [
        (-d.x, a.x - x0),
        (d.x, x1 - a.x),
        (-d.y, a.y - y0),
        (d.y, y1 - a.y),
    ] {
        if p == 0.0 {
            meets &= q >= 0.0;
        } else if p < 0.0 {
            lo = lo.max(q / p);
        } else {
            hi = hi.min(q / p);
        }
    }
    if meets && lo <= hi {
        return 0.0;
    }
    let corner_to_segment = |c: Point2<f64>| {
        let len2 = d.norm_squared();
        let f = if len2 > 0.0 {
            ((c - a).dot(&d) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        (c - (a + d * f)).norm()
    };
    [[x0, y0], [x0, y1], [x1, y0], [x1, y1]]
        .into_iter()
        .map(|[x, y]| corner_to_segment(Point2::new(x, y)))
        .chain([point_rect(a, rect), point_rect(b, rect)])
        .fold(f64::INFINITY, f64::min)
}

/// Distinct cells in `cells` (samples off the grid ignored) and the entries into a cell
/// already visited.
fn visits(cells: &[Option<Cell>], grid: Grid) -> (usize, usize) {
    let mut seen = fixedbitset::FixedBitSet::with_capacity(grid.cell_count());
    let (mut visited, mut revisited) = (0, 0);
    let mut here = None;
    for cell in cells.iter().flatten() {
        if here == Some(*cell) {
            continue;
        }
        here = Some(*cell);
        let index = grid.index(*cell);
        if seen.put(index) {
            revisited += 1;
        } else {
            visited += 1;
        }
    }
    (visited, revisited)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::Algorithm;
    use crate::layout::{GenerateSpec, build_layout};
    use crate::maze::analysis::shortest_path;

    fn course(columns: u64, rows: u64, seed: u64) -> Layout {
        let grid = Grid::new(columns, rows).unwrap();
        build_layout(&GenerateSpec::course(grid, Algorithm::Dfs, seed)).unwrap()
    }

    /// Samples in the maze frame of the course's 3 x 1 maze (cell (0,0) at floor x = -1),
    /// one a second.
    fn along_3x1(points: &[(f64, f64)]) -> Vec<Sample> {
        (0..)
            .zip(points)
            .map(|(t, &(x, y))| Sample {
                t: f64::from(t),
                x: x - 1.0,
                y,
                yaw: 0.0,
            })
            .collect()
    }

    /// As [`along_3x1`], with each leg from one point to the next (one second) cut into
    /// ten equal moves, so no move is longer than a tenth of the longest leg.
    fn dense_3x1(points: &[(f64, f64)]) -> Vec<Sample> {
        let mut samples = along_3x1(&points[..1]);
        for (k, pair) in (0..).zip(points.windows(2)) {
            let ((ax, ay), (bx, by)) = (pair[0], pair[1]);
            for i in 1..=10 {
                let f = f64::from(i) / 10.0;
                samples.push(Sample {
                    t: f64::from(k) + f,
                    x: ax + (bx - ax) * f - 1.0,
                    y: ay + (by - ay) * f,
                    yaw: 0.0,
                });
            }
        }
        samples
    }

    /// Drives along the solution from the start centre to the end centre at 0.5 m/s,
    /// sampled every 50 ms as the emulator's simulation steps are.
    fn solution_run(layout: &Layout) -> (Vec<Sample>, usize) {
        let grader = Grader::new(layout).unwrap();
        let grid = grader.maze.grid();
        let [sx, sy] = layout.start.cell;
        let [ex, ey] = layout.end.cell;
        let path = shortest_path(
            &grader.maze,
            grid.index(Cell::new(sx, sy)),
            grid.index(Cell::new(ex, ey)),
        )
        .unwrap();
        let maze_to_floor = grader.floor_to_maze.inverse();
        let waypoints: Vec<Sample> = (0..)
            .zip(&path)
            .map(|(k, &index)| {
                let c = grid.cell(index);
                let p = maze_to_floor
                    * Point2::new(
                        f64::from(c.x) * grader.cell_size,
                        f64::from(c.y) * grader.cell_size,
                    );
                Sample {
                    t: f64::from(k) * 2.0,
                    x: p.x,
                    y: p.y,
                    yaw: 0.0,
                }
            })
            .collect();
        let end = waypoints.last().unwrap().t;
        let samples = (0..=(end / 0.05).round() as u32)
            .map(|k| trajectory::interpolate(&waypoints, f64::from(k) * 0.05).unwrap())
            .collect();
        (samples, path.len())
    }

    #[test]
    fn a_perfect_run_along_the_solution_scores_spl_1() {
        let layout = course(9, 9, 42);
        let (samples, cells) = solution_run(&layout);
        let report = Grader::new(&layout)
            .unwrap()
            .grade(&samples, &GradeOptions::default());
        assert!(report.reached_end && report.complete);
        let shortest = report.shortest_length_m.unwrap();
        assert_eq!(shortest, (cells - 1) as f64);
        // End is reached half a cell before its centre, and corners are cut between samples
        let p = report.path_to_end_m.unwrap();
        assert!(p <= shortest - 0.5 + 1e-9, "{p} vs {shortest}");
        assert!((report.spl.unwrap() - 1.0).abs() < 1e-12, "{report:?}");
        assert_eq!((report.cells_visited, report.cells_revisited), (cells, 0));
        let line = report.line.unwrap();
        assert!(
            line.max_distance_m < 1e-9 && line.time_off_line_s == 0.0,
            "{line:?}"
        );
        assert_eq!((report.samples_off_floor, report.samples_off_grid), (0, 0));
        // 2 s a cell: End's edge is crossed after (cells - 1.5) cells
        let t = report.time_s.unwrap();
        assert!((t - 2.0 * (cells as f64 - 1.5)).abs() <= 0.05 + 1e-9, "{t}");
    }

    #[test]
    fn a_detour_scores_what_the_hand_calculation_says() {
        // The 3 x 1 course maze is one corridor: Start in cell 0, End in cell 2, so
        // l = 2 cells x 1 m = 2 m. The robot drives 0 -> 1 (1 m), back to 0.4 (0.6 m),
        // forward to 1 (0.6 m) and on to End's centre at 2 (1 m), a leg a second sampled
        // ten times: the first sample inside End's 1 m footprint is at x = 1.5, half-way
        // along the last leg (t = 3.5 s), so p = 2.7 m and SPL = 1 * 2 / max(2.7, 2).
        // Cells 0, 1, 0, 1, 2: 3 visited, 2 revisits.
        let layout = course(3, 1, 1);
        assert_eq!((layout.start.cell, layout.end.cell), ([0, 0], [2, 0]));
        let samples = dense_3x1(&[(0.0, 0.0), (1.0, 0.0), (0.4, 0.0), (1.0, 0.0), (2.0, 0.0)]);
        let report = Grader::new(&layout)
            .unwrap()
            .grade(&samples, &GradeOptions::default());
        assert!(report.complete, "{report:?}");
        assert_eq!(report.shortest_length_m, Some(2.0));
        assert!((report.path_to_end_m.unwrap() - 2.7).abs() < 1e-12);
        assert!(
            (report.spl.unwrap() - 2.0 / 2.7).abs() < 1e-12,
            "{report:?}"
        );
        assert_eq!(report.time_s, Some(3.5));
        assert_eq!((report.cells_visited, report.cells_revisited), (3, 2));
    }

    #[test]
    fn samples_that_jump_across_the_maze_are_never_complete_and_have_no_spl() {
        // the lie: a 9 x 9 run sampled a few times, each sample on the solution
        // but metres apart, reaches End along a chord through the maze
        let layout = course(9, 9, 42);
        let grader = Grader::new(&layout).unwrap();
        let (samples, _) = solution_run(&layout);
        // 0.025 m a sample: every 16th is 0.4 m on, every 40th a cell (1 m)
        let every = |n: usize| -> Vec<Sample> {
            let mut kept: Vec<Sample> = samples.iter().step_by(n).copied().collect();
            kept.push(*samples.last().unwrap());
            kept
        };
        let sparse = grader.grade(&every(40), &GradeOptions::default());
        assert!(sparse.reached_end, "what the samples show is kept");
        assert!(!sparse.complete, "{sparse:?}");
        assert_eq!(sparse.spl, None);
        assert!(sparse.sampling.jumps_over_max > 0, "{:?}", sparse.sampling);
        assert!((sparse.sampling.largest_jump_m - 1.0).abs() < 1e-9);
        let why = sparse.incomplete_reason.unwrap();
        assert!(why.starts_with("sampled too sparsely to grade"), "{why}");
        let across = [samples[0], *samples.last().unwrap()];
        let cut = grader.grade(&across, &GradeOptions::default());
        assert!(!cut.complete && cut.spl.is_none(), "{cut:?}");
        assert_eq!(cut.sampling.jumps_over_max, 1);
        let dense = grader.grade(&every(16), &GradeOptions::default());
        assert!(
            dense.complete && dense.incomplete_reason.is_none(),
            "{dense:?}"
        );
        assert!((dense.spl.unwrap() - 1.0).abs() < 1e-12, "{dense:?}");
        assert!((dense.sampling.largest_jump_m - 0.4).abs() < 1e-9);
        assert_eq!(dense.sampling.max_jump_m, 0.5);
    }

    #[test]
    fn a_followed_run_that_ended_early_says_so_before_the_grade_s_own_reason() {
        let layout = course(3, 1, 1);
        let grader = Grader::new(&layout).unwrap();
        let mut sparse = grader.grade(
            &along_3x1(&[(0.0, 0.0), (2.0, 0.0)]),
            &GradeOptions::default(),
        );
        sparse.followed(Some("interrupted".into()), Some(1.5));
        let why = sparse.incomplete_reason.unwrap();
        assert!(
            why.starts_with("interrupted; sampled too sparsely"),
            "{why}"
        );
        assert_eq!(sparse.wall_time_s, Some(1.5));
        let mut dense = grader.grade(
            &dense_3x1(&[(0.0, 0.0), (2.0, 0.0)]),
            &GradeOptions::default(),
        );
        dense.followed(None, None);
        assert!(dense.complete && dense.incomplete_reason.is_none());
        dense.followed(Some("interrupted".into()), None);
        assert_eq!(
            (dense.complete, dense.incomplete_reason.as_deref()),
            (false, Some("interrupted"))
        );
    }

    #[test]
    fn a_run_that_stops_short_scores_0_and_time_off_the_line_is_counted() {
        // 0.3 m beside the line's centre (0.05 m half-width): 0.25 m off the paint, from
        // t = 1 to t = 3; the run ends in cell 1, no sample more than half a cell on.
        let layout = course(3, 1, 1);
        let samples = along_3x1(&[(0.0, 0.0), (0.3, 0.3), (0.7, 0.3), (0.7, 0.0)]);
        let report = Grader::new(&layout)
            .unwrap()
            .grade(&samples, &GradeOptions::default());
        assert!(!report.reached_end && report.complete);
        assert_eq!(
            (report.spl, report.time_s, report.path_to_end_m),
            (Some(0.0), None, None)
        );
        let line = report.line.unwrap();
        assert!((line.max_distance_m - 0.25).abs() < 1e-12, "{line:?}");
        assert!((line.mean_distance_m - 0.5 / 4.0).abs() < 1e-12, "{line:?}");
        assert_eq!(line.time_off_line_s, 2.0);
    }

    #[test]
    fn segments_meet_rectangles_or_keep_their_distance() {
        let r = [0.0, 0.0, 1.0, 1.0];
        let p = |x, y| Point2::new(x, y);
        assert_eq!(segment_rect(p(-1.0, 0.5), p(2.0, 0.5), &r), 0.0);
        assert_eq!(segment_rect(p(0.5, 0.5), p(0.5, 0.5), &r), 0.0);
        assert!((segment_rect(p(-1.0, 2.0), p(2.0, 2.0), &r) - 1.0).abs() < 1e-12);
        // passes the corner (1, 1) at sqrt(2)/2 * 0.5
        let d = segment_rect(p(1.0, 2.5), p(2.5, 1.0), &r);
        assert!((d - 1.5 / 2f64.sqrt()).abs() < 1e-12, "{d}");
        assert!((segment_rect(p(3.0, 0.5), p(3.0, 0.5), &r) - 2.0).abs() < 1e-12);
    }

    #[test]
    fn a_robot_off_the_floor_is_reported_not_a_crash() {
        let layout = course(3, 1, 1);
        let samples = along_3x1(&[(40.0, 40.0), (0.0, 0.0), (2.0, 0.0)]);
        let report = Grader::new(&layout)
            .unwrap()
            .grade(&samples, &GradeOptions::default());
        assert_eq!((report.samples_off_floor, report.samples_off_grid), (1, 1));
        assert!(report.reached_end);
        assert_eq!(
            (report.start_cell, report.shortest_length_m, report.spl),
            (None, None, None)
        );
        let empty = Grader::new(&layout)
            .unwrap()
            .grade(&[], &GradeOptions::default());
        assert_eq!(
            (empty.samples, empty.reached_end, empty.path_length_m),
            (0, false, 0.0)
        );
    }

    #[test]
    fn cutting_through_a_wall_is_a_contact() {
        // 3 x 1 walled corridor, walls 0.05 m thick: the south wall's paint starts at
        // y = -0.475. A robot of radius 0.1 m at y = -0.45 overlaps it by 0.075 m; on the
        // centre line it keeps 0.5 - 0.025 - 0.1 = 0.375 m clear.
        let layout = crate::layout::runs::tests::wall_layout(3, 1, 1, 0.0, "none");
        let grader = Grader::new(&layout).unwrap();
        let options = GradeOptions {
            robot_radius: 0.1,
            end_size: None,
        };
        let clean = grader.grade(&along_3x1(&[(0.0, 0.0), (2.0, 0.0)]), &options);
        let walls = clean.walls.unwrap();
        assert!(
            (walls.closest_approach_m - 0.375).abs() < 1e-12,
            "{walls:?}"
        );
        assert_eq!(walls.contacts, 0);
        assert!(clean.line.is_none());
        let samples = along_3x1(&[
            (0.0, 0.0),
            (1.0, 0.0),
            (1.0, -0.45),
            (1.0, 0.0),
            (1.0, -0.6),
            (2.0, 0.0),
        ]);
        // the second dip passes through the wall between two samples (-0.6 is beyond
        // it): the way between them meets the wall, a clearance of -0.1 m (the radius)
        let walls = grader.grade(&samples, &options).walls.unwrap();
        assert!((walls.closest_approach_m + 0.1).abs() < 1e-12, "{walls:?}");
        assert_eq!(walls.contacts, 2);
    }
}
