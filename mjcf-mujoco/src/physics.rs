//! Simulation: a compiled model with its `mjData`.

use std::ffi::{CStr, c_long};
use std::ptr::NonNull;
use std::sync::Arc;

use mjcf::JointType;

use crate::bind::{self, BindTarget, Bound, ObjKind, Place, Slot};
use crate::error::{BindError, Error};
use crate::fields::Scalar;
use crate::guard::{self, Message};
use crate::model::{Compiled, Inner};
use crate::sys::{mjData, mjModel};

/// A simulation: a [`Compiled`] model and its state (MuJoCo's `mjData`), as
/// dm_control's `Physics`.
///
/// It is `Send` (a simulation can move to another thread) and not `Sync`. Many
/// simulations can share one compiled model ([`Physics::new`] on clones of it).
pub struct Physics {
    pub(crate) model: Compiled,
    pub(crate) data: NonNull<mjData>,
    /// Set by a fatal error inside MuJoCo, cleared by a reset.
    pub(crate) poisoned: bool,
    pub(crate) messages: Vec<Message>,
    /// [`Physics::set_warnings_as_errors`].
    pub(crate) warnings_as_errors: bool,
    /// A model field `mj_setConst` derives constants from was written, and the
    /// constants are not recomputed yet ([`Physics::update_constants`]).
    pub(crate) stale_constants: bool,
    /// A model field was written ([`Physics::get_mut`]): the compiled model is no
    /// longer what its source compiles to.
    pub(crate) written_raw: bool,
    /// The scratch data `mj_setConst` runs with (never the simulation's own).
    pub(crate) scratch: Option<NonNull<mjData>>,
}

// SAFETY: the `mjData` is owned by this value alone; MuJoCo keeps no reference to it
// between calls, and the model it is used with is `Sync`.
unsafe impl Send for Physics {}

impl Drop for Physics {
    fn drop(&mut self) {
        let delete = self.model.inner.mujoco.lib.fns.delete_data;
        // SAFETY: made by `mj_makeData`, deleted once, here (the scratch data too).
        unsafe {
            delete(self.data.as_ptr());
            if let Some(scratch) = self.scratch.take() {
                delete(scratch.as_ptr());
            }
        }
    }
}

impl std::fmt::Debug for Physics {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Physics")
            .field("model", &self.model)
            .field("time", &self.time())
            .field("poisoned", &self.poisoned)
            .finish_non_exhaustive()
    }
}

/// A kind of warning MuJoCo counts while simulating (`mjtWarning`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum WarningKind {
    /// `mjWARN_INERTIA`: a body's inertia is too small.
    Inertia,
    /// `mjWARN_CONTACTFULL`: too many contacts.
    ContactFull,
    /// `mjWARN_CNSTRFULL`: too many constraints.
    ConstraintFull,
    /// `mjWARN_BADQPOS`: NaN, Inf or a huge value in qpos.
    BadQpos,
    /// `mjWARN_BADQVEL`: NaN, Inf or a huge value in qvel.
    BadQvel,
    /// `mjWARN_BADQACC`: NaN, Inf or a huge value in qacc (the simulation diverged).
    BadQacc,
    /// `mjWARN_BADCTRL`: NaN, Inf or a huge value in ctrl.
    BadCtrl,
}

const WARNING_KINDS: [WarningKind; 7] = [
    WarningKind::Inertia,
    WarningKind::ContactFull,
    WarningKind::ConstraintFull,
    WarningKind::BadQpos,
    WarningKind::BadQvel,
    WarningKind::BadQacc,
    WarningKind::BadCtrl,
];

/// Warnings MuJoCo raised: of one kind, how often, and MuJoCo's text for the last.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct Warning {
    /// The kind.
    pub kind: WarningKind,
    /// How many times (in the call that returned it, or since the last reset).
    pub count: u32,
    /// MuJoCo's text (`mju_warningText`) for the last one, such as
    /// `Nan, Inf or huge value in QACC at DOF 3. The simulation is unstable.`.
    pub text: String,
    /// The element the last one is about, where MuJoCo says (a degree of freedom or
    /// position: its joint; a control: its actuator); `None` for too many contacts or
    /// constraints.
    pub element: Option<WarningElement>,
}

/// The element a [`Warning`] is about.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct WarningElement {
    /// Its kind ([`ObjKind::Joint`] or [`ObjKind::Actuator`]).
    pub kind: ObjKind,
    /// Its MuJoCo id.
    pub id: usize,
    /// Its full name as MuJoCo has it (`robot_1/knee`; `None` if unnamed).
    pub name: Option<String>,
    /// The scope it belongs to: its name up to the last `/` (`robot_1`), empty for
    /// the outermost model's own elements.
    pub scope: String,
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} (x{})", self.text, self.count)?;
        if let Some(e) = &self.element {
            let what = if e.kind == ObjKind::Actuator { "actuator" } else { "joint" };
            match (&e.name, e.scope.is_empty()) {
                (Some(n), true) => write!(f, " [{what} '{n}']")?,
                (Some(n), false) => write!(f, " [{what} '{n}' of scope '{}']", e.scope)?,
                (None, _) => write!(f, " [unnamed {what} {}]", e.id)?,
            }
        }
        Ok(())
    }
}

/// The warnings of one [`Physics::step`]: empty when it ran clean. Dropping them
/// unread is a compiler warning (a simulation that went unstable says so only here).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
#[must_use = "MuJoCo's warnings (a diverging simulation, too many contacts) are only reported here"]
pub struct Warnings(pub Vec<Warning>);

impl std::ops::Deref for Warnings {
    type Target = [Warning];
    fn deref(&self) -> &[Warning] {
        &self.0
    }
}

impl IntoIterator for Warnings {
    type Item = Warning;
    type IntoIter = std::vec::IntoIter<Warning>;
    fn into_iter(self) -> Self::IntoIter {
        self.0.into_iter()
    }
}

impl<'a> IntoIterator for &'a Warnings {
    type Item = &'a Warning;
    type IntoIter = std::slice::Iter<'a, Warning>;
    fn into_iter(self) -> Self::IntoIter {
        self.0.iter()
    }
}

impl std::fmt::Display for Warnings {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for (i, w) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str("; ")?;
            }
            write!(f, "{w}")?;
        }
        Ok(())
    }
}

impl Physics {
    /// A simulation of `model` in its default state (MuJoCo's `mj_makeData`).
    ///
    /// Time: O(size of the model's data).
    ///
    /// # Errors
    /// [`Error::Fatal`] when MuJoCo cannot allocate the data.
    pub fn new(model: &Compiled) -> Result<Physics, Error> {
        let fns = &model.inner.mujoco.lib.fns;
        let mut data: *mut mjData = std::ptr::null_mut();
        // SAFETY: a valid model; the guard calls `mj_makeData` and stores its result.
        let fatal =
            unsafe { guard::mjr_make_data(fns.make_data, model.inner.ptr.as_ptr(), &mut data) };
        let messages = guard::take_messages();
        if fatal != 0 {
            return Err(Error::Fatal { call: "Physics::new", message: guard::fatal_message() });
        }
        let data = NonNull::new(data).ok_or_else(|| Error::Fatal {
            call: "Physics::new",
            message: "mj_makeData returned no data".into(),
        })?;
        Ok(Physics {
            model: model.clone(),
            data,
            poisoned: false,
            messages,
            warnings_as_errors: false,
            stale_constants: false,
            written_raw: false,
            scratch: None,
        })
    }

    /// The compiled model.
    ///
    /// Time: O(1).
    pub fn model(&self) -> &Compiled {
        &self.model
    }

    pub(crate) fn m(&self) -> *const mjModel {
        self.model.inner.ptr.as_ptr()
    }

    pub(crate) fn d(&self) -> &mjData {
        // SAFETY: owned and valid while `self` lives.
        unsafe { self.data.as_ref() }
    }

    /// Runs a guarded call; a fatal error poisons the data.
    fn guarded(
        &mut self,
        call: &'static str,
        f: impl FnOnce(*const mjModel, *mut mjData) -> i32,
    ) -> Result<(), Error> {
        let fatal = f(self.m(), self.data.as_ptr());
        self.messages.extend(guard::take_messages());
        if fatal != 0 {
            self.poisoned = true;
            return Err(Error::Fatal { call, message: guard::fatal_message() });
        }
        Ok(())
    }

    fn check(&self) -> Result<(), Error> {
        if self.poisoned { Err(Error::Poisoned) } else { Ok(()) }
    }

    /// Resets the state to the model's defaults (`mj_resetData`); the one way out of
    /// [`Error::Poisoned`].
    ///
    /// Time: O(size of the data).
    ///
    /// # Errors
    /// [`Error::Fatal`] from inside MuJoCo.
    pub fn reset(&mut self) -> Result<(), Error> {
        self.update_constants()?;
        let f = self.model.inner.mujoco.lib.fns.reset_data;
        // SAFETY: valid model and data of that model; the guard calls `f` with them.
        self.guarded("Physics::reset", |m, d| unsafe { guard::mjr_call(f, m, d) })?;
        self.poisoned = false;
        Ok(())
    }

    /// Resets the state to the keyframe named `name` (`mj_resetDataKeyframe`); call
    /// [`Physics::forward`] to compute positions before reading them.
    ///
    /// Time: O(size of the data).
    ///
    /// # Errors
    /// [`Error::NoKey`] when the model has no key of that name; [`Error::Fatal`] from
    /// inside MuJoCo.
    pub fn reset_to_key(&mut self, name: &str) -> Result<(), Error> {
        let key = self
            .model
            .id(crate::ObjKind::Key, name)
            .ok_or_else(|| Error::NoKey { name: name.to_string() })?;
        self.update_constants()?;
        let f = self.model.inner.mujoco.lib.fns.reset_data_keyframe;
        let key = i32::try_from(key).map_err(|_| Error::NoKey { name: name.to_string() })?;
        // SAFETY: valid model and data, and a key id of the model.
        self.guarded("Physics::reset_to_key", |m, d| unsafe {
            guard::mjr_reset_key(f, m, d, key)
        })?;
        self.poisoned = false;
        Ok(())
    }

    /// Computes everything that follows from the state (`mj_forward`): positions,
    /// velocities, forces, sensors; time does not advance.
    ///
    /// Time: one MuJoCo forward pass.
    ///
    /// # Errors
    /// [`Error::Poisoned`]; [`Error::Fatal`] from inside MuJoCo.
    pub fn forward(&mut self) -> Result<(), Error> {
        self.check()?;
        self.update_constants()?;
        let f = self.model.inner.mujoco.lib.fns.forward;
        // SAFETY: valid model and data of that model.
        self.guarded("Physics::forward", |m, d| unsafe { guard::mjr_call(f, m, d) })
    }

    /// Advances the simulation by `n` time steps (`mj_step` `n` times) and returns the
    /// warnings MuJoCo raised during them (empty when it ran clean), each naming the
    /// element it is about where MuJoCo says ([`Warning::element`]).
    ///
    /// Time: n MuJoCo steps.
    ///
    /// # Errors
    /// [`Error::Poisoned`]; [`Error::Fatal`] from inside MuJoCo (the data is then
    /// poisoned until reset); with [`Physics::set_warnings_as_errors`],
    /// [`Error::Warned`] when MuJoCo warned (the steps were taken).
    pub fn step(&mut self, n: usize) -> Result<Warnings, Error> {
        self.check()?;
        self.update_constants()?;
        let before = self.counts();
        let f = self.model.inner.mujoco.lib.fns.step;
        let n = c_long::try_from(n).unwrap_or(c_long::MAX);
        // SAFETY: valid model and data of that model.
        self.guarded("Physics::step", |m, d| unsafe { guard::mjr_step(f, m, d, n) })?;
        let after = self.counts();
        let warnings = Warnings(self.warnings_between(&before, &after));
        if self.warnings_as_errors && !warnings.is_empty() {
            return Err(Error::Warned(warnings));
        }
        Ok(warnings)
    }

    /// Makes [`Physics::step`] return [`Error::Warned`] when MuJoCo warns (for
    /// properties such as "every generated scene simulates"); off by default.
    ///
    /// Time: O(1).
    pub fn set_warnings_as_errors(&mut self, yes: bool) {
        self.warnings_as_errors = yes;
    }

    /// The element MuJoCo's warning `kind` with `info` is about.
    fn warning_element(&self, kind: WarningKind, info: usize) -> Option<WarningElement> {
        let model = &self.model;
        let ints = |name: &str| model.ints(name).ok();
        let (obj, id) = match kind {
            // A position index: the joint whose positions hold it.
            WarningKind::BadQpos => {
                let adr = ints("jnt_qposadr")?;
                let joint =
                    adr.iter().rposition(|&a| usize::try_from(a).is_ok_and(|a| a <= info))?;
                (ObjKind::Joint, joint)
            }
            // A degree of freedom: its joint.
            WarningKind::BadQvel | WarningKind::BadQacc | WarningKind::Inertia => {
                let joint = *ints("dof_jntid")?.get(info)?;
                (ObjKind::Joint, usize::try_from(joint).ok()?)
            }
            WarningKind::BadCtrl => (ObjKind::Actuator, info),
            _ => return None,
        };
        if id >= model.count(obj) {
            return None;
        }
        let name = model.name(obj, id).filter(|n| !n.is_empty()).map(str::to_string);
        let scope = name.as_deref().and_then(|n| n.rsplit_once('/')).map_or("", |(s, _)| s);
        Some(WarningElement { kind: obj, id, scope: scope.to_string(), name })
    }

    fn counts(&self) -> [u32; 7] {
        let w = &self.d().warning;
        std::array::from_fn(|i| u32::try_from(w[i].number).unwrap_or(0))
    }

    fn warnings_between(&self, before: &[u32; 7], after: &[u32; 7]) -> Vec<Warning> {
        let fns = &self.model.inner.mujoco.lib.fns;
        (0..WARNING_KINDS.len())
            .filter(|&i| after[i] != before[i])
            .map(|i| {
                let info = usize::try_from(self.d().warning[i].lastinfo).unwrap_or(0);
                // SAFETY: a warning index below mjNWARNING; MuJoCo returns a static
                // buffer's text (or null).
                let text = unsafe {
                    let p = (fns.warning_text)(i as i32, info);
                    if p.is_null() {
                        String::new()
                    } else {
                        CStr::from_ptr(p).to_string_lossy().into_owned()
                    }
                };
                let kind = WARNING_KINDS[i];
                let element = self.warning_element(kind, info);
                Warning { kind, count: after[i].wrapping_sub(before[i]), text, element }
            })
            .collect()
    }

    /// Every warning since the last reset, by kind.
    ///
    /// Time: O(1).
    pub fn warnings(&self) -> Vec<Warning> {
        self.warnings_between(&[0; 7], &self.counts())
    }

    /// The messages MuJoCo logged in this simulation's calls (taken out).
    ///
    /// Time: O(1).
    pub fn take_messages(&mut self) -> Vec<Message> {
        std::mem::take(&mut self.messages)
    }

    /// The simulation time.
    ///
    /// Time: O(1).
    pub fn time(&self) -> f64 {
        self.d().time
    }

    /// Sets the simulation time.
    ///
    /// Time: O(1).
    pub fn set_time(&mut self, time: f64) {
        // SAFETY: owned data.
        unsafe { self.data.as_mut() }.time = time;
    }

    /// A whole array field of the data, by its `mjData` name (`qpos`, `xpos`, ...).
    ///
    /// Time: O(f) for the f fields of `mjData`.
    ///
    /// # Errors
    /// [`BindError::NoField`] for a name `mjData` has no array field of;
    /// [`BindError::WrongType`] for a field of another scalar type.
    pub fn data(&self, name: &str) -> Result<&[f64], BindError> {
        let (i, field) = data_field(name)?;
        // SAFETY: valid model and data.
        let raw = crate::fields::data_field(self.d(), unsafe { &*self.m() }, i)
            .ok_or_else(|| no_data_field(name))?;
        // SAFETY: the field's pointer and size from the data's own tables; borrowed
        // from `self`.
        unsafe { raw.slice(field, Scalar::F64, "f64") }
    }

    /// [`Physics::data`], to write.
    ///
    /// Time: as [`Physics::data`].
    ///
    /// # Errors
    /// As [`Physics::data`].
    pub fn data_mut(&mut self, name: &str) -> Result<&mut [f64], BindError> {
        let (i, field) = data_field(name)?;
        // SAFETY: valid model and data.
        let raw = crate::fields::data_field(self.d(), unsafe { &*self.m() }, i)
            .ok_or_else(|| no_data_field(name))?;
        // SAFETY: as in `data`, borrowed mutably from `self`, which owns the data.
        unsafe { raw.slice_mut(field, Scalar::F64, "f64") }
    }

    /// Positions (`qpos`).
    ///
    /// Time: O(f).
    pub fn qpos(&self) -> &[f64] {
        self.data("qpos").unwrap_or_default()
    }

    /// Positions (`qpos`), to write.
    ///
    /// Time: O(f).
    pub fn qpos_mut(&mut self) -> &mut [f64] {
        self.data_mut("qpos").unwrap_or_default()
    }

    /// Velocities (`qvel`).
    ///
    /// Time: O(f).
    pub fn qvel(&self) -> &[f64] {
        self.data("qvel").unwrap_or_default()
    }

    /// Velocities (`qvel`), to write.
    ///
    /// Time: O(f).
    pub fn qvel_mut(&mut self) -> &mut [f64] {
        self.data_mut("qvel").unwrap_or_default()
    }

    /// Controls (`ctrl`).
    ///
    /// Time: O(f).
    pub fn ctrl(&self) -> &[f64] {
        self.data("ctrl").unwrap_or_default()
    }

    /// Controls (`ctrl`), to write.
    ///
    /// Time: O(f).
    pub fn ctrl_mut(&mut self) -> &mut [f64] {
        self.data_mut("ctrl").unwrap_or_default()
    }

    /// Binds an element by locator, by kind and full name, or by kind and id (see
    /// [`Compiled::bind`]).
    ///
    /// Time: as [`Compiled::bind`].
    ///
    /// # Errors
    /// As [`Compiled::bind`].
    pub fn bind(&self, target: impl BindTarget) -> Result<Bound, BindError> {
        self.model.bind(target)
    }

    fn slot(&self, b: &Bound, field: &str) -> Result<Slot, BindError> {
        // SAFETY: valid model.
        bind::resolve(unsafe { &*self.m() }, b.kind, b.id, field)
    }

    /// A field of a bound element, as dm_control's `physics.bind(el).field`: a field
    /// of the data first (`qpos` and `qvel` of a joint, `xpos` and `xquat` of a body,
    /// `xpos` of a site, `ctrl` and `act` of an actuator, `sensordata` of a sensor),
    /// else of the model (`damping` of a joint, `mass` of a body, `friction` and
    /// `size` of a geom, `gainprm` of an actuator); `mjModel` and `mjData` names work
    /// too (`dof_damping`, `site_xpos`). The element's rows, row after row.
    ///
    /// Time: O(f) for the f fields of `mjModel` and `mjData`.
    ///
    /// # Errors
    /// [`BindError::NoField`] (naming the fields there are); [`BindError::WrongType`]
    /// for a field of integers (see [`Physics::ints`]).
    pub fn get(&self, b: &Bound, field: &str) -> Result<&[f64], BindError> {
        let slot = self.slot(b, field)?;
        // SAFETY: valid model and data.
        let raw = bind::raw(&slot, unsafe { &*self.m() }, Some(self.d()))
            .ok_or_else(|| no_data_field(field))?;
        // SAFETY: the field's pointer and size from the model's tables, borrowed from
        // `self`; the rows are the element's, within the field.
        let all: &[f64] = unsafe { raw.slice(slot.field, Scalar::F64, "f64") }?;
        Ok(&all[slot.rows.start * raw.cols..slot.rows.end * raw.cols])
    }

    /// [`Physics::get`], to write. Writing a model field when the compiled model is
    /// shared (with other simulations, or a [`Compiled`] kept elsewhere) first gives
    /// this simulation its own copy of the model (`mj_copyModel`), so the others keep
    /// their numbers.
    ///
    /// A written model field makes the model what compiling the edited model gives:
    /// when MuJoCo derives constants from the field (masses, inertias, body and joint
    /// poses, axes, armatures, gears, ranges, ...), they are recomputed
    /// (`mj_setConst`, with a scratch data of its own, never this simulation's) before
    /// the next call into MuJoCo ([`Physics::step`], [`Physics::forward`], the
    /// resets) or at [`Physics::update_constants`]. Nothing is recomputed after a
    /// field nothing derives from (friction, gains, damping, solver parameters).
    /// A field the compiler derives more from is refused ([`Error::NeedsRebuild`]):
    /// edit the `mjcf` model and [`Physics::rebuild`]. Write what a compile would
    /// hold: a unit axis, a unit quaternion. A position servo's damping ratio
    /// (`dampratio`) is turned into a damping from its gain by MuJoCo 4.0.0's
    /// compiler only (not by `mj_setConst`): a gain written here keeps the damping
    /// compiled from the old gain; a rebuild from the edited model compiles it.
    ///
    /// Time: O(f), plus the copy of the model the first time a shared one is written;
    /// `mj_setConst` (O(nv²) at most) before the next step after a write of a field
    /// constants derive from.
    ///
    /// # Errors
    /// As [`Physics::get`]; [`Error::NeedsRebuild`] for a model field that cannot be
    /// written in place (a geom's size or pose, a free body's pose, meshes, derived
    /// constants); [`Error::Fatal`] when MuJoCo cannot copy the model.
    pub fn get_mut(&mut self, b: &Bound, field: &str) -> Result<&mut [f64], Error> {
        let slot = self.slot(b, field)?;
        if slot.place == Place::Model {
            let class = crate::constants::class(slot.field.name);
            if let crate::constants::Class::Refused(reason) = class {
                return Err(Error::NeedsRebuild { field: slot.field.name, reason });
            }
            if matches!(slot.field.name, "body_pos" | "body_quat") && self.has_free_joint(b.id) {
                let reason = crate::constants::FREE_BODY_POSE;
                return Err(Error::NeedsRebuild { field: slot.field.name, reason });
            }
            self.own_model()?;
            self.written_raw = true;
            if class == crate::constants::Class::SetConst {
                self.stale_constants = true;
            }
        }
        // SAFETY: valid model and data.
        let raw = bind::raw(&slot, unsafe { &*self.m() }, Some(self.d()))
            .ok_or_else(|| no_data_field(field))?;
        // SAFETY: as in `get`; the model is owned by this simulation alone now
        // (`own_model`), and the data always is.
        let all: &mut [f64] = unsafe { raw.slice_mut(slot.field, Scalar::F64, "f64") }?;
        Ok(&mut all[slot.rows.start * raw.cols..slot.rows.end * raw.cols])
    }

    /// Whether body `body` has a free joint.
    fn has_free_joint(&self, body: usize) -> bool {
        let (Ok(jb), Ok(jt)) = (self.model.ints("jnt_bodyid"), self.model.ints("jnt_type")) else {
            return false;
        };
        jb.iter().zip(jt).any(|(&b, &t)| {
            usize::try_from(b).is_ok_and(|b| b == body)
                && JointType::from_mujoco(t.into()) == Some(JointType::Free)
        })
    }

    /// Recomputes the constants MuJoCo derives from the model's numbers
    /// (`mj_setConst`) if a field they derive from was written since
    /// ([`Physics::get_mut`]); the steps and resets call it. It runs with a scratch
    /// data of its own, reset first, as the compiler's: the simulation's state is not
    /// touched.
    ///
    /// Time: O(1) when nothing is stale; else `mj_setConst` (a forward pass at
    /// `qpos0` and O(nv²) for the inverse weights).
    ///
    /// # Errors
    /// [`Error::Fatal`] from inside MuJoCo (the simulation's data stays usable).
    pub fn update_constants(&mut self) -> Result<(), Error> {
        if !self.stale_constants {
            return Ok(());
        }
        self.own_model()?;
        let fns = self.model.inner.mujoco.lib.fns;
        let m = self.model.inner.ptr.as_ptr();
        let scratch = match self.scratch {
            Some(d) => d,
            None => {
                let mut d: *mut mjData = std::ptr::null_mut();
                // SAFETY: a valid model; the guard stores `mj_makeData`'s result.
                let fatal = unsafe { guard::mjr_make_data(fns.make_data, m, &mut d) };
                self.messages.extend(guard::take_messages());
                let d = NonNull::new(d).filter(|_| fatal == 0).ok_or_else(|| Error::Fatal {
                    call: "Physics::update_constants",
                    message: guard::fatal_message(),
                })?;
                self.scratch = Some(d);
                d
            }
        };
        // SAFETY: the model is this simulation's own (`own_model`), written only
        // here; the scratch data was made for a model of its sizes (this one, or the
        // one it was copied from) and is reset before `mj_setConst` reads it.
        let fatal = unsafe {
            let reset = guard::mjr_call(fns.reset_data, m, scratch.as_ptr());
            if reset != 0 {
                reset
            } else {
                guard::mjr_set_const(fns.set_const, m, scratch.as_ptr())
            }
        };
        self.messages.extend(guard::take_messages());
        if fatal != 0 {
            return Err(Error::Fatal {
                call: "Physics::update_constants",
                message: guard::fatal_message(),
            });
        }
        self.stale_constants = false;
        Ok(())
    }

    /// [`Physics::get`] for fields of integers (`contype` of a geom, `qposadr` of a
    /// joint).
    ///
    /// Time: as [`Physics::get`].
    ///
    /// # Errors
    /// As [`Physics::get`], the other way round.
    pub fn ints(&self, b: &Bound, field: &str) -> Result<&[i32], BindError> {
        let slot = self.slot(b, field)?;
        // SAFETY: valid model and data.
        let raw = bind::raw(&slot, unsafe { &*self.m() }, Some(self.d()))
            .ok_or_else(|| no_data_field(field))?;
        // SAFETY: as in `get`.
        let all: &[i32] = unsafe { raw.slice(slot.field, Scalar::I32, "i32") }?;
        Ok(&all[slot.rows.start * raw.cols..slot.rows.end * raw.cols])
    }

    /// [`Physics::get`] for fields of flags (`active` of an equality: MuJoCo's
    /// `eq_active`, 0 or 1).
    ///
    /// Time: as [`Physics::get`].
    ///
    /// # Errors
    /// As [`Physics::get`], for a field of flags.
    pub fn flags(&self, b: &Bound, field: &str) -> Result<&[u8], BindError> {
        let slot = self.slot(b, field)?;
        // SAFETY: valid model and data.
        let raw = bind::raw(&slot, unsafe { &*self.m() }, Some(self.d()))
            .ok_or_else(|| no_data_field(field))?;
        // SAFETY: as in `get`.
        let all: &[u8] = unsafe { raw.slice(slot.field, Scalar::Bool, "flags") }?;
        Ok(&all[slot.rows.start * raw.cols..slot.rows.end * raw.cols])
    }

    /// [`Physics::flags`], to write a field of the simulation's data (`active` of an
    /// equality).
    ///
    /// Time: as [`Physics::get`].
    ///
    /// # Errors
    /// As [`Physics::flags`]; [`BindError::NoField`] for a field of the model.
    pub fn flags_mut(&mut self, b: &Bound, field: &str) -> Result<&mut [u8], BindError> {
        let slot = self.slot(b, field)?;
        if slot.place == Place::Model {
            return Err(BindError::NoField {
                kind: b.kind.name(),
                field: field.to_string(),
                known: "the simulation's data fields of flags".into(),
            });
        }
        // SAFETY: valid model and data.
        let raw = bind::raw(&slot, unsafe { &*self.m() }, Some(self.d()))
            .ok_or_else(|| no_data_field(field))?;
        // SAFETY: as in `get_mut`: the data is this simulation's own.
        let all: &mut [u8] = unsafe { raw.slice_mut(slot.field, Scalar::Bool, "flags") }?;
        Ok(&mut all[slot.rows.start * raw.cols..slot.rows.end * raw.cols])
    }

    /// Makes the compiled model this simulation's own (copied if shared).
    pub(crate) fn own_model(&mut self) -> Result<(), Error> {
        if Arc::get_mut(&mut self.model.inner).is_some() {
            return Ok(());
        }
        let inner = &self.model.inner;
        let fns = &inner.mujoco.lib.fns;
        let mut copy: *mut mjModel = std::ptr::null_mut();
        // SAFETY: a valid source model; the guard calls `mj_copyModel(NULL, src)`.
        let fatal = unsafe { guard::mjr_copy_model(fns.copy_model, inner.ptr.as_ptr(), &mut copy) };
        self.messages.extend(guard::take_messages());
        let ptr = NonNull::new(copy).filter(|_| fatal == 0).ok_or_else(|| Error::Fatal {
            call: "Physics::get_mut",
            message: guard::fatal_message(),
        })?;
        self.model = Compiled {
            inner: Arc::new(Inner {
                mujoco: inner.mujoco.clone(),
                ptr,
                source: inner.source.clone(),
                messages: inner.messages.clone(),
            }),
        };
        Ok(())
    }
}

fn data_field(name: &str) -> Result<(usize, &'static crate::fields::Field), BindError> {
    let i = crate::fields::DATA_FIELDS
        .iter()
        .position(|f| f.name == name)
        .ok_or_else(|| no_data_field(name))?;
    Ok((i, &crate::fields::DATA_FIELDS[i]))
}

fn no_data_field(name: &str) -> BindError {
    BindError::NoField {
        kind: "data",
        field: name.to_string(),
        known: "mjData's array fields".into(),
    }
}
