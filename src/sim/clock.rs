//! One clock for every emulated server: when CoppeliaSim's main loop runs its next pass.
//!
//! CoppeliaSim executes remote API work once per main-loop pass. While the simulation is
//! stopped (or paused) the loop passes `idle_fps` times a second (`sim_intparam_idle_fps`,
//! default 8: a legacy blocking call takes 125 ms, `../shared/spec/real-coppeliasim-4.5.1.md`,
//! "Pacing"); at idle fps 0 it loops as fast as it can, so a request is served as soon as it
//! arrives (9-10 ms legacy, 0.45 ms ZeroMQ, same table). While the simulation runs, it passes
//! once per simulation step. The servers only wait on the answers of [`Clock`]; nothing else
//! in them decides time.

use std::time::{Duration, Instant};

use super::SimState;

/// The emulated main loop's timing settings.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Clock {
    /// One simulation step while the simulation runs (CoppeliaSim's default: 50 ms).
    pub step: Duration,
    /// The ZeroMQ add-on keeps polling its socket for this long after a reply before it goes
    /// back to serving once per idle pass (a request within the window is served at once).
    pub busy_window: Duration,
}

impl Default for Clock {
    fn default() -> Self {
        Clock {
            step: Duration::from_millis(50),
            busy_window: Duration::from_millis(50),
        }
    }
}

impl Clock {
    /// Time between two main-loop passes; `None` when the loop passes as soon as there is
    /// work (stopped or paused at idle fps 0).
    pub fn period(&self, state: SimState, idle_fps: i32) -> Option<Duration> {
        match state {
            SimState::Running => Some(self.step),
            SimState::Stopped | SimState::Paused if idle_fps <= 0 => None,
            SimState::Stopped | SimState::Paused => {
                Some(Duration::from_secs_f64(1.0 / f64::from(idle_fps)))
            }
        }
    }

    /// When a loop that last passed at `last_pass` passes next; `None`: as soon as input
    /// arrives.
    pub fn next_pass(&self, state: SimState, idle_fps: i32, last_pass: Instant) -> Option<Instant> {
        self.period(state, idle_fps).map(|p| last_pass + p)
    }

    /// When the ZeroMQ add-on serves a request that arrived at `arrived`, its previous reply
    /// having gone out at `last_reply`: at once within the busy window or with no period,
    /// otherwise one period after the request arrived (it waits for the next idle pass).
    pub fn serve_at(
        &self,
        state: SimState,
        idle_fps: i32,
        arrived: Instant,
        last_reply: Option<Instant>,
    ) -> Instant {
        let busy =
            last_reply.is_some_and(|t| arrived.saturating_duration_since(t) <= self.busy_window);
        match self.period(state, idle_fps) {
            Some(p) if !busy => arrived + p,
            _ => arrived,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const MS: Duration = Duration::from_millis(1);

    #[test]
    fn the_idle_rate_sets_the_period_while_stopped_or_paused() {
        let c = Clock::default();
        assert_eq!(c.period(SimState::Stopped, 8), Some(125 * MS));
        assert_eq!(c.period(SimState::Paused, 20), Some(50 * MS));
        assert_eq!(c.period(SimState::Stopped, 0), None);
        assert_eq!(c.period(SimState::Paused, -1), None);
    }

    #[test]
    fn a_running_simulation_passes_once_per_step_whatever_the_idle_rate() {
        let c = Clock::default();
        assert_eq!(c.period(SimState::Running, 0), Some(50 * MS));
        assert_eq!(c.period(SimState::Running, 8), Some(50 * MS));
    }

    #[test]
    fn the_next_pass_follows_the_last_one_by_one_period() {
        let c = Clock::default();
        let t = Instant::now();
        assert_eq!(c.next_pass(SimState::Stopped, 8, t), Some(t + 125 * MS));
        assert_eq!(c.next_pass(SimState::Stopped, 0, t), None);
    }

    #[test]
    fn zmq_requests_wait_one_idle_pass_unless_within_the_busy_window() {
        let c = Clock::default();
        let t = Instant::now();
        // first request, or one long after the last reply: the next idle pass
        assert_eq!(c.serve_at(SimState::Stopped, 8, t, None), t + 125 * MS);
        assert_eq!(
            c.serve_at(SimState::Stopped, 8, t + 500 * MS, Some(t)),
            t + 625 * MS
        );
        // right after a reply: served at once
        assert_eq!(
            c.serve_at(SimState::Stopped, 8, t + 10 * MS, Some(t)),
            t + 10 * MS
        );
        // idle fps 0: always at once
        assert_eq!(c.serve_at(SimState::Stopped, 0, t, None), t);
    }
}
