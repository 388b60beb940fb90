//! Comparing a mesh read back from a simulator with the one drawn: the same triangles, whatever
//! the vertex order and numbering (CoppeliaSim merges duplicate vertices when it creates a
//! mesh, so its vertices need not be the ones given).

use std::collections::{HashMap, HashSet};

use super::MazeMesh;

/// Vertices this close (metres, on every axis) are the same: CoppeliaSim merges vertices within
/// 1e-4 m, and `f32` keeps Floor coordinates to a few micrometres.
pub const VERTEX_TOLERANCE: f64 = 2e-4;

/// The differences between `wanted` and the triangles `vertices` / `indices` (relative to the
/// mesh's frame, which is the Floor's), `None` when they are the same triangles.
pub fn mesh_differences(wanted: &MazeMesh, vertices: &[f32], indices: &[i32]) -> Option<String> {
    let count = vertices.len() / 3;
    if !vertices.len().is_multiple_of(3)
        || !indices.len().is_multiple_of(3)
        || indices.iter().any(|&i| i < 0 || i as usize >= count)
    {
        return Some(format!(
            "is no mesh ({} coordinates, {} indices)",
            vertices.len(),
            indices.len()
        ));
    }
    let grid = VertexGrid::of(vertices);
    let find = |v: &[f32]| grid.find(v);
    let mut map = Vec::with_capacity(wanted.vertices.len() / 3);
    for v in wanted.vertices.chunks_exact(3) {
        match find(v) {
            Some(k) => map.push(k),
            None => {
                return Some(format!(
                    "has no vertex at ({:.4}, {:.4}, {:.4})",
                    v[0], v[1], v[2]
                ));
            }
        }
    }
    let drawn: HashSet<[usize; 3]> = wanted
        .indices
        .chunks_exact(3)
        .map(|t| canonical([0, 1, 2].map(|k| map[t[k] as usize])))
        .collect();
    // a read vertex stands for itself or the one it duplicates, as a drawn one does
    let same: Vec<usize> = vertices
        .chunks_exact(3)
        .enumerate()
        .map(|(k, v)| find(v).unwrap_or(k))
        .collect();
    let read: HashSet<[usize; 3]> = indices
        .chunks_exact(3)
        .map(|t| canonical([0, 1, 2].map(|k| same[t[k] as usize])))
        .collect();
    let missing = drawn.difference(&read).count();
    let extra = read.difference(&drawn).count();
    (missing + extra > 0).then(|| {
        format!(
            "differs: {missing} of its {} triangles missing, {extra} others",
            drawn.len()
        )
    })
}

/// Triangle `t` turned to start at its smallest index: the same triangle, whichever
/// vertex it was listed from, compares equal.
fn canonical(t: [usize; 3]) -> [usize; 3] {
    let s = (0..3).min_by_key(|&k| t[k]).unwrap_or(0);
    [t[s], t[(s + 1) % 3], t[(s + 2) % 3]]
}

/// A mesh's vertices in cells [`VERTEX_TOLERANCE`] wide, to find the one nearest a point.
struct VertexGrid<'a> {
    /// The vertices, x, y, z each.
    vertices: &'a [f32],
    /// The vertices' indices in each cell.
    cells: HashMap<[i64; 3], Vec<usize>>,
}

impl<'a> VertexGrid<'a> {
    /// The grid of `vertices` (x, y, z each).
    fn of(vertices: &'a [f32]) -> Self {
        let mut cells: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
        for (k, v) in vertices.chunks_exact(3).enumerate() {
            cells.entry(Self::cell(v)).or_default().push(k);
        }
        Self { vertices, cells }
    }

    /// The cell of point `v`.
    fn cell(v: &[f32]) -> [i64; 3] {
        let c = |x: f32| (f64::from(x) / VERTEX_TOLERANCE).floor() as i64;
        [c(v[0]), c(v[1]), c(v[2])]
    }

    /// The index of the vertex nearest `v` within [`VERTEX_TOLERANCE`] on every axis (of
    /// equally near ones, the first found), if any.
    fn find(&self, v: &[f32]) -> Option<usize> {
        let c = Self::cell(v);
        let mut best: Option<(f64, usize)> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    for &k in self
                        .cells
                        .get(&[c[0] + dx, c[1] + dy, c[2] + dz])
                        .into_iter()
                        .flatten()
                    {
                        let r = &self.vertices[k * 3..k * 3 + 3];
                        let d = (0..3)
                            .map(|i| (f64::from(r[i]) - f64::from(v[i])).abs())
                            .fold(0.0, f64::max);
                        if d <= VERTEX_TOLERANCE && best.is_none_or(|(b, _)| d < b) {
                            best = Some((d, k));
                        }
                    }
                }
            }
        }
        best.map(|(_, k)| k)
    }
}

/// The smallest and largest x, y, z of a mesh's vertices.
pub fn bounds(mesh: &MazeMesh) -> ([f64; 3], [f64; 3]) {
    let mut min = [f64::INFINITY; 3];
    let mut max = [f64::NEG_INFINITY; 3];
    for v in mesh.vertices.chunks_exact(3) {
        for k in 0..3 {
            min[k] = min[k].min(f64::from(v[k]));
            max[k] = max[k].max(f64::from(v[k]));
        }
    }
    (min, max)
}

#[cfg(test)]
mod tests {
    use super::super::MeshKind;
    use super::*;
    use vrep_maze_core::mesh::fingerprint;

    fn two_rects() -> MazeMesh {
        let vertices = vec![
            0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0, //
            1.0, 0.0, 0.0, 2.0, 0.0, 0.0, 2.0, 1.0, 0.0, 1.0, 1.0, 0.0,
        ];
        let indices = vec![0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7];
        MazeMesh {
            kind: MeshKind::Lines,
            fingerprint: fingerprint(MeshKind::Lines, &vertices, &indices),
            vertices,
            indices,
            pieces: vec![],
        }
    }

    #[test]
    fn merged_and_renumbered_vertices_are_the_same_mesh() {
        let m = two_rects();
        assert_eq!(mesh_differences(&m, &m.vertices, &m.indices), None);
        // merged duplicates, another order, a start vertex rotated, 50 um off
        let v = [
            2.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.00005, 0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 1.0, 0.0, 2.0,
            0.0, 0.0,
        ];
        let i = [1, 2, 3, 3, 4, 1, 2, 5, 0, 2, 0, 3];
        assert_eq!(mesh_differences(&m, &v, &i), None);
        // one triangle flipped, one vertex moved
        let flipped = [1, 3, 2, 3, 4, 1, 2, 5, 0, 2, 0, 3];
        assert!(
            mesh_differences(&m, &v, &flipped)
                .unwrap()
                .contains("1 of its 4")
        );
        let mut moved = v;
        moved[0] = 2.01;
        assert!(
            mesh_differences(&m, &moved, &i)
                .unwrap()
                .contains("no vertex")
        );
        assert!(mesh_differences(&m, &v[..17], &i).is_some());
        assert!(mesh_differences(&m, &v, &[0, 1, 9]).is_some());
    }
}
