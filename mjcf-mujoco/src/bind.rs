//! Binding elements of the `mjcf` model to MuJoCo's ids and fields (dm_control's
//! `physics.bind`).

use std::ffi::c_int;
use std::ops::Range;

use mjcf::JointType;

use crate::error::BindError;
use crate::fields::{self, DATA_FIELDS, Field, MODEL_FIELDS};
use crate::sys::{self, mjData, mjModel};

/// MuJoCo's kinds of compiled elements (`mjtObj`) that `mjcf` elements become.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum ObjKind {
    /// `mjOBJ_BODY` (bodies and attachment frames).
    Body,
    /// `mjOBJ_JOINT` (`<joint>`, `<freejoint>`).
    Joint,
    /// `mjOBJ_GEOM`.
    Geom,
    /// `mjOBJ_SITE`.
    Site,
    /// `mjOBJ_CAMERA`.
    Camera,
    /// `mjOBJ_LIGHT`.
    Light,
    /// `mjOBJ_FLEX`.
    Flex,
    /// `mjOBJ_MESH`.
    Mesh,
    /// `mjOBJ_SKIN`.
    Skin,
    /// `mjOBJ_HFIELD`.
    Hfield,
    /// `mjOBJ_TEXTURE`.
    Texture,
    /// `mjOBJ_MATERIAL`.
    Material,
    /// `mjOBJ_PAIR` (`<contact><pair>`).
    Pair,
    /// `mjOBJ_EXCLUDE`.
    Exclude,
    /// `mjOBJ_EQUALITY`.
    Equality,
    /// `mjOBJ_TENDON`.
    Tendon,
    /// `mjOBJ_ACTUATOR`.
    Actuator,
    /// `mjOBJ_SENSOR`.
    Sensor,
    /// `mjOBJ_NUMERIC`.
    Numeric,
    /// `mjOBJ_TEXT`.
    Text,
    /// `mjOBJ_TUPLE`.
    Tuple,
    /// `mjOBJ_KEY`.
    Key,
    /// `mjOBJ_PLUGIN`.
    Plugin,
}

impl ObjKind {
    /// Every kind.
    pub const ALL: [ObjKind; 23] = [
        ObjKind::Body,
        ObjKind::Joint,
        ObjKind::Geom,
        ObjKind::Site,
        ObjKind::Camera,
        ObjKind::Light,
        ObjKind::Flex,
        ObjKind::Mesh,
        ObjKind::Skin,
        ObjKind::Hfield,
        ObjKind::Texture,
        ObjKind::Material,
        ObjKind::Pair,
        ObjKind::Exclude,
        ObjKind::Equality,
        ObjKind::Tendon,
        ObjKind::Actuator,
        ObjKind::Sensor,
        ObjKind::Numeric,
        ObjKind::Text,
        ObjKind::Tuple,
        ObjKind::Key,
        ObjKind::Plugin,
    ];

    /// MuJoCo's `mjtObj` value.
    pub(crate) fn raw(self) -> c_int {
        (match self {
            ObjKind::Body => sys::mjtObj_mjOBJ_BODY,
            ObjKind::Joint => sys::mjtObj_mjOBJ_JOINT,
            ObjKind::Geom => sys::mjtObj_mjOBJ_GEOM,
            ObjKind::Site => sys::mjtObj_mjOBJ_SITE,
            ObjKind::Camera => sys::mjtObj_mjOBJ_CAMERA,
            ObjKind::Light => sys::mjtObj_mjOBJ_LIGHT,
            ObjKind::Flex => sys::mjtObj_mjOBJ_FLEX,
            ObjKind::Mesh => sys::mjtObj_mjOBJ_MESH,
            ObjKind::Skin => sys::mjtObj_mjOBJ_SKIN,
            ObjKind::Hfield => sys::mjtObj_mjOBJ_HFIELD,
            ObjKind::Texture => sys::mjtObj_mjOBJ_TEXTURE,
            ObjKind::Material => sys::mjtObj_mjOBJ_MATERIAL,
            ObjKind::Pair => sys::mjtObj_mjOBJ_PAIR,
            ObjKind::Exclude => sys::mjtObj_mjOBJ_EXCLUDE,
            ObjKind::Equality => sys::mjtObj_mjOBJ_EQUALITY,
            ObjKind::Tendon => sys::mjtObj_mjOBJ_TENDON,
            ObjKind::Actuator => sys::mjtObj_mjOBJ_ACTUATOR,
            ObjKind::Sensor => sys::mjtObj_mjOBJ_SENSOR,
            ObjKind::Numeric => sys::mjtObj_mjOBJ_NUMERIC,
            ObjKind::Text => sys::mjtObj_mjOBJ_TEXT,
            ObjKind::Tuple => sys::mjtObj_mjOBJ_TUPLE,
            ObjKind::Key => sys::mjtObj_mjOBJ_KEY,
            ObjKind::Plugin => sys::mjtObj_mjOBJ_PLUGIN,
        }) as c_int
    }

    /// Its name, as in MuJoCo's `mjOBJ_` names, lower case.
    pub fn name(self) -> &'static str {
        self.table().0
    }

    /// (name, the size field that counts it, the prefixes of its mjModel fields, the
    /// prefix of its mjData fields).
    fn table(self) -> (&'static str, &'static str, &'static [&'static str], &'static str) {
        match self {
            ObjKind::Body => ("body", "nbody", &["body_"], ""),
            ObjKind::Joint => ("joint", "njnt", &["jnt_", "dof_"], ""),
            ObjKind::Geom => ("geom", "ngeom", &["geom_"], "geom_"),
            ObjKind::Site => ("site", "nsite", &["site_"], "site_"),
            ObjKind::Camera => ("camera", "ncam", &["cam_"], "cam_"),
            ObjKind::Light => ("light", "nlight", &["light_"], "light_"),
            ObjKind::Flex => ("flex", "nflex", &["flex_"], "flex_"),
            ObjKind::Mesh => ("mesh", "nmesh", &["mesh_"], ""),
            ObjKind::Skin => ("skin", "nskin", &["skin_"], ""),
            ObjKind::Hfield => ("hfield", "nhfield", &["hfield_"], ""),
            ObjKind::Texture => ("texture", "ntex", &["tex_"], ""),
            ObjKind::Material => ("material", "nmat", &["mat_"], ""),
            ObjKind::Pair => ("pair", "npair", &["pair_"], ""),
            ObjKind::Exclude => ("exclude", "nexclude", &["exclude_"], ""),
            ObjKind::Equality => ("equality", "neq", &["eq_"], "eq_"),
            ObjKind::Tendon => ("tendon", "ntendon", &["tendon_"], "ten_"),
            ObjKind::Actuator => ("actuator", "nactuator", &["actuator_"], "actuator_"),
            ObjKind::Sensor => ("sensor", "nsensor", &["sensor_"], "sensor"),
            ObjKind::Numeric => ("numeric", "nnumeric", &["numeric_"], ""),
            ObjKind::Text => ("text", "ntext", &["text_"], ""),
            ObjKind::Tuple => ("tuple", "ntuple", &["tuple_"], ""),
            ObjKind::Key => ("key", "nkey", &["key_"], ""),
            ObjKind::Plugin => ("plugin", "nplugin", &["plugin_"], ""),
        }
    }
}

/// An element of a compiled model, bound from a locator of the `mjcf` model
/// ([`Compiled::bind`](crate::Compiled::bind)): its kind, its MuJoCo id and its name.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Bound {
    pub(crate) kind: ObjKind,
    pub(crate) id: usize,
    pub(crate) name: String,
}

impl Bound {
    /// MuJoCo's kind of the element.
    ///
    /// Time: O(1).
    pub fn kind(&self) -> ObjKind {
        self.kind
    }

    /// MuJoCo's id of the element (its index among the elements of its kind).
    ///
    /// Time: O(1).
    pub fn id(&self) -> usize {
        self.id
    }

    /// The name it has in the compiled model.
    ///
    /// Time: O(1).
    pub fn name(&self) -> &str {
        &self.name
    }
}

/// Where a bound field lives.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Place {
    Model,
    Data,
}

/// A field of one element: where, which field, and which of its rows.
#[derive(Clone, Debug)]
pub(crate) struct Slot {
    pub(crate) place: Place,
    pub(crate) index: usize,
    pub(crate) field: &'static Field,
    pub(crate) rows: Range<usize>,
}

/// An integer of a model field (`jnt_qposadr[id]`), -1 if there is none.
fn model_int(m: &mjModel, name: &str, row: usize) -> i64 {
    let Some(i) = MODEL_FIELDS.iter().position(|f| f.name == name) else { return -1 };
    let Some(raw) = fields::model_field(m, i) else { return -1 };
    if row >= raw.rows || raw.ptr.is_null() || MODEL_FIELDS[i].scalar != fields::Scalar::I32 {
        return -1;
    }
    // SAFETY: an int field of the model, row within its rows.
    i64::from(unsafe { *raw.ptr.cast::<i32>().add(row * raw.cols) })
}

/// The rows of a field counted by `rows` that element `id` of `kind` owns.
fn rows_of(m: &mjModel, kind: ObjKind, id: usize, rows: &str) -> Option<Range<usize>> {
    if rows == kind.table().1 {
        return Some(id..id + 1);
    }
    let span = |adr: &str, num: &str| -> Option<Range<usize>> {
        let n = usize::try_from(model_int(m, num, id)).ok()?;
        if n == 0 {
            // None of them (an actuator without activations: its address is -1).
            return Some(0..0);
        }
        let a = usize::try_from(model_int(m, adr, id)).ok()?;
        Some(a..a + n)
    };
    match (kind, rows) {
        (ObjKind::Joint, "nq" | "nv") => {
            let t = JointType::from_mujoco(model_int(m, "jnt_type", id))?;
            let (adr, n) =
                if rows == "nq" { ("jnt_qposadr", t.nq()) } else { ("jnt_dofadr", t.nv()) };
            let a = usize::try_from(model_int(m, adr, id)).ok()?;
            Some(a..a + n)
        }
        (ObjKind::Body, "nv") => span("body_dofadr", "body_dofnum"),
        (ObjKind::Body, "nmocap") => {
            let a = usize::try_from(model_int(m, "body_mocapid", id)).ok()?;
            Some(a..a + 1)
        }
        (ObjKind::Actuator, "nu") => span("actuator_ctrladr", "actuator_ctrlnum"),
        (ObjKind::Actuator, "nout") => span("actuator_outadr", "actuator_outnum"),
        (ObjKind::Actuator, "na") => span("actuator_actadr", "actuator_actnum"),
        (ObjKind::Sensor, "nsensordata") => span("sensor_adr", "sensor_dim"),
        (ObjKind::Tendon, "nwrap") => span("tendon_adr", "tendon_num"),
        _ => None,
    }
}

/// Finds field `name` of element `id` of `kind`: a field of mjData first (`qpos`,
/// `xpos`, `site_xpos`, or `xpos` for a site), then of mjModel (`damping` of a joint
/// is `dof_damping`, `mass` of a body `body_mass`; full names work too).
pub(crate) fn resolve(
    m: &mjModel,
    kind: ObjKind,
    id: usize,
    name: &str,
) -> Result<Slot, BindError> {
    let (_, _, _, data_prefix) = kind.table();
    let data_names = [format!("{data_prefix}{name}"), name.to_string()];
    for candidate in &data_names {
        if let Some(i) = DATA_FIELDS.iter().position(|f| f.name == candidate) {
            let field = &DATA_FIELDS[i];
            if let Some(rows) = rows_of(m, kind, id, field.rows) {
                return Ok(Slot { place: Place::Data, index: i, field, rows });
            }
        }
    }
    resolve_model(m, kind, id, name)
}

/// [`resolve`] among the fields of mjModel only.
pub(crate) fn resolve_model(
    m: &mjModel,
    kind: ObjKind,
    id: usize,
    name: &str,
) -> Result<Slot, BindError> {
    let (_, _, model_prefixes, _) = kind.table();
    let mut model_names: Vec<String> =
        model_prefixes.iter().map(|p| format!("{p}{name}")).collect();
    model_names.push(name.to_string());
    for candidate in &model_names {
        if let Some(i) = MODEL_FIELDS.iter().position(|f| f.name == candidate) {
            let field = &MODEL_FIELDS[i];
            if let Some(rows) = rows_of(m, kind, id, field.rows) {
                return Ok(Slot { place: Place::Model, index: i, field, rows });
            }
        }
    }
    Err(BindError::NoField {
        kind: kind.name(),
        field: name.to_string(),
        known: known_fields(m, kind, id),
    })
}

/// What [`Compiled::bind`](crate::Compiled::bind) binds: a locator of the `mjcf`
/// model (`&Loc`), a kind and a full name (`(ObjKind::Joint, "robot/knee")`, also
/// as a `String`), or a kind and a MuJoCo id (`(ObjKind::Joint, 3)`).
pub trait BindTarget {
    /// The element of `compiled` this names.
    ///
    /// # Errors
    /// As [`Compiled::bind`](crate::Compiled::bind).
    fn bind_in(&self, compiled: &crate::Compiled) -> Result<Bound, BindError>;
}

impl BindTarget for mjcf::Loc {
    fn bind_in(&self, compiled: &crate::Compiled) -> Result<Bound, BindError> {
        compiled.bind_loc(self)
    }
}

impl<T: BindTarget + ?Sized> BindTarget for &T {
    fn bind_in(&self, compiled: &crate::Compiled) -> Result<Bound, BindError> {
        (**self).bind_in(compiled)
    }
}

impl BindTarget for (ObjKind, &str) {
    fn bind_in(&self, compiled: &crate::Compiled) -> Result<Bound, BindError> {
        compiled.bind_name(self.0, self.1)
    }
}

impl BindTarget for (ObjKind, String) {
    fn bind_in(&self, compiled: &crate::Compiled) -> Result<Bound, BindError> {
        compiled.bind_name(self.0, &self.1)
    }
}

impl BindTarget for (ObjKind, &String) {
    fn bind_in(&self, compiled: &crate::Compiled) -> Result<Bound, BindError> {
        compiled.bind_name(self.0, self.1)
    }
}

impl BindTarget for (ObjKind, usize) {
    fn bind_in(&self, compiled: &crate::Compiled) -> Result<Bound, BindError> {
        compiled.bind_id(self.0, self.1)
    }
}

/// The edit distance between `a` and `b`, case-insensitive. Time: O(|a| · |b|).
fn distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().flat_map(char::to_lowercase).collect();
    let b: Vec<char> = b.chars().flat_map(char::to_lowercase).collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.iter().enumerate() {
        let mut diag = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let up = row[j + 1];
            row[j + 1] = (diag + usize::from(ca != cb)).min(up + 1).min(row[j] + 1);
            diag = up;
        }
    }
    row[b.len()]
}

/// The names of `kind` nearest `name` (at most five, nearest first): those whose
/// last part (after the scope's `/`) is `name`'s last part, in any scope, then those
/// within a third of its length in edit distance.
pub(crate) fn nearest(compiled: &crate::Compiled, kind: ObjKind, name: &str) -> Vec<String> {
    let leaf = |n: &str| n.rsplit('/').next().unwrap_or(n).to_string();
    let want_leaf = leaf(name);
    let bound = (name.chars().count() / 3).max(2);
    let mut scored: Vec<(usize, String)> = (0..compiled.count(kind))
        .filter_map(|id| compiled.name(kind, id))
        .filter(|n| !n.is_empty())
        .filter_map(|n| {
            let d = if leaf(n) == want_leaf { 0 } else { distance(n, name) };
            (d <= bound).then(|| (d, n.to_string()))
        })
        .collect();
    scored.sort();
    scored.into_iter().take(5).map(|(_, n)| n).collect()
}

/// The fields element `id` of `kind` has, comma-separated (for the error).
fn known_fields(m: &mjModel, kind: ObjKind, id: usize) -> String {
    let (_, _, model_prefixes, data_prefix) = kind.table();
    let short = |name: &'static str, prefixes: &[&str]| -> &'static str {
        prefixes.iter().filter(|p| !p.is_empty()).find_map(|p| name.strip_prefix(p)).unwrap_or(name)
    };
    let mut out: Vec<&str> = Vec::new();
    for f in DATA_FIELDS {
        if rows_of(m, kind, id, f.rows).is_some() {
            out.push(short(f.name, &[data_prefix]));
        }
    }
    for f in MODEL_FIELDS {
        if rows_of(m, kind, id, f.rows).is_some() {
            out.push(short(f.name, model_prefixes));
        }
    }
    out.join(", ")
}

/// The raw field a slot names, in `m` or `d`.
pub(crate) fn raw(slot: &Slot, m: &mjModel, d: Option<&mjData>) -> Option<fields::RawField> {
    match (slot.place, d) {
        (Place::Model, _) => fields::model_field(m, slot.index),
        (Place::Data, Some(d)) => fields::data_field(d, m, slot.index),
        (Place::Data, None) => None,
    }
}

#[cfg(test)]
mod tests {
    use mjcf::JointType;

    use crate::sys;

    /// `JointType`'s numbers (what `jnt_type` is read with) are MuJoCo's `mjtJoint`,
    /// as its header (the generated bindings) numbers them.
    #[test]
    fn joint_types_are_numbered_as_mujoco_s_header_numbers_them() {
        let header = [
            (sys::mjtJoint_mjJNT_FREE, JointType::Free),
            (sys::mjtJoint_mjJNT_BALL, JointType::Ball),
            (sys::mjtJoint_mjJNT_SLIDE, JointType::Slide),
            (sys::mjtJoint_mjJNT_HINGE, JointType::Hinge),
        ];
        for (number, t) in header {
            assert_eq!(JointType::from_mujoco(number.into()), Some(t));
            assert_eq!(i64::from(t.mujoco_number()), i64::from(number));
        }
    }
}
