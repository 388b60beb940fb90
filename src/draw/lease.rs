//! Telling concurrent runs apart: each `apply` or `clear` records a random token in the scene
//! (through [`Lease`], where the backend has one) and checks before each phase and at the end
//! that the token is still its own. A run started later takes the lease over, so an earlier
//! run stops at its next check with [`DrawError::Concurrent`] instead of drawing on, and the
//! later one's verification sees whatever the earlier left: a race ends in a clear error,
//! never in a wrong maze reported as verified.

use std::hash::{BuildHasher, RandomState};

use super::{Backend, BackendError, DrawError};

/// Name of the integer signal holding the token of the run drawing into the scene.
pub const LEASE_SIGNAL: &str = "vrep-maze.lease";

/// The scene-side record of who is drawing: see [`Backend::lease`].
pub trait Lease {
    /// Records `token` as the scene's current drawer, replacing any earlier record.
    fn claim(&mut self, token: i32) -> Result<(), BackendError>;
    /// The token recorded now, if any.
    fn holder(&mut self) -> Result<Option<i32>, BackendError>;
    /// Removes the record (only called by the run that holds it).
    fn release(&mut self) -> Result<(), BackendError>;
}

/// Edits sent between two lease checks (at about 0.45 ms per ZeroMQ call on a real
/// CoppeliaSim at idle fps 0, `../shared/spec/real-coppeliasim-4.5.1.md`: about 0.1 s).
const EDITS_PER_CHECK: usize = 200;

/// How long a run that takes the lease over from another waits before it reads the scene:
/// the other run stops at its next check, after at most [`EDITS_PER_CHECK`] calls (about
/// 0.1 s on a real simulator at idle fps 0), so its last writes land before this run looks.
const TAKEOVER_GRACE: std::time::Duration = std::time::Duration::from_secs(2);

/// This run's claim on a scene; `token` is `None` where the backend has no lease.
#[derive(Debug)]
pub(crate) struct Claim {
    token: Option<i32>,
    /// Another run held the lease when this one claimed it: a concurrent run (now stopping)
    /// or an interrupted one. Such a run verifies against what it reads from the scene, not
    /// against what it was told it set.
    contended: bool,
}

impl Claim {
    /// No claim: for a dry run, which changes nothing.
    pub(crate) fn none() -> Claim {
        Claim {
            token: None,
            contended: false,
        }
    }

    /// See [`Claim::contended`](Claim).
    pub(crate) fn contended(&self) -> bool {
        self.contended
    }

    /// Claims the scene with a fresh random token. A simulator that cannot record one (no
    /// integer signals) gives an empty claim: the run goes on unguarded.
    pub(crate) fn take(backend: &mut dyn Backend) -> Result<Claim, DrawError> {
        let Some(lease) = backend.lease() else {
            return Ok(Claim::none());
        };
        let token = random_token();
        let previous = match lease.holder() {
            Ok(holder) => holder,
            Err(BackendError::Remote(_)) => return Ok(Claim::none()),
            Err(e) => return Err(e.into()),
        };
        match lease.claim(token) {
            Ok(()) => {}
            Err(BackendError::Remote(_)) => return Ok(Claim::none()),
            Err(e) => return Err(e.into()),
        }
        let contended = previous.is_some();
        if contended {
            std::thread::sleep(TAKEOVER_GRACE);
        }
        Ok(Claim {
            token: Some(token),
            contended,
        })
    }

    /// How many edits to send between two checks: few enough that a run which lost the lease
    /// stops within a fraction of a second (about 0.1 s of ZeroMQ calls); unlimited (one
    /// request) without a lease.
    pub(crate) fn edits_per_check(&self) -> usize {
        if self.token.is_some() {
            EDITS_PER_CHECK
        } else {
            usize::MAX
        }
    }

    /// Fails with [`DrawError::Concurrent`] if another run has claimed the scene since.
    pub(crate) fn check(
        &self,
        backend: &mut dyn Backend,
        phase: &'static str,
    ) -> Result<(), DrawError> {
        let (Some(token), Some(lease)) = (self.token, backend.lease()) else {
            return Ok(());
        };
        match lease.holder()? {
            Some(t) if t == token => Ok(()),
            _ => Err(DrawError::Concurrent { phase }),
        }
    }

    /// Removes the record if it is still this run's (never another run's).
    pub(crate) fn release(self, backend: &mut dyn Backend) -> Result<(), DrawError> {
        let (Some(token), Some(lease)) = (self.token, backend.lease()) else {
            return Ok(());
        };
        if lease.holder()? == Some(token) {
            lease.release()?;
        }
        Ok(())
    }
}

/// Runs `work` under a fresh claim (an empty one for a dry run, which changes nothing) and
/// releases the claim afterwards, whatever `work` returned.
pub(crate) fn claimed<T>(
    scene: &mut dyn Backend,
    dry_run: bool,
    work: impl FnOnce(&mut dyn Backend, &Claim) -> Result<T, DrawError>,
) -> Result<T, DrawError> {
    let claim = if dry_run {
        Claim::none()
    } else {
        Claim::take(scene)?
    };
    let result = work(scene, &claim);
    let released = claim.release(scene);
    let value = result?;
    released?;
    Ok(value)
}

/// A random non-zero token (the standard library's per-process random hasher keys).
fn random_token() -> i32 {
    let bits = RandomState::new().hash_one((std::process::id(), std::time::SystemTime::now()));
    match bits as i32 {
        0 => 1,
        t => t,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tokens_differ_and_are_never_zero() {
        let tokens: std::collections::HashSet<i32> = (0..1000).map(|_| random_token()).collect();
        assert!(tokens.len() > 990, "{}", tokens.len());
        assert!(!tokens.contains(&0));
    }
}
