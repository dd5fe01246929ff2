//! The binding against MuJoCo's library: loading, compiling in memory, errors,
//! simulating, binding fields. Tests that need MuJoCo are ignored in a plain
//! `cargo test`; `.ci/run` runs them with `MUJOCO_LIB` set (`--include-ignored`).

use crate::support;

use std::io::Write as _;

use mjcf::{Model, Namespace, ReadOptions, element};
use mjcf_mujoco::{Compiled, Error, MuJoCo, ObjKind, Physics, WarningKind};
use support::mujoco;

fn ball() -> (Model, mjcf::Loc) {
    let mut model = Model::new("ball");
    let ball = model
        .add_mut(&model.worldbody(), element!("body", name = "ball", pos = [0, 0, 1]))
        .unwrap();
    model.add_mut(&ball, element!("freejoint", name = "free")).unwrap();
    model.add_mut(&ball, element!("geom", type = "sphere", size = [0.1])).unwrap();
    (model, ball)
}

#[test]
fn the_types_are_send_and_sync_as_documented() {
    fn send_sync<T: Send + Sync>() {}
    fn send<T: Send>() {}
    send_sync::<MuJoCo>();
    send_sync::<Compiled>();
    send::<Physics>();
}

#[test]
fn a_missing_library_says_what_to_install() {
    let e = MuJoCo::load_from("/nonexistent/libmujoco.so.4.0.0").unwrap_err();
    assert!(matches!(e, Error::Load { .. }), "{e}");
    assert!(e.to_string().contains("/nonexistent/libmujoco.so.4.0.0"), "{e}");
    let e = Error::NotFound { tried: "MUJOCO_LIB is not set".into() };
    let text = e.to_string();
    assert!(text.contains("pip install mujoco==4.0.0") && text.contains("MUJOCO_LIB"), "{text}");
    // The command that sets it, ready to paste into a shell.
    assert!(text.contains("export MUJOCO_LIB=$(python3 -c "), "{text}");
    assert!(text.contains(r#"mujoco.__file__), "libmujoco.so.4.0.0"))')"#), "{text}");
}

#[test]
fn a_library_that_is_not_mujoco_is_refused() {
    // The C library has none of MuJoCo's functions.
    let libc = [
        "/lib/x86_64-linux-gnu/libc.so.6",
        "/usr/lib/x86_64-linux-gnu/libc.so.6",
        "/lib64/libc.so.6",
    ]
    .into_iter()
    .find(|p| std::path::Path::new(p).exists())
    .expect("the C library");
    let e = MuJoCo::load_from(libc).unwrap_err();
    assert!(matches!(&e, Error::Load { reason, .. } if reason.contains("mj_versionString")), "{e}");
}

/// A shared library that says it is MuJoCo 3.17.0, built with the C compiler.
fn fake_mujoco(dir: &std::path::Path) -> std::path::PathBuf {
    let c = dir.join("fake.c");
    std::fs::File::create(&c)
        .unwrap()
        .write_all(b"int mj_version(void) { return 3017000; }\nconst char* mj_versionString(void) { return \"3.17.0\"; }\n")
        .unwrap();
    let so = dir.join("libmujoco.so.3.17.0");
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".into());
    let status = std::process::Command::new(cc)
        .args(["-shared", "-fPIC", "-o"])
        .arg(&so)
        .arg(&c)
        .status()
        .expect("a C compiler (cc) to build the fake library");
    assert!(status.success());
    so
}

#[test]
fn another_version_of_mujoco_is_refused_before_anything_is_called() {
    let dir = std::env::temp_dir().join(format!("mjcf-mujoco-fake-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let e = MuJoCo::load_from(fake_mujoco(&dir)).unwrap_err();
    std::fs::remove_dir_all(&dir).unwrap();
    assert!(matches!(&e, Error::Version { found, .. } if found == "3.17.0"), "{e}");
    assert!(e.to_string().contains("install MuJoCo 4.0.0"), "{e}");
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn it_loads_mujoco_4_0_0() {
    assert_eq!(mujoco().version(), "4.0.0");
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn a_falling_ball_falls_as_physics_says() {
    let (model, ball) = ball();
    let compiled = mujoco().compile(&model).unwrap();
    assert_eq!((compiled.sizes().nq, compiled.sizes().nv, compiled.sizes().nbody), (7, 6, 2));
    let mut physics = Physics::new(&compiled).unwrap();
    let b = physics.bind(&ball).unwrap();
    assert_eq!((b.kind(), b.id(), b.name()), (ObjKind::Body, 1, "ball"));
    physics.forward().unwrap();
    assert_eq!(physics.get(&b, "xpos").unwrap(), [0.0, 0.0, 1.0]);
    let warnings = physics.step(250).unwrap();
    assert!(warnings.is_empty(), "{warnings:?}");
    let t = physics.time();
    let z = physics.get(&b, "xpos").unwrap()[2];
    assert!((t - 0.5).abs() < 1e-9, "t = {t}");
    // Semi-implicit Euler lands within a step of 1 - g t² / 2.
    assert!((z - (1.0 - 0.5 * 9.81 * t * t)).abs() < 0.02, "z = {z}");
    physics.forward().unwrap();
    assert_eq!(physics.qpos()[2], physics.get(&b, "xpos").unwrap()[2]);
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn a_compile_error_names_the_element_of_the_mjcf_model() {
    let mut model = Model::new("m");
    let body = model.add_mut(&model.worldbody(), element!("body", name = "b")).unwrap();
    model.add_mut(&body, element!("geom", name = "g", size = [0.1])).unwrap();
    // A mesh geom without a mesh: MuJoCo refuses it and names its line.
    let bad = model.add_mut(&body, element!("geom", type = "mesh")).unwrap();
    let Err(Error::Compile(e)) = mujoco().compile(&model) else { panic!("compiled") };
    assert!(e.message.contains("must have valid meshid"), "{}", e.message);
    let element = e.element.as_ref().expect("the element MuJoCo names");
    assert_eq!(element.loc, bad);
    assert_eq!(element.tag, "geom");
    assert_eq!(element.full_name.as_deref(), Some("//unnamed_geom_1"));
    assert!(e.to_string().contains("<geom> named \"//unnamed_geom_1\""), "{e}");
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn compile_errors_of_text_are_typed_too() {
    let e = mujoco()
        .compile_xml("<mujoco><worldbody><geom/></mujoco>", &Default::default())
        .unwrap_err();
    assert!(matches!(&e, Error::Compile(c) if c.element.is_none() && !c.message.is_empty()), "{e}");
}

/// Twenty spheres falling on a plane, with `memory` bytes for MuJoCo's arena.
fn pile(memory: &str) -> Model {
    let mut m = Model::new("pile");
    m.set_attr_mut(&m.section("size").unwrap(), "memory", memory).unwrap();
    m.add_mut(&m.worldbody(), element!("geom", type = "plane", size = [1, 1, 1])).unwrap();
    for i in 0..20 {
        let b = m
            .add_mut(&m.worldbody(), element!("body", pos = [0.0, 0.0, 0.1 + 0.19 * i as f64]))
            .unwrap();
        m.add_mut(&b, element!("freejoint")).unwrap();
        m.add_mut(&b, element!("geom", size = [0.1])).unwrap();
    }
    m
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn a_fatal_error_inside_mujoco_returns_to_the_caller() {
    // 64 KiB of arena: enough to compile, too little for the constraints of a step.
    let compiled = mujoco().compile(&pile("64K")).unwrap();
    let mut physics = Physics::new(&compiled).unwrap();
    let e = physics.step(1).unwrap_err();
    assert!(
        matches!(&e, Error::Fatal { call: "Physics::step", message } if message.contains("mj_stackAlloc")),
        "{e}"
    );
    // The data is unusable until reset; then it works again (and fails the same way).
    assert!(matches!(physics.step(1), Err(Error::Poisoned)));
    assert!(matches!(physics.forward(), Err(Error::Poisoned)));
    physics.reset().unwrap();
    assert!(matches!(physics.step(1), Err(Error::Fatal { .. })));
    // A second simulation of the same model on another thread fails the same way.
    let compiled2 = compiled.clone();
    let other = std::thread::spawn(move || Physics::new(&compiled2).unwrap().step(1).is_err());
    assert!(other.join().unwrap());
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn warnings_come_back_from_the_step_that_raised_them_and_no_log_file_is_written() {
    let cwd = std::env::current_dir().unwrap();
    let log = cwd.join("MUJOCO_LOG.TXT");
    let existed = log.exists();
    // 16 KiB: the step runs out of room for constraints and says so.
    let compiled = mujoco().compile(&pile("16K")).unwrap();
    let mut physics = Physics::new(&compiled).unwrap();
    let warnings = physics.step(1).unwrap();
    assert_eq!(warnings.len(), 1, "{warnings:?}");
    assert_eq!(warnings[0].kind, WarningKind::ConstraintFull);
    assert_eq!(warnings[0].count, 1);
    assert!(warnings[0].text.contains("Increase arena memory"), "{}", warnings[0].text);
    assert_eq!(physics.warnings()[0].kind, WarningKind::ConstraintFull);
    // MuJoCo's first-time message went to the binding, not to a log file.
    assert!(physics.take_messages().iter().any(|m| m.warning && m.text.contains("arena")));
    assert_eq!(log.exists(), existed, "MUJOCO_LOG.TXT written in {}", cwd.display());
    physics.reset().unwrap();
    assert!(physics.warnings().is_empty());
}

/// A binary STL of a tetrahedron.
fn tetrahedron_stl() -> Vec<u8> {
    let v = [[0.0f32, 0.0, 0.0], [0.1, 0.0, 0.0], [0.0, 0.1, 0.0], [0.0, 0.0, 0.1]];
    let faces = [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]];
    let mut out = vec![0u8; 80];
    out.extend_from_slice(&(faces.len() as u32).to_le_bytes());
    for f in faces {
        out.extend_from_slice(&[0u8; 12]);
        for i in f {
            for c in v[i] {
                out.extend_from_slice(&c.to_le_bytes());
            }
        }
        out.extend_from_slice(&[0u8; 2]);
    }
    out
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn files_are_handed_over_in_memory() {
    let robot = ReadOptions::new()
        .asset("parts/tet.stl", tetrahedron_stl())
        .read_str(
            r#"<mujoco model="robot"><asset><mesh name="tet" file="parts/tet.stl"/></asset>
               <worldbody><body name="b"><freejoint/><geom type="mesh" mesh="tet"/></body></worldbody></mujoco>"#,
        )
        .unwrap();
    let mut arena = Model::new("arena");
    arena.attach_mut(&arena.worldbody(), &robot).unwrap();
    arena.attach_mut(&arena.worldbody(), &robot).unwrap();
    let compiled = mujoco().compile(&arena).unwrap();
    assert_eq!(compiled.sizes().ngeom, 2);
    assert!(compiled.id(ObjKind::Mesh, "robot_1/tet").is_some());
    // The mesh's volume gives the body's mass: 1/6 · 0.1³ · 1000 kg/m³.
    let b = compiled.bind(arena.find(Namespace::Body, "robot/b").unwrap()).unwrap();
    let mass = compiled.floats("body_mass").unwrap()[b.id()];
    assert!((mass - 1000.0 * 0.001 / 6.0).abs() < 1e-6, "{mass}");
}

/// A cart on a slide with a motor, a position sensor and a site.
fn cart() -> Model {
    let mut m = Model::new("cart");
    let body =
        m.add_mut(&m.worldbody(), element!("body", name = "cart", pos = [0.0, 0.0, 0.1])).unwrap();
    m.add_mut(
        &body,
        element!("joint", name = "x", type = "slide", axis = [1, 0, 0], damping = 0.5),
    )
    .unwrap();
    m.add_mut(
        &body,
        element!("geom", name = "box", type = "box", size = [0.1, 0.1, 0.1], mass = 2),
    )
    .unwrap();
    m.add_mut(&body, element!("site", name = "tip", pos = [0.1, 0.0, 0.0])).unwrap();
    m.add_mut(&m.actuator(), element!("motor", name = "push", joint = "x", gear = [2])).unwrap();
    m.add_mut(&m.sensor(), element!("jointpos", name = "xs", joint = "x")).unwrap();
    let keys = m.section("keyframe").unwrap();
    m.add_mut(&keys, element!("key", name = "moved", qpos = [0.5])).unwrap();
    m
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn bound_fields_read_and_write_data_and_model() {
    let model = cart();
    let compiled = mujoco().compile(&model).unwrap();
    let mut p = Physics::new(&compiled).unwrap();
    let find = |ns, name| p.bind(model.find(ns, name).unwrap()).unwrap();
    let (cart, x, boxg) =
        (find(Namespace::Body, "cart"), find(Namespace::Joint, "x"), find(Namespace::Geom, "box"));
    let (tip, push, xs) = (
        find(Namespace::Site, "tip"),
        find(Namespace::Actuator, "push"),
        find(Namespace::Sensor, "xs"),
    );
    // Model fields, by dm_control's short names and by MuJoCo's own.
    assert_eq!(p.get(&cart, "mass").unwrap(), [2.0]);
    assert_eq!(p.get(&x, "damping").unwrap(), [0.5]);
    assert_eq!(p.get(&x, "dof_damping").unwrap(), [0.5]);
    assert_eq!(p.get(&boxg, "size").unwrap(), [0.1, 0.1, 0.1]);
    assert_eq!(p.get(&boxg, "friction").unwrap(), [1.0, 0.005, 0.0001]);
    assert_eq!(p.get(&push, "gainprm").unwrap()[0], 1.0);
    assert_eq!(p.get(&push, "gear").unwrap()[0], 2.0);
    assert_eq!(p.ints(&x, "qposadr").unwrap(), [0]);
    // Data fields: a key, then controls and a step.
    p.reset_to_key("moved").unwrap();
    p.forward().unwrap();
    assert_eq!(p.get(&x, "qpos").unwrap(), [0.5]);
    assert_eq!(p.get(&cart, "xpos").unwrap(), [0.5, 0.0, 0.1]);
    assert_eq!(p.get(&tip, "xpos").unwrap(), [0.6, 0.0, 0.1]);
    assert_eq!(p.get(&xs, "sensordata").unwrap(), [0.5]);
    p.get_mut(&push, "ctrl").unwrap()[0] = 1.0;
    assert!(p.step(100).unwrap().is_empty());
    assert!(p.get(&x, "qvel").unwrap()[0] > 0.0);
    // A model field written without recompiling: more damping, less speed.
    let fast = p.get(&x, "qvel").unwrap()[0];
    p.reset_to_key("moved").unwrap();
    p.get_mut(&x, "damping").unwrap()[0] = 50.0;
    p.get_mut(&push, "ctrl").unwrap()[0] = 1.0;
    assert!(p.step(100).unwrap().is_empty());
    let slow = p.get(&x, "qvel").unwrap()[0];
    assert!(slow < fast / 2.0, "{slow} vs {fast}");
    // The compiled model shared with `compiled` was copied, not changed.
    assert_eq!(compiled.floats("dof_damping").unwrap(), [0.5]);
    assert_eq!(p.model().floats("dof_damping").unwrap(), [50.0]);
    // Unknown fields and wrong types say what there is.
    let e = p.get(&x, "nonsense").unwrap_err().to_string();
    assert!(e.contains("qpos") && e.contains("damping"), "{e}");
    assert!(p.get(&x, "qposadr").is_err());
    assert!(matches!(p.reset_to_key("nope"), Err(Error::NoKey { .. })));
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn one_compiled_model_serves_simulations_on_many_threads() {
    let (model, ball) = ball();
    let compiled = mujoco().compile(&model).unwrap();
    let zs: Vec<f64> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..4)
            .map(|i| {
                let compiled = &compiled;
                let ball = &ball;
                s.spawn(move || {
                    let mut p = Physics::new(compiled).unwrap();
                    let b = p.bind(ball).unwrap();
                    assert!(p.step(50 * (i + 1)).unwrap().is_empty());
                    p.get(&b, "xpos").unwrap()[2]
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    assert!(zs.windows(2).all(|w| w[1] < w[0]), "{zs:?}");
}

#[test]
fn the_pinned_version_is_one_everywhere() {
    let file = include_str!("../MUJOCO_VERSION").trim();
    assert_eq!(file, mjcf_mujoco::MUJOCO_VERSION);
    let metadata = env!("CARGO_PKG_VERSION").split_once("+mj-").map(|(_, v)| v);
    assert_eq!(metadata, Some(file), "the crate's version names its MuJoCo");
    let ci = include_str!("../../.ci/run");
    assert!(ci.contains("mjcf-mujoco/MUJOCO_VERSION"), ".ci/run installs the pinned wheel");
}
