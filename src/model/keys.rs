//! Composed keyframes ([`WriteOptions::merge_keyframes`](crate::WriteOptions)): one
//! key per key name over the whole composed model.
//!
//! Each model's key of a name covers that model's own joints (its frames' joints
//! included), actuators and mocap bodies, in its own document order. The composed key
//! lays them out in the composed model's order (the order MuJoCo numbers them: the
//! writer's); where a model has no key of that name, its part is MuJoCo's default:
//! `qpos0` (a hinge's or slide's `ref`, a ball's unit quaternion, a free joint's body
//! pose in the world), zero velocities, activations and controls, and the mocap
//! bodies' poses.
//!
//! A free joint's position and orientation, and a mocap body's, are in the world of
//! the model whose key gives them: an attached model's are carried through the pose
//! of its attachment frame (as MuJoCo compiles it: the frame's position and
//! orientation in any of MJCF's forms, nested frames composed), and a free joint's
//! linear velocity is turned with it (its angular velocity is in the body's own
//! frame). The slots come from [`Model::layout`] (joint types and `ref` followed
//! through default classes). A parent's key without a name is kept, padded with
//! defaults; attached models' unnamed keys are dropped.

use std::collections::HashMap;

use smol_str::SmolStr;

use crate::error::{ErrorKind, WriteError};
use crate::model::Model;
use crate::model::layout::{JointType, Layout};
use crate::model::pose::{self, Pose, floats};
use crate::model::tree::Node;
use crate::value::Value;

/// One composed key, ready to write.
pub(crate) struct MergedKey {
    pub(crate) name: Option<SmolStr>,
    /// `(attribute, values)` in schema order; a field no model's key sets is left out.
    pub(crate) fields: Vec<(&'static str, Vec<f64>)>,
    pub(crate) time: Option<f64>,
}

/// `values[at..at + len]`, if the key has that many.
fn part<'k>(
    keys: &HashMap<usize, &'k Node>,
    inst: usize,
    field: &str,
    at: usize,
    len: usize,
) -> Option<&'k [f64]> {
    floats(keys.get(&inst)?, field)?.get(at..at.checked_add(len)?)
}

/// The composed values of each field for one key name (`keys`: the key of that name
/// per instance).
fn compose_fields(
    layout: &Layout<'_>,
    keys: &HashMap<usize, &Node>,
) -> [(&'static str, Vec<f64>); 6] {
    let (mut qpos, mut qvel, mut act, mut ctrl, mut mpos, mut mquat) =
        (Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new(), Vec::new());
    for j in &layout.joints {
        let origin = layout.origin(j.inst);
        let (nq, nv) = (j.joint_type.nq(), j.joint_type.nv());
        match part(keys, j.inst, "qpos", j.own_qpos, nq) {
            Some(q) if j.joint_type == JointType::Free => {
                let p = pose::compose(
                    origin,
                    Pose { pos: [q[0], q[1], q[2]], quat: [q[3], q[4], q[5], q[6]] },
                );
                qpos.extend_from_slice(&p.pos);
                qpos.extend_from_slice(&p.quat);
            }
            Some(q) => qpos.extend_from_slice(q),
            None => qpos.extend_from_slice(&j.qpos0),
        }
        match part(keys, j.inst, "qvel", j.own_dof, nv) {
            Some(v) if j.joint_type == JointType::Free => {
                qvel.extend_from_slice(&pose::rotate(origin.quat, [v[0], v[1], v[2]]));
                qvel.extend_from_slice(&v[3..6]);
            }
            Some(v) => qvel.extend_from_slice(v),
            None => qvel.extend(std::iter::repeat_n(0.0, nv)),
        }
    }
    for a in &layout.actuators {
        match part(keys, a.inst, "act", a.own_act, a.nact) {
            Some(v) => act.extend_from_slice(v),
            None => act.extend(std::iter::repeat_n(0.0, a.nact)),
        }
        match part(keys, a.inst, "ctrl", a.own_ctrl, a.nctrl) {
            Some(v) => ctrl.extend_from_slice(v),
            None => ctrl.extend(std::iter::repeat_n(0.0, a.nctrl)),
        }
    }
    for b in &layout.mocap {
        let origin = layout.origin(b.inst);
        let p = part(keys, b.inst, "mpos", 3 * b.own, 3);
        let q = part(keys, b.inst, "mquat", 4 * b.own, 4);
        let own = Pose {
            pos: p.map_or(b.pose.pos, |p| [p[0], p[1], p[2]]),
            quat: q.map_or(b.pose.quat, |q| pose::normalize4([q[0], q[1], q[2], q[3]])),
        };
        // A default pose is already in the composed world; a key's is in its model's.
        let world = match (p, q) {
            (None, None) => own,
            _ => pose::compose(origin, own),
        };
        mpos.extend_from_slice(&world.pos);
        mquat.extend_from_slice(&world.quat);
    }
    [("qpos", qpos), ("qvel", qvel), ("act", act), ("mpos", mpos), ("mquat", mquat), ("ctrl", ctrl)]
}

/// The most values one field of a composed key holds (`qpos` of a million free
/// joints): the writer refuses longer ones, whose sizes come from `<replicate>`
/// counts or an `actdim`, before making them.
pub(crate) const MAX_KEY_VALUES: usize =
    JointType::Free.nq() * crate::model::layout::MAX_LAYOUT_ENTRIES;

/// The composed keys of `model` (see the module documentation); none, with nothing
/// laid out, when the model has no key.
///
/// # Errors
/// [`WriteError::TooLarge`] if a field of the composed keys would hold more than
/// [`MAX_KEY_VALUES`] values, or the layout more than
/// [`MAX_LAYOUT_ENTRIES`](crate::model::layout::MAX_LAYOUT_ENTRIES) joints and
/// mocap bodies; checked before any is made.
pub(crate) fn merged_keys(model: &Model) -> Result<Vec<MergedKey>, WriteError> {
    let sizes = model.layout_sizes();
    if sizes.keys.is_empty() {
        return Ok(Vec::new());
    }
    let total = |k: usize| sizes.per_inst.values().fold(0usize, |s, n| s.saturating_add(n[k]));
    for (what, size) in [
        ("composed keys' qpos", total(0)),
        ("composed keys' qvel", total(1)),
        ("composed keys' act", total(2)),
        ("composed keys' ctrl", total(3)),
        ("composed keys' mquat", total(4).saturating_mul(4)),
    ] {
        if size > MAX_KEY_VALUES {
            return Err(WriteError::TooLarge { what, size, limit: MAX_KEY_VALUES });
        }
    }
    let layout = model.layout().map_err(|e| match e.kind() {
        ErrorKind::TooLarge { what, size, limit } => {
            WriteError::TooLarge { what, size: *size, limit: *limit }
        }
        other => WriteError::Conflict(other.to_string()),
    })?;
    // Key names in order of first appearance; the parent's unnamed keys by position.
    let mut order: Vec<Option<SmolStr>> = Vec::new();
    let mut by_name: Vec<HashMap<usize, &Node>> = Vec::new();
    let mut slot_of: HashMap<SmolStr, usize> = HashMap::new();
    for (inst, key, _) in &layout.keys {
        let name = key.identifier().map(SmolStr::from);
        if name.is_none() && *inst != 0 {
            continue;
        }
        let i = match name.as_ref().and_then(|n| slot_of.get(n)) {
            Some(&i) => i,
            None => {
                if let Some(n) = &name {
                    slot_of.insert(n.clone(), order.len());
                }
                order.push(name.clone());
                by_name.push(HashMap::new());
                order.len() - 1
            }
        };
        by_name[i].entry(*inst).or_insert(key);
    }
    let keys = order
        .into_iter()
        .zip(by_name)
        .map(|(name, keys)| {
            let sets = |field: &str| keys.values().any(|k| floats(k, field).is_some());
            let fields = compose_fields(&layout, &keys)
                .into_iter()
                // `qpos` is always written, so that every model's part is there.
                .filter(|(field, _)| *field == "qpos" || sets(field))
                .collect();
            // The parent's time, else that of the first model (in attach order) with one.
            let first = keys.iter().min_by_key(|(i, _)| **i).map(|(_, k)| *k);
            let time = keys
                .get(&0)
                .copied()
                .or(first)
                .and_then(|k| k.attr(k.kind().attr_index("time")?))
                .and_then(Value::as_float);
            MergedKey { name, fields, time }
        })
        .collect();
    Ok(keys)
}
