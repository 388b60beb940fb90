//! Choosing the remote API for `apply` and `clear`: legacy (port 19997), ZeroMQ (port 23000),
//! or auto (try legacy, then ZeroMQ, and say which answered).

use std::time::Duration;

use anyhow::Context;

use super::ensure_usage;

use super::one_line;
use crate::draw::Backend;
use crate::legacy::LegacyBackend;
use crate::zmq_api::{ClientOptions, ZmqBackend};

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

/// Connects as `api` says. `port` overrides the API's default (not allowed with auto).
pub fn connect(
    api: Api,
    host: &str,
    port: Option<u16>,
    timeout: Duration,
) -> anyhow::Result<Box<dyn Backend>> {
    match api {
        Api::Legacy => {
            let port = port.unwrap_or(LEGACY_PORT);
            let backend = LegacyBackend::connect(host, port, timeout).with_context(|| {
                format!("connecting to CoppeliaSim's legacy remote API at {host}:{port}")
            })?;
            Ok(Box::new(backend))
        }
        Api::Zmq => {
            let port = port.unwrap_or(ZMQ_PORT);
            let options = ClientOptions {
                host: host.to_string(),
                port,
                timeout,
                protocol: None,
            };
            let backend = ZmqBackend::connect(&options).with_context(|| {
                format!("connecting to CoppeliaSim's ZeroMQ remote API at {host}:{port}")
            })?;
            Ok(Box::new(backend))
        }
        Api::Auto => {
            ensure_usage!(
                port.is_none(),
                "--port needs --api legacy or --api zmq (auto tries {LEGACY_PORT}, then {ZMQ_PORT})"
            );
            let legacy_err = match connect(
                Api::Legacy,
                host,
                None,
                timeout.min(Duration::from_millis(1500)),
            ) {
                Ok(b) => return Ok(b),
                Err(e) => e,
            };
            connect(Api::Zmq, host, None, timeout).map_err(|zmq_err| {
                anyhow::anyhow!(
                    "no CoppeliaSim remote API answered on {host}: legacy port {LEGACY_PORT}: {}; ZeroMQ port {ZMQ_PORT}: {}",
                    one_line(&legacy_err),
                    one_line(&zmq_err)
                )
            })
        }
    }
}
