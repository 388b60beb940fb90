//! The emulated main loop: when a pass happens, and what a pass does with the input list.
//!
//! Timing comes from the one clock, [`Clock::next_pass`](crate::sim::Clock::next_pass): idle
//! fps while the simulation is stopped or paused (at 0, a pass as soon as a message arrives),
//! one pass per simulation step while it runs. Received commands wait in the input list
//! ([`store`]); a pass stamps the reply header and executes them in order: oneshot and
//! blocking commands once, streaming ones every pass (at most once per their period) until
//! discontinued. Their results wait in the output buffer for the next reply.
//!
//! With realistic [`Timing`](crate::sim::Timing), a pass also takes the modeled server work of
//! the commands it executed ([`super::execute::execute_with_ops`] priced by `vrep_maze_core::coppelia::cost`), at least
//! [`CostModel::legacy_pass_floor`](crate::sim::CostModel::legacy_pass_floor) at idle fps 0
//! (2 ms: `docs/measurements.md` "Legacy calls at idle fps 0"; the spec's "Pacing" gives 9–10
//! ms, timed with other clients): its results are held back until then, replies meanwhile carry none (message
//! ID -1, as while no pass happened), and the next pass waits for it. A big pass checks the
//! stop flag between commands, so the server stops promptly even in the middle of one. Every
//! pass that executed commands is also appended to the simulator's ledger when it keeps one
//! ([`crate::sim::Simulator::ledger`]), whatever the timing.

use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use super::Shared;
use super::execute::execute_with_ops;
use crate::legacy::command::opmode;
use crate::legacy::wire::{Block, Message, MessageHeader, server_state, status};
use crate::sim::{Served, SimState, Simulator, Timing};

/// Reply header `scene_id`: the low 16 bits of CoppeliaSim's `sim_intparam_scene_unique_id`;
/// the emulated scene never changes identity, so any fixed value does.
const SCENE_ID: u16 = 0x5A17;

/// How often a waiting main loop checks whether the server is stopping.
const STOP_POLL: Duration = Duration::from_millis(50);

/// A command in the input list.
struct Stored {
    block: Block,
    /// When a pass last executed it (streaming commands wait out their period).
    last_exec: Option<Instant>,
}

/// The simulator and the main loop's state, shared with the session under one mutex.
pub(super) struct Core {
    /// The emulated CoppeliaSim.
    pub(super) sim: Simulator,
    /// Commands waiting for a pass, in arrival order (streaming ones stay).
    input: Vec<Stored>,
    /// Results of the latest pass, sent with the next reply.
    output: Vec<Block>,
    /// Header stamped by a pass and not sent yet.
    fresh: Option<MessageHeader>,
    /// Header of the latest pass: its fields are repeated (under message ID -1) by replies
    /// that follow no pass.
    stale: MessageHeader,
    /// ID and client time of the latest client message, for the next pass's header.
    latest_id: i32,
    latest_client_time: i32,
    /// A message arrived since the latest pass (at idle fps 0 it triggers one).
    new_input: bool,
    /// The latest pass is still working (modeled cost) until then: its results are held back.
    busy_until: Option<Instant>,
    /// Passes that executed the input list.
    pub(super) passes: u64,
    /// Client messages received.
    pub(super) messages: u64,
}

impl Core {
    pub(super) fn new(sim: Simulator) -> Core {
        Core {
            sim,
            input: Vec::new(),
            output: Vec::new(),
            fresh: None,
            stale: MessageHeader {
                message_id: -1,
                ..Default::default()
            },
            latest_id: -1,
            latest_client_time: 0,
            new_input: false,
            busy_until: None,
            passes: 0,
            messages: 0,
        }
    }

    /// Forgets the stored commands and unsent results (a client came or left).
    pub(super) fn end_session(&mut self) {
        self.input.clear();
        self.output.clear();
        self.fresh = None;
    }

    /// A client message arrived with these commands (the session has removed the kill block
    /// and split chunks): remember its ID and time for the next pass's header, store the
    /// commands, and return the reply: the results of the latest pass under its header, or
    /// no results under message ID -1 (other fields stale) if no pass happened since the
    /// previous reply.
    pub(super) fn receive(&mut self, header: &MessageHeader, blocks: Vec<Block>) -> Message {
        self.messages += 1;
        self.latest_id = header.message_id;
        self.latest_client_time = header.client_time;
        // at idle fps 0 every client message triggers a pass (CoppeliaSim then loops as fast as it can)
        self.new_input = true;
        store(&mut self.input, blocks);
        let stale = MessageHeader {
            message_id: -1,
            ..self.stale
        };
        if self.busy_until.is_some_and(|t| Instant::now() < t) {
            return Message {
                header: stale,
                blocks: vec![],
            };
        }
        let header = self.fresh.take().unwrap_or(stale);
        Message {
            header,
            blocks: std::mem::take(&mut self.output),
        }
    }

    /// One main-loop pass: bring the simulation up to now ([`Simulator::sync`]: the
    /// emulated robot moves), stamp the output header, execute the stored commands in order
    /// and stamp their replies with the simulation time. `started` is the start of the
    /// server clock, `now` the moment of the pass. Does nothing
    /// while the results of the previous pass have not been sent. Returns the modeled work
    /// of the commands executed (zero with instant `timing`); when `stop` is set it leaves
    /// the commands not executed yet in the input list.
    fn pass(
        &mut self,
        now: Instant,
        started: Instant,
        timing: &Timing,
        stop: &AtomicBool,
    ) -> Duration {
        if !self.output.is_empty() {
            return Duration::ZERO;
        }
        self.passes += 1;
        self.sim.sync(now);
        let header = MessageHeader {
            message_id: self.latest_id,
            client_time: self.latest_client_time,
            // CoppeliaSim: int(simGetSystemTime() * 1000.1)
            server_time: (started.elapsed().as_secs_f64() * 1000.1) as i32,
            scene_id: SCENE_ID,
            server_state: state_bits(self.sim.state),
        };
        self.fresh = Some(header);
        self.stale = header;
        // 0 while stopped: the simulation clock starts at 0 with every run
        let sim_time = self.sim.time_ms(now);
        // the pass is charged in the state it began in (before its commands change it)
        let mut charge = self.sim.charge(Served::LegacyPass, vec![]);
        let sim = &mut self.sim;
        let mut results = Vec::new();
        self.input.retain_mut(|s| {
            if stop.load(Ordering::Relaxed) {
                return true;
            }
            let mode = s.block.opmode();
            let mut reply = Block {
                delay: 0,
                sim_time,
                status: 0,
                data: vec![],
                split: None,
                ..s.block.clone()
            };
            if mode == opmode::DISCONTINUE {
                results.push(reply);
                return false;
            }
            let streaming = mode == opmode::STREAMING || mode == opmode::STREAMING_SPLIT;
            if streaming
                && let Some(t) = s.last_exec
                && now.duration_since(t) < Duration::from_millis(s.block.delay as u64)
            {
                return true;
            }
            s.last_exec = Some(now);
            let (ok, data, ops) = execute_with_ops(sim, &s.block);
            charge.ops.extend(ops);
            reply.status = if ok { 0 } else { status::REMOTE_ERROR };
            reply.data = data;
            results.push(reply);
            streaming
        });
        let executed = !results.is_empty();
        self.output = results;
        if !executed {
            return Duration::ZERO;
        }
        self.sim.record(&charge);
        timing.cost(|m| charge.work(m))
    }
}

/// The server-state byte of reply headers.
fn state_bits(state: SimState) -> u8 {
    match state {
        SimState::Stopped => 0,
        SimState::Running => server_state::NOT_STOPPED,
        SimState::Paused => server_state::NOT_STOPPED | server_state::PAUSED,
    }
}

/// Input-list rule: a new command replaces the stored one of the same identity (in place)
/// unless its do-not-overwrite bit is set; otherwise it is appended.
fn store(input: &mut Vec<Stored>, blocks: Vec<Block>) {
    let mut index: HashMap<(u16, Vec<u8>), usize> = input
        .iter()
        .enumerate()
        .map(|(i, s)| (s.block.identity(), i))
        .collect();
    for block in blocks {
        let key = block.identity();
        if block.status & status::DO_NOT_OVERWRITE == 0 {
            if let Some(&i) = index.get(&key) {
                input[i].block = block;
                continue;
            }
            index.insert(key, input.len());
        }
        input.push(Stored {
            block,
            last_exec: None,
        });
    }
}

/// The main-loop thread: waits for the next pass the clock allows (or for input at idle
/// fps 0), then passes; ends when the server stops.
pub(super) fn run(shared: &Shared) {
    let mut last_pass = Instant::now();
    let mut core = shared.lock();
    while !shared.stop.load(Ordering::SeqCst) {
        // the latest pass is still working: wait for it (the lock is free meanwhile)
        if let Some(busy) = core.busy_until {
            match busy.checked_duration_since(Instant::now()) {
                Some(wait) if !wait.is_zero() => {
                    core = shared
                        .wake
                        .wait_timeout(core, wait.min(STOP_POLL))
                        .unwrap_or_else(|e| e.into_inner())
                        .0;
                    continue;
                }
                _ => core.busy_until = None,
            }
        }
        let next = shared
            .config
            .clock
            .next_pass(core.sim.state, core.sim.idle_fps, last_pass);
        // with no pass due (idle fps 0), wait for input; wake regularly to see `stop`
        let wait = match next {
            None if core.new_input => None,
            None => Some(STOP_POLL),
            Some(at) => at.checked_duration_since(Instant::now()),
        };
        if let Some(wait) = wait.filter(|w| !w.is_zero()) {
            core = shared
                .wake
                .wait_timeout(core, wait.min(STOP_POLL))
                .unwrap_or_else(|e| e.into_inner())
                .0;
            continue;
        }
        last_pass = Instant::now();
        core.new_input = false;
        let work = core.pass(
            last_pass,
            shared.started,
            &shared.config.timing,
            &shared.stop,
        );
        if !work.is_zero() {
            core.busy_until = Some(last_pass + work);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::legacy::command::{Command, id, read_i32};
    use crate::sim::{Op, Scene};
    use vrep_maze_core::coppelia::HANDLE_WORLD;

    const STEP: Duration = Duration::from_millis(50);

    fn core() -> Core {
        Core::new(Simulator::new(Scene::course(), 0))
    }

    /// One pass now, with no modeled cost and no stop request.
    fn instant_pass(core: &mut Core) -> Duration {
        pass_at(core, Instant::now())
    }

    /// One pass at `now`, with no modeled cost and no stop request.
    fn pass_at(core: &mut Core, now: Instant) -> Duration {
        core.pass(
            now,
            Instant::now(),
            &Timing::instant(),
            &AtomicBool::new(false),
        )
    }

    fn header(message_id: i32) -> MessageHeader {
        MessageHeader {
            message_id,
            client_time: 1000 + message_id,
            ..Default::default()
        }
    }

    fn set_x(handle: i32, x: f32) -> Block {
        Command::SetPosition {
            handle,
            relative_to: HANDLE_WORLD,
            xyz: [x, 0.0, 0.0],
        }
        .to_block(opmode::ONESHOT)
    }

    fn stored(input: &[Stored]) -> Vec<Option<Command>> {
        input
            .iter()
            .map(|s| Command::from_block(&s.block))
            .collect()
    }

    #[test]
    fn store_replaces_the_same_identity_in_place_unless_told_not_to() {
        let mut input = vec![];
        let floor = Command::GetObjectHandle("Floor".into()).to_block(opmode::BLOCKING);
        store(
            &mut input,
            vec![set_x(1, 1.0), set_x(2, 2.0), floor.clone()],
        );
        // same identity (command and handle) replaces in place, even within one message
        store(&mut input, vec![set_x(1, 3.0), set_x(1, 4.0)]);
        let paste = Command::CopyPaste(vec![1]).to_block(opmode::BLOCKING);
        assert_eq!(
            paste.status & status::DO_NOT_OVERWRITE,
            status::DO_NOT_OVERWRITE
        );
        store(&mut input, vec![paste.clone(), paste]);
        let want = [
            set_x(1, 4.0),
            set_x(2, 2.0),
            floor,
            Command::CopyPaste(vec![1]).to_block(opmode::BLOCKING),
            Command::CopyPaste(vec![1]).to_block(opmode::BLOCKING),
        ];
        assert_eq!(
            stored(&input),
            want.iter().map(Command::from_block).collect::<Vec<_>>()
        );
    }

    #[test]
    fn replies_carry_the_latest_pass_results_under_its_header_or_id_minus_one() {
        let mut core = core();
        let floor = Command::GetObjectHandle("Floor".into());
        let r = core.receive(&header(0), vec![floor.to_block(opmode::BLOCKING)]);
        assert_eq!(
            (r.header.message_id, r.blocks.len()),
            (-1, 0),
            "no pass yet"
        );

        instant_pass(&mut core);
        let r = core.receive(&header(1), vec![]);
        assert_eq!(r.header.message_id, 0, "the latest message before the pass");
        assert_eq!(r.header.client_time, 1000);
        assert_eq!(r.header.scene_id, SCENE_ID);
        assert_eq!(r.header.server_state, 0);
        assert_eq!(r.blocks.len(), 1);
        let b = &r.blocks[0];
        assert_eq!(
            (b.raw_id(), b.opmode()),
            (id::GET_OBJECT_HANDLE, opmode::BLOCKING)
        );
        assert_eq!((b.status, b.delay, b.sim_time), (0, 0, 0));
        assert_eq!(read_i32(&b.data, 0), core.sim.scene.resolve("Floor").ok());
        assert!(core.input.is_empty(), "a blocking command runs once");

        let r = core.receive(&header(2), vec![]);
        assert_eq!((r.header.message_id, r.blocks.len()), (-1, 0));
        assert_eq!(
            r.header.client_time, 1000,
            "stale fields of the latest pass"
        );
        assert_eq!((core.passes, core.messages), (1, 3));
    }

    #[test]
    fn a_pass_waits_until_the_previous_results_were_sent() {
        let mut core = core();
        let get = Command::GetPosition {
            handle: core.sim.scene.resolve("Maze").unwrap(),
            relative_to: HANDLE_WORLD,
        };
        core.receive(&header(0), vec![get.to_block(opmode::STREAMING)]);
        instant_pass(&mut core);
        instant_pass(&mut core);
        assert_eq!(core.passes, 1, "the second pass found unsent results");
        let r = core.receive(&header(1), vec![]);
        assert_eq!(r.blocks.len(), 1);
        instant_pass(&mut core);
        assert_eq!(core.passes, 2);
        let missing = Command::GetObjectHandle("Nope".into()).to_block(opmode::BLOCKING);
        let r = core.receive(&header(2), vec![missing.clone(), missing]);
        assert_eq!(r.blocks.len(), 1, "the stream's result");
        instant_pass(&mut core);
        let r = core.receive(&header(3), vec![]);
        let failed: Vec<u8> = r
            .blocks
            .iter()
            .filter(|b| b.raw_id() == id::GET_OBJECT_HANDLE)
            .map(|b| b.status)
            .collect();
        assert_eq!(
            failed,
            [status::REMOTE_ERROR],
            "two identical requests are one"
        );
    }

    #[test]
    fn streaming_repeats_at_its_period_until_discontinued() {
        let mut core = core();
        let get = |name: &str| Command::GetPosition {
            handle: core.sim.scene.resolve(name).unwrap(),
            relative_to: HANDLE_WORLD,
        };
        let (maze, floor) = (get("Maze"), get("Floor"));
        let cycle = |core: &mut Core, blocks| {
            core.receive(&header(0), blocks);
            instant_pass(core);
            core.receive(&header(1), vec![]).blocks
        };
        assert_eq!(
            cycle(&mut core, vec![maze.to_block(opmode::STREAMING)]).len(),
            1
        );
        assert_eq!(cycle(&mut core, vec![]).len(), 1, "every pass");
        let stop = cycle(&mut core, vec![maze.to_block(opmode::DISCONTINUE)]);
        assert_eq!(stop.len(), 1);
        assert_eq!(stop[0].opmode(), opmode::DISCONTINUE);
        assert!(stop[0].data.is_empty() && stop[0].status == 0);
        assert_eq!(cycle(&mut core, vec![]).len(), 0);
        assert!(core.input.is_empty());

        let mut slow = floor.to_block(opmode::STREAMING);
        slow.delay = u16::MAX;
        assert_eq!(cycle(&mut core, vec![slow]).len(), 1, "runs at once");
        assert_eq!(
            cycle(&mut core, vec![]).len(),
            0,
            "then waits out its period"
        );
        assert_eq!(core.input.len(), 1);
    }

    #[test]
    fn a_stopping_server_leaves_the_rest_of_a_big_pass_undone() {
        let mut core = core();
        let blocks = (0..100).map(|i| set_x(i, 0.0)).collect();
        core.receive(&header(0), blocks);
        let stop = AtomicBool::new(true);
        core.pass(Instant::now(), Instant::now(), &Timing::instant(), &stop);
        assert_eq!(core.input.len(), 100, "nothing executed once stopping");
    }

    #[test]
    fn a_realistic_pass_takes_its_modeled_work_and_holds_its_results_back() {
        let mut core = core();
        let line = core.sim.scene.resolve("Line").unwrap();
        let real = Timing::realistic();
        let m = real.costs.unwrap();
        let paste = Command::CopyPaste(vec![line]).to_block(opmode::BLOCKING);
        core.receive(&header(0), vec![paste, set_x(line, 1.0)]);
        let work = core.pass(
            Instant::now(),
            Instant::now(),
            &real,
            &AtomicBool::new(false),
        );
        // at idle fps 0 a pass lasts at least the floor (docs/measurements.md: 2 ms)
        let pasted = m.ops(&[
            Op::LegacyCommand,
            Op::Paste {
                copies: 1,
                objects: 5,
            },
            Op::LegacyCommand,
            Op::HalfPose { objects: 6 },
        ]);
        assert_eq!(work, pasted.max(m.legacy_pass_floor));
        core.busy_until = Some(Instant::now() + Duration::from_secs(60));
        let r = core.receive(&header(1), vec![]);
        assert_eq!(
            (r.header.message_id, r.blocks.len()),
            (-1, 0),
            "still working"
        );
        core.busy_until = None;
        let r = core.receive(&header(2), vec![]);
        assert_eq!((r.header.message_id, r.blocks.len()), (0, 2));
        // an empty pass costs nothing; at idle fps 8 there is no floor
        assert_eq!(
            core.pass(
                Instant::now(),
                Instant::now(),
                &real,
                &AtomicBool::new(false)
            ),
            Duration::ZERO
        );
        core.sim.idle_fps = 8;
        core.receive(&header(3), vec![set_x(line, 2.0)]);
        let work = core.pass(
            Instant::now(),
            Instant::now(),
            &real,
            &AtomicBool::new(false),
        );
        assert_eq!(
            work,
            m.ops(&[Op::LegacyCommand, Op::HalfPose { objects: 6 }])
        );
    }

    #[test]
    fn passes_that_executed_commands_are_recorded_in_the_ledger_when_kept() {
        let mut core = core();
        let line = core.sim.scene.resolve("Line").unwrap();
        instant_pass(&mut core);
        core.receive(&header(0), vec![set_x(line, 1.0)]);
        instant_pass(&mut core);
        assert_eq!(core.sim.ledger, None, "not kept by default");
        core.sim.ledger = Some(vec![]);
        core.receive(&header(1), vec![set_x(line, 2.0), set_x(line, 3.0)]);
        instant_pass(&mut core);
        core.receive(&header(2), vec![]);
        instant_pass(&mut core); // executes nothing: not recorded
        let ledger = core.sim.ledger.take().unwrap();
        assert_eq!(ledger.len(), 1);
        assert_eq!(ledger[0].served, Served::LegacyPass);
        assert_eq!(ledger[0].idle_fps, 0);
        assert_eq!(
            ledger[0].ops.len(),
            2,
            "one set-x, replaced in the input list"
        );
    }

    #[test]
    fn running_passes_advance_sim_time_and_set_the_state_bits() {
        let mut core = core();
        let get = Command::GetIntParam(vrep_maze_core::coppelia::INTPARAM_IDLE_FPS);
        core.sim.start();
        let started = Instant::now();
        for n in 1..=2 {
            core.receive(&header(n), vec![get.to_block(opmode::BLOCKING)]);
            // a pass one step later than the previous one: one more step of simulation time
            pass_at(&mut core, started + STEP * n as u32 + STEP / 2);
            let r = core.receive(&header(n), vec![]);
            assert_eq!(r.header.server_state, server_state::NOT_STOPPED);
            assert_eq!(r.blocks[0].sim_time, 50 * n);
        }
        core.sim.pause();
        instant_pass(&mut core);
        let r = core.receive(&header(3), vec![]);
        assert_eq!(
            r.header.server_state,
            server_state::NOT_STOPPED | server_state::PAUSED
        );
        assert_eq!(state_bits(SimState::Stopped), 0);
    }
}
