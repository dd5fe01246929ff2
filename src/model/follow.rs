//! Keys that follow their elements: the rule, and the models it is not applied to,
//! are the guide's ([What it does](crate::guide#what-it-does)); this is how an edit
//! that adds, removes, reorders or retypes a model's own joints, actuators or mocap
//! bodies rewrites each of the model's own keys.
//!
//! A key's arrays (`qpos`, `qvel`, `act`, `ctrl`, `mpos`, `mquat`) are read against
//! the own layout before the edit (`super::layout`, as
//! [`WriteOptions::merge_keyframes`](crate::WriteOptions::merge_keyframes) reads
//! them), short arrays padded as MuJoCo pads them (`qpos` with the joints' default
//! positions, `mpos`/`mquat` with the mocap bodies' poses, the rest with zeros), then
//! laid out again after it: an element is the same when its id, type and width are,
//! and only the arrays a key has are rewritten (a key without `qpos` keeps MuJoCo's
//! `qpos0`).

use std::collections::HashMap;

use crate::schema::{ElementKind, Role};
use crate::value::Value;

use super::layout::Layout;
use super::tree::{ElementId, Node};
use super::{Attrs, Model};

/// A key array: its attribute and, per element of the own layout, its id, width and
/// default values.
type Slots = Vec<(ElementId, usize, Vec<f64>)>;

/// The own layout's slots for each key array, or `None` when keys are not followed
/// (see the module documentation).
fn slots(layout: &Layout<'_>) -> Option<[(&'static str, Slots); 6]> {
    if !layout.unexpanded.is_empty() {
        return None;
    }
    let joints: Vec<_> = layout.joints.iter().filter(|j| j.inst == 0).collect();
    let actuators: Vec<_> = layout.actuators.iter().filter(|a| a.inst == 0).collect();
    let mocap: Vec<_> = layout.mocap.iter().filter(|m| m.inst == 0).collect();
    let mut ids: Vec<ElementId> = joints.iter().map(|j| j.loc.id()).collect();
    ids.extend(actuators.iter().map(|a| a.loc.id()));
    ids.extend(mocap.iter().map(|m| m.loc.id()));
    let n = ids.len();
    ids.sort_unstable();
    ids.dedup();
    if ids.len() != n {
        return None;
    }
    let qpos = joints.iter().map(|j| (j.loc.id(), j.joint_type.nq(), j.qpos0.clone())).collect();
    let qvel = joints
        .iter()
        .map(|j| (j.loc.id(), j.joint_type.nv(), vec![0.0; j.joint_type.nv()]))
        .collect();
    let act = actuators.iter().map(|a| (a.loc.id(), a.nact, vec![0.0; a.nact])).collect();
    let ctrl = actuators.iter().map(|a| (a.loc.id(), a.nctrl, vec![0.0; a.nctrl])).collect();
    let mpos = mocap.iter().map(|m| (m.loc.id(), 3, m.pose.pos.to_vec())).collect();
    let mquat = mocap.iter().map(|m| (m.loc.id(), 4, m.pose.quat.to_vec())).collect();
    Some([
        ("qpos", qpos),
        ("qvel", qvel),
        ("act", act),
        ("ctrl", ctrl),
        ("mpos", mpos),
        ("mquat", mquat),
    ])
}

/// The values of `array` (as written, padded with each slot's default) by element.
fn by_element(array: &[f64], slots: &Slots) -> HashMap<ElementId, (usize, Vec<f64>)> {
    let mut at = 0;
    let mut out = HashMap::with_capacity(slots.len());
    for (id, width, default) in slots {
        let values =
            (0..*width).map(|k| array.get(at + k).copied().unwrap_or(default[k])).collect();
        out.insert(*id, (*width, values));
        at += width;
    }
    out
}

/// Whether an edit of a subtree holding `node` can change the own layout: it holds
/// a joint, an actuator or a body (a mocap body, or one holding joints).
pub(crate) fn moves_layout(node: &Node) -> bool {
    node.descendants().any(|n| {
        let k = n.kind();
        k.is(Role::Joint)
            || k.is(Role::Freejoint)
            || k.is(Role::Body)
            || k.role().is_some_and(|r| r.is_actuator())
    })
}

/// The model's own keys that hold an array, if any.
fn keys_with_arrays(m: &Model) -> Vec<&Node> {
    keys_holding_arrays(m).collect()
}

/// [`keys_with_arrays`], as they are found: the keyframe section looked for from the
/// end of the root's children, where the schema's order puts it.
fn keys_holding_arrays(m: &Model) -> impl Iterator<Item = &Node> {
    let section = m.root.children().iter().rev().find(|c| c.kind() == ElementKind::KEYFRAME);
    section.into_iter().flat_map(|s| s.children().iter()).filter(|k| {
        k.kind().is(Role::Key) && k.attrs().iter().any(|(_, v)| v.as_floats().is_some())
    })
}

/// Whether `m` has own keys for an edit to follow.
pub(crate) fn has_keys(m: &Model) -> bool {
    keys_holding_arrays(m).next().is_some()
}

impl Model {
    /// `after` (this model edited) with its own keys rewritten so that each value
    /// stays with its element (see the module documentation); `after` itself when
    /// nothing moved or keys cannot be followed.
    ///
    /// Time: O(n) for the two layouts, plus O(k · a) for `k` keys of `a` values.
    pub(crate) fn keys_followed(&self, after: Model) -> Model {
        let keys = keys_with_arrays(&after);
        if keys.is_empty() {
            return after;
        }
        // A layout too large to list (`<replicate>` counts) is not followed.
        let (Ok(before_layout), Ok(after_layout)) = (self.layout(), after.layout()) else {
            return after;
        };
        let (Some(old), Some(new)) = (slots(&before_layout), slots(&after_layout)) else {
            return after;
        };
        let same = old.iter().zip(&new).all(|((_, a), (_, b))| {
            a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.0 == y.0 && x.1 == y.1)
        });
        if same {
            return after;
        }
        let edits: Vec<(ElementId, Attrs)> = keys
            .iter()
            .map(|key| {
                let mut attrs = Attrs::new();
                for ((name, old_slots), (_, new_slots)) in old.iter().zip(&new) {
                    let kind = key.kind();
                    let Some(Value::Floats(array)) =
                        kind.attr_index(name).and_then(|i| key.attr(i))
                    else {
                        continue;
                    };
                    let was = by_element(array, old_slots);
                    let mut now = Vec::new();
                    for (id, width, default) in new_slots {
                        match was.get(id) {
                            Some((w, values)) if w == width => now.extend_from_slice(values),
                            _ => now.extend_from_slice(default),
                        }
                    }
                    // An array left with no element goes (MuJoCo reads an empty one
                    // as none, but the file need not say it).
                    attrs = if now.is_empty() { attrs.clear(name) } else { attrs.set(name, now) };
                }
                (key.id(), attrs)
            })
            .collect();
        let mut out = after.clone();
        for (id, attrs) in edits {
            let loc = out.scoped_loc(&[], id);
            match out.set(&loc, attrs) {
                Ok(m) => out = m,
                // A key the edit cannot rewrite stays as it was.
                Err(_) => continue,
            }
        }
        out
    }
}
