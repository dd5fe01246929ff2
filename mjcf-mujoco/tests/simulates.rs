//! Scenes of the simulating generators (`Palette::Simulates`) simulate: each one
//! compiles and steps 1,000 steps without a MuJoCo warning (no divergence, no bad
//! inertia), at least 99.9% of them. They are no static or weightless toys: the test
//! counts their joint types, contact-capable geoms in moving bodies, and attachment
//! frames by how many moving bodies are above them, and requires each of them.
//!
//! Scenes: `MJCF_SIM_SCENES` (default 300, about a minute in a debug build); the
//! full 10,000 is `MJCF_SIM_SCENES=10000`. `MJCF_SIM_DUMP=DIR` writes every scene to
//! `DIR/scene_I.xml`, to study one in MuJoCo.

use crate::support;

use std::collections::BTreeMap;

use mjcf::generate::{Palette, strategy};
use mjcf::{Event, JointType, Model};
use mjcf_mujoco::Physics;
use proptest::strategy::{Strategy, ValueTree};
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use support::mujoco;

/// How many scenes: `MJCF_SIM_SCENES`, else 300.
fn scene_count() -> usize {
    std::env::var("MJCF_SIM_SCENES").ok().and_then(|n| n.parse().ok()).unwrap_or(300)
}

/// For every attachment frame of `m`: how many moving bodies (bodies with a joint,
/// attachment frames with joints included) are above it.
fn attachment_depths(m: &Model) -> Vec<usize> {
    let mut out = Vec::new();
    // Per open element: whether it is a moving body.
    let mut stack: Vec<bool> = Vec::new();
    for event in m.walk() {
        match event {
            Event::Enter(e) => {
                if e.is_frame() {
                    out.push(stack.iter().filter(|x| **x).count());
                }
                let moving = e.children().any(|c| matches!(c.tag(), "joint" | "freejoint"));
                stack.push(moving && (e.tag() == "body" || e.is_frame()));
            }
            Event::Leave(_) => {
                stack.pop();
            }
        }
    }
    out
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn simulating_scenes_step_1000_steps_without_a_warning() {
    let mujoco = mujoco();
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &[99; 32]);
    let mut runner = TestRunner::new_with_rng(Config::default(), rng);
    let scenes = strategy::scene_recipe_in(Palette::Simulates);
    let n = scene_count();
    let mut joints = BTreeMap::<&str, usize>::new();
    let mut depths = BTreeMap::<usize, usize>::new();
    let (mut contact_geoms, mut scenes_with_contacts, mut nv_total) = (0, 0, 0);
    let mut failures = Vec::new();
    let mut warned = BTreeMap::<String, usize>::new();
    for i in 0..n {
        let m = scenes.new_tree(&mut runner).unwrap().current().build();
        assert!(m.check().is_empty(), "scene {i}: {:?}", m.check());
        if let Ok(dir) = std::env::var("MJCF_SIM_DUMP") {
            std::fs::write(format!("{dir}/scene_{i}.xml"), m.to_xml_string().unwrap()).unwrap();
        }
        for d in attachment_depths(&m) {
            *depths.entry(d).or_default() += 1;
        }
        let compiled = mujoco.compile(&m).unwrap_or_else(|e| panic!("scene {i}: {e}"));
        for t in compiled.ints("jnt_type").unwrap() {
            *joints.entry(JointType::from_mujoco((*t).into()).unwrap().keyword()).or_default() += 1;
        }
        nv_total += compiled.sizes().nv;
        // Geoms that collide (contype or conaffinity) in bodies that move.
        let (body, ct, ca) = (
            compiled.ints("geom_bodyid").unwrap(),
            compiled.ints("geom_contype").unwrap(),
            compiled.ints("geom_conaffinity").unwrap(),
        );
        let dofs = compiled.ints("body_dofnum").unwrap();
        let here = (0..body.len())
            .filter(|g| (ct[*g] | ca[*g]) != 0 && dofs[body[*g] as usize] > 0)
            .count();
        contact_geoms += here;
        scenes_with_contacts += usize::from(here > 0);
        let mut physics = Physics::new(&compiled).unwrap();
        let warnings = physics.step(1000).unwrap_or_else(|e| panic!("scene {i}: {e}"));
        if !warnings.is_empty() {
            for w in &warnings {
                *warned.entry(format!("{:?}", w.kind)).or_default() += 1;
            }
            failures.push((i, format!("{warnings:?}"), m.to_xml_string().unwrap()));
        }
    }
    eprintln!(
        "{n} simulating scenes, 1000 steps each: {} warned {warned:?}\n\
         joints by type: {joints:?}; {nv_total} dofs in all\n\
         contact-capable geoms in moving bodies: {contact_geoms} (in {scenes_with_contacts} scenes)\n\
         attachment frames by moving bodies above them: {depths:?}",
        failures.len()
    );
    let warned_scenes: Vec<usize> = failures.iter().map(|f| f.0).collect();
    eprintln!("scenes that warned: {warned_scenes:?}");
    for (i, w, xml) in failures.iter().take(3) {
        eprintln!("\n--- scene {i}: {w} ---\n{xml}");
    }
    assert!(failures.len() * 1000 <= n, "{} of {n} scenes warned", failures.len());
    for t in JointType::ALL.map(JointType::keyword) {
        assert!(joints.get(t).copied().unwrap_or(0) > 0, "no {t} joint: {joints:?}");
    }
    assert!(scenes_with_contacts * 2 > n, "scenes with contact geoms: {scenes_with_contacts}");
    let below: usize = depths.iter().filter(|(d, _)| **d > 0).map(|(_, c)| c).sum();
    assert!(below * 2 > n, "attachments below moving bodies: {depths:?}");
    assert!(depths.keys().any(|d| *d >= 2), "none below two moving bodies: {depths:?}");
}
