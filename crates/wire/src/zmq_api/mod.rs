//! The ZeroMQ remote API's codec (port 23000, CoppeliaSim 4.3 and later): [`cbor`] (values),
//! [`message`] (the request and reply maps of both protocol generations) and [`calls`]
//! (several calls as one Lua program), shared by our
//! client (`vrep_maze_client::zmq_api`) and our emulator (`vrep_maze_emulator::zmq_api`).

pub mod calls;
pub mod cbor;
pub mod message;

pub use message::Protocol;
