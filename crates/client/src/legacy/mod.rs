//! CoppeliaSim's legacy remote API (port 19997), the client's side: wire format and command
//! set (`vrep_maze_wire::legacy`, re-exported here), a native client with its drawing backend,
//! and the robot follower. The emulated server is in the emulator crate
//! (`vrep_maze_emulator::legacy`).
//!
//! Layers: [`wire`] (packets, message header, command blocks) → [`command`] (command IDs and
//! payloads), then on one side [`client`] → [`backend`] (the [`crate::draw::backend::Backend`]
//! implementation), on the other the emulator's `server`. The two sides share only `wire`,
//! `command` and [`vrep_maze_core::coppelia`]'s numbers: the client never imports the
//! emulator, nor the emulator the client.

pub mod backend;
pub mod client;
pub mod follow;
mod quick_ack;

pub use vrep_maze_wire::legacy::{command, wire};

pub use backend::LegacyBackend;
pub use client::{Client, ClientError, ClientOptions, Reply};
