//! Handles ([`ElementRef`]) carry their instance's context and their composed parent:
//! every name, child list and parent they give is checked here against the
//! straightforward answer, a walk of the composition from the root for each question
//! (what `full_name` and `children` did before they carried anything).

use super::cursor::Walk;
use super::{ElementRef, Event, Loc, Model};
use crate::element;
use crate::schema::Namespace;
use crate::schema::{ElementKind, Role};

fn read(xml: &str) -> Model {
    Model::from_xml_str(xml).expect("reads")
}

/// An arm (unnamed elements, a `<replicate>`, actuator and sensor sections), a robot
/// holding two arms, and an arena holding three robots (one at a site inside a
/// `<replicate>`) whose frames hold joints: attachments three levels deep.
fn composed() -> Model {
    let mut arm = read(
        r#"<mujoco model="arm"><default><default class="a"><geom size="0.1"/></default></default>
          <worldbody><body name="upper"><joint name="j"/><geom class="a"/>
            <body><geom size="0.1"/><joint/></body>
            <replicate count="2" offset="0 0 1"><geom size="0.1"/><site name="tip"/></replicate>
          </body><geom size="0.2"/></worldbody>
          <actuator><motor joint="j"/></actuator><sensor><jointpos joint="j"/></sensor></mujoco>"#,
    );
    let tip = arm.find(Namespace::Site, "tip").expect("tip");
    let mut hand = Model::new("hand");
    hand.add_mut(&hand.worldbody(), element!("geom", size = [0.05])).expect("adds");
    arm.attach_mut(&tip, &hand).expect("attaches the hand");
    let mut robot = read(
        r#"<mujoco model="robot"><worldbody><body name="torso"><geom size="0.3"/>
          <site name="left"/><site name="right"/></body><geom size="0.1"/></worldbody>
          <sensor><framepos objtype="body" objname="torso"/></sensor></mujoco>"#,
    );
    for side in ["left", "right"] {
        let site = robot.find(Namespace::Site, side).expect("site");
        robot.attach_mut(&site, &arm).expect("attaches an arm");
    }
    let mut arena = read(
        r#"<mujoco model="arena"><worldbody><geom type="plane" size="5 5 0.1"/>
          <replicate count="2" offset="2 0 0"><site name="spot"/><geom size="0.1"/></replicate>
          </worldbody></mujoco>"#,
    );
    let a = arena.attach_mut(&arena.worldbody(), &robot).expect("attaches");
    arena.add_mut(a.frame(), element!("joint", type = "slide")).expect("adds");
    arena.add_mut(a.frame(), element!("joint", type = "hinge")).expect("adds");
    arena.add_mut(a.frame(), element!("joint", name = "root")).expect("adds");
    let b = arena.attach_mut(&arena.worldbody(), &robot).expect("attaches");
    arena.add_mut(b.frame(), element!("freejoint")).expect("adds");
    let spot = arena.find(Namespace::Site, "spot").expect("spot");
    arena.attach_mut(&spot, &robot).expect("attaches in the replicate");
    arena
}

/// The name of the element at `loc`, by a walk from the root.
fn walked_full_name(top: &Model, loc: &Loc) -> Option<String> {
    let mut walk = Walk::new(top);
    let inst = walk.insts.along(loc.scope())?;
    let name = walk.insts.name_of_id(inst, loc.id())?;
    Some(name.to_string_in(&walk.insts.list[inst].names.prefix))
}

/// The composed children of the element at `loc`, by a walk from the root.
fn walked_children(top: &Model, loc: &Loc) -> Vec<Loc> {
    let mut walk = Walk::new(top);
    let inst = walk.insts.along(loc.scope()).expect("a scope of the model");
    let node = top.scoped_model(loc.scope()).and_then(|m| m.node_by_id(loc.id())).expect("node");
    let section = node.kind().spec().parent == Some(ElementKind::ROOT);
    let depth = match (node.kind() == ElementKind::ROOT, section, inst) {
        (true, _, 0) => 0,
        (_, true, 0) => 1,
        _ => 2,
    };
    let items = walk.expand(super::Item::plain(inst, node, depth, false));
    let name = top.name();
    items
        .iter()
        .map(|it| Loc::scoped(walk.insts.list[it.inst].frames.clone(), it.node.id(), name))
        .collect()
}

/// The parent of the element at `loc`, by a handle that knows none.
fn looked_up_parent(top: &Model, loc: &Loc) -> Option<Loc> {
    top.get(loc).expect("in the model").parent().map(|p| p.loc())
}

fn assert_handle_agrees(top: &Model, h: &ElementRef<'_>) {
    let loc = h.loc();
    let name = h.full_name();
    assert_eq!(name, walked_full_name(top, &loc), "{h:?}");
    assert_eq!(top.get(&loc).expect("in the model").full_name(), name, "{h:?}");
    assert_eq!(h.parent().map(|p| p.loc()), looked_up_parent(top, &loc), "{h:?}");
    if let Some(p) = h.parent() {
        assert_eq!(p.full_name(), walked_full_name(top, &p.loc()), "{h:?}");
    }
}

#[test]
fn handles_walked_down_by_children_agree_with_walks_from_the_root() {
    let m = composed();
    let xml = m.to_xml_string().expect("writes");
    let mut stack = vec![m.get(&m.root()).expect("root")];
    let (mut seen, mut named, mut unnamed, mut deepest) = (0, 0, 0, 0);
    while let Some(h) = stack.pop() {
        assert_handle_agrees(&m, &h);
        if let Some(name) = h.full_name() {
            assert!(
                xml.contains(&format!("name=\"{name}\""))
                    || h.kind().namespace() == Some(Namespace::Default),
                "{name} in {xml}"
            );
            named += 1;
            unnamed += usize::from(name.contains("unnamed_"));
        }
        let children: Vec<ElementRef<'_>> = h.children().collect();
        let locs: Vec<Loc> = children.iter().map(ElementRef::loc).collect();
        assert_eq!(locs, walked_children(&m, &h.loc()), "{h:?}");
        for c in &children {
            assert_eq!(c.parent().map(|p| p.loc()), Some(h.loc()), "{c:?}");
        }
        deepest = deepest.max(h.loc().scope().len());
        seen += 1;
        stack.extend(children);
    }
    let walked = m.walk().filter(|e| matches!(e, Event::Enter(_))).count();
    assert_eq!(seen, walked);
    assert_eq!(deepest, 3, "attachments three levels deep");
    assert!(unnamed > 20 && named > unnamed, "{named} named, {unnamed} unnamed");
}

#[test]
fn handles_of_the_preorder_walk_agree_with_walks_from_the_root() {
    let m = composed();
    let mut walk = m.walk();
    let (mut entered, mut skipped) = (0, 0);
    while let Some(event) = walk.next() {
        let Event::Enter(h) = event else { continue };
        assert_handle_agrees(&m, &h);
        entered += 1;
        // Skipping subtrees (a frame's joints, a `<replicate>` holding a robot)
        // leaves the parents of the handles after them right.
        if h.kind().is(Role::Replicate) || h.parent().is_some_and(|p| p.is_frame()) {
            walk.skip_subtree();
            skipped += 1;
        }
    }
    assert!(entered > 100 && skipped > 3, "{entered} entered, {skipped} skipped");
}

#[test]
fn handles_made_by_locators_agree_with_walks_from_the_root() {
    let m = composed();
    for ns in [Namespace::Body, Namespace::Geom, Namespace::Joint, Namespace::Site] {
        for loc in m.find_all(ns) {
            let h = m.get(&loc).expect("found");
            assert_handle_agrees(&m, &h);
            let children: Vec<Loc> = h.children().map(|c| c.loc()).collect();
            assert_eq!(children, walked_children(&m, &loc));
        }
    }
}

#[test]
fn handles_can_be_sent_and_shared_between_threads() {
    fn send_sync<T: Send + Sync>() {}
    send_sync::<ElementRef<'static>>();
}

#[test]
fn a_handle_deep_in_a_long_chain_drops_without_deep_recursion() {
    let depth = 50_000;
    let mut xml = String::from("<mujoco><worldbody>");
    xml.push_str(&"<body>".repeat(depth));
    xml.push_str(&"</body>".repeat(depth));
    xml.push_str("</worldbody></mujoco>");
    let m = read(&xml);
    let mut h = m.get(&m.worldbody()).expect("worldbody");
    for _ in 0..depth {
        h = h.children().next().expect("a body");
    }
    assert!(h.children().next().is_none());
    let up = h.parent().and_then(|p| p.parent()).expect("two up");
    drop(h);
    assert_eq!(up.children().count(), 1);
}

/// The handles `children` makes share their instance's context: naming one unnamed
/// element counts its model's positions once, for all of them, and a frame's
/// attached bodies get one context, grown from the frame's.
#[test]
fn handles_of_one_instance_share_one_context_counted_once() {
    let m = composed();
    let wb = m.get(&m.worldbody()).expect("worldbody");
    let children: Vec<ElementRef<'_>> = wb.children().collect();
    let (plane, frame) = (&children[0], children.iter().find(|c| c.is_frame()).expect("frame"));
    assert!(std::sync::Arc::ptr_eq(&plane.shared, &frame.shared));
    assert!(plane.shared.auto.get().is_none());
    assert_eq!(plane.full_name().as_deref(), Some("//unnamed_geom_0"));
    let counted = plane.shared.auto.get().expect("counted once named");
    let before = counted;
    for c in &children {
        c.full_name();
    }
    assert!(std::sync::Arc::ptr_eq(before, frame.shared.auto.get().expect("the same count")));
    let inside: Vec<ElementRef<'_>> =
        frame.children().filter(|c| !std::sync::Arc::ptr_eq(&c.shared, &frame.shared)).collect();
    assert!(!inside.is_empty());
    assert!(inside.iter().all(|c| std::sync::Arc::ptr_eq(&c.shared, &inside[0].shared)));
    let outer = inside[0].shared.outer.as_ref().map(|(o, _)| o);
    assert!(outer.is_some_and(|o| std::sync::Arc::ptr_eq(o, &frame.shared)));
}

/// The name of the element at `loc` counted afresh: by a walk from the root of a
/// copy of `m` that shares no count with it.
fn oracle_name(m: &Model, loc: &Loc) -> Option<String> {
    let fresh = m.with_source(m.side.source.clone());
    walked_full_name(&fresh, loc)
}

/// A model keeps the automatic-name positions of the version last counted: handles
/// made one by one by [`Model::element`] (`Model::full_name`, a binding's handles)
/// count a model once, and every edit, in place or not, is counted anew, so names
/// follow it (checked against a walk of the composition from the root).
#[test]
fn a_model_counts_its_unnamed_elements_once_per_version() {
    let mut m = composed();
    let geoms = m.find_all(Namespace::Geom);
    let first = m.element(&geoms[0]).expect("geom");
    assert_eq!(first.full_name(), oracle_name(&m, &geoms[0]));
    let counted = first.shared.auto.get().expect("counted").clone();
    for g in &geoms {
        let h = m.element(g).expect("geom");
        assert_eq!(h.full_name(), oracle_name(&m, g));
        if let Some(a) = h.shared.auto.get() {
            if std::ptr::eq(h.shared.model, first.shared.model) {
                assert!(std::sync::Arc::ptr_eq(a, &counted), "one count per model version");
            }
        }
    }
    // An unnamed geom added first in place: every automatic number after it moves.
    let old = m.clone();
    let wb = m.worldbody();
    m.insert_mut(&wb, 0, element!("geom", size = [0.5])).expect("inserts");
    for g in &m.find_all(Namespace::Geom) {
        assert_eq!(m.full_name(g), oracle_name(&m, g));
    }
    // The older version, asked again, still names by its own count.
    for g in &geoms {
        assert_eq!(old.full_name(g), oracle_name(&old, g));
    }
    let removed = m.remove(&geoms[0]).expect("removes");
    for g in &removed.find_all(Namespace::Geom) {
        assert_eq!(removed.full_name(g), oracle_name(&removed, g));
    }
}
