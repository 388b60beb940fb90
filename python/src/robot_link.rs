//! `vrep_maze.RobotLink`: the scene's wheeled robot, one simulation step a call, for a
//! learning environment (`vrep_maze.robot_env`) or a policy of the user's own.
//!
//! A link is its own ZeroMQ connection (a drawing `Session` beside it keeps its own): the
//! simulation runs in stepping mode while an episode lasts, so it advances only when
//! `step` says so, whatever the machine's pace. `begin` stops a running simulation (which
//! puts every dynamic object back), places the robot, turns stepping on, starts it and makes
//! the physics engine's world afresh; with `keep_running`, a `begin` while the link's
//! episode runs puts the robot back and makes the world afresh the same way, leaving the
//! simulation running, so that every episode runs alike to the last bit (with the camera,
//! either makes one step, so that the first image is a rendered frame); `end` stops it and
//! turns stepping off. The link sets the idle rate to 0 while open, so a stop and a start take
//! milliseconds; `close` puts it and the camera's resolution back. Calls run without the
//! GIL.

use std::sync::Mutex;

use numpy::ndarray::Array3;
use numpy::{PyArray1, PyArray3};
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};
use vrep_maze::cli::Command;
use vrep_maze::cli::RawClient;
use vrep_maze::robot::camera::Image;
use vrep_maze::robot::steer::NOTHING_RENDERS;
use vrep_maze::robot::wheels::Wheels;
use vrep_maze::robot::{Pose, Reading, RobotError, RobotPort, RobotSurvey, renders_nothing};
use vrep_maze::zmq_api::robot::ZmqRobot;

use crate::errors;
use crate::options;

/// What a link holds while open.
struct Linked {
    port: ZmqRobot<'static>,
    survey: RobotSurvey,
    /// The idle rate the link found, put back by `close`.
    idle_fps: i32,
    /// Whether an episode runs (the simulation started by this link).
    running: bool,
    /// Whether the running episode reads the camera.
    camera: bool,
}

/// The course robot stepped by the caller: `link = vrep_maze.RobotLink(port=23000)`, then
/// `link.begin(x, y, yaw)`, `link.step(left, right)` ..., `link.close()`.
#[pyclass(module = "vrep_maze")]
pub struct RobotLink {
    linked: Mutex<Option<Linked>>,
    /// Where it is connected.
    #[pyo3(get)]
    description: String,
}

impl RobotLink {
    /// Runs `work` on the open link without the GIL.
    fn with<T: Send>(
        &self,
        py: Python<'_>,
        work: impl FnOnce(&mut Linked) -> Result<T, RobotError> + Send,
    ) -> PyResult<T> {
        let mut guard = self
            .linked
            .lock()
            .map_err(|_| PyRuntimeError::new_err("the link's lock is poisoned"))?;
        let linked = guard
            .as_mut()
            .ok_or_else(|| PyValueError::new_err("the robot link is closed: make a new one"))?;
        py.detach(|| work(linked))
            .map_err(|e| errors::from_anyhow(py, &anyhow::anyhow!("the robot: {e}")))
    }
}

#[pymethods]
impl RobotLink {
    /// Connects to CoppeliaSim's ZeroMQ remote API and finds the robot.
    ///
    /// Keywords: `host`, `port`, `connect_timeout`, `timeout` as `connect` takes them, and
    /// `drive`'s names: `robot="Robot"`, `left_motor`, `right_motor`, `camera`, `floor`,
    /// `line`. Raises `SimulatorError` when nothing answers or the scene lacks a part.
    #[new]
    #[pyo3(signature = (api=None, host=None, port=None, **options))]
    fn new(
        py: Python<'_>,
        api: Option<Bound<'_, PyAny>>,
        host: Option<Bound<'_, PyAny>>,
        port: Option<Bound<'_, PyAny>>,
        options: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let options = options::with(options, py, &[("api", api), ("host", host), ("port", port)])?;
        let argv = options::command_line("drive", &["-", "--wheels"], &options)?;
        let Command::Drive(args) = options::parse(argv)? else {
            return Err(PyRuntimeError::new_err("drive parsed as another command"));
        };
        let names = args.robot_names();
        let opened = py.detach(|| -> anyhow::Result<(ZmqRobot<'static>, String)> {
            let RawClient::Zmq(client) = args.scene.client_until(None)? else {
                anyhow::bail!("a robot link steps the simulation over ZeroMQ: give api=\"zmq\"");
            };
            let endpoint = client.endpoint().to_string();
            let options = args.scene.options_for(&client);
            Ok((ZmqRobot::new(client, options), endpoint))
        });
        let (mut port, endpoint) = opened.map_err(|e| errors::from_anyhow(py, &e))?;
        let (survey, idle_fps) = py
            .detach(|| Ok::<_, RobotError>((port.survey(&names)?, port.set_idle_rate(0)?)))
            .map_err(|e| errors::from_anyhow(py, &anyhow::anyhow!("the robot: {e}")))?;
        Ok(Self {
            linked: Mutex::new(Some(Linked {
                port,
                survey,
                idle_fps,
                running: false,
                camera: false,
            })),
            description: format!("the robot `{}` over ZeroMQ at {endpoint}", names.robot),
        })
    }

    /// The wheels' radius and the track (metres), as read from the scene.
    #[getter]
    fn geometry(&self) -> PyResult<(f64, f64)> {
        let guard = self
            .linked
            .lock()
            .map_err(|_| PyRuntimeError::new_err("the link's lock is poisoned"))?;
        let linked = guard
            .as_ref()
            .ok_or_else(|| PyValueError::new_err("the robot link is closed: make a new one"))?;
        let d = linked.survey.drive;
        Ok((d.wheel_radius, d.track))
    }

    /// Renders the camera at `width` x `height` pixels until `close` (which puts the
    /// scene's resolution back). Ends a running episode first.
    fn set_camera_size(&self, py: Python<'_>, width: u32, height: u32) -> PyResult<()> {
        if !(1..=1024).contains(&width) || !(1..=1024).contains(&height) {
            return Err(PyValueError::new_err(format!(
                "camera_size must be 1 to 1024 pixels a side, got {width} x {height}"
            )));
        }
        self.with(py, |l| {
            halt(l)?;
            l.survey.camera = Some(l.port.set_camera_resolution(width, height)?);
            Ok(())
        })
    }

    /// Starts an episode: the robot at `(x, y)` facing `yaw` (floor frame), at rest: the
    /// simulation stopped if it runs, the robot placed, stepping turned on, the simulation
    /// started and the physics engine's world made afresh (`ZmqRobot::put_back`). With
    /// `keep_running`, when an episode of this link runs (with the same `camera`), the robot
    /// is put back and the world made afresh while the simulation runs, without a stop and a
    /// start (faster; other objects a run moved stay where they are). Either way the same
    /// actions give the same episode, to the last bit. The camera renders only when `camera` (else
    /// it is spared); then the simulation makes one step, so that the first image is a
    /// rendered frame of what is drawn now. Returns the first reading:
    /// `(time, pose, joints, image)`, `pose` an array `(x, y, yaw)`, `joints` the wheels'
    /// angles, `image` an `(height, width, 3)` `uint8` array (top row first) or `None`.
    #[pyo3(signature = (x, y, yaw, camera=false, keep_running=false))]
    fn begin<'py>(
        &self,
        py: Python<'py>,
        x: f64,
        y: f64,
        yaw: f64,
        camera: bool,
        keep_running: bool,
    ) -> PyResult<Bound<'py, PyTuple>> {
        if ![x, y, yaw].iter().all(|v| v.is_finite()) {
            return Err(PyValueError::new_err(format!(
                "the start pose must be finite, got ({x}, {y}, {yaw})"
            )));
        }
        let pose = Pose { x, y, yaw };
        let reading = self.with(py, |l| {
            // a simulation the user stopped since is started again below
            if keep_running && l.running && l.camera == camera && l.port.put_back(pose)? {
                if camera {
                    l.port.step()?;
                }
                return l.port.observe(camera);
            }
            halt(l)?;
            l.port.place(pose)?;
            l.port.remember_rest()?;
            l.port.prepare(camera)?;
            l.running = true;
            l.camera = camera;
            // a camera that renders nothing (no display) is said so at once: its every
            // frame takes seconds on a real 4.10 without a display, and is all black
            if camera && renders_nothing(&mut l.port)? {
                halt(l)?;
                return Err(RobotError::Scene(NOTHING_RENDERS.into()));
            }
            l.port.start_simulation()?;
            // the physics engine's world made afresh, as a `keep_running` begin makes it: every
            // episode then runs alike to the last bit, whichever way it began
            l.port.put_back(pose)?;
            if camera {
                // the camera renders during a step: before the first, its image is black
                l.port.step()?;
            }
            l.port.observe(camera)
        })?;
        reading_tuple(py, reading)
    }

    /// Sets the wheels' target velocities (rad/s), lets the simulation advance one step and
    /// returns the reading after it, as `begin` does (the image when `camera`).
    #[pyo3(signature = (left, right, camera=false))]
    fn step<'py>(
        &self,
        py: Python<'py>,
        left: f64,
        right: f64,
        camera: bool,
    ) -> PyResult<Bound<'py, PyTuple>> {
        if !(left.is_finite() && right.is_finite()) {
            return Err(PyValueError::new_err(format!(
                "wheel velocities must be finite, got ({left}, {right})"
            )));
        }
        let reading = self.with(py, |l| {
            if !l.running {
                return Err(RobotError::Scene(
                    "no episode runs: call begin(x, y, yaw) first".into(),
                ));
            }
            l.port.actuate(Wheels { left, right })?;
            l.port.step()?;
            l.port.observe(camera)
        })?;
        reading_tuple(py, reading)
    }

    /// Ends the episode: wheels stopped, the simulation stopped, stepping off. Nothing to
    /// end does nothing.
    fn end(&self, py: Python<'_>) -> PyResult<()> {
        self.with(py, halt)
    }

    /// Ends the episode, puts the camera's resolution back and closes the connection; later
    /// calls raise `ValueError`. Closing twice does nothing.
    fn close(&self, py: Python<'_>) -> PyResult<()> {
        let taken = self
            .linked
            .lock()
            .map_err(|_| PyRuntimeError::new_err("the link's lock is poisoned"))?
            .take();
        let Some(mut linked) = taken else {
            return Ok(());
        };
        let ended = py.detach(move || {
            let ended = halt(&mut linked);
            let restored = linked.port.set_idle_rate(linked.idle_fps).map(|_| ());
            linked.port.close();
            ended.and(restored)
        });
        ended.map_err(|e| errors::from_anyhow(py, &anyhow::anyhow!("the robot: {e}")))
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
        format!("<RobotLink {}>", self.description)
    }
}

/// Ends a running episode (`RobotPort::finish`: the simulation stopped, stepping off).
fn halt(l: &mut Linked) -> Result<(), RobotError> {
    if std::mem::take(&mut l.running) {
        l.port.finish()?;
    }
    Ok(())
}

/// A reading as `(time, pose, joints, image)`.
fn reading_tuple(py: Python<'_>, reading: Reading) -> PyResult<Bound<'_, PyTuple>> {
    let p = reading.pose;
    let pose = PyArray1::from_slice(py, &[p.x, p.y, p.yaw]);
    let joints = PyArray1::from_slice(py, &reading.joints);
    let image = match reading.image {
        Some(image) => image_array(py, image)?.into_any(),
        None => py.None().into_bound(py),
    };
    PyTuple::new(
        py,
        [
            reading.time.into_pyobject(py)?.into_any(),
            pose.into_any(),
            joints.into_any(),
            image,
        ],
    )
}

/// The image as `(height, width, 3)` bytes, the top row first (the simulator sends the
/// bottom row first).
fn image_array(py: Python<'_>, image: Image) -> PyResult<Bound<'_, PyArray3<u8>>> {
    let (w, h) = (image.width, image.height);
    let row = w * 3;
    let mut rgb = Vec::with_capacity(image.rgb.len());
    for r in (0..h).rev() {
        rgb.extend_from_slice(&image.rgb[r * row..(r + 1) * row]);
    }
    let array = Array3::from_shape_vec((h, w, 3), rgb)
        .map_err(|e| PyRuntimeError::new_err(e.to_string()))?;
    Ok(PyArray3::from_owned_array(py, array))
}
