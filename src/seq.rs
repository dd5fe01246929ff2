//! `Seq<T>`: the persistent sequence that holds an element's children.
//!
//! A B-tree of small nodes, each behind an `Arc`: leaves hold up to 32 items, branches
//! up to 16 subtrees with their lengths. A clone is one pointer copy; an edit copies
//! the nodes on one root-to-leaf path: O(log n) nodes of at most 32 pointers each
//! (about 80 pointer copies at 15,000 children, where the earlier √n chunks copied
//! some 250). An empty sequence allocates nothing.
//!
//! Finding an item again: each item has a slot number (`ord`), increasing along the
//! sequence and kept by every edit of other items; items have keys (element ids).
//! Items added at the end (or collected) get `(i + 1) · 2^32`; an item inserted
//! between two gets the midpoint of their slots (when two neighbours are 1 apart the
//! whole sequence is numbered afresh). A holder of an item's slot (the
//! identifier index) finds its position in O(log n) however many items were inserted
//! or removed before it since ([`Seq::position_of`]), checked by the key; a stale slot
//! falls back to a scan of the items' keys around a position hint.
//!
//! Removals do not rebalance (a leaf or branch that becomes empty is dropped, and a
//! root with one subtree is replaced by it), so the depth stays O(log of the largest
//! length the sequence had).

use std::sync::Arc;

/// Items a leaf holds at most.
const LEAF: usize = 32;
/// Subtrees a branch holds at most.
const FANOUT: usize = 16;
/// The slot spacing of items added at the end.
const GAP: u64 = 1 << 32;

/// The slot of the item at position `i` of a sequence built by adding at the end.
pub(crate) fn fresh_ord(i: usize) -> u64 {
    (i as u64).saturating_add(1).saturating_mul(GAP)
}

/// An item with a key: the sequence keeps each item's key beside it, to find an
/// item's position by key (element ids for children).
pub(crate) trait Keyed {
    fn key(&self) -> u64;
}

/// A leaf: items and their slots, in order. Versions of a sequence share every leaf
/// that the edits between them did not copy (`Arc::ptr_eq`).
#[derive(Clone)]
pub(crate) struct Leaf<T> {
    /// The items' slots, non-decreasing (increasing below 2^32 items); or empty
    /// when they are `fresh_ord(first + j)`: a leaf of a collected sequence (every
    /// model read) numbers its items as added at the end, which needs no list (one
    /// allocation less per leaf, 8 bytes less per item). The first edit of the leaf
    /// makes the list.
    ords: Vec<u64>,
    first: usize,
    items: Vec<T>,
}

impl<T> Leaf<T> {
    /// A leaf of items numbered as added at the end, the first at position `first`.
    fn fresh(first: usize, items: Vec<T>) -> Leaf<T> {
        Leaf { ords: Vec::new(), first, items }
    }

    /// A leaf with these slots (as many as items).
    fn listed(ords: Vec<u64>, items: Vec<T>) -> Leaf<T> {
        Leaf { ords, first: 0, items }
    }

    fn is_fresh(&self) -> bool {
        self.ords.len() != self.items.len()
    }

    /// The slot of the item at `j`.
    fn ord(&self, j: usize) -> Option<u64> {
        if self.is_fresh() {
            (j < self.items.len()).then(|| fresh_ord(self.first + j))
        } else {
            self.ords.get(j).copied()
        }
    }

    /// The number of items whose slot is below `ord` (slots are sorted).
    fn below(&self, ord: u64) -> usize {
        if !self.is_fresh() {
            return self.ords.partition_point(|o| *o < ord);
        }
        let (mut lo, mut hi) = (0, self.items.len());
        while lo < hi {
            let mid = lo + (hi - lo) / 2;
            if self.ord(mid).is_some_and(|o| o < ord) {
                lo = mid + 1;
            } else {
                hi = mid;
            }
        }
        lo
    }

    /// The slots as a list, to edit (made from the items' count if not yet a list:
    /// call before changing `items`).
    fn ords_mut(&mut self) -> &mut Vec<u64> {
        if self.is_fresh() {
            // With room for the item an edit is about to add.
            self.ords = Vec::with_capacity(self.items.capacity().max(self.items.len() + 1));
            self.ords.extend((self.first..self.first + self.items.len()).map(fresh_ord));
        }
        &mut self.ords
    }
}

impl<T> std::ops::Deref for Leaf<T> {
    type Target = [T];
    fn deref(&self) -> &[T] {
        &self.items
    }
}

/// A branch: its subtrees in order. One vector (of subtree, length, largest slot), so
/// that copying a branch on an edit's path is one allocation, not three.
#[derive(Clone)]
struct Branch<T> {
    kids: Vec<Kid<T>>,
}

/// A subtree of a branch, with what the branch needs to know of it.
#[derive(Clone)]
struct Kid<T> {
    tree: Tree<T>,
    /// The number of items under `tree`.
    len: usize,
    /// The largest slot under `tree` (its last item's).
    max: u64,
}

impl<T> Kid<T> {
    fn new(tree: Tree<T>, len: usize) -> Kid<T> {
        Kid { max: max_ord(&tree), tree, len }
    }
}

/// The slot of the last item of a non-empty subtree.
fn max_ord<T>(t: &Tree<T>) -> u64 {
    match t {
        Tree::Leaf(l) => l.items.len().checked_sub(1).and_then(|j| l.ord(j)).unwrap_or(0),
        Tree::Branch(b) => b.kids.last().map_or(0, |k| k.max),
    }
}

enum Tree<T> {
    Leaf(Arc<Leaf<T>>),
    Branch(Arc<Branch<T>>),
}

impl<T> Clone for Tree<T> {
    fn clone(&self) -> Self {
        match self {
            Tree::Leaf(l) => Tree::Leaf(l.clone()),
            Tree::Branch(b) => Tree::Branch(b.clone()),
        }
    }
}

#[derive(Clone)]
pub(crate) struct Seq<T> {
    root: Option<Tree<T>>,
    len: usize,
}

impl<T> Default for Seq<T> {
    fn default() -> Self {
        Seq { root: None, len: 0 }
    }
}

/// The subtree of `b` holding position `i` (`i <` the branch's length, or the last
/// subtree for `i` at the end) and the position within it.
fn descend<T>(b: &Branch<T>, mut i: usize) -> (usize, usize) {
    let last = b.kids.len().saturating_sub(1);
    for (k, l) in b.kids.iter().map(|c| c.len).enumerate() {
        if i < l || k == last {
            return (k, i);
        }
        i -= l;
    }
    (0, i)
}

/// What an insert into a subtree left: nothing more, or a new right sibling (with
/// its length) that the parent must take after it.
type Split<T> = Option<(Tree<T>, usize)>;

impl<T: Clone + Keyed> Seq<T> {
    pub(crate) fn new() -> Seq<T> {
        Seq::default()
    }

    pub(crate) fn len(&self) -> usize {
        self.len
    }

    pub(crate) fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The leaf holding position `i` (`i < len`) and the position within it.
    fn locate(&self, mut i: usize) -> Option<(&Arc<Leaf<T>>, usize)> {
        let mut t = self.root.as_ref()?;
        loop {
            match t {
                Tree::Leaf(l) => return Some((l, i)),
                Tree::Branch(b) => {
                    let (k, j) = descend(b, i);
                    t = &b.kids[k].tree;
                    i = j;
                }
            }
        }
    }

    pub(crate) fn get(&self, i: usize) -> Option<&T> {
        if i >= self.len {
            return None;
        }
        let (leaf, j) = self.locate(i)?;
        leaf.items.get(j)
    }

    pub(crate) fn iter(&self) -> Iter<'_, T> {
        self.range(0, self.len)
    }

    /// The first item that `pred` accepts. A sequence of one leaf (most elements'
    /// children) is searched as a slice, without an iterator's bookkeeping.
    pub(crate) fn find(&self, mut pred: impl FnMut(&T) -> bool) -> Option<&T> {
        match &self.root {
            Some(Tree::Leaf(leaf)) => leaf.items.iter().find(|x| pred(x)),
            _ => self.iter().find(|x| pred(x)),
        }
    }

    /// The items at positions `start..end` (clamped to the length), found in
    /// O(log n) rather than by stepping over the ones before.
    pub(crate) fn range(&self, start: usize, end: usize) -> Iter<'_, T> {
        let end = end.min(self.len);
        let start = start.min(end);
        let mut it = Iter {
            front: Vec::new(),
            front_items: [].iter(),
            back: Vec::new(),
            back_items: [].iter(),
            left: end - start,
        };
        if start == end {
            return it;
        }
        if let Some(Tree::Leaf(leaf)) = &self.root {
            // One leaf (most elements' children): both ends in it, no path.
            it.front_items = leaf.items[start..end].iter();
            it.back_items = leaf.items[start..end].iter();
        } else if let Some(root) = &self.root {
            let (stack, leaf, j) = path_to(root, start);
            it.front = stack;
            it.front_items = leaf.items[j..].iter();
            let (stack, leaf, j) = path_to(root, end - 1);
            it.back = stack;
            it.back_items = leaf.items[..=j].iter();
        }
        it
    }

    /// The leaves in order, each with the position of its first item. Versions of a
    /// sequence share (`Arc::ptr_eq`) every leaf that the edits between them did not
    /// copy, so a comparison can skip those without looking at their items.
    pub(crate) fn chunks(&self) -> Chunks<'_, T> {
        Chunks {
            stack: self.root.as_ref().map(|r| vec![(r, 0)]).unwrap_or_default(),
            at: 0,
            left: self.leaf_count(),
        }
    }

    fn leaf_count(&self) -> usize {
        fn count<T>(t: &Tree<T>) -> usize {
            match t {
                Tree::Leaf(_) => 1,
                Tree::Branch(b) => b.kids.iter().map(|k| count(&k.tree)).sum(),
            }
        }
        self.root.as_ref().map_or(0, count)
    }

    /// Whether both share one tree, so hold the same items (O(1)).
    pub(crate) fn ptr_eq(&self, other: &Seq<T>) -> bool {
        match (&self.root, &other.root) {
            (None, None) => true,
            (Some(Tree::Leaf(a)), Some(Tree::Leaf(b))) => Arc::ptr_eq(a, b),
            (Some(Tree::Branch(a)), Some(Tree::Branch(b))) => Arc::ptr_eq(a, b),
            _ => false,
        }
    }

    /// The position of the item with key `key`, looked for first at `hint`, then in
    /// windows that double around it: O(d + log n · log d) for an item `d` positions
    /// from the hint.
    pub(crate) fn position_near(&self, key: u64, hint: usize) -> Option<usize> {
        let hint = hint.min(self.len);
        if self.get(hint).is_some_and(|x| x.key() == key) {
            return Some(hint);
        }
        // Inserts before the item move it after the hint, removals before it, so
        // look after the hint first, then before.
        let (mut lo, mut hi) = (hint, hint);
        let mut w = LEAF;
        while lo > 0 || hi < self.len {
            let new_hi = (hi + w).min(self.len);
            if let Some(p) = self.key_position(key, hi, new_hi) {
                return Some(p);
            }
            hi = new_hi;
            let new_lo = lo.saturating_sub(w);
            if let Some(p) = self.key_position(key, new_lo, lo) {
                return Some(p);
            }
            lo = new_lo;
            w *= 2;
        }
        None
    }

    /// The position of `key` among positions `start..end`.
    fn key_position(&self, key: u64, start: usize, end: usize) -> Option<usize> {
        if start >= end {
            return None;
        }
        let root = self.root.as_ref()?;
        let (mut stack, leaf, j) = path_to(root, start);
        let mut at = start;
        let mut items = &leaf.items[j..];
        loop {
            let n = items.len().min(end - at);
            if let Some(p) = items[..n].iter().position(|x| x.key() == key) {
                return Some(at + p);
            }
            at += n;
            if at >= end {
                return None;
            }
            items = &adjacent_leaf(&mut stack, true)?.items;
        }
    }

    /// The slot of the item at position `i`.
    fn ord_at(&self, i: usize) -> Option<u64> {
        let (leaf, j) = self.locate(i)?;
        leaf.ord(j)
    }

    /// A slot for an item inserted at position `i`, between its neighbours' (`None`
    /// if they are too close).
    fn slot_for(&self, i: usize) -> Option<u64> {
        let prev = match i {
            0 => 0,
            // The last item's slot is the root's largest: no descent to find it.
            _ if i >= self.len => self.root.as_ref().map_or(0, max_ord),
            _ => self.ord_at(i - 1)?,
        };
        if i >= self.len {
            return prev.checked_add(GAP);
        }
        let next = self.ord_at(i)?;
        (next > prev + 1).then(|| prev + (next - prev) / 2)
    }

    /// The slot [`Seq::insert`] would give an item inserted at `i` (for a holder of
    /// slots that must record it before the insert), and whether that insert numbers
    /// the sequence afresh first (its neighbours' slots are too close).
    pub(crate) fn slot_at_insert(&self, i: usize) -> (u64, bool) {
        let i = i.min(self.len);
        match self.slot_for(i) {
            Some(o) => (o, false),
            // Numbered afresh, item `j` has slot `fresh_ord(j)`: the midpoint of the
            // neighbours' (or the next slot at the end).
            None if i == self.len => (fresh_ord(i), true),
            None => {
                let prev = if i == 0 { 0 } else { fresh_ord(i - 1) };
                (prev + (fresh_ord(i) - prev) / 2, true)
            }
        }
    }

    /// Inserts `value` at position `i` (at the end if `i >= len`); returns its slot
    /// (the one [`Seq::slot_at_insert`] tells).
    pub(crate) fn insert(&mut self, i: usize, value: T) -> u64 {
        let i = i.min(self.len);
        let (ord, afresh) = self.slot_at_insert(i);
        if afresh {
            // Past 2^32 items slots may repeat (found by scan).
            *self = self.iter().cloned().collect();
        }
        let Some(root) = self.root.as_mut() else {
            let leaf = Leaf::listed(vec![ord], vec![value]);
            self.root = Some(Tree::Leaf(Arc::new(leaf)));
            self.len = 1;
            return ord;
        };
        let old_len = self.len;
        if let Some((right, right_len)) = insert_into(root, i, ord, value) {
            let left = root.clone();
            *root = Tree::Branch(Arc::new(Branch {
                kids: vec![Kid::new(left, old_len + 1 - right_len), Kid::new(right, right_len)],
            }));
        }
        self.len += 1;
        ord
    }

    pub(crate) fn push_back(&mut self, value: T) {
        self.insert(self.len, value);
    }

    /// The position of the item with key `key` and slot `ord`: O(log n) while the slot
    /// is the item's; else (a slot from before the sequence was numbered afresh) as
    /// [`Seq::position_near`] from `hint`.
    pub(crate) fn position_of(&self, key: u64, ord: u64, hint: usize) -> Option<usize> {
        if let Some((p, x)) = self.first_at_or_after(ord) {
            if x.key() == key {
                return Some(p);
            }
        }
        self.position_near(key, hint)
    }

    /// The first position whose slot is at least `ord`, and its item (found in the
    /// same descent).
    fn first_at_or_after(&self, ord: u64) -> Option<(usize, &T)> {
        let mut t = self.root.as_ref()?;
        let mut at = 0;
        loop {
            match t {
                Tree::Leaf(l) => {
                    let j = l.below(ord);
                    return l.items.get(j).map(|x| (at + j, x));
                }
                Tree::Branch(b) => {
                    let k = b.kids.partition_point(|c| c.max < ord);
                    if k >= b.kids.len() {
                        return None;
                    }
                    at += b.kids[..k].iter().map(|c| c.len).sum::<usize>();
                    t = &b.kids[k].tree;
                }
            }
        }
    }

    /// Removes and returns the item at `i`, if any.
    pub(crate) fn remove(&mut self, i: usize) -> Option<T> {
        if i >= self.len {
            return None;
        }
        let root = self.root.as_mut()?;
        let removed = remove_from(root, i);
        self.len -= 1;
        if self.len == 0 {
            self.root = None;
        } else {
            // A root branch with one subtree is replaced by it.
            loop {
                let only = match &self.root {
                    Some(Tree::Branch(b)) if b.kids.len() == 1 => b.kids[0].tree.clone(),
                    _ => break,
                };
                self.root = Some(only);
            }
        }
        Some(removed)
    }

    /// The item at `i`, mutable: the nodes on its path that other versions share are
    /// copied first (`Arc::make_mut`), so only this sequence sees the change, and a
    /// uniquely owned path is edited where it is.
    pub(crate) fn get_mut(&mut self, i: usize) -> Option<&mut T> {
        if i >= self.len {
            return None;
        }
        let mut t = self.root.as_mut()?;
        let mut i = i;
        loop {
            match t {
                Tree::Leaf(l) => return Arc::make_mut(l).items.get_mut(i),
                Tree::Branch(b) => {
                    let b = Arc::make_mut(b);
                    let (k, j) = descend(b, i);
                    t = &mut b.kids[k].tree;
                    i = j;
                }
            }
        }
    }

    /// Replaces the item at `i` (nothing happens past the end).
    pub(crate) fn set(&mut self, i: usize, value: T) {
        if i >= self.len {
            return;
        }
        let Some(mut t) = self.root.as_mut() else { return };
        let mut i = i;
        loop {
            match t {
                Tree::Leaf(l) => {
                    let l = Arc::make_mut(l);
                    l.items[i] = value;
                    return;
                }
                Tree::Branch(b) => {
                    let b = Arc::make_mut(b);
                    let (k, j) = descend(b, i);
                    t = &mut b.kids[k].tree;
                    i = j;
                }
            }
        }
    }
}

/// Inserts at position `i` of the subtree `t` (`i <=` its length); returns the new
/// right sibling if `t` split.
fn insert_into<T: Clone>(t: &mut Tree<T>, i: usize, ord: u64, value: T) -> Split<T> {
    match t {
        Tree::Leaf(l) => {
            let l = leaf_to_grow(l);
            if l.items.len() < LEAF {
                l.ords_mut().insert(i, ord);
                l.items.insert(i, value);
                return None;
            }
            // Full: split in halves first, the right one made with room for a full
            // leaf, then insert into the half that holds position `i`. (Inserted
            // first, the full leaf grew to twice its size to be halved, and the right
            // half grew again as it filled.)
            let half = LEAF / 2;
            let mut ords = Vec::with_capacity(LEAF);
            ords.extend(l.ords_mut().drain(half..));
            let mut items = Vec::with_capacity(LEAF);
            items.extend(l.items.drain(half..));
            let mut right = Leaf::listed(ords, items);
            let at = if i <= half { &mut *l } else { &mut right };
            let j = if i <= half { i } else { i - half };
            at.ords_mut().insert(j, ord);
            at.items.insert(j, value);
            let n = right.items.len();
            Some((Tree::Leaf(Arc::new(right)), n))
        }
        Tree::Branch(b) => {
            let b = Arc::make_mut(b);
            let (k, j) = descend(b, i);
            let kid = &mut b.kids[k];
            let split = insert_into(&mut kid.tree, j, ord, value);
            kid.len += 1;
            kid.max = max_ord(&kid.tree);
            if let Some((right, n)) = split {
                kid.len -= n;
                b.kids.insert(k + 1, Kid::new(right, n));
            }
            if b.kids.len() <= FANOUT {
                return None;
            }
            let half = b.kids.len() / 2;
            let right = Branch { kids: b.kids.split_off(half) };
            let n = right.kids.iter().map(|c| c.len).sum();
            Some((Tree::Branch(Arc::new(right)), n))
        }
    }
}

/// `Arc::make_mut` for a leaf about to take one more item: a copy (of a shared leaf)
/// is made with room for it, so the insert does not allocate again to grow it.
fn leaf_to_grow<T: Clone>(l: &mut Arc<Leaf<T>>) -> &mut Leaf<T> {
    if Arc::get_mut(l).is_none() {
        // The copy is listed (an edit follows, which needs the slots).
        let mut ords = Vec::with_capacity(l.items.len() + 1);
        ords.extend((0..l.items.len()).filter_map(|j| l.ord(j)));
        let mut items = Vec::with_capacity(l.items.len() + 1);
        items.extend(l.items.iter().cloned());
        *l = Arc::new(Leaf::listed(ords, items));
    }
    Arc::make_mut(l)
}

/// Removes position `i` (`<` its length) of the subtree `t`; subtrees left empty are
/// dropped from their branch (the caller drops an empty root).
fn remove_from<T: Clone>(t: &mut Tree<T>, i: usize) -> T {
    match t {
        Tree::Leaf(l) => {
            let l = Arc::make_mut(l);
            l.ords_mut().remove(i);
            l.items.remove(i)
        }
        Tree::Branch(b) => {
            let b = Arc::make_mut(b);
            let (k, j) = descend(b, i);
            let kid = &mut b.kids[k];
            let removed = remove_from(&mut kid.tree, j);
            kid.len -= 1;
            if kid.len == 0 {
                b.kids.remove(k);
            } else {
                kid.max = max_ord(&kid.tree);
            }
            removed
        }
    }
}

/// The branches from `root` down to the leaf holding position `i` (each with the
/// index of the subtree taken), that leaf, and the position within it.
#[allow(clippy::type_complexity)]
fn path_to<T>(root: &Tree<T>, mut i: usize) -> (Vec<(&Branch<T>, usize)>, &Leaf<T>, usize) {
    let mut stack = Vec::new();
    let mut t = root;
    loop {
        match t {
            Tree::Leaf(l) => return (stack, l, i),
            Tree::Branch(b) => {
                let (k, j) = descend(b, i);
                stack.push((&**b, k));
                t = &b.kids[k].tree;
                i = j;
            }
        }
    }
}

/// The leaf after (`forward`) or before the one `stack` leads to (updating `stack`),
/// if any.
fn adjacent_leaf<'a, T>(
    stack: &mut Vec<(&'a Branch<T>, usize)>,
    forward: bool,
) -> Option<&'a Leaf<T>> {
    // Up to the first branch with a subtree on that side of the one taken.
    loop {
        let (b, k) = stack.last_mut()?;
        if forward && *k + 1 < b.kids.len() {
            *k += 1;
            break;
        }
        if !forward && *k > 0 {
            *k -= 1;
            break;
        }
        stack.pop();
    }
    // Down that subtree's near edge.
    let (b, k) = *stack.last()?;
    let mut t = &b.kids[k].tree;
    loop {
        match t {
            Tree::Leaf(l) => return Some(l),
            Tree::Branch(b) => {
                let edge = if forward { 0 } else { b.kids.len() - 1 };
                stack.push((&**b, edge));
                t = &b.kids[edge].tree;
            }
        }
    }
}

impl<T: Clone + Keyed> FromIterator<T> for Seq<T> {
    /// Full leaves, then full branches over them, level by level: O(n).
    fn from_iter<I: IntoIterator<Item = T>>(iter: I) -> Seq<T> {
        let mut level: Vec<(Tree<T>, usize)> = Vec::new();
        let mut len = 0;
        let mut iter = iter.into_iter().peekable();
        while iter.peek().is_some() {
            let items: Vec<T> = iter.by_ref().take(LEAF).collect();
            let n = items.len();
            let leaf = Tree::Leaf(Arc::new(Leaf::fresh(len, items)));
            len += n;
            if level.is_empty() && iter.peek().is_none() {
                // One leaf (most children lists): no list of subtrees to build.
                return Seq { root: Some(leaf), len };
            }
            level.push((leaf, n));
        }
        while level.len() > 1 {
            let mut up = Vec::with_capacity(level.len().div_ceil(FANOUT));
            let mut rest = level.into_iter().peekable();
            while rest.peek().is_some() {
                let kids: Vec<Kid<T>> =
                    rest.by_ref().take(FANOUT).map(|(t, n)| Kid::new(t, n)).collect();
                let n = kids.iter().map(|c| c.len).sum();
                up.push((Tree::Branch(Arc::new(Branch { kids })), n));
            }
            level = up;
        }
        Seq { root: level.pop().map(|(t, _)| t), len }
    }
}

impl<'a, T: Clone + Keyed> IntoIterator for &'a Seq<T> {
    type Item = &'a T;
    type IntoIter = Iter<'a, T>;
    fn into_iter(self) -> Iter<'a, T> {
        self.iter()
    }
}

impl<T: Clone + Keyed + std::fmt::Debug> std::fmt::Debug for Seq<T> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list().entries(self.iter()).finish()
    }
}

/// Items in order (double-ended, exact size): each end walks its own path down the
/// tree; `left` stops them where they meet.
pub(crate) struct Iter<'a, T> {
    front: Vec<(&'a Branch<T>, usize)>,
    front_items: std::slice::Iter<'a, T>,
    back: Vec<(&'a Branch<T>, usize)>,
    back_items: std::slice::Iter<'a, T>,
    left: usize,
}

impl<'a, T> Iterator for Iter<'a, T> {
    type Item = &'a T;
    fn next(&mut self) -> Option<&'a T> {
        if self.left == 0 {
            return None;
        }
        loop {
            if let Some(x) = self.front_items.next() {
                self.left -= 1;
                return Some(x);
            }
            self.front_items = adjacent_leaf(&mut self.front, true)?.items.iter();
        }
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        (self.left, Some(self.left))
    }
}

impl<T> DoubleEndedIterator for Iter<'_, T> {
    fn next_back(&mut self) -> Option<Self::Item> {
        if self.left == 0 {
            return None;
        }
        loop {
            if let Some(x) = self.back_items.next_back() {
                self.left -= 1;
                return Some(x);
            }
            self.back_items = adjacent_leaf(&mut self.back, false)?.items.iter();
        }
    }
}

impl<T> ExactSizeIterator for Iter<'_, T> {}

/// The leaves in order, each with the position of its first item.
pub(crate) struct Chunks<'a, T> {
    /// Subtrees still to visit, the next on top, with their first positions.
    stack: Vec<(&'a Tree<T>, usize)>,
    at: usize,
    left: usize,
}

impl<'a, T> Iterator for Chunks<'a, T> {
    type Item = (usize, &'a Arc<Leaf<T>>);
    fn next(&mut self) -> Option<Self::Item> {
        while let Some((t, _)) = self.stack.pop() {
            match t {
                Tree::Leaf(l) => {
                    let at = self.at;
                    self.at += l.items.len();
                    self.left -= 1;
                    return Some((at, l));
                }
                Tree::Branch(b) => self.stack.extend(b.kids.iter().rev().map(|k| (&k.tree, 0))),
            }
        }
        None
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        (self.left, Some(self.left))
    }
}

impl<T> ExactSizeIterator for Chunks<'_, T> {}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    impl Keyed for u32 {
        fn key(&self) -> u64 {
            u64::from(*self)
        }
    }

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

    /// A collected sequence keeps no slot lists (its leaves number their items as
    /// added at the end) and answers as if it did, before and after edits.
    #[test]
    fn collected_leaves_number_items_as_pushed() {
        for n in [0usize, 1, 31, 32, 33, 100, 1000] {
            let seq: Seq<u32> = (0..n as u32).collect();
            let mut pushed: Seq<u32> = Seq::new();
            (0..n as u32).for_each(|v| pushed.push_back(v));
            for i in 0..n {
                assert_eq!(seq.ord_at(i), Some(fresh_ord(i)));
                assert_eq!(seq.ord_at(i), pushed.ord_at(i));
                assert_eq!(seq.position_of(i as u64, fresh_ord(i), 0), Some(i));
            }
            assert_eq!(seq.ord_at(n), None);
            let mut edited = seq.clone();
            edited.insert(n / 2, 7777);
            edited.remove(0);
            let ords: Vec<u64> = (0..edited.len()).filter_map(|i| edited.ord_at(i)).collect();
            assert!(ords.len() == edited.len() && ords.windows(2).all(|w| w[0] < w[1]));
            for i in 1..n {
                let at = edited.position_of(i as u64, fresh_ord(i), 0);
                assert_eq!(at.and_then(|p| edited.get(p)).copied(), Some(i as u32));
            }
            // The original is unchanged.
            assert!(seq.iter().copied().eq(0..n as u32));
        }
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
                        let (planned, _) = seq.slot_at_insert(i);
                        prop_assert_eq!(seq.insert(i, v), planned);
                    }
                    Op::Remove(i) => {
                        let got = seq.remove(i);
                        let want = (i < model.len()).then(|| model.remove(i));
                        prop_assert_eq!(got, want);
                    }
                    Op::Set(i, v) => {
                        // Through `get_mut` on odd values, `set` on even ones.
                        if v % 2 == 1 {
                            if let Some(x) = seq.get_mut(i) {
                                *x = v;
                            }
                        } else {
                            seq.set(i, v);
                        }
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
                    // Found by key from any hint (keys may repeat: an item with it).
                    if let Some(&x) = m.get(i) {
                        for hint in [0, i, i / 2, m.len(), i + 100] {
                            let q = s.position_near(u64::from(x), hint);
                            prop_assert!(q.is_some_and(|q| m[q] == x));
                        }
                    }
                }
                // By slot: every item's slot finds it.
                for i in [0, m.len() / 3, m.len().saturating_sub(1)] {
                    if let (Some(x), Some(o)) = (m.get(i), s.ord_at(i)) {
                        let q = s.position_of(u64::from(*x), o, 0);
                        prop_assert!(q.is_some_and(|q| m[q] == *x));
                    }
                }
                // The leaves cover the items in order, each at its start.
                let mut at = 0;
                for (start, leaf) in s.chunks() {
                    prop_assert_eq!(start, at);
                    prop_assert!(!leaf.is_empty());
                    prop_assert_eq!(&leaf[..], &m[at..at + leaf.len()]);
                    at += leaf.len();
                }
                prop_assert_eq!(at, m.len());
                let ords: Vec<u64> = (0..m.len()).filter_map(|i| s.ord_at(i)).collect();
                prop_assert!(ords.len() == m.len() && ords.windows(2).all(|w| w[0] < w[1]));
                prop_assert_eq!(s.chunks().len(), s.chunks().count());
                prop_assert!(s.position_near(u64::MAX, m.len() / 2).is_none());
            }
        }
    }

    #[test]
    fn emptied_and_refilled_through_every_shape() {
        let mut m: Vec<u32> = (0..3000).collect();
        let mut s: Seq<u32> = m.iter().copied().collect();
        let kept = s.clone();
        // Remove from the middle, the front and the back until empty.
        let mut k = 7usize;
        while !m.is_empty() {
            k = (k * 31 + 17) % m.len().max(1);
            assert_eq!(s.remove(k), Some(m.remove(k)));
            if m.len() % 97 == 0 {
                assert!(s.iter().copied().eq(m.iter().copied()));
                assert!(s.iter().rev().copied().eq(m.iter().rev().copied()));
            }
        }
        assert!(s.is_empty() && s.iter().next().is_none() && s.chunks().len() == 0);
        // Refill by inserts at the front and in the middle (numbering afresh many
        // times: the slot told before each insert is the one it gives).
        let mut afresh = 0;
        for i in 0..2000u32 {
            let at = if i % 2 == 0 { 0 } else { m.len() / 2 };
            m.insert(at, i);
            let (planned, renumbers) = s.slot_at_insert(at);
            afresh += usize::from(renumbers);
            assert_eq!(s.insert(at, i), planned);
            assert_eq!(s.ord_at(at), Some(planned));
        }
        assert!(afresh > 0);
        assert!(s.iter().copied().eq(m.iter().copied()));
        assert_eq!(s.position_near(1999, 0), m.iter().position(|x| *x == 1999));
        for (i, x) in m.iter().enumerate() {
            let ord = s.ord_at(i).unwrap();
            assert_eq!(s.position_of(u64::from(*x), ord, 0), Some(i));
        }
        // A slot taken before many inserts before the item still finds it.
        let mut t: Seq<u32> = (0..100).collect();
        let ord = t.ord_at(99).unwrap();
        for i in 0..5000u32 {
            let at = (i as usize * 7) % 99;
            t.insert(at, 1000 + i);
        }
        assert_eq!(t.position_of(99, ord, 99), Some(t.len() - 1));
        assert!(kept.iter().copied().eq(0..3000));
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
