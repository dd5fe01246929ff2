//! `<include>` as MuJoCo reads it: a setting that both the file and an include set
//! takes the value that comes later in the document (MuJoCo pastes the included text
//! in place of the tag). The included file is read into the including model's elements
//! (one read, not a model merged afterwards): errors name the file and place they are
//! in, and the element order of root-level includes is the reference's (dm_control
//! `include_copy`s an included file after the including file's own content).

use mjcf::{ErrorKind, Model, Namespace, ReadError, ReadOptions};

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

/// Reads `main` with the in-memory files `files`.
fn read_with(files: &[(&str, &str)], main: &str) -> Result<Model, ReadError> {
    let mut opts = ReadOptions::new();
    for (path, text) in files {
        opts = opts.asset(path, text.as_bytes().to_vec());
    }
    opts.read_str(main)
}

/// The file and line:column of an error.
fn place(e: &ReadError) -> (String, usize, usize) {
    let file = e.file().map(|f| f.display().to_string()).unwrap_or_default();
    let pos = e.pos().map(|p| (p.line as usize, p.column as usize)).unwrap_or((0, 0));
    (file, pos.0, pos.1)
}

/// MuJoCo 4.0 takes the later value of a root default an include gives again (checked:
/// `geom_rgba` is the include's green when it comes after, the file's red when the file's
/// `<default>` comes after); reading it as a model merged afterwards refused it as an
/// `AttributeConflict`.
#[test]
fn a_root_default_an_include_gives_again_takes_the_later_value() {
    let inc = r#"<mujoco><default><geom rgba="0 1 0 1"/></default></mujoco>"#;
    let red = r#"<default><geom rgba="1 0 0 1"/></default>"#;
    let after = read_with(
        &[("inc.xml", inc)],
        &format!(r#"<mujoco>{red}<include file="inc.xml"/></mujoco>"#),
    );
    assert_eq!(setting(&after.unwrap(), "geom", "rgba"), "0 1 0 1");
    let before = read_with(
        &[("inc.xml", inc)],
        &format!(r#"<mujoco><include file="inc.xml"/>{red}</mujoco>"#),
    );
    assert_eq!(setting(&before.unwrap(), "geom", "rgba"), "1 0 0 1");
}

/// Two includes setting one setting: the later one wins, as MuJoCo reads them (one
/// merged after the other refused it as an `AttributeConflict`).
#[test]
fn two_includes_setting_one_setting_take_the_later_value() {
    let a = r#"<mujoco><option timestep="0.01"/></mujoco>"#;
    let b = r#"<mujoco><option timestep="0.02"/></mujoco>"#;
    let main = r#"<mujoco><include file="a.xml"/><include file="b.xml"/></mujoco>"#;
    let m = read_with(&[("a.xml", a), ("b.xml", b)], main).unwrap();
    assert_eq!(setting(&m, "option", "timestep"), "0.02");
}

/// A name the including file took, given again in an included file (at the root or
/// inside an element), is reported in the included file at the later tag.
#[test]
fn a_name_given_again_in_an_included_file_is_reported_at_its_tag_there() {
    let inc = "<mujoco>\n<asset>\n  <material name=\"red\"/></asset></mujoco>";
    let main = r#"<mujoco><asset><material name="red"/></asset><include file="inc.xml"/></mujoco>"#;
    let e = read_with(&[("inc.xml", inc)], main).unwrap_err();
    assert!(
        matches!(e.kind(), ErrorKind::DuplicateIdentifier { name, .. } if name == "red"),
        "{e}"
    );
    assert_eq!(place(&e), ("inc.xml".into(), 3, 3));
    let part = "<mujoco>\n  <geom name=\"g\" size=\"1\"/></mujoco>";
    let main = "<mujoco><worldbody><geom name=\"g\" size=\"1\"/>\n<include file=\"part.xml\"/></worldbody></mujoco>";
    let e = read_with(&[("part.xml", part)], main).unwrap_err();
    assert!(matches!(e.kind(), ErrorKind::DuplicateIdentifier { name, .. } if name == "g"), "{e}");
    assert_eq!(place(&e), ("part.xml".into(), 2, 3));
    // The other way round: the main file's later tag, in the main file.
    let main = "<mujoco><worldbody><include file=\"part.xml\"/>\n<geom name=\"g\" size=\"1\"/></worldbody></mujoco>";
    let e = read_with(&[("part.xml", part)], main).unwrap_err();
    assert_eq!(place(&e), (String::new(), 2, 1));
}

/// MuJoCo refuses a singleton given twice in one element ("unique element 'geom' found
/// 2 times"), an included file's content counting as the element's, and merges
/// sections given twice at the root (checked: `<option>` and `<default>` twice in one
/// file compile, both values kept).
#[test]
fn a_singleton_given_twice_in_one_element_is_refused_a_section_given_twice_merges() {
    let d = "<mujoco>\n  <geom rgba=\"0 1 0 1\"/></mujoco>";
    let class = |content: &str| {
        format!(
            r#"<mujoco><default><default class="a"><geom size="0.3"/>{content}</default></default></mujoco>"#
        )
    };
    for (main, file, pos) in [
        (class(r#"<include file="d.xml"/>"#), "d.xml", (2, 3)),
        (class("\n<geom rgba=\"0 1 0 1\"/>"), "", (2, 1)),
    ] {
        let e = read_with(&[("d.xml", d)], &main).unwrap_err();
        assert!(matches!(e.kind(), ErrorKind::DuplicateChild("geom")), "{e}");
        assert_eq!(place(&e), (file.into(), pos.0, pos.1));
    }
    // Given in two tags of the element (it is given twice at the root): merged.
    let twice = r#"<mujoco><visual><global fovy="30"/></visual><visual><global azimuth="10"/></visual>
        <default><geom rgba="1 0 0 1"/></default><default><geom size="0.2"/></default></mujoco>"#;
    let m = read_with(&[], twice).unwrap();
    assert_eq!(setting(&m, "global", "fovy"), "30");
    assert_eq!(setting(&m, "global", "azimuth"), "10");
    assert_eq!(setting(&m, "geom", "rgba"), "1 0 0 1");
    assert_eq!(setting(&m, "geom", "size"), "0.2");
}

/// An included file's elements nest at the depth of its `<include>`, so that
/// `max_depth` holds across files (the file's elements counted from its own root
/// escaped it).
#[test]
fn elements_of_an_included_file_count_at_the_depth_of_the_include() {
    let part = "<mujoco>\n  <body>\n    <body/>\n  </body>\n</mujoco>";
    let main = r#"<mujoco><worldbody><body><include file="part.xml"/></body></worldbody></mujoco>"#;
    // Root 0, worldbody 1, body 2, the file's bodies 3 and 4.
    let read = |depth| {
        ReadOptions::new()
            .asset("part.xml", part.as_bytes().to_vec())
            .max_depth(depth)
            .read_str(main)
    };
    let e = read(4).unwrap_err();
    assert!(matches!(e.kind(), ErrorKind::TooDeep(4)), "{e}");
    assert_eq!(place(&e), ("part.xml".into(), 3, 5));
    assert!(read(5).is_ok());
}

/// The compiler's folders are global in MuJoCo: a meshdir the including file sets
/// applies to the meshes an included file names (read as a model of its own, the
/// included file saw none of them and its mesh was not found).
#[test]
fn folders_the_including_file_sets_apply_to_files_an_included_file_names() {
    let robot = r#"<mujoco><asset><mesh name="a" file="a.stl"/></asset></mujoco>"#;
    let m = ReadOptions::new()
        .asset("robot.xml", robot.as_bytes().to_vec())
        .asset("assets/a.stl", b"solid m\nendsolid m\n".to_vec())
        .read_str(r#"<mujoco><compiler meshdir="assets"/><include file="robot.xml"/></mujoco>"#)
        .unwrap();
    assert!(m.find(Namespace::Mesh, "a").is_some());
}

/// References resolve across files in either order (one read, one index): renaming
/// the element renames them.
#[test]
fn references_between_files_resolve_in_either_order() {
    let inc = r#"<mujoco><asset><material name="red"/></asset><worldbody><geom name="i" size="1" material="blue"/></worldbody></mujoco>"#;
    let main = r#"<mujoco><worldbody><geom name="m" size="1" material="red"/></worldbody><include file="inc.xml"/><asset><material name="blue"/></asset></mujoco>"#;
    let m = read_with(&[("inc.xml", inc)], main).unwrap();
    let m = ["red", "blue"].iter().fold(m, |m, name| {
        let mat = m.find(Namespace::Material, name).unwrap();
        m.set(&mat, mjcf::Attrs::new().set("name", format!("{name}2"))).unwrap()
    });
    let xml = m.to_xml_string().unwrap();
    assert!(xml.contains(r#"material="red2""#), "{xml}");
    assert!(xml.contains(r#"material="blue2""#), "{xml}");
    assert!(!xml.contains(r#"material="red""#) && !xml.contains(r#"material="blue""#), "{xml}");
}

/// The element order of root-level includes is the reference's: a file's own content,
/// then each file it includes at its root (with theirs, in turn), whatever the place
/// of the include tag; content included inside an element stays in place.
#[test]
fn root_level_includes_come_after_the_including_files_own_content_as_in_dm_control() {
    let a = r#"<mujoco><include file="b.xml"/><worldbody><geom name="a" size="1"/></worldbody></mujoco>"#;
    let b = r#"<mujoco><worldbody><geom name="b" size="1"/></worldbody></mujoco>"#;
    let c = r#"<mujoco><worldbody><geom name="c" size="1"/></worldbody></mujoco>"#;
    let part = r#"<mujoco><geom name="p" size="1"/></mujoco>"#;
    let main = r#"<mujoco><include file="a.xml"/><worldbody><geom name="m1" size="1"/><include file="part.xml"/><geom name="m2" size="1"/></worldbody><include file="c.xml"/></mujoco>"#;
    let m =
        read_with(&[("a.xml", a), ("b.xml", b), ("c.xml", c), ("part.xml", part)], main).unwrap();
    let xml = m.to_xml_string().unwrap();
    let at = |n: &str| xml.find(&format!(r#"name="{n}""#)).unwrap();
    let order = ["m1", "p", "m2", "a", "b", "c"];
    assert!(order.windows(2).all(|w| at(w[0]) < at(w[1])), "{order:?} in\n{xml}");
}
