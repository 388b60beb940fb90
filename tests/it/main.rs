//! The integration tests, one binary (`cargo test --test it`; filter by module, e.g.
//! `cargo test --test it interrupt` or `cargo test --test it zmq2`): linking the crate once
//! instead of once per file. `support` holds what the topics share.

mod support;

mod architecture;
mod batch_where;
mod cli;
mod cli_fuzz;
mod cli_legacy;
mod cli_zmq;
mod completion;
mod connect;
mod copy_record;
mod costs;
mod ctrl_c;
mod draw;
mod export_golden;
mod export_lists;
mod export_model_load;
mod export_pointmaze;
mod export_robots;
mod export_ros;
mod first_hour;
mod generation_gate;
mod generators;
mod golden;
mod hints;
mod inspect;
mod interrupt;
mod legacy_client_server;
mod legacy_draw;
mod mesh_draw;
mod messages;
mod permissions;
mod properties;
mod readme;
mod render_controls;
mod robot_fit;
mod robot_real;
mod scenarios;
mod schema;
mod score;
mod score_cli;
mod session;
mod signals;
mod solve;
mod texture;
mod time_wait;
mod trust;
mod trust_draw;
mod trust_ours;
mod validate;
mod walls;
mod zmq_client_server;
mod zmq_concurrency;
mod zmq_draw;
