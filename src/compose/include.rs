//! `include_copy`: the copying merge of one model into another (reference §4).
//!
//! Root attributes and singletons merge by the schema's rules (values that must agree,
//! min, max, bytes-max, replace); repeated children are copied with fresh ids after the
//! receiving model's own; references between copied elements point at the copies.
//! With `override_attributes`, a named source element merges into the receiving
//! model's element of the same name, whose attributes it overwrites.
//!
//! The merge is atomic: on any error the receiving model is unchanged.

use std::collections::{HashMap, HashSet};

use crate::seq::Seq;
use smol_str::SmolStr;

use crate::error::{EditError, ErrorKind};
use crate::model::settings::combine;
use crate::model::tree::{Attr, ElementId, Node};
use crate::model::{Index, Model};
use crate::schema::{ElementKind, Multiplicity, Role};
use crate::value::{Reference, Value};

struct Copier<'a> {
    dest: &'a Model,
    override_attributes: bool,
    /// Source id → id in the result.
    ids: HashMap<ElementId, ElementId>,
}

impl Model {
    /// Copies `other`'s content into this model (dm_control's `include_copy`).
    ///
    /// Global settings merge by the schema's rules and a conflicting value is an error,
    /// except the compiler's `angle` and `eulerseq`: where both models set one and the
    /// values differ, `other` is converted into this model's conventions as
    /// [`Model::attach`] converts a child
    /// ([decision D17](crate::decisions#d17-models-in-other-angle-conventions-are-converted-not-refused));
    /// every repeated element of `other` is copied (fresh ids) after this model's own;
    /// references between copied elements point at the copies. With
    /// `override_attributes`, root attributes and settings are overwritten instead of
    /// checked (the source's `angle` and `eulerseq` too, so its numbers are copied as
    /// they are), and named elements merge into same-named elements of this model.
    ///
    /// The root's `model` attribute is replaced, as in the reference, but the model's
    /// [`name`](Model::name) (the one that scopes it when attached) stays.
    ///
    /// A source with attachments is refused, as in the reference: copy what it was
    /// built from instead. The receiving model may have attachments; they stay as
    /// they are.
    ///
    /// Time: O((n + m) · log(n + m)) for an `other` of `m` elements, as the
    /// identifier index is rebuilt, plus O(a · depth · log n) to refold the merged
    /// settings. With `override_attributes`, each named element of `other` directly
    /// in a merged element is also looked up here: O(width) if found, O(named
    /// elements) if not (a [`Model::find`] miss).
    ///
    /// # Errors
    /// Leaving `self` unchanged:
    /// - [`ErrorKind::SourceHasAttachments`]: `other` has attachments;
    /// - [`ErrorKind::AttributeConflict`]: without `override_attributes`, an
    ///   attribute of a merged element (a global setting, a root default-class
    ///   default) that must agree does not; or the result's settings disagree with
    ///   an attached model's; or `other`'s `eulerseq` cannot be converted (a
    ///   `<replicate>` turning about several axes);
    /// - [`ErrorKind::DuplicateIdentifier`]: a copied element's name is taken, or
    ///   (a name read from MJCF, `robot/x`) starts with the scope of an attachment of
    ///   this model and a `/`, so that the attachment's names would meet it;
    /// - [`ErrorKind::CopyConflict`]: with `override_attributes`, a named element of
    ///   `other` whose namesake here has another parent.
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, Namespace, element};
    /// let mut base = Model::new("base");
    /// base.add_mut(&base.worldbody(), element!("geom", name = "floor", type = "plane", size = [1.0, 1.0, 0.1]))?;
    /// let mut extra = Model::new("extra");
    /// extra.add_mut(&extra.asset(), element!("material", name = "red", rgba = [1, 0, 0, 1]))?;
    /// let ball = extra.add_mut(&extra.worldbody(), element!("geom", name = "ball", size = [0.1], material = "red"))?;
    /// let m = base.include_copy(&extra, false)?;
    /// assert!(m.find(Namespace::Geom, "floor").is_some());
    /// assert!(m.find(Namespace::Material, "red").is_some());
    /// assert_ne!(m.find(Namespace::Geom, "ball").unwrap().id(), ball.id()); // a copy
    /// assert_eq!(m.name(), "base");
    /// // Copying `floor` again is a name clash; `base` stays as it was.
    /// assert!(base.include_copy(&m, false).is_err());
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn include_copy(
        &self,
        other: &Model,
        override_attributes: bool,
    ) -> Result<Model, EditError> {
        if !other.index.scopes.is_empty() {
            return Err(EditError::new(ErrorKind::SourceHasAttachments, String::new()));
        }
        // Without `override_attributes`, the source in this model's conventions
        // (angle unit, euler sequence) where both set them and they differ
        // (`compose::angles`); with it, the source's settings replace ours, so its
        // numbers keep their meaning as they are.
        let converted = if override_attributes {
            None
        } else {
            let ours = crate::model::settings::merged(self)
                .map_err(|k| EditError::new(k, String::new()))?;
            super::angles::into_conventions(&ours, other)
                .map_err(|k| EditError::new(k, String::new()))?
        };
        let other = converted.as_ref().unwrap_or(other);
        let mut c = Copier { dest: self, override_attributes, ids: HashMap::new() };
        let mut path = String::new();
        let root = c
            .merge(&self.root, &other.root, &mut path)
            .map_err(|k| EditError::new(k, path.clone()))?;
        // References anywhere (in copied and in merged elements, such as an included
        // default class naming an included material) follow the copies.
        let root = remap_refs(&root, &c.ids, &HashSet::from([root.id()]));
        let own_name =
            (self.name() != other_name(&root)).then(|| Box::new(SmolStr::from(self.name())));
        let mut index = Index { scopes: self.index.scopes.clone(), own_name, ..Index::default() };
        let failed = index.insert_subtree(None, &root, 0);
        let m = self.next(root, index);
        if let Err(d) = failed {
            let path = m.path_of(d.id).map(|p| m.describe(&p)).unwrap_or_default();
            return Err(EditError::new(
                ErrorKind::DuplicateIdentifier { namespace: d.namespace, name: d.name },
                path,
            ));
        }
        crate::model::settings::check(&m).map_err(|k| EditError::new(k, String::new()))?;
        Ok(m)
    }

    /// [`Model::include_copy`] in place.
    ///
    /// Time: as [`Model::include_copy`].
    ///
    /// # Errors
    /// As [`Model::include_copy`]; `self` is unchanged on error.
    pub fn include_copy_mut(
        &mut self,
        other: &Model,
        override_attributes: bool,
    ) -> Result<(), EditError> {
        let r = self.include_copy(other, override_attributes).map(|m| (m, ()));
        self.apply(r)
    }
}

impl Copier<'_> {
    /// Merges `src` into `dest` (same kind), iteratively: merged children are followed
    /// with an explicit stack, so merging chains of any depth cannot overflow it.
    fn merge(&mut self, dest: &Node, src: &Node, path: &mut String) -> Result<Node, ErrorKind> {
        /// An element being merged.
        struct Merging<'s> {
            dest: Node,
            src: &'s Node,
            attrs: Vec<Attr>,
            children: Seq<Node>,
            /// The next of `src`'s children.
            next: usize,
            /// The position in the parent's children this merge replaces.
            slot: usize,
            path_len: usize,
        }
        fn start<'s>(
            c: &mut Copier<'_>,
            dest: &Node,
            src: &'s Node,
            slot: usize,
            path_len: usize,
        ) -> Result<Merging<'s>, ErrorKind> {
            c.ids.insert(src.id(), dest.id());
            let attrs = merge_attrs(dest, src, c.override_attributes)?;
            Ok(Merging {
                dest: dest.clone(),
                src,
                attrs,
                children: dest.children().clone(),
                next: 0,
                slot,
                path_len,
            })
        }
        let mut stack = vec![start(self, dest, src, 0, path.len())?];
        while let Some(top) = stack.last_mut() {
            if let Some(s) = top.src.children().get(top.next) {
                top.next += 1;
                let kind = s.kind();
                let existing = match kind.multiplicity() {
                    Multiplicity::Singleton | Multiplicity::OnDemand => {
                        top.children.iter().position(|c| c.kind() == kind)
                    }
                    Multiplicity::Repeated => self.override_target(&top.children, s)?,
                };
                match existing {
                    Some(p) => {
                        let path_len = path.len();
                        crate::model::push_path(path, kind.tag(), s.identifier());
                        // `p` is a position in these very children.
                        if let Some(d) = top.children.get(p).cloned() {
                            stack.push(start(self, &d, s, p, path_len)?);
                        }
                    }
                    None => {
                        let copy = self.copy(s);
                        top.children.push_back(copy);
                    }
                }
                continue;
            }
            let Some(mut done) = stack.pop() else { break };
            if done.dest.kind().is(Role::DefaultClass) {
                done.children = actuator_defaults_in_order(&done.dest, done.src, &done.children);
            }
            let node = done.dest.with_parts(done.attrs, done.children);
            path.truncate(done.path_len);
            match stack.last_mut() {
                Some(parent) => {
                    parent.children.set(done.slot, node);
                }
                None => return Ok(node),
            }
        }
        // The loop returns when the outermost element is merged.
        Ok(dest.clone())
    }

    /// With `override_attributes`, the position of the same-named child of `dest`.
    fn override_target(&self, children: &Seq<Node>, s: &Node) -> Result<Option<usize>, ErrorKind> {
        if !self.override_attributes {
            return Ok(None);
        }
        let (Some(ns), Some(name)) = (s.kind().namespace(), s.identifier()) else {
            return Ok(None);
        };
        let Some(loc) = self.dest.find(ns, name) else { return Ok(None) };
        match children.iter().position(|c| c.id() == loc.id()) {
            Some(p) => Ok(Some(p)),
            None => Err(ErrorKind::CopyConflict { namespace: ns, name: name.into() }),
        }
    }

    /// Copies a subtree with fresh ids (iteratively).
    fn copy(&mut self, src: &Node) -> Node {
        src.rebuild(|n, children| {
            let id = ElementId::fresh();
            self.ids.insert(n.id(), id);
            Node::new(id, n.kind(), n.attrs().to_vec(), children)
        })
    }
}

/// The children of the default class `dest` merged with `src` (`children`), with
/// their actuator defaults in document order (decision D11): those `dest` sets, in its
/// order, then those only `src` sets, in its order (what is copied comes after the
/// receiving model's own).
fn actuator_defaults_in_order(dest: &Node, src: &Node, children: &Seq<Node>) -> Seq<Node> {
    let set = |c: &Node| !c.attrs().is_empty() || !c.children().is_empty();
    let (own, theirs) = (dest.children(), src.children());
    if !theirs.iter().any(|c| crate::model::defaults::is_actuator_default(c.kind()) && set(c)) {
        // Nothing of theirs to place: the children as merged (shared).
        return children.clone();
    }
    let rank = |n: &Node| {
        if let Some(i) = own.iter().position(|c| c.id() == n.id() && set(c)) {
            return Some(i);
        }
        theirs.iter().position(|c| c.kind() == n.kind() && set(c)).map(|i| own.len() + i)
    };
    let mut list: Vec<Node> = children.iter().cloned().collect();
    crate::model::defaults::order(&mut list, |n| n, rank);
    list.into_iter().collect()
}

/// Merges the attributes of two elements of the same kind.
fn merge_attrs(dest: &Node, src: &Node, override_attributes: bool) -> Result<Vec<Attr>, ErrorKind> {
    let kind = dest.kind();
    let mut out: Vec<Attr> = dest.attrs().to_vec();
    for (i, v) in src.attrs() {
        let spec = kind.attr(*i as usize);
        let pos = out.binary_search_by_key(i, |(k, _)| *k);
        let new = match (&pos, override_attributes) {
            (Err(_), _) | (Ok(_), true) => v.clone(),
            (Ok(p), false) => combine(kind, *i as usize, &out[*p].1, v, spec.merge)?,
        };
        match pos {
            Ok(p) => out[p].1 = new,
            Err(p) => out.insert(p, (*i, new)),
        }
    }
    Ok(out)
}

/// The `model` attribute of a root node.
fn other_name(root: &Node) -> &str {
    ElementKind::ROOT
        .attr_index("model")
        .and_then(|i| root.attr(i))
        .and_then(Value::as_str)
        .unwrap_or("")
}

/// Rewrites element references through `ids` inside the subtrees rooted at `under`
/// (iteratively), sharing every subtree that does not change.
pub(crate) fn remap_refs(
    root: &Node,
    ids: &HashMap<ElementId, ElementId>,
    under: &HashSet<ElementId>,
) -> Node {
    // (node, children done, inside a remapped subtree)
    let mut stack: Vec<(&Node, bool, bool)> = vec![(root, false, under.contains(&root.id()))];
    let mut built: Vec<Node> = Vec::new();
    while let Some((n, done, inside)) = stack.pop() {
        if !done {
            stack.push((n, true, inside));
            for c in n.children().iter().rev() {
                stack.push((c, false, inside || under.contains(&c.id())));
            }
            continue;
        }
        let k = n.children().len();
        let new_children = built.split_off(built.len() - k);
        let children_same = new_children.iter().zip(n.children().iter()).all(|(a, b)| a.ptr_eq(b));
        let needs = inside
            && n.attrs().iter().any(
                |(_, v)| matches!(v, Value::Reference(Reference::Element(t)) if ids.get(t).is_some_and(|x| x != t)),
            );
        if children_same && !needs {
            built.push(n.clone());
            continue;
        }
        let attrs: Vec<Attr> = n
            .attrs()
            .iter()
            .map(|(i, v)| match v {
                Value::Reference(Reference::Element(t)) if inside => {
                    (*i, Value::Reference(Reference::Element(ids.get(t).copied().unwrap_or(*t))))
                }
                _ => (*i, v.clone()),
            })
            .collect();
        built.push(n.with_parts(attrs, new_children.into_iter().collect()));
    }
    built.pop().unwrap_or_else(|| root.clone())
}
