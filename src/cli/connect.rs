//! Choosing the remote API for `apply`, `clear`, `inspect` and `score` and connecting to it:
//! legacy (port 19997), ZeroMQ (port 23000), or auto (try legacy briefly, then ZeroMQ, and
//! say which answered). A command that draws gets a drawing backend ([`connect`]), `score`
//! the raw client it follows a robot with ([`connect_client`]), through the same waits,
//! messages and hints.
//!
//! What is tried is said at once on standard error (standard output stays for reports).
//! A real CoppeliaSim 4.5.1 refuses every connection on its legacy port for about a minute
//! after a session it closed first whose client answered with its own close (TCP's
//! TIME_WAIT on the port: spec `real-coppeliasim-4.5.1.md`, "Why the legacy port refuses for a minute: TIME_WAIT"). Our client
//! never leaves so; the legacy connect wait outlasts that minute only when the refusal can
//! be the cause: when an earlier run of this tool ended with its session here still open
//! ([`SessionMarker`]); then a
//! countdown shows on a terminal. Otherwise a port where nothing listens is said so within
//! [`NOTHING_LISTENS_AFTER`] and the wait ends after [`LEGACY_CONNECT_TIMEOUT`]. Ctrl-C
//! ends any wait at once.
//! A failure is one error line and `hint:` lines ([`ConnectError::hints`]), and a port that
//! speaks the other API is named as such.

use std::io::IsTerminal;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Duration;

use anyhow::Context;

use super::hinted::ConnectError;
use super::interrupt::Interrupted;
use super::session_marker::SessionMarker;
use super::usage::one_line;
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
/// Environment variable that moves the legacy default port (a simulator configured
/// elsewhere, or a test suite that must not touch the user's CoppeliaSim).
pub const LEGACY_PORT_VAR: &str = "VREP_MAZE_LEGACY_PORT";
/// Environment variable that moves the ZeroMQ default port, as [`LEGACY_PORT_VAR`].
pub const ZMQ_PORT_VAR: &str = "VREP_MAZE_ZMQ_PORT";

/// The legacy port used without `--port`: [`LEGACY_PORT_VAR`] if set, else [`LEGACY_PORT`].
pub fn legacy_port() -> anyhow::Result<u16> {
    port_from(LEGACY_PORT_VAR, LEGACY_PORT)
}

/// The ZeroMQ port used without `--port`: [`ZMQ_PORT_VAR`] if set, else [`ZMQ_PORT`].
pub fn zmq_port() -> anyhow::Result<u16> {
    port_from(ZMQ_PORT_VAR, ZMQ_PORT)
}

/// The port in the environment variable `var`, or `default` when it is unset; a value
/// that is not a port is a usage error.
fn port_from(var: &str, default: u16) -> anyhow::Result<u16> {
    match std::env::var(var) {
        Err(std::env::VarError::NotPresent) => Ok(default),
        Ok(v) => match v.trim().parse::<u16>() {
            Ok(p) if p > 0 => Ok(p),
            _ => Err(super::usage::usage(format!(
                "{var}={v:?} is not a port (1..=65535); unset it to use {default}"
            ))),
        },
        Err(_) => Err(super::usage::usage(format!(
            "{var} is not valid text; unset it to use {default}"
        ))),
    }
}

/// Connect wait of the legacy API when an earlier run ended with its session open: longer
/// than the minute (60–65 s measured) for which CoppeliaSim may then refuse connections.
pub const LEGACY_REFUSAL_WAIT: Duration = Duration::from_secs(75);
/// Default connect wait of the legacy API otherwise: a simulator that is starting opens
/// its port within it.
pub const LEGACY_CONNECT_TIMEOUT: Duration = Duration::from_secs(10);
/// How long refused connections go on before the wait says that nothing listens.
const NOTHING_LISTENS_AFTER: Duration = Duration::from_secs(2);
/// Default connect wait of the ZeroMQ API (it has no such refusal: a refused connection
/// fails at once; this bounds an unanswered TCP connection and the ZeroMQ greeting).
pub const ZMQ_CONNECT_TIMEOUT: Duration = Duration::from_secs(10);
/// How long `--api auto` tries the legacy port before it tries ZeroMQ.
const AUTO_LEGACY_WAIT: Duration = Duration::from_millis(1500);
/// Timeout of the quick look at the other API's port, for a hint.
const PROBE_TIMEOUT: Duration = Duration::from_secs(1);

fn connect_error(message: String, hints: Vec<String>) -> anyhow::Error {
    anyhow::Error::new(ConnectError {
        message,
        hints,
        nothing_listens: false,
        zmq_peer: false,
    })
}

/// Whether `error` is a legacy connection that nothing accepted (where CoppeliaSim's minute
/// of refusal can be the cause), not something else answering.
fn nothing_listened(error: &anyhow::Error) -> bool {
    error
        .downcast_ref::<ConnectError>()
        .is_some_and(|e| e.nothing_listens)
}

/// A connected backend and the line that names it (`legacy remote API at host:port`).
pub struct Connected {
    /// The connection.
    pub backend: Box<dyn Backend>,
    /// Which API answered, where, and (ZeroMQ) the simulator's version.
    pub description: String,
}

/// The client of the API that answered, for a command that does not draw (`score` follows
/// a robot with it).
pub enum RawClient {
    /// The legacy remote API.
    Legacy(legacy::Client),
    /// The ZeroMQ remote API.
    Zmq(zmq_api::Client),
}

/// What a connection is made into: a drawing backend ([`Connected`]) or a [`RawClient`].
trait Opened: Sized {
    /// The legacy connection `client` to `addr` (replies within `timeout`), whose session
    /// `marker` may record.
    fn legacy(client: legacy::Client, marker: SessionMarker, addr: &str, timeout: Duration)
    -> Self;
    /// Connects over ZeroMQ to `host:port`; once `stop` is set the connection's waits end
    /// with [`Interrupted`].
    fn zmq(
        host: &str,
        port: u16,
        timeout: Duration,
        connect_timeout: Duration,
        stop: Option<&AtomicBool>,
    ) -> anyhow::Result<Self>;
}

impl Opened for Connected {
    /// The session is recorded ([`SessionMarker`]) until the backend closes it cleanly.
    fn legacy(
        client: legacy::Client,
        marker: SessionMarker,
        addr: &str,
        timeout: Duration,
    ) -> Self {
        marker.opened();
        let backend = LegacyBackend::new(client, timeout)
            .at(addr)
            .on_clean_close(move || marker.closed());
        Connected {
            backend: Box::new(backend),
            description: format!("legacy remote API at {addr}"),
        }
    }

    fn zmq(
        host: &str,
        port: u16,
        timeout: Duration,
        connect_timeout: Duration,
        stop: Option<&AtomicBool>,
    ) -> anyhow::Result<Self> {
        zmq(host, port, timeout, connect_timeout, stop)
    }
}

impl Opened for RawClient {
    /// The session is not recorded: the follower that owns the client closes it.
    fn legacy(client: legacy::Client, _: SessionMarker, _: &str, _: Duration) -> Self {
        RawClient::Legacy(client)
    }

    fn zmq(
        host: &str,
        port: u16,
        timeout: Duration,
        connect_timeout: Duration,
        stop: Option<&AtomicBool>,
    ) -> anyhow::Result<Self> {
        zmq_client(host, port, timeout, connect_timeout, stop).map(RawClient::Zmq)
    }
}

/// Connects as `api` says. `port` overrides the API's default (auto tries both APIs on it);
/// `timeout` bounds each reply; `connect_timeout` the connection [default:
/// [`LEGACY_CONNECT_TIMEOUT`] (or [`LEGACY_REFUSAL_WAIT`] when an earlier run left
/// abruptly) or [`ZMQ_CONNECT_TIMEOUT`]]. Once `stop` is set (Ctrl-C) the wait ends with
/// [`Interrupted`], on either API.
pub fn connect(
    api: Api,
    host: &str,
    port: Option<u16>,
    timeout: Duration,
    connect_timeout: Option<Duration>,
    stop: Option<&AtomicBool>,
) -> anyhow::Result<Connected> {
    open(api, host, port, timeout, connect_timeout, stop)
}

/// Connects as [`connect`] does (the same waits, messages and hints), handing out the raw
/// client of the API that answered instead of a drawing backend.
pub fn connect_client(
    api: Api,
    host: &str,
    port: Option<u16>,
    timeout: Duration,
    connect_timeout: Option<Duration>,
    stop: Option<&AtomicBool>,
) -> anyhow::Result<RawClient> {
    open(api, host, port, timeout, connect_timeout, stop)
}

/// [`connect`] and [`connect_client`]: the connection made into `T`.
fn open<T: Opened>(
    api: Api,
    host: &str,
    port: Option<u16>,
    timeout: Duration,
    connect_timeout: Option<Duration>,
    stop: Option<&AtomicBool>,
) -> anyhow::Result<T> {
    match api {
        Api::Legacy => legacy(
            host,
            port.map_or_else(legacy_port, Ok)?,
            timeout,
            connect_timeout,
            Some(ZmqProbe {
                port: zmq_port()?,
                with_port: port.is_some(),
            }),
            stop,
        ),
        Api::Zmq => T::zmq(
            host,
            port.map_or_else(zmq_port, Ok)?,
            timeout,
            connect_timeout.unwrap_or(ZMQ_CONNECT_TIMEOUT),
            stop,
        ),
        Api::Auto => auto(host, port, timeout, connect_timeout, stop),
    }
}

/// `--api auto`: the legacy API first, briefly (or through CoppeliaSim's minute of refusal
/// when an earlier run left so), then the ZeroMQ one; when neither answers, one error that
/// says what each port did, with hints.
fn auto<T: Opened>(
    host: &str,
    port: Option<u16>,
    timeout: Duration,
    connect_timeout: Option<Duration>,
    stop: Option<&AtomicBool>,
) -> anyhow::Result<T> {
    // with --port, both APIs are tried on that port
    let (legacy_port, zmq_port) = match port {
        Some(p) => (p, p),
        None => (legacy_port()?, zmq_port()?),
    };
    let refusal = SessionMarker::for_address(host, legacy_port)
        .left_abruptly()
        .is_some();
    let wait = match connect_timeout {
        Some(t) => t.min(AUTO_LEGACY_WAIT),
        // the refusal can be the cause: wait it out on the legacy port
        None if refusal => LEGACY_REFUSAL_WAIT,
        None => AUTO_LEGACY_WAIT,
    };
    let legacy_err = match legacy(host, legacy_port, timeout, Some(wait), None, stop) {
        Ok(c) => return Ok(c),
        Err(e) if e.is::<Interrupted>() => return Err(e),
        Err(e) => e,
    };
    super::say::note(format!(
        "the legacy remote API did not answer at {}; trying the ZeroMQ one",
        socket_addr(host, legacy_port)
    ));
    let zmq_wait = connect_timeout.unwrap_or(ZMQ_CONNECT_TIMEOUT);
    T::zmq(host, zmq_port, timeout, zmq_wait, stop).map_err(|zmq_err| {
        if zmq_err.is::<Interrupted>() {
            return zmq_err;
        }
        auto_error(
            host,
            port,
            (legacy_port, &legacy_err),
            (zmq_port, zmq_err),
            wait,
        )
    })
}

/// Why `--api auto` found no remote API: one short line when nothing listens on either
/// port, with only the hints that fit. The legacy refusal of about a minute (after a
/// session CoppeliaSim closed first) is named only on the legacy default port, where a
/// CoppeliaSim serves it: a port given by hand where nothing listens is more likely a
/// typo, and the hint then looks whether the default ZeroMQ port answers.
fn auto_error(
    host: &str,
    port: Option<u16>,
    (legacy_port, legacy_err): (u16, &anyhow::Error),
    (zmq_port, zmq_err): (u16, anyhow::Error),
    wait: Duration,
) -> anyhow::Error {
    let refused = nothing_listened(legacy_err);
    let zmq_refused = matches!(zmq_err.downcast_ref(), Some(ZmqError::Connect { .. }));
    let zmq_peer = legacy_err
        .downcast_ref::<ConnectError>()
        .is_some_and(|e| e.zmq_peer);
    if zmq_peer && legacy_port == zmq_port {
        // a ZeroMQ peer that is not the remote API: its error names what it is
        return zmq_err;
    }
    if !(refused && zmq_refused) {
        // something answered that speaks neither API: no simulator to wait for
        return connect_error(
            format!(
                "no CoppeliaSim remote API answered on {host}: legacy port {legacy_port}: {}; ZeroMQ port {zmq_port}: {}",
                one_line(legacy_err),
                one_line(&zmq_err)
            ),
            vec![format!(
                "something other than CoppeliaSim listens there: check --port (CoppeliaSim serves the legacy remote API on {LEGACY_PORT}, the ZeroMQ one on {ZMQ_PORT})"
            )],
        );
    }
    let ports = if legacy_port == zmq_port {
        socket_addr(host, legacy_port)
    } else {
        format!(
            "{} (legacy) nor {} (ZeroMQ)",
            socket_addr(host, legacy_port),
            socket_addr(host, zmq_port)
        )
    };
    let message = format!(
        "no CoppeliaSim remote API answered: nothing accepts connections on {ports} (tried for {} s)",
        seconds(wait)
    );
    let mut hints = Vec::new();
    match port {
        Some(p) if p != LEGACY_PORT && p != ZMQ_PORT => {
            hints.push(format!(
                "check --port: CoppeliaSim serves the legacy remote API on {LEGACY_PORT}, the ZeroMQ one on {ZMQ_PORT}"
            ));
            if let Ok(default) = self::zmq_port()
                && default != p
                && zmq_answers(host, default)
            {
                hints.push(format!(
                    "the ZeroMQ remote API answers on {}: pass --port {default}",
                    socket_addr(host, default)
                ));
            }
        }
        _ => {
            hints.push("is CoppeliaSim running? (up to 4.10 it serves the legacy remote API on 19997; from 4.3 the ZeroMQ add-on serves 23000)".into());
            hints.push(format!(
                "after a session it closed first, CoppeliaSim refuses legacy connections for about a minute; auto tried for {} s: if another program left so, pass --api legacy --connect-timeout {} to wait it out",
                seconds(wait),
                LEGACY_REFUSAL_WAIT.as_secs()
            ));
        }
    }
    connect_error(message, hints)
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

/// Where a failed legacy connection looks for the ZeroMQ remote API, for a hint.
#[derive(Clone, Copy)]
struct ZmqProbe {
    /// The ZeroMQ default port.
    port: u16,
    /// Whether the user gave `--port` (then the hint names the ZeroMQ port too).
    with_port: bool,
}

impl ZmqProbe {
    /// The options that reach the ZeroMQ remote API found there.
    fn option(self) -> String {
        if self.with_port {
            format!("--api zmq --port {}", self.port)
        } else {
            "--api zmq".into()
        }
    }
}

/// Connects to the legacy remote API at `host:port`, waiting out CoppeliaSim's one-minute
/// refusal when an earlier run left abruptly; `zmq_probe`: a failure looks whether the
/// ZeroMQ port answers, for a hint.
fn legacy<T: Opened>(
    host: &str,
    port: u16,
    timeout: Duration,
    connect_timeout: Option<Duration>,
    zmq_probe: Option<ZmqProbe>,
    stop: Option<&AtomicBool>,
) -> anyhow::Result<T> {
    let addr = socket_addr(host, port);
    let marker = SessionMarker::for_address(host, port);
    let earlier = marker.left_abruptly();
    let connect_timeout = connect_timeout.unwrap_or(if earlier.is_some() {
        LEGACY_REFUSAL_WAIT
    } else {
        LEGACY_CONNECT_TIMEOUT
    });
    super::say::note(format!(
        "connecting to CoppeliaSim's legacy remote API at {addr} ..."
    ));
    let opts = legacy::ClientOptions {
        connect_timeout,
        reply_timeout: timeout,
        ..Default::default()
    };
    let mut countdown = Countdown::default();
    let mut said_nothing_listens = false;
    let mut said_earlier = false;
    let result = legacy::Client::connect_with(addr.as_str(), opts, &mut |r| {
        if stop.is_some_and(|s| s.load(Ordering::SeqCst)) {
            return false;
        }
        if let Some(earlier) = &earlier {
            // said only once the port refuses: a simulator that restarted since answers at
            // once, and the earlier run is no cause then
            if !said_earlier {
                said_earlier = true;
                eprintln!(
                    "{} refuses ({}); an earlier vrep-maze run (process {}) ended with its session there open, and if CoppeliaSim closed it first it refuses connections for about a minute: waiting up to {} s (Ctrl-C to stop)",
                    super::escape::escaped(&addr),
                    r.why,
                    earlier.pid,
                    seconds(connect_timeout)
                );
            }
            countdown.retrying(r);
        } else if !said_nothing_listens && r.waited >= NOTHING_LISTENS_AFTER {
            said_nothing_listens = true;
            nothing_listens_note(host, port, r.why, zmq_probe, connect_timeout);
        }
        true
    });
    countdown.done();
    let error = match result {
        Ok(client) => return Ok(T::legacy(client, marker, &addr, timeout)),
        Err(e) => e,
    };
    Err(match error {
        ClientError::Stopped { waited, .. } => anyhow::Error::new(Interrupted(format!(
            "while connecting to {addr} (after {} s): nothing was changed",
            seconds(Duration::from_secs_f64(waited))
        ))),
        ClientError::Connect { why, waited, .. } => {
            if waited + 0.5 < connect_timeout.as_secs_f64() {
                // only a name that does not resolve fails before the deadline
                return Err(connect_error(
                    format!("cannot connect to {addr}: {why}"),
                    vec!["check --host: a name this machine resolves, or an IP address".into()],
                ));
            }
            if earlier.is_some() {
                // the minute is over: the refusal is not the cause any more
                marker.closed();
            }
            nothing_accepted(&why, host, port, connect_timeout, zmq_probe)
        }
        other => answered_wrongly(other, &addr, port),
    })
}

/// The error of a legacy connection to `host:port` that nothing accepted within
/// `connect_timeout` (`why`: the last attempt's failure), with hints: the port, the
/// minute of refusal, and the ZeroMQ remote API if `zmq_probe` finds it answering.
fn nothing_accepted(
    why: &str,
    host: &str,
    port: u16,
    connect_timeout: Duration,
    zmq_probe: Option<ZmqProbe>,
) -> anyhow::Error {
    let addr = socket_addr(host, port);
    let mut hints = vec![format!(
        "is CoppeliaSim running with the legacy remote API on port {port}? (CoppeliaSim up to 4.10 starts it on {LEGACY_PORT})"
    )];
    if connect_timeout < LEGACY_REFUSAL_WAIT {
        hints.push(format!(
            "after a session it closed first (a client that waits for the server to close after its last message, or one silent for 10 s) CoppeliaSim refuses every connection on its legacy port for about a minute; if another program left so, pass --connect-timeout {} to wait it out",
            LEGACY_REFUSAL_WAIT.as_secs()
        ));
    }
    if let Some(z) = zmq_probe.filter(|z| z.port != port)
        && zmq_answers(host, z.port)
    {
        hints.push(format!(
            "the ZeroMQ remote API answers on {}: try {}",
            socket_addr(host, z.port),
            z.option()
        ));
    }
    anyhow::Error::new(ConnectError {
        message: format!(
            "cannot connect to {addr}: nothing accepted a connection within {} s ({why})",
            seconds(connect_timeout)
        ),
        hints,
        nothing_listens: true,
        zmq_peer: false,
    })
}

/// The error of a legacy connection to `addr` (port `port`) that something answered
/// other than a free legacy remote API: the ZeroMQ one, another protocol, a busy server.
fn answered_wrongly(error: ClientError, addr: &str, port: u16) -> anyhow::Error {
    match error {
        ClientError::ZeroMqPeer { .. } => anyhow::Error::new(ConnectError {
            message: format!(
                "port {port} speaks the ZeroMQ remote API, not the legacy one: use --api zmq"
            ),
            hints: vec![],
            nothing_listens: false,
            zmq_peer: true,
        }),
        not @ ClientError::NotLegacy { .. } => connect_error(
            not.to_string(),
            vec![format!(
                "check --port: CoppeliaSim serves the legacy remote API on {LEGACY_PORT} unless its remoteApiConnections.txt says otherwise"
            )],
        ),
        busy @ ClientError::Busy { .. } => connect_error(
            busy.to_string(),
            vec![
                "close the other client (another vrep-maze, a script) or wait until it is done, then run again".into(),
                "a simulator waiting in a dialog does not answer either: close the dialog".into(),
            ],
        ),
        other => anyhow::Error::new(other).context(format!("legacy remote API at {addr}")),
    }
}

/// Says that nothing listens on `host:port` (`why`: the last attempt's failure), nor on
/// the ZeroMQ port if `zmq_probe` finds none there, and how long the tries go on.
fn nothing_listens_note(
    host: &str,
    port: u16,
    why: &str,
    zmq_probe: Option<ZmqProbe>,
    connect_timeout: Duration,
) {
    let addr = socket_addr(host, port);
    eprintln!(
        "nothing listens on {} ({}){}; trying until {} s",
        super::escape::escaped(&addr),
        why,
        if let Some(z) = zmq_probe.filter(|z| z.port != port)
            && !accepts_tcp(host, z.port)
        {
            format!(", nor on the ZeroMQ port {}", z.port)
        } else {
            String::new()
        },
        seconds(connect_timeout)
    );
}

/// Whether anything accepts a TCP connection on `host:port` within [`PROBE_TIMEOUT`].
fn accepts_tcp(host: &str, port: u16) -> bool {
    use std::net::ToSocketAddrs;
    (host.trim_matches(['[', ']']), port)
        .to_socket_addrs()
        .into_iter()
        .flatten()
        .any(|a| std::net::TcpStream::connect_timeout(&a, PROBE_TIMEOUT).is_ok())
}

fn zmq(
    host: &str,
    port: u16,
    timeout: Duration,
    connect_timeout: Duration,
    stop: Option<&AtomicBool>,
) -> anyhow::Result<Connected> {
    let first = ZmqBackend::first_calls();
    let (client, outcomes) = zmq_open(host, port, timeout, connect_timeout, &first, stop)?;
    let addr = socket_addr(host, port);
    let backend = ZmqBackend::with_first(client, timeout, outcomes)
        .with_context(|| format!("ZeroMQ remote API at {addr}"))?;
    let description = backend.describe();
    Ok(Connected {
        backend: Box::new(backend),
        description,
    })
}

/// Connects a raw ZeroMQ client to `host:port`, as [`zmq`] connects before it makes the
/// client a backend.
fn zmq_client(
    host: &str,
    port: u16,
    timeout: Duration,
    connect_timeout: Duration,
    stop: Option<&AtomicBool>,
) -> anyhow::Result<zmq_api::Client> {
    zmq_open(host, port, timeout, connect_timeout, &[], stop).map(|(client, _)| client)
}

/// Connects a ZeroMQ client to `host:port`, sending `calls` with the connection's own
/// (`zmq_api::Client::connect_with`: one main-loop pass for all), and says what it tries;
/// `stop` (Ctrl-C) ends its waits with [`Interrupted`].
fn zmq_open(
    host: &str,
    port: u16,
    timeout: Duration,
    connect_timeout: Duration,
    calls: &[(&str, Vec<ciborium::Value>)],
    stop: Option<&AtomicBool>,
) -> anyhow::Result<(zmq_api::Client, Vec<zmq_api::Outcome>)> {
    super::say::note(format!(
        "connecting to CoppeliaSim's ZeroMQ remote API at {} ...",
        socket_addr(host, port)
    ));
    let options = zmq_api::ClientOptions {
        host: host.to_string(),
        port,
        timeout,
        connect_timeout: Some(connect_timeout),
        protocol: None,
    };
    zmq_api::Client::connect_until(&options, calls, stop)
        .map_err(|e| zmq_connect_error(e, host, port))
}

/// A failed ZeroMQ connection to `host:port` as one line and its hints: a port that speaks
/// the legacy API is named as such.
fn zmq_connect_error(error: ZmqError, host: &str, port: u16) -> anyhow::Error {
    let addr = socket_addr(host, port);
    match error {
        ZmqError::Stopped { .. } => anyhow::Error::new(Interrupted(format!(
            "while connecting to {addr}: nothing was changed"
        ))),
        e @ ZmqError::NotZeroMq { .. } => {
            if legacy_answers(&addr) {
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
            }
        }
        ZmqError::NotRemoteApi {
            ref socket_type, ..
        } => {
            // 4.3 to 4.5 publish the step count on the remote API's port plus one
            let below = port.checked_sub(1).filter(|_| socket_type == "PUB");
            let hint = match below {
                Some(rpc) if zmq_answers(host, rpc) => format!(
                    "the ZeroMQ remote API answers on {}: use --port {rpc} (CoppeliaSim 4.3 to 4.5 publish the simulation step on the port above it, {port})",
                    socket_addr(host, rpc)
                ),
                Some(rpc) => format!(
                    "CoppeliaSim 4.3 to 4.5 publish the simulation step on the port above the remote API's: is the remote API on {rpc}? (its default is {ZMQ_PORT})"
                ),
                None => format!(
                    "is port {port} CoppeliaSim's ZeroMQ remote API? (the add-on serves {ZMQ_PORT} from CoppeliaSim 4.3)"
                ),
            };
            connect_error(error.to_string(), vec![hint])
        }
        e @ ZmqError::Connect { .. } => anyhow::Error::new(e),
        e @ ZmqError::Resolve { .. } => connect_error(
            e.to_string(),
            vec!["check --host: a name this machine resolves, or an IP address".into()],
        ),
        e => anyhow::Error::new(e).context(format!("ZeroMQ remote API at {addr}")),
    }
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
                "{what}; retrying for {} s more — CoppeliaSim refuses connections for about a minute after a session it closed first (Ctrl-C to stop)",
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
        assert_eq!(
            super::super::usage::hints(&error),
            ["wait", "try --api zmq"]
        );
    }

    #[test]
    fn seconds_read_as_written_and_addresses_bracket_ipv6() {
        assert_eq!(seconds(LEGACY_REFUSAL_WAIT), "75");
        assert_eq!(seconds(Duration::from_millis(300)), "0.3");
        assert_eq!(seconds(AUTO_LEGACY_WAIT), "1.5");
        assert_eq!(socket_addr("::1", 19997), "[::1]:19997");
        assert_eq!(socket_addr("localhost", 23000), "localhost:23000");
    }
}
