//! CoppeliaSim's legacy remote API (port 19997): wire format, command set, a native client
//! with its drawing backend, and an emulator of the server over [`crate::sim`].
//!
//! Layers: [`wire`] (packets, message header, command blocks) → [`command`] (command IDs and
//! payloads), then on one side [`client`] → [`backend`] (the [`crate::draw::Backend`]
//! implementation), on the other [`server`]. The two sides share only `wire`, `command` and
//! [`crate::coppelia`]'s numbers: the client never imports the emulator, nor the emulator
//! the client.

pub mod backend;
pub mod client;
pub mod command;
pub mod server;
pub mod wire;

pub use backend::LegacyBackend;
pub use client::{Client, ClientError, ClientOptions, Reply};
pub use server::{ServerConfig, ServerHandle, spawn};

#[cfg(test)]
mod tests {
    /// The path segments named by the `use` declarations of a source file.
    fn imported_names(source: &str) -> Vec<&str> {
        let mut names = vec![];
        let mut in_use = false;
        for line in source.lines().map(str::trim) {
            in_use |= line.starts_with("use ") || line.starts_with("pub use ");
            if in_use {
                names.extend(
                    line.split(|c: char| !(c.is_alphanumeric() || c == '_'))
                        .filter(|w| !w.is_empty()),
                );
                in_use = !line.ends_with(';');
            }
        }
        names
    }

    #[test]
    fn client_side_and_emulator_do_not_import_each_other() {
        let client_side = [include_str!("client.rs"), include_str!("backend.rs")];
        for name in client_side.iter().flat_map(|s| imported_names(s)) {
            assert!(
                name != "server" && name != "sim",
                "the client side imports the emulator ({name})"
            );
        }
        let emulator = [
            include_str!("server/mod.rs"),
            include_str!("server/transport.rs"),
            include_str!("server/main_loop.rs"),
            include_str!("server/execute.rs"),
        ];
        for name in emulator.iter().flat_map(|s| imported_names(s)) {
            assert!(
                name != "client" && name != "backend",
                "the emulator imports the client side ({name})"
            );
        }
    }
}
