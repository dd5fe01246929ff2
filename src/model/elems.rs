//! `ElemMap`: the index's persistent map from element ids to their entries.
//!
//! A B+tree of small nodes behind `Arc`s, like `imbl::OrdMap`, with two differences
//! that matter for reading large models: it is built in one pass from sorted entries
//! (full leaves, no per-entry descent; a model read has tens of thousands), and an
//! entry added after the largest key (a new element: ids are handed out in increasing
//! order) leaves the full leaf it overflows full instead of splitting it in halves.
//! A clone is two pointer copies; an insert or removal copies the nodes on one
//! root-to-leaf path (at most 16 entries each). Removals do not rebalance (an empty
//! node is dropped, a root with one child is replaced by it), so the depth stays
//! O(log of the largest size the map had).
//!
//! The newest entries (at most 16, with keys above every key of the tree) are kept
//! apart, in a tail, like a persistent vector's: an element added to a model (a
//! fresh id, the largest) copies the tail alone, not the tree's right edge (a path
//! of three or four nodes in a model of tens of thousands of elements), so adding is
//! O(1) whatever the model's size, and the new element is found again at once. A
//! full tail goes into the tree as it is, a full leaf, shared with the versions
//! that hold it as their tail (one path copy per 16 appends).

use std::sync::Arc;

use crate::id::ElementId;

/// Entries per leaf and children per branch, at most.
const MAX: usize = 16;

#[derive(Clone)]
enum Node<V> {
    /// Entries in increasing key order.
    Leaf(Vec<(ElementId, V)>),
    /// Children in key order, each with a lower bound of its keys (its smallest key
    /// when it was built or last lowered; removals leave it as it was).
    Branch(Vec<(ElementId, Arc<Node<V>>)>),
}

/// A persistent map from element ids to values (the index's entries).
#[derive(Clone)]
pub(crate) struct ElemMap<V> {
    root: Option<Arc<Node<V>>>,
    /// A leaf of entries above every key of `root`, at most `MAX` (module docs);
    /// `None` rather than empty.
    tail: Option<Arc<Node<V>>>,
    /// Entries in `root` and `tail`.
    len: usize,
}

impl<V> Default for ElemMap<V> {
    fn default() -> Self {
        ElemMap { root: None, tail: None, len: 0 }
    }
}

impl<V: Clone> ElemMap<V> {
    /// The map of `entries` (distinct keys), in any order. O(n) for entries in
    /// increasing order, in a few increasing runs, or with ids from a range at most
    /// about twice their number (a model read: its ids were handed out together);
    /// O(n log n) otherwise.
    pub(crate) fn from_entries(mut entries: Vec<(ElementId, V)>) -> ElemMap<V> {
        // Where the order breaks: a few runs (a read model's empty singletons under
        // the root) are merged by the stable sort, many are placed by id.
        let breaks = entries.windows(2).filter(|w| w[0].0 >= w[1].0).count();
        if breaks > 0 {
            let (lo, hi) = match breaks > 16 {
                true => entries
                    .iter()
                    .fold((u64::MAX, 0), |(lo, hi), (k, _)| (lo.min(k.get()), hi.max(k.get()))),
                false => (0, u64::MAX),
            };
            let span = usize::try_from(hi - lo).unwrap_or(usize::MAX);
            if span < entries.len().saturating_mul(2).saturating_add(1024) {
                // Dense ids (a read model's: in document order they are not sorted,
                // its empty singletons being made last): each put in its place.
                let mut slots: Vec<Option<(ElementId, V)>> = Vec::new();
                slots.resize_with(span + 1, || None);
                for e in entries.drain(..) {
                    let k = (e.0.get() - lo) as usize;
                    slots[k] = Some(e);
                }
                entries.extend(slots.into_iter().flatten());
            } else {
                entries.sort_by_key(|(k, _)| *k);
                // Of equal keys (callers give none) one is kept: the tree stays sound.
                entries.dedup_by_key(|(k, _)| *k);
            }
        }
        let len = entries.len();
        let mut level: Vec<(ElementId, Arc<Node<V>>)> = Vec::with_capacity(len.div_ceil(MAX));
        let mut rest = entries.into_iter().peekable();
        while let Some(&(first, _)) = rest.peek() {
            let leaf: Vec<(ElementId, V)> = rest.by_ref().take(MAX).collect();
            level.push((first, Arc::new(Node::Leaf(leaf))));
        }
        while level.len() > 1 {
            let mut up = Vec::with_capacity(level.len().div_ceil(MAX));
            let mut rest = level.into_iter().peekable();
            while let Some(&(first, _)) = rest.peek() {
                let kids: Vec<(ElementId, Arc<Node<V>>)> = rest.by_ref().take(MAX).collect();
                up.push((first, Arc::new(Node::Branch(kids))));
            }
            level = up;
        }
        ElemMap { root: level.pop().map(|(_, n)| n), tail: None, len }
    }

    pub(crate) fn len(&self) -> usize {
        self.len
    }

    /// Whether both are one map (the same root, or both empty): O(1).
    pub(crate) fn ptr_eq(&self, other: &ElemMap<V>) -> bool {
        let roots = match (&self.root, &other.root) {
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            (None, None) => true,
            _ => false,
        };
        roots
            && match (&self.tail, &other.tail) {
                (Some(a), Some(b)) => Arc::ptr_eq(a, b),
                (None, None) => true,
                _ => false,
            }
    }

    /// The tail's entries.
    fn tail_entries(&self) -> Option<&[(ElementId, V)]> {
        match self.tail.as_deref()? {
            Node::Leaf(v) => Some(v),
            Node::Branch(_) => None,
        }
    }

    /// The tail's entries, if `id` belongs there (it is at least the tail's first key).
    fn tail_for(&self, id: &ElementId) -> Option<&[(ElementId, V)]> {
        self.tail_entries().filter(|t| t.first().is_some_and(|(k, _)| k <= id))
    }

    pub(crate) fn get(&self, id: &ElementId) -> Option<&V> {
        if let Some(t) = self.tail_for(id) {
            return t.binary_search_by_key(id, |(k, _)| *k).ok().map(|i| &t[i].1);
        }
        let mut node = self.root.as_deref()?;
        loop {
            match node {
                Node::Leaf(v) => {
                    return v.binary_search_by_key(id, |(k, _)| *k).ok().map(|i| &v[i].1);
                }
                Node::Branch(v) => {
                    let i = v.partition_point(|(k, _)| k <= id).checked_sub(1)?;
                    node = &v[i].1;
                }
            }
        }
    }

    #[cfg(test)]
    pub(crate) fn contains_key(&self, id: &ElementId) -> bool {
        self.get(id).is_some()
    }

    /// Sets the entry of `id`; returns the one it replaces.
    pub(crate) fn insert(&mut self, id: ElementId, entry: V) -> Option<V> {
        if self.tail_for(&id).is_some() {
            return self.insert_in_tail(id, entry);
        }
        // Above every key (a new element): a tail of its own.
        if self.tail.is_none() && self.root.as_deref().is_none_or(|r| last_key(r) < Some(id)) {
            self.tail = Some(Arc::new(Node::Leaf(vec![(id, entry)])));
            self.len += 1;
            return None;
        }
        let Some(root) = self.root.as_mut() else {
            // Unreachable: an empty tree with a tail takes every key in the tail.
            self.root = Some(Arc::new(Node::Leaf(vec![(id, entry)])));
            self.len += 1;
            return None;
        };
        let (old, split) = insert_into(for_insert(root), id, entry);
        if let Some(right) = split {
            let left = self.root.take().unwrap_or_else(|| Arc::new(Node::Leaf(Vec::new())));
            let left_key = first_key(&left).unwrap_or(id);
            self.root = Some(Arc::new(Node::Branch(vec![(left_key, left), right])));
        }
        if old.is_none() {
            self.len += 1;
        }
        old
    }

    /// [`ElemMap::insert`] of a key at least the tail's first. A key after a full
    /// tail sends the tail into the tree as it is (not copied: other versions may
    /// share it) and starts a new one; a tail grown past `MAX` otherwise gives its
    /// first `MAX` entries to the tree, as its new last leaf.
    fn insert_in_tail(&mut self, id: ElementId, entry: V) -> Option<V> {
        let full = self
            .tail_entries()
            .is_some_and(|t| t.len() >= MAX && t.last().is_some_and(|(k, _)| *k < id));
        if full {
            let tail = self.tail.take()?;
            self.push_leaf(tail);
            self.tail = Some(Arc::new(Node::Leaf(vec![(id, entry)])));
            self.len += 1;
            return None;
        }
        let Node::Leaf(tail) = node_to_grow(self.tail.as_mut()?) else { return None };
        match tail.binary_search_by_key(&id, |(k, _)| *k) {
            Ok(i) => return Some(std::mem::replace(&mut tail[i].1, entry)),
            Err(i) => tail.insert(i, (id, entry)),
        }
        let over = (tail.len() > MAX).then(|| {
            let rest = tail.split_off(MAX);
            std::mem::replace(tail, rest)
        });
        self.len += 1;
        if let Some(over) = over {
            self.push_leaf(Arc::new(Node::Leaf(over)));
        }
        None
    }

    /// Adds `leaf` (a non-empty leaf, its keys above every key of the tree) as the
    /// tree's last leaf.
    fn push_leaf(&mut self, leaf: Arc<Node<V>>) {
        let Some(key) = first_key(&leaf) else { return };
        let Some(root) = self.root.as_mut() else {
            self.root = Some(leaf);
            return;
        };
        let split = match &**root {
            Node::Leaf(_) => Some((key, leaf)),
            Node::Branch(_) => match node_to_grow(root) {
                Node::Branch(v) => push_right(v, key, leaf),
                Node::Leaf(_) => None,
            },
        };
        if let Some(right) = split {
            let left = self.root.take().unwrap_or_else(|| Arc::new(Node::Leaf(Vec::new())));
            let left_key = first_key(&left).unwrap_or(key);
            self.root = Some(Arc::new(Node::Branch(vec![(left_key, left), right])));
        }
    }

    /// Removes the entry of `id`, if any, and returns it.
    pub(crate) fn remove(&mut self, id: &ElementId) -> Option<V> {
        // Not there: nothing is copied.
        self.get(id)?;
        if self.tail_for(id).is_some() {
            let Node::Leaf(tail) = Arc::make_mut(self.tail.as_mut()?) else { return None };
            let i = tail.binary_search_by_key(id, |(k, _)| *k).ok()?;
            let (_, old) = tail.remove(i);
            if tail.is_empty() {
                self.tail = None;
            }
            self.len -= 1;
            return Some(old);
        }
        let root = self.root.as_mut()?;
        let old = remove_from(Arc::make_mut(root), id);
        if old.is_some() {
            self.len -= 1;
        }
        // An emptied root goes; a branch root with one child is replaced by it.
        loop {
            let next = match self.root.as_deref() {
                Some(Node::Leaf(v)) if v.is_empty() => None,
                Some(Node::Branch(v)) if v.len() <= 1 => v.first().map(|(_, c)| c.clone()),
                _ => break,
            };
            self.root = next;
        }
        old
    }

    /// Every entry in key order (for `Debug` and tests).
    fn entries(&self) -> Vec<(&ElementId, &V)> {
        let mut out = Vec::with_capacity(self.len);
        let mut stack: Vec<&Node<V>> = self.root.as_deref().into_iter().collect();
        while let Some(n) = stack.pop() {
            match n {
                Node::Leaf(v) => out.extend(v.iter().map(|(k, e)| (k, e))),
                Node::Branch(v) => stack.extend(v.iter().rev().map(|(_, c)| &**c)),
            }
        }
        out.extend(self.tail_entries().unwrap_or_default().iter().map(|(k, e)| (k, e)));
        out
    }
}

/// `Arc::make_mut` for a node about to take one more entry or child: a copy (of a
/// shared node) is made with room for it, so adding does not allocate again.
fn node_to_grow<V: Clone>(n: &mut Arc<Node<V>>) -> &mut Node<V> {
    if Arc::get_mut(n).is_none() {
        let copy = match &**n {
            Node::Leaf(v) => Node::Leaf(with_room(v)),
            Node::Branch(v) => Node::Branch(with_room(v)),
        };
        *n = Arc::new(copy);
    }
    Arc::make_mut(n)
}

/// The node an insert goes down to: a leaf takes one more entry (a copy made has room
/// for it), a branch only on a split below.
fn for_insert<V: Clone>(n: &mut Arc<Node<V>>) -> &mut Node<V> {
    match &**n {
        Node::Leaf(_) => node_to_grow(n),
        Node::Branch(_) => Arc::make_mut(n),
    }
}

/// A copy of `v` with room for one more.
fn with_room<T: Clone>(v: &[T]) -> Vec<T> {
    let mut out = Vec::with_capacity(v.len() + 1);
    out.extend_from_slice(v);
    out
}

/// The largest key of the subtree `n` (the last entry of its last leaf).
fn last_key<V>(mut n: &Node<V>) -> Option<ElementId> {
    loop {
        match n {
            Node::Leaf(v) => return v.last().map(|(k, _)| *k),
            Node::Branch(v) => n = &v.last()?.1,
        }
    }
}

/// Adds `leaf` (keys above every key of the branch `v`, the first `key`) at the
/// right edge of the branch, at the depth of its leaves; returns the branch's new
/// right sibling if it split. A full branch stays full (keys only arrive at the
/// end here).
fn push_right<V: Clone>(
    v: &mut Vec<(ElementId, Arc<Node<V>>)>,
    key: ElementId,
    leaf: Arc<Node<V>>,
) -> Option<(ElementId, Arc<Node<V>>)> {
    let split = match v.last_mut() {
        // The children are branches: down the right edge (copied if shared).
        Some((_, last)) if matches!(&**last, Node::Branch(_)) => match node_to_grow(last) {
            Node::Branch(kids) => push_right(kids, key, leaf),
            Node::Leaf(_) => None,
        },
        // The children are leaves (none copied): the new one is a sibling.
        _ => Some((key, leaf)),
    };
    v.push(split?);
    if v.len() <= MAX {
        return None;
    }
    let right = split_at(v, true);
    Some((right[0].0, Arc::new(Node::Branch(right))))
}

fn first_key<V>(n: &Node<V>) -> Option<ElementId> {
    match n {
        Node::Leaf(v) => v.first().map(|(k, _)| *k),
        Node::Branch(v) => v.first().map(|(k, _)| *k),
    }
}

/// Splits an overfull node (`MAX + 1` items): after an item added at its end, the
/// full left part stays full and the new item starts the right one (keys arrive in
/// increasing order); elsewhere, in halves.
fn split_at<T>(v: &mut Vec<T>, added_at_end: bool) -> Vec<T> {
    let at = if added_at_end { MAX } else { v.len() / 2 };
    v.split_off(at)
}

/// A node's new right sibling after a split, with its first key.
type Sibling<V> = (ElementId, Arc<Node<V>>);

/// Inserts into the subtree `node`; returns the replaced entry and, if the node
/// split, its new right sibling with its first key.
fn insert_into<V: Clone>(
    node: &mut Node<V>,
    id: ElementId,
    entry: V,
) -> (Option<V>, Option<Sibling<V>>) {
    match node {
        Node::Leaf(v) => match v.binary_search_by_key(&id, |(k, _)| *k) {
            Ok(i) => (Some(std::mem::replace(&mut v[i].1, entry)), None),
            Err(i) => {
                v.insert(i, (id, entry));
                if v.len() <= MAX {
                    return (None, None);
                }
                let right = split_at(v, i == MAX);
                let key = right[0].0;
                (None, Some((key, Arc::new(Node::Leaf(right)))))
            }
        },
        Node::Branch(v) => {
            // The child whose range holds `id`; below every bound, the first child,
            // whose bound is lowered to `id`.
            let i = v.partition_point(|(k, _)| *k <= id).saturating_sub(1);
            if id < v[i].0 {
                v[i].0 = id;
            }
            let (old, split) = insert_into(for_insert(&mut v[i].1), id, entry);
            let Some(sibling) = split else { return (old, None) };
            v.insert(i + 1, sibling);
            if v.len() <= MAX {
                return (old, None);
            }
            let right = split_at(v, i + 1 == MAX);
            let key = right[0].0;
            (old, Some((key, Arc::new(Node::Branch(right)))))
        }
    }
}

/// Removes `id` from the subtree `node` (known to hold it); an emptied child is
/// dropped from its parent.
fn remove_from<V: Clone>(node: &mut Node<V>, id: &ElementId) -> Option<V> {
    match node {
        Node::Leaf(v) => {
            let i = v.binary_search_by_key(id, |(k, _)| *k).ok()?;
            Some(v.remove(i).1)
        }
        Node::Branch(v) => {
            let i = v.partition_point(|(k, _)| k <= id).checked_sub(1)?;
            let child = Arc::make_mut(&mut v[i].1);
            let old = remove_from(child, id);
            let empty = match &*v[i].1 {
                Node::Leaf(l) => l.is_empty(),
                Node::Branch(b) => b.is_empty(),
            };
            if empty {
                v.remove(i);
            }
            old
        }
    }
}

impl<V: Clone + std::fmt::Debug> std::fmt::Debug for ElemMap<V> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_map().entries(self.entries()).finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::index::Entry;
    use crate::schema::ElementKind;
    use std::collections::BTreeMap;

    /// Ids in increasing order (fresh ones are), indexed by `n`.
    fn id(n: u64) -> ElementId {
        use std::sync::OnceLock;
        static IDS: OnceLock<Vec<ElementId>> = OnceLock::new();
        IDS.get_or_init(|| (0..10_000).map(|_| ElementId::fresh()).collect())[n as usize]
    }

    fn entry(n: u64) -> Entry {
        Entry {
            parent: None,
            kind: ElementKind::ROOT,
            text: None,
            frame: false,
            pos: n as usize,
            ord: n,
        }
    }

    fn same(m: &ElemMap<Entry>, model: &BTreeMap<u64, u64>) {
        assert_eq!(m.len(), model.len());
        let got: Vec<(ElementId, u64)> = m.entries().iter().map(|(k, e)| (**k, e.ord)).collect();
        let want: Vec<(ElementId, u64)> = model.iter().map(|(k, v)| (id(*k), *v)).collect();
        assert_eq!(got, want);
        for (k, v) in model {
            assert_eq!(m.get(&id(*k)).map(|e| e.ord), Some(*v));
        }
    }

    /// A small deterministic generator (xorshift), so failures repeat.
    fn rng(state: &mut u64) -> u64 {
        *state ^= *state << 13;
        *state ^= *state >> 7;
        *state ^= *state << 17;
        *state
    }

    #[test]
    fn built_from_entries_in_any_order() {
        for n in [0u64, 1, 15, 16, 17, 255, 256, 257, 4097] {
            let sorted = ElemMap::from_entries((0..n).map(|k| (id(k * 2), entry(k))).collect());
            let model: BTreeMap<u64, u64> = (0..n).map(|k| (k * 2, k)).collect();
            same(&sorted, &model);
            assert!(!sorted.contains_key(&id(1)));
            let mut shuffled: Vec<(ElementId, Entry)> =
                (0..n).rev().map(|k| (id(k * 2), entry(k))).collect();
            shuffled.push((id(1), entry(99)));
            let m = ElemMap::from_entries(shuffled);
            let mut model = model;
            model.insert(1, 99);
            same(&m, &model);
        }
    }

    #[test]
    fn built_from_sparse_entries_in_any_order() {
        // Keys spread over a range far larger than their number: sorted, not placed.
        let keys: Vec<u64> = (0..40).map(|k| (k * 211) % 9973).collect();
        let mut entries: Vec<(ElementId, Entry)> =
            keys.iter().map(|&k| (id(k), entry(k))).collect();
        entries.reverse();
        let m = ElemMap::from_entries(entries);
        let model: BTreeMap<u64, u64> = keys.iter().map(|&k| (k, k)).collect();
        same(&m, &model);
    }

    #[test]
    fn inserts_and_removals_agree_with_a_btreemap_and_keep_old_versions() {
        let mut state = 0x2545_F491_4F6C_DD1D;
        let mut m = ElemMap::from_entries((0..500).map(|k| (id(k * 3), entry(k))).collect());
        let mut model: BTreeMap<u64, u64> = (0..500).map(|k| (k * 3, k)).collect();
        let mut versions: Vec<(ElemMap<Entry>, BTreeMap<u64, u64>)> = Vec::new();
        for step in 0..20_000u64 {
            let r = rng(&mut state);
            let k = match r % 4 {
                // Appends after the largest key, as new elements are.
                0 => model.keys().next_back().map_or(0, |k| k + 1),
                _ => (r >> 8) % 2000,
            };
            if (r >> 40) % 3 == 0 {
                assert_eq!(m.remove(&id(k)).map(|e| e.ord), model.remove(&k));
            } else {
                assert_eq!(m.insert(id(k), entry(step)).map(|e| e.ord), model.insert(k, step));
            }
            if step % 2000 == 0 {
                same(&m, &model);
                versions.push((m.clone(), model.clone()));
            }
        }
        same(&m, &model);
        for (v, model) in &versions {
            same(v, model);
        }
        // Emptied completely, then reused.
        for k in model.keys().copied().collect::<Vec<_>>() {
            assert!(m.remove(&id(k)).is_some());
        }
        assert_eq!(m.len(), 0);
        assert!(m.root.is_none());
        assert!(m.insert(id(7), entry(1)).is_none());
        assert_eq!(m.get(&id(7)).map(|e| e.ord), Some(1));
    }

    #[test]
    fn appended_keys_fill_their_leaves() {
        let mut m = ElemMap::default();
        // One more than the tree's full leaves hold: that one is in the tail.
        for k in 0..=(MAX as u64 * MAX as u64) {
            m.insert(id(k), entry(k));
        }
        let Some(Node::Branch(kids)) = m.root.as_deref() else { panic!("a branch root") };
        assert_eq!(kids.len(), MAX);
        assert!(kids.iter().all(|(_, c)| matches!(&**c, Node::Leaf(v) if v.len() == MAX)));
        assert_eq!(m.tail_entries().map(<[_]>::len), Some(1));
    }

    /// Leaves at one depth, keys in order within and across nodes, every bound at
    /// most its subtree's keys, the tail above the tree.
    fn sound(m: &ElemMap<Entry>) {
        fn walk(n: &Node<Entry>, depth: usize, leaves: &mut Vec<usize>, keys: &mut Vec<ElementId>) {
            match n {
                Node::Leaf(v) => {
                    assert!(!v.is_empty() && v.len() <= MAX);
                    leaves.push(depth);
                    keys.extend(v.iter().map(|(k, _)| *k));
                }
                Node::Branch(v) => {
                    assert!(!v.is_empty() && v.len() <= MAX);
                    for (bound, c) in v {
                        let at = keys.len();
                        walk(c, depth + 1, leaves, keys);
                        assert!(keys[at..].iter().all(|k| k >= bound));
                    }
                }
            }
        }
        let (mut leaves, mut keys) = (Vec::new(), Vec::new());
        if let Some(r) = m.root.as_deref() {
            walk(r, 0, &mut leaves, &mut keys);
        }
        assert!(leaves.windows(2).all(|w| w[0] == w[1]), "leaves at one depth");
        if let Some(t) = m.tail_entries() {
            assert!(!t.is_empty() && t.len() <= MAX);
            keys.extend(t.iter().map(|(k, _)| *k));
        }
        assert!(keys.windows(2).all(|w| w[0] < w[1]), "keys in order");
        assert_eq!(keys.len(), m.len());
    }

    #[test]
    fn appends_go_through_the_tail_and_keep_old_versions() {
        // Built from entries (no tail), then appended to, with removals and
        // replacements near the end (in the tail) and before it (in the tree).
        let mut m = ElemMap::from_entries((0..40).map(|k| (id(k), entry(k))).collect());
        let mut model: BTreeMap<u64, u64> = (0..40).map(|k| (k, k)).collect();
        let mut versions = Vec::new();
        let mut state = 0x9E37_79B9_7F4A_7C15;
        for k in 40..6000u64 {
            assert!(m.insert(id(k), entry(k)).is_none());
            model.insert(k, k);
            let r = rng(&mut state);
            if r % 5 == 0 {
                // A recent key (often in the tail) or an older one.
                let back = (r >> 8) % if r % 2 == 0 { 20 } else { 400 };
                let old = k.saturating_sub(back);
                assert_eq!(m.remove(&id(old)).map(|e| e.ord), model.remove(&old));
            }
            if r % 7 == 0 {
                let old = k.saturating_sub((r >> 16) % 30);
                assert_eq!(m.insert(id(old), entry(k)).map(|e| e.ord), model.insert(old, k));
            }
            if k % 97 == 0 {
                sound(&m);
                versions.push((m.clone(), model.clone()));
            }
        }
        sound(&m);
        same(&m, &model);
        for (v, model) in &versions {
            sound(v);
            same(v, model);
        }
        // A clone shares its tail until either changes; then they differ.
        let mut c = m.clone();
        assert!(c.ptr_eq(&m));
        c.insert(id(6000), entry(1));
        assert!(!c.ptr_eq(&m));
        assert!(m.get(&id(6000)).is_none());
    }
}
