//! Reference checks before MuJoCo (`Model::check`), who refers to an element
//! (`references_to`), and the names MuJoCo will see (`full_name`, `from_full_name`).

use mjcf::{AdviceKind, EditError, Model, Namespace, ProblemKind, WriteOptions, element};

use crate::robot;
use robot::robot;

#[test]
fn a_motor_on_a_joint_that_does_not_exist_is_reported_with_a_suggestion() -> Result<(), EditError> {
    let mut arm = robot("arm");
    arm.add_mut(&arm.actuator(), element!("motor", name = "typo", joint = "hipp"))?;
    let problems = arm.check();
    assert_eq!(problems.len(), 1, "{problems:?}");
    let p = &problems[0];
    assert_eq!(p.path, "typo");
    assert_eq!(p.loc, arm.lookup(Namespace::Actuator, "typo")?);
    assert!(matches!(
        &p.kind,
        ProblemKind::DanglingReference { attribute: "joint", namespace: Namespace::Joint, suggestions, .. }
            if suggestions.first().map(|s| s.as_str()) == Some("hip")
    ));
    // Inside an attachment the same typo is found, named with its scope.
    let mut scene = Model::new("scene");
    scene.attach_mut(&scene.worldbody(), &arm)?;
    let problems = scene.check();
    assert_eq!(problems.len(), 1);
    assert_eq!(problems[0].path, "arm/typo");
    assert_eq!(
        problems[0].to_string(),
        "arm/typo: 'joint' names joint 'hipp', which does not exist (did you mean 'hip'?)"
    );
    Ok(())
}

#[test]
fn a_clean_composition_has_no_problems() -> Result<(), EditError> {
    let mut scene = Model::new("scene");
    let site = scene.add_mut(&scene.worldbody(), element!("site", name = "s"))?;
    let a = scene.attach_mut(&site, &robot("robot"))?;
    scene.add_mut(a.frame(), element!("joint", name = "slide", type = "slide"))?;
    // The robot's torso moves on its own hinge, so the sliding frame needs mass of its
    // own (MuJoCo refuses it otherwise; `a_moving_frame_without_mass_is_reported`).
    assert_eq!(scene.check().len(), 1);
    scene.add_mut(
        a.frame(),
        element!("inertial", pos = [0, 0, 0], mass = 1, diaginertia = [0.1; 3]),
    )?;
    assert_eq!(scene.check(), vec![]);
    Ok(())
}

#[test]
fn a_removed_joint_leaves_the_motor_without_one() -> Result<(), EditError> {
    // Read from MJCF, the motor's joint is resolved; removing the joint clears it.
    let m = Model::from_xml_str(
        r#"<mujoco><worldbody><body name="b"><joint name="j"/><geom size="1"/></body></worldbody>
           <actuator><motor name="mo" joint="j"/></actuator></mujoco>"#,
    )
    .unwrap();
    let j = m.lookup(Namespace::Joint, "j")?;
    let mo = m.lookup(Namespace::Actuator, "mo")?;
    assert_eq!(m.references_to(&j), vec![(mo.clone(), "joint")]);
    let removed = m.remove(&j)?;
    assert_eq!(removed.references_to(&mo), vec![]);
    let problems = removed.check();
    assert_eq!(problems.len(), 1, "{problems:?}");
    assert_eq!(problems[0].kind, ProblemKind::RemovedReference { attribute: "joint" });
    assert_eq!(problems[0].to_string(), "mo: 'joint' named an element that was removed");
    Ok(())
}

#[test]
fn a_moving_frame_without_mass_is_reported() -> Result<(), EditError> {
    // A robot whose only body has a joint and a site, no geom: nothing has mass.
    let mut ghost = Model::new("ghost");
    let b = ghost.add_mut(&ghost.worldbody(), element!("body", name = "b"))?;
    ghost.add_mut(&b, element!("site", name = "s"))?;
    let mut scene = Model::new("scene");
    let a = scene.attach_mut(&scene.worldbody(), &ghost)?;
    assert_eq!(scene.check(), vec![], "nothing moves yet");
    scene.add_mut(a.frame(), element!("freejoint"))?;
    let problems = scene.check();
    assert_eq!(problems.len(), 1, "{problems:?}");
    assert_eq!(problems[0].path, "ghost/");
    assert_eq!(problems[0].kind, ProblemKind::MasslessMovingBody);
    // A massive body below the frame is enough.
    let mut solid = ghost.clone();
    solid.add_mut(&b, element!("geom", size = [0.1]))?;
    let mut scene2 = Model::new("scene");
    let a2 = scene2.attach_mut(&scene2.worldbody(), &solid)?;
    scene2.add_mut(a2.frame(), element!("freejoint"))?;
    assert_eq!(scene2.check(), vec![]);
    Ok(())
}

#[test]
fn keys_are_held_to_the_model_they_will_be_written_for() -> Result<(), EditError> {
    // The robot's own key fits the robot (one hinge, one motor) ...
    let mut r = robot("robot");
    let keys = r.section("keyframe").unwrap();
    r.add_mut(&keys, element!("key", name = "home", qpos = [0.5], ctrl = [0.0]))?;
    assert_eq!(r.check(), vec![]);
    // ... and in a scene of two robots on free frames (nq = 2 * (7 + 1)) MuJoCo takes
    // it (a shorter key is padded), but written as it is its values would fall on the
    // first free joint: check says so, and what to do.
    let mut scene = Model::new("scene");
    for _ in 0..2 {
        let a = scene.attach_mut(&scene.worldbody(), &r)?;
        scene.add_mut(a.frame(), element!("freejoint"))?;
    }
    // MuJoCo compiles it, so check() says nothing of the keys (the frames move
    // without mass: the one problem here); advice() says so, once per key, and what
    // to do.
    let keys = |problems: Vec<mjcf::Problem>| -> Vec<mjcf::Problem> {
        problems
            .into_iter()
            .filter(|p| !matches!(p.kind, ProblemKind::MasslessMovingBody))
            .collect()
    };
    assert_eq!(keys(scene.check()), vec![]);
    let advice: Vec<AdviceKind> = scene.advice().into_iter().map(|a| a.kind).collect();
    assert_eq!(advice, [AdviceKind::UncomposedKey, AdviceKind::UncomposedKey]);
    assert!(scene.advice()[0].to_string().contains("merge_keyframes"));
    // Composed (merge_keyframes), each robot's key fits its robot, and there is no
    // advice.
    let merged = WriteOptions { merge_keyframes: true, ..WriteOptions::default() };
    assert_eq!(keys(scene.check_with(&merged)), vec![]);
    assert_eq!(scene.advice_with(&merged), vec![]);
    // A key with more values than there is room for: MuJoCo refuses it.
    let long = r.set_attr(&r.find(Namespace::Key, "home").unwrap(), "qpos", [0.5, 0.1])?;
    let a = scene.attach(&scene.worldbody(), &long)?.0;
    let lengths: Vec<(&str, usize, usize)> = a
        .check_with(&merged)
        .iter()
        .filter_map(|p| match p.kind {
            ProblemKind::KeyLength { attribute, expected, found } => {
                Some((attribute, expected, found))
            }
            _ => None,
        })
        .collect();
    assert_eq!(lengths, [("qpos", 1, 2)]);
    let own = scene.add(&scene.section("keyframe").unwrap(), element!("key", qpos = [0.0; 17]))?.0;
    let lengths: Vec<_> = own
        .check()
        .into_iter()
        .filter(|p| matches!(p.kind, ProblemKind::KeyLength { .. }))
        .collect();
    assert_eq!(lengths.len(), 1, "{lengths:?}");
    Ok(())
}

#[test]
fn full_names_go_both_ways() -> Result<(), EditError> {
    let mut scene = Model::new("scene");
    let s = scene.add_mut(&scene.worldbody(), element!("site", name = "s"))?;
    scene.attach_mut(&s, &robot("robot"))?;
    let a = scene.attach_mut(&s, &robot("robot"))?;
    scene.add_mut(a.frame(), element!("freejoint", name = "root"))?;
    let xml = scene.to_xml_string().unwrap();
    for (ns, name) in [
        (Namespace::Body, "robot_1/torso"),
        (Namespace::Body, "robot_1/"),
        (Namespace::Joint, "robot_1/root/"),
        (Namespace::Geom, "robot//unnamed_geom_1"),
        (Namespace::Geom, "robot_1//unnamed_geom_1"),
        (Namespace::Actuator, "robot_1/m"),
    ] {
        assert!(xml.contains(&format!("name=\"{name}\"")), "{name} is written:\n{xml}");
        let loc = scene.from_full_name(ns, name).unwrap_or_else(|| panic!("{name} not found"));
        assert_eq!(scene.full_name(&loc).as_deref(), Some(name));
    }
    assert_eq!(scene.from_full_name(Namespace::Geom, "robot_2//unnamed_geom_1"), None);
    Ok(())
}

/// An arm with a hinged link holding the site `tip`, a static post holding `top`,
/// and a site `ground` in the world.
fn arm() -> Result<Model, EditError> {
    let mut arm = Model::new("arm");
    let link = arm.add_mut(&arm.worldbody(), element!("body", name = "link"))?;
    arm.add_mut(&link, element!("joint", name = "shoulder"))?;
    arm.add_mut(&link, element!("geom", size = [0.1]))?;
    arm.add_mut(&link, element!("site", name = "tip"))?;
    let post = arm.add_mut(&arm.worldbody(), element!("body", name = "post"))?;
    arm.add_mut(&post, element!("site", name = "top"))?;
    arm.add_mut(&arm.worldbody(), element!("site", name = "ground"))?;
    Ok(arm)
}

/// A model named `name` whose one top-level body `b` holds `extra` and a geom.
fn floating(name: &str, extra: mjcf::Element, mocap: bool) -> Result<Model, EditError> {
    let mut m = Model::new(name);
    let body = if mocap {
        element!("body", name = "b", mocap = "true")
    } else {
        element!("body", name = "b")
    };
    let b = m.add_mut(&m.worldbody(), body)?;
    m.add_mut(&b, extra)?;
    m.add_mut(&b, element!("geom", size = [0.1]))?;
    Ok(m)
}

fn kinds(m: &Model) -> Vec<(String, ProblemKind)> {
    m.check().into_iter().map(|p| (p.path, p.kind)).collect()
}

#[test]
fn a_free_body_attached_inside_a_body_is_reported_and_attached_welded_is_not()
-> Result<(), EditError> {
    let arm = arm()?;
    let site = |n: &str| arm.find(Namespace::Site, n).unwrap();
    let ball = floating("ball", element!("freejoint"), false)?;
    for at in ["tip", "top"] {
        let (scene, _) = arm.attach(&site(at), &ball)?;
        assert_eq!(
            kinds(&scene),
            [("ball/b".to_string(), ProblemKind::FreeJointNotTopLevel)],
            "{at}"
        );
        let shown = scene.check()[0].to_string();
        assert!(shown.contains("free joint can only be used on top level"), "{shown}");
        assert!(shown.contains("attach_welded"), "{shown}");
        let (welded, _) = arm.attach_welded(&site(at), &ball)?;
        assert_eq!(kinds(&welded), [], "{at}");
    }
    // In the world the frame is written as MuJoCo's <frame>: the body stays top level.
    assert_eq!(kinds(&arm.attach(&site("ground"), &ball)?.0), []);
    // A free joint given to an attachment frame inside a body (`add` refuses a
    // <freejoint> there; a joint of type free it takes): the frame is a body.
    let (scene, a) = arm.attach(&site("tip"), &floating("box", element!("joint"), false)?)?;
    let scene = scene.add(a.frame(), element!("joint", type = "free"))?.0;
    assert!(
        kinds(&scene).iter().any(|(_, k)| *k == ProblemKind::FreeJointNotTopLevel),
        "{:?}",
        kinds(&scene)
    );
    Ok(())
}

#[test]
fn a_mocap_body_attached_anywhere_is_reported_and_attached_welded_is_a_plain_body()
-> Result<(), EditError> {
    let arm = arm()?;
    let target = floating("target", element!("site", name = "s"), true)?;
    for at in ["tip", "top", "ground"] {
        let site = arm.find(Namespace::Site, at).unwrap();
        let (scene, _) = arm.attach(&site, &target)?;
        assert_eq!(
            kinds(&scene),
            [("target/b".to_string(), ProblemKind::MocapNotFixedChildOfWorld)],
            "{at}"
        );
        assert!(scene.check()[0].to_string().contains("is not a fixed child of world"));
        let (welded, a) = arm.attach_welded(&site, &target)?;
        assert_eq!(kinds(&welded), [], "{at}");
        let b = welded.find(Namespace::Body, &format!("{}/b", a.scope())).unwrap();
        assert_eq!(welded.get(&b)?.attr("mocap"), None);
    }
    Ok(())
}

#[test]
fn a_plane_attached_inside_a_moving_body_is_reported() -> Result<(), EditError> {
    let arm = arm()?;
    let floor = floating("floor", element!("geom", type = "plane", size = [1.0, 1.0, 0.1]), false)?;
    let at = |n: &str| arm.find(Namespace::Site, n).unwrap();
    let (scene, _) = arm.attach(&at("tip"), &floor)?;
    let found = scene.check();
    assert_eq!(found.len(), 1, "{found:?}");
    assert_eq!(found[0].kind, ProblemKind::PlaneInMovingBody);
    assert!(found[0].to_string().contains("plane only allowed in static bodies"));
    assert_eq!(kinds(&arm.attach(&at("top"), &floor)?.0), []);
    Ok(())
}

#[test]
fn a_free_body_included_inside_a_body_is_reported() {
    let dir = std::env::temp_dir().join(format!("mjcf-check-include-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(
        dir.join("ball.xml"),
        r#"<mujoco><body name="ball"><freejoint/><geom size="0.1"/></body></mujoco>"#,
    )
    .unwrap();
    let main = |parent: &str| {
        format!(
            r#"<mujoco><worldbody>{}<include file="ball.xml"/>{}</worldbody></mujoco>"#,
            parent,
            if parent.is_empty() { "" } else { "</body>" }
        )
    };
    for (parent, refused) in [(r#"<body name="post"><geom size="1"/>"#, true), ("", false)] {
        std::fs::write(dir.join("main.xml"), main(parent)).unwrap();
        let m = Model::from_path(dir.join("main.xml")).unwrap();
        let found: Vec<_> = m.check().into_iter().map(|p| (p.path, p.kind)).collect();
        let expected = if refused {
            vec![("ball".to_string(), ProblemKind::FreeJointNotTopLevel)]
        } else {
            vec![]
        };
        assert_eq!(found, expected, "{parent}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}
