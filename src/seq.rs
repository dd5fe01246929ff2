//! `Seq<T>`: the persistent sequence that holds an element's children.
//!
//! Chunks of at most `max(64, √n)` items, each behind an `Arc`, in an `Arc`'d list
//! with the chunks' start positions. A clone is two pointer copies; an edit copies
//! the chunk list and the one chunk it changes: O(n / chunk + chunk) pointer copies,
//! about a hundred for a few thousand children. (`imbl::Vector`, an RRB tree, is
//! O(log n) in theory, but an insert or remove in the middle splits and rebalances
//! 64-wide nodes: some 40-60 µs at 2,000-4,000 items, measured.)

use std::sync::Arc;

const MIN_CHUNK: usize = 64;

#[derive(Clone)]
pub(crate) struct Seq<T> {
    chunks: Arc<Vec<Arc<Vec<T>>>>,
    /// `starts[k]`: the position of the first item of chunk `k`.
    starts: Arc<Vec<usize>>,
    len: usize,
}

impl<T> Default for Seq<T> {
    fn default() -> Self {
        Seq { chunks: Arc::new(Vec::new()), starts: Arc::new(Vec::new()), len: 0 }
    }
}

impl<T: Clone> Seq<T> {
    pub(crate) fn new() -> Seq<T> {
        Seq::default()
    }

    pub(crate) fn len(&self) -> usize {
        self.len
    }

    pub(crate) fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The largest chunk for a sequence of `len` items.
    fn max_chunk(len: usize) -> usize {
        MIN_CHUNK.max(len.isqrt())
    }

    /// The chunk holding position `i` (`i < len`) and the position within it.
    fn locate(&self, i: usize) -> (usize, usize) {
        let k = self.starts.partition_point(|s| *s <= i).saturating_sub(1);
        (k, i - self.starts.get(k).copied().unwrap_or(0))
    }

    pub(crate) fn get(&self, i: usize) -> Option<&T> {
        if i >= self.len {
            return None;
        }
        let (k, j) = self.locate(i);
        self.chunks.get(k)?.get(j)
    }

    pub(crate) fn iter(&self) -> Iter<'_, T> {
        Iter { chunks: self.chunks.iter(), front: [].iter(), back: [].iter(), left: self.len }
    }

    /// The items at positions `start..end` (clamped to the length), found in
    /// O(log chunks) rather than by stepping over the ones before.
    pub(crate) fn range(&self, start: usize, end: usize) -> Iter<'_, T> {
        let end = end.min(self.len);
        let start = start.min(end);
        if start == end {
            return Iter { chunks: [].iter(), front: [].iter(), back: [].iter(), left: 0 };
        }
        let (ks, js) = self.locate(start);
        let (ke, je) = self.locate(end - 1);
        let chunk = |k: usize| self.chunks.get(k).map_or(&[][..], |c| c.as_slice());
        let (front, middle, back) = if ks == ke {
            (chunk(ks).get(js..=je).unwrap_or(&[]), &[][..], &[][..])
        } else {
            (
                chunk(ks).get(js..).unwrap_or(&[]),
                self.chunks.get(ks + 1..ke).unwrap_or(&[]),
                chunk(ke).get(..=je).unwrap_or(&[]),
            )
        };
        Iter { chunks: middle.iter(), front: front.iter(), back: back.iter(), left: end - start }
    }

    /// The chunks in order, each with the position of its first item. Versions of a
    /// sequence share (`Arc::ptr_eq`) every chunk that the edits between them did not
    /// copy, so a comparison can skip those without looking at their items.
    pub(crate) fn chunks(&self) -> impl ExactSizeIterator<Item = (usize, &Arc<Vec<T>>)> + '_ {
        self.starts.iter().copied().zip(self.chunks.iter())
    }

    /// Whether both share one chunk list, so hold the same items (O(1)).
    pub(crate) fn ptr_eq(&self, other: &Seq<T>) -> bool {
        Arc::ptr_eq(&self.chunks, &other.chunks)
    }

    /// Recomputes the start positions from chunk `from` on.
    fn restart(&mut self, from: usize) {
        let starts = Arc::make_mut(&mut self.starts);
        starts.truncate(from);
        let mut at = match from {
            0 => 0,
            _ => {
                starts.last().copied().unwrap_or(0)
                    + self.chunks.get(from - 1).map_or(0, |c| c.len())
            }
        };
        for c in &self.chunks[from.min(self.chunks.len())..] {
            starts.push(at);
            at += c.len();
        }
    }

    /// Inserts `value` at position `i` (at the end if `i >= len`).
    pub(crate) fn insert(&mut self, i: usize, value: T) {
        if i >= self.len {
            self.push_back(value);
            return;
        }
        let (k, j) = self.locate(i);
        let max = Seq::<T>::max_chunk(self.len + 1);
        let chunks = Arc::make_mut(&mut self.chunks);
        let Some(chunk) = chunks.get_mut(k) else { return };
        let chunk = Arc::make_mut(chunk);
        chunk.insert(j, value);
        if chunk.len() > max {
            let tail = chunk.split_off(chunk.len() / 2);
            chunks.insert(k + 1, Arc::new(tail));
        }
        self.len += 1;
        self.restart(k);
    }

    pub(crate) fn push_back(&mut self, value: T) {
        let max = Seq::<T>::max_chunk(self.len + 1);
        let chunks = Arc::make_mut(&mut self.chunks);
        match chunks.last_mut() {
            Some(last) if last.len() < max => Arc::make_mut(last).push(value),
            _ => {
                chunks.push(Arc::new(vec![value]));
                Arc::make_mut(&mut self.starts).push(self.len);
            }
        }
        self.len += 1;
    }

    /// Removes and returns the item at `i`, if any.
    pub(crate) fn remove(&mut self, i: usize) -> Option<T> {
        if i >= self.len {
            return None;
        }
        let (k, j) = self.locate(i);
        let chunks = Arc::make_mut(&mut self.chunks);
        let chunk = Arc::make_mut(chunks.get_mut(k)?);
        let removed = chunk.remove(j);
        if chunk.is_empty() {
            chunks.remove(k);
        }
        self.len -= 1;
        self.restart(k);
        Some(removed)
    }

    /// Replaces the item at `i` (nothing happens past the end).
    pub(crate) fn set(&mut self, i: usize, value: T) {
        if i >= self.len {
            return;
        }
        let (k, j) = self.locate(i);
        let chunks = Arc::make_mut(&mut self.chunks);
        if let Some(slot) = chunks.get_mut(k).and_then(|c| Arc::make_mut(c).get_mut(j)) {
            *slot = value;
        }
    }
}

impl<T: Clone> FromIterator<T> for Seq<T> {
    fn from_iter<I: IntoIterator<Item = T>>(iter: I) -> Seq<T> {
        let items: Vec<T> = iter.into_iter().collect();
        let len = items.len();
        let size = Seq::<T>::max_chunk(len);
        let mut chunks = Vec::with_capacity(len.div_ceil(size));
        let mut starts = Vec::with_capacity(len.div_ceil(size));
        let mut items = items.into_iter().peekable();
        let mut at = 0;
        while items.peek().is_some() {
            let chunk: Vec<T> = items.by_ref().take(size).collect();
            starts.push(at);
            at += chunk.len();
            chunks.push(Arc::new(chunk));
        }
        Seq { chunks: Arc::new(chunks), starts: Arc::new(starts), len }
    }
}

impl<'a, T: Clone> IntoIterator for &'a Seq<T> {
    type Item = &'a T;
    type IntoIter = Iter<'a, T>;
    fn into_iter(self) -> Iter<'a, T> {
        self.iter()
    }
}

impl<T: Clone + std::fmt::Debug> std::fmt::Debug for Seq<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

/// Items in order (double-ended, exact size).
pub(crate) struct Iter<'a, T> {
    chunks: std::slice::Iter<'a, Arc<Vec<T>>>,
    front: std::slice::Iter<'a, T>,
    back: std::slice::Iter<'a, T>,
    left: usize,
}

impl<'a, T> Iterator for Iter<'a, T> {
    type Item = &'a T;
    fn next(&mut self) -> Option<&'a T> {
        loop {
            if let Some(x) = self.front.next() {
                self.left -= 1;
                return Some(x);
            }
            match self.chunks.next() {
                Some(c) => self.front = c.iter(),
                None => {
                    let x = self.back.next();
                    if x.is_some() {
                        self.left -= 1;
                    }
                    return x;
                }
            }
        }
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        (self.left, Some(self.left))
    }
}

impl<T> DoubleEndedIterator for Iter<'_, T> {
    fn next_back(&mut self) -> Option<Self::Item> {
        loop {
            if let Some(x) = self.back.next_back() {
                self.left -= 1;
                return Some(x);
            }
            match self.chunks.next_back() {
                Some(c) => self.back = c.iter(),
                None => {
                    let x = self.front.next_back();
                    if x.is_some() {
                        self.left -= 1;
                    }
                    return x;
                }
            }
        }
    }
}

impl<T> ExactSizeIterator for Iter<'_, T> {}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[derive(Clone, Debug)]
    enum Op {
        Insert(usize, u32),
        Remove(usize),
        Set(usize, u32),
        Push(u32),
    }

    fn op() -> impl Strategy<Value = Op> {
        prop_oneof![
            (0..5000usize, any::<u32>()).prop_map(|(i, v)| Op::Insert(i, v)),
            (0..5000usize).prop_map(Op::Remove),
            (0..5000usize, any::<u32>()).prop_map(|(i, v)| Op::Set(i, v)),
            any::<u32>().prop_map(Op::Push),
        ]
    }

    proptest! {
        /// Every operation agrees with `Vec`, and earlier versions never change.
        #[test]
        fn behaves_like_a_vec(start in 0..3000usize, ops in prop::collection::vec(op(), 0..200)) {
            let mut model: Vec<u32> = (0..start as u32).collect();
            let mut seq: Seq<u32> = model.iter().copied().collect();
            let mut versions = vec![(seq.clone(), model.clone())];
            for o in ops {
                match o {
                    Op::Insert(i, v) => {
                        let i = if model.is_empty() { 0 } else { i % (model.len() + 1) };
                        model.insert(i, v);
                        seq.insert(i, v);
                    }
                    Op::Remove(i) => {
                        let got = seq.remove(i);
                        let want = (i < model.len()).then(|| model.remove(i));
                        prop_assert_eq!(got, want);
                    }
                    Op::Set(i, v) => {
                        seq.set(i, v);
                        if let Some(x) = model.get_mut(i) {
                            *x = v;
                        }
                    }
                    Op::Push(v) => {
                        model.push(v);
                        seq.push_back(v);
                    }
                }
                prop_assert_eq!(seq.len(), model.len());
                versions.push((seq.clone(), model.clone()));
            }
            for (s, m) in &versions {
                prop_assert_eq!(s.iter().copied().collect::<Vec<_>>(), m.clone());
                prop_assert_eq!(s.iter().rev().copied().collect::<Vec<_>>(), m.iter().rev().copied().collect::<Vec<_>>());
                prop_assert_eq!(s.iter().len(), m.len());
                for i in [0, m.len() / 2, m.len().saturating_sub(1), m.len()] {
                    prop_assert_eq!(s.get(i), m.get(i));
                    let (a, b) = (i / 3, i + 70);
                    let want: Vec<u32> = m[a.min(m.len())..b.min(m.len())].to_vec();
                    prop_assert_eq!(s.range(a, b).copied().collect::<Vec<_>>(), want.clone());
                    prop_assert_eq!(s.range(a, b).len(), want.len());
                    prop_assert_eq!(s.range(a, b).rev().copied().collect::<Vec<_>>(), want.into_iter().rev().collect::<Vec<_>>());
                }
            }
        }
    }

    #[test]
    fn mixed_ends_of_the_iterator_meet_in_the_middle() {
        let s: Seq<u32> = (0..200).collect();
        let mut it = s.iter();
        let mut got = Vec::new();
        while let (Some(a), Some(b)) = (it.next(), it.next_back()) {
            got.push(*a);
            got.push(*b);
        }
        got.sort();
        assert_eq!(got, (0..200).collect::<Vec<_>>());
    }
}
