//! MuJoCo's integration state of a simulation, as arrays by name (the tests of
//! rebuilds compare them bit for bit).

use mjcf_mujoco::{ObjKind, Physics};

/// The f64 arrays of `mjSTATE_INTEGRATION` (time apart).
pub(crate) const ARRAYS: &[&str] = &[
    "qpos",
    "qvel",
    "act",
    "history",
    "qacc_warmstart",
    "ctrl",
    "qfrc_applied",
    "xfrc_applied",
    "mocap_pos",
    "mocap_quat",
    "userdata",
    "plugin_state",
    "plastic",
];

/// The state: time, the arrays, and each equality's `eq_active`, as f64.
pub(crate) fn state(p: &Physics) -> Vec<(&'static str, Vec<f64>)> {
    let mut out = vec![("time", vec![p.time()])];
    for f in ARRAYS {
        out.push((f, p.data(f).unwrap().to_vec()));
    }
    let neq = p.model().count(ObjKind::Equality);
    let active = (0..neq)
        .map(|e| f64::from(p.flags(&p.bind((ObjKind::Equality, e)).unwrap(), "active").unwrap()[0]))
        .collect();
    out.push(("eq_active", active));
    out
}

/// Gives `p` the state `s` (of a simulation of a model of the same layout).
#[allow(dead_code)]
pub(crate) fn set_state(p: &mut Physics, s: &[(&'static str, Vec<f64>)]) {
    for (name, v) in s {
        match *name {
            "time" => p.set_time(v[0]),
            "eq_active" => {
                for (e, x) in v.iter().enumerate() {
                    let b = p.bind((ObjKind::Equality, e)).unwrap();
                    p.flags_mut(&b, "active").unwrap()[0] = u8::from(*x != 0.0);
                }
            }
            _ => p.data_mut(name).unwrap().copy_from_slice(v),
        }
    }
}

/// The first array where `a` and `b` differ in any bit, with the largest relative
/// difference there.
#[allow(dead_code)]
pub(crate) fn first_difference(
    a: &[(&'static str, Vec<f64>)],
    b: &[(&'static str, Vec<f64>)],
) -> Option<(String, f64)> {
    for ((name, x), (_, y)) in a.iter().zip(b) {
        if x.len() != y.len() {
            return Some((format!("{name}: lengths {} and {}", x.len(), y.len()), f64::INFINITY));
        }
        if x.iter().zip(y).any(|(p, q)| p.to_bits() != q.to_bits()) {
            let rel = x
                .iter()
                .zip(y)
                .map(|(p, q)| (p - q).abs() / p.abs().max(q.abs()).max(1e-300))
                .fold(0.0, f64::max);
            return Some((name.to_string(), rel));
        }
    }
    None
}
