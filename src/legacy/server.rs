//! A protocol-faithful legacy remote API server over the in-memory [`Simulator`].
//!
//! One client at a time. Received commands are stored and executed once per emulated
//! main-loop pass (at `idle_fps` passes per second while the simulation is stopped, 0 = as
//! soon as a message arrives; one pass per 50 ms simulation step while it runs); every client
//! message gets exactly one reply carrying the results produced since the previous reply,
//! with the message ID of the latest client message seen before that pass (-1 if no pass).

use std::io;
use std::net::{Shutdown, SocketAddr, TcpListener, TcpStream};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use super::command::{Command, GroupData, SimControl, encode_handle_list, id, opmode};
use super::wire::{Block, MAX_PACKET_SIZE, Message, MessageHeader, read_message, write_message};
use crate::coppelia::frame::rotation_from_euler;
use crate::coppelia::{HANDLE_PARENT, HANDLE_WORLD};
use crate::sim::{Clock, SimState, Simulator};

/// Server settings.
#[derive(Debug, Clone)]
pub struct ServerConfig {
    /// Address to listen on (loopback by default).
    pub listen: SocketAddr,
    /// Largest packet the server sends (1300 like CoppeliaSim's default).
    pub max_packet_size: usize,
    /// A client silent for this long is dropped (CoppeliaSim: 10 s).
    pub idle_timeout: Duration,
    /// When the emulated main loop passes (the simulation step while running).
    pub clock: Clock,
    /// Write the scene as JSON here after every session and on shutdown.
    pub dump: Option<PathBuf>,
    /// Print one line per connection and protocol error on stderr.
    pub verbose: bool,
    /// Print every received message (header and blocks) on stderr.
    pub trace: bool,
    /// After a client leaves, the listening socket is closed and re-created this much later
    /// (CoppeliaSim: 500 ms and more; connections are refused meanwhile). Zero keeps it open.
    pub rebind_delay: Duration,
}

impl Default for ServerConfig {
    fn default() -> Self {
        ServerConfig {
            listen: SocketAddr::from(([127, 0, 0, 1], 19997)),
            max_packet_size: MAX_PACKET_SIZE,
            idle_timeout: Duration::from_secs(10),
            clock: Clock::default(),
            dump: None,
            verbose: false,
            trace: false,
            rebind_delay: Duration::ZERO,
        }
    }
}

struct Stored {
    block: Block,
    last_exec: Option<Instant>,
}

struct Core {
    sim: Simulator,
    input: Vec<Stored>,
    output: Vec<Block>,
    fresh: Option<MessageHeader>,
    stale: MessageHeader,
    latest_id: i32,
    latest_client_time: i32,
    new_input: bool,
    sim_time_ms: i32,
    passes: u64,
    messages: u64,
}

struct Shared {
    core: Mutex<Core>,
    wake: Condvar,
    stop: AtomicBool,
    active: Mutex<Option<TcpStream>>,
    started: Instant,
    config: ServerConfig,
}

impl Shared {
    fn lock(&self) -> MutexGuard<'_, Core> {
        self.core.lock().unwrap_or_else(|e| e.into_inner())
    }
}

/// A running server; dropping it does not stop it, call [`ServerHandle::shutdown`].
pub struct ServerHandle {
    addr: SocketAddr,
    shared: Arc<Shared>,
    threads: Vec<JoinHandle<()>>,
}

/// Counters for tests and benchmarks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ServerStats {
    /// Main-loop passes executed.
    pub passes: u64,
    /// Client messages received.
    pub messages: u64,
}

impl ServerHandle {
    /// The bound address (useful with port 0).
    pub fn local_addr(&self) -> SocketAddr {
        self.addr
    }

    /// Runs `f` on the simulator (between passes).
    pub fn with_sim<R>(&self, f: impl FnOnce(&mut Simulator) -> R) -> R {
        let mut core = self.shared.lock();
        let r = f(&mut core.sim);
        self.shared.wake.notify_all();
        r
    }

    /// Counters.
    pub fn stats(&self) -> ServerStats {
        let c = self.shared.lock();
        ServerStats {
            passes: c.passes,
            messages: c.messages,
        }
    }

    /// Stops the threads (closing the current session), writes the dump, returns the simulator.
    pub fn shutdown(self) -> Simulator {
        self.shared.stop.store(true, Ordering::SeqCst);
        self.shared.wake.notify_all();
        if let Some(s) = self
            .shared
            .active
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .take()
        {
            let _ = s.shutdown(Shutdown::Both);
        }
        for t in self.threads {
            let _ = t.join();
        }
        let sim = self.shared.lock().sim.clone();
        write_dump(&self.shared.config, &sim);
        sim
    }

    /// Blocks until the server stops (never, unless another thread shuts it down).
    pub fn wait(self) {
        for t in self.threads {
            let _ = t.join();
        }
    }
}

fn write_dump(config: &ServerConfig, sim: &Simulator) {
    if let Some(path) = &config.dump {
        let text = serde_json::to_string_pretty(&sim.scene.to_json()).unwrap_or_default();
        if let Err(e) = std::fs::write(path, text) {
            eprintln!(
                "vrep-maze serve: cannot write scene dump {}: {e}",
                path.display()
            );
        }
    }
}

/// Binds and starts the server threads (accept/session thread and main-loop thread).
pub fn spawn(config: ServerConfig, sim: Simulator) -> io::Result<ServerHandle> {
    let listener = TcpListener::bind(config.listen)?;
    let addr = listener.local_addr()?;
    let shared = Arc::new(Shared {
        core: Mutex::new(Core {
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
            sim_time_ms: 0,
            passes: 0,
            messages: 0,
        }),
        wake: Condvar::new(),
        stop: AtomicBool::new(false),
        active: Mutex::new(None),
        started: Instant::now(),
        config,
    });
    let s1 = shared.clone();
    let main_loop = std::thread::Builder::new()
        .name("sim-main-loop".into())
        .spawn(move || main_loop(&s1))?;
    let s2 = shared.clone();
    let acceptor = std::thread::Builder::new()
        .name("remote-api".into())
        .spawn(move || accept_loop(&s2, listener, addr))?;
    Ok(ServerHandle {
        addr,
        shared,
        threads: vec![main_loop, acceptor],
    })
}

/// Accepts one client at a time. Like CoppeliaSim, after a client leaves the listening
/// socket is closed and re-created `rebind_delay` later (connections are refused meanwhile).
fn accept_loop(shared: &Shared, listener: TcpListener, addr: SocketAddr) {
    let mut listener = Some(listener);
    while !shared.stop.load(Ordering::SeqCst) {
        let l = match listener.take() {
            Some(l) => l,
            None => match TcpListener::bind(addr) {
                Ok(l) => l,
                Err(e) => {
                    if shared.config.verbose {
                        eprintln!("vrep-maze serve: cannot listen on {addr} again: {e}; retrying");
                    }
                    std::thread::sleep(Duration::from_millis(200));
                    continue;
                }
            },
        };
        let _ = l.set_nonblocking(true);
        let stream = loop {
            if shared.stop.load(Ordering::SeqCst) {
                return;
            }
            match l.accept() {
                Ok((s, _)) => break s,
                Err(e) if e.kind() == io::ErrorKind::WouldBlock => {
                    std::thread::sleep(Duration::from_millis(10))
                }
                Err(_) => std::thread::sleep(Duration::from_millis(10)),
            }
        };
        let _ = stream.set_nonblocking(false);
        let peer = stream.peer_addr().ok();
        if shared.config.verbose {
            eprintln!("vrep-maze serve: client {peer:?} connected");
        }
        let why = session(shared, stream);
        shared
            .active
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .take();
        {
            let mut core = shared.lock();
            core.input.clear();
            core.output.clear();
            core.fresh = None;
            write_dump(&shared.config, &core.sim);
        }
        if shared.config.verbose {
            eprintln!("vrep-maze serve: client {peer:?} left: {why}");
        }
        if shared.config.rebind_delay.is_zero() {
            listener = Some(l);
        } else {
            drop(l);
            std::thread::sleep(shared.config.rebind_delay);
        }
    }
}

fn session(shared: &Shared, mut stream: TcpStream) -> String {
    let _ = stream.set_read_timeout(Some(shared.config.idle_timeout));
    let _ = stream.set_nodelay(true);
    *shared.active.lock().unwrap_or_else(|e| e.into_inner()) = stream.try_clone().ok();
    {
        let mut core = shared.lock();
        core.input.clear();
        core.output.clear();
        core.fresh = None;
    }
    loop {
        if shared.stop.load(Ordering::SeqCst) {
            let _ = stream.shutdown(Shutdown::Both);
            return "server stopping".into();
        }
        let bytes = match read_message(&mut stream) {
            Ok(b) => b,
            Err(e) => return format!("{e}"),
        };
        let msg = match Message::decode(&bytes) {
            Ok(m) => m,
            Err(e) => return format!("protocol error: {e}"),
        };
        if shared.config.trace {
            trace(&msg, bytes.len());
        }
        let kill = msg
            .blocks
            .last()
            .is_some_and(|b| b.raw_id() == id::KILL_CONNECTION);
        let reply = {
            let mut core = shared.lock();
            core.messages += 1;
            core.latest_id = msg.header.message_id;
            core.latest_client_time = msg.header.client_time;
            // at idle fps 0 every client message triggers a pass (CoppeliaSim then loops as fast as it can)
            core.new_input = true;
            let mut blocks = Vec::with_capacity(msg.blocks.len());
            for b in msg.blocks {
                if b.raw_id() == id::KILL_CONNECTION {
                    continue;
                }
                if b.split.is_some() {
                    if shared.config.verbose {
                        eprintln!(
                            "vrep-maze serve: split command chunks are not supported; ignored"
                        );
                    }
                    continue;
                }
                blocks.push(b);
            }
            store(&mut core.input, blocks);
            shared.wake.notify_all();
            let header = core.fresh.take().unwrap_or(MessageHeader {
                message_id: -1,
                ..core.stale
            });
            Message {
                header,
                blocks: std::mem::take(&mut core.output),
            }
        };
        if let Err(e) = write_message(&mut stream, &reply.encode(), shared.config.max_packet_size) {
            return format!("{e}");
        }
        if kill {
            let _ = stream.shutdown(Shutdown::Both);
            return "kill command".into();
        }
    }
}

/// One line per message and per block, for protocol debugging and conformance tests.
fn trace(msg: &Message, len: usize) {
    let h = &msg.header;
    let mut out = format!(
        "trace: message id={} client_time={} bytes={len} blocks={}",
        h.message_id,
        h.client_time,
        msg.blocks.len()
    );
    for b in &msg.blocks {
        out.push_str(&format!(
            "\ntrace:   block cmd={:#06x} opmode={:#07x} delay={} status={} id_bytes={} data_bytes={} size={}",
            b.raw_id(),
            b.opmode(),
            b.delay,
            b.status,
            b.id_data.len(),
            b.data.len(),
            b.encoded_len()
        ));
    }
    eprintln!("{out}");
}

/// Input-list rule: a new command replaces the stored one of the same identity (in place)
/// unless its do-not-overwrite bit is set; otherwise it is appended.
fn store(input: &mut Vec<Stored>, blocks: Vec<Block>) {
    let mut index: std::collections::HashMap<(u16, Vec<u8>), usize> = input
        .iter()
        .enumerate()
        .map(|(i, s)| ((s.block.raw_id(), s.block.id_data.clone()), i))
        .collect();
    for block in blocks {
        let key = (block.raw_id(), block.id_data.clone());
        if block.status & 1 == 0 {
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

/// How often a waiting main loop checks whether the server is stopping.
const STOP_POLL: Duration = Duration::from_millis(50);

fn main_loop(shared: &Shared) {
    let mut last_pass = Instant::now();
    let mut core = shared.lock();
    while !shared.stop.load(Ordering::SeqCst) {
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
        pass(shared, &mut core);
    }
}

fn state_bits(state: SimState) -> u8 {
    match state {
        SimState::Stopped => 0,
        SimState::Running => 1,
        SimState::Paused => 3,
    }
}

/// One main-loop pass: stamp the output header, execute the stored commands in order.
fn pass(shared: &Shared, core: &mut Core) {
    if !core.output.is_empty() {
        return;
    }
    core.passes += 1;
    if core.sim.state == SimState::Running {
        core.sim_time_ms = core
            .sim_time_ms
            .wrapping_add(shared.config.clock.step.as_millis() as i32);
    }
    let header = MessageHeader {
        message_id: core.latest_id,
        client_time: core.latest_client_time,
        server_time: (shared.started.elapsed().as_secs_f64() * 1000.1) as i32,
        scene_id: 0x5A17,
        server_state: state_bits(core.sim.state),
    };
    core.fresh = Some(header);
    core.stale = header;
    let now = Instant::now();
    let mut input = std::mem::take(&mut core.input);
    let mut results = Vec::new();
    input.retain_mut(|s| {
        let mode = s.block.opmode();
        let mut reply = Block {
            delay: 0,
            sim_time: core.sim_time_ms,
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
        let (ok, data) = execute(&mut core.sim, &s.block);
        reply.status = u8::from(!ok);
        reply.data = data;
        results.push(reply);
        streaming
    });
    if core.sim.state == SimState::Stopped {
        core.sim_time_ms = 0;
    }
    // commands that arrived during this pass (none: we hold the lock) keep their order
    input.append(&mut core.input);
    core.input = input;
    core.output = results;
}

fn f32x3(v: [f64; 3]) -> Vec<u8> {
    v.iter().flat_map(|x| (*x as f32).to_le_bytes()).collect()
}

fn widen(v: [f32; 3]) -> [f64; 3] {
    [v[0] as f64, v[1] as f64, v[2] as f64]
}

/// Executes one command; returns (success, reply pure data).
fn execute(sim: &mut Simulator, block: &Block) -> (bool, Vec<u8>) {
    let Some(cmd) = Command::from_block(block) else {
        return (false, block.data.clone());
    };
    let i32le = |v: i32| v.to_le_bytes().to_vec();
    let scene = &mut sim.scene;
    match cmd {
        Command::GetObjectHandle(name) => match scene.resolve(&name) {
            Ok(h) => (true, i32le(h)),
            Err(_) => (false, i32le(-1)),
        },
        Command::GetObjects(t) => {
            let hs: Vec<i32> = scene
                .objects()
                .filter(|o| t == -2 || o.kind.code() == t)
                .map(|o| o.handle)
                .collect();
            (true, encode_handle_list(&hs))
        }
        Command::GetObjectGroupData {
            object_type,
            data_type,
        } => match group_data(sim, object_type, data_type) {
            Some(g) => (true, g.encode()),
            None => (false, vec![]),
        },
        Command::GetObjectParent(h) => (
            true,
            i32le(
                scene
                    .get(h)
                    .ok()
                    .and_then(|o| o.parent)
                    .unwrap_or(HANDLE_WORLD),
            ),
        ),
        Command::SetObjectParent {
            handle,
            parent,
            keep_in_place,
        } => {
            let parent = (parent != HANDLE_WORLD).then_some(parent);
            (
                scene.set_parent(handle, parent, keep_in_place).is_ok(),
                vec![],
            )
        }
        Command::CopyPaste(hs) => (
            true,
            encode_handle_list(&scene.copy_paste(&hs).unwrap_or_default()),
        ),
        Command::SetPosition {
            handle,
            relative_to,
            xyz,
        } => (
            scene.set_position(handle, relative_to, widen(xyz)).is_ok(),
            vec![],
        ),
        Command::SetOrientation {
            handle,
            relative_to,
            euler,
        } => (
            scene
                .set_orientation(handle, relative_to, widen(euler))
                .is_ok(),
            vec![],
        ),
        Command::GetPosition {
            handle,
            relative_to,
        } => match scene.pose(handle, relative_to) {
            Ok((p, _)) => (true, f32x3(p)),
            Err(_) => (false, vec![]),
        },
        Command::GetOrientation {
            handle,
            relative_to,
        } => match scene.pose(handle, relative_to) {
            Ok((_, e)) => (true, f32x3(e)),
            Err(_) => (false, vec![]),
        },
        Command::GetQuaternion {
            handle,
            relative_to,
        } => match scene.pose(handle, relative_to) {
            Ok((_, e)) => {
                let q = rotation_from_euler(e);
                (
                    true,
                    [q.i, q.j, q.k, q.w]
                        .iter()
                        .flat_map(|x| (*x as f32).to_le_bytes())
                        .collect(),
                )
            }
            Err(_) => (false, vec![]),
        },
        Command::RemoveObject(h) => (scene.remove(h).is_ok(), vec![]),
        Command::GetIntParam(p) => match sim.int_param(p) {
            Some(v) => (true, i32le(v)),
            None => (false, vec![]),
        },
        Command::SetIntParam(p, v) => (sim.set_int_param(p, v), vec![]),
        Command::Simulation(c) => {
            let ok = match c {
                SimControl::Start => sim.start(),
                SimControl::Pause => sim.pause(),
                SimControl::Stop => sim.stop(),
            };
            (ok, vec![])
        }
        Command::GetIntSignal(name) => match sim.int_signals.get(&name) {
            Some(v) => (true, i32le(*v)),
            None => (false, vec![]),
        },
        Command::SetIntSignal(name, v) => {
            sim.int_signals.insert(name, v);
            (true, vec![])
        }
        Command::ClearIntSignal(name) => {
            if name.is_empty() {
                sim.int_signals.clear();
            } else {
                sim.int_signals.remove(&name);
            }
            (true, vec![])
        }
        Command::KillConnection => (true, vec![]),
    }
}

/// `simxGetObjectGroupData` over the scene; `None` = failure (unknown object or data type).
fn group_data(sim: &Simulator, object_type: i32, data_type: i32) -> Option<GroupData> {
    let scene = &sim.scene;
    let objects: Vec<_> = match object_type {
        109 => scene.objects().collect(),
        0..=107 => scene
            .objects()
            .filter(|o| o.kind.code() == object_type)
            .collect(),
        _ => return None,
    };
    let mut g = GroupData {
        handles: objects.iter().map(|o| o.handle).collect(),
        ..Default::default()
    };
    for o in &objects {
        let rel = |abs: bool| if abs { HANDLE_WORLD } else { HANDLE_PARENT };
        let pose = |abs: bool| scene.pose(o.handle, rel(abs)).ok();
        let push3 = |g: &mut GroupData, v: [f64; 3]| g.floats.extend(v.iter().map(|x| *x as f32));
        match data_type {
            0 => g.strings.push(o.name.clone()),
            1 => g.ints.push(o.kind.code()),
            2 => g.ints.push(o.parent.unwrap_or(HANDLE_WORLD)),
            3 | 4 => push3(&mut g, pose(data_type == 3)?.0),
            5 | 6 => push3(&mut g, pose(data_type == 5)?.1),
            7 | 8 => {
                let q = rotation_from_euler(pose(data_type == 7)?.1);
                g.floats
                    .extend([q.i, q.j, q.k, q.w].iter().map(|x| *x as f32));
            }
            9 | 10 => {
                let (p, e) = pose(data_type == 9)?;
                push3(&mut g, p);
                push3(&mut g, e);
            }
            20 => g.strings.push(o.alias.clone()),
            21 => g.strings.push(scene.path(o.handle).ok()?),
            _ => return None,
        }
    }
    Some(g)
}
