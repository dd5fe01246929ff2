//! The identifier index of one model: a persistent map kept exact by every edit.
//!
//! Two maps, both `imbl` (so a model clone shares them, and an edit copies
//! O(log n) of them):
//! - `names`: (namespace, identifier) → element, for `find` and duplicate checks;
//! - `elems`: element → (parent, kind, identifier), for locating an element by its id
//!   and for writing references to it.
//!
//! The index of an attached child lives in the child value, never in the parent's.

use imbl::{HashMap, Vector};
use smol_str::SmolStr;

use crate::schema::{ElementKind, Namespace};
use crate::tree::{ElementId, Node};

/// What the index knows about one element.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Entry {
    pub(crate) parent: Option<ElementId>,
    pub(crate) kind: ElementKind,
    pub(crate) name: Option<SmolStr>,
}

#[derive(Clone, Debug, Default)]
pub(crate) struct Index {
    pub(crate) names: HashMap<(Namespace, SmolStr), ElementId>,
    pub(crate) elems: HashMap<ElementId, Entry>,
    /// The model's attachments in attach order: (scope name, frame id).
    pub(crate) scopes: Vector<(SmolStr, ElementId)>,
    /// The model's name where it differs from its `model` attribute: `include_copy`
    /// replaces the attribute (as the reference does) but not the name that scopes
    /// the model when it is attached.
    pub(crate) own_name: Option<SmolStr>,
}

/// A name already taken, found while indexing.
#[derive(Debug)]
pub(crate) struct Duplicate {
    pub(crate) id: ElementId,
    pub(crate) namespace: Namespace,
    pub(crate) name: SmolStr,
}

impl Index {
    /// Adds `node` and its whole subtree, under `parent`. On a duplicate name the index
    /// is left partly updated: callers work on a copy and drop it on error.
    pub(crate) fn insert_subtree(&mut self, parent: Option<ElementId>, node: &Node) -> Result<(), Duplicate> {
        let in_frame = parent.is_some_and(|p| self.scope_of(p).is_some());
        let mut stack: Vec<(Option<ElementId>, &Node, bool)> = vec![(parent, node, in_frame)];
        while let Some((parent, n, in_frame)) = stack.pop() {
            self.insert_one(parent, n, !in_frame)?;
            // Reversed, so that elements are indexed in document order and a duplicate
            // is reported at its second occurrence. A frame's joints are unique per
            // frame only, so their names are not registered.
            let frame = n.attached().is_some();
            stack.extend(n.children().iter().rev().map(|c| (Some(n.id()), c, frame)));
        }
        Ok(())
    }

    fn insert_one(&mut self, parent: Option<ElementId>, n: &Node, register: bool) -> Result<(), Duplicate> {
        let name = n.identifier().map(SmolStr::from);
        if let (Some(ns), Some(name), true) = (n.kind().namespace(), &name, register) {
            let key = (ns, name.clone());
            if self.names.contains_key(&key) {
                return Err(Duplicate { id: n.id(), namespace: ns, name: name.clone() });
            }
            self.names.insert(key, n.id());
        }
        self.elems.insert(n.id(), Entry { parent, kind: n.kind(), name });
        Ok(())
    }

    /// Removes `node` and its subtree.
    pub(crate) fn remove_subtree(&mut self, node: &Node) {
        for n in node.descendants() {
            if let Some(e) = self.elems.remove(&n.id()) {
                if let (Some(ns), Some(name)) = (e.kind.namespace(), e.name) {
                    if self.names.get(&(ns, name.clone())) == Some(&n.id()) {
                        self.names.remove(&(ns, name));
                    }
                }
            }
            if n.attached().is_some() {
                self.scopes.retain(|(_, f)| *f != n.id());
            }
        }
    }

    /// Changes the identifier of `id` (already checked to be free).
    pub(crate) fn rename(&mut self, id: ElementId, new: Option<SmolStr>) {
        let Some(entry) = self.elems.get(&id).cloned() else { return };
        let in_frame = entry.parent.is_some_and(|p| self.scope_of(p).is_some());
        if let (Some(ns), false) = (entry.kind.namespace(), in_frame) {
            if let Some(old) = &entry.name {
                self.names.remove(&(ns, old.clone()));
            }
            if let Some(new) = &new {
                self.names.insert((ns, new.clone()), id);
            }
        }
        self.elems.insert(id, Entry { name: new, ..entry });
    }

    /// The scope name of the attachment whose frame is `frame`.
    pub(crate) fn scope_of(&self, frame: ElementId) -> Option<&SmolStr> {
        self.scopes.iter().find(|(_, f)| *f == frame).map(|(s, _)| s)
    }

    /// The frame of the attachment named `scope`.
    pub(crate) fn frame_of(&self, scope: &str) -> Option<ElementId> {
        self.scopes.iter().find(|(s, _)| s == scope).map(|(_, f)| *f)
    }

    /// The ids from the root down to `id`, inclusive.
    pub(crate) fn ancestry(&self, id: ElementId) -> Option<Vec<ElementId>> {
        let mut chain = vec![id];
        let mut cur = self.elems.get(&id)?;
        while let Some(p) = cur.parent {
            chain.push(p);
            cur = self.elems.get(&p)?;
        }
        chain.reverse();
        Some(chain)
    }
}
