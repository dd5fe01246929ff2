//! Keys that follow their elements: a model's own keyframes keep each value with its
//! joint, actuator or mocap body when those are added, removed, reordered, renamed or
//! retyped. `mjcf-mujoco/tests/keys_follow.rs` has MuJoCo judge it by name.

use mjcf::{Attrs, Model, Namespace, Referrers, element};

const ROBOT: &str = r#"<mujoco model="robot">
  <worldbody>
    <body name="a_body"><joint name="a" ref="0.1"/><geom size="0.1"/>
      <body name="b_body"><joint name="b" type="ball"/><geom size="0.1"/>
        <body name="c_body"><joint name="c" type="slide"/><geom size="0.1"/></body>
      </body>
    </body>
    <body name="target" mocap="true" pos="1 2 3"><geom size="0.1" contype="0" conaffinity="0"/></body>
  </worldbody>
  <actuator>
    <motor name="ma" joint="a"/>
    <position name="mc" joint="c" timeconst="0.1"/>
  </actuator>
  <keyframe>
    <key name="home" qpos="1 0.5 0.5 0.5 0.5 3" qvel="10 20 21 22 30" act="7" ctrl="100 300" mpos="4 5 6"/>
    <key name="short" qpos="1"/>
  </keyframe>
</mujoco>"#;

fn key(m: &Model, name: &str, attr: &str) -> Vec<f64> {
    let k = m.find(Namespace::Key, name).unwrap();
    m.get(&k).unwrap().floats(attr).map(<[f64]>::to_vec).unwrap_or_default()
}

#[test]
fn removing_a_joint_takes_its_values_out_of_every_key() {
    let m = Model::from_xml_str(ROBOT).unwrap();
    let r = m.remove_with(&m.find(Namespace::Body, "b_body").unwrap(), Referrers::Cascade).unwrap();
    // b and c (inside b_body) go, with the position actuator on c.
    assert_eq!(r.removed, ["mc"]);
    let m = r.model;
    assert_eq!(key(&m, "home", "qpos"), [1.0]);
    assert_eq!(key(&m, "home", "qvel"), [10.0]);
    assert_eq!(key(&m, "home", "ctrl"), [100.0]);
    assert_eq!(key(&m, "home", "act"), Vec::<f64>::new());
    assert_eq!(key(&m, "home", "mpos"), [4.0, 5.0, 6.0]);
    assert_eq!(key(&m, "short", "qpos"), [1.0]);
    assert!(m.check().is_empty(), "{:?}", m.check());
}

#[test]
fn a_new_joint_gets_its_default_and_the_others_keep_theirs() {
    let m = Model::from_xml_str(ROBOT).unwrap();
    let a = m.find(Namespace::Body, "a_body").unwrap();
    // A slide joint before `a` in the same body, with a reference position.
    let (m, _) =
        m.insert(&a, 0, element!("joint", name = "z", type = "slide", r#ref = 0.25)).unwrap();
    assert_eq!(key(&m, "home", "qpos"), [0.25, 1.0, 0.5, 0.5, 0.5, 0.5, 3.0]);
    assert_eq!(key(&m, "home", "qvel"), [0.0, 10.0, 20.0, 21.0, 22.0, 30.0]);
    // The short key is padded as MuJoCo pads it: each joint at its default.
    assert_eq!(key(&m, "short", "qpos"), [0.25, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0]);
    // An actuator and a mocap body.
    let (m, _) = m.add(&m.actuator(), element!("motor", name = "mb", joint = "a")).unwrap();
    assert_eq!(key(&m, "home", "ctrl"), [100.0, 300.0, 0.0]);
    let (m, _) = m
        .insert(
            &m.worldbody(),
            0,
            element!("body", name = "t0", mocap = true, pos = [9, 9, 9]).child(element!(
                "geom",
                size = [0.1],
                contype = 0,
                conaffinity = 0
            )),
        )
        .unwrap();
    assert_eq!(key(&m, "home", "mpos"), [9.0, 9.0, 9.0, 4.0, 5.0, 6.0]);
    assert!(m.check().is_empty(), "{:?}", m.check());
}

#[test]
fn renaming_keeps_values_and_retyping_defaults_them() {
    let m = Model::from_xml_str(ROBOT).unwrap();
    let a = m.find(Namespace::Joint, "a").unwrap();
    let renamed = m.set(&a, Attrs::new().set("name", "alpha")).unwrap();
    assert_eq!(key(&renamed, "home", "qpos"), key(&m, "home", "qpos"));
    let b = m.find(Namespace::Joint, "b").unwrap();
    let retyped = m.set(&b, Attrs::new().set("type", "hinge")).unwrap();
    assert_eq!(key(&retyped, "home", "qpos"), [1.0, 0.0, 3.0]);
    assert_eq!(key(&retyped, "home", "qvel"), [10.0, 0.0, 30.0]);
    // A body that stops being a mocap body takes its pose out of the key.
    let target = m.find(Namespace::Body, "target").unwrap();
    let fixed = m.set(&target, Attrs::new().set("mocap", false)).unwrap();
    assert_eq!(key(&fixed, "home", "mpos"), Vec::<f64>::new());
    // Moving a body changes no key.
    let moved = m.set(&target, Attrs::new().set("pos", [0.0, 0.0, 1.0])).unwrap();
    assert_eq!(key(&moved, "home", "mpos"), [4.0, 5.0, 6.0]);
}

#[test]
fn an_edit_that_moves_nothing_leaves_the_keys_as_written() {
    let m = Model::from_xml_str(ROBOT).unwrap();
    let g = m.find(Namespace::Body, "a_body").unwrap();
    let moved = m.set(&g, Attrs::new().set("pos", [1.0, 0.0, 0.0])).unwrap();
    let k = m.find(Namespace::Key, "short").unwrap();
    assert_eq!(moved.get(&k).unwrap().floats("qpos"), Some(&[1.0][..]), "a short key stays short");
}
