//! Our real clients against an instant emulator that keeps a ledger of the simulator's work,
//! priced by the pure cost model as the lock-step client the rows were measured with
//! (`vrep_maze::sim::cost::price_lock_step`: one main-loop pass per request, where our client
//! now sends some requests together, served by one pass), against the times a
//! real CoppeliaSim 4.5.1 took for the same steps (`../shared/spec/real-coppeliasim-4.5.1.md`,
//! "Costs that grow with the scene", the table "through `vrep-maze`", which holds every row of
//! issue 18's table). Every step must be within a factor 0.75..1.33 of the real figure. No
//! wall clock is measured: the ledger is priced.

use std::sync::Arc;
use std::time::Duration;

use vrep_maze::coppelia::DEFAULT_IDLE_FPS;
use vrep_maze::draw::{self, ApplyOptions, Backend};
use vrep_maze::legacy::{self, LegacyBackend};
use vrep_maze::sim::cost::price_lock_step;
use vrep_maze::sim::{Clock, CostModel, Simulator};
use vrep_maze::zmq_api::{self, ClientOptions, Protocol, ZmqBackend};

use crate::support::layouts::drawing;

/// The legacy server and a ZeroMQ protocol-1 server over one simulator (as `serve --api
/// both`), at CoppeliaSim's default idle rate, instant.
struct Both {
    legacy: Arc<legacy::ServerHandle>,
    zmq: zmq_api::ServerHandle,
}

impl Both {
    fn start() -> Both {
        let sim = Simulator::new(crate::support::layouts::big_course(), DEFAULT_IDLE_FPS);
        let cfg = legacy::ServerConfig {
            listen: "127.0.0.1:0".parse().unwrap(),
            ..Default::default()
        };
        let legacy = Arc::new(legacy::spawn(cfg, sim).unwrap());
        let cfg = zmq_api::ServerConfig {
            listen: "127.0.0.1:0".parse().unwrap(),
            protocol: Protocol::V1,
            ..Default::default()
        };
        let zmq = zmq_api::spawn_shared(cfg, legacy.clone()).unwrap();
        Both { legacy, zmq }
    }

    fn connect(&self, zmq: bool) -> Box<dyn Backend> {
        let timeout = Duration::from_secs(30);
        if zmq {
            Box::new(
                ZmqBackend::connect(&ClientOptions {
                    port: self.zmq.local_addr().port(),
                    timeout,
                    ..Default::default()
                })
                .unwrap(),
            )
        } else {
            Box::new(
                LegacyBackend::connect("127.0.0.1", self.legacy.local_addr().port(), timeout)
                    .unwrap(),
            )
        }
    }

    /// Draws the `n` x `n` course maze (Prim, seed 42, as the spec's runs) with our client
    /// over the chosen API; returns what a real 4.5.1 would have taken, priced from the
    /// ledger of the simulator's work, and the round trips our client took.
    fn apply(&self, zmq: bool, n: u64) -> (f64, usize) {
        self.legacy.with_sim(|s| s.ledger = Some(vec![]));
        let mut backend = self.connect(zmq);
        let d = drawing(n, 42);
        let report =
            draw::apply(backend.as_mut(), &d, &ApplyOptions::default(), &mut |_| {}).unwrap();
        backend.close().unwrap();
        let ledger = self.legacy.with_sim(|s| s.ledger.take()).unwrap();
        let priced = price_lock_step(&Clock::default(), &CostModel::measured(), &ledger);
        (priced.as_secs_f64(), report.round_trips)
    }

    fn shutdown(self) {
        self.zmq.shutdown();
        Arc::try_unwrap(self.legacy)
            .ok()
            .expect("nothing else holds the legacy server")
            .shutdown();
    }
}

/// `modelled` within a factor 0.75..1.33 of `real`.
fn close_to(step: &str, modelled: f64, real: f64) -> Result<(), String> {
    let ratio = modelled / real;
    if (0.75..=1.33).contains(&ratio) {
        Ok(())
    } else {
        Err(format!(
            "{step}: modelled {modelled:.2} s, real 4.5.1 {real} s (x{ratio:.2})"
        ))
    }
}

/// Runs the steps (API, maze size, the real figure) in order on one scene, and fails
/// naming every step the model misses.
fn check(both: &Both, steps: &[(&str, bool, u64, f64)]) {
    let misses: Vec<String> = steps
        .iter()
        .filter_map(|&(step, zmq, n, real)| {
            let (modelled, round_trips) = both.apply(zmq, n);
            eprintln!("{step}: modelled {modelled:.2} s, real {real} s, {round_trips} round trips");
            close_to(step, modelled, real).err()
        })
        .collect();
    assert!(misses.is_empty(), "{}", misses.join("\n"));
}

#[test]
fn the_legacy_rows_of_the_real_table_are_reproduced() {
    let both = Both::start();
    // spec "Costs that grow with the scene", through vrep-maze, legacy rows (the last is
    // issue 18's first row). The first draw into the course scene (0.92 s real) is mostly
    // connection and pacing the model does not price; it sets the scene up.
    both.apply(false, 9);
    check(
        &both,
        &[
            ("legacy: replace by 30x30", false, 30, 1.70),
            ("legacy: replace by 60x60", false, 60, 9.92),
            ("legacy: replace 60x60 by 100x100", false, 100, 62.1),
        ],
    );
    both.shutdown();
}

#[test]
fn the_zeromq_removal_rows_of_the_real_table_are_reproduced() {
    let both = Both::start();
    // the spec's ZeroMQ rows followed its legacy ones: the scene holds the 100x100 (drawn
    // here over the legacy API, which is faster to emulate than 40,000 ZeroMQ calls)
    both.apply(false, 100);
    check(
        &both,
        &[
            ("ZeroMQ: replace 100x100 by 30x30", true, 30, 32.4),
            ("ZeroMQ: replace 30x30 by 9x9", true, 9, 1.12),
        ],
    );
    both.apply(false, 100);
    check(&both, &[("ZeroMQ: replace 100x100 by 9x9", true, 9, 29.5)]);
    both.shutdown();
}

#[test]
#[ignore = "40,000 ZeroMQ calls: about a minute in a debug build (run with --ignored)"]
fn the_zeromq_draw_of_a_100x100_over_a_9x9_is_reproduced() {
    let both = Both::start();
    both.apply(true, 9);
    check(
        &both,
        &[("ZeroMQ: replace 9x9 by 100x100", true, 100, 139.8)],
    );
    both.shutdown();
}

/// `apply` of a 60x60 into the course scene (about 13 s on a real 4.5.1 by the model) warns
/// once on standard error, with the modelled seconds, and suggests `--draw mesh`; `-q`
/// silences it, and a 9x9 (under a second) draws without it.
#[test]
fn apply_warns_before_a_slow_copies_draw_unless_quiet() {
    use predicates::prelude::*;

    use crate::support::bin;
    use crate::support::cli::Serve;

    let dir = tempfile::tempdir().unwrap();
    let path = |n: &str| dir.path().join(format!("{n}.json")).display().to_string();
    for (n, size) in [("small", "9x9"), ("big", "60x60")] {
        bin()
            .args(["generate", "--seed", "42", "--size", size, "-o", &path(n)])
            .assert()
            .success();
    }
    let serve = |extra: &[&str]| {
        let scene = crate::support::layouts::big_course_file(dir.path());
        let mut args = vec![
            "--listen",
            "127.0.0.1:0",
            "--timing",
            "instant",
            "--scene",
            &scene,
        ];
        args.extend(extra);
        Serve::start(&args, 1)
    };
    let warning = predicate::str::is_match(
        r"(?m)^warning: drawing this maze as copies takes about \d+ s on a real CoppeliaSim 4\.5\.1 .*--draw mesh",
    )
    .unwrap();
    let s = serve(&[]);
    bin()
        .args(["apply", &path("small"), "--port", &s.port()])
        .assert()
        .success()
        .stderr(predicate::str::contains("warning").not());
    bin()
        .args(["apply", &path("big"), "--port", &s.port()])
        .assert()
        .success()
        .stderr(warning.count(1));
    drop(s);
    let s = serve(&[]);
    bin()
        .args(["-q", "apply", &path("big"), "--port", &s.port()])
        .assert()
        .success()
        .stderr(predicate::str::contains("warning").not());
}
