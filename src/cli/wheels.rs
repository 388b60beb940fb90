//! `vrep-maze drive --wheels`: the scene's wheeled robot through the maze by its motors, with
//! physics, the simulation stepped by this command, steered by pose or by camera
//! (`vrep_maze_core::robot`), moved through `vrep_maze_client::robot`; the run is graded as
//! `score` grades one, from the robot's true pose at every step.

use std::process::ExitCode;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;
use std::time::Duration;

use anyhow::{Result, anyhow};

use super::connect::RawClient;
use super::drive::{DriveArgs, SteerBy, checked};
use super::interrupt::Interrupt;
use super::reports::ScoreJson;
use super::score::{describe, exit_code};
use super::session_marker::SessionMarker;
use super::usage::ensure_usage;
use crate::layout::solution::solve;
use crate::layout::{Layout, Style, passages};
use crate::legacy::LegacyRobot;
use crate::maze::Grid;
use crate::robot::Pose;
use crate::robot::camera::LineColour;
use crate::robot::localize::LineMap;
use crate::robot::route::{Gains, legs};
use crate::robot::steer::{CameraSteer, Eye, PoseSteer, Steer};
use crate::robot::wheels::DiffDrive;
use crate::robot::{DriveOptions, Driven, RobotNames, RobotPort, RobotSurvey, drive, facing};
use crate::score::{GradeOptions, Grader, Report};
use crate::zmq_api::robot::ZmqRobot;

/// Refuses wheel speeds and timeouts out of range, and camera steering in a wall maze
/// (`layout`).
fn check_wheel_options(args: &DriveArgs, layout: &Layout) -> Result<()> {
    let parts = &args.parts;
    ensure_usage!(
        parts.wheel_max.is_finite() && parts.wheel_max > 0.0 && parts.wheel_max <= 1000.0,
        "--wheel-max must be more than 0 and at most 1000 rad/s, got {}",
        parts.wheel_max
    );
    ensure_usage!(
        parts.sim_timeout.is_finite() && parts.sim_timeout > 0.0 && parts.sim_timeout <= 86_400.0,
        "--sim-timeout must be more than 0 and at most a day, got {}",
        parts.sim_timeout
    );
    ensure_usage!(
        args.run_timeout.is_finite() && args.run_timeout > 0.0 && args.run_timeout <= 86_400.0,
        "--run-timeout must be more than 0 and at most a day, got {}",
        args.run_timeout
    );
    ensure_usage!(
        args.steer == SteerBy::Pose || layout.style == Style::Lines,
        "--steer camera follows drawn lines: this is a wall maze; steer it with --steer pose"
    );
    Ok(())
}

/// Runs `drive --wheels`.
pub fn run(args: DriveArgs) -> Result<ExitCode> {
    let layout = &checked(&args)?;
    let args = &args;
    let parts = &args.parts;
    check_wheel_options(args, layout)?;
    let interrupt = Interrupt::install()?;
    let client = args.scene.client_until(Some(&interrupt.shared()))?;
    if !parts.start_simulation {
        eprintln!(
            "waiting for the simulation to run (at most {} s): start it, or run `vrep-maze score {} --start-simulation` (or give drive --start-simulation)",
            args.run_timeout,
            super::escape::shell_word(&args.layout.display().to_string())
        );
    }
    let outcome = match client {
        RawClient::Zmq(client) => {
            let options = args.scene.options_for(&client);
            let mut port = ZmqRobot::new(client, options);
            let outcome = args.wheels_over(&mut port, layout, interrupt.shared());
            port.close();
            outcome
        }
        RawClient::Legacy(client) => {
            // the session is recorded until it closes cleanly: an abrupt end locks the port
            let marker =
                SessionMarker::for_address(&args.scene.host, client.peer().map_or(0, |a| a.port()));
            marker.opened();
            let options = crate::legacy::ClientOptions {
                reply_timeout: args.scene.timeout,
                ..Default::default()
            };
            let mut port = LegacyRobot::new(client, options);
            let outcome = args.wheels_over(&mut port, layout, interrupt.shared());
            if port.close().is_ok() {
                marker.closed();
            }
            outcome
        }
    };
    let (driven, report) = outcome?;
    let json = ScoreJson::of(&report);
    let text = if parts.json {
        serde_json::to_string_pretty(&json)? + "\n"
    } else {
        format!(
            "drove {} by its wheels ({}): {} steps, {:.1} s simulated, {:.1} s wall\n{}",
            args.robot,
            match args.steer {
                SteerBy::Pose => "steered by pose",
                SteerBy::Camera => "steered by camera",
            },
            driven.steps,
            driven.samples.last().map_or(0.0, |s| s.t),
            driven.wall_time_s,
            describe(&report, &json.hints)
        )
    };
    super::output::write_output(None, |w| w.write_all(text.as_bytes()))?;
    Ok(exit_code(&report, &interrupt))
}

impl DriveArgs {
    /// The robot's parts, the floor and the line template by these options' names.
    pub fn robot_names(&self) -> RobotNames {
        RobotNames {
            robot: self.robot.clone(),
            left_motor: self.parts.left_motor.clone(),
            right_motor: self.parts.right_motor.clone(),
            camera: self.parts.camera.clone(),
            floor: self.scene.floor.clone(),
            line: self.scene.line.clone(),
        }
    }

    /// Drives the wheeled robot of these options over `port` through `layout` (which
    /// passed validation) and grades the run: what `drive --wheels` does once connected,
    /// and a session's `drive` in Python. Setting `interrupt` ends the run early.
    pub fn wheels_over(
        &self,
        port: &mut dyn RobotPort,
        layout: &Layout,
        interrupt: Arc<AtomicBool>,
    ) -> Result<(Driven, Report)> {
        let grid = Grid::new(layout.grid.columns.into(), layout.grid.rows.into())?;
        let maze = passages::decode(grid, &layout.passages).map_err(|e| anyhow!("{e}"))?;
        let path = solve(layout, &maze, None).map_err(|e| anyhow!("{e}"))?;
        let route = legs(&path.waypoints);
        let first = path.waypoints[0];
        let start = Pose {
            x: first.x,
            y: first.y,
            yaw: facing([first.x, first.y], route.first().map(|l| l.to)),
        };
        let parts = &self.parts;
        let names = self.robot_names();
        let survey = port.survey(&names)?;
        let drive_geometry = DiffDrive::new(
            parts.wheel_radius.unwrap_or(survey.drive.wheel_radius),
            parts.track.unwrap_or(survey.drive.track),
        )
        .map_err(|e| anyhow!("{e}"))?;
        let gains = Gains {
            speed: self.speed.unwrap_or(match self.steer {
                SteerBy::Pose => 0.5,
                SteerBy::Camera => 0.3,
            }),
            wheel_max: parts.wheel_max,
            ..Gains::default()
        };
        let mut steer: Box<dyn Steer> = match self.steer {
            SteerBy::Pose => Box::new(PoseSteer::new(route, drive_geometry, gains)),
            SteerBy::Camera => Box::new(CameraSteer::new(
                route,
                drive_geometry,
                gains,
                eye(&survey, layout, &names)?,
                start,
            )),
        };
        let options = DriveOptions {
            start_simulation: parts.start_simulation,
            sim_limit: parts.sim_timeout,
            wall_limit: Duration::from_secs_f64(self.run_timeout),
            interrupt: Some(interrupt),
        };
        let driven = drive(port, steer.as_mut(), start, &options)?;
        let grader = Grader::new(layout).map_err(|e| anyhow!("{e}"))?;
        let mut report = grader.grade(&driven.samples, &GradeOptions::default());
        let ended = match (&driven.stopped, driven.arrived && report.reached_end) {
            (Some(why), _) => Some(why.clone()),
            (None, false) => Some("the robot finished its route outside End".into()),
            (None, true) => None,
        };
        report.followed(ended, Some(driven.wall_time_s));
        Ok((driven, report))
    }
}

/// What the camera steer needs: the camera, the lines' colour against the floor's, the map.
fn eye(survey: &RobotSurvey, layout: &Layout, names: &RobotNames) -> Result<Eye> {
    let camera = survey.camera.clone().ok_or_else(|| {
        anyhow!(
            "the robot has no camera named `{}` (--camera)",
            names.camera
        )
    })?;
    let (line, floor) = survey.colours.unwrap_or(([0.0, 1.0, 0.0], [1.0, 1.0, 1.0]));
    let colour = LineColour::new(line, floor).map_err(|e| anyhow!("`{}`: {e}", names.line))?;
    let map = LineMap::of(layout).map_err(|e| anyhow!("{e}"))?;
    Ok(Eye {
        camera,
        colour,
        map,
    })
}
