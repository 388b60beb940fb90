//! A protocol-faithful legacy remote API server over the in-memory [`Simulator`].
//!
//! One client at a time. Received commands are stored and executed once per emulated
//! main-loop pass (at `idle_fps` passes per second while the simulation is stopped or paused,
//! 0 = as soon as a message arrives; one pass per simulation step, 50 ms by default, while it
//! runs); every client message gets exactly one reply carrying the results produced since the
//! previous reply, with the message ID of the latest client message seen before that pass
//! (-1 if no pass).
//!
//! Where things are done:
//! * `transport.rs`: the listening socket and one client session at a time (its own thread);
//! * `main_loop.rs`: when a pass happens, and the input-list and streaming rules of a pass
//!   (the main-loop thread; it shares the simulator with the session under one mutex);
//! * `execute.rs`: what each command does to the simulator;
//! * here: settings, [`spawn`], the [`ServerHandle`] and the scene dump.

mod execute;
mod main_loop;
mod transport;

use std::io;
use std::net::{Shutdown, SocketAddr, TcpListener, TcpStream};
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Condvar, Mutex, MutexGuard};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use super::wire::MAX_PACKET_SIZE;
use crate::sim::{Clock, Simulator, Timing};
use main_loop::Core;

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
    /// (connections are refused meanwhile); zero keeps it open. CoppeliaSim's plugin sleeps
    /// 0.5 s (`../shared/spec/real-coppeliasim-4.5.1.md`, "Why the legacy port refuses for a
    /// minute: TIME_WAIT"), which `serve --timing realistic` models; the library's default
    /// is zero, as fast as tests want.
    pub rebind_delay: Duration,
    /// Modeled server work and the TIME_WAIT after a session the server closed first
    /// ([`Timing::instant`] by default: nothing modeled, no penalty;
    /// [`Timing::realistic`] for what a real CoppeliaSim 4.5.1 does).
    pub timing: Timing,
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
            timing: Timing::instant(),
        }
    }
}

/// What the session thread, the main-loop thread and the [`ServerHandle`] share.
struct Shared {
    /// The simulator with the input list and output buffer of the main loop.
    core: Mutex<Core>,
    /// Signalled when a message arrives or the simulator changes (a pass may be due).
    wake: Condvar,
    /// Set by [`ServerHandle::shutdown`]; both threads end when they see it.
    stop: AtomicBool,
    /// The connected client's socket, so that shutdown can close it under a blocked read.
    active: Mutex<Option<TcpStream>>,
    /// Start of the server clock (the server time of reply headers).
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

/// How much work the server has done, for tests and benchmarks.
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

    /// Main-loop passes and client messages so far.
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

/// Writes the scene as JSON to `config.dump`, if set, atomically (a failure is reported, not
/// fatal).
fn write_dump(config: &ServerConfig, sim: &Simulator) {
    if let Some(path) = &config.dump
        && let Err(e) = crate::sim::write_dump(sim, path)
    {
        eprintln!(
            "vrep-maze serve: cannot write scene dump {}: {e}",
            path.display()
        );
    }
}

/// Binds and starts the server threads (accept/session thread and main-loop thread).
pub fn spawn(config: ServerConfig, mut sim: Simulator) -> io::Result<ServerHandle> {
    // the simulation advances one clock step per main-loop pass while it runs
    sim.step = config.clock.step;
    let listener = TcpListener::bind(config.listen)?;
    let addr = listener.local_addr()?;
    let shared = Arc::new(Shared {
        core: Mutex::new(Core::new(sim)),
        wake: Condvar::new(),
        stop: AtomicBool::new(false),
        active: Mutex::new(None),
        started: Instant::now(),
        config,
    });
    let s1 = shared.clone();
    let main_loop = std::thread::Builder::new()
        .name("sim-main-loop".into())
        .spawn(move || main_loop::run(&s1))?;
    let s2 = shared.clone();
    let acceptor = std::thread::Builder::new()
        .name("remote-api".into())
        .spawn(move || transport::accept_loop(&s2, listener, addr))?;
    Ok(ServerHandle {
        addr,
        shared,
        threads: vec![main_loop, acceptor],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::legacy::command::{Command, opmode};
    use crate::legacy::wire::{Message, MessageHeader, read_message, write_message};
    use crate::sim::{Scene, Timing};

    const PENALTY: Duration = Duration::from_secs(2);

    fn server() -> ServerHandle {
        let config = ServerConfig {
            listen: "127.0.0.1:0".parse().unwrap(),
            timing: Timing {
                reconnect_penalty: PENALTY,
                ..Timing::realistic()
            },
            ..Default::default()
        };
        spawn(config, Simulator::new(Scene::course(), 0)).unwrap()
    }

    /// Sends one message (with the kill command last if `kill`) and reads its reply.
    fn exchange(stream: &mut TcpStream, kill: bool) {
        let blocks = if kill {
            vec![Command::KillConnection.to_block(opmode::ONESHOT)]
        } else {
            vec![]
        };
        let msg = Message {
            header: MessageHeader::default(),
            blocks,
        };
        write_message(stream, &msg.encode(), MAX_PACKET_SIZE).unwrap();
        read_message(stream).unwrap();
    }

    /// Tries to connect every 10 ms for up to `within`: true once `want_refused` holds.
    fn becomes(addr: SocketAddr, want_refused: bool, within: Duration) -> bool {
        let end = Instant::now() + within;
        while Instant::now() < end {
            // a connection that lands in the backlog of a socket being closed is reset later
            if TcpStream::connect(addr).is_err() == want_refused {
                return true;
            }
            std::thread::sleep(Duration::from_millis(10));
        }
        false
    }

    /// Leaves as the official client's `simxFinish` does: the kill block, its reply, one
    /// more message, then the server's close awaited.
    fn leave_as_simx_finish(mut stream: TcpStream) {
        use std::io::Read;
        exchange(&mut stream, true);
        let last = Message {
            header: MessageHeader::default(),
            blocks: vec![],
        };
        write_message(&mut stream, &last.encode(), MAX_PACKET_SIZE).unwrap();
        stream
            .set_read_timeout(Some(Duration::from_secs(5)))
            .unwrap();
        let _ = stream.read(&mut [0u8; 16]);
    }

    /// Reads until the server closes its side.
    fn wait_for_close(stream: &mut TcpStream) {
        use std::io::Read;
        stream
            .set_read_timeout(Some(Duration::from_secs(5)))
            .unwrap();
        assert_eq!(
            stream.read(&mut [0u8; 16]).unwrap(),
            0,
            "closed by the server"
        );
    }

    /// Waits for a connection that is accepted and served, for up to 10 s.
    fn served(addr: SocketAddr) -> TcpStream {
        let end = Instant::now() + Duration::from_secs(10);
        loop {
            if let Ok(c) = TcpStream::connect(addr) {
                return c;
            }
            assert!(Instant::now() < end, "accepted within 10 s");
            std::thread::sleep(Duration::from_millis(10));
        }
    }

    #[test]
    fn a_client_that_leaves_as_simx_finish_does_is_followed_at_once() {
        let s = server();
        for _ in 0..3 {
            let started = Instant::now();
            let mut c = served(s.local_addr());
            assert!(started.elapsed() < PENALTY / 4, "{:?}", started.elapsed());
            exchange(&mut c, false);
            leave_as_simx_finish(c);
        }
        s.shutdown();
    }

    #[test]
    fn a_client_that_answers_the_servers_close_with_its_own_leaves_the_port_in_time_wait() {
        let s = server();
        let addr = s.local_addr();
        let mut c = TcpStream::connect(addr).unwrap();
        exchange(&mut c, true);
        // the server closes first; our FIN in answer puts its end in TIME_WAIT
        wait_for_close(&mut c);
        drop(c);
        assert!(
            becomes(addr, true, PENALTY / 2),
            "refused during the penalty"
        );
        let started = Instant::now();
        leave_as_simx_finish(served(addr));
        assert!(started.elapsed() > PENALTY / 2, "{:?}", started.elapsed());
        s.shutdown();
    }

    #[test]
    fn a_client_that_closes_first_mid_session_is_followed_at_once() {
        let s = server();
        let addr = s.local_addr();
        let mut c = TcpStream::connect(addr).unwrap();
        exchange(&mut c, false);
        drop(c); // no kill command: end of file mid-session, before the server closed
        std::thread::sleep(Duration::from_millis(50));
        let mut c = TcpStream::connect(addr).expect("accepted at once");
        exchange(&mut c, false);
        leave_as_simx_finish(c);
        s.shutdown();
    }

    #[test]
    fn a_client_that_closes_before_sending_anything_leaves_no_penalty() {
        let s = server();
        let addr = s.local_addr();
        drop(TcpStream::connect(addr).unwrap()); // a port probe
        std::thread::sleep(Duration::from_millis(50));
        leave_as_simx_finish(TcpStream::connect(addr).expect("accepted at once"));
        s.shutdown();
    }

    #[test]
    fn the_library_default_has_no_penalty_and_no_modeled_costs() {
        let config = ServerConfig::default();
        assert_eq!(config.timing, Timing::instant());
        assert!(config.timing.reconnect_penalty.is_zero() && config.rebind_delay.is_zero());
    }

    #[test]
    fn shutdown_is_prompt_during_the_penalty() {
        let config = ServerConfig {
            listen: "127.0.0.1:0".parse().unwrap(),
            timing: Timing::realistic(), // 60 s
            ..Default::default()
        };
        let s = spawn(config, Simulator::new(Scene::course(), 0)).unwrap();
        let mut c = TcpStream::connect(s.local_addr()).unwrap();
        exchange(&mut c, true);
        wait_for_close(&mut c);
        drop(c); // the server closed first: TIME_WAIT
        assert!(becomes(s.local_addr(), true, Duration::from_secs(5)));
        // joins the accept thread, which is sleeping out the penalty
        s.shutdown();
    }
}
