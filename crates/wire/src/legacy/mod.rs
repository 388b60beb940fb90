//! The legacy remote API's codec (port 19997): [`wire`] (packets, message header, command
//! blocks) and [`command`] (command IDs and payloads), shared by our client
//! (`vrep_maze_client::legacy`) and our emulator (`vrep_maze_emulator::legacy`).

pub mod command;
pub mod wire;
