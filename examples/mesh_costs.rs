//! Times the mesh calls of `apply --draw mesh` and `inspect --layout` on a ZeroMQ server (a
//! real CoppeliaSim or `vrep-maze serve`), one call at a time at idle fps 0, for meshes of
//! several sizes: creating a mesh of n rectangles (`sim.createMeshShape`, or `sim.createShape`
//! with `--create-shape`), reading it back (`sim.getShapeMesh`) and removing it. Prints the
//! median of `--reps` of each, in milliseconds; what `docs/measurements.md` records.
//!
//!     cargo run --release --example mesh_costs -- PORT [--create-shape] [--reps N] [--boxes] [N...]
//!     cargo run --release --example mesh_costs -- PORT [--create-shape] [--reps N] --layout FILE [--packed [--stride K]]
//!
//! Shape k sits at (k mod 100, k div 100) times `--scale` metres (default 0.1), 0.6 x 0.2
//! times the scale. `--boxes` makes boxes (8 vertices, 12 triangles, as walls and posts) instead of flat
//! rectangles (4 vertices, 2 triangles, as lines). `--layout` times the meshes `apply --draw
//! mesh` makes of a layout: one create call each, or with `--packed` in batches of 8 by the
//! one-request program `apply` sends (`vrep_maze::coppelia::lua::create`), median of `--reps`;
//! `--stride K` sends each mesh's vertices reordered (vertex k at k·K mod n; 0: shuffled), to
//! see what the order costs the simulator. Each mesh's or batch's steps of the simulator's
//! search for coincident vertices (`vrep_maze::coppelia::vertex_merge`) are printed beside.

use std::borrow::Cow;
use std::time::{Duration, Instant};

use ciborium::Value;
use vrep_maze::coppelia::INTPARAM_IDLE_FPS;
use vrep_maze::coppelia::lua::{CreateMeshes, LuaMesh, create_meshes_code};
use vrep_maze::coppelia::vertex_merge::merge_steps;
use vrep_maze::zmq_api::cbor::{self, float_array, int};
use vrep_maze::zmq_api::{Client, ClientOptions};

/// Vertices and indices of `n` shapes on a grid: flat rectangles, or boxes.
fn shapes(n: usize, boxes: bool, scale: f64) -> (Vec<f64>, Vec<Value>) {
    let (mut v, mut ix) = (vec![], vec![]);
    for k in 0..n {
        let (x, y) = ((k % 100) as f64 * scale, (k / 100) as f64 * scale);
        let base = (v.len() / 3) as i64;
        let zs: &[f64] = if boxes { &[0.0, 0.2] } else { &[0.001] };
        for &z in zs {
            for (dx, dy) in [(0.0, 0.0), (0.6, 0.0), (0.6, 0.2), (0.0, 0.2)] {
                let (dx, dy) = (dx * scale, dy * scale);
                // f32 values, as the drawing sends (CBOR then carries them in 5 bytes)
                v.extend([x + dx, y + dy, z].map(|c| f64::from(c as f32)));
            }
        }
        let tris: &[[i64; 3]] = if boxes {
            &[
                [0, 1, 2],
                [0, 2, 3],
                [4, 6, 5],
                [4, 7, 6],
                [0, 4, 5],
                [0, 5, 1],
                [1, 5, 6],
                [1, 6, 2],
                [2, 6, 7],
                [2, 7, 3],
                [3, 7, 4],
                [3, 4, 0],
            ]
        } else {
            &[[0, 1, 2], [0, 2, 3]]
        };
        ix.extend(tris.iter().flatten().map(|i| int(base + i)));
    }
    (v, ix)
}

fn ms(d: Duration) -> f64 {
    d.as_secs_f64() * 1000.0
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn main() {
    let mut args = std::env::args().skip(1);
    let port: u16 = args.next().and_then(|p| p.parse().ok()).expect("PORT");
    let (mut create, mut reps, mut boxes, mut sizes) = ("sim.createMeshShape", 3, false, vec![]);
    let mut scale = 0.1;
    let mut layout = None;
    let mut lockstep = 0;
    let mut packed = false;
    let mut stride = 1;
    while let Some(a) = args.next() {
        match a.as_str() {
            "--create-shape" => create = "sim.createShape",
            "--reps" => reps = args.next().and_then(|n| n.parse().ok()).expect("--reps N"),
            "--boxes" => boxes = true,
            "--layout" => layout = args.next(),
            "--packed" => packed = true,
            "--stride" => {
                stride = args
                    .next()
                    .and_then(|n| n.parse().ok())
                    .expect("--stride N")
            }
            "--lockstep" => {
                lockstep = args
                    .next()
                    .and_then(|n| n.parse().ok())
                    .expect("--lockstep N")
            }
            "--scale" => scale = args.next().and_then(|n| n.parse().ok()).expect("--scale S"),
            n => sizes.push(n.parse::<usize>().expect("a size")),
        }
    }
    let mut c = Client::connect(&ClientOptions {
        port,
        timeout: Duration::from_secs(60),
        ..Default::default()
    })
    .expect("connect");
    // protocol 2 needs it; protocol 1 does not know it
    let _ = c.call("zmqRemoteApi.require", vec![Value::Text("sim".into())]);
    let fps = c
        .call_int("sim.getInt32Param", vec![int(INTPARAM_IDLE_FPS.into())])
        .expect("idle fps");
    if lockstep > 0 {
        // lock-step calls at the simulator's idle rate, each timed
        let times: Vec<String> = (0..lockstep)
            .map(|_| {
                let t = Instant::now();
                c.call("sim.getSimulationState", vec![]).expect("call");
                format!("{:.1}", ms(t.elapsed()))
            })
            .collect();
        println!("lock-step calls at idle fps {fps}, ms: {}", times.join(" "));
        return;
    }
    let set_fps = |c: &mut Client, f: i32| {
        c.call(
            "sim.setInt32Param",
            vec![int(INTPARAM_IDLE_FPS.into()), int(f.into())],
        )
        .expect("set idle fps");
    };
    set_fps(&mut c, 0);
    if let Some(path) = layout {
        if packed {
            packed_batches(&mut c, create, &path, reps, stride);
        } else {
            maze_meshes(&mut c, create, &path);
        }
        set_fps(&mut c, fps);
        c.close();
        return;
    }
    println!("n\ttriangles\t{create} ms\tgetShapeMesh ms\treply bytes\tremove ms");
    for n in sizes {
        let (v, ix) = shapes(n, boxes, scale);
        let triangles = ix.len() / 3;
        let (mut made, mut read, mut gone, mut bytes) = (vec![], vec![], vec![], 0);
        for _ in 0..reps {
            let args = vec![
                int(0),
                Value::Float(0.349),
                float_array(&v),
                Value::Array(ix.clone()),
            ];
            let t = Instant::now();
            let h = c.call_int(create, args).expect("create");
            made.push(ms(t.elapsed()));
            let t = Instant::now();
            let mesh = c
                .call("sim.getShapeMesh", vec![int(h.into())])
                .expect("read");
            read.push(ms(t.elapsed()));
            bytes = cbor::encode(&Value::Array(mesh)).len();
            let t = Instant::now();
            c.call("sim.removeObjects", vec![Value::Array(vec![int(h.into())])])
                .expect("remove");
            gone.push(ms(t.elapsed()));
        }
        println!(
            "{n}\t{triangles}\t{:.1}\t{:.1}\t{bytes}\t{:.1}",
            median(made),
            median(read),
            median(gone)
        );
    }
    set_fps(&mut c, fps);
    c.close();
}

/// The meshes `apply --draw mesh` makes of the layout in `path`.
fn layout_meshes(path: &str) -> vrep_maze::draw::mesh::MeshMaze {
    let text = std::fs::read_to_string(path).expect("layout file");
    let layout: vrep_maze::layout::Layout = serde_json::from_str(&text).expect("layout");
    vrep_maze::draw::mesh::MeshMaze::try_from(&layout).expect("mesh maze")
}

/// Creates the meshes of the layout in `path` in batches of 8 by the one-request program, under
/// a dummy, and removes them, `reps` times: the median time of each batch.
fn packed_batches(c: &mut Client, create: &str, path: &str, reps: usize, stride: usize) {
    let mut maze = layout_meshes(path);
    for m in &mut maze.meshes {
        reorder(&mut m.vertices, &mut m.indices, stride);
    }
    let holder = c
        .call_int("sim.createDummy", vec![Value::Float(0.01)])
        .expect("dummy");
    println!("batch\tmeshes\ttriangles\tvertices\tmerge steps\tcode KiB\tms");
    for (k, batch) in maze.meshes.chunks(8).enumerate() {
        let program = CreateMeshes {
            since_4_6: create == "sim.createShape",
            holder,
            floor: None,
            meshes: batch
                .iter()
                .map(|m| LuaMesh {
                    name: Cow::Owned(m.name()),
                    vertices: Cow::Borrowed(&m.vertices),
                    indices: Cow::Borrowed(&m.indices),
                    colour: [0.0, 1.0, 0.0],
                    special: 0,
                    respondable: false,
                })
                .collect(),
        };
        let code = create_meshes_code(&program);
        let mut times = vec![];
        for _ in 0..reps {
            let t = Instant::now();
            let answer = c
                .call("sim.executeLuaCode", vec![Value::Text(code.clone())])
                .expect("program");
            times.push(ms(t.elapsed()));
            let made = answer.get(1).cloned().expect("handles");
            c.call("sim.removeObjects", vec![made]).expect("remove");
        }
        let triangles: usize = batch.iter().map(|m| m.triangles()).sum();
        let vertices: usize = batch.iter().map(|m| m.vertices.len() / 3).sum();
        let steps: u64 = batch.iter().map(|m| merge_steps(&m.vertices)).sum();
        println!(
            "{k}\t{}\t{triangles}\t{vertices}\t{steps}\t{}\t{:.1}",
            batch.len(),
            code.len() / 1024,
            median(times)
        );
    }
    c.call(
        "sim.removeObjects",
        vec![Value::Array(vec![int(holder.into())])],
    )
    .expect("remove");
}

/// The same mesh with vertex k moved to (k * stride) mod n (a permutation when stride and n
/// share no factor; left as it is otherwise).
fn reorder(vertices: &mut Vec<f32>, indices: &mut [i32], stride: usize) {
    let n = vertices.len() / 3;
    if stride == 1 || n == 0 || (stride > 1 && gcd(stride, n) != 1) {
        return;
    }
    // stride 0: a shuffle (xorshift, fixed seed)
    let mut order: Vec<usize> = (0..n).map(|k| (k * stride.max(1)) % n).collect();
    if stride == 0 {
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        for k in (1..n).rev() {
            x ^= x << 13;
            x ^= x >> 7;
            x ^= x << 17;
            order.swap(k, (x % (k as u64 + 1)) as usize);
        }
    }
    let mut moved = vec![0.0f32; vertices.len()];
    for k in 0..n {
        let to = order[k];
        moved[3 * to..3 * to + 3].copy_from_slice(&vertices[3 * k..3 * k + 3]);
    }
    *vertices = moved;
    for i in indices.iter_mut() {
        *i = order[*i as usize] as i32;
    }
}

fn gcd(a: usize, b: usize) -> usize {
    if b == 0 { a } else { gcd(b, a % b) }
}

/// Creates, reads back and removes each mesh of the layout in `path`, timing each call.
fn maze_meshes(c: &mut Client, create: &str, path: &str) {
    let maze = layout_meshes(path);
    println!(
        "mesh\tkind\ttriangles\tvertices\tmerge steps\t{create} ms\tgetShapeMesh ms\treply bytes"
    );
    for (k, m) in maze.meshes.iter().enumerate() {
        let v: Vec<f64> = m.vertices.iter().map(|&x| f64::from(x)).collect();
        let ix = Value::Array(m.indices.iter().map(|&i| int(i.into())).collect());
        let t = Instant::now();
        let h = c
            .call_int(
                create,
                vec![int(0), Value::Float(0.349), float_array(&v), ix],
            )
            .expect("create");
        let made = ms(t.elapsed());
        let t = Instant::now();
        let mesh = c
            .call("sim.getShapeMesh", vec![int(h.into())])
            .expect("read");
        let read = ms(t.elapsed());
        let bytes = cbor::encode(&Value::Array(mesh)).len();
        c.call("sim.removeObjects", vec![Value::Array(vec![int(h.into())])])
            .expect("remove");
        println!(
            "{k}\t{:?}\t{}\t{}\t{}\t{made:.1}\t{read:.1}\t{bytes}",
            m.kind,
            m.triangles(),
            v.len() / 3,
            merge_steps(&m.vertices)
        );
    }
}
