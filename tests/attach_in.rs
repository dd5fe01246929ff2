//! `Model::attach_in`: attaching at a body or a MuJoCo `<frame>` (as MjSpec does),
//! beside `attach` at a site or the worldbody (as dm_control does).
//! `mjcf-mujoco/tests/attach_in.rs` has MuJoCo judge the poses.

use mjcf::{ErrorKind, Model, Namespace, element};

fn table() -> (Model, mjcf::Loc) {
    let mut t = Model::new("table");
    let top =
        t.add_mut(&t.worldbody(), element!("body", name = "top", pos = [0.0, 0.0, 0.8])).unwrap();
    t.add_mut(&top, element!("geom", size = [0.5, 0.5, 0.02], type = "box")).unwrap();
    (t, top)
}

fn arm() -> Model {
    let mut arm = Model::new("arm");
    let base = arm
        .add_mut(&arm.worldbody(), element!("body", name = "base", pos = [0.0, 0.0, 0.1]))
        .unwrap();
    arm.add_mut(&base, element!("joint", name = "shoulder")).unwrap();
    arm.add_mut(&base, element!("geom", size = [0.05])).unwrap();
    arm
}

#[test]
fn attach_in_a_body_puts_the_frame_last_among_its_children_without_a_pose() {
    let (t, top) = table();
    let (scene, a) = t.attach_in(&top, &arm()).unwrap();
    assert_eq!(a.scope(), "arm");
    let frame = scene.element(a.frame()).unwrap();
    assert_eq!(frame.parent().map(|p| p.loc()), Some(top.clone()));
    assert_eq!(
        scene.element(&top).unwrap().children().last().map(|c| c.loc()),
        Some(a.frame().clone())
    );
    assert!(frame.attrs().next().is_none(), "no pose of its own");
    assert!(scene.find(Namespace::Body, "arm/base").is_some());
    assert!(scene.find(Namespace::Joint, "arm/shoulder").is_some());
    assert_eq!(scene.detach(&a).unwrap(), t);
    let xml = scene.to_xml_string().unwrap();
    assert!(xml.contains("<body name=\"arm/\">"), "{xml}");
}

#[test]
fn attach_in_twice_and_with_a_scope_of_ones_own_numbers_scopes_as_attach_does() {
    let (t, top) = table();
    let (t, a) = t.attach_in(&top, &arm()).unwrap();
    let (t, b) = t.attach_in(&top, &arm()).unwrap();
    let (t, c) = t.attach_in_as(&top, &arm(), "left").unwrap();
    assert_eq!([a.scope(), b.scope(), c.scope()], ["arm", "arm_1", "left"]);
    assert!(t.find(Namespace::Body, "left/base").is_some());
    assert!(t.attach_in_as(&top, &arm(), "a/b").is_err());
}

#[test]
fn attach_in_a_frame_read_from_mjcf_and_in_a_body_of_an_attached_model() {
    let text = r#"<mujoco model="cell"><worldbody><frame name="mount" pos="1 0 0"><body name="plate"/></frame></worldbody></mujoco>"#;
    let cell = Model::from_xml_str(text).unwrap();
    let mount = cell.find(Namespace::Frame, "mount").unwrap();
    let (cell2, a) = cell.attach_in(&mount, &arm()).unwrap();
    assert_eq!(cell2.element(a.frame()).unwrap().parent().map(|p| p.loc()), Some(mount));
    // Inside an attachment: the body `table/top`.
    let (t, _) = table();
    let mut scene = Model::new("scene");
    scene.attach_mut(&scene.worldbody(), &t).unwrap();
    let top = scene.find(Namespace::Body, "table/top").unwrap();
    let (scene, b) = scene.attach_in(&top, &arm()).unwrap();
    assert_eq!(b.scope(), "table/arm");
    assert!(scene.find(Namespace::Body, "table/arm/base").is_some());
}

#[test]
fn attach_in_refuses_what_is_not_a_body_or_frame_and_attach_refuses_a_body() {
    let (t, top) = table();
    let (t, a) = t.attach_in(&top, &arm()).unwrap();
    let (t, site) = t.add(&top, element!("site", name = "s")).unwrap();
    for (at, inside) in [(&site, true), (a.frame(), true), (&top, false)] {
        let result = if inside { t.attach_in(at, &arm()) } else { t.attach(at, &arm()) };
        let e = result.unwrap_err();
        assert!(matches!(e.kind(), ErrorKind::InvalidParent(_)), "{e}");
        assert!(e.to_string().contains("attach_in"), "{e}");
    }
}
