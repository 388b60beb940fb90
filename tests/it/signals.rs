//! The scene signals this tool keeps (`draw::signals`): named as valid property names, so
//! that CoppeliaSim 4.10 (emulated by protocol 2) keeps them; an older version's records
//! under `vrep-maze.*` still recognised where 4.5.1 kept them, and removed once rewritten;
//! a simulator that keeps no signal said so in one warning, and drawn without them.

use vrep_maze::draw::mesh::{self, MeshMaze};
use vrep_maze::draw::signals::{COPIES, HOME, LEASE, SAVED_IDLE_FPS, Signal};
use vrep_maze::draw::{
    self, ApplyOptions, ApplyReport, Backend, BackendError, BoundingBox, Claimed, ClearOptions,
    ClearReport, Drawing, Edit, IdleRates, Lease, ObjectInfo, ObjectNames, Stage, Survey,
    SurveyNames,
};
use vrep_maze::generate::Algorithm;
use vrep_maze::sim::Scene;
use vrep_maze::sim::property::is_property_name;

use crate::support::backend::{Kind, Server};
use crate::support::backend_tests;
use crate::support::layouts::{course_layout, drawing};

backend_tests!(apply_reapply_and_clear_keep_their_signals_under_property_names);

fn apply(b: &mut dyn Backend, d: &Drawing) -> ApplyReport {
    draw::apply(b, d, &ApplyOptions::default(), &mut |_| {}).unwrap()
}

fn clear(b: &mut dyn Backend) -> ClearReport {
    draw::clear(b, &ClearOptions::default()).unwrap()
}

/// The line template's world position.
fn line_at(s: &Server) -> [f64; 3] {
    s.with_sim(|sim| {
        let l = sim.scene.resolve("Line").unwrap();
        sim.scene.pose(l, -1).unwrap().0
    })
}

fn near(a: [f64; 3], b: [f64; 3]) -> bool {
    a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-5)
}

/// Every signal name in the scene, integer and string.
fn signal_names(s: &Server) -> Vec<String> {
    s.with_sim(|sim| {
        let ints = sim.int_signals.keys();
        ints.chain(sim.string_signals.keys()).cloned().collect()
    })
}

/// The signals a cleared scene holds: none but the copy record (which may keep handles that
/// name nothing any more, `draw::record`), and an older version's record only emptied (the
/// legacy API cannot delete a string signal).
fn assert_cleared(s: &Server, k: &str) {
    let (ints, strings) = s.with_sim(|sim| (sim.int_signals.clone(), sim.string_signals.clone()));
    assert!(ints.is_empty(), "{k}: {ints:?}");
    for (name, value) in strings {
        let emptied = name == COPIES.old && value.is_empty();
        assert!(name == COPIES.name || emptied, "{k}: {name}");
    }
}

/// Apply, re-apply over that maze, clear: every run succeeds (over protocol 2 the old
/// names were dropped, and the first apply failed as a concurrent run), the records live
/// under property names while a maze is drawn, `clear` puts the template back home from its
/// record and leaves no signal.
fn apply_reapply_and_clear_keep_their_signals_under_property_names(kind: Kind) {
    let k = kind.name();
    let s = kind.serve(Scene::course(), 8);
    let home = line_at(&s);
    let mut b = s.connect();
    let first = apply(&mut *b, &drawing(9, 42));
    assert!(first.warnings.is_empty(), "{k}: {:?}", first.warnings);
    let names = signal_names(&s);
    assert!(names.iter().all(|n| is_property_name(n)), "{k}: {names:?}");
    for signal in HOME.iter().chain([&COPIES]) {
        assert!(
            names.iter().any(|n| n == signal.name),
            "{k}: {signal:?} in {names:?}"
        );
    }
    drop(b);
    let mut b = s.connect();
    let again = drawing(9, 7);
    let r = apply(&mut *b, &again);
    assert!(r.reused > 0, "{k}: {r:?}");
    draw::verify(&mut *b, &again, &ObjectNames::default()).unwrap();
    drop(b);
    let mut b = s.connect();
    let r = clear(&mut *b);
    assert!(r.warnings.is_empty(), "{k}: {:?}", r.warnings);
    let said = r.template.unwrap_or_default();
    assert!(said.contains("back where it stood"), "{k}: {said}");
    assert!(near(line_at(&s), home), "{k}");
    drop(b);
    assert_eq!(s.idle_fps(), 8, "{k}");
    assert_cleared(&s, k);
    s.shutdown();
}

/// Moves every signal from its new name to its old one: the scene as a version before
/// `vrep_maze.*` left it on 4.5.1.
fn as_an_older_version_left_it(s: &Server) {
    let all: Vec<Signal> = HOME.into_iter().chain([LEASE, SAVED_IDLE_FPS]).collect();
    s.with_sim(|sim| {
        for signal in &all {
            if let Some(v) = sim.int_signals.remove(signal.name) {
                sim.int_signals.insert(signal.old.into(), v);
            }
        }
        let record = sim
            .string_signals
            .remove(COPIES.name)
            .expect("a copy record");
        sim.string_signals.insert(COPIES.old.into(), record);
    });
}

/// 4.5.1 keeps any name: a maze an older version drew has its records under `vrep-maze.*`.
/// A re-apply reads its copy record and its template home there and moves both to the new
/// names; `clear` of such a maze puts the template back home from the old record.
#[test]
fn a_maze_an_older_version_drew_on_4_5_1_is_still_recognised() {
    for kind in [Kind::Legacy, Kind::Zmq1] {
        let k = kind.name();
        let s = kind.serve(Scene::course(), 0);
        let home = line_at(&s);
        let d = drawing(9, 42);
        apply(&mut *s.connect(), &d);
        as_an_older_version_left_it(&s);
        // the old records are read (the copies known, the home kept) and moved to the new
        // names
        let r = apply(&mut *s.connect(), &drawing(9, 7));
        assert!(
            r.reused > 0 && r.warnings.is_empty(),
            "{k}: {r:?} {:?}",
            r.warnings
        );
        let names = signal_names(&s);
        assert!(names.iter().any(|n| n == COPIES.name), "{k}: {names:?}");
        assert!(
            HOME.iter().all(|h| names.iter().any(|n| n == h.name)),
            "{k}: {names:?}"
        );
        assert!(
            s.with_sim(|sim| sim.int_signals.keys().all(|n| is_property_name(n))
                && sim.string_signals.get(COPIES.old).is_none_or(Vec::is_empty)),
            "{k}: {names:?}"
        );
        // and clear, over an old record of the template's home
        as_an_older_version_left_it(&s);
        let r = clear(&mut *s.connect());
        let said = r.template.unwrap_or_default();
        assert!(said.contains("back where it stood"), "{k}: {said}");
        assert!(near(line_at(&s), home), "{k}");
        assert_eq!(s.line_count(), 1, "{k}");
        assert_cleared(&s, k);
        s.shutdown();
    }
}

/// A run interrupted by an older version left the user's idle rate in the old signal: the
/// next run restores it from there and removes it.
#[test]
fn an_idle_rate_an_older_version_saved_is_restored() {
    for kind in Kind::ALL {
        let k = kind.name();
        let s = kind.serve(Scene::course(), 0);
        s.with_sim(|sim| sim.int_signals.insert(SAVED_IDLE_FPS.old.into(), 8));
        let r = clear(&mut *s.connect());
        assert_eq!(r.restored_idle_fps, Some(8), "{k}");
        assert_eq!(s.idle_fps(), 8, "{k}");
        assert_cleared(&s, k);
        s.shutdown();
    }
}

/// A connection to a simulator that keeps no signal: whatever is written is gone when read.
struct Forgetful(Box<dyn Backend>);

impl Backend for Forgetful {
    fn idle_rates(&mut self) -> Result<IdleRates, BackendError> {
        self.0.idle_rates()
    }
    fn survey(&mut self, names: &SurveyNames<'_>) -> Result<Survey, BackendError> {
        self.0.survey(names)
    }
    fn objects(&mut self) -> Result<Vec<ObjectInfo>, BackendError> {
        self.0.objects()
    }
    fn objects_from_scene(&mut self) -> Result<Vec<ObjectInfo>, BackendError> {
        self.0.objects_from_scene()
    }
    fn bounding_boxes(
        &mut self,
        handles: &[i32],
    ) -> Result<Vec<Option<BoundingBox>>, BackendError> {
        self.0.bounding_boxes(handles)
    }
    fn sizes(&mut self, handles: &[i32]) -> Result<Vec<Option<[f64; 3]>>, BackendError> {
        self.0.sizes(handles)
    }
    fn int_signals(&mut self, names: &[&str]) -> Result<Vec<Option<i32>>, BackendError> {
        Ok(vec![None; names.len()])
    }
    fn set_int_signals(&mut self, _: &[(&str, Option<i32>)]) -> Result<(), BackendError> {
        Ok(())
    }
    fn copy_paste(&mut self, groups: &[Vec<i32>]) -> Result<Vec<Vec<i32>>, BackendError> {
        self.0.copy_paste(groups)
    }
    fn edit(&mut self, edits: &[Edit]) -> Result<(), BackendError> {
        self.0.edit(edits)
    }
    fn set_idle_fps(&mut self, fps: i32, saved: Option<i32>) -> Result<(), BackendError> {
        self.0.set_idle_fps(fps, saved)
    }
    fn stop_simulation(&mut self) -> Result<(), BackendError> {
        self.0.stop_simulation()
    }
    fn round_trips(&self) -> usize {
        self.0.round_trips()
    }
    fn describe(&self) -> String {
        format!("{}, keeping no signal", self.0.describe())
    }
    fn lease(&mut self) -> Option<&mut dyn Lease> {
        Some(self)
    }
}

impl Lease for Forgetful {
    fn claim(&mut self, token: i32) -> Result<Claimed, BackendError> {
        let claimed = self.0.lease().expect("a ZeroMQ lease").claim(token)?;
        Ok(Claimed {
            read_back: None,
            ..claimed
        })
    }
    fn holder(&mut self) -> Result<Option<i32>, BackendError> {
        Ok(None)
    }
    fn release(&mut self) -> Result<(), BackendError> {
        Ok(())
    }
    fn unkept(&mut self) {
        self.0.lease().expect("a ZeroMQ lease").unkept()
    }
}

/// The lease does not read back: one warning naming the signal and the simulator, never a
/// false "another apply started"; the maze is drawn and verified, the copy record is neither
/// relied on nor written, `clear` says why it cannot put the template back, and the user's
/// idle rate comes back from memory.
#[test]
fn a_simulator_that_keeps_no_signal_is_said_so_and_drawn_without_them() {
    let s = Kind::Zmq2.serve(Scene::course(), 8);
    let mut b = Forgetful(s.connect());
    let d = drawing(9, 42);
    let r = apply(&mut b, &d);
    let unkept = |w: &[String]| {
        w.iter()
            .filter(|w| {
                w.contains("did not keep the integer signal `vrep_maze.lease`")
                    && w.contains("keeping no signal")
            })
            .count()
    };
    assert_eq!(unkept(&r.warnings), 1, "{:?}", r.warnings);
    draw::verify(&mut b, &d, &ObjectNames::default()).unwrap();
    assert_eq!(s.idle_fps(), 8);
    assert!(s.with_sim(|sim| !sim.string_signals.contains_key(COPIES.name)));
    let again = drawing(9, 7);
    let r = apply(&mut b, &again);
    assert_eq!(unkept(&r.warnings), 1, "{:?}", r.warnings);
    draw::verify(&mut b, &again, &ObjectNames::default()).unwrap();
    let r = clear(&mut b);
    assert_eq!(unkept(&r.warnings), 1, "{:?}", r.warnings);
    let said = r.template.unwrap_or_default();
    assert!(
        said.contains("keeps no signals") && said.contains("below the floor"),
        "{said}"
    );
    assert_eq!(s.line_count(), 1);
    assert_eq!(s.idle_fps(), 8);
    drop(b);
    s.shutdown();
}

/// The last check of a run is made by its release's read of the lease (one request fewer):
/// a run whose scene another run claims after its last check but before that read (in a
/// mesh apply, between "verifying" and the release only the meshes are read back) still
/// fails with "another run ... while verifying", and leaves the other run's claim in place,
/// over both ZeroMQ protocols (the legacy API, one client at a time, has no lease).
#[test]
fn a_claim_taken_after_the_last_read_fails_the_run_and_stays() {
    const OTHER: i32 = 0x5eed;
    for kind in [Kind::Zmq1, Kind::Zmq2] {
        let k = kind.name();
        let s = kind.serve(Scene::course(), 0);
        let mut b = s.connect();
        let maze = MeshMaze::try_from(&course_layout(Algorithm::Dfs, 5, 5, 7)).unwrap();
        let mut take_over = |stage: Stage| {
            if matches!(stage, Stage::Verifying) {
                s.with_sim(|sim| sim.int_signals.insert(LEASE.name.into(), OTHER));
            }
        };
        match mesh::apply(&mut *b, &maze, &ApplyOptions::default(), &mut take_over) {
            Err(draw::DrawError::Concurrent { phase }) => {
                assert_eq!(phase, "while verifying", "{k}")
            }
            other => panic!("{k}: {other:?}"),
        }
        let kept = s.with_sim(|sim| sim.int_signals.get(LEASE.name).copied());
        assert_eq!(kept, Some(OTHER), "{k}: the other run's claim was cleared");
        drop(b);
        s.shutdown();
    }
}
