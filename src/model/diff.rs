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

use std::collections::HashMap;
use std::sync::Arc;

use super::tree::{ElementId, Node};
use crate::model::{Loc, Model};
use crate::seq::Leaf;
use crate::value::Value;

/// One difference between two versions of a model, as found by [`Model::diff`].
///
/// Locators of elements inside attachments are scoped (through the attachment frames,
/// outermost first), like those [`Model::find`] returns for `robot/torso`.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Change {
    /// An element that only the new version has, with its subtree (which is not
    /// reported element by element). `loc` is valid in the new version.
    Added {
        /// The top of the added subtree.
        loc: Loc,
    },
    /// An element that only the old version has, with its subtree. `loc` is valid in
    /// the old version.
    Removed {
        /// The top of the removed subtree.
        loc: Loc,
    },
    /// An attribute set, cleared or changed on an element both versions have.
    AttrChanged {
        /// The element (valid in both versions).
        loc: Loc,
        /// The attribute's XML name.
        attribute: &'static str,
        /// Its value in the old version (`None`: not set).
        old: Option<Value>,
        /// Its value in the new version (`None`: not set).
        new: Option<Value>,
    },
    /// An element both versions have, at another place: under another parent, or
    /// under the same parent in another order relative to its siblings.
    ///
    /// Among the children of one parent that both versions have, the ones that keep
    /// their relative order are a largest such set (counting elements); the others are
    /// reported as moved. So adding or removing siblings moves nothing, and taking one
    /// child from the front to the back reports that one child only.
    ///
    /// No public edit moves an element (`insert` and `add` make new ids, `remove`
    /// drops them), so versions made with this crate's edits differ by `Removed` and
    /// `Added` instead; `Moved` is reported only where an id itself changed place.
    Moved {
        /// The element (valid in both versions).
        loc: Loc,
        /// Its parent in the old version.
        from: Loc,
        /// Its parent in the new version (equal to `from` for a move among siblings).
        to: Loc,
        /// Its position among the old parent's children.
        old_index: usize,
        /// Its position among the new parent's children.
        new_index: usize,
    },
    /// A model attached (see [`Model::attach`]): the frame with its children (such as
    /// a freejoint added to it) and the attached model. Reported instead of `Added`
    /// for the frame, and also for a frame inside an added subtree.
    Attached {
        /// The full scope path in the new version (`robot`, `arena/robot`).
        scope: String,
        /// The attachment frame (valid in the new version).
        frame: Loc,
    },
    /// A model detached (see [`Model::detach`]), or its frame removed with a subtree
    /// ([`Model::remove_with_attachments`]: the subtree's top is `Removed`, each
    /// attachment in it `Detached`).
    Detached {
        /// The full scope path in the old version.
        scope: String,
        /// The attachment frame (valid in the old version).
        frame: Loc,
    },
    /// An attachment renamed (see [`Model::rename_scope`]).
    RenamedScope {
        /// The full scope path in the old version.
        from: String,
        /// The full scope path in the new version.
        to: String,
        /// The attachment frame (valid in both versions).
        frame: Loc,
    },
}

impl Change {
    /// The change as one line for people, with the names MuJoCo will see:
    /// `~ robot/torso rgba: 0.5 0.5 0.5 1 -> 1 0 0 1`, `+ body box_3`,
    /// `- joint dog/hip`, `> body robot/leg moved`, `attached robot`,
    /// `detached robot_1`, `renamed robot_1 -> dog`. `old` and `new` are the two
    /// versions [`Model::diff`] compared.
    ///
    /// Time: O(levels · depth · log n) per line (O(size of the element's model) for
    /// an unnamed element, whose automatic name is its position).
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, element};
    /// let mut m = Model::new("m");
    /// let v0 = m.clone();
    /// m.add_mut(&m.worldbody(), element!("body", name = "box"))?;
    /// let lines: Vec<String> = v0.diff(&m).iter().map(|c| c.display(&v0, &m).to_string()).collect();
    /// assert_eq!(lines, ["+ body box"]);
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn display<'a>(&'a self, old: &'a Model, new: &'a Model) -> impl std::fmt::Display + 'a {
        ChangeDisplay { change: self, old, new }
    }
}

struct ChangeDisplay<'a> {
    change: &'a Change,
    old: &'a Model,
    new: &'a Model,
}

impl std::fmt::Display for ChangeDisplay<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        // `tag name` for an element MuJoCo names; otherwise its path (below).
        let name = |m: &Model, loc: &Loc| match m.element(loc) {
            Some(e) => match e.full_name().filter(|n| !n.is_empty()) {
                Some(n) => format!("{} {n}", e.tag()),
                None => path(e),
            },
            None => format!("{loc:?}"),
        };
        let value = |v: &Option<Value>| {
            v.as_ref().map_or_else(|| "(unset)".to_string(), ToString::to_string)
        };
        match self.change {
            Change::Added { loc } => write!(f, "+ {}", name(self.new, loc)),
            Change::Removed { loc } => write!(f, "- {}", name(self.old, loc)),
            Change::AttrChanged { loc, attribute, old, new } => {
                let n = name(self.new, loc);
                // A named element by its name alone; a path has no space to cut at.
                let n = n.split_once(' ').map_or(n.as_str(), |(_, n)| n);
                write!(f, "~ {n} {attribute}: {} -> {}", value(old), value(new))
            }
            Change::Moved { loc, .. } => write!(f, "> {} moved", name(self.new, loc)),
            Change::Attached { scope, .. } => write!(f, "attached {scope}"),
            Change::Detached { scope, .. } => write!(f, "detached {scope}"),
            Change::RenamedScope { from, to, .. } => write!(f, "renamed {from} -> {to}"),
        }
    }
}

/// The path of an element MuJoCo gives no name (a default class's `<position>`, an
/// `<inertial>`, `<option>`), written as error paths are: from the nearest ancestor
/// that has a name (`tag[name=..]`, the name MuJoCo sees) down through the tags, a
/// tag followed by `[i]` (its rank among its siblings of that tag) where its parent
/// has several: `default[name=large_actuator]/position`,
/// `body[name=robot/torso]/inertial`, `option`. So no two elements read the same.
///
/// Time: O(depth · (width + levels · depth · log n)), plus O(n) per unnamed ancestor
/// that has a namespace (whose automatic name is its position).
fn path(element: crate::model::ElementRef<'_>) -> String {
    let mut steps = Vec::new();
    let mut at = element;
    while let Some(parent) = at.parent() {
        if let Some(n) = at.full_name().filter(|n| !n.is_empty()) {
            steps.push(format!("{}[name={n}]", at.tag()));
            break;
        }
        let same: Vec<_> = parent.children().filter(|c| c.tag() == at.tag()).collect();
        match same.iter().position(|c| c.ptr_eq(&at)) {
            Some(i) if same.len() > 1 => steps.push(format!("{}[{i}]", at.tag())),
            _ => steps.push(at.tag().to_string()),
        }
        at = parent;
    }
    steps.reverse();
    steps.join("/")
}

/// What a diff looked at, for tests of its cost.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct DiffStats {
    /// Node pairs whose content was examined (not pruned as `ptr_eq`).
    pub(crate) examined: usize,
}

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

/// [`Model::diff`], with what it examined.
pub(crate) fn diff_with_stats(old: &Model, new: &Model) -> (Vec<Change>, DiffStats) {
    let mut d = Differ { scopes: Vec::new(), out: Vec::new(), stats: DiffStats::default() };
    if old.ptr_eq(new) {
        return (d.out, d.stats);
    }
    d.scopes.push(Scope { old, new, outer: None, frames: None });
    // Breadth first over pairs of models, so the outer model's changes come first.
    let mut next = 0;
    while next < d.scopes.len() {
        d.model_pair(next);
        next += 1;
    }
    (d.out, d.stats)
}

/// A pair of models being compared: the top pair, or the models two versions of an
/// attachment frame hold.
struct Scope<'m> {
    old: &'m Model,
    new: &'m Model,
    /// The enclosing pair, the frame, and its scope name in the old and new versions.
    outer: Option<(usize, ElementId, &'m str, &'m str)>,
    /// The frames from the top down to this pair's models, once needed.
    frames: Option<Arc<[ElementId]>>,
}

struct Differ<'m> {
    scopes: Vec<Scope<'m>>,
    out: Vec<Change>,
    stats: DiffStats,
}

type Pairs<'m> = Vec<(&'m Node, &'m Node)>;

/// One child in the new order, as matched against the old children.
enum Unit<'m> {
    /// A chunk both versions share: old chunk start, new chunk start, its items.
    Shared(usize, usize, &'m [Node]),
    /// A child of both: old position, new position, old node, new node.
    Both(usize, usize, &'m Node, &'m Node),
    /// A child only the new version has under this parent: position, node.
    New(usize, &'m Node),
}

impl<'m> Differ<'m> {
    /// The frames leading to the models of pair `s`, outermost first.
    fn frames(&mut self, s: usize) -> Arc<[ElementId]> {
        if let Some(f) = &self.scopes[s].frames {
            return f.clone();
        }
        let mut ids = Vec::new();
        let mut cur = s;
        while let Some((outer, frame, _, _)) = self.scopes[cur].outer {
            ids.push(frame);
            cur = outer;
        }
        ids.reverse();
        let frames: Arc<[ElementId]> = ids.into();
        self.scopes[s].frames = Some(frames.clone());
        frames
    }

    fn loc(&mut self, s: usize, id: ElementId) -> Loc {
        // Locators name the outermost model (the new one's name) in errors.
        let origin = self.scopes[0].new.name();
        Loc::scoped(self.frames(s), id, origin)
    }

    /// The full scope path of attachment `name` of pair `s`'s old or new model.
    fn scope_path(&self, s: usize, new: bool, name: &str) -> String {
        let mut parts = vec![name];
        let mut cur = s;
        while let Some((outer, _, old_name, new_name)) = self.scopes[cur].outer {
            parts.push(if new { new_name } else { old_name });
            cur = outer;
        }
        parts.reverse();
        parts.join("/")
    }

    fn model_pair(&mut self, s: usize) {
        let (old, new) = (self.scopes[s].old, self.scopes[s].new);
        if old.root.ptr_eq(&new.root) {
            return;
        }
        let mut stack: Pairs<'m> = Vec::new();
        if old.root.id() != new.root.id() || old.root.kind() != new.root.kind() {
            self.removed(s, &old.root);
            self.added(s, &new.root, &mut stack);
        } else {
            stack.push((&old.root, &new.root));
        }
        while let Some((a, b)) = stack.pop() {
            self.pair(s, a, b, &mut stack);
        }
    }

    /// Compares two versions of one element (same id, not `ptr_eq`).
    fn pair(&mut self, s: usize, a: &'m Node, b: &'m Node, stack: &mut Pairs<'m>) {
        self.stats.examined += 1;
        if a.kind() != b.kind() {
            // Not produced by edits (an id keeps its kind); reported as a replacement.
            self.removed(s, a);
            self.added(s, b, stack);
            return;
        }
        self.attrs(s, a, b);
        match (a.attached(), b.attached()) {
            (Some(x), Some(y)) => {
                if x.scope != y.scope {
                    let (from, to) =
                        (self.scope_path(s, false, &x.scope), self.scope_path(s, true, &y.scope));
                    let frame = self.loc(s, a.id());
                    self.out.push(Change::RenamedScope { from, to, frame });
                }
                if !x.model.ptr_eq(&y.model) {
                    let outer = Some((s, a.id(), x.scope.as_str(), y.scope.as_str()));
                    self.scopes.push(Scope { old: &x.model, new: &y.model, outer, frames: None });
                }
            }
            (Some(x), None) => {
                let (scope, frame) = (self.scope_path(s, false, &x.scope), self.loc(s, a.id()));
                self.out.push(Change::Detached { scope, frame });
            }
            (None, Some(y)) => {
                let (scope, frame) = (self.scope_path(s, true, &y.scope), self.loc(s, b.id()));
                self.out.push(Change::Attached { scope, frame });
            }
            (None, None) => {}
        }
        if !a.children().ptr_eq(b.children()) {
            self.children(s, a, b, stack);
        }
    }

    /// The attributes of two versions of one element (both sorted by schema index).
    fn attrs(&mut self, s: usize, a: &Node, b: &Node) {
        let (xs, ys) = (a.attrs(), b.attrs());
        if std::ptr::eq(xs, ys) {
            return;
        }
        let kind = a.kind();
        let (mut i, mut j) = (0, 0);
        let mut changed: Vec<(u16, Option<&Value>, Option<&Value>)> = Vec::new();
        loop {
            match (xs.get(i), ys.get(j)) {
                (None, None) => break,
                (Some((k, v)), Some((l, w))) if k == l => {
                    if v != w {
                        changed.push((*k, Some(v), Some(w)));
                    }
                    i += 1;
                    j += 1;
                }
                (Some((k, v)), Some((l, _))) if k < l => {
                    changed.push((*k, Some(v), None));
                    i += 1;
                }
                (Some((k, v)), None) => {
                    changed.push((*k, Some(v), None));
                    i += 1;
                }
                (_, Some((l, w))) => {
                    changed.push((*l, None, Some(w)));
                    j += 1;
                }
            }
        }
        for (k, old, new) in changed {
            let loc = self.loc(s, a.id());
            let attribute = kind.attr(k as usize).name;
            self.out.push(Change::AttrChanged {
                loc,
                attribute,
                old: old.cloned(),
                new: new.cloned(),
            });
        }
    }

    /// The children of two versions of one element (their sequences not `ptr_eq`).
    fn children(&mut self, s: usize, a: &'m Node, b: &'m Node, stack: &mut Pairs<'m>) {
        let (old, new) = (self.scopes[s].old, self.scopes[s].new);
        // Shared chunks, matched by pointer, in increasing order on both sides.
        let old_chunks: Vec<(usize, &'m Arc<Leaf<Node>>)> = a.children().chunks().collect();
        let by_ptr: HashMap<*const Leaf<Node>, usize> =
            old_chunks.iter().enumerate().map(|(i, (_, c))| (Arc::as_ptr(c), i)).collect();
        let mut old_shared = vec![false; old_chunks.len()];
        let mut new_chunks: Vec<(usize, &'m Arc<Leaf<Node>>, bool)> =
            Vec::with_capacity(b.children().chunks().len());
        let mut last: Option<usize> = None;
        for (start, c) in b.children().chunks() {
            let shared = match by_ptr.get(&Arc::as_ptr(c)) {
                Some(&i) if last.is_none_or(|l| i > l) => {
                    old_shared[i] = true;
                    last = Some(i);
                    true
                }
                _ => false,
            };
            new_chunks.push((start, c, shared));
        }
        // The other old children, by id.
        let mut gone: Vec<(usize, &'m Node, bool)> = Vec::new();
        for ((start, c), _) in old_chunks.iter().zip(&old_shared).filter(|(_, shared)| !**shared) {
            gone.extend(c.iter().enumerate().map(|(k, n)| (start + k, n, false)));
        }
        let by_id: HashMap<ElementId, usize> =
            gone.iter().enumerate().map(|(i, (_, n, _))| (n.id(), i)).collect();
        let mut units: Vec<Unit<'m>> = Vec::new();
        for (start, c, shared) in new_chunks {
            if shared {
                let old_start = old_chunks[by_ptr[&Arc::as_ptr(c)]].0;
                units.push(Unit::Shared(old_start, start, &c[..]));
                continue;
            }
            for (k, n) in c.iter().enumerate() {
                match by_id.get(&n.id()) {
                    Some(&i) => {
                        gone[i].2 = true;
                        units.push(Unit::Both(gone[i].0, start + k, gone[i].1, n));
                    }
                    None => units.push(Unit::New(start + k, n)),
                }
            }
        }
        // Old children under no new one: removed, unless the new version has them
        // elsewhere (then they are found there as moved).
        for (_, n, matched) in &gone {
            if !matched && !new.index.contains(n.id()) {
                self.removed(s, n);
            }
        }
        let kept = in_order(&units);
        let (from, to) = (self.loc(s, a.id()), self.loc(s, b.id()));
        let mut pairs: Pairs<'m> = Vec::new();
        for (unit, kept) in units.iter().zip(kept) {
            match *unit {
                Unit::Shared(old_start, new_start, items) => {
                    if !kept {
                        for (k, n) in items.iter().enumerate() {
                            let loc = self.loc(s, n.id());
                            let (from, to) = (from.clone(), to.clone());
                            let (old_index, new_index) = (old_start + k, new_start + k);
                            self.out.push(Change::Moved { loc, from, to, old_index, new_index });
                        }
                    }
                }
                Unit::Both(old_index, new_index, x, y) => {
                    if !kept {
                        let loc = self.loc(s, y.id());
                        let (from, to) = (from.clone(), to.clone());
                        self.out.push(Change::Moved { loc, from, to, old_index, new_index });
                    }
                    if !x.ptr_eq(y) {
                        pairs.push((x, y));
                    }
                }
                Unit::New(new_index, n) => {
                    if !(old.index.contains(n.id())
                        && self.moved_in(s, b, new_index, n, &mut pairs))
                    {
                        self.added(s, n, &mut pairs);
                    }
                }
            }
        }
        // Depth first in document order.
        stack.extend(pairs.into_iter().rev());
    }

    /// Reports `n` (child `new_index` of `parent` in the new version) as moved there
    /// from elsewhere in the old version, and queues the comparison of its two
    /// versions. False (nothing reported) if the old version cannot locate it.
    fn moved_in(
        &mut self,
        s: usize,
        parent: &Node,
        new_index: usize,
        n: &'m Node,
        pairs: &mut Pairs<'m>,
    ) -> bool {
        let old = self.scopes[s].old;
        let Some(path) = old.path_of(n.id()) else { return false };
        let (Some(old_node), Some(&old_index)) = (old.node_at(&path), path.last()) else {
            return false;
        };
        let Some(old_parent) = old.index.parent(n.id()) else {
            return false;
        };
        let (loc, from, to) =
            (self.loc(s, n.id()), self.loc(s, old_parent), self.loc(s, parent.id()));
        self.out.push(Change::Moved { loc, from, to, old_index, new_index });
        if !old_node.ptr_eq(n) {
            pairs.push((old_node, n));
        }
        true
    }

    /// Reports a subtree only the new version has: its top, the attachments in it,
    /// and the elements in it that the old version has elsewhere (as moved).
    fn added(&mut self, s: usize, top: &'m Node, pairs: &mut Pairs<'m>) {
        let old = self.scopes[s].old;
        let loc = self.loc(s, top.id());
        let change = match top.attached() {
            Some(a) => Change::Attached { scope: self.scope_path(s, true, &a.scope), frame: loc },
            None => Change::Added { loc },
        };
        self.out.push(change);
        let mut todo: Vec<(&'m Node, usize, &'m Node)> =
            top.children().iter().enumerate().rev().map(|(i, c)| (top, i, c)).collect();
        while let Some((parent, i, n)) = todo.pop() {
            if old.index.contains(n.id()) && self.moved_in(s, parent, i, n, pairs) {
                continue;
            }
            // Inside an added subtree only attachments are reported.
            if let Some(a) = n.attached() {
                let (scope, frame) = (self.scope_path(s, true, &a.scope), self.loc(s, n.id()));
                self.out.push(Change::Attached { scope, frame });
            }
            todo.extend(n.children().iter().enumerate().rev().map(|(i, c)| (n, i, c)));
        }
    }

    /// Reports a subtree only the old version has: its top and the attachments in it
    /// (looked for only if the old model has any). Elements the new version still has
    /// are reported where they are now.
    fn removed(&mut self, s: usize, top: &'m Node) {
        let (old, new) = (self.scopes[s].old, self.scopes[s].new);
        let loc = self.loc(s, top.id());
        let change = match top.attached() {
            Some(a) => Change::Detached { scope: self.scope_path(s, false, &a.scope), frame: loc },
            None => Change::Removed { loc },
        };
        self.out.push(change);
        if old.index.scopes.is_empty() {
            return;
        }
        let mut todo: Vec<&'m Node> = top.children().iter().rev().collect();
        while let Some(n) = todo.pop() {
            if new.index.contains(n.id()) {
                continue;
            }
            if let Some(a) = n.attached() {
                let (scope, frame) = (self.scope_path(s, false, &a.scope), self.loc(s, n.id()));
                self.out.push(Change::Detached { scope, frame });
            }
            todo.extend(n.children().iter().rev());
        }
    }
}

/// Which units (in the new order) keep their relative old order: a heaviest
/// increasing subsequence by old position, a shared chunk weighing its length.
/// Units that are not children of both versions are "kept". O(u log u).
fn in_order(units: &[Unit<'_>]) -> Vec<bool> {
    // (unit index, old position, weight) of the units both versions have here.
    let both: Vec<(usize, usize, usize)> = units
        .iter()
        .enumerate()
        .filter_map(|(i, u)| match u {
            Unit::Shared(old, _, items) => Some((i, *old, items.len())),
            Unit::Both(old, _, _, _) => Some((i, *old, 1)),
            Unit::New(..) => None,
        })
        .collect();
    let mut kept = vec![true; units.len()];
    if both.windows(2).all(|w| w[0].1 < w[1].1) {
        return kept;
    }
    let n = both.len();
    let mut by_old: Vec<usize> = (0..n).collect();
    by_old.sort_by_key(|&k| both[k].1);
    let mut rank = vec![0; n];
    for (r, &k) in by_old.iter().enumerate() {
        rank[k] = r + 1;
    }
    // A Fenwick tree over ranks of (best weight ending there, its unit).
    let mut tree: Vec<(usize, usize)> = vec![(0, usize::MAX); n + 1];
    let mut best = vec![0; n];
    let mut prev = vec![usize::MAX; n];
    for k in 0..n {
        let mut r = rank[k] - 1;
        let mut q = (0, usize::MAX);
        while r > 0 {
            if tree[r].0 > q.0 {
                q = tree[r];
            }
            r &= r - 1;
        }
        best[k] = q.0 + both[k].2;
        prev[k] = q.1;
        let mut r = rank[k];
        while r <= n {
            if best[k] > tree[r].0 {
                tree[r] = (best[k], k);
            }
            r += r & r.wrapping_neg();
        }
    }
    for (i, _, _) in &both {
        kept[*i] = false;
    }
    let mut k = (0..n).max_by_key(|&k| best[k]).unwrap_or(usize::MAX);
    while k != usize::MAX {
        kept[both[k].0] = true;
        k = prev[k];
    }
    kept
}

/// The robot of the integration tests, shared through `extern crate self as mjcf`
/// (lib.rs, tests only).
#[cfg(test)]
#[path = "../../tests/support/robot.rs"]
mod test_robot;

#[cfg(test)]
pub(super) mod tests {
    use super::*;
    use crate::model::Element;
    use crate::schema::Namespace;

    pub(crate) use super::test_robot::robot;

    /// An arena of `n` sites `spawn_i` (at x = i), without attachments.
    fn arena(n: usize) -> Model {
        let mut m = Model::new("arena");
        for i in 0..n {
            let site = Element::new("site")
                .attr("name", format!("spawn_{i}"))
                .attr("pos", [i as f64, 0.0, 0.0]);
            m = m.add(&m.worldbody(), site).unwrap().0;
        }
        m
    }

    /// The arena of `n` sites with `robot` attached at each.
    pub(crate) fn fleet(n: usize) -> Model {
        let mut m = arena(n);
        let r = robot("robot");
        for i in 0..n {
            let site = m.find(Namespace::Site, &format!("spawn_{i}")).unwrap();
            m = m.attach(&site, &r).unwrap().0;
        }
        m
    }

    /// `m` with its element `what` taken out and put back, with the same id, as child
    /// `at` (a position among all children) of `to`. No public edit moves an element
    /// (`insert` makes new ids), so this is how the tests make `Moved` happen.
    fn relocate(m: &Model, what: &Loc, to: &Loc, at: usize) -> Model {
        let node = m.node_by_id(what.id()).unwrap().clone();
        let m = m.remove(what).unwrap();
        let path = m.path_of(to.id()).unwrap();
        let mut index = m.index.clone();
        index.insert_subtree(Some(to.id()), &node, at).unwrap();
        let root = m
            .root
            .update_path(&path, |p| {
                let mut children = p.children().clone();
                children.insert(at, node);
                Ok::<_, ()>(p.with_children(children))
            })
            .unwrap();
        Model { root, index, files: m.files.clone(), source: m.source.clone() }
    }

    fn site(m: &Model, name: &str) -> Loc {
        m.find(Namespace::Site, name).unwrap()
    }

    #[test]
    fn one_attribute_in_one_of_a_thousand_attachments_is_found_in_o_depth() {
        let fleet = fleet(1000);
        let geom = fleet.find(Namespace::Geom, "robot_17/torso").unwrap();
        let frame = fleet.frame("robot_17").unwrap();
        assert_eq!(geom.scope(), &[frame.id()]);
        let m = fleet.set_attr(&geom, "rgba", [1.0, 0.0, 0.0, 1.0]).unwrap();
        let rgba = m.element(&geom).unwrap().attr("rgba").cloned();
        assert!(rgba.is_some());

        let (changes, stats) = diff_with_stats(&fleet, &m);
        assert_eq!(
            changes,
            vec![Change::AttrChanged {
                loc: geom.clone(),
                attribute: "rgba",
                old: None,
                new: rgba.clone()
            }]
        );
        // The root, the worldbody, the frame, and the robot's root, worldbody, torso
        // and geom; not the 2,000 children of the worldbody nor the 1,000 robots.
        let wb = fleet.node_by_id(fleet.worldbody().id()).unwrap();
        assert_eq!(wb.children().len(), 2000);
        assert!(stats.examined < 50, "examined {}", stats.examined);
        assert_eq!(stats.examined, 7);

        let back = m.diff(&fleet);
        assert_eq!(
            back,
            vec![Change::AttrChanged { loc: geom, attribute: "rgba", old: rgba, new: None }]
        );
        assert!(fleet.diff(&fleet.clone()).is_empty());
    }

    #[test]
    fn added_and_removed_subtrees_are_reported_at_their_top() {
        let m0 = robot("robot");
        let torso = m0.find(Namespace::Body, "torso").unwrap();
        let arm = Element::new("body")
            .attr("name", "arm")
            .child(Element::new("geom").attr("name", "arm").attr("size", [0.1]))
            .child(Element::new("body").attr("name", "hand"));
        let (m1, arm) = m0.add(&torso, arm).unwrap();
        assert_eq!(m0.diff(&m1), vec![Change::Added { loc: arm.clone() }]);
        assert_eq!(m1.diff(&m0), vec![Change::Removed { loc: arm.clone() }]);

        let g = m1.find(Namespace::Geom, "torso").unwrap();
        let m2 = m1.remove(&g).unwrap();
        let m2 = m2.set_attr(&arm, "pos", [0.0, 0.0, 1.0]).unwrap();
        let changes = m1.diff(&m2);
        assert_eq!(changes.len(), 2, "{changes:?}");
        assert!(changes.contains(&Change::Removed { loc: g }));
        assert!(
            changes
                .iter()
                .any(|c| matches!(c, Change::AttrChanged { loc, attribute: "pos", old: None, .. } if *loc == arm))
        );
    }

    #[test]
    fn an_element_under_another_parent_is_moved() {
        let m0 = robot("robot");
        let torso = m0.find(Namespace::Body, "torso").unwrap();
        let g = m0.find(Namespace::Geom, "torso").unwrap();
        let wb = m0.worldbody();
        let m1 = relocate(&m0, &g, &wb, 1);
        let moved = Change::Moved {
            loc: g.clone(),
            from: torso.clone(),
            to: wb.clone(),
            old_index: 1,
            new_index: 1,
        };
        assert_eq!(m0.diff(&m1), vec![moved]);
        let back = Change::Moved {
            loc: g.clone(),
            from: wb.clone(),
            to: torso.clone(),
            old_index: 1,
            new_index: 1,
        };
        assert_eq!(m1.diff(&m0), vec![back]);

        // Moved, and changed on the way.
        let m2 = m1.set_attr(&g, "size", [0.3]).unwrap();
        let changes = m0.diff(&m2);
        assert_eq!(changes.len(), 2, "{changes:?}");
        assert!(matches!(&changes[0], Change::Moved { loc, .. } if *loc == g));
        assert!(
            matches!(&changes[1], Change::AttrChanged { loc, attribute: "size", .. } if *loc == g)
        );

        // Into a new body: the body is added, the geom moved into it.
        let (m3, bx) = m0.add(&wb, Element::new("body").attr("name", "box")).unwrap();
        let m3 = relocate(&m3, &g, &bx, 0);
        let into = Change::Moved {
            loc: g.clone(),
            from: torso,
            to: bx.clone(),
            old_index: 1,
            new_index: 0,
        };
        assert_eq!(m0.diff(&m3), vec![Change::Added { loc: bx }, into]);
    }

    #[test]
    fn only_the_children_out_of_order_are_moved() {
        let m0 = robot("robot");
        let torso = m0.find(Namespace::Body, "torso").unwrap();
        let hip = m0.find(Namespace::Joint, "hip").unwrap();
        // joint, geom, geom, site -> geom, geom, site, joint
        let m1 = relocate(&m0, &hip, &torso, 3);
        let moved =
            Change::Moved { loc: hip, from: torso.clone(), to: torso, old_index: 0, new_index: 3 };
        assert_eq!(m0.diff(&m1), vec![moved]);

        // Across the chunks of 300 children: the first to the end.
        let mut m = Model::new("sites");
        for i in 0..300 {
            m = m
                .add(&m.worldbody(), Element::new("site").attr("name", format!("s{i}")))
                .unwrap()
                .0;
        }
        let wb = m.worldbody();
        let s0 = site(&m, "s0");
        let m2 = relocate(&m, &s0, &wb, 299);
        let (changes, stats) = diff_with_stats(&m, &m2);
        let moved = Change::Moved {
            loc: s0.clone(),
            from: wb.clone(),
            to: wb.clone(),
            old_index: 0,
            new_index: 299,
        };
        assert_eq!(changes, vec![moved]);
        assert_eq!(stats.examined, 2); // the root and the worldbody

        // And the last to the front, with an insert and a removal elsewhere.
        let s299 = site(&m, "s299");
        let m3 = relocate(&m, &s299, &wb, 0);
        let (m3, new) = m3.insert(&wb, 150, Element::new("site").attr("name", "new")).unwrap();
        let s77 = site(&m, "s77");
        let m3 = m3.remove(&s77).unwrap();
        let changes = m.diff(&m3);
        assert_eq!(changes.len(), 3, "{changes:?}");
        assert!(changes.contains(&Change::Removed { loc: s77 }));
        assert!(changes.contains(&Change::Added { loc: new }));
        assert!(changes.iter().any(
            |c| matches!(c, Change::Moved { loc, old_index: 299, new_index: 0, .. } if *loc == s299)
        ));
    }

    #[test]
    fn attach_detach_and_rename_scope() {
        let arena = arena(3);
        let r = robot("robot");
        let (m1, frame) = arena.attach(&site(&arena, "spawn_0"), &r).unwrap();
        assert_eq!(
            arena.diff(&m1),
            vec![Change::Attached { scope: "robot".into(), frame: frame.frame().clone() }]
        );
        let m2 = m1.detach("robot").unwrap();
        assert_eq!(
            m1.diff(&m2),
            vec![Change::Detached { scope: "robot".into(), frame: frame.frame().clone() }]
        );
        assert!(arena.diff(&m2).is_empty());
        let m3 = m1.rename_scope("robot", "walker").unwrap();
        let renamed = Change::RenamedScope {
            from: "robot".into(),
            to: "walker".into(),
            frame: frame.frame().clone(),
        };
        assert_eq!(m1.diff(&m3), vec![renamed]);

        // A freejoint on the frame comes with it; added later, it is an element.
        let (m4, fj) = m1.add(frame.frame(), Element::new("freejoint")).unwrap();
        assert_eq!(
            arena.diff(&m4),
            vec![Change::Attached { scope: "robot".into(), frame: frame.frame().clone() }]
        );
        assert_eq!(m1.diff(&m4), vec![Change::Added { loc: fj }]);
        let m5 = m4.set_attr(frame.frame(), "pos", [1.0, 2.0, 3.0]).unwrap();
        assert!(
            matches!(&m4.diff(&m5)[..], [Change::AttrChanged { loc, attribute: "pos", .. }] if loc == frame.frame())
        );
    }

    #[test]
    fn changes_inside_nested_attachments() {
        let arena = arena(3);
        let (arena, _) = arena.attach(&site(&arena, "spawn_1"), &robot("robot")).unwrap();
        let scene = Model::new("scene");
        let (scene, outer) = scene.attach_to_world(&arena).unwrap();

        // An attribute two levels down.
        let geom = scene.find(Namespace::Geom, "arena/robot/torso").unwrap();
        assert_eq!(geom.scope().len(), 2);
        let m1 = scene.set_attr(&geom, "rgba", [0.0, 1.0, 0.0, 1.0]).unwrap();
        let (changes, stats) = diff_with_stats(&scene, &m1);
        assert!(
            matches!(&changes[..], [Change::AttrChanged { loc, attribute: "rgba", .. }] if *loc == geom)
        );
        // Root, worldbody and frame of the scene and of the arena, then the robot's
        // root, worldbody, torso and geom.
        assert_eq!(stats.examined, 3 + 3 + 4);

        // A robot attached to a site of the attached robot.
        let mount = scene.find(Namespace::Site, "arena/robot/mount").unwrap();
        let (m2, inner) = scene.attach(&mount, &robot("robot")).unwrap();
        assert_eq!(inner.frame().scope(), mount.scope());
        assert_eq!(
            scene.diff(&m2),
            vec![Change::Attached {
                scope: "arena/robot/robot".into(),
                frame: inner.frame().clone()
            }]
        );
        assert_eq!(
            m2.diff(&scene),
            vec![Change::Detached {
                scope: "arena/robot/robot".into(),
                frame: inner.frame().clone()
            }]
        );

        // Renames, at both levels at once: paths are old and new ones.
        let m3 = m2
            .rename_scope("arena/robot/robot", "tool")
            .unwrap()
            .rename_scope("arena", "field")
            .unwrap();
        let changes = m2.diff(&m3);
        assert_eq!(
            changes,
            vec![
                Change::RenamedScope {
                    from: "arena".into(),
                    to: "field".into(),
                    frame: outer.frame().clone()
                },
                Change::RenamedScope {
                    from: "arena/robot/robot".into(),
                    to: "field/robot/tool".into(),
                    frame: inner.frame().clone()
                },
            ]
        );

        // The robot's torso removed with the attachment on its site.
        let torso = m2.find(Namespace::Body, "arena/robot/torso").unwrap();
        let m4 = m2.remove_with_attachments(&torso).unwrap();
        assert_eq!(
            m2.diff(&m4),
            vec![
                Change::Removed { loc: torso },
                Change::Detached {
                    scope: "arena/robot/robot".into(),
                    frame: inner.frame().clone()
                },
            ]
        );
    }

    #[test]
    fn unrelated_models_are_all_removed_and_all_added() {
        let xml = r#"<mujoco model="a"><worldbody><body name="b"><geom size="1"/></body></worldbody></mujoco>"#;
        let a = Model::from_xml_str(xml).unwrap();
        let b = Model::from_xml_str(xml).unwrap();
        assert_eq!(
            a.diff(&b),
            vec![Change::Removed { loc: a.root() }, Change::Added { loc: b.root() }]
        );
        // Models from `Model::new` share the empty template: their sections match.
        let (x, y) = (robot("robot"), robot("robot"));
        let (xb, yb) =
            (x.find(Namespace::Body, "torso").unwrap(), y.find(Namespace::Body, "torso").unwrap());
        let (xm, ym) =
            (x.find(Namespace::Actuator, "m").unwrap(), y.find(Namespace::Actuator, "m").unwrap());
        let changes = x.diff(&y);
        assert_eq!(changes.len(), 4, "{changes:?}");
        for c in [
            Change::Removed { loc: xb },
            Change::Added { loc: yb },
            Change::Removed { loc: xm },
            Change::Added { loc: ym },
        ] {
            assert!(changes.contains(&c), "{c:?} in {changes:?}");
        }
    }

    #[test]
    fn attachments_nested_a_thousand_deep() {
        let mut m = robot("robot");
        for _ in 0..1000 {
            m = Model::new("level").attach_to_world(&m).unwrap().0;
        }
        let path = format!("{}robot/torso", "level/".repeat(999));
        let geom = m.find(Namespace::Geom, &path).unwrap();
        let m1 = m.set_attr(&geom, "size", [0.2]).unwrap();
        let (changes, stats) = diff_with_stats(&m, &m1);
        assert!(
            matches!(&changes[..], [Change::AttrChanged { loc, attribute: "size", .. }] if *loc == geom)
        );
        assert_eq!(stats.examined, 3 * 1000 + 4);
    }

    /// Edits of a list of sites for the property test below.
    #[derive(Clone, Debug)]
    enum Edit {
        Relocate(usize, usize),
        Insert(usize),
        Remove(usize),
        Set(usize),
    }

    fn edit() -> impl proptest::strategy::Strategy<Value = Edit> {
        use proptest::prelude::*;
        prop_oneof![
            (0..400usize, 0..400usize).prop_map(|(a, b)| Edit::Relocate(a, b)),
            (0..400usize).prop_map(Edit::Insert),
            (0..400usize).prop_map(Edit::Remove),
            (0..400usize).prop_map(Edit::Set),
        ]
    }

    /// The length of a longest common subsequence.
    fn lcs(a: &[ElementId], b: &[ElementId]) -> usize {
        let mut row = vec![0usize; b.len() + 1];
        for x in a {
            let mut diag = 0;
            for (j, y) in b.iter().enumerate() {
                let up = row[j + 1];
                row[j + 1] = if x == y { diag + 1 } else { up.max(row[j]) };
                diag = up;
            }
        }
        row[b.len()]
    }

    proptest::proptest! {
        /// Over random edits of a long children list (several chunks): exactly the
        /// removed and added children are reported, every attribute change, and as
        /// few moves as there can be (the common children minus a longest common
        /// subsequence), after which the remaining order agrees.
        #[test]
        fn children_diff_is_exact_and_moves_are_minimal(n in 0..300usize, edits in proptest::collection::vec(edit(), 0..12)) {
            let mut m = Model::new("sites");
            for i in 0..n {
                m = m.add(&m.worldbody(), Element::new("site").attr("name", format!("s{i}"))).unwrap().0;
            }
            let wb = m.worldbody();
            let ids = |m: &Model| -> Vec<ElementId> {
                m.node_by_id(wb.id()).unwrap().children().iter().map(Node::id).collect()
            };
            let mut next = m.clone();
            let mut fresh = 0;
            let mut set = std::collections::HashSet::new();
            for e in edits {
                let now = ids(&next);
                match e {
                    Edit::Relocate(a, b) if !now.is_empty() => {
                        let what = Loc::scoped(std::sync::Arc::from([]), now[a % now.len()], "");
                        next = relocate(&next, &what, &wb, b % now.len());
                    }
                    Edit::Insert(a) => {
                        fresh += 1;
                        let el = Element::new("site").attr("name", format!("new{fresh}"));
                        next = next.insert(&wb, a % (now.len() + 1), el).unwrap().0;
                    }
                    Edit::Remove(a) if !now.is_empty() => {
                        let id = now[a % now.len()];
                        set.remove(&id);
                        next = next.remove(&Loc::scoped(std::sync::Arc::from([]), id, "")).unwrap();
                    }
                    Edit::Set(a) if !now.is_empty() => {
                        let id = now[a % now.len()];
                        set.insert(id);
                        next = next.set_attr(&Loc::scoped(std::sync::Arc::from([]), id, ""), "pos", [1.0, 2.0, a as f64]).unwrap();
                    }
                    _ => {}
                }
            }
            let (old, new) = (ids(&m), ids(&next));
            let changes = m.diff(&next);
            let mut removed = Vec::new();
            let mut added = Vec::new();
            let mut moved = std::collections::HashSet::new();
            let mut changed = std::collections::HashSet::new();
            for c in &changes {
                match c {
                    Change::Removed { loc } => removed.push(loc.id()),
                    Change::Added { loc } => added.push(loc.id()),
                    Change::Moved { loc, from, to, old_index, new_index } => {
                        proptest::prop_assert!(*from == wb && *to == wb);
                        proptest::prop_assert_eq!(old[*old_index], loc.id());
                        proptest::prop_assert_eq!(new[*new_index], loc.id());
                        proptest::prop_assert!(moved.insert(loc.id()));
                    }
                    Change::AttrChanged { loc, attribute: "pos", .. } => { changed.insert(loc.id()); }
                    other => proptest::prop_assert!(false, "unexpected {:?}", other),
                }
            }
            let want_removed: Vec<ElementId> = old.iter().copied().filter(|i| !new.contains(i)).collect();
            let want_added: Vec<ElementId> = new.iter().copied().filter(|i| !old.contains(i)).collect();
            removed.sort();
            added.sort();
            let (mut wr, mut wa) = (want_removed, want_added);
            wr.sort();
            wa.sort();
            proptest::prop_assert_eq!(removed, wr);
            proptest::prop_assert_eq!(added, wa);
            let want_changed: std::collections::HashSet<ElementId> = set.into_iter().filter(|i| old.contains(i)).collect();
            proptest::prop_assert_eq!(changed, want_changed);
            let common_old: Vec<ElementId> = old.iter().copied().filter(|i| new.contains(i)).collect();
            let common_new: Vec<ElementId> = new.iter().copied().filter(|i| old.contains(i)).collect();
            proptest::prop_assert_eq!(moved.len(), common_old.len() - lcs(&common_old, &common_new));
            let rest = |v: &[ElementId]| v.iter().copied().filter(|i| !moved.contains(i)).collect::<Vec<_>>();
            proptest::prop_assert_eq!(rest(&common_old), rest(&common_new));
        }
    }
}
