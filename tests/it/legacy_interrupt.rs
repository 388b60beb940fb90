//! A connection dropped at any point of `apply` leaves a scene that the next `apply` or
//! `clear` fully repairs (no stray lines).

use std::io::{Read, Write};
use std::net::{Shutdown, TcpListener, TcpStream};
use std::time::Duration;

use vrep_maze::draw::{self, ApplyOptions, Drawing, ObjectNames};
use vrep_maze::generate::Algorithm;
use vrep_maze::layout::{GenerateSpec, build_layout};
use vrep_maze::legacy::wire::{MAX_PACKET_SIZE, Message, read_message, write_message};
use vrep_maze::legacy::{LegacyBackend, ServerConfig, ServerHandle, spawn};
use vrep_maze::maze::Grid;
use vrep_maze::sim::{Scene, Simulator};

fn drawing(n: u64, seed: u64) -> Drawing {
    let spec = GenerateSpec::course(Grid::new(n, n).unwrap(), Algorithm::Dfs, seed);
    Drawing::from(&build_layout(&spec).unwrap())
}

/// Forwards `limit` client messages to the server (or up to the first message carrying a
/// command `cut_after`), then cuts both connections.
fn cutting_proxy(
    server: std::net::SocketAddr,
    limit: usize,
    cut_after: Option<u16>,
) -> (u16, std::thread::JoinHandle<()>) {
    let l = TcpListener::bind("127.0.0.1:0").unwrap();
    let port = l.local_addr().unwrap().port();
    let t = std::thread::spawn(move || {
        let (mut client, _) = l.accept().unwrap();
        let mut up = TcpStream::connect(server).unwrap();
        let mut up_r = up.try_clone().unwrap();
        let mut client_w = client.try_clone().unwrap();
        let back = std::thread::spawn(move || {
            let mut buf = [0u8; 8192];
            while let Ok(n) = up_r.read(&mut buf) {
                if n == 0 || client_w.write_all(&buf[..n]).is_err() {
                    break;
                }
            }
        });
        for _ in 0..limit {
            match read_message(&mut client) {
                Ok(m) => {
                    write_message(&mut up, &m, MAX_PACKET_SIZE).unwrap();
                    let decoded = Message::decode(&m).unwrap();
                    if cut_after.is_some_and(|c| decoded.blocks.iter().any(|b| b.raw_id() == c)) {
                        std::thread::sleep(Duration::from_millis(400)); // let the server execute it
                        break;
                    }
                }
                Err(_) => break,
            }
        }
        std::thread::sleep(Duration::from_millis(20));
        let _ = client.shutdown(Shutdown::Both);
        let _ = up.shutdown(Shutdown::Both);
        let _ = back.join();
    });
    (port, t)
}

fn server() -> ServerHandle {
    server_at(0)
}

fn server_at(fps: i32) -> ServerHandle {
    let cfg = ServerConfig {
        listen: "127.0.0.1:0".parse().unwrap(),
        ..Default::default()
    };
    spawn(cfg, Simulator::new(Scene::course(), fps)).unwrap()
}

fn connect(port: u16) -> LegacyBackend {
    LegacyBackend::connect("127.0.0.1", port, Duration::from_secs(2)).unwrap()
}

fn lines_in_scene(s: &ServerHandle) -> usize {
    s.with_sim(|sim| sim.scene.objects().filter(|o| o.alias == "Line").count())
}

#[test]
fn legacy_interrupted_apply_is_repaired_by_apply_and_by_clear() {
    let first = drawing(4, 1);
    let second = drawing(5, 2);
    let mut interrupted = 0;
    for limit in 1..40 {
        for repair_with_clear in [false, true] {
            let s = server();
            // an earlier maze is present
            let mut sc = connect(s.local_addr().port());
            draw::apply(&mut sc, &first, &ApplyOptions::default(), &mut |_| {}).unwrap();
            drop(sc);
            let (port, proxy) = cutting_proxy(s.local_addr(), limit, None);
            let mut sc = connect(port);
            let r = draw::apply(&mut sc, &second, &ApplyOptions::default(), &mut |_| {});
            drop(sc);
            proxy.join().unwrap();
            if r.is_ok() {
                s.shutdown();
                continue;
            }
            interrupted += 1;
            let mut sc = connect(s.local_addr().port());
            if repair_with_clear {
                draw::clear(&mut sc, &ObjectNames::default(), false).unwrap();
                assert_eq!(
                    lines_in_scene(&s),
                    1,
                    "cut after {limit} messages: clear left lines"
                );
            } else {
                draw::apply(&mut sc, &second, &ApplyOptions::default(), &mut |_| {}).unwrap();
                draw::verify(&mut sc, &second, &ObjectNames::default()).unwrap();
                assert_eq!(
                    lines_in_scene(&s),
                    second.lines.len(),
                    "cut after {limit} messages"
                );
            }
            drop(sc);
            s.shutdown();
        }
    }
    assert!(
        interrupted >= 10,
        "only {interrupted} runs were interrupted"
    );
}

#[test]
fn legacy_idle_rate_left_at_zero_by_an_interrupted_apply_is_restored() {
    let d = drawing(3, 4);
    for repair_with_clear in [false, true] {
        let s = server_at(8);
        // cut right after the message that raised the idle rate (set-integer-parameter)
        let (port, proxy) = cutting_proxy(s.local_addr(), usize::MAX, Some(0x1022));
        let mut sc = connect(port);
        assert!(draw::apply(&mut sc, &d, &ApplyOptions::default(), &mut |_| {}).is_err());
        drop(sc);
        proxy.join().unwrap();
        assert_eq!(
            s.with_sim(|sim| sim.idle_fps),
            0,
            "the interrupted run left the rate at 0"
        );
        let mut sc = connect(s.local_addr().port());
        if repair_with_clear {
            let r = draw::clear(&mut sc, &ObjectNames::default(), false).unwrap();
            assert_eq!(r.restored_idle_fps, Some(8));
        } else {
            draw::apply(&mut sc, &d, &ApplyOptions::default(), &mut |_| {}).unwrap();
        }
        drop(sc);
        let (fps, signals) = s.with_sim(|sim| (sim.idle_fps, sim.int_signals.len()));
        assert_eq!(
            (fps, signals),
            (8, 0),
            "user's rate restored and the record deleted"
        );
        s.shutdown();
    }
}
