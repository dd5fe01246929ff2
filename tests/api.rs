//! The user-facing API of issue 10: in-place twins, attachment handles, scope paths,
//! lookups that explain a miss, typed accessors, the composed cursor and walk.

use mjcf::{EditError, Element, ErrorKind, Event, Loc, Model, Namespace, element};

use crate::robot;
use robot::robot;

/// An arena with two sites, a robot attached at each (`robot`, `robot_1`) and a
/// freejoint on the first frame.
fn scene() -> Result<(Model, mjcf::Attachment, mjcf::Attachment), EditError> {
    let mut arena = Model::new("arena");
    let world = arena.worldbody();
    let a = arena.add_mut(&world, element!("site", name = "a", pos = [0, 0, 1]))?;
    let b = arena.add_mut(&world, element!("site", name = "b", pos = [1, 0, 1]))?;
    let first = arena.attach_mut(&a, &robot("robot"))?;
    let second = arena.attach_mut(&b, &robot("robot"))?;
    arena.add_mut(first.frame(), element!("freejoint", name = "root"))?;
    Ok((arena, first, second))
}

#[test]
fn in_place_edits_match_the_persistent_ones_and_leave_clones_alone() -> Result<(), EditError> {
    let base = Model::new("m");
    // Persistent.
    let (p1, body) = base.add(&base.worldbody(), element!("body", name = "b"))?;
    let p2 = p1.set_attr(&body, "pos", [1, 2, 3])?;
    // In place, on a clone taken first.
    let mut m = base.clone();
    let before = m.clone();
    let body2 = m.add_mut(&m.worldbody(), element!("body", name = "b"))?;
    let after_add = m.clone();
    m.set_attr_mut(&body2, "pos", [1, 2, 3])?;
    assert_eq!(m.to_xml_string().unwrap(), p2.to_xml_string().unwrap());
    assert_eq!(
        before.to_xml_string().unwrap(),
        base.to_xml_string().unwrap(),
        "the clone kept its content"
    );
    assert!(
        after_add.float(&body2, "pos").is_err(),
        "a clone taken between edits keeps its version"
    );
    assert_eq!(after_add.get(&body2)?.floats("pos"), None);
    assert_eq!(m.floats(&body2, "pos")?, [1.0, 2.0, 3.0]);
    // A failing in-place edit changes nothing.
    let snapshot = m.clone();
    let err = m.set_attr_mut(&body2, "pos", "not numbers").unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::InvalidValue { .. }));
    assert!(m.ptr_eq(&snapshot));
    let err = m.add_mut(&m.worldbody(), element!("body", name = "b")).unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::DuplicateIdentifier { .. }));
    assert!(m.ptr_eq(&snapshot));
    m.remove_mut(&body2)?;
    m.set_name("renamed");
    assert_eq!(m.name(), "renamed");
    assert_eq!(snapshot.name(), "m");
    Ok(())
}

#[test]
fn attach_returns_frame_and_scope_and_detach_takes_either() -> Result<(), EditError> {
    let (arena, first, second) = scene()?;
    assert_eq!(first.scope(), "robot");
    assert_eq!(second.scope(), "robot_1");
    assert_eq!(arena.scope_of_frame(second.frame()).as_deref(), Some("robot_1"));
    // By handle and by path, the same result.
    assert_eq!(arena.detach(&second)?, arena.detach("robot_1")?);
    // The handle follows a rename of its scope.
    let renamed = arena.rename_scope(&second, "dog")?;
    assert!(renamed.find(Namespace::Body, "dog/torso").is_some());
    let back = renamed.detach(&second)?;
    assert!(back.find(Namespace::Body, "dog/torso").is_none());
    assert!(back.find(Namespace::Body, "robot/torso").is_some());
    // Scope queries take handles too.
    assert_eq!(arena.attached(&first)?.name(), "robot");
    assert_eq!(&arena.frame("robot")?, first.frame());
    assert_eq!(arena.attachment("robot_1")?, second);
    Ok(())
}

#[test]
fn malformed_scope_paths_are_errors_everywhere() -> Result<(), EditError> {
    let (arena, _, _) = scene()?;
    for bad in ["/robot", "robot/", "", "robot//x", "/"] {
        let e = arena.detach(bad).unwrap_err();
        assert!(matches!(e.kind(), ErrorKind::InvalidScope(_)), "detach({bad:?}): {e}");
        assert!(matches!(arena.attached(bad).unwrap_err().kind(), ErrorKind::InvalidScope(_)));
        assert!(matches!(
            arena.rename_scope(bad, "x").unwrap_err().kind(),
            ErrorKind::InvalidScope(_)
        ));
        assert!(matches!(arena.frame(bad).unwrap_err().kind(), ErrorKind::InvalidScope(_)));
    }
    for bad in ["/robot/torso", "robot//torso", "/torso"] {
        assert_eq!(arena.find(Namespace::Body, bad), None, "find({bad:?})");
        let e = arena.lookup(Namespace::Body, bad).unwrap_err();
        assert!(matches!(e.kind(), ErrorKind::InvalidScope(_)), "lookup({bad:?}): {e}");
    }
    Ok(())
}

#[test]
fn misses_explain_themselves() -> Result<(), EditError> {
    let (mut arena, _, _) = scene()?;
    // A name: namespace, identifier, scope, and the nearest names.
    let e = arena.lookup(Namespace::Body, "robot_1/torsoo").unwrap_err();
    assert_eq!(
        e.to_string(),
        "no body named 'torsoo' in scope 'robot_1' (did you mean 'torso'?) at <mujoco>"
    );
    assert!(matches!(e.kind(), ErrorKind::UnknownName { namespace: Namespace::Body, .. }));
    // A scope: what is attached there.
    let e = arena.detach("robott").unwrap_err();
    assert!(e.to_string().contains("attached there: 'robot', 'robot_1'"), "{e}");
    // A tag, an attribute, a keyword.
    let e = arena.add_mut(&arena.worldbody(), element!("bodyy")).unwrap_err();
    assert!(e.to_string().contains("(did you mean 'body'?)"), "{e}");
    let e = arena.add_mut(&arena.worldbody(), element!("geom", rgb = [1, 0, 0])).unwrap_err();
    assert!(e.to_string().contains("(did you mean 'rgba'?)"), "{e}");
    let e = arena.add_mut(&arena.worldbody(), element!("geom", type = "sphear")).unwrap_err();
    assert!(e.to_string().contains("(did you mean 'sphere'?)"), "{e}");
    // A freejoint on a frame that is not in the worldbody names the frame's scope.
    let hand = robot("hand");
    let mount = arena.lookup(Namespace::Site, "robot/mount")?;
    let inner = arena.attach_mut(&mount, &hand)?;
    assert_eq!(inner.scope(), "robot/hand");
    let e = arena.add_mut(inner.frame(), element!("freejoint")).unwrap_err();
    assert!(matches!(e.kind(), ErrorKind::FreejointNotTopLevel(s) if s == "hand"), "{e}");
    assert!(e.to_string().contains("directly in the worldbody"), "{e}");
    // A stale locator names the model it came from.
    let mut other = Model::new("other_model");
    let body = other.add_mut(&other.worldbody(), element!("body"))?;
    let e = arena.add_mut(&body, element!("geom")).unwrap_err();
    assert!(e.to_string().contains("of model 'other_model'"), "{e}");
    Ok(())
}

#[test]
fn typed_accessors_read_values_in_one_call() -> Result<(), EditError> {
    let mut m = Model::new("m");
    let g = m.add_mut(
        &m.worldbody(),
        element!("geom", name = "g", size = [0.1, 0.2], mass = 2, type = "box", priority = 3),
    )?;
    let j =
        m.add_mut(&m.worldbody(), Element::new("body").child(element!("joint", name = "hinge")))?;
    m.add_mut(&m.actuator(), element!("motor", name = "mo", joint = "hinge"))?;
    assert_eq!(m.floats(&g, "size")?, [0.1, 0.2]);
    assert_eq!(m.float(&g, "mass")?, 2.0);
    assert_eq!(m.int(&g, "priority")?, 3);
    assert_eq!(m.string(&g, "type")?, "box");
    assert_eq!(m.string(&g, "name")?, "g");
    let motor = m.lookup(Namespace::Actuator, "mo")?;
    assert_eq!(m.string(&motor, "joint")?, "hinge");
    assert!(matches!(m.float(&g, "rgba").unwrap_err().kind(), ErrorKind::Unset { .. }));
    assert!(matches!(m.float(&g, "size").unwrap_err().kind(), ErrorKind::WrongType { .. }));
    assert!(matches!(m.float(&g, "sise").unwrap_err().kind(), ErrorKind::UnknownAttribute { .. }));
    let _ = j;
    // Integer arrays convert.
    let mut m2 = Model::new("m");
    let b = m2.add_mut(&m2.worldbody(), element!("body", pos = [1, 0, 0]))?;
    assert_eq!(m2.floats(&b, "pos")?, [1.0, 0.0, 0.0]);
    Ok(())
}

#[test]
fn the_cursor_knows_its_scope() -> Result<(), EditError> {
    let (arena, first, _) = scene()?;
    let torso = arena.lookup(Namespace::Body, "robot_1/torso")?;
    let view = arena.get(&torso)?;
    // loc() is exact: it resolves in the model it came from.
    assert_eq!(view.loc(), torso);
    assert_eq!(arena.get(&view.loc())?.identifier(), Some("torso"));
    assert_eq!(view.full_name().as_deref(), Some("robot_1/torso"));
    assert_eq!(view.scope(), "robot_1");
    // Up: the frame, then the worldbody.
    let frame = view.parent().unwrap();
    assert!(frame.is_frame());
    assert_eq!(frame.full_name().as_deref(), Some("robot_1/"));
    assert_eq!(frame.parent().unwrap().tag(), "worldbody");
    // Down from a frame: its own joints, then the attached bodies.
    let f = arena.get(first.frame())?;
    let kids: Vec<String> = f.children().map(|c| c.full_name().unwrap_or_default()).collect();
    assert_eq!(kids, ["robot/root/", "robot/torso"].map(String::from));
    // Unnamed elements get their automatic names.
    let geoms = arena.find_all(Namespace::Geom);
    let names: Vec<String> =
        geoms.iter().map(|g| arena.get(g).unwrap().full_name().unwrap()).collect();
    assert_eq!(
        names,
        ["robot/torso", "robot//unnamed_geom_1", "robot_1/torso", "robot_1//unnamed_geom_1"]
    );
    // A section's composed children: the arena's own actuators, then the robots'.
    let act = arena.get(&arena.actuator())?;
    let motors: Vec<String> = act.children().map(|c| c.full_name().unwrap()).collect();
    assert_eq!(motors, ["robot/m", "robot_1/m"]);
    // An attached actuator's composed parent is the arena's actuator section.
    let m = arena.lookup(Namespace::Actuator, "robot/m")?;
    assert!(arena.get(&m)?.parent().unwrap().ptr_eq(&act));
    Ok(())
}

#[test]
fn one_walk_for_writer_and_find_all() -> Result<(), EditError> {
    let (arena, _, _) = scene()?;
    // The walk enters elements in the order the writer writes them: compare every
    // named element's full name against the names in the output, in order.
    let mut walked = Vec::new();
    let mut walked_bodies = Vec::new();
    let mut depth = 0usize;
    let mut max_depth = 0;
    for e in arena.walk() {
        match e {
            Event::Enter(el) => {
                depth += 1;
                max_depth = max_depth.max(depth);
                if el.kind().namespace().is_some() && el.tag() != "default" {
                    walked.push(el.full_name().unwrap());
                }
                if el.kind().namespace() == Some(Namespace::Body) {
                    walked_bodies.push(el.full_name().unwrap());
                }
            }
            Event::Leave(_) => depth -= 1,
        }
    }
    assert_eq!(depth, 0, "every Enter has its Leave");
    let xml = arena.to_xml_string().unwrap();
    let written: Vec<String> = xml
        .lines()
        .filter(|l| {
            !l.trim_start().starts_with("<default") && !l.trim_start().starts_with("<mujoco")
        })
        .filter_map(|l| l.split(" name=\"").nth(1).map(|r| r[..r.find('"').unwrap()].to_string()))
        .collect();
    assert_eq!(walked, written);
    // find_all follows the same order.
    let bodies: Vec<String> = arena
        .find_all(Namespace::Body)
        .iter()
        .map(|l| arena.get(l).unwrap().full_name().unwrap())
        .collect();
    assert_eq!(bodies, walked_bodies);
    assert_eq!(bodies, ["robot/", "robot/torso", "robot_1/", "robot_1/torso"]);
    // skip_subtree skips children and the Leave.
    let mut w = arena.walk();
    let mut seen = 0;
    while let Some(e) = w.next() {
        if let Event::Enter(el) = &e {
            seen += 1;
            if el.tag() == "mujoco" {
                w.skip_subtree();
            }
        }
    }
    assert_eq!(seen, 1);
    Ok(())
}

#[test]
fn locators_are_values() {
    fn takes(_: &Loc) {}
    let m = Model::new("m");
    takes(&m.worldbody());
    let set: std::collections::HashSet<Loc> =
        [m.worldbody(), m.worldbody(), m.actuator()].into_iter().collect();
    assert_eq!(set.len(), 2);
}

/// An attached model's root default class is a class of its own beside the outermost
/// model's (the walk and `children` put its defaults under it), so `parent` of one of
/// its defaults is that class, whether the handle came from `children` or from a
/// locator; and an element of an attached model's `<asset>` has the outermost
/// `<asset>` as its parent either way.
#[test]
fn parents_of_attached_defaults_and_assets_agree_with_children() -> Result<(), EditError> {
    let robot = Model::from_xml_str(
        r#"<mujoco model="robot"><default><geom rgba="1 0 0 1"/></default>
          <asset><texture name="t" type="2d" builtin="checker" width="8" height="8"/></asset>
          <worldbody><body name="torso"><geom size="0.1"/></body></worldbody></mujoco>"#,
    )
    .expect("reads");
    let mut arena = Model::new("arena");
    arena.attach_mut(&arena.worldbody(), &robot)?;
    let root = arena.get(&arena.root())?;
    let classes: Vec<_> =
        root.children().filter(|c| c.tag() == "default" && !c.scope().is_empty()).collect();
    assert_eq!(classes.len(), 1, "the robot's root class, beside the arena's");
    let class = &classes[0];
    let mut defaults = 0;
    for d in class.children() {
        assert_eq!(d.parent().map(|p| p.loc()), Some(class.loc()));
        assert_eq!(arena.get(&d.loc())?.parent().map(|p| p.loc()), Some(class.loc()));
        defaults += 1;
    }
    assert!(defaults > 0);
    let asset = root.child("asset").expect("the arena's asset section");
    let texture = asset.children().find(|t| !t.scope().is_empty()).expect("the robot's texture");
    assert_eq!(texture.parent().map(|p| p.loc()), Some(asset.loc()));
    assert_eq!(arena.get(&texture.loc())?.parent().map(|p| p.loc()), Some(asset.loc()));
    Ok(())
}
