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
