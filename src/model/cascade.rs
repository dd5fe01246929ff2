//! Removing an element together with what refers to it ([`Model::remove_with`]).
//!
//! What refers to an element: any element of the same model (references never cross
//! an attachment) whose reference attribute names it, or names an element of its
//! subtree (removing a body removes its joints, so a motor on one of them refers to
//! the body's removal), by a resolved reference (read from MJCF) or by its name.
//!
//! A referrer *depends* on what it refers to when it exists only for it: an
//! actuator, a sensor, a tendon, an equality, a contact pair or exclude (the
//! elements of those namespaces, and everything inside them: a tendon's path
//! element refers for its tendon). A cascade removes those, and in turn what
//! depends on them (an actuator on a removed tendon). A referrer that cannot stay
//! without its reference goes too: a required one (a material's `<layer>` without
//! its texture), and a mesh or height-field geom without its mesh or height field.
//! Any other referrer (a geom naming a removed material, a body's `childclass`)
//! keeps its place and loses the reference, as [`Model::remove`] clears it, and the
//! removal reports it.

use std::collections::HashSet;

use crate::error::{EditError, ErrorKind};
use crate::schema::{Namespace, Role};
use crate::value::{Reference, Value};

use super::cursor::{Step, Walk};
use super::layout::{class_in_force, effective};
use super::tree::{ElementId, Node};
use super::{Loc, Model};

/// What [`Model::remove_with`] does with the elements that refer to what it removes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub enum Referrers {
    /// Refuse the removal when anything refers to the element (or to an element of
    /// its subtree), listing what does ([`ErrorKind::Referenced`]).
    Refuse,
    /// Remove, with the element, every actuator, sensor, tendon, equality, contact
    /// pair and exclude left referring to what was removed (and what refers to
    /// those, in turn); other references are cleared as [`Model::remove`] clears
    /// them, and reported.
    Cascade,
}

/// What [`Model::remove_with`] did.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct Removal {
    /// The model without the element (and, with [`Referrers::Cascade`], without what
    /// depended on it).
    pub model: Model,
    /// The elements removed besides the one asked for, by the name MuJoCo gives
    /// them ([`Model::full_name`]) or, unnamed and without a namespace, their tag.
    pub removed: Vec<String>,
    /// The references cleared on elements that stay: the element (named as in
    /// `removed`) and the attribute.
    pub cleared: Vec<(String, &'static str)>,
}

/// The namespaces whose elements exist only for what they refer to.
const DEPENDENT: [Namespace; 5] = [
    Namespace::Actuator,
    Namespace::Sensor,
    Namespace::Tendon,
    Namespace::Equality,
    Namespace::Contact,
];

impl Model {
    /// Removes the element at `loc` (as [`Model::remove`]) and decides what becomes
    /// of the elements that refer to it or to an element of its subtree:
    /// [`Referrers::Refuse`] refuses when there are any, listing them;
    /// [`Referrers::Cascade`] removes those that depend on it (actuators, sensors,
    /// tendons, equalities, contact pairs and excludes; see the module
    /// documentation), so nothing is left dangling, and reports what it removed and
    /// the references it cleared on elements that stay.
    ///
    /// Time: O(n) per round for a model of `n` elements, a round for each level of
    /// dependence (an actuator on a tendon on a removed site: two), plus each
    /// removal's own cost.
    ///
    /// # Errors
    /// As [`Model::remove`]; [`ErrorKind::Referenced`] (with `Refuse`) listing every
    /// element and attribute that refers to what the removal takes.
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, Namespace, Referrers, element};
    /// let mut m = Model::new("m");
    /// let b = m.add_mut(&m.worldbody(), element!("body", name = "arm"))?;
    /// m.add_mut(&b, element!("joint", name = "elbow"))?;
    /// m.add_mut(&b, element!("geom", size = [0.1]))?;
    /// m.add_mut(&m.actuator(), element!("motor", name = "m", joint = "elbow"))?;
    /// let elbow = m.find(Namespace::Joint, "elbow").unwrap();
    /// // Refused by default: the motor drives it.
    /// let e = m.remove_with(&elbow, Referrers::Refuse).unwrap_err();
    /// assert!(e.to_string().contains("m: joint"));
    /// // Cascade: the motor goes with it, and nothing dangles.
    /// let r = m.remove_with(&elbow, Referrers::Cascade)?;
    /// assert_eq!(r.removed, ["m"]);
    /// assert!(r.model.find(Namespace::Actuator, "m").is_none() && r.model.check().is_empty());
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn remove_with(&self, loc: &Loc, referrers: Referrers) -> Result<Removal, EditError> {
        let mut removal = Removal { model: self.clone(), removed: Vec::new(), cleared: Vec::new() };
        let mut todo = vec![loc.clone()];
        let mut done: HashSet<ElementId> = HashSet::new();
        while let Some(at) = todo.pop() {
            let m = &removal.model;
            // Gone with an element removed before it.
            if !done.insert(at.id()) || m.element(&at).is_none() {
                continue;
            }
            let found = m.referrers_of(&at);
            if referrers == Referrers::Refuse && !found.is_empty() {
                let by = found.iter().map(|(r, attr)| format!("{}: {attr}", label(m, r))).collect();
                let path = label(m, &at);
                return Err(EditError::new(ErrorKind::Referenced { by }, path));
            }
            if at != *loc {
                removal.removed.push(label(m, &at));
            }
            let mut next = Vec::new();
            let mut clear = Vec::new();
            for (r, attr) in found {
                match m.dependent_of(&r) {
                    Some(d) => next.push(d),
                    // The element cannot stay without it.
                    None if needed(m, &r, attr) => next.push(r),
                    None => {
                        removal.cleared.push((label(m, &r), attr));
                        clear.push((r, attr));
                    }
                }
            }
            let mut after = m.remove(&at)?;
            for (r, attr) in clear {
                // Gone with the removed subtree, or cleared: nothing is left naming it.
                if after.element(&r).is_some() {
                    after = after.clear_attr(&r, attr)?;
                }
            }
            removal.model = after;
            // Depth first in the order found, so reports read in document order.
            todo.extend(next.into_iter().rev());
        }
        Ok(removal)
    }

    /// Every element of `loc`'s own model, outside its subtree, whose reference
    /// attribute names `loc` or an element of its subtree, with the attribute.
    ///
    /// Time: O(n) for the composed model of `n` elements.
    fn referrers_of(&self, loc: &Loc) -> Vec<(Loc, &'static str)> {
        let mut out = Vec::new();
        let Some(node) = self.scoped_model(loc.scope()).and_then(|m| m.node_by_id(loc.id())) else {
            return out;
        };
        let ids: HashSet<ElementId> = node.descendants().map(Node::id).collect();
        let names: HashSet<(Namespace, &str)> = node
            .descendants()
            .filter_map(|n| Some((n.kind().namespace()?, n.identifier()?)))
            .collect();
        let top = self.name();
        let mut walk = Walk::new(self);
        while let Some(step) = walk.next() {
            let Step::Enter(item) = step else { continue };
            let inst = &walk.insts.list[item.inst];
            let node = item.node;
            if inst.frames[..] != *loc.scope() || ids.contains(&node.id()) {
                continue;
            }
            for (i, v) in node.attrs() {
                let i = *i as usize;
                let hit = match v {
                    Value::Reference(Reference::Element(id)) => ids.contains(id),
                    Value::Reference(Reference::Name(n)) => node
                        .reference_namespace(i)
                        .is_some_and(|ns| names.contains(&(ns, n.as_str()))),
                    _ => false,
                };
                if hit {
                    let at = Loc::scoped(inst.frames.clone(), node.id(), top);
                    out.push((at, node.kind().attr(i).name));
                }
            }
        }
        out
    }

    /// The outermost element at or above `loc` that exists only for what it refers
    /// to (of a [`DEPENDENT`] namespace), if any.
    fn dependent_of(&self, loc: &Loc) -> Option<Loc> {
        let mut found = None;
        let mut at = self.element(loc);
        while let Some(e) = at {
            if e.kind().namespace().is_some_and(|ns| DEPENDENT.contains(&ns)) {
                found = Some(e.loc());
            }
            at = e.parent();
        }
        found
    }
}

/// Whether the element at `loc` cannot stay without its reference `attr`: a
/// required attribute, or the mesh or height field a geom's type needs (its own
/// `type` or its classes': MuJoCo refuses a mesh geom without a mesh, "mesh geom must
/// have valid meshid", and a height-field geom without one).
fn needed(m: &Model, loc: &Loc, attr: &str) -> bool {
    let Some(e) = m.element(loc) else { return false };
    let kind = e.kind();
    if kind.attr_index(attr).is_some_and(|i| kind.attr(i).required) {
        return true;
    }
    if !kind.is(Role::Geom) || !matches!(attr, "mesh" | "hfield") {
        return false;
    }
    let Some(own) = m.scoped_model(loc.scope()) else { return false };
    let Some(node) = own.node_by_id(loc.id()) else { return false };
    let ty = effective(own, node, class_in_force(own, node), "type").and_then(Value::as_str);
    match attr {
        "mesh" => matches!(ty, Some("mesh" | "sdf")),
        _ => ty == Some("hfield"),
    }
}

/// How a removal names an element: the name MuJoCo gives it; unnamed and without a
/// namespace, its tag and the nearest named element it lies in (`<joint> in
/// coupling`).
fn label(m: &Model, loc: &Loc) -> String {
    if let Some(name) = m.full_name(loc) {
        return name;
    }
    let Some(e) = m.element(loc) else { return String::new() };
    let mut up = e.parent();
    while let Some(p) = up {
        if let Some(name) = p.full_name().filter(|_| p.identifier().is_some()) {
            return format!("<{}> in {name}", e.kind().tag());
        }
        up = p.parent();
    }
    format!("<{}>", e.kind().tag())
}
