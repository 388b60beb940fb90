//! A marker this tool leaves while a legacy remote API session is open, removed when the
//! session closes cleanly. CoppeliaSim refuses every legacy connection for about a minute
//! after a session it closed first whose client answered with its own close (spec
//! `real-coppeliasim-4.5.1.md`, "Why the legacy port refuses for a minute: TIME_WAIT"). Our client never leaves so,
//! but a run that ends with its session open can still cause it: CoppeliaSim drops a client
//! silent for 10 s (a suspended process) and the process's end then answers that close. A
//! marker whose process is gone says that an earlier run here ended so (killed, crashed,
//! suspended, a second Ctrl-C), so the next run knows when that refusal can be the cause of
//! a refused connection and waits it out only then.

use std::fs;
use std::io::Read;
use std::path::{Path, PathBuf};

/// The marker of sessions with the legacy remote API at `host:port` (one file per
/// simulator address, in the user's runtime directory or the temporary one).
#[derive(Debug, Clone)]
pub(crate) struct SessionMarker {
    path: PathBuf,
}

/// An earlier run that ended with its session open.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct LeftAbruptly {
    /// Its process id.
    pub pid: u32,
}

impl SessionMarker {
    /// The marker for `host:port`.
    pub(crate) fn for_address(host: &str, port: u16) -> SessionMarker {
        let dir = std::env::var_os("XDG_RUNTIME_DIR")
            .map(PathBuf::from)
            .filter(|d| d.is_dir())
            .unwrap_or_else(std::env::temp_dir);
        SessionMarker::in_dir(&dir, host, port)
    }

    /// The marker for `host:port` in `dir`.
    fn in_dir(dir: &Path, host: &str, port: u16) -> SessionMarker {
        let host: String = host
            .chars()
            .map(|c| {
                if c.is_ascii_alphanumeric() || c == '.' {
                    c
                } else {
                    '_'
                }
            })
            .collect();
        SessionMarker {
            path: dir.join(format!("vrep-maze-legacy-{host}-{port}.open")),
        }
    }

    /// The earlier run that ended with a session here open, if the marker says so: it
    /// exists and the process that wrote it no longer runs (a running one still holds its
    /// session, or is about to close it).
    pub(crate) fn left_abruptly(&self) -> Option<LeftAbruptly> {
        // a process id: a few bytes, whatever else lies at this path
        let mut text = String::new();
        fs::File::open(&self.path)
            .ok()?
            .take(64)
            .read_to_string(&mut text)
            .ok()?;
        let pid = text.trim().parse::<u32>().ok().unwrap_or(0);
        let running = pid == std::process::id()
            || (pid != 0
                && Path::new("/proc").is_dir()
                && Path::new(&format!("/proc/{pid}")).exists());
        (!running).then_some(LeftAbruptly { pid })
    }

    /// Notes that this process has a session open. Best effort: a marker that cannot be
    /// written only costs the next run its knowledge of an abrupt end.
    pub(crate) fn opened(&self) {
        let _ = fs::write(&self.path, format!("{}\n", std::process::id()));
    }

    /// Notes that no session is open any more (closed cleanly, or the refusal it could
    /// cause is over).
    pub(crate) fn closed(&self) {
        let _ = fs::remove_file(&self.path);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_marker_of_a_process_that_is_gone_says_it_left_abruptly() {
        let dir = tempfile::tempdir().unwrap();
        let marker = SessionMarker::in_dir(dir.path(), "::1", 19997);
        assert_eq!(marker.left_abruptly(), None, "no marker");
        marker.opened();
        assert_eq!(marker.left_abruptly(), None, "this process still runs");
        // a process id that is not running: above Linux's largest
        fs::write(&marker.path, "4194305\n").unwrap();
        assert_eq!(marker.left_abruptly(), Some(LeftAbruptly { pid: 4194305 }));
        marker.closed();
        assert_eq!(marker.left_abruptly(), None, "closed cleanly");
        assert!(marker.path.ends_with("vrep-maze-legacy-__1-19997.open"));
    }
}
