//! `score`: following a robot while the simulation runs and grading its run, as
//! `vrep-maze score` does, with the report as a dict and the trajectory as a NumPy array.
//!
//! Ctrl-C: while connecting, `KeyboardInterrupt` at once; once connected, the first stops
//! following at the next look (the simulation stopped if `start_simulation=True` started it,
//! the connection closed) and raises `Interrupted` carrying the partial `report` and
//! `trajectory`; a second raises `KeyboardInterrupt` at once.

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use numpy::PyArray2;
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use vrep_maze::cli::Command;

use crate::errors;
use crate::layout::Layout;
use crate::options;
use crate::reports::{report_dict, samples_array};
use crate::worker::{self, OnSignal};

/// Follows the robot while the simulation runs and grades its run through `layout`, as
/// `vrep-maze score` does.
///
/// Keywords are `score`'s options: `robot="Robot"`, the connection keywords of `apply`
/// (`api`, `host`, `port`, `floor`, `connect_timeout`, `reply_timeout`, ...),
/// `start_simulation`, `timeout` (wall seconds for the whole run), `until="end"` or
/// `"stop"`, `robot_radius`, `end_size`. Returns `(report, trajectory)`: the report as a
/// dict (the `--json` object, `report["complete"]` is `False` for a run that ended early)
/// and the samples as an `N x 4` float array of `t, x, y, yaw`. No robot of that name, or a
/// simulation that does not start within `timeout`, raises `SimulatorError`; a refused
/// option `ValueError`. Ctrl-C raises `Interrupted` with `.report` and `.trajectory` of the
/// partial run.
#[pyfunction]
#[pyo3(signature = (layout, robot=None, api=None, host=None, port=None, **options))]
pub fn score<'py>(
    py: Python<'py>,
    layout: &Layout,
    robot: Option<Bound<'py, PyAny>>,
    api: Option<Bound<'py, PyAny>>,
    host: Option<Bound<'py, PyAny>>,
    port: Option<Bound<'py, PyAny>>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyArray2<f64>>)> {
    let options = options::with(
        options,
        py,
        &[
            ("robot", robot),
            ("api", api),
            ("host", host),
            ("port", port),
        ],
    )?;
    let argv = options::command_line("score", &["-"], &options)?;
    let Command::Score(args) = options::parse(argv)? else {
        return Err(PyRuntimeError::new_err("score parsed as another command"));
    };
    let requested = Arc::new(AtomicBool::new(false));
    let connected = Arc::new(AtomicBool::new(false));
    let layout = layout.layout.clone();
    let job = {
        let (requested, connected) = (requested.clone(), connected.clone());
        move || args.score(&layout, requested, &connected)
    };
    let mut pending = None;
    let scored = worker::run(py, job, |raised| {
        if !connected.load(Ordering::SeqCst) || requested.swap(true, Ordering::SeqCst) {
            requested.store(true, Ordering::SeqCst);
            return OnSignal::Raise(raised);
        }
        eprintln!(
            "\ninterrupted: ending the run at the next look (press Ctrl-C again to stop at once)"
        );
        pending = Some(raised);
        OnSignal::Wait
    })?
    .map_err(|e| errors::from_anyhow(py, &e))?;
    let report = report_dict(py, &scored.report)?;
    let trajectory = samples_array(py, &scored.samples)?;
    if pending.is_some() {
        return Err(stopped_run(py, scored.samples.len(), report, trajectory)?);
    }
    Ok((report, trajectory))
}

/// The `Interrupted` of a run ended by Ctrl-C after `samples` samples, carrying the partial
/// `report` and `trajectory`.
pub(crate) fn stopped_run<'py>(
    py: Python<'py>,
    samples: usize,
    report: Bound<'py, PyAny>,
    trajectory: Bound<'py, PyArray2<f64>>,
) -> PyResult<PyErr> {
    let err = errors::interrupted(
        py,
        format!(
            "interrupted: the run was followed for {samples} samples; the partial report and trajectory are in .report and .trajectory"
        ),
        None,
    );
    let value = err.value(py);
    value.setattr("report", &report)?;
    value.setattr("trajectory", &trajectory)?;
    Ok(err)
}
