//! The socket side: the listening socket, one client session at a time, and `--trace`.
//!
//! A session reads a message, hands its commands to the main loop's
//! [`Core::receive`](super::main_loop::Core::receive) and
//! writes back the reply it returns; it ends on a socket or protocol error, after a message
//! whose last block is the kill command, or when the server stops.

use std::io;
use std::net::{Shutdown, SocketAddr, TcpListener, TcpStream};
use std::sync::atomic::Ordering;
use std::time::Duration;

use super::{Shared, write_dump};
use crate::legacy::command::id;
use crate::legacy::wire::{Message, read_message, write_message};

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
        let why = session(shared, stream);
        shared
            .active
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .take();
        {
            let mut core = shared.lock();
            core.end_session();
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

/// Serves one client until it leaves; returns why the session ended.
fn session(shared: &Shared, mut stream: TcpStream) -> String {
    let _ = stream.set_read_timeout(Some(shared.config.idle_timeout));
    let _ = stream.set_nodelay(true);
    *shared.active.lock().unwrap_or_else(|e| e.into_inner()) = stream.try_clone().ok();
    shared.lock().end_session();
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
            reply
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
