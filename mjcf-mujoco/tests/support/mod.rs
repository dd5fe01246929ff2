//! Shared by the binding's tests: MuJoCo, loaded from `MUJOCO_LIB`.

use mjcf_mujoco::MuJoCo;

/// MuJoCo 4.0.0, from `MUJOCO_LIB` (the tests that call this are ignored in a plain
/// `cargo test`; `.ci/run` runs them with the pinned wheel's library).
pub(crate) fn mujoco() -> MuJoCo {
    match MuJoCo::load() {
        Ok(m) => m,
        Err(e) => panic!("this test needs MuJoCo 4.0.0: {e}"),
    }
}

use mjcf_mujoco::{Compiled, ObjKind};

/// The compiled models' arrays two compiles of the same model must agree on (those
/// tools/readback_check.py compared): positions, orientations, masses and inertias,
/// sizes, joint ranges and axes, gains and biases, default poses, keyframes.
const FLOATS: &[&str] = &[
    "body_pos",
    "body_quat",
    "body_ipos",
    "body_iquat",
    "body_mass",
    "body_inertia",
    "jnt_pos",
    "jnt_axis",
    "jnt_range",
    "dof_damping",
    "dof_armature",
    "dof_frictionloss",
    "geom_size",
    "geom_pos",
    "geom_quat",
    "geom_friction",
    "site_pos",
    "site_size",
    "actuator_gear",
    "actuator_gainprm",
    "actuator_biasprm",
    "actuator_ctrlrange",
    "qpos0",
    "key_qpos",
    "key_ctrl",
    "tendon_stiffness",
];
const INTS: &[&str] = &[
    "body_parentid",
    "jnt_type",
    "geom_type",
    "geom_contype",
    "geom_conaffinity",
    "actuator_trntype",
    "actuator_trnid",
    "sensor_type",
    "sensor_objid",
];

/// The first difference between two compiled models, as MuJoCo sees them: sizes, the
/// names of every kind of element in order, and the arrays above, exactly.
pub(crate) fn compiled_difference(a: &Compiled, b: &Compiled) -> Option<String> {
    if a.sizes() != b.sizes() {
        return Some(format!("sizes {:?} vs {:?}", a.sizes(), b.sizes()));
    }
    for kind in ObjKind::ALL {
        let names = |m: &Compiled| -> Vec<Option<String>> {
            (0..m.count(kind)).map(|i| m.name(kind, i).map(str::to_string)).collect()
        };
        if a.count(kind) != b.count(kind) || names(a) != names(b) {
            return Some(format!("{} names: {:?} vs {:?}", kind.name(), names(a), names(b)));
        }
    }
    for field in FLOATS {
        let (x, y) = (a.floats(field).ok()?, b.floats(field).ok()?);
        if x.iter()
            .zip(y)
            .any(|(p, q)| p.to_bits() != q.to_bits() && (p - q).abs() > 1e-12 * p.abs().max(1.0))
        {
            return Some(format!("{field}: {x:?} vs {y:?}"));
        }
    }
    if a.floats32("geom_rgba").ok()? != b.floats32("geom_rgba").ok()? {
        return Some("geom_rgba differs".into());
    }
    for field in INTS {
        if a.ints(field).ok()? != b.ints(field).ok()? {
            return Some(format!("{field} differs"));
        }
    }
    None
}
