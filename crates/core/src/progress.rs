//! How far a long step got, told as it goes ([`Progress`]): the core counts, an adapter
//! shows (the command line a progress bar on a terminal), and nothing here knows of a
//! terminal.

/// Told the length of a step and each advance: a picture's rows as they are written, say.
/// `Sync`, so a step may tell it from several threads.
pub trait Progress: Sync {
    /// The step has `steps` in all.
    fn set_length(&self, steps: u64);
    /// `steps` more are done.
    fn advance(&self, steps: u64);
}

/// Tells nobody: for a caller that shows no progress.
#[derive(Debug, Clone, Copy, Default)]
pub struct Silent;

impl Progress for Silent {
    fn set_length(&self, _steps: u64) {}

    fn advance(&self, _steps: u64) {}
}
