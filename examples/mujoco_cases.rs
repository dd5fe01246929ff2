//! Writes models that test what MuJoCo must see, each with what to expect, for
//! `tools/mujoco_cases.py` (which compiles every one and checks counts, names and
//! numbers).
//!
//! ```text
//! cargo run --example mujoco_cases -- OUT
//! ```
//!
//! Each case is `OUT/<name>.xml` and `OUT/<name>.expect.json`: `{"field": value}`
//! pairs, where a field is a count (`nbody`), a name list (`body_names`), or an array
//! of the compiled model with indices (`actuator_gainprm[0][0]`).

use std::path::Path;

use mjcf::{AdviceKind, Model, ProblemKind, WriteOptions, element};

fn write(
    out: &Path,
    name: &str,
    m: &Model,
    expect: &str,
) -> Result<(), Box<dyn std::error::Error>> {
    write_with(out, name, m, expect, &WriteOptions::default())
}

fn write_with(
    out: &Path,
    name: &str,
    m: &Model,
    expect: &str,
    options: &WriteOptions,
) -> Result<(), Box<dyn std::error::Error>> {
    let xml = m.to_xml_string_with(options)?;
    std::fs::write(out.join(format!("{name}.xml")), &xml)?;
    std::fs::write(out.join(format!("{name}.expect.json")), expect)?;
    // What the written text reads back as must compile the same (names with `/`).
    let back = Model::from_xml_str(&xml)?;
    std::fs::write(out.join(format!("{name}.readback.xml")), back.to_xml_string()?)?;
    std::fs::write(out.join(format!("{name}.readback.expect.json")), expect)?;
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::path::PathBuf::from(std::env::args().nth(1).ok_or("usage: mujoco_cases OUT")?);
    std::fs::create_dir_all(&out)?;

    // D11: actuator defaults of a class apply in document order: `<velocity>` then
    // `<position>` leaves the position gains (kp 4000, kv 400), not the velocity's.
    let m = Model::from_xml_str(
        r#"<mujoco model="d11">
             <default><default class="arm"><velocity kv="1"/><position kp="4000" kv="400"/></default></default>
             <worldbody><body name="b"><joint name="j" axis="0 0 1"/><geom size="0.1"/></body></worldbody>
             <actuator><position name="p" joint="j" class="arm"/></actuator>
           </mujoco>"#,
    )?;
    write(
        &out,
        "d11_actuator_default_order",
        &m,
        r#"{"nu": 1, "actuator_gainprm[0][0]": 4000, "actuator_biasprm[0][1]": -4000, "actuator_biasprm[0][2]": -400}"#,
    )?;

    // D11 through a root-level include (issue 19 item 3): the included file's root
    // class holds `<motor>`, `<velocity>`, `<position>`, in that order; MuJoCo applies
    // them in that order, so the position gains (kp 4000, kv 400) stand. Both the file
    // and what it is written as compile so.
    std::fs::write(
        out.join("d11_defaults.xml"),
        r#"<mujoco><default><motor gear="2"/><velocity kv="1"/><position kp="4000" kv="400"/></default></mujoco>"#,
    )?;
    std::fs::write(
        out.join("d11_through_include.xml"),
        r#"<mujoco model="d11i"><include file="d11_defaults.xml"/>
             <worldbody><body name="b"><joint name="j" axis="0 0 1"/><geom size="0.1"/></body></worldbody>
             <actuator><position name="p" joint="j"/></actuator></mujoco>"#,
    )?;
    let expect = r#"{"nu": 1, "actuator_gainprm[0][0]": 4000, "actuator_biasprm[0][1]": -4000, "actuator_biasprm[0][2]": -400, "actuator_gear[0][0]": 2}"#;
    std::fs::write(out.join("d11_through_include.expect.json"), expect)?;
    let m = Model::from_path(out.join("d11_through_include.xml"))?;
    std::fs::write(out.join("d11_through_include.readback.xml"), m.to_xml_string()?)?;
    std::fs::write(out.join("d11_through_include.readback.expect.json"), expect)?;

    // D9: a root default class named `main` (MuJoCo's own name for it).
    let m = Model::from_xml_str(
        r#"<mujoco model="d9"><default class="main"><geom rgba="1 0 0 1"/></default>
             <worldbody><geom class="main" size="1"/><geom size="1"/></worldbody></mujoco>"#,
    )?;
    write(
        &out,
        "d9_root_class_main",
        &m,
        r#"{"ngeom": 2, "geom_rgba[0][1]": 0, "geom_rgba[1][1]": 0}"#,
    )?;

    // D10: a child whose top-level body carries a freejoint, attached with a frame that
    // neither moves nor has mass: the body stays top-level, its freejoint intact.
    let mut ball = Model::new("ball");
    let body = ball.add_mut(&ball.worldbody(), element!("body", name = "ball", pos = [0, 0, 1]))?;
    ball.add_mut(&body, element!("freejoint", name = "free"))?;
    ball.add_mut(&body, element!("geom", size = [0.1]))?;
    let mut scene = Model::new("scene");
    let spot =
        scene.add_mut(&scene.worldbody(), element!("site", name = "spot", pos = [1, 2, 0]))?;
    scene.attach_mut(&spot, &ball)?;
    scene.attach_mut(&scene.worldbody(), &ball)?;
    write(
        &out,
        "d10_free_bodies_stay_top_level",
        &scene,
        r#"{"nbody": 3, "njnt": 2, "body_names": ["world", "ball/ball", "ball_1/ball"],
            "joint_names": ["ball/free", "ball_1/free"], "jnt_type[0]": 0, "body_parentid[1]": 0,
            "body_parentid[2]": 0, "qpos0[0]": 1, "qpos0[1]": 2, "qpos0[2]": 1}"#,
    )?;
    // Composed keyframes: four robots on free frames, three with a `home` key of their
    // own (hinge at 0.1, 0.2, 0.3; control 1, 2, 3), the fourth without one (MuJoCo's
    // defaults: hinge 0, control 0); the arena's part is each frame's pose.
    let mut fleet = Model::new("fleet");
    for i in 0..4 {
        let mut robot = Model::new("robot");
        let b = robot
            .add_mut(&robot.worldbody(), element!("body", name = "b", pos = [0.0, 0.0, 0.5]))?;
        robot.add_mut(&b, element!("joint", name = "hinge", axis = [0, 0, 1]))?;
        robot.add_mut(&b, element!("geom", size = [0.1]))?;
        robot.add_mut(&robot.actuator(), element!("motor", name = "m", joint = "hinge"))?;
        if i < 3 {
            let home = element!(
                "key",
                name = "home",
                qpos = [0.1 * (i + 1) as f64],
                ctrl = [(i + 1) as f64]
            );
            robot.add_mut(&robot.section("keyframe").ok_or("no keyframe section")?, home)?;
        }
        let site = element!("site", name = format!("s{i}"), pos = [i as f64, 0.0, 1.0]);
        let site = fleet.add_mut(&fleet.worldbody(), site)?;
        let a = fleet.attach_mut(&site, &robot)?;
        fleet.add_mut(a.frame(), element!("freejoint"))?;
        // The robot's body moves on its hinge: the free frame needs mass of its own.
        let inertial = element!("inertial", pos = [0, 0, 0], mass = 0.1, diaginertia = [1e-3; 3]);
        fleet.add_mut(a.frame(), inertial)?;
        // MuJoCo compiles it (check() is empty), but advice() says each robot's key,
        // written as it is, would set the composed model's first joints (MuJoCo pads
        // it); merged, it fits and there is no advice.
        assert!(fleet.check().is_empty());
        assert!(fleet.advice().iter().all(|a| matches!(a.kind, AdviceKind::UncomposedKey)));
        let merged = WriteOptions { merge_keyframes: true, ..WriteOptions::default() };
        assert!(fleet.check_with(&merged).is_empty() && fleet.advice_with(&merged).is_empty());
    }
    let mut massless = fleet.clone();
    let frame = massless.frame("robot")?;
    let inertial =
        massless.get(&frame)?.children().find(|c| c.tag() == "inertial").ok_or("inertial")?;
    massless.remove_mut(&inertial.loc())?;
    let massless =
        massless.check().into_iter().filter(|p| p.kind == ProblemKind::MasslessMovingBody);
    assert_eq!(massless.count(), 1, "a free frame over a hinged body has no mass of its own");
    let merge = WriteOptions { merge_keyframes: true, ..WriteOptions::default() };
    write_with(
        &out,
        "keys_composed",
        &fleet,
        r#"{"nkey": 1, "key_names": ["home"], "nq": 32,
            "key_qpos[0][0]": 0, "key_qpos[0][2]": 1, "key_qpos[0][3]": 1, "key_qpos[0][7]": 0.1,
            "key_qpos[0][8]": 1, "key_qpos[0][15]": 0.2, "key_qpos[0][23]": 0.3,
            "key_qpos[0][24]": 3, "key_qpos[0][31]": 0,
            "key_ctrl[0][0]": 1, "key_ctrl[0][1]": 2, "key_ctrl[0][2]": 3, "key_ctrl[0][3]": 0}"#,
        &merge,
    )?;
    // An `<include>` inside a body: the included file's elements in its place (a
    // frame and a site, with the class of the including file's default).
    std::fs::write(
        out.join("include_part.xml"),
        r#"<mujoco><geom name="g2" size="0.2"/><site name="s2"/></mujoco>"#,
    )?;
    let main = r#"<mujoco model="inc"><default><geom rgba="0 1 0 1"/></default><worldbody>
        <body name="b"><joint/><include file="include_part.xml"/><geom name="g1" size="0.1"/></body>
        </worldbody></mujoco>"#;
    std::fs::write(out.join("include_in_body.xml"), main)?;
    let expect = r#"{"ngeom": 2, "geom_names": ["g2", "g1"], "nsite": 1, "geom_rgba[0][1]": 1}"#;
    std::fs::write(out.join("include_in_body.expect.json"), expect)?;
    let m = Model::from_path(out.join("include_in_body.xml"))?;
    std::fs::write(out.join("include_in_body.readback.xml"), m.to_xml_string()?)?;
    std::fs::write(out.join("include_in_body.readback.expect.json"), expect)?;
    // A robot file's compiler folder applies to the scene's files after the include
    // (MuJoCo's compiler settings are global).
    let mesh = std::fs::read(
        "tests/conformance/cases/real_02_jaco_arm_with_hand/meshes_decimated/base.stl",
    )?;
    std::fs::create_dir_all(out.join("assets"))?;
    std::fs::write(out.join("assets/a.stl"), &mesh)?;
    std::fs::write(out.join("assets/b.stl"), &mesh)?;
    std::fs::write(
        out.join("include_robot.xml"),
        r#"<mujoco model="robot"><compiler meshdir="assets"/><asset><mesh name="a" file="a.stl"/></asset>
        <worldbody><body name="r"><geom type="mesh" mesh="a"/></body></worldbody></mujoco>"#,
    )?;
    std::fs::write(
        out.join("include_meshdir.xml"),
        r#"<mujoco model="scene"><include file="include_robot.xml"/><asset><mesh name="b" file="b.stl"/></asset>
        <worldbody><geom type="mesh" mesh="b"/></worldbody></mujoco>"#,
    )?;
    let expect = r#"{"nmesh": 2, "ngeom": 2}"#;
    std::fs::write(out.join("include_meshdir.expect.json"), expect)?;
    let m = Model::from_path(out.join("include_meshdir.xml"))?;
    // Written out with its files beside it (their written names).
    m.export(&out, "include_meshdir.readback.xml", &WriteOptions::default())?;
    std::fs::write(out.join("include_meshdir.readback.expect.json"), expect)?;
    // An asset `<model>` whose file names a mesh of its own (in its `meshdir`),
    // attached with `<attach>`: exported, the model file comes with its mesh, at its
    // path relative to it, and MuJoCo loads the folder with no asset map.
    let source = out.join("model_source");
    std::fs::create_dir_all(source.join("sub/assets"))?;
    std::fs::write(source.join("sub/assets/model_mesh.stl"), &mesh)?;
    std::fs::write(
        source.join("sub/child.xml"),
        r#"<mujoco model="child"><compiler meshdir="assets"/><asset><mesh name="m" file="model_mesh.stl"/></asset>
        <worldbody><body name="cb"><geom type="mesh" mesh="m"/></body></worldbody></mujoco>"#,
    )?;
    std::fs::write(
        source.join("parent.xml"),
        r#"<mujoco model="parent"><asset><model name="c" file="sub/child.xml"/></asset>
        <worldbody><attach model="c" body="cb" prefix="c1-"/><frame pos="1 0 0"><attach model="c" body="cb" prefix="c2-"/></frame></worldbody></mujoco>"#,
    )?;
    let m = Model::from_path(source.join("parent.xml"))?;
    m.export(&out, "model_export.xml", &WriteOptions::default())?;
    std::fs::write(
        out.join("model_export.expect.json"),
        r#"{"nmesh": 2, "body_names": ["world", "c1-cb", "c2-cb"], "body_pos[2][0]": 1}"#,
    )?;
    // Attached into a scene, the asset model and its prefixes take the scope.
    let mut scene = Model::new("scene");
    scene.attach_mut(&scene.worldbody(), &m)?;
    scene.export(&out, "model_attached.xml", &WriteOptions::default())?;
    std::fs::write(
        out.join("model_attached.expect.json"),
        r#"{"nmesh": 2, "body_names": ["world", "parent/", "parent/c1-cb", "parent/c2-cb"]}"#,
    )?;
    names(&out)?;
    println!("wrote the cases to {}", out.display());
    Ok(())
}

/// A small robot: a body `torso` with an unnamed geom and a hinge `hip`.
fn small_robot(name: &str) -> Result<Model, Box<dyn std::error::Error>> {
    let mut m = Model::new(name);
    let b = m.add_mut(&m.worldbody(), element!("body", name = "torso"))?;
    m.add_mut(&b, element!("geom", size = [0.1]))?;
    m.add_mut(&b, element!("joint", name = "hip"))?;
    Ok(m)
}

/// An inertial for a moving frame.
fn frame_inertial() -> mjcf::Element {
    element!("inertial", pos = [0, 0, 0], mass = 0.1, diaginertia = [1e-3; 3])
}

/// The names written (issue 19 items 2, 5, 8; decision D14), as MuJoCo names them.
fn names(out: &Path) -> Result<(), Box<dyn std::error::Error>> {
    // Two unnamed joints on one frame: the first takes the frame's name, the second
    // its automatic name.
    let mut scene = Model::new("arena");
    let a = scene.attach_mut(&scene.worldbody(), &small_robot("robot")?)?;
    scene.add_mut(a.frame(), element!("joint", type = "hinge"))?;
    scene.add_mut(a.frame(), element!("joint", type = "slide"))?;
    scene.add_mut(a.frame(), frame_inertial())?;
    write(
        out,
        "names_frame_unnamed_joints",
        &scene,
        r#"{"njnt": 3, "joint_names": ["robot/", "//unnamed_joint_1", "robot/hip"], "jnt_type[1]": 2}"#,
    )?;
    // D14: a joint `a` on the frame of `hand`, and the unnamed joint of the frame of
    // the attachment `a` inside `hand` (both `hand/a/` as dm_control writes them).
    let mut hand = Model::new("hand");
    let inner = hand.attach_mut(&hand.worldbody(), &small_robot("a")?)?;
    hand.add_mut(inner.frame(), element!("joint"))?;
    hand.add_mut(inner.frame(), frame_inertial())?;
    let mut arm = Model::new("arm");
    let h = arm.attach_mut(&arm.worldbody(), &hand)?;
    arm.add_mut(h.frame(), element!("joint", name = "a"))?;
    arm.add_mut(h.frame(), frame_inertial())?;
    write(
        out,
        "names_d14_frame_joint_named_as_a_scope",
        &arm,
        r#"{"njnt": 3, "joint_names": ["hand/a/", "hand//unnamed_joint_0", "hand/a/hip"]}"#,
    )?;
    // A composed model read back (literal names `robot/`, `robot/torso`, the class
    // `robot/`) with `robot` attached again: the scope `robot_1`.
    let mut scene = Model::new("arena");
    scene.add_mut(&scene.worldbody(), element!("geom", size = [1]))?;
    scene.attach_mut(&scene.worldbody(), &small_robot("robot")?)?;
    let mut back = Model::from_xml_str(&scene.to_xml_string()?)?;
    back.attach_mut(&back.worldbody(), &small_robot("robot")?)?;
    // And an unnamed geom before the literal `//unnamed_geom_0`.
    back.insert_mut(&back.worldbody(), 0, element!("geom", size = [0.5]))?;
    write(
        out,
        "names_attached_into_a_composed_model_read_back",
        &back,
        r#"{"nbody": 5, "body_names": ["world", "robot/", "robot/torso", "robot_1/", "robot_1/torso"],
            "geom_names": ["//unnamed_geom_0~1", "//unnamed_geom_0", "robot//unnamed_geom_0", "robot_1//unnamed_geom_0"],
            "joint_names": ["robot/hip", "robot_1/hip"]}"#,
    )?;
    // A class named `/` inside another class (MuJoCo compiles it): the root class is
    // MuJoCo's main class alone, `/1` beside an attached model's root class, whose
    // geoms keep MuJoCo's default colour (0.5, 0.5, 0.5, 1).
    let slash = Model::from_xml_str(
        r#"<mujoco model="m"><default><geom rgba="1 0 0 1"/>
             <default class="a"><default class="/"><geom rgba="0 1 0 1"/></default></default></default>
           <worldbody><geom size="1"/><geom class="/" size="1"/></worldbody></mujoco>"#,
    )?;
    let expect =
        r#""geom_rgba[0][0]": 1, "geom_rgba[0][1]": 0, "geom_rgba[1][0]": 0, "geom_rgba[1][1]": 1"#;
    write(out, "names_class_slash", &slash, &format!("{{{expect}}}"))?;
    let mut with = slash.clone();
    with.attach_mut(&with.worldbody(), &small_robot("robot")?)?;
    write(
        out,
        "names_class_slash_attached",
        &with,
        &format!(r#"{{{expect}, "geom_rgba[2][0]": 0.5, "geom_rgba[2][1]": 0.5}}"#),
    )?;
    // A root class named `main` (decision D9) with an attached model: the robot's geom keeps
    // MuJoCo's default colour.
    let mut main = Model::from_xml_str(
        r#"<mujoco model="arena"><default class="main"><geom rgba="1 0 0 1"/></default>
           <worldbody><geom size="1"/></worldbody></mujoco>"#,
    )?;
    main.attach_mut(&main.worldbody(), &small_robot("robot")?)?;
    write(
        out,
        "names_root_main_attached",
        &main,
        r#"{"ngeom": 2, "geom_rgba[0][1]": 0, "geom_rgba[1][0]": 0.5, "geom_rgba[1][1]": 0.5}"#,
    )?;
    // Unnamed elements in a `<replicate>`, and an attached model at a site in it:
    // MuJoCo appends the copy's number to the written names.
    let mut rep = Model::from_xml_str(
        r#"<mujoco model="arena"><worldbody><geom size="1"/>
           <replicate count="2" offset="1 0 0"><geom size="0.1"/><site name="s"/></replicate>
           </worldbody></mujoco>"#,
    )?;
    let site = rep.find(mjcf::Namespace::Site, "s").ok_or("no site")?;
    rep.attach_mut(&site, &small_robot("robot")?)?;
    let names: Vec<String> =
        rep.find_all(mjcf::Namespace::Geom).iter().filter_map(|l| rep.full_name(l)).collect();
    assert_eq!(names, ["//unnamed_geom_0", "//unnamed_geom_1_", "robot//unnamed_geom_0_"]);
    write(
        out,
        "names_replicated",
        &rep,
        r#"{"ngeom": 5, "geom_names": ["//unnamed_geom_0", "//unnamed_geom_1_0", "//unnamed_geom_1_1",
            "robot//unnamed_geom_0_0", "robot//unnamed_geom_0_1"]}"#,
    )?;
    Ok(())
}
