//! Our native client against `serve`'s server (in-process), plus failure modes.

use std::io::{Read, Write};
use std::net::TcpListener;
use std::time::{Duration, Instant};

use vrep_maze::legacy::command::{
    Command, GroupData, SimControl, decode_handle_list, read_f32x3, read_i32,
};
use vrep_maze::legacy::{Client, ClientError, ClientOptions, ServerConfig, spawn};
use vrep_maze::sim::{Scene, Simulator};

fn server(fps: i32) -> vrep_maze::legacy::ServerHandle {
    let cfg = ServerConfig {
        listen: "127.0.0.1:0".parse().unwrap(),
        ..Default::default()
    };
    spawn(cfg, Simulator::new(Scene::course(), fps)).unwrap()
}

fn opts() -> ClientOptions {
    ClientOptions {
        connect_timeout: Duration::from_secs(2),
        reply_timeout: Duration::from_secs(2),
        ..Default::default()
    }
}

fn handle(c: &mut Client, name: &str) -> i32 {
    let r = c.call1(Command::GetObjectHandle(name.into())).unwrap();
    assert!(!r.remote_error, "{name}");
    read_i32(&r.data, 0).unwrap()
}

#[test]
fn legacy_handles_copy_names_and_errors() {
    let s = server(0);
    let mut c = Client::connect(s.local_addr(), opts()).unwrap();
    let line = handle(&mut c, "Line");
    assert_eq!(handle(&mut c, "/Line"), line);
    let missing = c.call1(Command::GetObjectHandle("Line#0".into())).unwrap();
    assert!(missing.remote_error);
    assert_eq!(read_i32(&missing.data, 0), Some(-1));
    // two copy-pastes batched into one message (do-not-overwrite)
    let r = c
        .call(&[
            Command::CopyPaste(vec![line]),
            Command::CopyPaste(vec![line]),
        ])
        .unwrap();
    let a = decode_handle_list(&r[0].data).unwrap()[0];
    let b = decode_handle_list(&r[1].data).unwrap()[0];
    assert!(b > a && a > line);
    let names = c
        .call1(Command::GetObjectGroupData {
            object_type: 109,
            data_type: 0,
        })
        .unwrap();
    let g = GroupData::decode(&names.data).unwrap();
    assert_eq!(&g.strings[g.strings.len() - 2..], ["Line0", "Line1"]);
    assert!(!c.call1(Command::RemoveObject(a)).unwrap().remote_error);
    assert!(
        c.call1(Command::RemoveObject(a)).unwrap().remote_error,
        "remove twice fails"
    );
    assert_eq!(c.round_trips(), 7);
    c.close().unwrap();
    s.shutdown();
}

#[test]
fn legacy_relative_pose_test_vector() {
    let s = server(0);
    let mut c = Client::connect(s.local_addr(), opts()).unwrap();
    let (a, b) = (handle(&mut c, "Start"), handle(&mut c, "End"));
    let r = c
        .call(&[
            Command::SetPosition {
                handle: a,
                relative_to: -1,
                xyz: [1.0, 2.0, 0.001],
            },
            Command::SetOrientation {
                handle: a,
                relative_to: -1,
                euler: [0.0, 0.0, std::f32::consts::FRAC_PI_2],
            },
            Command::SetPosition {
                handle: b,
                relative_to: a,
                xyz: [0.5, 0.0, 0.0],
            },
            Command::SetOrientation {
                handle: b,
                relative_to: a,
                euler: [0.1, 0.2, 0.3],
            },
            Command::GetPosition {
                handle: b,
                relative_to: -1,
            },
            Command::GetOrientation {
                handle: b,
                relative_to: -1,
            },
            Command::GetPosition {
                handle: a,
                relative_to: b,
            },
        ])
        .unwrap();
    assert!(r.iter().all(|r| !r.remote_error));
    let near = |v: [f32; 3], w: [f32; 3]| v.iter().zip(w).all(|(x, y)| (x - y).abs() < 2e-4);
    assert!(near(read_f32x3(&r[4].data, 0).unwrap(), [1.0, 2.5, 0.001]));
    assert!(near(
        read_f32x3(&r[5].data, 0).unwrap(),
        [-0.2010, 0.0980, 1.8907]
    ));
    assert!(near(
        read_f32x3(&r[6].data, 0).unwrap(),
        [-0.4681, 0.1448, -0.0993]
    ));
    c.close().unwrap();
    s.shutdown();
}

#[test]
fn legacy_idle_fps_paces_blocking_calls_and_state_bit() {
    let s = server(8);
    let mut c = Client::connect(s.local_addr(), opts()).unwrap();
    let t = Instant::now();
    for _ in 0..3 {
        assert_eq!(
            read_i32(&c.call1(Command::GetIntParam(26)).unwrap().data, 0),
            Some(8)
        );
    }
    assert!(
        t.elapsed() >= Duration::from_millis(200),
        "3 calls at 8 fps take >= 2 passes: {:?}",
        t.elapsed()
    );
    assert!(!c.call1(Command::SetIntParam(26, 0)).unwrap().remote_error);
    // 40 calls at fps 0 take well under the 39 passes (4.9 s) they would take at 8 fps,
    // however loaded the machine
    let t = Instant::now();
    for _ in 0..40 {
        c.call1(Command::GetIntParam(1)).unwrap();
    }
    assert!(
        t.elapsed() < Duration::from_millis(39 * 125 / 2),
        "fps 0 is fast: {:?}",
        t.elapsed()
    );
    assert!(
        !c.call1(Command::Simulation(SimControl::Start))
            .unwrap()
            .remote_error
    );
    c.call1(Command::GetIntParam(1)).unwrap();
    assert_eq!(c.simulation_running(), Some(true));
    assert!(
        !c.call1(Command::Simulation(SimControl::Stop))
            .unwrap()
            .remote_error
    );
    c.call1(Command::GetIntParam(1)).unwrap();
    assert_eq!(c.simulation_running(), Some(false));
    c.close().unwrap();
    s.shutdown();
}

#[test]
fn legacy_connection_refused_is_a_clear_error() {
    let port = TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port();
    let o = ClientOptions {
        connect_timeout: Duration::from_millis(300),
        ..opts()
    };
    let e = Client::connect(format!("127.0.0.1:{port}"), o)
        .err()
        .unwrap();
    assert!(matches!(e, ClientError::Connect { .. }), "{e}");
    assert!(e.to_string().contains("cannot connect"), "{e}");
}

/// A fake server: answers the client's first message (the connection check) with a valid
/// header-only reply, then runs `then` on the socket.
fn fake_server(
    then: impl FnOnce(std::net::TcpStream) + Send + 'static,
) -> (std::net::SocketAddr, std::thread::JoinHandle<()>) {
    use vrep_maze::legacy::wire::{
        MAX_PACKET_SIZE, Message, MessageHeader, read_message, write_message,
    };
    let l = TcpListener::bind("127.0.0.1:0").unwrap();
    let addr = l.local_addr().unwrap();
    let t = std::thread::spawn(move || {
        let (mut s, _) = l.accept().unwrap();
        let _ = read_message(&mut s);
        let hello = Message {
            header: MessageHeader {
                message_id: -1,
                ..Default::default()
            },
            blocks: vec![],
        };
        write_message(&mut s, &hello.encode(), MAX_PACKET_SIZE).unwrap();
        then(s);
    });
    (addr, t)
}

#[test]
fn legacy_silent_server_times_out() {
    let (addr, t) = fake_server(|mut s| {
        let mut buf = [0u8; 4096];
        while s.read(&mut buf).map(|n| n > 0).unwrap_or(false) {}
    });
    let o = ClientOptions {
        reply_timeout: Duration::from_millis(300),
        ..opts()
    };
    let mut c = Client::connect(addr, o).unwrap();
    let e = c.call1(Command::GetIntParam(1)).err().unwrap();
    assert!(matches!(e, ClientError::Timeout(_)), "{e}");
    drop(c);
    t.join().unwrap();
}

#[test]
fn legacy_server_that_never_answers_fails_connect_clearly() {
    let l = TcpListener::bind("127.0.0.1:0").unwrap();
    let o = ClientOptions {
        connect_timeout: Duration::from_millis(300),
        ..opts()
    };
    let e = Client::connect(l.local_addr().unwrap(), o).err().unwrap();
    assert!(e.to_string().contains("no answer"), "{e}");
}

#[test]
fn legacy_garbage_from_server_is_an_error_not_a_panic() {
    let garbage: [&[u8]; 3] = [
        b"HTTP/1.1 400 Bad Request\r\n\r\n",
        &[1, 0, 4, 0, 0, 0, 0, 0, 11, 0],
        &[
            1, 0, 30, 0, 0, 0, 0, 0, 11, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0xff, 0xff,
            0, 0, 0, 0, 0, 0, 0, 0, 0, 0,
        ],
    ];
    for g in garbage {
        // garbage as the answer to a call
        let bytes = g.to_vec();
        let (addr, t) = fake_server(move |mut s| {
            let mut buf = [0u8; 64];
            let _ = s.read(&mut buf);
            let _ = s.write_all(&bytes);
            std::thread::sleep(Duration::from_millis(100));
        });
        let mut c = Client::connect(addr, opts()).unwrap();
        let e = c.call1(Command::GetIntParam(1)).err().unwrap();
        assert!(
            matches!(e, ClientError::Wire(_) | ClientError::Closed),
            "{e}"
        );
        t.join().unwrap();
        // garbage as the answer to the connection check
        let l = TcpListener::bind("127.0.0.1:0").unwrap();
        let addr = l.local_addr().unwrap();
        let bytes = g.to_vec();
        let t = std::thread::spawn(move || {
            let (mut s, _) = l.accept().unwrap();
            let mut buf = [0u8; 64];
            let _ = s.read(&mut buf);
            let _ = s.write_all(&bytes);
            std::thread::sleep(Duration::from_millis(100));
        });
        let e = Client::connect(
            addr,
            ClientOptions {
                connect_timeout: Duration::from_millis(500),
                ..opts()
            },
        )
        .err()
        .unwrap();
        // bytes that are no legacy packet name the port as not a legacy server
        assert!(
            e.to_string()
                .contains("is not a CoppeliaSim legacy remote API server")
                || e.to_string().contains("protocol")
                || e.to_string().contains("dropped"),
            "{e}"
        );
        t.join().unwrap();
    }
}

#[test]
fn legacy_server_serves_one_client_at_a_time() {
    let s = server(0);
    let mut a = Client::connect(s.local_addr(), opts()).unwrap();
    a.call1(Command::GetIntParam(1)).unwrap();
    let busy = ClientOptions {
        connect_timeout: Duration::from_millis(400),
        ..opts()
    };
    let e = Client::connect(s.local_addr(), busy).err().unwrap();
    assert!(e.to_string().contains("another client"), "{e}");
    a.close().unwrap();
    let mut c = Client::connect(s.local_addr(), opts()).unwrap();
    c.call1(Command::GetIntParam(1)).unwrap();
    c.close().unwrap();
    s.shutdown();
}

fn raw_exchange(
    s: &mut std::net::TcpStream,
    id: i32,
    blocks: Vec<vrep_maze::legacy::wire::Block>,
) -> vrep_maze::legacy::wire::Message {
    use vrep_maze::legacy::wire::{
        MAX_PACKET_SIZE, Message, MessageHeader, read_message, write_message,
    };
    let m = Message {
        header: MessageHeader {
            message_id: id,
            ..Default::default()
        },
        blocks,
    };
    write_message(s, &m.encode(), MAX_PACKET_SIZE).unwrap();
    Message::decode(&read_message(s).unwrap()).unwrap()
}

#[test]
fn legacy_server_echoes_unknown_commands_with_the_error_bit_and_survives_garbage() {
    use vrep_maze::legacy::wire::Block;
    let s = server(0);
    // garbage: the server drops that client and serves the next one
    let mut g = std::net::TcpStream::connect(s.local_addr()).unwrap();
    g.write_all(b"GET / HTTP/1.1\r\nHost: x\r\n\r\n").unwrap();
    let mut buf = [0u8; 16];
    g.set_read_timeout(Some(Duration::from_secs(2))).unwrap();
    assert_eq!(
        g.read(&mut buf).unwrap_or(0),
        0,
        "connection closed without a reply"
    );
    let mut raw = std::net::TcpStream::connect(s.local_addr()).unwrap();
    raw.set_read_timeout(Some(Duration::from_secs(2))).unwrap();
    let joint = Block {
        cmd: 0x1001 | 0x10000,
        delay: 0,
        sim_time: 0,
        status: 0,
        id_data: 7i32.to_le_bytes().to_vec(),
        data: vec![1, 2, 3],
        split: None,
    };
    let mut reply = raw_exchange(&mut raw, 0, vec![joint.clone()]);
    let mut id = 1;
    while reply.blocks.is_empty() {
        std::thread::sleep(Duration::from_millis(2));
        reply = raw_exchange(&mut raw, id, vec![]);
        id += 1;
    }
    assert!(reply.header.message_id >= 0);
    let b = &reply.blocks[0];
    assert_eq!(
        (b.cmd, b.status, &b.id_data, &b.data),
        (joint.cmd, 1, &joint.id_data, &joint.data)
    );
    s.shutdown();
}

#[test]
fn legacy_kill_must_be_the_last_block() {
    let s = server(0);
    let mut raw = std::net::TcpStream::connect(s.local_addr()).unwrap();
    raw.set_read_timeout(Some(Duration::from_secs(2))).unwrap();
    let kill = Command::KillConnection.to_block(0);
    let ping = Command::GetIntParam(1).to_block(0x10000);
    // kill not last: the session goes on
    raw_exchange(&mut raw, 0, vec![kill.clone(), ping]);
    raw_exchange(&mut raw, 1, vec![]);
    // kill last: reply, then the server closes
    raw_exchange(&mut raw, 2, vec![kill]);
    let mut buf = [0u8; 8];
    assert_eq!(raw.read(&mut buf).unwrap_or(0), 0);
    s.shutdown();
}

/// Random bytes, random packets and random command blocks never take the server down.
#[test]
fn legacy_server_survives_fuzzed_clients() {
    use vrep_maze::legacy::wire::{Block, MAX_PACKET_SIZE, Message, MessageHeader, packetize};
    let s = server(0);
    let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut next = move || {
        x ^= x << 13;
        x ^= x >> 7;
        x ^= x << 17;
        x
    };
    let ids = [
        0x000A, 0x1007, 0x1012, 0x101A, 0x101B, 0x101C, 0x1021, 0x1022, 0x1028, 0x102A, 0x102E,
        0x200C, 0x200D, 0x200E, 0x3001, 0x3401, 0x1001,
    ];
    for case in 0..60 {
        let mut conn = std::net::TcpStream::connect(s.local_addr()).unwrap();
        conn.set_read_timeout(Some(Duration::from_millis(300)))
            .unwrap();
        let bytes: Vec<u8> = match case % 3 {
            0 => (0..(next() % 200)).map(|_| next() as u8).collect(),
            1 => {
                let body: Vec<u8> = (0..(18 + next() % 120)).map(|_| next() as u8).collect();
                let mut b = packetize(&body, MAX_PACKET_SIZE);
                b[8] = 11; // keep the version byte so the block decoder is reached
                b
            }
            _ => {
                let blocks = (0..(1 + next() % 5))
                    .map(|_| {
                        let raw = ids[(next() % ids.len() as u64) as usize];
                        let id_len = match raw {
                            0x1000..=0x1FFF => 4,
                            0x2000..=0x2FFF => 8,
                            _ => 0,
                        };
                        let mut id_data: Vec<u8> =
                            (0..id_len).map(|_| (next() % 40) as u8).collect();
                        if raw >= 0x3000 {
                            id_data = b"Line\0".to_vec();
                            if raw == 0x3401 {
                                id_data = b"\x01\0\0\0a\0b\0".to_vec();
                            }
                        }
                        Block {
                            cmd: raw as u32 | ((next() % 7) as u32) << 16,
                            delay: 0,
                            sim_time: 0,
                            status: (next() % 2) as u8,
                            id_data,
                            data: (0..(next() % 24)).map(|_| next() as u8).collect(),
                            split: None,
                        }
                    })
                    .collect();
                packetize(
                    &Message {
                        header: MessageHeader::default(),
                        blocks,
                    }
                    .encode(),
                    MAX_PACKET_SIZE,
                )
            }
        };
        let _ = conn.write_all(&bytes);
        let mut buf = [0u8; 4096];
        let _ = conn.read(&mut buf);
    }
    let mut c = Client::connect(s.local_addr(), opts()).unwrap();
    assert!(!c.call1(Command::GetIntParam(1)).unwrap().remote_error);
    c.close().unwrap();
    s.shutdown();
}

#[test]
fn legacy_client_retries_while_the_server_recreates_its_socket() {
    let cfg = ServerConfig {
        listen: "127.0.0.1:0".parse().unwrap(),
        rebind_delay: Duration::from_millis(600),
        ..Default::default()
    };
    let s = spawn(cfg, Simulator::new(Scene::course(), 0)).unwrap();
    let a = Client::connect(s.local_addr(), opts()).unwrap();
    a.close().unwrap();
    std::thread::sleep(Duration::from_millis(150));
    assert!(
        std::net::TcpStream::connect(s.local_addr()).is_err(),
        "refused while re-creating the socket"
    );
    let t = Instant::now();
    let mut b = Client::connect(s.local_addr(), opts()).unwrap();
    assert!(
        t.elapsed() >= Duration::from_millis(200),
        "{:?}",
        t.elapsed()
    );
    b.call1(Command::GetIntParam(1)).unwrap();
    b.close().unwrap();
    s.shutdown();
}
