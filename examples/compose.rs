//! compose.py: 200 randomized variants of a composed scene, built and exported.
use mjcf::{Model, Namespace, element};
use std::path::Path;

fn u(s: &mut u64, lo: f64, hi: f64) -> f64 {
    *s = (u128::from(*s) * 6364136223846793005 + 1442695040888963407) as u64; // Knuth's LCG
    lo + (hi - lo) * (*s >> 11) as f64 / (1u64 << 53) as f64
}

fn main() -> Result<(), mjcf::Error> {
    let out = std::env::args().nth(1).unwrap_or("variants".into());
    let case = Path::new("tests/conformance/cases/real_02_jaco_arm_with_hand");
    compose(case, Path::new(&out))
}

/// The whole job (W8 of `benches/figures.rs`): models read from `case`, variants to `out`.
pub fn compose(case: &Path, out: &Path) -> Result<(), mjcf::Error> {
    let mut arm = Model::from_path(case.join("jaco_arm.xml"))?;
    for (name, joint) in (1..=6).map(|i| (format!("m{i}"), format!("joint_{i}"))) {
        arm.add_top_mut(element!("motor", name = name, joint = joint, gear = [10]))?;
    }
    let hand = Model::from_path(case.join("jaco_hand.xml"))?;
    arm.attach_mut(&arm.lookup(Namespace::Site, "wristsite")?, &hand)?;

    let (mut arena, s, mut props) = (Model::new("arena"), &mut 1, Vec::new());
    arena.add_top_mut(element!("light", pos = [0, 0, 3], directional = true))?;
    arena.add_top_mut(element!("geom", name = "floor", type = "plane", size = [3, 3, 0.1]))?;
    let left = arena.add_top_mut(element!("site", name = "left", pos = [-0.6, 0, 0]))?;
    let turn = [0.0, 0.0, std::f64::consts::PI];
    let right = element!("site", name = "right", pos = [0.6, 0, 0], euler = turn);
    let right = arena.add_top_mut(right)?;
    arena.attach_mut(&left, &arm)?; // one arm value attached twice: nothing is copied
    arena.attach_mut(&right, &arm)?;
    for n in (0..10).map(|i| format!("prop_{i}")) {
        let body = element!("body", name = &n, pos = [u(s, -1., 1.), u(s, -1., 1.), 0.5]);
        let body = arena.add_top_mut(body.child(element!("freejoint", name = &n)))?;
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
        m.export(out, &format!("variant_{v:03}.xml"), &Default::default())?;
        Ok(())
    };
    (0..200).try_for_each(variant)
}
