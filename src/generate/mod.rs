//! Generators of valid models, compositions and edit sequences, for property tests
//! and fuzzing (features `proptest` and `arbitrary`).
//!
//! A generated model is described by a plain-data **recipe**: a [`ModelRecipe`] is a
//! model name, its global settings and a list of [`Step`]s (add a body, a geom, a
//! joint, a default class, an actuator, ..., attach another recipe's model at a
//! site); an [`EditRecipe`] is a list of [`Edit`]s (add, set, rename, remove, attach,
//! detach, rename a scope, `include_copy`). Recipes hold no model and no locator:
//! every choice of "which element" is a [`Pick`], an index taken modulo what exists
//! when the step runs, and every number is a [`Unit`] mapped into the range the
//! attribute needs. **Applying** a recipe builds the model step by step and skips
//! (or repairs) any step that would make it invalid, so *every* recipe, and so every
//! recipe a shrinker or a fuzzer makes out of another, gives a valid model:
//!
//! - elements only where the schema allows them, and attribute values of the type
//!   and length the schema gives ([`ElementKind::spec`](crate::ElementKind::spec)),
//!   in ranges MuJoCo accepts (positive sizes, masses and inertias, non-zero axes,
//!   `lo < hi` ranges);
//! - names unique per namespace (a taken name gets `_2`, `_3`, ...); references that
//!   resolve (actuators, sensors, tendons, equalities and contact pairs name
//!   existing elements, of the joint types they need);
//! - what MuJoCo compiles: every body has a geom with a size (so it has mass),
//!   moving attachment frames get an inertial, freejoints only on bodies and frames
//!   directly in the worldbody (and never with other joints), planes only in the
//!   worldbody;
//! - after every step, [`Model::check`] finds no more problems than before (none,
//!   for a model built from a recipe); an edit that would add one is repaired
//!   (a remove also removes or clears what referred to the removed elements) or
//!   skipped.
//!
//! With the `proptest` feature, [`strategy`] has the proptest strategies (recipes,
//! and the models they build); with the `arbitrary` feature, every recipe type
//! implements `arbitrary::Arbitrary`, for cargo-fuzz targets.
//!
//! # Properties to write with them
//!
//! Every generated scene (nested attachments, frames with joints and freejoints
//! included) compiles in MuJoCo. Compile each in memory with the workspace's
//! `mjcf-mujoco` crate (`MuJoCo::load()?.compile(&scene)`; its tests judge 1,325 of
//! them so), or write them out and compile them with MuJoCo from Python:
//!
//! ```no_run
//! # #[cfg(feature = "proptest")] {
//! use mjcf::generate::strategy;
//! use proptest::strategy::{Strategy, ValueTree};
//! use proptest::test_runner::TestRunner;
//!
//! let mut runner = TestRunner::deterministic();
//! for i in 0..100 {
//!     let scene = strategy::scene_recipe().new_tree(&mut runner).unwrap().current().build();
//!     assert!(scene.check().is_empty());
//!     std::fs::write(format!("/tmp/scene_{i}.xml"), scene.to_xml_string().unwrap()).unwrap();
//! }
//! # }
//! ```
//!
//! Undo after any edit sequence gives back the first version: the versions are
//! values, and the first one is the model the edits started from.
//!
//! ```
//! # #[cfg(feature = "proptest")] {
//! use mjcf::generate::strategy;
//! use proptest::prelude::*;
//!
//! proptest!(ProptestConfig::with_cases(8), |((scene, edits) in strategy::scene_and_edits())| {
//!     let base = scene.build();
//!     let before = base.to_xml_string().unwrap();
//!     let versions = edits.apply(&base);
//!     prop_assert!(versions[0] == base);
//!     for v in &versions {
//!         prop_assert!(v.check().is_empty()); // every version stays valid
//!     }
//!     prop_assert_eq!(versions[0].to_xml_string().unwrap(), before);
//! });
//! # }
//! ```
//!
//! A fuzz target takes the same recipes from bytes (feature `arbitrary`):
//!
//! ```ignore
//! fuzz_target!(|input: (mjcf::generate::ModelRecipe, mjcf::generate::EditRecipe)| {
//!     let versions = input.1.apply(&input.0.build());
//!     assert!(versions.iter().all(|v| v.check().is_empty()));
//! });
//! ```

#[cfg(any(test, feature = "proptest"))]
pub mod strategy;
#[cfg(test)]
mod tests;

use std::collections::HashSet;

use crate::error::ErrorKind;
use crate::model::{Attrs, Element, Event, Loc, Model, ProblemKind};
use crate::schema::{ArrayType, AttrType, ElementKind, Namespace, Role};
use crate::value::AttrInput;

/// The element names recipes use ([`Word`] picks one); a taken name gets a suffix.
pub const WORDS: &[&str] =
    &["a", "b", "c", "base", "link", "torso", "hip", "knee", "foot", "tip", "head", "tail"];

/// The model names recipes use (they become scope names when attached).
pub const MODEL_WORDS: &[&str] = &["robot", "arm", "leg", "hand", "prop", "arena"];

/// How deep attachments of recipes nest at most (deeper `Attach` steps are skipped).
pub const MAX_DEPTH: u32 = 3;

/// How many steps one [`ModelRecipe::build`] or [`EditRecipe::apply`] carries out at
/// most, nested recipes included (later ones are skipped), so any input, however
/// large or deeply nested, builds in bounded time.
pub const MAX_STEPS: usize = 512;

/// How many elements a composed model built by recipes may have: an attach that
/// would make it larger is skipped (attaching a model again and again could
/// otherwise double the output at every step).
pub const MAX_ELEMENTS: usize = 10_000;

/// A choice among what exists when a step runs: `Pick(i)` takes item `i mod len`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Pick(pub u16);

impl Pick {
    /// The item this picks, `None` if there is none.
    ///
    /// Time: O(1).
    pub fn of<T>(self, items: &[T]) -> Option<&T> {
        if items.is_empty() { None } else { items.get(usize::from(self.0) % items.len()) }
    }
}

/// A number in `[0, 1]` in steps of 1/1000: `Unit(k)` is `(k mod 1001) / 1000`.
/// Applying a recipe maps it into the range the attribute needs, to at most three
/// decimals (so the written numbers are short and exact).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Unit(pub u16);

impl Unit {
    /// The number in thousandths, `0..=1000`.
    ///
    /// Time: O(1).
    pub fn thousandths(self) -> i64 {
        i64::from(self.0 % 1001)
    }

    /// The number in `[0, 1]`.
    ///
    /// Time: O(1).
    pub fn fraction(self) -> f64 {
        self.thousandths() as f64 / 1000.0
    }
}

/// A name from [`WORDS`] (`Word(i)` is `WORDS[i mod len]`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Word(pub u8);

impl Word {
    /// The element name.
    ///
    /// Time: O(1).
    pub fn text(self) -> &'static str {
        WORDS[usize::from(self.0) % WORDS.len()]
    }

    /// The model name ([`MODEL_WORDS`]).
    ///
    /// Time: O(1).
    pub fn model_name(self) -> &'static str {
        MODEL_WORDS[usize::from(self.0) % MODEL_WORDS.len()]
    }

    /// The name of a joint of an attachment frame: for odd words a model name
    /// ([`Word::model_name`]), which the scope of an attachment inside the attached
    /// model can share (the names written for both then meet: DESIGN D14); an
    /// element name ([`Word::text`]) otherwise.
    ///
    /// Time: O(1).
    pub fn frame_joint_name(self) -> &'static str {
        if self.0 % 2 == 1 { Word(self.0 / 2).model_name() } else { self.text() }
    }
}

/// One more attribute of an element: which one of the attributes recipes set on
/// that tag ([`palette`]), and the numbers its value is made from (the schema gives
/// its type and length: a float, an array, an integer or a keyword).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct AttrDraw {
    /// Which attribute of the tag's palette.
    pub which: Pick,
    /// The numbers of the value (as many as its length needs).
    pub values: [Unit; 4],
    /// Picks the length of an array whose length may vary.
    pub len: u8,
}

/// A geom's shape (and so the length of its `size`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum Shape {
    /// `sphere`: a radius.
    #[default]
    Sphere,
    /// `capsule`: a radius and a half-length.
    Capsule,
    /// `cylinder`: a radius and a half-length.
    Cylinder,
    /// `ellipsoid`: three radii.
    Ellipsoid,
    /// `box`: three half-sizes.
    Box,
    /// `plane`, in the worldbody only (a box elsewhere).
    Plane,
    /// `mesh`, naming a mesh of the model (a sphere when there is none, or when the
    /// geom goes inside an attachment).
    Mesh(Pick),
}

/// A joint type that moves along or about an axis, or a ball.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum JointKind {
    /// `hinge`.
    #[default]
    Hinge,
    /// `slide`.
    Slide,
    /// `ball` (no axis, no range).
    Ball,
}

impl JointKind {
    /// Its degrees of freedom.
    ///
    /// Time: O(1).
    pub fn dofs(self) -> usize {
        if self == JointKind::Ball { 3 } else { 1 }
    }

    /// The `type` keyword.
    ///
    /// Time: O(1).
    pub fn keyword(self) -> &'static str {
        match self {
            JointKind::Hinge => "hinge",
            JointKind::Slide => "slide",
            JointKind::Ball => "ball",
        }
    }
}

/// An actuator element (on a hinge or slide joint).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum ActuatorKind {
    /// `motor`.
    #[default]
    Motor,
    /// `position`.
    Position,
    /// `velocity`.
    Velocity,
}

/// What a `framepos` sensor looks at.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum ObjKind {
    /// A body.
    #[default]
    Body,
    /// A geom.
    Geom,
    /// A site.
    Site,
}

/// A sensor element and what it names.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum SensorKind {
    /// `jointpos` on a hinge or slide joint.
    #[default]
    JointPos,
    /// `jointvel` on a hinge or slide joint.
    JointVel,
    /// `touch` on a site.
    Touch,
    /// `accelerometer` on a site.
    Accelerometer,
    /// `gyro` on a site.
    Gyro,
    /// `framepos` with `objtype` and `objname` (a reference whose namespace another
    /// attribute names).
    FramePos(ObjKind),
}

/// An equality constraint.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum EqualityKind {
    /// `connect` two bodies at an anchor.
    #[default]
    Connect,
    /// `weld` two bodies.
    Weld,
    /// `joint`: couple two hinge or slide joints.
    Joint,
}

/// The element a default class sets defaults for.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum DefaultTag {
    /// `geom`.
    #[default]
    Geom,
    /// `joint`.
    Joint,
    /// `site`.
    Site,
}

impl DefaultTag {
    fn tag(self) -> &'static str {
        match self {
            DefaultTag::Geom => "geom",
            DefaultTag::Joint => "joint",
            DefaultTag::Site => "site",
        }
    }
}

/// A geom: its shape and size, and what else it sets.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct GeomRecipe {
    /// Its name, if any.
    pub name: Option<Word>,
    /// Its shape.
    pub shape: Shape,
    /// Its size, as many entries as the shape needs (each 0.02 to 0.3).
    pub size: [Unit; 3],
    /// A default class of the model, if any exists.
    pub class: Option<Pick>,
    /// A material of the model, if any exists.
    pub material: Option<Pick>,
    /// More attributes ([`palette`] of `geom`).
    pub extras: Vec<AttrDraw>,
}

/// One joint of an attachment frame.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct FrameJoint {
    /// Its name (unique on its frame), if any.
    pub name: Option<Word>,
    /// Its type.
    pub kind: JointKind,
    /// Its axis (made non-zero).
    pub axis: [Unit; 3],
}

/// What an attachment frame gets: a freejoint (only when the frame is directly in
/// the worldbody; otherwise the joints are used), or joints; either way an inertial
/// when it moves.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct FrameRecipe {
    /// A freejoint, where one is allowed.
    pub free: bool,
    /// Joints, when there is no freejoint.
    pub joints: Vec<FrameJoint>,
}

/// A model's global settings.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct Settings {
    /// `option/@timestep`: 0.002, 0.004, 0.005 or 0.01 (merged by minimum when
    /// attached).
    pub timestep: Option<u8>,
    /// `compiler/@angle`: `radian` (true) or `degree` (false); two models that set
    /// it differently cannot be attached to one another (the attach is skipped).
    pub radian: Option<bool>,
}

/// One step of a [`ModelRecipe`], or an added element of an [`Edit::Add`]. Steps
/// that find nothing to pick (an actuator without a joint) are skipped.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum Step {
    /// A body with a geom, under the worldbody or a body (inside attachments too).
    Body {
        /// The parent: the worldbody, then every body that is not a frame.
        parent: Pick,
        /// Its name, if any.
        name: Option<Word>,
        /// Its position (each coordinate -1 to 1).
        pos: [Unit; 3],
        /// Its geom (unnamed), which gives it mass.
        geom: GeomRecipe,
        /// A freejoint, when the body is directly in the worldbody.
        free: bool,
        /// A default class of the model for `childclass`.
        childclass: Option<Pick>,
        /// More attributes ([`palette`] of `body`).
        extras: Vec<AttrDraw>,
    },
    /// A geom under the worldbody or a body.
    Geom {
        /// The parent, as for [`Step::Body`].
        parent: Pick,
        /// The geom.
        geom: GeomRecipe,
    },
    /// A site under the worldbody or a body (a place to attach at).
    Site {
        /// The parent, as for [`Step::Body`].
        parent: Pick,
        /// Its name, if any.
        name: Option<Word>,
        /// Its position (each coordinate -1 to 1).
        pos: [Unit; 3],
        /// More attributes ([`palette`] of `site`).
        extras: Vec<AttrDraw>,
    },
    /// A joint in a body (not one with a freejoint).
    Joint {
        /// The body: every body that is not a frame and has no freejoint.
        body: Pick,
        /// Its name, if any.
        name: Option<Word>,
        /// Its type.
        kind: JointKind,
        /// Its axis (made non-zero; not for a ball).
        axis: [Unit; 3],
        /// A range `lo < hi` (not for a ball).
        range: Option<[Unit; 2]>,
        /// A default class of the model.
        class: Option<Pick>,
        /// More attributes ([`palette`] of `joint`).
        extras: Vec<AttrDraw>,
    },
    /// A camera under the worldbody or a body.
    Camera {
        /// The parent, as for [`Step::Body`].
        parent: Pick,
        /// Its name, if any.
        name: Option<Word>,
        /// More attributes ([`palette`] of `camera`).
        extras: Vec<AttrDraw>,
    },
    /// A light under the worldbody or a body.
    Light {
        /// The parent, as for [`Step::Body`].
        parent: Pick,
        /// Its name, if any.
        name: Option<Word>,
        /// More attributes ([`palette`] of `light`).
        extras: Vec<AttrDraw>,
    },
    /// A default class, in the root class or another class of the model.
    Class {
        /// The parent class: the root class, then every named class.
        parent: Pick,
        /// Its name.
        name: Word,
        /// Defaults it sets, per element.
        defaults: Vec<(DefaultTag, AttrDraw)>,
    },
    /// A material.
    Material {
        /// Its name.
        name: Word,
        /// More attributes ([`palette`] of `material`).
        extras: Vec<AttrDraw>,
    },
    /// A mesh given by its vertices (a tetrahedron, scaled; no file).
    Mesh {
        /// Its name.
        name: Word,
        /// Its scale (each 0.05 to 0.3).
        scale: [Unit; 3],
    },
    /// An actuator on a named hinge or slide joint of the model.
    Actuator {
        /// The element.
        kind: ActuatorKind,
        /// Its name, if any.
        name: Option<Word>,
        /// The joint.
        joint: Pick,
        /// More attributes ([`palette`] of the actuator's tag).
        extras: Vec<AttrDraw>,
    },
    /// A sensor on a named element of the model.
    Sensor {
        /// The element and what it names.
        kind: SensorKind,
        /// Its name, if any.
        name: Option<Word>,
        /// The element it names.
        target: Pick,
        /// More attributes ([`palette`] of the sensor's tag).
        extras: Vec<AttrDraw>,
    },
    /// A fixed tendon over named hinge or slide joints (each once).
    Tendon {
        /// Its name, if any.
        name: Option<Word>,
        /// The joints and their coefficients (each 0.1 to 2).
        joints: Vec<(Pick, Unit)>,
    },
    /// An equality constraint between two named bodies or joints.
    Equality {
        /// The constraint.
        kind: EqualityKind,
        /// Its name, if any.
        name: Option<Word>,
        /// The first body or joint.
        first: Pick,
        /// The second (another one).
        second: Pick,
    },
    /// A contact exclusion between two named bodies (each pair once).
    Exclude {
        /// The first body.
        first: Pick,
        /// The second body.
        second: Pick,
    },
    /// A contact pair between two named geoms that are not planes.
    Pair {
        /// The first geom.
        first: Pick,
        /// The second geom.
        second: Pick,
    },
    /// Builds `child` and attaches it at a site (inside attachments too) or the
    /// worldbody; its frame gets what `frame` says.
    Attach {
        /// Where: the worldbody, then every site.
        at: Pick,
        /// The model to attach.
        child: Box<ModelRecipe>,
        /// The frame's joints.
        frame: FrameRecipe,
    },
    /// Attaches again a model an earlier `Attach` step built (one value, shared).
    AttachAgain {
        /// Where, as for [`Step::Attach`].
        at: Pick,
        /// Which of the models built so far.
        child: Pick,
        /// The frame's joints.
        frame: FrameRecipe,
    },
}

/// A model as plain data: build it with [`ModelRecipe::build`].
///
/// # Examples
/// ```
/// use mjcf::generate::{GeomRecipe, ModelRecipe, Pick, Shape, Step, Unit, Word};
/// let recipe = ModelRecipe {
///     steps: vec![Step::Body {
///         parent: Pick(0),
///         name: Some(Word(5)),
///         pos: [Unit(500); 3],
///         geom: GeomRecipe { shape: Shape::Box, size: [Unit(100); 3], ..GeomRecipe::default() },
///         free: true,
///         childclass: None,
///         extras: vec![],
///     }],
///     ..ModelRecipe::default()
/// };
/// let m = recipe.build();
/// assert!(m.find(mjcf::Namespace::Body, "torso").is_some());
/// assert!(m.check().is_empty());
/// ```
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct ModelRecipe {
    /// The model name ([`Word::model_name`]).
    pub name: Word,
    /// Its global settings.
    pub settings: Settings,
    /// The steps, in order.
    pub steps: Vec<Step>,
}

/// One edit of an [`EditRecipe`]. Targets are picked in the composed model (inside
/// attachments too) when the edit runs.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum Edit {
    /// Adds what a step adds (an attach included).
    Add(Step),
    /// Sets one attribute of an element ([`palette`] of its tag).
    Set {
        /// Among the elements with a palette, in walk order.
        target: Pick,
        /// The attribute and its value.
        attr: AttrDraw,
    },
    /// Renames an element, or takes its name away (only from one nothing refers to).
    Rename {
        /// Among the named-capable elements (not frames, not the root class).
        target: Pick,
        /// The new name; `None` clears it.
        name: Option<Word>,
    },
    /// Removes an element (not a section, not a frame) and repairs what referred to
    /// anything it held: referring actuators, sensors, tendons, equalities and
    /// contact elements are removed, optional references (`class`, `material`)
    /// cleared.
    Remove {
        /// Among the removable elements, in walk order.
        target: Pick,
    },
    /// Detaches an attachment (nested ones included).
    Detach {
        /// Among the scope paths.
        scope: Pick,
    },
    /// Renames an attachment's scope.
    RenameScope {
        /// Among the scope paths.
        scope: Pick,
        /// The new scope name ([`Word::model_name`]).
        to: Word,
    },
    /// `include_copy` of a model built from `source` (its `Attach` steps skipped, its
    /// names prefixed so that they rarely clash).
    IncludeCopy {
        /// The model to copy.
        source: ModelRecipe,
        /// `include_copy`'s `override_attributes`.
        override_attributes: bool,
    },
}

/// A sequence of edits as plain data: apply it with [`EditRecipe::apply`].
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct EditRecipe {
    /// The edits, in order.
    pub edits: Vec<Edit>,
}

impl ModelRecipe {
    /// Builds the model, skipping the steps that would make it invalid (and every
    /// step after the first [`MAX_STEPS`], nested recipes included).
    ///
    /// Time: O(s · N) for `s` steps and a composed model of N elements (each step is
    /// checked with [`Model::check`]).
    pub fn build(&self) -> Model {
        Builder::new().model(self, 0, "")
    }
}

impl EditRecipe {
    /// Applies the edits to `base`: the versions, `base` first, then one per edit
    /// that applied (an edit that would make the model invalid, or finds nothing to
    /// edit, makes none). Every version has no more [`Model::check`] problems than
    /// `base`.
    ///
    /// Time: O(e · N) for `e` edits and a composed model of N elements.
    ///
    /// # Examples
    /// ```
    /// use mjcf::generate::{Edit, EditRecipe, ModelRecipe, Pick, Word};
    /// let base = mjcf::Model::new("arena");
    /// let robot = ModelRecipe { name: Word(0), ..ModelRecipe::default() };
    /// let edits = EditRecipe {
    ///     edits: vec![
    ///         Edit::Add(mjcf::generate::Step::Attach { at: Pick(0), child: Box::new(robot), frame: Default::default() }),
    ///         Edit::RenameScope { scope: Pick(0), to: Word(1) },
    ///         Edit::Detach { scope: Pick(0) },
    ///     ],
    /// };
    /// let versions = edits.apply(&base);
    /// assert_eq!(versions.len(), 4);
    /// assert_eq!(versions[1].scopes().collect::<Vec<_>>(), ["robot"]);
    /// assert_eq!(versions[2].scopes().collect::<Vec<_>>(), ["arm"]);
    /// assert_eq!(versions[3], base); // detach gives back the model before the attach
    /// ```
    pub fn apply(&self, base: &Model) -> Vec<Model> {
        let mut b = Builder::new();
        let mut versions = vec![base.clone()];
        let mut current = base.clone();
        let allowed = base.check().len();
        for edit in &self.edits {
            if b.budget == 0 {
                break;
            }
            b.budget -= 1;
            if let Some(next) = b.edit(&current, edit, allowed) {
                versions.push(next.clone());
                current = next;
            }
        }
        versions
    }
}

// ---------------------------------------------------------------------------------
// Attribute palettes: which attributes recipes set on each tag, in which ranges. The
// schema gives each one's type and length.

/// The range of values an attribute of a palette takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Domain {
    /// Numbers from `lo / 1000` to `hi / 1000` (in steps of 1/1000).
    Real(i32, i32),
    /// Integers from `lo` to `hi`.
    Int(i32, i32),
    /// One of these integers.
    IntSet(&'static [i32]),
    /// One of these keywords (each one of the schema's).
    Words(&'static [&'static str]),
    /// A non-zero direction (three numbers from -1 to 1).
    Direction,
    /// A pair `lo < hi`: `lo` from `a / 1000` to `a / 10000`, `hi` from `b / 10000`
    /// to `b / 1000` (`a < 0 < b`).
    Range(i32, i32),
}

/// How many entries an array attribute of a palette gets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Length {
    /// The schema's length (1 if it has none).
    Full,
    /// From 1 to this many.
    UpTo(u8),
}

/// One attribute of a palette.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PaletteEntry {
    /// The attribute.
    pub name: &'static str,
    /// Its values.
    pub domain: Domain,
    /// Its length, for an array.
    pub length: Length,
}

const fn p(name: &'static str, domain: Domain, length: Length) -> PaletteEntry {
    PaletteEntry { name, domain, length }
}

use Domain::{Direction, Int, IntSet, Range, Real, Words};
use Length::{Full, UpTo};

const BOOL: &[&str] = &["false", "true"];

static BODY: &[PaletteEntry] = &[
    p("pos", Real(-1000, 1000), Full),
    p("euler", Real(-90_000, 90_000), Full),
    p("gravcomp", Real(0, 1000), Full),
];
static GEOM: &[PaletteEntry] = &[
    p("pos", Real(-300, 300), Full),
    p("euler", Real(-90_000, 90_000), Full),
    p("rgba", Real(0, 1000), Full),
    p("friction", Real(100, 2000), UpTo(3)),
    p("condim", IntSet(&[1, 3, 4, 6]), Full),
    p("contype", Int(0, 3), Full),
    p("conaffinity", Int(0, 3), Full),
    p("group", Int(0, 5), Full),
    p("priority", Int(0, 2), Full),
    p("density", Real(100_000, 2_000_000), Full),
    p("margin", Real(0, 10), Full),
];
static SITE: &[PaletteEntry] =
    &[p("rgba", Real(0, 1000), Full), p("size", Real(5, 50), UpTo(3)), p("group", Int(0, 5), Full)];
static JOINT: &[PaletteEntry] = &[
    p("pos", Real(-100, 100), Full),
    p("damping", Real(0, 2000), UpTo(1)),
    p("stiffness", Real(0, 5000), UpTo(1)),
    p("armature", Real(0, 100), Full),
    p("frictionloss", Real(0, 500), Full),
    p("group", Int(0, 5), Full),
];
static CAMERA: &[PaletteEntry] = &[
    p("pos", Real(-2000, 2000), Full),
    p("euler", Real(-90_000, 90_000), Full),
    p("fovy", Real(10_000, 90_000), Full),
    p("mode", Words(&["fixed", "track", "trackcom"]), Full),
];
static LIGHT: &[PaletteEntry] = &[
    p("pos", Real(-2000, 2000), Full),
    p("dir", Direction, Full),
    p("diffuse", Real(0, 1000), Full),
    p("specular", Real(0, 500), Full),
    p("directional", Words(BOOL), Full),
    p("castshadow", Words(BOOL), Full),
];
static MATERIAL: &[PaletteEntry] = &[
    p("rgba", Real(0, 1000), Full),
    p("specular", Real(0, 1000), Full),
    p("shininess", Real(0, 1000), Full),
    p("reflectance", Real(0, 1000), Full),
    p("emission", Real(0, 1000), Full),
];
static MESH: &[PaletteEntry] = &[p("scale", Real(50, 300), Full)];
static MOTOR: &[PaletteEntry] =
    &[p("gear", Real(500, 5000), UpTo(1)), p("ctrlrange", Range(-2000, 2000), Full)];
static POSITION: &[PaletteEntry] =
    &[p("kp", Real(1000, 100_000), Full), p("ctrlrange", Range(-1500, 1500), Full)];
static VELOCITY: &[PaletteEntry] =
    &[p("kv", Real(100, 10_000), Full), p("ctrlrange", Range(-2000, 2000), Full)];
static SENSOR: &[PaletteEntry] = &[p("noise", Real(0, 10), Full)];
static TENDON: &[PaletteEntry] =
    &[p("stiffness", Real(0, 2000), UpTo(1)), p("damping", Real(0, 1000), UpTo(1))];
static DEFAULT_GEOM: &[PaletteEntry] = &[
    p("rgba", Real(0, 1000), Full),
    p("friction", Real(100, 2000), UpTo(3)),
    p("density", Real(100_000, 2_000_000), Full),
    p("condim", IntSet(&[1, 3, 4, 6]), Full),
    p("contype", Int(0, 3), Full),
    p("conaffinity", Int(0, 3), Full),
    p("group", Int(0, 5), Full),
];
static DEFAULT_JOINT: &[PaletteEntry] = &[
    p("damping", Real(0, 2000), UpTo(1)),
    p("stiffness", Real(0, 5000), UpTo(1)),
    p("armature", Real(0, 100), Full),
];
static DEFAULT_SITE: &[PaletteEntry] =
    &[p("rgba", Real(0, 1000), Full), p("group", Int(0, 5), Full)];

/// The attributes recipes set on elements of `tag` (beyond the ones a step sets
/// itself: names, references, types, sizes, axes), with their ranges;
/// `in_default` for the element in a default class. Empty for other tags.
///
/// Time: O(1).
///
/// # Examples
/// ```
/// use mjcf::generate::palette;
/// assert!(palette("geom", false).iter().any(|e| e.name == "rgba"));
/// assert!(palette("worldbody", false).is_empty());
/// ```
pub fn palette(tag: &str, in_default: bool) -> &'static [PaletteEntry] {
    if in_default {
        return match tag {
            "geom" => DEFAULT_GEOM,
            "joint" => DEFAULT_JOINT,
            "site" => DEFAULT_SITE,
            _ => &[],
        };
    }
    match tag {
        "body" => BODY,
        "geom" => GEOM,
        "site" => SITE,
        "joint" => JOINT,
        "camera" => CAMERA,
        "light" => LIGHT,
        "material" => MATERIAL,
        "mesh" => MESH,
        "motor" => MOTOR,
        "position" => POSITION,
        "velocity" => VELOCITY,
        "jointpos" | "jointvel" | "touch" | "accelerometer" | "gyro" | "framepos" => SENSOR,
        "fixed" => TENDON,
        _ => &[],
    }
}

/// `lo..=hi` thousandths, picked by `u`, as a number of at most three decimals.
fn real(lo: i32, hi: i32, u: Unit) -> f64 {
    let (lo, hi) = (i64::from(lo), i64::from(hi));
    (lo + (hi - lo) * u.thousandths() / 1000) as f64 / 1000.0
}

fn int(lo: i32, hi: i32, u: Unit) -> i32 {
    let span = (hi - lo).unsigned_abs() + 1;
    lo + (u32::from(u.0) % span) as i32
}

/// A non-zero vector from three units (each -1 to 1); `[0, 0, 1]` if all are 0.
fn direction(u: [Unit; 3]) -> Vec<f64> {
    let v: Vec<f64> = u.iter().map(|x| real(-1000, 1000, *x)).collect();
    if v.iter().all(|x| *x == 0.0) { vec![0.0, 0.0, 1.0] } else { v }
}

/// The value of a palette entry on an element of `kind`, of the type and length the
/// schema gives that attribute; `None` when the kind has no such attribute or the
/// entry does not fit its type.
///
/// Time: O(log k) for the `k` attributes of the kind.
///
/// # Examples
/// ```
/// use mjcf::ElementKind;
/// use mjcf::generate::{AttrDraw, Unit, palette, value};
/// let geom = ElementKind::ROOT.child("worldbody").unwrap().child("geom").unwrap();
/// let rgba = palette("geom", false).iter().find(|e| e.name == "rgba").unwrap();
/// let v = value(geom, rgba, &AttrDraw { values: [Unit(1000); 4], ..AttrDraw::default() });
/// assert_eq!(v, Some(vec![1.0, 1.0, 1.0, 1.0].into())); // the schema's length: 4
/// ```
pub fn value(kind: ElementKind, entry: &PaletteEntry, draw: &AttrDraw) -> Option<AttrInput> {
    let ty = kind.attr(kind.attr_index(entry.name)?).ty;
    let length = |max_len: Option<u32>| -> usize {
        let n = match entry.length {
            Length::Full => max_len.map_or(1, |n| n as usize),
            Length::UpTo(k) => 1 + usize::from(draw.len % k.max(1)),
        };
        n.clamp(1, draw.values.len())
    };
    let v = &draw.values;
    Some(match (ty, entry.domain) {
        (AttrType::Float, Domain::Real(lo, hi)) => real(lo, hi, v[0]).into(),
        (AttrType::Int, Domain::Int(lo, hi)) => int(lo, hi, v[0]).into(),
        (AttrType::Int, Domain::IntSet(set)) => set[usize::from(v[0].0) % set.len()].into(),
        (AttrType::Keyword(words), Domain::Words(ours)) => {
            let ours: Vec<&str> = ours
                .iter()
                .copied()
                .filter(|w| words.iter().any(|s| s.eq_ignore_ascii_case(w)))
                .collect();
            (*Pick(v[0].0).of(&ours)?).into()
        }
        (AttrType::Array { elem: ArrayType::Float, max_len }, Domain::Real(lo, hi)) => {
            v[..length(max_len)].iter().map(|u| real(lo, hi, *u)).collect::<Vec<f64>>().into()
        }
        (AttrType::Array { elem: ArrayType::Int, max_len }, Domain::Int(lo, hi)) => {
            v[..length(max_len)].iter().map(|u| int(lo, hi, *u)).collect::<Vec<i32>>().into()
        }
        (AttrType::Array { elem: ArrayType::Float, max_len: Some(3) }, Domain::Direction) => {
            direction([v[0], v[1], v[2]]).into()
        }
        (AttrType::Array { elem: ArrayType::Float, max_len: Some(2) }, Domain::Range(a, b)) => {
            vec![real(a, a / 10, v[0]), real(b / 10, b, v[1])].into()
        }
        _ => return None,
    })
}

/// Sets the palette attributes `draws` pick on `el` (of `kind`), each at most once
/// and none in `taken`.
fn with_extras(
    mut el: Element,
    kind: ElementKind,
    pal: &[PaletteEntry],
    draws: &[AttrDraw],
    taken: &[&str],
) -> Element {
    let mut set: HashSet<&str> = taken.iter().copied().collect();
    for d in draws.iter().take(8) {
        let Some(entry) = d.which.of(pal) else { continue };
        if !set.insert(entry.name) {
            continue;
        }
        if let Some(v) = value(kind, entry, d) {
            el = el.attr(entry.name, v);
        }
    }
    el
}

// ---------------------------------------------------------------------------------
// What steps pick from.

fn view(m: &Model, loc: &Loc) -> Option<(&'static str, ElementKind, bool)> {
    let e = m.element(loc)?;
    Some((e.tag(), e.kind(), e.is_frame()))
}

/// The worldbody, then every body that is not a frame (inside attachments too).
fn body_parents(m: &Model) -> Vec<Loc> {
    let mut out = vec![m.worldbody()];
    out.extend(m.find_all(Namespace::Body).into_iter().filter(|l| !is_frame(m, l)));
    out
}

fn is_frame(m: &Model, loc: &Loc) -> bool {
    m.element(loc).is_some_and(|e| e.is_frame())
}

/// Whether a joint of this kind fits in a body after its joints: at most 6 degrees of
/// freedom, and no rotation after a ball (MuJoCo: "ball followed by rotation").
fn joint_fits(m: &Model, body: &Loc, kind: JointKind) -> bool {
    let ball = m.element(body).is_some_and(|e| {
        e.children().any(|c| c.kind().is(Role::Joint) && c.string("type") == Some("ball"))
    });
    dofs(m, body) + kind.dofs() <= 6 && !(ball && kind != JointKind::Slide)
}

/// The degrees of freedom of a body's own joints (a freejoint has 6).
fn dofs(m: &Model, loc: &Loc) -> usize {
    m.element(loc).map_or(6, |e| {
        e.children()
            .map(|c| match (c.kind().role(), c.string("type")) {
                (Some(Role::Freejoint), _) | (Some(Role::Joint), Some("free")) => 6,
                (Some(Role::Joint), Some("ball")) => 3,
                (Some(Role::Joint), _) => 1,
                _ => 0,
            })
            .sum()
    })
}

/// The named elements of this model's own tree in `ns` that pass `keep`, with their
/// names.
fn named(m: &Model, ns: Namespace, keep: impl Fn(&Model, &Loc) -> bool) -> Vec<String> {
    m.find_all(ns)
        .into_iter()
        .filter(|l| !l.is_scoped() && keep(m, l))
        .filter(|l| !m.element(l).and_then(|e| e.parent()).is_some_and(|p| p.is_frame()))
        .filter_map(|l| m.element(&l)?.identifier().map(str::to_string))
        .collect()
}

/// Whether a joint moves along or about one axis (a hinge or a slide).
fn scalar_joint(m: &Model, loc: &Loc) -> bool {
    m.element(loc).is_some_and(|e| {
        e.kind().is(Role::Joint) && matches!(e.string("type"), None | Some("hinge" | "slide"))
    })
}

fn not_plane(m: &Model, loc: &Loc) -> bool {
    m.element(loc).is_some_and(|e| e.string("type") != Some("plane"))
}

fn not_frame(m: &Model, loc: &Loc) -> bool {
    !is_frame(m, loc)
}

fn any(_: &Model, _: &Loc) -> bool {
    true
}

/// Two different items, picked by `a` and `b`.
fn two(items: &[String], a: Pick, b: Pick) -> Option<(&str, &str)> {
    let x = a.of(items)?;
    let rest: Vec<&String> = items.iter().filter(|s| *s != x).collect();
    Some((x, b.of(&rest)?))
}

/// Whether the model has no more problems than allowed.
fn valid(m: &Model, allowed: usize) -> bool {
    m.check().len() <= allowed
}

// ---------------------------------------------------------------------------------
// Applying recipes.

const TETRAHEDRON: [f64; 12] = [0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0];
const TIMESTEPS: [f64; 4] = [0.002, 0.004, 0.005, 0.01];

struct Builder {
    budget: usize,
    /// The models `Attach` steps built, for `AttachAgain`.
    children: Vec<Model>,
    /// How many `include_copy` sources were built (their name prefixes).
    copies: usize,
}

impl Builder {
    fn new() -> Builder {
        Builder { budget: MAX_STEPS, children: Vec::new(), copies: 0 }
    }

    /// Builds a recipe's model at attachment depth `depth`; names get `prefix`.
    fn model(&mut self, r: &ModelRecipe, depth: u32, prefix: &str) -> Model {
        let mut m = Model::new(r.name.model_name());
        if let Some(t) = r.settings.timestep {
            let t = TIMESTEPS[usize::from(t) % TIMESTEPS.len()];
            if let Some(next) = m.section("option").and_then(|o| m.set_attr(&o, "timestep", t).ok())
            {
                m = next;
            }
        }
        if let Some(radian) = r.settings.radian {
            let angle = if radian { "radian" } else { "degree" };
            if let Some(next) =
                m.section("compiler").and_then(|c| m.set_attr(&c, "angle", angle).ok())
            {
                m = next;
            }
        }
        for step in &r.steps {
            if self.budget == 0 {
                break;
            }
            self.budget -= 1;
            if let Some(next) = self.step(&m, step, depth, prefix, 0) {
                m = next;
            }
        }
        m
    }

    /// Adds `make(name)` under `parent`, named from `word` (with `prefix`, and a
    /// suffix when taken; unnamed when `word` is `None`), and checks the result.
    fn add_named(
        &self,
        m: &Model,
        parent: &Loc,
        make: impl Fn(Option<&str>) -> Element,
        word: Option<&str>,
        prefix: &str,
        allowed: usize,
    ) -> Option<(Model, Loc)> {
        let (next, loc) = match word {
            None => m.add(parent, make(None)).ok()?,
            Some(w) => {
                let base = format!("{prefix}{w}");
                let mut found = None;
                for k in 1..=6 {
                    let name = if k == 1 { base.clone() } else { format!("{base}_{k}") };
                    match m.add(parent, make(Some(&name))) {
                        Ok(r) => {
                            found = Some(r);
                            break;
                        }
                        Err(e) if matches!(e.kind(), ErrorKind::DuplicateIdentifier { .. }) => {}
                        Err(_) => return None,
                    }
                }
                found?
            }
        };
        valid(&next, allowed).then_some((next, loc))
    }

    fn geom(
        &self,
        m: &Model,
        kind: ElementKind,
        g: &GeomRecipe,
        in_world: bool,
        scoped: bool,
        name: Option<&str>,
    ) -> Element {
        let size =
            |n: usize| -> Vec<f64> { g.size[..n].iter().map(|u| real(20, 300, *u)).collect() };
        let mut el = Element::new("geom");
        let mut taken = vec!["type", "size"];
        let meshes = if scoped { Vec::new() } else { named(m, Namespace::Mesh, any) };
        el = match g.shape {
            Shape::Plane if in_world => el.attr("type", "plane").attr("size", size(3)),
            Shape::Box | Shape::Plane => el.attr("type", "box").attr("size", size(3)),
            Shape::Capsule => el.attr("type", "capsule").attr("size", size(2)),
            Shape::Cylinder => el.attr("type", "cylinder").attr("size", size(2)),
            Shape::Ellipsoid => el.attr("type", "ellipsoid").attr("size", size(3)),
            Shape::Mesh(i) if !meshes.is_empty() => {
                el.attr("type", "mesh").attr("mesh", i.of(&meshes).map_or("", String::as_str))
            }
            Shape::Sphere | Shape::Mesh(_) => el.attr("size", size(1)),
        };
        if !scoped {
            if let Some(c) = g.class.and_then(|c| c.of(&named(m, Namespace::Default, any)).cloned())
            {
                el = el.attr("class", c);
                taken.push("class");
            }
            if let Some(mat) =
                g.material.and_then(|c| c.of(&named(m, Namespace::Material, any)).cloned())
            {
                el = el.attr("material", mat);
                taken.push("material");
            }
        }
        if let Some(n) = name {
            el = el.attr("name", n);
        }
        with_extras(el, kind, palette("geom", false), &g.extras, &taken)
    }

    /// Carries out one step on `m`; `None` when it does not apply or would leave
    /// more than `allowed` problems.
    fn step(
        &mut self,
        m: &Model,
        step: &Step,
        depth: u32,
        prefix: &str,
        allowed: usize,
    ) -> Option<Model> {
        let world = m.worldbody();
        match step {
            Step::Body { parent, name, pos, geom, free, childclass, extras } => {
                let p = parent.of(&body_parents(m))?.clone();
                let kind = view(m, &p)?.1.child("body")?;
                let gkind = kind.child("geom")?;
                // Directly in the worldbody of the outermost model: an attached model's
                // worldbody is a frame in the composed model.
                let top = p == world && depth == 0;
                let scoped = p.is_scoped();
                let class = if scoped {
                    None
                } else {
                    childclass.and_then(|c| c.of(&named(m, Namespace::Default, any)).cloned())
                };
                let pos: Vec<f64> = pos.iter().map(|u| real(-1000, 1000, *u)).collect();
                let g = self.geom(m, gkind, geom, false, scoped, None);
                let make = |n: Option<&str>| {
                    let mut el = Element::new("body");
                    if let Some(n) = n {
                        el = el.attr("name", n);
                    }
                    el = el.attr("pos", pos.clone());
                    let mut taken = vec!["pos"];
                    if let Some(c) = &class {
                        el = el.attr("childclass", c.as_str());
                        taken.push("childclass");
                    }
                    el = with_extras(el, kind, palette("body", false), extras, &taken)
                        .child(g.clone());
                    if *free && top { el.child(Element::new("freejoint")) } else { el }
                };
                self.add_named(m, &p, make, name.map(Word::text), prefix, allowed).map(|r| r.0)
            }
            Step::Geom { parent, geom } => {
                let p = parent.of(&body_parents(m))?.clone();
                let kind = view(m, &p)?.1.child("geom")?;
                let (top, scoped) = (p == world && depth == 0, p.is_scoped());
                let make = |n: Option<&str>| self.geom(m, kind, geom, top, scoped, n);
                self.add_named(m, &p, make, geom.name.map(Word::text), prefix, allowed).map(|r| r.0)
            }
            Step::Site { parent, name, pos, extras } => {
                let p = parent.of(&body_parents(m))?.clone();
                let kind = view(m, &p)?.1.child("site")?;
                let pos: Vec<f64> = pos.iter().map(|u| real(-1000, 1000, *u)).collect();
                let make = |n: Option<&str>| {
                    let el = Element::new("site").attr("pos", pos.clone());
                    let el = with_extras(el, kind, palette("site", false), extras, &["pos"]);
                    if let Some(n) = n { el.attr("name", n) } else { el }
                };
                self.add_named(m, &p, make, name.map(Word::text), prefix, allowed).map(|r| r.0)
            }
            Step::Joint { body, name, kind: jk, axis, range, class, extras } => {
                // Bodies where the joint fits: no freejoint, at most 6 degrees of freedom.
                let bodies: Vec<Loc> =
                    body_parents(m).into_iter().skip(1).filter(|b| joint_fits(m, b, *jk)).collect();
                let b = body.of(&bodies)?.clone();
                let kind = view(m, &b)?.1.child("joint")?;
                let class = if b.is_scoped() {
                    None
                } else {
                    class.and_then(|c| c.of(&named(m, Namespace::Default, any)).cloned())
                };
                let make = |n: Option<&str>| {
                    let mut el = Element::new("joint").attr("type", jk.keyword());
                    let mut taken = vec!["type", "axis", "range"];
                    if *jk != JointKind::Ball {
                        el = el.attr("axis", direction(*axis));
                        if let Some([lo, hi]) = range {
                            el = el.attr("range", [real(-1500, -100, *lo), real(100, 1500, *hi)]);
                        }
                    }
                    if let Some(c) = &class {
                        el = el.attr("class", c.as_str());
                        taken.push("class");
                    }
                    if let Some(n) = n {
                        el = el.attr("name", n);
                    }
                    with_extras(el, kind, palette("joint", false), extras, &taken)
                };
                self.add_named(m, &b, make, name.map(Word::text), prefix, allowed).map(|r| r.0)
            }
            Step::Camera { parent, name, extras } | Step::Light { parent, name, extras } => {
                let tag = if matches!(step, Step::Camera { .. }) { "camera" } else { "light" };
                let p = parent.of(&body_parents(m))?.clone();
                let kind = view(m, &p)?.1.child(tag)?;
                let make = |n: Option<&str>| {
                    let el = with_extras(Element::new(tag), kind, palette(tag, false), extras, &[]);
                    if let Some(n) = n { el.attr("name", n) } else { el }
                };
                self.add_named(m, &p, make, name.map(Word::text), prefix, allowed).map(|r| r.0)
            }
            Step::Class { parent, name, defaults } => {
                let mut parents = vec![m.default_class()];
                parents.extend(m.find_all(Namespace::Default).into_iter().filter(|l| {
                    !l.is_scoped() && m.element(l).is_some_and(|e| e.identifier().is_some())
                }));
                let p = parent.of(&parents)?.clone();
                let kind = view(m, &p)?.1.child("default")?;
                let make = |n: Option<&str>| {
                    let mut el = Element::new("default").attr("class", n.unwrap_or("x"));
                    for t in [DefaultTag::Geom, DefaultTag::Joint, DefaultTag::Site] {
                        let draws: Vec<AttrDraw> =
                            defaults.iter().filter(|(d, _)| *d == t).map(|(_, a)| *a).collect();
                        let Some(ck) = kind.child(t.tag()) else { continue };
                        if !draws.is_empty() {
                            let child = Element::new(t.tag());
                            el = el.child(with_extras(
                                child,
                                ck,
                                palette(t.tag(), true),
                                &draws,
                                &[],
                            ));
                        }
                    }
                    el
                };
                self.add_named(m, &p, make, Some(name.text()), prefix, allowed).map(|r| r.0)
            }
            Step::Material { name, extras } => {
                let asset = m.asset();
                let kind = view(m, &asset)?.1.child("material")?;
                let make = |n: Option<&str>| {
                    let el = Element::new("material").attr("name", n.unwrap_or("x"));
                    with_extras(el, kind, palette("material", false), extras, &[])
                };
                self.add_named(m, &asset, make, Some(name.text()), prefix, allowed).map(|r| r.0)
            }
            Step::Mesh { name, scale } => {
                let asset = m.asset();
                let scale: Vec<f64> = scale.iter().map(|u| real(50, 300, *u)).collect();
                let make = |n: Option<&str>| {
                    Element::new("mesh")
                        .attr("name", n.unwrap_or("x"))
                        .attr("vertex", TETRAHEDRON)
                        .attr("scale", scale.clone())
                };
                self.add_named(m, &asset, make, Some(name.text()), prefix, allowed).map(|r| r.0)
            }
            Step::Actuator { kind: ak, name, joint, extras } => {
                let joints = named(m, Namespace::Joint, scalar_joint);
                let j = joint.of(&joints)?.clone();
                let section = m.actuator();
                let tag = match ak {
                    ActuatorKind::Motor => "motor",
                    ActuatorKind::Position => "position",
                    ActuatorKind::Velocity => "velocity",
                };
                let kind = view(m, &section)?.1.child(tag)?;
                let make = |n: Option<&str>| {
                    let el = Element::new(tag).attr("joint", j.as_str());
                    let el = with_extras(el, kind, palette(tag, false), extras, &["joint"]);
                    if let Some(n) = n { el.attr("name", n) } else { el }
                };
                self.add_named(m, &section, make, name.map(Word::text), prefix, allowed)
                    .map(|r| r.0)
            }
            Step::Sensor { kind: sk, name, target, extras } => {
                let section = m.sensor();
                let (tag, attrs): (&str, Vec<(&str, String)>) = match sk {
                    SensorKind::JointPos | SensorKind::JointVel => {
                        let t = if *sk == SensorKind::JointPos { "jointpos" } else { "jointvel" };
                        let j = target.of(&named(m, Namespace::Joint, scalar_joint))?.clone();
                        (t, vec![("joint", j)])
                    }
                    SensorKind::Touch | SensorKind::Accelerometer | SensorKind::Gyro => {
                        let t = match sk {
                            SensorKind::Touch => "touch",
                            SensorKind::Accelerometer => "accelerometer",
                            _ => "gyro",
                        };
                        (t, vec![("site", target.of(&named(m, Namespace::Site, any))?.clone())])
                    }
                    SensorKind::FramePos(obj) => {
                        let (objtype, names) = match obj {
                            ObjKind::Body => ("body", named(m, Namespace::Body, not_frame)),
                            ObjKind::Geom => ("geom", named(m, Namespace::Geom, any)),
                            ObjKind::Site => ("site", named(m, Namespace::Site, any)),
                        };
                        let o = target.of(&names)?.clone();
                        ("framepos", vec![("objtype", objtype.to_string()), ("objname", o)])
                    }
                };
                let kind = view(m, &section)?.1.child(tag)?;
                let make = |n: Option<&str>| {
                    let mut el = Element::new(tag);
                    for (k, v) in &attrs {
                        el = el.attr(k, v.as_str());
                    }
                    let el = with_extras(el, kind, palette(tag, false), extras, &[]);
                    if let Some(n) = n { el.attr("name", n) } else { el }
                };
                self.add_named(m, &section, make, name.map(Word::text), prefix, allowed)
                    .map(|r| r.0)
            }
            Step::Tendon { name, joints } => {
                let all = named(m, Namespace::Joint, scalar_joint);
                let mut chosen: Vec<(String, f64)> = Vec::new();
                for (j, c) in joints.iter().take(4) {
                    let j = j.of(&all)?;
                    if !chosen.iter().any(|(k, _)| k == j) {
                        chosen.push((j.clone(), real(100, 2000, *c)));
                    }
                }
                if chosen.is_empty() {
                    return None;
                }
                let section = m.section("tendon")?;
                let make = |n: Option<&str>| {
                    let mut el = Element::new("fixed");
                    if let Some(n) = n {
                        el = el.attr("name", n);
                    }
                    for (j, c) in &chosen {
                        el = el.child(
                            Element::new("joint").attr("joint", j.as_str()).attr("coef", *c),
                        );
                    }
                    el
                };
                self.add_named(m, &section, make, name.map(Word::text), prefix, allowed)
                    .map(|r| r.0)
            }
            Step::Equality { kind: ek, name, first, second } => {
                let section = m.section("equality")?;
                let (tag, a, b, names) = match ek {
                    EqualityKind::Connect => {
                        ("connect", "body1", "body2", named(m, Namespace::Body, not_frame))
                    }
                    EqualityKind::Weld => {
                        ("weld", "body1", "body2", named(m, Namespace::Body, not_frame))
                    }
                    EqualityKind::Joint => {
                        ("joint", "joint1", "joint2", named(m, Namespace::Joint, scalar_joint))
                    }
                };
                let (x, y) = two(&names, *first, *second)?;
                let anchor = [real(-100, 100, Unit(first.0)), 0.0, 0.0];
                let make = |n: Option<&str>| {
                    let mut el = Element::new(tag).attr(a, x).attr(b, y);
                    if *ek == EqualityKind::Connect {
                        el = el.attr("anchor", anchor);
                    }
                    if let Some(n) = n { el.attr("name", n) } else { el }
                };
                self.add_named(m, &section, make, name.map(Word::text), prefix, allowed)
                    .map(|r| r.0)
            }
            Step::Exclude { first, second } | Step::Pair { first, second } => {
                let section = m.section("contact")?;
                let (tag, a, b, names) = if matches!(step, Step::Exclude { .. }) {
                    ("exclude", "body1", "body2", named(m, Namespace::Body, not_frame))
                } else {
                    ("pair", "geom1", "geom2", named(m, Namespace::Geom, not_plane))
                };
                let (x, y) = two(&names, *first, *second)?;
                // Each pair once, either way round.
                let exists = m.element(&section)?.children().any(|c| {
                    c.tag() == tag
                        && matches!((c.string(a), c.string(b)), (Some(p), Some(q)) if (p, q) == (x, y) || (p, q) == (y, x))
                });
                if exists {
                    return None;
                }
                let el = Element::new(tag).attr(a, x).attr(b, y);
                let (next, _) = m.add(&section, el).ok()?;
                valid(&next, allowed).then_some(next)
            }
            Step::Attach { at, child, frame } => {
                if depth + 1 > MAX_DEPTH {
                    return None;
                }
                let child = self.model(child, depth + 1, "");
                self.children.push(child.clone());
                self.attach(m, *at, &child, frame, depth, prefix, allowed)
            }
            Step::AttachAgain { at, child, frame } => {
                let child = child.of(&self.children)?.clone();
                self.attach(m, *at, &child, frame, depth, prefix, allowed)
            }
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn attach(
        &self,
        m: &Model,
        at: Pick,
        child: &Model,
        frame: &FrameRecipe,
        depth: u32,
        prefix: &str,
        allowed: usize,
    ) -> Option<Model> {
        let mut places = vec![m.worldbody()];
        places.extend(m.find_all(Namespace::Site));
        let place = at.of(&places)?.clone();
        // The frame goes where the site is: directly in the worldbody, or not.
        let top = depth == 0
            && (place == m.worldbody()
                || m.element(&place)
                    .and_then(|e| e.parent())
                    .is_some_and(|p| p.kind().is(Role::Worldbody)));
        let (mut next, a) = m.attach(&place, child).ok()?;
        let frame_loc = a.frame().clone();
        let inertial = || {
            Element::new("inertial")
                .attr("pos", [0.0, 0.0, 0.0])
                .attr("mass", 0.1)
                .attr("diaginertia", [0.001, 0.001, 0.001])
        };
        if frame.free && top {
            next = next.add(&frame_loc, Element::new("freejoint")).ok()?.0;
            next = next.add(&frame_loc, inertial()).ok()?.0;
        } else if !frame.joints.is_empty() {
            // Joints that fit (at most 6 degrees of freedom, no rotation after a
            // ball joint); any number unnamed.
            let mut added = false;
            for j in frame.joints.iter().take(3) {
                if !joint_fits(&next, &frame_loc, j.kind) {
                    continue;
                }
                let make = |n: Option<&str>| {
                    let el = Element::new("joint").attr("type", j.kind.keyword());
                    let el = if j.kind == JointKind::Ball {
                        el
                    } else {
                        el.attr("axis", direction(j.axis))
                    };
                    if let Some(n) = n { el.attr("name", n) } else { el }
                };
                if let Some((n, _)) = self.add_named(
                    &next,
                    &frame_loc,
                    make,
                    j.name.map(Word::frame_joint_name),
                    prefix,
                    usize::MAX,
                ) {
                    next = n;
                    added = true;
                }
            }
            if added {
                next = next.add(&frame_loc, inertial()).ok()?.0;
            }
        }
        let small = next.walk().filter(|e| matches!(e, Event::Enter(_))).count() <= MAX_ELEMENTS;
        (small && valid(&next, allowed)).then_some(next)
    }

    /// Carries out one edit; `None` when it does not apply or would leave more than
    /// `allowed` problems.
    fn edit(&mut self, m: &Model, edit: &Edit, allowed: usize) -> Option<Model> {
        match edit {
            Edit::Add(step) => self.step(m, step, 0, "", allowed),
            Edit::Set { target, attr } => {
                let targets = elements(m, |e| !palette(e.tag, e.in_default).is_empty());
                let t = target.of(&targets)?;
                let entry = attr.which.of(palette(t.tag, t.in_default))?;
                let v = value(t.kind, entry, attr)?;
                let next = m.set_attr(&t.loc, entry.name, v).ok()?;
                valid(&next, allowed).then_some(next)
            }
            Edit::Rename { target, name } => {
                let targets = elements(m, |e| {
                    e.kind.identifier().is_some()
                        && !e.frame
                        && !e.in_frame
                        && e.kind != m_default_kind()
                });
                let t = target.of(&targets)?;
                let attr = t.kind.attr(t.kind.identifier()?).name;
                let next = match name {
                    None => {
                        // Only elements nothing refers to, that need no name.
                        let needs_name = matches!(
                            t.kind.role(),
                            Some(Role::DefaultClass | Role::Material | Role::Mesh)
                        );
                        if needs_name || !m.references_to(&t.loc).is_empty() {
                            return None;
                        }
                        m.clear_attr(&t.loc, attr).ok()?
                    }
                    Some(w) => {
                        let mut found = None;
                        for k in 1..=6 {
                            let n = if k == 1 {
                                w.text().to_string()
                            } else {
                                format!("{}_{k}", w.text())
                            };
                            match m.set_attr(&t.loc, attr, n.as_str()) {
                                Ok(r) => {
                                    found = Some(r);
                                    break;
                                }
                                Err(e)
                                    if matches!(
                                        e.kind(),
                                        ErrorKind::DuplicateIdentifier { .. }
                                    ) => {}
                                Err(_) => return None,
                            }
                        }
                        found?
                    }
                };
                valid(&next, allowed).then_some(next)
            }
            Edit::Remove { target } => {
                let targets = elements(m, |e| e.removable);
                let t = target.of(&targets)?;
                remove_repaired(m, &t.loc, allowed)
            }
            Edit::Detach { scope } => {
                let s = scope.of(&m.scope_paths())?.clone();
                let next = m.detach(&s).ok()?;
                valid(&next, allowed).then_some(next)
            }
            Edit::RenameScope { scope, to } => {
                let s = scope.of(&m.scope_paths())?.clone();
                let next = m.rename_scope(&s, to.model_name()).ok()?;
                valid(&next, allowed).then_some(next)
            }
            Edit::IncludeCopy { source, override_attributes } => {
                self.copies += 1;
                let prefix = format!("c{}_", self.copies);
                let source = self.model(source, MAX_DEPTH, &prefix);
                let next = m.include_copy(&source, *override_attributes).ok()?;
                valid(&next, allowed).then_some(next)
            }
        }
    }
}

/// The kind of the root default class.
fn m_default_kind() -> ElementKind {
    ElementKind::ROOT.child("default").unwrap_or(ElementKind::ROOT)
}

/// An element of the composed model, as edits pick them.
struct Target {
    loc: Loc,
    tag: &'static str,
    kind: ElementKind,
    frame: bool,
    in_default: bool,
    /// A child of an attachment frame (a frame joint or inertial).
    in_frame: bool,
    removable: bool,
}

/// The elements of the composed model (walk order) that pass `keep`.
fn elements(m: &Model, keep: impl Fn(&Target) -> bool) -> Vec<Target> {
    let mut out = Vec::new();
    // Per open element: whether it is an attachment frame.
    let mut stack: Vec<bool> = Vec::new();
    for event in m.walk() {
        match event {
            Event::Enter(e) => {
                let parent_frame = stack.last().copied().unwrap_or(false);
                let kind = e.kind();
                let multiplicity = kind.multiplicity();
                let t = Target {
                    loc: e.loc(),
                    tag: e.tag(),
                    kind,
                    frame: e.is_frame(),
                    in_default: kind.spec().parent.is_some_and(|p| p.is(Role::DefaultClass)),
                    in_frame: parent_frame,
                    removable: stack.len() >= 2
                        && !e.is_frame()
                        && multiplicity != crate::schema::Multiplicity::Singleton,
                };
                stack.push(e.is_frame());
                if keep(&t) {
                    out.push(t);
                }
            }
            Event::Leave(_) => {
                stack.pop();
            }
        }
    }
    out
}

/// Removes `loc`, then repairs what referred to anything removed: optional
/// references in the body tree and in assets are cleared, other referring elements
/// removed (a tendon's joint takes its tendon along). `None` if that does not bring
/// the problems back to `allowed`.
fn remove_repaired(m: &Model, loc: &Loc, allowed: usize) -> Option<Model> {
    let mut cur = m.remove(loc).ok()?;
    for _ in 0..16 {
        let problems = cur.check();
        if problems.len() <= allowed {
            return Some(cur);
        }
        let p = problems.into_iter().find(|p| {
            matches!(
                p.kind,
                ProblemKind::DanglingReference { .. }
                    | ProblemKind::RemovedReference { .. }
                    | ProblemKind::MissingRequired { .. }
            )
        })?;
        let e = cur.element(&p.loc)?;
        let parent = e.parent()?;
        let attribute = match p.kind {
            ProblemKind::DanglingReference { attribute, .. }
            | ProblemKind::RemovedReference { attribute }
            | ProblemKind::MissingRequired { attribute } => attribute,
            _ => return None,
        };
        let optional = !e.kind().attr(e.kind().attr_index(attribute)?).required;
        let in_tendon = parent.kind().is(Role::Tendon);
        let in_tree = !in_tendon && (in_body_tree(e.kind()) || in_assets(e.kind()));
        cur = if e.kind().is(Role::Geom) && attribute == "mesh" {
            // A mesh geom without its mesh becomes a sphere.
            let attrs = Attrs::new().clear("mesh").set("type", "sphere").set("size", [0.1]);
            cur.set(&p.loc, attrs).ok()?
        } else if optional && in_tree {
            cur.clear_attr(&p.loc, attribute).ok()?
        } else if in_tendon {
            cur.remove(&parent.loc()).ok()?
        } else {
            cur.remove(&p.loc).ok()?
        };
    }
    None
}

/// Whether elements of `kind` are in the kinematic tree (below the worldbody).
fn in_body_tree(kind: ElementKind) -> bool {
    let mut cur = kind.spec().parent;
    while let Some(k) = cur {
        if k.is(Role::Worldbody) {
            return true;
        }
        cur = k.spec().parent;
    }
    false
}

/// Whether elements of `kind` are assets (children of the `<asset>` section).
fn in_assets(kind: ElementKind) -> bool {
    kind.spec().parent.is_some_and(|p| Some(p) == ElementKind::ROOT.child("asset"))
}
