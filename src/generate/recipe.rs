//! Recipes: models and edit sequences as plain data (no model, no locator), with the
//! bounds every application keeps ([`MAX_STEPS`], [`MAX_DEPTH`], [`MAX_ELEMENTS`]).
//! [`ModelRecipe::build`] and [`EditRecipe::apply`] are in `builder`.

use crate::model::JointType;

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
#[derive(Clone, Copy, Default, PartialEq, Eq, Hash)]
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
#[derive(Clone, Copy, Default, PartialEq, Eq, Hash)]
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
#[derive(Clone, Copy, Default, PartialEq, Eq, Hash)]
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
    /// model can share (the names written for both then meet: decision D14); an
    /// element name ([`Word::text`]) otherwise.
    ///
    /// Time: O(1).
    pub fn frame_joint_name(self) -> &'static str {
        if self.0 % 2 == 1 { Word(self.0 / 2).model_name() } else { self.text() }
    }
}

/// One more attribute of an element: which one of the attributes recipes set on
/// that tag ([`palette`](super::palette())), and the numbers its value is made from (the schema gives
/// its type and length: a float, an array, an integer or a keyword).
#[derive(Clone, Copy, Default, PartialEq, Eq, Hash)]
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
        self.joint_type().nv()
    }

    /// The `type` keyword.
    ///
    /// Time: O(1).
    pub fn keyword(self) -> &'static str {
        self.joint_type().keyword()
    }

    /// The joint type it makes.
    ///
    /// Time: O(1).
    pub fn joint_type(self) -> JointType {
        match self {
            JointKind::Hinge => JointType::Hinge,
            JointKind::Slide => JointType::Slide,
            JointKind::Ball => JointType::Ball,
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
    pub(super) fn tag(self) -> &'static str {
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
    /// More attributes ([`palette`](super::palette()) of `geom`).
    pub extras: Vec<AttrDraw>,
}

/// One joint of an attachment frame.
#[derive(Clone, Copy, Default, PartialEq, Eq, Hash)]
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
    /// attached); unused by [`Palette::Simulates`], which keeps MuJoCo's 0.002.
    pub timestep: Option<u8>,
    /// `compiler/@angle`: `radian` (true) or `degree` (false); two models that set
    /// it differently are not attached to one another (the attach is skipped, as
    /// before `attach` converted such a child, decision D17, so that a seed keeps
    /// giving the same models).
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
        /// More attributes ([`palette`](super::palette()) of `body`).
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
        /// More attributes ([`palette`](super::palette()) of `site`).
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
        /// More attributes ([`palette`](super::palette()) of `joint`).
        extras: Vec<AttrDraw>,
    },
    /// A camera under the worldbody or a body.
    Camera {
        /// The parent, as for [`Step::Body`].
        parent: Pick,
        /// Its name, if any.
        name: Option<Word>,
        /// More attributes ([`palette`](super::palette()) of `camera`).
        extras: Vec<AttrDraw>,
    },
    /// A light under the worldbody or a body.
    Light {
        /// The parent, as for [`Step::Body`].
        parent: Pick,
        /// Its name, if any.
        name: Option<Word>,
        /// More attributes ([`palette`](super::palette()) of `light`).
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
        /// More attributes ([`palette`](super::palette()) of `material`).
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
        /// More attributes ([`palette`](super::palette()) of the actuator's tag).
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
        /// More attributes ([`palette`](super::palette()) of the sensor's tag).
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
    /// A MuJoCo `<frame>` (a placement, no body of its own) under the worldbody, a
    /// body or another `<frame>`: bodies, geoms and sites can then go inside it.
    Frame {
        /// The parent, as for [`Step::Body`] (`<frame>`s included).
        parent: Pick,
        /// Its position (each coordinate -1 to 1).
        pos: [Unit; 3],
        /// Its orientation (`euler`, each angle -90 to 90 degrees).
        euler: [Unit; 3],
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

/// Which models a recipe builds: the shapes its steps may make, and whether a step
/// that [`Model::check`](crate::Model::check) finds a problem in is skipped. Only the
/// outermost recipe's palette counts: the recipes it attaches are built with it.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum Palette {
    /// Valid models (the default): `check` finds nothing, MuJoCo compiles them.
    /// Attached models have no free bodies and no planes of their own, and
    /// freejoints go only on frames directly in the outermost worldbody.
    #[default]
    Valid,
    /// Also the shapes MuJoCo may refuse, for judging `check` against MuJoCo: attached
    /// models with free bodies and planes in their worldbody, attachment frames with
    /// a freejoint wherever they are (inside moving bodies, `<frame>`s and other
    /// attached models); [`Step::Frame`]s in the strategies' recipes. No step is
    /// skipped for what `check` says, so a built model may have problems.
    Wide,
    /// Valid models that simulate: what [`Palette::Valid`] gives, within ranges that
    /// keep MuJoCo's simulation stable: no geom smaller than 0.05, every joint and
    /// attachment-frame joint with armature (at least 0.1) and damping (at least 1),
    /// the `implicitfast` integrator at MuJoCo's default timestep, and each geom's
    /// `contype`/`conaffinity` set by what moves it (the module docs say why).
    Simulates,
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
#[derive(Clone, Default, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub struct ModelRecipe {
    /// The model name ([`Word::model_name`]).
    pub name: Word,
    /// Its global settings.
    pub settings: Settings,
    /// The steps, in order.
    pub steps: Vec<Step>,
    /// Which models it builds (of an attached recipe: unused, the outermost one's
    /// counts). Bytes for a fuzzer always give [`Palette::Valid`].
    #[cfg_attr(feature = "arbitrary", arbitrary(default))]
    pub palette: Palette,
}

/// One edit of an [`EditRecipe`]. Targets are picked in the composed model (inside
/// attachments too) when the edit runs.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "arbitrary", derive(arbitrary::Arbitrary))]
pub enum Edit {
    /// Adds what a step adds (an attach included).
    Add(Step),
    /// Sets one attribute of an element ([`palette`](super::palette()) of its tag).
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
