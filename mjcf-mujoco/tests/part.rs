//! MuJoCo judges `Model::part`: a gripper taken out of a scene file (with a floor,
//! lights, a skybox, a free box hung from a world site by a tendon) and attached
//! inside another model's body compiles, holds exactly the part's elements, and
//! every one of them compiles as in its own file: masses, inertias, geom sizes and
//! frictions, joint ranges, damping and armature, actuator gains, the root's own
//! pose relative to where it is attached.

use crate::support;

use std::collections::BTreeMap;

use mjcf::{Model, Namespace};
use mjcf_mujoco::{Compiled, ObjKind};
use support::mujoco;

const SCENE: &str = include_str!("../../examples/models/gripper_scene.xml");

/// `width` numbers of the array `field` for the element `name` of `kind`.
fn row(c: &Compiled, kind: ObjKind, name: &str, field: &str, width: usize) -> Vec<f64> {
    let id = c.id(kind, name).unwrap_or_else(|| panic!("no {name}"));
    c.floats(field).unwrap()[width * id..width * (id + 1)].to_vec()
}

fn dof(c: &Compiled, joint: &str, field: &str) -> f64 {
    let id = c.id(ObjKind::Joint, joint).unwrap();
    let adr = c.ints("jnt_dofadr").unwrap()[id] as usize;
    c.floats(field).unwrap()[adr]
}

#[test]
#[ignore = "needs MuJoCo (MUJOCO_LIB); run by .ci/run"]
fn a_gripper_taken_from_a_scene_compiles_as_in_its_own_file() {
    let mujoco = mujoco();
    let source = mujoco.compile_xml(SCENE, &BTreeMap::new()).unwrap();
    let part = Model::from_xml_str(SCENE).unwrap().part("base").unwrap();
    let mut arm = Model::new("arm");
    let hand = arm
        .add_mut(
            &arm.worldbody(),
            mjcf::element!("body", name = "hand", pos = [0.0, 0.0, 1.0], euler = [0.0, 90.0, 0.0]),
        )
        .unwrap();
    arm.add_mut(&hand, mjcf::element!("joint", name = "lift", type = "slide")).unwrap();
    arm.add_mut(&hand, mjcf::element!("geom", size = [0.05])).unwrap();
    let (scene, _) = arm.attach_in_as(&hand, &part.model, "gripper").unwrap();
    assert!(scene.check().is_empty(), "{:?}", scene.check());
    let composed = mujoco.compile(&scene).unwrap();
    // Exactly the arm's elements and the part's.
    assert_eq!(composed.count(ObjKind::Body), 1 + 1 + 1 + 3, "world, hand, frame, gripper bodies");
    assert_eq!(composed.count(ObjKind::Joint), 1 + 3);
    assert_eq!(composed.count(ObjKind::Actuator), 2);
    assert_eq!(composed.count(ObjKind::Tendon), 1);
    assert_eq!(composed.count(ObjKind::Light), 0);
    assert_eq!(composed.count(ObjKind::Texture), 0);
    assert_eq!(composed.count(ObjKind::Material), 1);
    for body in ["base", "left_finger", "right_finger"] {
        let ours = format!("gripper/{body}");
        for (field, w) in [("body_mass", 1), ("body_inertia", 3), ("body_ipos", 3)] {
            assert_eq!(
                row(&source, ObjKind::Body, body, field, w),
                row(&composed, ObjKind::Body, &ours, field, w),
                "{body} {field}"
            );
        }
    }
    // The root's own pose, now relative to its attachment frame (in the hand).
    for field in [("body_pos", 3), ("body_quat", 4)] {
        assert_eq!(
            row(&source, ObjKind::Body, "base", field.0, field.1),
            row(&composed, ObjKind::Body, "gripper/base", field.0, field.1),
            "{}",
            field.0
        );
    }
    for joint in ["wrist", "left", "right"] {
        let ours = format!("gripper/{joint}");
        assert_eq!(
            row(&source, ObjKind::Joint, joint, "jnt_range", 2),
            row(&composed, ObjKind::Joint, &ours, "jnt_range", 2),
            "{joint}"
        );
        for field in ["dof_damping", "dof_armature"] {
            assert_eq!(dof(&source, joint, field), dof(&composed, &ours, field), "{joint} {field}");
        }
    }
    for geom_of in ["left_finger", "right_finger"] {
        let gid = |c: &Compiled, body: &str| {
            let b = c.id(ObjKind::Body, body).unwrap();
            c.ints("body_geomadr").unwrap()[b] as usize
        };
        let (a, b) = (gid(&source, geom_of), gid(&composed, &format!("gripper/{geom_of}")));
        for (field, w) in [("geom_size", 3), ("geom_friction", 3)] {
            let fa = &source.floats(field).unwrap()[w * a..w * (a + 1)];
            let fb = &composed.floats(field).unwrap()[w * b..w * (b + 1)];
            assert_eq!(fa, fb, "{geom_of} {field}");
        }
    }
    for act in ["fingers", "wrist_motor"] {
        for (field, w) in [
            ("actuator_gainprm", 10),
            ("actuator_biasprm", 10),
            ("actuator_gear", 6),
            ("actuator_ctrlrange", 2),
        ] {
            assert_eq!(
                row(&source, ObjKind::Actuator, act, field, w),
                row(&composed, ObjKind::Actuator, &format!("gripper/{act}"), field, w),
                "{act} {field}"
            );
        }
    }
    assert!(composed.id(ObjKind::Body, "gripper/box").is_none());
    let _ = scene.find(Namespace::Tendon, "gripper/split").expect("the tendon inside comes along");
}
