//! Rebuilding a running simulation from a new version of its model, keeping its
//! state ([`Physics::rebuild`]).

mod carry;
mod ids;
mod in_place;

use std::sync::Arc;
use std::time::Instant;

use mjcf::Model;

pub(crate) use self::ids::Ids;
use crate::bind::ObjKind;
use crate::error::Error;
use crate::model::{Compiled, Source};
use crate::physics::Physics;

/// How a rebuild made the new model ([`RebuildReport::mode`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum RebuildMode {
    /// The model did not change: the simulation goes on as it was.
    None,
    /// Only numbers changed, written into the compiled model (with MuJoCo's derived
    /// constants recomputed where they derive from them): no compile, the
    /// simulation's data kept as it is.
    InPlace,
    /// The new model was compiled and the state carried over.
    Compiled,
}

impl RebuildMode {
    /// `none`, `in_place` or `compiled`.
    ///
    /// Time: O(1).
    pub fn name(self) -> &'static str {
        match self {
            RebuildMode::None => "none",
            RebuildMode::InPlace => "in_place",
            RebuildMode::Compiled => "compiled",
        }
    }
}

/// An element whose state was carried over.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct Carried {
    /// Its kind.
    pub kind: ObjKind,
    /// Its full name in the new model.
    pub name: String,
    /// Its full name in the old one (another for a renamed element).
    pub old_name: String,
}

/// Why an element of the new model starts at its default state.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum DefaultedWhy {
    /// The running simulation has no such element (new, or brought back by an undo:
    /// a rebuild never restores state from an earlier simulation).
    New,
    /// A joint whose type changed (its old positions are never read).
    TypeChanged,
    /// An actuator whose number of activations changed.
    ActivationChanged,
    /// An actuator whose number of controls changed.
    ControlsChanged,
    /// A body that became a mocap body.
    NewMocap,
}

/// An element of the new model at its default state: positions at `qpos0`, at rest,
/// no applied force, control 0, default activation.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct Defaulted {
    /// Its kind.
    pub kind: ObjKind,
    /// Its full name in the new model.
    pub name: String,
    /// Why.
    pub why: DefaultedWhy,
}

/// An element of the old model the new one does not have: its state is dropped.
#[derive(Clone, Debug, PartialEq, Eq)]
#[non_exhaustive]
pub struct Dropped {
    /// Its kind.
    pub kind: ObjKind,
    /// Its full name in the old model.
    pub name: String,
}

/// What a [`Physics::rebuild`] did: how, and what became of each joint's,
/// actuator's, body's and equality's state.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub struct RebuildReport {
    /// How the new model was made.
    pub mode: RebuildMode,
    /// Elements whose state was carried over (shared between the reports of
    /// rebuilds that change no element).
    pub carried: Arc<[Carried]>,
    /// Elements of the new model at their defaults, and why.
    pub defaulted: Vec<Defaulted>,
    /// Elements of the old model the new one lacks.
    pub dropped: Vec<Dropped>,
    /// Whole-model arrays (user data, plugin state, history buffers, plastic
    /// state) left at their defaults, and why.
    pub notes: Vec<String>,
    /// The seconds the rebuild took (the compile included).
    pub seconds: f64,
}

impl RebuildReport {
    fn new(mode: RebuildMode) -> RebuildReport {
        RebuildReport {
            mode,
            carried: Arc::new([]),
            defaulted: Vec::new(),
            dropped: Vec::new(),
            notes: Vec::new(),
            seconds: 0.0,
        }
    }
}

impl Physics {
    /// A rebuild with no change, or written in place (`None` when `model` must be
    /// compiled).
    fn without_compile(
        &mut self,
        source: &Source,
        model: &Model,
        options: &mjcf::WriteOptions,
        start: Instant,
    ) -> Result<Option<RebuildReport>, Error> {
        let changes = source.model.diff(model);
        if changes.is_empty() {
            let mut report = RebuildReport::new(RebuildMode::None);
            report.carried = all_carried(&self.model);
            report.seconds = start.elapsed().as_secs_f64();
            return Ok(Some(report));
        }
        let Some(old_ids) = ids::ids(&self.model) else { return Ok(None) };
        let Some(plan) = in_place::plan(&self.model, &old_ids, model, &changes) else {
            return Ok(None);
        };
        let all = all_carried(&self.model);
        self.own_model()?;
        // SAFETY: the model is this simulation's own now.
        unsafe { in_place::apply(self.model.raw(), &plan) };
        let inner = Arc::get_mut(&mut self.model.inner).ok_or_else(|| Error::Fatal {
            call: "Physics::rebuild",
            message: "the model is shared after it was copied".into(),
        })?;
        let source = Source::in_place(model.clone(), options.clone(), old_ids, all.clone());
        inner.source = Some(Arc::new(source));
        self.stale_constants |= plan.set_const;
        self.update_constants()?;
        let mut report = RebuildReport::new(RebuildMode::InPlace);
        report.carried = all;
        report.seconds = start.elapsed().as_secs_f64();
        Ok(Some(report))
    }
}

/// The kinds whose elements a report lists.
const REPORTED: [ObjKind; 4] =
    [ObjKind::Joint, ObjKind::Actuator, ObjKind::Body, ObjKind::Equality];

/// Every element of the reported kinds of `compiled`, carried under its own name
/// (listed once per compiled model).
fn all_carried(compiled: &Compiled) -> Arc<[Carried]> {
    let list = || -> Arc<[Carried]> {
        let mut all = Vec::new();
        for kind in REPORTED {
            for id in 0..compiled.count(kind) {
                let name = compiled.name(kind, id).unwrap_or_default().to_string();
                all.push(Carried { kind, old_name: name.clone(), name });
            }
        }
        all.into()
    };
    match compiled.inner.source.as_deref() {
        Some(source) => source.all.get_or_init(list).clone(),
        None => list(),
    }
}

impl Physics {
    /// Makes this simulation simulate `model` (any version of its model: numbers
    /// changed, elements added or removed, attached, detached, renamed, an undo or
    /// redo to any version), keeping MuJoCo's whole integration state: time, and per
    /// element positions and velocities, warm start accelerations and applied forces
    /// of each joint; controls and activations of each actuator; applied forces and
    /// mocap poses of each body; whether each equality is active; and user data,
    /// plugin state, history buffers and plastic state where the layouts agree.
    ///
    /// - No change ([`RebuildMode::None`]): nothing happens; the simulation continues
    ///   bit for bit as if there had been no rebuild.
    /// - Numbers only, of the attributes written in place (a geom's friction and
    ///   solver parameters; a joint's damping, friction loss, armature, stiffness; a
    ///   general actuator's gains, biases and dynamics, a motor's or general
    ///   actuator's gear; a body's position (not a free body's) and gravity
    ///   compensation; an inertial's mass and diagonal inertia), when the compiled
    ///   field held exactly the old value: written into the compiled model, MuJoCo's
    ///   derived constants recomputed where they derive from them (`mj_setConst`,
    ///   with a scratch data, never the simulation's) ([`RebuildMode::InPlace`]). The
    ///   model then is what compiling `model` gives.
    /// - Anything else: `model` is compiled, and each element of the new model takes
    ///   the state of the element of the running simulation it continues
    ///   ([`RebuildMode::Compiled`]): the same element of the `mjcf` model (a renamed
    ///   joint keeps its state), or, when the two are not versions of one `mjcf`
    ///   model (or one was compiled from text), the element of the same full name.
    ///   Elements the running simulation lacks (a robot brought back by an undo
    ///   included: state is never restored from an earlier simulation), joints
    ///   whose type changed and actuators whose activation or control count changed
    ///   start at their defaults (positions `qpos0`, at rest); their old state is
    ///   never read. The derived quantities (positions of bodies, forces) are
    ///   computed by the next [`Physics::step`] or [`Physics::forward`].
    ///
    /// The report says which it was, what was carried, defaulted and dropped, and
    /// how long it took. A model first written field by field ([`Physics::get_mut`])
    /// is compiled anew (its numbers are no longer its source's).
    ///
    /// Time: no change: O(E) to compare the versions (shared subtrees skipped) plus
    /// O(n) to list the elements; in place: as much, plus the writes and
    /// `mj_setConst` if a mass, inertia or pose changed; compiled: a compile plus
    /// O(n) to carry the state.
    ///
    /// # Errors
    /// [`Error::Compile`] (with the element and full name MuJoCo names) or
    /// [`Error::Write`] when the new model cannot be compiled: this simulation is
    /// left untouched and usable; [`Error::Poisoned`]; [`Error::Fatal`] from inside
    /// MuJoCo.
    pub fn rebuild(&mut self, model: &Model) -> Result<RebuildReport, Error> {
        let start = Instant::now();
        if self.poisoned {
            return Err(Error::Poisoned);
        }
        let old_source = self.model.inner.source.clone();
        let options = old_source.as_ref().map(|s| s.options.clone()).unwrap_or_default();
        if !self.written_raw {
            if let Some(source) = &old_source {
                if let Some(report) = self.without_compile(source, model, &options, start)? {
                    return Ok(report);
                }
            }
        }
        let compiled = self.model.inner.mujoco.compile_with(model, &options)?;
        let mut new = Physics::new(&compiled)?;
        new.warnings_as_errors = self.warnings_as_errors;
        let mut report = RebuildReport::new(RebuildMode::Compiled);
        let (old_ids, new_ids) = (ids::ids(&self.model), ids::ids(&compiled));
        let pair = match (&old_ids, &new_ids) {
            (Some(o), Some(n)) if ids::related(Some(o), Some(n)) => Some((&**o, &**n)),
            _ => None,
        };
        let mut carried = Vec::new();
        carry::carry(self, &mut new, pair, &mut report, &mut carried);
        report.carried = carried.into();
        *self = new;
        report.seconds = start.elapsed().as_secs_f64();
        Ok(report)
    }
}
