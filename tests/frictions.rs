//! The frictions a new user hit (issue 21), each shown removed: mixed number lists in
//! `element!`, the children of default classes (`child`), diff lines that name their
//! element, adding without naming the section (`add_top`), a chosen scope name
//! (`attach_as`), and an editor's `History`.

use mjcf::{Element, ErrorKind, History, Model, Namespace, element};

#[test]
fn element_macro_mixes_integers_and_floats_in_a_list() {
    let mixed = element!("geom", type = "box", size = [2, 2, 0.1], rgba = [1, 0.5, 0, 1]);
    let floats = Element::new("geom")
        .attr("type", "box")
        .attr("size", [2.0, 2.0, 0.1])
        .attr("rgba", [1.0, 0.5, 0.0, 1.0]);
    assert_eq!(mixed, floats);
    let mut m = Model::new("m");
    let cam = element!("camera", name = "c", xyaxes = [0, 1, 0, -0.5, 0, 1]);
    let cam = m.add_mut(&m.worldbody(), cam).unwrap();
    assert_eq!(m.floats(&cam, "xyaxes").unwrap(), [0.0, 1.0, 0.0, -0.5, 0.0, 1.0]);
}

#[test]
fn element_macro_lists_take_variables_repeats_and_trailing_commas() {
    let (x, n) = (0.25_f32, 3_u32);
    let e = element!("site", pos = [x, n, -1,], size = [0.1; 3], euler = [0.0, 0.0, 1.0],);
    let expected = Element::new("site")
        .attr("pos", [0.25, 3.0, -1.0])
        .attr("size", [0.1, 0.1, 0.1])
        .attr("euler", [0.0, 0.0, 1.0]);
    assert_eq!(e, expected);
    // A value that only starts with a list is a value as a whole.
    let e = element!("site", pos = [[1.0, 2.0, 3.0], [4.0, 5.0, 6.0]][1]);
    assert_eq!(e, Element::new("site").attr("pos", [4.0, 5.0, 6.0]));
    assert_eq!(element!("site",), Element::new("site"));
}

const TWO_CLASSES: &str = r#"<mujoco model="arm">
  <default>
    <default class="large_actuator"><position kp="2000"/></default>
    <default class="small_actuator"><position kp="500"/></default>
  </default>
  <worldbody><body name="torso"><inertial mass="1" pos="0 0 0"/></body></worldbody>
</mujoco>"#;

#[test]
fn child_reaches_the_position_of_a_default_class() {
    let mut m = Model::from_xml_str(TWO_CLASSES).unwrap();
    let large = m.lookup(Namespace::Default, "large_actuator").unwrap();
    let small = m.lookup(Namespace::Default, "small_actuator").unwrap();
    m.set_attr_mut(&m.child(&large, "position").unwrap(), "kp", 3000).unwrap();
    assert_eq!(m.float(&m.child(&large, "position").unwrap(), "kp").unwrap(), 3000.0);
    assert_eq!(m.float(&m.child(&small, "position").unwrap(), "kp").unwrap(), 500.0);
    let view = m.get(&small).unwrap();
    assert_eq!(view.child("position").and_then(|p| p.float("kp")), Some(500.0));
    // As in dm_control, a class read from MJCF has every default element (empty
    // where the file sets nothing); a tag a class cannot hold is never there.
    assert!(view.child("motor").is_some_and(|c| c.attrs().next().is_none()));
    assert!(view.child("body").is_none());
}

#[test]
fn child_of_a_missing_tag_is_an_error_naming_parent_and_tag() {
    let m = Model::from_xml_str(TWO_CLASSES).unwrap();
    let large = m.lookup(Namespace::Default, "large_actuator").unwrap();
    let e = m.child(&large, "body").unwrap_err();
    assert_eq!(e.kind(), &ErrorKind::NoChild { parent: "default", tag: "body".into() });
    assert_eq!(e.to_string(), "<default> has no <body> child at default[name=large_actuator]");
    assert_eq!(e.path(), "default[name=large_actuator]");
    let removed = m.remove(&large).unwrap();
    assert!(matches!(
        removed.child(&large, "position").unwrap_err().kind(),
        ErrorKind::StaleLocator { .. }
    ));
}

#[test]
fn diff_lines_name_the_default_class_of_an_unnamed_element() {
    let old = Model::from_xml_str(TWO_CLASSES).unwrap();
    let mut new = old.clone();
    for (class, kp) in [("large_actuator", 3000), ("small_actuator", 600)] {
        let class = new.lookup(Namespace::Default, class).unwrap();
        new.set_attr_mut(&new.child(&class, "position").unwrap(), "kp", kp).unwrap();
    }
    let torso = new.lookup(Namespace::Body, "torso").unwrap();
    new.set_attr_mut(&new.child(&torso, "inertial").unwrap(), "mass", 2).unwrap();
    let lines: Vec<String> =
        old.diff(&new).iter().map(|c| c.display(&old, &new).to_string()).collect();
    let mut lines = lines;
    lines.sort();
    assert_eq!(
        lines,
        [
            "~ body[name=torso]/inertial mass: 1 -> 2",
            "~ default[name=large_actuator]/position kp: 2000 -> 3000",
            "~ default[name=small_actuator]/position kp: 500 -> 600",
        ]
    );
}

#[test]
fn diff_lines_tell_unnamed_siblings_of_one_tag_apart() {
    let old = Model::from_xml_str(
        r#"<mujoco><extension><plugin plugin="p"><instance name="i">
        <config key="a" value="1"/><config key="b" value="2"/>
        </instance></plugin></extension></mujoco>"#,
    )
    .unwrap();
    let instance = old.lookup(Namespace::Plugin, "i").unwrap();
    let second = old.get(&instance).unwrap().children().nth(1).unwrap().loc();
    let new = old.set_attr(&second, "value", "3").unwrap();
    let lines: Vec<String> =
        old.diff(&new).iter().map(|c| c.display(&old, &new).to_string()).collect();
    assert_eq!(lines, ["~ instance[name=i]/config[1] value: 2 -> 3"]);
    let fewer = old.remove(&second).unwrap();
    let lines: Vec<String> =
        old.diff(&fewer).iter().map(|c| c.display(&old, &fewer).to_string()).collect();
    assert_eq!(lines, ["- instance[name=i]/config[1]"]);
}

#[test]
fn add_top_puts_each_tag_in_its_section() {
    let m = Model::new("m");
    for (tag, section) in [
        ("body", "worldbody"),
        ("geom", "worldbody"),
        ("site", "worldbody"),
        ("light", "worldbody"),
        ("camera", "worldbody"),
        ("frame", "worldbody"),
        ("motor", "actuator"),
        ("position", "actuator"),
        ("touch", "sensor"),
        ("mesh", "asset"),
        ("material", "asset"),
        ("pair", "contact"),
        ("exclude", "contact"),
        ("key", "keyframe"),
        ("weld", "equality"),
        ("fixed", "tendon"),
    ] {
        let loc = m.section_for(tag).unwrap();
        assert_eq!(m.get(&loc).unwrap().tag(), section, "{tag}");
    }
    let (m2, motor) = m.add_top(element!("motor", name = "m1")).unwrap();
    assert_eq!(m2.get(&motor).unwrap().parent().unwrap().tag(), "actuator");
    assert_eq!(m, Model::new("m")); // the persistent form leaves `self` as it was
}

#[test]
fn add_top_refuses_a_tag_no_section_takes_and_changes_nothing() {
    let mut m = Model::new("m");
    for tag in ["joint", "inertial", "freejoint", "nosuchtag"] {
        let e = m.add_top_mut(Element::new(tag)).unwrap_err();
        assert_eq!(e.kind(), &ErrorKind::NoSection { tag: tag.into() });
        assert_eq!(m, Model::new("m"));
    }
    // A tag several sections take is refused too, not placed in the first.
    let many: Vec<&str> = mjcf::ElementKind::all()
        .map(|k| k.tag())
        .filter(|t| {
            let root = mjcf::ElementKind::all().next().unwrap();
            root.spec()
                .children
                .iter()
                .filter(|s| s.tag() != "default" && s.child(t).is_some())
                .count()
                > 1
        })
        .collect();
    assert!(!many.is_empty());
    for tag in many {
        assert!(
            matches!(m.section_for(tag).unwrap_err().kind(), ErrorKind::NoSection { .. }),
            "{tag}"
        );
    }
}

fn hand() -> Model {
    let mut hand = Model::new("jaco_hand");
    let palm = hand.add_top_mut(element!("body", name = "palm")).unwrap();
    hand.add_mut(&palm, element!("site", name = "tip")).unwrap();
    hand
}

#[test]
fn attach_as_chooses_the_scope_with_the_same_uniqueness_rule() {
    let mut arm = Model::new("arm");
    let before = arm.clone();
    let a = arm.attach_as_mut(&arm.worldbody(), &hand(), "gripper").unwrap();
    let b = arm.attach_as_mut(&arm.worldbody(), &hand(), "gripper").unwrap();
    // A default-named attachment and a chosen name share one rule.
    let c = arm.attach_mut(&arm.worldbody(), &Model::new("gripper")).unwrap();
    assert_eq!([a.scope(), b.scope(), c.scope()], ["gripper", "gripper_1", "gripper_2"]);
    let xml = arm.to_xml_string().unwrap();
    assert!(xml.contains(r#"<body name="gripper/palm">"#), "{xml}");
    assert!(xml.contains(r#"<body name="gripper_1/palm">"#), "{xml}");
    assert_eq!(arm.attached(&a).unwrap().name(), "jaco_hand"); // the child keeps its name
    for x in [&c, &b, &a] {
        arm.detach_mut(x).unwrap();
    }
    assert_eq!(arm, before);
}

#[test]
fn attach_as_inside_an_attachment_and_in_the_persistent_form() {
    let arena = Model::new("arena");
    let (arena, outer) = arena.attach_as(&arena.worldbody(), &hand(), "left").unwrap();
    let tip = arena.lookup(Namespace::Site, "left/tip").unwrap();
    let (scene, inner) = arena.attach_as(&tip, &hand(), "gripper").unwrap();
    assert_eq!((outer.scope(), inner.scope()), ("left", "left/gripper"));
    assert!(scene.find(Namespace::Body, "left/gripper/palm").is_some());
    assert!(arena.find(Namespace::Body, "left/gripper/palm").is_none()); // unchanged
}

#[test]
fn attach_as_refuses_a_bad_scope_name_and_changes_nothing() {
    let mut arm = Model::new("arm");
    let before = arm.clone();
    for bad in ["", "a/b", "/", "nul\0"] {
        let e = arm.attach_as_mut(&arm.worldbody(), &hand(), bad).unwrap_err();
        assert!(
            matches!(e.kind(), ErrorKind::InvalidValue { attribute: "model", .. }),
            "{bad:?}: {e}"
        );
        assert_eq!(arm, before);
    }
}

fn boxes(history: &mut History, n: usize) {
    for i in 0..n {
        history
            .edit(format!("box {i}"), |m| {
                m.add_top_mut(element!("body", name = format!("box_{i}")))
            })
            .unwrap();
    }
}

#[test]
fn history_undo_redo_and_editing_after_undo_drops_the_redoable_entries() {
    let mut history = History::new(Model::new("m"));
    boxes(&mut history, 3);
    assert_eq!((history.len(), history.position()), (4, 3));
    assert!(history.undo() && history.undo());
    assert_eq!(history.label(history.position()), Some("box 0"));
    assert!(history.redo());
    assert_eq!(history.current(), history.get(2).unwrap());
    assert!(history.undo() && history.undo());
    assert!(!history.undo()); // at the oldest: nothing moves
    assert_eq!(history.position(), 0);
    assert!(history.go_to(3) && !history.redo() && !history.go_to(4));
    history.go_to(1);
    history.edit("other", |m| m.add_top_mut(element!("site", name = "s"))).unwrap();
    assert_eq!(history.len(), 3);
    assert_eq!(history.diff_lines(1, 2).unwrap(), ["+ site s"]);
    assert!(history.diff(0, 3).is_none());
}

#[test]
fn history_edit_that_fails_leaves_the_history_unchanged() {
    let mut history = History::new(Model::new("m"));
    boxes(&mut history, 1);
    let e = history.edit("bad", |m| m.add_top_mut(element!("body", name = "box_0")));
    assert!(matches!(e.unwrap_err().kind(), ErrorKind::DuplicateIdentifier { .. }));
    assert_eq!((history.len(), history.position()), (2, 1));
    // A closure that changed the copy before failing leaves no trace either.
    let e = history.edit("half", |m| {
        m.add_top_mut(element!("body", name = "kept_out"))?;
        m.add_top_mut(element!("joint"))
    });
    assert!(e.is_err());
    assert!(history.current().find(Namespace::Body, "kept_out").is_none());
}

#[test]
fn history_with_a_limit_forgets_the_oldest_entries() {
    let mut history = History::with_limit(Model::new("m"), 3);
    boxes(&mut history, 5);
    assert_eq!((history.len(), history.position()), (3, 2));
    assert_eq!(history.label(0), Some("box 2"));
    assert_eq!(history.diff_lines(0, 2).unwrap(), ["+ body box_3", "+ body box_4"]);
    let mut one = History::with_limit(Model::new("m"), 0); // keeps the current version
    boxes(&mut one, 2);
    assert_eq!((one.len(), one.label(0)), (1, Some("box 1")));
    assert!(!one.undo());
}

#[test]
fn history_versions_share_what_they_did_not_change() {
    let mut history = History::new(Model::new("m"));
    boxes(&mut history, 2);
    let (a, b) = (history.get(1).unwrap(), history.get(2).unwrap());
    let box0 = a.lookup(Namespace::Body, "box_0").unwrap();
    assert!(a.get(&box0).unwrap().ptr_eq(&b.get(&box0).unwrap()));
}

#[test]
fn attrs_macro_mixes_integers_and_floats_for_set() {
    let a = mjcf::attrs!(rgba = [1, 0.5, 0, 1], mass = 2, class = "main",);
    let b =
        mjcf::Attrs::new().set("rgba", [1.0, 0.5, 0.0, 1.0]).set("mass", 2).set("class", "main");
    assert_eq!(a, b);
    assert_eq!(mjcf::attrs!(), mjcf::Attrs::new());
    let mut m = Model::new("m");
    let g = m.add_top_mut(element!("geom", size = [0.1])).unwrap();
    m.set_mut(&g, mjcf::attrs!(rgba = [1, 0.5, 0, 1], pos = [0; 3])).unwrap();
    assert_eq!(m.floats(&g, "rgba").unwrap(), [1.0, 0.5, 0.0, 1.0]);
}

#[test]
fn child_reaches_into_an_attachment_and_diff_lines_name_its_elements() {
    let mut arena = Model::new("arena");
    let a = arena.attach_as_mut(&arena.worldbody(), &hand(), "left").unwrap();
    let palm = arena.child(a.frame(), "body").unwrap();
    assert!(palm.is_scoped());
    assert_eq!(arena.get(&palm).unwrap().full_name().as_deref(), Some("left/palm"));
    let old = arena.clone();
    arena.add_mut(&palm, element!("inertial", pos = [0; 3], mass = 1)).unwrap();
    let lines: Vec<String> =
        old.diff(&arena).iter().map(|c| c.display(&old, &arena).to_string()).collect();
    assert_eq!(lines, ["+ body[name=left/palm]/inertial"]);
}
