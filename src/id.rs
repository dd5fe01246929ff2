//! [`ElementId`]: the stable identity of an element (a leaf module: it imports nothing
//! of the crate).

use std::fmt;
use std::num::NonZeroU64;
use std::sync::atomic::{AtomicU64, Ordering};

/// A stable identity of an element, unique within a model.
///
/// It survives every edit of other elements and of the element's own attributes, so an
/// editor can hold it across versions. Ids are never reused: a removed element's id
/// names nothing in later versions.
#[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ElementId(NonZeroU64);

static NEXT_ID: AtomicU64 = AtomicU64::new(1);

impl ElementId {
    /// A new id, never handed out before in this process, and larger than every id
    /// handed out before it (one counter; an attach after another in a model's
    /// history gets a larger frame id, which the scopes' attach order relies on).
    pub(crate) fn fresh() -> ElementId {
        let n = NEXT_ID.fetch_add(1, Ordering::Relaxed);
        // The counter would need 2^64 allocations to wrap.
        ElementId(NonZeroU64::new(n).unwrap_or(NonZeroU64::MIN))
    }

    /// The first of `n` new consecutive ids (`first.nth(0)` … `first.nth(n - 1)`),
    /// never handed out before in this process, however many threads take ids.
    pub(crate) fn fresh_block(n: usize) -> ElementId {
        let n = NEXT_ID.fetch_add(n as u64, Ordering::Relaxed);
        ElementId(NonZeroU64::new(n).unwrap_or(NonZeroU64::MIN))
    }

    /// The id `i` places after this one (in a block from [`ElementId::fresh_block`]).
    pub(crate) fn nth(self, i: usize) -> ElementId {
        ElementId(self.0.saturating_add(i as u64))
    }
}

impl ElementId {
    /// The id as a number (unique, never 0).
    pub(crate) fn get(self) -> u64 {
        self.0.get()
    }
}

impl fmt::Debug for ElementId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "#{}", self.0)
    }
}
