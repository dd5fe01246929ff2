//! Checks before MuJoCo: what a composed model holds that MuJoCo would refuse, said
//! with the element's name and path; and who refers to an element.

use std::collections::HashMap;
use std::fmt;

use smol_str::SmolStr;

use crate::schema::{AttrType, ElementKind, Namespace};
use crate::suggest::Suggester;
use crate::value::{Reference, Value};

use super::cursor::{Insts, Item, Step, Walk};
use super::tree::{ElementId, Node};
use super::{Loc, Model};

/// A problem [`Model::check`] found: what, and on which element.
#[derive(Clone, Debug, PartialEq)]
pub struct Problem {
    /// The element.
    pub loc: Loc,
    /// The element as the writer names it (`robot_1/torso`, `//unnamed_actuator_3`:
    /// [`ElementRef::full_name`](crate::ElementRef::full_name)), or, for an element
    /// without a namespace, its scope prefix and tag.
    pub path: String,
    /// What is wrong.
    pub kind: ProblemKind,
}

/// What [`Model::check`] can find.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum ProblemKind {
    /// A reference that names nothing in its model (`joint="hinj"`), with the nearest
    /// existing names of that namespace.
    DanglingReference {
        /// The attribute.
        attribute: &'static str,
        /// The name it holds, as written in its model (no scope prefix).
        name: SmolStr,
        /// The namespace it names into.
        namespace: Namespace,
        /// The nearest names that exist ("did you mean").
        suggestions: Vec<SmolStr>,
    },
    /// A required attribute without a value: a required reference whose element was
    /// removed.
    MissingRequired {
        /// The attribute.
        attribute: &'static str,
    },
    /// An optional reference whose element was removed: it is no longer written, so
    /// the element loses it (an actuator its joint, which MuJoCo then refuses).
    RemovedReference {
        /// The attribute.
        attribute: &'static str,
    },
    /// A body (or attachment frame) that moves (it has joints or a freejoint) but has
    /// no mass: no inertial, no geom, and no body welded to it (below it, with no
    /// joint between) with mass. MuJoCo refuses it ("mass and inertia of moving bodies
    /// must be larger than mjMINVAL").
    MasslessMovingBody,
    /// A body (or attachment frame) whose joints have more than 6 degrees of
    /// freedom (a freejoint has 6, a ball joint 3, a hinge or slide 1): a freejoint
    /// beside another joint, say. MuJoCo refuses it ("more than 6 dofs in body").
    TooManyDofs {
        /// The degrees of freedom of its joints.
        dofs: usize,
    },
    /// A body (or attachment frame) with a hinge or ball joint after a ball joint.
    /// MuJoCo refuses it ("ball followed by rotation in body").
    RotationAfterBall,
    /// A keyframe whose array does not fit the composed model.
    KeyLength {
        /// `qpos`, `qvel` or `ctrl`.
        attribute: &'static str,
        /// The length the composed model needs.
        expected: usize,
        /// The length the key has.
        found: usize,
    },
}

impl fmt::Display for Problem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.kind {
            ProblemKind::DanglingReference { attribute, name, namespace, suggestions } => write!(
                f,
                "{}: '{attribute}' names {namespace} '{name}', which does not exist{}",
                self.path,
                crate::suggest::hint(suggestions)
            ),
            ProblemKind::MissingRequired { attribute } => {
                write!(f, "{}: required attribute '{attribute}' is not set", self.path)
            }
            ProblemKind::RemovedReference { attribute } => {
                write!(f, "{}: '{attribute}' named an element that was removed", self.path)
            }
            ProblemKind::MasslessMovingBody => write!(
                f,
                "{}: moves (has joints) but has no mass, and no body fixed to it has any; \
                 give it an inertial or a geom",
                self.path
            ),
            ProblemKind::TooManyDofs { dofs } => write!(
                f,
                "{}: its joints have {dofs} degrees of freedom, more than the 6 MuJoCo allows \
                 in one body (a freejoint has 6: it takes no other joint)",
                self.path
            ),
            ProblemKind::RotationAfterBall => write!(
                f,
                "{}: a hinge or ball joint follows a ball joint, which MuJoCo refuses; \
                 put the ball joint after them",
                self.path
            ),
            ProblemKind::KeyLength { attribute, expected, found } => write!(
                f,
                "{}: '{attribute}' has {found} values, the composed model needs {expected}",
                self.path
            ),
        }
    }
}

/// The namespace a reference attribute `i` of `node` names into.
fn ref_namespace(node: &Node, i: usize) -> Option<Namespace> {
    let kind = node.kind();
    match kind.attr(i).ty {
        AttrType::Reference(target) => target.namespace(|k| node.attr(k)),
        _ => None,
    }
}

/// Whether a plain name reference is one MuJoCo resolves without a named element:
/// the world body, the main default class.
fn builtin(ns: Namespace, name: &str) -> bool {
    matches!((ns, name), (Namespace::Body, "world") | (Namespace::Default, "/" | "main"))
}

/// The joint type of a joint element, as written or as its classes set it: `free`,
/// `ball`, `slide` or `hinge` (the default).
pub(crate) fn joint_type(model: &Model, node: &Node, class: Option<ElementId>) -> &'static str {
    if node.kind().tag() == "freejoint" {
        return "free";
    }
    let explicit = node.kind().attr_index("type").and_then(|i| node.attr(i));
    if let Some(Value::Keyword(k)) = explicit {
        return k;
    }
    // The class chain: the element's class, then its ancestors in the default tree.
    let mut cur = class;
    while let Some(id) = cur {
        let Some(class_node) = model.node_by_id(id) else { break };
        let joint_default = class_node.children().iter().find(|c| c.kind().tag() == "joint");
        if let Some(Value::Keyword(k)) =
            joint_default.and_then(|j| j.kind().attr_index("type").and_then(|i| j.attr(i)))
        {
            return k;
        }
        cur = model
            .index
            .parent(id)
            .filter(|p| model.node_by_id(*p).is_some_and(|n| n.kind().tag() == "default"));
    }
    "hinge"
}

/// An element open in [`Model::check`]'s walk, with what its subtree showed so far.
struct Open<'a> {
    inst: usize,
    node: &'a Node,
    /// It has joints (or a freejoint).
    moves: bool,
    /// It, or something welded below it, has mass.
    massive: bool,
    /// The degrees of freedom of its own joints.
    dofs: usize,
    /// One of its joints is a ball joint.
    ball: bool,
    /// A hinge or ball joint of its own follows a ball joint.
    rotation_after_ball: bool,
}

impl<'a> Open<'a> {
    fn new(inst: usize, node: &'a Node) -> Open<'a> {
        Open {
            inst,
            node,
            moves: false,
            massive: false,
            dofs: 0,
            ball: false,
            rotation_after_ball: false,
        }
    }
}

/// How a problem names the element the walk entered as `item`: the name the writer
/// writes for it, or (no namespace) its scope and tag.
fn problem_path(insts: &Insts<'_>, item: &Item<'_>) -> String {
    let prefix = &insts.list[item.inst].names.prefix;
    match insts.name_of_item(item) {
        Some(w) => w.to_string_in(prefix),
        None => format!("{prefix}{}", item.node.kind().tag()),
    }
}

impl Model {
    /// What MuJoCo would refuse in the composed model, found before it is written:
    /// references that name nothing in their model (the `joint="hinj"` typo, with the
    /// nearest names), references whose element was removed, moving bodies
    /// and attachment frames without mass (no inertial, no geom, no massive body
    /// welded below), bodies and frames whose joints MuJoCo refuses (more than 6
    /// degrees of freedom, such as a freejoint beside another joint; a hinge or ball
    /// joint after a ball joint), and keyframes whose `qpos`, `qvel` or `ctrl` length
    /// does not fit the composed model. Empty when none is found; this is not a full
    /// MuJoCo compile (classes are followed for joint types only; `act`, `mpos` and
    /// `mquat` of keys are not checked). Each problem names its element as the
    /// writer writes it.
    ///
    /// Time: O(N) for a composed model of N elements, plus, for dangling references,
    /// O(n log n) per model and namespace they name into (ranking its `n` names
    /// once) and a bounded number of name comparisons each (see
    /// [`Model::lookup`]).
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, ProblemKind, element};
    /// let mut m = Model::new("m");
    /// let b = m.add_mut(&m.worldbody(), element!("body", name = "b"))?;
    /// m.add_mut(&b, element!("joint", name = "hinge"))?;
    /// m.add_mut(&b, element!("geom", size = [0.1]))?;
    /// m.add_mut(&m.actuator(), element!("motor", name = "m", joint = "hinj"))?;
    /// let problems = m.check();
    /// assert_eq!(problems.len(), 1);
    /// assert!(matches!(&problems[0].kind, ProblemKind::DanglingReference { suggestions, .. } if suggestions[0] == "hinge"));
    /// assert_eq!(problems[0].to_string(), "m: 'joint' names joint 'hinj', which does not exist (did you mean 'hinge'?)");
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn check(&self) -> Vec<Problem> {
        let mut problems = Vec::new();
        let name = self.name();
        let mut walk = Walk::new(self);
        let mut open: Vec<Open<'_>> = Vec::new();
        let (mut nq, mut nv, mut nu) = (0usize, 0usize, 0usize);
        // Keys, with their locators and names.
        let mut keys: Vec<(&Node, Loc, String)> = Vec::new();
        // The class in force per instance: (childclass stack) is approximated by the
        // element's own class, else the nearest `childclass` above, else the root.
        let mut childclass: Vec<Option<ElementId>> = Vec::new();
        // Names ranked for suggestions, per model (instance) and namespace, once.
        let mut suggesters: HashMap<(usize, Namespace), Suggester<'_>> = HashMap::new();
        while let Some(step) = walk.next() {
            match step {
                Step::Enter(item) => {
                    let inst = &walk.insts.list[item.inst];
                    let m = inst.model;
                    let node = item.node;
                    let kind = node.kind();
                    let loc = || Loc::scoped(inst.frames.clone(), node.id(), name);
                    let path = || problem_path(&walk.insts, &item);
                    // References.
                    for (i, v) in node.attrs() {
                        let i = *i as usize;
                        let spec = kind.attr(i);
                        match v {
                            Value::Reference(Reference::Name(n)) => {
                                let Some(ns) = ref_namespace(node, i) else { continue };
                                if builtin(ns, n) || m.index.names.contains_key(&(ns, n.clone())) {
                                    continue;
                                }
                                if ns == Namespace::AttachmentFrame || m.find(ns, n).is_some() {
                                    continue;
                                }
                                let ranked =
                                    suggesters.entry((item.inst, ns)).or_insert_with(|| {
                                        Suggester::new(
                                            m.index
                                                .names
                                                .keys()
                                                .filter(|(k, _)| *k == ns)
                                                .map(|(_, n)| n.as_str()),
                                        )
                                    });
                                let suggestions =
                                    ranked.nearest(n, 3).into_iter().map(SmolStr::from).collect();
                                problems.push(Problem {
                                    loc: loc(),
                                    path: path(),
                                    kind: ProblemKind::DanglingReference {
                                        attribute: spec.name,
                                        name: n.clone(),
                                        namespace: ns,
                                        suggestions,
                                    },
                                });
                            }
                            Value::Reference(Reference::Element(id)) if !m.index.contains(*id) => {
                                let attribute = spec.name;
                                let kind = if spec.required {
                                    ProblemKind::MissingRequired { attribute }
                                } else {
                                    ProblemKind::RemovedReference { attribute }
                                };
                                problems.push(Problem { loc: loc(), path: path(), kind });
                            }
                            _ => {}
                        }
                    }
                    // Degrees of freedom, actuators, keys.
                    let parent_tag = open.last().map(|o| o.node.kind().tag());
                    let in_section = |tag: &str| {
                        kind.spec().parent.is_some_and(|p| p.tag() == tag)
                            && parent_tag == Some(tag)
                    };
                    if matches!(kind.tag(), "joint" | "freejoint") && parent_tag == Some("body") {
                        let class = node
                            .kind()
                            .class_attr()
                            .and_then(|c| match node.attr(c) {
                                Some(Value::Reference(Reference::Element(id))) => Some(*id),
                                _ => None,
                            })
                            .or(childclass.last().copied().flatten())
                            .or_else(|| {
                                m.root
                                    .child_of_kind(ElementKind::ROOT.child("default")?)
                                    .map(Node::id)
                            });
                        let ty = joint_type(m, node, class);
                        let (q, v) = match ty {
                            "free" => (7, 6),
                            "ball" => (4, 3),
                            _ => (1, 1),
                        };
                        nq += q;
                        nv += v;
                        if let Some(top) = open.last_mut() {
                            top.moves = true;
                            top.dofs += v;
                            top.rotation_after_ball |= top.ball && matches!(ty, "ball" | "hinge");
                            top.ball |= ty == "ball";
                        }
                    }
                    if in_section("actuator") {
                        nu += 1;
                    }
                    if in_section("keyframe") {
                        keys.push((node, loc(), path()));
                    }
                    // Mass: an inertial with mass, or a geom (MuJoCo gives geoms a
                    // density) that does not set its mass to 0.
                    let massive = match kind.tag() {
                        "inertial" => node
                            .attr(kind.attr_index("mass").unwrap_or(0))
                            .and_then(Value::as_float)
                            .is_some_and(|x| x > 0.0),
                        "geom" => {
                            node.attr(kind.attr_index("mass").unwrap_or(0))
                                .and_then(Value::as_float)
                                != Some(0.0)
                        }
                        _ => false,
                    };
                    if massive {
                        if let Some(top) = open.last_mut() {
                            top.massive = true;
                        }
                    }
                    let cc = kind.attr_index("childclass").and_then(|c| match node.attr(c) {
                        Some(Value::Reference(Reference::Element(id))) => Some(*id),
                        _ => None,
                    });
                    let inherited = if item.inst == open.last().map_or(0, |o| o.inst) {
                        childclass.last().copied().flatten()
                    } else {
                        None
                    };
                    childclass.push(cc.or(inherited));
                    open.push(Open::new(item.inst, node));
                }
                Step::Leave(item) => {
                    childclass.pop();
                    let Some(o) = open.pop() else { continue };
                    let is_body = o.node.kind().tag() == "body"
                        && o.node.kind().spec().parent.is_some_and(|p| p.tag() != "default");
                    let problem = |kind| {
                        let i = &walk.insts.list[o.inst];
                        let loc = Loc::scoped(i.frames.clone(), o.node.id(), name);
                        Problem { loc, path: problem_path(&walk.insts, &item), kind }
                    };
                    if is_body && o.moves && !o.massive {
                        problems.push(problem(ProblemKind::MasslessMovingBody));
                    }
                    if o.dofs > 6 {
                        problems.push(problem(ProblemKind::TooManyDofs { dofs: o.dofs }));
                    }
                    if o.rotation_after_ball {
                        problems.push(problem(ProblemKind::RotationAfterBall));
                    }
                    // Mass below counts for the parent only through a body that does
                    // not move on its own (welded to it): MuJoCo wants a moving body's
                    // own mass, or that of bodies welded to it, above zero.
                    if o.massive && !(is_body && o.moves) {
                        if let Some(top) = open.last_mut() {
                            top.massive = true;
                        }
                    }
                }
            }
        }
        for (key, loc, path) in keys {
            for (attribute, expected) in [("qpos", nq), ("qvel", nv), ("ctrl", nu)] {
                let found = key
                    .kind()
                    .attr_index(attribute)
                    .and_then(|a| key.attr(a))
                    .and_then(Value::as_floats);
                if let Some(values) = found {
                    if values.len() != expected {
                        problems.push(Problem {
                            loc: loc.clone(),
                            path: path.clone(),
                            kind: ProblemKind::KeyLength {
                                attribute,
                                expected,
                                found: values.len(),
                            },
                        });
                    }
                }
            }
        }
        problems
    }

    /// Every element that refers to the element at `loc`, with the attribute: by a
    /// resolved reference (read from MJCF) or by its name, within the target's own
    /// model (references never cross an attachment). An editor can warn before
    /// [`Model::remove`], which clears such resolved references.
    ///
    /// Time: O(n) for a composed model of n elements.
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, Namespace, element};
    /// let mut m = Model::new("m");
    /// let b = m.add_mut(&m.worldbody(), element!("body", name = "b"))?;
    /// let j = m.add_mut(&b, element!("joint", name = "hinge"))?;
    /// let motor = m.add_mut(&m.actuator(), element!("motor", joint = "hinge"))?;
    /// assert_eq!(m.references_to(&j), vec![(motor, "joint")]);
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn references_to(&self, loc: &Loc) -> Vec<(Loc, &'static str)> {
        let mut out = Vec::new();
        let Some(target) = self.element(loc) else { return out };
        let target_ns = target.kind().namespace();
        let target_name = target.identifier();
        let name = self.name();
        let mut walk = Walk::new(self);
        while let Some(step) = walk.next() {
            let Step::Enter(item) = step else { continue };
            let inst = &walk.insts.list[item.inst];
            if inst.frames[..] != *loc.scope() {
                continue;
            }
            let node = item.node;
            for (i, v) in node.attrs() {
                let i = *i as usize;
                let hit = match v {
                    Value::Reference(Reference::Element(id)) => *id == loc.id(),
                    Value::Reference(Reference::Name(n)) => {
                        target_name == Some(n.as_str())
                            && target_ns.is_some()
                            && ref_namespace(node, i) == target_ns
                    }
                    _ => false,
                };
                if hit {
                    out.push((
                        Loc::scoped(inst.frames.clone(), node.id(), name),
                        node.kind().attr(i).name,
                    ));
                }
            }
        }
        out
    }

    /// The name MuJoCo will give the element at `loc` (`robot_1/torso`, a frame's
    /// `robot_1/`, an unnamed geom's `//unnamed_geom_0`): the name to pass to
    /// `mj_name2id`. `None` if `loc` is not in this model or the element has no
    /// namespace. See [`ElementRef::full_name`](crate::ElementRef::full_name).
    ///
    /// Time: as [`ElementRef::full_name`](crate::ElementRef::full_name).
    pub fn full_name(&self, loc: &Loc) -> Option<String> {
        self.element(loc)?.full_name()
    }

    /// The element MuJoCo names `name` in `namespace` (the inverse of
    /// [`Model::full_name`]): a scoped name such as `robot_1/torso`, a frame's
    /// `robot_1/` (a body), a frame joint's `robot_1/root/`, or an automatic name
    /// such as `robot//unnamed_geom_1`.
    ///
    /// Time: O(levels · log n) for a scoped identifier; O(N) for frames, frame
    /// joints and automatic names, which are found by walking the composed model of
    /// `N` elements.
    pub fn from_full_name(&self, namespace: Namespace, name: &str) -> Option<Loc> {
        if let Some(loc) = self.find(namespace, name) {
            // (A frame, by its scope path, has no name of that namespace to check.)
            if namespace == Namespace::AttachmentFrame
                || self.full_name(&loc).as_deref() == Some(name)
            {
                return Some(loc);
            }
        }
        // Frames, their joints and unnamed elements: compare the names the walk gives.
        let top = self.name();
        let mut walk = Walk::new(self);
        let mut text = String::new();
        while let Some(step) = walk.next() {
            let Step::Enter(item) = step else { continue };
            if item.node.kind().namespace() != Some(namespace) {
                continue;
            }
            let Some(written) = walk.insts.name_of_item(&item) else { continue };
            let inst = &walk.insts.list[item.inst];
            text.clear();
            written.write(&inst.names.prefix, &mut text);
            if text == name {
                return Some(Loc::scoped(inst.frames.clone(), item.node.id(), top));
            }
        }
        None
    }
}
