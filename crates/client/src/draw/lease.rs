//! Telling concurrent runs apart: each `apply` or `clear` records a random token in the scene
//! (through [`Lease`], where the backend has one) and checks before each phase and at the end
//! that the token is still its own. A run started later takes the lease over, so an earlier
//! run stops at its next check with [`DrawError::Concurrent`] instead of drawing on, and the
//! later one's verification sees whatever the earlier left: a race ends in a clear error,
//! never in a wrong maze reported as verified.
//!
//! The claim is a run's first signal write that it reads back: a simulator that does not
//! keep it (CoppeliaSim 4.10 silently drops a signal whose name is no valid property name,
//! `../shared/spec/real-coppeliasim-4.10.md` "Signals are scene properties now") is said so
//! in one warning, and the run goes on without the scene's signals (`Claim::signals_kept`):
//! never a false [`DrawError::Concurrent`].

use std::cell::Cell;
use std::hash::{BuildHasher, RandomState};

use super::backend::{Backend, Lease};
use super::error::BackendError;
use super::error::DrawError;
use super::signals::LEASE;

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
    /// The warning that the simulator keeps no signals ([`Claim::signals_kept`]).
    unkept: Option<String>,
    /// The run's last check, left to [`Claim::release`] ([`Claim::check_at_release`]).
    last_check: Cell<Option<&'static str>>,
}

impl Claim {
    /// No claim: for a dry run, which changes nothing.
    pub fn none() -> Claim {
        Claim {
            token: None,
            contended: false,
            unkept: None,
            last_check: Cell::new(None),
        }
    }

    /// `false` when the simulator did not keep the lease it was given: the run has no lease,
    /// no copy record, and no record of the line template's home (`clear` cannot put it back).
    pub(crate) fn signals_kept(&self) -> bool {
        self.unkept.is_none()
    }

    /// The one warning line saying the simulator kept no signal, if it did not.
    pub fn warning(&self) -> Option<&str> {
        self.unkept.as_deref()
    }

    /// See [`Claim::contended`](Claim).
    pub(crate) fn contended(&self) -> bool {
        self.contended
    }

    /// Claims the scene with a fresh random token and reads it back. A simulator that does
    /// not keep it (or refuses integer signals) gives a claim without a token and with a
    /// warning: the run goes on unguarded, without the scene's signals.
    pub fn take(backend: &mut dyn Backend) -> Result<Claim, DrawError> {
        let simulator = backend.describe();
        let Some(lease) = backend.lease() else {
            return Ok(Claim::none());
        };
        let token = random_token();
        let claimed = match lease.claim(token) {
            Ok(c) if c.read_back.is_some() => c,
            Ok(_) => return Ok(Claim::unkept(lease, &simulator, "it read back empty")),
            Err(BackendError::Remote(e)) => return Ok(Claim::unkept(lease, &simulator, &e)),
            Err(e) => return Err(e.into()),
        };
        // another run's token read back: it claimed just after this one, and this run stops
        // at its first check
        let contended = claimed.previous.is_some();
        if contended {
            std::thread::sleep(TAKEOVER_GRACE);
        }
        Ok(Claim {
            token: Some(token),
            contended,
            unkept: None,
            last_check: Cell::new(None),
        })
    }

    /// The claim of a run on a simulator that did not keep the lease (`why`).
    fn unkept(lease: &mut dyn Lease, simulator: &str, why: &str) -> Claim {
        lease.unkept();
        Claim {
            token: None,
            contended: false,
            unkept: Some(format!(
                "the simulator did not keep the integer signal `{}` ({why}; {simulator}): drawing without a lease (a concurrent run is not detected), without a copy record, and `clear` cannot put the line template back",
                LEASE.name
            )),
            last_check: Cell::new(None),
        }
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
    pub fn check(&self, backend: &mut dyn Backend, phase: &'static str) -> Result<(), DrawError> {
        let (Some(token), Some(lease)) = (self.token, backend.lease()) else {
            return Ok(());
        };
        match lease.holder()? {
            Some(t) if t == token => Ok(()),
            _ => Err(DrawError::Concurrent { phase }),
        }
    }

    /// [`Claim::check`] for a run's last check, after its last read of the scene: made by
    /// the read [`Claim::release`] makes anyway (to clear only its own token), one request
    /// fewer. Its failure is the run's [`DrawError::Concurrent`] for `phase`, whatever else
    /// the run ended with.
    pub fn check_at_release(&self, phase: &'static str) {
        self.last_check.set(Some(phase));
    }

    /// Removes the record if it is still this run's (never another run's); fails with
    /// [`DrawError::Concurrent`] when it is not and the run left its last check here.
    pub(crate) fn release(self, backend: &mut dyn Backend) -> Result<(), DrawError> {
        let (Some(token), Some(lease)) = (self.token, backend.lease()) else {
            return Ok(());
        };
        if lease.holder()? == Some(token) {
            lease.release()?;
            return Ok(());
        }
        match self.last_check.get() {
            Some(phase) => Err(DrawError::Concurrent { phase }),
            None => Ok(()),
        }
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
    match claim.release(scene) {
        // the run's last check, made by the release, failed: another run drew over it
        Err(lost @ DrawError::Concurrent { .. }) => Err(lost),
        released => {
            let value = result?;
            released?;
            Ok(value)
        }
    }
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
