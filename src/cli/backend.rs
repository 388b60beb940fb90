//! Choosing the remote API for `apply` and `clear`: legacy (port 19997), ZeroMQ (port 23000),
//! or auto (try legacy, then ZeroMQ, and say which answered).

use std::time::Duration;

use anyhow::Context;

use crate::draw::Scene;
use crate::legacy::LegacyScene;
use crate::zmq_api::{ClientOptions, ZmqScene};

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

/// A connected scene over either API.
pub enum Backend {
    /// Legacy remote API.
    Legacy(LegacyScene),
    /// ZeroMQ remote API.
    Zmq(ZmqScene),
}

impl Backend {
    /// Connects as `api` says. `port` overrides the API's default (not allowed with auto).
    pub fn connect(
        api: Api,
        host: &str,
        port: Option<u16>,
        timeout: Duration,
    ) -> anyhow::Result<Backend> {
        match api {
            Api::Legacy => {
                let port = port.unwrap_or(LEGACY_PORT);
                let scene = LegacyScene::connect(host, port, timeout).with_context(|| {
                    format!("connecting to CoppeliaSim's legacy remote API at {host}:{port}")
                })?;
                Ok(Backend::Legacy(scene))
            }
            Api::Zmq => {
                let port = port.unwrap_or(ZMQ_PORT);
                let options = ClientOptions {
                    host: host.to_string(),
                    port,
                    timeout,
                    protocol: None,
                };
                let scene = ZmqScene::connect(&options).with_context(|| {
                    format!("connecting to CoppeliaSim's ZeroMQ remote API at {host}:{port}")
                })?;
                Ok(Backend::Zmq(scene))
            }
            Api::Auto => {
                anyhow::ensure!(
                    port.is_none(),
                    "--port needs --api legacy or --api zmq (auto tries {LEGACY_PORT}, then {ZMQ_PORT})"
                );
                let legacy = Backend::connect(
                    Api::Legacy,
                    host,
                    None,
                    timeout.min(Duration::from_millis(1500)),
                );
                let legacy_err = match legacy {
                    Ok(b) => return Ok(b),
                    Err(e) => e,
                };
                Backend::connect(Api::Zmq, host, None, timeout).map_err(|zmq_err| {
                    anyhow::anyhow!(
                        "no CoppeliaSim remote API answered on {host}: legacy port {LEGACY_PORT}: {}; ZeroMQ port {ZMQ_PORT}: {}",
                        one_line(&legacy_err),
                        one_line(&zmq_err)
                    )
                })
            }
        }
    }

    /// The scene operations.
    pub fn scene(&mut self) -> &mut dyn Scene {
        match self {
            Backend::Legacy(s) => s,
            Backend::Zmq(s) => s,
        }
    }

    /// The ZeroMQ scene, if that is the API in use.
    pub fn zmq(&mut self) -> Option<&mut ZmqScene> {
        match self {
            Backend::Zmq(s) => Some(s),
            Backend::Legacy(_) => None,
        }
    }

    /// One line saying which API is in use.
    pub fn describe(&self) -> String {
        match self {
            Backend::Legacy(_) => format!("legacy remote API (port {LEGACY_PORT} by default)"),
            Backend::Zmq(s) => {
                let v = s.version();
                let protocol = s
                    .client()
                    .protocol()
                    .map(|p| p.to_string())
                    .unwrap_or_else(|| "?".into());
                format!(
                    "ZeroMQ remote API at {}, protocol {protocol}, CoppeliaSim {}.{}.{}",
                    s.client().endpoint(),
                    v / 10000,
                    v / 100 % 100,
                    v % 100
                )
            }
        }
    }

    /// Closes the connection cleanly.
    pub fn close(self) {
        match self {
            Backend::Legacy(s) => {
                let _ = s.close();
            }
            Backend::Zmq(s) => drop(s),
        }
    }
}

fn one_line(e: &anyhow::Error) -> String {
    format!("{e:#}").replace('\n', " ")
}
