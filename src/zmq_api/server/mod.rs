//! An emulated ZeroMQ remote API server (the CoppeliaSim add-on) over a shared [`Simulator`].
//!
//! One REP socket, one thread. The add-on serves requests from CoppeliaSim's main loop, timed
//! by [`Clock::serve_at`]: a request arriving within the busy window of the previous reply is
//! served at once, a later one waits for the next pass (1 / `idle_fps`; none at idle fps 0).
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
use std::time::Instant;

use ciborium::Value;

use crate::sim::{Clock, SimState, Simulator};
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
    /// Write the scene as JSON here on shutdown.
    pub dump: Option<PathBuf>,
    /// Log requests that fail on stderr.
    pub verbose: bool,
}

impl Default for ServerConfig {
    fn default() -> Self {
        ServerConfig {
            listen: SocketAddr::from(([127, 0, 0, 1], 23000)),
            protocol: Protocol::V2,
            clock: Clock::default(),
            dump: None,
            verbose: false,
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
        if let Some(path) = &self.dump {
            let text = self
                .with_sim(|s| serde_json::to_string_pretty(&s.scene.to_json()).unwrap_or_default());
            if let Err(e) = std::fs::write(path, text) {
                eprintln!(
                    "vrep-maze serve: cannot write scene dump {}: {e}",
                    path.display()
                );
            }
        }
    }
}

/// Binds and starts the server over a simulator of its own.
pub fn spawn(config: ServerConfig, sim: Simulator) -> std::io::Result<ServerHandle> {
    spawn_shared(config, Arc::new(Mutex::new(sim)))
}

/// Binds and starts the server over a simulator it shares (e.g. with the legacy server);
/// an address in use is [`std::io::ErrorKind::AddrInUse`].
pub fn spawn_shared(config: ServerConfig, host: Arc<dyn SimHost>) -> std::io::Result<ServerHandle> {
    let io = |e: zmq::Error| std::io::Error::other(format!("ZeroMQ: {e}"));
    let context = zmq::Context::new();
    let socket = context.socket(zmq::REP).map_err(io)?;
    socket.set_linger(0).map_err(io)?;
    socket.set_rcvtimeo(50).map_err(io)?;
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
}

/// Receives, paces and answers requests until `stop` is set.
fn serve(socket: &zmq::Socket, state: &mut State, stop: &AtomicBool, requests: &AtomicU64) {
    let mut last_reply: Option<Instant> = None;
    while !stop.load(Ordering::SeqCst) {
        let bytes = match socket.recv_bytes(0) {
            Ok(b) => b,
            Err(zmq::Error::EAGAIN) => continue,
            Err(_) => break,
        };
        let arrived = Instant::now();
        requests.fetch_add(1, Ordering::SeqCst);
        let (mut sim_state, mut fps) = (SimState::Stopped, 0);
        state
            .host
            .with_sim(&mut |s| (sim_state, fps) = (s.state, s.idle_fps));
        let at = state
            .config
            .clock
            .serve_at(sim_state, fps, arrived, last_reply);
        if let Some(wait) = at.checked_duration_since(Instant::now()) {
            std::thread::sleep(wait);
        }
        let reply = handle(state, &bytes);
        // a REP socket must answer before it can receive again; a failed send drops the client
        let _ = socket.send(cbor::encode(&reply), 0);
        last_reply = Some(Instant::now());
    }
}

/// Answers one request (bytes in, reply map out).
fn handle(state: &mut State, bytes: &[u8]) -> Value {
    let protocol = state.config.protocol;
    let req = match cbor::decode(bytes).and_then(|v| Request::from_value(&v)) {
        Ok(r) => r,
        Err(e) => {
            if state.config.verbose {
                eprintln!("vrep-maze serve (zmq): bad request: {e}");
            }
            return message::err_reply(protocol, &format!("malformed request: {e}"));
        }
    };
    if protocol == Protocol::V1 {
        return outcome_reply(state, Protocol::V1, &req, None);
    }
    let Some(uuid) = req.uuid.clone() else {
        return cbor::map([
            ("success", Value::Bool(false)),
            ("error", Value::Text(VERSION_MISMATCH.into())),
        ]);
    };
    match req.func.as_str() {
        END => {
            state.pending.remove(&uuid);
            Value::Map(vec![])
        }
        EXECUTED => message::ret_reply(
            Protocol::V2,
            state.pending.remove(&uuid).unwrap_or_default(),
        ),
        _ => outcome_reply(state, Protocol::V2, &req, Some(uuid)),
    }
}

/// Calls the requested function and turns its outcome into the reply of `protocol`
/// (protocol 2: a deferred result is parked under the request's uuid, answered `_*wait*_`).
fn outcome_reply(
    state: &mut State,
    protocol: Protocol,
    req: &Request,
    uuid: Option<String>,
) -> Value {
    let mut outcome = Outcome::Ret(vec![]);
    let extras = &mut state.extras;
    state
        .host
        .with_sim(&mut |s| outcome = functions::call(s, extras, protocol, &req.func, &req.args));
    match outcome {
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
    }
}
