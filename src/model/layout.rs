//! The physics layout of a composed model, as MuJoCo numbers it: every joint with its
//! type and its `qpos` and `qvel` addresses, every actuator with its controls and
//! activations, every mocap body, and the keys. Composed keyframes
//! ([`WriteOptions::merge_keyframes`](crate::WriteOptions)) and [`Model::check`]'s key
//! lengths are computed from it; the binding crate's tests check it against MuJoCo's
//! compiled model (`jnt_qposadr`, `jnt_dofadr`, `nq`, `nv`, `nu`, `na`).
//!
//! MuJoCo numbers bodies in the order the written model starts them (the order of
//! [`Model::walk`]), and joints body by body: a body's own joints (those inside its
//! `<frame>`s included) before its children's, wherever they stand among its child
//! elements; actuators in the order they are written. `<frame>`s are transparent,
//! and a `<replicate>` holds its content `count` times, copy after copy (nested ones
//! inside out). Elements that make joints MuJoCo's compiler generates (`<attach>` of
//! an asset model, `<composite>`, `<flexcomp>`) are not expanded: they are listed in
//! [`Layout::unexpanded`], and the layout is exact only where that list is empty.
//!
//! A `<replicate>`'s copies are counted before any is listed (nested counts
//! multiplied, saturating): copies holding no joint and no mocap body are never
//! listed, and a layout listing more than [`MAX_LAYOUT_ENTRIES`] joints and mocap
//! bodies is refused. The sizes alone ([`Model::layout_sizes`], what
//! [`Model::check`] needs) are counted, never listed, whatever the counts.

use std::collections::HashMap;

use crate::error::{EditError, ErrorKind};
use crate::model::pose::{self, Angles, IDENTITY, Pose};
use crate::model::tree::{ElementId, Node};
use crate::model::{Loc, Model, Step, Walk, settings};
use crate::schema::{ElementKind, Role};
use crate::value::{Reference, Value};

/// The most joints and mocap bodies (each `<replicate>` copy counted) that
/// [`Model::layout`] lists one by one: a million (each listed joint takes on the
/// order of a hundred bytes, so a full layout stays within a few hundred megabytes).
/// MuJoCo itself has no bound of its own below its sizes' `int` (2,147,483,647),
/// where it refuses a `count` ("number is too large").
pub const MAX_LAYOUT_ENTRIES: usize = 1_000_000;

/// A joint's type, as MuJoCo compiles it (the element's own `type`, else its default
/// classes', else a hinge).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum JointType {
    /// A free joint: 7 positions (position, quaternion), 6 velocities.
    Free,
    /// A ball joint: 4 positions (quaternion), 3 velocities.
    Ball,
    /// A slide joint: 1 and 1.
    Slide,
    /// A hinge joint: 1 and 1.
    Hinge,
}

impl JointType {
    /// The positions (`qpos` entries) of a joint of this type.
    ///
    /// Time: O(1).
    pub const fn nq(self) -> usize {
        match self {
            JointType::Free => 7,
            JointType::Ball => 4,
            JointType::Slide | JointType::Hinge => 1,
        }
    }

    /// The degrees of freedom (`qvel` entries) of a joint of this type.
    ///
    /// Time: O(1).
    pub const fn nv(self) -> usize {
        match self {
            JointType::Free => 6,
            JointType::Ball => 3,
            JointType::Slide | JointType::Hinge => 1,
        }
    }

    /// Every joint type, in MuJoCo's numbering (`mjJNT_FREE` 0, `mjJNT_BALL` 1,
    /// `mjJNT_SLIDE` 2, `mjJNT_HINGE` 3: `ALL[t]` is the type of a compiled model's
    /// `jnt_type` `t`).
    pub const ALL: [JointType; 4] =
        [JointType::Free, JointType::Ball, JointType::Slide, JointType::Hinge];

    /// The type a joint's `type` keyword names (`"free"`, `"ball"`, `"slide"`,
    /// `"hinge"`), or `None` for any other word.
    ///
    /// ```
    /// use mjcf::JointType;
    /// assert_eq!(JointType::from_keyword("ball"), Some(JointType::Ball));
    /// assert_eq!(JointType::from_keyword("Ball"), None);
    /// ```
    ///
    /// Time: O(1).
    pub fn from_keyword(word: &str) -> Option<JointType> {
        JointType::ALL.into_iter().find(|t| t.keyword() == word)
    }

    /// The `type` keyword of this type (`"free"`, `"ball"`, `"slide"`, `"hinge"`).
    ///
    /// Time: O(1).
    pub fn keyword(self) -> &'static str {
        match self {
            JointType::Free => "free",
            JointType::Ball => "ball",
            JointType::Slide => "slide",
            JointType::Hinge => "hinge",
        }
    }

    /// The type of MuJoCo's number for it (a compiled model's `jnt_type`: see
    /// [`JointType::ALL`]), or `None` for a number MuJoCo does not use.
    ///
    /// ```
    /// use mjcf::JointType;
    /// assert_eq!(JointType::from_mujoco(0), Some(JointType::Free));
    /// assert_eq!(JointType::from_mujoco(4), None);
    /// ```
    ///
    /// Time: O(1).
    pub fn from_mujoco(number: i64) -> Option<JointType> {
        usize::try_from(number).ok().and_then(|i| JointType::ALL.get(i).copied())
    }

    /// MuJoCo's number for this type (its `mjtJoint`, a compiled model's `jnt_type`).
    ///
    /// Time: O(1).
    pub fn mujoco_number(self) -> i32 {
        match self {
            JointType::Free => 0,
            JointType::Ball => 1,
            JointType::Slide => 2,
            JointType::Hinge => 3,
        }
    }
}

/// A joint of the layout.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct LayoutJoint {
    /// The joint element (for a joint inside a `<replicate>`, each copy has the same
    /// locator).
    pub loc: Loc,
    /// Its type.
    pub joint_type: JointType,
    /// The address of its first position in `qpos` (MuJoCo's `jnt_qposadr`).
    pub qpos: usize,
    /// The address of its first velocity in `qvel` (MuJoCo's `jnt_dofadr`).
    pub dof: usize,
    /// The instance (model of the composition, in walk order) it belongs to.
    pub(crate) inst: usize,
    /// Its addresses among its own model's positions and velocities.
    pub(crate) own_qpos: usize,
    pub(crate) own_dof: usize,
    /// MuJoCo's default positions (`qpos0`): a hinge's or slide's `ref`, a ball's
    /// unit quaternion, a free joint's body pose in the world.
    pub(crate) qpos0: Vec<f64>,
}

/// An actuator of the layout.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct LayoutActuator {
    /// The actuator element.
    pub loc: Loc,
    /// The address of its first control in `ctrl`.
    pub ctrl: usize,
    /// Its controls (1, or 2 for a `<pid>`).
    pub nctrl: usize,
    /// The address of its first activation in `act`.
    pub act: usize,
    /// Its activations.
    pub nact: usize,
    pub(crate) inst: usize,
    pub(crate) own_ctrl: usize,
    pub(crate) own_act: usize,
}

/// A mocap body of the layout.
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct LayoutMocap {
    /// The body element.
    pub loc: Loc,
    /// Its index among the mocap bodies (`mocap_pos` row).
    pub index: usize,
    pub(crate) inst: usize,
    pub(crate) own: usize,
    /// Its pose in the world, as compiled.
    pub(crate) pose: Pose,
}

/// The physics layout of a composed model (see the module documentation), from
/// [`Model::layout`].
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct Layout<'a> {
    /// Every joint, in MuJoCo's order.
    pub joints: Vec<LayoutJoint>,
    /// Every actuator, in MuJoCo's order.
    pub actuators: Vec<LayoutActuator>,
    /// Every mocap body, in MuJoCo's order.
    pub mocap: Vec<LayoutMocap>,
    /// Positions (`nq`).
    pub nq: usize,
    /// Degrees of freedom (`nv`).
    pub nv: usize,
    /// Controls (`nu`).
    pub nu: usize,
    /// Activations (`na`).
    pub na: usize,
    /// Elements whose generated joints, bodies or actuators the layout does not count
    /// (`<attach>`, `<composite>`, `<flexcomp>`): the layout is exact when empty.
    pub unexpanded: Vec<Loc>,
    /// The keys, with the instance each belongs to, in document order.
    pub(crate) keys: Vec<(usize, &'a Node, Loc)>,
    /// Per instance: the pose of its model's world in the composed world (the pose of
    /// the attachment frame it hangs from; identity for the root model).
    pub(crate) origins: HashMap<usize, Pose>,
}

impl LayoutJoint {
    /// Whether the joint is the model's own (of its own tree, an attachment frame's
    /// joints included), not of a model attached to it: the joints its own keys
    /// hold values for.
    ///
    /// Time: O(1).
    pub fn is_own(&self) -> bool {
        self.inst == 0
    }
}

impl Layout<'_> {
    /// The pose of instance `inst`'s world in the composed world.
    pub(crate) fn origin(&self, inst: usize) -> Pose {
        self.origins.get(&inst).copied().unwrap_or(IDENTITY)
    }
}

/// A body of the compiled model (or the world, or the content of a `<replicate>`):
/// its own joints and whether it is a mocap body, then its child bodies. MuJoCo
/// numbers a body's joints before those of its children, wherever they stand among
/// its child elements, and bodies in the order they start.
#[derive(Default)]
struct BodyRec {
    /// The joints, each with the pose of its body in the world.
    joints: Vec<(LayoutJoint, Pose)>,
    mocap: Option<LayoutMocap>,
    children: Vec<Child>,
}

enum Child {
    Body(usize),
    /// A `<replicate>`'s content (a record of its own), `count` copies, each moved by
    /// `step` from the one before, about the replicate's pose `at`.
    Repeat {
        rec: usize,
        count: usize,
        at: Pose,
        step: Pose,
    },
}

/// An open element of the walk.
struct Open<'a> {
    inst: usize,
    node: &'a Node,
    /// Its pose in the world (for a body, frame or attachment frame: its own; else
    /// its parent's).
    pose: Pose,
    /// The body record its content belongs to.
    rec: usize,
}

/// The element's own class (a resolved `class` attribute).
pub(crate) fn class_of(node: &Node) -> Option<ElementId> {
    let c = node.kind().class_attr()?;
    match node.attr(c) {
        Some(Value::Reference(Reference::Element(id))) => Some(*id),
        _ => None,
    }
}

/// The default class in force for each element as a walk of the composed model
/// descends: the element's own class, else the nearest `childclass` above it in its
/// own model (an attached model starts without one), else its model's root class.
/// One per walk: [`ClassesInForce::enter`] at each element entered,
/// [`ClassesInForce::leave`] at each one left.
#[derive(Default)]
pub(crate) struct ClassesInForce {
    /// Per open element: its instance and the `childclass` in force for its content.
    open: Vec<(usize, Option<ElementId>)>,
}

impl ClassesInForce {
    /// The class in force for `node` (of walk instance `inst`, whose model is
    /// `model`), entered now.
    pub(crate) fn enter(&mut self, model: &Model, inst: usize, node: &Node) -> Option<ElementId> {
        let inherited = self.open.last().filter(|(i, _)| *i == inst).and_then(|(_, c)| *c);
        self.open.push((inst, childclass_of(node).or(inherited)));
        class_of(node).or(inherited).or_else(|| root_class(model))
    }

    /// The element entered last is left.
    pub(crate) fn leave(&mut self) {
        self.open.pop();
    }
}

/// The root default class of `model` (what an element without a class uses).
pub(crate) fn root_class(model: &Model) -> Option<ElementId> {
    model.root.child_of_kind(ElementKind::DEFAULT).map(Node::id)
}

/// The default class in force for `node` of `model` (as [`ClassesInForce`] finds it
/// in a walk): its own class, else the nearest `childclass` above it, else the
/// model's root class.
///
/// Time: O(depth · log n), a parent lookup per level.
pub(crate) fn class_in_force(model: &Model, node: &Node) -> Option<ElementId> {
    if let Some(c) = class_of(node) {
        return Some(c);
    }
    let mut cur = model.index.parent(node.id());
    while let Some(id) = cur {
        if let Some(c) = model.node_by_id(id).and_then(childclass_of) {
            return Some(c);
        }
        cur = model.index.parent(id);
    }
    root_class(model)
}

/// The class an element's `childclass` gives its content, if it sets one.
pub(crate) fn childclass_of(node: &Node) -> Option<ElementId> {
    let c = node.kind().attr_index("childclass")?;
    match node.attr(c) {
        Some(Value::Reference(Reference::Element(id))) => Some(*id),
        _ => None,
    }
}

/// The value of `attr` for `node`: its own, else that of the defaults of its tag in
/// `class` and the classes above it.
pub(crate) fn effective<'m>(
    model: &'m Model,
    node: &'m Node,
    class: Option<ElementId>,
    attr: &str,
) -> Option<&'m Value> {
    let kind = node.kind();
    kind.attr_index(attr)
        .and_then(|i| node.attr(i))
        .or_else(|| from_classes(model, kind, class, attr))
}

/// The value of `attr` the defaults of `kind`'s tag in `class` and the classes above it
/// give (a tendon's, `<fixed>` or `<spatial>`, are the class's `<tendon>`).
pub(crate) fn from_classes<'m>(
    model: &'m Model,
    kind: ElementKind,
    class: Option<ElementId>,
    attr: &str,
) -> Option<&'m Value> {
    class_defaults(model, kind, class).find_map(|d| d.attr(d.kind().attr_index(attr)?))
}

/// The defaults an element of `kind` takes from `class` and the classes above it,
/// nearest first: each class's element of its tag (a tendon's, `<fixed>` or
/// `<spatial>`, is the class's `<tendon>`).
pub(crate) fn class_defaults<'m>(
    model: &'m Model,
    kind: ElementKind,
    class: Option<ElementId>,
) -> impl Iterator<Item = &'m Node> + 'm {
    let root = model.root.child_of_kind(ElementKind::DEFAULT);
    class_chain_defaults(model, kind, class, root)
}

/// [`class_defaults`] of `class`, else (`None`) of the model's root class: the
/// defaults of an element whose class in force is `class` or the root class.
pub(crate) fn class_defaults_in_force<'m>(
    model: &'m Model,
    kind: ElementKind,
    class: Option<ElementId>,
) -> impl Iterator<Item = &'m Node> + 'm {
    let root = model.root.child_of_kind(ElementKind::DEFAULT);
    class_chain_defaults(model, kind, class.or(root.map(Node::id)), root)
}

/// [`class_defaults`], the model's root class (`root`) given.
fn class_chain_defaults<'m>(
    model: &'m Model,
    kind: ElementKind,
    class: Option<ElementId>,
    root: Option<&'m Node>,
) -> impl Iterator<Item = &'m Node> + 'm {
    // The root class, where most chains end (and most start), is found without a
    // lookup by id (which walks the index up and the tree down).
    let by_id = move |id: ElementId| match root {
        Some(r) if r.id() == id => Some(r),
        _ => model.node_by_id(id),
    };
    let classes = std::iter::successors(class, move |id| {
        if root.is_some_and(|r| r.id() == *id) {
            return None; // the root class is outermost
        }
        model
            .index
            .parent(*id)
            .filter(|p| by_id(*p).is_some_and(|n| n.kind().is(Role::DefaultClass)))
    });
    classes.filter_map(move |id| {
        let class_node = by_id(id)?;
        class_node.kind().defaults_for(kind).and_then(|k| class_node.child_of_kind(k))
    })
}

/// The joint type of a joint element, as written or as its classes set it: `free`,
/// `ball`, `slide` or `hinge` (the default); a `<freejoint>` is free.
pub(crate) fn joint_type(model: &Model, node: &Node, class: Option<ElementId>) -> JointType {
    if node.kind().is(Role::Freejoint) {
        return JointType::Free;
    }
    let of = |v: Option<&Value>| match v {
        // A keyword names one of the four (the schema's); any other word is a hinge.
        Some(Value::Keyword(k)) => Some(JointType::from_keyword(k).unwrap_or(JointType::Hinge)),
        _ => None,
    };
    let explicit = node.kind().attr_index("type").and_then(|i| node.attr(i));
    if let Some(t) = of(explicit) {
        return t;
    }
    // The class chain: the element's class, then its ancestors in the default tree.
    let typed = |j: &Node| of(j.kind().attr_index("type").and_then(|i| j.attr(i)));
    if let Some(t) = class_defaults(model, node.kind(), class).find_map(typed) {
        return t;
    }
    JointType::Hinge
}

/// The controls and activations of an actuator element, as MuJoCo 4.0 counts them
/// (probed with MuJoCo; the binding crate's tests hold the layout to MuJoCo's).
fn actuator_size(model: &Model, node: &Node, class: Option<ElementId>) -> (usize, usize) {
    let value = |attr: &str| effective(model, node, class, attr);
    // Any of its numbers above 0 (`inductance="0 0.001"` counts).
    let positive = |attr: &str| {
        value(attr).is_some_and(|v| match v.as_floats() {
            Some(xs) => xs.iter().any(|x| *x > 0.0),
            None => v.as_float().is_some_and(|x| x > 0.0),
        })
    };
    let set = |attr: &str| value(attr).is_some();
    let dyntype = value("dyntype").and_then(Value::as_str);
    let explicit = value("actdim").and_then(Value::as_int).and_then(|n| usize::try_from(n).ok());
    let role = node.kind().role();
    let act = match role {
        Some(Role::ActuatorStateful) => 1,
        Some(Role::ActuatorGeneral) => usize::from(dyntype.is_some_and(|d| d != "none")),
        Some(Role::ActuatorFiltered) => usize::from(positive("timeconst")),
        Some(Role::ActuatorDcmotor) => [positive("inductance"), set("thermal"), set("lugre")]
            .into_iter()
            .map(usize::from)
            .sum(),
        Some(Role::ActuatorPid) => usize::from(positive("ki")) + usize::from(positive("slewmax")),
        _ => 0,
    };
    // One control per word of `input` (`pos vel`); a <pid> takes both by default.
    let words = value("input").and_then(Value::as_str).map(|s| s.split_whitespace().count());
    let ctrl = words.unwrap_or(if role == Some(Role::ActuatorPid) { 2 } else { 1 });
    (ctrl, explicit.unwrap_or(act))
}

impl Model {
    /// The physics layout of the composed model: its joints with their `qpos` and
    /// `qvel` addresses, its actuators, its mocap bodies (see [`Layout`]).
    ///
    /// Time: O(N) for a composed model of N elements (O(N · c) where classes c deep
    /// are followed for joint types and actuator settings), plus the copies a
    /// `<replicate>` makes of joints and mocap bodies (copies without any are not
    /// made).
    ///
    /// # Errors
    /// [`ErrorKind::TooLarge`] if the layout would list more than
    /// [`MAX_LAYOUT_ENTRIES`] joints and mocap bodies (`<replicate>` copies
    /// counted); nothing is listed before the count.
    ///
    /// # Examples
    /// ```
    /// use mjcf::{JointType, Model, element};
    /// let mut robot = Model::new("robot");
    /// let torso = robot.add_mut(&robot.worldbody(), element!("body", name = "torso"))?;
    /// robot.add_mut(&torso, element!("joint", name = "hip", type = "ball"))?;
    /// robot.add_mut(&torso, element!("joint", name = "knee"))?;
    /// let mut arena = Model::new("arena");
    /// let a = arena.attach_mut(&arena.worldbody(), &robot)?;
    /// arena.add_mut(a.frame(), element!("freejoint"))?;
    /// let layout = arena.layout()?;
    /// let joints: Vec<_> = layout.joints.iter().map(|j| (j.joint_type, j.qpos, j.dof)).collect();
    /// assert_eq!(joints, [(JointType::Free, 0, 0), (JointType::Ball, 7, 6), (JointType::Hinge, 11, 9)]);
    /// assert_eq!((layout.nq, layout.nv), (12, 10));
    /// # Ok::<(), mjcf::Error>(())
    /// ```
    pub fn layout(&self) -> Result<Layout<'_>, EditError> {
        let gathered = gather(self);
        let (joints, mocap) = in_mujoco_order(&gathered.recs).map_err(|size| {
            let what = "joints and mocap bodies with their <replicate> copies";
            EditError::new(
                ErrorKind::TooLarge { what, size, limit: MAX_LAYOUT_ENTRIES },
                String::new(),
            )
        })?;
        Ok(numbered(gathered, joints, mocap))
    }

    /// The sizes of the layout without listing it: per instance of the composition
    /// (0 for this model, then attached models in walk order) its positions,
    /// velocities, activations, controls and mocap bodies, each `<replicate>` copy
    /// counted (saturating at `usize::MAX`); and the keys. Never refused.
    ///
    /// Time: O(N) for a composed model of N elements (as [`Model::layout`], without
    /// the copies).
    pub(crate) fn layout_sizes(&self) -> LayoutSizes<'_> {
        let gathered = gather(self);
        let mut per_inst: HashMap<usize, [usize; 5]> = HashMap::new();
        let mut add = |inst: usize, k: usize, n: usize| {
            let slot = &mut per_inst.entry(inst).or_default()[k];
            *slot = slot.saturating_add(n);
        };
        // Each record once, with the number of copies it is made in.
        let mut todo = vec![(0, 1usize)];
        while let Some((r, copies)) = todo.pop() {
            let rec = &gathered.recs[r];
            for (j, _) in &rec.joints {
                add(j.inst, 0, j.joint_type.nq().saturating_mul(copies));
                add(j.inst, 1, j.joint_type.nv().saturating_mul(copies));
            }
            if let Some(b) = &rec.mocap {
                add(b.inst, 4, copies);
            }
            todo.extend(rec.children.iter().map(|c| match *c {
                Child::Body(c) => (c, copies),
                Child::Repeat { rec, count, .. } => (rec, copies.saturating_mul(count)),
            }));
        }
        for a in &gathered.actuators {
            add(a.inst, 2, a.nact);
            add(a.inst, 3, a.nctrl);
        }
        LayoutSizes { per_inst, keys: gathered.keys }
    }
}

/// What [`Model::layout_sizes`] counts.
pub(crate) struct LayoutSizes<'a> {
    /// Per instance: positions, velocities, activations, controls, mocap bodies.
    pub(crate) per_inst: HashMap<usize, [usize; 5]>,
    /// The keys, with the instance each belongs to, in document order.
    pub(crate) keys: Vec<(usize, &'a Node, Loc)>,
}

/// What the walk of the composed model gathers, before MuJoCo's order is applied.
struct Gathered<'a> {
    /// The body records; record 0 is the world.
    recs: Vec<BodyRec>,
    /// The actuators, in document order (MuJoCo's).
    actuators: Vec<LayoutActuator>,
    /// The keys, with their instance.
    keys: Vec<(usize, &'a Node, Loc)>,
    /// Per instance, the pose of its model's world.
    origins: HashMap<usize, Pose>,
    /// The elements whose generated content is not counted.
    unexpanded: Vec<Loc>,
}

/// Walks the composed model once: each body's joints (with their default positions)
/// and mocap flag, its child bodies and replicates, the actuators, the keys and each
/// instance's origin.
fn gather(model: &Model) -> Gathered<'_> {
    let merged = settings::merged(model).ok();
    let compiler =
        merged.as_deref().and_then(|m| m.iter().find(|n| n.kind() == ElementKind::COMPILER));
    let angles = Angles::of(compiler);
    let name = model.name();
    let mut out = Gathered {
        recs: vec![BodyRec::default()],
        actuators: Vec::new(),
        keys: Vec::new(),
        origins: HashMap::new(),
        unexpanded: Vec::new(),
    };
    let mut open: Vec<Open<'_>> = Vec::new();
    let mut classes = ClassesInForce::default();
    let mut walk = Walk::new(model);
    while let Some(step) = walk.next() {
        let item = match step {
            Step::Enter(item) => item,
            Step::Leave(_) => {
                open.pop();
                classes.leave();
                continue;
            }
        };
        let frames = walk.insts.list[item.inst].frames.clone();
        let m = walk.insts.list[item.inst].model;
        let node = item.node;
        let loc = || Loc::scoped(frames.clone(), node.id(), name);
        let parent = open.last();
        let parent_pose = parent.map_or(IDENTITY, |p| p.pose);
        let mut rec = parent.map_or(0, |p| p.rec);
        if parent.is_some_and(|p| p.node.attached().is_some() && p.inst != item.inst) {
            out.origins.entry(item.inst).or_insert(parent_pose);
        }
        let class = classes.enter(m, item.inst, node);
        let in_body = rec != 0 || parent.is_some_and(|p| p.node.kind().is(Role::Replicate));
        let role = node.kind().role();
        let is_body = role == Some(Role::Body);
        let frame_like = node.attached().is_some() || role == Some(Role::Frame);
        let pose = if is_body || frame_like {
            pose::compose(parent_pose, pose::local_pose(node, &angles))
        } else {
            parent_pose
        };
        match role {
            // Joints of a body, directly or inside its `<frame>`s.
            Some(Role::Joint | Role::Freejoint) if in_body => {
                let at = (loc(), item.inst);
                let joint = layout_joint(m, node, class, parent_pose, at, &angles);
                out.recs[rec].joints.push((joint, parent_pose));
            }
            Some(Role::Attach | Role::MakesBodies) => out.unexpanded.push(loc()),
            _ => {}
        }
        if is_body || node.attached().is_some() {
            let new = out.recs.len();
            out.recs.push(BodyRec::default());
            out.recs[rec].children.push(Child::Body(new));
            rec = new;
            let mocap = effective(m, node, class, "mocap").and_then(Value::as_str);
            if is_body && mocap == Some("true") {
                out.recs[rec].mocap =
                    Some(LayoutMocap { loc: loc(), index: 0, inst: item.inst, own: 0, pose });
            }
        }
        if role == Some(Role::Replicate) {
            let new = out.recs.len();
            out.recs.push(BodyRec::default());
            let (count, step) = (replicate_count(node), pose::replicate_step(node, &angles));
            out.recs[rec].children.push(Child::Repeat { rec: new, count, at: pose, step });
            rec = new;
        }
        if role.is_some_and(Role::is_actuator) {
            let (nctrl, nact) = actuator_size(m, node, class);
            out.actuators.push(LayoutActuator {
                loc: loc(),
                ctrl: 0,
                nctrl,
                act: 0,
                nact,
                inst: item.inst,
                own_ctrl: 0,
                own_act: 0,
            });
        }
        if role == Some(Role::Key) {
            out.keys.push((item.inst, node, loc()));
        }
        open.push(Open { inst: item.inst, node, pose, rec });
    }
    out
}

/// A joint element of walk instance `inst` as the layout holds it (addresses not yet
/// given), its body at `body` in the world: its type, and MuJoCo's default positions
/// (`qpos0`): a free joint's body pose, a ball's unit quaternion, a slide's `ref`, a
/// hinge's `ref` in radians (the compiler's `angle` says what it is written in).
fn layout_joint(
    m: &Model,
    node: &Node,
    class: Option<ElementId>,
    body: Pose,
    (loc, inst): (Loc, usize),
    angles: &Angles,
) -> LayoutJoint {
    let joint_type = joint_type(m, node, class);
    let reference = || effective(m, node, class, "ref").and_then(Value::as_float).unwrap_or(0.0);
    let qpos0 = match joint_type {
        JointType::Free => [body.pos.as_slice(), &body.quat].concat(),
        JointType::Ball => vec![1.0, 0.0, 0.0, 0.0],
        JointType::Hinge => vec![angles.radians(reference())],
        JointType::Slide => vec![reference()],
    };
    LayoutJoint { loc, joint_type, qpos: 0, dof: 0, inst, own_qpos: 0, own_dof: 0, qpos0 }
}

/// The copies a `<replicate>` makes: its `count` (none below 1, as MuJoCo 4.0.0
/// compiles `count="0"` and `count="-1"`), 1 if it has none.
fn replicate_count(node: &Node) -> usize {
    node.attr(node.kind().attr_index("count").unwrap_or(usize::MAX))
        .and_then(Value::as_int)
        .map_or(1, |c| usize::try_from(c).unwrap_or(0))
}

/// The joints and mocap bodies each record lists with its copies and its
/// children's (saturating): records are made parent first, so children come later.
fn entries(recs: &[BodyRec]) -> Vec<usize> {
    let mut n = vec![0usize; recs.len()];
    for (r, rec) in recs.iter().enumerate().rev() {
        let own = rec.joints.len().saturating_add(usize::from(rec.mocap.is_some()));
        n[r] = rec.children.iter().fold(own, |sum, c| {
            sum.saturating_add(match *c {
                Child::Body(c) => n[c],
                Child::Repeat { rec, count, .. } => n[rec].saturating_mul(count),
            })
        });
    }
    n
}

/// The joints and mocap bodies in MuJoCo's order: bodies depth first, each body's
/// joints before its children's; a replicate's content once per copy, moved (a free
/// joint's default position and a mocap body's pose with it). Copies of content
/// without joints or mocap bodies are not made; past [`MAX_LAYOUT_ENTRIES`], the
/// count (nothing is listed).
fn in_mujoco_order(recs: &[BodyRec]) -> Result<(Vec<LayoutJoint>, Vec<LayoutMocap>), usize> {
    let n = entries(recs);
    if n[0] > MAX_LAYOUT_ENTRIES {
        return Err(n[0]);
    }
    let (mut joints, mut mocap) = (Vec::new(), Vec::new());
    let mut todo = vec![(0, IDENTITY)];
    while let Some((r, moved)) = todo.pop() {
        for (j, body) in &recs[r].joints {
            let mut j = j.clone();
            if j.joint_type == JointType::Free && moved != IDENTITY {
                let p = pose::compose(moved, *body);
                j.qpos0 = [p.pos.as_slice(), &p.quat].concat();
            }
            joints.push(j);
        }
        if let Some(b) = &recs[r].mocap {
            mocap.push(LayoutMocap { pose: pose::compose(moved, b.pose), ..b.clone() });
        }
        // Children in reverse onto the stack, so the first comes out first.
        for child in recs[r].children.iter().rev() {
            match *child {
                Child::Body(c) => todo.push((c, moved)),
                // Content listing nothing is not copied.
                Child::Repeat { rec, .. } if n[rec] == 0 => {}
                Child::Repeat { rec, count, at, step } => {
                    // At most MAX_LAYOUT_ENTRIES copies: each lists something.
                    let back = pose::inverse(at);
                    let mut shifts = Vec::with_capacity(count);
                    let mut shift = IDENTITY;
                    for _ in 0..count {
                        // The copy's transform in the world: at · shift · at⁻¹.
                        let copy = pose::compose(pose::compose(at, shift), back);
                        shifts.push(pose::compose(moved, copy));
                        shift = pose::compose(shift, step);
                    }
                    todo.extend(shifts.into_iter().rev().map(|s| (rec, s)));
                }
            }
        }
    }
    Ok((joints, mocap))
}

/// The layout with its addresses: each joint's, actuator's and mocap body's in the
/// composed model and in its own model's, in order.
fn numbered<'a>(
    gathered: Gathered<'a>,
    joints: Vec<LayoutJoint>,
    mocap: Vec<LayoutMocap>,
) -> Layout<'a> {
    let mut out = Layout {
        joints: Vec::with_capacity(joints.len()),
        actuators: Vec::with_capacity(gathered.actuators.len()),
        mocap: Vec::with_capacity(mocap.len()),
        nq: 0,
        nv: 0,
        nu: 0,
        na: 0,
        unexpanded: gathered.unexpanded,
        keys: gathered.keys,
        origins: gathered.origins,
    };
    // Per instance: its own positions, velocities, controls, activations and mocap
    // bodies so far.
    let mut own: HashMap<usize, [usize; 5]> = HashMap::new();
    for mut joint in joints {
        let counts = own.entry(joint.inst).or_default();
        (joint.qpos, joint.dof, joint.own_qpos, joint.own_dof) =
            (out.nq, out.nv, counts[0], counts[1]);
        let (q, v) = (joint.joint_type.nq(), joint.joint_type.nv());
        (out.nq, out.nv, counts[0], counts[1]) =
            (out.nq + q, out.nv + v, counts[0] + q, counts[1] + v);
        out.joints.push(joint);
    }
    for mut a in gathered.actuators {
        let counts = own.entry(a.inst).or_default();
        (a.ctrl, a.act, a.own_ctrl, a.own_act) = (out.nu, out.na, counts[2], counts[3]);
        // An `actdim` can be any number: saturating.
        (out.nu, out.na, counts[2], counts[3]) = (
            out.nu.saturating_add(a.nctrl),
            out.na.saturating_add(a.nact),
            counts[2].saturating_add(a.nctrl),
            counts[3].saturating_add(a.nact),
        );
        out.actuators.push(a);
    }
    for (i, mut b) in mocap.into_iter().enumerate() {
        let counts = own.entry(b.inst).or_default();
        (b.index, b.own) = (i, counts[4]);
        counts[4] += 1;
        out.mocap.push(b);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::schema::Namespace;

    fn read(xml: &str) -> Model {
        Model::from_xml_str(xml).unwrap()
    }

    /// The names of the layout's joints, in its order.
    fn joint_names(m: &Model) -> Vec<String> {
        let layout = m.layout().unwrap();
        layout
            .joints
            .iter()
            .map(|j| m.element(&j.loc).unwrap().identifier().unwrap().to_string())
            .collect()
    }

    #[test]
    fn a_joint_type_s_keyword_number_and_widths_name_it_once() {
        let widths: Vec<(&str, i32, usize, usize)> = JointType::ALL
            .iter()
            .map(|t| (t.keyword(), t.mujoco_number(), t.nq(), t.nv()))
            .collect();
        assert_eq!(
            widths,
            [("free", 0, 7, 6), ("ball", 1, 4, 3), ("slide", 2, 1, 1), ("hinge", 3, 1, 1)]
        );
        for t in JointType::ALL {
            assert_eq!(JointType::from_keyword(t.keyword()), Some(t));
            assert_eq!(JointType::from_mujoco(t.mujoco_number().into()), Some(t));
        }
        assert_eq!(JointType::from_keyword("freejoint"), None);
        assert_eq!(JointType::from_mujoco(-1), None);
        assert_eq!(JointType::from_mujoco(4), None);
    }

    #[test]
    fn a_joint_s_type_is_its_own_else_its_classes_else_a_hinge() {
        let m = read(
            r#"<mujoco><default><default class="s"><joint type="slide"/>
                 <default class="inner"/></default></default><worldbody>
                 <body><freejoint name="f"/><geom size="1"/></body>
                 <body><joint name="plain"/><geom size="1"/></body>
                 <body childclass="inner"><joint name="classed"/><joint name="own" type="ball"/>
                   <geom size="1"/></body>
               </worldbody></mujoco>"#,
        );
        let ty = |name: &str| {
            let loc = m.find(Namespace::Joint, name).unwrap();
            m.layout().unwrap().joints.iter().find(|j| j.loc == loc).unwrap().joint_type
        };
        assert_eq!(ty("f"), JointType::Free);
        assert_eq!(ty("classed"), JointType::Slide);
        assert_eq!(ty("own"), JointType::Ball);
        assert_eq!(ty("plain"), JointType::Hinge);
    }

    #[test]
    fn an_element_s_joint_type_is_the_layout_s_attached_and_frame_joints_included() {
        let robot = read(
            r#"<mujoco><default><joint type="ball"/><default class="s"><joint type="slide"/>
                 </default></default><worldbody>
                 <body childclass="s"><joint name="a"/><joint name="b" type="hinge"/><geom size="1"/></body>
                 <body><joint name="c"/><geom size="1"/></body></worldbody></mujoco>"#,
        );
        let mut arena = read(r#"<mujoco><default><joint type="slide"/></default></mujoco>"#);
        let at = arena.attach_mut(&arena.worldbody(), &robot).unwrap();
        arena.add_mut(at.frame(), crate::model::Element::new("joint")).unwrap();
        let layout = arena.layout().unwrap();
        let types: Vec<JointType> = layout.joints.iter().map(|j| j.joint_type).collect();
        assert_eq!(types.len(), 4);
        for t in [JointType::Ball, JointType::Slide, JointType::Hinge] {
            assert!(types.contains(&t), "{types:?}");
        }
        for j in &layout.joints {
            assert_eq!(
                arena.element(&j.loc).unwrap().joint_type(),
                Some(j.joint_type),
                "{:?}",
                j.loc
            );
        }
    }

    #[test]
    fn a_body_s_own_joints_come_before_its_children_s_wherever_they_stand() {
        let m = read(
            r#"<mujoco><worldbody>
                 <body name="a"><body name="b"><joint name="jb"/><geom size="1"/></body>
                   <joint name="ja"/><frame><joint name="jf"/></frame><geom size="1"/></body>
               </worldbody></mujoco>"#,
        );
        assert_eq!(joint_names(&m), ["ja", "jf", "jb"]);
    }

    #[test]
    fn a_joint_s_default_positions_are_its_type_s() {
        let m = read(
            r#"<mujoco><compiler angle="radian"/><default><joint ref="0.25"/></default><worldbody>
                 <body name="a" pos="1 2 3"><freejoint name="free"/><geom size="1"/></body>
                 <body name="b"><joint name="own" ref="0.5"/><joint name="classed"/>
                   <joint name="ball" type="ball"/><geom size="1"/></body>
               </worldbody></mujoco>"#,
        );
        let qpos0 = |name: &str| {
            let loc = m.find(Namespace::Joint, name).unwrap();
            let layout = m.layout().unwrap();
            layout.joints.iter().find(|j| j.loc == loc).unwrap().qpos0.clone()
        };
        assert_eq!(qpos0("free"), [1.0, 2.0, 3.0, 1.0, 0.0, 0.0, 0.0]);
        assert_eq!(qpos0("ball"), [1.0, 0.0, 0.0, 0.0]);
        assert_eq!(qpos0("own"), [0.5]);
        assert_eq!(qpos0("classed"), [0.25]);
    }

    /// MuJoCo 4.0.0 compiles a hinge's `ref` (its own or its class's) to radians
    /// under the default `angle="degree"`, and a key without `qpos` takes `qpos0`:
    /// `[1.5708, 0.5, 0.5236]` here, `[90, 0.5, 30]` with `angle="radian"`.
    #[test]
    fn a_hinge_s_ref_is_in_radians_as_mujoco_compiles_it() {
        let qpos0 = |compiler: &str| {
            let m = read(&format!(
                r#"<mujoco>{compiler}<default><default class="c"><joint ref="30"/></default></default>
                   <worldbody><body name="b"><joint name="h" ref="90"/>
                     <joint name="s" type="slide" ref="0.5"/><joint name="hc" class="c"/>
                     <geom size="1"/></body></worldbody></mujoco>"#
            ));
            m.layout().unwrap().joints.iter().flat_map(|j| j.qpos0.clone()).collect::<Vec<f64>>()
        };
        let degrees = [90f64.to_radians(), 0.5, 30f64.to_radians()];
        assert_eq!(qpos0(""), degrees);
        assert_eq!(qpos0(r#"<compiler angle="degree"/>"#), degrees);
        assert_eq!(qpos0(r#"<compiler angle="radian"/>"#), [90.0, 0.5, 30.0]);
    }

    #[test]
    fn a_replicate_s_content_is_numbered_once_per_copy_each_moved() {
        let m = read(
            r#"<mujoco><worldbody>
                 <replicate count="3" offset="1 0 0">
                   <body name="r"><freejoint name="f"/><geom size="1"/></body>
                 </replicate>
               </worldbody></mujoco>"#,
        );
        let replicate = m.find(Namespace::Body, "r").unwrap();
        let node = m.node_by_id(m.element(&replicate).unwrap().parent().unwrap().loc().id());
        assert_eq!(node.map(replicate_count), Some(3));
        let layout = m.layout().unwrap();
        let x: Vec<f64> = layout.joints.iter().map(|j| j.qpos0[0]).collect();
        assert_eq!(x, [0.0, 1.0, 2.0]);
        assert_eq!(layout.joints.iter().map(|j| j.qpos).collect::<Vec<_>>(), [0, 7, 14]);
        assert_eq!((layout.nq, layout.nv), (21, 18));
    }

    /// MuJoCo 4.0.0 compiles `count="0"` and `count="-1"` to no copy (`nq` 0).
    #[test]
    fn a_replicate_count_below_1_makes_no_copy() {
        for count in ["0", "-1"] {
            let m = read(&format!(
                r#"<mujoco><worldbody><replicate count="{count}">
                     <body><joint/><geom size="1"/></body></replicate></worldbody></mujoco>"#
            ));
            assert_eq!(m.layout().unwrap().nq, 0, "{count}");
        }
    }
}
