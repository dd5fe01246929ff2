//! The identifier index of one model: a persistent map kept exact by every edit.
//!
//! Two persistent maps (so a model clone shares them, and an edit copies
//! O(log n) of them):
//! - `names`: (namespace, identifier) → element, for `find` and duplicate checks;
//! - `elems`: element → (parent, kind, identifier), for locating an element by its id
//!   and for writing references to it. A B-tree (`ElemMap`, `super::elems`): ids are
//!   handed out in increasing order, so a model read or built in order fills its
//!   nodes (a read model's is built in one pass), where a hash trie holding every
//!   element left most slots of its 32-slot nodes empty (about twice the memory, and
//!   as many cache misses, for large models).
//!
//! The index of an attached child lives in the child value, never in the parent's.

use std::sync::{Arc, OnceLock};

use imbl::{GenericHashMap, HashMap, OrdMap};
use smol_str::SmolStr;

use super::elems::ElemMap;
use super::tree::{ElementId, Node};
use crate::id::IdHash;
use crate::schema::{ElementKind, Namespace};
use crate::seq::fresh_ord;

/// A persistent map keyed by element ids, hashed cheaply (ids are not user input).
pub(crate) type IdMap<V> = GenericHashMap<ElementId, V, IdHash, imbl::shared_ptr::DefaultSharedPtr>;

/// What the index knows about one element.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Entry {
    pub(crate) parent: Option<ElementId>,
    pub(crate) kind: ElementKind,
    pub(crate) name: Option<SmolStr>,
    /// The element's position among its parent's children when it was indexed: a
    /// hint, checked before use (later inserts and removals before it shift it).
    pub(crate) pos: usize,
    /// The element's slot in its parent's children (see `crate::seq`), which finds
    /// it in O(log width) whatever was inserted or removed before it; checked before
    /// use (a sequence numbered afresh has other slots).
    pub(crate) ord: u64,
}

#[derive(Clone, Debug, Default)]
pub(crate) struct Index {
    pub(crate) names: HashMap<(Namespace, SmolStr), ElementId>,
    pub(crate) elems: ElemMap,
    /// The model's own attachments: scope names and frames, in attach order.
    pub(crate) scopes: Scopes,
    /// The model's name where it differs from its `model` attribute: `include_copy`
    /// replaces the attribute (as the reference does) but not the name that scopes
    /// the model when it is attached.
    pub(crate) own_name: Option<SmolStr>,
    /// The merged global settings of the model with its attachments, once known.
    /// Shared by the versions whose settings and attachments are the same; every
    /// edit that can change them starts a new, empty one.
    pub(crate) merged: MergedCache,
}

/// A lazily computed, shared value of the merged settings sections (root order).
#[derive(Clone, Default)]
pub(crate) struct MergedCache(Arc<OnceLock<Arc<[Node]>>>);

impl MergedCache {
    pub(crate) fn get(&self) -> Option<&Arc<[Node]>> {
        self.0.get()
    }

    /// Stores `sections` (computed for this cache's model) and returns what it holds.
    pub(crate) fn fill(&self, sections: Arc<[Node]>) -> Arc<[Node]> {
        self.0.get_or_init(|| sections).clone()
    }

    /// Whether two versions share one cache (their merged settings are the same).
    pub(crate) fn same(&self, other: &MergedCache) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }
}

impl std::fmt::Debug for MergedCache {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(if self.get().is_some() { "MergedCache(known)" } else { "MergedCache(empty)" })
    }
}

/// A name already taken, found while indexing.
#[derive(Debug)]
pub(crate) struct Duplicate {
    pub(crate) id: ElementId,
    pub(crate) namespace: Namespace,
    pub(crate) name: SmolStr,
}

impl Index {
    /// Adds `node` and its whole subtree, under `parent`. On a duplicate name the index
    /// is left partly updated: callers work on a copy and drop it on error.
    pub(crate) fn insert_subtree(
        &mut self,
        parent: Option<ElementId>,
        node: &Node,
        at: usize,
    ) -> Result<(), Duplicate> {
        self.insert_subtree_at(parent, node, at, fresh_ord(at))
    }

    /// [`Index::insert_subtree`] for a node inserted at slot `ord` of its parent's
    /// children (the slot `Seq::insert` returned). The descendants' slots are those of
    /// sequences built by adding at the end (checked on use, as every slot is).
    pub(crate) fn insert_subtree_at(
        &mut self,
        parent: Option<ElementId>,
        node: &Node,
        at: usize,
        ord: u64,
    ) -> Result<(), Duplicate> {
        let in_frame = parent.is_some_and(|p| self.scope_of(p).is_some());
        let mut stack: Vec<(Option<ElementId>, &Node, bool, usize, u64)> =
            vec![(parent, node, in_frame, at, ord)];
        while let Some((parent, n, in_frame, pos, ord)) = stack.pop() {
            self.insert_one(parent, n, !in_frame, pos, ord)?;
            // Reversed, so that elements are indexed in document order and a duplicate
            // is reported at its second occurrence. A frame's joints are unique per
            // frame only, so their names are not registered.
            let frame = n.attached().is_some();
            stack.extend(
                n.children()
                    .iter()
                    .enumerate()
                    .rev()
                    .map(|(i, c)| (Some(n.id()), c, frame, i, fresh_ord(i))),
            );
        }
        Ok(())
    }

    /// The index of a model just read: `names` holds every identifier of the tree
    /// `root` (the reader collected them, in document order, finding duplicates at
    /// their second occurrence); the elements are added here. A read model has no
    /// attachments, so every name is registered.
    pub(crate) fn from_read(
        root: &Node,
        names: HashMap<(Namespace, SmolStr), ElementId>,
        elements: usize,
    ) -> Index {
        // Collected, then built in one pass (in document order the ids mostly
        // increase: the reader hands them out in that order). `elements` is the
        // reader's count, a hint for the list's size.
        let mut entries: Vec<(ElementId, Entry)> = Vec::with_capacity(elements);
        let mut stack: Vec<(Option<ElementId>, &Node, usize)> = vec![(None, root, 0)];
        while let Some((parent, n, pos)) = stack.pop() {
            let name = n.identifier().map(SmolStr::from);
            let entry = Entry { parent, kind: n.kind(), name, pos, ord: fresh_ord(pos) };
            entries.push((n.id(), entry));
            stack.extend(n.children().iter().enumerate().rev().map(|(i, c)| (Some(n.id()), c, i)));
        }
        Index { names, elems: ElemMap::from_entries(entries), ..Index::default() }
    }

    fn insert_one(
        &mut self,
        parent: Option<ElementId>,
        n: &Node,
        register: bool,
        pos: usize,
        ord: u64,
    ) -> Result<(), Duplicate> {
        let name = n.identifier().map(SmolStr::from);
        if let (Some(ns), Some(name), true) = (n.kind().namespace(), &name, register) {
            // One hash of the name: insert, and put the earlier element back if the
            // name was taken.
            let key = (ns, name.clone());
            if let Some(earlier) = self.names.insert(key.clone(), n.id()) {
                self.names.insert(key, earlier);
                return Err(Duplicate { id: n.id(), namespace: ns, name: name.clone() });
            }
        }
        self.elems.insert(n.id(), Entry { parent, kind: n.kind(), name, pos, ord });
        Ok(())
    }

    /// Removes `node` and its subtree.
    pub(crate) fn remove_subtree(&mut self, node: &Node) {
        for n in node.descendants() {
            if let Some(e) = self.elems.remove(&n.id()) {
                if let (Some(ns), Some(name)) = (e.kind.namespace(), e.name) {
                    if self.names.get(&(ns, name.clone())) == Some(&n.id()) {
                        self.names.remove(&(ns, name));
                    }
                }
            }
            if n.attached().is_some() {
                self.scopes.remove(n.id());
            }
        }
    }

    /// Changes the identifier of `id` (already checked to be free).
    pub(crate) fn rename(&mut self, id: ElementId, new: Option<SmolStr>) {
        let Some(entry) = self.elems.get(&id).cloned() else { return };
        let in_frame = entry.parent.is_some_and(|p| self.scope_of(p).is_some());
        if let (Some(ns), false) = (entry.kind.namespace(), in_frame) {
            if let Some(old) = &entry.name {
                self.names.remove(&(ns, old.clone()));
            }
            if let Some(new) = &new {
                self.names.insert((ns, new.clone()), id);
            }
        }
        self.elems.insert(id, Entry { name: new, ..entry });
    }

    /// The scope name of the attachment whose frame is `frame`.
    pub(crate) fn scope_of(&self, frame: ElementId) -> Option<&SmolStr> {
        self.scopes.scope_of(frame)
    }

    /// The frame of the attachment named `scope`.
    pub(crate) fn frame_of(&self, scope: &str) -> Option<ElementId> {
        self.scopes.frame_of(scope)
    }

    /// The ids from the root down to `id`, inclusive, each with its position hint
    /// and slot.
    pub(crate) fn ancestry(&self, id: ElementId) -> Option<Vec<(ElementId, usize, u64)>> {
        let mut cur = self.elems.get(&id)?;
        let mut chain = vec![(id, cur.pos, cur.ord)];
        while let Some(p) = cur.parent {
            cur = self.elems.get(&p)?;
            chain.push((p, cur.pos, cur.ord));
        }
        chain.reverse();
        Some(chain)
    }
}

/// A model's own attachments: (scope name, frame) in attach order, found by name and
/// by frame in O(log n). Persistent, like the rest of the index.
#[derive(Clone, Debug, Default)]
pub(crate) struct Scopes {
    /// Attach sequence number → (scope, frame, the attached model's merged-settings
    /// memo). The memo is the attached model's own (shared); it is replaced when an
    /// edit inside the attachment replaces it, so an unchanged `order` map means
    /// unchanged attachments as far as merged settings go.
    order: OrdMap<u64, (SmolStr, ElementId, MergedCache)>,
    by_name: HashMap<SmolStr, (u64, ElementId)>,
    by_frame: IdMap<u64>,
    next: u64,
    /// Per base name, a suffix below which every `base_n` is taken (a hint for the
    /// suffix rule; cleared whenever a scope name is freed).
    free_from: HashMap<SmolStr, u64>,
}

impl Scopes {
    pub(crate) fn is_empty(&self) -> bool {
        self.order.is_empty()
    }

    /// (scope, frame) in attach order.
    pub(crate) fn iter(&self) -> impl DoubleEndedIterator<Item = (&SmolStr, ElementId)> {
        self.order.values().map(|(s, f, _)| (s, *f))
    }

    pub(crate) fn scope_of(&self, frame: ElementId) -> Option<&SmolStr> {
        let seq = self.by_frame.get(&frame)?;
        self.order.get(seq).map(|(s, _, _)| s)
    }

    pub(crate) fn frame_of(&self, scope: &str) -> Option<ElementId> {
        self.by_name.get(scope).map(|(_, f)| *f)
    }

    /// Whether both hold the same attachments with the same merged-settings memos
    /// (O(1): the maps are shared or not).
    pub(crate) fn same(&self, other: &Scopes) -> bool {
        self.order.ptr_eq(&other.order)
    }

    /// Records that the model attached at `frame` now has merged-settings memo
    /// `memo` (nothing changes if it is the same memo).
    pub(crate) fn note_model(&mut self, frame: ElementId, memo: &MergedCache) {
        let Some(&seq) = self.by_frame.get(&frame) else { return };
        if let Some((scope, f, old)) = self.order.get(&seq) {
            if !old.same(memo) {
                let entry = (scope.clone(), *f, memo.clone());
                self.order.insert(seq, entry);
            }
        }
    }

    /// Adds an attachment (its scope name is free) of a model whose merged-settings
    /// memo is `memo`.
    pub(crate) fn push(&mut self, scope: SmolStr, frame: ElementId, memo: MergedCache) {
        let seq = self.next;
        self.next += 1;
        self.order.insert(seq, (scope.clone(), frame, memo));
        self.by_name.insert(scope, (seq, frame));
        self.by_frame.insert(frame, seq);
    }

    /// Removes the attachment whose frame is `frame`, if any.
    pub(crate) fn remove(&mut self, frame: ElementId) {
        if let Some(seq) = self.by_frame.remove(&frame) {
            if let Some((scope, _, _)) = self.order.remove(&seq) {
                self.by_name.remove(&scope);
            }
            self.free_from = HashMap::new();
        }
    }

    /// Renames the attachment whose frame is `frame` (to a free name).
    pub(crate) fn rename(&mut self, frame: ElementId, to: SmolStr) {
        let Some(&seq) = self.by_frame.get(&frame) else { return };
        let memo = self.order.get(&seq).map(|(_, _, m)| m.clone()).unwrap_or_default();
        if let Some((old, _, _)) = self.order.insert(seq, (to.clone(), frame, memo)) {
            self.by_name.remove(&old);
        }
        self.by_name.insert(to, (seq, frame));
        self.free_from = HashMap::new();
    }

    /// `base`, or `base_1`, `base_2`, ...: the first scope name not taken (the
    /// reference's suffix rule, gaps filled from 1). Amortised O(log n) while names
    /// are only added.
    pub(crate) fn free_name(&mut self, base: &str) -> SmolStr {
        if !self.by_name.contains_key(base) {
            return base.into();
        }
        let mut n = self.free_from.get(base).copied().unwrap_or(1);
        loop {
            let name = SmolStr::from(format!("{base}_{n}"));
            if !self.by_name.contains_key(&name) {
                self.free_from.insert(base.into(), n + 1);
                return name;
            }
            n += 1;
        }
    }
}
