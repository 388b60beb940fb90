//! An error said on one line with its remedies on `hint:` lines, for failures whose fix is
//! a command-line option (the connection's own are [`super::connect`]'s).

/// A failure and what to do about it.
#[derive(Debug, thiserror::Error)]
#[error("{message}")]
pub(crate) struct Hinted {
    message: String,
    hints: Vec<String>,
}

impl Hinted {
    /// Remedies, one line each.
    pub(crate) fn hints(&self) -> Vec<String> {
        self.hints.clone()
    }
}

/// `message` with `hints`, as an error.
pub(crate) fn hinted(message: impl std::fmt::Display, hints: Vec<String>) -> anyhow::Error {
    anyhow::Error::new(Hinted {
        message: message.to_string(),
        hints,
    })
}
