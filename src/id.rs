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

/// A hasher for element ids in the crate's maps: ids are handed out by this process
/// (never chosen by a user), so one multiply (Fibonacci hashing: the product's bits
/// spread consecutive ids evenly over the low bits persistent hash maps branch on)
/// replaces SipHash. User-controlled keys (names) keep SipHash.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct IdHash;

impl std::hash::BuildHasher for IdHash {
    type Hasher = IdHasher;
    fn build_hasher(&self) -> IdHasher {
        IdHasher(0)
    }
}

/// See [`IdHash`].
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct IdHasher(u64);

impl std::hash::Hasher for IdHasher {
    fn finish(&self) -> u64 {
        let h = self.0.wrapping_mul(0x9E37_79B9_7F4A_7C15);
        h ^ (h >> 32)
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = (self.0.rotate_left(8)) ^ u64::from(b);
        }
    }
    fn write_u64(&mut self, n: u64) {
        self.0 = self.0.rotate_left(32) ^ n;
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
