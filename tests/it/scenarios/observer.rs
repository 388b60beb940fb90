//! Reads a scene the way a person checking it would, independently of the code under test:
//! raw ZeroMQ calls (`sim.getObjectsInTree`, `sim.getObjectPose`, `sim.getShapeMesh`, ...),
//! no `draw`, no backend. It works on `serve` and on real 4.5.1 and 4.10, whichever API the
//! scenario drew through (4.5.1 serves ZeroMQ beside legacy on one scene).

use std::time::Duration;

use ciborium::Value;
use vrep_maze::coppelia::{HANDLE_ALL, HANDLE_SCENE, INTPARAM_IDLE_FPS, OBJECT_SHAPE_TYPE};
use vrep_maze::zmq_api::cbor;
use vrep_maze::zmq_api::{Client, ClientOptions};

/// A shape's triangles in the floor frame: `[x, y, z]` per corner.
pub type Triangle = [[f64; 3]; 3];

/// One object of the scene.
#[derive(Debug, Clone, PartialEq)]
pub struct Object {
    /// Its handle.
    pub handle: i32,
    /// Its alias.
    pub alias: String,
    /// Its parent's handle (`-1`: the scene root).
    pub parent: i32,
    /// Position relative to the floor.
    pub position: [f64; 3],
}

/// What the observer saw at one moment.
#[derive(Debug, Clone)]
pub struct Look {
    /// The idle rate the scene had before the observer raised it to read.
    pub idle_fps: i32,
    /// Every object of the scene.
    pub objects: Vec<Object>,
    /// Every shape's triangles, in the floor frame, by handle (floor and markers left out).
    pub triangles: Vec<(i32, Vec<Triangle>)>,
    /// `Start`'s handle.
    pub start: i32,
    /// `End`'s handle.
    pub end: i32,
}

impl Look {
    /// The object with this alias at the scene root (panics if there is none).
    pub fn root(&self, alias: &str) -> &Object {
        self.objects
            .iter()
            .find(|o| o.alias == alias && o.parent == -1)
            .unwrap_or_else(|| panic!("no {alias} at the scene root: {:?}", self.aliases()))
    }

    /// Every alias, sorted.
    pub fn aliases(&self) -> Vec<String> {
        let mut a: Vec<String> = self.objects.iter().map(|o| o.alias.clone()).collect();
        a.sort();
        a
    }

    /// The objects whose parent is `parent`'s handle, or below it.
    pub fn below(&self, parent: i32) -> Vec<&Object> {
        let mut out = vec![];
        let mut frontier = vec![parent];
        while let Some(p) = frontier.pop() {
            for o in self.objects.iter().filter(|o| o.parent == p) {
                out.push(o);
                frontier.push(o.handle);
            }
        }
        out
    }
}

/// A ZeroMQ connection that only reads (and raises the idle rate while it reads, restoring it).
pub struct Observer {
    client: Client,
}

fn call(client: &mut Client, func: &str, args: Vec<Value>) -> Vec<Value> {
    client
        .call(func, args)
        .unwrap_or_else(|e| panic!("observer: {func}: {e}"))
}

fn int(v: i64) -> Value {
    cbor::int(v)
}

fn text(s: &str) -> Value {
    Value::Text(s.into())
}

/// Numbers from a CBOR array, or from a byte string of little-endian `f32`s or `f64`s
/// (`packed`: how many bytes a number takes there).
fn floats(value: &Value) -> Vec<f64> {
    match value {
        Value::Array(items) => items.iter().map(|v| cbor::number(v).unwrap()).collect(),
        Value::Bytes(b) if b.len() % 4 == 0 => b
            .chunks_exact(4)
            .map(|c| f64::from(f32::from_le_bytes(c.try_into().unwrap())))
            .collect(),
        other => panic!("observer: not numbers: {}", cbor::describe(other)),
    }
}

fn ints(value: &Value) -> Vec<i64> {
    match value {
        Value::Array(items) => items.iter().map(|v| cbor::integer(v).unwrap()).collect(),
        Value::Bytes(b) if b.len() % 4 == 0 => b
            .chunks_exact(4)
            .map(|c| i64::from(i32::from_le_bytes(c.try_into().unwrap())))
            .collect(),
        other => panic!("observer: not integers: {}", cbor::describe(other)),
    }
}

/// `[x, y, z, qx, qy, qz, qw]` applied to a point.
fn transform(pose: &[f64], p: [f64; 3]) -> [f64; 3] {
    let q = nalgebra::UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(
        pose[6], pose[3], pose[4], pose[5],
    ));
    let v = q * nalgebra::Vector3::new(p[0], p[1], p[2]);
    [v.x + pose[0], v.y + pose[1], v.z + pose[2]]
}

impl Observer {
    /// Connects to the ZeroMQ remote API at `port` on the loopback.
    pub fn connect(port: u16) -> Observer {
        let client = Client::connect(&ClientOptions {
            port,
            timeout: Duration::from_secs(30),
            ..Default::default()
        })
        .unwrap_or_else(|e| panic!("observer: cannot connect to 127.0.0.1:{port}: {e}"));
        Observer { client }
    }

    /// The idle rate now.
    pub fn idle_fps(&mut self) -> i32 {
        let v = call(
            &mut self.client,
            "sim.getInt32Param",
            vec![int(INTPARAM_IDLE_FPS.into())],
        );
        cbor::int32(&v[0]).unwrap()
    }

    /// `sim.getSimulationState`: 0 stopped.
    pub fn simulation_state(&mut self) -> i32 {
        let v = call(&mut self.client, "sim.getSimulationState", vec![]);
        cbor::int32(&v[0]).unwrap()
    }

    /// Sets the idle rate (what a user does in the simulator's settings).
    pub fn set_idle_fps(&mut self, fps: i32) {
        call(
            &mut self.client,
            "sim.setInt32Param",
            vec![int(INTPARAM_IDLE_FPS.into()), int(fps.into())],
        );
    }

    /// Calls `func` as a user's script would (an edit of the scene), its answer.
    pub fn call(&mut self, func: &str, args: Vec<Value>) -> Vec<Value> {
        call(&mut self.client, func, args)
    }

    /// A handle by path (`/Floor`).
    pub fn handle(&mut self, path: &str) -> i32 {
        let v = call(&mut self.client, "sim.getObject", vec![text(path)]);
        cbor::int32(&v[0]).unwrap()
    }

    /// Moves `handle` to `position` relative to the floor (a user's edit).
    pub fn move_to(&mut self, handle: i32, position: [f64; 3]) {
        let floor = self.handle("/Floor");
        call(
            &mut self.client,
            "sim.setObjectPosition",
            vec![
                int(handle.into()),
                int(floor.into()),
                cbor::float_array(&position),
            ],
        );
    }

    /// Adds `Robot`, a dummy at floor (`x`, `y`), and returns its handle. On a real simulator
    /// the simulation is set to real time (`sim.boolparam_realtime_simulation`, 25: without
    /// physics these builds run about 300 times faster, `../shared/coppeliasim/README.md`), as
    /// a desktop CoppeliaSim with physics about runs.
    pub fn add_robot(&mut self, x: f64, y: f64, real_time: bool) -> i32 {
        let floor = self.handle("/Floor");
        let c = &mut self.client;
        let robot = call(c, "sim.createDummy", vec![Value::Float(0.05)]);
        let robot = robot[0].clone();
        call(c, "sim.setObjectAlias", vec![robot.clone(), text("Robot")]);
        call(
            c,
            "sim.setObjectPosition",
            vec![
                robot.clone(),
                int(floor.into()),
                cbor::float_array(&[x, y, 0.05]),
            ],
        );
        if real_time {
            call(c, "sim.setBoolParam", vec![int(25), Value::Bool(true)]);
        }
        cbor::int32(&robot).unwrap()
    }

    /// Drives `robot` along `waypoints` (simulation seconds, floor x and y; linear between
    /// them) by remote calls while the simulation runs (the scene has no script that could),
    /// until it has run and stopped, or `limit` passes.
    pub fn drive(mut self, robot: i32, waypoints: &[(f64, f64, f64)], limit: Duration) {
        let floor = self.handle("/Floor");
        let began = std::time::Instant::now();
        let mut ran = false;
        while began.elapsed() < limit {
            let state = call(&mut self.client, "sim.getSimulationState", vec![]);
            if cbor::int32(&state[0]) == Some(0) {
                if ran {
                    return;
                }
                std::thread::sleep(Duration::from_millis(10));
                continue;
            }
            ran = true;
            let t = call(&mut self.client, "sim.getSimulationTime", vec![]);
            let t = cbor::number(&t[0]).unwrap();
            let (x, y) = along(waypoints, t);
            let _ = self.client.call(
                "sim.setObjectPosition",
                vec![
                    int(robot.into()),
                    int(floor.into()),
                    cbor::float_array(&[x, y, 0.05]),
                ],
            );
        }
    }

    /// A user's copy of the shape `template` under `parent`, coloured `colour` (RGB 0..1):
    /// copy, re-parent (kept in place) and colour, as a person does it in the simulator.
    pub fn coloured_copy(&mut self, template: i32, parent: i32, colour: [f64; 3]) -> i32 {
        let c = &mut self.client;
        let v = call(
            c,
            "sim.copyPasteObjects",
            vec![Value::Array(vec![int(template.into())]), int(0)],
        );
        let copy = ints(&v[0])[0] as i32;
        call(
            c,
            "sim.setObjectParent",
            vec![int(copy.into()), int(parent.into()), Value::Bool(true)],
        );
        call(
            c,
            "sim.setShapeColor",
            vec![
                int(copy.into()),
                text(""),
                int(0),
                cbor::float_array(&colour),
            ],
        );
        copy
    }

    /// The ambient-diffuse colours of the shapes `handles` (`sim.getShapeColor`), read at
    /// idle rate 0 and the user's rate put back after.
    pub fn colours(&mut self, handles: &[i32]) -> Vec<[f64; 3]> {
        let idle_fps = self.idle_fps();
        self.set_idle_fps(0);
        let colours = handles
            .iter()
            .map(|&h| {
                let v = call(
                    &mut self.client,
                    "sim.getShapeColor",
                    vec![int(h.into()), text(""), int(0)],
                );
                let c = floats(&v[1]);
                [c[0], c[1], c[2]]
            })
            .collect();
        self.set_idle_fps(idle_fps);
        colours
    }

    /// Copies of the template `line` (by alias) directly under `maze`, and at the scene's
    /// root: a count in a few calls, where [`Observer::look`] reads every object.
    pub fn copies_of(&mut self, line: i32, maze: i32) -> (usize, usize) {
        let idle_fps = self.idle_fps();
        self.set_idle_fps(0);
        let c = &mut self.client;
        let tree = |c: &mut Client, base: i32, options: i64| {
            let found = call(
                c,
                "sim.getObjectsInTree",
                vec![int(base.into()), int(HANDLE_ALL.into()), int(options)],
            );
            ints(&found[0])
        };
        let alias = |c: &mut Client, h: i64| {
            let a = call(c, "sim.getObjectAlias", vec![int(h)]);
            cbor::text(&a[0]).unwrap().to_string()
        };
        // options 3: the base's first children only; 2: the scene's root objects
        let under = tree(c, maze, 3);
        let under = under.into_iter().filter(|&h| alias(c, h) == "Line").count();
        let roots = tree(c, HANDLE_SCENE, 2);
        let roots = roots
            .into_iter()
            .filter(|&h| h != i64::from(line) && alias(c, h) == "Line")
            .count();
        self.set_idle_fps(idle_fps);
        (under, roots)
    }

    /// Everything in the scene, read at idle rate 0 and the user's rate put back after.
    pub fn look(&mut self) -> Look {
        let idle_fps = self.idle_fps();
        self.set_idle_fps(0);
        let look = self.read(idle_fps);
        self.set_idle_fps(idle_fps);
        look
    }

    fn read(&mut self, idle_fps: i32) -> Look {
        let floor = self.handle("/Floor");
        let start = self.handle("/Start");
        let end = self.handle("/End");
        let c = &mut self.client;
        let all = call(
            c,
            "sim.getObjectsInTree",
            vec![int(HANDLE_SCENE.into()), int(HANDLE_ALL.into()), int(0)],
        );
        let handles = ints(&all[0]);
        let shapes = call(
            c,
            "sim.getObjectsInTree",
            vec![
                int(HANDLE_SCENE.into()),
                int(OBJECT_SHAPE_TYPE.into()),
                int(0),
            ],
        );
        let shapes = ints(&shapes[0]);
        let mut objects = vec![];
        for &h in &handles {
            let h = int(h);
            let alias = call(c, "sim.getObjectAlias", vec![h.clone()]);
            let parent = call(c, "sim.getObjectParent", vec![h.clone()]);
            let pose = call(
                c,
                "sim.getObjectPosition",
                vec![h.clone(), int(floor.into())],
            );
            let p = floats(&pose[0]);
            objects.push(Object {
                handle: cbor::int32(&h).unwrap(),
                alias: cbor::text(&alias[0]).unwrap().to_string(),
                parent: cbor::int32(&parent[0]).unwrap(),
                position: [p[0], p[1], p[2]],
            });
        }
        let mut triangles = vec![];
        for &h in shapes
            .iter()
            .filter(|&&h| ![floor, start, end].contains(&(h as i32)))
        {
            let pose = floats(&call(c, "sim.getObjectPose", vec![int(h), int(floor.into())])[0]);
            let mesh = call(c, "sim.getShapeMesh", vec![int(h)]);
            let v = floats(&mesh[0]);
            let idx = ints(&mesh[1]);
            let corner = |k: i64| {
                let k = k as usize * 3;
                transform(&pose, [v[k], v[k + 1], v[k + 2]])
            };
            let tris = idx
                .chunks_exact(3)
                .map(|t| [corner(t[0]), corner(t[1]), corner(t[2])])
                .collect();
            triangles.push((h as i32, tris));
        }
        Look {
            idle_fps,
            objects,
            triangles,
            start,
            end,
        }
    }
}

/// The point of `waypoints` at time `t` (linear between them; the last after the end).
fn along(waypoints: &[(f64, f64, f64)], t: f64) -> (f64, f64) {
    for pair in waypoints.windows(2) {
        let ((t0, x0, y0), (t1, x1, y1)) = (pair[0], pair[1]);
        if t < t1 {
            let a = ((t - t0) / (t1 - t0)).clamp(0.0, 1.0);
            return (x0 + a * (x1 - x0), y0 + a * (y1 - y0));
        }
    }
    let &(_, x, y) = waypoints.last().unwrap();
    (x, y)
}
