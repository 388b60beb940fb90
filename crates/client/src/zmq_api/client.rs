//! A ZeroMQ remote API client speaking both protocol generations.
//!
//! A DEALER socket framed as a REQ socket (an empty delimiter frame before each request), so
//! that [`Client::call_all`] can send several requests before their replies; send/receive
//! timeouts and LINGER 0; after a timeout the socket is replaced, so a late reply is never
//! read as the next call's. Every call is sent as a protocol-2 request;
//! the first reply tells the generation: a protocol-1 server (CoppeliaSim 4.3 to 4.5) answers
//! with `success`, after which requests shrink to `{func, args}`.

use std::net::{SocketAddr, TcpStream, ToSocketAddrs};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use ciborium::Value;

use super::cbor::{self, CborError};
use super::message::{END, EXECUTED, Protocol, Reply, Request, parse_reply};
use vrep_maze_wire::zmq_api::calls;

/// Longest wait for a ZeroMQ peer's greeting: it comes one round trip after the connection
/// (libzmq sends it from its I/O thread, however busy the simulator is).
const GREETING_WAIT: Duration = Duration::from_secs(2);

/// The room a ZeroMQ peer's greeting has beyond three times the connection's time: the
/// full suite beside other builds on a 2-core machine (load 9) saw serve's greeting come
/// later than 0.3 s, which a room of 250 ms called "does not speak ZeroMQ".
const GREETING_ROOM: Duration = Duration::from_secs(1);

/// The longest wait for a reply after a call timed out, until a reply comes again.
const AFTER_TIMEOUT_WAIT: Duration = Duration::from_secs(1);

/// How long the look at a silent server's port waits for its TCP connection.
const STILL_LISTENS_WAIT: Duration = Duration::from_secs(1);

/// The longest a connection's wait goes without looking at its stop flag
/// ([`Client::connect_until`]): a signal may interrupt another thread than the one that
/// waits, so the flag is what tells.
const STOP_LOOK: Duration = Duration::from_millis(50);

/// The most calls [`Client::read_all`] puts in one program: about 50 ms of the simulator's
/// time at 12 µs a call (one simulation step), so no single request holds its main loop for
/// long or waits past the reply timeout however large the scene (the size, colour and layer
/// of a 100x100's 20,000 copies: 60,000 calls in 15 programs, not one).
pub const MAX_PROGRAM_CALLS: usize = 4096;

/// The most requests [`Client::call_all`] sends before reading their replies: well under
/// libzmq's default high-water mark of 1,000 messages a socket, where a send would block.
const MAX_IN_FLIGHT: usize = 200;

/// How many `_*wait*_` / `_*repeat*_` / callback turns one call may take before we give up.
const MAX_TURNS: usize = 10_000;

/// Whether a protocol-2 add-on may answer `func` with `_*wait*_`: the stepping calls, which
/// yield until the next simulation step (zmqRemoteApi@coppeliasim-v4.10.0-rev0 `ZMQ remote
/// API server.lua:97-127`: `sim.step`, also named `sim.switchThread` and `sim.yield`), and
/// `sim.wait`, which may step too. Such a call is never sent together with others
/// ([`Client::call_all`]).
pub fn may_wait(func: &str) -> bool {
    matches!(
        func,
        "sim.step" | "sim.switchThread" | "sim.yield" | "sim.wait"
    )
}

/// Client errors; each displays as one line naming the function or endpoint.
#[derive(Debug, thiserror::Error)]
pub enum ZmqError {
    /// Nothing accepts TCP connections on the endpoint.
    #[error(
        "cannot connect to {endpoint}: {why} (is CoppeliaSim running with the ZeroMQ remote API add-on on this port?)"
    )]
    Connect {
        /// `tcp://host:port`.
        endpoint: String,
        /// OS error.
        why: String,
    },
    /// The host name does not resolve to an address.
    #[error("cannot connect to {endpoint}: {why}: no address for that host name")]
    Resolve {
        /// `tcp://host:port`.
        endpoint: String,
        /// The resolver's error.
        why: String,
    },
    /// The port accepts TCP connections but the peer does not greet in ZeroMQ's ZMTP (a
    /// ZeroMQ peer sends its 10-byte signature, 0xFF ... 0x7F, as soon as it is connected).
    #[error("{endpoint} does not speak ZeroMQ: {detail}")]
    NotZeroMq {
        /// `tcp://host:port`.
        endpoint: String,
        /// What it did instead (stayed silent, closed, sent other bytes).
        detail: String,
    },
    /// The caller stopped the connection (its stop flag was set: Ctrl-C) before the
    /// server answered; nothing was asked of the simulator but reads.
    #[error("stopped connecting to {endpoint}")]
    Stopped {
        /// `tcp://host:port`.
        endpoint: String,
    },
    /// The port speaks ZeroMQ, but its socket is not one a request can be answered by (the
    /// remote API's is a REP socket): CoppeliaSim 4.3 to 4.5 publish the simulation step on a
    /// PUB socket one port above the remote API's (`../shared/spec/zmq-remote-api.md`).
    #[error(
        "{endpoint} is a ZeroMQ {socket_type} socket, which answers no request: not the remote API (a REP socket)"
    )]
    NotRemoteApi {
        /// `tcp://host:port`.
        endpoint: String,
        /// The socket type its ZMTP handshake announced (`PUB`).
        socket_type: String,
    },
    /// No reply in time.
    #[error(
        "{func}: no reply from {endpoint} within {secs:.1} s (is it a ZeroMQ remote API server? is the simulator busy in a dialog?)"
    )]
    Timeout {
        /// Function being called.
        func: String,
        /// `tcp://host:port`.
        endpoint: String,
        /// Timeout in seconds.
        secs: f64,
    },
    /// No reply in time, and nothing accepts connections on the endpoint any more: the
    /// simulator ended (or was killed). Every later call of the client fails so at once.
    #[error(
        "{func}: no reply from {endpoint} within {secs:.1} s, and nothing listens there any more: the simulator closed or was killed"
    )]
    Gone {
        /// Function being called.
        func: String,
        /// `tcp://host:port`.
        endpoint: String,
        /// Timeout in seconds.
        secs: f64,
    },
    /// The server reported an error. CoppeliaSim's messages often start `in sim.f: `; the
    /// function is then not named twice.
    #[error("{}", remote_text(.func, .message))]
    Remote {
        /// Function being called.
        func: String,
        /// Server's message (newlines restored).
        message: String,
    },
    /// The reply could not be understood.
    #[error("{func}: malformed reply: {detail}")]
    Malformed {
        /// Function being called.
        func: String,
        /// What is wrong.
        detail: String,
    },
    /// The ZeroMQ library failed.
    #[error("ZeroMQ error on {endpoint}: {error}")]
    Transport {
        /// `tcp://host:port`.
        endpoint: String,
        /// Library error (printed in the message, so not a `source`).
        error: zmq::Error,
    },
}

/// What the server said of one call of [`Client::call_all`]: its return values, or its error
/// ([`ZmqError::Remote`]).
pub type Outcome = Result<Vec<Value>, ZmqError>;

/// Sorts a call's result for [`Client::call_all`]: the server's refusal is the call's
/// outcome, any other failure ends the exchange.
fn outcome(result: Result<Vec<Value>, ZmqError>) -> Result<Outcome, ZmqError> {
    match result {
        Err(e @ ZmqError::Remote { .. }) => Ok(Err(e)),
        Err(e) => Err(e),
        Ok(values) => Ok(Ok(values)),
    }
}

/// `func: message`, unless the message already names the function (`in func: ...`).
fn remote_text(func: &str, message: &str) -> String {
    if message.starts_with(&format!("in {func}")) {
        message.to_string()
    } else {
        format!("{func}: {message}")
    }
}

impl ZmqError {
    /// True for a remote error whose message says the function does not exist.
    pub fn is_no_such_function(&self) -> bool {
        matches!(self, ZmqError::Remote { message, .. } if message.contains("No such function"))
    }
}

/// Connection settings.
#[derive(Debug, Clone)]
pub struct ClientOptions {
    /// Host name or address.
    pub host: String,
    /// Port (CoppeliaSim's default is 23000).
    pub port: u16,
    /// Send and receive timeout of one round trip.
    pub timeout: Duration,
    /// How long to wait for the TCP connection and the peer's ZeroMQ greeting [default:
    /// `timeout`, at most 3 s]. A refused connection fails at once: a ZeroMQ remote API
    /// server does not refuse connections for a while the way the legacy one does.
    pub connect_timeout: Option<Duration>,
    /// Force a protocol generation instead of detecting it from the first reply.
    pub protocol: Option<Protocol>,
}

impl Default for ClientOptions {
    fn default() -> Self {
        ClientOptions {
            host: "127.0.0.1".into(),
            port: 23000,
            timeout: Duration::from_secs(5),
            connect_timeout: None,
            protocol: None,
        }
    }
}

/// What a client has exchanged so far, for reports and benchmarks.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ClientStats {
    /// Remote function calls made.
    pub calls: u64,
    /// Request/reply round trips (calls plus wait/repeat turns).
    pub round_trips: u64,
}

/// A connected client.
pub struct Client {
    context: zmq::Context,
    socket: zmq::Socket,
    endpoint: String,
    timeout: Duration,
    uuid: String,
    protocol: Option<Protocol>,
    stats: ClientStats,
    /// The server's address, to look whether it still listens after a timeout.
    address: Option<std::net::SocketAddr>,
    /// Set once a timeout found nothing listening any more: later calls fail at once.
    gone: bool,
    /// Set by a timeout, cleared by the next reply: while set, calls wait at most
    /// [`AFTER_TIMEOUT_WAIT`], so the clean-up after a silent server (restoring the idle
    /// rate, the goodbye) does not multiply the wait the user asked for.
    timed_out: bool,
    /// Cleared once the server could not run a program of [`calls`] (a simulator without
    /// `sim.executeLuaCode`, or that refuses it): [`Client::read_all`] then sends each call.
    programs: bool,
}

impl std::fmt::Debug for Client {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Client")
            .field("endpoint", &self.endpoint)
            .field("protocol", &self.protocol)
            .finish()
    }
}

/// The path `sim.getObject` needs for a user-given name: names are aliases at the scene
/// root unless they already are paths (`/Maze/Line`, `./x`, `:x`).
pub fn object_path(name: &str) -> String {
    if name.starts_with(['/', '.', ':']) {
        name.to_string()
    } else {
        format!("/{name}")
    }
}

/// A random (version 4) UUID in the usual 8-4-4-4-12 form.
pub fn new_uuid() -> String {
    let mut b: [u8; 16] = rand::random();
    b[6] = (b[6] & 0x0f) | 0x40;
    b[8] = (b[8] & 0x3f) | 0x80;
    let h: String = b.iter().map(|x| format!("{x:02x}")).collect();
    format!(
        "{}-{}-{}-{}-{}",
        &h[0..8],
        &h[8..12],
        &h[12..16],
        &h[16..20],
        &h[20..32]
    )
}

impl Client {
    /// Connects: checks that the port accepts TCP connections and that the peer greets in
    /// ZeroMQ's ZMTP (else [`ZmqError::NotZeroMq`] at once, not a timeout of the first
    /// call), opens the socket, then
    /// calls `zmqRemoteApi.require('sim')`, which also reveals the protocol generation (a
    /// protocol-1 server has no `require`, and `sim` is global there).
    pub fn connect(options: &ClientOptions) -> Result<Client, ZmqError> {
        Client::connect_with(options, &[]).map(|(client, _)| client)
    }

    /// Connects as [`Client::connect`] does, sending `calls` together with its
    /// `zmqRemoteApi.require('sim')` before any reply is read, whatever the protocol (the
    /// add-on of either generation serves queued requests in the same main-loop pass:
    /// [`Client::call_all`]), so the connection and `calls` wait for one pass. For reads
    /// only: a protocol-2 server that asks to repeat one gets it again after the others.
    /// Returns the client and what the server said of each of `calls`.
    pub fn connect_with(
        options: &ClientOptions,
        calls: &[(&str, Vec<Value>)],
    ) -> Result<(Client, Vec<Outcome>), ZmqError> {
        Client::connect_until(options, calls, None)
    }

    /// Connects as [`Client::connect_with`] does until `stop` is set (Ctrl-C): then the
    /// wait for the greeting or for the first replies ends with [`ZmqError::Stopped`]
    /// within `STOP_LOOK`, whichever thread the signal interrupted. Once connected, the
    /// client no longer looks at `stop`: a call in flight is finished.
    pub fn connect_until(
        options: &ClientOptions,
        calls: &[(&str, Vec<Value>)],
        stop: Option<&AtomicBool>,
    ) -> Result<(Client, Vec<Outcome>), ZmqError> {
        let mut client = Client::open_until(options, stop)?;
        let require = options.protocol != Some(Protocol::V1);
        let mut all: Vec<(&str, Vec<Value>)> = Vec::with_capacity(calls.len() + 1);
        if require {
            all.push(("zmqRemoteApi.require", vec![Value::Text("sim".into())]));
        }
        all.extend(calls.iter().cloned());
        let mut outcomes = Vec::with_capacity(all.len());
        for chunk in all.chunks(MAX_IN_FLIGHT) {
            outcomes.extend(client.call_together(chunk, stop)?);
        }
        if require {
            match outcomes.remove(0) {
                Ok(_) => {}
                Err(e) if e.is_no_such_function() || client.protocol == Some(Protocol::V1) => {}
                Err(e) => return Err(e),
            }
        }
        Ok((client, outcomes))
    }

    /// Opens the socket without any call (for tests of the raw call loop).
    pub fn open(options: &ClientOptions) -> Result<Client, ZmqError> {
        Client::open_until(options, None)
    }

    /// [`Client::open`], the greeting's wait ended by `stop` ([`Client::connect_until`]).
    fn open_until(options: &ClientOptions, stop: Option<&AtomicBool>) -> Result<Client, ZmqError> {
        let ipv6 = options.host.contains(':');
        let host = options.host.trim_matches(['[', ']']);
        let endpoint = if ipv6 {
            format!("tcp://[{host}]:{}", options.port)
        } else {
            format!("tcp://{host}:{}", options.port)
        };
        let wait = options
            .connect_timeout
            .unwrap_or(options.timeout.min(Duration::from_secs(3)));
        let (stream, connected_in, address) = first_stream(host, options.port, wait, &endpoint)?;
        // the greeting comes about one round trip (the connection's time) after it, from
        // libzmq's I/O thread, which a loaded machine may not run for a few hundred
        // milliseconds: a second's room before the peer is judged
        let greeting_wait = (connected_in * 3 + GREETING_ROOM)
            .min(GREETING_WAIT)
            .min(wait);
        let mut stream = stream;
        match check_greeting(&mut stream, greeting_wait, stop) {
            Ok(()) => {}
            Err(Greeting::Stopped) => return Err(ZmqError::Stopped { endpoint }),
            Err(Greeting::Not(detail)) => {
                return Err(ZmqError::NotZeroMq { endpoint, detail });
            }
        }
        // a peer that announces a socket no request reaches (4.5.1's PUB on 23001) fails
        // now, not after the first call's whole timeout
        if let Some(socket_type) = peer_socket_type(&mut stream, greeting_wait)
            && !ANSWERING_SOCKETS.contains(&socket_type.as_str())
        {
            return Err(ZmqError::NotRemoteApi {
                endpoint,
                socket_type,
            });
        }
        drop(stream);
        let context = zmq::Context::new();
        let socket = new_socket(&context, &endpoint, options.timeout, ipv6)?;
        Ok(Client {
            context,
            socket,
            endpoint,
            timeout: options.timeout,
            uuid: new_uuid(),
            protocol: options.protocol,
            stats: ClientStats::default(),
            address,
            gone: false,
            timed_out: false,
            programs: true,
        })
    }

    /// The protocol generation (known after the first reply).
    pub fn protocol(&self) -> Option<Protocol> {
        self.protocol
    }

    /// `tcp://host:port`.
    pub fn endpoint(&self) -> &str {
        &self.endpoint
    }

    /// Counters so far.
    pub fn stats(&self) -> ClientStats {
        self.stats
    }

    fn request(&self, func: &str, args: Vec<Value>) -> Request {
        match self.protocol {
            Some(Protocol::V1) => Request::v1(func, args),
            _ => Request::v2(func, args, &self.uuid),
        }
    }

    /// One round trip; a timeout replaces the socket. A signal that interrupts the wait
    /// (Ctrl-C, whose handler sets a flag the caller checks between calls) does not end it:
    /// the wait goes on until the reply or the timeout. After a timeout, a server that no
    /// longer accepts connections is [`ZmqError::Gone`], for this call and every later one.
    fn round_trip(&mut self, func: &str, request: &Request) -> Result<Value, ZmqError> {
        let mut replies = self.exchange(&[(func, request)], None)?;
        Ok(replies.remove(0))
    }

    /// Sends every request before reading any reply, then reads the replies in order (one
    /// request is a round trip). Any failure replaces the socket when replies are still
    /// outstanding, so no late reply is ever taken for a later call's. Once `stop` is set
    /// the wait ends with [`ZmqError::Stopped`] (the socket replaced).
    fn exchange(
        &mut self,
        requests: &[(&str, &Request)],
        stop: Option<&AtomicBool>,
    ) -> Result<Vec<Value>, ZmqError> {
        let first = requests.first().map_or("", |(f, _)| f);
        if self.gone {
            return Err(self.gone_error(first));
        }
        self.stats.round_trips += requests.len() as u64;
        let wait = if self.timed_out {
            self.timeout.min(AFTER_TIMEOUT_WAIT)
        } else {
            self.timeout
        };
        let deadline = Instant::now() + wait;
        let mut sent = Ok(());
        for (_, request) in requests {
            sent = self.send(request, deadline);
            if sent.is_err() {
                break;
            }
        }
        let mut replies = Vec::with_capacity(requests.len());
        for (func, _) in requests {
            let received = match &sent {
                Ok(()) => self.receive(deadline, stop),
                Err(e) => Err(Waited::Failed(*e)),
            };
            let bytes = match received {
                Ok(b) => {
                    self.timed_out = false;
                    b
                }
                Err(why) => {
                    let outstanding = replies.len() + 1 < requests.len();
                    return Err(self.no_reply(why, func, wait, outstanding));
                }
            };
            if std::env::var_os("VREP_MAZE_TRACE").is_some() {
                eprintln!(
                    "zmq: {func} answered {:.1} ms after the send ({} bytes)",
                    (Instant::now() + wait - deadline).as_secs_f64() * 1000.0,
                    bytes.len()
                );
            }
            match cbor::decode(&bytes) {
                Ok(value) => replies.push(value),
                Err(CborError(detail)) => {
                    if replies.len() + 1 < requests.len() {
                        self.reset()?;
                    }
                    return Err(ZmqError::Malformed {
                        func: func.to_string(),
                        detail,
                    });
                }
            }
        }
        Ok(replies)
    }

    /// The error of a call to `func` on a server that is gone.
    fn gone_error(&self, func: &str) -> ZmqError {
        ZmqError::Gone {
            func: func.to_string(),
            endpoint: self.endpoint.clone(),
            secs: self.timeout.as_secs_f64(),
        }
    }

    /// The error of a reply to `func` that did not come (`why`) within `wait`, the socket
    /// replaced where a late reply could still arrive: after a stop or a timeout, or a
    /// failure with replies still `outstanding`. A server that no longer listens after a
    /// timeout is gone, for every later call too. An error replacing the socket is
    /// returned instead.
    fn no_reply(&mut self, why: Waited, func: &str, wait: Duration, outstanding: bool) -> ZmqError {
        match why {
            Waited::Stopped => {
                if let Err(e) = self.reset() {
                    return e;
                }
                ZmqError::Stopped {
                    endpoint: self.endpoint.clone(),
                }
            }
            Waited::Failed(zmq::Error::EAGAIN | zmq::Error::EINTR) => {
                self.timed_out = true;
                if let Err(e) = self.reset() {
                    return e;
                }
                if !self.still_listens() {
                    self.gone = true;
                    return self.gone_error(func);
                }
                ZmqError::Timeout {
                    func: func.to_string(),
                    endpoint: self.endpoint.clone(),
                    secs: wait.as_secs_f64(),
                }
            }
            Waited::Failed(error) => {
                if outstanding && let Err(e) = self.reset() {
                    return e;
                }
                ZmqError::Transport {
                    endpoint: self.endpoint.clone(),
                    error,
                }
            }
        }
    }

    /// Sends one request as a REQ socket would (an empty delimiter frame, then the request),
    /// through interrupted sends until `deadline`.
    fn send(&mut self, request: &Request, deadline: Instant) -> Result<(), zmq::Error> {
        let frames: [(Vec<u8>, i32); 2] = [(vec![], zmq::SNDMORE), (request.encode(), 0)];
        for (frame, flags) in frames {
            loop {
                match self.socket.send(&frame[..], flags) {
                    Err(zmq::Error::EINTR) if Instant::now() < deadline => {}
                    other => {
                        other?;
                        break;
                    }
                }
            }
        }
        Ok(())
    }

    /// The next reply (its frames after the empty delimiter), waited for until `deadline`
    /// (`EAGAIN` then), through interrupted waits, or until `stop` is set.
    fn receive(&mut self, deadline: Instant, stop: Option<&AtomicBool>) -> Result<Vec<u8>, Waited> {
        loop {
            if stop.is_some_and(|s| s.load(Ordering::SeqCst)) {
                return Err(Waited::Stopped);
            }
            let mut left = deadline.saturating_duration_since(Instant::now());
            if left.is_zero() {
                return Err(Waited::Failed(zmq::Error::EAGAIN));
            }
            if stop.is_some() {
                left = left.min(STOP_LOOK);
            }
            let ms = i64::try_from(left.as_millis()).unwrap_or(i64::MAX).max(1);
            match self.socket.poll(zmq::POLLIN, ms) {
                Ok(0) | Err(zmq::Error::EINTR) => {}
                Ok(_) => match self.socket.recv_multipart(zmq::DONTWAIT) {
                    Err(zmq::Error::EAGAIN | zmq::Error::EINTR) => {}
                    Ok(frames) => {
                        let body = frames
                            .into_iter()
                            .skip_while(Vec::is_empty)
                            .flatten()
                            .collect();
                        return Ok(body);
                    }
                    Err(e) => return Err(Waited::Failed(e)),
                },
                Err(e) => return Err(Waited::Failed(e)),
            }
        }
    }

    /// Whether the server still accepts TCP connections (a quick look, after a timeout).
    fn still_listens(&self) -> bool {
        self.address.is_none_or(|a| {
            TcpStream::connect_timeout(&a, STILL_LISTENS_WAIT.min(self.timeout)).is_ok()
        })
    }

    fn reset(&mut self) -> Result<(), ZmqError> {
        let ipv6 = self.endpoint.starts_with("tcp://[");
        self.socket = new_socket(&self.context, &self.endpoint, self.timeout, ipv6)?;
        Ok(())
    }

    /// Calls a remote function and returns its return values (empty for none), running the
    /// `_*wait*_` / `_*repeat*_` loop of protocol 2.
    pub fn call(&mut self, func: &str, args: Vec<Value>) -> Result<Vec<Value>, ZmqError> {
        self.stats.calls += 1;
        let request = self.request(func, args);
        let value = self.round_trip(func, &request)?;
        self.settle(func, request, value)
    }

    /// Runs the `_*wait*_` / `_*repeat*_` loop of protocol 2 from `value`, the reply to
    /// `request`, until the call's result (or error). Learns the protocol generation from
    /// the first reply.
    fn settle(
        &mut self,
        func: &str,
        request: Request,
        mut value: Value,
    ) -> Result<Vec<Value>, ZmqError> {
        let malformed = |detail: String| ZmqError::Malformed {
            func: func.to_string(),
            detail,
        };
        let mut last = request;
        for _ in 0..MAX_TURNS {
            let (reply, protocol) = parse_reply(&value).map_err(|CborError(d)| malformed(d))?;
            if self.protocol.is_none() {
                self.protocol = Some(protocol);
            }
            match reply {
                Reply::Ret(values) => return Ok(values),
                Reply::Err(message) => {
                    return Err(ZmqError::Remote {
                        func: func.to_string(),
                        message,
                    });
                }
                Reply::Wait => last = self.request(EXECUTED, vec![]),
                // resend the last message (the official client does so: after a wait it
                // resends `_*executed*_`, never the original call, which would run twice)
                Reply::Repeat => {}
                // We register no callbacks: answer with no results so the server can go on.
                Reply::Callback(_) => last = self.request(EXECUTED, vec![]),
            }
            value = self.round_trip(func, &last)?;
        }
        Err(malformed(format!(
            "more than {MAX_TURNS} wait/repeat turns"
        )))
    }

    /// Calls a function that returns one value.
    pub fn call1(&mut self, func: &str, args: Vec<Value>) -> Result<Value, ZmqError> {
        let values = self.call(func, args)?;
        values
            .into_iter()
            .next()
            .ok_or_else(|| ZmqError::Malformed {
                func: func.to_string(),
                detail: "no return value".into(),
            })
    }

    /// Calls a function that returns one integer (a handle, a state, a parameter).
    pub fn call_int(&mut self, func: &str, args: Vec<Value>) -> Result<i32, ZmqError> {
        let v = self.call1(func, args)?;
        cbor::int32(&v).ok_or_else(|| ZmqError::Malformed {
            func: func.to_string(),
            detail: format!("expected an integer, got {}", cbor::describe(&v)),
        })
    }

    /// Calls several functions, each as [`Client::call`] would; the outer error is a failed
    /// exchange (timeout, transport, malformed reply), the inner ones what the server said
    /// of each call. Against a protocol-1 server (CoppeliaSim 4.3 to 4.5) every request is
    /// sent before any reply is read: its add-on serves the requests queued on its socket in
    /// the same main-loop pass, for up to 5 ms (zmqRemoteApi@coppeliasim-v4.5.1-rev4
    /// `simAddOnZMQ remote API server.lua:86-105`, `maxTimeSlot` 0.005 at line 127), where a
    /// lock-step client waits one pass per call (93-125 ms at idle fps 8,
    /// `../shared/spec/real-coppeliasim-4.5.1.md` "Pacing"). Against protocol 2 they are sent
    /// together too unless one of them can block ([`may_wait`]): a 4.6+ add-on answers
    /// `_*wait*_` only from a stepping call and then takes the next queued request for the
    /// `_*executed*_` it waits for (zmqRemoteApi@coppeliasim-v4.10.0-rev0 `ZMQ remote API
    /// server.lua:97-127`), while every other call is answered as it comes; sent together,
    /// the client's own turn-around between calls goes (`docs/measurements.md` "ZeroMQ calls
    /// sent together on 4.10"). An unknown protocol is called in turn.
    pub fn call_all(&mut self, calls: &[(&str, Vec<Value>)]) -> Result<Vec<Outcome>, ZmqError> {
        let together = match self.protocol {
            Some(Protocol::V1) => true,
            Some(Protocol::V2) => !calls.iter().any(|(func, _)| may_wait(func)),
            None => false,
        };
        if !together {
            return calls
                .iter()
                .map(|(func, args)| outcome(self.call(func, args.clone())))
                .collect();
        }
        let mut outcomes = Vec::with_capacity(calls.len());
        for chunk in calls.chunks(MAX_IN_FLIGHT) {
            outcomes.extend(self.call_together(chunk, None)?);
        }
        Ok(outcomes)
    }

    /// Calls that only read, each outcome as [`Client::call_all`] gives it, made by one
    /// request a [`MAX_PROGRAM_CALLS`]: a Lua program that makes them in turn ([`calls`]:
    /// about 12 µs a call inside the simulator, against 0.1-0.2 ms a request). Where the
    /// server cannot run it, or an argument cannot be written as Lua, they are sent as
    /// [`Client::call_all`] sends them (so only reads: a program that failed as a whole may
    /// have made some of its calls).
    pub fn read_all(&mut self, calls: &[(&str, Vec<Value>)]) -> Result<Vec<Outcome>, ZmqError> {
        let mut out = Vec::with_capacity(calls.len());
        for chunk in calls.chunks(MAX_PROGRAM_CALLS) {
            out.extend(self.read_chunk(chunk)?);
        }
        Ok(out)
    }

    /// [`Client::read_all`] of at most [`MAX_PROGRAM_CALLS`] calls.
    fn read_chunk(&mut self, calls: &[(&str, Vec<Value>)]) -> Result<Vec<Outcome>, ZmqError> {
        let code = (self.programs && calls.len() > 1)
            .then(|| calls::calls_code(calls))
            .flatten();
        if let Some(code) = code {
            match self.call("sim.executeLuaCode", vec![Value::Text(code)]) {
                Ok(values) => {
                    if let Some(each) = calls::answers(&values, calls.len()) {
                        return Ok(each
                            .into_iter()
                            .zip(calls)
                            .map(|(o, (func, _))| {
                                o.map_err(|message| ZmqError::Remote {
                                    func: func.to_string(),
                                    message,
                                })
                            })
                            .collect());
                    }
                }
                Err(ZmqError::Remote { .. }) => {}
                Err(e) => return Err(e),
            }
            self.programs = false;
        }
        self.call_all(calls)
    }

    /// [`Client::call_all`] of at most [`MAX_IN_FLIGHT`] calls, all sent before any reply is
    /// read; `stop` ends the wait for the replies ([`Client::exchange`]).
    fn call_together(
        &mut self,
        calls: &[(&str, Vec<Value>)],
        stop: Option<&AtomicBool>,
    ) -> Result<Vec<Outcome>, ZmqError> {
        self.stats.calls += calls.len() as u64;
        let requests: Vec<Request> = calls
            .iter()
            .map(|(func, args)| self.request(func, args.clone()))
            .collect();
        let pairs: Vec<(&str, &Request)> = calls.iter().map(|(f, _)| *f).zip(&requests).collect();
        let replies = self.exchange(&pairs, stop)?;
        // every reply is read: a protocol-2 wait or repeat goes on one call at a time
        replies
            .into_iter()
            .zip(requests)
            .zip(calls)
            .map(|((value, request), (func, _))| outcome(self.settle(func, request, value)))
            .collect()
    }

    /// Says goodbye (protocol 2 `_*end*_`), waiting briefly for the reply.
    pub fn close(mut self) {
        self.end();
    }

    fn end(&mut self) {
        if self.protocol == Some(Protocol::V2) && !self.gone {
            let _ = self.socket.set_rcvtimeo(200);
            let _ = self.socket.set_sndtimeo(200);
            let req = self.request(END, vec![]);
            let deadline = Instant::now() + Duration::from_millis(200);
            if self.send(&req, deadline).is_ok() {
                let _ = self.receive(deadline, None);
            }
            self.protocol = None;
        }
    }
}

impl Drop for Client {
    fn drop(&mut self) {
        self.end();
    }
}

/// Why a wait for a reply ended without one.
enum Waited {
    /// The caller's stop flag was set.
    Stopped,
    /// The socket failed (`EAGAIN`: the deadline passed).
    Failed(zmq::Error),
}

/// The ZeroMQ socket types that answer a DEALER's requests: the remote API's REP (and
/// the ROUTER `serve` uses, as a REP socket is built on one).
const ANSWERING_SOCKETS: [&str; 2] = ["REP", "ROUTER"];

/// Our half of a ZMTP 3.0 greeting after the 10-byte signature (sent by then): version 3.0,
/// the NULL mechanism, not as server, and the filler (ZMTP 3.0, RFC 23).
fn greeting_rest() -> [u8; 54] {
    let mut rest = [0u8; 54];
    rest[0] = 3;
    rest[2..6].copy_from_slice(b"NULL");
    rest
}

/// The socket type the peer announces in its READY command, once the greeting's signature
/// is read from `stream`: our greeting is sent (not our READY, which a peer whose socket
/// does not go with a DEALER answers by closing the connection), the peer's rest of the
/// greeting and its READY read within `wait`. `None` when it does not tell (an older ZMTP,
/// another mechanism, no READY in time): a peer is judged only on what it says.
fn peer_socket_type(stream: &mut TcpStream, wait: Duration) -> Option<String> {
    use std::io::{Read, Write};
    let deadline = Instant::now() + wait;
    let mut ours = vec![0xFF, 0, 0, 0, 0, 0, 0, 0, 1, 0x7F];
    ours.extend_from_slice(&greeting_rest());
    stream.write_all(&ours).ok()?;
    let mut read = |n: usize| -> Option<Vec<u8>> {
        let mut buf = vec![0u8; n];
        let mut got = 0;
        while got < n {
            let left = deadline.saturating_duration_since(Instant::now());
            if left.is_zero() {
                return None;
            }
            stream.set_read_timeout(Some(left)).ok()?;
            match stream.read(&mut buf[got..]) {
                Ok(0) => return None,
                Ok(k) => got += k,
                Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
                Err(_) => return None,
            }
        }
        Some(buf)
    };
    let rest = read(54)?;
    if rest[0] < 3 || &rest[2..7] != b"NULL\0" {
        return None;
    }
    let flags = read(1)?[0];
    if flags & 0x04 == 0 {
        return None;
    }
    let size = if flags & 0x02 != 0 {
        usize::try_from(u64::from_be_bytes(read(8)?.try_into().ok()?)).ok()?
    } else {
        usize::from(read(1)?[0])
    };
    if size > 4096 {
        return None;
    }
    parse_ready(&read(size)?)
}

/// The `Socket-Type` of a READY command's body (`None` if it is no READY or lacks it).
fn parse_ready(body: &[u8]) -> Option<String> {
    let name_len = usize::from(*body.first()?);
    if body.get(1..1 + name_len)? != b"READY" {
        return None;
    }
    let mut at = 1 + name_len;
    while at < body.len() {
        let n = usize::from(body[at]);
        let name = body.get(at + 1..at + 1 + n)?;
        at += 1 + n;
        let len = u32::from_be_bytes(body.get(at..at + 4)?.try_into().ok()?) as usize;
        at += 4;
        let value = body.get(at..at + len)?;
        at += len;
        if name.eq_ignore_ascii_case(b"Socket-Type") {
            return String::from_utf8(value.to_vec()).ok();
        }
    }
    None
}

/// Why a peer's greeting was not taken.
#[derive(Debug, PartialEq)]
enum Greeting {
    /// The caller's stop flag was set.
    Stopped,
    /// What the peer did instead of greeting in ZMTP.
    Not(String),
}

/// A byte stream read with a deadline ([`check_greeting`]'s peer: a [`TcpStream`]).
trait TimedRead {
    /// Reads into `buf`, waiting at most `wait`.
    fn read_within(&mut self, buf: &mut [u8], wait: Duration) -> std::io::Result<usize>;
}

impl TimedRead for &mut TcpStream {
    fn read_within(&mut self, buf: &mut [u8], wait: Duration) -> std::io::Result<usize> {
        use std::io::Read;
        self.set_read_timeout(Some(wait))?;
        self.read(buf)
    }
}

/// A TCP connection to the first of the addresses of `host:port` (`endpoint`) that accepts
/// one within `wait`, how long it took, and the address.
fn first_stream(
    host: &str,
    port: u16,
    wait: Duration,
    endpoint: &str,
) -> Result<(TcpStream, Duration, Option<SocketAddr>), ZmqError> {
    let connect_err = |why: String| ZmqError::Connect {
        endpoint: endpoint.to_string(),
        why,
    };
    let addrs: Vec<_> = (host, port)
        .to_socket_addrs()
        .map_err(|e| ZmqError::Resolve {
            endpoint: endpoint.to_string(),
            why: e.to_string(),
        })?
        .collect();
    let mut last = String::from("no address");
    let mut connected_in = Duration::ZERO;
    let mut address = None;
    let stream = addrs
        .iter()
        .find_map(|a| {
            let attempt = Instant::now();
            match TcpStream::connect_timeout(a, wait) {
                Ok(s) => {
                    connected_in = attempt.elapsed();
                    address = Some(*a);
                    Some(s)
                }
                Err(e) => {
                    last = e.to_string();
                    None
                }
            }
        })
        .ok_or_else(|| connect_err(last))?;
    Ok((stream, connected_in, address))
}

/// Reads the first 10 bytes the peer sends on `stream` within `wait`: a ZMTP greeting starts
/// with 0xFF and has 0x7F at byte 9. Says what the peer did otherwise. A signal that
/// interrupts a read (Ctrl-C) does not end the wait; `stop`, once set, does.
fn check_greeting(
    mut stream: impl TimedRead,
    wait: Duration,
    stop: Option<&AtomicBool>,
) -> Result<(), Greeting> {
    let deadline = Instant::now() + wait;
    let mut got = Vec::with_capacity(10);
    let mut buf = [0u8; 10];
    while got.len() < 10 {
        if stop.is_some_and(|s| s.load(Ordering::SeqCst)) {
            return Err(Greeting::Stopped);
        }
        let mut left = deadline.saturating_duration_since(Instant::now());
        if left.is_zero() {
            break;
        }
        if stop.is_some() {
            left = left.min(STOP_LOOK);
        }
        match stream.read_within(&mut buf[..10 - got.len()], left) {
            Ok(0) => {
                return Err(Greeting::Not(format!(
                    "it closed the connection without a ZeroMQ greeting{}",
                    shown(&got)
                )));
            }
            Ok(n) => {
                got.extend_from_slice(&buf[..n]);
                if got[0] != 0xFF {
                    break;
                }
            }
            Err(e)
                if matches!(
                    e.kind(),
                    std::io::ErrorKind::WouldBlock
                        | std::io::ErrorKind::TimedOut
                        | std::io::ErrorKind::Interrupted
                ) => {}
            Err(e) => {
                return Err(Greeting::Not(format!(
                    "{e} before a ZeroMQ greeting{}",
                    shown(&got)
                )));
            }
        }
    }
    if got.len() == 10 && got[0] == 0xFF && got[9] == 0x7F {
        Ok(())
    } else if got.is_empty() {
        Err(Greeting::Not(format!(
            "no ZeroMQ greeting within {:.1} s (a ZeroMQ peer sends one at once)",
            wait.as_secs_f64()
        )))
    } else {
        Err(Greeting::Not(format!(
            "its first bytes are no ZeroMQ greeting{}",
            shown(&got)
        )))
    }
}

/// `" (it sent 01 00 ...)"` for the bytes a peer sent, or nothing.
fn shown(bytes: &[u8]) -> String {
    if bytes.is_empty() {
        return String::new();
    }
    let hex: Vec<String> = bytes.iter().map(|b| format!("{b:02x}")).collect();
    format!(" (it sent {})", hex.join(" "))
}

fn new_socket(
    context: &zmq::Context,
    endpoint: &str,
    timeout: Duration,
    ipv6: bool,
) -> Result<zmq::Socket, ZmqError> {
    let transport = |source| ZmqError::Transport {
        endpoint: endpoint.to_string(),
        error: source,
    };
    // DEALER, not REQ: it may send the next request before the last reply (see
    // `Client::call_all`); it adds the empty delimiter frame a REQ socket adds itself
    let socket = context.socket(zmq::DEALER).map_err(transport)?;
    let ms = i32::try_from(timeout.as_millis())
        .unwrap_or(i32::MAX)
        .max(1);
    socket.set_linger(0).map_err(transport)?;
    socket.set_ipv6(ipv6).map_err(transport)?;
    socket.set_rcvtimeo(ms).map_err(transport)?;
    socket.set_sndtimeo(ms).map_err(transport)?;
    socket.connect(endpoint).map_err(transport)?;
    Ok(socket)
}

#[cfg(test)]
mod tests {
    use std::io::Write;
    use std::net::TcpListener;

    use super::*;

    /// What `check_greeting` says of a peer that, once connected, runs `peer`.
    fn greeting_of(peer: impl FnOnce(TcpStream) + Send + 'static) -> Result<(), String> {
        let l = TcpListener::bind("127.0.0.1:0").unwrap();
        let addr = l.local_addr().unwrap();
        let t = std::thread::spawn(move || peer(l.accept().unwrap().0));
        let r = check_greeting(
            &mut TcpStream::connect(addr).unwrap(),
            Duration::from_millis(300),
            None,
        );
        t.join().unwrap();
        r.map_err(|e| match e {
            Greeting::Not(detail) => detail,
            Greeting::Stopped => panic!("no stop flag was given"),
        })
    }

    /// A peer whose reads go as scripted: each an error of that kind or those bytes.
    struct Scripted(Vec<Result<Vec<u8>, std::io::ErrorKind>>);

    impl TimedRead for Scripted {
        fn read_within(&mut self, buf: &mut [u8], _: Duration) -> std::io::Result<usize> {
            match self.0.remove(0) {
                Ok(bytes) => {
                    buf[..bytes.len()].copy_from_slice(&bytes);
                    Ok(bytes.len())
                }
                Err(kind) => Err(kind.into()),
            }
        }
    }

    #[test]
    fn a_peer_says_its_socket_type_in_its_ready_command() {
        let context = zmq::Context::new();
        for (kind, name) in [
            (zmq::PUB, "PUB"),
            (zmq::REP, "REP"),
            (zmq::ROUTER, "ROUTER"),
        ] {
            let peer = context.socket(kind).unwrap();
            peer.bind("tcp://127.0.0.1:0").unwrap();
            let endpoint = peer.get_last_endpoint().unwrap().unwrap();
            let addr = endpoint.trim_start_matches("tcp://").to_string();
            let mut stream = TcpStream::connect(addr).unwrap();
            let wait = Duration::from_secs(10);
            check_greeting(&mut stream, wait, None).unwrap();
            assert_eq!(peer_socket_type(&mut stream, wait).as_deref(), Some(name));
        }
        let dealer = b"\x05READY\x0bSocket-Type\x00\x00\x00\x06DEALER";
        assert_eq!(parse_ready(dealer).as_deref(), Some("DEALER"));
        assert_eq!(parse_ready(b"\x05ERROR"), None);
    }

    #[test]
    fn a_signal_during_the_greeting_is_no_verdict_on_the_peer() {
        let signature = vec![0xFF, 0, 0, 0, 0, 0, 0, 0, 1, 0x7F];
        // Ctrl-C interrupts the read (EINTR): the greeting is still read
        let interrupted = Scripted(vec![
            Err(std::io::ErrorKind::Interrupted),
            Ok(signature[..4].to_vec()),
            Err(std::io::ErrorKind::Interrupted),
            Ok(signature[4..].to_vec()),
        ]);
        let hour = Duration::from_secs(3600);
        assert_eq!(check_greeting(interrupted, hour, None), Ok(()));
        // and once the caller's flag is set, the wait ends as stopped, not as a verdict
        let stop = AtomicBool::new(true);
        let silent = Scripted(vec![Err(std::io::ErrorKind::Interrupted)]);
        assert_eq!(
            check_greeting(silent, hour, Some(&stop)),
            Err(Greeting::Stopped)
        );
    }

    #[test]
    fn a_server_gone_during_a_call_fails_it_and_every_later_call_at_once() {
        let context = zmq::Context::new();
        let server = context.socket(zmq::REP).unwrap();
        server.bind("tcp://127.0.0.1:0").unwrap();
        let endpoint = server.get_last_endpoint().unwrap().unwrap();
        let port = endpoint.rsplit(':').next().unwrap().parse().unwrap();
        let mut client = Client::open(&ClientOptions {
            port,
            timeout: Duration::from_millis(300),
            ..Default::default()
        })
        .unwrap();
        // the server ends: nothing listens on its port any more
        drop(server);
        drop(context);
        let first = client.call("sim.getInt32Param", vec![]).unwrap_err();
        assert!(matches!(first, ZmqError::Gone { .. }), "{first}");
        assert!(first.to_string().contains("nothing listens there any more"));
        let rounds = client.stats().round_trips;
        let later = client.call("sim.setInt32Param", vec![]).unwrap_err();
        assert!(matches!(later, ZmqError::Gone { .. }), "{later}");
        assert_eq!(client.stats().round_trips, rounds, "no request was sent");
    }

    #[test]
    fn after_a_timeout_the_clean_up_calls_wait_briefly() {
        // a server that takes requests and never answers (a frozen simulator)
        let context = zmq::Context::new();
        let server = context.socket(zmq::ROUTER).unwrap();
        server.bind("tcp://127.0.0.1:0").unwrap();
        let endpoint = server.get_last_endpoint().unwrap().unwrap();
        let port = endpoint.rsplit(':').next().unwrap().parse().unwrap();
        let mut client = Client::open(&ClientOptions {
            port,
            timeout: Duration::from_millis(1500),
            ..Default::default()
        })
        .unwrap();
        let secs = |e: ZmqError| match e {
            ZmqError::Timeout { secs, .. } => secs,
            other => panic!("{other}"),
        };
        assert_eq!(secs(client.call("sim.a", vec![]).unwrap_err()), 1.5);
        assert_eq!(secs(client.call("sim.b", vec![]).unwrap_err()), 1.0);
        drop(server);
    }

    #[test]
    fn a_zmtp_signature_is_a_greeting_and_anything_else_is_named() {
        let signature = [0xFF, 0, 0, 0, 0, 0, 0, 0, 1, 0x7F];
        assert_eq!(
            greeting_of(move |mut s| s.write_all(&signature).unwrap()),
            Ok(())
        );
        // the silent peer's connection stays open until the check is over (handed back
        // here), however late a loaded machine runs the check's thread
        let (held, kept) = std::sync::mpsc::channel();
        let silent = greeting_of(move |s| held.send(s).unwrap());
        drop(kept);
        assert!(
            silent
                .unwrap_err()
                .contains("no ZeroMQ greeting within 0.3 s")
        );
        let http = greeting_of(|mut s| s.write_all(b"HTTP/1.1 400").unwrap());
        assert!(
            http.as_ref().unwrap_err().contains("it sent 48 54 54 50"),
            "{http:?}"
        );
        let closed = greeting_of(drop);
        assert!(
            closed
                .as_ref()
                .unwrap_err()
                .contains("closed the connection without a ZeroMQ greeting"),
            "{closed:?}"
        );
    }
}
