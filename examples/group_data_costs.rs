//! Times `simxGetObjectGroupData` of every object (object type 109): one data type a call
//! (names, types, parents, poses, aliases, full paths), then several in one call, as `apply`
//! asks them, at idle fps 0, median of `--reps`, in ms. A reply longer than a packet shows
//! what the server's Nagle and the client's acknowledgements cost (`docs/measurements.md`
//! "Replies of several packets").
//!
//!     cargo run --release --example group_data_costs -- PORT [--reps N]

use std::time::Instant;

use vrep_maze::legacy::command::Command;
use vrep_maze::legacy::{Client, ClientOptions};

fn main() {
    let mut args = std::env::args().skip(1);
    let port: u16 = args.next().and_then(|p| p.parse().ok()).expect("PORT");
    let reps = match (args.next().as_deref(), args.next()) {
        (Some("--reps"), Some(n)) => n.parse().expect("--reps N"),
        _ => 7,
    };
    let mut c =
        Client::connect(format!("127.0.0.1:{port}"), ClientOptions::default()).expect("connect");
    // idle fps 0 (parameter 26), as `apply` runs, restored at the end
    let fps = c.call(&[Command::GetIntParam(26)]).expect("idle fps")[0]
        .data
        .clone();
    c.call(&[Command::SetIntParam(26, 0)]).expect("idle fps 0");
    println!("data types\tms");
    let sets: [&[i32]; 9] = [
        &[0],
        &[1],
        &[2],
        &[9],
        &[20],
        &[21],
        &[0, 2, 9, 1],
        &[2, 20],
        &[0, 1],
    ];
    for data_types in sets {
        let commands: Vec<Command> = data_types
            .iter()
            .map(|&data_type| Command::GetObjectGroupData {
                object_type: 109,
                data_type,
            })
            .collect();
        let mut times: Vec<f64> = (0..reps)
            .map(|_| {
                let t = Instant::now();
                c.call(&commands).expect("group data");
                t.elapsed().as_secs_f64() * 1000.0
            })
            .collect();
        times.sort_by(f64::total_cmp);
        println!("{data_types:?}\t{:.1}", times[times.len() / 2]);
    }
    let fps = i32::from_le_bytes(fps[..4].try_into().expect("an int"));
    c.call(&[Command::SetIntParam(26, fps)])
        .expect("idle fps back");
    c.close().expect("close");
}
