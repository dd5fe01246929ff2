//! Tests of the palettes: the wide palette reaches the shapes MuJoCo may refuse, the
//! simulating palette keeps its ranges and contact classes, the `<frame>` step, and
//! how recipes and models print.

use proptest::strategy::{Strategy, ValueTree};
use proptest::test_runner::{Config, RngSeed, TestRunner};

use super::simulate::{ContactClass, contact_classes};
use super::strategy::{scene_recipe, scene_recipe_in};
use super::*;
use crate::model::{Event, Model};
use crate::schema::Role;
use crate::{Namespace, element};

fn runner(seed: u64) -> TestRunner {
    TestRunner::new(Config { rng_seed: RngSeed::Fixed(seed), ..Config::default() })
}

/// What is above an element as the walk enters it.
#[derive(Clone, Copy, Default)]
struct Above {
    moving: usize,
    mujoco_frame: bool,
    attachment: bool,
}

/// Counts of what the wide palette promises, over `m`.
fn tally(m: &Model, counts: &mut std::collections::BTreeMap<&'static str, usize>) {
    let mut stack: Vec<Above> = Vec::new();
    for event in m.walk() {
        let Event::Enter(e) = event else {
            stack.pop();
            continue;
        };
        let above = stack.last().copied().unwrap_or_default();
        let kids: Vec<(&str, Option<&str>)> =
            e.children().map(|c| (c.tag(), c.string("type"))).collect();
        let mut note =
            |k: &'static str, yes: bool| *counts.entry(k).or_default() += usize::from(yes);
        if e.is_frame() {
            note("attached below a moving body", above.moving > 0);
            note("attached inside a <frame>", above.mujoco_frame);
            note("attached inside an attached model", above.attachment);
            note(
                "frame freejoint below a moving body",
                above.moving > 0 && kids.iter().any(|k| k.0 == "freejoint"),
            );
            let mut types: Vec<&str> =
                kids.iter().filter(|k| k.0 == "joint").map(|k| k.1.unwrap_or("hinge")).collect();
            types.sort_unstable();
            types.dedup();
            note("frame with mixed joint types", types.len() >= 2);
        }
        if above.attachment && !e.is_frame() {
            note(
                "free body in an attached model",
                e.kind().is(Role::Body) && kids.iter().any(|k| k.0 == "freejoint"),
            );
            note(
                "plane in an attached model",
                e.kind().is(Role::Geom) && e.string("type") == Some("plane"),
            );
        }
        note("site in a <frame>", above.mujoco_frame && e.kind().is(Role::Site));
        let moves = kids.iter().any(|k| matches!(k.0, "joint" | "freejoint"));
        stack.push(Above {
            moving: above.moving + usize::from(moves && (e.kind().is(Role::Body) || e.is_frame())),
            mujoco_frame: above.mujoco_frame || (e.kind().is(Role::Frame) && !e.is_frame()),
            attachment: above.attachment || e.is_frame(),
        });
    }
}

/// Over 60 wide scenes: attachments below moving bodies, inside `<frame>`s and inside
/// attached models; attached models with free bodies and planes; frame freejoints
/// below moving bodies; frames with mixed joint types.
#[test]
fn wide_scenes_reach_what_mujoco_may_refuse() {
    let mut runner = runner(27);
    let mut counts = std::collections::BTreeMap::new();
    for _ in 0..60 {
        let r = scene_recipe_in(Palette::Wide).new_tree(&mut runner).unwrap().current();
        assert_eq!(r.palette, Palette::Wide);
        let m = r.build();
        assert!(m.to_xml_string().is_ok());
        tally(&m, &mut counts);
    }
    for (what, n) in &counts {
        assert!(*n > 0, "no {what} in 60 wide scenes: {counts:?}");
    }
    assert!(counts.len() >= 8, "{counts:?}");
}

/// Valid scenes reach none of the shapes the wide palette adds.
#[test]
fn valid_scenes_keep_free_bodies_and_planes_out_of_attached_models() {
    let mut runner = runner(27);
    let mut counts = std::collections::BTreeMap::new();
    for _ in 0..60 {
        let m = scene_recipe().new_tree(&mut runner).unwrap().current().build();
        tally(&m, &mut counts);
    }
    for what in [
        "free body in an attached model",
        "plane in an attached model",
        "frame freejoint below a moving body",
        "site in a <frame>",
    ] {
        assert_eq!(counts.get(what).copied().unwrap_or(0), 0, "{what}: {counts:?}");
    }
}

/// Simulating scenes are valid, and keep their ranges: every joint with armature at
/// least 0.1 and damping at least 1, geoms at least 0.05, `implicitfast`, each geom
/// with the contact bits of its class.
#[test]
fn simulating_scenes_are_valid_and_keep_their_ranges() {
    let mut runner = runner(99);
    let mut classes = std::collections::BTreeMap::<String, usize>::new();
    for _ in 0..20 {
        let m =
            scene_recipe_in(Palette::Simulates).new_tree(&mut runner).unwrap().current().build();
        assert!(m.check().is_empty(), "{:?}", m.check());
        let option = m.section("option").unwrap();
        assert_eq!(m.string(&option, "integrator").unwrap(), "implicitfast");
        for event in m.walk() {
            let Event::Enter(e) = event else { continue };
            let in_default = e.parent().is_some_and(|p| p.kind().is(Role::DefaultClass));
            if e.kind().is(Role::Joint) && !in_default {
                let armature = e.float("armature");
                assert!(armature.is_some_and(|a| a >= 0.1), "{}", m.to_xml_string().unwrap());
                // `damping` is an array (MuJoCo 4.0's polynomial damping).
                assert!(m.floats(&e.loc(), "damping").unwrap()[0] >= 1.0);
            }
            if e.kind().is(Role::Geom) && e.string("type") != Some("mesh") {
                assert!(m.floats(&e.loc(), "size").unwrap().iter().all(|s| *s >= 0.05));
            }
        }
        for (loc, class) in contact_classes(&m) {
            let bits = (
                m.int(&loc, "contype").unwrap() as i32,
                m.int(&loc, "conaffinity").unwrap() as i32,
            );
            assert_eq!(bits, class.bits());
            *classes.entry(format!("{class:?}")).or_default() += 1;
        }
    }
    assert_eq!(classes.len(), 3, "{classes:?}");
}

/// A geom's contact class is that of the nearest moving body at or above it.
#[test]
fn contact_classes_follow_the_nearest_moving_body() {
    let mut m = Model::new("m");
    let w = m.worldbody();
    m.add_mut(&w, element!("geom", name = "ground", size = [0.1])).unwrap();
    let free = m.add_mut(&w, element!("body", name = "free")).unwrap();
    m.add_mut(&free, element!("freejoint")).unwrap();
    m.add_mut(&free, element!("geom", name = "on_free", size = [0.1])).unwrap();
    let arm = m.add_mut(&free, element!("body", name = "arm")).unwrap();
    m.add_mut(&arm, element!("joint", name = "hinge")).unwrap();
    let hand = m.add_mut(&arm, element!("body", name = "hand")).unwrap();
    m.add_mut(&hand, element!("geom", name = "on_hand", size = [0.1])).unwrap();
    let class = |name: &str| {
        let loc = m.find(Namespace::Geom, name).unwrap();
        contact_classes(&m).into_iter().find(|(l, _)| *l == loc).unwrap().1
    };
    assert_eq!(class("ground"), ContactClass::Static);
    assert_eq!(class("on_free"), ContactClass::Free);
    assert_eq!(class("on_hand"), ContactClass::Articulated);
}

/// A `<frame>` step in the default palette builds a valid model, with what later
/// steps put inside the frame.
#[test]
fn a_frame_step_holds_bodies_and_sites() {
    let r = ModelRecipe {
        steps: vec![
            Step::Frame { parent: Pick(0), pos: [Unit(600); 3], euler: [Unit(500); 3] },
            // Parents: the worldbody, then the frame.
            Step::Site { parent: Pick(1), name: Some(Word(0)), pos: [Unit(0); 3], extras: vec![] },
            Step::Body {
                parent: Pick(1),
                name: Some(Word(3)),
                pos: [Unit(0); 3],
                geom: GeomRecipe::default(),
                free: false,
                childclass: None,
                extras: vec![],
            },
        ],
        ..ModelRecipe::default()
    };
    let m = r.build();
    assert!(m.check().is_empty());
    let xml = m.to_xml_string().unwrap();
    let frame = xml.find("<frame").unwrap();
    assert!(xml[frame..].find("<site name=\"a\"").is_some(), "{xml}");
    assert!(xml[frame..].find("<body name=\"base\"").is_some(), "{xml}");
}

/// `{:#?}` of a model is its MJCF text; `{:?}` stays short.
#[test]
fn a_model_prints_as_mjcf_in_alternate_debug() {
    let m = scene_recipe().new_tree(&mut runner(3)).unwrap().current().build();
    let long = format!("{m:#?}");
    assert!(long.contains(m.to_xml_string().unwrap().trim_end()), "{long}");
    assert!(!format!("{m:?}").contains("<mujoco"));
}

/// A recipe prints its picks as `#i`, its numbers in `[0, 1]`, its names as words,
/// and (`{:#?}`) the MJCF text of the model it builds.
#[test]
fn recipes_print_compactly_and_with_what_they_build() {
    let r = scene_recipe().new_tree(&mut runner(3)).unwrap().current();
    let short = format!("{r:?}");
    assert!(
        !short.contains("Pick(") && !short.contains("Unit(") && !short.contains("Word("),
        "{short}"
    );
    assert!(short.contains("parent: #") || short.contains("at: #"), "{short}");
    let long = format!("{r:#?}");
    assert!(long.contains(r.build().to_xml_string().unwrap().trim_end()), "{long}");
}
