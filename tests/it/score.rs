//! `score` end to end over every backend: an emulated robot (`serve --robot`) drives a path
//! while the simulation runs, and the scorer follows and grades it: a perfect run, a run
//! that stops short, one that cuts through walls, one whose simulation is stopped mid-run.

use std::thread;
use std::time::{Duration, Instant};

use vrep_maze::generate::Algorithm;
use vrep_maze::layout::Layout;
use vrep_maze::layout::walls::{WallOptions, into_walls};
use vrep_maze::legacy::follow::LegacyFollower;
use vrep_maze::maze::Grid;
use vrep_maze::score::follow::{FollowError, FollowOptions, Followed, Follower, Until, follow};
use vrep_maze::score::{GradeOptions, Grader, Report, Sample};
use vrep_maze::sim::{Clock, RobotPath, Scene, Simulator};
use vrep_maze::zmq_api::follow::ZmqFollower;
use vrep_maze::{legacy, zmq_api};

use crate::support::backend::{Kind, Server, TIMEOUT};
use crate::support::{backend_tests, course_layout};

/// A short simulation step, so a run of a few simulated seconds takes a fraction of that.
const STEP: Duration = Duration::from_millis(20);

/// Simulated seconds the robot stands at its start before it drives.
const DWELL: f64 = 0.3;

/// The robot's speed, metres a second (the emulated simulation runs in real time, a step
/// every [`STEP`]): a follower slowed by a busy machine may miss 600 ms of steps and still
/// see every half cell, as `score` needs to grade the run (at 1.6 m/s, a load of 15 on two
/// cores made one miss 490 ms).
const SPEED: f64 = 0.8;

/// The 3 x 3 course maze (DFS, seed 1): cell (i, j) at floor (i - 1, j - 1), Start in
/// (0, 0), End in (2, 0); the solution goes up column 0, along row 2 and down column 2
/// (6 cells, 6 m), and walls stand between (0, 0), (1, 0) and (2, 0).
fn maze(walls: bool) -> Layout {
    let mut layout = course_layout(Algorithm::Dfs, 3, 3, 1);
    if walls {
        let grid = Grid::new(3, 3).unwrap();
        let maze = vrep_maze::layout::passages::decode(grid, &layout.passages).unwrap();
        into_walls(&mut layout, &maze, &WallOptions::default(), true).unwrap();
    }
    layout
}

/// Waypoints through floor points at `speed` m/s, after [`DWELL`] at the first one (so the
/// scorer, which may join a few steps after the start, sees where the robot started).
fn path(points: &[(f64, f64)], speed: f64) -> Vec<Sample> {
    let (x, y) = points[0];
    let mut t = DWELL;
    let mut out: Vec<Sample> = vec![Sample {
        t: 0.0,
        x,
        y,
        yaw: 0.0,
    }];
    for &(x, y) in points {
        if let Some(last) = out.last() {
            t += (x - last.x).hypot(y - last.y) / speed;
        }
        out.push(Sample { t, x, y, yaw: 0.0 });
    }
    out
}

/// The solution of [`maze`], centre to centre.
const SOLUTION: [(f64, f64); 4] = [(-1.0, -1.0), (-1.0, 1.0), (1.0, 1.0), (1.0, -1.0)];

fn serve(kind: Kind, waypoints: Vec<Sample>) -> Server {
    let mut sim = Simulator::new(Scene::course(), 0);
    sim.robot = Some(RobotPath::add_to(&mut sim.scene, "Robot", waypoints).unwrap());
    let clock = Clock {
        step: STEP,
        ..Clock::default()
    };
    kind.serve_sim(sim, clock)
}

fn follower(kind: Kind, server: &Server) -> Box<dyn Follower> {
    let port = server.addr().port();
    match kind {
        Kind::Legacy => {
            let opts = legacy::ClientOptions {
                connect_timeout: TIMEOUT,
                reply_timeout: TIMEOUT,
                ..Default::default()
            };
            let client = legacy::Client::connect_with(
                format!("127.0.0.1:{port}").as_str(),
                opts,
                &mut |_| true,
            )
            .unwrap();
            Box::new(LegacyFollower::new(client))
        }
        Kind::Zmq1 | Kind::Zmq2 => {
            let client = zmq_api::Client::connect(&zmq_api::ClientOptions {
                port,
                timeout: TIMEOUT,
                ..Default::default()
            })
            .unwrap();
            Box::new(ZmqFollower::new(client))
        }
    }
}

fn options(until: Until) -> FollowOptions {
    FollowOptions {
        robot: "Robot".into(),
        floor: "Floor".into(),
        until,
        timeout: Duration::from_secs(60),
        start_simulation: true,
        interrupt: None,
        grade: GradeOptions::default(),
    }
}

/// Follows and grades a run of `waypoints` on a `kind` server; `stop_at` stops the
/// simulation from outside once it reaches that simulation time.
fn run(
    kind: Kind,
    layout: &Layout,
    waypoints: Vec<Sample>,
    until: Until,
    stop_at: Option<f64>,
) -> (Followed, Report) {
    let waypoints0 = waypoints[0];
    let server = serve(kind, waypoints);
    let stopper = stop_at.map(|t| {
        let host = server.host();
        thread::spawn(move || {
            let deadline = Instant::now() + Duration::from_secs(30);
            while Instant::now() < deadline {
                let stopped = crate::support::backend::with_sim(&*host, |sim| {
                    let now = sim.time(Instant::now());
                    now >= t && sim.stop()
                });
                if stopped {
                    return;
                }
                thread::sleep(Duration::from_millis(5));
            }
            panic!("the simulation never reached {t} s");
        })
    });
    let grader = Grader::new(layout).unwrap();
    let mut f = follower(kind, &server);
    let followed = follow(f.as_mut(), &grader, &options(until))
        .unwrap_or_else(|e| panic!("{}: {e}", kind.name()));
    f.close();
    if let Some(s) = stopper {
        s.join().unwrap();
    }
    let running = server.with_sim(|sim| sim.state != vrep_maze::sim::SimState::Stopped);
    assert!(
        !running,
        "{}: the simulation it started is stopped again",
        kind.name()
    );
    let robot_home = server.with_sim(|sim| {
        let robot = sim.scene.resolve("Robot").unwrap();
        let floor = sim.scene.resolve("Floor").unwrap();
        sim.scene.pose(robot, floor).unwrap().0
    });
    let home = waypoints0;
    assert!(
        (robot_home[0] - home.x).abs() < 1e-9 && (robot_home[1] - home.y).abs() < 1e-9,
        "{}: the stop put the robot back where it started: {robot_home:?}",
        kind.name()
    );
    server.shutdown();
    let mut report = grader.grade(&followed.samples, &GradeOptions::default());
    report.followed(followed.incomplete.clone(), followed.wall_time_s);
    (followed, report)
}

fn perfect_run(kind: Kind) {
    let layout = maze(false);
    let (followed, report) = run(kind, &layout, path(&SOLUTION, SPEED), Until::End, None);
    let name = kind.name();
    assert!(report.complete && report.reached_end, "{name}: {report:?}");
    assert_eq!(report.shortest_length_m, Some(6.0), "{name}");
    assert!(
        (report.spl.unwrap() - 1.0).abs() < 1e-9,
        "{name}: SPL {:?}",
        report.spl
    );
    assert_eq!(
        (report.cells_visited, report.cells_revisited),
        (7, 0),
        "{name}"
    );
    // legacy positions travel as f32
    assert!(report.line.unwrap().max_distance_m < 1e-6, "{name}");
    let t = report.time_s.unwrap();
    // End's footprint starts 0.5 m before its centre: 5.5 m at SPEED, give or take the
    // steps between samples (every second one at ZeroMQ protocol 1)
    let expected = 5.5 / SPEED;
    assert!(
        (expected - 0.15..=expected + 0.2).contains(&(t - DWELL)),
        "{name}: reached at {t} s, expected about {expected} s"
    );
    assert!(
        followed.samples.windows(2).all(|w| w[0].t < w[1].t),
        "{name}"
    );
    assert!(
        followed.samples.len() >= 10,
        "{name}: {} samples",
        followed.samples.len()
    );
}

fn a_run_that_stops_short(kind: Kind) {
    // up column 0 and on to the middle of the top row (3 m), then standing; the
    // simulation is stopped 0.45 s after the robot stood still
    let layout = maze(false);
    let waypoints = path(&[(-1.0, -1.0), (-1.0, 1.0), (0.0, 1.0)], SPEED);
    let stop = DWELL + 3.0 / SPEED + 0.45;
    let (followed, report) = run(kind, &layout, waypoints, Until::Stop, Some(stop));
    let name = kind.name();
    assert_eq!(
        followed.incomplete, None,
        "{name}: --until stop ends with the stop"
    );
    assert!(report.complete && !report.reached_end, "{name}: {report:?}");
    assert_eq!(report.spl, Some(0.0), "{name}");
    assert!(
        (report.path_length_m - 3.0).abs() < 0.3,
        "{name}: {} m",
        report.path_length_m
    );
    assert_eq!(report.cells_visited, 4, "{name}");
}

fn a_run_that_cuts_through_walls(kind: Kind) {
    // straight east from Start to End, through the two walls between them
    let layout = maze(true);
    let (_, report) = run(
        kind,
        &layout,
        path(&[(-1.0, -1.0), (1.0, -1.0)], SPEED),
        Until::End,
        None,
    );
    let name = kind.name();
    assert!(report.reached_end, "{name}");
    let walls = report.walls.unwrap();
    assert_eq!(walls.contacts, 2, "{name}: {walls:?}");
    assert!(walls.closest_approach_m < -0.09, "{name}: {walls:?}");
    // SPL only weighs the length: driving through walls is what the wall report shows
    assert!((report.spl.unwrap() - 1.0).abs() < 1e-9, "{name}");
}

fn a_simulation_stopped_mid_run(kind: Kind) {
    let layout = maze(false);
    // stopped after 0.32 m of the 6 m
    let (followed, report) = run(kind, &layout, path(&SOLUTION, SPEED), Until::End, Some(0.7));
    let name = kind.name();
    let why = followed.incomplete.as_deref().unwrap_or_default();
    assert!(
        why.contains("stopped before the robot reached End"),
        "{name}: {why:?}"
    );
    assert!(!report.complete && !report.reached_end, "{name}");
    assert!(
        !followed.samples.is_empty(),
        "{name}: the partial run is kept"
    );
    assert!(
        followed.samples.iter().all(|s| s.t <= 0.75),
        "{name}: nothing after the stop"
    );
}

fn a_missing_robot_is_named_before_any_waiting(kind: Kind) {
    let server = serve(kind, path(&SOLUTION, SPEED));
    let grader = Grader::new(&maze(false)).unwrap();
    let mut f = follower(kind, &server);
    let opts = FollowOptions {
        robot: "Rover".into(),
        ..options(Until::End)
    };
    let e = follow(f.as_mut(), &grader, &opts).unwrap_err();
    f.close();
    assert_eq!(
        e,
        FollowError::NoSuchObject("Rover".into()),
        "{}",
        kind.name()
    );
    let state = server.with_sim(|sim| sim.state);
    assert_eq!(
        state,
        vrep_maze::sim::SimState::Stopped,
        "nothing was started"
    );
    server.shutdown();
}

backend_tests!(
    perfect_run,
    a_run_that_stops_short,
    a_run_that_cuts_through_walls,
    a_simulation_stopped_mid_run,
    a_missing_robot_is_named_before_any_waiting
);
