//! What a rebuild of a running simulation costs (issue 29 item 7), one run, side by
//! side, on the scene of `examples/rebuild.rs` (four quadrupeds of
//! examples/models/quadruped.xml on a floor):
//!
//! - `Physics::rebuild` after a numbers-only edit MuJoCo derives nothing from (the
//!   floor's friction): written in place;
//! - after one it derives constants from (a body's inertial mass): written in place
//!   with `mj_setConst`, beside the write plus `mj_setConst` alone
//!   (`Physics::get_mut` and `Physics::update_constants`);
//! - after a structural edit (a body added or removed): compiled, the state carried,
//!   beside a plain compile of the same model (`MuJoCo::compile_with`);
//! - with `MJCF_PYTHON` (a Python with the pinned `mujoco` wheel), MjSpec's
//!   `recompile` of the same model after the same friction edit.
//!
//! ```sh
//! MUJOCO_LIB=.../libmujoco.so.4.0.0 MJCF_PYTHON=.../python cargo bench -p mjcf-mujoco --bench rebuild
//! ```
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use mjcf::{Model, Namespace, WriteOptions, element};
use mjcf_mujoco::{MuJoCo, ObjKind, Physics, RebuildMode};

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The median of `runs` timings of `f` (given the run's index).
fn median(runs: usize, mut f: impl FnMut(usize) -> Duration) -> Duration {
    let mut t: Vec<Duration> = (0..runs).map(&mut f).collect();
    t.sort();
    t[runs / 2]
}

fn us(d: Duration) -> String {
    format!("{:.1} µs", d.as_secs_f64() * 1e6)
}

/// Four quadrupeds on a floor, r1's base with an explicit inertial.
fn scene() -> Model {
    let robot = Model::from_path(repo().join("examples/models/quadruped.xml")).expect("robot");
    let mut m = Model::new("arena");
    let w = m.worldbody();
    m.add_mut(&w, element!("geom", name = "floor", type = "plane", size = [0, 0, 0.05])).unwrap();
    for (k, (x, y)) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)].into_iter().enumerate() {
        let site =
            m.add_mut(&w, element!("site", name = format!("s{k}"), pos = [x, y, 0.0])).unwrap();
        m.attach_as_mut(&site, &robot, &format!("r{k}")).unwrap();
    }
    let base = m.find(Namespace::Body, "r1/base").unwrap();
    let inertial =
        element!("inertial", pos = [0, 0, 0], mass = 4.0, diaginertia = [0.02, 0.06, 0.07]);
    m.add_mut(&base, inertial).unwrap();
    m
}

/// MjSpec's `recompile` after a floor friction edit, median seconds, from Python.
fn mjspec_recompile(python: &str, xml: &str, runs: usize) -> Option<f64> {
    let script = r#"
import sys, time, mujoco
spec = mujoco.MjSpec.from_string(open(sys.argv[1]).read())
m = spec.compile()
d = mujoco.MjData(m)
for _ in range(100):
    mujoco.mj_step(m, d)
floor = spec.geom("floor")
t = []
for i in range(int(sys.argv[2])):
    floor.friction[0] = 0.5 + 0.1 * (i % 2)
    s = time.perf_counter()
    m, d = spec.recompile(m, d)
    t.append(time.perf_counter() - s)
t.sort()
print(t[len(t) // 2])
"#;
    let file = std::env::temp_dir().join(format!("mjcf-bench-rebuild-{}.xml", std::process::id()));
    std::fs::write(&file, xml).ok()?;
    let out = std::process::Command::new(python)
        .args(["-c", script])
        .arg(&file)
        .arg(runs.to_string())
        .output()
        .ok()?;
    let _ = std::fs::remove_file(&file);
    String::from_utf8(out.stdout).ok()?.trim().parse().ok()
}

fn main() {
    let mujoco = MuJoCo::load().expect("MuJoCo 4.0.0 (set MUJOCO_LIB)");
    let options = WriteOptions { merge_keyframes: true, ..WriteOptions::default() };
    let m = scene();
    let mut physics = Physics::new(&mujoco.compile_with(&m, &options).expect("compiles")).unwrap();
    physics.reset_to_key("home").unwrap();
    let _ = physics.step(100).unwrap();
    let floor = m.find(Namespace::Geom, "floor").unwrap();
    let inertial = m.get(&m.find(Namespace::Body, "r1/base").unwrap()).unwrap();
    let inertial = inertial.children().find(|c| c.tag() == "inertial").unwrap().loc();
    let runs = 201;

    // Numbers MuJoCo derives nothing from.
    let versions: Vec<Model> =
        (0..2).map(|i| m.set_attr(&floor, "friction", [0.5 + 0.1 * i as f64]).unwrap()).collect();
    let friction = median(runs, |i| {
        let start = Instant::now();
        let r = physics.rebuild(&versions[i % 2]).unwrap();
        let t = start.elapsed();
        assert_eq!(r.mode, RebuildMode::InPlace);
        t
    });
    // Numbers MuJoCo derives constants from.
    let now = physics.model().source().unwrap().clone();
    let versions: Vec<Model> =
        (0..2).map(|i| now.set_attr(&inertial, "mass", 4.5 + i as f64).unwrap()).collect();
    let mass = median(runs, |i| {
        let start = Instant::now();
        let r = physics.rebuild(&versions[i % 2]).unwrap();
        let t = start.elapsed();
        assert_eq!(r.mode, RebuildMode::InPlace);
        t
    });
    // The same write and mj_setConst alone, on a simulation of its own.
    let mut alone = Physics::new(physics.model()).unwrap();
    let base = alone.bind((ObjKind::Body, "r1/base")).unwrap();
    let set_const = median(runs, |i| {
        let start = Instant::now();
        alone.get_mut(&base, "mass").unwrap()[0] = 4.0 + (i % 2) as f64;
        alone.update_constants().unwrap();
        start.elapsed()
    });
    // Structural: an obstacle added and removed.
    let now = physics.model().source().unwrap().clone();
    let mut with = now.clone();
    let w = with.worldbody();
    let body = with.add_mut(&w, element!("body", name = "obstacle", pos = [3, 3, 0.1])).unwrap();
    with.add_mut(&body, element!("geom", type = "box", size = [0.1, 0.1, 0.1])).unwrap();
    let versions = [with, now];
    // Interleaved, so that the machine's load weighs on both alike.
    let (mut structural, mut compile) = (Vec::new(), Vec::new());
    for i in 0..runs / 2 {
        let start = Instant::now();
        let c = mujoco.compile_with(&versions[(i + 1) % 2], &options).unwrap();
        compile.push(start.elapsed());
        std::hint::black_box(c);
        let start = Instant::now();
        let r = physics.rebuild(&versions[i % 2]).unwrap();
        structural.push(start.elapsed());
        assert_eq!(r.mode, RebuildMode::Compiled);
    }
    let (structural, compile) =
        (median(structural.len(), |i| structural[i]), median(compile.len(), |i| compile[i]));
    let xml = m.to_xml_string_with(&options).unwrap();
    let spec = std::env::var("MJCF_PYTHON").ok().and_then(|p| mjspec_recompile(&p, &xml, runs));
    let spec_text = spec.map_or("- (set MJCF_PYTHON)".into(), |s| format!("{:.1} µs", s * 1e6));
    println!(
        "rebuild of four quadrupeds on a floor (median of {runs} runs; structural {}):",
        runs / 2
    );
    println!("  numbers only (floor friction), in place      {:>12}", us(friction));
    println!("  MjSpec recompile after the same edit          {spec_text:>12}");
    if let Some(s) = spec {
        println!("    ratio: {:.0}x faster", s / friction.as_secs_f64());
    }
    println!("  a mass (inertial), in place with mj_setConst  {:>12}", us(mass));
    println!("  the write plus mj_setConst alone              {:>12}", us(set_const));
    println!("  structural (a body added/removed), compiled   {:>12}", us(structural));
    println!("  a plain compile of the same models            {:>12}", us(compile));
    println!("    ratio: {:.2}x", structural.as_secs_f64() / compile.as_secs_f64());
}
