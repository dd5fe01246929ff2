//! Composition: sharing of attached values, detach as exact undo, and property tests
//! over random op sequences (attach, detach, scope rename, edits inside attachments,
//! include_copy).
//!
//! Properties run `PROPTEST_CASES` cases (default 128) from proptest's fixed seed.

use std::collections::HashSet;

use mjcf::{Element, ErrorKind, Loc, Model, Namespace};
use proptest::prelude::*;
use proptest::test_runner::Config;

use crate::robot;
use robot::robot;

#[test]
fn one_child_attached_many_times_is_shared_not_copied() {
    let child = robot("robot");
    let mut scene = Model::new("arena");
    for _ in 0..50 {
        scene = scene.attach_to_world(&child).unwrap().0;
    }
    let scopes: Vec<&str> = scene.scopes().collect();
    assert_eq!(scopes.len(), 50);
    assert_eq!(scopes[0], "robot");
    assert_eq!(scopes[1], "robot_1");
    assert_eq!(scopes[49], "robot_49");
    assert_eq!(scopes.iter().collect::<HashSet<_>>().len(), 50);
    for s in &scopes {
        let inside = scene.attached(s).unwrap();
        assert!(inside.ptr_eq(&child), "{s} holds a copy");
        let torso = scene.find(Namespace::Body, &format!("{s}/torso")).unwrap();
        let el = scene.element(&torso).unwrap();
        assert!(el.ptr_eq(&child.element(&child.find(Namespace::Body, "torso").unwrap()).unwrap()));
    }
    let xml = scene.to_xml_string().unwrap();
    assert!(xml.contains(r#"<body name="robot_49/torso">"#));
    assert!(xml.contains(r#"<motor name="robot_49/m" class="robot_49/" joint="robot_49/hip"/>"#));
}

#[test]
fn detach_gives_back_the_parent_exactly() {
    let arena = Model::new("arena");
    let (arena, site) =
        arena.add(&arena.worldbody(), Element::new("site").attr("name", "s")).unwrap();
    let (arena, opt) = (arena.clone(), arena.section("option").unwrap());
    let arena = arena.set_attr(&opt, "timestep", 0.01).unwrap();
    let child = robot("c");
    let child = child.set_attr(&child.section("option").unwrap(), "timestep", 0.002).unwrap();
    let (scene, _) = arena.attach(&site, &child).unwrap();
    assert!(scene.to_xml_string().unwrap().contains(r#"timestep="0.002""#));
    let back = scene.detach("c").unwrap();
    assert_eq!(back, arena);
    assert_eq!(back.to_xml_string().unwrap(), arena.to_xml_string().unwrap());
    assert!(matches!(scene.detach("nope").unwrap_err().kind(), ErrorKind::NotAttached { .. }));
}

#[test]
fn conflicts_are_refused_at_attach_and_at_later_edits() {
    let parent = Model::new("p");
    let parent = parent.set_attr(&parent.section("compiler").unwrap(), "angle", "radian").unwrap();
    let child = Model::new("c");
    let child = child.set_attr(&child.section("compiler").unwrap(), "angle", "degree").unwrap();
    // A unit that differs is converted (decision D17, `tests/angles.rs`); another
    // compiler setting must agree.
    let (converted, a) = parent.attach_to_world(&child).unwrap();
    let held = converted.attached(&a).unwrap();
    assert_eq!(held.string(&held.section("compiler").unwrap(), "angle").unwrap(), "radian");
    let strict =
        parent.set_attr(&parent.section("compiler").unwrap(), "autolimits", false).unwrap();
    let loose = child.set_attr(&child.section("compiler").unwrap(), "autolimits", true).unwrap();
    let err = strict.attach_to_world(&loose).unwrap_err();
    assert!(
        matches!(err.kind(), ErrorKind::AttributeConflict { attribute: "autolimits", .. }),
        "{err}"
    );
    // Attached first, then a conflicting edit on either side is refused.
    let plain = Model::new("p");
    let (scene, _) = plain.attach_to_world(&child).unwrap();
    let err = scene.set_attr(&scene.section("compiler").unwrap(), "angle", "radian").unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::AttributeConflict { .. }), "{err}");
    let inner = scene.locate_in("c", &child.section("compiler").unwrap()).unwrap();
    assert!(scene.set_attr(&inner, "angle", "radian").is_ok());
}

#[test]
fn nested_attach_at_a_site_inside_an_attachment() {
    let arm = robot("arm");
    let (scene, _) = Model::new("world").attach_to_world(&arm).unwrap();
    let mount = scene.find(Namespace::Site, "arm/mount").unwrap();
    let (scene, frame) = scene.attach(&mount, &robot("gripper")).unwrap();
    assert_eq!(scene.scope_of_frame(frame.frame()).as_deref(), Some("arm/gripper"));
    assert!(scene.find(Namespace::Joint, "arm/gripper/hip").is_some());
    let xml = scene.to_xml_string().unwrap();
    assert!(xml.contains(r#"<body name="arm/gripper/torso">"#), "{xml}");
    assert!(xml.contains(r#"<default class="arm/gripper/"/>"#), "{xml}");
    // The arm value inside the scene changed; the arm value itself did not.
    assert!(arm.find(Namespace::AttachmentFrame, "gripper").is_none());
    let before = scene.edit_attached("arm", |a| a.detach("gripper")).unwrap();
    assert_eq!(scene.detach("arm/gripper").unwrap(), before);
    assert!(
        before.attached("arm").unwrap().ptr_eq(&arm) || before.attached("arm").unwrap() == &arm
    );
}

// ---------------------------------------------------------------------------------
// Property tests over random op sequences.

#[derive(Clone, Debug)]
enum Action {
    /// Attach robot `which` at the site of index `at` (of all sites) or the world.
    Attach {
        which: usize,
        at: Option<prop::sample::Index>,
    },
    Detach {
        scope: prop::sample::Index,
    },
    RenameScope {
        scope: prop::sample::Index,
        to: usize,
    },
    /// Set a geom's size somewhere (possibly inside an attachment).
    SetSize {
        geom: prop::sample::Index,
        size: f64,
    },
    /// include_copy a fresh robot-like model into the root.
    IncludeCopy {
        name: usize,
    },
}

const NAMES: [&str; 4] = ["robot", "arm", "robot_1", "leg"];

fn action() -> impl Strategy<Value = Action> {
    prop_oneof![
        4 => (0..NAMES.len(), prop::option::of(any::<prop::sample::Index>()))
            .prop_map(|(which, at)| Action::Attach { which, at }),
        2 => any::<prop::sample::Index>().prop_map(|scope| Action::Detach { scope }),
        1 => (any::<prop::sample::Index>(), 0..NAMES.len()).prop_map(|(scope, to)| Action::RenameScope { scope, to }),
        2 => (any::<prop::sample::Index>(), 0.01..1.0f64).prop_map(|(geom, size)| Action::SetSize { geom, size }),
        1 => (0..3usize).prop_map(|name| Action::IncludeCopy { name }),
    ]
}

/// (tag, name) of every element, and every (attribute, value) of a motor, from the
/// written XML.
fn written(xml: &str) -> (Vec<(String, String)>, Vec<String>) {
    let mut names = Vec::new();
    let mut motor_joints = Vec::new();
    let mut reader = quick_xml::Reader::from_str(xml);
    loop {
        match reader.read_event().expect("our output is well-formed") {
            quick_xml::events::Event::Start(t) | quick_xml::events::Event::Empty(t) => {
                let tag = t.name().as_ref().to_string();
                for a in t.attributes().flatten() {
                    let v = a.value.to_string();
                    match a.key.as_ref() {
                        "name" => names.push((tag.clone(), v)),
                        "joint" if tag == "motor" => motor_joints.push(v),
                        _ => {}
                    }
                }
            }
            quick_xml::events::Event::Eof => break,
            _ => {}
        }
    }
    (names, motor_joints)
}

fn namespace_of(tag: &str) -> &str {
    match tag {
        "freejoint" => "joint",
        "motor" | "position" => "actuator",
        t => t,
    }
}

fn step(m: &Model, a: &Action, robots: &[Model]) -> Result<Model, mjcf::EditError> {
    match a {
        Action::Attach { which, at } => {
            let sites = m.find_all(Namespace::Site);
            let target: Loc = match at {
                Some(i) if !sites.is_empty() => sites[i.index(sites.len())].clone(),
                _ => m.worldbody(),
            };
            m.attach(&target, &robots[*which]).map(|(m, _)| m)
        }
        Action::Detach { scope } => {
            let paths = m.scope_paths();
            if paths.is_empty() {
                return Ok(m.clone());
            }
            m.detach(&paths[scope.index(paths.len())])
        }
        Action::RenameScope { scope, to } => {
            let paths = m.scope_paths();
            if paths.is_empty() {
                return Ok(m.clone());
            }
            m.rename_scope(&paths[scope.index(paths.len())], NAMES[*to])
        }
        Action::SetSize { geom, size } => {
            let geoms = m.find_all(Namespace::Geom);
            if geoms.is_empty() {
                return Ok(m.clone());
            }
            m.set_attr(&geoms[geom.index(geoms.len())], "size", [*size])
        }
        Action::IncludeCopy { name } => {
            let src = Model::new("inc");
            let (src, _) = src
                .add(
                    &src.worldbody(),
                    Element::new("geom").attr("name", format!("inc{name}")).attr("size", [0.2]),
                )
                .unwrap();
            m.include_copy(&src, false)
        }
    }
}

proptest! {
    #![proptest_config(Config { cases: std::env::var("PROPTEST_CASES").ok().and_then(|c| c.parse().ok()).unwrap_or(128), ..Config::default() })]

    #[test]
    fn random_compositions_keep_their_invariants(actions in prop::collection::vec(action(), 1..24)) {
        let robots: Vec<Model> = NAMES.iter().map(|n| robot(n)).collect();
        let base = Model::new("arena");
        let (base, _) = base.add(&base.worldbody(), Element::new("site").attr("name", "spawn")).unwrap();
        let mut history: Vec<(Model, String)> = vec![(base.clone(), base.to_xml_string().unwrap())];
        let mut m = base;
        for a in &actions {
            let next = match step(&m, a, &robots) {
                Ok(n) => n,
                // A refused op (a name taken by a rename, a geom name taken by
                // include_copy) changes nothing.
                Err(_) => continue,
            };
            // Attach then detach gives back the value exactly.
            if let Action::Attach { .. } = a {
                let new_scope = next.scope_paths().into_iter().find(|p| !m.scope_paths().contains(p));
                let new_scope = new_scope.expect("attach adds a scope");
                prop_assert_eq!(&next.detach(&new_scope).unwrap(), &m);
            }
            m = next;
            let xml = m.to_xml_string().unwrap();
            let (names, motor_joints) = written(&xml);
            // Identifiers are unique per namespace.
            let mut seen: HashSet<(&str, &str)> = HashSet::new();
            for (tag, name) in &names {
                prop_assert!(seen.insert((namespace_of(tag), name.as_str())), "{} {} twice in\n{}", tag, name, xml);
            }
            // Every motor's joint names a joint of the output.
            let joints: HashSet<&str> =
                names.iter().filter(|(t, _)| namespace_of(t) == "joint").map(|(_, n)| n.as_str()).collect();
            for j in &motor_joints {
                prop_assert!(joints.contains(j.as_str()), "motor joint {} missing in\n{}", j, xml);
            }
            history.push((m.clone(), xml));
        }
        // Earlier values never changed.
        for (old, text) in &history {
            prop_assert_eq!(&old.to_xml_string().unwrap(), text);
        }
        // The robots were never changed by being attached.
        for (r, n) in robots.iter().zip(NAMES) {
            prop_assert_eq!(r.to_xml_string().unwrap(), robot(n).to_xml_string().unwrap());
        }
    }

    #[test]
    fn n_attaches_of_one_child_give_n_distinct_scopes(n in 1usize..40, name in 0..NAMES.len()) {
        let child = robot(NAMES[name]);
        let mut m = Model::new("arena");
        for _ in 0..n {
            m = m.attach_to_world(&child).unwrap().0;
        }
        let scopes: HashSet<&str> = m.scopes().collect();
        prop_assert_eq!(scopes.len(), n);
        let xml = m.to_xml_string().unwrap();
        for s in &scopes {
            let expected = format!(r#"<body name="{s}/torso">"#);
            prop_assert!(xml.contains(&expected), "{} missing", expected);
        }
    }
}

#[test]
fn merged_settings_follow_edits_inside_nested_attachments() {
    // Versions share their folded settings; every edit that can change the fold must
    // show in the output of the new version and leave the old one as it was.
    let inner = Model::new("inner");
    let mid = Model::new("mid").attach_to_world(&inner).unwrap().0;
    let top = Model::new("top").attach_to_world(&mid).unwrap().0;
    let before = top.to_xml_string().unwrap();
    assert!(!before.contains("timestep"));
    let option = top.locate_in("mid/inner", &inner.section("option").unwrap()).unwrap();
    let edited = top.set_attr(&option, "timestep", 0.005).unwrap();
    assert!(edited.to_xml_string().unwrap().contains(r#"timestep="0.005""#));
    assert_eq!(top.to_xml_string().unwrap(), before);
    // The middle model, taken out of the new version, folds the edit too.
    assert!(
        edited.attached("mid").unwrap().to_xml_string().unwrap().contains(r#"timestep="0.005""#)
    );
    // A conflicting setting at the top is refused, one that agrees is accepted.
    let compiler = top.locate_in("mid/inner", &inner.section("compiler").unwrap()).unwrap();
    let edited = edited.set_attr(&compiler, "angle", "radian").unwrap();
    let top_compiler = edited.section("compiler").unwrap();
    let err = edited.set_attr(&top_compiler, "angle", "degree").unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::AttributeConflict { attribute: "angle", .. }), "{err}");
    assert!(edited.set_attr(&top_compiler, "angle", "radian").is_ok());
    // Detaching the middle model takes its settings with it.
    let back = edited.detach("mid").unwrap();
    assert!(!back.to_xml_string().unwrap().contains("timestep"));
    assert!(back.set_attr(&back.section("compiler").unwrap(), "angle", "degree").is_ok());
    // Removing the attachments with a body that holds their frame does too.
    let (arena, site) = Model::new("arena")
        .add(&Model::new("arena").worldbody(), Element::new("body").attr("name", "b"))
        .unwrap();
    let (arena, s) = arena.add(&site, Element::new("site").attr("name", "s")).unwrap();
    let (scene, _) = arena.attach(&s, edited.attached("mid").unwrap()).unwrap();
    assert!(scene.to_xml_string().unwrap().contains(r#"timestep="0.005""#));
    let body = scene.find(Namespace::Body, "b").unwrap();
    let cleared = scene.remove_with_attachments(&body).unwrap();
    assert!(!cleared.to_xml_string().unwrap().contains("timestep"));
}

/// decision D15: the attachment frame sits where MuJoCo puts the site, also when the
/// site's class or its `fromto` places it (dm_control copies the site's own
/// attributes only).
#[test]
fn a_frame_is_placed_where_mujoco_places_its_site() {
    let arena = mjcf::ReadOptions::new()
        .read_str(
            r#"<mujoco model="arena"><default><default class="spot"><site pos="1 2 0.5" euler="0 0 45"/></default></default>
               <worldbody><site name="by_class" class="spot"/><site name="own" class="spot" pos="3 0 0"/>
               <site name="ft" type="capsule" size="0.01" fromto="0 -1 0 0.3 -1 0.4"/></worldbody></mujoco>"#,
        )
        .unwrap();
    let robot = Model::new("robot");
    let frame_of = |site: &str| {
        let mut a = arena.clone();
        let at = a.find(mjcf::Namespace::Site, site).unwrap();
        let f = a.attach_mut(&at, &robot).unwrap();
        let el = a.get(f.frame()).unwrap();
        el.attrs().map(|(n, v)| format!("{n}={v}")).collect::<Vec<_>>()
    };
    assert_eq!(frame_of("by_class"), ["pos=1 2 0.5", "euler=0 0 45"]);
    // Its own position wins; the orientation still comes from the class.
    assert_eq!(frame_of("own"), ["pos=3 0 0", "euler=0 0 45"]);
    // A fromto: its middle, and the z axis from its end back to its start.
    assert_eq!(frame_of("ft"), ["pos=0.15 -1 0.2", "zaxis=-0.3 0 -0.4"]);
}
