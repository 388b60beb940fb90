//! The modeled server work of mesh shapes on a real CoppeliaSim: creating one, reading one
//! back, merging several, removing one. Pure functions; the emulated servers sleep what they
//! return when their timing is realistic.
//!
//! Creating and reading back are priced by the mesh's triangles and vertices, with constants
//! per version ([`MeshCosts::V4_5_1`]: `sim.createMeshShape`; [`MeshCosts::V4_10`]:
//! `sim.createShape`, slower, and a `sim.getShapeMesh` that also returns normals). Creating
//! is priced by the steps of the simulator's search for coincident vertices too
//! ([`crate::coppelia::vertex_merge`]): that search is the same code in both builds, about
//! 20.5 ns a step on this machine, and it is what makes a mesh of posts cost up to two and a
//! half times a mesh of walls of the same counts (`docs/measurements.md` "Where posts spend
//! their time": every batch `apply` sends for six layouts within 0.95-1.04 on both builds).
//!
//! `sim.groupShapes(handles, true)` merged 40 meshes (20,000 rectangles) in 2.36 s (same spec
//! section): 118 µs per rectangle merged. Removing a mesh of any size took under 1 ms: it
//! costs what removing any one object costs (`crate::coppelia::cost`).

use std::time::Duration;

/// Per-version constants of the mesh calls.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshCosts {
    /// Creating a mesh by a call of its own, per mesh (beside the call's own cost) ...
    pub create_per_mesh: Duration,
    /// ... per triangle ...
    pub create_per_triangle: Duration,
    /// ... and per vertex given.
    pub create_per_vertex: Duration,
    /// Creating a mesh, per million steps of the search for coincident vertices
    /// ([`crate::coppelia::vertex_merge::merge_steps`]), in both ways of creating one.
    pub create_per_million_merge_steps: Duration,
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
    /// CoppeliaSim 4.5.1, `sim.createMeshShape`. Creating fitted to every mesh of a
    /// micromouse, a 100x100 line maze and a 50x50 wall maze with posts made one call each,
    /// and to the batches of six layouts made by one program each; reading back timed in
    /// `apply` runs: the lines of a 100x100 read in about 500 ms, the walls and posts of a
    /// 50x50 (47 meshes, 45,660 triangles) in 1,580 ms (`docs/measurements.md` "Where posts
    /// spend their time" and "Mesh calls on the real builds").
    pub const V4_5_1: MeshCosts = MeshCosts {
        create_per_mesh: Duration::from_micros(300),
        create_per_triangle: Duration::from_nanos(7_860),
        create_per_vertex: Duration::from_nanos(1_390),
        create_per_million_merge_steps: Duration::from_micros(20_500),
        read_per_triangle: Duration::from_nanos(28_500),
        read_per_vertex: Duration::from_nanos(9_200),
        // the 47 meshes of the 50x50 walls in 33-38 ms at idle fps 0 (`docs/measurements.md`,
        // "Meshes read back in one request")
        packed_read_per_triangle: Duration::from_nanos(740),
        // batches of 1 to 8 meshes (100 to 8,000 triangles) in 1.6 to 185 ms at idle fps 0
        packed_create_per_program: Duration::from_micros(920),
        packed_create_per_triangle: Duration::from_nanos(4_800),
        packed_create_per_vertex: Duration::from_nanos(230),
    };

    /// CoppeliaSim 4.10.0, `sim.createShape`, the same meshes on a freshly started simulator
    /// (as the bench starts one), fitted the same way: lines read back in 660 ms, walls and
    /// posts in 2,700 ms; slower than 4.5.1, and slower still in a simulator that has made and
    /// removed many meshes before (same sections).
    pub const V4_10: MeshCosts = MeshCosts {
        create_per_mesh: Duration::from_micros(3_100),
        create_per_triangle: Duration::from_nanos(10_050),
        create_per_vertex: Duration::from_nanos(7_290),
        create_per_million_merge_steps: Duration::from_micros(20_500),
        read_per_triangle: Duration::from_nanos(57_800),
        read_per_vertex: Duration::from_nanos(2_000),
        // the same 47 meshes in 35-46 ms (same section)
        packed_read_per_triangle: Duration::from_nanos(920),
        // the same batches in 2.3 to 210 ms
        packed_create_per_program: Duration::from_micros(930),
        packed_create_per_triangle: Duration::from_nanos(6_900),
        packed_create_per_vertex: Duration::from_nanos(2_600),
    };

    /// Server time of creating a mesh of `triangles` triangles and `vertices` vertices whose
    /// coincident vertices take `merge_steps` steps to find.
    pub fn create(&self, triangles: usize, vertices: usize, merge_steps: u64) -> Duration {
        self.create_per_mesh
            + per(self.create_per_triangle, triangles)
            + per(self.create_per_vertex, vertices)
            + self.merging(merge_steps)
    }

    /// Server time of `sim.getShapeMesh` of a mesh of `triangles` triangles and `vertices`
    /// vertices.
    pub fn read(&self, triangles: usize, vertices: usize) -> Duration {
        per(self.read_per_triangle, triangles) + per(self.read_per_vertex, vertices)
    }

    /// Server time of making and dressing meshes of `triangles` triangles and `vertices`
    /// vertices in all in one `sim.executeLuaCode`, their coincident vertices found in
    /// `merge_steps` steps.
    pub fn packed_create(&self, triangles: usize, vertices: usize, merge_steps: u64) -> Duration {
        self.packed_create_per_program
            + per(self.packed_create_per_triangle, triangles)
            + per(self.packed_create_per_vertex, vertices)
            + self.merging(merge_steps)
    }

    /// Server time of `steps` steps of the search for coincident vertices.
    fn merging(&self, steps: u64) -> Duration {
        self.create_per_million_merge_steps
            .mul_f64(steps as f64 / 1e6)
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
        // docs/measurements.md "Where posts spend their time": every mesh of a micromouse, a
        // 100x100 line maze and a 50x50 wall maze with posts made by a call of its own
        // (`mesh_costs --layout`, two or three runs): (costs, meshes, triangles, vertices,
        // merge steps, milliseconds in all)
        let made = [
            (
                MeshCosts::V4_5_1,
                2,
                1_210,
                968,
                65_844,
                [12.1, 13.5].as_slice(),
            ),
            (
                MeshCosts::V4_5_1,
                12,
                11_912,
                23_824,
                4_878_904,
                [241.0, 240.5].as_slice(),
            ),
            (
                MeshCosts::V4_5_1,
                35,
                33_234,
                30_440,
                18_778_710,
                [735.3, 709.9].as_slice(),
            ),
            (
                MeshCosts::V4_10,
                2,
                1_210,
                968,
                65_844,
                [23.2, 22.9, 24.7].as_slice(),
            ),
            (
                MeshCosts::V4_10,
                12,
                11_912,
                23_824,
                4_878_904,
                [464.4, 452.6].as_slice(),
            ),
            (
                MeshCosts::V4_10,
                35,
                33_234,
                30_440,
                18_778_710,
                [1084.5, 1131.3].as_slice(),
            ),
        ];
        for (costs, meshes, t, v, steps, measured) in made {
            let per_mesh = (t / meshes, v / meshes, steps / meshes as u64);
            let c = costs.create(per_mesh.0, per_mesh.1, per_mesh.2) * meshes as u32;
            for &ms in measured {
                assert!(close(c, ms / 1000.0), "create {t}: {c:?} vs {ms} ms");
            }
        }
        // "Mesh calls on the real builds", in `apply` runs: seconds of reading back every
        // mesh of a 100x100 line maze and of a 50x50 wall maze with posts: (costs,
        // triangles, vertices, read)
        let read = [
            (MeshCosts::V4_5_1, 10_680, 21_360, 0.475),
            (MeshCosts::V4_5_1, 45_660, 30_440, 1.451),
            (MeshCosts::V4_5_1, 45_660, 30_440, 1.709),
            (MeshCosts::V4_10, 10_680, 21_360, 0.663),
            (MeshCosts::V4_10, 10_680, 21_360, 0.655),
            (MeshCosts::V4_10, 45_660, 30_440, 2.588),
            (MeshCosts::V4_10, 45_660, 30_440, 2.892),
        ];
        for (costs, t, v, measured) in read {
            let r = costs.read(t, v);
            assert!(close(r, measured), "read {t}: {r:?} vs {measured} s");
        }
        // 4.10 is the slower of the two; an empty mesh reads in no time
        assert!(MeshCosts::V4_10.create(1000, 2000, 0) > MeshCosts::V4_5_1.create(1000, 2000, 0));
        assert_eq!(MeshCosts::V4_5_1.read(0, 0), Duration::ZERO);
    }

    #[test]
    fn the_search_for_coincident_vertices_is_what_makes_posts_dear() {
        // "Where posts spend their time": a batch of 8 post meshes (8,000 triangles, 6,400
        // vertices, 6,652,979 steps) took 209.6 ms on 4.10 and 184.8 ms on 4.5.1, a batch of
        // walls of the same counts (525,203 steps) 83.9 and 51.9 ms
        for (costs, posts, walls) in [
            (MeshCosts::V4_10, 209.6, 83.9),
            (MeshCosts::V4_5_1, 184.8, 51.9),
        ] {
            let p = costs.packed_create(8_000, 6_400, 6_652_979);
            let w = costs.packed_create(8_000, 6_400, 525_203);
            assert!(close(p, posts / 1000.0), "posts {p:?} vs {posts} ms");
            assert!(close(w, walls / 1000.0), "walls {w:?} vs {walls} ms");
        }
    }

    #[test]
    fn merging_forty_meshes_of_500_takes_what_it_took() {
        assert!(close(merge_shapes(40 * 500 * 2), 2.36));
    }
}
