//! MuJoCo judges `Model::remove_with(.., Referrers::Cascade)`: removing any element
//! that others refer to, of every kind the fixture has (bodies, joints, sites,
//! geoms, tendons, materials), and any element of generated scenes, leaves a model
//! that `check()` finds nothing dangling in and MuJoCo 4.0.0 compiles.

use crate::support;

use mjcf::{Model, Namespace, ProblemKind, Referrers};
use support::mujoco;

/// The fixture of the crate's own tests (tests/remove_with.rs): an arm whose every
/// dependent kind refers into the body `forearm`'s subtree.
const ARM: &str = include_str!("../../tests/remove_with.xml");

fn no_dangling(m: &Model, what: &str) {
    for p in m.check() {
        let dangles = matches!(
            p.kind,
            ProblemKind::DanglingReference { .. }
                | ProblemKind::RemovedReference { .. }
                | ProblemKind::MissingRequired { .. }
        );
        assert!(!dangles, "{what}: {p}");
    }
}

#[test]
#[ignore = "needs MuJoCo (MUJOCO_LIB); run by .ci/run"]
fn every_referred_element_of_the_fixture_removed_with_cascade_compiles() {
    let mujoco = mujoco();
    let m = Model::from_xml_str(ARM).unwrap();
    mujoco.compile(&m).unwrap();
    let mut judged = 0;
    for (ns, name) in [
        (Namespace::Body, "forearm"),
        (Namespace::Body, "upper"),
        (Namespace::Joint, "elbow"),
        (Namespace::Joint, "shoulder"),
        (Namespace::Site, "tip"),
        (Namespace::Site, "upper_site"),
        (Namespace::Geom, "forearm_geom"),
        (Namespace::Tendon, "cable"),
        (Namespace::Tendon, "coupling"),
        (Namespace::Material, "red"),
    ] {
        let loc = m.find(ns, name).unwrap();
        assert!(m.remove_with(&loc, Referrers::Refuse).is_err(), "{name} is referred to");
        let r = m.remove_with(&loc, Referrers::Cascade).unwrap();
        no_dangling(&r.model, name);
        // MuJoCo compiles it exactly when check() finds nothing (a removed geom can
        // leave its moving body without mass, which check() reports).
        let xml = r.model.to_xml_string().unwrap();
        let problems = r.model.check();
        match mujoco.compile(&r.model) {
            Ok(_) => assert!(problems.is_empty(), "{name}: {problems:?}"),
            Err(e) => assert!(!problems.is_empty(), "{name}: MuJoCo refuses: {e}\n{xml}"),
        }
        judged += 1;
    }
    assert_eq!(judged, 10);
}

#[test]
#[ignore = "needs MuJoCo (MUJOCO_LIB); run by .ci/run"]
fn any_element_of_generated_scenes_removed_with_cascade_leaves_nothing_dangling() {
    use mjcf::generate::strategy;
    use proptest::strategy::{Strategy, ValueTree};
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
    let mujoco = mujoco();
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &[11; 32]);
    let mut runner = TestRunner::new_with_rng(Config::default(), rng);
    let scenes = strategy::scene_recipe();
    let (mut removals, mut cascaded, mut compiled) = (0, 0, 0);
    for i in 0..60 {
        let scene = scenes.new_tree(&mut runner).unwrap().current().build();
        // Every named element, of the scene's own model or of an attached one.
        let named: Vec<mjcf::Loc> = scene
            .walk()
            .filter_map(|e| match e {
                mjcf::Event::Enter(e) if e.identifier().is_some() => Some(e.loc()),
                _ => None,
            })
            .collect();
        for loc in named.iter().step_by(3) {
            let Ok(r) = scene.remove_with(loc, Referrers::Cascade) else { continue };
            removals += 1;
            cascaded += usize::from(!r.removed.is_empty());
            no_dangling(&r.model, &format!("scene {i}"));
            // What MuJoCo compiled before, it compiles after a cascade that leaves no
            // body without mass (a removed geom may leave one: check() says so).
            if r.model.check().is_empty() {
                let xml = r.model.to_xml_string().unwrap();
                if let Err(e) = mujoco.compile(&r.model) {
                    panic!("scene {i}: {e}\n{xml}");
                }
                compiled += 1;
            }
        }
    }
    println!("{removals} removals, {cascaded} cascaded, {compiled} compiled");
    assert!(removals > 100 && cascaded > 10 && compiled > 50, "{removals} {cascaded} {compiled}");
}
