//! Checks before MuJoCo: what a composed model holds that MuJoCo would refuse, said
//! with the element's name and path; advice on what it compiles but likely not as
//! meant ([`Model::advice`]); and who refers to an element.
//!
//! [`Model::check`] is a list of named rules ([`rules`]) over one walk of the
//! composed model (`walk`): the walk tells each rule every element it enters and
//! leaves, with its model, the default class in force and where it lands once
//! composed (the body it is in, whether that body is at the world's top level, moves,
//! or is below a moving body). A rule is one file here, one line in [`rules`] and a
//! unit test beside it; each problem it finds carries MuJoCo 4.0.0's own words.

use std::fmt;

use smol_str::SmolStr;

use crate::schema::Namespace;
use crate::value::{Reference, Value};
use crate::write_options::WriteOptions;

use super::cursor::{Insts, Item, Step, Walk};
use super::naming;
use super::{Loc, Model};

mod actuator_fixes;
mod actuator_spec;
mod actuators;
mod advice;
mod arrays;
mod attach;
mod bodies;
mod dofs;
mod expansion;
mod free_joint;
mod history;
pub(crate) use free_joint::top_level_floating;
mod key_length;
mod limits;
mod massless;
mod mocap;
mod plane;
mod references;
mod target;
mod values;
mod walk;

pub use advice::{Advice, AdviceKind};
use walk::Rule;

/// The rules [`Model::check_with`] holds the model to, for the model written with
/// `options`: one line each.
fn rules<'m>(model: &'m Model, options: &WriteOptions) -> Vec<Box<dyn Rule<'m> + 'm>> {
    vec![
        Box::new(references::References::default()),
        Box::new(massless::MasslessMovingBody::default()),
        Box::new(dofs::TooManyDofs::default()),
        Box::new(dofs::RotationAfterBall::default()),
        Box::new(free_joint::FreeJointNotTopLevel::default()),
        Box::new(mocap::MocapNotFixedChildOfWorld),
        Box::new(plane::PlaneInMovingBody),
        Box::new(key_length::KeyLength::new(model, options)),
        Box::new(arrays::ArrayLengths),
        Box::new(limits::Limits::new(model)),
        Box::new(values::Values::new(model)),
        Box::new(bodies::Bodies::new(model)),
        Box::new(history::History::new(model)),
        Box::new(attach::Attach),
        Box::new(actuators::Actuators::new(model)),
    ]
}

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
    /// A body with a free joint (`<freejoint>`, or a joint of type `free`, by its own
    /// type or its classes') that is not at the world's top level once composed: its
    /// parent is a body (an attachment frame written as a body counts; `<frame>`s,
    /// `<replicate>`s and attachment frames written as `<frame>` are transparent).
    /// MuJoCo refuses it ("free joint can only be used on top level"). Attaching a
    /// model with free top-level bodies at a site inside a body makes it; attach with
    /// [`Model::attach_welded`] instead, or at a site of the world.
    FreeJointNotTopLevel,
    /// A plane geom (its own `type` or its classes') in a body that moves or is below
    /// a moving body. MuJoCo refuses it ("plane only allowed in static bodies");
    /// static is welded to the world (a mocap body is static).
    PlaneInMovingBody,
    /// A mocap body whose parent is a body once composed, or that has joints. MuJoCo
    /// refuses it ("mocap body '…' is not a fixed child of world"). An attachment
    /// frame written as a body is a body: a model with mocap top-level bodies attached
    /// anywhere makes it unless its frame is written as MuJoCo's `<frame>`; attach it
    /// with [`Model::attach_welded`], which makes them plain bodies.
    MocapNotFixedChildOfWorld,
    /// A limited range that is not one: a joint's, tendon's or actuator's low end not
    /// below its high end, or a limited ball joint's low end not 0 (its own or its
    /// classes' values; see the `limits` rule for when a range is limited). MuJoCo
    /// refuses it with `mujoco`'s words (`range[0] should be smaller than range[1] in
    /// joint`, `invalid control range for actuator`, ...).
    InvalidRange {
        /// The range attribute (`range`, `ctrlrange`, `actuatorfrcrange`, ...).
        attribute: &'static str,
        /// Its two numbers.
        range: [f64; 2],
        /// MuJoCo 4.0.0's message.
        mujoco: &'static str,
    },
    /// A range given without its `limited` while the compiler's `autolimits` is off:
    /// MuJoCo refuses it ("joint has `range` but not `limited`").
    RangeWithoutLimited {
        /// What has it, as MuJoCo says: `joint`, `tendon` or `actuator`.
        element: &'static str,
        /// The range attribute.
        attribute: &'static str,
        /// The attribute that would say whether it is a limit.
        limited: &'static str,
    },
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
    /// Something else MuJoCo refuses in the element's own values (an attribute out
    /// of its range, a zero axis, two attributes that exclude each other, a keyword
    /// another one rules out), or in what it names (a sensor's joint of the wrong
    /// type, a tendon's path), found by one of the checks of the `values` rule (or of
    /// a rule that needs the model's settings: `user` lengths, limit sensors), in
    /// MuJoCo 4.0.0's words.
    Refused {
        /// The check's name, stable (`geom-size-positive`).
        rule: &'static str,
        /// The attribute at fault, when one is.
        attribute: Option<&'static str>,
        /// MuJoCo 4.0.0's message, with names and numbers filled in (MuJoCo's
        /// numeric ids left out).
        mujoco: String,
        /// What to do about it.
        fix: &'static str,
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
            ProblemKind::FreeJointNotTopLevel => write!(
                f,
                "{}: a body with a free joint, not at the world's top level (MuJoCo: \
                 \"free joint can only be used on top level\"); attach its model at a site \
                 of the world, or with Model::attach_welded, or remove the free joint",
                self.path
            ),
            ProblemKind::PlaneInMovingBody => write!(
                f,
                "{}: a plane in a body that moves or is below a moving body (MuJoCo: \
                 \"plane only allowed in static bodies\"); put the plane in the world or a \
                 body without joints above it, or use a box",
                self.path
            ),
            ProblemKind::InvalidRange { attribute, range: [lo, hi], mujoco } => write!(
                f,
                "{}: limited '{attribute}' is {lo} {hi}, not a range MuJoCo takes (MuJoCo: \"{mujoco}\"); \
                 give a low end below the high end (0 for a ball joint's), or make it unlimited",
                self.path
            ),
            ProblemKind::RangeWithoutLimited { element, attribute, limited } => write!(
                f,
                "{}: '{attribute}' is given without '{limited}' while the compiler's autolimits is \
                 off (MuJoCo: \"{element} has `{attribute}` but not `{limited}`. set the \
                 autolimits=\"true\" compiler option, specify `{limited}` explicitly (\"true\" or \
                 \"false\"), or remove the `{attribute}` attribute.\")",
                self.path
            ),
            ProblemKind::MocapNotFixedChildOfWorld => write!(
                f,
                "{0}: a mocap body that is not a child of the world without joints (MuJoCo: \
                 \"mocap body '{0}' is not a fixed child of world\"); put it in the world \
                 and remove its joints, attach its model with Model::attach_welded, or make \
                 it a plain body",
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
            ProblemKind::Refused { attribute: Some(a), mujoco, fix, .. } => {
                write!(f, "{}: '{a}' (MuJoCo: \"{mujoco}\"); {fix}", self.path)
            }
            ProblemKind::Refused { attribute: None, mujoco, fix, .. } => {
                write!(f, "{} (MuJoCo: \"{mujoco}\"); {fix}", self.path)
            }
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
    /// What MuJoCo would refuse in the composed model, found before it is written,
    /// and only that (what MuJoCo compiles but likely not as meant is
    /// [`Model::advice`]): references that name nothing in their model (the
    /// `joint="hinj"` typo, with the nearest names), references whose element was
    /// removed, moving bodies and attachment frames without mass (no inertial, no
    /// geom, no massive body welded below), bodies and frames whose joints MuJoCo
    /// refuses (more than 6 degrees of freedom, such as a freejoint beside another
    /// joint; a hinge or ball joint after a ball joint), free joints on bodies that
    /// are not at the world's top level once composed, mocap bodies that are not
    /// fixed children of the world, planes in moving bodies, keys longer than the
    /// model, arrays shorter than MuJoCo accepts (`pos="1 2"`; the minimums probed
    /// from MuJoCo 4.0.0), and what MuJoCo refuses of an element's own values and of
    /// its targets ([`ProblemKind::Refused`], in MuJoCo's words, with the check's
    /// name: out-of-range numbers, degenerate orientations, attributes that exclude
    /// each other, actuators, sensors, tendons, equalities, assets, settings, MuJoCo's
    /// own `<attach>`). Each is said once, naming its element as the writer writes
    /// it ([the names](crate::guide#names)), with MuJoCo's own words and what to do;
    /// a reference to a `<replicate>`'s copies (`j0`) or into an `<attach>`ed part
    /// (`p-j`) names what MuJoCo makes. Empty when none is found; this is not a full
    /// MuJoCo compile: the content of files (meshes, textures, height fields, skins),
    /// meshes whose hull MuJoCo computes only for colliding geoms, and plugins are
    /// MuJoCo's to judge ([`Model::advice`] names the plugins).
    ///
    /// Composition never turns a model refused silently: for each shape that
    /// attaching, adding or removing can make and MuJoCo refuses, the edit refuses
    /// with a typed error that says what and how to fix it, or the edit is allowed (a
    /// user may attach first and fix after) and `check()` reports it, in MuJoCo's
    /// words, with the remedy:
    ///
    /// | shape | where decided | remedy |
    /// |---|---|---|
    /// | a model with free top-level bodies attached at a site inside a body (moving or not): below a body there is no top level | `check()`: [`FreeJointNotTopLevel`](ProblemKind::FreeJointNotTopLevel) | [`Model::attach_welded`], or a site of the world (the frame is then written as MuJoCo's `<frame>`, keeping the bodies top level) |
    /// | a `<freejoint>` added to an attachment frame not directly in the worldbody | `add` refuses: [`ErrorKind::FreejointNotTopLevel`](crate::ErrorKind::FreejointNotTopLevel) | attach at a site of the worldbody |
    /// | a `<joint type="free">` (or free by its class) added to a body or attachment frame below a body | `check()`: [`FreeJointNotTopLevel`](ProblemKind::FreeJointNotTopLevel) | remove it, or move the body to the world |
    /// | a model with mocap top-level bodies attached anywhere (the attachment frame is written as a body) | `check()`: [`MocapNotFixedChildOfWorld`](ProblemKind::MocapNotFixedChildOfWorld) | [`Model::attach_welded`] (they become plain bodies fixed to the site's body) |
    /// | a model with a plane attached in or below a moving body, or a joint added above a plane | `check()`: [`PlaneInMovingBody`](ProblemKind::PlaneInMovingBody) | attach at a site of a static body or the world |
    /// | joints added to an attachment frame beyond 6 degrees of freedom, or a rotation after a ball joint | `check()`: [`TooManyDofs`](ProblemKind::TooManyDofs), [`RotationAfterBall`](ProblemKind::RotationAfterBall) (the frame is a body) | fewer joints, the ball joint last |
    /// | a joint added to an attachment frame without mass | `check()`: [`MasslessMovingBody`](ProblemKind::MasslessMovingBody) | an `<inertial>` on the frame |
    /// | a key longer than the model (an attached model's key held to its own model with `merge_keyframes`, or a joint removed) | `check_with(&options)`: [`KeyLength`](ProblemKind::KeyLength) | shorten the key |
    /// | a removed element still referred to | `check()`: [`RemovedReference`](ProblemKind::RemovedReference), [`MissingRequired`](ProblemKind::MissingRequired) | [`Model::references_to`] before removing |
    /// | a global setting that disagrees between the models | `attach` refuses: [`ErrorKind::AttributeConflict`](crate::ErrorKind::AttributeConflict) | make the settings agree |
    /// | the compiler's `angle` (degrees or radians) or `eulerseq` set differently in both models | `attach` converts the child's orientations and joint values into the parent's conventions (as [`Model::attach`] says); only a `<replicate>` turning about several axes whose sequence changes, or a sequence that is not three of `xyzXYZ`, is refused ([`ErrorKind::AttributeConflict`](crate::ErrorKind::AttributeConflict)) | give the replicate one axis, or both models one sequence |
    /// | names: each attached model's names get a unique scope prefix | never a clash (`robot`, `robot_1`, ...) | — |
    ///
    /// MuJoCo judges that `check()` finds a problem exactly when it refuses the
    /// model, over generated scenes and what composition makes of them
    /// (`mjcf-mujoco/tests/check.rs`: mutants of generated scenes, and 2,000 scenes of
    /// the wide generators, which attach models with free bodies and planes at sites
    /// inside moving bodies, `<frame>`s and other attached models).
    ///
    /// How far it reaches is measured against MuJoCo 4.0.0's own refusals:
    /// `mjcf-mujoco/refusals/catalog.tsv` lists 760 distinct messages of its compiler
    /// and XML reader (455 reachable from MJCF text, 90 needing a file's content, 215
    /// unreachable: C API only, internal checks, plugins, or another refusal comes
    /// first), with 337 pairs of a model MuJoCo refuses with that message and a near
    /// twin it compiles (327 of the 455). `mjcf-mujoco/tests/refusals.rs` has MuJoCo
    /// judge every pair: the reader or `check()` objects to all 337 refused models
    /// with MuJoCo's message (a [`ProblemKind`] of that class, or
    /// [`ProblemKind::Refused`] in MuJoCo's words), to none of the twins, and no two
    /// rules say one message.
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
        expansion::parts_read_once(|| {
            let mut rules = rules(self, options);
            walk::run(self, &mut rules)
        })
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
                            && node.reference_namespace(i) == target_ns
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
    /// `mj_name2id`, by the [naming rules](crate::guide#names). `None` if `loc` is not
    /// in this model or the element has no namespace. See
    /// [`ElementRef::full_name`](crate::ElementRef::full_name).
    ///
    /// Time: as [`ElementRef::full_name`](crate::ElementRef::full_name) of a handle
    /// made by [`Model::element`]: O(levels · depth · log n), and for an unnamed
    /// element O(n) the first time a version of its model is asked (its model's
    /// elements counted, and the count kept with the model). To name many elements,
    /// name the handles of one walk ([`Model::walk`],
    /// [`ElementRef::children`](crate::ElementRef::children)), which share the rest.
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
pub(crate) mod tests {
    use super::*;

    /// The problems `rule` alone finds in `m`, in walk order.
    /// The node of the element `name` of namespace `ns` in `m`.
    pub(crate) fn node<'m>(
        m: &'m Model,
        ns: crate::schema::Namespace,
        name: &str,
    ) -> &'m crate::model::tree::Node {
        let loc = m.find(ns, name).expect("the element exists");
        m.node_by_id(loc.id()).expect("its node")
    }

    pub(crate) fn kinds_of<'m>(m: &'m Model, rule: impl Rule<'m> + 'm) -> Vec<ProblemKind> {
        let mut rules: Vec<Box<dyn Rule<'m> + 'm>> = vec![Box::new(rule)];
        walk::run(m, &mut rules).into_iter().map(|p| p.kind).collect()
    }

    #[test]
    fn check_says_each_distinct_problem_once() {
        // Two rules that find the same problem on the same element: said once.
        struct Twice;
        impl<'m> Rule<'m> for Twice {
            fn enter(&mut self, e: &walk::Event<'m>, out: &mut Vec<ProblemKind>) {
                if e.node.kind().is(crate::schema::Role::Worldbody) {
                    out.push(ProblemKind::RotationAfterBall);
                    out.push(ProblemKind::RotationAfterBall);
                }
            }
        }
        let m = Model::new("m");
        let mut rules: Vec<Box<dyn Rule<'_> + '_>> = vec![Box::new(Twice), Box::new(Twice)];
        assert_eq!(walk::run(&m, &mut rules).len(), 1);
    }
}
