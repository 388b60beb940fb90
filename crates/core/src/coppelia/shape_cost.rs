//! The modeled server work of mesh shapes on a real CoppeliaSim: creating one, reading one
//! back, merging several, removing one. Pure functions; the emulated servers sleep what they
//! return when their timing is realistic.
//!
//! Creating and reading back are priced by the mesh's triangles and vertices, with constants
//! per version ([`MeshCosts::V4_5_1`]: `sim.createMeshShape`; [`MeshCosts::V4_10`]:
//! `sim.createShape`, slower, and a `sim.getShapeMesh` that also returns normals), fitted to
//! the meshes `apply --draw mesh` makes (flat rectangles for lines, boxes for walls and
//! posts), timed on the real builds at idle fps 0 within `apply` runs: `docs/measurements.md`
//! "Mesh calls on the real builds". Those meshes are created 5 to 10 times faster than the
//! shapes of `../shared/spec/real-coppeliasim-4.5.1.md` ("One object instead of thousands":
//! one mesh of 500 rectangles, 148 ms), which the same program reproduces with its own grid of
//! rectangles (137 to 244 ms for 500): the cost depends on the geometry, not only on its size,
//! and the model keeps what vrep-maze's meshes cost.
//!
//! `sim.groupShapes(handles, true)` merged 40 meshes (20,000 rectangles) in 2.36 s (same spec
//! section): 118 µs per rectangle merged. Removing a mesh of any size took under 1 ms: it
//! costs what removing any one object costs (`crate::coppelia::cost`).

use std::time::Duration;

/// Per-version constants of the mesh calls.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshCosts {
    /// Creating a mesh, per triangle.
    pub create_per_triangle: Duration,
    /// Creating a mesh, per vertex given.
    pub create_per_vertex: Duration,
    /// `sim.getShapeMesh`, per triangle returned.
    pub read_per_triangle: Duration,
    /// `sim.getShapeMesh`, per vertex returned.
    pub read_per_vertex: Duration,
    /// Meshes made and dressed from packed data by one `sim.executeLuaCode`
    /// ([`crate::coppelia::lua::create`]): each program, whatever it makes ...
    pub packed_create_per_program: Duration,
    /// ... per triangle ...
    pub packed_create_per_triangle: Duration,
    /// ... and per vertex given.
    pub packed_create_per_vertex: Duration,
    /// Meshes read inside the simulator and packed as binary strings, in one
    /// `sim.executeLuaCode` ([`crate::coppelia::lua`]), per triangle.
    pub packed_read_per_triangle: Duration,
}

impl MeshCosts {
    /// CoppeliaSim 4.5.1, `sim.createMeshShape`, timed in `apply --draw mesh` runs: the lines
    /// of a 100x100 (11 meshes, 10,680 triangles, 21,360 vertices) made in about 250 ms and
    /// read back in about 500 ms, the walls and posts of a 50x50 (47 meshes, 45,660 triangles,
    /// 30,440 vertices) in about 650 ms and 1,580 ms (`docs/measurements.md` "Mesh calls on
    /// the real builds"; the constants solve those four figures).
    pub const V4_5_1: MeshCosts = MeshCosts {
        create_per_triangle: Duration::from_nanos(9_400),
        create_per_vertex: Duration::from_nanos(7_200),
        read_per_triangle: Duration::from_nanos(28_500),
        read_per_vertex: Duration::from_nanos(9_200),
        // the 47 meshes of the 50x50 walls in 33-38 ms at idle fps 0 (`docs/measurements.md`,
        // "Meshes read back in one request")
        packed_read_per_triangle: Duration::from_nanos(740),
        // batches of 1 to 8 meshes (82 to 8,000 triangles) in 1.0 to 106 ms at idle fps 0
        // (`docs/measurements.md`, "Meshes created in one request")
        packed_create_per_program: Duration::ZERO,
        packed_create_per_triangle: Duration::from_nanos(1_700),
        packed_create_per_vertex: Duration::from_nanos(5_800),
    };

    /// CoppeliaSim 4.10.0, `sim.createShape`, the same meshes on a freshly started simulator
    /// (as the bench starts one): lines made in about 390 ms and read back in 660 ms, walls
    /// and posts in about 1,100 ms (989-1,854) and 2,700 ms: slower than 4.5.1, and slower
    /// still in a simulator that has made and removed many meshes before (same section).
    pub const V4_10: MeshCosts = MeshCosts {
        create_per_triangle: Duration::from_nanos(17_900),
        create_per_vertex: Duration::from_nanos(9_300),
        read_per_triangle: Duration::from_nanos(57_800),
        read_per_vertex: Duration::from_nanos(2_000),
        // the same 47 meshes in 35-46 ms (same section)
        packed_read_per_triangle: Duration::from_nanos(920),
        // the same batches in 2.7 to 162 ms (same section)
        packed_create_per_program: Duration::from_micros(750),
        packed_create_per_triangle: Duration::from_nanos(4_700),
        packed_create_per_vertex: Duration::from_nanos(7_800),
    };

    /// Server time of creating a mesh of `triangles` triangles and `vertices` vertices.
    pub fn create(&self, triangles: usize, vertices: usize) -> Duration {
        per(self.create_per_triangle, triangles) + per(self.create_per_vertex, vertices)
    }

    /// Server time of `sim.getShapeMesh` of a mesh of `triangles` triangles and `vertices`
    /// vertices.
    pub fn read(&self, triangles: usize, vertices: usize) -> Duration {
        per(self.read_per_triangle, triangles) + per(self.read_per_vertex, vertices)
    }

    /// Server time of making and dressing meshes of `triangles` triangles and `vertices`
    /// vertices in all in one `sim.executeLuaCode`.
    pub fn packed_create(&self, triangles: usize, vertices: usize) -> Duration {
        self.packed_create_per_program
            + per(self.packed_create_per_triangle, triangles)
            + per(self.packed_create_per_vertex, vertices)
    }

    /// Server time of reading meshes of `triangles` triangles in all in one
    /// `sim.executeLuaCode`.
    pub fn packed_read(&self, triangles: usize) -> Duration {
        per(self.packed_read_per_triangle, triangles)
    }
}

/// Seconds per rectangle merged by `sim.groupShapes` (2.36 s for 20,000).
const MERGE_PER_RECTANGLE: f64 = 2.36 / 20_000.0;

/// Server time of `sim.groupShapes` merging shapes of `triangles` triangles in all.
pub fn merge_shapes(triangles: usize) -> Duration {
    Duration::from_secs_f64(MERGE_PER_RECTANGLE * triangles as f64 / 2.0)
}

fn per(d: Duration, n: usize) -> Duration {
    d.saturating_mul(u32::try_from(n).unwrap_or(u32::MAX))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `model` within a factor 0.75 to 1.33 of `measured` seconds.
    fn close(model: Duration, measured: f64) -> bool {
        let r = model.as_secs_f64() / measured;
        (0.75..=1.33).contains(&r)
    }

    #[test]
    fn the_meshes_of_a_line_and_a_wall_maze_cost_what_they_cost_on_each_version() {
        // docs/measurements.md "Mesh calls on the real builds", in `apply` runs: seconds of
        // creating and of reading back every mesh of a 100x100 line maze and of a 50x50 wall
        // maze with posts: (costs, triangles, vertices, create, read)
        let rows = [
            (MeshCosts::V4_5_1, 10_680, 21_360, 0.227, 0.475),
            (MeshCosts::V4_5_1, 45_660, 30_440, 0.619, 1.451),
            (MeshCosts::V4_5_1, 45_660, 30_440, 0.711, 1.709),
            (MeshCosts::V4_10, 10_680, 21_360, 0.396, 0.663),
            (MeshCosts::V4_10, 10_680, 21_360, 0.387, 0.655),
            (MeshCosts::V4_10, 45_660, 30_440, 0.989, 2.588),
            (MeshCosts::V4_10, 45_660, 30_440, 1.25, 2.892),
        ];
        for (costs, t, v, create, read) in rows {
            let (c, r) = (costs.create(t, v), costs.read(t, v));
            assert!(close(c, create), "create {t}: {c:?} vs {create} s");
            assert!(close(r, read), "read {t}: {r:?} vs {read} s");
        }
        // 4.10 is the slower of the two; an empty mesh costs nothing
        assert!(MeshCosts::V4_10.create(1000, 2000) > MeshCosts::V4_5_1.create(1000, 2000));
        assert_eq!(MeshCosts::V4_5_1.read(0, 0), Duration::ZERO);
    }

    #[test]
    fn merging_forty_meshes_of_500_takes_what_it_took() {
        assert!(close(merge_shapes(40 * 500 * 2), 2.36));
    }
}
