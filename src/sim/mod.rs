//! The in-memory scene model behind every emulated CoppeliaSim server (protocol-neutral).
//!
//! [`Scene`] holds the objects; [`Simulator`] adds what a running CoppeliaSim has around the
//! scene: the simulation state (changes made while running are undone on stop), the idle
//! main-loop rate (`sim_intparam_idle_fps`) and integer parameters.

pub mod clock;
pub mod cost;
mod index;
pub mod mesh;
pub mod model;
pub mod scene;
pub mod svg;

use crate::coppelia::{INTPARAM_IDLE_FPS, INTPARAM_PROGRAM_VERSION};

pub use clock::{Clock, ZmqPacer, ZmqPacing};
pub use cost::{Charge, CostModel, Op, Served, Timing};
pub use mesh::{Mesh, MeshError};
pub use scene::{NamingMode, NewObject, Object, ObjectType, Scene, SimError};

/// The program version we report (CoppeliaSim 4.5.1).
pub const PROGRAM_VERSION: i32 = 40501;

/// Simulation state.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SimState {
    /// Stopped: edits persist.
    Stopped,
    /// Running: edits are undone on stop.
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
    /// Scene as it was when the simulation started (restored on stop).
    saved: Option<Scene>,
    /// Integer signals (`simxSetIntegerSignal`): named values kept by the simulator.
    pub int_signals: std::collections::BTreeMap<String, i32>,
    /// When `Some`, the servers append what each request made the simulator do
    /// ([`cost::Charge`]), so a run against an instant emulator can be priced afterwards.
    pub ledger: Option<Vec<Charge>>,
    /// Where files sent with `simxTransferFile` go (CoppeliaSim's
    /// `sim_stringparam_remoteapi_temp_file_dir`); the system's temporary folder by default.
    pub temp_dir: std::path::PathBuf,
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
            ledger: None,
            temp_dir: std::env::temp_dir(),
        }
    }

    /// A charge for `ops` served now (before they change the idle rate or the state).
    pub fn charge(&self, served: Served, ops: Vec<Op>) -> Charge {
        Charge {
            served,
            idle_fps: self.idle_fps,
            state: self.state,
            ops,
        }
    }

    /// Appends a served request's work to [`Simulator::ledger`] if it is kept.
    pub fn record(&mut self, charge: &Charge) {
        if let Some(ledger) = &mut self.ledger {
            ledger.push(charge.clone());
        }
    }

    /// Starts (or resumes) the simulation. Returns false if it is already running.
    pub fn start(&mut self) -> bool {
        match self.state {
            SimState::Stopped => {
                self.saved = Some(self.scene.clone());
                self.state = SimState::Running;
                true
            }
            SimState::Paused => {
                self.state = SimState::Running;
                true
            }
            SimState::Running => false,
        }
    }

    /// Pauses a running simulation. Returns false if it is not running.
    pub fn pause(&mut self) -> bool {
        if self.state == SimState::Running {
            self.state = SimState::Paused;
            true
        } else {
            false
        }
    }

    /// Stops the simulation, undoing every change made since it started.
    /// Returns false if it was already stopped.
    pub fn stop(&mut self) -> bool {
        if self.state == SimState::Stopped {
            return false;
        }
        if let Some(saved) = self.saved.take() {
            self.scene = saved;
        }
        self.state = SimState::Stopped;
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
    crate::atomic_file::write_atomically(path, |w| w.write_all(text.as_bytes()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::coppelia::DEFAULT_IDLE_FPS;

    #[test]
    fn changes_while_running_are_undone() {
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
}
