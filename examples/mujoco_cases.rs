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

use mjcf::{Model, ProblemKind, WriteOptions, element};

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
        // check() agrees with MuJoCo here (its keys fit only once merged).
        assert!(fleet.check().iter().all(|p| matches!(p.kind, ProblemKind::KeyLength { .. })));
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
    println!("wrote the cases to {}", out.display());
    Ok(())
}
