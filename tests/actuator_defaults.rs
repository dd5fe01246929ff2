//! decision D11 wherever a default class's content comes from: its actuator defaults
//! (`<motor>`, `<velocity>`, `<position>`, ...) are written in the order they were
//! read or given, which is the order MuJoCo applies them in (the last one sets the
//! gains), not in schema order (`motor`, `position`, `velocity`). Issue 19 item 3:
//! through a root-level `<include>` they were written in schema order, and a real
//! humanoid's position gains of 4000 became 1. `tools/mujoco_cases.py` compiles the
//! include case (`examples/mujoco_cases.rs`, `d11_through_include`).

use mjcf::{Element, Model, ReadOptions, element};

/// The actuator default tags of the written text, in order.
fn order(m: &Model) -> Vec<String> {
    let xml = m.to_xml_string().unwrap();
    xml.lines()
        .map(str::trim_start)
        .filter_map(|l| {
            let tag = l.strip_prefix('<')?.split([' ', '/', '>']).next()?;
            ["motor", "velocity", "position", "general"].contains(&tag).then(|| tag.to_string())
        })
        .collect()
}

const ORDERED: &str = r#"<motor gear="2"/><velocity kv="1"/><position kp="4000" kv="400"/>"#;

fn in_order() -> Vec<String> {
    ["motor", "velocity", "position"].map(String::from).to_vec()
}

fn with_file(name: &str, text: &str) -> ReadOptions {
    ReadOptions::new().asset(name, text.as_bytes().to_vec())
}

/// The issue's case: the root class's actuator defaults come from a root-level
/// include.
#[test]
fn actuator_defaults_from_a_root_level_include_keep_their_order() {
    let inc = format!("<mujoco><default>{ORDERED}</default></mujoco>");
    let m = with_file("defaults.xml", &inc)
        .read_str(r#"<mujoco><include file="defaults.xml"/></mujoco>"#)
        .unwrap();
    assert_eq!(order(&m), in_order());
    // A named class of the included file, too (copied whole).
    let inc =
        format!(r#"<mujoco><default><default class="arm">{ORDERED}</default></default></mujoco>"#);
    let m = with_file("defaults.xml", &inc)
        .read_str(r#"<mujoco><include file="defaults.xml"/></mujoco>"#)
        .unwrap();
    assert_eq!(order(&m), in_order());
}

/// An include inside a class: its elements in place of the tag, between the class's
/// own (each file's positions count from its own start, so they are not the order).
#[test]
fn actuator_defaults_around_an_include_inside_a_class_keep_their_order() {
    let inc = r#"<mujoco><position kp="4000" kv="400"/></mujoco>"#;
    let main = r#"<mujoco><default><default class="arm">
        <motor gear="2"/><velocity kv="1"/>
        <include file="pos.xml"/>
        </default></default></mujoco>"#;
    let m = with_file("pos.xml", inc).read_str(main).unwrap();
    assert_eq!(order(&m), in_order());
    // Before the class's own.
    let main = r#"<mujoco><default><default class="arm"><include file="pos.xml"/><motor gear="2"/></default></default></mujoco>"#;
    let m = with_file("pos.xml", inc).read_str(main).unwrap();
    assert_eq!(order(&m), ["position", "motor"]);
}

/// `include_copy`: the receiving class's actuator defaults, then the copied ones, each
/// in its order; without actuator defaults to copy, its children stay in their order.
#[test]
fn include_copy_keeps_the_order_of_actuator_defaults() {
    let src =
        Model::from_xml_str(&format!("<mujoco><default>{ORDERED}</default></mujoco>")).unwrap();
    let m = Model::new("m").include_copy(&src, false).unwrap();
    assert_eq!(order(&m), in_order());
    let own = Model::from_xml_str(r#"<mujoco><default><general gainprm="3"/></default></mujoco>"#)
        .unwrap();
    let m = own.include_copy(&src, false).unwrap();
    assert_eq!(order(&m), ["general", "motor", "velocity", "position"]);
    let plain =
        Model::from_xml_str(r#"<mujoco><default><geom size="1"/></default></mujoco>"#).unwrap();
    let m = own.include_copy(&plain, false).unwrap();
    let kinds = |m: &Model| -> Vec<&'static str> {
        m.get(&m.default_class()).unwrap().children().map(|c| c.tag()).collect()
    };
    assert_eq!(kinds(&m), kinds(&own));
    assert_eq!(order(&m), ["general"]);
}

/// A class built as an [`Element`] (added, or inserted, into a model): its actuator
/// defaults in the order of its children.
#[test]
fn a_class_built_as_an_element_keeps_the_order_of_its_actuator_defaults() {
    let class = Element::new("default")
        .attr("class", "arm")
        .child(element!("motor", gear = [2]))
        .child(element!("velocity", kv = 1))
        .child(element!("position", kp = 4000, kv = 400))
        .child(element!("geom", size = [0.1]));
    let mut m = Model::new("m");
    m.add_mut(&m.default_class(), class.clone()).unwrap();
    assert_eq!(order(&m), in_order());
    // Read back, the same.
    let back = Model::from_xml_str(&m.to_xml_string().unwrap()).unwrap();
    assert_eq!(order(&back), in_order());
    let mut m = Model::new("m");
    m.insert_mut(&m.default_class(), 0, class).unwrap();
    assert_eq!(order(&m), in_order());
}

/// An attached model's classes are written as they are, in its order.
#[test]
fn attached_classes_keep_the_order_of_their_actuator_defaults() {
    let robot = Model::from_xml_str(&format!(
        r#"<mujoco model="robot"><default><default class="arm">{ORDERED}</default></default></mujoco>"#
    ))
    .unwrap();
    let mut scene = Model::new("scene");
    scene.attach_mut(&scene.worldbody(), &robot).unwrap();
    assert_eq!(order(&scene), in_order());
}
