//! `vrep-maze drive`: a minimal robot for trying `score` at once. It adds a dummy named
//! `Robot` at Start if the scene has none, and while the simulation runs moves it along the
//! maze's solution at `--speed`, by remote calls (`sim.setObjectPosition` at the simulation
//! time it reads), so it needs no script: the real 4.5.1 course scene has no main script, so
//! no child script of it would ever run. Over the ZeroMQ remote API, on `serve --api both`
//! (or `--api zmq`) and on a real CoppeliaSim alike.

use std::process::ExitCode;
use std::sync::atomic::Ordering;
use std::time::{Duration, Instant};

use anyhow::{Context, Result, anyhow};
use ciborium::Value;

use super::apply::ConnectArgs;
use super::connect::RawClient;
use super::hinted::hinted;
use super::interrupt::{INTERRUPTED_EXIT_CODE, Interrupt};
use super::usage::ensure_usage;
use crate::layout::passages;
use crate::layout::solution::{Waypoint, solve};
use crate::maze::Grid;
use crate::zmq_api::cbor::{self, float_array, int};
use crate::zmq_api::{Client, ZmqError};

/// `sim.boolparam_realtime_simulation`.
const BOOLPARAM_REALTIME: i64 = 25;
/// `sim.simulation_stopped`.
const SIMULATION_STOPPED: i32 = 0;
/// The robot dummy's height above the floor, metres.
const ROBOT_Z: f64 = 0.05;

/// Options of `drive`.
#[derive(Debug, clap::Args)]
#[command(
    after_help = "Examples:\n  vrep-maze serve --api both &\n  vrep-maze apply maze.json\n  vrep-maze drive maze.json --api zmq &      # adds Robot at Start, drives it while the simulation runs\n  vrep-maze score maze.json --start-simulation\n\nExit codes: 0 the simulation ran and stopped, 1 error, 2 usage, 130 interrupted."
)]
pub struct DriveArgs {
    /// The layout whose solution the robot follows.
    pub layout: std::path::PathBuf,
    /// The robot's name: an object the scene has, or the dummy added at Start.
    #[arg(long, default_value = "Robot")]
    pub robot: String,
    /// Metres a second along the solution (turns take no time).
    #[arg(long, value_name = "M/S", default_value_t = 1.0)]
    pub speed: f64,
    /// Run the simulation in real time (`sim.boolparam_realtime_simulation`): a headless
    /// CoppeliaSim without physics runs some 300 times faster than the remote calls that
    /// move the robot can follow.
    #[arg(long)]
    pub real_time: bool,
    /// Wall-clock seconds at most, waiting for the simulation included.
    #[arg(long = "run-timeout", value_name = "SECS", default_value_t = 600.0)]
    pub run_timeout: f64,
    /// Where the simulator is (ZeroMQ: `--api zmq`, or auto when legacy does not answer).
    #[command(flatten)]
    pub scene: ConnectArgs,
}

/// Runs `drive`.
pub fn run(args: DriveArgs) -> Result<ExitCode> {
    ensure_usage!(
        args.speed.is_finite() && args.speed > 0.0 && args.speed <= 100.0,
        "--speed must be more than 0 and at most 100 m/s, got {}",
        args.speed
    );
    ensure_usage!(
        args.run_timeout.is_finite() && args.run_timeout > 0.0 && args.run_timeout <= 86_400.0,
        "--run-timeout must be more than 0 and at most a day, got {}",
        args.run_timeout
    );
    let layout = crate::layout::read_layout(&args.layout)?;
    crate::validate::checked(&layout).context("nothing was driven")?;
    let grid = Grid::new(layout.grid.columns.into(), layout.grid.rows.into())?;
    let maze = passages::decode(grid, &layout.passages).map_err(|e| anyhow!("{e}"))?;
    let path = solve(&layout, &maze, None).map_err(|e| anyhow!("{e}"))?;
    let interrupt = Interrupt::install()?;
    let mut client = match args.scene.client_until(Some(&interrupt.shared()))? {
        RawClient::Zmq(client) => client,
        RawClient::Legacy(client) => {
            let _ = client.close();
            return Err(hinted(
                "drive needs the ZeroMQ remote API, but the legacy API answered",
                vec![
                    "pass --api zmq (CoppeliaSim 4.5.1 and later serve it on 23000 beside legacy), or start the emulator with `vrep-maze serve --api both`".into(),
                ],
            ));
        }
    };
    let driven = drive(&mut client, &args, &path.waypoints, &interrupt);
    client.close();
    let moves = driven.map_err(|e| anyhow!("{e}"))?;
    if interrupt.requested() {
        eprintln!("interrupted after {moves} moves");
        return Ok(ExitCode::from(INTERRUPTED_EXIT_CODE));
    }
    println!(
        "drove {} along the solution ({} m at {} m/s): {moves} moves; the simulation stopped",
        args.robot, path.length, args.speed
    );
    Ok(ExitCode::SUCCESS)
}

/// Finds or adds the robot, then moves it while the simulation runs, until it stops (or
/// the time is up, or Ctrl-C). Returns the moves sent.
fn drive(
    client: &mut Client,
    args: &DriveArgs,
    waypoints: &[Waypoint],
    interrupt: &Interrupt,
) -> Result<usize, ZmqError> {
    let floor = client.call_int("sim.getObject", vec![path_of(&args.scene.floor)])?;
    let start = &waypoints[0];
    let robot = match client.call_int("sim.getObject", vec![path_of(&args.robot)]) {
        Ok(robot) => robot,
        Err(ZmqError::Remote { .. }) => {
            let robot = client.call_int("sim.createDummy", vec![Value::Float(0.05)])?;
            client.call(
                "sim.setObjectAlias",
                vec![int(robot.into()), Value::Text(args.robot.clone())],
            )?;
            eprintln!("added `{}`, a dummy, at Start", args.robot);
            robot
        }
        Err(e) => return Err(e),
    };
    let place = |client: &mut Client, x: f64, y: f64| {
        client.call(
            "sim.setObjectPosition",
            vec![
                int(robot.into()),
                int(floor.into()),
                float_array(&[x, y, ROBOT_Z]),
            ],
        )
    };
    place(client, start.x, start.y)?;
    if args.real_time {
        client.call(
            "sim.setBoolParam",
            vec![int(BOOLPARAM_REALTIME), Value::Bool(true)],
        )?;
    }
    eprintln!(
        "waiting for the simulation to run (at most {} s); start it, or run `vrep-maze score ... --start-simulation`",
        args.run_timeout
    );
    let began = Instant::now();
    let limit = Duration::from_secs_f64(args.run_timeout);
    let (mut ran, mut moves) = (false, 0);
    while began.elapsed() < limit && !interrupt.shared().load(Ordering::SeqCst) {
        let state = client.call_int("sim.getSimulationState", vec![])?;
        if state == SIMULATION_STOPPED {
            if ran {
                break;
            }
            std::thread::sleep(Duration::from_millis(20));
            continue;
        }
        ran = true;
        let t = client.call1("sim.getSimulationTime", vec![])?;
        let t = cbor::number(&t).unwrap_or(0.0);
        let (x, y) = along(waypoints, t * args.speed);
        place(client, x, y)?;
        moves += 1;
    }
    Ok(moves)
}

/// A name as `sim.getObject` takes it: a path, `/Floor` for `Floor`.
fn path_of(name: &str) -> Value {
    Value::Text(if name.starts_with('/') || name.starts_with('.') {
        name.to_string()
    } else {
        format!("/{name}")
    })
}

/// The point `distance` metres along `waypoints` (the last one past the end).
fn along(waypoints: &[Waypoint], distance: f64) -> (f64, f64) {
    for pair in waypoints.windows(2) {
        let (a, b) = (&pair[0], &pair[1]);
        if distance < b.distance {
            let span = b.distance - a.distance;
            let f = if span > 0.0 {
                ((distance - a.distance) / span).clamp(0.0, 1.0)
            } else {
                1.0
            };
            return (a.x + f * (b.x - a.x), a.y + f * (b.y - a.y));
        }
    }
    waypoints.last().map_or((0.0, 0.0), |w| (w.x, w.y))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(x: f64, y: f64, distance: f64) -> Waypoint {
        Waypoint {
            x,
            y,
            yaw: 0.0,
            distance,
        }
    }

    #[test]
    fn along_interpolates_and_stays_at_the_end() {
        let path = [
            at(0.0, 0.0, 0.0),
            at(1.0, 0.0, 1.0),
            at(1.0, 0.0, 1.0),
            at(1.0, 2.0, 3.0),
        ];
        assert_eq!(along(&path, 0.5), (0.5, 0.0));
        assert_eq!(along(&path, 2.0), (1.0, 1.0));
        assert_eq!(along(&path, 9.0), (1.0, 2.0));
        assert_eq!(along(&path, 0.0), (0.0, 0.0));
    }
}
