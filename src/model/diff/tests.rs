//! The diff's tests: what each change reports, and what the walk examines.

use super::*;
use crate::model::tree::{ElementId, Node};
use crate::model::{Element, Loc};
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
    Model { root, index, files: m.files.clone(), side: m.side.clone() }
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
    assert!(changes.iter().any(
        |c| matches!(c, Change::AttrChanged { loc, attribute: "pos", old: None, .. } if *loc == arm)
    ));
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
    assert!(matches!(&changes[1], Change::AttrChanged { loc, attribute: "size", .. } if *loc == g));

    // Into a new body: the body is added, the geom moved into it.
    let (m3, bx) = m0.add(&wb, Element::new("body").attr("name", "box")).unwrap();
    let m3 = relocate(&m3, &g, &bx, 0);
    let into =
        Change::Moved { loc: g.clone(), from: torso, to: bx.clone(), old_index: 1, new_index: 0 };
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
        m = m.add(&m.worldbody(), Element::new("site").attr("name", format!("s{i}"))).unwrap().0;
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
        vec![Change::Attached { scope: "arena/robot/robot".into(), frame: inner.frame().clone() }]
    );
    assert_eq!(
        m2.diff(&scene),
        vec![Change::Detached { scope: "arena/robot/robot".into(), frame: inner.frame().clone() }]
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
            Change::Detached { scope: "arena/robot/robot".into(), frame: inner.frame().clone() },
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
