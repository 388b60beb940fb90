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
//!
//! A call that fails on the connection itself (the simulator closed or killed,
//! [`BackendError::Transport`]) leaves the session to connect again before its next call, when
//! it was opened with a way to ([`Session::reconnecting`]): a restarted simulator is then
//! drawn on by the next call, as a new `apply` would.

use super::backend::Backend;
use super::clear;
use super::clear::{ClearOptions, ClearReport};
use super::error::BackendError;
use super::error::DrawError;
use super::names::ObjectNames;
use super::report::Stage;
use super::run::{Job, Picture, Report, RunError, run};
use super::verify;

/// Makes a new connection to the same simulator ([`Session::reconnecting`]).
pub type Reconnect = Box<dyn FnMut() -> Result<Box<dyn Backend>, BackendError> + Send>;

/// A connected simulator that runs job after job ([`Session::apply`], [`Session::clear`],
/// [`Session::verify`]) on one connection, closed by [`Session::close`] or on drop.
pub struct Session {
    /// The connection; `None` once closed.
    backend: Option<Box<dyn Backend>>,
    /// How to connect again after the connection was lost, if the session may.
    reconnect: Option<Reconnect>,
    /// A call failed on the connection itself: the next one connects again first.
    lost: bool,
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
            reconnect: None,
            lost: false,
        }
    }

    /// A session on `backend` that connects again with `reconnect` before the call after
    /// one that lost the connection.
    pub fn reconnecting(backend: Box<dyn Backend>, reconnect: Reconnect) -> Session {
        Session {
            backend: Some(backend),
            reconnect: Some(reconnect),
            lost: false,
        }
    }

    /// The connection for the next call: a new one if a call lost it ([`Session::mark_lost`])
    /// and the session may connect again (a failed attempt leaves it lost, for the call
    /// after). For what a session does not wrap, as [`Session::backend`].
    pub fn connected(&mut self) -> Result<&mut dyn Backend, SessionError> {
        if self.backend.is_none() {
            return Err(Closed.into());
        }
        if self.lost
            && let Some(reconnect) = self.reconnect.as_mut()
        {
            let fresh = reconnect().map_err(DrawError::Backend)?;
            if let Some(mut old) = self.backend.replace(fresh) {
                let _ = old.close();
            }
            self.lost = false;
        }
        Ok(self.backend()?)
    }

    /// Notes whether `result` lost the connection, and passes it on.
    fn noted<T>(&mut self, result: Result<T, SessionError>) -> Result<T, SessionError> {
        if let Err(e) = &result {
            self.lost |= e.lost_connection();
        }
        result
    }

    /// A call made on [`Session::connected`] lost the connection: the next one connects
    /// again first (a session opened with [`Session::reconnecting`]).
    pub fn mark_lost(&mut self) {
        self.lost = true;
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
        let result = self
            .connected()
            .and_then(|scene| Ok(run(scene, job, progress)?));
        self.noted(result)
    }

    /// Removes the drawn maze ([`clear()`]) on the open connection.
    pub fn clear(&mut self, opts: &ClearOptions) -> Result<ClearReport, SessionError> {
        let result = self.connected().and_then(|scene| Ok(clear(scene, opts)?));
        self.noted(result)
    }

    /// Checks the scene against `picture` ([`verify()`] or [`super::mesh::verify()`]) on the
    /// open connection.
    pub fn verify(&mut self, picture: &Picture, names: &ObjectNames) -> Result<(), SessionError> {
        let result = self.connected().and_then(|scene| {
            Ok(match picture {
                Picture::Copies(drawing) => verify(scene, drawing, names),
                Picture::Mesh(maze) => super::mesh::verify(scene, maze, names),
            }?)
        });
        self.noted(result)
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

impl SessionError {
    /// Whether the connection itself failed ([`BackendError::lost_connection`]), not the job.
    pub fn lost_connection(&self) -> bool {
        match self {
            SessionError::Closed(_) => false,
            SessionError::Run(RunError::Draw(DrawError::Backend(e)))
            | SessionError::Run(RunError::Create(e))
            | SessionError::Run(RunError::Save { source: e, .. })
            | SessionError::Draw(DrawError::Backend(e)) => e.lost_connection(),
            SessionError::Run(_) | SessionError::Draw(_) => false,
        }
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
