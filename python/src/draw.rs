//! `apply` and `clear`: drawing into CoppeliaSim as `vrep-maze apply` and `vrep-maze clear`
//! do, over the same connection code and the same `draw` functions, with their reports as
//! Python objects.
//!
//! Ctrl-C: the first stops the drawing after the request in flight (the idle rate restored,
//! the connection closed cleanly) and raises `Interrupted`; while still connecting, or at a
//! second Ctrl-C, `KeyboardInterrupt` is raised at once and the worker thread ends on its own
//! (it stops at its next request, or closes the connection it was making).

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use anyhow::Context;
use pyo3::exceptions::{PyAttributeError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use vrep_maze::cli::Command;
use vrep_maze::cli::reports::ApplyCounts;
use vrep_maze::draw::run::Authored;
use vrep_maze::draw::{self, Backend, DrawError, RunError};

use crate::errors;
use crate::layout::Layout;
use crate::options;
use crate::worker::{self, OnSignal};

/// What `apply` did: the numbers `vrep-maze apply` prints. `str(report)` is its line.
///
/// The counts (`lines`, `posts`, `reused`, `pasted`, `removed`, `removed_meshes`,
/// `unchanged`, `placed`, `placed_unread`, `markers_unchanged`, `markers_placed`,
/// `nothing_to_do`, `edits`, `round_trips`) are the command line's own type
/// ([`ApplyCounts`]), read by name as `vrep-maze apply --json` names them.
#[pyclass(frozen, module = "vrep_maze")]
pub struct ApplyReport {
    /// The counts, as the `--json` document has them.
    counts: ApplyCounts,
    /// `draw="mesh"`: the meshes the maze is drawn as (`lines` and `posts` then count
    /// straight runs and posts, `reused` meshes kept, `pasted` meshes created); 0 for copies.
    #[pyo3(get)]
    meshes: usize,
    /// What the user should know (a marker larger than a cell, a size not read, a template
    /// standing on the maze): the `warning:` lines of `vrep-maze apply`.
    #[pyo3(get)]
    warnings: Vec<String>,
    /// The user's objects under the maze dummy (no copies of a template): left alone.
    #[pyo3(get)]
    left_alone: Vec<String>,
    /// Wall time, seconds.
    #[pyo3(get)]
    elapsed: f64,
    /// The simulation was running and `stop_simulation=True` stopped it first.
    #[pyo3(get)]
    stopped_simulation: bool,
    /// `dry_run=True`: nothing was changed.
    #[pyo3(get)]
    dry_run: bool,
    /// Every line, start and end was read back in place (always, unless a dry run).
    #[pyo3(get)]
    verified: bool,
    /// Objects `create_missing=True` created.
    #[pyo3(get)]
    created: Vec<String>,
    /// Where `save_scene` saved the scene (on the simulator's machine), if asked.
    #[pyo3(get)]
    saved_scene: Option<String>,
    /// The line `vrep-maze apply` prints.
    #[pyo3(get)]
    summary: String,
}

#[pymethods]
impl ApplyReport {
    fn __str__(&self) -> &str {
        &self.summary
    }

    fn __repr__(&self) -> String {
        format!("<ApplyReport {}>", self.summary)
    }

    /// A count by its name in [`ApplyCounts`] (`report.lines`, `report.placed_unread`, ...).
    fn __getattr__<'py>(&self, py: Python<'py>, name: &str) -> PyResult<Bound<'py, PyAny>> {
        let counts = serde_json::to_value(&self.counts)
            .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
        match counts.get(name) {
            Some(serde_json::Value::Bool(b)) => Ok(b.into_pyobject(py)?.to_owned().into_any()),
            Some(serde_json::Value::Number(n)) => {
                let n = n.as_u64().unwrap_or_default();
                Ok(n.into_pyobject(py)?.into_any())
            }
            _ => Err(PyAttributeError::new_err(format!(
                "'ApplyReport' object has no attribute '{name}'"
            ))),
        }
    }
}

impl From<Drawn> for ApplyReport {
    /// The report of a whole apply ([`Drawn::report`]).
    fn from(drawn: Drawn) -> ApplyReport {
        drawn.report.into()
    }
}

impl From<draw::Report> for ApplyReport {
    /// The report of a whole apply, with the command line's line.
    fn from(done: draw::Report) -> ApplyReport {
        let draw::Report {
            created,
            drawn: report,
            saved_scene,
        } = done;
        ApplyReport {
            counts: ApplyCounts::of(&report),
            meshes: report.meshes,
            warnings: report.warnings.clone(),
            left_alone: report.left_alone.clone(),
            elapsed: report.elapsed.as_secs_f64(),
            stopped_simulation: report.stopped_simulation,
            dry_run: report.dry_run,
            verified: !report.dry_run,
            created,
            saved_scene,
            summary: vrep_maze::cli::summary::apply_line(&report),
        }
    }
}

/// What `clear` did. `str(report)` is what `vrep-maze clear` prints.
#[pyclass(frozen, get_all, module = "vrep_maze")]
pub struct ClearReport {
    /// Names of the copies of the templates removed (or, in a dry run, that would be).
    removed: Vec<String>,
    /// Names of a mesh maze's objects removed (`draw="mesh"`): its meshes, then their
    /// holder `MazeMeshes`.
    removed_meshes: Vec<String>,
    /// Messages exchanged with the simulator.
    round_trips: usize,
    /// The idle rate restored (an interrupted `apply` had left it at 0), if it was.
    restored_idle_fps: Option<i32>,
    /// The simulation was running and `stop_simulation=True` stopped it first.
    stopped_simulation: bool,
    /// `dry_run=True`: nothing was changed.
    dry_run: bool,
    /// The user's objects under the maze dummy (no copies of a template): left alone.
    left_alone: Vec<String>,
    /// Where the line template went (one line), if it moved (or, a dry run, would): back
    /// where it stood before the first `apply`, or below the floor.
    template: Option<String>,
    /// Where `Start` and `End` went (one line): back where they stood before the first
    /// `apply`, or left where they are (no record of that).
    markers: Option<String>,
    /// Warnings (the simulator did not keep the scene's signals).
    warnings: Vec<String>,
    /// The lines `vrep-maze clear` prints.
    summary: String,
}

#[pymethods]
impl ClearReport {
    fn __str__(&self) -> &str {
        &self.summary
    }

    fn __repr__(&self) -> String {
        let verb = if self.dry_run {
            "would remove"
        } else {
            "removed"
        };
        let meshes = self
            .removed_meshes
            .iter()
            .filter(|n| *n != vrep_maze::draw::mesh::HOLDER)
            .count();
        format!(
            "<ClearReport {verb} {} maze cop{} and {meshes} mesh(es); {} round trip(s)>",
            self.removed.len(),
            if self.removed.len() == 1 { "y" } else { "ies" },
            self.round_trips
        )
    }
}

impl ClearReport {
    /// The report of a clear (`dry_run` as asked) under the maze dummy `parent`.
    pub(crate) fn of(report: draw::ClearReport, dry_run: bool, parent: &str) -> ClearReport {
        let summary = vrep_maze::cli::summary::clear_lines(&report, parent, dry_run, |m| {
            m.worded(&crate::wording::Keywords)
        })
        .join("\n");
        ClearReport {
            removed: report.removed,
            removed_meshes: report.removed_meshes,
            round_trips: report.round_trips,
            restored_idle_fps: report.restored_idle_fps,
            stopped_simulation: report.stopped_simulation,
            dry_run,
            left_alone: report.left_alone,
            template: report.template,
            markers: report.markers,
            warnings: report.warnings,
            summary,
        }
    }
}

/// How a drawing job ended, short of an error.
pub(crate) enum Finished<T> {
    /// It did the whole job.
    Done(T),
    /// Ctrl-C stopped it cleanly: what the command line says, and (apply) lines placed of
    /// all.
    Stopped {
        message: String,
        counts: Option<(usize, usize)>,
    },
    /// Ctrl-C ended it early with a partial result, which the caller raises with (a
    /// session's `score`).
    Partial(T),
}

/// A whole apply's report, with what an interrupt counts in it: a Ctrl-C that came after
/// the last request, too late to stop the drawing, raises `Interrupted` with every piece
/// placed ([`Drawn::late`]), as an earlier one raises it with the pieces placed so far.
pub(crate) struct Drawn {
    /// What `draw::run` reported.
    pub(crate) report: draw::Report,
    /// The pieces of the drawing (an interrupt's `total`).
    pub(crate) total: usize,
    /// What they are ("copies", "line runs": [`vrep_maze::cli::summary::interrupted_counts`]).
    pub(crate) counts: String,
}

impl Drawn {
    /// The `Interrupted` message and counts for a Ctrl-C that came once the maze was drawn
    /// (all of it placed; none in a dry run, which changed nothing).
    pub(crate) fn late(&self) -> Option<(String, Option<(usize, usize)>)> {
        let (total, counts) = (self.total, &self.counts);
        Some(if self.report.drawn.dry_run {
            (
                format!(
                    "interrupted after the dry run: 0 of {total} {counts}; nothing was changed"
                ),
                Some((0, total)),
            )
        } else {
            (
                format!(
                    "interrupted after the maze was drawn and verified: {total} of {total} {counts}; the idle rate is restored"
                ),
                Some((total, total)),
            )
        })
    }
}

/// What a connection job needs to know about Ctrl-C.
#[derive(Default)]
pub(crate) struct Stop {
    /// Set at the first Ctrl-C: the job stops after the request in flight.
    pub(crate) requested: Arc<AtomicBool>,
    /// Set once the connection is made (before that, Ctrl-C raises at once).
    pub(crate) connected: Arc<AtomicBool>,
}

/// Runs a drawing `job` on a worker thread with Ctrl-C handled as the command line handles
/// it, and turns its outcome into the Python result; a Ctrl-C the job finished before it
/// saw raises `KeyboardInterrupt`.
pub(crate) fn run_drawing<T: Send + 'static, R>(
    py: Python<'_>,
    stop: &Stop,
    job: impl FnOnce() -> anyhow::Result<Finished<T>> + Send + 'static,
    report: impl FnOnce(T) -> R,
) -> PyResult<R> {
    run_drawing_late(py, stop, job, report, |_| None)
}

/// [`run_drawing`], where a Ctrl-C the job finished before it saw (it came after the last
/// request) raises `Interrupted` with the message and counts `late` gives for what the job
/// did, or `KeyboardInterrupt` where `late` gives none.
pub(crate) fn run_drawing_late<T: Send + 'static, R>(
    py: Python<'_>,
    stop: &Stop,
    job: impl FnOnce() -> anyhow::Result<Finished<T>> + Send + 'static,
    report: impl FnOnce(T) -> R,
    late: impl FnOnce(&T) -> Option<(String, Option<(usize, usize)>)>,
) -> PyResult<R> {
    let mut pending = None;
    let finished = worker::run(py, job, |raised| {
        if !stop.connected.load(Ordering::SeqCst) || stop.requested.swap(true, Ordering::SeqCst) {
            // nothing drawn yet, or a second Ctrl-C: stop at once
            stop.requested.store(true, Ordering::SeqCst);
            return OnSignal::Raise(raised);
        }
        eprintln!(
            "\ninterrupted: finishing what is in flight (press Ctrl-C again to stop at once)"
        );
        pending = Some(raised);
        OnSignal::Wait
    })?;
    match (finished.map_err(|e| errors::from_anyhow(py, &e))?, pending) {
        (Finished::Stopped { message, counts }, _) => Err(errors::interrupted(py, message, counts)),
        // the job ended before it saw the Ctrl-C: the script stops all the same, as an
        // earlier Ctrl-C stops it where the job says what it did
        (Finished::Done(done), Some(ctrl_c)) => Err(match late(&done) {
            Some((message, counts)) => errors::interrupted(py, message, counts),
            None => ctrl_c,
        }),
        (Finished::Done(done), None) | (Finished::Partial(done), _) => Ok(report(done)),
    }
}

/// How a `clear` ended: an interrupt is a clean stop, said as the command line says it.
pub(crate) fn cleared(
    result: Result<draw::ClearReport, DrawError>,
) -> anyhow::Result<Finished<draw::ClearReport>> {
    match result {
        Err(DrawError::Interrupted { placed, total }) => Ok(Finished::Stopped {
            message: vrep_maze::cli::summary::clear_interrupted(placed, total),
            counts: None,
        }),
        other => Ok(Finished::Done(other?)),
    }
}

/// Draws `layout` into CoppeliaSim as `vrep-maze apply` does and verifies it.
///
/// Every option of `apply` is a keyword: `api="auto"` (the default: port 19997 with the
/// legacy API, else 23000 with ZeroMQ), `"legacy"` or `"zmq"`; `host="127.0.0.1"`; `port`; the scene's object names
/// `floor="Floor"`, `parent="Maze"`, `line="Line"`, `start="Start"`, `end="End"`;
/// `connect_timeout` and `timeout` (seconds); `stop_simulation`, `while_running` (draw
/// into a running simulation: the maze lasts until it stops), `dry_run`,
/// `create_missing` (ZeroMQ only) as `True`/`False`; `save_scene="/path/maze.ttt"`
/// (ZeroMQ only); `draw="copies"` (the default: one copy of the template per line) or
/// `"mesh"` (a few mesh shapes, one rectangle or box per straight run; ZeroMQ creates them,
/// the legacy API loads them as an XML model); `robot="Robot"` and `robot_width` (metres,
/// else read from the scene's robot) for the warning, in `report.warnings`, of a robot that
/// does not fit the passages. Returns an `ApplyReport`. A refused option raises `ValueError`, a
/// simulator that does not answer or refuses `SimulatorError` (with the command line's
/// hints in `.hints`). Drawing runs without the GIL; Ctrl-C stops after the request in
/// flight, restores the idle rate, closes the connection and raises `Interrupted` (running
/// the same call again finishes the maze); a second Ctrl-C raises `KeyboardInterrupt` at
/// once.
#[pyfunction]
#[pyo3(signature = (layout, api=None, host=None, port=None, **options))]
pub fn apply(
    py: Python<'_>,
    layout: &Layout,
    api: Option<Bound<'_, PyAny>>,
    host: Option<Bound<'_, PyAny>>,
    port: Option<Bound<'_, PyAny>>,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<ApplyReport> {
    let options = options::with(options, py, &[("api", api), ("host", host), ("port", port)])?;
    // the layout is the object, not a file: `-` only fills the command's place for it
    let argv = options::command_line("apply", &["-"], &options)?;
    let Command::Apply(args) = options::parse(argv)? else {
        return Err(PyRuntimeError::new_err("apply parsed as another command"));
    };
    if (args.create_missing || args.save_scene.is_some()) && args.scene.asks_legacy() {
        return Err(PyValueError::new_err(
            "create_missing=True and save_scene need the ZeroMQ remote API (api=\"zmq\"): the legacy API cannot create objects or save scenes",
        ));
    }
    let stop = Stop::default();
    let interrupt = stop.requested.clone();
    let layout = layout.layout.clone();
    let connected = stop.connected.clone();
    let job = move || {
        let job = args
            .job(&layout, Some(interrupt))
            .context("nothing was drawn")?;
        let mut backend = args.scene.connect()?;
        connected.store(true, Ordering::SeqCst);
        let result = draw_connected(backend.as_mut(), &job);
        let closed = backend.close().is_ok();
        Ok(match result? {
            Finished::Stopped { message, counts } if closed => Finished::Stopped {
                message: message + " and the connection closed cleanly",
                counts,
            },
            finished => finished,
        })
    };
    run_drawing_late(py, &stop, job, ApplyReport::from, Drawn::late)
}

/// `apply`'s work once connected ([`draw::run`]: create what is missing, draw and verify,
/// save the scene), with its failures in the words `vrep-maze apply` uses.
pub(crate) fn draw_connected(
    backend: &mut dyn Backend,
    job: &draw::Job<'_>,
) -> anyhow::Result<Finished<Drawn>> {
    let total = job.picture.pieces();
    let counts = vrep_maze::cli::summary::interrupted_counts(&job.picture);
    if job.options.interrupted() {
        return Ok(Finished::Stopped {
            message: format!("interrupted: 0 of {total} {counts}; the idle rate is unchanged"),
            counts: Some((0, total)),
        });
    }
    match draw::run(backend, job, &mut |_| {}) {
        Ok(report) => Ok(Finished::Done(Drawn {
            report,
            total,
            counts,
        })),
        Err(RunError::Draw(DrawError::Interrupted { placed, total })) => Ok(Finished::Stopped {
            message: format!(
                "interrupted: {placed} of {total} {counts}; the idle rate is restored"
            ),
            counts: Some((placed, total)),
        }),
        Err(RunError::NoAuthoring(Authored::CreateMissing)) => Err(anyhow::anyhow!(
            "--create-missing needs the ZeroMQ remote API, but the legacy API answered (use --api zmq)"
        )),
        Err(RunError::NoAuthoring(Authored::SaveScene)) => Err(anyhow::anyhow!(
            "--save-scene needs the ZeroMQ remote API, but the legacy API answered (use --api zmq)"
        )),
        Err(RunError::Create(e)) => {
            Err(anyhow::Error::new(e).context("creating the missing scene objects"))
        }
        Err(RunError::Draw(e)) => Err(e.into()),
        Err(RunError::Save { path, source }) => {
            Err(anyhow::Error::new(source).context(format!("saving the scene to {path}")))
        }
    }
}

/// Removes a drawn maze from CoppeliaSim as `vrep-maze clear` does (the templates stay).
///
/// Takes the connection keywords of `apply` (`api`, `host`, `port`, `floor`, `parent`,
/// `line`, `start`, `end`, `connect_timeout`, `timeout`) and `stop_simulation`,
/// `dry_run`. Returns a `ClearReport`. Errors and Ctrl-C as for `apply`.
#[pyfunction]
#[pyo3(signature = (api=None, host=None, port=None, **options))]
pub fn clear(
    py: Python<'_>,
    api: Option<Bound<'_, PyAny>>,
    host: Option<Bound<'_, PyAny>>,
    port: Option<Bound<'_, PyAny>>,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<ClearReport> {
    let options = options::with(options, py, &[("api", api), ("host", host), ("port", port)])?;
    let args = options::clear_args(&options)?;
    let stop = Stop::default();
    let dry_run = args.dry_run;
    let opts = args.options(Some(stop.requested.clone()));
    let parent = opts.names.parent.clone();
    let scene = args.scene;
    let connected = stop.connected.clone();
    let job = move || {
        let mut backend = scene.connect()?;
        connected.store(true, Ordering::SeqCst);
        let result = draw::clear(backend.as_mut(), &opts);
        let _ = backend.close();
        cleared(result)
    };
    run_drawing(py, &stop, job, |report| {
        ClearReport::of(report, dry_run, &parent)
    })
}
