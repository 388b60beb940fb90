//! CoppeliaSim's legacy remote API (port 19997): wire format, command set, a native client,
//! a protocol-faithful server over [`crate::sim`], and the drawing backend.
//!
//! Layers: [`wire`] (packets, message header, command blocks) → [`command`] (command IDs and
//! payloads) → [`client`] / [`server`] → [`backend`] (the [`crate::draw::Backend`] implementation).

pub mod backend;
pub mod client;
pub mod command;
pub mod server;
pub mod wire;

pub use backend::LegacyBackend;
pub use client::{Client, ClientError, ClientOptions, Reply};
pub use server::{ServerConfig, ServerHandle, spawn};
