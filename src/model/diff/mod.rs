//! [`Model::diff`]: the changes between two versions of a model, found by element id
//! and skipping everything the versions share.
//!
// Implementation notes:
// - One pass per pair of models (the top pair, then each attachment whose attached
//   model differs), each a depth-first walk of node pairs on an explicit stack, so
//   deep trees and deeply nested attachments cannot overflow the stack.
// - A pair of `ptr_eq` nodes is never looked into. Of two children sequences, the
//   chunks both share are matched by pointer and only the items of the other chunks
//   are matched by id.

mod change;
mod order;
mod walk;

pub use change::Change;
pub(crate) use walk::diff_with_stats;

use crate::model::Model;

impl Model {
    /// The changes that turn `self` (the old version) into `other` (the new one).
    ///
    /// Elements are matched by their stable [`crate::ElementId`]: an element of both
    /// versions is compared (attributes, attachment, children; attribute values as
    /// [`Value`](crate::Value)'s `==` compares them, floats by their bits with every
    /// NaN one value, so setting NaN again is no change and `0` to `-0` is one), one
    /// of only one version
    /// is `Added` or `Removed` (its subtree's top only), one with another parent or
    /// out of order among its siblings is [`Change::Moved`]. An attachment frame is
    /// `Attached`, `Detached` or `RenamedScope`d, and when the model it holds differs,
    /// the diff goes on inside it, with locators scoped through the frame. Subtrees and
    /// attached models that both versions share (`ptr_eq`) are skipped unexamined.
    ///
    /// Models that are not versions of each other share no ids: if their roots differ,
    /// the diff is `Removed` of the old root and `Added` of the new one. (Every
    /// [`Model::new`] starts from one shared empty tree, so two models built from
    /// `Model::new` share the root and the sections: their diff removes and adds the
    /// sections' children instead. Models read from XML share nothing.)
    ///
    /// The changes come in a deterministic order: the top model's, then those inside
    /// each differing attachment (outer ones first); within one model, depth first:
    /// an element's own changes, then its removed children, then its added and moved
    /// children in their new order, then the changes inside its children.
    ///
    /// Time: O(E · (a + c + s) + (A + R) · log n). E is the number of node pairs
    /// examined: the elements that differ and their ancestors, through attachment
    /// frames (for one edit, the depth of the edited element). Per examined pair, a is
    /// its attribute count, c the number of chunks of its children sequence (w / 64 to
    /// w / 32 for w children added one by one, √w past 4,096 children; removals can
    /// leave smaller chunks) and s the children in chunks the two versions do not share
    /// (an edit of a children list copies one chunk, of at most max(64, √w) items). A and R are the sizes of added and removed subtrees (R
    /// counts only when the model has attachments), each element looked up in the
    /// other version's index (log n). Moves among siblings add O(u log u) for the u
    /// siblings and shared chunks involved. Unrelated models cost O(n log n).
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Change, Element, Model, Namespace};
    /// let m0 = Model::new("robot");
    /// let (m1, _) = m0.add(&m0.worldbody(), Element::new("geom").attr("name", "g").attr("size", [0.1])).unwrap();
    /// let g = m1.find(Namespace::Geom, "g").unwrap();
    /// let m2 = m1.set_attr(&g, "rgba", [1.0, 0.0, 0.0, 1.0]).unwrap();
    ///
    /// assert_eq!(m0.diff(&m1), vec![Change::Added { loc: g.clone() }]);
    /// let changes = m1.diff(&m2);
    /// assert!(matches!(
    ///     &changes[..],
    ///     [Change::AttrChanged { loc, attribute: "rgba", old: None, new: Some(_) }] if *loc == g
    /// ));
    /// assert!(m2.diff(&m2).is_empty());
    /// ```
    pub fn diff(&self, other: &Model) -> Vec<Change> {
        diff_with_stats(self, other).0
    }
}

/// The robot of the integration tests, shared through `extern crate self as mjcf`
/// (lib.rs, tests only).
#[cfg(test)]
#[path = "../../../tests/support/robot.rs"]
mod test_robot;

#[cfg(test)]
pub(super) mod tests;
