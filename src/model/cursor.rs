//! The composed document: one preorder walk over a model with its attachments, in
//! the order the writer writes (the handles, `super::handle`, walk and name by it).
//!
//! The order rules live here once, in [`Walk::expand`]:
//! - the root's sections in schema order; right after the root `<default>` class, the
//!   root class of every attached model (depth first, in attach order), each a
//!   sibling class;
//! - an attachment frame holds its own children (joints, freejoint, inertial), then
//!   the attached model's worldbody children;
//! - every other top-level section (`asset`, `actuator`, ...) holds its own children,
//!   then the same section's children of every attached model (depth first, in
//!   attach order); global settings sections hold only their own (the writer writes
//!   the merged ones);
//! - everything else holds its own children.
//!
//! The writer and [`Model::find_all`] both fold over this walk.
//!
//! The walk is also where names come from (`super::naming` has the rules): each
//! instance gets its scope prefix once, from its parent's, and the walk counts the
//! elements of each namespace of each model as it enters them, which is the position
//! an unnamed element's automatic name holds. [`Insts::name_of_item`] names what the
//! walk enters; [`Insts::name_of_id`] names any element of an instance (a reference's
//! target, `ElementRef::full_name`), counting its model once by the same walk
//! ([`Walk::own`]).

use std::cell::OnceCell;
use std::collections::HashMap;
use std::sync::{Arc, Mutex, Weak};

use crate::id::IdHash;
use crate::schema::{ElementKind, Namespace, Role};

use super::naming::{ElemCtx, InstNames, Named, Written, first_unnamed_joint};
use super::settings::is_settings_section;
use super::tree::{ElementId, Node, NodeData};
use super::{Loc, Model};

/// One model of a composition: the outermost (index 0) or an attachment at any depth.
#[derive(Clone)]
pub(crate) struct Inst<'a> {
    pub(crate) model: &'a Model,
    /// The frames from the outermost model down to this one (empty for index 0).
    pub(crate) frames: Arc<[ElementId]>,
    /// The attachment frame (a node of the parent instance's model), for attachments.
    pub(crate) frame: Option<&'a Node>,
    /// Its prefix and how its root class is written.
    pub(crate) names: InstNames,
    /// The name of its root default class (what an element without a class of its
    /// own is written with).
    root_class: Written<'a>,
    /// Per namespace (`ns as usize`), how many of the model's elements of it the walk
    /// has entered.
    counters: [u32; Namespace::ALL.len()],
    /// Every element's automatic-name position and whether a `<replicate>` of its
    /// model is above it, counted once when a name needs it ([`Insts::name_of_id`]).
    auto: OnceCell<Arc<AutoPositions>>,
}

impl<'a> Inst<'a> {
    fn new(
        model: &'a Model,
        frames: Arc<[ElementId]>,
        frame: Option<&'a Node>,
        names: InstNames,
    ) -> Inst<'a> {
        let root_class = section(model, "default")
            .and_then(|r| {
                names.name_of(model, Named::of_node(r), &ElemCtx::default(), || (0, false))
            })
            .unwrap_or(Written::RootClass);
        let (counters, auto) = ([0; Namespace::ALL.len()], OnceCell::new());
        Inst { model, frames, frame, names, root_class, counters, auto }
    }

    /// The position of the next element of `ns` (counted).
    fn count(&mut self, ns: Namespace) -> u32 {
        // In the instance itself (no list to grow, nothing to follow): the walk counts
        // every element it enters.
        let Some(c) = self.counters.get_mut(ns as usize) else { return 0 };
        *c += 1;
        *c - 1
    }
}

/// The models of a composition met so far, each once: an attached model gets one
/// index for the whole walk.
#[derive(Clone)]
pub(crate) struct Insts<'a> {
    pub(crate) list: Vec<Inst<'a>>,
    by_frame: HashMap<(usize, ElementId), usize>,
    /// `attached_under(0)`, once asked: the root and every top-level section ask
    /// (each lookup of a frame is a path search).
    under_root: Option<Arc<[usize]>>,
}

impl<'a> Insts<'a> {
    fn new(top: &'a Model) -> Insts<'a> {
        let names = InstNames::top(top);
        Insts {
            list: vec![Inst::new(top, Arc::from([]), None, names)],
            by_frame: HashMap::new(),
            under_root: None,
        }
    }

    /// The instance attached at `frame` (a node of instance `parent`).
    fn attached(&mut self, parent: usize, frame: &'a Node) -> Option<usize> {
        let a = frame.attached()?;
        if let Some(&i) = self.by_frame.get(&(parent, frame.id())) {
            return Some(i);
        }
        let mut frames = self.list[parent].frames.to_vec();
        frames.push(frame.id());
        let i = self.list.len();
        let outer = &self.list[parent];
        let in_replicate = in_replicate(outer.model, frame.id());
        let names = outer.names.attached(&a.scope, &a.model, in_replicate);
        self.list.push(Inst::new(&a.model, frames.into(), Some(frame), names));
        self.by_frame.insert((parent, frame.id()), i);
        Some(i)
    }

    /// The name of instance `inst`'s root default class (what an element without a
    /// class of its own is written with).
    pub(crate) fn root_class_name(&self, inst: usize) -> Written<'a> {
        self.list[inst].root_class
    }

    /// The name `item` (entered by the walk) is written with, `None` for elements
    /// without a namespace.
    #[inline(always)]
    pub(crate) fn name_of_item(&self, item: &Item<'a>) -> Option<Written<'a>> {
        let inst = &self.list[item.inst];
        // A frame's joint: its frame (the walk keeps items small: this is rare).
        let frame = if item.in_frame {
            let m = inst.model;
            m.index.parent(item.node.id()).and_then(|p| m.node_by_id(p))
        } else {
            None
        };
        let ctx = ElemCtx { frame, first_unnamed: item.first_unnamed, enclosing: inst.frame };
        inst.names
            .name_of(inst.model, Named::of_node(item.node), &ctx, || (item.auto, item.replicated))
    }

    /// The name element `id` of instance `inst` is written with, wherever it lies
    /// (ahead of the walk too); `None` for elements without a namespace or not in
    /// the model. An unnamed element's model is counted once (O(n)), the first time
    /// one is asked for.
    pub(crate) fn name_of_id(&self, inst: usize, id: ElementId) -> Option<Written<'a>> {
        // Members of runs have no namespace, so every element with a name has an
        // entry of its own.
        let entry = self.list[inst].model.index.elems.get(&id)?;
        self.name_of_entry(inst, id, entry)
    }

    /// [`Insts::name_of_id`] of an element whose index entry is `entry`.
    pub(crate) fn name_of_entry(
        &self,
        inst: usize,
        id: ElementId,
        entry: &'a super::Entry,
    ) -> Option<Written<'a>> {
        let i = &self.list[inst];
        let m = i.model;
        name_in(&i.names, m, i.frame, id, entry, || {
            let counted = i.auto.get_or_init(|| m.auto_positions());
            counted.get(&id).copied().unwrap_or((0, false))
        })
    }

    /// The instance of the model attached along `frames` from instance 0. Only that
    /// instance is made: the models between are passed through, each appending its
    /// scope to one prefix, so this is linear in the levels (an instance per level,
    /// each copying its parent's frame list and prefix, was quadratic).
    #[cfg(test)]
    pub(crate) fn along(&mut self, frames: &[ElementId]) -> Option<usize> {
        let Some((last, outer)) = frames.split_last() else { return Some(0) };
        if outer.is_empty() {
            let node = self.list[0].model.node_by_id(*last)?;
            return self.attached(0, node);
        }
        let mut model = self.list[0].model;
        let mut names = self.list[0].names.clone();
        for f in outer {
            let a = model.node_by_id(*f)?.attached()?;
            names.descend(&a.scope, &a.model, in_replicate(model, *f));
            model = &a.model;
        }
        let frame = model.node_by_id(*last)?;
        let a = frame.attached()?;
        names.descend(&a.scope, &a.model, in_replicate(model, *last));
        self.list.push(Inst::new(&a.model, Arc::from(frames), Some(frame), names));
        Some(self.list.len() - 1)
    }

    /// Every instance attached under `inst`, depth first in attach order.
    fn attached_under(&mut self, inst: usize) -> Vec<usize> {
        let mut out = Vec::new();
        let mut stack = vec![inst];
        while let Some(i) = stack.pop() {
            if i != inst {
                out.push(i);
            }
            let m = self.list[i].model;
            let mut children: Vec<usize> = m
                .index
                .attachments()
                .filter_map(|(_, f)| self.attached(i, m.node_by_id(f)?))
                .collect();
            children.reverse();
            stack.extend(children);
        }
        out
    }
}

/// An element of the walk.
#[derive(Clone, Copy)]
pub(crate) struct Item<'a> {
    /// The instance (model) it belongs to.
    pub(crate) inst: usize,
    pub(crate) node: &'a Node,
    /// 0 for the root, 1 for sections (and attached root default classes), ...
    pub(crate) depth: usize,
    /// Whether it is an own child of an attachment frame (a frame's joint or
    /// inertial).
    pub(crate) in_frame: bool,
    /// For a frame's joint: whether it is the first unnamed one of its frame.
    pub(crate) first_unnamed: bool,
    /// Whether a `<replicate>` of its own model is above it.
    pub(crate) replicated: bool,
    /// Its position among its model's elements of its namespace, in document order
    /// (set when the walk enters it; 0 for elements without a namespace).
    pub(crate) auto: u32,
}

impl<'a> Item<'a> {
    /// An item with no frame, counted later.
    pub(crate) fn plain(inst: usize, node: &'a Node, depth: usize, replicated: bool) -> Item<'a> {
        Item { inst, node, depth, in_frame: false, first_unnamed: false, replicated, auto: 0 }
    }
}

/// A step of the preorder walk.
#[derive(Clone, Copy)]
pub(crate) enum Step<'a> {
    Enter(Item<'a>),
    Leave(Item<'a>),
}

/// The preorder walk of a composed document (or of a part of it).
pub(crate) struct Walk<'a> {
    pub(crate) insts: Insts<'a>,
    stack: Vec<Step<'a>>,
    /// The element just entered, whose subtree `skip_subtree` would skip.
    entered: Option<usize>,
    /// Elements below the sections for which this holds are not entered at all (see
    /// [`Walk::pruned`]).
    prune: Option<fn(&Node) -> bool>,
    /// Whether attached models are left out ([`Walk::own`]).
    own: bool,
}

impl<'a> Walk<'a> {
    /// The walk of the whole composed `model`, from its root.
    pub(crate) fn new(model: &'a Model) -> Walk<'a> {
        Walk::plain(model, &model.root, 0)
    }

    /// The walk of `model`'s own elements: the composed walk without what its
    /// attachments hold (their frames are entered). Its elements are entered in the
    /// order the composed walk enters them, wherever `model` is attached, so it
    /// counts them as that walk does (settings sections, which only the outermost
    /// model's walk enters, hold no element with a namespace).
    pub(crate) fn own(model: &'a Model) -> Walk<'a> {
        Walk { own: true, ..Walk::new(model) }
    }

    /// A walk of a plain subtree with no attachments in it (such as a merged
    /// settings section), written as part of instance 0 at `depth`.
    pub(crate) fn plain(model: &'a Model, node: &'a Node, depth: usize) -> Walk<'a> {
        Walk {
            insts: Insts::new(model),
            stack: vec![Step::Enter(Item::plain(0, node, depth, false))],
            entered: None,
            prune: None,
            own: false,
        }
    }

    /// The same walk without the plain children (below depth 1, of neither a frame
    /// nor a top-level section) for which `prune` holds: they are neither entered nor
    /// left. The writer prunes the empty singletons (every default class has 21),
    /// which it would skip anyway.
    pub(crate) fn pruned(mut self, prune: fn(&Node) -> bool) -> Walk<'a> {
        self.prune = Some(prune);
        self
    }

    /// How many steps are pending on the walk's stack.
    pub(crate) fn pending(&self) -> usize {
        self.stack.len()
    }

    /// Skips the children and the `Leave` of the element entered last.
    pub(crate) fn skip_subtree(&mut self) {
        if let Some(len) = self.entered.take() {
            self.stack.truncate(len);
        }
    }

    /// The composed children of `item`, in document order (the rules of the module
    /// documentation).
    pub(crate) fn expand(&mut self, item: Item<'a>) -> Vec<Item<'a>> {
        let Item { inst, node, depth, replicated, .. } = item;
        let below = replicated || node.kind().is(Role::Replicate);
        let plain = |n: &'a Node, inst: usize| Item::plain(inst, n, depth + 1, false);
        let mut out: Vec<Item<'a>> = Vec::with_capacity(node.children().len());
        if node.attached().is_some() {
            let first_unnamed = first_unnamed_joint(node);
            out.extend(node.children().iter().map(|c| Item {
                in_frame: true,
                first_unnamed: first_unnamed == Some(c.id()),
                ..Item::plain(inst, c, depth + 1, below)
            }));
            if self.own {
                return out;
            }
            if let Some(child) = self.insts.attached(inst, node) {
                if let Some(wb) = section(self.insts.list[child].model, "worldbody") {
                    out.extend(wb.children().iter().map(|c| plain(c, child)));
                }
            }
            return out;
        }
        out.extend(node.children().iter().map(|c| Item::plain(inst, c, depth + 1, below)));
        if inst != 0
            || depth > 1
            || self.own
            || node.kind().spec().parent.is_some_and(|p| p != ElementKind::ROOT)
        {
            return out;
        }
        if depth == 0 {
            // The root: after the root default class, every attached root class.
            let Some(p) = out.iter().position(|c| c.node.kind().is(Role::DefaultClass)) else {
                return out;
            };
            let kind = out[p].node.kind();
            let siblings: Vec<Item<'a>> = self
                .attached_under_root()
                .iter()
                .filter_map(|&j| {
                    let sec = self.insts.list[j].model.root.child_of_kind(kind)?;
                    Some(Item::plain(j, sec, 1, false))
                })
                .collect();
            out.splice(p + 1..p + 1, siblings);
            return out;
        }
        let kind = node.kind();
        if matches!(kind.role(), Some(Role::Worldbody | Role::DefaultClass))
            || is_settings_section(kind)
        {
            return out;
        }
        for &j in self.attached_under_root().iter() {
            if let Some(sec) = self.insts.list[j].model.root.child_of_kind(kind) {
                out.extend(sec.children().iter().map(|c| plain(c, j)));
            }
        }
        out
    }

    /// Every instance attached under the outermost model, depth first in attach order.
    fn attached_under_root(&mut self) -> Arc<[usize]> {
        if let Some(u) = &self.insts.under_root {
            return u.clone();
        }
        let u: Arc<[usize]> = self.insts.attached_under(0).into();
        self.insts.under_root = Some(u.clone());
        u
    }
}

impl<'a> Iterator for Walk<'a> {
    type Item = Step<'a>;

    #[inline(always)]
    fn next(&mut self) -> Option<Step<'a>> {
        self.entered = None;
        let step = self.stack.pop()?;
        let Step::Enter(item) = step else { return Some(step) };
        // Counted as it is entered: its model's elements are entered in document
        // order. (The item is made anew, not patched where it lies: a field written
        // and the whole item read back at once stalls the load.)
        let auto = match item.node.kind().namespace() {
            Some(ns) => self.insts.list[item.inst].count(ns),
            None => 0,
        };
        let item = Item { auto, ..item };
        self.entered = Some(self.stack.len());
        self.stack.push(Step::Leave(item));
        let Item { inst, node, depth, .. } = item;
        let own_only = node.attached().is_none()
            && (inst != 0
                || depth > 1
                || node.kind().spec().parent.is_some_and(|p| p != ElementKind::ROOT));
        if own_only {
            // Most elements: their own children only (what `expand` gives them),
            // pushed without a list in between (and most have none).
            let children = node.children();
            if !children.is_empty() {
                let prune = self.prune.filter(|_| depth >= 1);
                let below = item.replicated || node.kind().is(Role::Replicate);
                self.stack.reserve(children.len());
                for c in children.iter().rev() {
                    if prune.is_some_and(|p| p(c)) {
                        continue;
                    }
                    self.stack.push(Step::Enter(Item::plain(inst, c, depth + 1, below)));
                }
            }
        } else {
            let children = self.expand(item);
            self.stack.extend(children.into_iter().rev().map(Step::Enter));
        }
        Some(Step::Enter(item))
    }
}

pub(crate) fn section<'m>(model: &'m Model, tag: &str) -> Option<&'m Node> {
    model.root.child_of_kind(ElementKind::ROOT.child(tag)?)
}

/// Whether the element `id` of `model` lies inside a `<replicate>`.
pub(crate) fn in_replicate(model: &Model, id: ElementId) -> bool {
    let mut cur = model.index.parent(id);
    while let Some(p) = cur {
        let Some(e) = model.index.entry(p) else { return false };
        if e.kind.is(Role::Replicate) {
            return true;
        }
        cur = e.parent;
    }
    false
}

/// The name element `id` (index entry `entry`) of `model` is written with, in an
/// instance named by `names` attached at `enclosing` (`None` for the outermost);
/// `auto` gives its automatic-name position when the name needs it.
pub(crate) fn name_in<'a>(
    names: &InstNames,
    m: &'a Model,
    enclosing: Option<&'a Node>,
    id: ElementId,
    entry: &'a super::Entry,
    auto: impl FnOnce() -> (u32, bool),
) -> Option<Written<'a>> {
    let frame =
        entry.parent.filter(|p| m.index.scope_of(*p).is_some()).and_then(|p| m.node_by_id(p));
    let ctx = ElemCtx {
        frame,
        first_unnamed: frame.is_some_and(|f| first_unnamed_joint(f) == Some(id)),
        enclosing,
    };
    names.name_of(m, Named::of_entry(entry), &ctx, auto)
}

/// Every element of a model with a namespace: its automatic-name position and
/// whether a `<replicate>` of the model is above it.
pub(crate) type AutoPositions = HashMap<ElementId, (u32, bool), IdHash>;

/// A model's [`AutoPositions`], kept for the version they were counted for (by its
/// root node: every edit makes a new root, [`Node::is`]). The versions made from one
/// another share one cache, which keeps the last count asked for, so naming unnamed
/// elements through handles made one by one ([`Model::full_name`], a binding's
/// handles) counts a model once, not once per name.
pub(crate) type AutoCache = Mutex<Option<(Weak<NodeData>, Arc<AutoPositions>)>>;

impl Model {
    /// [`AutoPositions`] of this version: counted ([`auto_positions`], O(n)) unless
    /// the cache holds this version's.
    pub(crate) fn auto_positions(&self) -> Arc<AutoPositions> {
        let cached = |c: &Option<(Weak<NodeData>, Arc<AutoPositions>)>| {
            c.as_ref().filter(|(root, _)| self.root.is(root)).map(|(_, a)| a.clone())
        };
        let lock = || self.side.auto.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        if let Some(a) = cached(&lock()) {
            return a;
        }
        // Counted without the lock held: another thread may count the same version.
        let counted = Arc::new(auto_positions(self));
        *lock() = Some((self.root.downgrade(), counted.clone()));
        counted
    }
}

/// Every element of `model` with a namespace: its automatic-name position and
/// whether a `<replicate>` of the model is above it, as the composed walk counts
/// them ([`Walk::own`]).
fn auto_positions(model: &Model) -> AutoPositions {
    let mut out = HashMap::with_hasher(IdHash);
    for step in Walk::own(model) {
        if let Step::Enter(item) = step {
            if item.inst == 0 && item.node.kind().namespace().is_some() {
                out.insert(item.node.id(), (item.auto, item.replicated));
            }
        }
    }
    out
}

impl Model {
    /// Every element of `namespace`, in the order of [`Model::walk`]: attachment
    /// frames count as bodies, their joints as joints.
    ///
    /// Time: as a whole [`Model::walk`]: O(N + a · depth · log n).
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, Namespace, element};
    /// let mut robot = Model::new("robot");
    /// robot.add_mut(&robot.worldbody(), element!("body", name = "torso"))?;
    /// let mut arena = Model::new("arena");
    /// arena.add_mut(&arena.worldbody(), element!("body", name = "table"))?;
    /// arena.attach_mut(&arena.worldbody(), &robot)?;
    /// let bodies: Vec<String> = arena
    ///     .find_all(Namespace::Body)
    ///     .iter()
    ///     .filter_map(|loc| arena.get(loc).ok()?.full_name())
    ///     .collect();
    /// assert_eq!(bodies, ["table", "robot/", "robot/torso"]); // the frame is a body
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn find_all(&self, namespace: Namespace) -> Vec<Loc> {
        let mut out = Vec::new();
        let name = self.name();
        let mut walk = Walk::new(self);
        while let Some(step) = walk.next() {
            if let Step::Enter(item) = step {
                if item.node.kind().namespace() == Some(namespace)
                    && namespace != Namespace::AttachmentFrame
                {
                    out.push(Loc::scoped(
                        walk.insts.list[item.inst].frames.clone(),
                        item.node.id(),
                        name,
                    ));
                }
            }
        }
        out
    }
}
