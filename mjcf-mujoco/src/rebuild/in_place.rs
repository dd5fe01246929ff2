//! Which edits of a model can be written into its compiled model in place (numbers
//! only, no compile), and the writes that make the compiled model what compiling the
//! edited model gives.
//!
//! An edit is written in place when every change is an attribute of an element (not
//! of a default class) in [`RULES`], whose compiled field held exactly the attribute's
//! old value: the compiled numbers were a copy of the attribute, so the new numbers
//! are a copy of the new one. Components the new value does not give come from the
//! element's class, and so does the old value's (a value of `k` numbers for a field of
//! more leaves the rest to the class): they are kept. Anything else (a name, a class,
//! an element added, removed or moved, an angle the compiler converts, a value the
//! compiler derived rather than copied) is compiled.
//!
//! One structural edit is written in place too: an `<inertial>` added to a body
//! (its `pos`, `mass`, `diaginertia` and optionally `quat`), which replaces what the
//! compiler computed from the body's geoms by the inertial's numbers, as compiling
//! does when no compiler setting (`inertiafromgeom="true"`, `boundmass`,
//! `boundinertia`, `balanceinertia`, `settotalmass`, `alignfree`) alters them.

use mjcf::{Change, ElementRef, JointType, Model, Value};

use crate::bind::{self, ObjKind};
use crate::constants::{Class, class};
use crate::fields;
use crate::model::Compiled;
use crate::rebuild::ids::Ids;
use crate::sys::mjModel;

/// An attribute copied into a model field.
struct Rule {
    tags: &'static [&'static str],
    attr: &'static str,
    field: &'static str,
    /// The field is the parent element's (an `<inertial>`'s body).
    parent: bool,
}

const fn rule(tags: &'static [&'static str], attr: &'static str, field: &'static str) -> Rule {
    Rule { tags, attr, field, parent: false }
}

/// The attributes a rebuild writes in place, and their fields.
const RULES: &[Rule] = &[
    rule(&["geom"], "friction", "geom_friction"),
    rule(&["geom"], "solref", "geom_solref"),
    rule(&["geom"], "solimp", "geom_solimp"),
    rule(&["geom"], "solmix", "geom_solmix"),
    rule(&["joint"], "damping", "dof_damping"),
    rule(&["joint"], "frictionloss", "dof_frictionloss"),
    rule(&["joint"], "armature", "dof_armature"),
    rule(&["joint"], "stiffness", "jnt_stiffness"),
    rule(&["general"], "gainprm", "actuator_gainprm"),
    rule(&["general"], "biasprm", "actuator_biasprm"),
    rule(&["general"], "dynprm", "actuator_dynprm"),
    rule(&["general", "motor"], "gear", "actuator_gear"),
    rule(&["body"], "pos", "body_pos"),
    rule(&["body"], "gravcomp", "body_gravcomp"),
    Rule { tags: &["inertial"], attr: "mass", field: "body_mass", parent: true },
    Rule { tags: &["inertial"], attr: "diaginertia", field: "body_inertia", parent: true },
];

/// The writes of an in-place rebuild.
#[derive(Debug, Default)]
pub(crate) struct Plan {
    /// (index in `MODEL_FIELDS`, first scalar, values).
    pub(crate) writes: Vec<(usize, usize, Vec<f64>)>,
    /// Some field `mj_setConst` derives from is written.
    pub(crate) set_const: bool,
}

fn floats(v: &Value) -> Option<Vec<f64>> {
    v.as_floats().map(<[f64]>::to_vec).or_else(|| v.as_float().map(|x| vec![x]))
}

fn in_default(e: &ElementRef<'_>) -> bool {
    let mut p = e.parent();
    while let Some(e) = p {
        if e.tag() == "default" {
            return true;
        }
        p = e.parent();
    }
    false
}

/// Whether body `body` of `m` has a free joint.
fn free_body(compiled: &Compiled, body: usize) -> bool {
    let (Ok(jb), Ok(jt)) = (compiled.ints("jnt_bodyid"), compiled.ints("jnt_type")) else {
        return true;
    };
    jb.iter().zip(jt).any(|(&b, &t)| {
        usize::try_from(b).is_ok_and(|b| b == body)
            && JointType::from_mujoco(t.into()) == Some(JointType::Free)
    })
}

/// The writes that make `compiled` (compiled from an earlier version, its elements
/// `ids`) what compiling `new` gives, if `changes` can all be written in place.
///
/// Time: O(c · (depth + f)) for c changes (f: the model fields, found by name).
pub(crate) fn plan(
    compiled: &Compiled,
    ids: &Ids,
    new: &Model,
    changes: &[Change],
) -> Option<Plan> {
    let m: &mjModel = compiled.raw();
    let mut plan = Plan::default();
    for change in changes {
        if let Change::Added { loc } = change {
            added_inertial(compiled, ids, new, loc, &mut plan)?;
            continue;
        }
        let Change::AttrChanged { loc, attribute, old, new: Some(value) } = change else {
            return None;
        };
        let element = new.element(loc)?;
        if in_default(&element) {
            return None;
        }
        let rule =
            RULES.iter().find(|r| r.attr == *attribute && r.tags.contains(&element.tag()))?;
        let target = if rule.parent { element.parent()?.loc() } else { loc.clone() };
        let &(kind, id) = ids.by_loc.get(&target)?;
        if !copied_as_given(compiled, new, &element, rule.field, kind, id) {
            return None;
        }
        let slot = bind::resolve_model(m, kind, id, rule.field).ok()?;
        let raw = fields::model_field(m, slot.index)?;
        if raw.ptr.is_null() || slot.field.scalar != fields::Scalar::F64 {
            return None;
        }
        // SAFETY: the field's pointer and size from the model's own tables.
        let all: &[f64] = unsafe { raw.slice(slot.field, fields::Scalar::F64, "f64") }.ok()?;
        let cols = raw.cols;
        let cur = &all[slot.rows.start * cols..slot.rows.end * cols];
        let new_vals = floats(value)?;
        let old_vals = match old {
            Some(v) => Some(floats(v)?),
            None => None,
        };
        let rows = slot.rows.len();
        let (k, j) = (new_vals.len(), old_vals.as_ref().map_or(0, Vec::len));
        if k == 0 || k > cols || j > k || (rows > 1 && cols != 1) {
            return None;
        }
        // The compiled numbers were a copy of the old value.
        if let Some(o) = &old_vals {
            for r in 0..rows {
                if cur[r * cols..r * cols + j] != o[..] {
                    return None;
                }
            }
        }
        for r in 0..rows {
            let start = (slot.rows.start + r) * cols;
            plan.writes.push((slot.index, start, new_vals.clone()));
        }
        match class(rule.field) {
            Class::Free => {}
            Class::SetConst => plan.set_const = true,
            Class::Refused(_) => return None,
        }
    }
    Some(plan)
}

/// The compiler settings under which an inertial is not copied as given (bounded,
/// balanced, scaled, fused with static children, or the free body aligned to it).
const INERTIA_SETTINGS: &[&str] =
    &["boundmass", "boundinertia", "balanceinertia", "settotalmass", "alignfree", "fusestatic"];

/// Whether a compiler setting of `model` changes inertias from what they are given.
fn inertia_settings_alter(model: &Model) -> bool {
    model.walk().any(|ev| match ev {
        mjcf::Event::Enter(e) if e.tag() == "compiler" => {
            e.string("inertiafromgeom") == Some("true")
                || e.attrs().any(|(a, _)| INERTIA_SETTINGS.contains(&a))
        }
        _ => false,
    })
}

/// MuJoCo 4.0's `mjGAIN_MUSCLE` and `mjGAIN_USER` (mjtGain), whose length ranges
/// the compiler computes.
const GAIN_MUSCLE_OR_USER: [i32; 2] = [2, 6];
/// MuJoCo 4.0's `mjBIAS_MUSCLE` and `mjBIAS_USER` (mjtBias).
const BIAS_MUSCLE_OR_USER: [i32; 2] = [2, 5];
/// `mjGAIN_FIXED`, `mjGAIN_AFFINE` (and `mjBIAS_NONE`, `mjBIAS_AFFINE`): the types
/// whose parameters the compiler copies (others, such as PID and DC motor
/// actuators, derive more from them).
const PLAIN_TYPES: [i32; 2] = [0, 1];

/// Whether the compiler copies the attribute of `element` (compiled as element `id`
/// of `kind`) into `field` as given, beyond the check that the field held the old
/// value (which a transform can pass: a zero position in a rotated frame):
/// - a body's position, when its parent is a body (not a frame, an attachment or
///   a replicate, whose transforms compose with it) and it has no free joint;
/// - an inertial's numbers, when no compiler setting alters inertias;
/// - a gear, when no actuator length range is computed from it (muscle and user
///   actuators, or every actuator with `<lengthrange mode="all">`);
/// - a general actuator's gains and biases, unless it is position-like with a damping
///   ratio (a positive third bias, which the compiler turns into a damping from the
///   gain): its own biasprm must give a third number of at most 0.
fn copied_as_given(
    compiled: &Compiled,
    new: &Model,
    element: &ElementRef<'_>,
    field: &str,
    kind: ObjKind,
    id: usize,
) -> bool {
    let at = |name: &str, cols: usize, i: usize| -> f64 {
        compiled.floats(name).ok().and_then(|v| v.get(id * cols + i).copied()).unwrap_or(f64::NAN)
    };
    let int = |name: &str| compiled.ints(name).ok().and_then(|v| v.get(id).copied());
    match field {
        "body_pos" => {
            kind == ObjKind::Body
                && !free_body(compiled, id)
                && element
                    .parent()
                    .is_some_and(|p| matches!(p.tag(), "body" | "worldbody") && !p.is_frame())
        }
        "body_mass" | "body_inertia" => !inertia_settings_alter(new),
        "actuator_gear" => {
            let all = new.walk().any(|ev| match ev {
                mjcf::Event::Enter(e) if e.tag() == "lengthrange" => {
                    e.string("mode") == Some("all")
                }
                _ => false,
            });
            !all && int("actuator_gaintype").is_some_and(|t| !GAIN_MUSCLE_OR_USER.contains(&t))
                && int("actuator_biastype").is_some_and(|t| !BIAS_MUSCLE_OR_USER.contains(&t))
        }
        "actuator_gainprm" | "actuator_biasprm" => {
            let plain = |name: &str| int(name).is_some_and(|t| PLAIN_TYPES.contains(&t));
            let position_like = at("actuator_gainprm", 10, 0) == -at("actuator_biasprm", 10, 1);
            let own = element.floats("biasprm");
            plain("actuator_gaintype")
                && plain("actuator_biastype")
                && (!position_like || own.is_some_and(|b| b.len() >= 3 && b[2] <= 0.0))
        }
        _ => true,
    }
}

/// The writes of an `<inertial>` added to a body (see the module's docs).
fn added_inertial(
    compiled: &Compiled,
    ids: &Ids,
    new: &Model,
    loc: &mjcf::Loc,
    plan: &mut Plan,
) -> Option<()> {
    let element = new.element(loc)?;
    if element.tag() != "inertial" || in_default(&element) {
        return None;
    }
    if element.attrs().any(|(a, _)| !matches!(a, "pos" | "quat" | "mass" | "diaginertia")) {
        return None;
    }
    if inertia_settings_alter(new) {
        return None;
    }
    let body = element.parent()?;
    if body.tag() != "body" && !body.is_frame() {
        return None;
    }
    let &(kind, id) = ids.by_loc.get(&body.loc())?;
    if kind != ObjKind::Body {
        return None;
    }
    let pos = element.floats("pos")?;
    let mass = element.float("mass")?;
    let inertia = element.floats("diaginertia")?;
    let mut quat =
        element.floats("quat").map_or([1.0, 0.0, 0.0, 0.0], |q| [q[0], q[1], q[2], q[3]]);
    // The compiler's normalization (mjuu_normvec): divided by the norm unless it is
    // within 1e-9 of 1.
    let norm = quat.iter().map(|x| x * x).sum::<f64>();
    if norm < 1e-9 || pos.len() != 3 || inertia.len() != 3 {
        return None;
    }
    let norm = norm.sqrt();
    if (norm - 1.0).abs() > 1e-9 {
        quat.iter_mut().for_each(|x| *x /= norm);
    }
    let m: &mjModel = compiled.raw();
    for (field, values) in [
        ("body_mass", vec![mass]),
        ("body_ipos", pos.to_vec()),
        ("body_iquat", quat.to_vec()),
        ("body_inertia", inertia.to_vec()),
    ] {
        let slot = bind::resolve_model(m, ObjKind::Body, id, field).ok()?;
        let raw = fields::model_field(m, slot.index)?;
        plan.writes.push((slot.index, slot.rows.start * raw.cols, values));
    }
    plan.set_const = true;
    Some(())
}

/// Writes `plan` into `m`.
///
/// # Safety
/// `m` is a valid model no one else reads or writes meanwhile, the one `plan` was
/// made for (or a copy of it).
pub(crate) unsafe fn apply(m: &mjModel, plan: &Plan) {
    for (index, start, values) in &plan.writes {
        let Some(raw) = fields::model_field(m, *index) else { continue };
        let field = &fields::MODEL_FIELDS[*index];
        // SAFETY: as the caller promises; the plan's ranges lie within the field.
        if let Ok(all) = unsafe { raw.slice_mut::<f64>(field, fields::Scalar::F64, "f64") } {
            all[*start..*start + values.len()].copy_from_slice(values);
        }
    }
}
