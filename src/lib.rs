//! Build and compose MuJoCo MJCF models as persistent values.
//!
//! A [`Model`] is an immutable value: every edit returns a new model and leaves the old
//! one as it was. Versions share every subtree an edit did not touch, so keeping old
//! versions (undo) costs only what changed, and `clone()` is a pointer copy.
//!
//! ```
//! use mjcf::{Element, Model, Namespace};
//!
//! let arena = Model::new("arena");
//! let (arena, _) = arena
//!     .add(&arena.worldbody(), Element::new("geom").attr("name", "floor").attr("type", "plane").attr("size", [5.0, 5.0, 0.1]))
//!     .unwrap();
//! let xml = arena.to_xml_string().unwrap();
//! assert!(xml.contains(r#"<geom name="floor" class="/" type="plane" size="5 5 0.1"/>"#));
//! assert!(arena.find(Namespace::Geom, "floor").is_some());
//! ```
//!
//! # What is shared, and what an edit costs
//! - Nodes are `Arc`-shared and hold no parent pointers; children are `imbl` vectors.
//! - An edit copies the path from the edited element to the root: O(depth · log width).
//! - Each model keeps a persistent identifier index (O(log n) `find` and duplicate
//!   checks), updated by every edit.
//! - Everything that depends on where an element sits (scope prefixes, auto names,
//!   default-class names) is computed when the model is written, never stored.
#![forbid(unsafe_code)]
#![warn(missing_docs)]

mod compose;
mod error;
mod files;
mod model;
mod schema;
mod seq;
mod tree;
mod value;
mod xml;

pub use crate::error::{EditError, Error, ErrorKind, ReadError, TextPos, ValueError, WriteError};
pub use crate::model::diff::Change;
pub use crate::model::{Attrs, Element, ElementRef, Loc, Model};
pub use crate::schema::{
    ArrayType, AttrSpec, AttrType, ElementKind, ElementSpec, Merge, Multiplicity, Namespace, PathNamespace, RefTarget,
};
pub use crate::tree::ElementId;
pub use crate::value::{AttrInput, FileAsset, Reference, Value};
pub use crate::xml::{ReadOptions, WriteOptions};

#[cfg(doctest)]
#[doc = include_str!("../README.md")]
struct ReadmeDoctests;
