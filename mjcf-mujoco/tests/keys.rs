//! MuJoCo judges composed keyframes (`WriteOptions::merge_keyframes`): reset to the
//! composed key, every attached robot's floating base sits where its attachment frame
//! (as MuJoCo compiles the site it was attached at) composed with the robot's own key
//! puts it, for sites oriented in every form MJCF allows; the fleet then steps without
//! a warning.

use crate::support;

use mjcf::{Model, Namespace, ReadOptions, WriteOptions, element};
use mjcf_mujoco::Physics;
use support::mujoco;

/// A floating robot whose `home` key puts its base off the origin, turned and tilted.
const ROBOT: &str = r#"
<mujoco model="robot">
  <worldbody>
    <body name="base" pos="0 0 0.3">
      <freejoint/>
      <geom type="box" size="0.1 0.05 0.02"/>
      <body name="arm" pos="0.1 0 0"><joint name="elbow" axis="0 1 0"/><geom size="0.02"/></body>
    </body>
    <body name="target" mocap="true" pos="0 0.3 0"><geom size="0.01" contype="0" conaffinity="0"/></body>
  </worldbody>
  <keyframe>
    <key name="home" qpos="0.1 -0.2 0.5 0.9238795 0.1530459 0.1530459 0.3061862 0.7"
         qvel="1 2 3 0.1 0.2 0.3 0" mpos="0.2 0.3 0.4" mquat="0.7071068 0 0 0.7071068"/>
  </keyframe>
</mujoco>"#;

/// A 3x3 rotation matrix (row major) times another, and times a vector.
fn matmul(a: &[f64], b: &[f64]) -> [f64; 9] {
    std::array::from_fn(|k| (0..3).map(|i| a[3 * (k / 3) + i] * b[3 * i + k % 3]).sum())
}

fn matvec(a: &[f64], v: &[f64]) -> [f64; 3] {
    std::array::from_fn(|r| (0..3).map(|i| a[3 * r + i] * v[i]).sum())
}

fn quat_to_mat(q: &[f64]) -> [f64; 9] {
    let n = q.iter().map(|x| x * x).sum::<f64>().sqrt();
    let (w, x, y, z) = (q[0] / n, q[1] / n, q[2] / n, q[3] / n);
    [
        1.0 - 2.0 * (y * y + z * z),
        2.0 * (x * y - w * z),
        2.0 * (x * z + w * y),
        2.0 * (x * y + w * z),
        1.0 - 2.0 * (x * x + z * z),
        2.0 * (y * z - w * x),
        2.0 * (x * z - w * y),
        2.0 * (y * z + w * x),
        1.0 - 2.0 * (x * x + y * y),
    ]
}

fn close(a: &[f64], b: &[f64], what: &str) {
    assert_eq!(a.len(), b.len(), "{what}");
    for (x, y) in a.iter().zip(b) {
        assert!((x - y).abs() < 1e-6, "{what}: {a:?} vs {b:?}");
    }
}

/// The sites: (attributes) in every form of orientation, some inside frames.
fn arena(compiler: Option<(&str, &str)>) -> (Model, Vec<mjcf::Loc>) {
    let mut a = Model::new("arena");
    a.set_attr_mut(&a.section("option").unwrap(), "gravity", [0.0, 0.0, 0.0]).unwrap();
    if let Some((angle, seq)) = compiler {
        let c = a.section("compiler").unwrap();
        a.set_attr_mut(&c, "angle", angle).unwrap();
        a.set_attr_mut(&c, "eulerseq", seq).unwrap();
    }
    let deg = compiler.is_none_or(|(angle, _)| angle == "degree");
    let angle = |d: f64| if deg { d } else { d.to_radians() };
    let w = a.worldbody();
    let sites = [
        element!("site", pos = [1.0, 0.0, 0.0]),
        element!("site", pos = [2.0, 0.0, 0.5], quat = [0.5, 0.5, 0.5, 0.5]),
        element!("site", pos = [3.0, 0.0, 0.0], axisangle = [1.0, 1.0, 0.0, angle(60.0)]),
        element!("site", pos = [4.0, 0.0, 0.0], euler = [angle(10.0), angle(20.0), angle(30.0)]),
        element!("site", pos = [5.0, 0.0, 0.0], xyaxes = [0.0, 1.0, 0.0, -1.0, 0.0, 0.2]),
        element!("site", pos = [6.0, 0.0, 0.0], zaxis = [0.3, -0.2, 1.0]),
    ];
    let mut out: Vec<mjcf::Loc> = sites.into_iter().map(|s| a.add_mut(&w, s).unwrap()).collect();
    // Inside two MuJoCo frames in the world (a floating base must stay top-level),
    // each turned: frames compose.
    let outer = a
        .add_mut(&w, element!("frame", pos = [0.0, 3.0, 0.0], euler = [0.0, 0.0, angle(90.0)]))
        .unwrap();
    let frame = a
        .add_mut(
            &outer,
            element!("frame", pos = [0.5, 0.0, 0.0], axisangle = [0.0, 1.0, 0.0, angle(20.0)]),
        )
        .unwrap();
    out.push(
        a.add_mut(&frame, element!("site", pos = [0.0, 0.0, 1.0], zaxis = [0.0, 1.0, 1.0]))
            .unwrap(),
    );
    (a, out)
}

fn check_fleet(arena: Model, sites: &[mjcf::Loc]) {
    let robot = ReadOptions::new().read_str(ROBOT).unwrap();
    let target = robot.find(Namespace::Body, "target").unwrap();
    let mut arena = arena;
    let scopes: Vec<String> =
        sites.iter().map(|s| arena.attach_mut(s, &robot).unwrap().scope().to_string()).collect();
    let options = WriteOptions { merge_keyframes: true, ..WriteOptions::default() };
    let compiled = mujoco().compile_with(&arena, &options).unwrap();
    let mut p = Physics::new(&compiled).unwrap();
    p.reset_to_key("home").unwrap();
    p.forward().unwrap();
    let base = robot.find(Namespace::Body, "base").unwrap();
    let key_pos = [0.1, -0.2, 0.5];
    let key_rot = quat_to_mat(&[0.9238795, 0.1530459, 0.1530459, 0.3061862]);
    for (site, scope) in sites.iter().zip(&scopes) {
        let s = p.bind(site).unwrap();
        let (sp, sr) = (p.get(&s, "xpos").unwrap().to_vec(), p.get(&s, "xmat").unwrap().to_vec());
        let b = p.bind(arena.locate_in(scope.as_str(), &base).unwrap()).unwrap();
        let moved = matvec(&sr, &key_pos);
        let want: Vec<f64> = (0..3).map(|i| sp[i] + moved[i]).collect();
        close(p.get(&b, "xpos").unwrap(), &want, &format!("{scope} base position"));
        close(
            p.get(&b, "xmat").unwrap(),
            &matmul(&sr, &key_rot),
            &format!("{scope} base orientation"),
        );
        // Its velocity turned with it: linear in the world, angular in the body.
        let j = p
            .bind(
                arena.find(Namespace::Joint, &format!("{scope}//unnamed_joint_0")).unwrap_or_else(
                    || {
                        arena
                            .locate_in(scope.as_str(), &robot.find_all(Namespace::Joint)[0])
                            .unwrap()
                    },
                ),
            )
            .unwrap();
        close(
            &p.get(&j, "qvel").unwrap()[..3],
            &matvec(&sr, &[1.0, 2.0, 3.0]),
            &format!("{scope} velocity"),
        );
        close(
            &p.get(&j, "qvel").unwrap()[3..],
            &[0.1, 0.2, 0.3],
            &format!("{scope} angular velocity"),
        );
        // The mocap body's key pose, carried the same way.
        let t = p.bind(arena.locate_in(scope.as_str(), &target).unwrap()).unwrap();
        let moved = matvec(&sr, &[0.2, 0.3, 0.4]);
        let want: Vec<f64> = (0..3).map(|i| sp[i] + moved[i]).collect();
        close(p.get(&t, "xpos").unwrap(), &want, &format!("{scope} mocap position"));
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let mrot = quat_to_mat(&[h, 0.0, 0.0, h]);
        close(
            p.get(&t, "xmat").unwrap(),
            &matmul(&sr, &mrot),
            &format!("{scope} mocap orientation"),
        );
    }
    let warnings = p.step(1000).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn composed_keys_place_floating_bases_at_their_frames() {
    let (arena, sites) = arena(None);
    check_fleet(arena, &sites);
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn composed_keys_follow_the_compilers_angle_unit_and_euler_sequence() {
    let (arena, sites) = arena(Some(("radian", "ZYX")));
    check_fleet(arena, &sites);
    let (arena, sites) = arena_with_class_site();
    check_fleet(arena, &sites);
}

/// A site placed by its class (pos and orientation from the default), and one given
/// by `fromto`.
fn arena_with_class_site() -> (Model, Vec<mjcf::Loc>) {
    let a = ReadOptions::new()
        .read_str(
            r#"<mujoco model="arena"><option gravity="0 0 0"/>
               <default><default class="spot"><site pos="1 2 0.5" euler="0 0 45"/></default></default>
               <worldbody><site name="s1" class="spot"/>
               <site name="s2" type="capsule" size="0.01" fromto="0 -1 0 0.3 -1 0.4"/></worldbody></mujoco>"#,
        )
        .unwrap();
    let sites =
        vec![a.find(Namespace::Site, "s1").unwrap(), a.find(Namespace::Site, "s2").unwrap()];
    (a, sites)
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn the_example_fleet_stands_where_it_was_put() {
    let robot =
        Model::from_path(concat!(env!("CARGO_MANIFEST_DIR"), "/../examples/models/quadruped.xml"))
            .unwrap();
    let mut arena = Model::new("arena");
    arena
        .add_mut(&arena.worldbody(), element!("geom", type = "plane", size = [10.0, 10.0, 0.1]))
        .unwrap();
    let base = robot.find(Namespace::Body, "base").unwrap();
    let mut scopes = Vec::new();
    for k in 0..9 {
        let site = element!("site", pos = [(k % 3) as f64, (k / 3) as f64, 0.0]);
        let site = arena.add_mut(&arena.worldbody(), site).unwrap();
        scopes.push(arena.attach_mut(&site, &robot).unwrap().scope().to_string());
    }
    let options = WriteOptions { merge_keyframes: true, ..WriteOptions::default() };
    let mujoco = mujoco();
    // One robot alone, from its own key: its standing height.
    let mut alone = Model::new("alone");
    alone
        .add_mut(&alone.worldbody(), element!("geom", type = "plane", size = [10.0, 10.0, 0.1]))
        .unwrap();
    let a = alone.attach_mut(&alone.worldbody(), &robot).unwrap();
    let compiled = mujoco.compile_with(&alone, &options).unwrap();
    let mut p = Physics::new(&compiled).unwrap();
    p.reset_to_key("home").unwrap();
    assert!(p.step(1000).unwrap().is_empty());
    let b = p.bind(alone.locate_in(a.scope(), &base).unwrap()).unwrap();
    let height = p.get(&b, "xpos").unwrap()[2];
    // The fleet.
    let compiled = mujoco.compile_with(&arena, &options).unwrap();
    let mut p = Physics::new(&compiled).unwrap();
    p.reset_to_key("home").unwrap();
    let warnings = p.step(1000).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    for (k, scope) in scopes.iter().enumerate() {
        let b = p.bind(arena.locate_in(scope.as_str(), &base).unwrap()).unwrap();
        let x = p.get(&b, "xpos").unwrap();
        let (dx, dy) = (x[0] - (k % 3) as f64, x[1] - (k / 3) as f64);
        assert!(dx.hypot(dy) < 0.05, "{scope} is {:.3} m from its site", dx.hypot(dy));
        assert!((x[2] - height).abs() < 0.01, "{scope} at height {} against {height}", x[2]);
    }
}
