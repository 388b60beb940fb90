//! One clock for every emulated server: when CoppeliaSim's main loop runs its next pass, and
//! when the ZeroMQ add-on serves a request. Facts from `../shared/spec/real-coppeliasim-4.5.1.md`
//! ("Pacing") and CoppeliaSim's sources (tag `coppeliasim-v4.5.1-rev4` unless said otherwise).
//!
//! CoppeliaSim executes remote API work once per main-loop pass. While the simulation is
//! stopped (or paused) a pass lasts 1000 / `idle_fps` ms, at least 20 ms, at idle fps above 0
//! (`sim_intparam_idle_fps`, default 8: a legacy blocking call takes 125 ms, "Pacing"); at
//! idle fps 0 there is no sleep, so a request is served as soon as it arrives (2.1–2.4 ms
//! legacy, `docs/measurements.md` "Legacy calls at idle fps 0"; 0.10-0.19 ms ZeroMQ, "ZeroMQ calls on
//! 4.5.1") (coppeliaSimLib `simThread.cpp:4612-4621`). While the
//! simulation runs, it passes once per simulation step. The servers ask [`Clock`] and
//! [`ZmqPacer`] when a pass runs, and sleep the modelled work of what they serve
//! (`super::cost`) besides.

use std::time::{Duration, Instant};

use super::SimState;

/// The shortest main-loop pass at idle fps above 0 (coppeliaSimLib `simThread.cpp:4612-4621`).
pub const MIN_IDLE_PASS: Duration = Duration::from_millis(20);

/// How long one main-loop pass of the ZeroMQ add-on goes on serving requests that are
/// already queued on its socket (zmqRemoteApi@coppeliasim-v4.5.1-rev4 `simAddOnZMQ remote API
/// server.lua:86-105`: poll without waiting, serve, until nothing is queued or
/// `maxTimeSlot`, 0.005 s by default at line 127, has passed since the pass began). A
/// lock-step client's next request is never queued yet, so it gets one request per pass
/// (spec "Pacing"); a client that sends several before reading gets them all served.
pub const ZMQ_TIME_SLOT: Duration = Duration::from_millis(5);

/// The emulated main loop's timing settings.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Clock {
    /// One simulation step while the simulation runs (CoppeliaSim's default: 50 ms).
    pub step: Duration,
    /// ZeroMQ protocol 2 (4.6 and later): once a pass has served a request, the add-on keeps
    /// serving requests that arrive until this long after the pass began, while the
    /// simulation is not running (zmqRemoteApi@coppeliasim-v4.6.0-rev0 `simAddOnZMQ remote
    /// API server.lua:415-473, 546-547`: 50 ms). Protocol 1 (4.5.1) has no such window.
    pub busy_window: Duration,
    /// The same window while the simulation runs, per connected client (same lines: 2 ms ×
    /// clients; the emulator counts one client).
    pub running_window: Duration,
}

impl Default for Clock {
    fn default() -> Self {
        Clock {
            step: Duration::from_millis(50),
            busy_window: Duration::from_millis(50),
            running_window: Duration::from_millis(2),
        }
    }
}

/// Which generation of the ZeroMQ add-on paces requests.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ZmqPacing {
    /// 4.3 to 4.5 (protocol 1): the queued requests once per pass, then no more polling until
    /// the next pass (zmqRemoteApi@4.5.1 `simAddOnZMQ remote API server.lua:86-105,
    /// 165-179`): a lock-step client gets one request per pass, 93–125 ms per call at idle
    /// fps 8 (spec "Pacing").
    OnePerPass,
    /// 4.6 and later (protocol 2): as [`ZmqPacing::OnePerPass`], plus the busy window of
    /// [`Clock::busy_window`] / [`Clock::running_window`].
    Window,
}

impl Clock {
    /// Time between two main-loop passes; `None` when the loop passes as soon as there is
    /// work (stopped or paused at idle fps 0).
    pub fn period(&self, state: SimState, idle_fps: i32) -> Option<Duration> {
        match state {
            SimState::Running => Some(self.step),
            SimState::Stopped | SimState::Paused if idle_fps <= 0 => None,
            SimState::Stopped | SimState::Paused => {
                Some(Duration::from_secs_f64(1.0 / f64::from(idle_fps)).max(MIN_IDLE_PASS))
            }
        }
    }

    /// When a loop that last passed at `last_pass` passes next; `None`: as soon as input
    /// arrives.
    pub fn next_pass(&self, state: SimState, idle_fps: i32, last_pass: Instant) -> Option<Instant> {
        self.period(state, idle_fps).map(|p| last_pass + p)
    }

    /// The ZeroMQ protocol-2 window in this state.
    pub fn window(&self, state: SimState) -> Duration {
        match state {
            SimState::Running => self.running_window,
            SimState::Stopped | SimState::Paused => self.busy_window,
        }
    }
}

/// When the ZeroMQ add-on serves each request: main-loop passes on a grid of one period from
/// an origin (re-anchored when a pass overruns), and the pass that served the latest request.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ZmqPacer {
    /// A moment a pass began.
    origin: Instant,
    /// Start of the pass that served the latest request.
    served_pass: Option<Instant>,
}

impl ZmqPacer {
    /// Passes begin at `origin` (the server's start).
    pub fn new(origin: Instant) -> ZmqPacer {
        ZmqPacer {
            origin,
            served_pass: None,
        }
    }

    /// The start of the pass running at `t` (passes of `period` from the origin).
    fn pass_start(&self, period: Duration, t: Instant) -> Instant {
        let since = t.saturating_duration_since(self.origin);
        let k = since.as_nanos() / period.as_nanos().max(1);
        self.origin + period * u32::try_from(k).unwrap_or(u32::MAX)
    }

    /// When a request that arrived at `arrived` is served. At idle fps 0 (no period): at
    /// once. Otherwise at the first pass that begins at or after `arrived` and after the pass
    /// that served the previous request; protocol 2 also serves it at once if it arrives
    /// within the window of a pass that has served one already.
    pub fn serve_at(
        &self,
        clock: &Clock,
        pacing: ZmqPacing,
        state: SimState,
        idle_fps: i32,
        arrived: Instant,
    ) -> Instant {
        let Some(p) = clock.period(state, idle_fps) else {
            return arrived;
        };
        let start = self.pass_start(p, arrived);
        if pacing == ZmqPacing::Window
            && self.served_pass == Some(start)
            && arrived < start + clock.window(state)
        {
            return arrived;
        }
        let mut at = if start == arrived { start } else { start + p };
        if let Some(prev) = self.served_pass
            && at <= prev
        {
            at = prev + p;
        }
        at
    }

    /// A request was served at `at` and its work ended at `done`: remember the pass that
    /// served it; a pass that overran its period delays the next one (the grid restarts at
    /// `done`). At idle fps 0 each request has a pass of its own, beginning at `at`: if the
    /// request raised the idle rate, the next pass follows one period after it, and over
    /// protocol 2 a request arriving within the window is still served by it (measured on
    /// 4.10.0: after `apply` restores idle fps 8 its last calls are answered in 0.1-0.3 ms,
    /// `docs/measurements.md` "Pacing after the idle rate is restored"). Over protocol 2 that
    /// pass began with the first request after the previous pass's window closed: at idle fps
    /// 0 a pass serves every request arriving within its window (the 4.10 add-on's
    /// `handleQueue`, `ZMQ remote API server.lua:455-516` of the build: it polls until 50 ms
    /// after it began, once it has served one).
    pub fn served(
        &mut self,
        clock: &Clock,
        (pacing, state, idle_fps): (ZmqPacing, SimState, i32),
        (at, done): (Instant, Instant),
    ) {
        let Some(p) = clock.period(state, idle_fps) else {
            let window = clock.window(state);
            let same_pass = pacing == ZmqPacing::Window
                && self.served_pass.is_some_and(|s| at >= s && at < s + window);
            if !same_pass {
                self.origin = at;
                self.served_pass = Some(at);
            }
            return;
        };
        let start = self.pass_start(p, at);
        if done >= start + p {
            self.origin = done;
            self.served_pass = Some(done.checked_sub(p).unwrap_or(done));
        } else {
            self.served_pass = Some(start);
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
        // a pass lasts at least 20 ms at idle fps above 0
        assert_eq!(c.period(SimState::Stopped, 1000), Some(20 * MS));
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

    /// Serves a lock-step client whose requests arrive `think` after each reply and take
    /// `work`; returns the times between successive replies.
    fn lock_step(pacing: ZmqPacing, state: SimState, fps: i32, n: usize) -> Vec<Duration> {
        let c = Clock::default();
        let t0 = Instant::now();
        let mut pacer = ZmqPacer::new(t0);
        let mut t = t0 + 3 * MS;
        let mut replies = vec![];
        for _ in 0..n {
            let at = pacer.serve_at(&c, pacing, state, fps, t);
            assert!(at >= t);
            let done = at + MS / 2;
            pacer.served(&c, (pacing, state, fps), (at, done));
            replies.push(done);
            t = done + MS; // the client thinks 1 ms
        }
        replies.windows(2).map(|w| w[1] - w[0]).collect()
    }

    #[test]
    fn protocol_1_serves_one_request_per_pass() {
        // spec "Pacing": 93–125 ms per call at idle fps 8
        let gaps = lock_step(ZmqPacing::OnePerPass, SimState::Stopped, 8, 6);
        assert!(gaps.iter().all(|g| *g == 125 * MS), "{gaps:?}");
        // running: one per simulation step
        let gaps = lock_step(ZmqPacing::OnePerPass, SimState::Running, 8, 4);
        assert!(gaps.iter().all(|g| *g == 50 * MS), "{gaps:?}");
        // idle fps 0: no sleep, served at once
        let gaps = lock_step(ZmqPacing::OnePerPass, SimState::Stopped, 0, 4);
        assert!(gaps.iter().all(|g| *g == 3 * MS / 2), "{gaps:?}");
    }

    #[test]
    fn protocol_2_serves_at_once_within_the_window_of_a_pass_that_served() {
        // each call takes 1.5 ms: the first request of a pass waits for the pass, then the
        // ones arriving before 50 ms into it are served at once
        let gaps = lock_step(ZmqPacing::Window, SimState::Stopped, 8, 80);
        let fast = gaps.iter().filter(|g| **g == 3 * MS / 2).count();
        let slow: Vec<_> = gaps.iter().filter(|g| **g > 3 * MS / 2).collect();
        assert!(slow.len() >= 2 && fast > slow.len() * 20, "{gaps:?}");
        assert!(
            slow.iter().all(|g| **g > 70 * MS && **g <= 125 * MS),
            "{slow:?}"
        );
        // running: a 2 ms window within each 50 ms step
        let gaps = lock_step(ZmqPacing::Window, SimState::Running, 8, 12);
        assert!(
            gaps.iter().filter(|g| **g == 3 * MS / 2).count() >= 3,
            "{gaps:?}"
        );
        assert!(gaps.iter().any(|g| *g > 40 * MS), "{gaps:?}");
    }

    #[test]
    fn the_window_opens_only_once_a_pass_has_served_a_request() {
        let c = Clock::default();
        let t0 = Instant::now();
        let pacer = ZmqPacer::new(t0);
        // a request 10 ms into a pass that served nothing waits for the next pass
        let at = pacer.serve_at(&c, ZmqPacing::Window, SimState::Stopped, 8, t0 + 10 * MS);
        assert_eq!(at, t0 + 125 * MS);
        // a request exactly at a pass start is served by it
        assert_eq!(
            pacer.serve_at(
                &c,
                ZmqPacing::OnePerPass,
                SimState::Stopped,
                8,
                t0 + 250 * MS
            ),
            t0 + 250 * MS
        );
    }

    #[test]
    fn a_request_that_raises_the_idle_rate_keeps_its_pass_window() {
        let c = Clock::default();
        let t0 = Instant::now();
        let mut pacer = ZmqPacer::new(t0);
        // served at once at idle fps 0 (the request set idle fps 8)
        let at = t0 + 1000 * MS + MS / 3;
        assert_eq!(
            pacer.serve_at(&c, ZmqPacing::Window, SimState::Stopped, 0, at),
            at
        );
        pacer.served(&c, (ZmqPacing::Window, SimState::Stopped, 0), (at, at + MS));
        // protocol 2: the next request, 2 ms later, is served by the same pass's window
        let next = at + 2 * MS;
        let served = |pacing| pacer.serve_at(&c, pacing, SimState::Stopped, 8, next);
        assert_eq!(served(ZmqPacing::Window), next);
        // protocol 1: it waits for the next pass, one period after that pass began
        assert_eq!(served(ZmqPacing::OnePerPass), at + 125 * MS);
    }

    #[test]
    fn at_idle_fps_0_a_protocol_2_pass_serves_its_window() {
        let c = Clock::default();
        let t0 = Instant::now();
        let mut pacer = ZmqPacer::new(t0);
        let idle0 = (ZmqPacing::Window, SimState::Stopped, 0);
        // requests every 10 ms at idle fps 0: the pass that began with the first serves
        // them until 50 ms after it began
        for k in 0..5 {
            let at = t0 + 10 * MS * k;
            pacer.served(&c, idle0, (at, at + MS / 2));
        }
        // the last one raised the idle rate: a request 20 ms later (60 ms after the pass
        // began) waits for the next pass, one period after the pass began
        let late = t0 + 60 * MS;
        let at = pacer.serve_at(&c, ZmqPacing::Window, SimState::Stopped, 8, late);
        assert_eq!(at, t0 + 125 * MS);
        // one 5 ms after it, within the window, is served at once
        let soon = t0 + 45 * MS;
        let at = pacer.serve_at(&c, ZmqPacing::Window, SimState::Stopped, 8, soon);
        assert_eq!(at, soon);
    }

    #[test]
    fn a_pass_that_overruns_delays_the_next() {
        let c = Clock::default();
        let t0 = Instant::now();
        let mut pacer = ZmqPacer::new(t0);
        let at = pacer.serve_at(&c, ZmqPacing::OnePerPass, SimState::Stopped, 8, t0);
        assert_eq!(at, t0);
        pacer.served(
            &c,
            (ZmqPacing::OnePerPass, SimState::Stopped, 8),
            (at, t0 + 300 * MS),
        );
        let next = pacer.serve_at(
            &c,
            ZmqPacing::OnePerPass,
            SimState::Stopped,
            8,
            t0 + 301 * MS,
        );
        assert_eq!(next, t0 + 425 * MS);
    }
}
