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
//! - `runs`: the singleton children an element is created with (a default class's 21
//!   `geom`, `joint`, `position`, ...; `visual`'s `global`, `quality`, ...), which
//!   have consecutive ids, kinds without identifiers and their schema places, indexed
//!   as one entry per parent (first child's id → parent, count) instead of one each:
//!   their entries are derived on lookup ([`Index::entry`]). For deeply nested default
//!   classes this is 1 entry per class instead of 22. No reference can name a member
//!   of a run (its kind has no identifier), so a reference's target always has an
//!   entry in `elems`.
//!
//! The index of an attached child lives in the child value, never in the parent's.

use std::borrow::Cow;
use std::sync::{Arc, OnceLock};

use imbl::{HashMap, OrdMap};
use smol_str::SmolStr;

use super::elems::ElemMap;
use super::tree::{ElementId, Node};
use crate::schema::{ElementKind, Multiplicity, Namespace};
use crate::seq::fresh_ord;

/// What the index knows about one element.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Entry {
    pub(crate) parent: Option<ElementId>,
    pub(crate) kind: ElementKind,
    /// The identifier; for an attachment frame (`frame`), which has none, the scope
    /// name of its attachment: so the frame's own entry answers `scope_of`, and no
    /// map of its own (one more persistent map to copy a path of per attach) is
    /// needed. Read through [`Entry::name`] and [`Entry::scope`].
    pub(crate) text: Option<SmolStr>,
    /// Whether the element is an attachment frame (in the entry's padding: no size).
    pub(crate) frame: bool,
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
    /// Read through [`Index::entry`], which also knows the members of `runs`.
    pub(crate) elems: ElemMap<Entry>,
    /// Runs of singleton children without an entry of their own (module docs): the
    /// first child's id → (the parent, the run's length).
    pub(crate) runs: OrdMap<ElementId, (ElementId, u8)>,
    /// The model's own attachments: scope names and frames, in attach order.
    pub(crate) scopes: Scopes,
    /// The model's name where it differs from its `model` attribute: `include_copy`
    /// replaces the attribute (as the reference does) but not the name that scopes
    /// the model when it is attached.
    pub(crate) own_name: Option<Box<SmolStr>>,
    /// The merged global settings of the model with its attachments, once known.
    /// Shared by the versions whose settings and attachments are the same; every
    /// edit that can change them starts a new, empty one.
    pub(crate) merged: MergedCache,
    /// The literal names holding a `/` (read from MJCF, or copied from a model that
    /// was), counted by the part before their first `/` (`robot` for `robot/torso`,
    /// `""` for `//unnamed_geom_0`), over every namespace. A scope may not be such a
    /// part (`free_scope_name` skips it; `insert_one` refuses a name whose part is a
    /// scope), so that the names an attachment writes (`robot/...`) meet no literal
    /// name (`model::naming`). Empty for models built through the API, which refuses
    /// `/` in names.
    pub(crate) slashed: Slashed,
}

/// [`Index::slashed`]: a map kept behind one pointer, shared until changed, so that a
/// model (held by value in each of its attachments) stays small; `None` rather than
/// empty.
#[derive(Clone, Debug, Default)]
pub(crate) struct Slashed(Option<Arc<HashMap<SmolStr, u32>>>);

impl Slashed {
    /// The map of `counts` (the literal names holding a `/`, by the part before it).
    pub(crate) fn from_counts(counts: HashMap<SmolStr, u32>) -> Slashed {
        Slashed((!counts.is_empty()).then(|| Arc::new(counts)))
    }

    pub(crate) fn contains_key(&self, segment: &str) -> bool {
        self.0.as_ref().is_some_and(|m| m.contains_key(segment))
    }

    /// One more name with `segment` before its first `/`.
    fn add(&mut self, segment: &str) {
        let counts = Arc::make_mut(self.0.get_or_insert_with(Default::default));
        *counts.entry(segment.into()).or_insert(0) += 1;
    }

    /// One name fewer with `segment`; whether it was the last one.
    fn take(&mut self, segment: &str) -> bool {
        let Some(counts) = self.0.as_mut() else { return false };
        match counts.get(segment).copied() {
            Some(c) if c > 1 => {
                Arc::make_mut(counts).insert(segment.into(), c - 1);
                false
            }
            Some(_) => {
                Arc::make_mut(counts).remove(segment);
                if counts.is_empty() {
                    self.0 = None;
                }
                true
            }
            None => false,
        }
    }
}

/// The part of a name before its first `/`, if it has one.
pub(crate) fn slashed_segment(name: &str) -> Option<&str> {
    name.split_once('/').map(|(s, _)| s)
}

/// A lazily computed, shared value of the merged settings sections (root order).
#[derive(Clone, Default)]
pub(crate) struct MergedCache(Arc<OnceLock<Merged>>);

/// What a [`MergedCache`] holds.
struct Merged {
    sections: Arc<[Node]>,
    /// Merged sections of an attached model whose fold into `sections` changed
    /// nothing (the last attach's, when it was so): attaching a model with these
    /// very sections again (`Arc::ptr_eq`; a fleet of one robot) needs no fold.
    absorbed: Option<Arc<[Node]>>,
}

impl MergedCache {
    /// A new cache holding `sections` (the merged settings of the model it goes to),
    /// and `absorbed`, merged sections whose fold into them changes nothing.
    pub(crate) fn filled(sections: Arc<[Node]>, absorbed: Option<Arc<[Node]>>) -> MergedCache {
        MergedCache(Arc::new(OnceLock::from(Merged { sections, absorbed })))
    }

    pub(crate) fn get(&self) -> Option<&Arc<[Node]>> {
        self.0.get().map(|m| &m.sections)
    }

    /// Whether folding `theirs` into the sections held changes nothing, as known
    /// without folding (the same `Arc` was folded in before, to no effect).
    pub(crate) fn absorbs(&self, theirs: &Arc<[Node]>) -> bool {
        self.0.get().and_then(|m| m.absorbed.as_ref()).is_some_and(|a| Arc::ptr_eq(a, theirs))
    }

    /// Stores `sections` (computed for this cache's model) and returns what it holds.
    pub(crate) fn fill(&self, sections: Arc<[Node]>) -> Arc<[Node]> {
        self.0.get_or_init(|| Merged { sections, absorbed: None }).sections.clone()
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

impl Entry {
    /// The element's identifier (an attachment frame has none).
    pub(crate) fn name(&self) -> Option<&SmolStr> {
        if self.frame { None } else { self.text.as_ref() }
    }

    /// The scope name of the attachment, if the element is an attachment frame.
    pub(crate) fn scope(&self) -> Option<&SmolStr> {
        if self.frame { self.text.as_ref() } else { None }
    }
}

/// An element waiting to be indexed: its parent, itself, whether its parent is an
/// attachment frame, its position and slot, and whether it is indexed through a run
/// (`runs`) rather than by an entry of its own.
type ToIndex<'a> = (Option<ElementId>, &'a Node, bool, usize, u64, bool);

/// A name already taken, found while indexing: by another element of the
/// namespace, or (a name with a `/`) by an attachment whose scope is the part before
/// its `/` (its names are written `scope/...`).
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
        let mut stack: Vec<ToIndex<'_>> = vec![(parent, node, in_frame, at, ord, false)];
        while let Some((parent, n, in_frame, pos, ord, in_run)) = stack.pop() {
            if !in_run {
                self.insert_one(parent, n, !in_frame, pos, ord)?;
            }
            let run = singleton_run(n);
            if let (Some(first), true) = (n.children().get(0), run > 0) {
                self.runs.insert(first.id(), (n.id(), run as u8));
            }
            // Reversed, so that elements are indexed in document order and a duplicate
            // is reported at its second occurrence. A frame's joints are unique per
            // frame only, so their names are not registered.
            let frame = n.attached().is_some();
            // Members of the run without children have nothing more to index.
            stack.extend(
                n.children()
                    .iter()
                    .enumerate()
                    .rev()
                    .filter(|(i, c)| *i >= run || !c.children().is_empty())
                    .map(|(i, c)| (Some(n.id()), c, frame, i, fresh_ord(i), i < run)),
            );
        }
        Ok(())
    }

    /// What the index knows about `id`: its own entry, or the one its run implies.
    pub(crate) fn entry(&self, id: ElementId) -> Option<Cow<'_, Entry>> {
        if let Some(e) = self.elems.get(&id) {
            return Some(Cow::Borrowed(e));
        }
        let (first, &(parent, len)) = self.runs.get_prev(&id)?;
        let i = usize::try_from(id.get() - first.get()).ok().filter(|i| *i < usize::from(len))?;
        let kind = self.entry(parent)?.kind.singleton_children().nth(i)?;
        Some(Cow::Owned(Entry {
            parent: Some(parent),
            kind,
            text: None,
            frame: false,
            pos: i,
            ord: fresh_ord(i),
        }))
    }

    /// Whether `id` is an element of this model.
    pub(crate) fn contains(&self, id: ElementId) -> bool {
        self.entry(id).is_some()
    }

    /// The parent of `id`, if `id` is an element of this model and not its root.
    pub(crate) fn parent(&self, id: ElementId) -> Option<ElementId> {
        self.entry(id)?.parent
    }

    /// The identifier of `id`, if it is an element of this model with one.
    pub(crate) fn name(&self, id: ElementId) -> Option<&SmolStr> {
        // Members of runs have no identifier.
        self.elems.get(&id)?.name()
    }

    /// The number of elements indexed.
    pub(crate) fn len(&self) -> usize {
        self.elems.len() + self.runs.values().map(|(_, n)| usize::from(*n)).sum::<usize>()
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
            let duplicate = || Duplicate { id: n.id(), namespace: ns, name: name.clone() };
            let segment = slashed_segment(name);
            if segment.is_some_and(|s| self.frame_of(s).is_some()) {
                return Err(duplicate());
            }
            // One hash of the name: insert, and put the earlier element back if the
            // name was taken.
            let key = (ns, name.clone());
            if let Some(earlier) = self.names.insert(key.clone(), n.id()) {
                self.names.insert(key, earlier);
                return Err(duplicate());
            }
            if let Some(s) = segment {
                self.slashed.add(s);
            }
        }
        // A frame's entry holds its scope name (the node's own, which attach and
        // scope renames keep equal to the one in `scopes`).
        let (text, frame) = match n.attached() {
            Some(a) => (Some(a.scope.clone()), true),
            None => (name, false),
        };
        self.elems.insert(n.id(), Entry { parent, kind: n.kind(), text, frame, pos, ord });
        Ok(())
    }

    /// Removes `node` and its subtree.
    pub(crate) fn remove_subtree(&mut self, node: &Node) {
        for n in node.descendants() {
            if let Some(first) = n.children().get(0) {
                if self.runs.get(&first.id()).is_some_and(|(p, _)| *p == n.id()) {
                    self.runs.remove(&first.id());
                }
            }
            if let Some(e) = self.elems.remove(&n.id()) {
                if let Some(scope) = e.scope() {
                    self.scopes.remove(scope, n.id());
                } else if let (Some(ns), Some(name)) = (e.kind.namespace(), e.text) {
                    if self.names.get(&(ns, name.clone())) == Some(&n.id()) {
                        self.unslash(&name);
                        self.names.remove(&(ns, name));
                    }
                }
            }
        }
    }

    /// Changes the identifier of `id` (already checked to be free).
    pub(crate) fn rename(&mut self, id: ElementId, new: Option<SmolStr>) {
        let Some(entry) = self.entry(id).map(Cow::into_owned) else { return };
        if entry.frame {
            // A frame has no identifier (its attributes are the frame's own few).
            return;
        }
        let in_frame = entry.parent.is_some_and(|p| self.scope_of(p).is_some());
        if let (Some(ns), false) = (entry.kind.namespace(), in_frame) {
            if let Some(old) = &entry.text {
                self.unslash(old);
                self.names.remove(&(ns, old.clone()));
            }
            if let Some(new) = &new {
                if let Some(s) = slashed_segment(new) {
                    self.slashed.add(s);
                }
                self.names.insert((ns, new.clone()), id);
            }
        }
        self.elems.insert(id, Entry { text: new, ..entry });
    }

    /// Forgets `name` (a registered name going away) in `slashed`. Freeing a part
    /// may free a scope name: the suffix hints start afresh.
    fn unslash(&mut self, name: &str) {
        let Some(s) = slashed_segment(name) else { return };
        if self.slashed.take(s) {
            self.scopes.free_from = OrdMap::new();
        }
    }

    /// Whether a literal name of the model starts with `segment` and a `/`.
    pub(crate) fn has_slashed_segment(&self, segment: &str) -> bool {
        self.slashed.contains_key(segment)
    }

    /// The scope name of the attachment whose frame is `frame`: the frame's entry
    /// holds it (a frame is never a member of a run: it has no consecutive siblings
    /// made with it).
    pub(crate) fn scope_of(&self, frame: ElementId) -> Option<&SmolStr> {
        // A model without attachments has no frames (most models, and every robot of
        // a fleet, whose references the writer asks this about): no lookup.
        if self.scopes.is_empty() {
            return None;
        }
        self.elems.get(&frame)?.scope()
    }

    /// Renames the attachment whose frame is `frame` (to a free name).
    pub(crate) fn rename_scope(&mut self, frame: ElementId, to: SmolStr) {
        let Some(entry) = self.elems.get(&frame).filter(|e| e.frame) else { return };
        let old = entry.text.clone();
        let entry = Entry { text: Some(to.clone()), ..entry.clone() };
        self.elems.insert(frame, entry);
        self.scopes.rename(old.as_ref(), frame, to);
    }

    /// `id` and its ancestors up to the root, nearest first, each given to `each`
    /// with its position hint and slot; `None` if one is not indexed.
    pub(crate) fn ancestry(
        &self,
        id: ElementId,
        mut each: impl FnMut(ElementId, usize, u64),
    ) -> Option<()> {
        // Read in place where the element has an entry of its own (all but members of
        // runs): an entry returned by value is copied through memory at every level.
        let step = |id: ElementId| match self.elems.get(&id) {
            Some(e) => Some((e.parent, e.pos, e.ord)),
            None => self.entry(id).map(|e| (e.parent, e.pos, e.ord)),
        };
        let mut cur = Some(id);
        while let Some(id) = cur {
            let (parent, pos, ord) = step(id)?;
            each(id, pos, ord);
            cur = parent;
        }
        Some(())
    }
}

/// A model's own attachments: (scope name, frame), found by name in O(log n) (by
/// frame: the frame's index entry holds its scope name, [`Index::scope_of`]), listed
/// in attach order. Persistent, like the rest of the index.
///
/// Attach order is frame-id order: a frame gets a fresh id when it is attached
/// (`ElementId::fresh`, one atomic counter), every attach of a model's history comes
/// after the attaches it builds on, and a frame keeps its id for life (renames and
/// edits inside the attachment keep it). So the attach order is that of the frames,
/// sorted, on the rare calls that list the attachments, and an attach updates one
/// persistent map of names (and the small `free_from`), not two or three.
/// (An edit inside an attachment that changes its merged settings resets the outer
/// model's memo itself: `Model::in_scope`.)
///
/// The names themselves are in the frames' index entries: the map is keyed by a hash
/// of the name (SipHash, once per call), its entries two words (a node copied on an
/// attach's path is a plain copy of 16 of them, where names cost a clone each, and a
/// step down compares integers, not strings), and a name found is checked against
/// its frame's entry. Two names of one hash (hardly ever) put the later in
/// `collided`, by name.
#[derive(Clone, Debug, Default)]
pub(crate) struct Scopes {
    /// Hash of the scope name → frame. B-trees, not hash tries: an edit copies a few
    /// 16-entry nodes where a hash trie copies 32-slot ones.
    by_hash: OrdMap<u64, ElementId>,
    /// Scope → frame, for a name whose hash another name has in `by_hash`.
    collided: OrdMap<SmolStr, ElementId>,
    /// Per base name, a suffix below which every `base_n` is taken (a hint for the
    /// suffix rule; cleared whenever a scope name is freed).
    free_from: OrdMap<SmolStr, u64>,
}

/// The hash of a scope name that keys [`Scopes`] (SipHash: names are the user's).
fn name_hash(name: &str) -> u64 {
    use std::hash::Hasher;
    let mut h = std::hash::DefaultHasher::new();
    h.write(name.as_bytes());
    h.finish()
}

impl Scopes {
    pub(crate) fn is_empty(&self) -> bool {
        self.by_hash.is_empty() && self.collided.is_empty()
    }

    /// (scope, frame) in attach order (frame-id order: see the type's docs), the
    /// names from the frames' entries in `elems`. O(a log a) for `a` attachments.
    fn iter<'a>(
        &'a self,
        elems: &'a ElemMap<Entry>,
    ) -> impl DoubleEndedIterator<Item = (&'a SmolStr, ElementId)> + 'a {
        let mut frames: Vec<ElementId> =
            self.by_hash.values().chain(self.collided.values()).copied().collect();
        frames.sort_unstable();
        frames.into_iter().filter_map(|f| Some((elems.get(&f)?.scope()?, f)))
    }

    /// The frame of the attachment named `scope` (`elems` holds the frames' names).
    fn frame_of(&self, scope: &str, hash: u64, elems: &ElemMap<Entry>) -> Option<ElementId> {
        if let Some(&f) = self.by_hash.get(&hash) {
            if elems.get(&f).and_then(Entry::scope).is_some_and(|s| s == scope) {
                return Some(f);
            }
        }
        self.collided.get(scope).copied()
    }

    /// Whether both hold the same attachments (O(1): the maps are shared or not).
    pub(crate) fn same(&self, other: &Scopes) -> bool {
        self.by_hash.ptr_eq(&other.by_hash) && self.collided.ptr_eq(&other.collided)
    }

    /// Adds an attachment under `name` (from [`Index::free_scope_name`]: free, and
    /// chosen for `base`).
    pub(crate) fn push(&mut self, base: &str, name: FreeName, frame: ElementId) {
        if name.suffix > 0 {
            self.free_from.insert(base.into(), name.suffix + 1);
        }
        self.add(name.name, name.hash, frame);
    }

    /// Adds `name` (free) for `frame`: by its hash, or, if another name has that
    /// hash, by name.
    fn add(&mut self, name: SmolStr, hash: u64, frame: ElementId) {
        if let Some(other) = self.by_hash.insert(hash, frame) {
            self.by_hash.insert(hash, other);
            self.collided.insert(name, frame);
        }
    }

    /// Removes the attachment `scope`, if its frame is `frame`.
    fn remove(&mut self, scope: &SmolStr, frame: ElementId) {
        self.remove_hashed(scope, name_hash(scope), frame);
    }

    /// [`Scopes::remove`] of `scope`, whose hash is `hash`.
    fn remove_hashed(&mut self, scope: &SmolStr, hash: u64, frame: ElementId) {
        if self.by_hash.get(&hash) == Some(&frame) {
            self.by_hash.remove(&hash);
        } else if self.collided.get(scope) == Some(&frame) {
            self.collided.remove(scope);
        } else {
            return;
        }
        self.free_from = OrdMap::new();
    }

    /// Renames the attachment `old` whose frame is `frame` (to a free name).
    fn rename(&mut self, old: Option<&SmolStr>, frame: ElementId, to: SmolStr) {
        if let Some(old) = old {
            self.remove(old, frame);
        }
        let hash = name_hash(&to);
        self.add(to, hash, frame);
        self.free_from = OrdMap::new();
    }
}

impl Index {
    /// The frame of the attachment named `scope`.
    pub(crate) fn frame_of(&self, scope: &str) -> Option<ElementId> {
        self.scopes.frame_of(scope, name_hash(scope), &self.elems)
    }

    /// This model's own attachments, (scope, frame) in attach order. O(a log a) for
    /// `a` attachments.
    pub(crate) fn attachments(&self) -> impl DoubleEndedIterator<Item = (&SmolStr, ElementId)> {
        self.scopes.iter(&self.elems)
    }

    /// `base`, or `base_1`, `base_2`, ...: the first scope name not taken by an
    /// attachment or by the part before the `/` of a literal name (the reference's
    /// suffix rule, gaps filled from 1). Amortised O(log n) while names
    /// are only added. Changes nothing: [`Scopes::push`] records the hint.
    pub(crate) fn free_scope_name(&self, base: &str) -> FreeName {
        // Taken by an attachment, or by literal names `name/...` (which the
        // attachment's names would meet).
        let taken = |name: &str, hash: u64| {
            self.scopes.frame_of(name, hash, &self.elems).is_some()
                || self.has_slashed_segment(name)
        };
        // A hint for `base` means `base` was taken when it was noted, and no name was
        // freed since (that clears the hints): taken still.
        let mut n = match self.scopes.free_from.get(base) {
            Some(n) => *n,
            None => {
                let hash = name_hash(base);
                if !taken(base, hash) {
                    return FreeName { name: base.into(), suffix: 0, hash };
                }
                1
            }
        };
        loop {
            let name = suffixed(base, n);
            let hash = name_hash(&name);
            if !taken(&name, hash) {
                return FreeName { name, suffix: n, hash };
            }
            n += 1;
        }
    }
}

/// `base_n`, built in place (no `String` for names of up to 23 bytes, and no
/// formatting machinery: an attach asks for one).
fn suffixed(base: &str, n: u64) -> SmolStr {
    let (mut digits, mut at, mut n) = ([0u8; 20], 20, n);
    loop {
        at -= 1;
        digits[at] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            break;
        }
    }
    let mut name = smol_str::SmolStrBuilder::new();
    name.push_str(base);
    name.push('_');
    digits[at..].iter().for_each(|d| name.push(char::from(*d)));
    name.finish()
}

/// The index of a model being read, built a node at a time as the reader makes the
/// nodes (bottom-up), while they are still in cache: a walk of the finished tree
/// would read every node again, cold. The entries and runs are those the tree's
/// walk from the root would make (runs of singletons as in `insert_subtree_at`);
/// their order does not matter (`ElemMap::from_entries` places them by id).
pub(crate) struct ReadIndex {
    entries: Vec<(ElementId, Entry)>,
    runs: OrdMap<ElementId, (ElementId, u8)>,
}

impl ReadIndex {
    /// For `elements` nodes (the reader's count, so that the list is not grown by
    /// copying).
    pub(crate) fn with_capacity(elements: usize) -> ReadIndex {
        ReadIndex { entries: Vec::with_capacity(elements), runs: OrdMap::new() }
    }

    /// The entries of the children of `n` (not of their children), and the run of
    /// `n`'s singletons; `name` gives the identifier of the child at a position;
    /// `visit` is called with each child whose own children the walk of the tree
    /// would index.
    fn level<'n>(
        &mut self,
        n: &'n Node,
        name: impl Fn(usize, &Node) -> Option<SmolStr>,
        mut visit: impl FnMut(&'n Node),
    ) {
        let run = singleton_run(n);
        if let (Some(first), true) = (n.children().get(0), run > 0) {
            self.runs.insert(first.id(), (n.id(), run as u8));
        }
        for (i, c) in n.children().iter().enumerate() {
            let in_run = i < run;
            if in_run && c.children().is_empty() {
                continue;
            }
            if !in_run {
                let name = name(i, c);
                let entry = Entry {
                    parent: Some(n.id()),
                    kind: c.kind(),
                    text: name,
                    frame: false,
                    pos: i,
                    ord: fresh_ord(i),
                };
                self.entries.push((c.id(), entry));
            }
            visit(c);
        }
    }

    /// Indexes the children of `n`, a node just made from children already indexed;
    /// `names` holds their identifiers (`Node::identifier`), in order: the reader
    /// knows them without reading the children's attributes again, cold.
    pub(crate) fn children(&mut self, n: &Node, names: &[Option<SmolStr>]) {
        self.level(n, |i, _| names.get(i).cloned().flatten(), |_| ());
    }

    /// Indexes every descendant of `n` (a node made whole, whose children were not
    /// indexed: an empty singleton with singletons of its own).
    pub(crate) fn descendants(&mut self, n: &Node) {
        let mut stack = vec![n];
        while let Some(n) = stack.pop() {
            self.level(n, |_, c| c.identifier().map(SmolStr::from), |c| stack.push(c));
        }
    }

    /// The index, with the entry of `root` (whose descendants are indexed) and
    /// `names`, every identifier of the tree (the reader collected them, in document
    /// order, finding duplicates at their second occurrence). A read model has no
    /// attachments, so every name is registered.
    pub(crate) fn finish(
        mut self,
        root: &Node,
        names: HashMap<(Namespace, SmolStr), ElementId>,
        slashed: HashMap<SmolStr, u32>,
    ) -> Index {
        let name = root.identifier().map(SmolStr::from);
        let entry = Entry {
            parent: None,
            kind: root.kind(),
            text: name,
            frame: false,
            pos: 0,
            ord: fresh_ord(0),
        };
        self.entries.push((root.id(), entry));
        Index {
            names,
            elems: ElemMap::from_entries(self.entries),
            runs: self.runs,
            slashed: Slashed::from_counts(slashed),
            ..Index::default()
        }
    }
}

/// How many of `n`'s first children form a run (module docs): all its singleton
/// children, in schema order, of kinds without identifiers (so that no reference
/// can name them, and every reference target has an entry of its own), with
/// consecutive ids; 0 when they do not (a
/// singleton read from a file has the id of where it was read), or when there are
/// fewer than two.
fn singleton_run(n: &Node) -> usize {
    let children = n.children();
    // Singletons come first: most elements (bodies, geoms, ...) have none, and are
    // answered here without looking at the schema.
    let Some(first) =
        children.get(0).filter(|c| c.kind().multiplicity() == Multiplicity::Singleton)
    else {
        return 0;
    };
    let mut count = 0;
    for (i, kind) in n.kind().singleton_children().enumerate() {
        match children.get(i) {
            Some(c)
                if c.kind() == kind
                    && c.id().get() == first.id().get() + i as u64
                    && kind.namespace().is_none() =>
            {
                count += 1;
            }
            _ => return 0,
        }
    }
    if count < 2 || count > usize::from(u8::MAX) { 0 } else { count }
}

/// A free scope name and its suffix (`robot_3`: 3; `robot`: 0).
#[derive(Clone, Debug)]
pub(crate) struct FreeName {
    pub(crate) name: SmolStr,
    suffix: u64,
    /// The name's hash (computed once: it keys [`Scopes`]).
    hash: u64,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn suffixed_names_are_what_format_writes() {
        for (base, n) in [("robot", 0), ("robot", 1), ("r", 10), ("", 907), ("é", u64::MAX)] {
            assert_eq!(suffixed(base, n), format!("{base}_{n}"));
        }
        let long = "a".repeat(40);
        assert_eq!(suffixed(&long, 12), format!("{long}_12"));
    }

    /// Names of one hash: the later by name, each found, listed and removed.
    #[test]
    fn scope_names_of_one_hash() {
        let frames: Vec<ElementId> = (0..3).map(|_| ElementId::fresh()).collect();
        let names = ["a", "b", "c"];
        let mut elems = ElemMap::default();
        for (f, n) in frames.iter().zip(names) {
            let entry = Entry {
                parent: None,
                kind: crate::schema::ElementKind::ROOT,
                text: Some(n.into()),
                frame: true,
                pos: 0,
                ord: 0,
            };
            elems.insert(*f, entry);
        }
        let mut s = Scopes::default();
        for (f, n) in frames.iter().zip(names) {
            s.add(n.into(), 7, *f);
        }
        for (f, n) in frames.iter().zip(names) {
            assert_eq!(s.frame_of(n, 7, &elems), Some(*f));
        }
        assert_eq!(s.frame_of("d", 7, &elems), None);
        let listed: Vec<(&str, ElementId)> = s.iter(&elems).map(|(n, f)| (n.as_str(), f)).collect();
        assert_eq!(listed, names.iter().copied().zip(frames.iter().copied()).collect::<Vec<_>>());
        let before = s.clone();
        // Removing the one keyed by hash leaves the others found.
        s.remove_hashed(&"a".into(), 7, frames[0]);
        assert_eq!(s.frame_of("a", 7, &elems), None);
        assert_eq!(s.frame_of("b", 7, &elems), Some(frames[1]));
        assert_eq!(s.frame_of("c", 7, &elems), Some(frames[2]));
        // Not its frame: nothing removed.
        s.remove_hashed(&"c".into(), 7, frames[1]);
        assert_eq!(s.frame_of("c", 7, &elems), Some(frames[2]));
        s.remove_hashed(&"b".into(), 7, frames[1]);
        s.remove_hashed(&"c".into(), 7, frames[2]);
        assert!(s.is_empty());
        assert!(!before.same(&s) && before.same(&before.clone()));
        assert_eq!(before.frame_of("b", 7, &elems), Some(frames[1]));
    }
}
