//! `Model::part`: a body's subtree of another model with exactly what it needs (the
//! classes and assets it uses, what refers only into it, the compiler settings),
//! none of the source's scene (floor, lights, skybox, other bodies, keyframes,
//! option), and what refers outside it reported. `mjcf-mujoco/tests/part.rs` has
//! MuJoCo compile each element of the part as in its own file.

use mjcf::{ErrorKind, Model, Namespace};

const SCENE: &str = include_str!("../examples/models/gripper_scene.xml");

fn names(m: &Model, ns: Namespace) -> Vec<String> {
    let mut out: Vec<String> = m
        .walk()
        .filter_map(|e| match e {
            mjcf::Event::Enter(e) if e.kind().namespace() == Some(ns) => {
                e.identifier().map(str::to_string)
            }
            _ => None,
        })
        .collect();
    out.sort();
    out
}

#[test]
fn a_part_holds_exactly_the_subtree_and_what_refers_only_into_it() {
    let scene = Model::from_xml_str(SCENE).unwrap();
    let part = scene.part("base").unwrap();
    let m = &part.model;
    assert_eq!(m.name(), "base");
    assert_eq!(names(m, Namespace::Body), ["base", "left_finger", "right_finger"]);
    assert_eq!(names(m, Namespace::Joint), ["left", "right", "wrist"]);
    assert_eq!(names(m, Namespace::Site), ["pinch"]);
    assert_eq!(names(m, Namespace::Tendon), ["split"]);
    assert_eq!(names(m, Namespace::Equality), ["mirror"]);
    assert_eq!(names(m, Namespace::Actuator), ["fingers", "wrist_motor"]);
    assert_eq!(names(m, Namespace::Sensor), ["left_pos"]);
    assert_eq!(names(m, Namespace::Material), ["metal"]);
    assert!(names(m, Namespace::Texture).is_empty(), "no skybox, no floor texture");
    assert!(names(m, Namespace::Light).is_empty());
    assert!(names(m, Namespace::Key).is_empty());
    assert_eq!(names(m, Namespace::Default), ["finger", "robotiq"]);
    // What refers outside the part (partly, as the weld and the exclude, or wholly)
    // is left out, and reported.
    let mut left_out = part.left_out.clone();
    left_out.sort();
    assert_eq!(left_out, ["box_pos", "hold", "rope", "to_mount"], "{:?}", part.left_out);
    // The childclass in force at the root comes with it.
    let base = m.find(Namespace::Body, "base").unwrap();
    assert_eq!(m.get(&base).unwrap().string("childclass"), Some("robotiq"));
    // The compiler's settings stay, the scene's go.
    let xml = m.to_xml_string().unwrap();
    assert!(xml.contains("angle=\"radian\"") && xml.contains("autolimits=\"true\""), "{xml}");
    assert!(
        !xml.contains("timestep") && !xml.contains("headlight") && !xml.contains("extent"),
        "{xml}"
    );
    assert!(m.check().is_empty(), "{:?}", m.check());
    // The source is a value: unchanged.
    assert_eq!(scene, Model::from_xml_str(SCENE).unwrap());
}

#[test]
fn a_part_attaches_under_a_scope_and_detaches_back() {
    let part = Model::from_xml_str(SCENE).unwrap().part("base").unwrap();
    let mut arm = Model::new("arm");
    let hand = arm.add_mut(&arm.worldbody(), mjcf::element!("body", name = "hand")).unwrap();
    arm.add_mut(&hand, mjcf::element!("geom", size = [0.05])).unwrap();
    let (scene, a) = arm.attach_in_as(&hand, &part.model, "gripper").unwrap();
    for name in ["gripper/base", "gripper/left_finger"] {
        assert!(scene.find(Namespace::Body, name).is_some(), "{name}");
    }
    assert!(scene.find(Namespace::Actuator, "gripper/fingers").is_some());
    assert_eq!(scene.detach(&a).unwrap(), arm);
    assert!(scene.check().is_empty(), "{:?}", scene.check());
}

#[test]
fn a_part_of_the_world_body_or_of_a_missing_body_is_a_typed_error() {
    let scene = Model::from_xml_str(SCENE).unwrap();
    let e = scene.part("bsae").unwrap_err();
    assert!(e.to_string().contains("base"), "suggests the nearest name: {e}");
    let e = scene.part_at(&scene.worldbody()).unwrap_err();
    assert!(matches!(e.kind(), ErrorKind::InvalidParent(_)), "{e}");
    let floor = scene.find(Namespace::Geom, "floor").unwrap();
    assert!(matches!(scene.part_at(&floor).unwrap_err().kind(), ErrorKind::InvalidParent(_)));
}

#[test]
fn a_free_part_is_fine_at_the_top_level_and_reported_below_a_body() {
    // The box is free: at the world's top level it compiles.
    let scene = Model::from_xml_str(SCENE).unwrap();
    let part = scene.part("box").unwrap();
    assert_eq!(
        names(&part.model, Namespace::Tendon),
        Vec::<String>::new(),
        "the rope hangs from the world"
    );
    let world = Model::new("world");
    let (top, _) = world.attach(&world.worldbody(), &part.model).unwrap();
    assert!(top.check().is_empty(), "{:?}", top.check());
    // Inside a body it is no longer at the top: check() says what MuJoCo refuses.
    let mut table = Model::new("table");
    let b = table.add_mut(&table.worldbody(), mjcf::element!("body", name = "b")).unwrap();
    table.add_mut(&b, mjcf::element!("geom", size = [0.1])).unwrap();
    let (below, _) = table.attach_in(&b, &part.model).unwrap();
    let problems = below.check();
    assert!(
        problems.iter().any(|p| matches!(p.kind, mjcf::ProblemKind::FreeJointNotTopLevel)),
        "{problems:?}"
    );
    // The remedy: welded, it compiles below a body.
    let (welded, _) = table.attach_in(&b, &part.model.welded().unwrap()).unwrap();
    assert!(welded.check().is_empty(), "{:?}", welded.check());
}
