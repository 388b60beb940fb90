//! An emulated ZeroMQ remote API server (the CoppeliaSim add-on) over a shared [`Simulator`].
//!
//! One REP socket, one thread. The add-on serves requests from CoppeliaSim's main loop, timed
//! by [`ZmqPacer::serve_at`]: protocol 1 (4.5.1) one request per pass, protocol 2 (4.6+) also
//! at once within the busy window of a pass that served one; at idle fps 0 at once. A pass
//! also serves the requests already queued on the socket when it has answered one, for up to
//! [`ZMQ_TIME_SLOT`] (what a client that sends before reading replies meets). With
//! realistic [`Timing`], each call then takes its modeled cost (`vrep_maze_core::coppelia::cost`: about
//! 0.45 ms a call, plus the simulator's own work for pastes, re-parenting and removals, which
//! grows with the objects in the scene; `../shared/spec/real-coppeliasim-4.5.1.md` "Pacing",
//! "ZeroMQ costs at idle fps 0" and "Costs that grow with the scene") before its reply, and
//! is appended to the simulator's ledger when it keeps one.
//! This module is the transport (socket, request and reply maps of either protocol generation,
//! protocol-2 results held back behind `_*wait*_`); the functions themselves are in the
//! `functions` registry.

mod functions;

use std::collections::HashMap;
use std::net::SocketAddr;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use ciborium::Value;
use vrep_maze_core::coppelia::vertex_merge::merge_steps;
use vrep_maze_wire::zmq_api::calls;

use crate::sim::cost::{self, Op};
use crate::sim::{
    Charge, Clock, Served, SimState, Simulator, Timing, ZMQ_TIME_SLOT, ZmqPacer, ZmqPacing,
};
use crate::zmq_api::cbor;
use crate::zmq_api::message::{self, END, EXECUTED, Protocol, Request, VERSION_MISMATCH};
use functions::{Extras, Outcome};

/// Where the simulator lives: its own mutex, or shared with the legacy server (`--api both`).
pub trait SimHost: Send + Sync {
    /// Runs `f` on the simulator, holding whatever lock guards it.
    fn with_sim(&self, f: &mut dyn FnMut(&mut Simulator));
}

impl SimHost for Mutex<Simulator> {
    fn with_sim(&self, f: &mut dyn FnMut(&mut Simulator)) {
        f(&mut self.lock().unwrap_or_else(|e| e.into_inner()));
    }
}

impl SimHost for crate::legacy::ServerHandle {
    fn with_sim(&self, f: &mut dyn FnMut(&mut Simulator)) {
        crate::legacy::ServerHandle::with_sim(self, |s| f(s));
    }
}

/// How to run the emulated server: address, protocol generation, pacing, scene dump, logging.
#[derive(Debug, Clone)]
pub struct ServerConfig {
    /// Address to bind (port 0 = any free port).
    pub listen: SocketAddr,
    /// Protocol generation to speak.
    pub protocol: Protocol,
    /// When the emulated main loop serves a request.
    pub clock: Clock,
    /// How requests are paced; `None` (the default): as the add-on of [`Self::protocol`]'s
    /// generation does (protocol 1: one request per main-loop pass; protocol 2: also at once
    /// within the busy window of a pass that served one). `Some(ZmqPacing::Window)` with
    /// protocol 1 keeps a protocol-1 test fast at idle fps above 0 (not what 4.5.1 does).
    pub pacing: Option<ZmqPacing>,
    /// Write the scene as JSON here on shutdown.
    pub dump: Option<PathBuf>,
    /// Log requests that fail on stderr.
    pub verbose: bool,
    /// Modeled cost of each call ([`Timing::instant`] by default: none;
    /// [`Timing::realistic`]: what a real CoppeliaSim 4.5.1 takes). The reconnect penalty is
    /// legacy only.
    pub timing: Timing,
}

impl Default for ServerConfig {
    fn default() -> Self {
        ServerConfig {
            listen: SocketAddr::from(([127, 0, 0, 1], 23000)),
            protocol: Protocol::V2,
            clock: Clock::default(),
            pacing: None,
            dump: None,
            verbose: false,
            timing: Timing::instant(),
        }
    }
}

/// A running server: its address and request count, its simulator, and how to stop it.
pub struct ServerHandle {
    addr: SocketAddr,
    stop: Arc<AtomicBool>,
    requests: Arc<AtomicU64>,
    thread: Option<JoinHandle<()>>,
    host: Arc<dyn SimHost>,
    dump: Option<PathBuf>,
}

impl ServerHandle {
    /// The address bound (with the port chosen when [`ServerConfig::listen`] had port 0).
    pub fn local_addr(&self) -> SocketAddr {
        self.addr
    }

    /// Requests received so far.
    pub fn requests(&self) -> u64 {
        self.requests.load(Ordering::SeqCst)
    }

    /// Runs `f` on the simulator, between requests (it holds the simulator's lock).
    pub fn with_sim<R>(&self, f: impl FnOnce(&mut Simulator) -> R) -> R {
        let mut f = Some(f);
        let mut out = None;
        self.host.with_sim(&mut |s| {
            if let Some(f) = f.take() {
                out = Some(f(s));
            }
        });
        out.expect("SimHost::with_sim runs its closure")
    }

    /// Stops the server thread, then writes the scene dump if [`ServerConfig::dump`] asks.
    pub fn shutdown(mut self) {
        self.stop.store(true, Ordering::SeqCst);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
        if let Some(path) = &self.dump
            && let Err(e) = self.with_sim(|s| crate::sim::write_dump(s, path))
        {
            eprintln!(
                "vrep-maze serve: cannot write scene dump {}: {e}",
                path.display()
            );
        }
    }
}

/// Binds and starts the server over a simulator of its own.
pub fn spawn(config: ServerConfig, mut sim: Simulator) -> std::io::Result<ServerHandle> {
    sim.step = config.clock.step;
    spawn_shared(config, Arc::new(Mutex::new(sim)))
}

/// Binds and starts the server over a simulator it shares (e.g. with the legacy server);
/// an address in use is [`std::io::ErrorKind::AddrInUse`].
pub fn spawn_shared(config: ServerConfig, host: Arc<dyn SimHost>) -> std::io::Result<ServerHandle> {
    let io = |e: zmq::Error| std::io::Error::other(format!("ZeroMQ: {e}"));
    let context = zmq::Context::new();
    // ROUTER, answering as a REP socket does: it lets the server see which requests are
    // already waiting when it answers one (`serve`)
    let socket = context.socket(zmq::ROUTER).map_err(io)?;
    socket.set_linger(0).map_err(io)?;
    socket.set_rcvtimeo(50).map_err(io)?;
    // a peer that is not a ZeroMQ client (a legacy client pointed at this port) never
    // completes the greeting: drop it after 2 s rather than libzmq's 30 s
    socket.set_handshake_ivl(2000).map_err(io)?;
    socket.set_sndtimeo(1000).map_err(io)?;
    let ip = config.listen.ip();
    socket.set_ipv6(ip.is_ipv6()).map_err(io)?;
    let ip = if ip.is_ipv6() {
        format!("[{ip}]")
    } else {
        ip.to_string()
    };
    let port = if config.listen.port() == 0 {
        "*".to_string()
    } else {
        config.listen.port().to_string()
    };
    socket
        .bind(&format!("tcp://{ip}:{port}"))
        .map_err(|e| match e {
            zmq::Error::EADDRINUSE => {
                std::io::Error::new(std::io::ErrorKind::AddrInUse, "address in use")
            }
            e => io(e),
        })?;
    let last = socket.get_last_endpoint().map_err(io)?.unwrap_or_default();
    let bound_port = last
        .rsplit(':')
        .next()
        .and_then(|p| p.parse().ok())
        .unwrap_or(config.listen.port());
    let addr = SocketAddr::new(config.listen.ip(), bound_port);
    let stop = Arc::new(AtomicBool::new(false));
    let requests = Arc::new(AtomicU64::new(0));
    let dump = config.dump.clone();
    let mut state = State {
        config,
        host: host.clone(),
        extras: Extras::default(),
        pending: HashMap::new(),
        clients: Default::default(),
    };
    let (s, r) = (stop.clone(), requests.clone());
    let thread = std::thread::Builder::new()
        .name("zmq-remote-api".into())
        .spawn(move || {
            let _context = context;
            serve(&socket, &mut state, &s, &r);
        })?;
    Ok(ServerHandle {
        addr,
        stop,
        requests,
        thread: Some(thread),
        host,
        dump,
    })
}

/// What the server thread keeps between requests.
struct State {
    config: ServerConfig,
    host: Arc<dyn SimHost>,
    /// Object properties the scene does not model (special properties, shape parameters).
    extras: Extras,
    /// Protocol 2: results waiting for the client's `_*executed*_`, per uuid.
    pending: HashMap<String, Vec<Value>>,
    /// Protocol 2: the clients seen and not gone (`_*end*_`), by uuid: a new one's first
    /// request costs more ([`Op::ZmqNewClient`]).
    clients: std::collections::HashSet<String>,
}

/// What a call to this emulator takes on loopback with no modeled cost (`--timing instant`:
/// 0.09-0.10 ms per call measured with our client on the 2-core machine), taken off each
/// modeled call so that the whole call takes what the model says.
const LOOPBACK_ROUND_TRIP: Duration = Duration::from_micros(90);

/// The last stretch of a wait spent yielding instead of sleeping: a sleep overshoots by
/// tens of microseconds, a sizeable share of a 0.45 ms call.
const SPIN: Duration = Duration::from_micros(200);

/// Waits until `t`, or less if the server stops meanwhile; false if it stopped.
fn sleep_until(t: Instant, stop: &AtomicBool) -> bool {
    while let Some(left) = t.checked_duration_since(Instant::now()) {
        if stop.load(Ordering::SeqCst) {
            return false;
        }
        if left > SPIN {
            std::thread::sleep((left - SPIN).min(Duration::from_millis(20)));
        } else {
            std::thread::yield_now();
        }
    }
    !stop.load(Ordering::SeqCst)
}

/// A request as the ROUTER socket gives it.
struct Incoming {
    /// The peer's routing frames, up to the empty delimiter a REQ peer sends: what the reply
    /// goes back with.
    envelope: Vec<Vec<u8>>,
    /// The request.
    body: Vec<u8>,
    /// When the server took it off the socket.
    arrived: Instant,
    /// It was already waiting when the request before it was answered.
    queued: bool,
}

/// The next request on `socket` (`flags`: 0 waits up to the receive timeout, `DONTWAIT`
/// not at all).
fn receive(socket: &zmq::Socket, flags: i32, queued: bool) -> Result<Incoming, zmq::Error> {
    let mut frames = socket.recv_multipart(flags)?;
    let body = frames.pop().unwrap_or_default();
    Ok(Incoming {
        envelope: frames,
        body,
        arrived: Instant::now(),
        queued,
    })
}

/// Receives, paces and answers requests until `stop` is set. Before it answers a request it
/// takes in every request already waiting, queued behind it: the add-on serves those in the
/// same main-loop pass while its time slot lasts ([`ZMQ_TIME_SLOT`]); a lock-step client's
/// next request cannot be among them.
fn serve(socket: &zmq::Socket, state: &mut State, stop: &AtomicBool, requests: &AtomicU64) {
    let mut pacer = ZmqPacer::new(Instant::now());
    let pacing = state.config.pacing.unwrap_or(match state.config.protocol {
        Protocol::V1 => ZmqPacing::OnePerPass,
        Protocol::V2 => ZmqPacing::Window,
    });
    let clock = state.config.clock;
    let mut backlog: std::collections::VecDeque<Incoming> = Default::default();
    // the pass still serving the requests queued on the socket, if any: its start and the
    // modeled time its requests took so far
    let mut queue_pass: Option<(Instant, Duration)> = None;
    while !stop.load(Ordering::SeqCst) {
        let incoming = match backlog.pop_front() {
            Some(r) => r,
            None => match receive(socket, 0, false) {
                Ok(r) => r,
                Err(zmq::Error::EAGAIN) => continue,
                Err(_) => break,
            },
        };
        let arrived = incoming.arrived;
        requests.fetch_add(1, Ordering::SeqCst);
        let (mut sim_state, mut fps) = (SimState::Stopped, 0);
        state
            .host
            .with_sim(&mut |s| (sim_state, fps) = (s.state, s.idle_fps));
        let queued = queue_pass.take().filter(|_| incoming.queued);
        let (at, (pass, spent)) = match queued {
            Some(pass) => (Instant::now(), pass),
            None => {
                let at = pacer.serve_at(&clock, pacing, sim_state, fps, arrived);
                (at, (at, Duration::ZERO))
            }
        };
        if !sleep_until(at, stop) {
            break;
        }
        // the modeled cost is what a call takes end to end on a real simulator (the spec's
        // 0.45 ms was timed by a client): the emulator's own processing and its loopback
        // round trip count towards it
        let (reply, ops) = handle(state, &incoming.body);
        let charge = Charge {
            served: Served::ZmqCall,
            idle_fps: fps,
            state: sim_state,
            ops,
            queued: queued.is_some(),
        };
        state.host.with_sim(&mut |s| s.record(&charge));
        let work = state.config.timing.cost(|m| charge.work(m));
        if !sleep_until(
            at.max(arrived) + work.saturating_sub(LOOPBACK_ROUND_TRIP),
            stop,
        ) {
            break;
        }
        while let Ok(r) = receive(socket, zmq::DONTWAIT, true) {
            backlog.push_back(r);
        }
        // the reply goes back as a REP socket sends it; a failed send drops the client
        let mut frames = incoming.envelope;
        frames.push(cbor::encode(&reply));
        let _ = socket.send_multipart(frames, 0);
        pacer.served(&clock, (pacing, sim_state, fps), (at, Instant::now()));
        // the add-on polls again and serves a request already queued in the same pass,
        // until its time slot is spent (the modeled time of the calls it served, not the
        // emulator's own, which a debug build makes longer); also when this request raised
        // the idle rate from 0 (4.5.1: `apply`'s last call, sent with the one restoring idle
        // fps 8, was answered 0.3-1.4 ms after both were sent, 7 runs of 7;
        // `docs/measurements.md` "Pacing after the idle rate is restored")
        let spent = spent + work;
        if backlog.front().is_some_and(|r| r.queued) && spent < ZMQ_TIME_SLOT {
            queue_pass = Some((pass, spent));
        }
    }
}

/// Answers one request (bytes in, reply map out) and says what work a real CoppeliaSim would
/// have done for it.
fn handle(state: &mut State, bytes: &[u8]) -> (Value, Vec<Op>) {
    let protocol = state.config.protocol;
    let base = vec![Op::ZmqCall];
    let req = match cbor::decode(bytes).and_then(|v| Request::from_value(&v)) {
        Ok(r) => r,
        Err(e) => {
            if state.config.verbose {
                eprintln!("vrep-maze serve (zmq): bad request: {e}");
            }
            return (
                message::err_reply(protocol, &format!("malformed request: {e}")),
                base,
            );
        }
    };
    if protocol == Protocol::V1 {
        return outcome_reply(state, Protocol::V1, &req, None);
    }
    let Some(uuid) = req.uuid.clone() else {
        let reply = cbor::map([
            ("success", Value::Bool(false)),
            ("error", Value::Text(VERSION_MISMATCH.into())),
        ]);
        return (reply, base);
    };
    if req.func != END && state.clients.insert(uuid.clone()) {
        let (reply, mut ops) = served_v2(state, &req, uuid);
        ops.push(Op::ZmqNewClient);
        return (reply, ops);
    }
    served_v2(state, &req, uuid)
}

/// Answers a protocol-2 request of the client `uuid`: its leaving, the `_*executed*_` a
/// waiting call expects, or a call.
fn served_v2(state: &mut State, req: &Request, uuid: String) -> (Value, Vec<Op>) {
    let base = vec![Op::ZmqCall];
    match req.func.as_str() {
        END => {
            state.pending.remove(&uuid);
            state.clients.remove(&uuid);
            (Value::Map(vec![]), base)
        }
        EXECUTED => (
            message::ret_reply(
                Protocol::V2,
                state.pending.remove(&uuid).unwrap_or_default(),
            ),
            base,
        ),
        _ => outcome_reply(state, Protocol::V2, req, Some(uuid)),
    }
}

/// The work a call to `func` with `args` makes a real CoppeliaSim 4.5.1 do, from the scene
/// before the call (`vrep_maze_core::coppelia::cost`: spec "Pacing", "ZeroMQ costs at idle fps 0",
/// "Costs that grow with the scene"): the call itself, and a paste, re-parenting or removal
/// by the objects it walks, a pose by its constant. `sim.getObjectsInTree` is priced after
/// the call ([`tree_ops`]); serving any call adds [`Op::ZmqServe`] for the scene after it.
fn call_ops(sim: &Simulator, func: &str, args: &[Value]) -> Vec<Op> {
    let scene = &sim.scene;
    let listed = || args.first().and_then(cbor::handles).unwrap_or_default();
    let int_arg = |i: usize| args.get(i).and_then(cbor::int32);
    let work = match func {
        "sim.copyPasteObjects" => cost::paste(scene, &listed()),
        "sim.removeObjects" => cost::remove(scene, &listed()),
        "sim.removeObject" => cost::remove(scene, &int_arg(0).into_iter().collect::<Vec<_>>()),
        "sim.setObjectParent" => {
            let parent = int_arg(1).filter(|&p| p != vrep_maze_core::coppelia::HANDLE_WORLD);
            return vec![Op::ZmqSet, cost::set_parent(scene, parent)];
        }
        "sim.setObjectPose" => return vec![Op::ZmqSet, cost::pose(scene, false)],
        "sim.setObjectPosition" | "sim.setObjectOrientation" => cost::pose(scene, true),
        _ => return vec![Op::ZmqCall],
    };
    vec![Op::ZmqCall, work]
}

/// `sim.getObjectsInTree`'s work: the call, and per handle it returned (spec "ZeroMQ costs").
fn tree_ops(outcome: &Outcome) -> Vec<Op> {
    let handles = match outcome {
        Outcome::Ret(v) => match v.first() {
            Some(Value::Array(hs)) => hs.len(),
            _ => 0,
        },
        _ => 0,
    };
    vec![Op::ZmqTree { handles }]
}

/// The work of mesh shapes beyond a call's own cost (`vrep_maze_core::coppelia::shape_cost`), from
/// the scene after the call: a created mesh by its triangles and the vertices given, a mesh
/// read back by its triangles and vertices, our Lua programs by the meshes they made or read,
/// a merge by the triangles of the shape it made.
fn shape_ops(sim: &Simulator, func: &str, args: &[Value], outcome: &Outcome) -> Option<Op> {
    let Outcome::Ret(values) = outcome else {
        return None;
    };
    match func {
        "sim.createMeshShape" | "sim.createShape" => match (args.get(2), args.get(3)) {
            (Some(Value::Array(vertices)), Some(Value::Array(indices))) => {
                let coordinates: Vec<f32> = vertices
                    .iter()
                    .map(|v| cbor::number(v).unwrap_or(0.0) as f32)
                    .collect();
                Some(Op::CreateMesh {
                    triangles: indices.len() / 3,
                    vertices: vertices.len() / 3,
                    merge_steps: merge_steps(&coordinates),
                })
            }
            _ => None,
        },
        "sim.getShapeMesh" => {
            let h = args.first().and_then(cbor::int32)?;
            let mesh = sim.scene.get(h).ok()?.shape_mesh()?;
            Some(Op::ReadMesh {
                triangles: mesh.triangles(),
                vertices: mesh.vertices.len() / 3,
            })
        }
        "sim.executeLuaCode" => {
            let code = args.first().and_then(cbor::text)?;
            if let Some(batch) = vrep_maze_core::coppelia::lua::parse_create_meshes(code) {
                // priced by the meshes it made and the vertices given, as a mesh of its own
                // (none when it failed and undid them)
                let made = values.first() == Some(&Value::Bool(true));
                let meshes = batch.meshes.iter().filter(|_| made);
                return Some(Op::CreateMeshesPacked {
                    triangles: meshes.clone().map(|m| m.indices.len() / 3).sum(),
                    vertices: meshes.clone().map(|m| m.vertices.len() / 3).sum(),
                    merge_steps: meshes.map(|m| merge_steps(&m.vertices)).sum(),
                });
            }
            let triangles = vrep_maze_core::coppelia::lua::parse_read_meshes(code)
                .or_else(|| vrep_maze_core::coppelia::lua::parse_read_dressed(code))?
                .into_iter()
                .filter_map(|h| Some(sim.scene.get(h).ok()?.shape_mesh()?.triangles()))
                .sum();
            Some(Op::ReadMeshesPacked { triangles })
        }
        "sim.groupShapes" => {
            let h = values.first().and_then(cbor::int32)?;
            let triangles = sim.scene.get(h).ok()?.shape_mesh()?.triangles();
            Some(Op::MergeShapes { triangles })
        }
        // a loaded model by the triangles under its base (`vrep_maze_core::coppelia::model_cost`)
        "sim.loadModel" => {
            let base = values.first().and_then(cbor::int32)?;
            let triangles = sim
                .scene
                .subtree(base)
                .into_iter()
                .filter_map(|h| sim.scene.get(h).ok()?.mesh.as_ref().map(|m| m.triangles()))
                .sum();
            Some(Op::LoadModel { triangles })
        }
        _ => None,
    }
}

/// The work of the calls a program of several calls made (`vrep_maze_wire::zmq_api::calls`),
/// from the scene after it: each call's own, and a call inside the program in place of a
/// request ([`Op::ProgramCall`], by the handles a tree returned). Such programs only read,
/// so the scene after is the scene each call saw.
fn program_ops(sim: &Simulator, func: &str, args: &[Value], outcome: &Outcome) -> Vec<Op> {
    let code = args.first().and_then(cbor::text);
    let (Some(each), Outcome::Ret(values)) = (
        code.filter(|_| func == "sim.executeLuaCode")
            .and_then(calls::parse_calls),
        outcome,
    ) else {
        return vec![];
    };
    let answers = calls::answers(values, each.len()).unwrap_or_default();
    let mut ops = vec![];
    for (k, (func, args)) in each.iter().enumerate() {
        let handles = match answers.get(k) {
            Some(Ok(results)) if func == "sim.getObjectsInTree" => {
                results.first().and_then(cbor::array).map_or(0, <[_]>::len)
            }
            _ => 0,
        };
        ops.push(Op::ProgramCall { handles });
        ops.extend(
            call_ops(sim, func, args)
                .into_iter()
                .filter(|op| !matches!(op, Op::ZmqCall | Op::ZmqSet)),
        );
    }
    ops
}

/// Calls the requested function and turns its outcome into the reply of `protocol`
/// (protocol 2: a deferred result is parked under the request's uuid, answered `_*wait*_`).
fn outcome_reply(
    state: &mut State,
    protocol: Protocol,
    req: &Request,
    uuid: Option<String>,
) -> (Value, Vec<Op>) {
    let mut outcome = Outcome::Ret(vec![]);
    let mut work = vec![];
    let extras = &mut state.extras;
    state.host.with_sim(&mut |s| {
        // simulation time and the emulated robot are brought up to the moment of the call
        s.sync(Instant::now());
        work = call_ops(s, &req.func, &req.args);
        outcome = functions::call(s, extras, protocol, &req.func, &req.args);
        // what the simulator logs (deprecation notes): shown with the failed requests
        for note in extras.notes.drain(..) {
            if state.config.verbose {
                eprintln!("vrep-maze serve (zmq): {note}");
            }
        }
        if req.func == "sim.getObjectsInTree" {
            work = tree_ops(&outcome);
        }
        work.extend(shape_ops(s, &req.func, &req.args, &outcome));
        work.extend(program_ops(s, &req.func, &req.args, &outcome));
        work.push(Op::ZmqServe {
            objects: s.scene.len(),
        });
    });
    let reply = match outcome {
        Outcome::Ret(values) => message::ret_reply(protocol, values),
        Outcome::Err(e) => {
            if state.config.verbose {
                eprintln!("vrep-maze serve (zmq): {}: {e}", req.func);
            }
            message::err_reply(protocol, &e)
        }
        Outcome::WaitThen(values) => match uuid {
            Some(u) => {
                state.pending.insert(u, values);
                message::func_reply(message::WAIT)
            }
            None => message::ret_reply(protocol, values),
        },
    };
    (reply, work)
}

#[cfg(test)]
mod tests {
    use crate::zmq_api::cbor::int;
    use std::io::Write;

    use super::*;
    use crate::sim::Scene;
    use vrep_maze_core::coppelia::INTPARAM_PROGRAM_VERSION;

    fn server(timing: Timing) -> ServerHandle {
        let config = ServerConfig {
            listen: "127.0.0.1:0".parse().unwrap(),
            protocol: Protocol::V1,
            timing,
            ..Default::default()
        };
        spawn(config, Simulator::new(Scene::course(), 0)).unwrap()
    }

    /// One protocol-1 call from a fresh REQ socket: the reply, or `None` after 5 s.
    fn call(addr: SocketAddr, func: &str, args: Vec<Value>) -> Option<Value> {
        let context = zmq::Context::new();
        let s = context.socket(zmq::REQ).unwrap();
        s.set_linger(0).unwrap();
        s.set_rcvtimeo(5000).unwrap();
        s.connect(&format!("tcp://{addr}")).unwrap();
        let req = cbor::map([
            ("func", Value::Text(func.into())),
            ("args", Value::Array(args)),
        ]);
        s.send(cbor::encode(&req), 0).unwrap();
        s.recv_bytes(0).ok().map(|b| cbor::decode(&b).unwrap())
    }

    #[test]
    fn bytes_that_are_not_zeromq_do_not_hold_up_the_next_client() {
        let s = server(Timing::instant());
        let addr = s.local_addr();
        let idle_fps = || call(addr, "sim.getInt32Param", vec![cbor::int(26)]);
        assert!(idle_fps().is_some());
        // a legacy client's first packet (header 01 00, length, packets left, message), and
        // one that stops in the middle of a frame; both peers stay connected
        let mut legacy = std::net::TcpStream::connect(addr).unwrap();
        legacy
            .write_all(&[1, 0, 26, 0, 0, 0, 0x2a, 0x2a, 0, 0, 1, 0, 0, 0, 2, 0, 0, 0])
            .unwrap();
        let mut partial = std::net::TcpStream::connect(addr).unwrap();
        partial.write_all(&[1, 0, 2, 1, 0x41, 0x30]).unwrap();
        std::thread::sleep(std::time::Duration::from_millis(100));
        assert!(idle_fps().is_some(), "answered while they are connected");
        drop((legacy, partial));
        assert!(idle_fps().is_some(), "answered after they left");
        s.shutdown();
    }

    #[test]
    fn removing_a_removed_handle_is_ok_over_the_wire() {
        let s = server(Timing::realistic());
        let line = s.with_sim(|sim| sim.scene.resolve("Line").unwrap());
        let list = || vec![Value::Array(vec![cbor::int(line.into())])];
        for _ in 0..2 {
            let reply = call(s.local_addr(), "sim.removeObjects", list()).unwrap();
            assert_eq!(cbor::get(&reply, "success"), Some(&Value::Bool(true)));
        }
        s.shutdown();
    }

    #[test]
    fn calls_do_the_work_the_model_prices_from_the_scene_before_them() {
        let sim = Simulator::new(Scene::course(), 0);
        let (maze, line) = (
            sim.scene.resolve("Maze").unwrap(),
            sim.scene.resolve("Line").unwrap(),
        );
        let handles =
            |hs: &[i32]| vec![Value::Array(hs.iter().map(|h| int((*h).into())).collect())];
        assert_eq!(
            call_ops(&sim, "sim.copyPasteObjects", &handles(&[line, line])),
            [
                Op::ZmqCall,
                Op::Paste {
                    copies: 1,
                    objects: 5
                }
            ]
        );
        assert_eq!(
            call_ops(&sim, "sim.removeObjects", &handles(&[line, 99])),
            [
                Op::ZmqCall,
                Op::Remove {
                    count: 1,
                    objects: 5
                }
            ]
        );
        let to_maze = vec![int(line.into()), int(maze.into()), Value::Bool(false)];
        assert_eq!(
            call_ops(&sim, "sim.setObjectParent", &to_maze),
            [
                Op::ZmqSet,
                Op::SetParent {
                    children: 0,
                    parentless: 5
                }
            ]
        );
        assert_eq!(
            call_ops(&sim, "sim.setObjectPose", &[]),
            [Op::ZmqSet, Op::Pose { objects: 5 }]
        );
        assert_eq!(call_ops(&sim, "sim.getObject", &[]), [Op::ZmqCall]);
        let tree = Outcome::Ret(vec![Value::Array(vec![int(1); 500])]);
        assert_eq!(tree_ops(&tree), [Op::ZmqTree { handles: 500 }]);
    }

    /// A protocol-1 server over the course scene at `idle_fps`, keeping a ledger.
    fn ledger_server(idle_fps: i32) -> ServerHandle {
        let mut sim = Simulator::new(Scene::course(), idle_fps);
        sim.ledger = Some(vec![]);
        let config = ServerConfig {
            listen: "127.0.0.1:0".parse().unwrap(),
            protocol: Protocol::V1,
            ..Default::default()
        };
        spawn(config, sim).unwrap()
    }

    #[test]
    fn served_calls_are_recorded_in_the_ledger_when_kept() {
        let s = ledger_server(0);
        let line = s.with_sim(|sim| sim.scene.resolve("Line").unwrap());
        let list = vec![Value::Array(vec![int(line.into()); 3]), int(0)];
        assert!(call(s.local_addr(), "sim.copyPasteObjects", list).is_some());
        let ledger = s.with_sim(|sim| sim.ledger.take()).unwrap();
        s.shutdown();
        assert_eq!(ledger.len(), 1);
        assert_eq!(
            ledger[0].ops,
            [
                Op::ZmqCall,
                Op::Paste {
                    copies: 1,
                    objects: 5
                },
                Op::ZmqServe { objects: 6 }
            ]
        );
    }

    /// zmqRemoteApi@coppeliasim-v4.5.1-rev4 `simAddOnZMQ remote API server.lua:86-105`: a
    /// pass serves the requests queued on the socket; a lock-step client has none queued.
    #[test]
    fn a_pass_serves_the_requests_already_queued_and_a_lock_step_client_has_none() {
        let s = ledger_server(8);
        let mut client =
            vrep_maze_client::zmq_api::Client::connect(&vrep_maze_client::zmq_api::ClientOptions {
                port: s.local_addr().port(),
                protocol: Some(Protocol::V1),
                ..Default::default()
            })
            .unwrap();
        let version = || {
            (
                "sim.getInt32Param",
                vec![int(INTPARAM_PROGRAM_VERSION.into())],
            )
        };
        client.call(version().0, version().1).unwrap();
        client.call(version().0, version().1).unwrap();
        let outcomes = client
            .call_all(&[version(), ("sim.noSuchFunction", vec![]), version()])
            .unwrap();
        drop(client);
        let ledger = s.with_sim(|sim| sim.ledger.take()).unwrap();
        s.shutdown();
        assert_eq!(outcomes.len(), 3);
        assert!(outcomes[0].is_ok() && outcomes[1].is_err() && outcomes[2].is_ok());
        let queued: Vec<bool> = ledger.iter().map(|c| c.queued).collect();
        assert_eq!(queued, [false, false, false, true, true]);
    }

    /// At idle fps 0, a request sent together with the one that restores idle fps 8 is
    /// served by the same pass, not the next (the real 4.5.1, 7 runs of 7:
    /// `docs/measurements.md` "Pacing after the idle rate is restored").
    #[test]
    fn a_request_queued_behind_the_restored_idle_rate_shares_its_pass() {
        // realistic timing: the first call takes its modelled time, so the second is
        // queued behind it whatever the machine's speed
        let mut sim = Simulator::new(Scene::course(), 0);
        sim.ledger = Some(vec![]);
        let config = ServerConfig {
            listen: "127.0.0.1:0".parse().unwrap(),
            protocol: Protocol::V1,
            timing: Timing::realistic(),
            ..Default::default()
        };
        let s = spawn(config, sim).unwrap();
        let mut client =
            vrep_maze_client::zmq_api::Client::connect(&vrep_maze_client::zmq_api::ClientOptions {
                port: s.local_addr().port(),
                protocol: Some(Protocol::V1),
                ..Default::default()
            })
            .unwrap();
        let restore = (
            "sim.setInt32Param",
            vec![
                int(vrep_maze_core::coppelia::INTPARAM_IDLE_FPS.into()),
                int(8),
            ],
        );
        let version = (
            "sim.getInt32Param",
            vec![int(INTPARAM_PROGRAM_VERSION.into())],
        );
        let outcomes = client.call_all(&[restore, version]).unwrap();
        drop(client);
        let ledger = s.with_sim(|sim| sim.ledger.take()).unwrap();
        s.shutdown();
        assert!(outcomes.iter().all(Result::is_ok));
        let queued: Vec<bool> = ledger.iter().map(|c| c.queued).collect();
        assert_eq!(queued.last(), Some(&true), "{queued:?}");
    }

    /// The connection's own call and the first reads, sent before any reply, are served by
    /// one pass on a fresh connection too.
    #[test]
    fn the_first_requests_of_a_connection_share_a_pass() {
        let s = ledger_server(8);
        let version = || {
            (
                "sim.getInt32Param",
                vec![int(INTPARAM_PROGRAM_VERSION.into())],
            )
        };
        let (client, outcomes) = vrep_maze_client::zmq_api::Client::connect_with(
            &vrep_maze_client::zmq_api::ClientOptions {
                port: s.local_addr().port(),
                ..Default::default()
            },
            &[version(), version()],
        )
        .unwrap();
        drop(client);
        let ledger = s.with_sim(|sim| sim.ledger.take()).unwrap();
        s.shutdown();
        assert!(outcomes.iter().all(Result::is_ok));
        let queued: Vec<bool> = ledger.iter().map(|c| c.queued).collect();
        assert_eq!(queued, [false, true, true]);
    }
}
