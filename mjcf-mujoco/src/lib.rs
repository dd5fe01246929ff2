//! Compile, bind and simulate [`mjcf`] models with MuJoCo, from Rust.
//!
//! MuJoCo's library is loaded at run time ([`MuJoCo::load`]: `MUJOCO_LIB`, else the
//! system's library paths), so building this crate needs no MuJoCo. The bindings were
//! made for MuJoCo [`MUJOCO_VERSION`] exactly, and any other version is refused
//! (MuJoCo's struct layouts change between releases; MuJoCo's own headers check the
//! same). The `mujoco` Python wheel of that version ships the library:
//! `pip install mujoco==4.0.0`, then `MUJOCO_LIB=.../site-packages/mujoco/libmujoco.so.4.0.0`.
//!
//! ```no_run
//! use mjcf::{Model, element};
//! use mjcf_mujoco::{MuJoCo, Physics};
//!
//! let mut model = Model::new("ball");
//! let ball = model.add_mut(&model.worldbody(), element!("body", name = "ball", pos = [0, 0, 1]))?;
//! model.add_mut(&ball, element!("freejoint"))?;
//! model.add_mut(&ball, element!("geom", type = "sphere", size = [0.1]))?;
//!
//! let mujoco = MuJoCo::load()?;
//! let compiled = mujoco.compile(&model)?; // in memory: no file is written
//! let mut physics = Physics::new(&compiled)?;
//! let ball = physics.bind(&ball)?;
//! let warnings = physics.step(500)?; // each names its joint or actuator, if any
//! assert!(warnings.is_empty(), "{warnings}");
//! println!("the ball is at {:?}", physics.get(&ball, "xpos")?);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! # Binding
//! [`Physics::bind`] (and [`Compiled::bind`]) takes a locator of the `mjcf` model, a
//! kind and full name (`(ObjKind::Actuator, "arm/gripper/fingers_actuator")`, which
//! works for models compiled from a path or from text too, and suggests the nearest
//! names when it is missing), or a kind and MuJoCo id. A bound element's fields are
//! read by MuJoCo's names with their true widths: an actuator's `gainprm` is its 10
//! numbers, a joint's `qpos` its 7, 4 or 1 ([`Physics::get`], [`Compiled::get`]).
//!
//! # Editing a running simulation
//! An editor keeps its model in an [`mjcf::History`] and, after each edit, undo or
//! redo, rebuilds the running simulation from the current version
//! ([`Physics::rebuild`]): numbers only are written into the compiled model in place
//! (MuJoCo's derived constants recomputed, so that the model is what compiling the
//! edited model gives); anything else is compiled, and every joint, actuator, body
//! and equality keeps its state (by element identity: a renamed joint keeps its
//! state), new ones starting at their defaults. A model MuJoCo refuses leaves the
//! simulation as it was.
//!
//! ```no_run
//! use mjcf::{History, Model, Namespace, element};
//! use mjcf_mujoco::{MuJoCo, ObjKind, Physics, RebuildMode};
//!
//! let mut robot = Model::new("robot");
//! let torso = robot.add_mut(&robot.worldbody(), element!("body", name = "torso", pos = [0, 0, 1]))?;
//! robot.add_mut(&torso, element!("freejoint"))?;
//! robot.add_mut(&torso, element!("geom", name = "box", type = "box", size = [0.1, 0.1, 0.1]))?;
//! let mut history = History::new(robot);
//!
//! let mujoco = MuJoCo::load()?;
//! let mut physics = Physics::new(&mujoco.compile(history.current())?)?;
//! let _ = physics.step(100)?;
//!
//! // Numbers only: written in place, the simulation goes on from where it was.
//! let geom = history.current().find(Namespace::Geom, "box").unwrap();
//! history.edit("friction", |m| m.set_attr_mut(&geom, "friction", [0.5]))?;
//! assert_eq!(physics.rebuild(history.current())?.mode, RebuildMode::InPlace);
//!
//! // A new element: compiled; the torso keeps its position and velocity.
//! history.edit("ball", |m| {
//!     let ball = m.add_mut(&m.worldbody(), element!("body", name = "ball", pos = [1, 0, 1]))?;
//!     m.add_mut(&ball, element!("freejoint"))?;
//!     m.add_mut(&ball, element!("geom", type = "sphere", size = [0.1]))
//! })?;
//! let report = physics.rebuild(history.current())?;
//! assert_eq!(report.mode, RebuildMode::Compiled); // report.defaulted: the ball's joint
//! let _ = physics.step(100)?;
//!
//! // Undo and redo drive the simulation too: the ball goes, and comes back at rest.
//! history.undo();
//! physics.rebuild(history.current())?;
//! history.redo();
//! physics.rebuild(history.current())?;
//! let ball = physics.bind((ObjKind::Body, "ball"))?;
//! let _ = physics.step(1)?;
//! println!("the ball is at {:?}", physics.get(&ball, "xpos")?);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! A model field written directly ([`Physics::get_mut`]) is followed by the
//! recomputation of the constants MuJoCo derives from it (`mj_setConst`, with a
//! scratch data: never the running simulation's), or refused with
//! [`Error::NeedsRebuild`] when the compiler derives more from it (a geom's size).
//!
//! # Errors and MuJoCo's fatal errors
//! What MuJoCo reports in its error buffer (parsing, compiling) is a
//! [`CompileError`], with the element of the `mjcf` model MuJoCo names, found through
//! the line of the written XML ([`mjcf::Model::to_xml_written`]). MuJoCo's fatal
//! errors (`mju_error`, which MuJoCo expects not to return: out of memory, an overflow
//! of the data's arena) return, through a small C guard (setjmp/longjmp in C, never
//! across a Rust frame), to the call that entered MuJoCo, as [`Error::Fatal`]; the
//! simulation's data is then unusable ([`Error::Poisoned`]) until [`Physics::reset`].
//! A fatal error on a thread MuJoCo started itself (none is started by this crate)
//! prints the message and aborts. Loading the library replaces MuJoCo's process-wide
//! log handler: warnings are collected per call ([`Compiled::messages`],
//! [`Physics::step`]'s warnings, which a caller cannot drop unread without a compiler
//! warning, each naming the joint or actuator it is about with its scope;
//! [`Physics::set_warnings_as_errors`] makes them errors), nothing is printed, and no
//! `MUJOCO_LOG.TXT` is written.
//!
//! # Threads
//! [`MuJoCo`] and [`Compiled`] are `Send + Sync` (a compiled model is only read while
//! simulating; any number of simulations on any threads can share one), and
//! [`Physics`] is `Send`.

mod bind;
mod compile;
mod constants;
mod error;
mod fields;
mod guard;
mod library;
mod model;
mod physics;
mod rebuild;
#[allow(clippy::all, unsafe_op_in_unsafe_fn, missing_docs, unreachable_pub, dead_code)]
mod sys;

pub use crate::bind::{BindTarget, Bound, ObjKind};
pub use crate::error::{BindError, CompileError, Error, ErrorElement};
pub use crate::guard::Message;
pub use crate::library::MuJoCo;
pub use crate::model::{Compiled, Sizes};
pub use crate::physics::{Physics, Warning, WarningElement, WarningKind, Warnings};
pub use crate::rebuild::{Carried, Defaulted, DefaultedWhy, Dropped, RebuildMode, RebuildReport};

/// The MuJoCo version the bindings were made for, the only one loaded.
pub const MUJOCO_VERSION: &str = "4.0.0";
