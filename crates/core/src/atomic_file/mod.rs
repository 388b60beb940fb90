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
    let mut write = Some(write);
    match stage_replacing(path, &mut write)? {
        Some(temp) => fs::rename(&temp, path).inspect_err(|_| {
            let _ = fs::remove_file(&temp);
        }),
        None => write_through(
            path,
            write.take().expect("not called when the owner is not kept"),
        ),
    }
}

/// Writes what `write` produces (taken out of its option) to a temporary sibling of `path`
/// and flushes it to disk, ready to be renamed over `path` ([`write_replacing`]'s rules):
/// its path, or `None` where the replacement could not be given the replaced file's owner
/// or group (`write` then not called: the file is to be written in place). Nothing is left
/// behind on an error.
fn stage_replacing(
    path: &Path,
    write: &mut Option<impl FnOnce(&mut dyn Write) -> io::Result<()>>,
) -> io::Result<Option<PathBuf>> {
    let replaced = match fs::metadata(path) {
        Ok(meta) => {
            // opening for writing asks the OS exactly what writing in place would
            fs::OpenOptions::new().write(true).open(path)?;
            Some(meta)
        }
        Err(_) => None,
    };
    let temp = temporary_sibling(path)?;
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
        file.into_inner().map_err(|e| e.into_error())?.sync_all()
    })();
    match result {
        Ok(()) => Ok(Some(temp)),
        Err(e) => {
            let _ = fs::remove_file(&temp);
            if e.get_ref().is_some_and(|inner| inner.is::<OwnerNotKept>()) {
                Ok(None)
            } else {
                Err(e)
            }
        }
    }
}

/// A file of [`write_all_or_none`] that could not be written, and why.
#[derive(Debug, thiserror::Error)]
#[error("{}: {error}", path.display())]
pub struct WriteError {
    /// The file.
    pub path: PathBuf,
    /// What the OS said.
    pub error: io::Error,
}

/// One output of [`write_all_or_none`], made ready: a temporary sibling written and flushed
/// to disk, to be renamed over it, or the file itself opened, to be written through (a
/// link, a device, another user's file: [`write_atomically`]'s rules).
enum Staged<'a> {
    /// Renamed over `path` to commit.
    Renamed { temp: PathBuf, path: &'a Path },
    /// Written into `file` to commit (emptied first if `regular`).
    Through {
        file: fs::File,
        regular: bool,
        bytes: &'a [u8],
        path: &'a Path,
    },
}

impl Staged<'_> {
    /// Removes what staging made (the temporary sibling); nothing is written.
    fn discard(self) {
        if let Staged::Renamed { temp, .. } = self {
            let _ = fs::remove_file(temp);
        }
    }
}

/// Writes each of `files` (a path and its bytes) as [`write_atomically`] writes one, all or
/// none: every file is first written to a temporary sibling and flushed to disk (or, one to
/// be written through, opened), and only when all are ready are they written through and
/// renamed into place. A file that cannot be written (a dangling link, a folder in the way,
/// no permission, a full disk) fails the whole before any file changed, and no temporary is
/// left. Only a failure after that (a rename refused) can leave the files renamed before it.
pub fn write_all_or_none(files: &[(&Path, &[u8])]) -> Result<(), WriteError> {
    let mut staged = Vec::with_capacity(files.len());
    for &(path, bytes) in files {
        match stage(path, bytes) {
            Ok(ready) => staged.push(ready),
            Err(error) => {
                staged.into_iter().for_each(Staged::discard);
                return Err(WriteError {
                    path: path.to_path_buf(),
                    error,
                });
            }
        }
    }
    // the writes through first: a write can fail where a rename beside the file hardly does
    staged.sort_by_key(|s| matches!(s, Staged::Renamed { .. }));
    let mut staged = staged.into_iter();
    while let Some(ready) = staged.next() {
        let committed = match ready {
            Staged::Renamed { temp, path } => fs::rename(&temp, path)
                .inspect_err(|_| {
                    let _ = fs::remove_file(&temp);
                })
                .map_err(|error| (path, error)),
            Staged::Through {
                file,
                regular,
                bytes,
                path,
            } => write_into(file, regular, bytes).map_err(|error| (path, error)),
        };
        if let Err((path, error)) = committed {
            staged.for_each(Staged::discard);
            return Err(WriteError {
                path: path.to_path_buf(),
                error,
            });
        }
    }
    Ok(())
}

/// Makes `bytes` ready to be written to `path` ([`Staged`]).
fn stage<'a>(path: &'a Path, bytes: &'a [u8]) -> io::Result<Staged<'a>> {
    let through = || -> io::Result<Staged<'a>> {
        let regular = fs::metadata(path).is_ok_and(|m| m.is_file());
        // not emptied yet: only once every file is ready
        let file = fs::OpenOptions::new().write(true).open(path)?;
        Ok(Staged::Through {
            file,
            regular,
            bytes,
            path,
        })
    };
    match fs::symlink_metadata(path) {
        Ok(meta) if !meta.file_type().is_file() => through(),
        _ => {
            let mut write = Some(|w: &mut dyn Write| w.write_all(bytes));
            match stage_replacing(path, &mut write)? {
                Some(temp) => Ok(Staged::Renamed { temp, path }),
                None => through(),
            }
        }
    }
}

/// Writes `bytes` into `file` opened by [`stage`], emptied first if it is a regular file.
fn write_into(file: fs::File, regular: bool, bytes: &[u8]) -> io::Result<()> {
    if regular {
        file.set_len(0)?;
    }
    let mut out = io::BufWriter::new(file);
    out.write_all(bytes)?;
    out.flush()
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

    #[cfg(unix)]
    #[test]
    fn several_files_are_written_all_or_none() {
        let dir = tempfile::TempDir::new().unwrap();
        let names = |dir: &Path| {
            let mut names: Vec<String> = fs::read_dir(dir)
                .unwrap()
                .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .collect();
            names.sort();
            names
        };
        let (pgm, yaml) = (dir.path().join("m.pgm"), dir.path().join("m.yaml"));
        write_all_or_none(&[(&pgm, b"image"), (&yaml, b"map")]).unwrap();
        assert_eq!(fs::read(&pgm).unwrap(), b"image");
        assert_eq!(fs::read(&yaml).unwrap(), b"map");
        // a dangling link, a folder in the way: nothing changes, nothing is left
        let (s_pgm, s_yaml) = (dir.path().join("s.pgm"), dir.path().join("s.yaml"));
        std::os::unix::fs::symlink(dir.path().join("gone/s.yaml"), &s_yaml).unwrap();
        let e = write_all_or_none(&[(&s_pgm, b"image"), (&s_yaml, b"map")]).unwrap_err();
        assert_eq!(e.path, s_yaml);
        assert_eq!(e.error.kind(), io::ErrorKind::NotFound);
        fs::create_dir(dir.path().join("d.yaml")).unwrap();
        let e = write_all_or_none(&[(&pgm, b"new image"), (&dir.path().join("d.yaml"), b"map")])
            .unwrap_err();
        assert!(
            e.to_string()
                .starts_with(&dir.path().join("d.yaml").display().to_string())
        );
        assert_eq!(fs::read(&pgm).unwrap(), b"image", "the old file stays");
        assert_eq!(names(dir.path()), ["d.yaml", "m.pgm", "m.yaml", "s.yaml"]);
        // a link to a file is written through, with the rest
        let target = dir.path().join("target.yaml");
        fs::write(&target, b"old contents, longer than the new").unwrap();
        std::os::unix::fs::symlink(&target, s_yaml.with_file_name("t.yaml")).unwrap();
        write_all_or_none(&[
            (&s_pgm, b"image"),
            (&s_yaml.with_file_name("t.yaml"), b"map"),
        ])
        .unwrap();
        assert_eq!(fs::read(&target).unwrap(), b"map");
        assert_eq!(fs::read(&s_pgm).unwrap(), b"image");
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
