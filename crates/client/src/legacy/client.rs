//! Native legacy remote API client (no C library): blocking and oneshot calls, batching any
//! number of commands into one message, identity-based reply matching.
//!
//! Unlike the C client it has no background thread: a blocking call sends one message with
//! all its command blocks, then keeps the ping-pong going with header-only messages every
//! `poll_interval` until a reply carries a result for every command (reply header message
//! ID >= the ID of the carrying message), or the timeout expires.

use std::collections::HashMap;
use std::net::{SocketAddr, TcpStream, ToSocketAddrs};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use super::command::{Command, opmode};
use super::quick_ack::QuickAck;
use super::wire::{
    Block, MAX_PACKET_SIZE, Message, MessageHeader, WireError, read_message, server_state, status,
    write_message,
};

/// Why connecting or a call failed.
#[derive(Debug, thiserror::Error)]
pub enum ClientError {
    /// Nobody accepted the connection before the deadline (nothing listens, or CoppeliaSim
    /// refuses connections: it does so for about a minute after a session it closed first,
    /// its port then being in TCP TIME_WAIT).
    #[error(
        "cannot connect to {addr}: nothing accepted a connection within {waited:.1} s ({why}; is CoppeliaSim running with the legacy remote API on this port? it refuses every connection for about a minute after a session it closed first)"
    )]
    Connect {
        /// Address tried.
        addr: String,
        /// The last attempt's failure (OS error, or the connection dropped at once).
        why: String,
        /// How long we retried.
        waited: f64,
    },
    /// A connection was accepted but nothing answered our first message: the simulator
    /// serves one client at a time, so another one is probably connected.
    #[error(
        "connected to {addr}, but no answer within {waited:.1} s: another client is probably connected (the simulator serves one at a time)"
    )]
    Busy {
        /// Address tried.
        addr: String,
        /// How long we waited for the answer.
        waited: f64,
    },
    /// The peer greeted us in ZeroMQ's ZMTP (first byte 0xFF, 0x7F at byte 9): the port is
    /// the ZeroMQ remote API's.
    #[error("{addr} speaks the ZeroMQ remote API, not the legacy one")]
    ZeroMqPeer {
        /// Address tried.
        addr: String,
    },
    /// The port answers, but not as a legacy remote API server does (an HTTP server, bytes
    /// that are no legacy packet).
    #[error("{addr} is not a CoppeliaSim legacy remote API server: {what}")]
    NotLegacy {
        /// Address tried.
        addr: String,
        /// What it did instead.
        what: String,
    },
    /// The caller stopped the connection wait (its `retrying` callback said so: Ctrl-C).
    #[error("stopped waiting to connect to {addr} after {waited:.1} s")]
    Stopped {
        /// Address tried.
        addr: String,
        /// How long we had retried.
        waited: f64,
    },
    /// The server did not answer in time.
    #[error(
        "no reply from the simulator within {0:.1} s (simulation paused in a dialog, or not a legacy remote API server?)"
    )]
    Timeout(f64),
    /// The server closed the connection.
    #[error("the simulator closed the connection")]
    Closed,
    /// Transport error or malformed bytes (printed in the message, so not a `source`).
    #[error("legacy remote API protocol error: {0}")]
    Wire(WireError),
    /// A reply whose payload does not match the command.
    #[error("malformed reply to command {cmd:#06x}: {why}")]
    BadReply {
        /// Raw command ID.
        cmd: u16,
        /// What is wrong.
        why: String,
    },
}

impl From<WireError> for ClientError {
    fn from(e: WireError) -> ClientError {
        ClientError::Wire(e)
    }
}

/// Connection settings.
#[derive(Debug, Clone)]
pub struct ClientOptions {
    /// How long to keep retrying to connect.
    pub connect_timeout: Duration,
    /// Pause between connection attempts.
    pub retry_interval: Duration,
    /// Timeout of one blocking call.
    pub reply_timeout: Duration,
    /// Pause between keep-alive messages while waiting.
    pub poll_interval: Duration,
    /// Largest packet we send.
    pub max_packet_size: usize,
}

impl Default for ClientOptions {
    fn default() -> Self {
        ClientOptions {
            connect_timeout: Duration::from_secs(10),
            retry_interval: Duration::from_millis(100),
            reply_timeout: Duration::from_secs(5),
            poll_interval: Duration::from_millis(2),
            max_packet_size: MAX_PACKET_SIZE,
        }
    }
}

/// The kinds of `commands` in order, each with how many times it comes in a row
/// (`GetIntegerSignal x7, SetPosition`): what `VREP_MAZE_TRACE` names a message by.
fn command_kinds(commands: &[Command]) -> String {
    let mut kinds: Vec<(String, usize)> = Vec::new();
    for c in commands {
        let debug = format!("{c:?}");
        let kind = debug
            .split(['(', ' ', '{'])
            .next()
            .unwrap_or_default()
            .to_string();
        match kinds.last_mut() {
            Some((last, n)) if *last == kind => *n += 1,
            _ => kinds.push((kind, 1)),
        }
    }
    kinds
        .iter()
        .map(|(k, n)| {
            if *n > 1 {
                format!("{k} x{n}")
            } else {
                k.clone()
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// A failed connection attempt that [`Client::connect_with`] is about to retry.
#[derive(Debug, Clone, Copy)]
pub struct Retrying<'a> {
    /// Time since the first attempt.
    pub waited: Duration,
    /// Time left until the connect timeout.
    pub left: Duration,
    /// Why the latest attempt failed (the OS error, or the connection dropped at once).
    pub why: &'a str,
}

/// What a connection accepted by the server turned out to be, when not an error.
enum Accepted {
    /// Open: the server answered.
    Open(Client),
    /// Dropped at once (why, to retry): the server was re-creating its socket.
    Dropped(String),
}

/// The result of one command.
#[derive(Debug, Clone, PartialEq)]
pub struct Reply {
    /// The server flagged an error (C client: `simx_return_remote_error_flag`, 8).
    pub remote_error: bool,
    /// Pure data of the reply.
    pub data: Vec<u8>,
    /// The simulation time the command was executed at, ms (`simxGetLastCmdTime`:
    /// `int(simTime * 1000.01)`, 0 while the simulation is stopped).
    pub sim_time: i32,
}

/// A connected client. However it ends ([`Client::close`], or dropped on an error path), it
/// leaves the one way (the private `end_session`), so the simulator's port listens again at
/// once.
pub struct Client {
    stream: TcpStream,
    /// The server answered our first message and the session has not ended yet: dropping
    /// the client must still leave properly (never set for a peer we only probed).
    open: bool,
    opts: ClientOptions,
    next_id: i32,
    clock: Instant,
    header: Option<MessageHeader>,
    inbox: HashMap<(u16, Vec<u8>), Block>,
    round_trips: usize,
    messages: usize,
}

impl Client {
    /// Connects (IPv4/IPv6, names resolved), retrying until `connect_timeout`.
    pub fn connect(
        addr: impl ToSocketAddrs + std::fmt::Display,
        opts: ClientOptions,
    ) -> Result<Client, ClientError> {
        Client::connect_with(addr, opts, &mut |_| true)
    }

    /// [`Client::connect`], calling `retrying` after each failed attempt that will be
    /// retried (for a countdown: CoppeliaSim refuses connections for about a minute after a
    /// session it closed first); when it returns `false` the wait ends with
    /// [`ClientError::Stopped`].
    pub fn connect_with(
        addr: impl ToSocketAddrs + std::fmt::Display,
        opts: ClientOptions,
        retrying: &mut dyn FnMut(&Retrying<'_>) -> bool,
    ) -> Result<Client, ClientError> {
        let started = Instant::now();
        let name = addr.to_string();
        let fail = |why: String| ClientError::Connect {
            addr: name.clone(),
            why,
            waited: started.elapsed().as_secs_f64(),
        };
        let addrs: Vec<SocketAddr> = addr
            .to_socket_addrs()
            .map_err(|e| fail(e.to_string()))?
            .collect();
        let mut last = String::from("no address");
        loop {
            for a in &addrs {
                let left = opts
                    .connect_timeout
                    .saturating_sub(started.elapsed())
                    .max(Duration::from_millis(50));
                let attempt = Instant::now();
                match TcpStream::connect_timeout(a, left) {
                    Ok(stream) => {
                        match Client::try_accepted(stream, a, &name, &opts, started, attempt)? {
                            Accepted::Open(client) => return Ok(client),
                            Accepted::Dropped(why) => last = why,
                        }
                    }
                    Err(e) => last = e.to_string(),
                }
            }
            let waited = started.elapsed();
            if waited + opts.retry_interval >= opts.connect_timeout {
                return Err(fail(last));
            }
            let go_on = retrying(&Retrying {
                waited,
                left: opts.connect_timeout - waited,
                why: &last,
            });
            if !go_on {
                return Err(ClientError::Stopped {
                    addr: name.clone(),
                    waited: waited.as_secs_f64(),
                });
            }
            std::thread::sleep(opts.retry_interval);
        }
    }

    /// Checks the connection `stream` accepted at `a` (`name`), `attempt` being when it
    /// was tried and `started` when connecting began: open once the server answers a
    /// header-only message, dropped at once (to retry), or an error that ends connecting
    /// (a ZeroMQ peer, a web server, another protocol, a busy server).
    fn try_accepted(
        stream: TcpStream,
        a: &SocketAddr,
        name: &str,
        opts: &ClientOptions,
        started: Instant,
        attempt: Instant,
    ) -> Result<Accepted, ClientError> {
        stream.set_nodelay(true).ok();
        // A ZeroMQ peer greets at once; a legacy server never speaks first.
        // Look before sending: legacy bytes that reach a ZeroMQ socket can
        // keep it from answering its next clients for seconds.
        if greets_in_zmtp(&stream, greeting_wait(attempt.elapsed())) {
            return Err(ClientError::ZeroMqPeer {
                addr: name.to_string(),
            });
        }
        let mut client = Client {
            stream,
            open: false,
            opts: opts.clone(),
            next_id: 0,
            clock: Instant::now(),
            header: None,
            inbox: HashMap::new(),
            round_trips: 0,
            messages: 0,
        };
        // A connection can land in the backlog of a listening socket the server
        // is about to close (it re-creates it after each client): check that
        // the server answers a header-only message before using it.
        let wait = opts
            .reply_timeout
            .min(opts.connect_timeout.saturating_sub(started.elapsed()))
            .max(Duration::from_millis(200));
        client.stream.set_read_timeout(Some(wait)).ok();
        match client.exchange(vec![]) {
            Ok(_) => {
                client.open = true;
                Ok(Accepted::Open(client))
            }
            Err(ClientError::Timeout(_)) => {
                // a web server waits for a request's end before it answers
                if answers_in_http(a, wait) {
                    return Err(not_legacy_http(name));
                }
                Err(ClientError::Busy {
                    addr: name.to_string(),
                    waited: wait.as_secs_f64(),
                })
            }
            Err(ClientError::Wire(WireError::BadPacket { marker, .. }))
                if marker == u16::from_le_bytes(*b"HT") =>
            {
                Err(not_legacy_http(name))
            }
            Err(e @ (ClientError::Closed | ClientError::Wire(WireError::Io(_)))) => {
                Ok(Accepted::Dropped(format!(
                    "connection dropped at once ({e}): the server was re-creating its socket"
                )))
            }
            Err(ClientError::Wire(WireError::BadPacket { marker, .. }))
                if client.greeted_in_zmtp(marker) =>
            {
                Err(ClientError::ZeroMqPeer {
                    addr: name.to_string(),
                })
            }
            Err(ClientError::Wire(e)) => Err(ClientError::NotLegacy {
                addr: name.to_string(),
                what: e.to_string(),
            }),
            Err(e) => Err(e),
        }
    }

    /// Whether the peer's first bytes (`marker`: bytes 0 and 1 of the bad packet header we
    /// read, then 4 more after that header) are a ZMTP greeting's signature: byte 0 is 0xFF,
    /// byte 9 is 0x7F. A ZeroMQ peer sends it as soon as the connection is made.
    fn greeted_in_zmtp(&mut self, marker: u16) -> bool {
        use std::io::Read;
        if marker & 0xFF != 0xFF {
            return false;
        }
        self.stream
            .set_read_timeout(Some(Duration::from_millis(500)))
            .ok();
        let mut rest = [0u8; 4];
        self.stream.read_exact(&mut rest).is_ok() && rest[3] == 0x7F
    }

    /// The simulator's address (to reach it again on a fresh connection).
    pub fn peer(&self) -> Option<SocketAddr> {
        self.stream.peer_addr().ok()
    }

    /// Blocking calls done so far (each is one round trip, however many commands it carried).
    pub fn round_trips(&self) -> usize {
        self.round_trips
    }

    /// Messages sent so far (including keep-alives).
    pub fn messages(&self) -> usize {
        self.messages
    }

    /// Header of the latest reply with a message ID other than -1 (like `simxGetInMessageInfo`).
    pub fn last_header(&self) -> Option<MessageHeader> {
        self.header
    }

    /// Whether the latest fresh reply header said the simulation is not stopped.
    pub fn simulation_running(&self) -> Option<bool> {
        self.header
            .map(|h| h.server_state & server_state::NOT_STOPPED != 0)
    }

    fn exchange(&mut self, blocks: Vec<Block>) -> Result<(i32, Message), ClientError> {
        let id = self.next_id;
        self.next_id = self.next_id.wrapping_add(1);
        let header = MessageHeader {
            message_id: id,
            client_time: (self.clock.elapsed().as_millis() as i32) & 0x03FF_FFFF,
            ..Default::default()
        };
        let bytes = Message { header, blocks }.encode();
        let _in_flight = InFlight::enter();
        write_message(&mut self.stream, &bytes, self.opts.max_packet_size)
            .map_err(|e| map_io(e, self.opts.reply_timeout))?;
        self.messages += 1;
        let reply = Message::decode(
            &read_message(&mut QuickAck(&self.stream))
                .map_err(|e| map_io(e, self.opts.reply_timeout))?,
        )?;
        if reply.header.message_id != -1 {
            self.header = Some(reply.header);
        }
        Ok((id, reply))
    }

    /// Sends `commands` in one message and waits until every result has arrived; results in
    /// command order. Commands of the same identity (e.g. several copy-pastes) are matched
    /// in order.
    pub fn call(&mut self, commands: &[Command]) -> Result<Vec<Reply>, ClientError> {
        let deadline = Instant::now() + self.opts.reply_timeout;
        self.round_trips += 1;
        let blocks: Vec<Block> = commands
            .iter()
            .map(|c| c.to_block(opmode::BLOCKING))
            .collect();
        let mut wanted: HashMap<(u16, Vec<u8>), std::collections::VecDeque<usize>> = HashMap::new();
        for (i, b) in blocks.iter().enumerate() {
            wanted.entry(b.identity()).or_default().push_back(i);
        }
        let mut got: Vec<Option<Reply>> = vec![None; blocks.len()];
        let mut missing = blocks.len();
        self.stream
            .set_read_timeout(Some(self.opts.reply_timeout))
            .map_err(|e| ClientError::Wire(e.into()))?;
        let (my_id, mut reply) = self.exchange(blocks)?;
        loop {
            let fresh =
                reply.header.message_id != -1 && reply.header.message_id.wrapping_sub(my_id) >= 0;
            for b in reply.blocks {
                let key = (b.raw_id(), b.id_data);
                match wanted
                    .get_mut(&key)
                    .filter(|_| fresh)
                    .and_then(|q| q.pop_front())
                {
                    Some(slot) => {
                        got[slot] = Some(Reply {
                            remote_error: b.status & status::REMOTE_ERROR != 0,
                            data: b.data,
                            sim_time: b.sim_time,
                        });
                        missing -= 1;
                    }
                    None => {
                        let b = Block {
                            id_data: key.1.clone(),
                            ..b
                        };
                        self.inbox.insert(key, b);
                    }
                }
            }
            if missing == 0 {
                if std::env::var_os("VREP_MAZE_TRACE").is_some() {
                    eprintln!(
                        "legacy: call of {} command(s) answered in {:.1} ms (message {my_id}, {} messages so far): {}",
                        got.len(),
                        (Instant::now() + self.opts.reply_timeout - deadline).as_secs_f64()
                            * 1000.0,
                        self.messages,
                        command_kinds(commands)
                    );
                }
                return Ok(got.into_iter().flatten().collect());
            }
            let now = Instant::now();
            if now >= deadline {
                return Err(ClientError::Timeout(self.opts.reply_timeout.as_secs_f64()));
            }
            std::thread::sleep(self.opts.poll_interval.min(deadline - now));
            self.stream
                .set_read_timeout(Some(
                    deadline
                        .saturating_duration_since(Instant::now())
                        .max(Duration::from_millis(1)),
                ))
                .map_err(|e| ClientError::Wire(e.into()))?;
            reply = self.exchange(vec![])?.1;
        }
    }

    /// One blocking command.
    pub fn call1(&mut self, command: Command) -> Result<Reply, ClientError> {
        Ok(self.call(std::slice::from_ref(&command))?.remove(0))
    }

    /// Sends `commands` in oneshot mode in one message without waiting for their results
    /// (they land in the inbox, see [`Client::take_inbox`]).
    pub fn oneshot(&mut self, commands: &[Command]) -> Result<(), ClientError> {
        self.stream
            .set_read_timeout(Some(self.opts.reply_timeout))
            .map_err(|e| ClientError::Wire(e.into()))?;
        let blocks = commands
            .iter()
            .map(|c| c.to_block(opmode::ONESHOT))
            .collect();
        let (_, reply) = self.exchange(blocks)?;
        for b in reply.blocks {
            self.inbox.insert(b.identity(), b);
        }
        Ok(())
    }

    /// Sends `commands` in streaming mode (`simx_opmode_streaming` + `period_ms`: the server
    /// keeps them and executes them every main-loop pass, at most once per period) in one
    /// message, without waiting; their results arrive in the inbox with later replies (read
    /// them with [`Client::buffered`], keep them coming with [`Client::poll`]).
    pub fn stream(&mut self, commands: &[Command], period_ms: u16) -> Result<(), ClientError> {
        let blocks = commands
            .iter()
            .map(|c| Block {
                delay: period_ms,
                ..c.to_block(opmode::STREAMING)
            })
            .collect();
        self.send_and_merge(blocks)
    }

    /// Ends the streams of `commands` (`simx_opmode_discontinue`) and forgets their results.
    pub fn discontinue(&mut self, commands: &[Command]) -> Result<(), ClientError> {
        let blocks: Vec<Block> = commands
            .iter()
            .map(|c| c.to_block(opmode::DISCONTINUE))
            .collect();
        for b in &blocks {
            self.inbox.remove(&b.identity());
        }
        self.send_and_merge(blocks)
    }

    /// One message without commands: merges the results the server produced since the
    /// previous reply into the inbox (what the C client's communication thread does every
    /// few milliseconds).
    pub fn poll(&mut self) -> Result<(), ClientError> {
        self.send_and_merge(vec![])
    }

    /// `simx_opmode_buffer`: the latest result received for the identity of `command`
    /// (kept in the inbox) and the simulation time it was executed at, in ms
    /// (`simxGetLastCmdTime`: `int(simTime * 1000.01)`, 0 while the simulation is stopped);
    /// `None` until one arrived.
    pub fn buffered(&self, command: &Command) -> Option<(Reply, i32)> {
        let b = command.to_block(0);
        self.inbox.get(&(b.raw_id(), b.id_data)).map(|b| {
            (
                Reply {
                    remote_error: b.status & status::REMOTE_ERROR != 0,
                    data: b.data.clone(),
                    sim_time: b.sim_time,
                },
                b.sim_time,
            )
        })
    }

    /// Sends `blocks` in one message and merges the reply's results into the inbox (the
    /// newest result per identity, discontinue echoes left out).
    fn send_and_merge(&mut self, blocks: Vec<Block>) -> Result<(), ClientError> {
        self.stream
            .set_read_timeout(Some(self.opts.reply_timeout))
            .map_err(|e| ClientError::Wire(e.into()))?;
        let (_, reply) = self.exchange(blocks)?;
        for b in reply.blocks {
            if b.opmode() != opmode::DISCONTINUE {
                self.inbox.insert(b.identity(), b);
            }
        }
        Ok(())
    }

    /// Removes and returns the latest reply received for the identity of `command`
    /// (`simx_opmode_buffer` + remove).
    pub fn take_inbox(&mut self, command: &Command) -> Option<Reply> {
        let b = command.to_block(0);
        self.inbox.remove(&(b.raw_id(), b.id_data)).map(|b| Reply {
            remote_error: b.status & status::REMOTE_ERROR != 0,
            data: b.data,
            sim_time: b.sim_time,
        })
    }

    /// Ends the session as the official client's `simxFinish` does (the kill command, its
    /// reply, one last message: the private `end_session`), so the simulator's port listens
    /// again at once; `Err` if the simulator did not acknowledge the kill command.
    pub fn close(mut self) -> Result<(), ClientError> {
        self.end_session()
    }

    /// The one way a session ends, as the official client's `simxFinish` ends it
    /// (`../shared/spec/real-coppeliasim-4.5.1.md`, "Why the legacy port refuses for a
    /// minute: TIME_WAIT"): the kill block, its reply (briefly awaited), then one more
    /// header-only message. CoppeliaSim closes its side right after that reply; our last
    /// message reaches a closed socket (or one closed with it unread), so the server's kernel
    /// answers with a reset and the server's side ends without TIME_WAIT. A client that
    /// answered the server's close with its own FIN instead would leave the port refusing
    /// every connection for a minute whenever the server closed first. Does nothing the
    /// second time.
    fn end_session(&mut self) -> Result<(), ClientError> {
        if !std::mem::take(&mut self.open) {
            return Ok(());
        }
        self.stream.set_read_timeout(Some(LEAVE_WAIT)).ok();
        self.exchange(vec![Command::KillConnection.to_block(opmode::ONESHOT)])?;
        let last = Message {
            header: MessageHeader {
                message_id: self.next_id,
                ..Default::default()
            },
            blocks: vec![],
        };
        if write_message(&mut self.stream, &last.encode(), self.opts.max_packet_size).is_ok() {
            wait_for_the_end(&mut self.stream, LEAVE_WAIT);
        }
        Ok(())
    }
}

impl Drop for Client {
    /// A client dropped without [`Client::close`] (an error path, an interrupted run) leaves
    /// the same way.
    fn drop(&mut self) {
        let _ = self.end_session();
    }
}

/// How long leaving waits for the kill command's reply, then for the server's close.
const LEAVE_WAIT: Duration = Duration::from_millis(500);

/// Legacy exchanges under way in this process: a message sent, its reply not read yet.
static IN_FLIGHT: AtomicUsize = AtomicUsize::new(0);

/// Whether a legacy exchange is under way in this process. A real CoppeliaSim 4.5.1 ends
/// when its legacy client vanishes in the middle of one (a SIGKILL mid-draw,
/// `../shared/spec/real-coppeliasim-4.5.1.md` "Connections, again"; a second Ctrl-C that
/// exits at once did the same, 3 of 3 tries): a process that must stop at once waits for
/// the reply in flight first.
pub fn exchange_in_flight() -> bool {
    IN_FLIGHT.load(Ordering::SeqCst) > 0
}

/// Counts one exchange in [`IN_FLIGHT`] while it lives.
struct InFlight;

impl InFlight {
    fn enter() -> InFlight {
        IN_FLIGHT.fetch_add(1, Ordering::SeqCst);
        InFlight
    }
}

impl Drop for InFlight {
    fn drop(&mut self) {
        IN_FLIGHT.fetch_sub(1, Ordering::SeqCst);
    }
}

/// Reads and discards until the peer closes or resets the connection, or `wait` has passed.
fn wait_for_the_end(stream: &mut TcpStream, wait: Duration) {
    use std::io::Read;
    let deadline = Instant::now() + wait;
    let mut buf = [0u8; 256];
    loop {
        let left = deadline.saturating_duration_since(Instant::now());
        if left.is_zero() || stream.set_read_timeout(Some(left)).is_err() {
            return;
        }
        match stream.read(&mut buf) {
            Ok(0) => return,
            Err(e) if e.kind() != std::io::ErrorKind::Interrupted => return,
            Ok(_) | Err(_) => {}
        }
    }
}

/// [`ClientError::NotLegacy`] for a peer that answers in HTTP.
fn not_legacy_http(addr: &str) -> ClientError {
    ClientError::NotLegacy {
        addr: addr.to_string(),
        what: "it answers in HTTP (a web server?)".into(),
    }
}

/// Whether the peer at `addr` answers an HTTP request (on a connection of its own) within
/// `wait` with an HTTP status line. Asked only of a peer that did not answer a legacy
/// message: a legacy server ignores the request (and the connection closes).
fn answers_in_http(addr: &SocketAddr, wait: Duration) -> bool {
    use std::io::{Read, Write};
    let wait = wait.min(Duration::from_secs(1));
    let Ok(mut stream) = TcpStream::connect_timeout(addr, wait) else {
        return false;
    };
    let mut start = [0u8; 5];
    stream.set_read_timeout(Some(wait)).is_ok()
        && stream.write_all(b"HEAD / HTTP/1.0\r\n\r\n").is_ok()
        && stream.read_exact(&mut start).is_ok()
        && &start == b"HTTP/"
}

/// How long to look for a ZeroMQ greeting after a connection that took `connected_in` (about
/// one round trip): a few round trips, at least 15 ms, at most 300 ms.
fn greeting_wait(connected_in: Duration) -> Duration {
    (connected_in * 3 + Duration::from_millis(15)).min(Duration::from_millis(300))
}

/// Whether the peer sent, within `wait` and before we sent anything, the start of a ZMTP
/// greeting (first byte 0xFF, 0x7F at byte 9). Only peeks: nothing is consumed.
fn greets_in_zmtp(stream: &TcpStream, wait: Duration) -> bool {
    let deadline = Instant::now() + wait;
    let mut buf = [0u8; 10];
    loop {
        let left = deadline.saturating_duration_since(Instant::now());
        if left.is_zero() || stream.set_read_timeout(Some(left)).is_err() {
            return false;
        }
        match stream.peek(&mut buf) {
            Ok(0) | Err(_) => return false,
            Ok(_) if buf[0] != 0xFF => return false,
            Ok(10) => return buf[9] == 0x7F,
            // part of the greeting: wait for the rest
            Ok(_) => std::thread::sleep(Duration::from_millis(1)),
        }
    }
}

fn map_io(e: WireError, timeout: Duration) -> ClientError {
    match e {
        WireError::Io(io) => match io.kind() {
            std::io::ErrorKind::WouldBlock | std::io::ErrorKind::TimedOut => {
                ClientError::Timeout(timeout.as_secs_f64())
            }
            std::io::ErrorKind::UnexpectedEof
            | std::io::ErrorKind::ConnectionReset
            | std::io::ErrorKind::ConnectionAborted
            | std::io::ErrorKind::BrokenPipe => ClientError::Closed,
            _ => ClientError::Wire(WireError::Io(io)),
        },
        other => ClientError::Wire(other),
    }
}

#[cfg(test)]
mod tests {
    use std::io::{Read, Write};
    use std::net::TcpListener;

    use super::*;

    /// The first 10 bytes libzmq sends on a new connection.
    const ZMTP_SIGNATURE: [u8; 10] = [0xFF, 0, 0, 0, 0, 0, 0, 0, 1, 0x7F];

    #[test]
    fn an_exchange_waiting_for_its_reply_is_in_flight() {
        let l = TcpListener::bind("127.0.0.1:0").unwrap();
        let addr = l.local_addr().unwrap();
        let (received, read) = std::sync::mpsc::channel();
        let (answer, answered) = std::sync::mpsc::channel::<()>();
        let server = std::thread::spawn(move || {
            let (mut s, _) = l.accept().unwrap();
            let mut first = [0u8; 1];
            s.read_exact(&mut first).unwrap();
            received.send(()).unwrap();
            let _ = answered.recv();
        });
        let opts = ClientOptions {
            connect_timeout: Duration::from_millis(300),
            ..ClientOptions::default()
        };
        let client = std::thread::spawn(move || Client::connect(addr, opts));
        read.recv().unwrap();
        // the connection's first message is sent and its reply not read
        assert!(exchange_in_flight());
        answer.send(()).unwrap();
        server.join().unwrap();
        assert!(client.join().unwrap().is_err());
    }

    #[test]
    fn a_zeromq_peer_is_recognised_before_anything_is_sent_to_it() {
        let l = TcpListener::bind("127.0.0.1:0").unwrap();
        let addr = l.local_addr().unwrap();
        let server = std::thread::spawn(move || {
            let (mut s, _) = l.accept().unwrap();
            s.write_all(&ZMTP_SIGNATURE).unwrap();
            let mut got = vec![];
            s.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
            let _ = s.read_to_end(&mut got);
            got
        });
        let e = Client::connect(addr, ClientOptions::default())
            .err()
            .unwrap();
        assert!(matches!(e, ClientError::ZeroMqPeer { .. }), "{e}");
        assert_eq!(
            e.to_string(),
            format!("{addr} speaks the ZeroMQ remote API, not the legacy one")
        );
        assert!(server.join().unwrap().is_empty(), "legacy bytes were sent");
    }

    #[test]
    fn refused_attempts_call_the_retry_hook_and_the_error_tells_the_truth() {
        let port = TcpListener::bind("127.0.0.1:0")
            .unwrap()
            .local_addr()
            .unwrap()
            .port();
        let opts = ClientOptions {
            connect_timeout: Duration::from_millis(400),
            ..Default::default()
        };
        let mut lefts = vec![];
        let e = Client::connect_with(format!("127.0.0.1:{port}"), opts, &mut |r| {
            assert!(!r.why.is_empty());
            lefts.push(r.left);
            true
        })
        .err()
        .unwrap();
        assert!(matches!(e, ClientError::Connect { .. }), "{e}");
        assert!(!lefts.is_empty());
        assert!(lefts.windows(2).all(|w| w[0] >= w[1]), "{lefts:?}");
        let text = e.to_string();
        assert!(text.contains("about a minute"), "{text}");
        assert!(!text.contains("few seconds"), "{text}");
    }

    #[test]
    fn the_caller_stops_the_connection_wait() {
        let port = std::net::TcpListener::bind("127.0.0.1:0")
            .unwrap()
            .local_addr()
            .unwrap()
            .port();
        let opts = ClientOptions {
            connect_timeout: Duration::from_secs(60),
            ..Default::default()
        };
        let mut calls = 0;
        let e = Client::connect_with(format!("127.0.0.1:{port}"), opts, &mut |_| {
            calls += 1;
            calls < 3
        })
        .err()
        .unwrap();
        assert!(matches!(e, ClientError::Stopped { .. }), "{e}");
        assert_eq!(calls, 3);
    }

    #[test]
    fn the_greeting_wait_is_a_few_round_trips_within_bounds() {
        assert_eq!(greeting_wait(Duration::ZERO), Duration::from_millis(15));
        assert_eq!(
            greeting_wait(Duration::from_millis(10)),
            Duration::from_millis(45)
        );
        assert_eq!(
            greeting_wait(Duration::from_secs(2)),
            Duration::from_millis(300)
        );
    }
}
