//! What every robot-simulator format (MJCF, SDF, URDF, Webots) writes: the maze as boxes in
//! the floor frame, taken from the mesh geometry ([`crate::mesh`]: one box per
//! maximal straight run of wall and one per post, one flat rectangle per run of lines), with
//! each box's centre, size and yaw, a name and the colour the pictures draw it in.
//!
//! The floor frame is the simulator's world frame: the floor is centred on its origin, the
//! maze lies where the layout's origin and rotation put it. Metres and radians throughout;
//! every number is written rounded to the nanometre (or nanoradian) by [`num`], so the same
//! layout always gives the same bytes.

use crate::layout::geometry::round_half_away;
use crate::layout::{Layout, Pose};
use crate::mesh::{MeshKind, MeshMaze, Piece};
use crate::render::figure::{self, Colour};

/// What a box is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Part {
    /// A maximal straight run of wall: collides.
    Wall,
    /// A post at a lattice corner: collides.
    Post,
    /// A maximal straight run of lines, painted on the floor: visual only.
    Line,
    /// The `Start` or `End` marker (or URDF's floor slab): visual only.
    Marker,
}

impl Part {
    /// Walls and posts stop robots; lines and markers are paint.
    pub fn collides(self) -> bool {
        matches!(self, Part::Wall | Part::Post)
    }

    /// The material name the formats give it.
    pub fn material(self) -> &'static str {
        match self {
            Part::Wall => "wall",
            Part::Post => "post",
            Part::Line => "line",
            Part::Marker => "marker",
        }
    }
}

/// One box in the floor frame.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Slab {
    /// Unique among the maze's boxes: `wall_0`, `post_3`, `line_12`, `start`, `end`.
    pub name: String,
    /// What it is.
    pub part: Part,
    /// Its centre, metres.
    pub centre: [f64; 3],
    /// Full extents along its own x, y and z, metres.
    pub size: [f64; 3],
    /// Rotation about z, radians.
    pub yaw: f64,
    /// Red, green, blue, 0..1.
    pub rgb: [f64; 3],
}

/// A maze ready to write in any of the robot-simulator formats.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Solids {
    /// Names the maze for the file's title: `dfs seed 3, 4x3 walls`.
    pub title: String,
    /// The floor's extents along x and y, metres, centred on the origin.
    pub floor: [f64; 2],
    /// The floor's colour.
    pub floor_rgb: [f64; 3],
    /// Walls (runs, then posts) or lines, in the mesh geometry's order.
    pub maze: Vec<Slab>,
    /// The start marker, named `start`.
    pub start: Slab,
    /// The end marker, named `end`.
    pub end: Slab,
}

impl Solids {
    /// The boxes of a layout that passed [`crate::validate::checked`], drawn as `maze`.
    ///
    /// Lines are boxes from the floor up to the line height (`line.z`), markers half a cell
    /// square from the floor up to the marker height, so each shows above what lies below.
    pub fn new(layout: &Layout, maze: &MeshMaze) -> Solids {
        let mut counts = [0usize; 3];
        let yaw = layout.grid.rotation;
        let slabs = maze
            .meshes
            .iter()
            .flat_map(|mesh| mesh.pieces.iter().map(move |piece| (mesh.kind, piece)));
        let mut boxes = Vec::new();
        for (kind, piece) in slabs {
            let (part, colour, index) = match kind {
                MeshKind::Walls => (Part::Wall, figure::WALL, 0),
                MeshKind::Posts => (Part::Post, figure::WALL, 1),
                MeshKind::Lines => (Part::Line, figure::LINE, 2),
            };
            let name = format!("{}_{}", part.material(), counts[index]);
            counts[index] += 1;
            boxes.push(slab(name, part, piece, yaw, colour));
        }
        let side = layout.grid.cell_size / 2.0;
        let g = &layout.generator;
        Solids {
            title: format!(
                "vrep-maze {} seed {}, {}x{} {}",
                g.algorithm,
                g.seed,
                layout.grid.columns,
                layout.grid.rows,
                layout.style.name()
            ),
            floor: layout.floor.size,
            floor_rgb: rgb(figure::FLOOR),
            maze: boxes,
            start: marker("start", maze.start, side, figure::START),
            end: marker("end", maze.end, side, figure::END),
        }
    }

    /// Every box: the maze's, then `start` and `end`.
    pub fn all(&self) -> impl Iterator<Item = &Slab> {
        self.maze.iter().chain([&self.start, &self.end])
    }
}

/// The box of a mesh piece (a flat rectangle becomes a box from the floor to its height).
fn slab(name: String, part: Part, piece: &Piece, yaw: f64, colour: Colour) -> Slab {
    let [a, b, _, d] = piece.corners;
    let centre = |k: usize| piece.corners.iter().map(|c| c[k]).sum::<f64>() / 4.0;
    let (bottom, top) = if part == Part::Line {
        (0.0, piece.top)
    } else {
        (piece.bottom, piece.top)
    };
    Slab {
        name,
        part,
        centre: [centre(0), centre(1), (bottom + top) / 2.0],
        size: [
            (b[0] - a[0]).hypot(b[1] - a[1]),
            (d[0] - a[0]).hypot(d[1] - a[1]),
            top - bottom,
        ],
        yaw,
        rgb: rgb(colour),
    }
}

/// A marker: a square of `side` from the floor up to the pose's height, turned as it is.
fn marker(name: &str, pose: Pose, side: f64, colour: Colour) -> Slab {
    Slab {
        name: name.to_string(),
        part: Part::Marker,
        centre: [pose.x, pose.y, pose.z / 2.0],
        size: [side, side, pose.z],
        yaw: pose.yaw,
        rgb: rgb(colour),
    }
}

/// A picture colour as red, green, blue in 0..1.
fn rgb(Colour(c): Colour) -> [f64; 3] {
    c.map(|v| f64::from(v) / 255.0)
}

/// `value` rounded to 1e-9 (a nanometre, a nanoradian) in Rust's shortest form: `0.1`, `-2`,
/// `0` (never `-0`).
pub(super) fn num(value: f64) -> String {
    let r = round_half_away(value * 1e9) / 1e9;
    format!("{}", if r == 0.0 { 0.0 } else { r })
}

/// Numbers separated by single spaces: `1 0.5 0`.
pub(super) fn nums(values: &[f64]) -> String {
    let mut out = String::new();
    for (i, v) in values.iter().enumerate() {
        if i > 0 {
            out.push(' ');
        }
        out.push_str(&num(*v));
    }
    out
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::generate::Algorithm;
    use crate::layout::runs::tests::wall_layout;
    use crate::layout::{GenerateSpec, build_layout};
    use crate::maze::Grid;

    /// A 4 x 3 line maze turned by `degrees`.
    pub(crate) fn line_layout(degrees: f64) -> Layout {
        let grid = Grid::new(4, 3).unwrap();
        let mut spec = GenerateSpec::course(grid, Algorithm::Prim, 5);
        spec.geometry.rotation = degrees.to_radians();
        build_layout(&spec).unwrap()
    }

    /// A 4 x 3 wall maze with posts as thick as the walls, turned by `degrees`.
    pub(crate) fn post_layout(degrees: f64) -> Layout {
        let grid = Grid::new(4, 3).unwrap();
        let mut spec = GenerateSpec::course(grid, Algorithm::Prim, 5);
        spec.geometry.rotation = degrees.to_radians();
        let mut layout = build_layout(&spec).unwrap();
        let maze = crate::layout::passages::decode(grid, &layout.passages).unwrap();
        let options = crate::layout::walls::WallOptions {
            length: 0.95,
            posts: Some(0.05),
            ..Default::default()
        };
        crate::layout::walls::into_walls(&mut layout, &maze, &options, true).unwrap();
        layout
    }

    /// The boxes of a layout.
    pub(crate) fn solids(layout: &Layout) -> Solids {
        Solids::new(layout, &MeshMaze::try_from(layout).unwrap())
    }

    #[test]
    fn numbers_are_short_rounded_and_never_negative_zero() {
        assert_eq!(num(0.1 + 0.2), "0.3");
        assert_eq!(num(-1e-12), "0");
        assert_eq!(num(2.0), "2");
        assert_eq!(num(-1.2345678915), "-1.234567892");
        assert_eq!(nums(&[1.0, 0.5, 0.0]), "1 0.5 0");
    }

    #[test]
    fn wall_boxes_stand_on_the_floor_at_the_maze_rotation() {
        let layout = wall_layout(5, 4, 3, 30.0, "start");
        let s = solids(&layout);
        let wall = layout.wall.as_ref().unwrap();
        assert!(s.maze.iter().all(|b| b.part == Part::Wall));
        for b in &s.maze {
            assert!((b.centre[2] - wall.height / 2.0).abs() < 1e-12);
            assert!((b.size[2] - wall.height).abs() < 1e-12);
            assert_eq!(b.yaw, layout.grid.rotation);
            // one side is the thickness, the other a whole number of cells
            let cells = b.size[0].max(b.size[1]) / layout.grid.cell_size;
            assert!((b.size[0].min(b.size[1]) - wall.thickness).abs() < 1e-9);
            assert!((cells - cells.round()).abs() < 1e-9, "{b:?}");
        }
        // the runs cover every wall of the layout, corner to corner
        let covered: f64 = s.maze.iter().map(|b| b.size[0].max(b.size[1])).sum();
        let expected = layout.walls.len() as f64 * layout.grid.cell_size;
        assert!((covered - expected).abs() < 1e-6, "{covered} vs {expected}");
        assert_eq!(s.start.name, "start");
        assert_eq!(
            [s.start.centre[0], s.start.centre[1]],
            [layout.start.pose.x, layout.start.pose.y]
        );
        assert_eq!(s.all().count(), s.maze.len() + 2);
    }

    #[test]
    fn posts_are_boxes_as_high_as_the_walls_at_every_corner() {
        let layout = post_layout(0.0);
        let s = solids(&layout);
        let posts: Vec<_> = s.maze.iter().filter(|b| b.part == Part::Post).collect();
        assert_eq!(posts.len(), layout.posts.len());
        assert_eq!(posts.len(), 5 * 4);
        for (b, p) in posts.iter().zip(&layout.posts) {
            assert!(b.part.collides());
            assert!((b.centre[0] - p.x).abs() < 1e-9 && (b.centre[1] - p.y).abs() < 1e-9);
            assert!((b.size[0] - 0.05).abs() < 1e-12 && (b.size[2] - 2.0 * p.z).abs() < 1e-9);
        }
        assert_eq!(posts[0].name, "post_0");
    }

    #[test]
    fn lines_are_thin_green_paint_and_names_are_unique() {
        let layout = line_layout(0.0);
        let s = solids(&layout);
        assert!(!s.maze.is_empty());
        for b in &s.maze {
            assert_eq!(b.part, Part::Line);
            assert!(!b.part.collides());
            assert_eq!(b.size[2], layout.line.z);
            assert_eq!(b.rgb, [0.0, 1.0, 0.0]);
            assert!((b.size[0].min(b.size[1]) - layout.line.width).abs() < 1e-12);
        }
        let mut names: Vec<_> = s.all().map(|b| b.name.as_str()).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), s.maze.len() + 2);
        assert_eq!(s.floor, layout.floor.size);
    }
}
