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
