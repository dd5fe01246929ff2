//! Carrying MuJoCo's integration state (`mjSTATE_INTEGRATION`) from a running
//! simulation to the simulation of a newly compiled model, element by element.

use crate::bind::ObjKind;
use crate::fields::{self, Scalar};
use crate::physics::Physics;
use crate::rebuild::ids::{Ids, matching};
use crate::rebuild::{Carried, Defaulted, DefaultedWhy, Dropped, RebuildReport};
use crate::sys::{mjData, mjModel};

/// A data array of `p`, as a raw slice of `T`.
///
/// # Safety
/// `T` is the field's scalar type; the slice must not outlive `p`, nor alias another
/// live slice of the same field.
unsafe fn array<'a, T>(p: &Physics, name: &str, scalar: Scalar) -> &'a mut [T] {
    let Some(i) = fields::DATA_FIELDS.iter().position(|f| f.name == name) else {
        return &mut [];
    };
    // SAFETY: valid model and data of `p`.
    let (m, d): (&mjModel, &mjData) = unsafe { (&*p.m(), p.d()) };
    let Some(raw) = fields::data_field(d, m, i) else { return &mut [] };
    // SAFETY: as the caller promises.
    unsafe { raw.slice_mut(&fields::DATA_FIELDS[i], scalar, "") }.unwrap_or_default()
}

/// Copies `n` scalars of field `name` from `old` at `from` to `new` at `to`.
fn copy<T: Copy>(
    old: &Physics,
    new: &Physics,
    name: &str,
    s: Scalar,
    from: usize,
    to: usize,
    n: usize,
) {
    // SAFETY: two data of two simulations; the slices live for this call only.
    let (src, dst) = unsafe { (array::<T>(old, name, s), array::<T>(new, name, s)) };
    if from + n <= src.len() && to + n <= dst.len() {
        dst[to..to + n].copy_from_slice(&src[from..from + n]);
    }
}

fn ints<'a>(p: &'a Physics, name: &str) -> &'a [i32] {
    p.model().ints(name).unwrap_or_default()
}

fn at(v: &[i32], i: usize) -> usize {
    v.get(i).and_then(|&x| usize::try_from(x).ok()).unwrap_or(usize::MAX)
}

/// Positions and degrees of freedom of a joint of MuJoCo type `t`.
fn widths(t: i32) -> (usize, usize) {
    match u32::try_from(t).unwrap_or(u32::MAX) {
        crate::sys::mjtJoint_mjJNT_FREE => (7, 6),
        crate::sys::mjtJoint_mjJNT_BALL => (4, 3),
        _ => (1, 1),
    }
}

/// Carries the state of `old` into `new` (just made, at its defaults), recording
/// what was carried, defaulted and dropped in `report`.
pub(crate) fn carry(
    old: &Physics,
    new: &mut Physics,
    ids: Option<(&Ids, &Ids)>,
    report: &mut RebuildReport,
) {
    new.set_time(old.time());
    let mut per_kind =
        |kind: ObjKind, each: &mut dyn FnMut(usize, usize) -> Option<DefaultedWhy>| {
            let matched = matching(old.model(), new.model(), kind, ids);
            let mut used = vec![false; old.model().count(kind)];
            for (id, o) in matched.old_of.iter().enumerate() {
                let name = new.model().name(kind, id).unwrap_or_default().to_string();
                let why = match o {
                    Some(o) => {
                        used[*o] = true;
                        each(id, *o)
                    }
                    None => Some(DefaultedWhy::New),
                };
                match (why, o) {
                    (None, Some(o)) => {
                        let old_name = old.model().name(kind, *o).unwrap_or_default().to_string();
                        report.carried.push(Carried { kind, name, old_name });
                    }
                    (Some(why), _) => report.defaulted.push(Defaulted { kind, name, why }),
                    (None, None) => {}
                }
            }
            for (o, used) in used.iter().enumerate() {
                if !used {
                    let name = old.model().name(kind, o).unwrap_or_default().to_string();
                    report.dropped.push(Dropped { kind, name });
                }
            }
        };
    let (ot, nt) = (ints(old, "jnt_type"), ints(new, "jnt_type"));
    let (oq, nq) = (ints(old, "jnt_qposadr"), ints(new, "jnt_qposadr"));
    let (od, nd) = (ints(old, "jnt_dofadr"), ints(new, "jnt_dofadr"));
    per_kind(ObjKind::Joint, &mut |j, o| {
        if ot.get(o) != nt.get(j) {
            return Some(DefaultedWhy::TypeChanged);
        }
        let (q, v) = widths(nt[j]);
        copy::<f64>(old, new, "qpos", Scalar::F64, at(oq, o), at(nq, j), q);
        for f in ["qvel", "qacc_warmstart", "qfrc_applied"] {
            copy::<f64>(old, new, f, Scalar::F64, at(od, o), at(nd, j), v);
        }
        None
    });
    let (oca, nca) = (ints(old, "actuator_ctrladr"), ints(new, "actuator_ctrladr"));
    let (ocn, ncn) = (ints(old, "actuator_ctrlnum"), ints(new, "actuator_ctrlnum"));
    let (oaa, naa) = (ints(old, "actuator_actadr"), ints(new, "actuator_actadr"));
    let (oan, nan) = (ints(old, "actuator_actnum"), ints(new, "actuator_actnum"));
    per_kind(ObjKind::Actuator, &mut |a, o| {
        if oan.get(o) != nan.get(a) {
            return Some(DefaultedWhy::ActivationChanged);
        }
        if ocn.get(o) != ncn.get(a) {
            return Some(DefaultedWhy::ControlsChanged);
        }
        copy::<f64>(old, new, "ctrl", Scalar::F64, at(oca, o), at(nca, a), at(ncn, a));
        let n = usize::try_from(nan.get(a).copied().unwrap_or(0)).unwrap_or(0);
        if n > 0 {
            copy::<f64>(old, new, "act", Scalar::F64, at(oaa, o), at(naa, a), n);
        }
        None
    });
    let (om, nm) = (ints(old, "body_mocapid"), ints(new, "body_mocapid"));
    per_kind(ObjKind::Body, &mut |b, o| {
        copy::<f64>(old, new, "xfrc_applied", Scalar::F64, 6 * o, 6 * b, 6);
        let (from, to) = (at(om, o), at(nm, b));
        if from != usize::MAX && to != usize::MAX {
            copy::<f64>(old, new, "mocap_pos", Scalar::F64, 3 * from, 3 * to, 3);
            copy::<f64>(old, new, "mocap_quat", Scalar::F64, 4 * from, 4 * to, 4);
        } else if to != usize::MAX {
            return Some(DefaultedWhy::NewMocap);
        }
        None
    });
    per_kind(ObjKind::Equality, &mut |e, o| {
        copy::<u8>(old, new, "eq_active", Scalar::Bool, o, e, 1);
        None
    });
    carry_global(old, new, ids.is_some(), report);
}

/// Arrays of the whole model (user data, plugin state, history buffers, plastic
/// state): carried when both models lay them out alike, else at their defaults.
fn carry_global(old: &Physics, new: &Physics, related: bool, report: &mut RebuildReport) {
    // SAFETY: valid models of both simulations.
    let (om, nm): (&mjModel, &mjModel) = unsafe { (&*old.m(), &*new.m()) };
    let same_layout =
        |a: &[&str]| a.iter().all(|f| old.model().ints(f).ok() == new.model().ints(f).ok());
    let arrays: [(&str, i64, i64, bool); 4] = [
        ("userdata", om.nuserdata, nm.nuserdata, true),
        ("plugin_state", om.npluginstate, nm.npluginstate, related && om.nplugin == nm.nplugin),
        (
            "history",
            om.nhistory,
            nm.nhistory,
            related && same_layout(&["actuator_historyadr", "sensor_historyadr"]),
        ),
        (
            "plastic",
            om.nplastic,
            nm.nplastic,
            related && same_layout(&["jnt_plasticadr", "tendon_plasticadr"]),
        ),
    ];
    for (name, o, n, alike) in arrays {
        if n == 0 {
            continue;
        }
        if o == n && alike {
            let n = usize::try_from(n).unwrap_or(0);
            copy::<f64>(old, new, name, Scalar::F64, 0, 0, n);
        } else {
            report
                .notes
                .push(format!("{name}: laid out otherwise in the new model; at its defaults"));
        }
    }
}
