//! One connection kept open for many jobs ([`Session`]): a training loop that draws a new
//! maze every episode pays for connecting once, then each [`Session::apply`] costs only its
//! own requests.
//!
//! Each call stands on its own as a separate run does ([`super::session`]): it raises the
//! idle rate and restores it before it returns (at the user's rate 0 that is one read), it
//! claims the scene ([`super::lease`]) and surveys it again, since the user may have moved,
//! renamed or deleted objects, started the simulation or changed the idle rate in the
//! simulator between two calls. Nothing is kept raised across calls, so a Ctrl-C, a lost
//! connection or a crashed client between calls leaves the scene exactly as the user set it,
//! and one within a call leaves it as an interrupted `apply` does: repaired by the next
//! `apply` or `clear`. What the session does know for good is what the connection found
//! once (the API, the simulator's version, its protocol): the backend holds it.

use super::run::{Job, Picture, Report, RunError, run};
use super::{Backend, BackendError, ClearOptions, ClearReport, DrawError, ObjectNames};
use super::{Stage, clear, verify};

/// A connected simulator that runs job after job ([`Session::apply`], [`Session::clear`],
/// [`Session::verify`]) on one connection, closed by [`Session::close`] or on drop.
pub struct Session {
    /// The connection; `None` once closed.
    backend: Option<Box<dyn Backend>>,
}

/// What a [`Session`] was asked after [`Session::close`].
#[derive(Debug, thiserror::Error, PartialEq, Eq)]
#[error("the session is closed: connect again")]
pub struct Closed;

impl Session {
    /// A session on a connected `backend` (the command line's and Python's `connect`).
    pub fn new(backend: Box<dyn Backend>) -> Session {
        Session {
            backend: Some(backend),
        }
    }

    /// The connection, for what a session does not wrap (`inspect`, `score`), or [`Closed`].
    pub fn backend(&mut self) -> Result<&mut dyn Backend, Closed> {
        match self.backend.as_mut() {
            Some(backend) => Ok(backend.as_mut()),
            None => Err(Closed),
        }
    }

    /// Whether [`Session::close`] ended it.
    pub fn is_closed(&self) -> bool {
        self.backend.is_none()
    }

    /// One line naming the API, where it answered and the simulator's version.
    pub fn describe(&self) -> Option<String> {
        self.backend.as_ref().map(|b| b.describe())
    }

    /// Runs `job` ([`run`]: create what is missing, draw and verify, save) on the open
    /// connection, telling `progress` its stages.
    pub fn apply(
        &mut self,
        job: &Job<'_>,
        progress: &mut dyn FnMut(Stage),
    ) -> Result<Report, SessionError> {
        Ok(run(self.backend()?, job, progress)?)
    }

    /// Removes the drawn maze ([`clear()`]) on the open connection.
    pub fn clear(&mut self, opts: &ClearOptions) -> Result<ClearReport, SessionError> {
        Ok(clear(self.backend()?, opts)?)
    }

    /// Checks the scene against `picture` ([`verify()`] or [`super::mesh::verify()`]) on the
    /// open connection.
    pub fn verify(&mut self, picture: &Picture, names: &ObjectNames) -> Result<(), SessionError> {
        let scene = self.backend()?;
        Ok(match picture {
            Picture::Copies(drawing) => verify(scene, drawing, names),
            Picture::Mesh(maze) => super::mesh::verify(scene, maze, names),
        }?)
    }

    /// Ends the connection the way the official client does ([`Backend::close`]); later
    /// calls answer [`Closed`]. Closing a closed session does nothing.
    pub fn close(&mut self) -> Result<(), BackendError> {
        match self.backend.take() {
            Some(mut backend) => backend.close(),
            None => Ok(()),
        }
    }
}

impl Drop for Session {
    /// Closes the connection, ignoring errors (the backend's own drop would too).
    fn drop(&mut self) {
        let _ = self.close();
    }
}

/// Why a [`Session`] call failed.
#[derive(Debug, thiserror::Error)]
pub enum SessionError {
    /// The session was closed first.
    #[error(transparent)]
    Closed(#[from] Closed),
    /// An apply failed ([`RunError`]).
    #[error(transparent)]
    Run(#[from] RunError),
    /// A clear or verify failed ([`DrawError`]).
    #[error(transparent)]
    Draw(#[from] DrawError),
}
