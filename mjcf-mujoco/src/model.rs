//! A compiled model (`mjModel`), with the `mjcf` model it was compiled from.

use std::ffi::{CStr, CString, c_int};
use std::ptr::NonNull;
use std::sync::Arc;

use mjcf::{Loc, Model, Namespace, Written};

use crate::bind::{BindTarget, Bound, ObjKind, Slot};
use crate::error::{BindError, Error, ErrorElement};
use crate::fields::{self, Field, RawField, Scalar};
use crate::guard::Message;
use crate::library::MuJoCo;
use crate::sys::mjModel;

/// A model compiled by MuJoCo (its `mjModel`), with the `mjcf` model it was compiled
/// from, so that the model's locators bind to MuJoCo's ids ([`Compiled::bind`]).
///
/// It is `Send + Sync`: MuJoCo only reads a compiled model while simulating, so any
/// number of [`Physics`](crate::Physics) on any threads can share one. Cloning is
/// O(1) (shared); writing a model field through a `Physics` copies the model first if
/// it is shared ([`Physics::get_mut`](crate::Physics::get_mut)).
#[derive(Clone)]
pub struct Compiled {
    pub(crate) inner: Arc<Inner>,
}

pub(crate) struct Inner {
    pub(crate) mujoco: MuJoCo,
    pub(crate) ptr: NonNull<mjModel>,
    /// The `mjcf` model and where its elements were written, when compiled from one.
    pub(crate) source: Option<Arc<Source>>,
    pub(crate) messages: Vec<Message>,
}

// SAFETY: the `mjModel` is owned by `Inner` alone (deleted on drop); through `&Inner`
// MuJoCo only reads it (`const mjModel*` in every function the binding calls with a
// shared model), and it is written only through `&mut`, when the `Arc` is not shared.
unsafe impl Send for Inner {}
// SAFETY: as above: shared access is read-only.
unsafe impl Sync for Inner {}

impl Drop for Inner {
    fn drop(&mut self) {
        // SAFETY: the model was made by MuJoCo and is deleted once, here.
        unsafe { (self.mujoco.lib.fns.delete_model)(self.ptr.as_ptr()) }
    }
}

impl std::fmt::Debug for Compiled {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let m = self.raw();
        f.debug_struct("Compiled")
            .field("nq", &m.nq)
            .field("nv", &m.nv)
            .field("nu", &m.nu)
            .field("nbody", &m.nbody)
            .field("njnt", &m.njnt)
            .field("ngeom", &m.ngeom)
            .finish_non_exhaustive()
    }
}

/// The sizes of a compiled model that most code needs.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct Sizes {
    /// Position coordinates (`nq`).
    pub nq: usize,
    /// Degrees of freedom (`nv`).
    pub nv: usize,
    /// Controls (`nu`).
    pub nu: usize,
    /// Activations (`na`).
    pub na: usize,
    /// Bodies, the world included (`nbody`).
    pub nbody: usize,
    /// Joints (`njnt`).
    pub njnt: usize,
    /// Geoms (`ngeom`).
    pub ngeom: usize,
    /// Sites (`nsite`).
    pub nsite: usize,
    /// Actuators (`nactuator`).
    pub nactuator: usize,
    /// Sensors (`nsensor`).
    pub nsensor: usize,
    /// Mocap bodies (`nmocap`).
    pub nmocap: usize,
    /// Keyframes (`nkey`).
    pub nkey: usize,
    /// Tendons (`ntendon`).
    pub ntendon: usize,
    /// Cameras (`ncam`).
    pub ncam: usize,
    /// Lights (`nlight`).
    pub nlight: usize,
}

fn count(n: i64) -> usize {
    usize::try_from(n).unwrap_or(0)
}

impl Compiled {
    pub(crate) fn new(
        mujoco: MuJoCo,
        ptr: NonNull<mjModel>,
        source: Option<Source>,
        messages: Vec<Message>,
    ) -> Compiled {
        Compiled { inner: Arc::new(Inner { mujoco, ptr, source: source.map(Arc::new), messages }) }
    }

    /// The raw `mjModel`.
    pub(crate) fn raw(&self) -> &mjModel {
        // SAFETY: valid while `inner` lives; shared access reads only.
        unsafe { self.inner.ptr.as_ref() }
    }

    /// The `mjcf` model it was compiled from (`None` when compiled from text or a file).
    ///
    /// Time: O(1).
    pub fn source(&self) -> Option<&Model> {
        self.inner.source.as_deref().map(|s| &s.model)
    }

    /// The MJCF text MuJoCo compiled, with where each element was written (`None`
    /// when compiled from text or a file). For a model a rebuild wrote in place
    /// ([`Physics::rebuild`](crate::Physics::rebuild)), the edited model's text,
    /// written the first time it is asked for.
    ///
    /// Time: O(1); the first call after an in-place rebuild writes the model (O(N)).
    pub fn written(&self) -> Option<&Written> {
        self.inner.source.as_deref().and_then(Source::written)
    }

    /// What MuJoCo logged while compiling (its warnings).
    ///
    /// Time: O(1).
    pub fn messages(&self) -> &[Message] {
        &self.inner.messages
    }

    /// The model's sizes.
    ///
    /// Time: O(1).
    pub fn sizes(&self) -> Sizes {
        let m = self.raw();
        Sizes {
            nq: count(m.nq),
            nv: count(m.nv),
            nu: count(m.nu),
            na: count(m.na),
            nbody: count(m.nbody),
            njnt: count(m.njnt),
            ngeom: count(m.ngeom),
            nsite: count(m.nsite),
            nactuator: count(m.nactuator),
            nsensor: count(m.nsensor),
            nmocap: count(m.nmocap),
            nkey: count(m.nkey),
            ntendon: count(m.ntendon),
            ncam: count(m.ncam),
            nlight: count(m.nlight),
        }
    }

    /// How many elements of `kind` the compiled model has.
    ///
    /// Time: O(1).
    pub fn count(&self, kind: ObjKind) -> usize {
        let m = self.raw();
        count(match kind {
            ObjKind::Body => m.nbody,
            ObjKind::Joint => m.njnt,
            ObjKind::Geom => m.ngeom,
            ObjKind::Site => m.nsite,
            ObjKind::Camera => m.ncam,
            ObjKind::Light => m.nlight,
            ObjKind::Flex => m.nflex,
            ObjKind::Mesh => m.nmesh,
            ObjKind::Skin => m.nskin,
            ObjKind::Hfield => m.nhfield,
            ObjKind::Texture => m.ntex,
            ObjKind::Material => m.nmat,
            ObjKind::Pair => m.npair,
            ObjKind::Exclude => m.nexclude,
            ObjKind::Equality => m.neq,
            ObjKind::Tendon => m.ntendon,
            ObjKind::Actuator => m.nactuator,
            ObjKind::Sensor => m.nsensor,
            ObjKind::Numeric => m.nnumeric,
            ObjKind::Text => m.ntext,
            ObjKind::Tuple => m.ntuple,
            ObjKind::Key => m.nkey,
            ObjKind::Plugin => m.nplugin,
        })
    }

    /// MuJoCo's id of the element of `kind` named `name` (`mj_name2id`), if any.
    ///
    /// Time: O(1) expected (MuJoCo's name hash).
    pub fn id(&self, kind: ObjKind, name: &str) -> Option<usize> {
        let name = CString::new(name).ok()?;
        // SAFETY: a valid model and a NUL-terminated name; `mj_name2id` only reads.
        let id =
            unsafe { (self.inner.mujoco.lib.fns.name2id)(self.raw(), kind.raw(), name.as_ptr()) };
        usize::try_from(id).ok()
    }

    /// The name of the element of `kind` with MuJoCo id `id` (`mj_id2name`), if it has
    /// one.
    ///
    /// Time: O(1).
    pub fn name(&self, kind: ObjKind, id: usize) -> Option<&str> {
        let id = c_int::try_from(id).ok()?;
        // SAFETY: a valid model; `mj_id2name` returns null or a string inside the model.
        let p = unsafe { (self.inner.mujoco.lib.fns.id2name)(self.raw(), kind.raw(), id) };
        // SAFETY: the string lives as long as the model.
        (!p.is_null()).then(|| unsafe { CStr::from_ptr(p) }.to_str().ok()).flatten()
    }

    /// Binds an element in one call: by locator of the `mjcf` model it was compiled
    /// from (`&Loc`), or by kind and full name (`(ObjKind::Actuator,
    /// "arm/gripper/fingers_actuator")`, which also works for models compiled from a
    /// path or from text, and for unnamed elements by the name the writer gave them,
    /// `//unnamed_joint_0`), or by kind and MuJoCo id (`(ObjKind::Joint, 3)`). Its
    /// fields are then read by MuJoCo's names with their true widths
    /// ([`Compiled::get`], [`Physics::get`](crate::Physics::get)).
    ///
    /// A locator is found by the name it was written with
    /// ([`ElementRef::full_name`](mjcf::ElementRef::full_name)), as dm_control's
    /// `physics.bind`.
    ///
    /// Time: by name, MuJoCo's hash lookup (O(n) more to suggest names when it is
    /// missing); by locator, O(levels · depth · log n) to name the element (O(n)
    /// more for an unnamed one; O(E) more for an attachment frame, to see how it was
    /// written), plus MuJoCo's lookup.
    ///
    /// # Errors
    /// [`BindError::NotFound`] with the nearest names of that kind for a name MuJoCo
    /// does not have; [`BindError::NoId`] for an id out of range; for a locator:
    /// no source model, a locator of another model, an element MuJoCo keeps no record
    /// of (a `<frame>`, a default class).
    pub fn bind(&self, target: impl BindTarget) -> Result<Bound, BindError> {
        target.bind_in(self)
    }

    /// [`Compiled::bind`] of a locator.
    pub(crate) fn bind_loc(&self, loc: &Loc) -> Result<Bound, BindError> {
        let model = self.source().ok_or(BindError::NoSource)?;
        let element = model.get(loc).map_err(|e| BindError::NoElement(e.to_string()))?;
        let kind = ObjKind::of(&element).ok_or(BindError::NotCompiled { tag: element.tag() })?;
        // An attachment frame written as MuJoCo's `<frame>` is no body of MuJoCo's.
        if element.is_frame() {
            let written = self.written().and_then(|w| w.elements().iter().find(|e| e.loc == *loc));
            if written.is_some_and(|w| w.tag == "frame") {
                return Err(BindError::NotCompiled { tag: "frame" });
            }
        }
        let name = element.full_name().ok_or(BindError::Unnamed { tag: element.tag() })?;
        self.bind_name(kind, &name)
    }

    /// [`Compiled::bind`] by kind and full name.
    pub(crate) fn bind_name(&self, kind: ObjKind, name: &str) -> Result<Bound, BindError> {
        match self.id(kind, name) {
            Some(id) => Ok(Bound { kind, id, name: name.to_string() }),
            None => Err(BindError::NotFound {
                kind: kind.name(),
                name: name.to_string(),
                suggestions: crate::bind::nearest(self, kind, name),
            }),
        }
    }

    /// [`Compiled::bind`] by kind and MuJoCo id.
    pub(crate) fn bind_id(&self, kind: ObjKind, id: usize) -> Result<Bound, BindError> {
        if id >= self.count(kind) {
            return Err(BindError::NoId { kind: kind.name(), id, count: self.count(kind) });
        }
        let name = self.name(kind, id).unwrap_or_default().to_string();
        Ok(Bound { kind, id, name })
    }

    /// A model field of a bound element, by MuJoCo's name with or without its prefix
    /// (`gainprm` or `actuator_gainprm` of an actuator: its 10 numbers; `mass` of a
    /// body; `range` of a joint: 2; `damping` of a joint: one per degree of freedom),
    /// the element's rows, row after row. Fields of the simulation's data (`qpos`,
    /// `xpos`) are [`Physics::get`](crate::Physics::get)'s.
    ///
    /// Time: O(f) for the f fields of `mjModel` (found by name).
    ///
    /// # Errors
    /// [`BindError::NoField`] naming the fields there are; [`BindError::WrongType`]
    /// for a field of integers (see [`Compiled::get_ints`]).
    pub fn get(&self, b: &Bound, field: &str) -> Result<&[f64], BindError> {
        let (slot, raw) = self.model_slot(b, field)?;
        // SAFETY: the field's pointer and size from the model's own tables, borrowed
        // from `self`; the rows are the element's.
        let all: &[f64] = unsafe { raw.slice(slot.field, Scalar::F64, "f64") }?;
        Ok(&all[slot.rows.start * raw.cols..slot.rows.end * raw.cols])
    }

    /// [`Compiled::get`] for fields of integers (`type` and `qposadr` of a joint).
    ///
    /// Time: as [`Compiled::get`].
    ///
    /// # Errors
    /// As [`Compiled::get`], the other way round.
    pub fn get_ints(&self, b: &Bound, field: &str) -> Result<&[i32], BindError> {
        let (slot, raw) = self.model_slot(b, field)?;
        // SAFETY: as in `get`.
        let all: &[i32] = unsafe { raw.slice(slot.field, Scalar::I32, "i32") }?;
        Ok(&all[slot.rows.start * raw.cols..slot.rows.end * raw.cols])
    }

    fn model_slot(&self, b: &Bound, field: &str) -> Result<(Slot, RawField), BindError> {
        let slot = crate::bind::resolve_model(self.raw(), b.kind, b.id, field)?;
        let raw = crate::bind::raw(&slot, self.raw(), None).ok_or_else(|| no_model_field(field))?;
        Ok((slot, raw))
    }

    /// The model field `name` (`jnt_qposadr`, `geom_friction`, ...), all rows.
    pub(crate) fn field(&self, name: &str) -> Option<(&'static Field, RawField)> {
        let i = fields::MODEL_FIELDS.iter().position(|f| f.name == name)?;
        Some((&fields::MODEL_FIELDS[i], fields::model_field(self.raw(), i)?))
    }

    /// The model field `name` as numbers (`body_mass`, `geom_size`, ...): every row,
    /// row after row.
    ///
    /// Time: O(f) for the f fields of `mjModel` (found by name).
    ///
    /// # Errors
    /// [`BindError::NoField`] for a name `mjModel` has no array field of;
    /// [`BindError::WrongType`] for a field of integers (see [`Compiled::ints`]).
    pub fn floats(&self, name: &str) -> Result<&[f64], BindError> {
        let (field, raw) = self.field(name).ok_or_else(|| no_model_field(name))?;
        // SAFETY: the field's pointer and size come from the model's own tables.
        unsafe { raw.slice(field, Scalar::F64, "f64") }
    }

    /// The model field `name` as single-precision numbers (`geom_rgba`,
    /// `mat_rgba`, ...).
    ///
    /// Time: O(f), as [`Compiled::floats`].
    ///
    /// # Errors
    /// As [`Compiled::floats`].
    pub fn floats32(&self, name: &str) -> Result<&[f32], BindError> {
        let (field, raw) = self.field(name).ok_or_else(|| no_model_field(name))?;
        // SAFETY: the field's pointer and size come from the model's own tables.
        unsafe { raw.slice(field, Scalar::F32, "f32") }
    }

    /// The model field `name` as integers (`jnt_qposadr`, `body_parentid`, ...).
    ///
    /// Time: O(f), as [`Compiled::floats`].
    ///
    /// # Errors
    /// As [`Compiled::floats`], the other way round.
    pub fn ints(&self, name: &str) -> Result<&[i32], BindError> {
        let (field, raw) = self.field(name).ok_or_else(|| no_model_field(name))?;
        // SAFETY: the field's pointer and size come from the model's own tables.
        unsafe { raw.slice(field, Scalar::I32, "i32") }
    }
}

fn no_model_field(name: &str) -> BindError {
    BindError::NoField {
        kind: "model",
        field: name.to_string(),
        known: "mjModel's array fields".into(),
    }
}

/// The `mjcf` model a compiled model was compiled from (or written in place from),
/// and where its elements were written.
pub(crate) struct Source {
    pub(crate) model: Model,
    pub(crate) options: mjcf::WriteOptions,
    written: std::sync::OnceLock<Option<Written>>,
    /// Each compiled element by locator (`crate::rebuild`), found once.
    pub(crate) ids: std::sync::OnceLock<Arc<crate::rebuild::Ids>>,
    /// Every element a rebuild reports, under its own name (the report of a rebuild
    /// that changes no element), listed once.
    pub(crate) all: std::sync::OnceLock<Arc<[crate::rebuild::Carried]>>,
}

impl Source {
    /// A model compiled from `written`.
    pub(crate) fn compiled(model: Model, options: mjcf::WriteOptions, written: Written) -> Source {
        let cell = std::sync::OnceLock::new();
        let _ = cell.set(Some(written));
        let (ids, all) = (std::sync::OnceLock::new(), std::sync::OnceLock::new());
        Source { model, options, written: cell, ids, all }
    }

    /// A model written in place into a compiled model whose elements are `ids`, all
    /// of them `all`.
    pub(crate) fn in_place(
        model: Model,
        options: mjcf::WriteOptions,
        ids: Arc<crate::rebuild::Ids>,
        all: Arc<[crate::rebuild::Carried]>,
    ) -> Source {
        let (cell, every) = (std::sync::OnceLock::new(), std::sync::OnceLock::new());
        let _ = cell.set(ids);
        let _ = every.set(all);
        Source { model, options, written: std::sync::OnceLock::new(), ids: cell, all: every }
    }

    /// Where its elements were written (written now if not yet).
    pub(crate) fn written(&self) -> Option<&Written> {
        self.written.get_or_init(|| self.model.to_xml_written(&self.options).ok()).as_ref()
    }
}

/// A compile error located in the `mjcf` model: the element at the line MuJoCo names.
pub(crate) fn locate(error: Error, model: &Model, written: &Written) -> Error {
    let Error::Compile(mut e) = error else { return error };
    if let Some(w) = e.line.and_then(|line| written.element_at_line(line)) {
        let full_name = model.get(&w.loc).ok().and_then(|el| el.full_name());
        e.element = Some(ErrorElement { loc: w.loc.clone(), tag: w.tag, full_name });
    }
    Error::Compile(e)
}

impl ObjKind {
    /// The kind of compiled element an `mjcf` element becomes (an attachment frame a
    /// body), if any: `None` for elements MuJoCo's compiled model keeps no record of
    /// (a `<frame>`, a default class, a section).
    ///
    /// Time: O(1).
    pub fn of(element: &mjcf::ElementRef<'_>) -> Option<ObjKind> {
        if element.is_frame() {
            return Some(ObjKind::Body);
        }
        Some(match element.kind().namespace()? {
            Namespace::Body => ObjKind::Body,
            Namespace::Joint => ObjKind::Joint,
            Namespace::Geom => ObjKind::Geom,
            Namespace::Site => ObjKind::Site,
            Namespace::Camera => ObjKind::Camera,
            Namespace::Light => ObjKind::Light,
            Namespace::Actuator => ObjKind::Actuator,
            Namespace::Sensor => ObjKind::Sensor,
            Namespace::Tendon => ObjKind::Tendon,
            Namespace::Equality => ObjKind::Equality,
            Namespace::Mesh => ObjKind::Mesh,
            Namespace::Hfield => ObjKind::Hfield,
            Namespace::Texture => ObjKind::Texture,
            Namespace::Material => ObjKind::Material,
            Namespace::Skin => ObjKind::Skin,
            Namespace::Key => ObjKind::Key,
            Namespace::Numeric => ObjKind::Numeric,
            Namespace::Text => ObjKind::Text,
            Namespace::Tuple => ObjKind::Tuple,
            Namespace::Plugin => ObjKind::Plugin,
            Namespace::Flexcomp => ObjKind::Flex,
            Namespace::Contact => match element.tag() {
                "pair" => ObjKind::Pair,
                "exclude" => ObjKind::Exclude,
                _ => return None,
            },
            Namespace::Deformable => match element.tag() {
                "flex" => ObjKind::Flex,
                "skin" => ObjKind::Skin,
                _ => return None,
            },
            _ => return None,
        })
    }
}
