//! `vrep_maze.connect(...)`: one connection kept open for many `apply`, `clear`, `inspect`
//! and `score` calls (`draw::Session`), so a training loop that draws a maze every episode connects once.
//!
//! The connection lives on a thread of its own (a backend stays on the thread that made it);
//! each call hands it a task and waits as `vrep_maze.apply` does, so Ctrl-C, a lost
//! connection and a restarted simulator behave as there: the first Ctrl-C stops after the
//! request in flight with the idle rate restored and raises `Interrupted` (the session stays
//! open; the same call again finishes the maze), an error raises `SimulatorError` and leaves
//! the scene as an interrupted `apply` does, for the next `apply` or `clear` to repair. The
//! call after one that lost the connection connects again first
//! (`draw::Session::reconnecting`).

use std::sync::Mutex;
use std::sync::atomic::Ordering;
use std::sync::mpsc::{self, Sender};

use anyhow::Context;
use numpy::PyArray2;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};
use vrep_maze::cli::{Command, Interrupted, inspect};
use vrep_maze::draw::{self, BackendError, DrawError};

use crate::draw::{
    ApplyReport, ClearReport, Drawn, Finished, Stop, cleared, draw_connected, run_drawing,
    run_drawing_late,
};
use crate::errors;
use crate::layout::Layout;
use crate::options;
use crate::score;

/// Work for the connection's thread.
type Task = Box<dyn FnOnce(&mut draw::Session) + Send>;

/// An open connection to CoppeliaSim: `with vrep_maze.connect(api="zmq") as sim:
/// sim.apply(layout, draw="mesh")`. Closed by `close()` or at the end of the `with` block.
#[pyclass(module = "vrep_maze")]
pub struct Session {
    /// The connection thread's queue; `None` once closed.
    tasks: Mutex<Option<Sender<Task>>>,
    /// Which API answered, where, and the simulator's version.
    #[pyo3(get)]
    description: String,
}

/// Connects to CoppeliaSim once for many calls; returns a `Session`.
///
/// Takes the connection keywords of `apply`: `api`, `host`, `port`, `connect_timeout`,
/// `timeout`. Raises `SimulatorError` when nothing answers.
#[pyfunction]
#[pyo3(signature = (api=None, host=None, port=None, **options))]
pub fn connect(
    py: Python<'_>,
    api: Option<Bound<'_, PyAny>>,
    host: Option<Bound<'_, PyAny>>,
    port: Option<Bound<'_, PyAny>>,
    options: Option<&Bound<'_, PyDict>>,
) -> PyResult<Session> {
    let options = options::with(options, py, &[("api", api), ("host", host), ("port", port)])?;
    let args = options::clear_args(&options)?;
    let scene = args.scene;
    let (tasks, queue) = mpsc::channel::<Task>();
    let stop = Stop::default();
    let job = move || {
        let (opened, made) = mpsc::channel();
        std::thread::Builder::new()
            .name("vrep-maze session".into())
            .spawn(move || {
                let backend = match scene.connect() {
                    Ok(backend) => backend,
                    Err(e) => return drop(opened.send(Err(e))),
                };
                // after a call lost the connection, the next connects again as this did
                let reconnect = move || {
                    scene
                        .connect()
                        .map_err(|e| BackendError::Transport(format!("{e:#}")))
                };
                let mut session = draw::Session::reconnecting(backend, Box::new(reconnect));
                let _ = opened.send(Ok(session.describe().unwrap_or_default()));
                for task in queue {
                    task(&mut session);
                }
                let _ = session.close();
            })?;
        let description = made.recv().context("the connection thread ended")??;
        Ok(Finished::Done(description))
    };
    let description = run_drawing(py, &stop, job, |d| d)?;
    Ok(Session {
        tasks: Mutex::new(Some(tasks)),
        description,
    })
}

impl Session {
    /// Runs `work` on the connection's thread as a drawing job (Ctrl-C handled as in
    /// `apply`), its outcome made into the Python result by `report`.
    fn run<T: Send + 'static, R>(
        &self,
        py: Python<'_>,
        stop: &Stop,
        work: impl FnOnce(&mut draw::Session) -> anyhow::Result<Finished<T>> + Send + 'static,
        report: impl FnOnce(T) -> R,
    ) -> PyResult<R> {
        self.run_late(py, stop, work, report, |_| None)
    }

    /// [`Session::run`], a Ctrl-C that came after the last request said as `late` says
    /// ([`run_drawing_late`]).
    fn run_late<T: Send + 'static, R>(
        &self,
        py: Python<'_>,
        stop: &Stop,
        work: impl FnOnce(&mut draw::Session) -> anyhow::Result<Finished<T>> + Send + 'static,
        report: impl FnOnce(T) -> R,
        late: impl FnOnce(&T) -> Option<(String, Option<(usize, usize)>)>,
    ) -> PyResult<R> {
        let tasks = self
            .tasks
            .lock()
            .map_err(|_| PyRuntimeError::new_err("the session's lock is poisoned"))?
            .clone()
            .ok_or_else(|| PyValueError::new_err("the session is closed: connect again"))?;
        stop.connected.store(true, Ordering::SeqCst);
        let job = move || {
            let (reply, answer) = mpsc::channel();
            let task: Task = Box::new(move |session| {
                let result = work(session);
                if result.as_ref().is_err_and(lost_connection) {
                    session.mark_lost();
                }
                let _ = reply.send(result);
            });
            tasks
                .send(task)
                .map_err(|_| anyhow::anyhow!("the session's connection thread ended"))?;
            answer
                .recv()
                .map_err(|_| anyhow::anyhow!("the session's connection thread ended"))?
        };
        run_drawing_late(py, stop, job, report, late)
    }
}

#[pymethods]
impl Session {
    /// Draws `layout` as `vrep_maze.apply` does, on this connection. Takes `apply`'s
    /// keywords but the connection's (`draw`, the object names, `stop_simulation`,
    /// `dry_run`, `create_missing`, `save_scene`, `resize_floor`). Returns an `ApplyReport`.
    #[pyo3(signature = (layout, **options))]
    fn apply(
        &self,
        py: Python<'_>,
        layout: &Layout,
        options: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<ApplyReport> {
        let options = options::with(options, py, &[])?;
        let argv = options::command_line("apply", &["-"], &options)?;
        let Command::Apply(args) = options::parse(argv)? else {
            return Err(PyRuntimeError::new_err("apply parsed as another command"));
        };
        let stop = Stop::default();
        let interrupt = stop.requested.clone();
        let layout = layout.layout.clone();
        let work = move |session: &mut draw::Session| {
            let job = args
                .job(&layout, Some(interrupt))
                .context("nothing was drawn")?;
            draw_connected(session.connected()?, &job)
        };
        self.run_late(py, &stop, work, ApplyReport::from, Drawn::late)
    }

    /// Removes the drawn maze as `vrep_maze.clear` does, on this connection (keywords: the
    /// object names, `stop_simulation`, `dry_run`). Returns a `ClearReport`.
    #[pyo3(signature = (**options))]
    fn clear(&self, py: Python<'_>, options: Option<&Bound<'_, PyDict>>) -> PyResult<ClearReport> {
        let options = options::with(options, py, &[])?;
        let args = options::clear_args(&options)?;
        let stop = Stop::default();
        let dry_run = args.dry_run;
        let opts = args.options(Some(stop.requested.clone()));
        let parent = opts.names.parent.clone();
        let work =
            move |session: &mut draw::Session| cleared(draw::clear(session.connected()?, &opts));
        self.run(py, &stop, work, |report| {
            ClearReport::of(report, dry_run, &parent)
        })
    }

    /// What the scene holds, as `vrep-maze inspect --json` reports it, as a dict (the same
    /// keys: `connection`, `idle_fps`, `objects` (the templates and markers), `maze` (the
    /// copies and meshes drawn), ...), on this connection; given a `layout`,
    /// `report["layout"]["matches"]` says whether the drawn maze is that layout and
    /// `report["layout"]["differences"]` lists what differs.
    /// Keywords: the object names (`floor`, `parent`, `line`, ...). Only reads: the idle
    /// rate is raised while reading and restored. Ctrl-C raises `Interrupted` (nothing was
    /// changed).
    #[pyo3(signature = (layout=None, **options))]
    fn inspect<'py>(
        &self,
        py: Python<'py>,
        layout: Option<&Layout>,
        options: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let options = options::with(options, py, &[])?;
        let argv = options::command_line("inspect", &[], &options)?;
        let Command::Inspect(args) = options::parse(argv)? else {
            return Err(PyRuntimeError::new_err("inspect parsed as another command"));
        };
        args.scene
            .check_roles()
            .map_err(|e| errors::from_anyhow(py, &e))?;
        let names = args.scene.names();
        let wanted = layout
            .map(|l| inspect::Wanted::new("the layout".into(), (*l.layout).clone()))
            .transpose()
            .map_err(|e| errors::from_anyhow(py, &e))?;
        let connection = self.description.clone();
        let stop = Stop::default();
        let flag = stop.requested.clone();
        let work = move |session: &mut draw::Session| {
            let read = inspect::read_report(
                session.connected()?,
                &names,
                connection,
                wanted.as_ref(),
                &flag,
            );
            match read {
                Err(e) if e.is::<Interrupted>() => Ok(Finished::Stopped {
                    message: e.to_string(),
                    counts: None,
                }),
                other => Ok(Finished::Done(other?)),
            }
        };
        let report = self.run(py, &stop, work, |report| report)?;
        let text = serde_json::to_string(&report)
            .map_err(|e| PyRuntimeError::new_err(format!("the report: {e}")))?;
        py.import("json")?.call_method1("loads", (text,))
    }

    /// Follows the robot while the simulation runs and grades its run through `layout`, as
    /// `vrep_maze.score` does, on this connection (which stays open). Takes `score`'s
    /// keywords but the connection's (`robot`, `floor`, `start_simulation`, `timeout`,
    /// `until`, `robot_radius`, `end_size`). Returns `(report, trajectory)`; Ctrl-C ends
    /// the run at the next look and raises `Interrupted` with `.report` and `.trajectory` of
    /// the partial run.
    #[pyo3(signature = (layout, robot=None, **options))]
    fn score<'py>(
        &self,
        py: Python<'py>,
        layout: &Layout,
        robot: Option<Bound<'py, PyAny>>,
        options: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyArray2<f64>>)> {
        let options = options::with(options, py, &[("robot", robot)])?;
        let argv = options::command_line("score", &["-"], &options)?;
        let Command::Score(args) = options::parse(argv)? else {
            return Err(PyRuntimeError::new_err("score parsed as another command"));
        };
        let stop = Stop::default();
        let interrupt = stop.requested.clone();
        let layout = layout.layout.clone();
        let work = move |session: &mut draw::Session| {
            let backend = session.connected()?;
            let mut follower = backend
                .follower()
                .ok_or_else(|| anyhow::anyhow!("this connection cannot follow a robot"))?;
            let scored = args.score_over(follower.as_mut(), &layout, interrupt.clone());
            follower.close();
            Ok(if interrupt.load(Ordering::SeqCst) {
                Finished::Partial(scored?)
            } else {
                Finished::Done(scored?)
            })
        };
        let scored = self.run(py, &stop, work, |scored| scored)?;
        let report = crate::reports::report_dict(py, &scored.report)?;
        let trajectory = crate::reports::samples_array(py, &scored.samples)?;
        if stop.requested.load(Ordering::SeqCst) {
            return Err(score::stopped_run(
                py,
                scored.samples.len(),
                report,
                trajectory,
            )?);
        }
        Ok((report, trajectory))
    }

    /// Drives the scene's wheeled robot through `layout` by its wheel joints, with physics,
    /// the simulation stepped by this session (as `vrep-maze drive --wheels`), and returns
    /// the run's grade: the `score` report as a dict (`report["reached_end"]`,
    /// `report["spl"]`, `report["line"]`, ...).
    ///
    /// Keywords are `drive`'s: `steer="pose"` (ground truth) or `"camera"` (the camera and
    /// the wheels' odometry alone, line mazes), `robot`, `left_motor`, `right_motor`,
    /// `camera`, `speed`, `wheel_radius`, `track`, `wheel_max`, `sim_timeout`, `run_timeout`,
    /// `floor`, `line`, and `start_simulation` (default `True`; `False` waits for the
    /// simulation to be started, e.g. by `vrep-maze score --start-simulation`). A session
    /// drives only the wheeled robot: `wheels=False` is a `ValueError`. Ctrl-C ends the run
    /// at the next step, the simulation stopped, and raises `KeyboardInterrupt`.
    #[pyo3(signature = (layout, wheels=true, **options))]
    fn drive<'py>(
        &self,
        py: Python<'py>,
        layout: &Layout,
        wheels: bool,
        options: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        if !wheels {
            return Err(PyValueError::new_err(
                "a session drives the scene's wheeled robot: drive(layout, wheels=True, ...); the kinematic robot is `vrep-maze drive` without --wheels",
            ));
        }
        let options = options::with(options, py, &[])?;
        if !options.contains("start_simulation")? {
            options.set_item("start_simulation", true)?;
        }
        let argv = options::command_line("drive", &["-", "--wheels"], &options)?;
        let Command::Drive(args) = options::parse(argv)? else {
            return Err(PyRuntimeError::new_err("drive parsed as another command"));
        };
        let stop = Stop::default();
        let interrupt = stop.requested.clone();
        let layout = layout.layout.clone();
        let work = move |session: &mut draw::Session| {
            let backend = session.connected()?;
            let mut port = backend.robot().ok_or_else(|| {
                anyhow::anyhow!(
                    "this connection cannot drive a wheeled robot: connect with api=\"zmq\""
                )
            })?;
            let driven = args.wheels_over(port.as_mut(), &layout, interrupt.clone());
            drop(port);
            let (_, report) = driven?;
            Ok(if interrupt.load(Ordering::SeqCst) {
                Finished::Partial(report)
            } else {
                Finished::Done(report)
            })
        };
        let report = self.run(py, &stop, work, |report| report)?;
        if stop.requested.load(Ordering::SeqCst) {
            return Err(pyo3::exceptions::PyKeyboardInterrupt::new_err(
                "interrupted: the robot was stopped and the simulation with it",
            ));
        }
        crate::reports::report_dict(py, &report)
    }

    /// Closes the connection (the official client's way, so that the simulator is ready for
    /// the next client at once) and waits until it is closed; later calls raise
    /// `ValueError`. Closing twice does nothing.
    fn close(&self, py: Python<'_>) -> PyResult<()> {
        let tasks = self
            .tasks
            .lock()
            .map_err(|_| PyRuntimeError::new_err("the session's lock is poisoned"))?
            .take();
        let Some(tasks) = tasks else {
            return Ok(());
        };
        let (reply, answer) = mpsc::channel();
        let task: Task = Box::new(move |session| {
            // a connection already lost has nothing left to close
            let _ = reply.send(session.close());
        });
        if tasks.send(task).is_ok() {
            drop(tasks);
            let _ = py.detach(move || answer.recv());
        }
        Ok(())
    }

    fn __enter__(slf: Py<Self>) -> Py<Self> {
        slf
    }

    #[pyo3(signature = (*_exc))]
    fn __exit__(&self, py: Python<'_>, _exc: &Bound<'_, PyTuple>) -> PyResult<bool> {
        self.close(py)?;
        Ok(false)
    }

    fn __repr__(&self) -> String {
        format!("<Session {}>", self.description)
    }
}

/// Whether `error` is the connection's own failure (the simulator closed or killed), after
/// which the session's next call connects again.
fn lost_connection(error: &anyhow::Error) -> bool {
    error
        .downcast_ref::<DrawError>()
        .is_some_and(|e| matches!(e, DrawError::Backend(b) if b.lost_connection()))
        || error
            .downcast_ref::<BackendError>()
            .is_some_and(BackendError::lost_connection)
}
