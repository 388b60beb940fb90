//! What the integration tests share: the binary and its `serve` child ([`cli`]), mazes to
//! draw ([`layouts`]), the three emulated backends ([`backend`]), a cutting proxy
//! ([`proxy`]) and the real CoppeliaSim of `../shared/coppeliasim/` ([`real_sim`]).

pub mod backend;
pub mod cli;
pub mod layouts;
pub mod proxy;
#[path = "../../common/real_sim.rs"]
pub mod real_sim;

pub use cli::bin;
pub use layouts::course_layout;

/// Instantiates each backend-neutral scenario `fn scenario(kind: Kind)` once per backend,
/// as `scenario::legacy`, `scenario::zmq1` and `scenario::zmq2`, so a failure names the
/// backend (and `cargo test --test it zmq1` runs one backend).
macro_rules! backend_tests {
    ($($scenario:ident),+ $(,)?) => {$(
        mod $scenario {
            use crate::support::backend::Kind;

            #[test]
            fn legacy() {
                super::$scenario(Kind::Legacy)
            }

            #[test]
            fn zmq1() {
                super::$scenario(Kind::Zmq1)
            }

            #[test]
            fn zmq2() {
                super::$scenario(Kind::Zmq2)
            }
        }
    )+};
}
pub(crate) use backend_tests;
