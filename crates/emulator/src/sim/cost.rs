//! The emulator's side of the cost model: whether the servers take the time a real
//! CoppeliaSim 4.5.1 takes ([`Timing`]), what each request made the simulator do ([`Charge`],
//! recorded in [`crate::sim::Simulator::ledger`] when asked), and its price ([`price`]: the
//! main-loop pacing of [`Clock`] plus the work priced by [`CostModel`], the pure model of
//! [`vrep_maze_core::coppelia::cost`], where every figure cites `../shared/spec/real-coppeliasim-4.5.1.md`).
//!
//! The servers sleep [`CostModel::legacy_pass`] / [`CostModel::ops`] of the same charges they
//! record, so a client run against an *instant* emulator that records its ledger is priced
//! exactly as the realistic emulator would have slept, without waiting for it.

use std::time::Duration;

pub use vrep_maze_core::coppelia::cost::{CostModel, Op};

use super::{Clock, Scene, SimState};

/// Whether the emulated servers take the time a real CoppeliaSim takes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timing {
    /// The modeled server work of each operation; `None`: every operation is instant.
    pub costs: Option<CostModel>,
    /// Legacy API: how long the port refuses every connection after a session whose server
    /// side closed first and whose client answered with its own close (or not at all): TCP's
    /// TIME_WAIT on the port, which the plugin binds again without SO_REUSEADDR (spec "Why
    /// the legacy port refuses for a minute: TIME_WAIT": 60 s, measured 60–63 s; the older
    /// 62–65 s of "Connections (legacy API)" were the same thing).
    pub reconnect_penalty: Duration,
}

impl Default for Timing {
    /// [`Timing::instant`]: the library's default, so tests stay fast.
    fn default() -> Self {
        Timing::instant()
    }
}

impl Timing {
    /// No modeled costs and no reconnect penalty (the main loop still passes at the idle rate).
    pub fn instant() -> Timing {
        Timing {
            costs: None,
            reconnect_penalty: Duration::ZERO,
        }
    }

    /// What a real CoppeliaSim 4.5.1 takes: [`CostModel::measured`] and a 60 s TIME_WAIT
    /// (spec "Why the legacy port refuses for a minute: TIME_WAIT").
    pub fn realistic() -> Timing {
        Timing {
            costs: Some(CostModel::measured()),
            reconnect_penalty: Duration::from_secs(60),
        }
    }

    /// What a real CoppeliaSim 4.10 takes: [`Timing::realistic`] with its mesh costs
    /// ([`CostModel::v4_10`]). It has no legacy API, so the reconnect penalty never applies.
    pub fn realistic_v4_10() -> Timing {
        Timing {
            costs: Some(CostModel::v4_10()),
            ..Timing::realistic()
        }
    }

    /// The modeled cost, or zero when instant.
    pub fn cost(&self, f: impl FnOnce(&CostModel) -> Duration) -> Duration {
        self.costs.as_ref().map_or(Duration::ZERO, f)
    }
}

/// Which kind of request a charge is: what the servers serve at once.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Served {
    /// A legacy main-loop pass that executed commands.
    LegacyPass,
    /// A ZeroMQ call.
    ZmqCall,
}

/// One served request in the ledger: its kind, the main-loop state it was served in, and
/// the work it made the simulator do (from the scene as it was before).
#[derive(Debug, Clone, PartialEq)]
pub struct Charge {
    /// A legacy pass or a ZeroMQ call.
    pub served: Served,
    /// `sim_intparam_idle_fps` when it was served.
    pub idle_fps: i32,
    /// The simulation state when it was served.
    pub state: SimState,
    /// The work done.
    pub ops: Vec<Op>,
    /// Served by the main-loop pass that served the request before it, because it was
    /// already queued ([`crate::sim::ZMQ_TIME_SLOT`]): it waited for no pass of its own.
    pub queued: bool,
}

impl Charge {
    /// Whether the main loop spins (stopped or paused at idle fps 0): a legacy pass then
    /// takes at least [`CostModel::legacy_pass_floor`].
    pub fn spinning(&self) -> bool {
        self.state != SimState::Running && self.idle_fps <= 0
    }

    /// The work's time ([`CostModel`]): what the realistic server sleeps for it.
    pub fn work(&self, model: &CostModel) -> Duration {
        match self.served {
            Served::LegacyPass => model.legacy_pass(&self.ops, self.spinning()),
            Served::ZmqCall => model.ops(&self.ops),
        }
    }
}

/// What a charge takes on a real simulator: one main-loop period of waiting for the pass
/// that serves it (none while the loop spins at idle fps 0: spec "Pacing", a legacy blocking
/// call takes 125 ms at idle fps 8, a ZeroMQ call 93–125 ms; none for a request served by
/// the pass of the one before it, [`Charge::queued`]), then its work.
pub fn price(clock: &Clock, model: &CostModel, charge: &Charge) -> Duration {
    let wait = match charge.queued {
        true => None,
        false => clock.period(charge.state, charge.idle_fps),
    };
    wait.unwrap_or_default() + charge.work(model)
}

/// [`price`] of every charge of a ledger.
pub fn price_all(clock: &Clock, model: &CostModel, ledger: &[Charge]) -> Duration {
    ledger.iter().map(|c| price(clock, model, c)).sum()
}

/// [`price_all`] as a client that sends one request at a time meets it: every charge waits
/// for a pass of its own, [`Charge::queued`] or not (what the spec's rows "through
/// `vrep-maze`" were measured with: a release of 2026-11-23, before requests were sent ahead
/// of replies).
pub fn price_lock_step(clock: &Clock, model: &CostModel, ledger: &[Charge]) -> Duration {
    ledger
        .iter()
        .map(|c| {
            price(
                clock,
                model,
                &Charge {
                    queued: false,
                    ..c.clone()
                },
            )
        })
        .sum()
}

/// The work of pasting `handles` (each distinct existing handle once: spec "Costs that grow
/// with the scene", `copyPasteObjects([Line, Line, Line, Line])` made one copy) into `scene`.
pub fn paste(scene: &Scene, handles: &[i32]) -> Op {
    Op::Paste {
        copies: distinct_existing(scene, handles),
        objects: scene.len(),
    }
}

/// The work of re-parenting one object of `scene` under `parent` (`None`: the scene root).
pub fn set_parent(scene: &Scene, parent: Option<i32>) -> Op {
    Op::SetParent {
        children: scene.child_count(parent),
        parentless: scene.child_count(None),
    }
}

/// The work of setting one pose (or, `half`, a position or an orientation) in `scene`.
pub fn pose(scene: &Scene, half: bool) -> Op {
    let objects = scene.len();
    if half {
        Op::HalfPose { objects }
    } else {
        Op::Pose { objects }
    }
}

/// The work of removing `handles` (those that exist, once each) from `scene`.
pub fn remove(scene: &Scene, handles: &[i32]) -> Op {
    Op::Remove {
        count: distinct_existing(scene, handles),
        objects: scene.len(),
    }
}

fn distinct_existing(scene: &Scene, handles: &[i32]) -> usize {
    let mut hs: Vec<i32> = handles
        .iter()
        .copied()
        .filter(|&h| scene.get(h).is_ok())
        .collect();
    hs.sort_unstable();
    hs.dedup();
    hs.len()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn instant_timing_costs_nothing_and_the_library_default_is_instant() {
        assert_eq!(Timing::default(), Timing::instant());
        assert_eq!(Timing::instant().cost(|m| m.zmq_call), Duration::ZERO);
        let real = Timing::realistic();
        assert_eq!(real.cost(|m| m.zmq_call), Duration::from_micros(150));
        assert_eq!(real.reconnect_penalty, Duration::from_secs(60));
    }

    #[test]
    fn scene_work_counts_distinct_existing_objects_before_the_change() {
        let scene = Scene::course();
        let line = scene.resolve("Line").unwrap();
        let maze = scene.resolve("Maze").unwrap();
        assert_eq!(
            paste(&scene, &[line, line, line, 999]),
            Op::Paste {
                copies: 1,
                objects: 5
            }
        );
        assert_eq!(
            remove(&scene, &[line, line]),
            Op::Remove {
                count: 1,
                objects: 5
            }
        );
        // the course scene's objects are all parentless; Maze has no child yet
        assert_eq!(
            set_parent(&scene, Some(maze)),
            Op::SetParent {
                children: 0,
                parentless: 5
            }
        );
    }

    #[test]
    fn a_charge_costs_one_pass_of_waiting_then_its_work() {
        let (clock, m) = (Clock::default(), CostModel::measured());
        let charge = |served, idle_fps| Charge {
            served,
            idle_fps,
            state: SimState::Stopped,
            ops: vec![Op::LegacyCommand],
            queued: false,
        };
        // spec "Pacing": a legacy blocking call at idle fps 8 waits a 125 ms pass
        let slow = charge(Served::LegacyPass, 8);
        assert_eq!(
            price(&clock, &m, &slow),
            Duration::from_millis(125) + m.legacy_command
        );
        // at idle fps 0 a legacy pass takes at least the floor, a ZeroMQ call its work
        let fast = charge(Served::LegacyPass, 0);
        assert_eq!(price(&clock, &m, &fast), m.legacy_pass_floor);
        let call = charge(Served::ZmqCall, 0);
        assert_eq!(price(&clock, &m, &call), m.legacy_command);
        assert_eq!(
            price_all(&clock, &m, &[fast, call]),
            m.legacy_pass_floor + m.legacy_command
        );
        // a ZeroMQ request queued behind another is served by the same pass
        let paced = charge(Served::ZmqCall, 8);
        let queued = Charge {
            queued: true,
            ..paced.clone()
        };
        assert_eq!(
            price_all(&clock, &m, &[paced, queued]),
            Duration::from_millis(125) + 2 * m.legacy_command
        );
    }
}
