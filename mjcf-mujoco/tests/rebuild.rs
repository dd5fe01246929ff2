//! Physics::rebuild: a running simulation follows its model's edits (numbers written
//! in place, compiles, renames, detach and undo), keeping MuJoCo's integration state
//! by element identity, else by full name; MuJoCo judges each continuation.

use crate::state;
use crate::support;

use mjcf::{History, Model, Namespace, WriteOptions, element};
use mjcf_mujoco::{DefaultedWhy, Error, ObjKind, Physics, RebuildMode};
use state::{first_difference, set_state, state};
use support::mujoco;

fn repo() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// Two quadrupeds (r0, r1) on a floor, a mocap body `target` welded to r0's base by
/// an inactive equality `tie`, and an actuator with an activation (`thrust`, on r0's
/// front right hip).
fn scene() -> Model {
    let robot = Model::from_path(repo().join("examples/models/quadruped.xml")).unwrap();
    let mut m = Model::new("arena");
    let w = m.worldbody();
    m.add_mut(&w, element!("geom", name = "floor", type = "plane", size = [0, 0, 0.05])).unwrap();
    for (k, x) in [(0, 0.0), (1, 1.0)] {
        let site =
            m.add_mut(&w, element!("site", name = format!("s{k}"), pos = [x, 0.0, 0.0])).unwrap();
        m.attach_as_mut(&site, &robot, &format!("r{k}")).unwrap();
    }
    let target =
        m.add_mut(&w, element!("body", name = "target", mocap = true, pos = [0, 0, 1])).unwrap();
    m.add_mut(
        &target,
        element!("geom", type = "sphere", size = [0.05], contype = 0, conaffinity = 0),
    )
    .unwrap();
    let eq = m.section("equality").unwrap();
    m.add_mut(
        &eq,
        element!("weld", name = "tie", body1 = "target", body2 = "r0/base", active = false),
    )
    .unwrap();
    let act = m.actuator();
    m.add_mut(
        &act,
        element!(
            "general",
            name = "thrust",
            joint = "r0/fr_hip",
            dyntype = "integrator",
            gainprm = [0.5]
        ),
    )
    .unwrap();
    m
}

fn options() -> WriteOptions {
    WriteOptions { merge_keyframes: true, ..WriteOptions::default() }
}

/// A running simulation of `m`: home key, controls, applied forces, 100 steps.
fn running(m: &Model) -> Physics {
    let compiled = mujoco().compile_with(m, &options()).unwrap();
    let mut p = Physics::new(&compiled).unwrap();
    p.reset_to_key("home").unwrap();
    let n = p.ctrl().len();
    for (j, c) in p.ctrl_mut().iter_mut().enumerate() {
        *c = 0.1 + 0.01 * j as f64 / n as f64;
    }
    let base = p.bind((ObjKind::Body, "r0/base")).unwrap();
    p.get_mut(&base, "xfrc_applied").unwrap()[2] = 5.0;
    let hip = p.bind((ObjKind::Joint, "r1/fl_hip")).unwrap();
    p.get_mut(&hip, "qfrc_applied").unwrap()[0] = 0.2;
    let target = p.bind((ObjKind::Body, "target")).unwrap();
    p.get_mut(&target, "mocap_pos").unwrap()[0] = 0.25;
    assert!(p.step(100).unwrap().is_empty());
    p
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn a_rebuild_with_no_change_continues_bit_for_bit() {
    let m = scene();
    let (mut a, mut b) = (running(&m), running(&m));
    let report = b.rebuild(&m).unwrap();
    assert_eq!(report.mode, RebuildMode::None);
    assert!(report.defaulted.is_empty() && report.dropped.is_empty());
    assert_eq!(first_difference(&state(&a), &state(&b)), None);
    assert!(a.step(50).unwrap().is_empty() && b.step(50).unwrap().is_empty());
    assert_eq!(first_difference(&state(&a), &state(&b)), None);
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn a_compiled_rebuild_of_the_same_model_read_anew_carries_the_whole_state_by_name() {
    // Read back from its text: the same model, no element identity shared, so the
    // state goes by full name; compiled, the step after equals the one without.
    let m = scene();
    let (mut a, mut b) = (running(&m), running(&m));
    let again = Model::from_xml_str(&m.to_xml_string_with(&options()).unwrap()).unwrap();
    let report = b.rebuild(&again).unwrap();
    assert_eq!(report.mode, RebuildMode::Compiled);
    assert!(report.defaulted.is_empty(), "{:?}", report.defaulted);
    assert!(report.dropped.is_empty(), "{:?}", report.dropped);
    assert_eq!(first_difference(&state(&a), &state(&b)), None);
    assert!(a.step(1).unwrap().is_empty() && b.step(1).unwrap().is_empty());
    assert_eq!(first_difference(&state(&a), &state(&b)), None);
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn a_renamed_joint_keeps_its_state_by_identity() {
    let m = scene();
    let mut p = running(&m);
    let hip = m.find(Namespace::Joint, "r1/fl_hip").unwrap();
    let before = p.get(&p.bind((ObjKind::Joint, "r1/fl_hip")).unwrap(), "qpos").unwrap().to_vec();
    let before_qfrc =
        p.get(&p.bind((ObjKind::Joint, "r1/fl_hip")).unwrap(), "qfrc_applied").unwrap().to_vec();
    let renamed = m.set_attr(&hip, "name", "fl_hip_renamed").unwrap();
    let report = p.rebuild(&renamed).unwrap();
    assert_eq!(report.mode, RebuildMode::Compiled);
    assert!(report.carried.iter().any(|c| c.kind == ObjKind::Joint
        && c.name == "r1/fl_hip_renamed"
        && c.old_name == "r1/fl_hip"));
    let j = p.bind((ObjKind::Joint, "r1/fl_hip_renamed")).unwrap();
    assert_eq!(p.get(&j, "qpos").unwrap(), before);
    assert_eq!(p.get(&j, "qfrc_applied").unwrap(), before_qfrc);
    assert!(report.defaulted.is_empty() && report.dropped.is_empty());
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn a_joint_whose_type_changed_and_an_actuator_whose_activations_changed_start_at_their_defaults() {
    let m = scene();
    let mut p = running(&m);
    let knee = m.find(Namespace::Joint, "r0/fl_knee").unwrap();
    let thrust = m.find(Namespace::Actuator, "thrust").unwrap();
    let edited = m.set_attr(&knee, "type", "slide").unwrap();
    let edited = edited.set_attr(&thrust, "dyntype", "none").unwrap();
    let t = p.bind((ObjKind::Actuator, "thrust")).unwrap();
    assert_eq!(p.get(&t, "act").unwrap().len(), 1);
    let report = p.rebuild(&edited).unwrap();
    let why = |name: &str| report.defaulted.iter().find(|d| d.name == name).map(|d| d.why);
    assert_eq!(why("r0/fl_knee"), Some(DefaultedWhy::TypeChanged));
    assert_eq!(why("thrust"), Some(DefaultedWhy::ActivationChanged));
    let knee = p.bind((ObjKind::Joint, "r0/fl_knee")).unwrap();
    assert_eq!(p.get(&knee, "qpos").unwrap(), [0.0]);
    assert_eq!(p.get(&knee, "qvel").unwrap(), [0.0]);
    let t = p.bind((ObjKind::Actuator, "thrust")).unwrap();
    assert_eq!(p.get(&t, "ctrl").unwrap(), [0.0]);
    assert!(p.get(&t, "act").unwrap().is_empty());
    assert!(p.step(1).unwrap().is_empty());
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn a_model_mujoco_refuses_leaves_the_running_simulation_untouched() {
    let m = scene();
    let mut p = running(&m);
    let before = state(&p);
    // A moving body with no mass: MuJoCo refuses it and names it.
    let mut bad = m.clone();
    let b = bad.add_mut(&bad.worldbody(), element!("body", name = "ghost")).unwrap();
    bad.add_mut(&b, element!("joint", name = "ghost_slide", type = "slide")).unwrap();
    let e = p.rebuild(&bad).unwrap_err();
    match &e {
        Error::Compile(c) => {
            let el = c.element.as_ref().expect("the element MuJoCo names");
            assert_eq!(el.full_name.as_deref(), Some("ghost"), "{e}");
        }
        other => panic!("{other}"),
    }
    assert_eq!(first_difference(&before, &state(&p)), None);
    let mut fresh = running(&m);
    assert!(p.step(10).unwrap().is_empty() && fresh.step(10).unwrap().is_empty());
    assert_eq!(first_difference(&state(&fresh), &state(&p)), None);
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn an_undone_detach_brings_the_robot_back_at_its_defaults() {
    let mut history = History::new(scene());
    let mut p = running(history.current());
    history.push("detach r1", history.current().detach("r1").unwrap());
    let report = p.rebuild(history.current()).unwrap();
    assert!(report.dropped.iter().any(|d| d.name == "r1/fl_hip" && d.kind == ObjKind::Joint));
    assert!(p.step(10).unwrap().is_empty());
    assert!(history.undo());
    let report = p.rebuild(history.current()).unwrap();
    assert_eq!(report.mode, RebuildMode::Compiled);
    let new =
        |name: &str| report.defaulted.iter().any(|d| d.name == name && d.why == DefaultedWhy::New);
    assert!(new("r1/fl_hip") && new("r1/base"), "{:?}", report.defaulted);
    let hip = p.bind((ObjKind::Joint, "r1/fl_hip")).unwrap();
    assert_eq!(p.get(&hip, "qpos").unwrap(), [0.0]);
    assert_eq!(p.get(&hip, "qfrc_applied").unwrap(), [0.0]);
    // r0 kept its state through both rebuilds.
    let hip0 = p.bind((ObjKind::Joint, "r0/fl_hip")).unwrap();
    assert_ne!(p.get(&hip0, "qpos").unwrap(), [0.0]);
}

/// Numbers only: written in place, and the simulation then equals a fresh compile
/// of the edited model given the same state, step for step.
#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn a_numbers_only_edit_is_written_in_place_and_equals_a_fresh_compile() {
    let m = scene();
    let floor = m.find(Namespace::Geom, "floor").unwrap();
    let damped = m.find(Namespace::Joint, "r0/fl_hip").unwrap();
    let thrust = m.find(Namespace::Actuator, "thrust").unwrap();
    let edited = m.set_attr(&floor, "friction", [0.5]).unwrap();
    let edited = edited.set_attr(&damped, "armature", 0.05).unwrap();
    let edited = edited.set_attr(&thrust, "gainprm", [0.7]).unwrap();
    let mut p = running(&m);
    let report = p.rebuild(&edited).unwrap();
    assert_eq!(report.mode, RebuildMode::InPlace);
    let fresh = mujoco().compile_with(&edited, &options()).unwrap();
    let mut q = Physics::new(&fresh).unwrap();
    set_state(&mut q, &state(&p));
    for name in ["geom_friction", "dof_armature", "actuator_gainprm", "dof_M0", "dof_invweight0"] {
        assert_eq!(p.model().floats(name).unwrap(), fresh.floats(name).unwrap(), "{name}");
    }
    for _ in 0..20 {
        assert!(p.step(1).unwrap().is_empty() && q.step(1).unwrap().is_empty());
        assert_eq!(first_difference(&state(&p), &state(&q)), None);
    }
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn fields_the_compiler_derives_more_from_are_refused_with_a_rebuild_hint() {
    let m = scene();
    let mut p = running(&m);
    let floor = p.bind((ObjKind::Geom, "floor")).unwrap();
    let e = p.get_mut(&floor, "size").unwrap_err();
    assert!(matches!(e, Error::NeedsRebuild { field: "geom_size", .. }), "{e}");
    assert!(e.to_string().contains("rebuild"), "{e}");
    let base = p.bind((ObjKind::Body, "r0/base")).unwrap();
    let e = p.get_mut(&base, "pos").unwrap_err();
    assert!(matches!(e, Error::NeedsRebuild { field: "body_pos", .. }), "{e}");
    assert!(matches!(p.get_mut(&base, "subtreemass"), Err(Error::NeedsRebuild { .. })));
    // A mass is written, and its constants recomputed before the next step.
    let before = p.model().floats("body_subtreemass").unwrap()[base.id()];
    p.get_mut(&base, "mass").unwrap()[0] += 1.0;
    assert!(p.step(1).unwrap().is_empty());
    assert_eq!(p.model().floats("body_subtreemass").unwrap()[base.id()], before + 1.0);
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn an_inertial_added_to_a_body_is_written_in_place_and_equals_a_fresh_compile() {
    // r1's base: its mass times 1.5, its inertia and inertial frame as compiled.
    let m = scene();
    let mut p = running(&m);
    let base = p.bind((ObjKind::Body, "r1/base")).unwrap();
    let mass = p.get(&base, "mass").unwrap()[0];
    let (ipos, iquat, inertia) = (
        p.get(&base, "ipos").unwrap().to_vec(),
        p.get(&base, "iquat").unwrap().to_vec(),
        p.get(&base, "inertia").unwrap().to_vec(),
    );
    let mut edited = m.clone();
    let at = edited.find(Namespace::Body, "r1/base").unwrap();
    let inertial = element!(
        "inertial",
        pos = ipos.as_slice(),
        quat = iquat.as_slice(),
        mass = 1.5 * mass,
        diaginertia = inertia.as_slice()
    );
    edited.add_mut(&at, inertial).unwrap();
    let report = p.rebuild(&edited).unwrap();
    assert_eq!(report.mode, RebuildMode::InPlace);
    assert_eq!(p.get(&base, "mass").unwrap(), [1.5 * mass]);
    let fresh = mujoco().compile_with(&edited, &options()).unwrap();
    let mut q = Physics::new(&fresh).unwrap();
    set_state(&mut q, &state(&p));
    let names = ["body_mass", "body_ipos", "body_iquat", "body_inertia", "body_subtreemass"];
    for name in names.iter().chain(&["body_invweight0", "dof_invweight0", "dof_M0"]) {
        assert_eq!(p.model().floats(name).unwrap(), fresh.floats(name).unwrap(), "{name}");
    }
    for _ in 0..20 {
        assert!(p.step(1).unwrap().is_empty() && q.step(1).unwrap().is_empty());
        assert_eq!(first_difference(&state(&p), &state(&q)), None);
    }
}

/// The editor loop of the crate's docs, run.
#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn the_editor_loop_of_the_crate_docs_runs() {
    let mut robot = Model::new("robot");
    let torso = robot
        .add_mut(&robot.worldbody(), element!("body", name = "torso", pos = [0, 0, 1]))
        .unwrap();
    robot.add_mut(&torso, element!("freejoint")).unwrap();
    robot
        .add_mut(&torso, element!("geom", name = "box", type = "box", size = [0.1, 0.1, 0.1]))
        .unwrap();
    let mut history = History::new(robot);
    let mut physics = Physics::new(&mujoco().compile(history.current()).unwrap()).unwrap();
    assert!(physics.step(100).unwrap().is_empty());
    let geom = history.current().find(Namespace::Geom, "box").unwrap();
    history.edit("friction", |m| m.set_attr_mut(&geom, "friction", [0.5])).unwrap();
    assert_eq!(physics.rebuild(history.current()).unwrap().mode, RebuildMode::InPlace);
    let free = physics.bind((ObjKind::Joint, 0)).unwrap();
    let (q, v) = (
        physics.get(&free, "qpos").unwrap().to_vec(),
        physics.get(&free, "qvel").unwrap().to_vec(),
    );
    history
        .edit("ball", |m| {
            let ball =
                m.add_mut(&m.worldbody(), element!("body", name = "ball", pos = [1, 0, 1]))?;
            m.add_mut(&ball, element!("freejoint"))?;
            m.add_mut(&ball, element!("geom", type = "sphere", size = [0.1]))
        })
        .unwrap();
    let report = physics.rebuild(history.current()).unwrap();
    assert_eq!(report.mode, RebuildMode::Compiled);
    assert!(report.defaulted.iter().any(|d| d.name == "ball" && d.why == DefaultedWhy::New));
    // The torso keeps falling from where it was.
    let free = physics.bind((ObjKind::Joint, "//unnamed_joint_0")).unwrap();
    assert_eq!(physics.get(&free, "qpos").unwrap(), q);
    assert_eq!(physics.get(&free, "qvel").unwrap(), v);
    assert!(physics.step(100).unwrap().is_empty());
    assert!(history.undo());
    physics.rebuild(history.current()).unwrap();
    assert!(physics.bind((ObjKind::Body, "ball")).is_err());
    assert!(history.redo());
    physics.rebuild(history.current()).unwrap();
    let ball = physics.bind((ObjKind::Body, "ball")).unwrap();
    physics.forward().unwrap();
    assert_eq!(
        physics.get(&ball, "xpos").unwrap(),
        [1.0, 0.0, 1.0],
        "back at rest where it starts"
    );
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn a_model_written_field_by_field_is_compiled_anew_by_a_rebuild() {
    // Its numbers are no longer its source's: a rebuild to the same source compiles it
    // (the written damping goes), keeping the state.
    let m = scene();
    let mut p = running(&m);
    let hip = p.bind((ObjKind::Joint, "r0/fl_hip")).unwrap();
    let damping = p.get(&hip, "damping").unwrap()[0];
    p.get_mut(&hip, "damping").unwrap()[0] = damping + 5.0;
    let before = state(&p);
    let report = p.rebuild(&m).unwrap();
    assert_eq!(report.mode, RebuildMode::Compiled);
    assert_eq!(first_difference(&before, &state(&p)), None);
    let hip = p.bind((ObjKind::Joint, "r0/fl_hip")).unwrap();
    assert_eq!(p.get(&hip, "damping").unwrap(), [damping]);
    assert_eq!(p.rebuild(&m).unwrap().mode, RebuildMode::None);
}

/// The default class's `<joint>` (damping 1, armature 0.01) of the robot in scope `r0`.
fn r0_default_joint(m: &Model) -> mjcf::Loc {
    m.walk()
        .find_map(|ev| match ev {
            mjcf::Event::Enter(e)
                if e.tag() == "joint" && e.parent().is_some_and(|p| p.tag() == "default") =>
            {
                Some(e.loc())
            }
            _ => None,
        })
        .expect("a default joint")
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn numbers_the_compiler_does_not_copy_as_given_are_compiled_and_equal_a_fresh_compile() {
    // A default class's damping (every joint of the class), a hinge's range (degrees,
    // converted), a free body's position (its joint's qpos0), an attribute cleared (the
    // class's value comes back), a zero position in a rotated frame, the gain of a
    // servo with a damping ratio, a mass under a bound: each compiled, each step as a
    // fresh compile's.
    let mut m = scene();
    // A body at the origin of a rotated frame (its compiled position, 0, is its own).
    let w = m.worldbody();
    let frame = m.add_mut(&w, element!("frame", name = "turned", euler = [0, 0, 90])).unwrap();
    let spun = m.add_mut(&frame, element!("body", name = "spun")).unwrap();
    m.add_mut(&spun, element!("geom", type = "sphere", size = [0.05], pos = [2, 2, 0.05])).unwrap();
    // A position-like general actuator with a damping ratio (a positive third bias).
    let act = m.actuator();
    let servo = element!(
        "general",
        name = "servo",
        joint = "r1/hl_hip",
        gainprm = [20.0],
        biasprm = [0.0, -20.0, 0.7]
    );
    let servo = m.add_mut(&act, servo).unwrap();
    // An explicit inertial under a compiler's bound on masses.
    let hl = m.find(Namespace::Body, "r1/hl").unwrap();
    let inertial =
        element!("inertial", pos = [0, 0, 0], mass = 0.3, diaginertia = [0.01, 0.01, 0.01]);
    let inertial = m.add_mut(&hl, inertial).unwrap();
    let bounded = {
        let mut b = m.clone();
        let compiler = b.section("compiler").unwrap();
        b.set_attr_mut(&compiler, "boundmass", 0.2).unwrap();
        b
    };
    let class_joint = r0_default_joint(&m);
    let knee = m.find(Namespace::Joint, "r1/fl_knee").unwrap();
    let base = m.find(Namespace::Body, "r1/base").unwrap();
    let floor = m.find(Namespace::Geom, "floor").unwrap();
    let with_friction = m.set_attr(&floor, "friction", [0.7]).unwrap();
    let edits = [
        (m.clone(), m.set_attr(&class_joint, "damping", 3.0).unwrap()),
        (m.clone(), m.set_attr(&knee, "range", [-2.0, 0.5]).unwrap()),
        (m.clone(), m.set_attr(&base, "pos", [0.0, 0.0, 0.5]).unwrap()),
        (with_friction.clone(), with_friction.clear_attr(&floor, "friction").unwrap()),
        (m.clone(), m.set_attr(&spun, "pos", [0.1, 0.0, 0.0]).unwrap()),
        (m.clone(), m.set_attr(&servo, "gainprm", [30.0]).unwrap()),
        (bounded.clone(), bounded.set_attr(&inertial, "mass", 0.1).unwrap()),
    ];
    for (i, (from, to)) in edits.iter().enumerate() {
        let mut p = running(from);
        let report = p.rebuild(to).unwrap();
        assert_eq!(report.mode, RebuildMode::Compiled, "edit {i}");
        let fresh = mujoco().compile_with(to, &options()).unwrap();
        let mut q = Physics::new(&fresh).unwrap();
        set_state(&mut q, &state(&p));
        for _ in 0..5 {
            assert!(p.step(1).unwrap().is_empty() && q.step(1).unwrap().is_empty());
            assert_eq!(first_difference(&state(&p), &state(&q)), None, "edit {i}");
        }
    }
}
