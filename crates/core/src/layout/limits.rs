//! The ranges every number of a layout lies in: one place that `generate` (before it
//! allocates anything) and `validate` (on what it reads) both check against, so
//! `generate` can never write a layout that `validate` rejects.
//!
//! | quantity | option ([`Opt`]) | layout field | range |
//! |---|---|---|---|
//! | cell side | `--cell-size` | `grid.cell_size` | 0.001..10000 m, and at least line length - line width |
//! | line length | `--line-length` | `line.length` | 0.001..10000 m, and at least (cell + width) / 64 |
//! | line width | `--line-width` | `line.width` | 0.001..10000 m, and less than the cell side |
//! | line height | `--line-z` | `line.z` | 1e-6..0.05 m |
//! | marker height | `--marker-z` | `start.pose.z`, `end.pose.z` | 1e-6..0.05 m, and above the lines |
//! | rotation | `--rotation` | `grid.rotation` | any finite angle (stored folded into one turn either way) |
//! | origin | `--origin` | `grid.origin` | -5000..5000 m on each axis |
//! | floor | `--floor-size` | `floor.size` | 0.001..10000 m on each axis |
//! | braid | `--braid` | `generator.options.braid` | 0..1 |
//!
//! Lower bounds are whole micrometres, so a value in range stays in range after the
//! writer rounds it to the micrometre.

use std::fmt;

use super::geometry::Geometry;
use crate::maze::Grid;
use crate::wording::{Message, Opt, Value};

/// The largest floor side, metres: 10 km, the smallest round size that still holds the
/// largest grid (4096x4096) at the course's 1 m cells (a 4100 m floor), far beyond any
/// simulated course (10 m), and small enough that every coordinate keeps picometre
/// precision in an `f64`.
pub const MAX_FLOOR: f64 = 10_000.0;
/// The smallest cell side, line length, line width and floor side, metres: 1 mm, a
/// hundred times the tolerance segment checks work to.
pub const MIN_LENGTH: f64 = 0.001;
/// The lowest line or marker, metres: they lie above the floor, and the layout stores
/// micrometres.
pub const MIN_HEIGHT: f64 = 1e-6;
/// The highest line or marker, metres: lines are marks on the floor (the course uses
/// 1 mm and 2 mm); 5 cm is already an obstacle for a small robot.
pub const MAX_HEIGHT: f64 = 0.05;
/// The most copies of the line template one passage may take (the course takes 2).
pub const MAX_SEGMENTS_PER_PASSAGE: usize = 64;
/// The most segments a layout may hold: enough for the course template on the largest
/// (4096x4096) grid even fully braided, and a bound on memory (32 bytes a segment).
pub const MAX_SEGMENTS: u64 = 1 << 26;
/// The largest error the writer's rounding puts into one stored number: half a
/// micrometre (or microradian).
pub const ROUNDING: f64 = 0.5e-6;
/// Position tolerance of the segment checks, in the maze frame: 10 micrometres, well
/// above what rounding can do to a position (`ROUNDING` on each axis, at most 0.71 um
/// in all) and well below the smallest cell ([`MIN_LENGTH`]).
pub const SEGMENT_TOLERANCE: f64 = 1e-5;

/// The range a quantity must lie in, both ends included.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Range {
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
    /// Unit printed after the range (`"m"`, `"rad"` or empty).
    pub unit: &'static str,
}

impl Range {
    /// `true` if `value` is finite and within the range.
    pub fn contains(&self, value: f64) -> bool {
        value.is_finite() && value >= self.min && value <= self.max
    }
}

impl fmt::Display for Range {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}..{}", show(self.min), show(self.max))?;
        if !self.unit.is_empty() {
            write!(f, " {}", self.unit)?;
        }
        Ok(())
    }
}

/// Cell side, line length, line width.
pub const LENGTH: Range = Range {
    min: MIN_LENGTH,
    max: MAX_FLOOR,
    unit: "m",
};
/// Line and marker heights.
pub const HEIGHT: Range = Range {
    min: MIN_HEIGHT,
    max: MAX_HEIGHT,
    unit: "m",
};
/// Each coordinate of the origin: the centre of cell (0, 0) lies on the largest floor.
pub const ORIGIN: Range = Range {
    min: -MAX_FLOOR / 2.0,
    max: MAX_FLOOR / 2.0,
    unit: "m",
};
/// Each side of the floor.
pub const FLOOR: Range = Range {
    min: MIN_LENGTH,
    max: MAX_FLOOR,
    unit: "m",
};
/// A stored rotation: one turn either way, at the microradian (generate folds any
/// finite angle into it).
#[allow(clippy::approx_constant)] // deliberately one turn at the microradian, as stored
pub const ROTATION: Range = Range {
    min: -6.283185,
    max: 6.283185,
    unit: "rad",
};
/// A stored heading (yaw) of a segment or marker: (-pi, pi] at the microradian
/// (pi rounds up to 3.141593).
#[allow(clippy::approx_constant)] // deliberately pi at the microradian, as stored
pub const YAW: Range = Range {
    min: -3.141593,
    max: 3.141593,
    unit: "rad",
};
/// The share of dead ends to braid away.
pub const BRAID: Range = Range {
    min: 0.0,
    max: 1.0,
    unit: "",
};

/// How quantities are named in messages: by `generate` option or by layout field.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Naming {
    /// By the option that sets it ([`Opt::CellSize`], ...), which each adapter words.
    Options,
    /// `grid.cell_size`, `line.z`, ...
    Layout,
}

/// The name of a quantity in a message.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Name {
    /// The option that sets it.
    Opt(Opt),
    /// One axis (`x`, `y`) of an option that sets a pair.
    Axis(Opt, &'static str),
    /// A layout field: `grid.cell_size`, `segments[3].yaw`.
    Field(String),
}

impl Name {
    /// The name alone.
    pub fn alone(&self) -> Message {
        match self {
            Name::Opt(opt) => Message::opt(*opt),
            Name::Axis(opt, axis) => Message::opt(*opt).and(format!(" {axis}")),
            Name::Field(field) => Message::text(field.clone()),
        }
    }

    /// The name with the value it has: `--line-z 0.001`, `line.z 0.001`.
    pub fn with(&self, value: &str) -> Message {
        match self {
            Name::Opt(opt) => Message::setting(*opt, Value::Number(value.to_string())),
            other => other.alone().and(format!(" {value}")),
        }
    }
}

impl From<&str> for Name {
    fn from(field: &str) -> Self {
        Name::Field(field.to_string())
    }
}

impl From<String> for Name {
    fn from(field: String) -> Self {
        Name::Field(field)
    }
}

impl fmt::Display for Name {
    /// A field as it is, an option in the neutral wording.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.alone().fmt(f)
    }
}

/// One number that is out of its range, or out of step with another.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Violation {
    /// The option or field, e.g. [`Opt::CellSize`] or `grid.cell_size`.
    pub name: Name,
    /// The value the message starts with, as shown (`0.4`), if it does.
    pub value: Option<String>,
    /// What is wrong, after the value: `is out of range 0.001..10000 m`.
    pub message: Message,
}

impl Violation {
    /// The whole line, as `generate` reports it: `--braid -0.5 is out of range 0..1`.
    pub fn line(&self) -> Message {
        let name = match &self.value {
            Some(value) => self.name.with(value),
            None => self.name.alone(),
        };
        name.and(" ").and_message(self.message.clone())
    }

    /// What is wrong, the value first (`0.4 is out of range 0.001..10000 m`): a layout
    /// problem's text, beside its field ([`Name`]'s `Display`).
    pub fn problem(&self) -> String {
        match &self.value {
            Some(value) => format!("{value} {}", self.message),
            None => self.message.to_string(),
        }
    }
}

impl fmt::Display for Violation {
    /// [`Violation::line`] in the neutral wording.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.line().fmt(f)
    }
}

fn violation(name: &Name, value: Option<String>, message: impl Into<Message>) -> Violation {
    Violation {
        name: name.clone(),
        value,
        message: message.into(),
    }
}

/// A number as messages print it: plain when of ordinary size, `1e308` or `1e-300`
/// otherwise (never three hundred digits).
pub fn show(value: f64) -> String {
    let magnitude = value.abs();
    if !value.is_finite() || magnitude == 0.0 || (1e-4..1e15).contains(&magnitude) {
        format!("{value}")
    } else {
        format!("{value:e}")
    }
}

/// `value` checked against `range`: `None` if inside.
pub fn check_range(name: impl Into<Name>, value: f64, range: Range) -> Option<Violation> {
    (!range.contains(value)).then(|| {
        violation(
            &name.into(),
            Some(show(value)),
            format!("is out of range {range}"),
        )
    })
}

/// A length: the message says "positive" first for zero, negative or non-finite values.
fn check_length(name: &Name, value: f64, range: Range) -> Option<Violation> {
    if !(value.is_finite() && value > 0.0) {
        return Some(violation(
            name,
            None,
            format!("must be a positive number of metres, not {}", show(value)),
        ));
    }
    check_range(name.clone(), value, range)
}

/// The share of dead ends to braid (`--braid`).
pub fn check_braid(braid: f64) -> Option<Violation> {
    check_range(Name::Opt(Opt::Braid), braid, BRAID).map(|mut v| {
        v.message = v.message.and(format!(
            ": braid is a share of the dead ends, and {} is not a number from 0 to 1",
            show(braid)
        ));
        v
    })
}

/// The names of the geometry's quantities.
struct Names {
    cell: Name,
    length: Name,
    width: Name,
    line_z: Name,
    marker_z: Name,
    origin: [Name; 2],
    rotation: Name,
}

fn names(naming: Naming) -> Names {
    match naming {
        Naming::Options => Names {
            cell: Name::Opt(Opt::CellSize),
            length: Name::Opt(Opt::LineLength),
            width: Name::Opt(Opt::LineWidth),
            line_z: Name::Opt(Opt::LineZ),
            marker_z: Name::Opt(Opt::MarkerZ),
            origin: [Name::Axis(Opt::Origin, "x"), Name::Axis(Opt::Origin, "y")],
            rotation: Name::Opt(Opt::Rotation),
        },
        Naming::Layout => Names {
            cell: "grid.cell_size".into(),
            length: "line.length".into(),
            width: "line.width".into(),
            line_z: "line.z".into(),
            marker_z: "start.pose.z".into(),
            origin: ["grid.origin[0]".into(), "grid.origin[1]".into()],
            rotation: "grid.rotation".into(),
        },
    }
}

/// The line template against the cell: every number in range, the line narrower than
/// a cell, a single copy no longer than a passage's cover (else it reaches over the
/// walls), at most [`MAX_SEGMENTS_PER_PASSAGE`] copies a passage, and the markers above
/// the lines. Relations are checked on the micrometre values a layout stores.
pub fn check_template(geometry: &Geometry, naming: Naming) -> Vec<Violation> {
    let n = names(naming);
    let mut found: Vec<Violation> = [
        check_length(&n.cell, geometry.cell_size, LENGTH),
        check_length(&n.length, geometry.line_length, LENGTH),
        check_length(&n.width, geometry.line_width, LENGTH),
    ]
    .into_iter()
    .flatten()
    .collect();
    let g = geometry.rounded();
    if found.is_empty() {
        found.extend(check_fit(&g, &n));
    }
    let heights: Vec<Violation> = [
        check_range(n.line_z.clone(), geometry.line_z, HEIGHT),
        check_range(n.marker_z.clone(), geometry.marker_z, HEIGHT),
    ]
    .into_iter()
    .flatten()
    .collect();
    if heights.is_empty() && g.marker_z <= g.line_z {
        found.push(violation(
            &n.marker_z,
            Some(show(g.marker_z)),
            Message::text("m is not above ")
                .and_message(n.line_z.with(&show(g.line_z)))
                .and(" m: the markers must lie on top of the lines"),
        ));
    }
    found.extend(heights);
    found
}

/// The line template against the cell, on in-range lengths.
fn check_fit(g: &Geometry, n: &Names) -> Option<Violation> {
    let (c, l, w) = (g.cell_size, g.line_length, g.line_width);
    if w >= c {
        Some(violation(
            &n.width,
            Some(show(w)),
            Message::text("m is not narrower than ")
                .and_message(n.cell.with(&show(c)))
                .and(" m: lines that wide paint over the walls between passages"),
        ))
    } else if l > c + w + 1e-9 {
        Some(violation(
            &n.cell,
            Some(show(c)),
            Message::text(format!(
                "m is too small for the line template: one {} m line would reach over the walls; a cell needs at least ",
                show(l)
            ))
            .and_message(n.length.alone())
            .and(" - ")
            .and_message(n.width.alone())
            .and(format!(" = {} m", show(round_um(l - w)))),
        ))
    } else if g.segments_per_passage() > MAX_SEGMENTS_PER_PASSAGE {
        Some(violation(
            &n.length,
            Some(show(l)),
            Message::text("m is too short for ")
                .and_message(n.cell.with(&show(c)))
                .and(format!(
                    " m: a passage would take {} copies of the line, at most {MAX_SEGMENTS_PER_PASSAGE} are allowed (the line needs at least (cell + width) / {MAX_SEGMENTS_PER_PASSAGE} = {} m)",
                    g.segments_per_passage(),
                    show((c + w) / MAX_SEGMENTS_PER_PASSAGE as f64)
                )),
        ))
    } else if l <= w + 2.0 * SEGMENT_TOLERANCE {
        // copies are spread by (c + w - l) / (n - 1); with l <= w some copy of one passage
        // lands exactly on a copy of the next where they meet at a cell centre
        Some(violation(
            &n.length,
            Some(show(l)),
            Message::text("m is not longer than ")
                .and_message(n.width.with(&show(w)))
                .and(" m: copies of so short a line land on each other where passages meet"),
        ))
    } else {
        None
    }
}

/// Where the maze lies: a finite rotation (any angle when generating, a folded one in a
/// layout) and an origin on the largest floor.
pub fn check_placement(geometry: &Geometry, naming: Naming) -> Vec<Violation> {
    let n = names(naming);
    let rotation = match naming {
        Naming::Options if !geometry.rotation.is_finite() => Some(violation(
            &n.rotation,
            Some(show(geometry.rotation)),
            "rad is not a finite angle",
        )),
        Naming::Options => None,
        Naming::Layout => check_range(n.rotation, geometry.rotation, ROTATION),
    };
    let [x, y] = n.origin;
    [
        rotation,
        check_range(x, geometry.origin[0], ORIGIN),
        check_range(y, geometry.origin[1], ORIGIN),
    ]
    .into_iter()
    .flatten()
    .collect()
}

/// A floor size, each side in [`FLOOR`].
pub fn check_floor(size: [f64; 2], naming: Naming) -> Vec<Violation> {
    let name = |axis: usize| match naming {
        Naming::Options => Name::Axis(Opt::FloorSize, ["x", "y"][axis]),
        Naming::Layout => ["floor.size[0]", "floor.size[1]"][axis].into(),
    };
    (0..2)
        .filter_map(|axis| check_length(&name(axis), size[axis], FLOOR))
        .collect()
}

/// How far a layout's computed floor extent may exceed the floor: the writer's rounding
/// of the origin (half a micrometre each way) and of the rotation (half a microradian,
/// which moves a grid corner by up to its distance from cell (0, 0)'s centre times
/// that), on both sides of the floor, and of the segment poses near its edge (under a
/// micrometre each way). A 25 m maze turned 180 degrees fits a 25 m floor.
pub fn floor_tolerance(geometry: &Geometry, grid: Grid) -> f64 {
    let h = geometry.cell_size / 2.0;
    let reach_x = f64::from(grid.width() - 1) * geometry.cell_size + h;
    let reach_y = f64::from(grid.height() - 1) * geometry.cell_size + h;
    let radius = reach_x.hypot(reach_y);
    8.0 * ROUNDING + 2.0 * radius * ROUNDING
}

/// How far a marker may lie from its cell centre, in the maze frame: the rounding of x
/// and y (`ROUNDING` each, so `ROUNDING * sqrt 2`) plus the rounding of the rotation
/// swinging a point `distance` metres from cell (0, 0)'s centre, plus float noise.
pub fn marker_tolerance(distance: f64) -> f64 {
    ROUNDING * std::f64::consts::SQRT_2 + distance * ROUNDING + 1e-9
}

/// The most segments a maze on `grid` can need with `per_passage` copies a passage:
/// a perfect maze has cells - 1 passages; braiding can open every wall between cells.
pub fn segments_bound(grid: Grid, braided: bool, per_passage: usize) -> u64 {
    let (w, h) = (u64::from(grid.width()), u64::from(grid.height()));
    let passages = if braided {
        w * (h - 1) + h * (w - 1)
    } else {
        w * h - 1
    };
    passages.saturating_mul(per_passage as u64)
}

fn round_um(value: f64) -> f64 {
    super::geometry::round_um(value)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layout::geometry::course;
    use crate::wording::testing::dashed;

    fn course_geometry() -> Geometry {
        Geometry::course(Grid::new(9, 9).unwrap())
    }

    #[test]
    fn the_course_is_in_range() {
        let g = course_geometry();
        assert!(check_template(&g, Naming::Options).is_empty());
        assert!(check_placement(&g, Naming::Layout).is_empty());
        assert!(check_floor([course::FLOOR_SIZE; 2], Naming::Layout).is_empty());
        assert!(check_braid(0.0).is_none() && check_braid(1.0).is_none());
    }

    #[test]
    fn messages_name_the_option_the_value_and_the_range() {
        assert_eq!(
            dashed(&check_braid(-0.5).unwrap().line()),
            "--braid -0.5 is out of range 0..1: braid is a share of the dead ends, and -0.5 is not a number from 0 to 1"
        );
        let mut g = course_geometry();
        g.cell_size = 1e308;
        assert_eq!(
            dashed(&check_template(&g, Naming::Options)[0].line()),
            "--cell-size 1e308 is out of range 0.001..10000 m"
        );
        g.cell_size = 0.4;
        let v = &check_template(&g, Naming::Options)[0];
        assert_eq!(v.name, Name::Opt(Opt::CellSize));
        assert!(
            dashed(&v.message).contains("at least --line-length - --line-width = 0.5 m"),
            "{v}"
        );
        g.cell_size = 1.0;
        g.line_width = 1.5;
        assert!(
            check_template(&g, Naming::Layout)[0]
                .to_string()
                .starts_with("line.width 1.5 m is not narrower than grid.cell_size 1 m")
        );
        g.line_width = 0.1;
        g.line_length = 0.01;
        assert!(
            check_template(&g, Naming::Options)[0]
                .message
                .to_string()
                .contains("110 copies")
        );
        g.line_length = 0.05;
        g.cell_size = 0.5;
        let v = &check_template(&g, Naming::Options)[0];
        assert!(
            v.name == Name::Opt(Opt::LineLength)
                && v.message.to_string().contains("not longer than"),
            "{v}"
        );
        g.cell_size = 1.0;
        g.line_length = 0.6;
        g.marker_z = 0.001;
        assert_eq!(
            check_template(&g, Naming::Layout)[0].name,
            "start.pose.z".into()
        );
        g.line_z = -5.0;
        assert_eq!(
            check_template(&g, Naming::Layout)[0].to_string(),
            "line.z -5 is out of range 1e-6..0.05 m"
        );
    }

    #[test]
    fn an_exact_fit_is_allowed() {
        let mut g = course_geometry();
        g.cell_size = 0.5; // 0.6 = 0.5 + 0.1: one copy covers the passage exactly
        assert!(check_template(&g, Naming::Options).is_empty());
        assert_eq!(g.segments_per_passage(), 1);
    }

    #[test]
    fn placement_and_floor() {
        let mut g = course_geometry();
        g.rotation = 1e308;
        assert!(check_placement(&g, Naming::Options).is_empty());
        assert_eq!(
            check_placement(&g, Naming::Layout)[0].name,
            "grid.rotation".into()
        );
        g.rotation = f64::NAN;
        assert!(
            check_placement(&g, Naming::Options)[0]
                .problem()
                .contains("not a finite angle")
        );
        g.rotation = 0.0;
        g.origin = [1e308, 0.0];
        assert_eq!(
            dashed(&check_placement(&g, Naming::Options)[0].line()),
            "--origin x 1e308 is out of range -5000..5000 m"
        );
        assert_eq!(
            check_floor([1e308, 10.0], Naming::Layout)[0].to_string(),
            "floor.size[0] 1e308 is out of range 0.001..10000 m"
        );
        assert!(
            check_floor([-1.0, 10.0], Naming::Layout)[0]
                .problem()
                .contains("positive number of metres, not -1")
        );
        assert_eq!(show(1e-300), "1e-300");
        assert_eq!(show(0.4), "0.4");
    }

    #[test]
    fn segment_bound_covers_the_course_on_the_largest_grid() {
        let grid = Grid::new(4096, 4096).unwrap();
        assert!(segments_bound(grid, true, 2) <= MAX_SEGMENTS);
        assert!(segments_bound(grid, false, 5) > MAX_SEGMENTS);
        assert_eq!(segments_bound(Grid::new(1, 1).unwrap(), true, 2), 0);
    }
}
