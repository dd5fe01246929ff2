//! Carrying MuJoCo's integration state (`mjSTATE_INTEGRATION`) from a running
//! simulation to the simulation of a newly compiled model, element by element.

use mjcf::JointType;

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

/// A data array of `old` and of `new`, found once.
struct Pair<'a, T> {
    src: &'a mut [T],
    dst: &'a mut [T],
}

impl<T: Copy> Pair<'_, T> {
    fn new(old: &Physics, new: &Physics, name: &str, s: Scalar) -> Self {
        // SAFETY: two data of two simulations; each field is taken once, and the
        // pair lives for one `carry` call, while both simulations do.
        unsafe { Pair { src: array::<T>(old, name, s), dst: array::<T>(new, name, s) } }
    }

    /// Copies `n` scalars from `from` to `to`.
    fn copy(&mut self, from: usize, to: usize, n: usize) {
        if from.saturating_add(n) <= self.src.len() && to.saturating_add(n) <= self.dst.len() {
            self.dst[to..to + n].copy_from_slice(&self.src[from..from + n]);
        }
    }
}

fn ints<'a>(p: &'a Physics, name: &str) -> &'a [i32] {
    p.model().ints(name).unwrap_or_default()
}

fn at(v: &[i32], i: usize) -> usize {
    v.get(i).and_then(|&x| usize::try_from(x).ok()).unwrap_or(usize::MAX)
}

/// Positions and degrees of freedom of a joint of MuJoCo type `t` (none for a number
/// MuJoCo does not use).
fn widths(t: i32) -> (usize, usize) {
    JointType::from_mujoco(t.into()).map_or((0, 0), |t| (t.nq(), t.nv()))
}

/// Carries the state of `old` into `new` (just made, at its defaults), recording
/// what was carried, defaulted and dropped in `report`.
pub(crate) fn carry(
    old: &Physics,
    new: &mut Physics,
    ids: Option<(&Ids, &Ids)>,
    report: &mut RebuildReport,
    carried: &mut Vec<Carried>,
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
                        carried.push(Carried { kind, name, old_name });
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
    let f64s = |name: &str| Pair::<f64>::new(old, new, name, Scalar::F64);
    let mut qpos = f64s("qpos");
    let mut dofs = [f64s("qvel"), f64s("qacc_warmstart"), f64s("qfrc_applied")];
    per_kind(ObjKind::Joint, &mut |j, o| {
        if ot.get(o) != nt.get(j) {
            return Some(DefaultedWhy::TypeChanged);
        }
        let (q, v) = widths(nt[j]);
        qpos.copy(at(oq, o), at(nq, j), q);
        for f in &mut dofs {
            f.copy(at(od, o), at(nd, j), v);
        }
        None
    });
    let (oca, nca) = (ints(old, "actuator_ctrladr"), ints(new, "actuator_ctrladr"));
    let (ocn, ncn) = (ints(old, "actuator_ctrlnum"), ints(new, "actuator_ctrlnum"));
    let (oaa, naa) = (ints(old, "actuator_actadr"), ints(new, "actuator_actadr"));
    let (oan, nan) = (ints(old, "actuator_actnum"), ints(new, "actuator_actnum"));
    let (mut ctrl, mut act) = (f64s("ctrl"), f64s("act"));
    per_kind(ObjKind::Actuator, &mut |a, o| {
        if oan.get(o) != nan.get(a) {
            return Some(DefaultedWhy::ActivationChanged);
        }
        if ocn.get(o) != ncn.get(a) {
            return Some(DefaultedWhy::ControlsChanged);
        }
        ctrl.copy(at(oca, o), at(nca, a), at(ncn, a));
        let n = usize::try_from(nan.get(a).copied().unwrap_or(0)).unwrap_or(0);
        if n > 0 {
            act.copy(at(oaa, o), at(naa, a), n);
        }
        None
    });
    let (om, nm) = (ints(old, "body_mocapid"), ints(new, "body_mocapid"));
    let (mut xfrc, mut mpos, mut mquat) =
        (f64s("xfrc_applied"), f64s("mocap_pos"), f64s("mocap_quat"));
    per_kind(ObjKind::Body, &mut |b, o| {
        xfrc.copy(6 * o, 6 * b, 6);
        let (from, to) = (at(om, o), at(nm, b));
        if from != usize::MAX && to != usize::MAX {
            mpos.copy(3 * from, 3 * to, 3);
            mquat.copy(4 * from, 4 * to, 4);
        } else if to != usize::MAX {
            return Some(DefaultedWhy::NewMocap);
        }
        None
    });
    let mut active = Pair::<u8>::new(old, new, "eq_active", Scalar::Bool);
    per_kind(ObjKind::Equality, &mut |e, o| {
        active.copy(o, e, 1);
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
            Pair::<f64>::new(old, new, name, Scalar::F64).copy(0, 0, n);
        } else {
            report
                .notes
                .push(format!("{name}: laid out otherwise in the new model; at its defaults"));
        }
    }
}
