//! The Python package `mjcf`: MuJoCo MJCF models as persistent values, over the
//! `mjcf` crate.
//!
//! Every Python object here is a thin handle on a crate value: a `model::PyModel`
//! holds an `mjcf::Model` (a cheap, structure-sharing clone), an element handle holds
//! a model and the element's locator, so a handle stays valid for the model value it
//! was taken from whatever edits follow. Nothing is mutated in place but a
//! `History`'s position. Reading, writing and saving release the GIL.
#![forbid(unsafe_code)]

mod convert;
mod element;
mod errors;
mod history;
mod model;

use pyo3::prelude::*;

/// The extension module `mjcf`.
#[pymodule]
#[pyo3(name = "_mjcf")]
fn mjcf_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add_class::<model::PyModel>()?;
    m.add_class::<element::PyElement>()?;
    m.add_class::<element::PyAttachment>()?;
    m.add_class::<element::PyProblem>()?;
    m.add_class::<history::PyHistory>()?;
    errors::register(py, m)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}

/// Assertions that the crate's values can cross threads, which releasing the GIL
/// around reading, writing and saving needs (a compile-time check).
const _: () = {
    const fn send_sync<T: Send + Sync>() {}
    send_sync::<mjcf::Model>();
    send_sync::<mjcf::Loc>();
    send_sync::<mjcf::Attachment>();
    send_sync::<mjcf::History>();
};
