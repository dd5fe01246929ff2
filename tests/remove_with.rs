//! `Model::remove_with`: removal that refuses while anything refers to what it
//! removes, or cascades to what depends on it (actuators, sensors, tendons,
//! equalities, contact pairs and excludes), leaving nothing dangling.
//! `mjcf-mujoco/tests/remove_with.rs` has MuJoCo compile the results.

use mjcf::{ErrorKind, Model, Namespace, ProblemKind, Referrers};

/// An arm whose every dependent kind refers into the body `forearm`'s subtree.
const ARM: &str = include_str!("remove_with.xml");

fn arm() -> Model {
    Model::from_xml_str(ARM).unwrap()
}

/// The problems check() reports that are references left dangling.
fn dangling(m: &Model) -> Vec<String> {
    m.check()
        .into_iter()
        .filter(|p| {
            matches!(
                p.kind,
                ProblemKind::DanglingReference { .. }
                    | ProblemKind::RemovedReference { .. }
                    | ProblemKind::MissingRequired { .. }
            )
        })
        .map(|p| p.to_string())
        .collect()
}

#[test]
fn refuse_lists_every_referrer_of_the_subtree_and_changes_nothing() {
    let m = arm();
    let forearm = m.find(Namespace::Body, "forearm").unwrap();
    let e = m.remove_with(&forearm, Referrers::Refuse).unwrap_err();
    let ErrorKind::Referenced { by } = e.kind() else { panic!("{e}") };
    for expected in [
        "watch: target",
        "<joint> in coupling: joint",
        "<site> in cable: site",
        "tie: joint2",
        "hold: body1",
        "touch: geom2",
        "skip: body2",
        "elbow_motor: joint",
        "elbow_angle: joint",
        "tip_touch: site",
    ] {
        assert!(
            by.iter().any(|b| b.ends_with(expected) || b == expected),
            "{expected} not in {by:?}"
        );
    }
    assert!(!by.iter().any(|b| b.contains("shoulder_motor")), "{by:?}");
    // Nothing refers to an unused element: removed as `remove` removes it.
    let r =
        m.remove_with(&m.find(Namespace::Actuator, "coupled").unwrap(), Referrers::Refuse).unwrap();
    assert!(r.removed.is_empty() && r.cleared.is_empty());
}

#[test]
fn cascade_removes_what_depends_and_clears_what_stays_so_nothing_dangles() {
    let m = arm();
    assert!(m.check().is_empty());
    let forearm = m.find(Namespace::Body, "forearm").unwrap();
    let r = m.remove_with(&forearm, Referrers::Cascade).unwrap();
    let mut removed = r.removed.clone();
    removed.sort();
    let mut expected = vec![
        "coupling",
        "cable",
        "tie",
        "hold",
        "touch",
        "skip",
        "elbow_motor",
        "elbow_angle",
        "tip_touch",
        "cable_pull",
        "coupled",
    ];
    expected.sort();
    assert_eq!(removed, expected, "a tendon takes the actuators on it along");
    assert_eq!(r.cleared, [("watch".to_string(), "target")]);
    assert!(dangling(&r.model).is_empty(), "{:?}", dangling(&r.model));
    for kept in ["shoulder_motor", "shoulder_angle"] {
        let ns = if kept.ends_with("motor") { Namespace::Actuator } else { Namespace::Sensor };
        assert!(r.model.find(ns, kept).is_some(), "{kept}");
    }
}

#[test]
fn cascade_inside_an_attached_model_stays_in_that_model() {
    let mut scene = Model::new("scene");
    scene.attach_mut(&scene.worldbody(), &arm()).unwrap();
    scene.attach_mut(&scene.worldbody(), &arm()).unwrap();
    let elbow = scene.find(Namespace::Joint, "arm_1/elbow").unwrap();
    let r = scene.remove_with(&elbow, Referrers::Cascade).unwrap();
    assert!(r.removed.iter().all(|n| n.starts_with("arm_1/")), "{:?}", r.removed);
    assert!(r.removed.contains(&"arm_1/elbow_motor".to_string()), "{:?}", r.removed);
    assert!(r.model.find(Namespace::Actuator, "arm/elbow_motor").is_some());
    assert!(r.model.find(Namespace::Actuator, "arm_1/elbow_motor").is_none());
    assert!(dangling(&r.model).is_empty(), "{:?}", dangling(&r.model));
}

#[test]
fn a_material_removed_with_cascade_is_cleared_from_the_geom_that_stays() {
    let m = arm();
    let red = m.find(Namespace::Material, "red").unwrap();
    let r = m.remove_with(&red, Referrers::Cascade).unwrap();
    assert!(r.removed.is_empty());
    assert_eq!(r.cleared, [("upper_geom".to_string(), "material")]);
    assert!(dangling(&r.model).is_empty());
}

/// What cannot stay without its reference goes with it (each shape refused by MuJoCo
/// 4.0.0 when the reference is only cleared): a mesh geom (by its own type or its
/// class's) with its mesh, a height-field geom with its height field, a material's
/// `<layer>` with its texture; a geom of another type keeps its place.
#[test]
fn a_referrer_that_cannot_stay_without_its_reference_goes_with_it() {
    let m = Model::from_xml_str(
        r#"<mujoco><default><default class="meshy"><geom type="mesh"/></default></default>
           <asset><mesh name="me" builtin="sphere" params="1"/><hfield name="hf" nrow="3" ncol="3" size="1 1 1 .1"/>
           <texture name="tex" type="2d" builtin="checker" width="8" height="8"/>
           <material name="mat"><layer texture="tex" role="rgb"/></material></asset>
           <worldbody><geom name="own" type="mesh" mesh="me"/><geom name="by_class" class="meshy" mesh="me"/>
           <geom name="fitted" type="box" size="1 1 1" mesh="me"/><geom name="ground" type="hfield" hfield="hf"/></worldbody></mujoco>"#,
    )
    .unwrap();
    let me = m.find(Namespace::Mesh, "me").unwrap();
    let r = m.remove_with(&me, Referrers::Cascade).unwrap();
    assert_eq!(r.removed, ["own", "by_class"]);
    assert_eq!(r.cleared, [("fitted".to_string(), "mesh")]);
    let hf = m.find(Namespace::Hfield, "hf").unwrap();
    assert_eq!(m.remove_with(&hf, Referrers::Cascade).unwrap().removed, ["ground"]);
    let tex = m.find(Namespace::Texture, "tex").unwrap();
    let r = m.remove_with(&tex, Referrers::Cascade).unwrap();
    assert_eq!(r.removed, ["<layer> in mat"]);
    assert!(!r.model.to_xml_string().unwrap().contains("<layer"));
}
