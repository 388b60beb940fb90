//! What a real CoppeliaSim 4.5.1 spends on scene operations: a pure model, shared by the
//! emulator (which sleeps what it says) and the clients (which size requests and warn about
//! slow draws with it). Every figure cites `../shared/spec/real-coppeliasim-4.5.1.md` (the spec
//! folder beside this repository).
//!
//! # The simulator's own work ("Costs that grow with the scene")
//!
//! Timed inside the simulator (idle fps 0, course scene plus n copies of `Line`):
//!
//! | n | paste all n | `setObjectParent` of all n | set the pose of all n | `removeObjects` of all n |
//! |---|---|---|---|---|
//! | 1,000 | 0.185 s | 0.068 s | 0.003 s | 0.059 s |
//! | 4,000 | 2.41 s | 1.42 s | 0.024 s | 1.14 s |
//! | 8,000 | 10.1 s | 5.32 s | 0.044 s | 4.11 s |
//! | 20,000 | 65.7 s | 42.7 s | 0.16 s | 36.3 s |
//!
//! Pasting one object costs time in proportion to the objects already in the scene (each
//! copy's lowest free `Line<N>` name, and `copyPasteObjects` finding each copy by a walk over
//! every object: coppeliaSimLib@coppeliasim-v4.5.1-rev4 `simInternal.cpp:6508-6523`); the n
//! copies are pasted into scenes of 0..n objects, so the total is about
//! [`CostModel::paste_per_object`] · n²/2 (spec: "about 1.6e-7·n²").
//! Removing one object likewise ([`CostModel::remove_per_object`], total about
//! 7e-8·n²). Re-parenting one object walks the new parent's children and the parentless
//! objects (coppeliaSimLib `sceneObjectContainer.cpp:1110-1157`); while n pasted copies go under
//! `Maze` one by one, those two add up to n, so the total is
//! [`CostModel::parent_per_object`] · n² (spec: "about 1e-7·n²"). A pose costs a few
//! microseconds (the spec's "about 8 µs" is the 20,000 column; its table gives 3 µs a pose
//! among 1,000 copies, 6 among 4,000), modelled as [`CostModel::pose`] plus a little per
//! object ([`CostModel::pose_per_thousand_objects`]). The constants are fitted so that every cell of
//! the table is within a factor 0.75..1.33 (unit tests below).
//!
//! # What each request adds ("Pacing", "ZeroMQ costs at idle fps 0")
//!
//! A ZeroMQ call at idle fps 0 takes about 0.45 ms end to end in the spec ("Pacing"), but
//! 0.10–0.19 ms on the real 4.5.1 build ([`CostModel::zmq_call`], `docs/measurements.md`
//! "ZeroMQ calls on 4.5.1"; the real build decides); `sim.setObjectParent` /
//! `sim.setObjectPose` 0.33–0.45 ms in the spec, 0.12–0.22 ms measured ([`CostModel::zmq_set`]);
//! `sim.getObjectsInTree(Maze, -1, 3)` 0.3 ms, 0.9 ms with 500 children. A legacy blocking
//! call at idle fps 0 took 9–10 ms in the spec's "Pacing" (timed with other clients), but
//! 2.1–2.4 ms with vrep-maze's: a pass that executed commands takes
//! at least 2 ms ([`CostModel::legacy_pass_floor`], `docs/measurements.md` "Legacy calls at
//! idle fps 0"). A ZeroMQ call in a big scene takes more than that
//! ([`CostModel::zmq_call_per_thousand_objects`], fitted to the residue of the spec's 9x9 to
//! 100x100 row), and each legacy drawing command a little more than the simulator's own work ([`CostModel::legacy_command`], fitted to "Drawing cost on the
//! server (legacy API, idle fps 0)" and the legacy rows of the "through vrep-maze" table).

use std::time::Duration;

pub use super::shape_cost::MeshCosts;

/// One piece of work a CoppeliaSim request makes the simulator do.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Op {
    /// `copies` distinct objects pasted into a scene of `objects` objects.
    Paste {
        /// Copies made (repeated handles are pasted once).
        copies: usize,
        /// Objects in the scene before the paste.
        objects: usize,
    },
    /// One object re-parented under a parent with `children` children, `parentless` objects
    /// in the scene (both before the change).
    SetParent {
        /// Children of the new parent.
        children: usize,
        /// Objects without parent.
        parentless: usize,
    },
    /// One pose set (position and orientation) in a scene of `objects` objects.
    Pose {
        /// Objects in the scene.
        objects: usize,
    },
    /// Half a pose: the legacy API sets the position and the orientation by two commands.
    HalfPose {
        /// Objects in the scene.
        objects: usize,
    },
    /// `count` objects removed from a scene of `objects` objects.
    Remove {
        /// Objects removed (ones that existed).
        count: usize,
        /// Objects in the scene before the removal.
        objects: usize,
    },
    /// One ZeroMQ call (its transport and the add-on's dispatch).
    ZmqCall,
    /// The first request of a ZeroMQ client the add-on has not seen (protocol 2: a new
    /// uuid), besides its call.
    ZmqNewClient,
    /// One ZeroMQ `sim.setObjectParent` or `sim.setObjectPose` call, its own work aside.
    ZmqSet,
    /// What serving one ZeroMQ call adds in a scene of `objects` objects, besides the work
    /// above (fitted: see [`CostModel::zmq_call_per_thousand_objects`]).
    ZmqServe {
        /// Objects in the scene.
        objects: usize,
    },
    /// One ZeroMQ `sim.getObjectsInTree` call returning `handles` handles.
    ZmqTree {
        /// Handles returned.
        handles: usize,
    },
    /// One call made inside one of our Lua programs (several calls in one request,
    /// `vrep_maze_wire::zmq_api::calls`), returning `handles` handles (a tree's), its own work
    /// aside.
    ProgramCall {
        /// Handles returned.
        handles: usize,
    },
    /// One legacy drawing command (paste, set-parent, set-position, set-orientation,
    /// remove), its own work aside.
    LegacyCommand,
    /// `sim.createMeshShape` / `sim.createShape` of a mesh ([`super::shape_cost`]).
    CreateMesh {
        /// Triangles of the mesh.
        triangles: usize,
        /// Vertices given.
        vertices: usize,
        /// Steps of the search for its coincident vertices ([`super::vertex_merge`]).
        merge_steps: u64,
    },
    /// `sim.getShapeMesh` of a mesh ([`super::shape_cost`]).
    ReadMesh {
        /// Triangles of the mesh.
        triangles: usize,
        /// Vertices of the mesh.
        vertices: usize,
    },
    /// Meshes of `triangles` triangles and `vertices` vertices in all made and dressed by one
    /// `sim.executeLuaCode` from packed data ([`super::lua::create`], [`super::shape_cost`]).
    CreateMeshesPacked {
        /// Triangles of the meshes.
        triangles: usize,
        /// Vertices given.
        vertices: usize,
        /// Steps of the searches for their coincident vertices ([`super::vertex_merge`]).
        merge_steps: u64,
    },
    /// Meshes of `triangles` triangles in all read and packed in one `sim.executeLuaCode`
    /// ([`super::lua`], [`super::shape_cost`]).
    ReadMeshesPacked {
        /// Triangles of the meshes.
        triangles: usize,
    },
    /// `sim.groupShapes` merging shapes of `triangles` triangles in all
    /// ([`super::shape_cost`]).
    MergeShapes {
        /// Triangles of the merged shape.
        triangles: usize,
    },
    /// Loading an XML model of `triangles` triangles (`simxLoadModel`, `sim.loadModel`;
    /// [`super::model_cost`]).
    LoadModel {
        /// Triangles of the model's meshes.
        triangles: usize,
    },
}

/// The constants of the model (see the module documentation for the fit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CostModel {
    /// Pasting one copy, per object already in the scene.
    pub paste_per_object: Duration,
    /// Pasting one copy, whatever the scene (none on 4.5.1, whose table the per-object term
    /// alone fits; 0.22 ms on 4.10: [`CostModel::v4_10`]).
    pub paste_per_copy: Duration,
    /// Re-parenting one object, per child of the new parent and per parentless object.
    pub parent_per_object: Duration,
    /// Removing one object, per object in the scene.
    pub remove_per_object: Duration,
    /// Removing objects in one call, per pair of objects removed (none on 4.5.1; 0.24 µs on
    /// 4.10, whose removals grow with the square of their count: [`CostModel::v4_10`]).
    pub remove_per_pair: Duration,
    /// Setting one pose, besides [`CostModel::pose_per_thousand_objects`] (spec "Costs that
    /// grow with the scene": 3 µs a pose among 1,000 copies, 8 µs among 20,000).
    pub pose: Duration,
    /// Setting one pose, per thousand objects in the scene.
    pub pose_per_thousand_objects: Duration,
    /// One legacy drawing command besides the simulator's own work.
    pub legacy_command: Duration,
    /// The least time a legacy main-loop pass that executed commands takes at idle fps 0
    /// (`docs/measurements.md` "Legacy calls at idle fps 0": 2.1–2.4 ms a call with
    /// vrep-maze's client; spec "Pacing" gives 9–10 ms, timed with other clients).
    pub legacy_pass_floor: Duration,
    /// One ZeroMQ call at idle fps 0, end to end: 0.15 ms (`docs/measurements.md` "ZeroMQ
    /// calls on 4.5.1": medians 0.10–0.19 ms on the real 4.5.1; the spec's "Pacing" says
    /// about 0.45 ms, timed with an older client: the real build decides).
    pub zmq_call: Duration,
    /// The first request of a new protocol-2 client, besides its call: 5.5 ms on 4.10
    /// (`docs/measurements.md` "A new client on 4.10": 3.7-8.8 ms with vrep-maze's client,
    /// median 5.5, within the pass that serves it; the add-on makes the client a coroutine and its `require`
    /// loads the module for it: `ZMQ remote API server.lua:477-490, 518-535` at
    /// coppeliasim-v4.10.0-rev0). None on 4.5.1, whose protocol 1 keeps no clients.
    pub zmq_new_client: Duration,
    /// One ZeroMQ `sim.setObjectParent` or `sim.setObjectPose`: 0.17 ms (`docs/measurements.md`
    /// "ZeroMQ calls on 4.5.1": medians 0.12–0.22 ms; the spec's "ZeroMQ costs at idle fps 0"
    /// says 0.33–0.45 ms).
    pub zmq_set: Duration,
    /// Serving one ZeroMQ call, per thousand objects in the scene. Not measured directly:
    /// the residue of the spec's "ZeroMQ: replace 9x9 by 100x100 (19,838 pasted, 40,107
    /// calls)", 139.8 s, once the simulator's own work (pasting, re-parenting, poses, all
    /// timed inside it) and 0.45 ms a call are taken off: about 28 s over 40,107 calls, most
    /// of them served among 15,000 to 20,000 objects (that run's client pasted its last
    /// 15,000 copies in one round, then re-parented and placed them one call each). Each
    /// call is served in a main-loop pass, and a pass's own upkeep growing with the scene
    /// would explain it (a hypothesis: no measurement isolates it); the legacy API, which
    /// serves a whole request in one pass, shows no such residue.
    /// Kept at the fit with the spec's 0.45 ms calls: with the real build's 0.15 ms the
    /// spec's row is still reproduced within 0.75..1.33 (`tests/it/costs.rs`).
    pub zmq_call_per_thousand_objects: Duration,
    /// One call inside one of our Lua programs: 5-10 µs on both builds, where a request of
    /// its own costs 0.1-0.2 ms (`docs/measurements.md` "Calls made in one request": ten
    /// reads of parents and poses in 0.20-0.26 ms, an empty program 0.12-0.17 ms).
    pub program_call: Duration,
    /// ZeroMQ `sim.getObjectsInTree`: the call, 0.15 ms (each of the four a reset makes
    /// answered in 0.1-0.2 ms on both real builds at idle fps 0, `docs/measurements.md` "Calls
    /// made in one request"; the spec's "ZeroMQ costs" says 0.3 ms, timed with an older
    /// client whose every call took 0.45 ms: the real build decides) ...
    pub zmq_tree: Duration,
    /// ... and per handle returned (0.9 ms with 500 children).
    pub zmq_tree_per_handle: Duration,
    /// Creating and reading back meshes, which differ by version ([`MeshCosts`]).
    pub mesh: MeshCosts,
}

impl Default for CostModel {
    fn default() -> Self {
        CostModel::measured()
    }
}

/// Σ_{i<k} (m + sign·i) objects: what `k` operations walk when the scene starts at `m`
/// objects and grows (sign 1) or shrinks (sign -1) by one with each.
fn walked(k: usize, m: usize, grows: bool) -> f64 {
    let (k, m) = (k as f64, m as f64);
    let series = k * (k - 1.0) / 2.0;
    if grows {
        k * m + series
    } else {
        (k * m - series).max(0.0)
    }
}

impl CostModel {
    /// The fit to the spec's tables (module documentation).
    pub fn measured() -> CostModel {
        CostModel {
            paste_per_object: Duration::from_nanos(320),
            paste_per_copy: Duration::ZERO,
            parent_per_object: Duration::from_nanos(85),
            remove_per_object: Duration::from_nanos(144),
            remove_per_pair: Duration::ZERO,
            pose: Duration::from_nanos(3600),
            pose_per_thousand_objects: Duration::from_nanos(260),
            legacy_command: Duration::from_micros(100),
            legacy_pass_floor: Duration::from_millis(2),
            zmq_call: Duration::from_micros(150),
            zmq_new_client: Duration::ZERO,
            zmq_set: Duration::from_micros(170),
            zmq_call_per_thousand_objects: Duration::from_micros(40),
            program_call: Duration::from_micros(8),
            zmq_tree: Duration::from_micros(150),
            zmq_tree_per_handle: Duration::from_nanos(1200),
            mesh: MeshCosts::V4_5_1,
        }
    }

    /// What CoppeliaSim 4.10 takes: as [`CostModel::measured`] but for its meshes
    /// ([`MeshCosts::V4_10`]; `docs/measurements.md` "Mesh calls on the real builds") and its
    /// quicker calls: 0.1-0.3 ms a call at idle fps 0, median 0.1-0.2 ms
    /// (`docs/measurements.md` "ZeroMQ calls on 4.10"), and its pastes: about 0.22 ms a copy
    /// plus 0.2 µs per object walked, where 4.5.1 takes 0.32 µs per object walked and nothing
    /// a copy (`docs/measurements.md` "Pasting on 4.10": 64 copies in 15.5 ms among 69
    /// objects, 28.3 ms among 1,069), its removals, which add about 0.24 µs per pair of
    /// objects removed, and its trees, 2 µs a handle returned ("Removing and listing on
    /// 4.10": 256 copies removed in 18.9 ms where 4.5.1 takes 3.6 ms; 1,005 handles listed in
    /// 2.13 ms, 1.44 ms on 4.5.1).
    pub fn v4_10() -> CostModel {
        CostModel {
            remove_per_pair: Duration::from_nanos(240),
            zmq_tree_per_handle: Duration::from_nanos(2000),
            mesh: MeshCosts::V4_10,
            paste_per_copy: Duration::from_micros(222),
            zmq_new_client: Duration::from_micros(5_500),
            paste_per_object: Duration::from_nanos(200),
            zmq_call: Duration::from_micros(150),
            zmq_set: Duration::from_micros(150),
            ..CostModel::measured()
        }
    }

    /// The time one piece of work takes.
    pub fn op(&self, op: &Op) -> Duration {
        let per = |d: Duration, objects: f64| Duration::from_secs_f64(d.as_secs_f64() * objects);
        match *op {
            Op::Paste { copies, objects } => {
                per(self.paste_per_copy, copies as f64)
                    + per(self.paste_per_object, walked(copies, objects, true))
            }
            Op::SetParent {
                children,
                parentless,
            } => per(self.parent_per_object, (children + parentless) as f64),
            Op::Pose { objects } => {
                self.pose + per(self.pose_per_thousand_objects, objects as f64 / 1000.0)
            }
            Op::HalfPose { objects } => self.op(&Op::Pose { objects }) / 2,
            Op::Remove { count, objects } => {
                per(self.remove_per_object, walked(count, objects, false))
                    + per(self.remove_per_pair, (count * count) as f64)
            }
            Op::ZmqCall => self.zmq_call,
            Op::ZmqNewClient => self.zmq_new_client,
            Op::ZmqSet => self.zmq_set,
            Op::ZmqServe { objects } => {
                per(self.zmq_call_per_thousand_objects, objects as f64 / 1000.0)
            }
            Op::ZmqTree { handles } => {
                self.zmq_tree + per(self.zmq_tree_per_handle, handles as f64)
            }
            Op::ProgramCall { handles } => {
                self.program_call + per(self.zmq_tree_per_handle, handles as f64)
            }
            Op::LegacyCommand => self.legacy_command,
            Op::CreateMesh {
                triangles,
                vertices,
                merge_steps,
            } => self.mesh.create(triangles, vertices, merge_steps),
            Op::ReadMesh {
                triangles,
                vertices,
            } => self.mesh.read(triangles, vertices),
            Op::CreateMeshesPacked {
                triangles,
                vertices,
                merge_steps,
            } => self.mesh.packed_create(triangles, vertices, merge_steps),
            Op::ReadMeshesPacked { triangles } => self.mesh.packed_read(triangles),
            Op::MergeShapes { triangles } => super::shape_cost::merge_shapes(triangles),
            Op::LoadModel { triangles } => super::model_cost::model_load(triangles),
        }
    }

    /// The time a list of work takes.
    pub fn ops(&self, ops: &[Op]) -> Duration {
        ops.iter().map(|o| self.op(o)).sum()
    }

    /// The time a legacy main-loop pass that executed `ops` takes: their work, and at least
    /// [`CostModel::legacy_pass_floor`] when the loop spins (stopped at idle fps 0).
    pub fn legacy_pass(&self, ops: &[Op], spinning: bool) -> Duration {
        let work = self.ops(ops);
        if spinning {
            work.max(self.legacy_pass_floor)
        } else {
            work
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A factor of `want` within 0.75..1.33, or a message saying by how much it is not.
    fn within(what: &str, got: Duration, want: f64) {
        let ratio = got.as_secs_f64() / want;
        assert!(
            (0.75..=1.33).contains(&ratio),
            "{what}: modelled {:.3} s vs {want} s measured (x{ratio:.2})",
            got.as_secs_f64()
        );
    }

    /// The course scene: Floor, Maze, Line, Start, End.
    const COURSE: usize = 5;

    /// Pasting n copies of `Line` in doubling rounds of `copyPasteObjects` (the template,
    /// then every copy so far) into the course scene, as the spec's experiment did.
    fn paste_all(m: &CostModel, n: usize) -> Duration {
        let (mut have, mut t) = (1, Duration::ZERO);
        while have < n + 1 {
            let copies = have.min(n + 1 - have);
            t += m.op(&Op::Paste {
                copies,
                objects: COURSE - 1 + have,
            });
            have += copies;
        }
        t
    }

    /// Re-parenting the n pasted (parentless) copies to `Maze` one by one.
    fn parent_all(m: &CostModel, n: usize) -> Duration {
        (0..n)
            .map(|k| {
                m.op(&Op::SetParent {
                    children: k,
                    parentless: COURSE - 1 + n - k,
                })
            })
            .sum()
    }

    #[test]
    fn every_cell_of_the_in_simulator_table_is_reproduced() {
        let m = CostModel::measured();
        // spec "Costs that grow with the scene": n, paste, set parent, pose, remove
        let table = [
            (1_000, 0.185, 0.068, 0.003, 0.059),
            (4_000, 2.41, 1.42, 0.024, 1.14),
            (8_000, 10.1, 5.32, 0.044, 4.11),
            (20_000, 65.7, 42.7, 0.16, 36.3),
        ];
        for (n, paste, parent, pose, remove) in table {
            within(&format!("paste {n}"), paste_all(&m, n), paste);
            within(&format!("set parent {n}"), parent_all(&m, n), parent);
            let objects = COURSE + n;
            within(
                &format!("pose {n}"),
                m.op(&Op::Pose { objects }) * n as u32,
                pose,
            );
            let removed = m.op(&Op::Remove {
                count: n,
                objects: COURSE + n,
            });
            within(&format!("remove {n}"), removed, remove);
        }
    }

    #[test]
    fn scene_work_grows_with_the_objects_walked() {
        let m = CostModel::measured();
        let paste = |copies, objects| m.op(&Op::Paste { copies, objects });
        assert_eq!(paste(0, 100), Duration::ZERO);
        // one copy into 1,000 objects walks 1,000; two walk 1,000 + 1,001
        assert_eq!(paste(1, 1000), m.paste_per_object * 1000);
        assert_eq!(paste(2, 1000), m.paste_per_object * 2001);
        let remove = |count, objects| m.op(&Op::Remove { count, objects });
        assert_eq!(remove(2, 1000), m.remove_per_object * 1999);
        // removing objects that are not there walks nothing
        assert_eq!(remove(3, 0), Duration::ZERO);
        let parent = m.op(&Op::SetParent {
            children: 3,
            parentless: 4,
        });
        assert_eq!(parent, m.parent_per_object * 7);
        let pose = |objects| m.op(&Op::Pose { objects });
        let half = m.op(&Op::HalfPose { objects: 10 }) * 2;
        assert!(half.abs_diff(pose(10)) <= Duration::from_nanos(1));
        assert!(pose(20_000) > pose(1_000));
    }

    #[test]
    fn per_request_costs_follow_the_pacing_and_zeromq_tables() {
        let m = CostModel::measured();
        let ms = |d: Duration| d.as_secs_f64() * 1000.0;
        // docs/measurements.md "ZeroMQ calls on 4.5.1": medians 0.10-0.19 ms a call,
        // 0.12-0.22 ms a set (the spec's "Pacing" 0.45 ms lost to the real build);
        // "Legacy calls at idle fps 0": a legacy call 2.1–2.4 ms with our client
        assert!((0.10..=0.19).contains(&ms(m.op(&Op::ZmqCall))));
        assert!((0.12..=0.22).contains(&ms(m.op(&Op::ZmqSet))));
        assert_eq!(m.legacy_pass(&[], true), Duration::from_millis(2));
        assert_eq!(m.legacy_pass(&[Op::LegacyCommand], false), m.legacy_command);
        // getObjectsInTree: 0.1-0.2 ms a call on both real builds ("Calls made in one
        // request"; the spec's "ZeroMQ costs" 0.3 ms lost to the real build), and the spec's
        // 0.6 ms more with 500 children
        assert!((0.10..=0.20).contains(&ms(m.op(&Op::ZmqTree { handles: 0 }))));
        let children = m.op(&Op::ZmqTree { handles: 500 }) - m.op(&Op::ZmqTree { handles: 0 });
        assert!((ms(children) - 0.6).abs() < 0.01);
    }

    /// `docs/measurements.md` "Pasting on 4.10": `copyPasteObjects` of k distinct copies of
    /// `Line` in one call at idle fps 0 on the real 4.10.0, median of 7, less one call's
    /// 0.12 ms round trip.
    #[test]
    fn pastes_on_4_10_follow_the_measured_table() {
        let m = CostModel::v4_10();
        let call = 0.000_12;
        for (objects, copies, real_ms) in [
            (69, 8, 2.01),
            (69, 64, 15.48),
            (269, 16, 4.34),
            (269, 64, 17.08),
            (1069, 8, 4.09),
            (1069, 64, 28.29),
        ] {
            let paste = m.op(&Op::Paste { copies, objects });
            within(
                &format!("4.10: {copies} copies among {objects}"),
                paste,
                real_ms / 1000.0 - call,
            );
        }
        // 4.5.1 pays nothing a copy
        assert_eq!(CostModel::measured().paste_per_copy, Duration::ZERO);
    }

    /// `docs/measurements.md` "A new client on 4.10": a new client's first request, in the
    /// pass that serves it, 3.7-8.8 ms with vrep-maze's client, median 5.5 ms.
    #[test]
    fn a_new_client_costs_on_4_10_only() {
        let first = |m: CostModel| m.ops(&[Op::ZmqCall, Op::ZmqNewClient]);
        within(
            "4.10: a new client's first call",
            first(CostModel::v4_10()),
            0.0055,
        );
        assert_eq!(first(CostModel::measured()), CostModel::measured().zmq_call);
    }

    #[test]
    fn batches_of_meshes_made_in_one_request_cost_what_they_cost_on_each_version() {
        // docs/measurements.md "Where posts spend their time": the batches `apply --draw mesh`
        // sends for a 9x9 line maze, a micromouse with and without posts, a 100x100 line maze
        // and a 50x50 wall maze with and without posts, each request timed end to end at idle
        // fps 0 (median of 5): (model, meshes' triangles, vertices, merge steps, ms measured)
        let rows = [
            (CostModel::v4_10(), 100, 200, 7_439, 2.3),
            (CostModel::v4_10(), 1_210, 968, 65_844, 13.0),
            (CostModel::v4_10(), 3_652, 3_328, 479_059, 43.9),
            (CostModel::v4_10(), 8_000, 16_000, 3_574_376, 168.3),
            (CostModel::v4_10(), 3_912, 7_824, 1_304_528, 73.9),
            (CostModel::v4_10(), 8_000, 6_400, 525_203, 83.9),
            (CostModel::v4_10(), 4_040, 3_232, 210_976, 41.5),
            (CostModel::v4_10(), 7_224, 9_632, 945_494, 100.9),
            (CostModel::v4_10(), 8_000, 6_400, 6_652_979, 209.6),
            (CostModel::v4_10(), 8_000, 6_400, 3_158_407, 139.5),
            (CostModel::v4_10(), 8_000, 6_400, 5_597_234, 186.9),
            (CostModel::v4_10(), 2_010, 1_608, 2_424_596, 69.1),
            (CostModel::measured(), 100, 200, 7_439, 1.6),
            (CostModel::measured(), 1_210, 968, 65_844, 8.2),
            (CostModel::measured(), 3_652, 3_328, 479_059, 28.5),
            (CostModel::measured(), 8_000, 16_000, 3_574_376, 117.2),
            (CostModel::measured(), 3_912, 7_824, 1_304_528, 50.5),
            (CostModel::measured(), 8_000, 6_400, 525_203, 51.9),
            (CostModel::measured(), 4_040, 3_232, 210_976, 26.6),
            (CostModel::measured(), 7_224, 9_632, 945_494, 55.1),
            (CostModel::measured(), 8_000, 6_400, 6_652_979, 184.8),
            (CostModel::measured(), 8_000, 6_400, 3_158_407, 107.7),
            (CostModel::measured(), 8_000, 6_400, 5_597_234, 158.9),
            (CostModel::measured(), 2_010, 1_608, 2_424_596, 59.0),
        ];
        for (model, triangles, vertices, merge_steps, ms) in rows {
            let op = Op::CreateMeshesPacked {
                triangles,
                vertices,
                merge_steps,
            };
            let modelled = model.ops(&[Op::ZmqCall, op]);
            within(&format!("{triangles} triangles"), modelled, ms / 1000.0);
            if triangles < 1_000 {
                continue;
            }
            // more than a thousand triangles cost less than they would in a call of their own
            let one_call = model.ops(&[
                Op::ZmqCall,
                Op::CreateMesh {
                    triangles,
                    vertices,
                    merge_steps,
                },
            ]);
            assert!(
                modelled < one_call,
                "{triangles}: {modelled:?} vs {one_call:?}"
            );
        }
    }

    /// `docs/measurements.md` "Removing and listing on 4.10": `removeObjects` of k pasted
    /// copies of `Line` in one call at idle fps 0, median of 7, in the course scene (5
    /// objects) and with 1,000 more; `getObjectsInTree` of the scene, median of 11.
    #[test]
    fn removals_and_trees_follow_the_measured_tables() {
        let ms = |d: Duration| d.as_secs_f64() * 1000.0;
        // (model, k removed, objects before, ms measured end to end)
        let removals = [
            (CostModel::v4_10(), 64, 69, 1.60),
            (CostModel::v4_10(), 256, 261, 18.90),
            (CostModel::measured(), 64, 69, 0.60),
        ];
        let ratio = |m: &CostModel, count, objects, want: f64| {
            ms(m.ops(&[Op::ZmqCall, Op::Remove { count, objects }])) / want
        };
        for (m, count, objects, want) in removals {
            let r = ratio(&m, count, objects, want);
            assert!(
                (0.75..=1.33).contains(&r),
                "{count} among {objects}: x{r:.2}"
            );
        }
        // A known gap: removing part of a scene costs the real builds less than the spec's
        // fit (every object of a scene removed) says, 1.4-1.9 times over for 256 of 261 on
        // 4.5.1 and among 1,000 objects on both (same section); the bound fails once the model
        // is mended, to be tightened then.
        let big = [
            (CostModel::measured(), 256, 261, 3.57),
            (CostModel::v4_10(), 64, 1069, 7.30),
            (CostModel::v4_10(), 256, 1261, 39.39),
            (CostModel::measured(), 64, 1069, 5.12),
            (CostModel::measured(), 256, 1261, 21.76),
        ];
        for (m, count, objects, want) in big {
            let r = ratio(&m, count, objects, want);
            assert!(
                (1.33..=2.0).contains(&r),
                "{count} among {objects}: x{r:.2}"
            );
        }
        let tree = |m: &CostModel, handles| ms(m.ops(&[Op::ZmqTree { handles }]));
        let r = tree(&CostModel::v4_10(), 1005) / 2.13;
        assert!((0.75..=1.33).contains(&r), "4.10 tree: x{r:.2}");
        let r = tree(&CostModel::measured(), 1005) / 1.44;
        assert!((0.75..=1.33).contains(&r), "4.5.1 tree: x{r:.2}");
    }
}
