//! A connection a follower owns, or borrows from an open drawing session.

use std::ops::{Deref, DerefMut};

/// A client owned (closed when its user is done) or lent by a drawing backend (left open
/// for the backend's next call).
pub enum Held<'a, C> {
    /// Owned: its user closes it.
    Owned(C),
    /// Borrowed from a drawing backend ([`crate::draw::backend::Backend::follower`]).
    Lent(&'a mut C),
}

impl<C> Held<'_, C> {
    /// The client if owned (to close it), `None` if lent.
    pub fn into_owned(self) -> Option<C> {
        match self {
            Held::Owned(c) => Some(c),
            Held::Lent(_) => None,
        }
    }
}

impl<C> Deref for Held<'_, C> {
    type Target = C;
    fn deref(&self) -> &C {
        match self {
            Held::Owned(c) => c,
            Held::Lent(c) => c,
        }
    }
}

impl<C> DerefMut for Held<'_, C> {
    fn deref_mut(&mut self) -> &mut C {
        match self {
            Held::Owned(c) => c,
            Held::Lent(c) => c,
        }
    }
}
