//! `<include>` as MuJoCo reads it: a setting that both the file and an include set
//! takes the value that comes later in the document (MuJoCo pastes the included text
//! in place of the tag).

use mjcf::{Model, ReadOptions};

fn read(main: &str) -> Model {
    let inc =
        r#"<mujoco><option timestep="0.002"/><visual><map stiffness="700"/></visual></mujoco>"#;
    ReadOptions::new().asset("inc.xml", inc.as_bytes().to_vec()).read_str(main).unwrap()
}

fn setting(m: &Model, tag: &str, attr: &str) -> String {
    let xml = m.to_xml_string().unwrap();
    let line = xml.lines().find(|l| l.trim_start().starts_with(&format!("<{tag} "))).unwrap_or("");
    line.split(&format!("{attr}=\""))
        .nth(1)
        .and_then(|r| r.split('"').next())
        .unwrap_or("")
        .to_string()
}

#[test]
fn an_include_before_a_setting_is_overridden_by_it() {
    let m = read(
        r#"<mujoco><include file="inc.xml"/><option timestep="0.01"/><visual><map stiffness="100"/></visual></mujoco>"#,
    );
    assert_eq!(setting(&m, "option", "timestep"), "0.01");
    assert_eq!(setting(&m, "map", "stiffness"), "100");
}

#[test]
fn an_include_after_a_setting_overrides_it() {
    let m = read(
        r#"<mujoco><option timestep="0.01"/><visual><map stiffness="100"/></visual><include file="inc.xml"/></mujoco>"#,
    );
    assert_eq!(setting(&m, "option", "timestep"), "0.002");
    assert_eq!(setting(&m, "map", "stiffness"), "700");
}

#[test]
fn settings_only_one_side_sets_are_merged() {
    let m = read(r#"<mujoco><option gravity="0 0 -1"/><include file="inc.xml"/></mujoco>"#);
    assert_eq!(setting(&m, "option", "timestep"), "0.002");
    assert_eq!(setting(&m, "option", "gravity"), "0 0 -1");
}

#[test]
fn an_include_inside_a_body_is_read_in_place() {
    let part = r#"<mujoco><geom name="g2" size="0.2"/><site name="s2"/></mujoco>"#;
    let m = ReadOptions::new()
        .asset("part.xml", part.as_bytes().to_vec())
        .read_str(
            r#"<mujoco><worldbody><body name="b"><include file="part.xml"/><geom name="g1" size="0.1"/></body></worldbody></mujoco>"#,
        )
        .unwrap();
    let xml = m.to_xml_string().unwrap();
    let g2 = xml.find(r#"name="g2""#).unwrap();
    let g1 = xml.find(r#"name="g1""#).unwrap();
    assert!(g2 < g1, "in document order, in place of the include:\n{xml}");
    assert!(m.find(mjcf::Namespace::Site, "s2").is_some());
    let body = m.find(mjcf::Namespace::Body, "b").unwrap();
    assert_eq!(m.get(&body).unwrap().children().filter(|c| c.tag() == "geom").count(), 2);
    // Nested: an include inside the included file's elements.
    let outer = r#"<mujoco><body name="c"><include file="part.xml"/></body></mujoco>"#;
    let m = ReadOptions::new()
        .asset("part.xml", part.as_bytes().to_vec())
        .asset("outer.xml", outer.as_bytes().to_vec())
        .read_str(r#"<mujoco><worldbody><include file="outer.xml"/></worldbody></mujoco>"#)
        .unwrap();
    assert!(m.find(mjcf::Namespace::Geom, "g2").is_some());
    assert!(m.find(mjcf::Namespace::Body, "c").is_some());
}

#[test]
fn an_include_inside_an_element_that_includes_itself_is_a_cycle() {
    let part = r#"<mujoco><body><include file="part.xml"/></body></mujoco>"#;
    let e = ReadOptions::new()
        .asset("part.xml", part.as_bytes().to_vec())
        .read_str(r#"<mujoco><worldbody><include file="part.xml"/></worldbody></mujoco>"#)
        .unwrap_err();
    assert!(matches!(e.kind(), mjcf::ErrorKind::IncludeCycle(_)), "{e}");
}

#[test]
fn folders_an_included_file_sets_apply_to_files_named_after_it() {
    // MuJoCo's compiler settings are global: a robot file's meshdir applies to the
    // meshes the including scene names after the include.
    let mesh = b"solid m\nendsolid m\n".to_vec();
    let robot = r#"<mujoco model="robot"><compiler meshdir="assets"/><asset><mesh name="a" file="a.stl"/></asset></mujoco>"#;
    let m = ReadOptions::new()
        .asset("robot.xml", robot.as_bytes().to_vec())
        .asset("assets/a.stl", mesh.clone())
        .asset("assets/b.stl", mesh)
        .read_str(r#"<mujoco><include file="robot.xml"/><asset><mesh name="b" file="b.stl"/></asset></mujoco>"#)
        .unwrap();
    assert!(m.find(mjcf::Namespace::Mesh, "a").is_some());
    assert!(m.find(mjcf::Namespace::Mesh, "b").is_some());
}
