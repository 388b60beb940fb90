//! Errors said on one line with their remedies on `hint:` lines: failures whose fix is a
//! command-line option ([`Hinted`]) and connections that could not be made
//! ([`ConnectError`], made by [`super::connect`]).

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

/// A connection that could not be made, said on one line, with what to do about it.
#[derive(Debug, thiserror::Error)]
#[error("{message}")]
pub(crate) struct ConnectError {
    /// The error line.
    pub(crate) message: String,
    /// Remedies, one line each.
    pub(crate) hints: Vec<String>,
    /// Nothing accepted a connection (rather than something that is not the API answering).
    pub(crate) nothing_listens: bool,
    /// A legacy connection found a ZeroMQ peer: the ZeroMQ attempt tells what it is.
    pub(crate) zmq_peer: bool,
}

impl ConnectError {
    /// Remedies, one line each.
    pub(crate) fn hints(&self) -> Vec<String> {
        self.hints.clone()
    }
}
