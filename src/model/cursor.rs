//! The composed document: one cursor ([`ElementRef`]) and one preorder walk
//! ([`Model::walk`]) over a model with its attachments, in the order the writer writes.
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
//! target, [`ElementRef::full_name`]), counting its model once by the same walk
//! ([`Walk::own`]).

use std::cell::OnceCell;
use std::collections::HashMap;
use std::fmt;
use std::sync::Arc;

use crate::error::{EditError, ErrorKind};
use crate::id::IdHash;
use crate::schema::{ElementKind, Namespace, Role};
use crate::value::{Reference, Value};

use super::layout::{self, JointType};
use super::naming::{ElemCtx, InstNames, Named, Written, first_unnamed_joint};
use super::settings::is_settings_section;
use super::tree::{ElementId, Node};
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
    counters: Vec<u32>,
    /// Every element's automatic-name position and whether a `<replicate>` of its
    /// model is above it, counted once when a name needs it ([`Insts::name_of_id`]).
    auto: OnceCell<HashMap<ElementId, (u32, bool), IdHash>>,
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
        let (counters, auto) = (Vec::new(), OnceCell::new());
        Inst { model, frames, frame, names, root_class, counters, auto }
    }

    /// The position of the next element of `ns` (counted).
    fn count(&mut self, ns: Namespace) -> u32 {
        let k = ns as usize;
        if self.counters.len() <= k {
            self.counters.resize(k + 1, 0);
        }
        self.counters[k] += 1;
        self.counters[k] - 1
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
    #[inline]
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
        let frame =
            entry.parent.filter(|p| m.index.scope_of(*p).is_some()).and_then(|p| m.node_by_id(p));
        let ctx = ElemCtx {
            frame,
            first_unnamed: frame.is_some_and(|f| first_unnamed_joint(f) == Some(id)),
            enclosing: i.frame,
        };
        i.names.name_of(m, Named::of_entry(entry), &ctx, || {
            let counted = i.auto.get_or_init(|| auto_positions(m));
            counted.get(&id).copied().unwrap_or((0, false))
        })
    }

    /// The instance of the model attached along `frames` from instance 0. Only that
    /// instance is made: the models between are passed through, each appending its
    /// scope to one prefix, so this is linear in the levels (an instance per level,
    /// each copying its parent's frame list and prefix, was quadratic).
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
    fn plain(inst: usize, node: &'a Node, depth: usize, replicated: bool) -> Item<'a> {
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

    fn next(&mut self) -> Option<Step<'a>> {
        self.entered = None;
        let mut step = self.stack.pop()?;
        if let Step::Enter(item) = &mut step {
            // Counted as it is entered: its model's elements are entered in document
            // order.
            if let Some(ns) = item.node.kind().namespace() {
                item.auto = self.insts.list[item.inst].count(ns);
            }
            let item = *item;
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
        }
        Some(step)
    }
}

fn section<'m>(model: &'m Model, tag: &str) -> Option<&'m Node> {
    model.root.child_of_kind(ElementKind::ROOT.child(tag)?)
}

/// Whether the element `id` of `model` lies inside a `<replicate>`.
fn in_replicate(model: &Model, id: ElementId) -> bool {
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

/// Every element of `model` with a namespace: its automatic-name position and
/// whether a `<replicate>` of the model is above it, as the composed walk counts
/// them ([`Walk::own`]).
fn auto_positions(model: &Model) -> HashMap<ElementId, (u32, bool), IdHash> {
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

/// A step of [`Model::walk`]: entering an element (before its children) or leaving it
/// (after them).
#[derive(Clone, Debug)]
pub enum Event<'a> {
    /// Before the element's children.
    Enter(ElementRef<'a>),
    /// After the element's children.
    Leave(ElementRef<'a>),
}

/// The preorder walk of a composed model, from [`Model::walk`].
pub struct Preorder<'a> {
    walk: Walk<'a>,
}

impl<'a> Preorder<'a> {
    /// Skips the children of the element entered last, and its `Leave`.
    ///
    /// Time: O(1).
    pub fn skip_subtree(&mut self) {
        self.walk.skip_subtree();
    }
}

impl fmt::Debug for Preorder<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Preorder").field("pending", &self.walk.stack.len()).finish()
    }
}

impl<'a> Iterator for Preorder<'a> {
    type Item = Event<'a>;

    fn next(&mut self) -> Option<Event<'a>> {
        let step = self.walk.next()?;
        let (Step::Enter(item) | Step::Leave(item)) = step;
        let inst = &self.walk.insts.list[item.inst];
        let view =
            ElementRef::new(self.walk.insts.list[0].model, inst.model, &inst.frames, item.node);
        Some(match step {
            Step::Enter(_) => Event::Enter(view),
            Step::Leave(_) => Event::Leave(view),
        })
    }
}

impl Model {
    /// The preorder walk of the composed model: the root, its sections, and every
    /// element, attached models' included, in the order they are written (see
    /// [`Model::to_xml_string`]).
    ///
    /// Time: O(1) to start and amortised per event (entering an element lists its
    /// children): O(N) for the whole walk, plus O(a · depth · log n) at the root
    /// and at each top-level section, which gather the attached models' content.
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Event, Model, element};
    /// let mut m = Model::new("m");
    /// m.add_mut(&m.worldbody(), element!("body", name = "a"))?;
    /// let tags: Vec<&str> = m.walk().filter_map(|e| match e {
    ///     Event::Enter(el) => Some(el.tag()),
    ///     Event::Leave(_) => None,
    /// }).collect();
    /// assert_eq!(tags.first(), Some(&"mujoco"));
    /// let wb = tags.iter().position(|t| *t == "worldbody").unwrap();
    /// assert_eq!(tags[wb + 1], "body");
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn walk(&self) -> Preorder<'_> {
        Preorder { walk: Walk::new(self) }
    }

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

    /// The view of the element at `loc`.
    ///
    /// Time: O(levels · depth · log n) (locating the element).
    ///
    /// # Errors
    /// [`ErrorKind::StaleLocator`] if `loc` names no element of this model (removed,
    /// or from another model).
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, element};
    /// let mut m = Model::new("m");
    /// let g = m.add_mut(&m.worldbody(), element!("geom", name = "g", type = "box", size = [0.1, 0.1, 0.1]))?;
    /// let e = m.get(&g)?;
    /// assert_eq!((e.tag(), e.identifier()), ("geom", Some("g")));
    /// assert_eq!(e.string("type"), Some("box"));
    /// assert_eq!(e.floats("size"), Some(&[0.1, 0.1, 0.1][..]));
    /// let without = m.remove(&g)?;
    /// assert!(without.get(&g).is_err());
    /// assert!(without.element(&g).is_none());
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn get(&self, loc: &Loc) -> Result<ElementRef<'_>, EditError> {
        self.element(loc).ok_or_else(|| self.stale(loc))
    }

    /// The view of the element at `loc`, if it exists in this version
    /// ([`Model::get`] without the error).
    ///
    /// Time: O(levels · depth · log n) (locating the element).
    pub fn element(&self, loc: &Loc) -> Option<ElementRef<'_>> {
        let m = self.scoped_model(loc.scope())?;
        let node = m.node_by_id(loc.id())?;
        let frames: Arc<[ElementId]> = Arc::from(loc.scope());
        Some(ElementRef::new(self, m, &frames, node))
    }
}

/// A read-only view of one element of a composed model: it knows its model and the
/// attachments it lies in, so it can go up, down and name itself as MuJoCo will.
#[derive(Clone)]
pub struct ElementRef<'a> {
    /// The model the view was taken from (the outermost).
    top: &'a Model,
    /// The model holding the element.
    model: &'a Model,
    frames: Arc<[ElementId]>,
    node: &'a Node,
}

impl<'a> ElementRef<'a> {
    fn new(
        top: &'a Model,
        model: &'a Model,
        frames: &Arc<[ElementId]>,
        node: &'a Node,
    ) -> ElementRef<'a> {
        ElementRef { top, model, frames: frames.clone(), node }
    }

    /// The element's locator in the model the view was taken from (scoped when the
    /// element lies inside an attachment).
    ///
    /// Time: O(1).
    pub fn loc(&self) -> Loc {
        Loc::scoped(self.frames.clone(), self.node.id(), self.top.name())
    }

    /// The XML tag (`body` for an attachment frame).
    ///
    /// Time: O(1).
    pub fn tag(&self) -> &'static str {
        self.node.kind().tag()
    }

    /// The schema kind.
    ///
    /// Time: O(1).
    pub fn kind(&self) -> ElementKind {
        self.node.kind()
    }

    /// Whether this is an attachment frame.
    ///
    /// Time: O(1).
    pub fn is_frame(&self) -> bool {
        self.node.attached().is_some()
    }

    /// The joint's type as MuJoCo compiles it, for a `<joint>` (its own `type`, else
    /// its classes', else a hinge) or a `<freejoint>` (free); `None` for any other
    /// element. The layout ([`Model::layout`]) gives each joint the same type.
    ///
    /// ```
    /// use mjcf::{JointType, Model};
    /// let m = Model::from_xml_str(r#"<mujoco><default><joint type="slide"/></default>
    ///   <worldbody><body><joint name="j"/><geom size="1"/></body></worldbody></mujoco>"#)?;
    /// let j = m.find(mjcf::Namespace::Joint, "j").unwrap();
    /// assert_eq!(m.element(&j).unwrap().joint_type(), Some(JointType::Slide));
    /// assert_eq!(m.element(&m.worldbody()).unwrap().joint_type(), None);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    ///
    /// Time: O(depth · log n) (its class in force, then the classes above it).
    pub fn joint_type(&self) -> Option<JointType> {
        matches!(self.node.kind().role(), Some(Role::Joint | Role::Freejoint)).then(|| {
            let class = layout::class_in_force(self.model, self.node);
            layout::joint_type(self.model, self.node, class)
        })
    }

    /// The element's own identifier (no scope prefix), if set.
    ///
    /// Time: O(1).
    pub fn identifier(&self) -> Option<&'a str> {
        self.node.identifier()
    }

    /// The scope path of the model holding the element (`""`, `robot`,
    /// `arena/robot_1`).
    ///
    /// Time: O(levels · depth · log n).
    pub fn scope(&self) -> String {
        self.top.scope_path(&self.loc()).unwrap_or_default()
    }

    /// The name MuJoCo will give the element in the written model, exactly as the
    /// writer writes it (both follow one set of rules: README "Names"): the
    /// identifier with its scope prefix (`robot_1/torso`), an attachment frame's scope
    /// (`robot_1/`), a frame joint's (`robot_1/root/`), or the automatic name of an
    /// unnamed element (`//unnamed_geom_0`, `robot//unnamed_geom_2`, `//unnamed_geom_1_`
    /// inside a `<replicate>`); `None` for elements without a namespace.
    ///
    /// Time: O(levels · depth · log n) for named elements and frames; O(n) more for
    /// unnamed ones (n of the element's model), whose number is their position.
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, Namespace, element};
    /// let mut robot = Model::new("robot");
    /// let torso = robot.add_mut(&robot.worldbody(), element!("body", name = "torso"))?;
    /// robot.add_mut(&torso, element!("geom", size = [0.1]))?;
    /// let mut arena = Model::new("arena");
    /// let a = arena.attach_mut(&arena.worldbody(), &robot)?;
    /// let torso = arena.find(Namespace::Body, "robot/torso").unwrap();
    /// assert_eq!(arena.get(&torso)?.full_name().as_deref(), Some("robot/torso"));
    /// assert_eq!(arena.get(a.frame())?.full_name().as_deref(), Some("robot/"));
    /// let geom = &arena.find_all(Namespace::Geom)[0];
    /// assert_eq!(arena.get(geom)?.full_name().as_deref(), Some("robot//unnamed_geom_0"));
    /// assert_eq!(arena.get(&arena.worldbody())?.full_name(), None); // no namespace
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn full_name(&self) -> Option<String> {
        let mut walk = Walk::new(self.top);
        let inst = walk.insts.along(&self.frames)?;
        let name = walk.insts.name_of_id(inst, self.node.id())?;
        Some(name.to_string_in(&walk.insts.list[inst].names.prefix))
    }

    /// The value of attribute `name`, if set.
    ///
    /// Time: O(1) (binary searches over the element's attributes).
    pub fn attr(&self, name: &str) -> Option<&'a Value> {
        self.node.attr(self.node.kind().attr_index(name)?)
    }

    /// The set attributes, in schema order.
    ///
    /// Time: O(1) per attribute.
    pub fn attrs(&self) -> impl Iterator<Item = (&'static str, &'a Value)> + 'a {
        let kind = self.node.kind();
        self.node.attrs().iter().map(move |(i, v)| (kind.attr(*i as usize).name, v))
    }

    /// A float attribute, if set.
    ///
    /// Time: O(1), as [`ElementRef::attr`].
    pub fn float(&self, name: &str) -> Option<f64> {
        self.attr(name)?.as_float()
    }

    /// A float array attribute (`pos`, `size`, `rgba`), if set.
    ///
    /// Time: O(1), as [`ElementRef::attr`].
    pub fn floats(&self, name: &str) -> Option<&'a [f64]> {
        self.attr(name)?.as_floats()
    }

    /// An integer attribute, if set.
    ///
    /// Time: O(1), as [`ElementRef::attr`].
    pub fn int(&self, name: &str) -> Option<i64> {
        self.attr(name)?.as_int()
    }

    /// An integer array attribute, if set.
    ///
    /// Time: O(1), as [`ElementRef::attr`].
    pub fn ints(&self, name: &str) -> Option<&'a [i64]> {
        self.attr(name)?.as_ints()
    }

    /// A text attribute (string, keyword, name, folder), or the name a reference
    /// gives (for a resolved reference, its target's own identifier), if set.
    ///
    /// Time: O(1); O(log n) for a resolved reference.
    pub fn string(&self, name: &str) -> Option<&'a str> {
        match self.attr(name)? {
            Value::Reference(Reference::Element(id)) => {
                self.model.index.name(*id).map(smol_str::SmolStr::as_str)
            }
            v => v.as_str(),
        }
    }

    /// The composed parent: for a top-level body of an attached model, its
    /// attachment frame; for an element directly in a section of an attached model,
    /// that section of the outermost model; `None` for the root.
    ///
    /// Time: O(levels · depth · log n).
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, Namespace, element};
    /// let mut robot = Model::new("robot");
    /// robot.add_mut(&robot.worldbody(), element!("body", name = "torso"))?;
    /// let mut arena = Model::new("arena");
    /// arena.attach_mut(&arena.worldbody(), &robot)?;
    /// let torso = arena.find(Namespace::Body, "robot/torso").unwrap();
    /// let frame = arena.get(&torso)?.parent().unwrap(); // not the robot's worldbody
    /// assert!(frame.is_frame());
    /// assert_eq!(frame.parent().map(|p| p.tag()), Some("worldbody"));
    /// assert!(arena.get(&arena.root())?.parent().is_none());
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn parent(&self) -> Option<ElementRef<'a>> {
        let parent = self.model.index.parent(self.node.id())?;
        let pnode = self.model.node_by_id(parent)?;
        let is_section = pnode.kind().spec().parent == Some(ElementKind::ROOT);
        match self.frames.split_last() {
            Some((frame, outer)) if pnode.kind().is(Role::Worldbody) && is_section => {
                let outer_model = self.top.scoped_model(outer)?;
                let fnode = outer_model.node_by_id(*frame)?;
                Some(ElementRef::new(self.top, outer_model, &Arc::from(outer), fnode))
            }
            Some(_) if is_section => {
                let sec = self.top.root.child_of_kind(pnode.kind())?;
                Some(ElementRef::new(self.top, self.top, &Arc::from([]), sec))
            }
            Some(_) if pnode.kind() == ElementKind::ROOT => {
                Some(ElementRef::new(self.top, self.top, &Arc::from([]), &self.top.root))
            }
            _ => Some(ElementRef::new(self.top, self.model, &self.frames, pnode)),
        }
    }

    /// The composed children, in document order: an attachment frame's own
    /// children then the attached model's bodies; a top-level section's own
    /// elements then those of every attached model.
    ///
    /// Time: O(width + levels · depth · log n), plus O(a · depth · log n) for the
    /// root or a top-level section; the list is made when this is called.
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, element};
    /// let mut robot = Model::new("robot");
    /// robot.add_mut(&robot.worldbody(), element!("body", name = "torso"))?;
    /// let mut arena = Model::new("arena");
    /// arena.add_mut(&arena.worldbody(), element!("geom", name = "floor", type = "plane", size = [1.0, 1.0, 0.1]))?;
    /// arena.attach_mut(&arena.worldbody(), &robot)?;
    /// let wb = arena.get(&arena.worldbody())?;
    /// let names: Vec<String> = wb.children().filter_map(|c| c.full_name()).collect();
    /// assert_eq!(names, ["floor", "robot/"]);
    /// let frame = wb.children().last().unwrap(); // holds the attached model's bodies
    /// let inside: Vec<String> = frame.children().filter_map(|c| c.full_name()).collect();
    /// assert_eq!(inside, ["robot/torso"]);
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn children(&self) -> impl Iterator<Item = ElementRef<'a>> + 'a {
        let mut walk = Walk::new(self.top);
        let top = self.top;
        let inst = walk.insts.along(&self.frames).unwrap_or(0);
        let depth = if self.node.kind() == ElementKind::ROOT && inst == 0 {
            0
        } else if self.node.kind().spec().parent == Some(ElementKind::ROOT) && inst == 0 {
            1
        } else {
            // Deeper than any rule of a top-level section or the root applies.
            2
        };
        let items = walk.expand(Item::plain(inst, self.node, depth, false));
        let insts = walk.insts;
        items
            .into_iter()
            .map(move |it| {
                let i = &insts.list[it.inst];
                ElementRef::new(top, i.model, &i.frames, it.node)
            })
            .collect::<Vec<_>>()
            .into_iter()
    }

    /// Whether two views show the same shared node; after an edit, every element
    /// the edit did not touch is still the same node.
    ///
    /// Time: O(1).
    pub fn ptr_eq(&self, other: &ElementRef<'_>) -> bool {
        self.node.ptr_eq(other.node)
    }
}

impl fmt::Debug for ElementRef<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(self.node, f)
    }
}

impl Model {
    /// The value of attribute `name` of the element at `loc`.
    fn value_at<'s>(
        &'s self,
        loc: &Loc,
        name: &str,
    ) -> Result<(&'static str, &'s Value), EditError> {
        let e = self.get(loc)?;
        let path = || self.scope_path(loc).unwrap_or_default();
        let kind = e.kind();
        let index = kind
            .attr_index(name)
            .ok_or_else(|| EditError::new(ErrorKind::unknown_attribute(kind, name), path()))?;
        let spec = kind.attr(index);
        let v = e.node.attr(index).ok_or_else(|| {
            EditError::new(ErrorKind::Unset { tag: kind.tag(), attribute: spec.name }, path())
        })?;
        Ok((spec.name, v))
    }

    fn typed<'s, T>(
        &'s self,
        loc: &Loc,
        name: &str,
        f: impl FnOnce(&'s Value) -> Option<T>,
    ) -> Result<T, EditError> {
        let (attribute, v) = self.value_at(loc, name)?;
        let tag = self.get(loc)?.tag();
        f(v).ok_or_else(|| {
            EditError::new(
                ErrorKind::WrongType { tag, attribute },
                self.scope_path(loc).unwrap_or_default(),
            )
        })
    }

    /// The float attribute `name` of the element at `loc`.
    ///
    /// Time: O(levels · depth · log n) (locating the element).
    ///
    /// # Errors
    /// [`ErrorKind::StaleLocator`], [`ErrorKind::UnknownAttribute`],
    /// [`ErrorKind::Unset`], or [`ErrorKind::WrongType`] for an attribute of another
    /// type.
    pub fn float(&self, loc: &Loc, name: &str) -> Result<f64, EditError> {
        self.typed(loc, name, Value::as_float)
    }

    /// The float array attribute `name` (`pos`, `size`, `rgba`) of the element at
    /// `loc`.
    ///
    /// Time: O(levels · depth · log n) (locating the element).
    ///
    /// # Errors
    /// As [`Model::float`].
    pub fn floats(&self, loc: &Loc, name: &str) -> Result<&[f64], EditError> {
        self.typed(loc, name, Value::as_floats)
    }

    /// The integer attribute `name` of the element at `loc`.
    ///
    /// Time: O(levels · depth · log n) (locating the element).
    ///
    /// # Errors
    /// As [`Model::float`].
    pub fn int(&self, loc: &Loc, name: &str) -> Result<i64, EditError> {
        self.typed(loc, name, Value::as_int)
    }

    /// The integer array attribute `name` of the element at `loc`.
    ///
    /// Time: O(levels · depth · log n) (locating the element).
    ///
    /// # Errors
    /// As [`Model::float`].
    pub fn ints(&self, loc: &Loc, name: &str) -> Result<&[i64], EditError> {
        self.typed(loc, name, Value::as_ints)
    }

    /// The text attribute `name` of the element at `loc` (see [`ElementRef::string`]).
    ///
    /// Time: O(levels · depth · log n) (locating the element).
    ///
    /// # Errors
    /// As [`Model::float`].
    pub fn string(&self, loc: &Loc, name: &str) -> Result<&str, EditError> {
        self.value_at(loc, name)?;
        let e = self.get(loc)?;
        let tag = e.tag();
        let attribute = e.kind().attr(e.kind().attr_index(name).unwrap_or(0)).name;
        e.string(name).ok_or_else(|| {
            EditError::new(
                ErrorKind::WrongType { tag, attribute },
                self.scope_path(loc).unwrap_or_default(),
            )
        })
    }
}
