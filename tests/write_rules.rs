//! The writer's rules (issue 20 item 4; the table in `src/xml/write/mod.rs`), one test
//! each: what the rule writes, and that it reads back as its reader rule says.
//! Every test goes through [`round_trip`]: written, read back (with the files the
//! text names), the model read back writes the same text, and reads back as the
//! same model. Where a rule keeps the model (a flat model in the shape the writer
//! writes), the model read back is the model written; a composed model reads back
//! flat, its names literal (decision D13).
//!
//! The last test ties the table to this file: every test here is in the table, and
//! every rule of the table names a test here and functions that exist.

use std::collections::BTreeSet;

use mjcf::{
    AttrInput, Attrs, Element, FileAsset, Model, Namespace, ReadOptions, Value, WriteOptions,
    element,
};

fn read(xml: &str) -> Model {
    Model::from_xml_str(xml).unwrap_or_else(|e| panic!("{e}\n{xml}"))
}

/// Writes `m` with `options`, reads the text back (with the files it names) and
/// checks the round trip: the model read back writes the same text, and that text
/// reads back as the same model. Returns the text and the model read back.
fn round_trip_with(m: &Model, options: &WriteOptions) -> (String, Model) {
    let xml = m.to_xml_string_with(options).unwrap_or_else(|e| panic!("cannot write: {e}"));
    let back = read_with_files(m, &xml, options);
    let again = back.to_xml_string_with(options).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(again, xml, "read back, it writes another text");
    let twice = read_with_files(&back, &again, options);
    assert!(twice == back, "read back twice, another model:\n{again}");
    (xml, back)
}

fn round_trip(m: &Model) -> (String, Model) {
    round_trip_with(m, &WriteOptions::default())
}

fn read_with_files(m: &Model, xml: &str, options: &WriteOptions) -> Model {
    let mut read = ReadOptions::new();
    for (name, file) in m.assets(options).unwrap_or_else(|e| panic!("{e}")) {
        read = read.asset(&name, file.contents().to_vec());
    }
    read.read_str(xml).unwrap_or_else(|e| panic!("does not read back: {e}\n{xml}"))
}

/// A model of the shape the writer writes, as MJCF around `defaults` (the root
/// class's content) and `world` (the worldbody's).
fn flat(defaults: &str, world: &str) -> Model {
    read(&format!(
        r#"<mujoco model="m"><default><default class="/">{defaults}</default></default><worldbody>{world}</worldbody></mujoco>"#
    ))
}

/// A robot: a body with a named joint and an unnamed geom.
fn robot(name: &str) -> Model {
    let mut m = Model::new(name);
    let b = m.add_mut(&m.worldbody(), element!("body", name = "torso")).unwrap();
    m.add_mut(&b, element!("geom", size = [0.1])).unwrap();
    m.add_mut(&b, element!("joint", name = "hip")).unwrap();
    m
}

/// A model whose one body carries a freejoint.
fn ball() -> Model {
    let mut m = Model::new("ball");
    let b = m.add_mut(&m.worldbody(), element!("body", name = "ball")).unwrap();
    m.add_mut(&b, Element::new("freejoint")).unwrap();
    m.add_mut(&b, element!("geom", size = [0.1])).unwrap();
    m
}

fn has_name(m: &Model, ns: Namespace, name: &str) -> bool {
    m.find(ns, name).is_some()
}

/// The identifiers of the elements of `ns`, in document order.
fn identifiers(m: &Model, ns: Namespace) -> Vec<Option<String>> {
    let ids = m.find_all(ns);
    ids.iter().map(|l| m.get(l).unwrap().identifier().map(str::to_string)).collect()
}

#[test]
fn scoped_names_read_back_as_literal_names() {
    let mut scene = Model::new("arena");
    let a = scene.attach_mut(&scene.worldbody(), &robot("robot")).unwrap();
    let torso = scene.from_full_name(Namespace::Body, "robot/torso").unwrap();
    let (xml, back) = round_trip(&scene);
    assert!(xml.contains(r#"<body name="robot/torso">"#), "{xml}");
    assert!(xml.contains(r#"<joint name="robot/hip" class="robot/"/>"#), "{xml}");
    assert_eq!(scene.full_name(&torso).as_deref(), Some("robot/torso"));
    for (ns, name) in [(Namespace::Body, "robot/torso"), (Namespace::Joint, "robot/hip")] {
        assert!(has_name(&back, ns, name), "{name} is a literal name read back");
    }
    assert!(has_name(&back, Namespace::Body, &format!("{}/", a.scope())));
}

#[test]
fn automatic_names_are_forgotten_and_derived_again() {
    let m = flat(
        "",
        r#"<geom class="/" size="1"/><geom name="g" class="/" size="1"/><geom class="/" size="1"/>"#,
    );
    let (xml, back) = round_trip(&m);
    assert!(xml.contains(r#"<geom name="//unnamed_geom_0" class="/" size="1"/>"#), "{xml}");
    assert!(xml.contains(r#"<geom name="//unnamed_geom_2" class="/" size="1"/>"#), "{xml}");
    assert_eq!(identifiers(&back, Namespace::Geom), [None, Some("g".into()), None]);
    assert!(back == m, "the automatic names read back as no names");
}

#[test]
fn automatic_names_in_a_replicate_end_in_an_underscore() {
    let m = flat(
        "",
        r#"<geom class="/" size="1"/><replicate count="2" offset="1 0 0"><geom class="/" size="1"/></replicate>"#,
    );
    let (xml, back) = round_trip(&m);
    assert!(xml.contains(r#"<geom name="//unnamed_geom_1_" class="/" size="1"/>"#), "{xml}");
    assert_eq!(identifiers(&back, Namespace::Geom), [None, None]);
    assert!(back == m, "the replicated automatic name reads back as no name");
}

#[test]
fn a_composed_output_keeps_its_automatic_names() {
    let mut scene = Model::new("arena");
    scene.add_mut(&scene.worldbody(), element!("geom", size = [1])).unwrap();
    scene.attach_mut(&scene.worldbody(), &robot("robot")).unwrap();
    let (xml, back) = round_trip(&scene);
    assert!(
        xml.contains("<default>\n    <default class=\"/\"/>\n    <default class=\"robot/\"/>"),
        "{xml}"
    );
    // Counted over each model's own elements: kept as they were written.
    assert!(has_name(&back, Namespace::Geom, "//unnamed_geom_0"), "{xml}");
    assert!(has_name(&back, Namespace::Geom, "robot//unnamed_geom_0"), "{xml}");
    assert!(has_name(&back, Namespace::Default, "/"), "the class `/` stays a class");
}

#[test]
fn root_classes_share_one_wrapper() {
    let m = flat(r#"<geom rgba="1 0 0 1"/>"#, r#"<geom class="/" size="1"/>"#);
    let (xml, back) = round_trip(&m);
    assert!(
        xml.contains("<default>\n    <default class=\"/\">\n      <geom rgba=\"1 0 0 1\"/>"),
        "{xml}"
    );
    // Folded into the root class: no class named `/`.
    assert!(!has_name(&back, Namespace::Default, "/"), "{xml}");
    assert!(back == m);
    // With an attached model: its root class beside, in the same wrapper.
    let r = read(
        r#"<mujoco model="robot"><default><default class="soft"><geom rgba="0 0 1 1"/></default></default></mujoco>"#,
    );
    let mut scene = m.clone();
    scene.attach_mut(&scene.worldbody(), &r).unwrap();
    let (xml, _) = round_trip(&scene);
    assert_eq!(xml.matches("<default>").count(), 1, "{xml}");
    assert!(
        xml.contains(
            "    </default>\n    <default class=\"robot/\">\n      <default class=\"robot/soft\">"
        ),
        "{xml}"
    );
    assert!(xml.contains("  </default>\n  <worldbody>"), "{xml}");
}

#[test]
fn a_root_class_named_main_is_the_wrapper() {
    let m = read(
        r#"<mujoco model="m"><default class="main"><geom rgba="1 0 0 1"/></default><worldbody><geom class="main" size="1"/></worldbody></mujoco>"#,
    );
    let (xml, back) = round_trip(&m);
    assert!(xml.starts_with("<mujoco model=\"m\">\n  <default class=\"main\">\n    <geom rgba=\"1 0 0 1\"/>\n  </default>"), "{xml}");
    assert!(xml.contains(r#"<geom name="//unnamed_geom_0" class="main" size="1"/>"#), "{xml}");
    assert!(back == m);
    // Beside a class named `/`, an unnamed root class is the wrapper too.
    let m = read(
        r#"<mujoco model="m"><default><geom rgba="1 0 0 1"/><default class="a"><default class="/"/></default></default></mujoco>"#,
    );
    let (xml, back) = round_trip(&m);
    assert!(
        xml.contains("<default>\n    <geom rgba=\"1 0 0 1\"/>\n    <default class=\"a\">"),
        "{xml}"
    );
    assert!(back == m);
}

#[test]
fn a_lone_slash_class_in_the_main_class_stays_a_class() {
    // An unnamed root class whose one written child is the class `/` (its `<geom/>`
    // is empty): written plainly, the reader would fold `/` into the root class.
    let m = read(
        r#"<mujoco model="m"><default><geom/><default class="/"><geom rgba="0 1 0 1"/></default></default><worldbody><geom class="/" size="1"/></worldbody></mujoco>"#,
    );
    let (xml, back) = round_trip(&m);
    assert!(
        xml.contains("<default class=\"main\">\n    <default class=\"/\">\n      <geom rgba"),
        "{xml}"
    );
    assert!(has_name(&back, Namespace::Default, "/"), "{xml}");
    assert!(xml.contains(r#"<geom name="//unnamed_geom_0" class="/" size="1"/>"#), "{xml}");
}

#[test]
fn a_root_class_beside_a_class_named_slash_is_numbered() {
    let mut m = read(
        r#"<mujoco model="m"><default><geom rgba="1 0 0 1"/><default class="a"><default class="/"/></default></default><worldbody><geom size="1"/></worldbody></mujoco>"#,
    );
    m.attach_mut(&m.worldbody(), &robot("robot")).unwrap();
    // After the attachment: its automatic name counts the outermost model's geoms
    // only, which the flat model read back does not tell apart (a composed output).
    m.add_mut(&m.worldbody(), element!("geom", size = [2])).unwrap();
    let (xml, back) = round_trip(&m);
    assert!(xml.contains(r#"<geom name="//unnamed_geom_1" class="/1" size="2"/>"#), "{xml}");
    assert!(has_name(&back, Namespace::Geom, "//unnamed_geom_1"), "kept as a literal name");
    assert!(
        xml.contains("<default>\n    <default class=\"/1\">\n      <geom rgba=\"1 0 0 1\"/>"),
        "{xml}"
    );
    assert!(xml.contains(r#"<geom name="//unnamed_geom_0" class="/1" size="1"/>"#), "{xml}");
    assert!(has_name(&back, Namespace::Default, "/1") && has_name(&back, Namespace::Default, "/"));
}

#[test]
fn elements_without_a_class_name_the_root_class() {
    let m = flat(
        r#"<default class="c"><geom rgba="0 0 1 1"/></default>"#,
        r#"<geom class="/" size="1"/><geom class="c" size="1"/><site class="/"/>"#,
    );
    let (xml, back) = round_trip(&m);
    assert!(xml.contains(r#"<geom name="//unnamed_geom_0" class="/" size="1"/>"#), "{xml}");
    assert!(xml.contains(r#"<geom name="//unnamed_geom_1" class="c" size="1"/>"#), "{xml}");
    assert!(xml.contains(r#"<site name="//unnamed_site_0" class="/"/>"#), "{xml}");
    assert!(back == m);
    // An element built without a class is written with the root class's name too,
    // and reads back with the root class as its class.
    let mut built = Model::new("m");
    built.add_mut(&built.worldbody(), element!("geom", size = [1])).unwrap();
    let (xml, back) = round_trip(&built);
    assert!(xml.contains(r#"class="/""#), "{xml}");
    let g = &back.find_all(Namespace::Geom)[0];
    assert_eq!(back.get(g).unwrap().string("class"), None, "the root class has no name");
    assert!(back.get(g).unwrap().attr("class").is_some(), "{xml}");
}

#[test]
fn an_attached_model_is_outside_its_frames_childclass() {
    let m = flat(
        r#"<default class="c"><geom rgba="0 0 1 1"/></default>"#,
        r#"<body name="b" childclass="c"><geom size="1"/><site name="s"/></body>"#,
    );
    let (xml, back) = round_trip(&m);
    assert!(xml.contains(r#"<geom name="//unnamed_geom_0" size="1"/>"#), "{xml}");
    assert!(xml.contains(r#"<site name="s"/>"#), "{xml}");
    assert!(back == m);
    let mut scene = m.clone();
    let s = scene.find(Namespace::Site, "s").unwrap();
    scene.attach_mut(&s, &robot("robot")).unwrap();
    let (xml, _) = round_trip(&scene);
    assert!(xml.contains(r#"<geom name="//unnamed_geom_0" size="1"/>"#), "{xml}");
    assert!(
        xml.contains(r#"<geom name="robot//unnamed_geom_0" class="robot/" size="0.1"/>"#),
        "{xml}"
    );
}

#[test]
fn named_references_keep_their_meaning() {
    // `world` is the one world body in every scope (decision D5); `main` names the root class.
    let r = read(
        r#"<mujoco model="robot"><worldbody><body name="b"><freejoint/><geom class="main" size="1"/></body></worldbody><equality><weld body1="world" body2="b"/></equality></mujoco>"#,
    );
    let mut scene = Model::new("arena");
    scene.attach_mut(&scene.worldbody(), &r).unwrap();
    let (xml, back) = round_trip(&scene);
    assert!(xml.contains(r#"<weld name="robot//unnamed_equality_0" class="robot/" body1="world" body2="robot/b"/>"#), "{xml}");
    assert!(
        xml.contains(r#"<geom name="robot//unnamed_geom_0" class="robot/" size="1"/>"#),
        "{xml}"
    );
    let weld = &back.find_all(Namespace::Equality)[0];
    assert_eq!(back.get(weld).unwrap().string("body1"), Some("world"));
}

#[test]
fn references_to_removed_elements_are_left_out_or_refused() {
    let m = read(
        r#"<mujoco model="m"><asset><material name="red" rgba="1 0 0 1"/></asset><worldbody><body name="b"><geom size="1" material="red"/><joint name="j"/></body></worldbody><equality><joint joint1="j"/></equality></mujoco>"#,
    );
    let mat = m.find(Namespace::Material, "red").unwrap();
    let without_material = m.remove(&mat).unwrap();
    let (xml, back) = round_trip(&without_material);
    assert!(!xml.contains("material"), "{xml}");
    let g = &back.find_all(Namespace::Geom)[0];
    assert_eq!(back.get(g).unwrap().attr("material"), None);
    let j = m.find(Namespace::Joint, "j").unwrap();
    let without_joint = m.remove(&j).unwrap();
    let e = without_joint.to_xml_string().unwrap_err();
    assert!(
        matches!(&e, mjcf::WriteError::MissingRequired { tag: "joint", attribute: "joint1", .. }),
        "{e}"
    );
}

#[test]
fn empty_singletons_are_left_out_and_made_again() {
    let m = flat(
        r#"<geom/><joint/><default class="c"><site/><geom rgba="1 0 0 1"/></default>"#,
        r#"<body name="b"><geom class="/" size="1"/></body>"#,
    );
    let (xml, back) = round_trip(&m);
    assert!(!xml.contains("<joint") && !xml.contains("<site"), "{xml}");
    assert!(
        xml.contains("<default class=\"c\">\n        <geom rgba=\"1 0 0 1\"/>\n      </default>"),
        "{xml}"
    );
    assert!(back == m, "the empty singletons are made again");
}

#[test]
fn empty_sections_are_left_out_and_made_again() {
    let m = read(
        r#"<mujoco model="m"><default><default class="/"/></default><asset/><worldbody/><actuator/><sensor/></mujoco>"#,
    );
    let (xml, back) = round_trip(&m);
    assert_eq!(
        xml,
        "<mujoco model=\"m\">\n  <default>\n    <default class=\"/\"/>\n  </default>\n</mujoco>\n"
    );
    assert!(back == m);
    // A section is written once it holds something, in schema order.
    let mut one = m.clone();
    one.add_mut(&one.asset(), element!("material", name = "red")).unwrap();
    let (xml, _) = round_trip(&one);
    assert!(
        xml.contains("  <asset>\n    <material name=\"red\" class=\"/\"/>\n  </asset>\n</mujoco>"),
        "{xml}"
    );
}

#[test]
fn settings_are_written_merged() {
    let arena = read(r#"<mujoco model="arena"><option timestep="0.001"/></mujoco>"#);
    let r = read(
        r#"<mujoco model="robot"><compiler angle="radian"/><option gravity="0 0 -1"/><worldbody><body name="b"/></worldbody></mujoco>"#,
    );
    let mut scene = arena.clone();
    scene.attach_mut(&scene.worldbody(), &r).unwrap();
    let (xml, back) = round_trip(&scene);
    assert!(xml.contains(r#"<compiler angle="radian"/>"#), "{xml}");
    assert!(xml.contains(r#"<option timestep="0.001" gravity="0 0 -1"/>"#), "{xml}");
    assert_eq!(xml.matches("<option").count(), 1, "{xml}");
    let option = back.child(&back.root(), "option").unwrap();
    assert_eq!(back.floats(&option, "gravity").unwrap(), [0.0, 0.0, -1.0]);
}

#[test]
fn merged_keys_read_back_as_keys_that_fit() {
    let arena = read(
        r#"<mujoco model="arena"><worldbody><body name="door"><joint name="hinge"/><geom size="1"/></body></worldbody><keyframe><key name="home" qpos="0.5"/></keyframe></mujoco>"#,
    );
    let mut ball = ball();
    ball.add_mut(
        &ball.section("keyframe").unwrap(),
        element!("key", name = "home", qpos = [0, 0, 1, 1, 0, 0, 0]),
    )
    .unwrap();
    let mut scene = arena.clone();
    scene.attach_mut(&scene.worldbody(), &ball).unwrap();
    let merged = WriteOptions { merge_keyframes: true, ..WriteOptions::default() };
    let (xml, back) = round_trip_with(&scene, &merged);
    assert!(xml.contains(r#"<key name="home" qpos="0.5 0 0 1 1 0 0 0"/>"#), "{xml}");
    assert_eq!(xml.matches("<key ").count(), 1, "{xml}");
    assert_eq!(back.find_all(Namespace::Key).len(), 1);
    assert!(back.check().is_empty(), "{:?}", back.check());
    // Written without merging, the keys are each model's.
    let plain = scene.to_xml_string().unwrap();
    assert_eq!(plain.matches("<key ").count(), 2, "{plain}");
}

#[test]
fn an_attachment_frame_reads_back_as_a_body() {
    let mut scene = Model::new("arena");
    let s =
        scene.add_mut(&scene.worldbody(), element!("site", name = "s", pos = [1, 2, 3])).unwrap();
    let a = scene.attach_mut(&s, &robot("robot")).unwrap();
    scene.add_mut(a.frame(), element!("joint", name = "slide", type = "slide")).unwrap();
    let (xml, back) = round_trip(&scene);
    assert!(xml.contains("<body name=\"robot/\" pos=\"1 2 3\">\n      <joint name=\"robot/slide/\" class=\"/\" type=\"slide\"/>"), "{xml}");
    let frame = back.find(Namespace::Body, "robot/").unwrap();
    assert_eq!(back.floats(&frame, "pos").unwrap(), [1.0, 2.0, 3.0]);
    assert!(back.get(&frame).unwrap().tag() == "body" && !back.get(&frame).unwrap().is_frame());
}

#[test]
fn a_frame_over_free_bodies_is_written_as_a_frame() {
    let mut scene = Model::new("arena");
    scene.attach_mut(&scene.worldbody(), &ball()).unwrap();
    let (xml, back) = round_trip(&scene);
    assert!(
        xml.contains("<frame name=\"ball/\">\n      <body name=\"ball/ball\">\n        <freejoint"),
        "{xml}"
    );
    assert!(back.check().is_empty(), "{:?}", back.check());
    // In a `<frame>` in the world (MuJoCo's own, or an attachment frame written
    // so), still in the world.
    let mut framed = read(
        r#"<mujoco model="arena"><worldbody><frame name="f" pos="1 0 0"><site name="s"/></frame></worldbody></mujoco>"#,
    );
    let s = framed.find(Namespace::Site, "s").unwrap();
    framed.attach_mut(&s, &ball()).unwrap();
    let (xml, back) = round_trip(&framed);
    assert!(xml.contains("<frame name=\"f\" pos=\"1 0 0\">\n      <site name=\"s\" class=\"/\"/>\n      <frame name=\"ball/\">"), "{xml}");
    assert!(back.check().is_empty(), "{:?}", back.check());
    let mut nested = ball();
    nested.attach_mut(&nested.worldbody(), &ball()).unwrap();
    let mut outer = Model::new("outer");
    outer.attach_mut(&outer.worldbody(), &nested).unwrap();
    let (xml, back) = round_trip(&outer);
    assert!(xml.contains("<frame name=\"ball/\">"), "{xml}");
    assert!(xml.contains("<frame name=\"ball/ball/\">"), "{xml}");
    assert!(back.check().is_empty(), "{:?}", back.check());
    // Free bodies at the attached model's world level but not among its worldbody's
    // children (MuJoCo 4.0 refuses a free joint below a body: "free joint can only
    // be used on top level"): inside a MuJoCo `<frame>`, a `<replicate>`, an
    // attachment of its own that holds no other body, or free by a default class.
    let in_frame = read(
        r#"<mujoco model="p"><worldbody><frame pos="0 0 1"><body name="b"><freejoint/><geom size=".1"/></body></frame></worldbody></mujoco>"#,
    );
    let in_replicate = read(
        r#"<mujoco model="p"><worldbody><replicate count="2" offset="1 0 0"><body name="b"><freejoint/><geom size=".1"/></body></replicate></worldbody></mujoco>"#,
    );
    let by_class = read(
        r#"<mujoco model="p"><default><default class="free"><joint type="free"/></default></default><worldbody><frame childclass="free"><body name="b"><joint/><geom size=".1"/></body></frame></worldbody></mujoco>"#,
    );
    let mut holder = Model::new("holder");
    holder.attach_mut(&holder.worldbody(), &ball()).unwrap();
    for (what, part) in
        [("frame", in_frame), ("replicate", in_replicate), ("class", by_class), ("nested", holder)]
    {
        let mut scene = Model::new("arena");
        scene.attach_mut(&scene.worldbody(), &part).unwrap();
        let scope = part.name();
        let (xml, back) = round_trip(&scene);
        assert!(xml.contains(&format!("<frame name=\"{scope}/\">")), "{what}: {xml}");
        assert!(back.check().is_empty(), "{what}: {:?}", back.check());
    }
    // A free body below a body is no world-level body: the frame stays a body.
    let below = read(
        r#"<mujoco model="p"><worldbody><body name="a"><body name="b"><freejoint/><geom size=".1"/></body></body></worldbody></mujoco>"#,
    );
    let mut scene = Model::new("arena");
    scene.attach_mut(&scene.worldbody(), &below).unwrap();
    assert!(scene.to_xml_string().unwrap().contains("<body name=\"p/\">"));
    // A frame that moves is a body (and its model's freejoint is then MuJoCo's to
    // refuse, as the reference writes it).
    let mut moving = Model::new("arena");
    let a = moving.attach_mut(&moving.worldbody(), &ball()).unwrap();
    moving.add_mut(a.frame(), element!("joint", name = "j")).unwrap();
    let xml = moving.to_xml_string().unwrap();
    assert!(xml.contains("<body name=\"ball/\">"), "{xml}");
    // Not in the world: a body.
    let mut deep = Model::new("arena");
    let b = deep.add_mut(&deep.worldbody(), element!("body", name = "b")).unwrap();
    let s = deep.add_mut(&b, element!("site", name = "s")).unwrap();
    deep.attach_mut(&s, &ball()).unwrap();
    let xml = deep.to_xml_string().unwrap();
    assert!(xml.contains("<body name=\"ball/\">"), "{xml}");
}

#[test]
fn files_read_back_under_their_names() {
    let stl = FileAsset::new("cube", ".stl", b"solid cube\nendsolid cube\n".to_vec());
    let mut m = Model::new("m");
    let mesh =
        Attrs::new().set("name", "cube").set("file", AttrInput::Value(Value::File(stl.clone())));
    m.add_mut(&m.asset(), Element::new("mesh").attrs(mesh)).unwrap();
    let (xml, back) = round_trip(&m);
    assert!(xml.contains(&format!(r#"file="cube-{}.stl""#, stl.sha1_hex())), "{xml}");
    let file =
        |m: &Model| match m.get(&m.find(Namespace::Mesh, "cube").unwrap()).unwrap().attr("file") {
            Some(Value::File(f)) => f.clone(),
            other => panic!("{other:?}"),
        };
    assert_eq!(file(&back), stl, "read back as `cube.stl`");
    let plain = WriteOptions { filename_with_hash: false, ..WriteOptions::default() };
    let (xml, back) = round_trip_with(&m, &plain);
    assert!(xml.contains(r#"file="cube.stl""#), "{xml}");
    assert_eq!(file(&back), stl);
}

#[test]
fn base_paths_are_not_written() {
    let stl = b"solid cube\nendsolid cube\n".to_vec();
    let m = ReadOptions::new()
        .asset("meshes/cube.stl", stl.clone())
        .read_str(r#"<mujoco model="m"><compiler meshdir="meshes"/><asset><mesh name="cube" file="cube.stl"/></asset></mujoco>"#)
        .unwrap();
    let (xml, back) = round_trip(&m);
    assert!(!xml.contains("meshdir") && !xml.contains("<compiler"), "{xml}");
    let f = back.get(&back.find(Namespace::Mesh, "cube").unwrap()).unwrap();
    assert!(
        matches!(f.attr("file"), Some(Value::File(f)) if f.contents() == stl && f.stem() == "cube")
    );
}

#[test]
fn an_unnamed_model_reads_back_unnamed() {
    let mut m = Model::new("m");
    m.clear_attr_mut(&m.root(), "model").unwrap();
    let (xml, back) = round_trip(&m);
    assert!(xml.starts_with("<mujoco model=\"unnamed_model\">"), "{xml}");
    assert_eq!(back.name(), "unnamed_model");
    assert_eq!(read("<mujoco/>").name(), "unnamed_model");
}

#[test]
fn names_with_markup_characters_read_back() {
    let name = "a&b<c>\"d\" é\tz";
    let m = flat("", &format!(r#"<body name="{}"/>"#, "a&amp;b&lt;c&gt;&quot;d&quot; &#233;&#9;z"));
    let (xml, back) = round_trip(&m);
    assert!(xml.contains(r#"<body name="a&amp;b&lt;c&gt;&quot;d&quot; &#233;&#9;z"/>"#), "{xml}");
    assert!(has_name(&back, Namespace::Body, name));
    assert!(back == m);
    // A character XML cannot hold (`Model::new` takes any name) is refused.
    let e = Model::new("a\u{1}").to_xml_string().unwrap_err();
    assert!(matches!(e, mjcf::WriteError::InvalidCharacter { character: '\u{1}', .. }), "{e}");
}

/// The table of rules in `src/xml/write/mod.rs` and this file agree: every test here is
/// one rule's test, every rule names a test here, and every function a rule names
/// exists where the table says.
#[test]
fn the_rule_table_lists_every_rule_with_its_test() {
    let root = env!("CARGO_MANIFEST_DIR");
    let read = |p: &str| std::fs::read_to_string(format!("{root}/{p}")).unwrap();
    let (doc, tests, policy) =
        (read("src/xml/write/mod.rs"), read("tests/write_rules.rs"), read("src/xml/rules.rs"));
    let rows: Vec<Vec<&str>> = doc
        .lines()
        .filter_map(|l| l.strip_prefix("//! | "))
        .skip(1)
        .map(|r| r.split(" | ").collect())
        .collect();
    assert!(rows.len() >= 20, "{} rows", rows.len());
    let named: BTreeSet<&str> =
        rows.iter().map(|r| r[4].trim_end_matches(" |").trim_matches('`')).collect();
    let here: BTreeSet<&str> = tests
        .split("#[test]\nfn ")
        .skip(1)
        .filter_map(|t| t.split('(').next())
        .filter(|t| *t != "the_rule_table_lists_every_rule_with_its_test")
        .collect();
    assert_eq!(named, here, "the table's tests and this file's");
    for row in &rows {
        for f in row[1].split(", ") {
            let Some(f) = f.strip_prefix("[`policy::").and_then(|f| f.strip_suffix("`]")) else {
                continue;
            };
            // Defined there, or re-exported there from the layer that decides it (the
            // model's `frame_keeps_bodies_top_level`, which check() asks too).
            let reexported = policy.lines().any(|l| {
                l.trim_start().starts_with("pub(crate) use crate::model::") && l.contains(f)
            });
            assert!(
                policy.contains(&format!("fn {f}("))
                    || policy.contains(&format!("fn {f}<"))
                    || reexported,
                "policy::{f}"
            );
        }
    }
}
