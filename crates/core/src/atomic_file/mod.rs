//! Writing files so that an interrupted run never leaves half a file: write a temporary
//! sibling, flush it to disk, then rename it over the target. Only a regular file (or a new
//! one) is replaced so; a device, FIFO, socket or symbolic link (`/dev/null`, `/dev/stdout`,
//! a named pipe, a link into another folder) is written through, never replaced.

mod syncing;

use std::fs;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

use syncing::SyncingFile;

/// Writes what `write` produces to `path`: atomically if `path` is a regular file or does
/// not exist, straight into it otherwise (see the module docs).
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> io::Result<()> {
    match fs::symlink_metadata(path) {
        Ok(meta) if !meta.file_type().is_file() => write_through(path, write),
        _ => write_replacing(path, write),
    }
}

/// Writes into whatever `path` is (following a link), truncating it if it is a regular file.
fn write_through(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> io::Result<()> {
    let regular = fs::metadata(path).is_ok_and(|m| m.is_file());
    let file = fs::OpenOptions::new()
        .write(true)
        .truncate(regular)
        .open(path)?;
    let mut out = io::BufWriter::new(file);
    write(&mut out)?;
    out.flush()
}

/// Writes a temporary sibling, flushes it to disk (while writing, see [`SyncingFile`]) and
/// renames it over `path`. A file that is replaced must be one the user could write in
/// place (else the OS's "permission denied", nothing written), and its replacement gets
/// its mode, owner and group; where the owner or group cannot be given (another user's
/// file that the user may write), the file is written in place instead, so it keeps them.
fn write_replacing(
    path: &Path,
    write: impl FnOnce(&mut dyn Write) -> io::Result<()>,
) -> io::Result<()> {
    let replaced = match fs::metadata(path) {
        Ok(meta) => {
            // opening for writing asks the OS exactly what writing in place would
            fs::OpenOptions::new().write(true).open(path)?;
            Some(meta)
        }
        Err(_) => None,
    };
    let temp = temporary_sibling(path)?;
    let mut write = Some(write);
    let result = (|| -> io::Result<()> {
        let file = fs::File::create(&temp)?;
        if let Some(meta) = &replaced
            && !keeps_owner(&file, meta)
        {
            return Err(io::Error::other(OwnerNotKept));
        }
        if let Some(meta) = &replaced {
            file.set_permissions(meta.permissions())?;
        }
        let mut file = io::BufWriter::new(SyncingFile::new(file));
        let write = write.take().expect("written once");
        write(&mut file)?;
        file.into_inner().map_err(|e| e.into_error())?.sync_all()?;
        fs::rename(&temp, path)
    })();
    if result.is_err() {
        let _ = fs::remove_file(&temp);
    }
    match (result, write) {
        (Err(e), Some(write)) if e.get_ref().is_some_and(|inner| inner.is::<OwnerNotKept>()) => {
            write_through(path, write)
        }
        (result, _) => result,
    }
}

/// The replacement of another user's file could not be given its owner or group.
#[derive(Debug, thiserror::Error)]
#[error("the replaced file's owner or group cannot be kept")]
struct OwnerNotKept;

/// Gives `file` the owner and group of `meta` (the file it replaces); `false` where the OS
/// does not permit it (only root may give a file away).
fn keeps_owner(file: &fs::File, meta: &fs::Metadata) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        let Ok(ours) = file.metadata() else {
            return false;
        };
        if (ours.uid(), ours.gid()) == (meta.uid(), meta.gid()) {
            return true;
        }
        std::os::unix::fs::fchown(file, Some(meta.uid()), Some(meta.gid())).is_ok()
    }
    #[cfg(not(unix))]
    {
        let _ = (file, meta);
        true
    }
}

/// `dir/.name.tmp-<pid>-<thread>`: unique per process and thread, hidden, beside the target
/// (a rename only stays atomic within one file system).
fn temporary_sibling(path: &Path) -> io::Result<PathBuf> {
    let name = path
        .file_name()
        .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "not a file name"))?;
    let mut temp = std::ffi::OsString::from(".");
    temp.push(name);
    temp.push(format!(
        ".tmp-{}-{:?}",
        std::process::id(),
        std::thread::current().id()
    ));
    let temp: String = temp
        .to_string_lossy()
        .chars()
        .filter(|c| c.is_alphanumeric() || "._-".contains(*c))
        .collect();
    Ok(path.with_file_name(temp))
}

/// Removes the temporary files that [`write_atomically`] left in `dir` when its process was
/// killed before it could rename them (a process still running keeps its own). Returns how
/// many it removed.
pub fn remove_stale_temporaries(dir: &Path) -> io::Result<usize> {
    let mut removed = 0;
    for entry in fs::read_dir(dir)? {
        let entry = entry?;
        let name = entry.file_name();
        let Some(pid) = temporary_owner(&name.to_string_lossy()) else {
            continue;
        };
        if pid != std::process::id() && !process_running(pid, &entry.path()) {
            fs::remove_file(entry.path())?;
            removed += 1;
        }
    }
    Ok(removed)
}

/// The process that made a temporary sibling named `.name.tmp-<pid>-<thread>`, if `name` is one.
fn temporary_owner(name: &str) -> Option<u32> {
    let (_, tail) = name.strip_prefix('.')?.rsplit_once(".tmp-")?;
    let (pid, thread) = tail.split_once('-')?;
    thread.starts_with("ThreadId").then_some(())?;
    pid.parse().ok()
}

/// Whether process `pid` still runs: `/proc` tells where there is one; elsewhere a temporary
/// younger than an hour is taken to belong to a running process.
fn process_running(pid: u32, temporary: &Path) -> bool {
    let proc = Path::new("/proc");
    if proc.is_dir() {
        return proc.join(pid.to_string()).exists();
    }
    fs::metadata(temporary)
        .and_then(|m| m.modified())
        .is_ok_and(|t| t.elapsed().is_ok_and(|age| age.as_secs() < 3600))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_whole_files_and_leaves_no_temporaries() {
        let dir = tempfile::TempDir::new().unwrap();
        let path = dir.path().join("a.json");
        write_atomically(&path, |w| w.write_all(b"first")).unwrap();
        write_atomically(&path, |w| w.write_all(b"second")).unwrap();
        assert_eq!(fs::read(&path).unwrap(), b"second");
        let failed = write_atomically(&path, |w| {
            w.write_all(b"half")?;
            Err(io::Error::other("interrupted"))
        });
        assert!(failed.is_err());
        assert_eq!(
            fs::read(&path).unwrap(),
            b"second",
            "old file kept on failure"
        );
        let names: Vec<_> = fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names, vec![std::ffi::OsString::from("a.json")]);
    }

    #[cfg(unix)]
    #[test]
    fn links_and_special_files_are_written_through_never_replaced() {
        let dir = tempfile::TempDir::new().unwrap();
        let target = dir.path().join("target.json");
        fs::write(&target, b"old contents, longer than the new").unwrap();
        let link = dir.path().join("link.json");
        std::os::unix::fs::symlink(&target, &link).unwrap();
        write_atomically(&link, |w| w.write_all(b"new")).unwrap();
        assert!(
            fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        assert_eq!(fs::read(&target).unwrap(), b"new");

        let null = Path::new("/dev/null");
        write_atomically(null, |w| w.write_all(b"gone")).unwrap();
        assert!(
            !fs::metadata(null).unwrap().is_file(),
            "/dev/null is still a device"
        );

        let fifo = dir.path().join("fifo");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if made.is_ok_and(|s| s.success()) {
            let reader = {
                let fifo = fifo.clone();
                std::thread::spawn(move || fs::read(fifo).unwrap())
            };
            write_atomically(&fifo, |w| w.write_all(b"through the pipe")).unwrap();
            assert_eq!(reader.join().unwrap(), b"through the pipe");
            assert!(!fs::metadata(&fifo).unwrap().is_file(), "still a FIFO");
        }
        let names: Vec<_> = fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.contains(".tmp-"))
            .collect();
        assert!(names.is_empty(), "{names:?}");
    }

    #[test]
    fn stale_temporaries_of_dead_processes_are_removed_and_others_kept() {
        let dir = tempfile::TempDir::new().unwrap();
        let ours = temporary_sibling(&dir.path().join("a.json")).unwrap();
        let ours_name = ours.file_name().unwrap().to_string_lossy().into_owned();
        assert_eq!(temporary_owner(&ours_name), Some(std::process::id()));
        // a pid far above any Linux pid_max: no such process
        let dead = dir.path().join(".b.json.tmp-4294967290-ThreadId1");
        let keep = dir.path().join("b.json");
        let unrelated = dir.path().join(".c.json.tmp-notes");
        for p in [&ours, &dead, &keep, &unrelated] {
            fs::write(p, b"x").unwrap();
        }
        assert_eq!(remove_stale_temporaries(dir.path()).unwrap(), 1);
        assert!(!dead.exists());
        assert!(ours.exists() && keep.exists() && unrelated.exists());
    }
}
