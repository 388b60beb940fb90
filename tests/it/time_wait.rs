//! The legacy port after a session, against `vrep-maze serve --timing realistic`, which
//! models CoppeliaSim 4.5.1's (`../shared/spec/real-coppeliasim-4.5.1.md`, "Why the legacy
//! port refuses for a minute: TIME_WAIT"): a client that waits for the server to close after
//! the kill reply leaves the port refusing for the TIME_WAIT penalty; ours leaves it
//! listening after the plugin's 0.5 s, however the run ends.

use std::io::Read;
use std::net::TcpStream;
use std::time::{Duration, Instant};

use vrep_maze::legacy::command::{Command, opmode};
use vrep_maze::legacy::wire::{
    MAX_PACKET_SIZE, Message, MessageHeader, read_message, write_message,
};

use crate::support::bin;
use crate::support::cli::{Serve, generate};

/// `serve` on a free port with realistic timing and `extra` options.
fn serve(extra: &[&str]) -> Serve {
    let mut args = vec!["--listen", "127.0.0.1:0", "--timing", "realistic"];
    args.extend_from_slice(extra);
    Serve::start(&args, 1)
}

/// How long after now the port first accepts a connection (tried every 10 ms), if within
/// `within`. The successful try is a port probe: it costs the next client the 0.5 s.
fn listens_after(port: &str, within: Duration) -> Option<Duration> {
    let started = Instant::now();
    while started.elapsed() < within {
        if TcpStream::connect(format!("127.0.0.1:{port}")).is_ok() {
            return Some(started.elapsed());
        }
        std::thread::sleep(Duration::from_millis(10));
    }
    None
}

/// A session that ends as many clients end it: the kill block, its reply, then the
/// client waits for the server's close and answers it with its own.
fn leave_after_the_server(port: &str) {
    let mut s = TcpStream::connect(format!("127.0.0.1:{port}")).unwrap();
    let kill = Message {
        header: MessageHeader::default(),
        blocks: vec![Command::KillConnection.to_block(opmode::ONESHOT)],
    };
    write_message(&mut s, &kill.encode(), MAX_PACKET_SIZE).unwrap();
    read_message(&mut s).unwrap();
    s.set_read_timeout(Some(Duration::from_secs(5))).unwrap();
    assert_eq!(
        s.read(&mut [0u8; 16]).unwrap(),
        0,
        "the server closes first"
    );
}

#[test]
fn a_client_that_waits_for_the_server_to_close_leaves_the_port_refusing_then_ours_does_not() {
    let dir = tempfile::tempdir().unwrap();
    let m = generate(dir.path(), "1", "dfs");
    // a penalty long enough that "listens at once" has seconds of room on a loaded machine
    let s = serve(&["--reconnect-penalty", "8", "--idle-fps", "0"]);
    let port = s.port();
    leave_after_the_server(&port);
    let refused_for = listens_after(&port, Duration::from_secs(30)).expect("listens again");
    assert!(refused_for > Duration::from_secs(7), "{refused_for:?}");
    for command in [vec!["apply", m.as_str()], vec!["clear"], vec!["inspect"]] {
        bin()
            .args(&command)
            .args(["--api", "legacy", "--port", &port, "--connect-timeout", "2"])
            .assert()
            .success();
        let after = listens_after(&port, Duration::from_secs(30)).expect("listens again");
        // well under the 8 s penalty its leaving would have cost
        assert!(after < Duration::from_secs(4), "{command:?}: {after:?}");
    }
}

#[test]
fn twenty_runs_back_to_back_all_connect_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let m = generate(dir.path(), "2", "dfs");
    // the 60 s penalty of realistic timing: one refusal would outlast every connect timeout
    let s = serve(&["--idle-fps", "0"]);
    let port = s.port();
    for run in 0..20 {
        let command = if run % 2 == 0 {
            vec!["apply", m.as_str()]
        } else {
            vec!["clear"]
        };
        // a refusal (60 s) would outlast the connect timeout: success is the proof
        bin()
            .args(&command)
            .args(["--api", "legacy", "--port", &port, "--connect-timeout", "3"])
            .assert()
            .success();
    }
}
