//! An apply over ZeroMQ cut off after any number of calls (the simulator stops answering)
//! leaves a scene that the next apply, or clear, fully repairs.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use vrep_maze::draw::{self, ApplyOptions, Drawing, ObjectNames};
use vrep_maze::generate::Algorithm;
use vrep_maze::layout::{GenerateSpec, build_layout};
use vrep_maze::maze::Grid;
use vrep_maze::sim::{Scene, Simulator};
use vrep_maze::zmq_api::{ClientOptions, Protocol, ServerConfig, ServerHandle, ZmqBackend, spawn};

/// Forwards `limit` requests to `target`, then goes silent. Returns its port.
fn cutting_proxy(target: u16, limit: usize, stop: Arc<AtomicBool>) -> u16 {
    let ctx = zmq::Context::new();
    let front = ctx.socket(zmq::REP).unwrap();
    front.set_linger(0).unwrap();
    front.set_rcvtimeo(50).unwrap();
    front.bind("tcp://127.0.0.1:*").unwrap();
    let port = front
        .get_last_endpoint()
        .unwrap()
        .unwrap()
        .rsplit(':')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    let back = ctx.socket(zmq::REQ).unwrap();
    back.set_linger(0).unwrap();
    back.connect(&format!("tcp://127.0.0.1:{target}")).unwrap();
    std::thread::spawn(move || {
        let _ctx = ctx;
        let mut n = 0;
        while !stop.load(Ordering::SeqCst) {
            let Ok(req) = front.recv_bytes(0) else {
                continue;
            };
            if n >= limit {
                break; // silent from now on
            }
            n += 1;
            back.send(req, 0).unwrap();
            let reply = back.recv_bytes(0).unwrap();
            front.send(reply, 0).unwrap();
        }
        while !stop.load(Ordering::SeqCst) {
            std::thread::sleep(Duration::from_millis(20));
        }
    });
    port
}

fn connect(port: u16, ms: u64) -> Result<ZmqBackend, draw::BackendError> {
    ZmqBackend::connect(&ClientOptions {
        port,
        timeout: Duration::from_millis(ms),
        ..Default::default()
    })
}

fn lines(s: &ServerHandle) -> usize {
    s.with_sim(|sim| sim.scene.objects().filter(|o| o.alias == "Line").count())
}

#[test]
fn zmq_apply_cut_at_any_call_is_repaired() {
    let spec = GenerateSpec::course(Grid::new(4, 4).unwrap(), Algorithm::Prim, 3);
    let d = Drawing::from(&build_layout(&spec).unwrap());
    let other = Drawing::from(
        &build_layout(&GenerateSpec::course(
            Grid::new(3, 3).unwrap(),
            Algorithm::Prim,
            1,
        ))
        .unwrap(),
    );
    let cfg = ServerConfig {
        listen: "127.0.0.1:0".parse().unwrap(),
        protocol: Protocol::V2,
        ..Default::default()
    };
    for (i, limit) in [3usize, 8, 12, 14, 16, 20, 30, 45, 60, 75, 90]
        .into_iter()
        .enumerate()
    {
        let s = spawn(cfg.clone(), Simulator::new(Scene::course(), 0)).unwrap();
        if i % 2 == 1 {
            // start from an earlier, different maze
            let mut sc = connect(s.local_addr().port(), 3000).unwrap();
            draw::apply(&mut sc, &other, &ApplyOptions::default(), &mut |_| {}).unwrap();
        }
        let stop = Arc::new(AtomicBool::new(false));
        let proxy = cutting_proxy(s.local_addr().port(), limit, stop.clone());
        let cut = connect(proxy, 300).and_then(|mut sc| {
            draw::apply(&mut sc, &d, &ApplyOptions::default(), &mut |_| {})
                .map_err(|e| draw::BackendError::Transport(e.to_string()))
        });
        assert!(cut.is_err(), "cut after {limit} calls should fail");
        stop.store(true, Ordering::SeqCst);
        let mut sc = connect(s.local_addr().port(), 3000).unwrap();
        if i % 3 == 2 {
            draw::clear(&mut sc, &ObjectNames::default(), false).unwrap();
            assert_eq!(
                lines(&s),
                1,
                "clear after a cut at {limit} leaves only the template"
            );
        } else {
            draw::apply(&mut sc, &d, &ApplyOptions::default(), &mut |_| {}).unwrap();
            assert_eq!(lines(&s), d.lines.len(), "apply after a cut at {limit}");
            draw::verify(&mut sc, &d, &ObjectNames::default()).unwrap();
        }
        drop(sc);
        s.shutdown();
    }
}

#[test]
fn zmq_idle_rate_left_at_zero_by_an_interrupted_apply_is_restored() {
    let d = Drawing::from(
        &build_layout(&GenerateSpec::course(
            Grid::new(4, 4).unwrap(),
            Algorithm::Prim,
            3,
        ))
        .unwrap(),
    );
    let cfg = ServerConfig {
        listen: "127.0.0.1:0".parse().unwrap(),
        protocol: Protocol::V2,
        ..Default::default()
    };
    for repair_with_clear in [false, true] {
        let s = spawn(cfg.clone(), Simulator::new(Scene::course(), 8)).unwrap();
        let stop = Arc::new(AtomicBool::new(false));
        // 30 calls: past raising the idle rate, long before restoring it.
        let proxy = cutting_proxy(s.local_addr().port(), 30, stop.clone());
        let cut = connect(proxy, 300).and_then(|mut sc| {
            draw::apply(&mut sc, &d, &ApplyOptions::default(), &mut |_| {})
                .map_err(|e| draw::BackendError::Transport(e.to_string()))
        });
        assert!(cut.is_err());
        stop.store(true, Ordering::SeqCst);
        assert_eq!(
            s.with_sim(|sim| sim.idle_fps),
            0,
            "the cut run left the rate at 0"
        );
        let mut sc = connect(s.local_addr().port(), 3000).unwrap();
        if repair_with_clear {
            let report = draw::clear(&mut sc, &ObjectNames::default(), false).unwrap();
            assert_eq!(report.restored_idle_fps, Some(8));
        } else {
            draw::apply(&mut sc, &d, &ApplyOptions::default(), &mut |_| {}).unwrap();
        }
        drop(sc);
        let (fps, signals) = s.with_sim(|sim| (sim.idle_fps, sim.int_signals.len()));
        assert_eq!(
            (fps, signals),
            (8, 0),
            "user's rate restored and the record deleted"
        );
        s.shutdown();
    }
}
