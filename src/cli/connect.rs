//! Choosing the remote API for `apply` and `clear` and connecting to it: legacy (port 19997),
//! ZeroMQ (port 23000), or auto (try legacy briefly, then ZeroMQ, and say which answered).
//!
//! What is tried is said at once on standard error (standard output stays for reports).
//! The legacy API's connect wait is long by default: a real CoppeliaSim 4.5.1 refuses every
//! connection on its legacy port for about a minute after a client left abruptly (spec
//! `real-coppeliasim-4.5.1.md`, "Connections"); on a terminal the wait shows a countdown.
//! A failure is one error line and `hint:` lines ([`ConnectError::hints`]), and a port that
//! speaks the other API is named as such.

use std::io::IsTerminal;
use std::time::Duration;

use anyhow::Context;

use super::one_line;
use crate::draw::Backend;
use crate::legacy::client::Retrying;
use crate::legacy::{self, ClientError, LegacyBackend};
use crate::zmq_api::{self, ZmqBackend, ZmqError};

/// Which remote API to talk to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Api {
    /// Legacy remote API, port 19997 (CoppeliaSim up to 4.10, V-REP 3.x).
    Legacy,
    /// ZeroMQ remote API, port 23000 (CoppeliaSim 4.3 and later, the only one from 4.11).
    Zmq,
    /// Try the legacy port, then the ZeroMQ port; print which one answered.
    Auto,
}

/// The legacy remote API's default port.
pub const LEGACY_PORT: u16 = 19997;
/// The ZeroMQ remote API's default port.
pub const ZMQ_PORT: u16 = 23000;

/// Default connect wait of the legacy API: longer than the minute (62–65 s measured) for
/// which CoppeliaSim refuses connections after a client left abruptly.
pub const LEGACY_CONNECT_TIMEOUT: Duration = Duration::from_secs(75);
/// Default connect wait of the ZeroMQ API (it has no such refusal: a refused connection
/// fails at once; this bounds an unanswered TCP connection and the ZeroMQ greeting).
pub const ZMQ_CONNECT_TIMEOUT: Duration = Duration::from_secs(10);
/// How long `--api auto` tries the legacy port before it tries ZeroMQ.
const AUTO_LEGACY_WAIT: Duration = Duration::from_millis(1500);
/// Timeout of the quick look at the other API's port, for a hint.
const PROBE_TIMEOUT: Duration = Duration::from_secs(1);

/// A connection that could not be made, said on one line, with what to do about it.
#[derive(Debug, thiserror::Error)]
#[error("{message}")]
pub(crate) struct ConnectError {
    message: String,
    hints: Vec<String>,
}

impl ConnectError {
    /// Remedies, one line each.
    pub(crate) fn hints(&self) -> Vec<String> {
        self.hints.clone()
    }
}

fn connect_error(message: String, hints: Vec<String>) -> anyhow::Error {
    anyhow::Error::new(ConnectError { message, hints })
}

/// A connected backend and the line that names it (`legacy remote API at host:port`).
pub struct Connected {
    /// The connection.
    pub backend: Box<dyn Backend>,
    /// Which API answered, where, and (ZeroMQ) the simulator's version.
    pub description: String,
}

/// Connects as `api` says. `port` overrides the API's default (auto tries both APIs on it);
/// `timeout` bounds each reply; `connect_timeout` the connection [default:
/// [`LEGACY_CONNECT_TIMEOUT`] or [`ZMQ_CONNECT_TIMEOUT`]].
pub fn connect(
    api: Api,
    host: &str,
    port: Option<u16>,
    timeout: Duration,
    connect_timeout: Option<Duration>,
) -> anyhow::Result<Connected> {
    match api {
        Api::Legacy => legacy(
            host,
            port.unwrap_or(LEGACY_PORT),
            timeout,
            connect_timeout.unwrap_or(LEGACY_CONNECT_TIMEOUT),
            true,
        ),
        Api::Zmq => zmq(
            host,
            port.unwrap_or(ZMQ_PORT),
            timeout,
            connect_timeout.unwrap_or(ZMQ_CONNECT_TIMEOUT),
        ),
        Api::Auto => {
            // with --port, both APIs are tried on that port
            let (legacy_port, zmq_port) = port.map_or((LEGACY_PORT, ZMQ_PORT), |p| (p, p));
            let wait = connect_timeout.map_or(AUTO_LEGACY_WAIT, |t| t.min(AUTO_LEGACY_WAIT));
            let legacy_err = match legacy(host, legacy_port, timeout, wait, false) {
                Ok(c) => return Ok(c),
                Err(e) => e,
            };
            super::say::note(format!(
                "the legacy remote API did not answer at {}; trying the ZeroMQ one",
                socket_addr(host, legacy_port)
            ));
            let zmq_wait = connect_timeout.unwrap_or(ZMQ_CONNECT_TIMEOUT);
            zmq(host, zmq_port, timeout, zmq_wait).map_err(|zmq_err| {
                connect_error(
                    format!(
                        "no CoppeliaSim remote API answered on {host}: legacy port {legacy_port}: {}; ZeroMQ port {zmq_port}: {}",
                        one_line(&legacy_err),
                        one_line(&zmq_err)
                    ),
                    vec![
                        "is CoppeliaSim running? (up to 4.10 it serves the legacy remote API on 19997; from 4.3 the ZeroMQ add-on serves 23000)".into(),
                        format!(
                            "after a client leaves abruptly, CoppeliaSim refuses every legacy connection for about a minute; auto tries the legacy port for only {} s: --api legacy waits that minute out",
                            seconds(wait)
                        ),
                    ],
                )
            })
        }
    }
}

/// `host:port`, with brackets around an IPv6 address.
fn socket_addr(host: &str, port: u16) -> String {
    if host.contains(':') && !host.starts_with('[') {
        format!("[{host}]:{port}")
    } else {
        format!("{host}:{port}")
    }
}

/// `75` or `0.3`: seconds as the user would write them.
fn seconds(d: Duration) -> String {
    let s = d.as_secs_f64();
    if (s - s.round()).abs() < 0.05 {
        format!("{s:.0}")
    } else {
        format!("{s:.1}")
    }
}

fn legacy(
    host: &str,
    port: u16,
    timeout: Duration,
    connect_timeout: Duration,
    probe_zmq: bool,
) -> anyhow::Result<Connected> {
    let addr = socket_addr(host, port);
    super::say::note(format!(
        "connecting to CoppeliaSim's legacy remote API at {addr} ..."
    ));
    let opts = legacy::ClientOptions {
        connect_timeout,
        reply_timeout: timeout,
        ..Default::default()
    };
    let mut countdown = Countdown::default();
    let result = legacy::Client::connect_with(addr.as_str(), opts, &mut |r| countdown.retrying(r));
    countdown.done();
    let error = match result {
        Ok(client) => {
            return Ok(Connected {
                backend: Box::new(LegacyBackend::new(client, timeout)),
                description: format!("legacy remote API at {addr}"),
            });
        }
        Err(e) => e,
    };
    Err(match error {
        ClientError::Connect { why, waited, .. } => {
            if waited + 0.5 < connect_timeout.as_secs_f64() {
                // only a name that does not resolve fails before the deadline
                return Err(connect_error(
                    format!("cannot connect to {addr}: {why}"),
                    vec!["check --host: a name this machine resolves, or an IP address".into()],
                ));
            }
            let mut hints = vec![
                format!(
                    "is CoppeliaSim running with the legacy remote API on port {port}? (CoppeliaSim up to 4.10 starts it on {LEGACY_PORT})"
                ),
                format!(
                    "after a client leaves abruptly (Ctrl-C, a crash) CoppeliaSim refuses every connection on its legacy port for about a minute: wait, then run again{}",
                    if connect_timeout < LEGACY_CONNECT_TIMEOUT {
                        format!(
                            ", or pass --connect-timeout {} to wait it out",
                            LEGACY_CONNECT_TIMEOUT.as_secs()
                        )
                    } else {
                        String::new()
                    }
                ),
            ];
            if probe_zmq && port != ZMQ_PORT && zmq_answers(host, ZMQ_PORT) {
                hints.push(format!(
                    "the ZeroMQ remote API answers on {}: try --api zmq",
                    socket_addr(host, ZMQ_PORT)
                ));
            }
            connect_error(
                format!(
                    "cannot connect to {addr}: nothing accepted a connection within {} s ({why})",
                    seconds(connect_timeout)
                ),
                hints,
            )
        }
        ClientError::ZeroMqPeer { .. } => connect_error(
            format!("port {port} speaks the ZeroMQ remote API, not the legacy one: use --api zmq"),
            vec![],
        ),
        busy @ ClientError::Busy { .. } => connect_error(
            busy.to_string(),
            vec![
                "close the other client (another vrep-maze, a script) or wait until it is done, then run again".into(),
                "a simulator waiting in a dialog does not answer either: close the dialog".into(),
            ],
        ),
        other => anyhow::Error::new(other).context(format!("legacy remote API at {addr}")),
    })
}

fn zmq(
    host: &str,
    port: u16,
    timeout: Duration,
    connect_timeout: Duration,
) -> anyhow::Result<Connected> {
    let addr = socket_addr(host, port);
    super::say::note(format!(
        "connecting to CoppeliaSim's ZeroMQ remote API at {addr} ..."
    ));
    let options = zmq_api::ClientOptions {
        host: host.to_string(),
        port,
        timeout,
        connect_timeout: Some(connect_timeout),
        protocol: None,
    };
    let client = match zmq_api::Client::connect(&options) {
        Ok(client) => client,
        Err(e @ ZmqError::NotZeroMq { .. }) => {
            return Err(if legacy_answers(&addr) {
                connect_error(
                    format!(
                        "port {port} speaks the legacy remote API, not the ZeroMQ one: use --api legacy"
                    ),
                    vec![],
                )
            } else {
                connect_error(
                    e.to_string(),
                    vec![format!(
                        "is port {port} CoppeliaSim's ZeroMQ remote API? (the add-on serves {ZMQ_PORT} from CoppeliaSim 4.3)"
                    )],
                )
            });
        }
        Err(e @ ZmqError::Connect { .. }) => return Err(anyhow::Error::new(e)),
        Err(e) => {
            return Err(anyhow::Error::new(e).context(format!("ZeroMQ remote API at {addr}")));
        }
    };
    let backend =
        ZmqBackend::new(client, timeout).with_context(|| format!("ZeroMQ remote API at {addr}"))?;
    let description = backend.describe();
    Ok(Connected {
        backend: Box::new(backend),
        description,
    })
}

/// Whether a ZeroMQ remote API answers a call on `host:port` within [`PROBE_TIMEOUT`].
fn zmq_answers(host: &str, port: u16) -> bool {
    let options = zmq_api::ClientOptions {
        host: host.to_string(),
        port,
        timeout: PROBE_TIMEOUT,
        connect_timeout: Some(PROBE_TIMEOUT),
        protocol: None,
    };
    zmq_api::Client::connect(&options)
        .map(zmq_api::Client::close)
        .is_ok()
}

/// Whether a legacy remote API answers on `addr`. It leaves as the official client does
/// (the kill command), so the simulator takes the next client at once. The connect wait
/// covers the emulator's and CoppeliaSim's re-creation of the socket after a client left.
fn legacy_answers(addr: &str) -> bool {
    let opts = legacy::ClientOptions {
        connect_timeout: 3 * PROBE_TIMEOUT,
        reply_timeout: PROBE_TIMEOUT,
        ..Default::default()
    };
    legacy::Client::connect(addr, opts)
        .map(|c| {
            let _ = c.close();
        })
        .is_ok()
}

/// The countdown of a refused legacy connection, on standard error when it is a terminal
/// (nothing otherwise).
#[derive(Default)]
struct Countdown {
    bar: Option<indicatif::ProgressBar>,
}

impl Countdown {
    fn retrying(&mut self, r: &Retrying<'_>) {
        if self.bar.is_none() {
            if !std::io::stderr().is_terminal() {
                return;
            }
            let bar = indicatif::ProgressBar::new_spinner();
            bar.set_style(
                indicatif::ProgressStyle::with_template("{spinner} {msg}")
                    .unwrap_or_else(|_| indicatif::ProgressStyle::default_spinner()),
            );
            bar.enable_steady_tick(Duration::from_millis(100));
            self.bar = Some(bar);
        }
        if let Some(bar) = &self.bar {
            let what = if r.why.contains("dropped") {
                "dropped at once"
            } else {
                "refused"
            };
            bar.set_message(format!(
                "{what}; retrying for {} s more — CoppeliaSim refuses connections for about a minute after a client left abruptly (Ctrl-C to stop)",
                r.left.as_secs_f64().ceil()
            ));
        }
    }

    fn done(self) {
        if let Some(bar) = self.bar {
            bar.finish_and_clear();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_connect_error_is_one_line_and_its_remedies_are_hints() {
        let error = connect_error(
            "cannot connect to 127.0.0.1:19997: nothing accepted a connection within 75 s".into(),
            vec!["wait".into(), "try --api zmq".into()],
        );
        assert_eq!(
            one_line(&error),
            "cannot connect to 127.0.0.1:19997: nothing accepted a connection within 75 s"
        );
        assert_eq!(super::super::hints(&error), ["wait", "try --api zmq"]);
    }

    #[test]
    fn seconds_read_as_written_and_addresses_bracket_ipv6() {
        assert_eq!(seconds(LEGACY_CONNECT_TIMEOUT), "75");
        assert_eq!(seconds(Duration::from_millis(300)), "0.3");
        assert_eq!(seconds(AUTO_LEGACY_WAIT), "1.5");
        assert_eq!(socket_addr("::1", 19997), "[::1]:19997");
        assert_eq!(socket_addr("localhost", 23000), "localhost:23000");
    }
}
