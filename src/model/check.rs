//! Checks before MuJoCo: what a composed model holds that MuJoCo would refuse, said
//! with the element's name and path; and who refers to an element.

use std::collections::HashMap;
use std::fmt;

use smol_str::SmolStr;

use crate::schema::{AttrType, Namespace, Role};
use crate::suggest::Suggester;
use crate::value::{Reference, Value};
use crate::write_options::WriteOptions;

use super::cursor::{Insts, Item, Step, Walk};
use super::layout::{JointType, joint_type};
use super::tree::Node;
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
    /// A keyframe array with more values than the model has room for (MuJoCo refuses
    /// it, "invalid qpos size"; a shorter one it pads with zeros): the composed
    /// model's, or with [`WriteOptions::merge_keyframes`] the key's own model's.
    KeyLength {
        /// `qpos`, `qvel`, `act`, `ctrl`, `mpos` or `mquat`.
        attribute: &'static str,
        /// The most values there is room for.
        expected: usize,
        /// The length the key has.
        found: usize,
    },
    /// A key of an attached model, written as it is (without
    /// [`WriteOptions::merge_keyframes`]): MuJoCo compiles it, but its values fall on
    /// the composed model's first joints and actuators (the parent's), not on the
    /// attached model's. Write with `merge_keyframes`, which carries each attached
    /// model's key to its own joints and through its attachment frame.
    UncomposedKey,
    /// An array shorter than MuJoCo accepts (`pos="1 2"`: MuJoCo refuses it, "does not
    /// have enough data"); the minimums are MuJoCo's, probed from MuJoCo 4.0.0.
    ArrayTooShort {
        /// The attribute.
        attribute: &'static str,
        /// The fewest numbers MuJoCo accepts.
        minimum: usize,
        /// The numbers it has.
        found: usize,
    },
    /// Mesh data whose length is not a multiple of what one item takes (`vertex` and
    /// `face` by 3, `texcoord` by 2); MuJoCo refuses it.
    ArrayNotMultiple {
        /// The attribute.
        attribute: &'static str,
        /// What its length must be a multiple of.
        of: usize,
        /// The numbers it has.
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
                crate::error::hint(suggestions)
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
                "{}: '{attribute}' has {found} values, the model has room for {expected}",
                self.path
            ),
            ProblemKind::UncomposedKey => write!(
                f,
                "{}: a key of an attached model, written as it is, sets the composed model's \
                 first joints, not this model's; write with WriteOptions::merge_keyframes",
                self.path
            ),
            ProblemKind::ArrayTooShort { attribute, minimum, found } => write!(
                f,
                "{}: '{attribute}' has {found} numbers, MuJoCo needs at least {minimum}",
                self.path
            ),
            ProblemKind::ArrayNotMultiple { attribute, of, found } => write!(
                f,
                "{}: '{attribute}' has {found} numbers, MuJoCo needs a multiple of {of}",
                self.path
            ),
        }
    }
}

/// The namespace a reference attribute `i` of `node` names into.
fn ref_namespace(node: &Node, i: usize) -> Option<Namespace> {
    let kind = node.kind();
    match kind.attr(i).ty {
        AttrType::Reference(target) => {
            let other = target.depends_on().and_then(|k| node.attr(k));
            target.namespace(other.map(|v| v.as_str().unwrap_or("")))
        }
        _ => None,
    }
}

/// An element open in [`Model::check`]'s walk, with what its subtree showed so far.
struct Open<'a> {
    inst: usize,
    node: &'a Node,
    /// Its own joints (for a body or an attachment frame).
    joints: BodyJoints,
    /// It, or something welded below it, has mass.
    massive: bool,
}

/// The joints of one body (or attachment frame), as [`Model::check`]'s rules on
/// joints see them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
struct BodyJoints {
    /// It has joints (or a freejoint).
    moves: bool,
    /// The degrees of freedom of its joints.
    dofs: usize,
    /// One of its joints is a ball joint.
    ball: bool,
    /// A hinge or ball joint follows a ball joint.
    rotation_after_ball: bool,
}

impl BodyJoints {
    /// A joint of type `ty` is added after those seen so far.
    fn add(&mut self, ty: JointType) {
        self.moves = true;
        self.dofs += ty.nv();
        self.rotation_after_ball |= self.ball && matches!(ty, JointType::Ball | JointType::Hinge);
        self.ball |= ty == JointType::Ball;
    }

    /// Rules *at most 6 degrees of freedom per body* ([`ProblemKind::TooManyDofs`])
    /// and *no rotation after a ball joint* ([`ProblemKind::RotationAfterBall`]).
    fn problems(&self) -> Vec<ProblemKind> {
        let mut out = Vec::new();
        if self.dofs > 6 {
            out.push(ProblemKind::TooManyDofs { dofs: self.dofs });
        }
        if self.rotation_after_ball {
            out.push(ProblemKind::RotationAfterBall);
        }
        out
    }
}

/// Rule *a moving body has mass* ([`ProblemKind::MasslessMovingBody`]): a body with
/// joints, with no mass of its own nor of bodies welded below it.
fn massless_moving_body(is_body: bool, joints: &BodyJoints, massive: bool) -> Option<ProblemKind> {
    (is_body && joints.moves && !massive).then_some(ProblemKind::MasslessMovingBody)
}

/// Whether `node` (of the model `m`) gives the body it is in mass: an inertial with a
/// mass above 0, a geom (MuJoCo gives geoms a density) that does not set its mass to
/// 0, or an `<attach>` whose part brings a body welded to it (attached with no joint)
/// that has mass, its own or welded below it (a part that cannot be read on its own
/// counts as giving mass: what it holds is unknown).
fn gives_mass(m: &Model, node: &Node) -> bool {
    let kind = node.kind();
    let mass = || node.attr(kind.attr_index("mass").unwrap_or(0)).and_then(Value::as_float);
    match kind.role() {
        Some(Role::Inertial) => mass().is_some_and(|x| x > 0.0),
        Some(Role::Geom) => mass() != Some(0.0),
        Some(Role::Attach) => attach_gives_mass(m, node),
        _ => false,
    }
}

/// [`gives_mass`] for an `<attach>`: the attached body (its `body`, else the part's
/// worldbody, whose bodies it brings) has mass welded to it.
fn attach_gives_mass(m: &Model, attach: &Node) -> bool {
    let kind = attach.kind();
    let attr = |name: &str| kind.attr_index(name).and_then(|i| attach.attr(i));
    let Some(part) = attached_part(m, attr("model")) else { return true };
    let top = match attr("body") {
        Some(Value::Reference(Reference::Name(n))) => part.find(Namespace::Body, n),
        Some(v) => v.as_str().and_then(|n| part.find(Namespace::Body, n)),
        None => Some(part.worldbody()),
    };
    let Some(top) = top.and_then(|loc| part.node_by_id(loc.id())) else { return true };
    if !top.kind().is(Role::Body) {
        return welded_mass(&part, top);
    }
    // A body that moves on its own (a joint of its own) gives the frame no mass.
    !moves(top) && (top.children().iter().any(|c| gives_mass(&part, c)) || welded_mass(&part, top))
}

/// Whether the body `b` has a joint (or a freejoint) of its own.
fn moves(b: &Node) -> bool {
    b.children().iter().any(|j| matches!(j.kind().role(), Some(Role::Joint | Role::Freejoint)))
}

/// Whether a body welded below `node` (a child body without joints, or one inside a
/// frame, and so on down) has mass of its own.
fn welded_mass(m: &Model, node: &Node) -> bool {
    node.children().iter().any(|c| match c.kind().role() {
        Some(Role::Body) if !moves(c) => {
            c.children().iter().any(|g| gives_mass(m, g)) || welded_mass(m, c)
        }
        Some(Role::Frame) => c.children().iter().any(|g| gives_mass(m, g)) || welded_mass(m, c),
        _ => false,
    })
}

/// Names ranked for suggestions, per model (walk instance) and namespace, each made
/// once.
type Suggesters<'m> = HashMap<(usize, Namespace), Suggester<'m>>;

/// Rule *references resolve*: each reference by name of `node` (of the model `m`,
/// walk instance `inst`) names an element of its own model or a builtin name
/// ([`ProblemKind::DanglingReference`], with the nearest names), and each resolved
/// reference an element still there ([`ProblemKind::MissingRequired`] for a required
/// attribute, [`ProblemKind::RemovedReference`] for an optional one).
fn unresolved_references<'m>(
    m: &'m Model,
    inst: usize,
    node: &Node,
    suggesters: &mut Suggesters<'m>,
) -> Vec<ProblemKind> {
    let kind = node.kind();
    let mut out = Vec::new();
    for (i, v) in node.attrs() {
        let i = *i as usize;
        let spec = kind.attr(i);
        match v {
            Value::Reference(Reference::Name(n)) => {
                let Some(ns) = ref_namespace(node, i) else { continue };
                if super::naming::is_builtin_name(ns, n)
                    || m.index.names.contains_key(&(ns, n.clone()))
                {
                    continue;
                }
                if ns == Namespace::AttachmentFrame || m.find(ns, n).is_some() {
                    continue;
                }
                if named_by_expansion(m, ns, n) {
                    continue;
                }
                let ranked = suggesters.entry((inst, ns)).or_insert_with(|| {
                    Suggester::new(
                        m.index.names.keys().filter(|(k, _)| *k == ns).map(|(_, n)| n.as_str()),
                    )
                });
                let suggestions = ranked.nearest(n, 3).into_iter().map(SmolStr::from).collect();
                out.push(ProblemKind::DanglingReference {
                    attribute: spec.name,
                    name: n.clone(),
                    namespace: ns,
                    suggestions,
                });
            }
            Value::Reference(Reference::Element(id)) if !m.index.contains(*id) => {
                let attribute = spec.name;
                out.push(if spec.required {
                    ProblemKind::MissingRequired { attribute }
                } else {
                    ProblemKind::RemovedReference { attribute }
                });
            }
            _ => {}
        }
    }
    out
}

/// Whether MuJoCo makes the name `name` of namespace `ns` when it expands an element
/// of `m` that the model keeps as written: a copy of a `<replicate>` (an element `j`
/// inside `<replicate count="3">` gives `j0`, `j1`, `j2`: its name, then for each
/// replicate around it, innermost first, the replicate's `sep` and the copy's index
/// padded with zeros to the digits of its count), or an element of a part that an
/// `<attach>` of `m` brings in (the attach's `prefix`, which may be empty, then a name
/// of the part's model file, found the same way; a part that cannot be read on its
/// own, or one attached inside a replicate, is taken to hold any name with that
/// prefix).
///
/// Time: O(N) for `m` of N elements, plus reading the part of an attach whose prefix
/// `name` starts with (called only for a name found nowhere else).
fn named_by_expansion(m: &Model, ns: Namespace, name: &str) -> bool {
    let Some(root) = m.node_by_id(m.root().id()) else { return false };
    let mut levels = Vec::new();
    expansion_makes(m, root, ns, name, &mut levels)
}

/// [`named_by_expansion`] below `node`, with `levels` the (count, sep) of the
/// replicates around it, outermost first.
fn expansion_makes<'n>(
    m: &Model,
    node: &'n Node,
    ns: Namespace,
    name: &str,
    levels: &mut Vec<(i64, &'n str)>,
) -> bool {
    let kind = node.kind();
    let text = |attr: &str| kind.attr_index(attr).and_then(|i| node.attr(i));
    match kind.role() {
        Some(Role::Attach) => {
            let prefix = text("prefix").and_then(Value::as_str).unwrap_or("");
            if let Some(inner) = name.strip_prefix(prefix) {
                // Inside a replicate the part's names take suffixes too: not
                // looked into.
                if !levels.is_empty() {
                    return true;
                }
                match attached_part(m, text("model")) {
                    Some(part) => {
                        if part.find(ns, inner).is_some() || named_by_expansion(&part, ns, inner) {
                            return true;
                        }
                    }
                    // A part that cannot be read here: its names are unknown.
                    None => return true,
                }
            }
        }
        Some(Role::Replicate) => {
            let count = text("count").and_then(Value::as_int).unwrap_or(0);
            let sep = text("sep").and_then(Value::as_str).unwrap_or("");
            levels.push((count, sep));
            let found = node.children().iter().any(|c| expansion_makes(m, c, ns, name, levels));
            levels.pop();
            return found;
        }
        _ => {}
    }
    if !levels.is_empty()
        && kind.namespace() == Some(ns)
        && node.identifier().is_some_and(|base| is_replicated_name(name, base, levels))
    {
        return true;
    }
    node.children().iter().any(|c| expansion_makes(m, c, ns, name, levels))
}

/// The part an `<attach model="...">` of `m` brings in: its asset `<model>`'s file,
/// read on its own; `None` when it cannot be read here (its own files are not at
/// hand, say).
fn attached_part(m: &Model, model: Option<&Value>) -> Option<Model> {
    let asset = match model? {
        Value::Reference(Reference::Name(n)) => m.node_by_id(m.find(Namespace::Model, n)?.id())?,
        Value::Reference(Reference::Element(id)) => m.node_by_id(*id)?,
        _ => return None,
    };
    let kind = asset.kind();
    let Some(Value::File(file)) = kind.attr_index("file").and_then(|i| asset.attr(i)) else {
        return None;
    };
    Model::from_xml_str(std::str::from_utf8(file.contents()).ok()?).ok()
}

/// Whether `name` is the name of a copy of `base` made by the replicates `levels`
/// (count, sep; outermost first): `base`, then each level's `sep` and index (padded
/// with zeros to the digits of its count), innermost first, so the outermost last.
/// The names of the inner levels alone (`j05` for `j05-1` of a replicate of 10 inside
/// one of 2 with `sep="-"`) compile too: MuJoCo copies what refers to them with the
/// outer levels.
fn is_replicated_name(name: &str, base: &str, levels: &[(i64, &str)]) -> bool {
    (0..=levels.len()).any(|outer| strips_to(name, base, &levels[outer..]))
}

/// Whether `name` is `base` followed by the suffixes of `levels` (outermost first:
/// its suffix is the last).
fn strips_to(name: &str, base: &str, levels: &[(i64, &str)]) -> bool {
    let mut rest = name;
    for (count, sep) in levels {
        let digits = count.max(&1).to_string().len();
        let Some(cut) = rest.len().checked_sub(digits) else { return false };
        let Some(index) = rest.get(cut..) else { return false };
        if !index.bytes().all(|b| b.is_ascii_digit())
            || index.parse::<i64>().map_or(true, |i| i >= *count)
        {
            return false;
        }
        let Some(before) = rest[..cut].strip_suffix(sep) else { return false };
        rest = before;
    }
    rest == base
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
    /// joint after a ball joint), keys longer than the model, arrays shorter than
    /// MuJoCo accepts (`pos="1 2"`; the minimums probed from MuJoCo 4.0.0), and keys
    /// of attached models written without `merge_keyframes` ([`ProblemKind::UncomposedKey`];
    /// see [`Model::check_with`]). Empty when none is found; this is not a full MuJoCo
    /// compile. Each problem names its element as the writer writes it.
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
        self.check_with(&WriteOptions::default())
    }

    /// [`Model::check`] of the model as it will be written with `options`: with
    /// [`WriteOptions::merge_keyframes`], each model's keys are held to that model's
    /// own joints and actuators (the composed key takes its part from each); without,
    /// every key is written as it is and held to the composed model.
    ///
    /// Time: as [`Model::check`].
    pub fn check_with(&self, options: &WriteOptions) -> Vec<Problem> {
        let mut problems = Vec::new();
        let name = self.name();
        let mut walk = Walk::new(self);
        let mut open: Vec<Open<'_>> = Vec::new();
        let mut classes = super::layout::ClassesInForce::default();
        let mut suggesters = Suggesters::new();
        while let Some(step) = walk.next() {
            match step {
                Step::Enter(item) => {
                    let inst = &walk.insts.list[item.inst];
                    let m = inst.model;
                    let node = item.node;
                    let class = classes.enter(m, item.inst, node);
                    let found = unresolved_references(m, item.inst, node, &mut suggesters);
                    if !found.is_empty() {
                        let loc = Loc::scoped(inst.frames.clone(), node.id(), name);
                        let path = problem_path(&walk.insts, &item);
                        problems.extend(found.into_iter().map(|kind| Problem {
                            loc: loc.clone(),
                            path: path.clone(),
                            kind,
                        }));
                    }
                    // Degrees of freedom (the layout's own count is in Model::layout).
                    let in_body = open.last().is_some_and(|o| o.node.kind().is(Role::Body));
                    let role = node.kind().role();
                    if matches!(role, Some(Role::Joint | Role::Freejoint)) && in_body {
                        if let Some(top) = open.last_mut() {
                            top.joints.add(joint_type(m, node, class));
                        }
                    }
                    if gives_mass(m, node) {
                        if let Some(top) = open.last_mut() {
                            top.massive = true;
                        }
                    }
                    open.push(Open {
                        inst: item.inst,
                        node,
                        joints: BodyJoints::default(),
                        massive: false,
                    });
                }
                Step::Leave(item) => {
                    classes.leave();
                    let Some(o) = open.pop() else { continue };
                    let is_body = o.node.kind().is(Role::Body);
                    let massless = massless_moving_body(is_body, &o.joints, o.massive);
                    let found: Vec<ProblemKind> =
                        massless.into_iter().chain(o.joints.problems()).collect();
                    if !found.is_empty() {
                        let i = &walk.insts.list[o.inst];
                        let loc = Loc::scoped(i.frames.clone(), o.node.id(), name);
                        let path = problem_path(&walk.insts, &item);
                        problems.extend(found.into_iter().map(|kind| Problem {
                            loc: loc.clone(),
                            path: path.clone(),
                            kind,
                        }));
                    }
                    // Mass below counts for the parent only through a body that does
                    // not move on its own (welded to it): MuJoCo wants a moving body's
                    // own mass, or that of bodies welded to it, above zero.
                    if o.massive && !(is_body && o.joints.moves) {
                        if let Some(top) = open.last_mut() {
                            top.massive = true;
                        }
                    }
                }
            }
        }
        self.key_lengths(options, &mut problems);
        self.short_arrays(&mut problems);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::Element;

    /// The node of the element `name` of namespace `ns` in `m`.
    fn node<'m>(m: &'m Model, ns: Namespace, name: &str) -> &'m Node {
        let loc = m.find(ns, name).expect("the element exists");
        m.node_by_id(loc.id()).expect("its node")
    }

    #[test]
    fn body_joints_count_degrees_of_freedom_by_joint_type() {
        let mut joints = BodyJoints::default();
        assert!(!joints.moves);
        joints.add(JointType::Free);
        assert_eq!((joints.moves, joints.dofs), (true, 6));
        assert_eq!(joints.problems(), []);
        joints.add(JointType::Slide);
        assert_eq!(joints.dofs, 7);
        assert_eq!(joints.problems(), [ProblemKind::TooManyDofs { dofs: 7 }]);
        let mut three = BodyJoints::default();
        for ty in [JointType::Ball, JointType::Slide, JointType::Slide, JointType::Slide] {
            three.add(ty);
        }
        assert_eq!((three.dofs, three.problems()), (6, vec![]));
    }

    #[test]
    fn only_a_hinge_or_ball_after_a_ball_is_a_rotation_after_ball() {
        let after_ball = |second: JointType| {
            let mut joints = BodyJoints::default();
            joints.add(JointType::Ball);
            joints.add(second);
            joints.problems()
        };
        assert_eq!(after_ball(JointType::Hinge), [ProblemKind::RotationAfterBall]);
        assert_eq!(after_ball(JointType::Ball), [ProblemKind::RotationAfterBall]);
        assert_eq!(after_ball(JointType::Slide), []);
        let mut before = BodyJoints::default();
        before.add(JointType::Hinge);
        before.add(JointType::Ball);
        assert_eq!(before.problems(), []);
    }

    #[test]
    fn only_a_moving_body_without_mass_is_massless() {
        let mut moving = BodyJoints::default();
        moving.add(JointType::Hinge);
        let still = BodyJoints::default();
        assert_eq!(
            massless_moving_body(true, &moving, false),
            Some(ProblemKind::MasslessMovingBody)
        );
        assert_eq!(massless_moving_body(true, &moving, true), None);
        assert_eq!(massless_moving_body(true, &still, false), None);
        // Only what the caller says is a body is held to the rule.
        assert_eq!(massless_moving_body(false, &moving, false), None);
    }

    #[test]
    fn an_inertial_with_mass_and_a_geom_not_of_mass_0_give_mass() {
        let m = Model::from_xml_str(
            r#"<mujoco><worldbody>
                 <body name="a"><inertial pos="0 0 0" mass="1" diaginertia="1 1 1"/></body>
                 <body name="b"><inertial pos="0 0 0" mass="0" diaginertia="1 1 1"/></body>
                 <geom name="dense" size="1"/><geom name="weightless" size="1" mass="0"/>
                 <site name="s"/>
               </worldbody></mujoco>"#,
        )
        .unwrap();
        let inertial =
            |body: &str| node(&m, Namespace::Body, body).children().iter().next().unwrap();
        assert!(gives_mass(&m, inertial("a")));
        assert!(!gives_mass(&m, inertial("b")));
        assert!(gives_mass(&m, node(&m, Namespace::Geom, "dense")));
        assert!(!gives_mass(&m, node(&m, Namespace::Geom, "weightless")));
        assert!(!gives_mass(&m, node(&m, Namespace::Site, "s")));
    }

    #[test]
    fn references_by_name_resolve_in_their_model_or_are_dangling_with_suggestions() {
        let mut m = Model::new("m");
        let b = m.add_mut(&m.worldbody(), Element::new("body").attr("name", "b")).unwrap();
        m.add_mut(&b, Element::new("joint").attr("name", "hinge")).unwrap();
        m.add_mut(&m.actuator(), Element::new("motor").attr("name", "ok").attr("joint", "hinge"))
            .unwrap();
        m.add_mut(&m.actuator(), Element::new("motor").attr("name", "typo").attr("joint", "hinj"))
            .unwrap();
        let mut suggesters = Suggesters::new();
        let ok = node(&m, Namespace::Actuator, "ok");
        assert_eq!(unresolved_references(&m, 0, ok, &mut suggesters), []);
        let typo = node(&m, Namespace::Actuator, "typo");
        assert_eq!(
            unresolved_references(&m, 0, typo, &mut suggesters),
            [ProblemKind::DanglingReference {
                attribute: "joint",
                name: "hinj".into(),
                namespace: Namespace::Joint,
                suggestions: vec!["hinge".into()],
            }]
        );
    }

    #[test]
    fn a_replicated_name_is_the_base_then_each_level_s_sep_and_padded_index() {
        // As MuJoCo 4.0.0 names them (checked with the wheel).
        assert!(is_replicated_name("j0", "j", &[(3, "")]));
        assert!(is_replicated_name("j2", "j", &[(3, "")]));
        assert!(!is_replicated_name("j3", "j", &[(3, "")]));
        assert!(is_replicated_name("j07", "j", &[(10, "")]));
        assert!(!is_replicated_name("j7", "j", &[(10, "")]));
        assert!(is_replicated_name("j-1", "j", &[(2, "-")]));
        // Nested (outer 2 with sep "-", inner 10): the inner index first, the outer
        // last; the inner levels alone name copies too.
        let nested = [(2, "-"), (10, "")];
        assert!(is_replicated_name("j09-1", "j", &nested));
        assert!(is_replicated_name("j05", "j", &nested));
        assert!(!is_replicated_name("j00-2", "j", &nested));
        assert!(!is_replicated_name("j9-0", "j", &nested));
        assert!(!is_replicated_name("j-1", "j", &nested));
        assert!(!is_replicated_name("j0", "j", &nested));
        assert!(!is_replicated_name("k0", "j", &[(3, "")]));
    }

    #[test]
    fn references_to_replicated_copies_and_attached_parts_are_not_dangling() {
        let m = Model::from_xml_str(
            r#"<mujoco><worldbody>
                 <replicate count="3" offset="1 0 0">
                   <body name="b"><joint name="j"/><geom size=".1"/></body>
                 </replicate>
               </worldbody>
               <actuator><motor name="copy" joint="j2"/><motor name="base" joint="j"/>
                 <motor name="beyond" joint="j3"/></actuator></mujoco>"#,
        )
        .unwrap();
        let problems = |name: &str| {
            let mut suggesters = Suggesters::new();
            unresolved_references(&m, 0, node(&m, Namespace::Actuator, name), &mut suggesters).len()
        };
        assert_eq!(problems("copy"), 0);
        assert_eq!(problems("base"), 0);
        assert_eq!(problems("beyond"), 1);
    }

    #[test]
    fn a_resolved_reference_to_a_removed_element_is_missing_or_removed_as_it_is_required() {
        let m = Model::from_xml_str(
            r#"<mujoco><worldbody>
                 <body name="a"><joint name="j"/><geom size="1"/></body>
                 <body name="b"><geom size="1"/></body>
               </worldbody>
               <contact><exclude body1="a" body2="b"/></contact>
               <actuator><motor name="mo" joint="j"/></actuator></mujoco>"#,
        )
        .unwrap();
        let a = m.find(Namespace::Body, "a").unwrap();
        let removed = m.remove(&a).unwrap();
        let mut suggesters = Suggesters::new();
        let motor = node(&removed, Namespace::Actuator, "mo");
        assert_eq!(
            unresolved_references(&removed, 0, motor, &mut suggesters),
            [ProblemKind::RemovedReference { attribute: "joint" }]
        );
        let contact = removed.section("contact").unwrap();
        let exclude = removed.node_by_id(contact.id()).unwrap().children().iter().next().unwrap();
        assert_eq!(
            unresolved_references(&removed, 0, exclude, &mut suggesters),
            [ProblemKind::MissingRequired { attribute: "body1" }]
        );
    }
}
