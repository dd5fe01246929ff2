//! MuJoCo judges the conversion of angles when models whose `<compiler angle>` or
//! `<compiler eulerseq>` differ are composed (`attach_to_world`, `attach_in`,
//! `include_copy`, a `part` attached, the composition saved as a scene): every body,
//! geom, site, camera and joint of the child compiles in the composed model to what
//! it compiles to in the child's own file (local poses, inertial frames, joint
//! ranges, `qpos0`, and the spring forces at `qpos0`, which `springref` sets), over
//! generated children in degrees and radians, with every euler sequence kind (moving
//! axes, fixed axes, mixed, repeated axes), orientations and joint values in default
//! classes, joint types from classes, a `<flexcomp>` and a `<replicate>`.

use crate::support;

use std::collections::BTreeMap;

use mjcf::{Model, Namespace};
use mjcf_mujoco::{Compiled, ObjKind, Physics};
use support::mujoco;

/// A small deterministic generator (xorshift).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }

    /// An angle in `unit` (`degree` or `radian`), up to `max` radians.
    fn angle(&mut self, unit: &str, max: f64) -> f64 {
        let a = self.next() * max;
        if unit == "degree" { a.to_degrees() } else { a }
    }

    fn euler(&mut self, unit: &str) -> String {
        let e: Vec<String> = (0..3).map(|_| format!("{:.6}", self.angle(unit, 3.0))).collect();
        e.join(" ")
    }

    fn axisangle(&mut self, unit: &str) -> String {
        let axis: Vec<String> = (0..3).map(|_| format!("{:.4}", self.next() + 1.5)).collect();
        format!("{} {:.6}", axis.join(" "), self.angle(unit, 3.0))
    }
}

/// A number with 5 decimals.
fn n5(x: f64) -> String {
    format!("{x:.5}")
}

/// A child model in `unit` and `seq`: every element kind whose numbers the compiler
/// reads by `angle` or `eulerseq`, own or from default classes (a `<flexcomp>`'s
/// orientation places the bodies it makes).
fn child_xml(seed: u64, unit: &str, seq: &str) -> String {
    let mut r = Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1);
    let range =
        |r: &mut Rng| format!("{:.5} {:.5}", -r.angle(unit, 1.5).abs(), r.angle(unit, 1.5).abs());
    format!(
        r#"<mujoco model="kid">
  <compiler angle="{unit}" eulerseq="{seq}"/>
  <default>
    <joint range="{root_range}" springref="{springref}" stiffness="1"/>
    <geom euler="{class_geom}"/>
    <default class="ball"><joint type="ball" range="0 {ball}"/></default>
    <default class="slide"><joint type="slide"/><site axisangle="{class_site}"/></default>
    <default class="cam"><camera euler="{class_cam}"/></default>
  </default>
  <worldbody>
    <body name="b0" pos="0.1 0.2 0.3" euler="{b0}">
      <inertial pos="0 0 0.1" mass="1" diaginertia="0.1 0.2 0.3" euler="{inertial}"/>
      <joint name="h0" axis="0 0 1" ref="{ref0}"/>
      <geom name="g0" size="0.1"/>
      <geom name="g1" size="0.1" axisangle="{g1}"/>
      <site name="s0" euler="{s0}"/>
      <camera name="c0" class="cam"/>
      <camera name="c1" axisangle="{c1}"/>
      <frame name="f0" pos="0 0.2 0" euler="{f0}">
        <body name="b1" axisangle="{b1}">
          <joint name="h1" axis="1 0 0" range="{h1_range}" ref="{ref1}"/>
          <geom name="g2" size="0.1" euler="{g2}"/>
        </body>
      </frame>
      <body name="b2" childclass="slide" euler="{b2}">
        <joint name="sl1" range="-0.3 0.4"/>
        <joint name="sl2" axis="0 1 0"/>
        <joint name="h2" type="hinge" axis="1 0 0" limited="false" ref="{ref2}"/>
        <site name="s1"/>
        <geom name="g3" size="0.1"/>
      </body>
      <body name="b3" pos="0 0 -0.3"><joint name="ball1" class="ball"/><geom name="g4" size="0.1"/></body>
    </body>
    <flexcomp name="fc" type="grid" count="2 2 1" spacing="0.1 0.1 0.1" pos="0 0 2" euler="{fc}" dim="2" radius="0.01" mass="1"/>
    <replicate count="3" euler="{rep} 0 0">
      <body name="r" pos="1 0 0"><geom name="rg" size="0.05"/></body>
    </replicate>
  </worldbody>
  <actuator><position name="p0" joint="h0" ctrlrange="-30 30" ctrllimited="true" kp="1"/></actuator>
</mujoco>"#,
        root_range = range(&mut r),
        springref = n5(r.angle(unit, 1.0)),
        class_geom = r.euler(unit),
        ball = n5(r.angle(unit, 1.5).abs() + 0.1),
        class_site = r.axisangle(unit),
        class_cam = r.euler(unit),
        b0 = r.euler(unit),
        inertial = r.euler(unit),
        ref0 = n5(r.angle(unit, 1.0)),
        g1 = r.axisangle(unit),
        s0 = r.euler(unit),
        c1 = r.axisangle(unit),
        f0 = r.euler(unit),
        b1 = r.axisangle(unit),
        h1_range = range(&mut r),
        ref1 = n5(r.angle(unit, 1.0)),
        g2 = r.euler(unit),
        b2 = r.euler(unit),
        ref2 = n5(r.angle(unit, 1.0)),
        rep = n5(r.angle(unit, 1.0)),
        fc = r.euler(unit),
    )
}

/// A host in `unit` and `seq` with a turned body of its own and a body to attach in.
fn host_xml(unit: &str, seq: &str) -> String {
    let a = if unit == "degree" { "30" } else { "0.5235987755982988" };
    format!(
        r#"<mujoco model="host">
  <compiler angle="{unit}" eulerseq="{seq}"/>
  <worldbody>
    <body name="hb" euler="{a} 0 {a}"><joint name="hj" range="-{a} {a}"/><geom name="hg" size="0.1"/></body>
    <body name="mount"/>
  </worldbody>
</mujoco>"#
    )
}

/// A compiled model, with `qpos0` and the passive forces there (the joints' springs
/// pull towards `qpos_spring`, which `springref` sets).
struct Judged {
    c: Compiled,
    qpos0: Vec<f64>,
    passive: Vec<f64>,
}

fn compile(model: &Model) -> Judged {
    let xml = model.to_xml_string().unwrap();
    judged(mujoco().compile_xml(&xml, &BTreeMap::new()).unwrap_or_else(|e| panic!("{e}\n{xml}")))
}

/// `model` saved as a scene (each attached model a file of its own, with its own
/// `<compiler>`, MuJoCo's `<attach>`), compiled.
fn compile_scene(model: &Model, n: usize) -> Judged {
    let dir = std::env::temp_dir().join(format!("mjcf-angles-{}-{n}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let saved = model.save_scene(&dir, "scene.xml").unwrap();
    let c = mujoco().compile_path(saved.path());
    let _ = std::fs::remove_dir_all(&dir);
    judged(c.unwrap())
}

fn judged(c: Compiled) -> Judged {
    let mut physics = Physics::new(&c).unwrap();
    physics.forward().unwrap();
    let qpos0 = physics.qpos().to_vec();
    let passive = physics.data("qfrc_passive").unwrap().to_vec();
    Judged { c, qpos0, passive }
}

/// The per-element fields compared, with their row width.
const FIELDS: &[(ObjKind, &[(&str, usize)])] = &[
    (ObjKind::Body, &[("body_pos", 3), ("body_quat", 4), ("body_ipos", 3), ("body_iquat", 4)]),
    (ObjKind::Geom, &[("geom_pos", 3), ("geom_quat", 4)]),
    (ObjKind::Site, &[("site_pos", 3), ("site_quat", 4)]),
    (ObjKind::Camera, &[("cam_pos", 3), ("cam_quat", 4)]),
    (ObjKind::Joint, &[("jnt_pos", 3), ("jnt_axis", 3), ("jnt_range", 2)]),
    // Not converted by MuJoCo: a position actuator's ctrlrange on a hinge.
    (ObjKind::Actuator, &[("actuator_ctrlrange", 2)]),
];

/// `x` and `y` agree to 1e-9; quaternions (`quat`) up to their sign, which gives the
/// same rotation.
fn close(x: &[f64], y: &[f64], quat: bool) -> bool {
    let d = |s: f64| x.iter().zip(y).map(|(p, q)| (p - s * q).abs()).fold(0.0, f64::max);
    d(1.0) < 1e-9 || (quat && d(-1.0) < 1e-9)
}

/// Every named element of `alone` found in `composed` as `prefix` + its name has the
/// same compiled fields, `qpos0` and spring forces there; returns how many
/// elements were compared.
fn assert_same(alone: &Judged, composed: &Judged, prefix: &str, what: &str) -> usize {
    let (ja, jc) = (alone, composed);
    let (alone, composed) = (&ja.c, &jc.c);
    let mut compared = 0;
    for (kind, fields) in FIELDS {
        for id in 0..alone.count(*kind) {
            // (The world body is the composed model's own.)
            let Some(name) = alone.name(*kind, id).filter(|n| !n.is_empty() && *n != "world")
            else {
                continue;
            };
            let full = format!("{prefix}{name}");
            let other = composed.id(*kind, &full).unwrap_or_else(|| panic!("{what}: no {full}"));
            for (field, w) in *fields {
                let (a, b) = (alone.floats(field).unwrap(), composed.floats(field).unwrap());
                let (x, y) = (&a[w * id..w * id + w], &b[w * other..w * other + w]);
                assert!(close(x, y, *w == 4), "{what}: {field} of {full}: {x:?} != {y:?}");
            }
            if *kind == ObjKind::Joint {
                let ints = |c: &Compiled, f: &str, i: usize| c.ints(f).unwrap()[i];
                let n = match ints(alone, "jnt_type", id) {
                    0 => 7,
                    1 => 4,
                    _ => 1,
                };
                let (qa, qb) =
                    (ints(alone, "jnt_qposadr", id), ints(composed, "jnt_qposadr", other));
                let (x, y) = (&ja.qpos0[qa as usize..][..n], &jc.qpos0[qb as usize..][..n]);
                assert!(close(x, y, n == 4), "{what}: qpos0 of {full}: {x:?} != {y:?}");
                let dofs = if n == 7 {
                    6
                } else if n == 4 {
                    3
                } else {
                    1
                };
                let (da, db) = (ints(alone, "jnt_dofadr", id), ints(composed, "jnt_dofadr", other));
                let (x, y) =
                    (&ja.passive[da as usize..][..dofs], &jc.passive[db as usize..][..dofs]);
                assert!(close(x, y, false), "{what}: spring force of {full}: {x:?} != {y:?}");
            }
            compared += 1;
        }
    }
    compared
}

/// A compiler's `angle` and `eulerseq`.
type Conventions = (&'static str, &'static str);

/// The (child, host) conventions tried: unit and sequence differing, each alone and
/// both, both ways; sequences of moving, fixed, mixed and repeated axes (the host's
/// has the axis of the child's first letter, about which the `<replicate>` turns).
const PAIRS: &[(Conventions, Conventions)] = &[
    (("degree", "xyz"), ("radian", "xyz")),
    (("radian", "xyz"), ("degree", "xyz")),
    (("degree", "xyz"), ("degree", "ZYX")),
    (("degree", "zXy"), ("radian", "XYZ")),
    (("radian", "ZYX"), ("degree", "yxz")),
    (("degree", "xyx"), ("radian", "XzX")),
    (("radian", "zYz"), ("degree", "yzy")),
    (("radian", "XzX"), ("degree", "zyx")),
];

#[test]
#[ignore = "needs MuJoCo (MUJOCO_LIB); run by .ci/run"]
fn a_child_in_other_angle_conventions_compiles_in_the_host_as_in_its_own_file() {
    let mut compared = 0;
    for (n, ((cu, cs), (hu, hs))) in PAIRS.iter().enumerate() {
        for seed in 0..4u64 {
            let what = format!("child {cu}/{cs} in host {hu}/{hs}, seed {seed}");
            let child = Model::from_xml_str(&child_xml(seed + 10 * n as u64, cu, cs)).unwrap();
            let host = Model::from_xml_str(&host_xml(hu, hs)).unwrap();
            let (alone, host_alone) = (compile(&child), compile(&host));
            // At the world.
            let (world, _) = host.attach_to_world(&child).unwrap();
            let composed = compile(&world);
            compared += assert_same(&alone, &composed, "kid/", &what);
            // Saved as a scene, the converted child is a file of its own.
            let scene = compile_scene(&world, n);
            compared += assert_same(&alone, &scene, "kid/", &format!("{what}, scene"));
            // The host's own elements are untouched.
            compared += assert_same(&host_alone, &composed, "", &what);
            // Inside a body, by attach_in.
            let mount = host.find(Namespace::Body, "mount").unwrap();
            let (inside, _) = host.attach_in(&mount, &child).unwrap();
            compared += assert_same(&alone, &compile(&inside), "kid/", &what);
            // Copied in.
            let copied = host.include_copy(&child, false).unwrap();
            compared += assert_same(&alone, &compile(&copied), "", &what);
            // A part of it, attached.
            let part = child.part("b0").unwrap().model;
            let (with_part, a) = host.attach_to_world(&part).unwrap();
            let prefix = format!("{}/", a.scope());
            compared += assert_same(&compile(&part), &compile(&with_part), &prefix, &what);
        }
    }
    assert!(compared > 500, "{compared}");
}

#[test]
#[ignore = "needs MuJoCo (MUJOCO_LIB); run by .ci/run"]
fn a_child_attached_inside_an_attachment_is_converted_to_the_outermost_conventions() {
    let child = Model::from_xml_str(&child_xml(7, "degree", "zXy")).unwrap();
    let host = Model::from_xml_str(&host_xml("radian", "XYZ")).unwrap();
    // A middle model that sets nothing, attached first; the child goes inside it.
    let mut middle = Model::new("middle");
    middle.add_mut(&middle.worldbody(), mjcf::element!("body", name = "m")).unwrap();
    let (scene, a) = host.attach_to_world(&middle).unwrap();
    let at = scene.find(Namespace::Body, "middle/m").unwrap();
    let (scene, _) = scene.attach_in(&at, &child).unwrap();
    assert_eq!(a.scope(), "middle");
    let n = assert_same(&compile(&child), &compile(&scene), "middle/kid/", "nested");
    assert!(n > 20, "{n}");
}

#[test]
#[ignore = "needs MuJoCo (MUJOCO_LIB); run by .ci/run"]
fn a_model_whose_unit_comes_from_what_it_holds_attached_is_converted_whole() {
    let child = Model::from_xml_str(&child_xml(3, "degree", "ZYX")).unwrap();
    // The middle model sets nothing itself: its numbers read as the child's settings
    // say, which its merged settings take.
    let mut middle = Model::from_xml_str(
        r#"<mujoco model="middle"><worldbody>
        <body name="m" euler="0 30 60"><joint name="mj" range="-45 45"/><geom name="mg" size="0.1"/></body>
        </worldbody></mujoco>"#,
    )
    .unwrap();
    let world = middle.worldbody();
    middle.attach_mut(&world, &child).unwrap();
    let host = Model::from_xml_str(&host_xml("radian", "xYz")).unwrap();
    let (scene, _) = host.attach_to_world(&middle).unwrap();
    let composed = compile(&scene);
    let n = assert_same(&compile(&middle), &composed, "middle/", "middle");
    assert!(n > 30, "{n}");
    assert!(assert_same(&compile(&host), &composed, "", "host") > 3);
}
