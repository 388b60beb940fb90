//! The socket side: the listening socket, one client session at a time, and `--trace`.
//!
//! A session reads a message, hands its commands to the main loop's
//! [`Core::receive`](super::main_loop::Core::receive) and
//! writes back the reply it returns; it ends on a socket or protocol error, after a message
//! whose last block is the kill command, or when the server stops.
//!
//! After a session the port refuses connections for a while, as CoppeliaSim's does
//! (`../shared/spec/real-coppeliasim-4.5.1.md`, "Why the legacy port refuses for a minute:
//! TIME_WAIT"): the plugin closes its listening socket with the connection, sleeps 0.5 s
//! ([`ServerConfig::rebind_delay`](super::ServerConfig::rebind_delay)) and binds the port
//! again without SO_REUSEADDR. When the server's side closed first (right after its reply to
//! the kill block, or on its idle timeout or a protocol error) and the client answered that
//! close with its own FIN, or not at all, the server's end of the connection holds the port
//! (TIME_WAIT, or FIN_WAIT_2 while the client stays silent) and every connection is refused
//! for [`Timing::reconnect_penalty`](crate::sim::Timing::reconnect_penalty) (60 s). When the
//! client closed first, or answered with data or a reset (what the official client's
//! `simxFinish` and ours do), the port listens again after the 0.5 s. The older
//! measurements of the minute after a Ctrl-C or an error (spec "Connections (legacy API)")
//! were of a client that sent the kill block and then waited for the server to close.

use std::io::{self, Read};
use std::net::{Shutdown, SocketAddr, TcpListener, TcpStream};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use super::{Shared, write_dump};
use crate::legacy::command::id;
use crate::legacy::wire::{Message, WireError, read_message, write_message};

/// Accepts one client at a time. Like CoppeliaSim, after a client leaves the listening
/// socket is closed and re-created `rebind_delay` later (connections are refused meanwhile).
pub(super) fn accept_loop(shared: &Shared, listener: TcpListener, addr: SocketAddr) {
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
        let mut stream = loop {
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
        let (why, end) = session(shared, &mut stream);
        shared
            .active
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .take();
        {
            let mut core = shared.lock();
            core.end_session();
            if end != End::Killed {
                write_dump(&shared.config, &core.sim);
            }
        }
        if shared.config.verbose {
            eprintln!("vrep-maze serve: client {peer:?} left: {why}");
        }
        let penalty = shared.config.timing.reconnect_penalty;
        let rebind = shared.config.rebind_delay;
        let stopping = shared.stop.load(Ordering::SeqCst);
        let server_first = !stopping && end != End::ClientFirst && !penalty.is_zero();
        if rebind.is_zero() && !server_first {
            listener = Some(l);
            continue;
        }
        drop(l);
        let closed_for = if server_first {
            server_closes(shared, &mut stream, penalty)
        } else {
            rebind
        };
        drop(stream);
        sleep_unless_stopped(&shared.stop, closed_for.max(rebind));
    }
}

/// How a session ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum End {
    /// The client's end of file or reset arrived before the server closed (it left
    /// mid-session or before sending anything, or the reply could not be written).
    ClientFirst,
    /// The server replied to the kill block and closes its side now.
    Killed,
    /// The server gave up on the client (idle timeout, protocol error) and closes its side.
    ServerFirst,
}

/// The server closes its side first (`stream`: the session's connection) and watches how
/// the client answers, within `penalty`; returns how long the port still refuses
/// connections from then on (spec "Why the legacy port refuses for a minute: TIME_WAIT").
/// A client whose FIN, data or reset had already arrived closed first (unread data makes the
/// close a reset): no TIME_WAIT. Otherwise the server's FIN goes out; data or a reset in
/// answer meets a closed socket, whose kernel resets the connection: no TIME_WAIT either.
/// The client's FIN puts the server's end in TIME_WAIT for `penalty` from then; silence
/// keeps it in FIN_WAIT_2 (the kernel's 60 s orphan timeout, modeled as `penalty`).
fn server_closes(shared: &Shared, stream: &mut TcpStream, penalty: Duration) -> Duration {
    let rebind = shared.config.rebind_delay;
    let mut byte = [0u8; 1];
    let _ = stream.set_nonblocking(true);
    let arrived = stream.peek(&mut byte);
    let _ = stream.set_nonblocking(false);
    match arrived {
        Err(e) if e.kind() == io::ErrorKind::WouldBlock => {}
        _ => return rebind,
    }
    let _ = stream.shutdown(Shutdown::Write);
    let started = Instant::now();
    let mut buf = [0u8; 256];
    while !shared.stop.load(Ordering::SeqCst) {
        let Some(left) = penalty
            .checked_sub(started.elapsed())
            .filter(|l| !l.is_zero())
        else {
            // FIN_WAIT_2 timed out: the port is free
            return Duration::ZERO;
        };
        let _ = stream.set_read_timeout(Some(left.min(Duration::from_millis(20))));
        match stream.read(&mut buf) {
            Ok(0) => {
                if shared.config.verbose {
                    eprintln!(
                        "vrep-maze serve: the client answered the server's close with its own: the port is in TIME_WAIT, refusing connections for {:.1} s",
                        penalty.as_secs_f64()
                    );
                }
                return penalty;
            }
            Err(e)
                if matches!(
                    e.kind(),
                    io::ErrorKind::WouldBlock
                        | io::ErrorKind::TimedOut
                        | io::ErrorKind::Interrupted
                ) => {}
            // data at a closed socket, or the client's reset: the connection is reset
            Ok(_) | Err(_) => return rebind,
        }
    }
    Duration::ZERO
}

/// Sleeps `d`, or less if the server stops meanwhile.
fn sleep_unless_stopped(stop: &AtomicBool, d: Duration) {
    let end = Instant::now() + d;
    while !stop.load(Ordering::SeqCst) {
        let Some(left) = end.checked_duration_since(Instant::now()) else {
            return;
        };
        std::thread::sleep(left.min(Duration::from_millis(20)));
    }
}

/// Serves one client until it leaves; returns why the session ended, and how.
fn session(shared: &Shared, stream: &mut TcpStream) -> (String, End) {
    let _ = stream.set_read_timeout(Some(shared.config.idle_timeout));
    // Nagle's algorithm stays on, as on the real server (`../shared/spec/legacy-remote-api.md`
    // §2: no TCP_NODELAY): with one write a packet, a reply's second packet waits for the
    // client's acknowledgement of the first, which a client that delays its acknowledgements
    // (the C client; Linux waits up to 40 ms) makes late: the kernel does the modelling, so
    // the socket keeps its default
    *shared.active.lock().unwrap_or_else(|e| e.into_inner()) = stream.try_clone().ok();
    shared.lock().end_session();
    loop {
        if shared.stop.load(Ordering::SeqCst) {
            let _ = stream.shutdown(Shutdown::Both);
            return ("server stopping".into(), End::ServerFirst);
        }
        let bytes = match read_message(stream) {
            Ok(b) => b,
            Err(WireError::Io(e)) if !timed_out(&e) => return (e.to_string(), End::ClientFirst),
            Err(e) => return (format!("{e}"), End::ServerFirst),
        };
        let msg = match Message::decode(&bytes) {
            Ok(m) => m,
            Err(e) => return (format!("protocol error: {e}"), End::ServerFirst),
        };
        if shared.config.trace {
            trace(&msg, bytes.len());
        }
        let kill = msg
            .blocks
            .last()
            .is_some_and(|b| b.raw_id() == id::KILL_CONNECTION);
        // the kill block is never stored (only its position matters); split chunks we ignore
        let mut blocks = Vec::with_capacity(msg.blocks.len());
        for b in msg.blocks {
            if b.raw_id() == id::KILL_CONNECTION {
                continue;
            }
            if b.split.is_some() {
                if shared.config.verbose {
                    eprintln!("vrep-maze serve: split command chunks are not supported; ignored");
                }
                continue;
            }
            blocks.push(b);
        }
        let reply = {
            let mut core = shared.lock();
            let reply = core.receive(&msg.header, blocks);
            shared.wake.notify_all();
            if kill {
                // the client's work is done (its blocking calls had their results): the dump
                // is on disk before its last reply, so `apply && render dump` never races
                write_dump(&shared.config, &core.sim);
            }
            reply
        };
        if let Err(e) = write_message(stream, &reply.encode(), shared.config.max_packet_size) {
            return (format!("{e}"), End::ClientFirst);
        }
        if kill {
            return ("kill command".into(), End::Killed);
        }
    }
}

/// Whether a read failed on the idle timeout (the server gives up on a silent client).
fn timed_out(e: &io::Error) -> bool {
    matches!(
        e.kind(),
        io::ErrorKind::WouldBlock | io::ErrorKind::TimedOut
    )
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
