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
//! the model in place (atomically: on error it is unchanged). Either way, values taken
//! before the edit keep their content.
//!
//! # What is shared, and what an edit costs
//! - Nodes are `Arc`-shared and hold no parent pointers; children are a chunked
//!   persistent sequence (`Arc`'d chunks of at most `max(64, √n)` nodes).
//! - An edit copies the path from the edited element to the root, and on that path
//!   the chunk list and one chunk of each children sequence: O(depth · √width)
//!   pointer copies at worst, O(depth) for narrow trees.
//! - Each model keeps a persistent identifier index (O(log n) `find` and duplicate
//!   checks), updated by every edit.
//! - Everything that depends on where an element sits (scope prefixes, auto names,
//!   default-class names, merged settings) is computed when the model is written or
//!   walked, never stored.
#![forbid(unsafe_code)]

mod compose;
mod error;
mod files;
mod id;
mod model;
mod schema;
mod seq;
mod suggest;
mod value;
mod xml;

pub use crate::error::{
    EditError, Error, ErrorKind, ExportError, ReadError, TextPos, ValueError, WriteError,
};
pub use crate::id::ElementId;
pub use crate::model::diff::Change;
pub use crate::model::{
    Attachment, Attrs, Element, ElementRef, Event, Loc, Model, Preorder, ScopeRef,
};
pub use crate::schema::{
    ArrayType, AttrSpec, AttrType, ElementKind, ElementSpec, Merge, Multiplicity, Namespace,
    PathNamespace, RefTarget,
};
pub use crate::value::{AttrInput, FileAsset, Reference, Value};
pub use crate::xml::{ReadOptions, WriteOptions};

/// An [`Element`] with attributes, as `Element::new(tag).attr(name, value)...`:
/// `element!("geom", type = "box", size = [0.1, 0.1, 0.1], mass = 1)`.
///
/// Attribute names are written as bare words (`type`, `class` and other keywords
/// included); values are anything [`Value`](crate::Value) inputs convert from: text,
/// numbers, arrays of numbers, booleans. Nothing is checked until the element is
/// added to a model.
///
/// # Examples
/// ```
/// use mjcf::{Element, element};
/// let a = element!("geom", type = "box", size = [0.1, 0.1, 0.1], mass = 1);
/// let b = Element::new("geom").attr("type", "box").attr("size", [0.1, 0.1, 0.1]).attr("mass", 1);
/// assert_eq!(a, b);
/// ```
#[macro_export]
macro_rules! element {
    ($tag:expr $(, $name:tt = $value:expr)* $(,)?) => {
        $crate::Element::new($tag)$(.attr(stringify!($name), $value))*
    };
}

#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
