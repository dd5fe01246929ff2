//! Composing models whose `<compiler angle>` or `eulerseq` differ (decision D17):
//! `attach` (every variant), `include_copy` and an attached `part` convert the
//! incoming model's numbers into the receiving model's conventions instead of
//! refusing. MuJoCo judges the compiled result in `mjcf-mujoco/tests/angles.rs`;
//! these tests hold what is written, what stays, and what is still refused.

use mjcf::{ErrorKind, Model, Namespace, Value};

fn host(settings: &str) -> Model {
    Model::from_xml_str(&format!(
        r#"<mujoco model="host"><compiler {settings}/><worldbody>
        <body name="hb" euler="10 0 0"/><site name="spawn" pos="1 0 0"/></worldbody></mujoco>"#
    ))
    .unwrap()
}

const KID: &str = r#"<mujoco model="kid">
  <compiler angle="degree"/>
  <default>
    <joint range="-90 90"/>
    <default class="slide"><joint type="slide"/></default>
    <default class="ball"><joint type="ball" range="0 60"/></default>
    <default class="turned"><geom euler="0 0 180"/></default>
  </default>
  <worldbody>
    <body name="b" euler="0 0 90" pos="0 0 1">
      <joint name="h" ref="45" springref="-30"/>
      <joint name="free_range" range="-180 180" limited="false"/>
      <geom name="g" size="0.1" axisangle="0 0 1 90"/>
      <geom name="t" size="0.1" class="turned"/>
      <body name="s" childclass="slide"><joint name="sl" ref="0.5"/><geom size="0.1"/></body>
      <body name="ba"><joint name="bj" class="ball"/><geom size="0.1"/></body>
    </body>
  </worldbody>
</mujoco>"#;

fn kid() -> Model {
    Model::from_xml_str(KID).unwrap()
}

fn close(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12)
}

/// The numbers of `attr` (an array, or one number) of the element named `name`.
fn floats(m: &Model, ns: Namespace, name: &str, attr: &str) -> Vec<f64> {
    let loc = m.find(ns, name).unwrap_or_else(|| panic!("no {name}"));
    match m.get(&loc).unwrap().attr(attr) {
        Some(Value::Float(x)) => vec![*x],
        Some(Value::Floats(v)) => v.to_vec(),
        other => panic!("{name} {attr}: {other:?}"),
    }
}

fn has(m: &Model, ns: Namespace, name: &str, attr: &str) -> bool {
    let loc = m.find(ns, name).unwrap();
    m.get(&loc).unwrap().attr(attr).is_some()
}

#[test]
fn a_degree_child_attached_to_a_radian_host_is_converted() {
    let host = host(r#"angle="radian""#);
    let spawn = host.find(Namespace::Site, "spawn").unwrap();
    let (scene, a) = host.attach(&spawn, &kid()).unwrap();
    let d = std::f64::consts::PI / 180.0;
    let f = |ns, n, attr| floats(&scene, ns, n, attr);
    assert!(close(&f(Namespace::Body, "kid/b", "euler"), &[0.0, 0.0, 90.0 * d]));
    assert!(close(&f(Namespace::Geom, "kid/g", "axisangle"), &[0.0, 0.0, 1.0, 90.0 * d]));
    // The hinge's own values, and the range it takes from the root class, set on it.
    assert!(close(&f(Namespace::Joint, "kid/h", "ref"), &[45.0 * d]));
    assert!(close(&f(Namespace::Joint, "kid/h", "springref"), &[-30.0 * d]));
    assert!(close(&f(Namespace::Joint, "kid/h", "range"), &[-90.0 * d, 90.0 * d]));
    // A ball's range (from its class) too; an unlimited joint's and a slide's not.
    assert!(close(&f(Namespace::Joint, "kid/bj", "range"), &[0.0, 60.0 * d]));
    assert!(close(&f(Namespace::Joint, "kid/free_range", "range"), &[-180.0, 180.0]));
    assert!(close(&f(Namespace::Joint, "kid/sl", "ref"), &[0.5]));
    assert!(!has(&scene, Namespace::Joint, "kid/sl", "range"));
    // The attached model says radians, as the merged settings do; the host is as it was.
    let attached = scene.attached(&a).unwrap();
    let compiler = attached.section("compiler").unwrap();
    assert_eq!(attached.string(&compiler, "angle").unwrap(), "radian");
    assert!(close(&floats(&scene, Namespace::Body, "hb", "euler"), &[10.0, 0.0, 0.0]));
    let text = scene.to_xml_string().unwrap();
    assert_eq!(text.matches(" angle=").count(), 1, "{text}");
    assert!(text.contains(r#"<compiler angle="radian"/>"#), "{text}");
    // Detach gives back the host exactly.
    assert_eq!(scene.detach(&a).unwrap(), host);
}

#[test]
fn a_class_keeps_its_joint_numbers_and_its_orientation_is_converted() {
    let (scene, a) = host(r#"angle="radian""#).attach_to_world(&kid()).unwrap();
    let attached = scene.attached(&a).unwrap();
    // The root class's range serves the slide joints as it is; the hinge has its own.
    let text = attached.to_xml_string().unwrap();
    assert!(text.contains(r#"<joint range="-90 90"/>"#), "{text}");
    let pi = std::f64::consts::PI;
    assert!(text.contains(&format!(r#"<geom euler="0 0 {pi}"/>"#)), "{text}");
}

#[test]
fn a_radian_child_attached_to_a_degree_host_is_converted() {
    let child = Model::from_xml_str(
        r#"<mujoco model="r"><compiler angle="radian"/><worldbody>
        <body name="b" euler="0 0 1.5"><joint name="j" range="-1 1"/><geom size="0.1"/></body>
        </worldbody></mujoco>"#,
    )
    .unwrap();
    let host = host(r#"angle="degree""#);
    for scene in [
        host.attach_to_world(&child).unwrap().0,
        host.attach_as(&host.worldbody(), &child, "other").unwrap().0,
        host.attach_in(&host.find(Namespace::Body, "hb").unwrap(), &child).unwrap().0,
        host.attach_welded(&host.find(Namespace::Site, "spawn").unwrap(), &child).unwrap().0,
    ] {
        let prefix = scene.scopes().next().unwrap().to_string();
        let euler = floats(&scene, Namespace::Body, &format!("{prefix}/b"), "euler");
        assert!(close(&euler, &[0.0, 0.0, 1.5f64.to_degrees()]), "{euler:?}");
        let range = floats(&scene, Namespace::Joint, &format!("{prefix}/j"), "range");
        assert!(close(&range, &[-1f64.to_degrees(), 1f64.to_degrees()]), "{range:?}");
    }
}

#[test]
fn another_euler_sequence_becomes_the_same_rotation_as_an_axisangle() {
    let child = Model::from_xml_str(
        r#"<mujoco model="z"><compiler eulerseq="zyx"/><worldbody>
        <body name="b" euler="90 0 0"/><body name="c" axisangle="1 0 0 30"/>
        <replicate count="2" euler="45 0 0"><body name="r"/></replicate>
        </worldbody></mujoco>"#,
    )
    .unwrap();
    let (scene, _) = host(r#"eulerseq="xyz""#).attach_to_world(&child).unwrap();
    // 90 degrees about z (the sequence's first letter): axis z, 90 degrees.
    assert!(close(&floats(&scene, Namespace::Body, "z/b", "axisangle"), &[0.0, 0.0, 1.0, 90.0]));
    assert!(!has(&scene, Namespace::Body, "z/b", "euler"));
    // An axisangle does not depend on the sequence.
    assert!(close(&floats(&scene, Namespace::Body, "z/c", "axisangle"), &[1.0, 0.0, 0.0, 30.0]));
    // A replicate turning about z alone: the z letter of the new sequence.
    let text = scene.to_xml_string().unwrap();
    assert!(text.contains(r#"<replicate count="2" euler="0 0 45">"#), "{text}");
}

#[test]
fn what_cannot_be_converted_is_refused_and_changes_nothing() {
    // A replicate turning about two axes has no equivalent in another sequence.
    let child = Model::from_xml_str(
        r#"<mujoco model="z"><compiler eulerseq="zyx"/><worldbody>
        <replicate count="2" euler="45 10 0"><body name="r"/></replicate>
        </worldbody></mujoco>"#,
    )
    .unwrap();
    let mut xyz = host(r#"eulerseq="xyz""#);
    let before = xyz.clone();
    let world = xyz.worldbody();
    let err = xyz.attach_mut(&world, &child).unwrap_err();
    assert!(
        matches!(
            err.kind(),
            ErrorKind::AttributeConflict { tag: "replicate", attribute: "euler", .. }
        ),
        "{err}"
    );
    assert_eq!(xyz, before);
    let err = xyz.include_copy(&child, false).unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::AttributeConflict { .. }), "{err}");
    // A sequence that is not three of xyzXYZ is not converted either.
    let bad = Model::from_xml_str(
        r#"<mujoco model="q"><compiler eulerseq="xyq"/><worldbody><body euler="1 2 3"/></worldbody></mujoco>"#,
    )
    .unwrap();
    let err = xyz.attach(&xyz.worldbody(), &bad).unwrap_err();
    assert!(
        matches!(
            err.kind(),
            ErrorKind::AttributeConflict { tag: "compiler", attribute: "eulerseq", .. }
        ),
        "{err}"
    );
    // Other compiler attributes must still agree.
    let other = Model::from_xml_str(r#"<mujoco model="o"><compiler autolimits="false"/></mujoco>"#)
        .unwrap();
    let agrees = host(r#"autolimits="true""#);
    let err = agrees.attach(&agrees.worldbody(), &other).unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::AttributeConflict { attribute: "autolimits", .. }));
}

#[test]
fn a_side_that_leaves_the_unit_unset_takes_the_other_s_unconverted() {
    // As before: only values both models set are converted.
    let plain = Model::from_xml_str(r#"<mujoco model="host"><worldbody/></mujoco>"#).unwrap();
    let child = kid();
    let (scene, a) = plain.attach_to_world(&child).unwrap();
    assert_eq!(scene.attached(&a).unwrap(), &child);
    assert!(close(&floats(&scene, Namespace::Body, "kid/b", "euler"), &[0.0, 0.0, 90.0]));
    // A child in the host's conventions is shared, not copied.
    let (scene, a) = host(r#"angle="degree""#).attach_to_world(&child).unwrap();
    assert_eq!(scene.attached(&a).unwrap(), &child);
}

#[test]
fn include_copy_converts_the_source_unless_it_overrides_the_settings() {
    let host = host(r#"angle="radian""#);
    let d = std::f64::consts::PI / 180.0;
    let copied = host.include_copy(&kid(), false).unwrap();
    assert!(close(&floats(&copied, Namespace::Body, "b", "euler"), &[0.0, 0.0, 90.0 * d]));
    assert!(close(&floats(&copied, Namespace::Joint, "h", "range"), &[-90.0 * d, 90.0 * d]));
    assert!(close(&floats(&copied, Namespace::Body, "hb", "euler"), &[10.0, 0.0, 0.0]));
    // With override_attributes the source's settings replace the host's: its numbers
    // are copied as they are, and the result says degrees.
    let overridden = host.include_copy(&kid(), true).unwrap();
    assert!(close(&floats(&overridden, Namespace::Body, "b", "euler"), &[0.0, 0.0, 90.0]));
    let compiler = overridden.section("compiler").unwrap();
    assert_eq!(overridden.string(&compiler, "angle").unwrap(), "degree");
}

#[test]
fn an_attached_part_is_converted() {
    let source = kid();
    let part = source.part("s").unwrap().model;
    let (scene, a) = host(r#"angle="radian""#).attach_to_world(&part).unwrap();
    // A slide joint's ref is not an angle.
    let name = format!("{}/sl", a.scope());
    assert!(close(&floats(&scene, Namespace::Joint, &name, "ref"), &[0.5]));
    let part = source.part("b").unwrap().model;
    let (scene, a) = host(r#"angle="radian""#).attach_to_world(&part).unwrap();
    let euler = floats(&scene, Namespace::Body, &format!("{}/b", a.scope()), "euler");
    assert!(close(&euler, &[0.0, 0.0, std::f64::consts::FRAC_PI_2]), "{euler:?}");
}

#[test]
fn a_later_edit_of_the_host_s_unit_still_conflicts_with_the_attachment() {
    let host = host(r#"angle="radian""#);
    let (scene, _) = host.attach_to_world(&kid()).unwrap();
    let compiler = scene.section("compiler").unwrap();
    let err = scene.set_attr(&compiler, "angle", "degree").unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::AttributeConflict { attribute: "angle", .. }), "{err}");
}

#[test]
fn a_fleet_shares_the_converted_copy_the_first_attach_holds() {
    let arena = host(r#"angle="radian""#);
    let (scene, a) = arena.attach_to_world(&kid()).unwrap();
    let converted = scene.attached(&a).unwrap().clone();
    let (scene, b) = scene.attach_to_world(&converted).unwrap();
    assert!(scene.attached(&b).unwrap().ptr_eq(&converted));
    assert_eq!(scene.attached(&a).unwrap(), scene.attached(&b).unwrap());
}

#[test]
fn a_child_whose_unit_comes_from_its_own_attachment_is_converted_with_it() {
    // The middle model sets no unit; the model attached to it says degrees, so the
    // middle model's own numbers are degrees too (its merged settings).
    let mut middle = Model::from_xml_str(
        r#"<mujoco model="mid"><worldbody><body name="m" euler="0 0 90"/></worldbody></mujoco>"#,
    )
    .unwrap();
    let world = middle.worldbody();
    middle.attach_mut(&world, &kid()).unwrap();
    let (scene, a) = host(r#"angle="radian""#).attach_to_world(&middle).unwrap();
    let half = std::f64::consts::FRAC_PI_2;
    assert!(close(&floats(&scene, Namespace::Body, "mid/m", "euler"), &[0.0, 0.0, half]));
    assert!(close(&floats(&scene, Namespace::Body, "mid/kid/b", "euler"), &[0.0, 0.0, half]));
    // The compiler that set the unit says radians now; the middle one still sets none.
    let held = scene.attached(&a).unwrap();
    assert!(held.get(&held.section("compiler").unwrap()).unwrap().attr("angle").is_none());
    let inner = held.attached("kid").unwrap();
    assert_eq!(inner.string(&inner.section("compiler").unwrap(), "angle").unwrap(), "radian");
}
