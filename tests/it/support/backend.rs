//! The three backends the drawing scenarios run against: the legacy remote API and the
//! ZeroMQ remote API in protocols 1 and 2, each an in-process emulated server over a
//! [`Scene`], reached through a `Box<dyn Backend>`.

use std::net::SocketAddr;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use vrep_maze::coppelia::HANDLE_WORLD;
use vrep_maze::draw::{Backend, BackendError};
use vrep_maze::legacy::{self, LegacyBackend};
use vrep_maze::sim::{Clock, Scene, Simulator};
use vrep_maze::zmq_api::{self, ClientOptions, Protocol, SimHost, ZmqBackend};

/// Timeout of a connection that is not meant to fail: generous, so that a loaded machine
/// (a 2-core laptop building something else) only makes a test slower, never fail. A
/// working server answers in milliseconds; this is reached only by a bug.
pub const TIMEOUT: Duration = Duration::from_secs(60);

/// A backend under test.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// The legacy remote API (port 19997).
    Legacy,
    /// The ZeroMQ remote API, protocol 1 (CoppeliaSim 4.5.1).
    Zmq1,
    /// The ZeroMQ remote API, protocol 2.
    Zmq2,
}

impl Kind {
    /// Every backend.
    pub const ALL: [Kind; 3] = [Kind::Legacy, Kind::Zmq1, Kind::Zmq2];

    /// Its name in failure messages.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Legacy => "legacy",
            Kind::Zmq1 => "ZeroMQ protocol 1",
            Kind::Zmq2 => "ZeroMQ protocol 2",
        }
    }

    fn protocol(self) -> Option<Protocol> {
        match self {
            Kind::Legacy => None,
            Kind::Zmq1 => Some(Protocol::V1),
            Kind::Zmq2 => Some(Protocol::V2),
        }
    }

    /// Starts an emulated server of this kind over `scene` with the user's idle rate `fps`.
    pub fn serve(self, scene: Scene, fps: i32) -> Server {
        self.serve_sim(Simulator::new(scene, fps), Clock::default())
    }

    /// Starts an emulated server of this kind over `sim`, its main loop timed by `clock`.
    pub fn serve_sim(self, sim: Simulator, clock: Clock) -> Server {
        match self.protocol() {
            None => {
                let cfg = legacy::ServerConfig {
                    listen: "127.0.0.1:0".parse().unwrap(),
                    clock,
                    ..Default::default()
                };
                let handle = Arc::new(legacy::spawn(cfg, sim).unwrap());
                Server {
                    kind: self,
                    addr: handle.local_addr(),
                    host: handle.clone(),
                    handle: Handle::Legacy(handle),
                }
            }
            Some(protocol) => {
                let cfg = zmq_api::ServerConfig {
                    listen: "127.0.0.1:0".parse().unwrap(),
                    protocol,
                    clock,
                    ..Default::default()
                };
                // the legacy server and `zmq_api::spawn` set the step from their clock
                let mut sim = sim;
                sim.step = clock.step;
                let host: Arc<dyn SimHost> = Arc::new(Mutex::new(sim));
                let handle = zmq_api::spawn_shared(cfg, host.clone()).unwrap();
                Server {
                    kind: self,
                    addr: handle.local_addr(),
                    host,
                    handle: Handle::Zmq(handle),
                }
            }
        }
    }

    /// Connects a backend of this kind to `port` on the loopback (a server or a proxy);
    /// `timeout` bounds the connection and every request.
    pub fn connect(self, port: u16, timeout: Duration) -> Result<Box<dyn Backend>, BackendError> {
        Ok(match self.protocol() {
            None => Box::new(LegacyBackend::connect("127.0.0.1", port, timeout)?),
            Some(_) => Box::new(ZmqBackend::connect(&ClientOptions {
                port,
                timeout,
                ..Default::default()
            })?),
        })
    }

    /// The most round trips `apply` may take to draw an `n` x `n` maze into the course
    /// scene, where this backend promises a bound: the legacy API batches each stage into
    /// one message (ZeroMQ makes one call per request: no such bound).
    pub fn apply_round_trip_bound(self, n: u64) -> Option<usize> {
        match (self, n) {
            (Kind::Legacy, 9) => Some(15),
            (Kind::Legacy, 30) => Some(20),
            _ => None,
        }
    }
}

enum Handle {
    Legacy(Arc<legacy::ServerHandle>),
    Zmq(zmq_api::ServerHandle),
}

/// A running emulated server; [`Server::shutdown`] stops it.
pub struct Server {
    kind: Kind,
    addr: SocketAddr,
    host: Arc<dyn SimHost>,
    handle: Handle,
}

/// Every object as (alias, parent alias, world pose rounded to 0.1 mm / 0.1 mrad), sorted.
pub type Snapshot = Vec<(String, Option<String>, [i64; 6])>;

impl Server {
    /// Where it listens.
    pub fn addr(&self) -> SocketAddr {
        self.addr
    }

    /// Connects a backend directly (for ZeroMQ, checking the detected protocol).
    pub fn connect(&self) -> Box<dyn Backend> {
        let mut b = self
            .kind
            .connect(self.addr.port(), TIMEOUT)
            .unwrap_or_else(|e| panic!("{}: {e}", self.kind.name()));
        let description = b.describe();
        match self.kind.protocol() {
            Some(p) => {
                let n = if p == Protocol::V1 { 1 } else { 2 };
                assert!(
                    description.starts_with("ZeroMQ remote API")
                        && description.contains(&format!(", protocol {n}, ")),
                    "{description}"
                );
                assert!(b.authoring().is_some(), "{description}");
            }
            None => {
                assert!(
                    description.starts_with("legacy remote API"),
                    "{description}"
                );
                assert!(b.authoring().is_none(), "the legacy API creates nothing");
            }
        }
        b
    }

    /// The simulator, shared (e.g. with a proxy that cuts when the scene reaches a state).
    pub fn host(&self) -> Arc<dyn SimHost> {
        self.host.clone()
    }

    /// Runs `f` on the simulator.
    pub fn with_sim<R>(&self, f: impl FnOnce(&mut Simulator) -> R) -> R {
        with_sim(&*self.host, f)
    }

    /// The requests (legacy: messages) the server has received.
    pub fn requests(&self) -> u64 {
        match &self.handle {
            Handle::Legacy(h) => h.stats().messages,
            Handle::Zmq(h) => h.requests(),
        }
    }

    /// The maze lines in the scene, template included.
    pub fn line_count(&self) -> usize {
        self.with_sim(|sim| sim.scene.objects().filter(|o| o.alias == "Line").count())
    }

    /// The simulator's current idle rate.
    pub fn idle_fps(&self) -> i32 {
        self.with_sim(|sim| sim.idle_fps)
    }

    /// Sets the idle rate as a user in CoppeliaSim's settings would.
    pub fn set_idle_fps(&self, fps: i32) {
        self.with_sim(|sim| sim.idle_fps = fps);
    }

    /// See [`Snapshot`].
    pub fn snapshot(&self) -> Snapshot {
        self.with_sim(|sim| {
            let r = |x: f64| (x * 1e4).round() as i64;
            let mut out: Snapshot = sim
                .scene
                .objects()
                .map(|o| {
                    let (p, e) = sim.scene.pose(o.handle, HANDLE_WORLD).unwrap();
                    let parent = o.parent.map(|p| sim.scene.get(p).unwrap().alias.clone());
                    (
                        o.alias.clone(),
                        parent,
                        [r(p[0]), r(p[1]), r(p[2]), r(e[0]), r(e[1]), r(e[2])],
                    )
                })
                .collect();
            out.sort();
            out
        })
    }

    /// Stops the server (every proxy to it must be gone).
    pub fn shutdown(self) {
        let Server { host, handle, .. } = self;
        drop(host);
        match handle {
            Handle::Legacy(h) => {
                Arc::try_unwrap(h)
                    .ok()
                    .expect("nothing else holds the legacy server")
                    .shutdown();
            }
            Handle::Zmq(h) => h.shutdown(),
        }
    }
}

/// Runs `f` on the simulator of `host`.
pub fn with_sim<R>(host: &dyn SimHost, f: impl FnOnce(&mut Simulator) -> R) -> R {
    let mut f = Some(f);
    let mut out = None;
    host.with_sim(&mut |s| {
        if let Some(f) = f.take() {
            out = Some(f(s));
        }
    });
    out.expect("SimHost::with_sim runs its closure")
}
