//! compose.py: 200 randomized variants of a composed scene, built in parallel and exported.
use mjcf::{Model, Namespace, WriteOptions, element};
use std::f64::consts::PI;
use std::path::Path;

fn u(s: &mut u64, lo: f64, hi: f64) -> f64 {
    *s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407); // Knuth's LCG
    lo + (hi - lo) * (*s >> 11) as f64 / (1u64 << 53) as f64
}

fn main() -> Result<(), mjcf::Error> {
    let out = std::env::args().nth(1).unwrap_or("variants".into());
    compose(Path::new("tests/conformance/cases/real_02_jaco_arm_with_hand"), Path::new(&out))
}

/// The whole job, timed by `benches/figures.rs` (W8): the models read from `case`, the
/// scene, and its 200 variants exported to `out`.
pub fn compose(case: &Path, out: &Path) -> Result<(), mjcf::Error> {
    let mut arm = Model::from_path(case.join("jaco_arm.xml"))?;
    for i in 1..=6 {
        let motor = element!("motor", name = format!("m{i}"), joint = format!("joint_{i}"));
        arm.add_mut(&arm.actuator(), motor.attr("gear", [10]))?;
    }
    let hand = Model::from_path(case.join("jaco_hand.xml"))?;
    arm.attach_mut(&arm.lookup(Namespace::Site, "wristsite")?, &hand)?;

    let (mut arena, s, mut props) = (Model::new("arena"), &mut 1, Vec::new());
    let w = arena.worldbody();
    arena.add_mut(&w, element!("light", pos = [0, 0, 3], directional = true))?;
    arena.add_mut(&w, element!("geom", name = "floor", type = "plane", size = [3., 3., 0.1]))?;
    let left = arena.add_mut(&w, element!("site", name = "left", pos = [-0.6, 0., 0.]))?;
    let right = element!("site", name = "right", pos = [0.6, 0., 0.], euler = [0., 0., PI]);
    let right = arena.add_mut(&w, right)?;
    arena.attach_mut(&left, &arm)?; // one arm value attached twice: nothing is copied
    arena.attach_mut(&right, &arm)?;
    for n in (0..10).map(|i| format!("prop_{i}")) {
        let body = element!("body", name = &n, pos = [u(s, -1., 1.), u(s, -1., 1.), 0.5]);
        let body = arena.add_mut(&w, body.child(element!("freejoint", name = &n)))?;
        let geom = element!("geom", name = &n, type = "box", size = [0.03; 3], mass = 0.1);
        props.push((body.clone(), arena.add_mut(&body, geom)?));
    }

    let ring = arena.lookup(Namespace::Geom, "jaco_arm_1/ring_2")?;
    let variant = |v: u64| -> Result<(), mjcf::Error> {
        let (mut m, s) = (arena.clone(), &mut v.clone()); // an O(1) clone of the scene
        for (body, geom) in &props {
            m.set_attr_mut(body, "pos", [u(s, -1., 1.), u(s, -1., 1.), 0.5])?;
            m.set_attr_mut(geom, "rgba", [u(s, 0., 1.), u(s, 0., 1.), u(s, 0., 1.), 1.])?;
        }
        m.set_attr_mut(&ring, "size", [u(s, 0.03, 0.06), 0.011])?;
        Ok(m.export(out, &format!("variant_{v:03}.xml"), &WriteOptions::default()).map(drop)?)
    };
    std::thread::scope(|sc| {
        let workers = [0, 1].map(|t| sc.spawn(move || (t..200).step_by(2).try_for_each(variant)));
        workers.into_iter().try_for_each(|h| h.join().expect("a variant panicked"))
    })
}
