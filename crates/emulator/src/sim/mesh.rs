//! A shape's triangles, as the emulated scene keeps them: vertices relative to the shape's
//! frame (as CoppeliaSim's `sim.getShapeMesh` answers), and the mesh of a primitive shape
//! (plane, cuboid), which the scene derives from its size.

use serde::{Deserialize, Serialize};

/// Triangles relative to the shape's frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Mesh {
    /// x, y, z per vertex, metres.
    pub vertices: Vec<f32>,
    /// Three vertex indices per triangle.
    pub indices: Vec<i32>,
}

/// Why vertices and indices make no mesh (the texts CoppeliaSim's errors carry).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum MeshError {
    /// Fewer than 3 vertices, a count not a multiple of 3, or a non-finite coordinate.
    #[error("bad vertices")]
    BadVertices,
    /// Fewer than 3 indices, a count not a multiple of 3, or an index naming no vertex.
    #[error("bad indices")]
    BadIndices,
}

/// Vertices closer than this are one: CoppeliaSim's default `identicalVertexTolerance`, 1e-6 m
/// ([`vrep_maze_core::coppelia::vertex_merge::TOLERANCE`]; both real builds keep two corners
/// 2 µm apart and merge them 0.5 µm apart).
const IDENTICAL_VERTEX: f32 = vrep_maze_core::coppelia::vertex_merge::TOLERANCE as f32;

impl Mesh {
    /// A mesh checked as `sim.createMeshShape` checks it, with duplicate vertices merged
    /// and repeated triangles dropped as CoppeliaSim 4.5.1 does when it creates one
    /// (`CMeshRoutines::removeDuplicateVerticesAndTriangles`).
    pub fn new(vertices: Vec<f32>, indices: Vec<i32>) -> Result<Mesh, MeshError> {
        if indices.len() < 3 || !indices.len().is_multiple_of(3) {
            return Err(MeshError::BadIndices);
        }
        let count = vertices.len() / 3;
        if indices.iter().any(|&i| i < 0 || i as usize >= count) {
            return Err(MeshError::BadIndices);
        }
        if vertices.len() < 9
            || !vertices.len().is_multiple_of(3)
            || vertices.iter().any(|v| !v.is_finite())
        {
            return Err(MeshError::BadVertices);
        }
        Ok(Mesh { vertices, indices }.merged())
    }

    /// Duplicate vertices (closer than [`IDENTICAL_VERTEX`], each merged into the first kept
    /// one it is that close to) merged, unreferenced ones dropped, and each triangle kept
    /// once.
    fn merged(self) -> Mesh {
        use std::collections::{HashMap, HashSet};
        // kept vertices by their cell on a grid of the tolerance's step: a vertex within the
        // tolerance of another lies in the same cell or a neighbouring one
        let cell = |v: &[f32]| [0, 1, 2].map(|k| (v[k] / IDENTICAL_VERTEX).floor() as i64);
        let mut by_cell: HashMap<[i64; 3], Vec<i32>> = HashMap::new();
        let mut vertices: Vec<f32> = Vec::new();
        let mut remap = Vec::with_capacity(self.vertices.len() / 3);
        for v in self.vertices.chunks_exact(3) {
            let c = cell(v);
            let near = (0..27).find_map(|n| {
                let at = [c[0] + n % 3 - 1, c[1] + n / 3 % 3 - 1, c[2] + n / 9 - 1];
                by_cell.get(&at)?.iter().copied().find(|&id| {
                    let k = id as usize * 3;
                    let d2: f32 = (0..3).map(|a| (vertices[k + a] - v[a]).powi(2)).sum();
                    d2.sqrt() < IDENTICAL_VERTEX
                })
            });
            let id = near.unwrap_or_else(|| {
                let id = (vertices.len() / 3) as i32;
                vertices.extend_from_slice(v);
                by_cell.entry(c).or_default().push(id);
                id
            });
            remap.push(id);
        }
        let mut seen = HashSet::new();
        let mut indices = Vec::with_capacity(self.indices.len());
        for t in self.indices.chunks_exact(3) {
            let t = [
                remap[t[0] as usize],
                remap[t[1] as usize],
                remap[t[2] as usize],
            ];
            if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
                continue;
            }
            // one triangle whatever vertex it starts from
            let start = (0..3).min_by_key(|&k| t[k]).unwrap_or(0);
            let canonical = [t[start], t[(start + 1) % 3], t[(start + 2) % 3]];
            if seen.insert(canonical) {
                indices.extend(t);
            }
        }
        Mesh { vertices, indices }
    }

    /// The mesh of a primitive shape of `size`: a plane (z size 0) is 4 vertices and 2
    /// triangles facing +z, anything else a box of 8 vertices and 12 triangles, centred on
    /// the shape's frame.
    pub fn primitive(size: [f64; 3]) -> Mesh {
        let [x, y, z] = size.map(|s| (s / 2.0) as f32);
        let square = [[-x, -y], [x, -y], [x, y], [-x, y]];
        if z == 0.0 {
            return Mesh {
                vertices: square.iter().flat_map(|&[a, b]| [a, b, 0.0]).collect(),
                indices: vec![0, 1, 2, 0, 2, 3],
            };
        }
        let mut vertices: Vec<f32> = square.iter().flat_map(|&[a, b]| [a, b, -z]).collect();
        vertices.extend(square.iter().flat_map(|&[a, b]| [a, b, z]));
        let mut indices = vec![4, 5, 6, 4, 6, 7, 0, 2, 1, 0, 3, 2];
        for i in 0..4 {
            let j = (i + 1) % 4;
            indices.extend([i, j, j + 4, i, j + 4, i + 4]);
        }
        Mesh { vertices, indices }
    }

    /// The smallest and largest x, y, z of the vertices.
    pub fn bounds(&self) -> ([f64; 3], [f64; 3]) {
        let mut min = [f64::INFINITY; 3];
        let mut max = [f64::NEG_INFINITY; 3];
        for v in self.vertices.chunks_exact(3) {
            for k in 0..3 {
                min[k] = min[k].min(f64::from(v[k]));
                max[k] = max[k].max(f64::from(v[k]));
            }
        }
        (min, max)
    }

    /// Triangles.
    pub fn triangles(&self) -> usize {
        self.indices.len() / 3
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn duplicates_merge_and_bad_input_is_refused() {
        // two squares sharing an edge: 8 vertices given, 6 kept
        let v = vec![
            0.0,
            0.0,
            0.0,
            1.0,
            0.0,
            0.0,
            1.0,
            1.0,
            0.0,
            0.0,
            1.0,
            0.0, //
            1.0,
            0.0,
            0.0,
            2.0,
            0.0,
            0.0,
            2.0,
            1.0,
            0.0,
            1.000_000_5,
            1.0,
            0.0,
        ];
        let i = vec![0, 1, 2, 0, 2, 3, 4, 5, 6, 4, 6, 7, 1, 2, 0];
        let m = Mesh::new(v, i).unwrap();
        assert_eq!((m.vertices.len() / 3, m.triangles()), (6, 4));
        assert_eq!(m.bounds(), ([0.0; 3], [2.0, 1.0, 0.0]));
        // 10 µm apart is two vertices, as on both real builds
        let apart = vec![
            0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 1.00001, 0.0, 0.0,
        ];
        let m = Mesh::new(apart, vec![0, 1, 2, 0, 3, 2]).unwrap();
        assert_eq!(m.vertices.len() / 3, 4);
        assert_eq!(
            Mesh::new(vec![0.0; 9], vec![0, 1]),
            Err(MeshError::BadIndices)
        );
        assert_eq!(
            Mesh::new(vec![0.0; 9], vec![0, 1, 3]),
            Err(MeshError::BadIndices)
        );
        assert_eq!(
            Mesh::new(vec![0.0; 8], vec![0, 1, 1]),
            Err(MeshError::BadVertices)
        );
        assert_eq!(
            Mesh::new(vec![f32::NAN; 9], vec![0, 1, 2]),
            Err(MeshError::BadVertices)
        );
    }

    #[test]
    fn primitives_have_their_size() {
        let plane = Mesh::primitive([0.6, 0.1, 0.0]);
        assert_eq!((plane.vertices.len(), plane.triangles()), (12, 2));
        let (min, max) = plane.bounds();
        assert!((max[0] - min[0] - 0.6).abs() < 1e-6 && max[2] == 0.0);
        let cube = Mesh::primitive([1.0, 0.05, 0.2]);
        assert_eq!((cube.vertices.len(), cube.triangles()), (24, 12));
        assert!((cube.bounds().1[2] - 0.1).abs() < 1e-6);
    }
}
