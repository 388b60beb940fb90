//! The in-memory scene model behind every emulated CoppeliaSim server (protocol-neutral).
//!
//! [`Scene`] holds the objects; [`Simulator`] adds what a running CoppeliaSim has around the
//! scene: the simulation state (what a run made is removed on stop, poses go back), the idle
//! main-loop rate (`sim_intparam_idle_fps`) and integer parameters.

pub mod clock;
pub mod cost;
mod index;
pub mod mesh;
pub mod model;
pub mod object;
pub mod property;
pub mod robot;
pub mod scene;
pub mod top_view;

use std::time::{Duration, Instant};

use vrep_maze_core::coppelia::{INTPARAM_IDLE_FPS, INTPARAM_PROGRAM_VERSION};

pub use clock::{Clock, ZMQ_TIME_SLOT, ZmqPacer, ZmqPacing};
pub use cost::{Charge, CostModel, Op, Served, Timing};
pub use mesh::{Mesh, MeshError};
pub use object::{Object, ObjectType};
pub use robot::RobotPath;
pub use scene::{NamingMode, NewObject, Scene, SimError};

/// The program version we report (CoppeliaSim 4.5.1).
pub const PROGRAM_VERSION: i32 = 40501;

/// Simulation state.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SimState {
    /// Stopped: edits persist.
    Stopped,
    /// Running: what is made now is removed on stop, and poses go back ([`Scene::end_run`]).
    Running,
    /// Paused (counts as "not stopped").
    Paused,
}

/// A simulator: scene + simulation state + idle rate.
#[derive(Debug, Clone)]
pub struct Simulator {
    /// The current scene.
    pub scene: Scene,
    /// Main-loop passes per second while the simulation is not running (0 = as fast as possible).
    pub idle_fps: i32,
    /// Simulation state.
    pub state: SimState,
    /// Scene as it was when the simulation started (what its stop goes back to).
    saved: Option<Scene>,
    /// Integer signals (`simxSetIntegerSignal`): named values kept by the simulator.
    pub int_signals: std::collections::BTreeMap<String, i32>,
    /// String signals (`simxSetStringSignal`, `sim.setStringSignal`): named byte strings.
    pub string_signals: std::collections::BTreeMap<String, Vec<u8>>,
    /// When `Some`, the servers append what each request made the simulator do
    /// ([`cost::Charge`]), so a run against an instant emulator can be priced afterwards.
    pub ledger: Option<Vec<Charge>>,
    /// Where files sent with `simxTransferFile` go (CoppeliaSim's
    /// `sim_stringparam_remoteapi_temp_file_dir`); the system's temporary folder by default.
    pub temp_dir: std::path::PathBuf,
    /// One simulation step (CoppeliaSim's default: 50 ms); simulation time advances in
    /// whole steps while the simulation runs.
    pub step: Duration,
    /// Simulation steps done before the latest start or resume.
    steps_before: u64,
    /// When the simulation last started or resumed, while it runs.
    running_since: Option<Instant>,
    /// The emulated robot, if the scene has one (`serve --robot`).
    pub robot: Option<RobotPath>,
}

impl Simulator {
    /// A stopped simulator over `scene` with the given idle rate.
    pub fn new(scene: Scene, idle_fps: i32) -> Simulator {
        Simulator {
            scene,
            idle_fps,
            state: SimState::Stopped,
            saved: None,
            int_signals: Default::default(),
            string_signals: Default::default(),
            ledger: None,
            temp_dir: std::env::temp_dir(),
            step: Duration::from_millis(50),
            steps_before: 0,
            running_since: None,
            robot: None,
        }
    }

    /// A charge for `ops` served now (before they change the idle rate or the state).
    pub fn charge(&self, served: Served, ops: Vec<Op>) -> Charge {
        Charge {
            served,
            idle_fps: self.idle_fps,
            state: self.state,
            ops,
            queued: false,
        }
    }

    /// Appends a served request's work to [`Simulator::ledger`] if it is kept.
    pub fn record(&mut self, charge: &Charge) {
        if let Some(ledger) = &mut self.ledger {
            ledger.push(charge.clone());
        }
    }

    /// Simulation steps done by `now`: the simulation advances one step per
    /// [`Simulator::step`] of wall time while it runs (CoppeliaSim's real-time pace), holds
    /// still while paused and is back at 0 when stopped.
    pub fn steps(&self, now: Instant) -> u64 {
        let running = self.running_since.map_or(0, |since| {
            let elapsed = now.saturating_duration_since(since).as_nanos();
            (elapsed / self.step.as_nanos().max(1)) as u64
        });
        self.steps_before + running
    }

    /// Simulation time at `now`, seconds: whole steps times the step (`sim.getSimulationTime`).
    pub fn time(&self, now: Instant) -> f64 {
        self.steps(now) as f64 * self.step.as_secs_f64()
    }

    /// Simulation time at `now` as legacy reply blocks carry it: `int(simTime * 1000.01)`
    /// ms (`../shared/spec/legacy-remote-api.md` §4, `simxCmd.cpp:483-486`), 0 while stopped.
    pub fn time_ms(&self, now: Instant) -> i32 {
        (self.time(now) * 1000.01) as i32
    }

    /// Brings what moves with simulation time up to `now`: the robot goes where its path
    /// is at the current simulation time. The servers call this before they read or change
    /// the scene.
    pub fn sync(&mut self, now: Instant) {
        if self.state == SimState::Stopped {
            return;
        }
        let t = self.time(now);
        if let Some(robot) = &self.robot {
            // the robot's object may have been removed: then nothing moves
            let _ = robot.place(&mut self.scene, t);
        }
    }

    /// Starts (or resumes) the simulation. Returns false if it is already running.
    pub fn start(&mut self) -> bool {
        match self.state {
            SimState::Stopped => {
                self.saved = Some(self.scene.clone());
                self.state = SimState::Running;
                self.steps_before = 0;
                self.running_since = Some(Instant::now());
                true
            }
            SimState::Paused => {
                self.state = SimState::Running;
                self.running_since = Some(Instant::now());
                true
            }
            SimState::Running => false,
        }
    }

    /// Pauses a running simulation. Returns false if it is not running.
    pub fn pause(&mut self) -> bool {
        if self.state == SimState::Running {
            self.steps_before = self.steps(Instant::now());
            self.running_since = None;
            self.state = SimState::Paused;
            true
        } else {
            false
        }
    }

    /// Stops the simulation: what was made since it started is removed and what it started
    /// with goes back to its pose ([`Scene::end_run`]). Returns false if it was already
    /// stopped.
    pub fn stop(&mut self) -> bool {
        if self.state == SimState::Stopped {
            return false;
        }
        if let Some(started) = self.saved.take() {
            self.scene.end_run(&started);
        }
        self.state = SimState::Stopped;
        self.steps_before = 0;
        self.running_since = None;
        true
    }

    /// `simGetInt32Param` for the parameters we model.
    pub fn int_param(&self, id: i32) -> Option<i32> {
        match id {
            INTPARAM_PROGRAM_VERSION => Some(PROGRAM_VERSION),
            INTPARAM_IDLE_FPS => Some(self.idle_fps),
            _ => None,
        }
    }

    /// `simSetInt32Param`; only the idle rate is writable (0..=1000).
    pub fn set_int_param(&mut self, id: i32, value: i32) -> bool {
        if id == INTPARAM_IDLE_FPS && (0..=1000).contains(&value) {
            self.idle_fps = value;
            true
        } else {
            false
        }
    }
}

/// Writes `sim`'s scene as a `--dump` file (the JSON of [`Scene::to_json`]), atomically: a
/// reader never sees half a file, and a failed write keeps the previous one.
pub fn write_dump(sim: &Simulator, path: &std::path::Path) -> std::io::Result<()> {
    let text = serde_json::to_string_pretty(&sim.scene.to_json())?;
    vrep_maze_core::atomic_file::write_atomically(path, |w| w.write_all(text.as_bytes()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use vrep_maze_core::coppelia::DEFAULT_IDLE_FPS;

    #[test]
    fn what_a_run_made_is_removed_on_stop() {
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let line = sim.scene.resolve("Line").unwrap();
        assert!(sim.start());
        sim.scene.copy_paste(&[line]).unwrap();
        assert_eq!(sim.scene.len(), 6);
        assert!(sim.stop());
        assert_eq!(sim.scene.len(), 5);
        assert!(!sim.stop());
        assert!(sim.set_int_param(INTPARAM_IDLE_FPS, 0));
        assert_eq!(sim.int_param(INTPARAM_IDLE_FPS), Some(0));
        assert!(!sim.set_int_param(INTPARAM_PROGRAM_VERSION, 3));
    }

    #[test]
    fn a_stop_removes_what_the_run_made_and_keeps_what_it_removed_or_recoloured() {
        // as measured on the real 4.5.1 and 4.10 (docs/measurements.md, "What a stop undoes")
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let line = sim.scene.resolve("Line").unwrap();
        let start = sim.scene.resolve("Start").unwrap();
        let end = sim.scene.resolve("End").unwrap();
        let at_start = sim.scene.pose(line, -1).unwrap();
        assert!(sim.start());
        let made = sim.scene.copy_paste(&[line]).unwrap()[0];
        sim.scene.set_parent(end, Some(made), true).unwrap();
        sim.scene.set_position(line, -1, [1.0, 2.0, 3.0]).unwrap();
        sim.scene.set_colour(line, [255, 0, 0]).unwrap();
        sim.scene.remove(start).unwrap();
        assert!(sim.stop());
        assert!(sim.scene.get(made).is_err(), "made while running: removed");
        assert!(
            sim.scene.get(start).is_err(),
            "removed while running: stays removed"
        );
        assert!(
            sim.scene.get(end).is_ok(),
            "under a made object: moved up, kept"
        );
        assert_eq!(
            sim.scene.pose(line, -1).unwrap(),
            at_start,
            "the pose goes back"
        );
        assert_eq!(
            sim.scene.get(line).unwrap().colour,
            [255, 0, 0],
            "a colour stays"
        );
    }

    #[test]
    fn simulation_time_counts_whole_steps_while_running_only() {
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let step = sim.step;
        assert_eq!(sim.steps(Instant::now() + step * 10), 0, "stopped");
        sim.start();
        let since = sim.running_since.unwrap();
        assert_eq!(sim.steps(since), 0);
        assert_eq!(sim.steps(since + step * 3 - Duration::from_nanos(1)), 2);
        assert_eq!(sim.time_ms(since + step * 3), 150);
        assert!((sim.time(since + step * 3) - 0.15).abs() < 1e-12);
        sim.stop();
        assert_eq!(sim.steps(since + step * 3), 0, "back at 0 when stopped");
    }

    #[test]
    fn the_robot_follows_its_path_while_running_and_goes_back_on_stop() {
        use vrep_maze_core::score::Sample;
        let mut sim = Simulator::new(Scene::course(), DEFAULT_IDLE_FPS);
        let waypoints = vec![
            Sample {
                t: 0.0,
                x: 0.0,
                y: 0.0,
                yaw: 0.0,
            },
            Sample {
                t: 1.0,
                x: 1.0,
                y: 0.0,
                yaw: 0.0,
            },
        ];
        let path = RobotPath::add_to(&mut sim.scene, "Robot", waypoints).unwrap();
        let handle = path.handle;
        sim.robot = Some(path);
        let x = |sim: &Simulator| {
            sim.scene
                .pose(handle, vrep_maze_core::coppelia::HANDLE_WORLD)
                .unwrap()
                .0[0]
        };
        sim.sync(Instant::now() + Duration::from_secs(5));
        assert_eq!(x(&sim), 0.0, "a stopped simulation does not move the robot");
        sim.start();
        let since = sim.running_since.unwrap();
        sim.sync(since + sim.step * 10);
        assert!((x(&sim) - 0.5).abs() < 1e-12);
        sim.stop();
        assert_eq!(x(&sim), 0.0, "stopping restores the scene");
    }
}
