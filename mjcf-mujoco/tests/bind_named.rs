//! Binding in one call: by kind and full name (models compiled from text or a path
//! too, with suggestions for a missing name), by id, and by locator; fields by
//! MuJoCo's names with their true widths.

use crate::support;

use std::collections::BTreeMap;

use mjcf::{Model, Namespace, element};
use mjcf_mujoco::{BindError, ObjKind, Physics};
use support::mujoco;

const XML: &str = r#"<mujoco model="w">
  <compiler angle="radian"/>
  <worldbody>
    <body name="base" pos="0 0 1">
      <freejoint/>
      <geom type="sphere" size="0.1"/>
      <body name="upper" pos="0 0 -0.2">
        <joint name="shoulder" type="ball"/>
        <geom type="capsule" size="0.02 0.1"/>
        <body name="lower" pos="0 0 -0.2">
          <joint name="elbow" type="hinge" axis="0 1 0" range="-1 1"/>
          <geom type="capsule" size="0.02 0.1"/>
        </body>
      </body>
    </body>
  </worldbody>
  <actuator>
    <general name="arm/gripper/fingers_actuator" joint="elbow" gainprm="3 0 0 0 0 0 0 0 0 7"/>
  </actuator>
</mujoco>"#;

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn a_model_compiled_from_text_binds_by_kind_and_name_with_true_widths() {
    let compiled = mujoco().compile_xml(XML, &BTreeMap::new()).unwrap();
    assert!(compiled.source().is_none());
    let act = compiled.bind((ObjKind::Actuator, "arm/gripper/fingers_actuator")).unwrap();
    // The actuator's gainprm: its 10 numbers, without indexing a raw array.
    assert_eq!(compiled.get(&act, "gainprm").unwrap(), [3.0, 0., 0., 0., 0., 0., 0., 0., 0., 7.0]);
    assert_eq!(compiled.get(&act, "actuator_gainprm").unwrap().len(), 10);
    let mut p = Physics::new(&compiled).unwrap();
    p.forward().unwrap();
    // A joint's qpos and qvel: 7 and 6 (free), 4 and 3 (ball), 1 and 1 (hinge).
    let free = p.bind((ObjKind::Joint, 0)).unwrap();
    let ball = p.bind((ObjKind::Joint, "shoulder")).unwrap();
    let hinge = p.bind((ObjKind::Joint, "elbow".to_string())).unwrap();
    assert_eq!(p.get(&free, "qpos").unwrap(), [0.0, 0.0, 1.0, 1.0, 0.0, 0.0, 0.0]);
    assert_eq!(p.get(&free, "qvel").unwrap().len(), 6);
    assert_eq!(p.get(&ball, "qpos").unwrap(), [1.0, 0.0, 0.0, 0.0]);
    assert_eq!(p.get(&ball, "qvel").unwrap().len(), 3);
    assert_eq!(p.get(&hinge, "qpos").unwrap().len(), 1);
    assert_eq!(p.get(&hinge, "range").unwrap(), [-1.0, 1.0]);
    assert_eq!(p.get(&ball, "damping").unwrap().len(), 3, "one per degree of freedom");
    assert_eq!(compiled.get_ints(&hinge, "type").unwrap(), [3]);
    let lower = p.bind((ObjKind::Body, "lower")).unwrap();
    assert_eq!(p.get(&lower, "xpos").unwrap().len(), 3);
    assert_eq!(p.get(&lower, "xfrc_applied").unwrap().len(), 6);
    assert_eq!(p.get(&act, "ctrl").unwrap().len(), 1);
    // A model field is not the compiled model's through Compiled::get.
    assert!(matches!(compiled.get(&hinge, "qpos"), Err(BindError::NoField { .. })));
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn a_missing_name_suggests_the_nearest_names_of_its_kind() {
    let compiled = mujoco().compile_xml(XML, &BTreeMap::new()).unwrap();
    // The name without its scope: the scoped one is suggested.
    let e = compiled.bind((ObjKind::Actuator, "fingers_actuator")).unwrap_err();
    match &e {
        BindError::NotFound { kind, name, suggestions } => {
            assert_eq!((*kind, name.as_str()), ("actuator", "fingers_actuator"));
            assert_eq!(suggestions, &["arm/gripper/fingers_actuator".to_string()]);
        }
        other => panic!("{other}"),
    }
    assert!(e.to_string().contains(r#"did you mean "arm/gripper/fingers_actuator"?"#), "{e}");
    // A misspelling.
    let e = compiled.bind((ObjKind::Joint, "elbw")).unwrap_err();
    assert!(
        matches!(&e, BindError::NotFound { suggestions, .. } if suggestions[0] == "elbow"),
        "{e}"
    );
    // Nothing near: no suggestion, and the kind is part of the lookup.
    let e = compiled.bind((ObjKind::Body, "elbow")).unwrap_err();
    assert!(matches!(&e, BindError::NotFound { suggestions, .. } if suggestions.is_empty()), "{e}");
    let e = compiled.bind((ObjKind::Joint, 3)).unwrap_err();
    assert!(matches!(e, BindError::NoId { id: 3, count: 3, .. }), "{e}");
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn a_path_compiled_model_binds_by_name() {
    let dir = std::env::temp_dir().join(format!("mjcf-bind-named-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("w.xml");
    std::fs::write(&path, XML).unwrap();
    let compiled = mujoco().compile_path(&path).unwrap();
    let b = compiled.bind((ObjKind::Joint, "elbow")).unwrap();
    assert_eq!((b.kind(), b.id(), b.name()), (ObjKind::Joint, 2, "elbow"));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn a_locator_and_its_full_name_bind_the_same_element_unnamed_ones_too() {
    let mut robot = Model::new("robot");
    let b = robot.add_mut(&robot.worldbody(), element!("body", name = "b")).unwrap();
    robot.add_mut(&b, element!("joint", type = "hinge")).unwrap();
    robot.add_mut(&b, element!("geom", size = [0.1])).unwrap();
    let mut arena = Model::new("arena");
    arena.attach_mut(&arena.worldbody(), &robot).unwrap();
    let compiled = mujoco().compile(&arena).unwrap();
    let joint = &arena.find_all(Namespace::Joint)[0];
    let name = arena.get(joint).unwrap().full_name().unwrap();
    assert_eq!(name, "robot//unnamed_joint_0");
    let by_loc = compiled.bind(joint).unwrap();
    let by_name = compiled.bind((ObjKind::Joint, name.as_str())).unwrap();
    assert_eq!(by_loc, by_name);
    let body = compiled.bind((ObjKind::Body, "robot/b")).unwrap();
    assert_eq!(compiled.bind(arena.find(Namespace::Body, "robot/b").unwrap()).unwrap(), body);
}
