//! The walk of a diff: pairs of models (the top pair, then each differing
//! attachment), each walked depth first over pairs of nodes, skipping what the
//! versions share.

use std::collections::HashMap;
use std::sync::Arc;

use super::change::Change;
use super::order::{Unit, in_order};
use crate::model::tree::{ElementId, Node};
use crate::model::{Loc, Model};
use crate::seq::Leaf;
use crate::value::Value;

/// What a diff looked at, for tests of its cost.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct DiffStats {
    /// Node pairs whose content was examined (not pruned as `ptr_eq`).
    pub(crate) examined: usize,
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
