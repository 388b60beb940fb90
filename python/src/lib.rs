//! `vrep_maze._vrep_maze`: the Python bindings of the `vrep_maze` library.
//!
//! Every option goes through the command line's own parser (`options`), so a keyword argument
//! means and refuses exactly what the `vrep-maze` option of the same name does, with the same
//! message. Long work (generating, drawing, rendering) runs without the GIL; generating and
//! drawing run on a worker thread while the calling thread watches Python's signals, so
//! Ctrl-C works as in the command line (`worker`). The pure-Python package `vrep_maze`
//! (`python/vrep_maze/`) re-exports what is defined here.

mod batch;
mod cli;
mod draw;
mod errors;
mod layout;
mod options;
mod remedies;
mod reports;
mod robot_link;
mod score;
mod session;
mod wording;
mod worker;

use pyo3::prelude::*;

/// The extension module, `vrep_maze._vrep_maze`.
#[pymodule]
fn _vrep_maze(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(layout::generate, m)?)?;
    m.add_function(wrap_pyfunction!(layout::load, m)?)?;
    m.add_function(wrap_pyfunction!(draw::apply, m)?)?;
    m.add_function(wrap_pyfunction!(draw::clear, m)?)?;
    m.add_function(wrap_pyfunction!(session::connect, m)?)?;
    m.add_function(wrap_pyfunction!(batch::batch, m)?)?;
    m.add_function(wrap_pyfunction!(score::score, m)?)?;
    m.add_function(wrap_pyfunction!(cli::main, m)?)?;
    m.add_class::<layout::Layout>()?;
    m.add_class::<draw::ApplyReport>()?;
    m.add_class::<draw::ClearReport>()?;
    m.add_class::<session::Session>()?;
    m.add_class::<robot_link::RobotLink>()?;
    m.add_class::<batch::Batch>()?;
    m.add("ValidationError", py.get_type::<errors::ValidationError>())?;
    m.add("SimulatorError", py.get_type::<errors::SimulatorError>())?;
    m.add("Interrupted", py.get_type::<errors::Interrupted>())?;
    Ok(())
}
