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

use mjcf::{Model, element};

fn write(
    out: &Path,
    name: &str,
    m: &Model,
    expect: &str,
) -> Result<(), Box<dyn std::error::Error>> {
    std::fs::write(out.join(format!("{name}.xml")), m.to_xml_string()?)?;
    std::fs::write(out.join(format!("{name}.expect.json")), expect)?;
    if name.starts_with("d10") {
        // Not yet: the reader does not know MuJoCo's `<frame>`, which this output holds.
        return Ok(());
    }
    // What the written text reads back as must compile the same (names with `/`).
    let back = Model::from_xml_str(&m.to_xml_string()?)?;
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
    println!("wrote the cases to {}", out.display());
    Ok(())
}
