//! The pure geometry of a mesh maze: from a validated layout, one rectangle per maximal
//! straight run of lines ([`crate::layout::runs`]), or one box per wall run and per post,
//! split into meshes small enough to create quickly, each with a name that carries a
//! fingerprint of what it holds.
//!
//! Frame: every vertex is in the **Floor frame** (metres, as `f32`). A mesh is drawn with its
//! own frame on the Floor's (`createMeshShape` makes it at the world origin; the drawing then
//! sets its pose to the identity relative to the Floor), so its vertices read back relative to
//! the shape frame (`sim.getShapeMesh`) are the ones given here.

use nalgebra::{Isometry2, Point2, Vector2};

use crate::layout::runs::{OpenSides, for_each_run, for_each_wall_run, post_rect};
use crate::layout::sizes::{Sizes, TemplateUse};
use crate::layout::walls::WallAxis;
use crate::layout::{Layout, Pose, Style, passages};
use crate::maze::Grid;

/// The alias of the dummy under the maze dummy that holds a mesh maze's meshes.
pub const HOLDER: &str = "MazeMeshes";

/// What every mesh's name starts with: `MazeMesh_l_0123456789abcdef`.
pub const MESH_PREFIX: &str = "MazeMesh";

/// The most triangles one mesh holds: 500 rectangles. CoppeliaSim 4.5.1 created one mesh of
/// 500 rectangles in 148 ms and 20,000 rectangles as 40 such meshes in 2.44 s, while one mesh
/// of 1,000 took 428 ms and one of 20,000 6.1 to 9.2 s
/// (`../shared/spec/real-coppeliasim-4.5.1.md`, "One object instead of thousands").
pub const MAX_TRIANGLES: usize = 1000;

/// What a mesh holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum MeshKind {
    /// Flat rectangles at the line height, one per run of lines: static, not respondable.
    Lines,
    /// Boxes standing on the floor, one per wall run: static, respondable.
    Walls,
    /// Boxes standing on the floor, one per post: static, respondable.
    Posts,
}

impl MeshKind {
    /// The letter a mesh name carries: `l`, `w` or `p`.
    pub fn letter(self) -> char {
        match self {
            MeshKind::Lines => 'l',
            MeshKind::Walls => 'w',
            MeshKind::Posts => 'p',
        }
    }

    /// The kind a name's letter stands for.
    pub fn from_letter(c: char) -> Option<MeshKind> {
        match c {
            'l' => Some(MeshKind::Lines),
            'w' => Some(MeshKind::Walls),
            'p' => Some(MeshKind::Posts),
            _ => None,
        }
    }

    /// Boxes (walls, posts) collide with robots; lines are paint on the floor.
    pub fn respondable(self) -> bool {
        self != MeshKind::Lines
    }
}

/// One mesh to draw: triangles in the Floor frame.
#[derive(Debug, Clone, PartialEq)]
pub struct MazeMesh {
    /// What it holds.
    pub kind: MeshKind,
    /// x, y, z of each vertex, Floor frame, metres.
    pub vertices: Vec<f32>,
    /// Three vertex indices per triangle, counter-clockwise seen from outside.
    pub indices: Vec<i32>,
    /// The rectangles (lines) or boxes (walls, posts) it holds, Floor frame: each rectangle
    /// as its four corners' (x, y) and its z range (`z0 == z1` for a flat rectangle).
    pub pieces: Vec<Piece>,
    /// FNV-1a hash of the kind, the vertices' bits and the indices.
    pub fingerprint: u64,
}

/// A rectangle (flat, `bottom == top`) or a box (from `bottom` to `top`) in the Floor frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Piece {
    /// The footprint's corners, counter-clockwise seen from above.
    pub corners: [[f64; 2]; 4],
    /// Lowest z.
    pub bottom: f64,
    /// Highest z.
    pub top: f64,
}

impl MazeMesh {
    /// Its name (and alias): [`MESH_PREFIX`], the kind's letter and the fingerprint in hex.
    pub fn name(&self) -> String {
        mesh_name(self.kind, self.fingerprint)
    }

    /// Triangles it holds.
    pub fn triangles(&self) -> usize {
        self.indices.len() / 3
    }
}

/// The name of a mesh of `kind` with `fingerprint`: `MazeMesh_l_0123456789abcdef`.
pub fn mesh_name(kind: MeshKind, fingerprint: u64) -> String {
    format!("{MESH_PREFIX}_{}_{fingerprint:016x}", kind.letter())
}

/// The kind and fingerprint a mesh name carries, `None` for any other name. Accepts a path
/// (`/Maze/MazeMesh_l_...`) and a CoppeliaSim copy suffix is not a mesh of ours.
pub fn parse_mesh_name(name: &str) -> Option<(MeshKind, u64)> {
    let last = name.rsplit('/').next().unwrap_or(name);
    let rest = last.strip_prefix(MESH_PREFIX)?.strip_prefix('_')?;
    let (letter, hex) = rest.split_once('_')?;
    let mut letters = letter.chars();
    let kind = MeshKind::from_letter(letters.next()?)?;
    if letters.next().is_some() || hex.len() != 16 {
        return None;
    }
    let fingerprint = u64::from_str_radix(hex, 16).ok()?;
    Some((kind, fingerprint))
}

/// A layout drawn as meshes: the meshes, and where the template and markers go.
#[derive(Debug, Clone, PartialEq)]
#[non_exhaustive]
pub struct MeshMaze {
    /// Lines or walls.
    pub style: Style,
    /// The meshes, lines (or walls, then posts) in the runs' order.
    pub meshes: Vec<MazeMesh>,
    /// Line maze: where the `Line` template goes (the first segment, which a mesh covers),
    /// `None` for a maze without segments (the template then hides under `Start`) and for a
    /// wall maze (its template stays where the scene has it).
    pub template: Option<Pose>,
    /// Pose of the start marker.
    pub start: Pose,
    /// Pose of the end marker.
    pub end: Pose,
    /// The sizes the layout was generated for (the line template, which lies on the first
    /// line, and the markers must have them).
    pub sizes: Sizes,
}

impl MeshMaze {
    /// Rectangles and boxes in all meshes.
    pub fn pieces(&self) -> usize {
        self.meshes.iter().map(|m| m.pieces.len()).sum()
    }

    /// What this maze asks of the templates: a line maze's template lies on its first line,
    /// so it must have the layout's line size; walls and posts are boxes of the layout's
    /// sizes, whatever the `Wall` and `Post` templates measure (only their looks are read).
    pub fn template_use(&self) -> TemplateUse<'_> {
        TemplateUse {
            style: self.style,
            sizes: &self.sizes,
            template: self.template.is_some(),
            posts: false,
        }
    }
}

impl TryFrom<&Layout> for MeshMaze {
    type Error = crate::validate::Invalid;

    /// The meshes of a layout that passed [`crate::validate::checked`] (the one gate).
    fn try_from(layout: &Layout) -> Result<MeshMaze, Self::Error> {
        crate::validate::checked(layout)?;
        Ok(mesh_maze(layout))
    }
}

/// The meshes of a checked layout.
fn mesh_maze(layout: &Layout) -> MeshMaze {
    let grid = Grid::new(layout.grid.columns.into(), layout.grid.rows.into())
        .expect("a checked layout has a grid");
    let maze = passages::decode(grid, &layout.passages).expect("a checked layout decodes");
    let iso = Isometry2::new(
        Vector2::new(layout.grid.origin[0], layout.grid.origin[1]),
        layout.grid.rotation,
    );
    let c = layout.grid.cell_size;
    let mut builder = Builder::new(iso);
    match (&layout.style, &layout.wall) {
        (Style::Walls, Some(wall)) => {
            let open = OpenSides::of(&maze, &wall.openings);
            // a run goes from corner to corner: posts, never thinner than the walls in a
            // valid layout, hide its ends
            let ends_hidden = layout.post.is_some();
            let Ok(()) = for_each_wall_run::<std::convert::Infallible>(
                &maze,
                &open,
                |run| {
                    let sides = if ends_hidden {
                        Sides::Long(run.axis)
                    } else {
                        Sides::All
                    };
                    builder.add(
                        MeshKind::Walls,
                        run.rect(c, wall.thickness),
                        (0.0, wall.height),
                        sides,
                    );
                    Ok(())
                },
                |_| {},
            );
            if let Some(post) = &layout.post {
                for j in 0..=grid.height() {
                    for i in 0..=grid.width() {
                        let rect = post_rect([i, j], c, post.size);
                        builder.add(MeshKind::Posts, rect, (0.0, wall.height), Sides::All);
                    }
                }
            }
        }
        _ => {
            let (w, z) = (layout.line.width, layout.line.z);
            let Ok(()) = for_each_run::<std::convert::Infallible>(
                &maze,
                |run| {
                    builder.add(MeshKind::Lines, run.rect(c, w), (z, z), Sides::All);
                    Ok(())
                },
                |_| {},
            );
        }
    }
    MeshMaze {
        style: layout.style,
        meshes: builder.finish(),
        template: (layout.style == Style::Lines)
            .then(|| layout.segments.first().copied())
            .flatten(),
        start: layout.start.pose,
        end: layout.end.pose,
        sizes: Sizes::of(layout),
    }
}

/// The sides a box is drawn with, besides its top. What is never seen is left out, since
/// CoppeliaSim 4.10 takes about 20 µs a triangle to create a mesh (`docs/measurements.md`
/// "Creating meshes on 4.10"): the bottom, on the floor, always; the ends of a wall run where
/// posts hide them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Sides {
    /// All four sides: a post, or a wall run whose ends show.
    All,
    /// The two long sides of a wall run along this axis: its ends lie inside posts.
    Long(WallAxis),
}

impl Sides {
    /// Whether side `k` (0: y0, 1: x1, 2: y1, 3: x0) is drawn.
    fn draws(self, k: i32) -> bool {
        match self {
            Sides::All => true,
            Sides::Long(WallAxis::AlongX) => k % 2 == 0,
            Sides::Long(WallAxis::AlongY) => k % 2 == 1,
        }
    }
}

/// Collects pieces into meshes of at most [`MAX_TRIANGLES`] triangles, one kind per mesh.
struct Builder {
    iso: Isometry2<f64>,
    done: Vec<MazeMesh>,
    open: Option<MazeMesh>,
}

impl Builder {
    fn new(iso: Isometry2<f64>) -> Self {
        Builder {
            iso,
            done: Vec::new(),
            open: None,
        }
    }

    /// Adds the maze-frame rectangle `[x0, y0, x1, y1]` as a flat rectangle at `bottom`
    /// (`bottom == top`) or a box from `bottom` to `top` with its top and `sides` (never its
    /// bottom, which stands on the floor).
    fn add(
        &mut self,
        kind: MeshKind,
        [x0, y0, x1, y1]: [f64; 4],
        (bottom, top): (f64, f64),
        sides: Sides,
    ) {
        let flat = bottom == top;
        // side k runs from corner k to corner k + 1: the y0, x1, y1 and x0 sides
        let drawn = (0..4).filter(move |&k| sides.draws(k));
        let triangles = if flat {
            2
        } else {
            2 + 2 * drawn.clone().count()
        };
        let fits = self
            .open
            .as_ref()
            .is_some_and(|m| m.kind == kind && m.triangles() + triangles <= MAX_TRIANGLES);
        if !fits {
            self.close();
            self.open = Some(MazeMesh {
                kind,
                vertices: Vec::new(),
                indices: Vec::new(),
                pieces: Vec::new(),
                fingerprint: 0,
            });
        }
        let corners = [[x0, y0], [x1, y0], [x1, y1], [x0, y1]].map(|[x, y]| {
            let p = self.iso * Point2::new(x, y);
            [p.x, p.y]
        });
        let mesh = self.open.as_mut().expect("opened above");
        let base = (mesh.vertices.len() / 3) as i32;
        let mut push = |z: f64| {
            for [x, y] in corners {
                mesh.vertices.extend([x as f32, y as f32, z as f32]);
            }
        };
        push(bottom);
        if flat {
            mesh.indices.extend([0, 1, 2, 0, 2, 3].map(|i| base + i));
        } else {
            push(top);
            let mut faces = vec![4, 5, 6, 4, 6, 7];
            for i in drawn {
                let j = (i + 1) % 4;
                faces.extend([i, j, j + 4, i, j + 4, i + 4]);
            }
            mesh.indices.extend(faces.into_iter().map(|i| base + i));
        }
        mesh.pieces.push(Piece {
            corners,
            bottom,
            top,
        });
    }

    fn close(&mut self) {
        if let Some(mut mesh) = self.open.take() {
            mesh.fingerprint = fingerprint(mesh.kind, &mesh.vertices, &mesh.indices);
            self.done.push(mesh);
        }
    }

    fn finish(mut self) -> Vec<MazeMesh> {
        self.close();
        self.done
    }
}

/// FNV-1a (64 bits) of the kind's letter, every vertex's `f32` bits and every index: the
/// same mesh always has the same fingerprint, on every platform and Rust version.
pub fn fingerprint(kind: MeshKind, vertices: &[f32], indices: &[i32]) -> u64 {
    const OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;
    let mut hash = OFFSET;
    let mut eat = |bytes: &[u8]| {
        for &b in bytes {
            hash ^= u64::from(b);
            hash = hash.wrapping_mul(PRIME);
        }
    };
    eat(&[kind.letter() as u8]);
    for v in vertices {
        eat(&v.to_bits().to_le_bytes());
    }
    for i in indices {
        eat(&i.to_le_bytes());
    }
    hash
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::generate::Algorithm;
    use crate::layout::runs::tests::{count_runs, count_wall_runs, wall_layout};
    use crate::layout::{GenerateSpec, build_layout};

    fn line_layout(w: u32, h: u32, seed: u64, degrees: f64) -> Layout {
        let grid = Grid::new(w.into(), h.into()).unwrap();
        let mut spec = GenerateSpec::course(grid, Algorithm::Prim, seed);
        spec.geometry.rotation = degrees.to_radians();
        build_layout(&spec).unwrap()
    }

    #[test]
    fn one_rectangle_per_run_in_meshes_of_at_most_500() {
        let layout = line_layout(40, 30, 7, 0.0);
        let m = MeshMaze::try_from(&layout).unwrap();
        let grid = Grid::new(40, 30).unwrap();
        let maze = passages::decode(grid, &layout.passages).unwrap();
        assert_eq!(m.pieces(), count_runs(&maze));
        assert!(m.meshes.len() >= 2);
        for mesh in &m.meshes {
            assert_eq!(mesh.kind, MeshKind::Lines);
            assert!(mesh.triangles() <= MAX_TRIANGLES);
            assert_eq!(mesh.vertices.len(), mesh.pieces.len() * 12);
            assert_eq!(mesh.triangles(), mesh.pieces.len() * 2);
            assert!(mesh.vertices.chunks(3).all(|v| v[2] == 0.001));
            assert_eq!(
                parse_mesh_name(&mesh.name()),
                Some((mesh.kind, mesh.fingerprint))
            );
        }
        assert_eq!(m.template, Some(layout.segments[0]));
        // a mesh is its contents: another maze, other fingerprints
        let other = MeshMaze::try_from(&line_layout(40, 30, 8, 0.0)).unwrap();
        assert_ne!(other.meshes[0].fingerprint, m.meshes[0].fingerprint);
        assert_eq!(MeshMaze::try_from(&layout).unwrap(), m);
    }

    #[test]
    fn rectangles_lie_where_the_rotated_maze_lies_and_face_up() {
        let layout = line_layout(3, 2, 1, 90.0);
        let m = MeshMaze::try_from(&layout).unwrap();
        for mesh in &m.meshes {
            for t in mesh.indices.chunks(3) {
                let v = |k: i32| {
                    let k = k as usize * 3;
                    let p = &mesh.vertices[k..k + 3];
                    [f64::from(p[0]), f64::from(p[1])]
                };
                let (a, b, c) = (v(t[0]), v(t[1]), v(t[2]));
                let cross = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
                assert!(cross > 0.0, "a triangle faces down");
            }
        }
        // every segment's centre lies inside some rectangle
        for s in &layout.segments {
            let inside = m.meshes.iter().flat_map(|mesh| &mesh.pieces).any(|p| {
                let xs = p.corners.map(|c| c[0]);
                let ys = p.corners.map(|c| c[1]);
                let min = |a: [f64; 4]| a.iter().copied().fold(f64::INFINITY, f64::min);
                let max = |a: [f64; 4]| a.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                (min(xs) - 1e-6..=max(xs) + 1e-6).contains(&s.x)
                    && (min(ys) - 1e-6..=max(ys) + 1e-6).contains(&s.y)
            });
            assert!(inside, "{s:?}");
        }
    }

    /// Directed edges of `mesh`'s triangles, counted.
    fn edges(mesh: &MazeMesh) -> std::collections::HashMap<(i32, i32), usize> {
        let mut edges = std::collections::HashMap::new();
        for t in mesh.indices.chunks(3) {
            for k in 0..3 {
                *edges.entry((t[k], t[(k + 1) % 3])).or_insert(0) += 1;
            }
        }
        edges
    }

    /// Whether the edge from vertex `a` to `b` of `mesh` lies on the floor (z = 0).
    fn on_floor(mesh: &MazeMesh, (a, b): (i32, i32)) -> bool {
        let z = |k: i32| mesh.vertices[k as usize * 3 + 2];
        z(a) == 0.0 && z(b) == 0.0
    }

    #[test]
    fn walls_without_posts_are_boxes_open_only_at_the_floor() {
        let layout = wall_layout(5, 4, 3, 0.0, "start");
        assert!(layout.post.is_none());
        let m = MeshMaze::try_from(&layout).unwrap();
        let grid = Grid::new(5, 4).unwrap();
        let maze = passages::decode(grid, &layout.passages).unwrap();
        let openings = &layout.wall.as_ref().unwrap().openings;
        assert_eq!(m.pieces(), count_wall_runs(&maze, openings));
        assert!(m.meshes.iter().all(|mesh| mesh.kind == MeshKind::Walls));
        assert_eq!(m.template, None);
        let mesh = &m.meshes[0];
        // the top and four sides: a run's ends show where no post hides them
        assert_eq!(mesh.triangles(), mesh.pieces.len() * 10);
        // every edge above the floor is shared by two triangles, in opposite directions; the
        // bottom, which stands on the floor, is left out
        let edges = edges(mesh);
        for (&(a, b), &n) in &edges {
            let twin = edges.get(&(b, a)).copied();
            assert_eq!(n, 1);
            assert!(
                twin == Some(1) || on_floor(mesh, (a, b)),
                "open edge {a}-{b}"
            );
        }
        let height = layout.wall.as_ref().unwrap().height as f32;
        assert!(
            mesh.vertices
                .chunks(3)
                .all(|v| v[2] == 0.0 || v[2] == height)
        );
    }

    /// A 5x4 wall maze with a post of side `post` at every corner.
    fn posts_layout(post: f64) -> Layout {
        let grid = Grid::new(5, 4).unwrap();
        let mut layout = build_layout(&GenerateSpec::course(grid, Algorithm::Prim, 3)).unwrap();
        let maze = passages::decode(grid, &layout.passages).unwrap();
        let defaults = crate::layout::walls::WallOptions::default();
        let options = crate::layout::walls::WallOptions {
            length: layout.grid.cell_size - post,
            posts: Some(post),
            ..defaults
        };
        crate::layout::walls::into_walls(&mut layout, &maze, &options, true).unwrap();
        layout
    }

    #[test]
    fn posts_hide_the_ends_of_wall_runs_and_nothing_else_is_left_out() {
        let thickness = crate::layout::walls::WallOptions::default().thickness;
        let m = MeshMaze::try_from(&posts_layout(thickness)).unwrap();
        assert!(m.meshes.iter().any(|mesh| mesh.kind == MeshKind::Posts));
        for mesh in &m.meshes {
            // walls: the top and the two long sides; posts: the top and four sides
            let per_piece = if mesh.kind == MeshKind::Walls { 6 } else { 10 };
            assert_eq!(
                mesh.triangles(),
                mesh.pieces.len() * per_piece,
                "{:?}",
                mesh.kind
            );
            for t in mesh.indices.chunks(3) {
                let v = |k: i32| &mesh.vertices[k as usize * 3..k as usize * 3 + 3];
                let (a, b, c) = (v(t[0]), v(t[1]), v(t[2]));
                let horizontal = a[2] == b[2] && b[2] == c[2];
                // no bottom: a horizontal triangle is a top
                assert!(!horizontal || a[2] > 0.0);
                if mesh.kind == MeshKind::Walls && !horizontal {
                    // a wall's side spans its length: along x or along y
                    let span = |i: usize| {
                        let xs = [a[i], b[i], c[i]];
                        xs.iter().copied().fold(f32::MIN, f32::max)
                            - xs.iter().copied().fold(f32::MAX, f32::min)
                    };
                    assert!(span(0).max(span(1)) > 2.0 * thickness as f32, "an end cap");
                }
            }
        }
    }

    #[test]
    fn names_parse_back_and_others_do_not() {
        let name = mesh_name(MeshKind::Posts, 0xfeed);
        assert_eq!(name, "MazeMesh_p_000000000000feed");
        assert_eq!(
            parse_mesh_name(&format!("/Maze/{name}")),
            Some((MeshKind::Posts, 0xfeed))
        );
        for no in [
            "MazeMesh",
            "MazeMesh_x_000000000000feed",
            "MazeMesh_p_feed",
            "MazeMesh_p_000000000000feed0",
            "MazeMesh_pp_000000000000feed",
            "Line0",
        ] {
            assert_eq!(parse_mesh_name(no), None, "{no}");
        }
        assert_ne!(
            fingerprint(MeshKind::Lines, &[0.0; 9], &[0, 1, 2]),
            fingerprint(MeshKind::Walls, &[0.0; 9], &[0, 1, 2])
        );
    }
}
