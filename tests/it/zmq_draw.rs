//! apply / clear / verify over the ZeroMQ backend against the in-process server, in both
//! protocols; fresh scenes with --create-missing; legacy and ZeroMQ drawing the same scene.

use std::sync::Arc;
use std::time::Duration;

use ciborium::Value;
use vrep_maze::coppelia::HANDLE_WORLD;
use vrep_maze::draw::{
    self, ApplyOptions, Authoring, Backend, BackendError, DrawError, Drawing, Edit, ObjectInfo,
    ObjectNames, Survey,
};
use vrep_maze::generate::Algorithm;
use vrep_maze::layout::{GenerateSpec, build_layout};
use vrep_maze::legacy::{self, LegacyBackend};
use vrep_maze::maze::Grid;
use vrep_maze::sim::{Scene, Simulator};
use vrep_maze::zmq_api::cbor::{self, int};
use vrep_maze::zmq_api::{
    ClientOptions, Protocol, ServerConfig, ServerHandle, ZmqBackend, spawn, spawn_shared,
};

fn drawing(n: u64, seed: u64) -> Drawing {
    let spec = GenerateSpec::course(Grid::new(n, n).unwrap(), Algorithm::Prim, seed);
    Drawing::from(&build_layout(&spec).unwrap())
}

fn config(protocol: Protocol) -> ServerConfig {
    ServerConfig {
        listen: "127.0.0.1:0".parse().unwrap(),
        protocol,
        ..Default::default()
    }
}

fn server(scene: Scene, fps: i32, protocol: Protocol) -> ServerHandle {
    spawn(config(protocol), Simulator::new(scene, fps)).unwrap()
}

fn connect(port: u16) -> ZmqBackend {
    ZmqBackend::connect(&ClientOptions {
        port,
        timeout: Duration::from_secs(3),
        ..Default::default()
    })
    .unwrap()
}

fn no_progress(_: draw::Stage) {}

fn line_count(s: &ServerHandle) -> usize {
    s.with_sim(|sim| sim.scene.objects().filter(|o| o.alias == "Line").count())
}

fn apply_and_reapply(protocol: Protocol) {
    let s = server(Scene::course(), 8, protocol);
    let mut sc = connect(s.local_addr().port());
    assert_eq!(sc.client().protocol(), Some(protocol));
    let d = drawing(9, 42);
    let r = draw::apply(&mut sc, &d, &ApplyOptions::default(), &mut no_progress).unwrap();
    assert_eq!((r.lines, r.pasted, r.reused, r.removed), (160, 159, 0, 0));
    assert_eq!(line_count(&s), 160);
    assert_eq!(
        s.with_sim(|sim| sim.idle_fps),
        8,
        "user's idle rate restored"
    );
    draw::verify(&mut sc, &d, &ObjectNames::default()).unwrap();
    let again = draw::apply(&mut sc, &d, &ApplyOptions::default(), &mut no_progress).unwrap();
    assert_eq!(
        (again.pasted, again.removed, again.edits, again.reused),
        (0, 0, 0, 159),
        "{again}"
    );
    let small = drawing(3, 2);
    let r = draw::apply(&mut sc, &small, &ApplyOptions::default(), &mut no_progress).unwrap();
    assert_eq!((r.pasted, r.removed), (0, 160 - small.lines.len()));
    assert!(matches!(
        draw::verify(&mut sc, &d, &ObjectNames::default()),
        Err(DrawError::Verify(_))
    ));
    let c = draw::clear(&mut sc, &ObjectNames::default(), false).unwrap();
    assert_eq!(c.removed.len(), small.lines.len() - 1);
    assert_eq!(line_count(&s), 1, "only the template is left");
    assert!(
        draw::clear(&mut sc, &ObjectNames::default(), false)
            .unwrap()
            .removed
            .is_empty()
    );
    drop(sc);
    s.shutdown();
}

#[test]
fn zmq_apply_verify_reapply_replace_clear_protocol_2() {
    apply_and_reapply(Protocol::V2);
}

#[test]
fn zmq_apply_verify_reapply_replace_clear_protocol_1() {
    apply_and_reapply(Protocol::V1);
}

#[test]
fn zmq_create_missing_in_an_empty_scene() {
    let s = server(Scene::empty(), 0, Protocol::V2);
    let mut sc = connect(s.local_addr().port());
    let d = drawing(4, 1);
    let names = ObjectNames::default();
    match draw::apply(&mut sc, &d, &ApplyOptions::default(), &mut no_progress) {
        Err(DrawError::Missing { names, .. }) => {
            assert_eq!(names, ["Floor", "Maze", "Line", "Start", "End"])
        }
        other => panic!("{other:?}"),
    }
    let created = sc.create_missing(&names).unwrap();
    assert_eq!(created, ["Floor", "Maze", "Line", "Start", "End"]);
    assert!(sc.create_missing(&names).unwrap().is_empty(), "idempotent");
    draw::apply(&mut sc, &d, &ApplyOptions::default(), &mut no_progress).unwrap();
    s.with_sim(|sim| {
        let get = |n: &str| {
            sim.scene
                .get(sim.scene.resolve(n).unwrap())
                .unwrap()
                .clone()
        };
        let (line, start, end, maze) = (get("Line"), get("Start"), get("End"), get("Maze"));
        assert_eq!((line.size, line.colour), ([0.6, 0.1, 0.0], [0, 255, 0]));
        assert_eq!((start.size, start.colour), ([1.0, 1.0, 0.0], [0, 0, 255]));
        assert_eq!((end.size, end.colour), ([1.0, 1.0, 0.0], [255, 0, 0]));
        assert_eq!(maze.kind.code(), 4, "Maze is a dummy");
        let (p, _) = sim.scene.pose(start.handle, HANDLE_WORLD).unwrap();
        assert!((p[2] - 0.002).abs() < 1e-9);
    });
    // not collidable, measurable or detectable; renderable (the camera sees it); static, not respondable
    let mut c = vrep_maze::zmq_api::Client::connect(&ClientOptions {
        port: s.local_addr().port(),
        ..Default::default()
    })
    .unwrap();
    let line = c
        .call_int("sim.getObject", vec![Value::Text("/Line".into())])
        .unwrap();
    assert_eq!(
        c.call_int("sim.getObjectSpecialProperty", vec![int(line.into())])
            .unwrap(),
        2048
    );
    assert_eq!(
        c.call_int("sim.getObjectInt32Param", vec![int(line.into()), int(3004)])
            .unwrap(),
        0
    );
    assert_eq!(
        c.call_int("sim.getObjectInt32Param", vec![int(line.into()), int(3003)])
            .unwrap(),
        1
    );
    let path = std::env::temp_dir().join(format!("vrep-maze-zmq-save-{}.json", std::process::id()));
    sc.save_scene(path.to_str().unwrap()).unwrap();
    let saved = Scene::from_json(&std::fs::read_to_string(&path).unwrap()).unwrap();
    assert_eq!(saved.len(), 4 + d.lines.len());
    let _ = std::fs::remove_file(path);
    s.shutdown();
}

#[test]
fn zmq_refuses_a_running_simulation_and_stops_it_when_asked() {
    let s = server(Scene::course(), 0, Protocol::V2);
    s.with_sim(|sim| sim.start());
    let mut sc = connect(s.local_addr().port());
    let d = drawing(3, 3);
    assert!(matches!(
        draw::apply(&mut sc, &d, &ApplyOptions::default(), &mut no_progress),
        Err(DrawError::SimulationRunning)
    ));
    let opts = ApplyOptions {
        stop_simulation: true,
        ..Default::default()
    };
    let r = draw::apply(&mut sc, &d, &opts, &mut no_progress).unwrap();
    assert!(r.stopped_simulation);
    assert_eq!(line_count(&s), d.lines.len());
    s.shutdown();
}

/// Fails every edit: the idle rate must still be restored.
struct FailingEdits(ZmqBackend);

impl Backend for FailingEdits {
    fn survey(&mut self, names: &[&str]) -> Result<Survey, BackendError> {
        self.0.survey(names)
    }
    fn objects(&mut self) -> Result<Vec<ObjectInfo>, BackendError> {
        self.0.objects()
    }
    fn copy_paste(&mut self, groups: &[Vec<i32>]) -> Result<Vec<Vec<i32>>, BackendError> {
        self.0.copy_paste(groups)
    }
    fn edit(&mut self, _: &[Edit]) -> Result<(), BackendError> {
        Err(BackendError::Remote("injected failure".into()))
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
        format!("{} failing every edit", self.0.describe())
    }
}

#[test]
fn zmq_idle_rate_restored_on_error_and_next_apply_repairs() {
    let s = server(Scene::course(), 8, Protocol::V2);
    let port = s.local_addr().port();
    let d = drawing(5, 9);
    let mut failing = FailingEdits(connect(port));
    let e = draw::apply(&mut failing, &d, &ApplyOptions::default(), &mut no_progress).unwrap_err();
    assert!(e.to_string().contains("injected failure"), "{e}");
    assert_eq!(s.with_sim(|sim| sim.idle_fps), 8);
    // the pasted copies are parentless root objects with alias Line: found again as strays
    let mut sc = connect(port);
    let r = draw::apply(&mut sc, &d, &ApplyOptions::default(), &mut no_progress).unwrap();
    assert_eq!((r.pasted, r.reused), (0, d.lines.len() - 1), "{r}");
    assert_eq!(line_count(&s), d.lines.len());
    s.shutdown();
}

type Snapshot = Vec<(String, Option<String>, [i64; 6])>;

/// Every object as (alias, parent alias, world pose rounded to 0.1 mm / 0.1 mrad), sorted.
fn snapshot(sim: &Simulator) -> Snapshot {
    let r = |x: f64| (x * 1e4).round() as i64;
    let mut out: Snapshot = sim
        .scene
        .objects()
        .map(|o| {
            let (p, e) = sim.scene.pose(o.handle, HANDLE_WORLD).unwrap();
            let parent = o.parent.map(|p| sim.scene.get(p).unwrap().alias.clone());
            (
                o.alias.clone(),
                parent,
                [r(p[0]), r(p[1]), r(p[2]), r(e[0]), r(e[1]), r(e[2])],
            )
        })
        .collect();
    out.sort();
    out
}

#[test]
fn zmq_and_legacy_draw_the_same_scene() {
    let d = drawing(9, 42);
    let lg = legacy::spawn(
        legacy::ServerConfig {
            listen: "127.0.0.1:0".parse().unwrap(),
            ..Default::default()
        },
        Simulator::new(Scene::course(), 0),
    )
    .unwrap();
    let mut l = LegacyBackend::connect("127.0.0.1", lg.local_addr().port(), Duration::from_secs(3))
        .unwrap();
    draw::apply(&mut l, &d, &ApplyOptions::default(), &mut no_progress).unwrap();
    l.close().unwrap();
    let z = server(Scene::course(), 0, Protocol::V2);
    let mut sc = connect(z.local_addr().port());
    draw::apply(&mut sc, &d, &ApplyOptions::default(), &mut no_progress).unwrap();
    let (a, b) = (lg.with_sim(|s| snapshot(s)), z.with_sim(|s| snapshot(s)));
    assert_eq!(a.len(), 164, "Floor, Maze, Start, End and 160 lines");
    assert_eq!(a, b);
    z.shutdown();
    lg.shutdown();
}

#[test]
fn zmq_and_legacy_share_one_scene_with_api_both() {
    let lg = legacy::spawn(
        legacy::ServerConfig {
            listen: "127.0.0.1:0".parse().unwrap(),
            ..Default::default()
        },
        Simulator::new(Scene::course(), 0),
    )
    .unwrap();
    let lg = Arc::new(lg);
    let z = spawn_shared(config(Protocol::V2), lg.clone()).unwrap();
    let d = drawing(6, 5);
    let mut sc = connect(z.local_addr().port());
    draw::apply(&mut sc, &d, &ApplyOptions::default(), &mut no_progress).unwrap();
    drop(sc);
    // verified through the other API
    let mut l = LegacyBackend::connect("127.0.0.1", lg.local_addr().port(), Duration::from_secs(3))
        .unwrap();
    draw::verify(&mut l, &d, &ObjectNames::default()).unwrap();
    let cleared = draw::clear(&mut l, &ObjectNames::default(), false).unwrap();
    assert_eq!(cleared.removed.len(), d.lines.len() - 1);
    l.close().unwrap();
    let mut c = vrep_maze::zmq_api::Client::connect(&ClientOptions {
        port: z.local_addr().port(),
        ..Default::default()
    })
    .unwrap();
    let maze = c
        .call_int("sim.getObject", vec![Value::Text("/Maze".into())])
        .unwrap();
    let kids = c
        .call1(
            "sim.getObjectsInTree",
            vec![int(maze.into()), int(-2), int(3)],
        )
        .unwrap();
    assert_eq!(cbor::handles(&kids), Some(vec![]));
    drop(c);
    z.shutdown();
    Arc::try_unwrap(lg).ok().unwrap().shutdown();
}

#[test]
fn zmq_template_inside_the_maze_dummy_is_kept_and_reused() {
    let mut scene = Scene::course();
    let (maze, line) = (
        scene.resolve("Maze").unwrap(),
        scene.resolve("Line").unwrap(),
    );
    scene.set_parent(line, Some(maze), true).unwrap();
    let s = server(scene, 0, Protocol::V2);
    let mut sc = connect(s.local_addr().port());
    let d = drawing(3, 4);
    let r = draw::apply(&mut sc, &d, &ApplyOptions::default(), &mut no_progress).unwrap();
    assert_eq!(r.pasted, d.lines.len() - 1);
    let again = draw::apply(&mut sc, &d, &ApplyOptions::default(), &mut no_progress).unwrap();
    assert_eq!((again.pasted, again.edits), (0, 0), "{again}");
    let c = draw::clear(&mut sc, &ObjectNames::default(), false).unwrap();
    assert_eq!(c.removed.len(), d.lines.len() - 1);
    assert_eq!(line_count(&s), 1);
    drop(sc);
    s.shutdown();
}
