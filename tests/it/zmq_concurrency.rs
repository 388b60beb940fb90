//! Two runs drawing into one ZeroMQ scene at once: each either verifies a scene that holds
//! exactly its maze, or fails with a clear error; "verified" never describes a wrong scene.

use std::time::Duration;

use vrep_maze::draw::{self, ApplyOptions, DrawError, Drawing, ObjectNames};
use vrep_maze::generate::Algorithm;
use vrep_maze::layout::{GenerateSpec, build_layout};
use vrep_maze::maze::Grid;
use vrep_maze::sim::Simulator;
use vrep_maze::zmq_api::{ClientOptions, Protocol, ServerConfig, ZmqBackend, spawn};

fn drawing(n: u64, seed: u64) -> Drawing {
    let spec = GenerateSpec::course(Grid::new(n, n).unwrap(), Algorithm::Prim, seed);
    Drawing::try_from(&build_layout(&spec).unwrap()).unwrap()
}

fn connect(port: u16) -> ZmqBackend {
    ZmqBackend::connect(&ClientOptions {
        port,
        timeout: Duration::from_secs(5),
        ..Default::default()
    })
    .unwrap()
}

#[test]
fn concurrent_applies_never_verify_a_wrong_scene() {
    let config = ServerConfig {
        listen: "127.0.0.1:0".parse().unwrap(),
        protocol: Protocol::V2,
        ..Default::default()
    };
    let server = spawn(
        config,
        Simulator::new(crate::support::layouts::big_course(), 0),
    )
    .unwrap();
    let port = server.local_addr().port();
    let (mut verified, mut refused) = (0, 0);
    for trial in 0..4u64 {
        // the same maze twice (the observed 1,186-instead-of-798 case) and two different ones
        let (a, b) = if trial % 2 == 0 {
            (drawing(20, trial), drawing(20, trial))
        } else {
            (drawing(20, trial), drawing(12, trial + 100))
        };
        let runs: Vec<_> = [a, b]
            .into_iter()
            .map(|d| {
                std::thread::spawn(move || {
                    let mut backend = connect(port);
                    let r = draw::apply(&mut backend, &d, &ApplyOptions::default(), &mut |_| {});
                    (d, r)
                })
            })
            .collect();
        let results: Vec<_> = runs.into_iter().map(|t| t.join().unwrap()).collect();
        for (d, r) in &results {
            match r {
                Ok(_) => {
                    verified += 1;
                    // the scene holds exactly this maze, checked by a fresh reader
                    let mut check = connect(port);
                    draw::verify(&mut check, d, &ObjectNames::default()).unwrap_or_else(|e| {
                        panic!("trial {trial}: a run said verified but the scene differs: {e}")
                    });
                }
                Err(DrawError::Concurrent { .. } | DrawError::Verify(_)) => refused += 1,
                Err(e) => panic!("trial {trial}: unexpected error {e}"),
            }
        }
        // either way, running one apply alone repairs the scene
        let (d, _) = &results[0];
        let mut alone = connect(port);
        draw::apply(&mut alone, d, &ApplyOptions::default(), &mut |_| {}).unwrap();
    }
    eprintln!("{verified} verified, {refused} refused");
    assert!(
        verified + refused == 8,
        "{verified} verified, {refused} refused"
    );
    server.shutdown();
}
