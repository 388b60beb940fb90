//! Our ZeroMQ client against `serve` (both protocols) and against scripted fake servers:
//! timeouts, `_*wait*_` / `_*repeat*_`, malformed CBOR, recorded protocol-1 pairs.

use std::time::{Duration, Instant};

use ciborium::Value;
use vrep_maze::sim::{Scene, Simulator};
use vrep_maze::zmq_api::cbor::{self, int};
use vrep_maze::zmq_api::message::{Protocol, Request};
use vrep_maze::zmq_api::{Client, ClientOptions, ServerConfig, ServerHandle, ZmqError, spawn};

fn serve(protocol: Protocol, fps: i32) -> ServerHandle {
    let cfg = ServerConfig {
        listen: "127.0.0.1:0".parse().unwrap(),
        protocol,
        ..Default::default()
    };
    spawn(cfg, Simulator::new(Scene::course(), fps)).unwrap()
}

fn opts(port: u16, ms: u64) -> ClientOptions {
    ClientOptions {
        port,
        timeout: Duration::from_millis(ms),
        ..Default::default()
    }
}

fn text(s: &str) -> Value {
    Value::Text(s.into())
}

fn exercise(protocol: Protocol) {
    let s = serve(protocol, 0);
    let mut c = Client::connect(&opts(s.local_addr().port(), 3000)).unwrap();
    assert_eq!(c.protocol(), Some(protocol));
    let line = c.call_int("sim.getObject", vec![text("/Line")]).unwrap();
    let maze = c.call_int("sim.getObject", vec![text("/Maze")]).unwrap();
    let missing = c.call("sim.getObject", vec![text("/Nope")]).unwrap_err();
    assert!(matches!(missing, ZmqError::Remote { .. }), "{missing}");
    let none = c.call_int(
        "sim.getObject",
        vec![text("/Nope"), cbor::map([("noError", Value::Bool(true))])],
    );
    assert_eq!(none.unwrap(), -1);
    let copies = c
        .call1(
            "sim.copyPasteObjects",
            vec![Value::Array(vec![int(line.into())]), int(0)],
        )
        .unwrap();
    let copy = cbor::handles(&copies).unwrap()[0];
    let path = c
        .call1("sim.getObjectAlias", vec![int(copy.into()), int(1)])
        .unwrap();
    assert_eq!(cbor::text(&path), Some("/Line[1]"));
    assert_eq!(
        c.call_int("sim.getObject", vec![text("/Line[1]")]).unwrap(),
        copy
    );
    // both argument orders of setObjectPosition
    c.call(
        "sim.setObjectPosition",
        vec![
            int(copy.into()),
            int(-1),
            cbor::float_array(&[1.0, 2.0, 0.001]),
        ],
    )
    .unwrap();
    let p = c
        .call1("sim.getObjectPosition", vec![int(copy.into()), int(-1)])
        .unwrap();
    assert_eq!(cbor::numbers::<3>(&p), Some([1.0, 2.0, 0.001]));
    c.call(
        "sim.setObjectPosition",
        vec![
            int(copy.into()),
            cbor::float_array(&[0.5, 0.0, 0.0]),
            int(maze.into()),
        ],
    )
    .unwrap();
    let p = c
        .call1(
            "sim.getObjectPosition",
            vec![int(copy.into()), int(maze.into())],
        )
        .unwrap();
    assert_eq!(cbor::numbers::<3>(&p), Some([0.5, 0.0, 0.0]));
    c.call(
        "sim.setObjectParent",
        vec![int(copy.into()), int(maze.into()), Value::Bool(true)],
    )
    .unwrap();
    let kids = c
        .call1(
            "sim.getObjectsInTree",
            vec![int(maze.into()), int(-2), int(1)],
        )
        .unwrap();
    assert_eq!(cbor::handles(&kids), Some(vec![copy]));
    let err = c.call("sim.x", vec![]).unwrap_err();
    assert_eq!(err.to_string(), "sim.x: No such function: sim.x");
    assert!(err.is_no_such_function());
    // a function with no return value answers an empty map: seen as no values
    assert_eq!(
        c.call(
            "sim.removeObjects",
            vec![Value::Array(vec![int(copy.into())])]
        )
        .unwrap(),
        vec![]
    );
    // removing it again succeeds silently, as on a real 4.5.1
    // (`../shared/spec/real-coppeliasim-4.5.1.md`, "ZeroMQ API details")
    assert_eq!(
        c.call(
            "sim.removeObjects",
            vec![Value::Array(vec![int(copy.into())])]
        )
        .unwrap(),
        vec![]
    );
    assert_eq!(c.call_int("sim.getInt32Param", vec![int(26)]).unwrap(), 0);
    let stats = c.stats();
    assert!(stats.round_trips >= stats.calls);
    c.close();
    s.shutdown();
}

#[test]
fn zmq_client_against_serve_protocol_2() {
    exercise(Protocol::V2);
}

#[test]
fn zmq_client_against_serve_protocol_1() {
    exercise(Protocol::V1);
}

#[test]
fn zmq_stop_simulation_goes_through_wait() {
    let s = serve(Protocol::V2, 0);
    s.with_sim(|sim| sim.start());
    let mut c = Client::connect(&opts(s.local_addr().port(), 3000)).unwrap();
    assert_eq!(c.call_int("sim.getSimulationState", vec![]).unwrap(), 17);
    let before = c.stats().round_trips;
    assert_eq!(c.call("sim.stopSimulation", vec![]).unwrap(), vec![]);
    assert_eq!(c.stats().round_trips - before, 2, "request + _*executed*_");
    assert_eq!(c.call_int("sim.getSimulationState", vec![]).unwrap(), 0);
    s.shutdown();
}

#[test]
fn zmq_idle_fps_paces_spaced_calls() {
    // protocol 1 (4.5.1): one request per main-loop pass, so lock-step calls at idle fps 8
    // take a pass each (93-125 ms measured on a real 4.5.1)
    let s = serve(Protocol::V1, 8);
    let mut c = Client::connect(&opts(s.local_addr().port(), 3000)).unwrap();
    let t = Instant::now();
    for _ in 0..4 {
        c.call("sim.getSimulationState", vec![]).unwrap();
    }
    assert!(
        t.elapsed() >= Duration::from_millis(3 * 100),
        "4 calls at 8 fps took {:?}",
        t.elapsed()
    );
    s.shutdown();
    // protocol 2 (4.6+): within a pass that served a request the add-on keeps serving for
    // 50 ms, so back-to-back calls are not paced one per pass: 40 calls take well under
    // the 39 passes (4.9 s) they would take paced, however loaded the machine
    let s = serve(Protocol::V2, 8);
    let mut c = Client::connect(&opts(s.local_addr().port(), 3000)).unwrap();
    c.call("sim.getSimulationState", vec![]).unwrap();
    let t = Instant::now();
    for _ in 0..40 {
        c.call("sim.getSimulationState", vec![]).unwrap();
    }
    assert!(
        t.elapsed() < Duration::from_millis(39 * 125 / 2),
        "40 back-to-back calls took {:?}",
        t.elapsed()
    );
    s.shutdown();
}

#[test]
fn zmq_request_without_uuid_is_an_old_client() {
    let s = serve(Protocol::V2, 0);
    let reply = raw_exchange(
        s.local_addr().port(),
        &Request::v1("sim.getSimulationState", vec![]).encode(),
    );
    let v = cbor::decode(&reply).unwrap();
    assert_eq!(cbor::get(&v, "success"), Some(&Value::Bool(false)));
    assert!(
        cbor::text(cbor::get(&v, "error").unwrap())
            .unwrap()
            .contains("does not match")
    );
    s.shutdown();
}

fn raw_exchange(port: u16, bytes: &[u8]) -> Vec<u8> {
    let ctx = zmq::Context::new();
    let sock = ctx.socket(zmq::REQ).unwrap();
    sock.set_rcvtimeo(3000).unwrap();
    sock.set_linger(0).unwrap();
    sock.connect(&format!("tcp://127.0.0.1:{port}")).unwrap();
    sock.send(bytes, 0).unwrap();
    sock.recv_bytes(0).unwrap()
}

fn hex(s: &str) -> Vec<u8> {
    let s: String = s.split_whitespace().collect();
    (0..s.len())
        .step_by(2)
        .map(|i| u8::from_str_radix(&s[i..i + 2], 16).unwrap())
        .collect()
}

/// Protocol 1 (CoppeliaSim 4.5.1) request/reply pairs, byte for byte: `{func, args}` in,
/// `{success, ret}` / `{success: false, error}` out, empty returns as an empty map.
#[test]
fn zmq_protocol_1_recorded_pairs() {
    let s = serve(Protocol::V1, 0);
    let port = s.local_addr().port();
    let line = s.with_sim(|sim| sim.scene.resolve("Line").unwrap());
    assert_eq!(line, 12);
    let pairs = [
        // {"func": "sim.getObject", "args": ["/Line"]} -> {"success": true, "ret": [12]}
        (
            "a2 64 66756e63 6d 73696d2e6765744f626a656374 64 61726773 81 65 2f4c696e65",
            "a2 67 73756363657373 f5 63 726574 81 0c",
        ),
        // {"func": "sim.getObjectPosition", "args": [12, -1]} -> ret [[0.0, 0.0, 0.001]]
        // (floats in their shortest exact width, as the Lua encoder may also pick)
        (
            "a2 64 66756e63 75 73696d2e6765744f626a656374506f736974696f6e 64 61726773 82 0c 20",
            "a2 67 73756363657373 f5 63 726574 81 83 f90000 f90000 fb3f50624dd2f1a9fc",
        ),
        // {"func": "sim.setObjectPosition", "args": [12, -1, [0, 0, 0.5]]} -> {"success": true, "ret": {}}
        (
            "a2 64 66756e63 75 73696d2e7365744f626a656374506f736974696f6e 64 61726773 83 0c 20 83 00 00 f93800",
            "a2 67 73756363657373 f5 63 726574 a0",
        ),
        // {"func": "sim.x", "args": []} -> {"success": false, "error": "No such function: sim.x"}
        (
            "a2 64 66756e63 65 73696d2e78 64 61726773 80",
            "a2 67 73756363657373 f4 65 6572726f72 77 4e6f20737563682066756e6374696f6e3a2073696d2e78",
        ),
        // protocol 1 has no zmqRemoteApi.require
        (
            "a2 64 66756e63 74 7a6d7152656d6f74654170692e72657175697265 64 61726773 81 63 73696d",
            "a2 67 73756363657373 f4 65 6572726f72 78 26 4e6f20737563682066756e6374696f6e3a207a6d7152656d6f74654170692e72657175697265",
        ),
    ];
    for (req, want) in pairs {
        assert_eq!(raw_exchange(port, &hex(req)), hex(want), "request {req}");
    }
    s.shutdown();
}

/// A scripted REP server: answers each request with the next scripted reply (raw bytes, or
/// `None` = stay silent until the client gave up), records the requests.
fn fake_server(script: Vec<Option<Vec<u8>>>) -> (u16, std::thread::JoinHandle<Vec<Value>>) {
    let ctx = zmq::Context::new();
    let sock = ctx.socket(zmq::REP).unwrap();
    sock.set_linger(0).unwrap();
    sock.set_rcvtimeo(5000).unwrap();
    sock.bind("tcp://127.0.0.1:*").unwrap();
    let port: u16 = sock
        .get_last_endpoint()
        .unwrap()
        .unwrap()
        .rsplit(':')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    let t = std::thread::spawn(move || {
        let _ctx = ctx;
        let mut seen = vec![];
        for reply in script {
            let Ok(req) = sock.recv_bytes(0) else { break };
            seen.push(cbor::decode(&req).unwrap());
            match reply {
                Some(r) => sock.send(r, 0).unwrap(),
                None => {
                    // past the client's timeout (2 s)
                    std::thread::sleep(Duration::from_millis(2500));
                    // the client has dropped this socket: the reply goes nowhere
                    sock.send(
                        cbor::encode(&cbor::map([("ret", Value::Array(vec![int(0)]))])),
                        0,
                    )
                    .unwrap();
                }
            }
        }
        seen
    });
    (port, t)
}

fn reply(v: Value) -> Option<Vec<u8>> {
    Some(cbor::encode(&v))
}

#[test]
fn zmq_client_runs_the_wait_and_repeat_loop() {
    let func = |f: &str| cbor::map([("func", text(f)), ("args", Value::Array(vec![]))]);
    let (port, t) = fake_server(vec![
        reply(func("_*repeat*_")),
        reply(func("_*wait*_")),
        reply(func("_*repeat*_")),
        reply(func("_*wait*_")),
        reply(cbor::map([("ret", Value::Array(vec![int(42)]))])),
    ]);
    let mut c = Client::open(&opts(port, 2000)).unwrap();
    assert_eq!(
        c.call_int("sim.getObject", vec![text("/Line")]).unwrap(),
        42
    );
    assert_eq!((c.stats().calls, c.stats().round_trips), (1, 5));
    let seen = t.join().unwrap();
    let funcs: Vec<&str> = seen
        .iter()
        .map(|v| cbor::text(cbor::get(v, "func").unwrap()).unwrap())
        .collect();
    // a repeat resends the last message: the call before any wait, `_*executed*_` after one
    assert_eq!(
        funcs,
        [
            "sim.getObject",
            "sim.getObject",
            "_*executed*_",
            "_*executed*_",
            "_*executed*_"
        ]
    );
    assert_eq!(seen[0], seen[1], "repeat resends the request unchanged");
    for v in &seen {
        assert!(cbor::get(v, "uuid").is_some() && cbor::get(v, "argsL").is_some());
    }
    std::mem::forget(c); // no _*end*_ exchange with the finished fake
}

#[test]
fn zmq_client_times_out_then_recovers_with_a_fresh_socket() {
    let (port, t) = fake_server(vec![
        None,
        reply(cbor::map([("ret", Value::Array(vec![int(7)]))])),
    ]);
    // long enough that the second call's reply comes within it on a loaded machine
    let mut c = Client::open(&opts(port, 2000)).unwrap();
    let e = c.call("sim.getSimulationState", vec![]).unwrap_err();
    assert!(matches!(e, ZmqError::Timeout { .. }), "{e}");
    assert!(e.to_string().contains("no reply"), "{e}");
    // the fake answers the first request late (to the dropped socket), then the second
    std::thread::sleep(Duration::from_millis(600));
    assert_eq!(c.call_int("sim.getSimulationState", vec![]).unwrap(), 7);
    t.join().unwrap();
    std::mem::forget(c);
}

#[test]
fn zmq_client_reports_malformed_replies_without_panicking() {
    let bad: Vec<Option<Vec<u8>>> = vec![
        Some(vec![0xff, 0x00]),
        Some(vec![]),
        Some(hex("a1 63 726574")),
        reply(cbor::map([("ret", text("x"))])),
        reply(int(3)),
        reply(cbor::map([("success", int(1))])),
        reply(cbor::map([("ok", Value::Bool(true))])),
    ];
    let n = bad.len();
    let (port, t) = fake_server(bad);
    let mut c = Client::open(&opts(port, 2000)).unwrap();
    for _ in 0..n {
        let e = c.call("sim.getSimulationState", vec![]).unwrap_err();
        assert!(matches!(e, ZmqError::Malformed { .. }), "{e}");
        assert!(!e.to_string().contains('\n'));
    }
    t.join().unwrap();
    std::mem::forget(c);
}

#[test]
fn zmq_connect_to_a_closed_port_is_a_clear_error() {
    let port = std::net::TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port();
    let e = Client::connect(&opts(port, 500)).unwrap_err();
    assert!(matches!(e, ZmqError::Connect { .. }), "{e}");
    assert!(e.to_string().contains(&format!("tcp://127.0.0.1:{port}")));
}

#[test]
fn zmq_server_answers_malformed_requests_and_keeps_serving() {
    let s = serve(Protocol::V2, 0);
    let port = s.local_addr().port();
    for bad in [
        vec![0xff],
        vec![],
        hex("a1 64 66756e63 01"),
        hex("83 01 02 03"),
        hex("a2 64 66756e63 61 66 64 61726773 05"),
    ] {
        let v = cbor::decode(&raw_exchange(port, &bad)).unwrap();
        let err = cbor::text(cbor::get(&v, "err").unwrap())
            .unwrap()
            .to_string();
        assert!(err.starts_with("malformed request"), "{err}");
    }
    let mut c = Client::connect(&opts(port, 3000)).unwrap();
    assert_eq!(c.call_int("sim.getSimulationState", vec![]).unwrap(), 0);
    // wrong argument types are Lua-style errors, not crashes
    let e = c
        .call("sim.setObjectPosition", vec![text("x")])
        .unwrap_err();
    assert!(e.to_string().contains("argument 1"), "{e}");
    s.shutdown();
}

#[test]
fn zmq_over_ipv6_loopback() {
    let cfg = ServerConfig {
        listen: "[::1]:0".parse().unwrap(),
        ..Default::default()
    };
    let Ok(s) = spawn(cfg, Simulator::new(Scene::course(), 0)) else {
        eprintln!("no IPv6 loopback here; skipped");
        return;
    };
    let options = ClientOptions {
        host: "::1".into(),
        ..opts(s.local_addr().port(), 3000)
    };
    let mut c = Client::connect(&options).unwrap();
    assert!(c.endpoint().starts_with("tcp://[::1]:"));
    assert_eq!(c.call_int("sim.getSimulationState", vec![]).unwrap(), 0);
    drop(c);
    s.shutdown();
}

/// A ROUTER fake of a protocol-2 add-on: answers `warm_up` lone requests at once, then for
/// each of `batches` takes every request that arrives within 300 ms before it answers any,
/// and returns how many requests each batch held.
fn batching_server(warm_up: usize, batches: usize) -> (u16, std::thread::JoinHandle<Vec<usize>>) {
    let ctx = zmq::Context::new();
    let sock = ctx.socket(zmq::ROUTER).unwrap();
    sock.set_linger(0).unwrap();
    sock.bind("tcp://127.0.0.1:*").unwrap();
    let endpoint = sock.get_last_endpoint().unwrap().unwrap();
    let port: u16 = endpoint.rsplit(':').next().unwrap().parse().unwrap();
    let t = std::thread::spawn(move || {
        let _ctx = ctx;
        let answer = |frames: &[Vec<u8>], k: i64| {
            let body = cbor::encode(&cbor::map([("ret", Value::Array(vec![int(k)]))]));
            sock.send_multipart([frames[0].clone(), vec![], body], 0)
                .unwrap();
        };
        for k in 0..warm_up {
            let frames = sock.recv_multipart(0).unwrap();
            answer(&frames, k as i64);
        }
        let mut sizes = vec![];
        for _ in 0..batches {
            let mut held = vec![sock.recv_multipart(0).unwrap()];
            while sock.poll(zmq::POLLIN, 300).unwrap() > 0 {
                held.push(sock.recv_multipart(0).unwrap());
            }
            for (k, frames) in held.iter().enumerate() {
                answer(frames, k as i64);
            }
            sizes.push(held.len());
        }
        sizes
    });
    (port, t)
}

/// Over protocol 2, `call_all` sends independent calls before reading any reply (a 4.10
/// add-on answers each as it comes), but a call that may be answered `_*wait*_` (`sim.step`)
/// goes on its own: the add-on would take the next queued request for its `_*executed*_`.
#[test]
fn zmq_protocol_2_calls_are_sent_together_unless_one_may_wait() {
    let (port, t) = batching_server(1, 3);
    let mut c = Client::open(&opts(port, 5000)).unwrap();
    // the first reply, `{ret: [...]}`, tells protocol 2
    c.call_int("sim.getSimulationState", vec![]).unwrap();
    assert_eq!(c.protocol(), Some(Protocol::V2));
    let read = |name: &str| ("sim.getInt32Signal", vec![text(name)]);
    let outcomes = c.call_all(&[read("a"), read("b"), read("c")]).unwrap();
    let got: Vec<i64> = outcomes
        .into_iter()
        .map(|o| cbor::int32(&o.unwrap()[0]).unwrap().into())
        .collect();
    assert_eq!(got, [0, 1, 2], "the replies in the order of the calls");
    c.call_all(&[read("a"), ("sim.step", vec![])]).unwrap();
    std::mem::forget(c); // no _*end*_ exchange with the finished fake
    assert_eq!(t.join().unwrap(), [3, 1, 1]);
}

/// `read_all` makes several reads by one request (a Lua program, `zmq_api::calls`), each
/// outcome what `call_all` gives: a handle, a failure naming the object, a missing function;
/// over both protocols.
#[test]
fn reads_made_by_one_request_answer_what_separate_calls_answer() {
    use vrep_maze::sim::cost::Op;
    for protocol in [Protocol::V1, Protocol::V2] {
        let cfg = ServerConfig {
            listen: "127.0.0.1:0".parse().unwrap(),
            protocol,
            ..Default::default()
        };
        let s = spawn(cfg, Simulator::new(Scene::course(), 0)).unwrap();
        let mut c = Client::connect(&opts(s.local_addr().port(), 3000)).unwrap();
        let no_error = || cbor::map([("noError", Value::Bool(true))]);
        let reads = [
            ("sim.getObject", vec![text("/Line"), no_error()]),
            ("sim.getObject", vec![text("/Nothing"), no_error()]),
            ("sim.getObjectPose", vec![int(999_999), int(-1)]),
            ("sim.getInt32Signal", vec![text("vrep_maze_absent")]),
            ("sim.noSuchFunction", vec![]),
        ];
        let before = c.stats().round_trips;
        s.with_sim(|sim| sim.ledger = Some(vec![]));
        let together = c.read_all(&reads).unwrap();
        assert_eq!(c.stats().round_trips - before, 1, "{protocol:?}");
        // priced as one request of five calls made inside the simulator
        let ledger = s.with_sim(|sim| sim.ledger.take()).unwrap();
        assert_eq!(ledger.len(), 1);
        let inside = ledger[0]
            .ops
            .iter()
            .filter(|op| matches!(op, Op::ProgramCall { .. }))
            .count();
        assert_eq!(inside, reads.len());
        let apart = c.call_all(&reads).unwrap();
        assert_eq!(together.len(), apart.len());
        for (k, (t, a)) in together.iter().zip(&apart).enumerate() {
            match (t, a) {
                (Ok(t), Ok(a)) => assert_eq!(t, a, "{protocol:?} read {k}"),
                (Err(t), Err(a)) => {
                    assert_eq!(t.is_no_such_function(), a.is_no_such_function());
                    let said = |e: &ZmqError| e.to_string().contains("object does not exist");
                    assert_eq!(said(t), said(a), "{protocol:?} read {k}: {t} / {a}");
                }
                other => panic!("{protocol:?} read {k}: {other:?}"),
            }
        }
        assert!(together[4].as_ref().unwrap_err().is_no_such_function());
        c.close();
        s.shutdown();
    }
}

/// More reads than one program holds go as several programs, one request each, their
/// outcomes in the order of the reads: a scene of thousands of recorded copies is read
/// without a request the simulator would take seconds over.
#[test]
fn reads_beyond_one_program_go_as_several_programs_in_order() {
    use vrep_maze::zmq_api::MAX_PROGRAM_CALLS;
    let cfg = ServerConfig {
        listen: "127.0.0.1:0".parse().unwrap(),
        protocol: Protocol::V2,
        ..Default::default()
    };
    let s = spawn(cfg, Simulator::new(Scene::course(), 0)).unwrap();
    let mut c = Client::connect(&opts(s.local_addr().port(), 3000)).unwrap();
    let names = ["/Line", "/Start", "/End"];
    let reads: Vec<(&str, Vec<Value>)> = (0..2 * MAX_PROGRAM_CALLS + 1)
        .map(|k| ("sim.getObject", vec![text(names[k % 3])]))
        .collect();
    let each: Vec<i64> = names
        .iter()
        .map(|n| c.call_int("sim.getObject", vec![text(n)]).unwrap().into())
        .collect();
    let before = c.stats().round_trips;
    let got = c.read_all(&reads).unwrap();
    assert_eq!(c.stats().round_trips - before, 3);
    assert_eq!(got.len(), reads.len());
    for (k, outcome) in got.iter().enumerate() {
        let handle = cbor::int32(&outcome.as_ref().unwrap()[0]).unwrap();
        assert_eq!(i64::from(handle), each[k % 3], "read {k}");
    }
    c.close();
    s.shutdown();
}

/// Where the server cannot run the program (this fake answers `[k]` to everything),
/// `read_all` sends the reads as `call_all` does, and sends no program again.
#[test]
fn reads_go_one_request_each_where_no_program_runs() {
    let (port, t) = batching_server(1, 3);
    let mut c = Client::open(&opts(port, 5000)).unwrap();
    c.call_int("sim.getSimulationState", vec![]).unwrap();
    let read = |name: &str| ("sim.getInt32Signal", vec![text(name)]);
    for _ in 0..2 {
        let outcomes = c.read_all(&[read("a"), read("b"), read("c")]).unwrap();
        let got: Vec<i64> = outcomes
            .into_iter()
            .map(|o| cbor::int32(&o.unwrap()[0]).unwrap().into())
            .collect();
        assert_eq!(got, [0, 1, 2]);
    }
    std::mem::forget(c); // no _*end*_ exchange with the finished fake
    // the program, then its reads sent together, then the next reads without a program
    assert_eq!(t.join().unwrap(), [1, 3, 3]);
}

/// A protocol-2 add-on charges a client's first request for making the client (5.5 ms on
/// 4.10, `CostModel::zmq_new_client`): once per client, again for a client that left with
/// `_*end*_` and came back, never over protocol 1.
#[test]
fn a_new_protocol_2_client_costs_once() {
    use vrep_maze::sim::{Timing, cost::Op};
    for (protocol, timing, per_client) in [
        (Protocol::V2, Timing::realistic_v4_10(), 1),
        (Protocol::V1, Timing::realistic(), 0),
    ] {
        let cfg = ServerConfig {
            listen: "127.0.0.1:0".parse().unwrap(),
            protocol,
            timing,
            ..Default::default()
        };
        let s = spawn(cfg, Simulator::new(Scene::course(), 0)).unwrap();
        s.with_sim(|sim| sim.ledger = Some(vec![]));
        for _ in 0..2 {
            let mut c = Client::connect(&opts(s.local_addr().port(), 3000)).unwrap();
            for _ in 0..3 {
                c.call_int("sim.getObject", vec![text("/Line")]).unwrap();
            }
            c.close();
        }
        let ledger = s.with_sim(|sim| sim.ledger.take()).unwrap();
        let new_clients = ledger
            .iter()
            .filter(|c| c.ops.contains(&Op::ZmqNewClient))
            .count();
        assert_eq!(new_clients, 2 * per_client, "{protocol:?}");
        assert!(ledger.len() >= 8, "{} requests", ledger.len());
        s.shutdown();
    }
}
