//! Build and compose MuJoCo MJCF models as persistent values.
//!
//! A [`Model`] is an immutable value: every edit returns a new model and leaves the old
//! one as it was. Versions share every subtree an edit did not touch, so keeping old
//! versions (undo) costs only what changed, and `clone()` is a pointer copy.
//!
//! ```
//! use mjcf::{Model, Namespace, element};
//!
//! let mut arena = Model::new("arena");
//! let floor = element!("geom", name = "floor", type = "plane", size = [5.0, 5.0, 0.1]);
//! arena.add_mut(&arena.worldbody(), floor)?;
//! let spawn = arena.add_mut(&arena.worldbody(), element!("site", name = "spawn"))?;
//!
//! let mut robot = Model::new("robot");
//! robot.add_mut(&robot.worldbody(), element!("body", name = "torso"))?;
//!
//! let before = arena.clone(); // O(1); an undo point
//! let a = arena.attach_mut(&spawn, &robot)?;
//! arena.add_mut(a.frame(), element!("freejoint"))?;
//! assert!(arena.to_xml_string()?.contains(r#"<body name="robot/torso"/>"#));
//! arena.detach_mut(&a)?;
//! assert_eq!(arena, before);
//! # Ok::<(), mjcf::Error>(())
//! ```
//!
//! Every edit comes twice: `add(&self, ..) -> Result<(Model, Loc)>` returns the new
//! version for functional code, and `add_mut(&mut self, ..) -> Result<Loc>` replaces
//! the model in place (atomically: on error it is unchanged, as every operation
//! promises: [Guarantees and limits](crate::guide#guarantees-and-limits)). Either way,
//! values taken before the edit keep their content. The [`guide`] is the manual.
//!
//! # What is shared, and what an edit costs
//! - Nodes are `Arc`-shared and hold no parent pointers; the children of an element
//!   are a chunked persistent sequence (`Arc`'d chunks of at most `max(64, √width)`
//!   nodes, for `width` children).
//! - An edit copies the path from the edited element to the root, and on that path
//!   the chunk list and one chunk of each children sequence: O(depth · √width)
//!   pointer copies at worst, O(depth) for narrow trees.
//! - Each model keeps a persistent identifier index (O(log n) `find` of an existing
//!   name, and duplicate checks), updated by every edit.
//! - Everything that depends on where an element sits (scope prefixes, auto names,
//!   default-class names: [Names](crate::guide#names); merged settings) is computed
//!   when the model is written or walked, never stored.
//!
//! # Costs
//! Every function states its time as `Time: O(..)`, in these terms:
//! - `n`: the elements of the model (its own tree: an attached model's elements
//!   count in that model's `n`); `N`: the elements of the composed model, attached
//!   models included;
//! - `depth`: the nesting depth of the element an operation is aimed at; `width`: the
//!   most siblings of an element on the way down to it;
//! - `levels`: the models on the way to that element: 1 for the model's own elements,
//!   one more per attachment it lies inside; `a`: the attachments of the composed
//!   model, at every level;
//! - `s`: the elements of a subtree added, copied or removed.
//!
//! Two costs recur:
//! - locating an element by its [`Loc`] follows parent links in the identifier
//!   index and, at each level, the element's position when it was indexed:
//!   O(depth · log n). After siblings before it were removed (or many inserted),
//!   that position is off and finding the element scans up to O(width) at that level.
//! - an edit copies the path: O(depth · √width), as above. Dropping a version frees
//!   only what no other version shares; an in-place edit frees about what it copied,
//!   plus whatever it removed that nothing else holds.
#![forbid(unsafe_code)]

// The unit tests share the integration tests' fixtures (`tests/support`), which name
// the crate `mjcf`.
#[cfg(test)]
extern crate self as mjcf;

mod compose;
#[doc = include_str!("decisions.md")]
pub mod decisions {}
#[doc = include_str!("guide.md")]
pub mod guide {}
mod error;
mod files;
#[cfg(any(test, feature = "proptest", feature = "arbitrary"))]
pub mod generate;
mod history;
mod id;
mod model;
mod schema;
mod seq;
mod suggest;
mod value;
mod write_options;
mod xml;

pub use crate::compose::Part;
pub use crate::error::{
    EditError, Error, ErrorKind, ExportError, ReadError, TextPos, ValueError, WriteError,
};
pub use crate::history::History;
pub use crate::id::ElementId;
pub use crate::model::diff::Change;
pub use crate::model::{
    Advice, AdviceKind, Attachment, Attrs, Element, ElementRef, Event, JointType, Layout,
    LayoutActuator, LayoutJoint, LayoutMocap, Loc, MAX_LAYOUT_ENTRIES, Model, Preorder, Problem,
    ProblemKind, Referrers, Removal, ScopeRef,
};
pub use crate::schema::{
    ArrayType, AttrSpec, AttrType, ElementKind, ElementSpec, Merge, Multiplicity, Namespace,
    PathNamespace, RefTarget,
};
pub use crate::value::{AttrInput, FileAsset, Reference, Value};
pub use crate::xml::{
    ReadOptions, SaveError, SaveOptions, SavedScene, Scene, ScenePart, SourceText, WriteOptions,
    Written, WrittenElement,
};

/// An [`Element`] with attributes, as `Element::new(tag).attr(name, value)...`:
/// `element!("geom", type = "box", size = [0.1, 0.1, 0.1], mass = 1)`.
///
/// Attribute names are written as bare words (`type`, `class` and other keywords
/// included); values are anything [`Value`] inputs convert from: text,
/// numbers, arrays of numbers, booleans. A bracketed list written in the call may mix
/// integers and floats, as in Python (`size = [2, 2, 0.1]`): each item is converted by
/// `f64::from`, so any number type that converts to `f64` without loss fits (`i32`,
/// `u32`, `f32`, ...; a `usize` or `i64` needs `as f64`). Nothing is checked until
/// the element is added to a model.
///
/// # Examples
/// ```
/// use mjcf::{Element, element};
/// let a = element!("geom", type = "box", size = [0.1, 0.1, 0.1], mass = 1);
/// let b = Element::new("geom").attr("type", "box").attr("size", [0.1, 0.1, 0.1]).attr("mass", 1);
/// assert_eq!(a, b);
/// // Keywords are bare words; a raw identifier is the same name.
/// assert_eq!(element!("joint", ref = 0.5), element!("joint", r#ref = 0.5));
/// // Integers and floats mixed in one list, as Python's `[2, 2, .1]`:
/// let (x, i) = (0.5_f32, 3_u32);
/// let c = element!("camera", xyaxes = [0, 1, 0, -0.5, x, i], pos = [2, 2, 0.1]);
/// assert_eq!(c, Element::new("camera").attr("xyaxes", [0.0, 1.0, 0.0, -0.5, 0.5, 3.0]).attr("pos", [2.0, 2.0, 0.1]));
/// ```
#[macro_export]
macro_rules! element {
    ($tag:expr $(, $($attrs:tt)*)?) => {
        $crate::__assign!(attr; $crate::Element::new($tag); $($($attrs)*)?)
    };
}

/// [`Attrs`] written as [`element!`]'s attributes, for [`Model::set`](crate::Model::set):
/// `attrs!(rgba = [1, 0.5, 0, 1], mass = 2)` is
/// `Attrs::new().set("rgba", [1.0, 0.5, 0.0, 1.0]).set("mass", 2)`. A bracketed list
/// may mix integers and floats, as in [`element!`].
///
/// # Examples
/// ```
/// use mjcf::{Model, attrs, element};
/// let mut m = Model::new("m");
/// let g = m.add_top_mut(element!("geom", size = [0.1]))?;
/// m.set_mut(&g, attrs!(rgba = [1, 0.5, 0, 1], mass = 2))?;
/// assert_eq!(m.floats(&g, "rgba")?, [1.0, 0.5, 0.0, 1.0]);
/// # Ok::<(), mjcf::EditError>(())
/// ```
#[macro_export]
macro_rules! attrs {
    ($($attrs:tt)*) => {
        $crate::__assign!(set; $crate::Attrs::new(); $($attrs)*)
    };
}

/// The attribute list of [`element!`] and [`attrs!`]: `$method` (`attr` or `set`)
/// called on `$target` once per `name = value`.
#[doc(hidden)]
#[macro_export]
macro_rules! __assign {
    ($method:ident; $target:expr;) => {
        $target
    };
    // A bracketed list of numbers: each item converted on its own, so that integers
    // and floats mix. Any other value (`[0.1; 3]`, a variable, text) is the next arm's.
    ($method:ident; $target:expr; $name:tt = [$($item:expr),* $(,)?] $(, $($rest:tt)*)?) => {
        $crate::__assign!($method; $target.$method(
            $crate::__name(stringify!($name)),
            [$(<::core::primitive::f64 as ::core::convert::From<_>>::from($item)),*],
        ); $($($rest)*)?)
    };
    ($method:ident; $target:expr; $name:tt = $value:expr $(, $($rest:tt)*)?) => {
        $crate::__assign!($method; $target.$method($crate::__name(stringify!($name)), $value); $($($rest)*)?)
    };
}

/// An attribute name as [`element!`] and [`attrs!`] are given it: a raw identifier
/// (`r#ref`, `r#type`) is the name without its `r#`.
#[doc(hidden)]
pub fn __name(written: &'static str) -> &'static str {
    written.strip_prefix("r#").unwrap_or(written)
}

#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
