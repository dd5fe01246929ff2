//! MuJoCo judges `Model::attach_in` (attaching at a body or a `<frame>`): the composed
//! model compiles, and every body of the attached model lands where the same model
//! written by hand inside that body (or frame) puts it, for turned and shifted
//! bodies and frames, at the world's level and inside an attached model.

use crate::support;

use std::collections::BTreeMap;

use mjcf::{Model, Namespace};
use mjcf_mujoco::{ObjKind, Physics};
use support::mujoco;

const ARM: &str = r#"<mujoco model="arm">
  <worldbody>
    <body name="base" pos="0.1 0.2 0.3" euler="0 0 30">
      <joint name="shoulder" axis="0 1 0"/>
      <geom size="0.05"/>
      <body name="link" pos="0 0 0.4" quat="0.9 0.1 0.2 0.3"><joint name="elbow"/><geom size="0.03"/></body>
    </body>
  </worldbody>
</mujoco>"#;

/// The host: a turned and shifted body, a `<frame>` inside another body.
const HOST: &str = r#"<mujoco model="host">
  <worldbody>
    <body name="table" pos="1 2 0.8" axisangle="0 0 1 40">
      <geom type="box" size="0.5 0.5 0.02"/>
      <body name="mount" pos="0.2 0 0.1" xyaxes="0 1 0 -1 0 0"/>
      <frame name="corner" pos="-0.3 0.3 0" euler="10 0 0"/>
    </body>
  </worldbody>
</mujoco>"#;

/// The arm's bodies and joints, as written inside another element by hand (names
/// scoped as the writer scopes them).
const ARM_INSIDE: &str = r#"<body name="arm/"><body name="arm/base" pos="0.1 0.2 0.3" euler="0 0 30">
      <joint name="arm/shoulder" axis="0 1 0"/>
      <geom size="0.05"/>
      <body name="arm/link" pos="0 0 0.4" quat="0.9 0.1 0.2 0.3"><joint name="arm/elbow"/><geom size="0.03"/></body>
    </body></body>"#;

/// World positions and orientations of the named bodies after `mj_forward`.
fn poses(xml: &str, bodies: &[&str]) -> Vec<(String, Vec<f64>)> {
    let compiled =
        mujoco().compile_xml(xml, &BTreeMap::new()).unwrap_or_else(|e| panic!("{e}\n{xml}"));
    let mut physics = Physics::new(&compiled).unwrap();
    physics.forward().unwrap();
    let (xpos, xquat) =
        (physics.data("xpos").unwrap().to_vec(), physics.data("xquat").unwrap().to_vec());
    bodies
        .iter()
        .map(|b| {
            let id = compiled.id(ObjKind::Body, b).unwrap_or_else(|| panic!("no body {b}"));
            let mut v = xpos[3 * id..3 * id + 3].to_vec();
            v.extend_from_slice(&xquat[4 * id..4 * id + 4]);
            (b.to_string(), v)
        })
        .collect()
}

fn assert_close(a: &[(String, Vec<f64>)], b: &[(String, Vec<f64>)]) {
    for ((name, x), (_, y)) in a.iter().zip(b) {
        let d = x.iter().zip(y).map(|(p, q)| (p - q).abs()).fold(0.0, f64::max);
        assert!(d < 1e-12, "{name}: {x:?} != {y:?}");
    }
}

#[test]
#[ignore = "needs MuJoCo (MUJOCO_LIB); run by .ci/run"]
fn a_model_attached_in_a_body_or_frame_lands_where_mujoco_puts_it_written_there() {
    let host = Model::from_xml_str(HOST).unwrap();
    let arm = Model::from_xml_str(ARM).unwrap();
    let bodies = ["arm/base", "arm/link"];
    let geom = "<geom type=\"box\" size=\"0.5 0.5 0.02\"/>";
    let mount = "<body name=\"mount\" pos=\"0.2 0 0.1\" xyaxes=\"0 1 0 -1 0 0\"";
    let corner = "<frame name=\"corner\" pos=\"-0.3 0.3 0\" euler=\"10 0 0\"";
    // Where the arm goes, and HOST with the arm written there by hand.
    let cases = [
        (Namespace::Body, "table", HOST.replace(geom, &format!("{geom}{ARM_INSIDE}"))),
        (
            Namespace::Body,
            "mount",
            HOST.replace(&format!("{mount}/>"), &format!("{mount}>{ARM_INSIDE}</body>")),
        ),
        (
            Namespace::Frame,
            "corner",
            HOST.replace(&format!("{corner}/>"), &format!("{corner}>{ARM_INSIDE}</frame>")),
        ),
    ];
    for (ns, at, by_hand) in cases {
        assert_ne!(by_hand, HOST);
        let loc = host.find(ns, at).unwrap();
        let (scene, _) = host.attach_in(&loc, &arm).unwrap();
        assert!(scene.check().is_empty(), "{:?}", scene.check());
        let ours = poses(&scene.to_xml_string().unwrap(), &bodies);
        assert_close(&ours, &poses(&by_hand, &bodies));
    }
}

#[test]
#[ignore = "needs MuJoCo (MUJOCO_LIB); run by .ci/run"]
fn a_model_attached_in_a_body_of_an_attached_model_compiles_with_every_name_scoped() {
    let host = Model::from_xml_str(HOST).unwrap();
    let arm = Model::from_xml_str(ARM).unwrap();
    let mut scene = Model::new("scene");
    scene.attach_mut(&scene.worldbody(), &host).unwrap();
    scene.attach_mut(&scene.worldbody(), &host).unwrap();
    for scope in ["host", "host_1"] {
        let mount = scene.find(Namespace::Body, &format!("{scope}/mount")).unwrap();
        scene.attach_in_mut(&mount, &arm).unwrap();
    }
    let compiled = mujoco().compile(&scene).unwrap();
    for name in ["host/arm/base", "host_1/arm/link"] {
        assert!(compiled.id(ObjKind::Body, name).is_some(), "{name}");
    }
    assert_eq!(compiled.count(ObjKind::Joint), 4);
}
