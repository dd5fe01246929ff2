//! MuJoCo's warnings while stepping name the element they are about (the joint of a
//! degree of freedom or position, the actuator of a control) with its full name and
//! scope, and can be made errors.

use crate::support;

use mjcf::{Model, element};
use mjcf_mujoco::{Error, ObjKind, Physics, WarningKind};
use support::mujoco;

/// A scene with a robot attached as `robot_1` (after a first copy): a free base and a
/// hinge with a motor.
fn scene() -> Model {
    let mut robot = Model::new("robot");
    let base = robot
        .add_mut(&robot.worldbody(), element!("body", name = "base", pos = [0, 0, 1]))
        .unwrap();
    robot.add_mut(&base, element!("freejoint", name = "root")).unwrap();
    robot.add_mut(&base, element!("geom", size = [0.1])).unwrap();
    let arm = robot.add_mut(&base, element!("body", name = "arm", pos = [0.2, 0, 0])).unwrap();
    robot.add_mut(&arm, element!("joint", name = "elbow")).unwrap();
    robot.add_mut(&arm, element!("geom", size = [0.05])).unwrap();
    robot.add_mut(&robot.actuator(), element!("motor", name = "m", joint = "elbow")).unwrap();
    let mut arena = Model::new("arena");
    arena.attach_mut(&arena.worldbody(), &robot).unwrap();
    arena.attach_mut(&arena.worldbody(), &robot).unwrap();
    arena
}

#[test]
#[ignore = "needs MuJoCo (MUJOCO_LIB); run by .ci/run"]
fn a_warning_names_its_joint_or_actuator_and_the_scope() {
    let compiled = mujoco().compile(&scene()).unwrap();
    let mut p = Physics::new(&compiled).unwrap();
    // The second robot's elbow spins beyond what MuJoCo accepts.
    let elbow = compiled.id(ObjKind::Joint, "robot_1/elbow").unwrap();
    let dof = compiled.ints("jnt_dofadr").unwrap()[elbow] as usize;
    p.qvel_mut()[dof] = 1e12;
    let warnings = p.step(1).unwrap();
    let w = warnings.iter().find(|w| w.kind == WarningKind::BadQvel).expect("a bad qvel");
    let e = w.element.as_ref().expect("its joint");
    assert_eq!(
        (e.kind, e.id, e.name.as_deref(), e.scope.as_str()),
        (ObjKind::Joint, elbow, Some("robot_1/elbow"), "robot_1")
    );
    assert!(w.to_string().contains("joint 'robot_1/elbow' of scope 'robot_1'"), "{w}");
    // A control that is not a number: its actuator.
    p.reset().unwrap();
    let m = compiled.id(ObjKind::Actuator, "robot/m").unwrap();
    p.ctrl_mut()[m] = f64::NAN;
    let warnings = p.step(1).unwrap();
    let w = warnings.iter().find(|w| w.kind == WarningKind::BadCtrl).expect("a bad ctrl");
    let e = w.element.as_ref().unwrap();
    assert_eq!(
        (e.kind, e.name.as_deref(), e.scope.as_str()),
        (ObjKind::Actuator, Some("robot/m"), "robot")
    );
    // A clean step says nothing.
    p.reset().unwrap();
    assert!(p.step(10).unwrap().is_empty());
}

#[test]
#[ignore = "needs MuJoCo (MUJOCO_LIB); run by .ci/run"]
fn warnings_can_be_errors() {
    let compiled = mujoco().compile(&scene()).unwrap();
    let mut p = Physics::new(&compiled).unwrap();
    p.set_warnings_as_errors(true);
    assert!(p.step(5).unwrap().is_empty());
    p.qvel_mut()[6] = 1e12;
    match p.step(1) {
        Err(Error::Warned(w)) => assert!(w.iter().any(|w| w.kind == WarningKind::BadQvel), "{w}"),
        other => panic!("expected a warning as an error, got {other:?}"),
    }
    // The data is usable: stepping goes on.
    p.reset().unwrap();
    assert!(p.step(1).is_ok());
}
