//! Course geometry: where cells, markers and line segments lie in the floor frame.
//!
//! The maze has its own frame: cell (i, j) is centred at (i * cell, j * cell). An
//! isometry (nalgebra) moves that frame onto the floor: translation = the floor position
//! of cell (0, 0), rotation = the maze's rotation about z.

use std::f64::consts::{PI, TAU};

use nalgebra::{Isometry2, Point2, Vector2};

use super::Pose;
use crate::maze::{Cell, Direction, Grid};

/// The course defaults (course-scene.md): 1 m cells, `Line` 0.6 m x 0.1 m at 1 mm,
/// markers at 2 mm.
pub mod course {
    /// Cell side, metres.
    pub const CELL_SIZE: f64 = 1.0;
    /// `Line` template length, metres.
    pub const LINE_LENGTH: f64 = 0.6;
    /// `Line` template width, metres.
    pub const LINE_WIDTH: f64 = 0.1;
    /// Height of lines above the floor, metres.
    pub const LINE_Z: f64 = 0.001;
    /// Height of `Start` and `End`, metres (above the lines, hiding them).
    pub const MARKER_Z: f64 = 0.002;
    /// The course floor: four 5 m panels.
    pub const FLOOR_SIZE: f64 = 10.0;
    /// Floor panel side, metres: automatic floors grow in whole panels.
    pub const FLOOR_PANEL: f64 = 5.0;
    /// Columns and rows of the course maze.
    pub const SIZE: u32 = 9;
}

/// Everything that turns cells and passages into floor poses.
#[derive(Debug, Clone, PartialEq)]
pub struct Geometry {
    /// Side of a cell, metres.
    pub cell_size: f64,
    /// Floor (x, y) of cell (0, 0)'s centre.
    pub origin: [f64; 2],
    /// Maze rotation about z, radians.
    pub rotation: f64,
    /// Line template length, metres.
    pub line_length: f64,
    /// Line template width, metres.
    pub line_width: f64,
    /// Height of lines, metres.
    pub line_z: f64,
    /// Height of the start and end markers, metres.
    pub marker_z: f64,
}

impl Geometry {
    /// Course geometry for `grid`, centred on the floor origin with cells on whole
    /// multiples of the cell size (for an even side the extra column or row goes to +x/+y).
    pub fn course(grid: Grid) -> Self {
        Self {
            cell_size: course::CELL_SIZE,
            origin: Self::centred_origin(grid, course::CELL_SIZE),
            rotation: 0.0,
            line_length: course::LINE_LENGTH,
            line_width: course::LINE_WIDTH,
            line_z: course::LINE_Z,
            marker_z: course::MARKER_Z,
        }
    }

    /// The origin that centres `grid` on the floor origin: cell (0, 0) at
    /// `-floor((n - 1) / 2) * cell_size` on each axis.
    pub fn centred_origin(grid: Grid, cell_size: f64) -> [f64; 2] {
        let half = |n: u32| -f64::from((n - 1) / 2) * cell_size;
        [half(grid.width()), half(grid.height())]
    }

    /// This geometry turned about the centre of `grid`: its `origin` is read as where cell
    /// (0, 0)'s centre lies before the turn, and moved so that the maze's centre (the middle
    /// of its cells) stays where the unturned maze has it. What `--rotation` does: on the
    /// course, `--rotation 90` turns the maze in place and it still fits the 10 m floor.
    /// Without a rotation the geometry is returned unchanged.
    pub fn turned_about_centre(mut self, grid: Grid) -> Self {
        if self.rotation == 0.0 {
            return self;
        }
        let centre = Vector2::new(
            f64::from(grid.width() - 1) * self.cell_size / 2.0,
            f64::from(grid.height() - 1) * self.cell_size / 2.0,
        );
        let turned = nalgebra::Rotation2::new(self.rotation) * centre;
        self.origin = [
            self.origin[0] + centre.x - turned.x,
            self.origin[1] + centre.y - turned.y,
        ];
        self
    }

    /// This geometry as a layout stores it: every length rounded to the micrometre and
    /// the rotation, folded into -2pi..2pi when beyond a full turn, to the microradian.
    /// Layouts are computed from these values, so what `validate` recomputes from the
    /// file is what was drawn, at any rotation.
    pub fn rounded(&self) -> Self {
        let rotation = if self.rotation.abs() > TAU {
            self.rotation % TAU
        } else {
            self.rotation
        };
        Self {
            cell_size: round_um(self.cell_size),
            origin: self.origin.map(round_um),
            rotation: round_um(rotation),
            line_length: round_um(self.line_length),
            line_width: round_um(self.line_width),
            line_z: round_um(self.line_z),
            marker_z: round_um(self.marker_z),
        }
    }

    /// The maze-to-floor isometry.
    pub fn maze_to_floor(&self) -> Isometry2<f64> {
        Isometry2::new(Vector2::new(self.origin[0], self.origin[1]), self.rotation)
    }

    /// Floor (x, y) of the centre of `cell`.
    pub fn cell_centre(&self, cell: Cell) -> Point2<f64> {
        self.maze_to_floor() * self.local_centre(cell)
    }

    /// Maze-frame (x, y) of the centre of `cell`.
    pub fn local_centre(&self, cell: Cell) -> Point2<f64> {
        Point2::new(
            f64::from(cell.x) * self.cell_size,
            f64::from(cell.y) * self.cell_size,
        )
    }

    /// The marker pose for `cell`.
    pub fn marker_pose(&self, cell: Cell) -> Pose {
        let centre = self.cell_centre(cell);
        Pose::rounded(centre.x, centre.y, self.marker_z, self.rotation)
    }

    /// Segments drawn per passage: `ceil((cell + width) / length)`, at least 1.
    pub fn segments_per_passage(&self) -> usize {
        let span = (self.cell_size + self.line_width) / self.line_length;
        // The epsilon keeps an exact fit (e.g. 1.2 / 0.6) from rounding up to one more.
        ((span - 1e-9).ceil() as usize).max(1)
    }

    /// Offsets along the passage, from the first cell's centre, of the segment centres:
    /// spread evenly so the segments cover from `width / 2` before one centre to
    /// `width / 2` past the other (0.25 and 0.75 for the course).
    pub fn segment_offsets(&self) -> Vec<f64> {
        let n = self.segments_per_passage();
        if n == 1 {
            return vec![self.cell_size / 2.0];
        }
        let first = self.line_length / 2.0 - self.line_width / 2.0;
        let last = self.cell_size + self.line_width / 2.0 - self.line_length / 2.0;
        let step = (last - first) / (n - 1) as f64;
        (0..n).map(|k| first + step * k as f64).collect()
    }

    /// Places the segments of passages with these `offsets` (see
    /// [`segment_offsets`](Self::segment_offsets)).
    pub fn passage_placer<'a>(&self, offsets: &'a [f64]) -> PassagePlacer<'a> {
        let rounded_yaw =
            |local_yaw: f64| Pose::rounded(0.0, 0.0, 0.0, local_yaw + self.rotation).yaw;
        PassagePlacer {
            iso: self.maze_to_floor(),
            cell_size: self.cell_size,
            z: round_um(self.line_z),
            yaw_along_x: rounded_yaw(0.0),
            yaw_along_y: rounded_yaw(PI / 2.0),
            offsets,
        }
    }

    /// The floor-frame corners of the rectangle the grid covers (cell edges, not centres).
    pub fn grid_corners(&self, grid: Grid) -> [Point2<f64>; 4] {
        let h = self.cell_size / 2.0;
        let max_x = f64::from(grid.width() - 1) * self.cell_size + h;
        let max_y = f64::from(grid.height() - 1) * self.cell_size + h;
        let iso = self.maze_to_floor();
        [
            iso * Point2::new(-h, -h),
            iso * Point2::new(max_x, -h),
            iso * Point2::new(max_x, max_y),
            iso * Point2::new(-h, max_y),
        ]
    }
}

/// Places the segments of passages ([`Geometry::passage_placer`]): the maze-to-floor
/// isometry (a sine and a cosine), the segments' height and their two headings, each
/// rounded once, so a segment costs one point transform and two roundings.
#[derive(Debug, Clone, Copy)]
pub struct PassagePlacer<'a> {
    iso: Isometry2<f64>,
    cell_size: f64,
    z: f64,
    yaw_along_x: f64,
    yaw_along_y: f64,
    offsets: &'a [f64],
}

impl<'a> PassagePlacer<'a> {
    /// Floor poses of the segments that draw the passage from `cell` towards `dir`, as
    /// [`Pose::rounded`] makes them.
    pub fn segments(self, cell: Cell, dir: Direction) -> impl Iterator<Item = Pose> + use<'a> {
        let start = Point2::new(
            f64::from(cell.x) * self.cell_size,
            f64::from(cell.y) * self.cell_size,
        );
        let (axis, yaw) = match dir {
            Direction::East => (Vector2::new(1.0, 0.0), self.yaw_along_x),
            Direction::North => (Vector2::new(0.0, 1.0), self.yaw_along_y),
            Direction::West => (Vector2::new(-1.0, 0.0), self.yaw_along_x),
            Direction::South => (Vector2::new(0.0, -1.0), self.yaw_along_y),
        };
        self.offsets.iter().map(move |&t| {
            let p = self.iso * (start + axis * t);
            Pose {
                x: round_um(p.x),
                y: round_um(p.y),
                z: self.z,
                yaw,
            }
        })
    }
}

/// An angle folded into (-pi, pi].
pub fn normalize_angle(angle: f64) -> f64 {
    if angle > -PI && angle <= PI {
        // Already in range: skip the (slow) remainder, which would return it unchanged.
        return angle;
    }
    let mut a = angle % (2.0 * PI);
    if a <= -PI {
        a += 2.0 * PI;
    } else if a > PI {
        a -= 2.0 * PI;
    }
    a
}

/// `value` rounded to the micrometre (or microradian), with -0 made 0: the only
/// precision a layout stores.
pub fn round_um(value: f64) -> f64 {
    let r = round_half_away(value * 1e6) / 1e6;
    if r == 0.0 { 0.0 } else { r }
}

/// `x.round()` (half away from zero), exactly, without the libm call that `f64::round`
/// is on baseline x86-64: the fraction `x - trunc(x)` is exact below 2^52.
pub(crate) fn round_half_away(x: f64) -> f64 {
    if x.is_nan() || x.abs() >= 4.5e15 {
        return x.round();
    }
    let whole = (x as i64 as f64).copysign(x);
    let fraction = x - whole;
    if fraction >= 0.5 {
        whole + 1.0
    } else if fraction <= -0.5 {
        whole - 1.0
    } else {
        whole
    }
}

impl Pose {
    /// A pose with every field rounded to the micrometre and the yaw folded into (-pi, pi].
    pub fn rounded(x: f64, y: f64, z: f64, yaw: f64) -> Self {
        let yaw = round_um(normalize_angle(yaw));
        // Rounding can push pi up past the fold point; fold again on the rounded value.
        let yaw = if yaw <= -round_um(PI) {
            round_um(PI)
        } else {
            yaw
        };
        Self {
            x: round_um(x),
            y: round_um(y),
            z: round_um(z),
            yaw,
        }
    }
}

/// The four corners (x, y) of a `length` x `width` rectangle centred on `pose`.
pub fn rectangle_corners(pose: &Pose, length: f64, width: f64) -> [Point2<f64>; 4] {
    let iso = Isometry2::new(Vector2::new(pose.x, pose.y), pose.yaw);
    let (l, w) = (length / 2.0, width / 2.0);
    [
        iso * Point2::new(-l, -w),
        iso * Point2::new(l, -w),
        iso * Point2::new(l, w),
        iso * Point2::new(-l, w),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn course_passage_has_two_segments_at_quarter_points() {
        let grid = Grid::new(9, 9).unwrap();
        let g = Geometry::course(grid);
        assert_eq!(g.origin, [-4.0, -4.0]);
        assert_eq!(g.segments_per_passage(), 2);
        let offsets = g.segment_offsets();
        assert!((offsets[0] - 0.25).abs() < 1e-12 && (offsets[1] - 0.75).abs() < 1e-12);
        let east: Vec<Pose> = g
            .passage_placer(&offsets)
            .segments(Cell::new(0, 0), Direction::East)
            .collect();
        assert_eq!(east[0], Pose::rounded(-3.75, -4.0, 0.001, 0.0));
        assert_eq!(east[1], Pose::rounded(-3.25, -4.0, 0.001, 0.0));
        let north: Vec<Pose> = g
            .passage_placer(&offsets)
            .segments(Cell::new(8, 8), Direction::South)
            .collect();
        assert_eq!(north[0].x, 4.0);
        assert_eq!(north[0].y, 3.75);
        assert_eq!(north[0].yaw, round_um(PI / 2.0));
        assert_eq!(north[0].yaw.to_string(), "1.570796");
    }

    #[test]
    fn segment_count_follows_the_formula() {
        let mut g = Geometry::course(Grid::new(2, 2).unwrap());
        g.line_length = 0.3;
        assert_eq!(g.segments_per_passage(), 4); // ceil(1.1 / 0.3)
        g.line_length = 0.55;
        assert_eq!(g.segments_per_passage(), 2); // exactly 1.1 / 0.55
        g.line_length = 2.0;
        assert_eq!(g.segment_offsets(), vec![0.5]);
    }

    #[test]
    fn a_turn_keeps_the_maze_centre_in_place() {
        let grid = Grid::new(9, 5).unwrap();
        let plain = Geometry::course(grid);
        assert_eq!(plain.clone().turned_about_centre(grid), plain);
        let centre = |g: &Geometry| {
            let a = g.cell_centre(Cell::new(0, 0));
            let b = g.cell_centre(Cell::new(8, 4));
            ((a.x + b.x) / 2.0, (a.y + b.y) / 2.0)
        };
        for degrees in [90.0f64, 45.0, -30.0, 180.0] {
            let mut g = Geometry::course(grid);
            g.rotation = degrees.to_radians();
            let turned = g.turned_about_centre(grid);
            let (x, y) = centre(&turned);
            let (x0, y0) = centre(&plain);
            assert!(
                (x - x0).abs() < 1e-12 && (y - y0).abs() < 1e-12,
                "{degrees}"
            );
        }
    }

    #[test]
    fn even_sides_and_rotation() {
        let g = Geometry::course(Grid::new(20, 15).unwrap());
        assert_eq!(g.origin, [-9.0, -7.0]);
        let mut r = Geometry::course(Grid::new(3, 3).unwrap());
        r.rotation = PI / 2.0;
        let c = r.cell_centre(Cell::new(1, 0));
        assert!(
            (c.x - -1.0).abs() < 1e-12 && (c.y - -0.0).abs() < 1e-12,
            "{c}"
        );
    }

    #[test]
    fn rounding_half_away_is_f64_round() {
        for x in [
            0.0,
            -0.0,
            0.5,
            -0.5,
            1.5,
            2.5,
            -2.5,
            0.499_999_999_999_999_94,
            1e15 + 0.5,
            4.6e15,
            -7.5e15,
            1e300,
            f64::NAN,
            f64::INFINITY,
            -1_234.499_999,
            1_234.500_000_1,
        ] {
            assert_eq!(round_half_away(x).to_bits(), x.round().to_bits(), "{x}");
        }
    }

    #[test]
    fn rounding_is_clean() {
        assert_eq!(round_um(0.1 + 0.2), 0.3);
        assert_eq!(round_um(-1e-9).to_string(), "0");
        assert_eq!(normalize_angle(3.0 * PI / 2.0), -PI / 2.0);
        assert_eq!(Pose::rounded(0.0, 0.0, 0.0, -PI).yaw, round_um(PI));
    }
}
