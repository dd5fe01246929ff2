//! What compiling with MuJoCo costs from Rust (issue: MuJoCo in the loop), as ratios
//! measured in one run:
//!
//! - our part of a compile (writing the MJCF and gathering its files, handed over in
//!   memory) against MuJoCo's own compile of the same text (`compile_xml`), for the
//!   N = 100 quadruped fleet and for `examples/compose.rs`'s 200 variants; with
//!   `MJCF_PYTHON` (a Python with the pinned `mujoco` wheel), MjSpec's `compile` of the
//!   same texts beside them;
//! - 1,000 variants that differ only in numbers, written into one compiled model
//!   (`Physics::get_mut` on bound elements, then a reset and a forward pass) against
//!   compiling each variant.
//!
//! ```sh
//! MUJOCO_LIB=.../libmujoco.so.4.0.0 cargo bench -p mjcf-mujoco --bench mujoco
//! ```
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use mjcf::{Element, Model, Namespace, WriteOptions};
use mjcf_mujoco::{MuJoCo, Physics};

#[path = "../examples/compose.rs"]
#[allow(dead_code, unreachable_pub)]
mod compose;

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// The median of `runs` timings of `f`.
fn median(runs: usize, mut f: impl FnMut()) -> Duration {
    let mut t: Vec<Duration> = (0..runs)
        .map(|_| {
            let start = Instant::now();
            f();
            start.elapsed()
        })
        .collect();
    t.sort();
    t[runs / 2]
}

fn ms(d: Duration) -> String {
    format!("{:.2} ms", d.as_secs_f64() * 1e3)
}

/// The N-robot fleet of the performance workloads (W1).
fn fleet(n: usize) -> Model {
    let models = repo().join("benches/models");
    let robot = Model::from_path(models.join("quadruped_robot.xml")).expect("the robot reads");
    // arena_100.xml has 100 sites, spawn_0 to spawn_99.
    let mut m = Model::from_path(models.join("arena_100.xml")).expect("the arena reads");
    for i in 0..n {
        let site = m.find(Namespace::Site, &format!("spawn_{i}")).expect("the site");
        let a = m.attach_mut(&site, &robot).expect("attach");
        m.add_mut(a.frame(), Element::new("freejoint")).expect("freejoint");
    }
    m
}

/// MjSpec's compile of each text, from Python: seconds for all of them.
fn mjspec_seconds(python: &str, texts: &[(String, PathBuf)]) -> Option<f64> {
    let dir = std::env::temp_dir().join(format!("mjcf-bench-mjspec-{}", std::process::id()));
    std::fs::create_dir_all(&dir).ok()?;
    let list: Vec<String> = texts
        .iter()
        .enumerate()
        .map(|(i, (xml, assets))| {
            let f = dir.join(format!("m{i}.xml"));
            std::fs::write(&f, xml).expect("write");
            format!("{}\t{}", f.display(), assets.display())
        })
        .collect();
    std::fs::write(dir.join("list"), list.join("\n")).ok()?;
    let script = r#"
import os, sys, time, mujoco
pairs = [l.split('\t') for l in open(sys.argv[1]).read().splitlines()]
specs = []
for xml, folder in pairs:
    assets = {f: open(os.path.join(folder, f), 'rb').read() for f in os.listdir(folder)} if folder else {}
    specs.append(mujoco.MjSpec.from_string(open(xml).read(), assets=assets))
t = time.perf_counter()
for s in specs:
    s.compile()
print(time.perf_counter() - t)
"#;
    let out = std::process::Command::new(python)
        .args(["-c", script])
        .arg(dir.join("list"))
        .current_dir(&dir)
        .output()
        .ok()?;
    let _ = std::fs::remove_dir_all(&dir);
    String::from_utf8(out.stdout).ok()?.trim().parse().ok()
}

fn main() {
    let mujoco = MuJoCo::load().expect("MuJoCo 4.0.0 (set MUJOCO_LIB)");
    let python = std::env::var("MJCF_PYTHON").ok();
    let options = WriteOptions::default();
    println!("{:<58} {:>12} {:>12} {:>8} {:>12}", "workload", "ours", "MuJoCo", "ratio", "MjSpec");

    // The fleet: one model, compiled several times.
    let m = fleet(100);
    let ours = median(5, || {
        let w = m.to_xml_written(&options).expect("write");
        let a = m.assets(&options).expect("assets");
        std::hint::black_box((w, a));
    });
    let (xml, assets) = (m.to_xml_string().expect("write"), m.assets(&options).expect("assets"));
    let theirs = median(5, || {
        mujoco.compile_xml(&xml, &assets).expect("compiles");
    });
    let folder = std::env::temp_dir().join(format!("mjcf-bench-fleet-{}", std::process::id()));
    m.export(&folder, "fleet.xml", &options).expect("export");
    let spec = python.as_deref().and_then(|p| mjspec_seconds(p, &[(xml.clone(), folder.clone())]));
    let _ = std::fs::remove_dir_all(&folder);
    row("compile the N=100 fleet: write + hand-over vs MuJoCo's compile", ours, theirs, spec);

    // compose.rs's 200 variants: exported by the example, read back, each compiled once.
    let out = std::env::temp_dir().join(format!("mjcf-bench-variants-{}", std::process::id()));
    compose::compose(&repo().join("tests/conformance/cases/real_02_jaco_arm_with_hand"), &out)
        .expect("compose.rs");
    let variants: Vec<Model> = (0..200)
        .map(|v| Model::from_path(out.join(format!("variant_{v:03}.xml"))).expect("reads"))
        .collect();
    let start = Instant::now();
    let texts: Vec<_> = variants
        .iter()
        .map(|v| (v.to_xml_string().expect("write"), v.assets(&options).expect("assets")))
        .collect();
    let ours = start.elapsed();
    let start = Instant::now();
    for (xml, assets) in &texts {
        mujoco.compile_xml(xml, assets).expect("compiles");
    }
    let theirs = start.elapsed();
    let spec = python.as_deref().and_then(|p| {
        mjspec_seconds(p, &texts.iter().map(|(x, _)| (x.clone(), out.clone())).collect::<Vec<_>>())
    });
    let _ = std::fs::remove_dir_all(&out);
    row("compile compose.rs's 200 variants: ours vs MuJoCo's compile", ours, theirs, spec);

    // 1,000 variants differing in numbers: written into one compiled model, or compiled.
    let m = fleet(10);
    let geoms: Vec<_> = m.find_all(Namespace::Geom).into_iter().take(20).collect();
    let compiled = mujoco.compile(&m).expect("compiles");
    let mut physics = Physics::new(&compiled).expect("data");
    let bound: Vec<_> = geoms.iter().map(|g| physics.bind(g).expect("bound")).collect();
    let start = Instant::now();
    for v in 0..1000 {
        for b in &bound {
            physics.get_mut(b, "friction").expect("friction")[0] = 0.5 + (v % 10) as f64 * 0.1;
        }
        physics.reset().expect("reset");
        physics.forward().expect("forward");
    }
    let written = start.elapsed();
    let n = 50;
    let start = Instant::now();
    let mut variant = m.clone();
    for v in 0..n {
        for g in &geoms {
            variant
                .set_attr_mut(g, "friction", [0.5 + (v % 10) as f64 * 0.1, 0.005, 0.0001])
                .expect("set");
        }
        let c = mujoco.compile(&variant).expect("compiles");
        let mut p = Physics::new(&c).expect("data");
        p.forward().expect("forward");
    }
    let recompiled = start.elapsed() * (1000 / n) as u32;
    println!(
        "{:<58} {:>12} {:>12} {:>7.0}x",
        "1,000 variants of the N=10 fleet: written into one model vs compiled",
        ms(written),
        ms(recompiled),
        recompiled.as_secs_f64() / written.as_secs_f64()
    );
    println!("(recompiling measured over {n} variants and scaled to 1,000)");
}

fn row(what: &str, ours: Duration, theirs: Duration, spec: Option<f64>) {
    let spec = spec.map_or("-".to_string(), |s| format!("{:.2} ms", s * 1e3));
    println!(
        "{what:<58} {:>12} {:>12} {:>7.2}x {:>12}",
        ms(ours),
        ms(theirs),
        ours.as_secs_f64() / theirs.as_secs_f64(),
        spec
    );
}
