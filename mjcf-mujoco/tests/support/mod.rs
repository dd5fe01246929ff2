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

/// The compiled arrays two compiles of one model must agree on (those
/// tools/readback_check.py compared): positions, orientations, masses and inertias,
/// sizes, joint ranges and axes, gains and biases, default poses. Keyframes are the
/// caller's to add (a saved scene lays attached keys out as MuJoCo does).
#[allow(dead_code)]
pub(crate) const COMPARED_FLOATS: &[&str] = &[
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
    "tendon_stiffness",
];

/// The integer arrays compared beside [`COMPARED_FLOATS`].
#[allow(dead_code)]
pub(crate) const COMPARED_INTS: &[&str] = &[
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

/// The first of the arrays `floats`, `geom_rgba` and [`COMPARED_INTS`] where `a` and
/// `b` differ (floats beyond a relative 1e-12), if any.
#[allow(dead_code)]
pub(crate) fn array_difference(
    a: &mjcf_mujoco::Compiled,
    b: &mjcf_mujoco::Compiled,
    floats: &[&str],
) -> Option<String> {
    for field in floats {
        let (x, y) = (a.floats(field).ok()?, b.floats(field).ok()?);
        if x.len() != y.len()
            || x.iter().zip(y).any(|(p, q)| {
                p.to_bits() != q.to_bits() && (p - q).abs() > 1e-12 * p.abs().max(1.0)
            })
        {
            return Some(format!("{field}: {x:?} vs {y:?}"));
        }
    }
    if a.floats32("geom_rgba").ok()? != b.floats32("geom_rgba").ok()? {
        return Some("geom_rgba differs".into());
    }
    for field in COMPARED_INTS {
        if a.ints(field).ok()? != b.ints(field).ok()? {
            return Some(format!("{field} differs"));
        }
    }
    None
}
