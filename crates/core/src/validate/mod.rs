//! Checking a layout: is it well formed, solvable, a tree (or honest about its loops),
//! drawn gap-free, and on the floor? Every problem found is reported, each naming what
//! and where.
//!
//! [`Validator`] checks a layout in one pass over its segments, as a
//! [`SegmentSink`]: the reader hands it each segment as it is read, so a layout of any
//! size is checked without its segments in memory. [`validate`] runs it on a layout in
//! memory.

mod coverage;
mod goal;
mod head;
mod robot;
mod segment;
mod walls;

use std::fmt;
use std::thread;

use crate::layout::json::SegmentSink;
use crate::layout::limits;
use crate::layout::{Layout, Pose, Style, passages};
use crate::maze::{Grid, Maze, Metrics};
use crate::wording::{Message, Opt, Setting, Value, Wording};

use coverage::Coverage;
pub use robot::{Between, Passage, narrowest_passage, robot_fit};

/// One thing wrong with a layout.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Problem {
    /// The field or object concerned, e.g. `segments[12]` or `end`.
    pub location: String,
    /// What is wrong; it can name an option (the one to generate the maze anew with).
    pub message: Message,
}

impl Problem {
    /// `location: message`, the message in `wording`'s words.
    pub fn worded(&self, wording: &dyn Wording) -> String {
        format!("{}: {}", self.location, self.message.worded(wording))
    }
}

impl fmt::Display for Problem {
    /// `location: message`, the message in the neutral wording.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}: {}", self.location, self.message)
    }
}

/// The outcome of validating a layout.
#[derive(Debug, Clone, PartialEq)]
pub struct Report {
    /// What is wrong (the first [`MAX_KEPT`]); empty when the layout is valid.
    pub problems: Vec<Problem>,
    /// Problems found beyond those kept.
    pub omitted: usize,
    /// The metrics measured on the passages (when start and end could be measured).
    pub metrics: Option<Metrics>,
}

impl Report {
    /// `true` if nothing is wrong.
    pub fn is_ok(&self) -> bool {
        self.problems.is_empty()
    }

    /// How many problems were found, kept or not.
    pub fn count(&self) -> usize {
        self.problems.len() + self.omitted
    }
}

/// The most problems a report keeps: a broken layout of millions of segments can have
/// millions, and the first ones say what is wrong.
pub const MAX_KEPT: usize = 10_000;

/// Collects problems as validation goes, keeping the first [`MAX_KEPT`].
#[derive(Debug, Default)]
struct Problems {
    kept: Vec<Problem>,
    omitted: usize,
}

impl Problems {
    /// A layout field out of its range or step ([`limits::Violation`] named by field).
    fn violation(&mut self, v: &limits::Violation) {
        self.add(v.name.to_string(), v.problem());
    }

    fn add(&mut self, location: impl Into<String>, message: impl Into<Message>) {
        if self.kept.len() < MAX_KEPT {
            self.kept.push(Problem {
                location: location.into(),
                message: message.into(),
            });
        } else {
            self.omitted += 1;
        }
    }

    /// These problems, then `other`'s.
    fn append(&mut self, other: Problems) {
        for problem in other.kept {
            self.add(problem.location, problem.message);
        }
        self.omitted += other.omitted;
    }
}

/// Grids from this many cells check their structure and route on a second thread while
/// the segments stream in.
const PARALLEL_CELLS: usize = 1 << 16;

/// Validates `layout` and measures it.
pub fn validate(layout: &Layout) -> Report {
    let mut validator = Validator::new(layout);
    for (index, pose) in layout.segments.iter().enumerate() {
        validator.segment(index, *pose);
    }
    validator.finish()
}

/// Validates a layout in one pass over its segments: made from the rest of the layout,
/// fed every segment (as a [`SegmentSink`]), then [`finish`](Validator::finish)ed.
pub struct Validator {
    /// Lines or walls: a wall layout has no segments.
    style: Style,
    /// The one cause of the many problems that follow, said first ([`cell_size_edited`]).
    cause: Problems,
    /// The generator's and the head's numbers.
    head: Problems,
    /// The segments' own numbers.
    numbers: Problems,
    number_checks: segment::Numbers,
    /// A number everything else depends on is wrong: only numbers are reported.
    blocking: bool,
    segments: usize,
    /// What is checked once the numbers are sound.
    placed: Option<Placed>,
}

/// When `grid.cell_size` disagrees with the cell size the start and end markers were placed
/// for (their distance over their cells' distance, whatever the rotation), as after a hand
/// edit: the line that says so and how to get a layout of that size. Every segment and
/// marker problem that follows has this one cause.
fn cell_size_edited(layout: &Layout) -> Option<Message> {
    let (a, b) = (&layout.start, &layout.end);
    let cells = (f64::from(a.cell[0]) - f64::from(b.cell[0]))
        .hypot(f64::from(a.cell[1]) - f64::from(b.cell[1]));
    let metres = (a.pose.x - b.pose.x).hypot(a.pose.y - b.pose.y);
    let placed_for = metres / cells;
    let size = layout.grid.cell_size;
    let differs = (placed_for - size).abs() > 1e-6 * size.abs().max(1.0);
    // and both markers are where their cells are with that size (not a hand-moved marker)
    let (sin, cos) = layout.grid.rotation.sin_cos();
    let [ox, oy] = layout.grid.origin;
    let fits = |e: &crate::layout::Endpoint| {
        let [cx, cy] = e.cell.map(|c| f64::from(c) * placed_for);
        (ox + cx * cos - cy * sin - e.pose.x).hypot(oy + cx * sin + cy * cos - e.pose.y) < 1e-3
    };
    let markers_fit = fits(a) && fits(b);
    let plausible = cells > 0.0 && placed_for.is_finite() && placed_for > 0.0 && size > 0.0;
    (plausible && differs && markers_fit).then(|| {
        Message::text(format!(
            "is {size} m, but the maze was made for cells of {} m (its start and end markers are that far apart): edit it back, or make the maze anew with `",
            (placed_for * 1e6).round() / 1e6
        ))
        .and_generate(vec![Setting {
            opt: Opt::CellSize,
            value: Value::number(size),
        }])
        .and("` and the rest of its options")
    })
}

/// The checks that need a sound geometry.
struct Placed {
    /// Grid, passages, endpoints: problems found from the head.
    found: Problems,
    /// Structure and route, measured beside the segments on big grids.
    route: Option<Route>,
    coverage: Option<Coverage>,
    /// Segments off their passages, found as they were placed.
    strays: Problems,
    /// A wall layout's walls and a goal region: problems found from the head.
    walls: Problems,
    floor: Option<(Problems, segment::Floor)>,
}

/// The structure and route checks, done now or on their own thread.
enum Route {
    Done(Problems, Option<Metrics>),
    Running(thread::JoinHandle<(Problems, Option<Metrics>)>),
}

impl Validator {
    /// Checks everything but the segments of `layout` (whose `segments` are ignored) and
    /// gets ready for them.
    pub fn new(layout: &Layout) -> Self {
        let mut head = Problems::default();
        head::check_generator(layout, &mut head);
        let geometry = head::check_numbers(layout, &mut head);
        let placed = geometry.map(|geometry| placed(layout, &geometry));
        let mut cause = Problems::default();
        if let Some(line) = cell_size_edited(layout) {
            cause.add("grid.cell_size", line);
        }
        Self {
            style: layout.style,
            cause,
            head,
            numbers: Problems::default(),
            number_checks: segment::Numbers::new(layout),
            blocking: placed.is_none(),
            segments: 0,
            placed,
        }
    }

    /// How many segments it was fed.
    pub fn segments(&self) -> usize {
        self.segments
    }

    /// The report: every problem, in the order of the layout's fields.
    pub fn finish(self) -> Report {
        let mut problems = self.cause;
        problems.append(self.head);
        if self.style == Style::Walls && self.segments > 0 {
            problems.add(
                "segments",
                format!(
                    "has {} line segment(s): a wall layout draws walls, so segments must be empty",
                    self.segments
                ),
            );
        }
        problems.append(self.numbers);
        let mut metrics = None;
        if let Some(placed) = self.placed.filter(|_| !self.blocking) {
            problems.append(placed.found);
            if let Some(route) = placed.route {
                let (found, measured) = match route {
                    Route::Done(found, measured) => (found, measured),
                    Route::Running(handle) => handle.join().unwrap_or_else(|panic| {
                        std::panic::resume_unwind(panic);
                    }),
                };
                problems.append(found);
                metrics = measured;
            }
            problems.append(placed.strays);
            if let Some(coverage) = placed.coverage {
                coverage.finish(&mut problems);
            }
            problems.append(placed.walls);
            if let Some((floor, _)) = placed.floor {
                problems.append(floor);
            }
        }
        Report {
            problems: problems.kept,
            omitted: problems.omitted,
            metrics,
        }
    }
}

impl SegmentSink for Validator {
    fn segment(&mut self, index: usize, pose: Pose) {
        self.segments += 1;
        if self.segments as u64 == limits::MAX_SEGMENTS + 1 {
            self.head.add(
                "segments",
                format!(
                    "holds more than {} segments, the most a layout may",
                    limits::MAX_SEGMENTS
                ),
            );
        }
        if !self.number_checks.check(index, &pose, &mut self.numbers) {
            self.blocking = true;
        }
        if self.blocking || self.segments as u64 > limits::MAX_SEGMENTS {
            return;
        }
        let Some(placed) = &mut self.placed else {
            return;
        };
        if let Some(coverage) = &mut placed.coverage {
            coverage.place(index, &pose, &mut placed.strays);
        }
        if let Some((problems, floor)) = &mut placed.floor {
            floor.check(index, &pose, problems);
        }
    }
}

/// The head's checks that need a sound geometry, and the segment checks made ready.
fn placed(layout: &Layout, geometry: &crate::layout::Geometry) -> Placed {
    let mut found = Problems::default();
    let grid = match Grid::new(layout.grid.columns.into(), layout.grid.rows.into()) {
        Ok(grid) => grid,
        Err(e) => {
            found.add("grid", e.to_string());
            return Placed {
                found,
                route: None,
                coverage: None,
                strays: Problems::default(),
                walls: Problems::default(),
                floor: None,
            };
        }
    };
    if let Err(e) = passages::check_encoding(&layout.passage_encoding) {
        found.add("passage_encoding", e);
    }
    let maze = match passages::decode(grid, &layout.passages) {
        Ok(maze) => Some(maze),
        Err(e) => {
            found.add("passages", e);
            None
        }
    };
    let start = head::check_endpoint(
        &layout.start.cell,
        &layout.start.pose,
        "start",
        grid,
        geometry,
        &mut found,
    );
    let end = head::check_endpoint(
        &layout.end.cell,
        &layout.end.pose,
        "end",
        grid,
        geometry,
        &mut found,
    );
    let mut floor = Problems::default();
    head::check_floor(layout, grid, geometry, &mut floor);
    let floor = Some((floor, segment::Floor::new(layout, grid, geometry)));
    let Some(maze) = maze else {
        return Placed {
            found,
            route: None,
            coverage: None,
            strays: Problems::default(),
            walls: Problems::default(),
            floor,
        };
    };
    let route = start_route(layout, &maze, start, end);
    let mut shape = Problems::default();
    walls::check_walls(layout, &maze, geometry, &mut shape);
    goal::check_goal(layout, &maze, &mut shape);
    let coverage = match layout.style {
        Style::Lines => Some(Coverage::new(maze, geometry, layout.line.length)),
        Style::Walls => None,
    };
    Placed {
        found,
        route: Some(route),
        coverage,
        strays: Problems::default(),
        walls: shape,
        floor,
    }
}

/// Starts the structure and route checks of `maze` against the layout's declared metrics,
/// from cell `start` to `end` (when both are sound): on their own thread on a big grid,
/// done at once on a small one.
fn start_route(layout: &Layout, maze: &Maze, start: Option<usize>, end: Option<usize>) -> Route {
    let declared = layout.metrics.clone();
    let route_of = move |maze: &Maze| {
        let mut found = Problems::default();
        head::check_structure(&declared, maze, &mut found);
        let measured = match (start, end) {
            (Some(start), Some(end)) => head::check_route(&declared, maze, start, end, &mut found),
            _ => None,
        };
        (found, measured)
    };
    if maze.grid().cell_count() >= PARALLEL_CELLS {
        let own = maze.clone();
        Route::Running(thread::spawn(move || route_of(&own)))
    } else {
        let (found, measured) = route_of(maze);
        Route::Done(found, measured)
    }
}

/// The most problems an error shows: the first ones say what is wrong, and a broken layout
/// can have millions.
pub const MAX_SHOWN: usize = 20;

/// A layout that failed [`validate`]. Every consumer of layouts (drawing, rendering, writing
/// a dataset) passes [`checked`] first and refuses with this, so nothing is ever drawn,
/// rendered or written from a layout that `vrep-maze validate` rejects.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("invalid layout ({} problem(s); `vrep-maze validate` lists them)", self.count())]
pub struct Invalid {
    /// What is wrong, in the order [`validate`] found it (the first [`MAX_KEPT`]).
    pub problems: Vec<Problem>,
    /// Problems found beyond those kept.
    pub omitted: usize,
}

impl Invalid {
    /// How many problems were found, kept or not.
    pub fn count(&self) -> usize {
        self.problems.len() + self.omitted
    }

    /// The first [`MAX_SHOWN`] problems, one per line in `wording`'s words, then how many
    /// more there are.
    pub fn shown(&self, wording: &dyn Wording) -> Vec<String> {
        let mut lines: Vec<String> = self
            .problems
            .iter()
            .take(MAX_SHOWN)
            .map(|p| p.worded(wording))
            .collect();
        let total = self.count();
        if total > MAX_SHOWN {
            lines.push(format!("... and {} more problem(s)", total - MAX_SHOWN));
        }
        lines
    }
}

impl Report {
    /// The metrics when nothing is wrong, else the problems as an [`Invalid`].
    pub fn into_result(self) -> Result<Option<Metrics>, Invalid> {
        if self.is_ok() {
            Ok(self.metrics)
        } else {
            Err(Invalid {
                problems: self.problems,
                omitted: self.omitted,
            })
        }
    }
}

/// The one gate every consumer of a layout passes: `Ok` when [`validate`] finds nothing.
pub fn checked(layout: &Layout) -> Result<(), Invalid> {
    validate(layout).into_result().map(|_| ())
}
