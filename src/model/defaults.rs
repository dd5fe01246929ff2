//! The actuator defaults of a default class keep their document order (decision D11).
//!
//! `<position>`, `<velocity>`, `<motor>`, `<general>`, ... in a default class all set
//! the class's one actuator default, and MuJoCo applies them in document order: a
//! later `<position kp>` overrides an earlier `<velocity kv>`. They are singletons of
//! the class, which are otherwise kept in schema order; every path that builds a
//! class's children places its actuator defaults with [`order`]: the reader (document
//! order, includes included), the builder of an [`Element`](super::Element) (the
//! order of its children), and `include_copy` (the receiving class's, then the
//! copied class's).

use crate::schema::{ElementKind, Role};

use super::tree::Node;

/// Whether `kind` is an actuator default of a default class (`position` in a class;
/// [`Role::DefaultActuator`]). Time: O(1).
pub(crate) fn is_actuator_default(kind: ElementKind) -> bool {
    kind.is(Role::DefaultActuator)
}

/// Places the actuator defaults among `children` (a default class's) in the order of
/// `rank`: those it ranks first, by rank (ties in their current order), then the rest
/// in their current order, in the places the actuator defaults hold now; every other
/// child stays where it is. Time: O(k log k) for the `k` children.
pub(crate) fn order<T>(
    children: &mut [T],
    node: impl Fn(&T) -> &Node,
    rank: impl Fn(&T) -> Option<usize>,
) where
    T: Clone,
{
    let places: Vec<usize> =
        (0..children.len()).filter(|&i| is_actuator_default(node(&children[i]).kind())).collect();
    if places.len() < 2 {
        return;
    }
    let mut ordered: Vec<T> = places.iter().map(|&i| children[i].clone()).collect();
    // Stable: equal ranks, and the unranked, keep their current order.
    ordered.sort_by_key(|c| rank(c).map_or((1, 0), |r| (0, r)));
    for (place, item) in places.into_iter().zip(ordered) {
        children[place] = item;
    }
}
