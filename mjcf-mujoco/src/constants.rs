//! Writing numbers into a compiled model: which fields can be written in place, and
//! what must follow a write so that the model is what compiling the edited model
//! gives.
//!
//! MuJoCo's compiler ends with `mj_setConst`, which derives constants from the model's
//! numbers in its reference configuration (`qpos0`): each body's subtree mass and
//! inverse weights, each degree of freedom's `M0`, `invweight0` and length, tendon and
//! actuator lengths and accelerations at `qpos0`, cameras' and lights' reference
//! poses, the model's statistics (mean inertia, extent), which frames coincide
//! (`*_sameframe`), the trees and their sleep policies (a damping ratio is turned
//! into a damping by the compiler alone, in MuJoCo 4.0.0). The binding runs it again after a
//! write of a field it reads, with a scratch `mjData` of its own, reset first (never
//! the running simulation's data: `mj_setConst` moves the data it is given to
//! `qpos0`). Fields the compiler derives more from than `mj_setConst` recomputes are
//! refused ([`Class::Refused`]): a geom's size, pose and margin (the body's mass and
//! inertia when taken from its geoms, bounding volumes, the body's margin), meshes,
//! height fields, flexes, skins and textures (compile-time geometry), the derived
//! constants themselves (they would be recomputed over the write), and a free body's
//! pose (its free joint's `qpos0` is the pose it had at compile time). Those need a
//! rebuild from the edited model ([`Physics::rebuild`](crate::Physics::rebuild)).

/// What writing a model field takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Class {
    /// Nothing derives from it: the write alone is what compiling gives.
    Free,
    /// `mj_setConst` derives constants from it: recomputed after the write.
    SetConst,
    /// The compiler derives more from it than `mj_setConst` recomputes.
    Refused(&'static str),
}

/// Fields nothing is derived from (contact and constraint parameters, gains, passive
/// forces MuJoCo applies as given). `mj_setConst` reads none of them.
const FREE: &[&str] = &[
    "geom_friction",
    "geom_solref",
    "geom_solimp",
    "geom_solmix",
    "geom_user",
    "dof_frictionloss",
    "dof_damping",
    "dof_dampingpoly",
    "dof_solref",
    "dof_solimp",
    "jnt_solref",
    "jnt_solimp",
    "jnt_stiffness",
    "jnt_stiffnesspoly",
    "jnt_margin",
    "jnt_user",
    "body_user",
    "actuator_gainprm",
    "actuator_dynprm",
    "actuator_ctrlrange",
    "actuator_forcerange",
    "actuator_actrange",
    "actuator_user",
    "pair_friction",
    "pair_solref",
    "pair_solreffriction",
    "pair_solimp",
    "eq_solref",
    "eq_solimp",
    "tendon_frictionloss",
    "tendon_solref_lim",
    "tendon_solimp_lim",
    "tendon_solref_fri",
    "tendon_solimp_fri",
    "sensor_noise",
    "sensor_cutoff",
];

const DERIVED: &str = "MuJoCo derives it from the model's other numbers (mj_setConst or the compiler); \
     write what it is derived from";
const GEOMETRY: &str = "compile-time geometry (bounding volumes, meshes, inertia from geoms)";

/// Constants MuJoCo derives (written over by `mj_setConst` or fixed by the compiler).
const DERIVED_FIELDS: &[&str] = &[
    "body_subtreemass",
    "body_invweight0",
    "body_margin",
    "dof_invweight0",
    "dof_M0",
    "dof_length",
    "tendon_invweight0",
    "tendon_length0",
    "actuator_acc0",
    "actuator_length0",
    "actuator_lengthrange",
    "cam_pos0",
    "cam_poscom0",
    "cam_mat0",
    "light_pos0",
    "light_poscom0",
    "light_dir0",
    "geom_rbound",
    "geom_aabb",
];

/// Fields the compiler derives a body's inertia, bounding volumes or margins from.
const GEOM_FIELDS: &[&str] = &["geom_size", "geom_pos", "geom_quat", "geom_margin", "geom_gap"];

/// Prefixes of compile-time geometry.
const GEOMETRY_PREFIXES: &[&str] =
    &["mesh_", "hfield_", "tex_", "flex_", "flexvert_", "flexedge_", "skin_", "bvh_", "oct_"];

/// What writing the model field `name` takes.
pub(crate) fn class(name: &str) -> Class {
    if FREE.contains(&name) {
        Class::Free
    } else if DERIVED_FIELDS.contains(&name) {
        Class::Refused(DERIVED)
    } else if GEOM_FIELDS.contains(&name) {
        Class::Refused(
            "the compiler derives the body's mass and inertia (from its geoms), bounding \
             volumes and margins from it",
        )
    } else if GEOMETRY_PREFIXES.iter().any(|p| name.starts_with(p)) {
        Class::Refused(GEOMETRY)
    } else {
        Class::SetConst
    }
}

/// Why a free body's pose cannot be written in place.
pub(crate) const FREE_BODY_POSE: &str =
    "the body has a free joint, whose qpos0 is the pose the body had when compiled";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_listed_field_is_a_float_field_of_the_model() {
        for name in FREE.iter().chain(DERIVED_FIELDS).chain(GEOM_FIELDS) {
            let field = crate::fields::MODEL_FIELDS.iter().find(|f| f.name == *name);
            assert!(field.is_some(), "{name} is no field of mjModel");
        }
    }

    #[test]
    fn masses_and_poses_take_set_const_sizes_and_derived_constants_are_refused() {
        assert_eq!(class("body_mass"), Class::SetConst);
        assert_eq!(class("body_pos"), Class::SetConst);
        assert_eq!(class("dof_armature"), Class::SetConst);
        assert_eq!(class("geom_friction"), Class::Free);
        assert!(matches!(class("geom_size"), Class::Refused(_)));
        assert!(matches!(class("body_subtreemass"), Class::Refused(_)));
        assert!(matches!(class("mesh_vert"), Class::Refused(_)));
    }
}
