//! What only the ZeroMQ backend does: fresh scenes with --create-missing and saving them
//! (both protocols), and serving one scene with the legacy API (`--api both`). The
//! scenarios every backend shares are in `draw`.

use std::sync::Arc;
use std::time::Duration;

use ciborium::Value;
use vrep_maze::coppelia::HANDLE_WORLD;
use vrep_maze::draw::{self, ApplyOptions, Backend, DrawError, ObjectNames};
use vrep_maze::legacy::{self, LegacyBackend};
use vrep_maze::sim::{Scene, Simulator};
use vrep_maze::zmq_api::cbor::{self, int};
use vrep_maze::zmq_api::{ClientOptions, Protocol, ServerConfig, ZmqBackend, spawn_shared};

use crate::support::backend::Kind;
use crate::support::layouts::drawing;

fn config(protocol: Protocol) -> ServerConfig {
    ServerConfig {
        listen: "127.0.0.1:0".parse().unwrap(),
        protocol,
        ..Default::default()
    }
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

#[test]
fn zmq_create_missing_in_an_empty_scene_protocol_2() {
    create_missing_in_an_empty_scene(Kind::Zmq2);
}

#[test]
fn zmq_create_missing_in_an_empty_scene_protocol_1() {
    create_missing_in_an_empty_scene(Kind::Zmq1);
}

fn create_missing_in_an_empty_scene(kind: Kind) {
    let s = kind.serve(Scene::empty(), 0);
    let mut sc = s.connect();
    let d = drawing(4, 1);
    let names = ObjectNames::default();
    match draw::apply(&mut *sc, &d, &ApplyOptions::default(), &mut no_progress) {
        Err(DrawError::Missing { objects, .. }) => {
            let names: Vec<&str> = objects.iter().map(|(_, name)| name.as_str()).collect();
            assert_eq!(names, ["Floor", "Maze", "Line", "Start", "End"])
        }
        other => panic!("{other:?}"),
    }
    let created = sc
        .authoring()
        .unwrap()
        .create_missing(&names, &d.sizes)
        .unwrap();
    assert_eq!(created, ["Floor", "Maze", "Line", "Start", "End"]);
    assert!(
        sc.authoring()
            .unwrap()
            .create_missing(&names, &d.sizes)
            .unwrap()
            .is_empty(),
        "idempotent"
    );
    draw::apply(&mut *sc, &d, &ApplyOptions::default(), &mut no_progress).unwrap();
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
        port: s.addr().port(),
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
    let path = std::env::temp_dir().join(format!(
        "vrep-maze-zmq-save-{}-{kind:?}.json",
        std::process::id()
    ));
    sc.authoring()
        .unwrap()
        .save_scene(path.to_str().unwrap())
        .unwrap();
    let saved = Scene::from_json(&std::fs::read_to_string(&path).unwrap()).unwrap();
    assert_eq!(saved.len(), 4 + d.pieces.len());
    let _ = std::fs::remove_file(path);
    s.shutdown();
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
    let cleared = draw::clear(&mut l, &draw::ClearOptions::default()).unwrap();
    assert_eq!(cleared.removed.len(), d.pieces.len() - 1);
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
