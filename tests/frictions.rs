//! The frictions a new user hit (issue 21), each shown removed: mixed number lists in
//! `element!`, ...

use mjcf::{Element, ErrorKind, Model, Namespace, element};

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
