//! A file synced to disk while it is written, so that syncing it at the end is quick.
//!
//! An operating system keeps written data in memory and writes it to disk later: a big
//! file written at full speed is mostly still in memory when the final `sync_all` asks
//! for it, and that call then waits while the disk catches up (seconds for a 2 GB
//! layout). Here a helper thread asks for the data written so far every [`SYNC_EVERY`]
//! bytes, so the disk works while the file is still being produced.

use std::fs::File;
use std::io::{self, Write};
use std::sync::mpsc::{self, SyncSender};
use std::thread::{self, JoinHandle};

/// Bytes written between two background syncs.
const SYNC_EVERY: u64 = 64 << 20;

/// A file whose written data is synced in the background; [`sync_all`](Self::sync_all)
/// finishes the job.
pub(super) struct SyncingFile {
    file: File,
    /// Bytes written since the last background sync was asked for.
    unsynced: u64,
    every: u64,
    /// Wakes the helper; its handle. Started with the first background sync.
    helper: Option<(SyncSender<()>, JoinHandle<io::Result<()>>)>,
}

impl SyncingFile {
    /// `file`, synced in the background every [`SYNC_EVERY`] bytes.
    pub fn new(file: File) -> Self {
        Self::syncing_every(file, SYNC_EVERY)
    }

    fn syncing_every(file: File, every: u64) -> Self {
        Self {
            file,
            unsynced: 0,
            every,
            helper: None,
        }
    }

    /// Waits for the helper, then syncs data and metadata: the file is on disk when this
    /// returns `Ok`.
    pub fn sync_all(mut self) -> io::Result<()> {
        self.stop_helper()?;
        self.file.sync_all()
    }

    fn stop_helper(&mut self) -> io::Result<()> {
        match self.helper.take() {
            Some((wake, helper)) => {
                drop(wake);
                helper.join().expect("the sync helper does not panic")
            }
            None => Ok(()),
        }
    }

    /// Asks the helper (started on first use) to sync what has been written; if it is still
    /// busy with the previous request, that one will cover this data too.
    fn sync_in_background(&mut self) -> io::Result<()> {
        if self.helper.is_none() {
            let file = self.file.try_clone()?;
            let (wake, woken) = mpsc::sync_channel::<()>(1);
            let helper = thread::spawn(move || {
                for () in woken {
                    file.sync_data()?;
                }
                Ok(())
            });
            self.helper = Some((wake, helper));
        }
        if let Some((wake, _)) = &self.helper {
            // Full: a request is pending and will see this data. Gone: the helper failed,
            // and `sync_all` reports why.
            let _ = wake.try_send(());
        }
        Ok(())
    }
}

impl Write for SyncingFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let written = self.file.write(buf)?;
        self.unsynced += written as u64;
        if self.unsynced >= self.every {
            self.unsynced = 0;
            self.sync_in_background()?;
        }
        Ok(written)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.file.flush()
    }
}

impl Drop for SyncingFile {
    /// A file given up half-written (an error elsewhere) still waits for its helper, so no
    /// thread outlives it holding the file open.
    fn drop(&mut self) {
        let _ = self.stop_helper();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn everything_written_arrives_in_order() {
        let dir = tempfile::TempDir::new().unwrap();
        let path = dir.path().join("f");
        let mut file = SyncingFile::syncing_every(File::create(&path).unwrap(), 1000);
        let mut expected = Vec::new();
        for i in 0..50u8 {
            let chunk = vec![i; 333];
            file.write_all(&chunk).unwrap();
            expected.extend_from_slice(&chunk);
        }
        assert!(file.helper.is_some(), "background syncs were asked for");
        file.sync_all().unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), expected);
    }
}
