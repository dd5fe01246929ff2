//! Content equality of models (`impl PartialEq for Model` calls [`equal`]).
//!
//! Two models are equal when they have the same name, the same tree (kinds,
//! attributes, children in order), the same attachments (frames at the same places,
//! scope names, attach order, and attached models equal in the same sense,
//! recursively), however and wherever each was built. Element ids are not compared,
//! except through resolved references: walking both trees in parallel pairs the
//! elements at the same positions, and a `Reference::Element` of one model must point
//! at the element paired with the one the other model's reference points at (a dead
//! reference, whose target is not in its model, matches only another dead one).
//!
//! Time: O(E · (a + c) + P + r · log n) where E is the number of node pairs examined
//! (those not `ptr_eq`: for versions of one model, what differs and its ancestors),
//! a their attribute counts, c the chunks of their children sequences, P the children
//! in chunks the two sequences do not share, r the resolved references in examined
//! nodes (each looked up in the index) and n the model size. Two more terms occur only
//! when they can matter: O(k) for the k attachments when the attach lists are not
//! shared, and O(T) for the size T of the shared subtrees when some examined pair has
//! different ids (models built separately; then a shared subtree's references are
//! checked against those ids). Models built separately share nothing but the empty
//! template of `Model::new`, so they cost O(n), and so does a mismatch found late.
//! Iterative throughout (deep trees, attachments nested any number of levels).

use std::collections::{HashMap, HashSet};
use std::sync::Arc;

use super::tree::{Attr, ElementId, Node};
use crate::model::Model;
use crate::seq::Seq;
use crate::value::{Reference, Value};

/// Whether `a` and `b` have the same content (see the module documentation).
pub(crate) fn equal(a: &Model, b: &Model) -> bool {
    equal_with_stats(a, b).0
}

/// A hash of `model`'s content, consistent with [`equal`]: equal models hash alike.
/// It covers the name, the tree (kinds, attributes, children in order) and the
/// attachments (scope names and the attached models' hashes), floats by their bits
/// with every NaN one value (as `Value`'s equality compares them); a resolved
/// reference counts only as one (its target's id differs between equal models), and
/// the attach order is left out.
///
/// Time: O(n) for the n elements of the distinct model values of the composition
/// (each attached value once, however often it is attached). Iterative.
pub(crate) fn content_hash(model: &Model) -> u64 {
    use std::hash::{Hash, Hasher};
    // The distinct models of the composition, each after the models attached in it.
    let mut order: Vec<&Model> = Vec::new();
    let mut seen: HashSet<*const ()> = HashSet::new();
    let mut stack: Vec<(&Model, bool)> = vec![(model, false)];
    while let Some((m, done)) = stack.pop() {
        if done {
            order.push(m);
            continue;
        }
        if !seen.insert(m.root.as_ptr()) {
            continue;
        }
        stack.push((m, true));
        for node in m.root.descendants() {
            if let Some(a) = node.attached() {
                stack.push((&a.model, false));
            }
        }
    }
    let mut hashes: HashMap<*const (), u64> = HashMap::with_capacity(order.len());
    for m in order {
        let mut h = std::collections::hash_map::DefaultHasher::new();
        m.name().hash(&mut h);
        for node in m.root.descendants() {
            node.kind().hash(&mut h);
            h.write_usize(node.attrs().len());
            for (i, v) in node.attrs() {
                h.write_u16(*i);
                match v {
                    Value::Reference(Reference::Element(_)) => h.write_u8(0xff),
                    _ => v.hash(&mut h),
                }
            }
            h.write_usize(node.children().len());
            if let Some(a) = node.attached() {
                a.scope.hash(&mut h);
                h.write_u64(hashes.get(&a.model.root.as_ptr()).copied().unwrap_or(0));
            }
        }
        hashes.insert(m.root.as_ptr(), h.finish());
    }
    hashes.get(&model.root.as_ptr()).copied().unwrap_or(0)
}

/// What a comparison looked at, for tests of its cost.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct EqStats {
    /// Node pairs whose content was compared (not pruned as `ptr_eq`).
    pub(crate) examined: usize,
    /// Nodes of shared subtrees scanned for references.
    pub(crate) scanned: usize,
}

/// [`equal`], with what it looked at.
pub(crate) fn equal_with_stats(a: &Model, b: &Model) -> (bool, EqStats) {
    let mut stats = EqStats::default();
    // Pairs of models still to compare: the top pair, then attached ones.
    let mut models: Vec<(&Model, &Model)> = vec![(a, b)];
    while let Some((a, b)) = models.pop() {
        if a.name() != b.name() {
            return (false, stats);
        }
        // One tree: the same elements, attachments and references.
        if !a.ptr_eq(b) && !same_tree(a, b, &mut models, &mut stats) {
            return (false, stats);
        }
    }
    (true, stats)
}

/// Compares the trees of two models (not their attached models, which are queued on
/// `models`), then the attach order and the references through the id pairing.
fn same_tree<'m>(
    a: &'m Model,
    b: &'m Model,
    models: &mut Vec<(&'m Model, &'m Model)>,
    stats: &mut EqStats,
) -> bool {
    // The ids of examined elements at the same positions (a's → b's). Elements of
    // shared subtrees pair with themselves.
    let mut pairing: HashMap<ElementId, ElementId> = HashMap::new();
    let mut refs: Vec<(ElementId, ElementId)> = Vec::new();
    let mut shared: Vec<&'m [Node]> = Vec::new();
    let mut stack: Vec<(&'m Node, &'m Node)> = vec![(&a.root, &b.root)];
    while let Some((x, y)) = stack.pop() {
        if x.ptr_eq(y) {
            shared.push(std::slice::from_ref(x));
            continue;
        }
        stats.examined += 1;
        if x.kind() != y.kind()
            || x.children().len() != y.children().len()
            || !same_attrs(x.attrs(), y.attrs(), &mut refs)
        {
            return false;
        }
        pairing.insert(x.id(), y.id());
        match (x.attached(), y.attached()) {
            (None, None) => {}
            (Some(p), Some(q)) => {
                if p.scope != q.scope {
                    return false;
                }
                models.push((&p.model, &q.model));
            }
            _ => return false,
        }
        if !x.children().ptr_eq(y.children()) {
            child_pairs(x.children(), y.children(), &mut stack, &mut shared);
        }
    }
    // The attach order (it orders the attachments' sections when written).
    if !a.index.scopes.same(&b.index.scopes) {
        let (mut i, mut j) = (a.index.attachments(), b.index.attachments());
        loop {
            match (i.next(), j.next()) {
                (None, None) => break,
                (Some((s, f)), Some((t, g)))
                    if s == t && pairing.get(&f).copied().unwrap_or(f) == g => {}
                _ => return false,
            }
        }
    }
    // References in examined elements: through the pairing, or to themselves if the
    // target sits in a shared subtree, or both dead.
    for (p, q) in refs {
        let ok = match pairing.get(&p) {
            Some(t) => *t == q,
            None if a.index.contains(p) => p == q,
            None => !b.index.contains(q),
        };
        if !ok {
            return false;
        }
    }
    // References in shared subtrees are the same ids on both sides: right unless they
    // point at an element paired with another id.
    let unpaired: HashSet<ElementId> =
        pairing.iter().filter(|(x, y)| x != y).flat_map(|(x, y)| [*x, *y]).collect();
    if !unpaired.is_empty() {
        for n in shared.iter().flat_map(|s| s.iter()).flat_map(Node::descendants) {
            stats.scanned += 1;
            let points_at_unpaired = |(_, v): &Attr| match v {
                Value::Reference(Reference::Element(t)) => unpaired.contains(t),
                _ => false,
            };
            if n.attrs().iter().any(points_at_unpaired) {
                return false;
            }
        }
    }
    true
}

/// Whether two attribute lists are equal, resolved references aside (collected as
/// pairs to check once the ids are paired).
fn same_attrs(xs: &[Attr], ys: &[Attr], refs: &mut Vec<(ElementId, ElementId)>) -> bool {
    if std::ptr::eq(xs, ys) {
        return true;
    }
    xs.len() == ys.len()
        && xs.iter().zip(ys).all(|((i, v), (j, w))| {
            i == j
                && match (v, w) {
                    (
                        Value::Reference(Reference::Element(p)),
                        Value::Reference(Reference::Element(q)),
                    ) => {
                        refs.push((*p, *q));
                        true
                    }
                    _ => v == w,
                }
        })
}

/// Queues the pairs of children at the same positions of two sequences of one length,
/// skipping the chunks both share at the same position (noted as shared).
fn child_pairs<'m>(
    xs: &'m Seq<Node>,
    ys: &'m Seq<Node>,
    stack: &mut Vec<(&'m Node, &'m Node)>,
    shared: &mut Vec<&'m [Node]>,
) {
    let (mut cx, mut cy) = (xs.chunks(), ys.chunks());
    let (mut x, mut y) = (cx.next(), cy.next());
    let mut pos = 0;
    while pos < xs.len() {
        while x.is_some_and(|(s, c)| s + c.len() <= pos) {
            x = cx.next();
        }
        while y.is_some_and(|(s, c)| s + c.len() <= pos) {
            y = cy.next();
        }
        let (Some((sx, a)), Some((sy, b))) = (x, y) else { return };
        if sx == pos && sy == pos && Arc::ptr_eq(a, b) {
            shared.push(a);
            pos += a.len();
            continue;
        }
        let end = (sx + a.len()).min(sy + b.len());
        stack.extend((pos..end).map(|p| (&a[p - sx], &b[p - sy])));
        pos = end;
    }
}

#[cfg(test)]
mod tests {
    use std::thread;

    use super::*;
    use crate::model::Element;
    use crate::model::diff::tests::{fleet, robot};
    use crate::schema::Namespace;

    /// A scene built with adds and attaches: 20 sites, robots at the even ones (one
    /// with a freejoint, one recoloured), and a robot on a robot.
    fn scene() -> Model {
        let mut m = Model::new("scene");
        for i in 0..20 {
            let site = Element::new("site")
                .attr("name", format!("spawn_{i}"))
                .attr("pos", [i as f64, 0.0, 0.0]);
            m = m.add(&m.worldbody(), site).unwrap().0;
        }
        let r = robot("robot");
        for i in (0..20).step_by(2) {
            let site = m.find(Namespace::Site, &format!("spawn_{i}")).unwrap();
            m = m.attach(&site, &r).unwrap().0;
        }
        let frame = m.frame("robot_2").unwrap();
        m = m.add(&frame, Element::new("freejoint")).unwrap().0;
        let geom = m.find(Namespace::Geom, "robot_4/torso").unwrap();
        m = m.set_attr(&geom, "rgba", [0.5, 0.5, 0.5, 1.0]).unwrap();
        let mount = m.find(Namespace::Site, "robot_6/mount").unwrap();
        m.attach(&mount, &robot("gripper")).unwrap().0
    }

    const XML: &str = r#"<mujoco model="walker">
      <default><default class="leg"><joint damping="1"/></default></default>
      <worldbody>
        <body name="torso">
          <joint name="hip" class="leg"/>
          <geom name="torso" size="0.1"/>
          <body name="thigh"><joint name="knee" class="leg"/><geom size="0.05"/></body>
        </body>
        <body name="other"><joint name="spare"/></body>
      </worldbody>
      <actuator><motor name="m_hip" joint="hip"/><motor name="m_knee" joint="knee"/></actuator>
      <sensor><jointpos joint="knee"/><jointvel joint="spare"/></sensor>
      <contact><exclude body1="torso" body2="thigh"/></contact>
    </mujoco>"#;

    fn on_two_threads(f: fn() -> Model) -> (Model, Model) {
        let (a, b) = (thread::spawn(f), thread::spawn(f));
        (a.join().unwrap(), b.join().unwrap())
    }

    #[test]
    fn models_built_the_same_way_on_two_threads_are_equal() {
        let (a, b) = on_two_threads(scene);
        assert!(!a.ptr_eq(&b));
        assert_ne!(a.find(Namespace::Site, "spawn_0"), b.find(Namespace::Site, "spawn_0")); // other ids
        assert_eq!(a, b);
        assert_eq!(b, a);
        assert_eq!(a.to_xml_string().unwrap(), b.to_xml_string().unwrap());

        let geom = b.find(Namespace::Geom, "robot_8/torso").unwrap();
        let c = b.set_attr(&geom, "rgba", [1.0, 0.0, 0.0, 1.0]).unwrap();
        assert_ne!(a, c);
        assert_ne!(c, a);
        let inner = b.find(Namespace::Geom, "robot_6/gripper/torso").unwrap();
        assert_ne!(a, b.set_attr(&inner, "size", [0.3]).unwrap());
        assert_ne!(a, b.rename_scope("robot_6/gripper", "hand").unwrap());
        assert_ne!(a, b.with_name("other"));
        assert_ne!(a, b.detach("robot_6/gripper").unwrap());
    }

    fn hash_of<T: std::hash::Hash>(x: &T) -> u64 {
        use std::hash::Hasher;
        let mut h = std::collections::hash_map::DefaultHasher::new();
        x.hash(&mut h);
        h.finish()
    }

    /// Floats compare as the writer writes them, in `==`, `Hash` and `diff` alike:
    /// every NaN (any payload, either sign) is one value, so two versions that set
    /// NaN are equal, hash alike and differ in nothing; `0` and `-0` (written `0` and
    /// `-0`) differ.
    #[test]
    fn floats_compare_by_their_bits_with_every_nan_one_value_in_eq_hash_and_diff() {
        let base = Model::from_xml_str(
            r#"<mujoco><worldbody><geom name="g" size="1"/></worldbody></mujoco>"#,
        )
        .unwrap();
        let g = base.find(Namespace::Geom, "g").unwrap();
        let nans = [f64::NAN, -f64::NAN, f64::from_bits(0x7ff8_0000_0000_0001)];
        let set =
            |x: f64| base.set_attr(&g, "size", [x, 1.0]).unwrap().set_attr(&g, "mass", x).unwrap();
        let first = set(f64::NAN);
        for x in nans {
            let other = set(x);
            assert!(!other.ptr_eq(&first));
            assert_eq!(other, first, "{x:?}");
            assert_eq!(hash_of(&other), hash_of(&first), "{x:?}");
            assert_eq!(other.diff(&first), [], "{x:?}");
            assert_eq!(other.to_xml_string().unwrap(), first.to_xml_string().unwrap());
        }
        // Two models read from one text with NaN: equal, with one hash.
        let text = r#"<mujoco><worldbody><geom size="nan 1" mass="nan"/></worldbody></mujoco>"#;
        let (a, b) = (Model::from_xml_str(text).unwrap(), Model::from_xml_str(text).unwrap());
        assert_eq!(a, b);
        assert_eq!(hash_of(&a), hash_of(&b));
        // `0` and `-0` are written differently: unequal, and a change.
        let (zero, minus) = (set(0.0), set(-0.0));
        assert_ne!(zero.to_xml_string().unwrap(), minus.to_xml_string().unwrap());
        assert_ne!(zero, minus);
        assert_ne!(hash_of(&zero), hash_of(&minus));
        let changes = zero.diff(&minus);
        assert_eq!(changes.len(), 2, "{changes:?}");
        assert!(changes.iter().all(|c| matches!(c, crate::Change::AttrChanged { .. })));
        // Values and the builder's inputs follow the same rule.
        assert_eq!(Value::Float(f64::NAN), Value::Float(-f64::NAN));
        assert_eq!(hash_of(&Value::Float(f64::NAN)), hash_of(&Value::Float(-f64::NAN)));
        assert_ne!(Value::Float(0.0), Value::Float(-0.0));
        assert_eq!(
            Element::new("geom").attr("size", [f64::NAN]),
            Element::new("geom").attr("size", [-f64::NAN])
        );
    }

    /// Equal models hash alike, however they were built (two threads, other ids,
    /// attached models shared or not); a change of one attribute changes the hash.
    #[test]
    fn equal_models_hash_alike() {
        let (a, b) = on_two_threads(scene);
        assert_eq!(a, b);
        assert_eq!(hash_of(&a), hash_of(&b));
        let geom = b.find(Namespace::Geom, "robot_6/gripper/torso").unwrap();
        let c = b.set_attr(&geom, "size", [0.3]).unwrap();
        assert_ne!(hash_of(&a), hash_of(&c));
        let (a, b) = on_two_threads(|| Model::from_xml_str(XML).unwrap());
        assert_eq!(hash_of(&a), hash_of(&b));
        // The index's cache of merged settings is the interior mutability clippy sees;
        // it takes no part in equality or the hash.
        #[allow(clippy::mutable_key_type)]
        let set: std::collections::HashSet<Model> = [a, b, c].into_iter().collect();
        assert_eq!(set.len(), 2);
    }

    #[test]
    fn attach_order_counts() {
        let mut base = Model::new("arena");
        for i in 0..2 {
            base = base
                .add(&base.worldbody(), Element::new("site").attr("name", format!("s{i}")))
                .unwrap()
                .0;
        }
        let site = |m: &Model, s: &str| m.find(Namespace::Site, s).unwrap();
        let (a, _) = base.attach(&site(&base, "s0"), &robot("robot")).unwrap();
        let (a, _) = a.attach(&site(&a, "s1"), &robot("robot")).unwrap();
        // The same frames and scope names, attached the other way round.
        let (b, _) = base.attach(&site(&base, "s1"), &robot("robot")).unwrap();
        let b = b.rename_scope("robot", "robot_1").unwrap();
        let (b, _) = b.attach(&site(&b, "s0"), &robot("robot")).unwrap();
        assert_eq!(a.scopes().collect::<Vec<_>>(), ["robot", "robot_1"]);
        assert_eq!(b.scopes().collect::<Vec<_>>(), ["robot_1", "robot"]);
        assert_ne!(a.to_xml_string().unwrap(), b.to_xml_string().unwrap());
        assert_ne!(a, b);
    }

    #[test]
    fn a_model_read_twice_on_two_threads_is_equal_references_included() {
        let (a, b) = on_two_threads(|| Model::from_xml_str(XML).unwrap());
        let motor = a.find(Namespace::Actuator, "m_knee").unwrap();
        assert!(matches!(
            a.element(&motor).unwrap().attr("joint"),
            Some(Value::Reference(Reference::Element(_)))
        ));
        assert_eq!(a, b);
        let knee = b.find(Namespace::Joint, "knee").unwrap();
        assert_ne!(a, b.set_attr(&knee, "damping", 2.0).unwrap());
        // A reference by name where the other is resolved.
        let m = b.find(Namespace::Actuator, "m_hip").unwrap();
        let by_name =
            b.set_attr(&m, "joint", Value::Reference(Reference::Name("hip".into()))).unwrap();
        assert_ne!(a, by_name);
    }

    #[test]
    fn references_to_elements_of_the_same_shape_are_told_apart() {
        // Two unnamed joints, the motor on the first in one model, on the second in
        // the other: the trees agree but for where the reference points.
        let read = |target: &str| {
            let xml = format!(
                r#"<mujoco><worldbody><body name="p"><joint name="a"/><joint name="b"/></body></worldbody>
                <actuator><motor joint="{target}"/></actuator></mujoco>"#
            );
            let m = Model::from_xml_str(&xml).unwrap();
            let (ja, jb) =
                (m.find(Namespace::Joint, "a").unwrap(), m.find(Namespace::Joint, "b").unwrap());
            m.clear_attr(&ja, "name").unwrap().clear_attr(&jb, "name").unwrap()
        };
        assert_eq!(read("a"), read("a"));
        assert_ne!(read("a"), read("b"));

        // The same, with the motors in a subtree the two versions share: one version
        // renames the target and puts a new joint of its old name before it, the
        // other adds a joint of the new name after it.
        let base = Model::from_xml_str(
            r#"<mujoco><worldbody><body name="p"><joint name="j1"/></body></worldbody>
            <actuator><motor joint="j1"/></actuator></mujoco>"#,
        )
        .unwrap();
        let (p, j1) =
            (base.find(Namespace::Body, "p").unwrap(), base.find(Namespace::Joint, "j1").unwrap());
        let renamed = |base: &Model| {
            let m = base.set_attr(&j1, "name", "k").unwrap();
            m.insert(&p, 0, Element::new("joint").attr("name", "j1")).unwrap().0
        };
        let a = renamed(&base);
        let b = base.add(&p, Element::new("joint").attr("name", "k")).unwrap().0;
        let actuator = |m: &Model| m.node_by_id(m.actuator().id()).unwrap().clone();
        assert!(actuator(&a).ptr_eq(&actuator(&b)));
        assert_ne!(a.to_xml_string().unwrap(), b.to_xml_string().unwrap());
        let (eq, stats) = equal_with_stats(&a, &b);
        assert!(!eq);
        assert!(stats.scanned > 0);
        // Built the same way twice: the new joints have other ids, the motor is right.
        let (eq, stats) = equal_with_stats(&a, &renamed(&base));
        assert!(eq);
        assert!(stats.scanned > 0);
    }

    #[test]
    fn a_dead_reference_matches_only_a_dead_one() {
        let read = || Model::from_xml_str(XML).unwrap();
        let gone = |m: &Model| {
            let spare = m.find(Namespace::Joint, "spare").unwrap();
            let other = m.find(Namespace::Body, "other").unwrap();
            // The joint goes (the sensor's reference to it is dead) and an equal one
            // takes its place, under a new id.
            let m = m.remove(&spare).unwrap();
            m.insert(&other, 0, Element::new("joint").attr("name", "spare")).unwrap().0
        };
        let (a, b) = (read(), read());
        assert_eq!(a, b);
        assert_eq!(gone(&a), gone(&b)); // dead on both sides, other ids
        assert_ne!(gone(&a), b); // dead against alive
        assert_ne!(a, gone(&b));
    }

    #[test]
    fn versions_of_a_fleet_compare_in_o_depth() {
        let fleet = fleet(1000);
        let geom = fleet.find(Namespace::Geom, "robot_17/torso").unwrap();
        let red = fleet.set_attr(&geom, "rgba", [1.0, 0.0, 0.0, 1.0]).unwrap();
        let (eq, stats) = equal_with_stats(&fleet, &red);
        assert!(!eq);
        assert!(stats.examined < 50, "examined {}", stats.examined);
        let back = red.clear_attr(&geom, "rgba").unwrap();
        assert!(!back.ptr_eq(&fleet));
        let (eq, stats) = equal_with_stats(&fleet, &back);
        assert!(eq);
        assert_eq!((stats.examined, stats.scanned), (7, 0));
    }

    #[test]
    fn deep_trees_and_deep_attachments_compare_without_overflow() {
        let deep = || {
            let depth = 100_000;
            let mut text = String::from("<mujoco><worldbody>");
            text.push_str(&"<body>".repeat(depth));
            text.push_str(r#"<geom name="deepest" size="1"/>"#);
            text.push_str(&"</body>".repeat(depth));
            text.push_str("</worldbody></mujoco>");
            Model::from_xml_str(&text).unwrap()
        };
        let (a, b) = on_two_threads(deep);
        assert_eq!(a, b);
        let g = b.find(Namespace::Geom, "deepest").unwrap();
        assert_ne!(a, b.set_attr(&g, "size", [2.0]).unwrap());

        let nested = || {
            let mut m = robot("robot");
            for _ in 0..1000 {
                m = Model::new("level").attach_to_world(&m).unwrap().0;
            }
            m
        };
        let (a, b) = on_two_threads(nested);
        assert_eq!(a, b);
        let path = format!("{}robot/torso", "level/".repeat(999));
        let g = b.find(Namespace::Geom, &path).unwrap();
        assert_ne!(a, b.set_attr(&g, "size", [0.2]).unwrap());
    }
}
