//! The handle on one element of a composed model ([`ElementRef`]) and the preorder
//! walk that gives handles ([`Model::walk`]).
//!
//! A handle carries what naming it and listing its children need, shared with the
//! handles made from it: its instance's context ([`Shared`]: the model, the frames
//! from the outermost model down to it, the attachment frame, the instance's naming
//! state and, once a name asks, its model's automatic-name positions), and, for a
//! handle that [`ElementRef::children`] made, the handle it was made from (its
//! composed parent). So `full_name` costs the name, not a walk of the composition
//! from the root, and `children` (and `parent`, for a handle `children` made) costs
//! the answer, not a search from the top. The walk's handles share their instances'
//! contexts but keep no parent (keeping one cost the walk of a fleet about 30% more
//! instructions per element). A handle made by [`Model::element`] starts a context
//! of its own, filled the first time it is asked; the automatic-name positions it
//! needs are its model's, counted once per version of the model and kept with it.

use std::fmt;
use std::sync::{Arc, OnceLock};

use crate::error::{EditError, ErrorKind};
use crate::schema::{ElementKind, Role};
use crate::value::{Reference, Value};

use super::cursor::{AutoPositions, Item, Step, Walk, in_replicate, name_in, section};
use super::layout::{self, JointType};
use super::naming::InstNames;
use super::tree::{ElementId, Node};
use super::{Loc, Model};

/// How an instance's elements are named: its naming state and its attachment frame
/// (a node of the instance above; `None` for the outermost model).
struct Naming<'a> {
    names: InstNames,
    frame: Option<&'a Node>,
}

/// What the handles of one model instance of a composition share.
pub(super) struct Shared<'a> {
    /// The model the handles were taken from (the outermost).
    top: &'a Model,
    /// The model of the instance.
    pub(super) model: &'a Model,
    /// The frames from the outermost model down to the instance (empty for it).
    frames: Arc<[ElementId]>,
    /// The context of the instance it is attached in and its attachment frame there,
    /// when it was made from a handle of that one (its naming then grows from that
    /// one's).
    pub(super) outer: Option<(Arc<Shared<'a>>, &'a Node)>,
    /// Its naming, made the first time a name is asked (`None`: the frames lead
    /// nowhere, which a handle's frames always do).
    naming: OnceLock<Option<Naming<'a>>>,
    /// Every element's automatic-name position in the model, counted the first time
    /// an unnamed element's name is asked.
    pub(super) auto: OnceLock<Arc<AutoPositions>>,
}

impl<'a> Shared<'a> {
    /// The context of the instance attached along `frames` (empty: the outermost
    /// model), `model` its model; its naming is made when asked.
    fn new(top: &'a Model, model: &'a Model, frames: Arc<[ElementId]>) -> Arc<Shared<'a>> {
        let (outer, naming, auto) = (None, OnceLock::new(), OnceLock::new());
        Arc::new(Shared { top, model, frames, outer, naming, auto })
    }

    /// The context of the model attached at `frame`, an element of this instance.
    fn attached(self: &Arc<Self>, frame: &'a Node, model: &'a Model) -> Arc<Shared<'a>> {
        let mut frames = Vec::with_capacity(self.frames.len() + 1);
        frames.extend_from_slice(&self.frames);
        frames.push(frame.id());
        Arc::new(Shared {
            top: self.top,
            model,
            frames: frames.into(),
            outer: Some((self.clone(), frame)),
            naming: OnceLock::new(),
            auto: OnceLock::new(),
        })
    }

    /// The context of instance `inst` of a walk over `top`, its naming taken from
    /// the walk.
    fn of_walk(walk: &Walk<'a>, inst: usize) -> Arc<Shared<'a>> {
        let i = &walk.insts.list[inst];
        let s = Shared::new(walk.insts.list[0].model, i.model, i.frames.clone());
        let naming = Naming { names: i.names.clone(), frame: i.frame };
        let _ = s.naming.set(Some(naming));
        s
    }

    /// The context of the outermost model: the end of the chain of `outer`, when it
    /// reaches it.
    fn top_of(self: &Arc<Self>) -> Arc<Shared<'a>> {
        let mut s = self;
        while let Some((o, _)) = &s.outer {
            s = o;
        }
        if s.frames.is_empty() { s.clone() } else { Shared::new(self.top, self.top, Arc::from([])) }
    }

    /// The instance's naming: its outer instance's, grown by its scope, or followed
    /// from the outermost model along its frames (as the composed walk names it).
    fn naming(&self) -> Option<&Naming<'a>> {
        self.naming
            .get_or_init(|| {
                if let Some((o, frame)) = &self.outer {
                    let a = frame.attached()?;
                    let inside = in_replicate(o.model, frame.id());
                    let names = o.naming()?.names.attached(&a.scope, &a.model, inside);
                    return Some(Naming { names, frame: Some(frame) });
                }
                let mut names = InstNames::top(self.top);
                let (mut model, mut frame) = (self.top, None);
                for &f in self.frames.iter() {
                    let node = model.node_by_id(f)?;
                    let a = node.attached()?;
                    names.descend(&a.scope, &a.model, in_replicate(model, f));
                    (model, frame) = (&a.model, Some(node));
                }
                Some(Naming { names, frame })
            })
            .as_ref()
    }
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
    /// The context of each instance the walk has given a handle in.
    shared: Vec<Option<Arc<Shared<'a>>>>,
}

impl<'a> Preorder<'a> {
    /// Skips the children of the element entered last, and its `Leave`.
    ///
    /// Time: O(1).
    pub fn skip_subtree(&mut self) {
        self.walk.skip_subtree();
    }

    /// The context of instance `inst` of the walk.
    fn shared(&mut self, inst: usize) -> Arc<Shared<'a>> {
        if self.shared.len() <= inst {
            self.shared.resize(inst + 1, None);
        }
        self.shared[inst].get_or_insert_with(|| Shared::of_walk(&self.walk, inst)).clone()
    }
}

impl fmt::Debug for Preorder<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Preorder").field("pending", &self.walk.pending()).finish()
    }
}

impl<'a> Iterator for Preorder<'a> {
    type Item = Event<'a>;

    fn next(&mut self) -> Option<Event<'a>> {
        let step = self.walk.next()?;
        let (Step::Enter(item) | Step::Leave(item)) = step;
        let view = ElementRef { shared: self.shared(item.inst), node: item.node, up: None };
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
        Preorder { walk: Walk::new(self), shared: Vec::new() }
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
    /// ([`Model::get`] without the error). The view starts a context of its own
    /// (naming its instance is left to the first name asked), which the views made
    /// from it share.
    ///
    /// Time: O(levels · depth · log n) (locating the element).
    pub fn element(&self, loc: &Loc) -> Option<ElementRef<'_>> {
        let m = self.scoped_model(loc.scope())?;
        let node = m.node_by_id(loc.id())?;
        let shared = Shared::new(self, m, Arc::from(loc.scope()));
        Some(ElementRef { shared, node, up: None })
    }
}

/// A read-only view of one element of a composed model: it knows its model and the
/// attachments it lies in, so it can go up, down and name itself as MuJoCo will.
#[derive(Clone)]
pub struct ElementRef<'a> {
    /// Its instance's context, shared with the handles of the same instance made
    /// from one another.
    pub(super) shared: Arc<Shared<'a>>,
    node: &'a Node,
    /// Its composed parent, when it was made from it, without a parent of its own: a
    /// chain of handles would be dropped one stack frame per level (and a drop of our
    /// own, which could unwind it, would make a handle's borrow of its model last
    /// until it is dropped).
    up: Option<Arc<ElementRef<'a>>>,
}

impl<'a> ElementRef<'a> {
    /// This handle as the parent its children keep (without its own parent).
    fn as_up(&self) -> Arc<ElementRef<'a>> {
        Arc::new(ElementRef { shared: self.shared.clone(), node: self.node, up: None })
    }

    /// A handle on `node` of the same instance, whose composed parent is `up`.
    fn sibling(&self, node: &'a Node, up: &Option<Arc<ElementRef<'a>>>) -> ElementRef<'a> {
        ElementRef { shared: self.shared.clone(), node, up: up.clone() }
    }

    /// The element's locator in the model the view was taken from (scoped when the
    /// element lies inside an attachment).
    ///
    /// Time: O(1).
    pub fn loc(&self) -> Loc {
        Loc::scoped(self.shared.frames.clone(), self.node.id(), self.shared.top.name())
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
            let class = layout::class_in_force(self.shared.model, self.node);
            layout::joint_type(self.shared.model, self.node, class)
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
        self.shared.top.scope_path(&self.loc()).unwrap_or_default()
    }

    /// The name MuJoCo will give the element in the written model, exactly as the
    /// writer writes it (both follow one set of rules: [Names](crate::guide#names)): the
    /// identifier with its scope prefix (`robot_1/torso`), an attachment frame's scope
    /// (`robot_1/`), a frame joint's (`robot_1/root/`), or the automatic name of an
    /// unnamed element (`//unnamed_geom_0`, `robot//unnamed_geom_2`, `//unnamed_geom_1_`
    /// inside a `<replicate>`); `None` for elements without a namespace.
    ///
    /// Time: O(log n + the name's length) (its index entry, then the name spelt);
    /// O(depth · log n) more for a joint of an attachment frame (its frame found).
    /// The handles of one instance made from one another ([`ElementRef::children`],
    /// [`ElementRef::parent`], [`Model::walk`]) share what the name needs, each part
    /// made once, the first time one of them asks: the instance's prefix (O(the
    /// prefix's length) from the instance above it; O(levels · depth · log n) from
    /// the outermost model for a handle made by [`Model::element`]) and, for an
    /// unnamed element, whose number is its position, the positions of its model's
    /// elements (O(n), n of the element's model, once per version of that model: the
    /// model keeps the last count, so handles made one by one by [`Model::element`]
    /// share it too).
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
        let s = &*self.shared;
        let (m, id) = (s.model, self.node.id());
        // Members of runs have no namespace, so every element with a name has an
        // entry of its own.
        let entry = m.index.elems.get(&id)?;
        let naming = s.naming()?;
        let name = name_in(&naming.names, m, naming.frame, id, entry, || {
            let counted = s.auto.get_or_init(|| m.auto_positions());
            counted.get(&id).copied().unwrap_or((0, false))
        })?;
        Some(name.to_string_in(&naming.names.prefix))
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
                self.shared.model.index.name(*id).map(smol_str::SmolStr::as_str)
            }
            v => v.as_str(),
        }
    }

    /// The composed parent: for a top-level body of an attached model, its
    /// attachment frame; for an element directly in a section of an attached model,
    /// that section of the outermost model (directly in its root default class: that
    /// class, which is a class of its own beside the outermost model's); `None` for
    /// the root.
    ///
    /// Time: O(1) for a handle made by [`ElementRef::children`] (it keeps the handle
    /// it was made from); otherwise O(depth · log n) (its
    /// parent found by its id), O(levels · depth · log n) for a top-level body of an
    /// attached model whose handle was made by [`Model::element`] (its frame found
    /// from the outermost model).
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
        if let Some(up) = &self.up {
            return Some(ElementRef::clone(up));
        }
        let s = &self.shared;
        let (top, model) = (s.top, s.model);
        let parent = model.index.parent(self.node.id())?;
        let pnode = model.node_by_id(parent)?;
        let is_section = pnode.kind().spec().parent == Some(ElementKind::ROOT);
        // The sections whose content the outermost model's gathers (an attached
        // model's root default class is a class of its own, beside the outermost
        // one's).
        let merged = is_section && !pnode.kind().is(Role::DefaultClass);
        let at = |shared, node| Some(ElementRef { shared, node, up: None });
        match s.frames.split_last() {
            Some((frame, outer)) if pnode.kind().is(Role::Worldbody) && is_section => {
                match &s.outer {
                    Some((o, fnode)) => at(o.clone(), *fnode),
                    None => {
                        let outer_model = top.scoped_model(outer)?;
                        let fnode = outer_model.node_by_id(*frame)?;
                        at(Shared::new(top, outer_model, Arc::from(outer)), fnode)
                    }
                }
            }
            Some(_) if merged => at(s.top_of(), top.root.child_of_kind(pnode.kind())?),
            Some(_) if pnode.kind() == ElementKind::ROOT => at(s.top_of(), &top.root),
            _ => at(s.clone(), pnode),
        }
    }

    /// The composed children, in document order: an attachment frame's own
    /// children then the attached model's bodies; a top-level section's own
    /// elements then those of every attached model.
    ///
    /// Time: O(width); for an attachment frame, O(1) more (the attached model's
    /// handles share one new context, made from this handle's); for the root or a
    /// top-level section of the outermost model, O(a · depth · log n) more (the
    /// attached models' content gathered). The list is made when this is called.
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
        let s = &self.shared;
        let kind = self.node.kind();
        let children = self.node.children();
        let top_level = s.frames.is_empty()
            && (kind == ElementKind::ROOT || kind.spec().parent == Some(ElementKind::ROOT));
        if children.is_empty() && !top_level && self.node.attached().is_none() {
            return Vec::new().into_iter();
        }
        let up = Some(self.as_up());
        let mut out = Vec::with_capacity(children.len());
        if top_level {
            // The root and the top-level sections gather the attached models'
            // content: the composed walk's rules.
            let mut walk = Walk::new(s.top);
            let depth = if kind == ElementKind::ROOT { 0 } else { 1 };
            let items = walk.expand(Item::plain(0, self.node, depth, false));
            let mut shared: Vec<Option<Arc<Shared<'a>>>> = vec![Some(s.clone())];
            for it in items {
                if shared.len() <= it.inst {
                    shared.resize(it.inst + 1, None);
                }
                let sh = shared[it.inst].get_or_insert_with(|| Shared::of_walk(&walk, it.inst));
                out.push(ElementRef { shared: sh.clone(), node: it.node, up: up.clone() });
            }
            return out.into_iter();
        }
        // Deeper than any rule of a top-level section or the root applies: the own
        // children, then an attachment frame's model's bodies.
        out.extend(children.iter().map(|c| self.sibling(c, &up)));
        if let Some(a) = self.node.attached() {
            if let Some(wb) = section(&a.model, "worldbody") {
                let inner = s.attached(self.node, &a.model);
                out.extend(wb.children().iter().map(|c| ElementRef {
                    shared: inner.clone(),
                    node: c,
                    up: up.clone(),
                }));
            }
        }
        out.into_iter()
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
