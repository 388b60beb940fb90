//! What a graded run gives Python: the report as the `--json` dict, the trajectory as a
//! NumPy array (`score`, `Session.score`, `Session.drive`, `Layout.grade`).

use numpy::PyArray2;
use numpy::ndarray::Array2;
use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use vrep_maze::cli::reports::ScoreJson;
use vrep_maze::score::{Report, Sample};

/// The report as `--json` writes it (with its `hints`), as a Python dict.
pub fn report_dict<'py>(py: Python<'py>, report: &Report) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(&ScoreJson::of(report))
        .map_err(|e| PyRuntimeError::new_err(format!("the report: {e}")))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// The samples as an `N x 4` array of `t, x, y, yaw`.
pub fn samples_array<'py>(
    py: Python<'py>,
    samples: &[Sample],
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let flat: Vec<f64> = samples
        .iter()
        .flat_map(|s| [s.t, s.x, s.y, s.yaw])
        .collect();
    let array = Array2::from_shape_vec((samples.len(), 4), flat)
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    Ok(PyArray2::from_owned_array(py, array))
}
