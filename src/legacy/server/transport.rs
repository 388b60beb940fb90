//! The socket side: the listening socket, one client session at a time, and `--trace`.
//!
//! A session reads a message, hands its commands to the main loop's
//! [`Core::receive`](super::main_loop::Core::receive) and
//! writes back the reply it returns; it ends on a socket or protocol error, after a message
//! whose last block is the kill command, or when the server stops.
//!
//! A session that ends any other way than with the kill command (connection reset, end of
//! file, the idle timeout, a protocol error) closes the port for
//! [`Timing::reconnect_penalty`](crate::sim::Timing::reconnect_penalty): every connection is
//! refused until it expires (`../shared/spec/real-coppeliasim-4.5.1.md`, "Connections (legacy
//! API)": about 60 s, measured 62–65 s stopped and 43–60 s running; the real cause is the
//! server socket in TIME_WAIT and a re-bind without SO_REUSEADDR retried every 2.5 s,
//! simExtRemoteApi `inConnection.cpp:243-277`, `simxSocket.cpp:544-554`).

use std::io;
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
        let (why, killed) = session(shared, stream);
        shared
            .active
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .take();
        {
            let mut core = shared.lock();
            core.end_session();
            if !killed {
                write_dump(&shared.config, &core.sim);
            }
        }
        if shared.config.verbose {
            eprintln!("vrep-maze serve: client {peer:?} left: {why}");
        }
        let penalty = shared.config.timing.reconnect_penalty;
        let closed_for = if killed || shared.stop.load(Ordering::SeqCst) {
            shared.config.rebind_delay
        } else {
            shared.config.rebind_delay.max(penalty)
        };
        if closed_for.is_zero() {
            listener = Some(l);
        } else {
            drop(l);
            if shared.config.verbose && !killed && !penalty.is_zero() {
                eprintln!(
                    "vrep-maze serve: the client left without the kill command: refusing connections for {:.1} s",
                    closed_for.as_secs_f64()
                );
            }
            sleep_unless_stopped(&shared.stop, closed_for);
        }
    }
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

/// Serves one client until it leaves; returns why the session ended, and whether it ended
/// cleanly (with the kill command, or closed by the client before any message).
fn session(shared: &Shared, mut stream: TcpStream) -> (String, bool) {
    let _ = stream.set_read_timeout(Some(shared.config.idle_timeout));
    let _ = stream.set_nodelay(true);
    *shared.active.lock().unwrap_or_else(|e| e.into_inner()) = stream.try_clone().ok();
    shared.lock().end_session();
    let mut exchanged = false;
    loop {
        if shared.stop.load(Ordering::SeqCst) {
            let _ = stream.shutdown(Shutdown::Both);
            return ("server stopping".into(), false);
        }
        let bytes = match read_message(&mut stream) {
            Ok(b) => b,
            // A client that closed before sending anything (a port probe) is not counted as
            // leaving abruptly: the measured refusal followed clients killed or interrupted
            // during their exchanges, and by the source it follows a close on the server's
            // side, while a probe closes first itself (spec "Connections (legacy API)";
            // simExtRemoteApi inConnection.cpp:243-277). Unmeasured: a modeling choice.
            Err(WireError::Io(e))
                if !exchanged && e.kind() == std::io::ErrorKind::UnexpectedEof =>
            {
                return ("closed before sending anything".into(), true);
            }
            Err(e) => return (format!("{e}"), false),
        };
        exchanged = true;
        let msg = match Message::decode(&bytes) {
            Ok(m) => m,
            Err(e) => return (format!("protocol error: {e}"), false),
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
        if let Err(e) = write_message(&mut stream, &reply.encode(), shared.config.max_packet_size) {
            return (format!("{e}"), kill);
        }
        if kill {
            let _ = stream.shutdown(Shutdown::Both);
            return ("kill command".into(), true);
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
