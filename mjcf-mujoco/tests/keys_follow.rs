//! MuJoCo judges keys that follow their elements: a key given to a generated model
//! (every own joint a value of its own) compiles, after each version of a generated
//! edit sequence (adds, removes, renames, sets, attaches, detaches), to the same
//! values for every joint that stayed, found by its name in each version, and to
//! `qpos0` for every joint new to the model; and the crate's fixture, edited as its
//! tests edit it, compiles to the values they expect.

use crate::support;

use std::collections::HashMap;

use mjcf::{JointType, Loc, Model, WriteOptions, element};
use mjcf_mujoco::{Compiled, ObjKind, Physics};
use support::mujoco;

fn merged() -> WriteOptions {
    WriteOptions { merge_keyframes: true, ..WriteOptions::default() }
}

/// Where the joint `joint` (by the name MuJoCo gives it) is in `qpos`.
fn span(c: &Compiled, joint: &str) -> std::ops::Range<usize> {
    let j = c.id(ObjKind::Joint, joint).unwrap_or_else(|| panic!("no joint {joint}"));
    let adr = c.ints("jnt_qposadr").unwrap()[j] as usize;
    let t = JointType::from_mujoco(c.ints("jnt_type").unwrap()[j].into()).unwrap();
    adr..adr + t.nq()
}

/// The compiled `judge` key's `qpos` of the joint `joint`.
fn key_qpos(c: &Compiled, joint: &str) -> Vec<f64> {
    let mut physics = Physics::new(c).unwrap();
    physics.reset_to_key("judge").unwrap();
    physics.qpos()[span(c, joint)].to_vec()
}

fn qpos0(c: &Compiled, joint: &str) -> Vec<f64> {
    let mut physics = Physics::new(c).unwrap();
    physics.reset().unwrap();
    physics.qpos()[span(c, joint)].to_vec()
}

/// The model with a jointed body of the judge's own and a key `judge` that gives
/// each own joint a value of its own.
fn with_key(m: &Model) -> Option<Model> {
    let mut m = m.clone();
    let arm = element!("body", name = "judge_arm", pos = [0, 0, 1])
        .child(element!("joint", name = "judge_hinge"))
        .child(element!("geom", size = [0.1]))
        .child(
            element!("body", name = "judge_hand", pos = [0, 0, 0.3])
                .child(element!("joint", name = "judge_ball", type = "ball"))
                .child(element!("geom", size = [0.05])),
        );
    m.add_mut(&m.worldbody(), arm).ok()?;
    let layout = m.layout().ok()?;
    let mut qpos = Vec::new();
    for (k, j) in layout.joints.iter().filter(|j| j.is_own()).enumerate() {
        let t = 0.05 + 0.01 * k as f64;
        match j.joint_type {
            JointType::Free => {
                qpos.extend([t, -t, 1.0 + t, (t / 2.0).cos(), (t / 2.0).sin(), 0.0, 0.0])
            }
            JointType::Ball => qpos.extend([(t / 2.0).cos(), 0.0, (t / 2.0).sin(), 0.0]),
            _ => qpos.push(t),
        }
    }
    if qpos.is_empty() || layout.joints.len() * 7 < qpos.len() || !layout.unexpanded.is_empty() {
        return None;
    }
    m.add_top_mut(element!("key", name = "judge", qpos = qpos)).ok()?;
    Some(m)
}

/// Every own joint, by locator.
fn own_joints(m: &Model) -> HashMap<Loc, (String, JointType)> {
    m.layout()
        .unwrap()
        .joints
        .iter()
        .filter(|j| j.is_own())
        .filter_map(|j| Some((j.loc.clone(), (m.full_name(&j.loc)?, j.joint_type))))
        .collect()
}

#[test]
#[ignore = "needs MuJoCo (MUJOCO_LIB); run by .ci/run"]
fn compiled_keys_keep_each_joints_values_by_name_over_generated_edit_sequences() {
    use mjcf::generate::strategy;
    use proptest::strategy::{Strategy, ValueTree};
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
    let mujoco = mujoco();
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &[23; 32]);
    let mut runner = TestRunner::new_with_rng(Config::default(), rng);
    let sequences = strategy::scene_and_edits();
    let (mut versions, mut kept, mut fresh) = (0, 0, 0);
    for i in 0..100 {
        let (recipe, edits) = sequences.new_tree(&mut runner).unwrap().current();
        let Some(first) = with_key(&recipe.build()) else { continue };
        let before = mujoco.compile_with(&first, &merged()).unwrap();
        let joints0 = own_joints(&first);
        for (v, m) in edits.apply(&first).iter().enumerate().skip(1) {
            if m.find(mjcf::Namespace::Key, "judge").is_none() {
                continue;
            }
            let Ok(after) = mujoco.compile_with(m, &merged()) else { continue };
            versions += 1;
            for (loc, (name, ty)) in own_joints(m) {
                match joints0.get(&loc) {
                    Some((name0, ty0)) if *ty0 == ty => {
                        assert_eq!(
                            key_qpos(&before, name0),
                            key_qpos(&after, &name),
                            "sequence {i} version {v}: joint {name0} -> {name}"
                        );
                        kept += 1;
                    }
                    _ => {
                        // qpos0 as the layout derives it (a free joint's pose composed
                        // through frames: within rounding of MuJoCo's own).
                        let (got, want) = (key_qpos(&after, &name), qpos0(&after, &name));
                        let close = got.len() == want.len()
                            && got.iter().zip(&want).all(|(a, b)| (a - b).abs() < 1e-12);
                        assert!(
                            close,
                            "sequence {i} version {v}: new joint {name}: {got:?} {want:?}"
                        );
                        fresh += 1;
                    }
                }
            }
        }
    }
    println!("{versions} versions, {kept} joint values kept, {fresh} new joints at qpos0");
    assert!(versions > 100 && kept > 200, "{versions} {kept} {fresh}");
}
