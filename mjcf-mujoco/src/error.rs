//! The binding's errors.

use std::path::PathBuf;

/// What went wrong in a call to MuJoCo, or before it.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// No MuJoCo library was found where [`MuJoCo::load`](crate::MuJoCo::load) looked.
    #[error(
        "MuJoCo's library was not found ({tried}): install MuJoCo {expected} and point \
         MUJOCO_LIB at its library, in a shell: `pip install mujoco=={expected}` then \
         `export MUJOCO_LIB=$(python3 -c 'import os, mujoco; print(os.path.join(os.path.dirname(mujoco.__file__), \"libmujoco.so.{expected}\"))')` \
         (or pass the file's path to MuJoCo::load_from)",
        expected = crate::MUJOCO_VERSION
    )]
    NotFound {
        /// What was tried, in order.
        tried: String,
    },
    /// The library file could not be loaded (not found, not a shared library, or
    /// missing a function the binding calls).
    #[error("cannot load MuJoCo from {path}: {reason}", path = path.display())]
    Load {
        /// The file.
        path: PathBuf,
        /// The loader's reason.
        reason: String,
    },
    /// The library is another version of MuJoCo than the bindings were made for.
    #[error(
        "{path} is MuJoCo {found}, and these bindings are for MuJoCo {expected} exactly \
         (MuJoCo's struct layouts change between releases): install MuJoCo {expected}",
        path = path.display(),
        expected = crate::MUJOCO_VERSION
    )]
    Version {
        /// The file.
        path: PathBuf,
        /// The version it reports (`mj_versionString`).
        found: String,
    },
    /// The model could not be written as MJCF.
    #[error(transparent)]
    Write(Box<mjcf::WriteError>),
    /// MuJoCo refused the model (its parser or compiler).
    #[error(transparent)]
    Compile(Box<CompileError>),
    /// MuJoCo raised a fatal error (`mju_error`) during `call`; the simulation data it
    /// was working on must be reset before it is used again.
    #[error("MuJoCo fatal error in {call}: {message}")]
    Fatal {
        /// The binding's function that entered MuJoCo.
        call: &'static str,
        /// MuJoCo's message.
        message: String,
    },
    /// MuJoCo warned while stepping, with
    /// [`Physics::set_warnings_as_errors`](crate::Physics::set_warnings_as_errors) on
    /// (the steps were taken; the data is usable).
    #[error("MuJoCo warned while stepping: {0}")]
    Warned(crate::physics::Warnings),
    /// The simulation data met a fatal error in an earlier call and has not been reset.
    #[error("the simulation data is unusable after a fatal MuJoCo error; reset it first")]
    Poisoned,
    /// A model field that cannot be written in place: the compiler derives more from
    /// it than MuJoCo's `mj_setConst` recomputes. Edit the `mjcf` model and rebuild
    /// ([`Physics::rebuild`](crate::Physics::rebuild)).
    #[error(
        "{field} cannot be written in a compiled model ({reason}): edit the mjcf model and \
         rebuild (Physics::rebuild)"
    )]
    NeedsRebuild {
        /// The field (MuJoCo's name).
        field: &'static str,
        /// Why.
        reason: &'static str,
    },
    /// No key of that name in the compiled model.
    #[error("no keyframe named {name:?} in the compiled model")]
    NoKey {
        /// The name asked for.
        name: String,
    },
    /// An element of the `mjcf` model that the compiled model does not have, or that
    /// cannot be bound.
    #[error(transparent)]
    Bind(#[from] BindError),
}

impl From<mjcf::WriteError> for Error {
    fn from(e: mjcf::WriteError) -> Error {
        Error::Write(Box::new(e))
    }
}

impl From<CompileError> for Error {
    fn from(e: CompileError) -> Error {
        Error::Compile(Box::new(e))
    }
}

/// MuJoCo's refusal of a model, with where it points in the `mjcf` model when MuJoCo
/// names an element.
#[derive(Debug, Clone, thiserror::Error)]
#[error("MuJoCo refused the model: {message}{}", element_note(.element))]
#[non_exhaustive]
pub struct CompileError {
    /// MuJoCo's message, as it gave it.
    pub message: String,
    /// The line of the written XML MuJoCo names, if any.
    pub line: Option<usize>,
    /// The element of the `mjcf` model at that line (or of the name MuJoCo gives).
    pub element: Option<ErrorElement>,
}

/// An element of the compiled `mjcf` model that an error points at.
#[derive(Debug, Clone)]
#[non_exhaustive]
pub struct ErrorElement {
    /// Its locator in the model given to `compile`.
    pub loc: mjcf::Loc,
    /// Its tag.
    pub tag: &'static str,
    /// The name it was written with (its `full_name`), if any.
    pub full_name: Option<String>,
}

fn element_note(element: &Option<ErrorElement>) -> String {
    match element {
        Some(ErrorElement { tag, full_name: Some(name), .. }) => {
            format!(" (at the <{tag}> named {name:?})")
        }
        Some(ErrorElement { tag, full_name: None, .. }) => format!(" (at an unnamed <{tag}>)"),
        None => String::new(),
    }
}

fn did_you_mean(suggestions: &[String]) -> String {
    if suggestions.is_empty() {
        return String::new();
    }
    let names: Vec<String> = suggestions.iter().map(|s| format!("{s:?}")).collect();
    format!(" (did you mean {}?)", names.join(", "))
}

/// Why an element or a field could not be bound.
#[derive(Debug, Clone, thiserror::Error)]
#[non_exhaustive]
pub enum BindError {
    /// The compiled model was not compiled from an `mjcf` model (it came from a file or
    /// text), so it has no locators.
    #[error("the compiled model has no mjcf model to bind locators of (it was compiled from text)")]
    NoSource,
    /// The locator names no element of the model that was compiled.
    #[error("the locator names no element of the compiled model: {0}")]
    NoElement(String),
    /// The element is of a kind that MuJoCo's compiled model keeps no record of
    /// (a `<frame>`, a default class, a section).
    #[error("a <{tag}> has no counterpart in the compiled model")]
    NotCompiled {
        /// Its tag.
        tag: &'static str,
    },
    /// The element has no name in the written model, so it cannot be found by name.
    #[error("the <{tag}> has no name in the written model")]
    Unnamed {
        /// Its tag.
        tag: &'static str,
    },
    /// MuJoCo has no element of that kind and name: a misspelt name given to
    /// [`Compiled::bind`](crate::Compiled::bind) (the nearest names of that kind are
    /// suggested), or for a locator a bug of the writer or of `full_name`, which
    /// MuJoCo judges in this crate's tests.
    #[error("MuJoCo has no {kind} named {name:?}{}", did_you_mean(.suggestions))]
    NotFound {
        /// MuJoCo's object kind.
        kind: &'static str,
        /// The name looked up.
        name: String,
        /// The nearest names of that kind the compiled model has (at most five,
        /// nearest first; empty when none is near).
        suggestions: Vec<String>,
    },
    /// No element of that kind has that MuJoCo id.
    #[error("no {kind} has id {id} (the model has {count})")]
    NoId {
        /// MuJoCo's object kind.
        kind: &'static str,
        /// The id asked for.
        id: usize,
        /// How many there are.
        count: usize,
    },
    /// No field of that name for this kind of element.
    #[error("no field {field:?} for a {kind} (fields: {known})")]
    NoField {
        /// MuJoCo's object kind.
        kind: &'static str,
        /// The field asked for.
        field: String,
        /// The fields there are, comma-separated.
        known: String,
    },
    /// The field holds another scalar type than was asked for.
    #[error("the field {field} holds {holds}, not {asked}")]
    WrongType {
        /// The field.
        field: &'static str,
        /// What it holds (`f64`, `i32`, ...).
        holds: &'static str,
        /// What was asked.
        asked: &'static str,
    },
}
