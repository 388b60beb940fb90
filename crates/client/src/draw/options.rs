//! What a draw of either mode is asked ([`ApplyOptions`]): the object names, dry run,
//! stopping (or drawing into) a running simulation, growing the floor, the Ctrl-C flag.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use super::names::ObjectNames;
use super::robot::RobotCheck;

/// Options of `apply()`.
#[derive(Debug, Clone)]
pub struct ApplyOptions {
    /// Names of the scene objects the drawing uses.
    pub names: ObjectNames,
    /// Stop a running simulation instead of refusing.
    pub stop_simulation: bool,
    /// Draw into a running simulation instead of refusing. What is made then lasts until
    /// the simulation stops: CoppeliaSim removes objects made while it runs when it stops
    /// (and what was removed stays removed), so a later apply on the stopped simulation
    /// draws the maze again. For episodes drawn between simulation steps (RobotMaze-v0).
    pub while_running: bool,
    /// Only survey and plan; change nothing.
    pub dry_run: bool,
    /// Copy-paste commands per round trip (each copies the whole current set of lines).
    pub paste_blocks_per_round: usize,
    /// Set by a Ctrl-C handler: the run stops after the request in flight, restores the
    /// idle rate and fails with [`DrawError::Interrupted`](super::DrawError::Interrupted).
    pub interrupt: Option<Arc<AtomicBool>>,
    /// Grow a floor smaller than the layout's to its size ([`super::floor::resize`]; the
    /// ZeroMQ API only) instead of refusing with [`DrawError::Floor`](super::DrawError::Floor).
    pub resize_floor: bool,
    /// The robot whose footprint is checked against the passages after the draw.
    pub robot: RobotCheck,
}

impl Default for ApplyOptions {
    fn default() -> Self {
        ApplyOptions {
            names: ObjectNames::default(),
            stop_simulation: false,
            while_running: false,
            dry_run: false,
            paste_blocks_per_round: 16,
            interrupt: None,
            resize_floor: false,
            robot: RobotCheck::default(),
        }
    }
}

impl ApplyOptions {
    /// Whether Ctrl-C asked the run to stop ([`ApplyOptions::interrupt`]).
    pub fn interrupted(&self) -> bool {
        self.interrupt
            .as_ref()
            .is_some_and(|flag| flag.load(Ordering::SeqCst))
    }
}
