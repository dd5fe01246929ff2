//! The element a reference attribute names, found in the referring element's own
//! model, with the default class in force for it: what the checks that judge an
//! element by another one's values read (a sensor's joint type, a tendon's wrapping
//! geom, an equality's joints).

use crate::model::Model;
use crate::model::layout::{class_in_force, effective};
use crate::model::tree::{ElementId, Node};
use crate::value::{Reference, Value};

/// An element named by a reference, in its model, with its class in force.
#[derive(Clone, Copy)]
pub(crate) struct Target<'m> {
    /// Its model (the referring element's).
    pub(crate) model: &'m Model,
    /// The element.
    pub(crate) node: &'m Node,
    /// The default class in force for it: its own, else the nearest `childclass`
    /// above it, else its model's root class.
    pub(crate) class: Option<ElementId>,
}

impl<'m> Target<'m> {
    /// The value of `attr`: its own, else its classes'.
    pub(crate) fn get(&self, attr: &str) -> Option<&'m Value> {
        effective(self.model, self.node, self.class, attr)
    }
}

/// The element `value` (a reference attribute of `node`, at schema index `i`) names in
/// `model`: the element itself, or the one its name names there. `None` for a name
/// nothing of `model` holds (a dangling name, a copy `<replicate>` makes, a name in
/// an attached model): the checks judging through references judge only what they
/// find.
pub(crate) fn resolve<'m>(
    model: &'m Model,
    node: &Node,
    i: usize,
    value: &Value,
) -> Option<Target<'m>> {
    let id = match value {
        Value::Reference(Reference::Element(id)) => *id,
        Value::Reference(Reference::Name(n)) => {
            let ns = node.reference_namespace(i)?;
            *model.index.names.get(&(ns, n.clone()))?
        }
        _ => return None,
    };
    let target = model.node_by_id(id)?;
    Some(Target { model, node: target, class: class_in_force(model, target) })
}

/// The element `node`'s attribute `attr` (its own, else its classes' in `class`)
/// names in `model`.
pub(crate) fn named<'m>(
    model: &'m Model,
    node: &Node,
    class: Option<ElementId>,
    attr: &str,
) -> Option<Target<'m>> {
    let i = node.kind().attr_index(attr)?;
    let value = node
        .attr(i)
        .or_else(|| crate::model::layout::from_classes(model, node.kind(), class, attr))?;
    resolve(model, node, i, value)
}

/// A reference attribute of an element: its model, the element, the attribute's
/// schema index and its value.
pub(crate) type Ref<'a> = (&'a Model, &'a Node, usize, &'a Value);

/// Whether two references name the same element: the same name, or the same element
/// once resolved.
pub(crate) fn same(a: Ref<'_>, b: Ref<'_>) -> bool {
    if let (Some(x), Some(y)) = (a.3.as_str(), b.3.as_str()) {
        return x == y;
    }
    match (resolve(a.0, a.1, a.2, a.3), resolve(b.0, b.1, b.2, b.3)) {
        (Some(x), Some(y)) => x.node.id() == y.node.id(),
        _ => false,
    }
}
