//! A TCP proxy that cuts the connection between a client and a simulator mid-session, for
//! both remote APIs: it forwards bytes as they come and counts the client's *turns* (what
//! the client sends before the simulator answers: one request of the legacy API, one
//! ZeroMQ request or `_*executed*_`, or a part of the ZeroMQ handshake), and at the turn
//! where [`Cut`] says so, forwards nothing more, closes every connection and stops
//! listening. The client then sees the connection dropped (legacy) or no reply and nothing
//! listening any more (ZeroMQ: one timeout, after which its client fails every later call
//! at once); the simulator has run exactly the turns before the cut.

use std::io::{ErrorKind, Read, Write};
use std::net::{Shutdown, SocketAddr, TcpListener, TcpStream};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};
use std::thread::JoinHandle;
use std::time::Duration;

/// When to cut.
pub enum Cut {
    /// Never: forward and count.
    Never,
    /// After this many client turns.
    After(usize),
    /// At the first client turn at which this holds (checked before forwarding the turn).
    When(Box<dyn Fn() -> bool + Send + Sync>),
}

#[derive(Default)]
struct Inner {
    turns: usize,
    cut: bool,
    /// Per connection: did the client send last (within its current turn)?
    client_last: Vec<bool>,
    /// Every stream, both sides, to close on a cut.
    streams: Vec<TcpStream>,
    pumps: Vec<JoinHandle<()>>,
}

struct Shared {
    cut: Cut,
    stop: AtomicBool,
    inner: Mutex<Inner>,
}

impl Shared {
    fn lock(&self) -> MutexGuard<'_, Inner> {
        self.inner.lock().unwrap_or_else(|e| e.into_inner())
    }
}

fn cut_all(inner: &mut Inner) {
    inner.cut = true;
    for s in &inner.streams {
        let _ = s.shutdown(Shutdown::Both);
    }
}

/// A running proxy; dropping it closes every connection and joins its threads.
pub struct Proxy {
    port: u16,
    shared: Arc<Shared>,
    accept: Option<JoinHandle<()>>,
}

impl Proxy {
    /// Listens on a free loopback port and forwards each connection to `target`.
    pub fn start(target: SocketAddr, cut: Cut) -> Proxy {
        let listener = TcpListener::bind("127.0.0.1:0").unwrap();
        listener.set_nonblocking(true).unwrap();
        let port = listener.local_addr().unwrap().port();
        let shared = Arc::new(Shared {
            cut,
            stop: AtomicBool::new(false),
            inner: Mutex::default(),
        });
        let s = shared.clone();
        let accept = std::thread::spawn(move || {
            // after a cut the listener is closed: a ZeroMQ client's look at the port after
            // its timeout finds nothing listening
            while !s.stop.load(Ordering::SeqCst) && !s.lock().cut {
                let client = match listener.accept() {
                    Ok((c, _)) => c,
                    Err(e) if e.kind() == ErrorKind::WouldBlock => {
                        std::thread::sleep(Duration::from_millis(2));
                        continue;
                    }
                    Err(_) => break,
                };
                if s.lock().cut {
                    break;
                }
                client.set_nonblocking(false).unwrap();
                let Ok(upstream) = TcpStream::connect(target) else {
                    continue;
                };
                let _ = client.set_nodelay(true);
                let _ = upstream.set_nodelay(true);
                let mut inner = s.lock();
                if inner.cut {
                    continue;
                }
                let conn = inner.client_last.len();
                inner.client_last.push(false);
                inner.streams.push(client.try_clone().unwrap());
                inner.streams.push(upstream.try_clone().unwrap());
                let (c2, u2) = (client.try_clone().unwrap(), upstream.try_clone().unwrap());
                let (sa, sb) = (s.clone(), s.clone());
                inner.pumps.push(std::thread::spawn(move || {
                    pump(&sa, conn, client, upstream, true)
                }));
                inner
                    .pumps
                    .push(std::thread::spawn(move || pump(&sb, conn, u2, c2, false)));
            }
            drop(listener);
            let pumps = {
                let mut inner = s.lock();
                cut_all(&mut inner);
                std::mem::take(&mut inner.pumps)
            };
            for p in pumps {
                let _ = p.join();
            }
        });
        Proxy {
            port,
            shared,
            accept: Some(accept),
        }
    }

    /// The port to connect the client to.
    pub fn port(&self) -> u16 {
        self.port
    }

    /// The client turns forwarded so far.
    pub fn turns(&self) -> usize {
        self.shared.lock().turns
    }

    /// Whether it has cut.
    pub fn has_cut(&self) -> bool {
        self.shared.lock().cut
    }
}

impl Drop for Proxy {
    fn drop(&mut self) {
        self.shared.stop.store(true, Ordering::SeqCst);
        if let Some(t) = self.accept.take() {
            let _ = t.join();
        }
    }
}

/// Copies `from` to `to`; `up` is the client-to-simulator direction, where turns start.
fn pump(s: &Shared, conn: usize, mut from: TcpStream, mut to: TcpStream, up: bool) {
    let mut buf = [0u8; 16 * 1024];
    loop {
        let n = match from.read(&mut buf) {
            Ok(0) | Err(_) => break,
            Ok(n) => n,
        };
        {
            let mut inner = s.lock();
            if inner.cut {
                return;
            }
            if up && !inner.client_last[conn] {
                let cut = match &s.cut {
                    Cut::Never => false,
                    Cut::After(n) => inner.turns >= *n,
                    Cut::When(f) => f(),
                };
                if cut {
                    cut_all(&mut inner);
                    return;
                }
                inner.turns += 1;
            }
            inner.client_last[conn] = up;
        }
        if to.write_all(&buf[..n]).is_err() {
            break;
        }
    }
    // pass the end of the stream on
    let _ = to.shutdown(Shutdown::Write);
}
