//! `mjcf.History`: an undo list of model versions.
use mjcf::History;
use pyo3::exceptions::PyIndexError;
use pyo3::prelude::*;

use crate::model::PyModel;

/// An undo/redo list of model versions (each a cheap, structure-sharing value):
/// `push(model, label)` after an edit, `undo()`, `redo()`; `current` is the model at
/// the present position. Pushing after an undo drops the versions ahead.
#[pyclass(module = "mjcf", name = "History")]
#[derive(Debug)]
pub(crate) struct PyHistory {
    inner: History,
}

impl PyHistory {
    fn current_model(&self) -> PyModel {
        PyModel::from(self.inner.current().clone())
    }
}

#[pymethods]
impl PyHistory {
    /// A history whose first version is `model`; `limit` caps the versions kept (the
    /// oldest are dropped).
    #[new]
    #[pyo3(signature = (model, limit = None))]
    fn new(model: PyRef<'_, PyModel>, limit: Option<usize>) -> PyHistory {
        let m = model.inner.clone();
        let inner = match limit {
            Some(n) => History::with_limit(m, n.max(1)),
            None => History::new(m),
        };
        PyHistory { inner }
    }

    /// Records `model` as the next version (dropping any versions ahead of the
    /// present one); returns it.
    #[pyo3(signature = (model, label = ""))]
    fn push(&mut self, model: PyRef<'_, PyModel>, label: &str) -> PyModel {
        self.inner.push(label, model.inner.clone());
        self.current_model()
    }

    /// Steps back one version if there is one; returns the model now current.
    fn undo(&mut self) -> PyModel {
        self.inner.undo();
        self.current_model()
    }

    /// Steps forward one version if there is one; returns the model now current.
    fn redo(&mut self) -> PyModel {
        self.inner.redo();
        self.current_model()
    }

    /// Moves to version `index`; returns the model now current.
    fn go_to(&mut self, index: usize) -> PyResult<PyModel> {
        if !self.inner.go_to(index) {
            return Err(PyIndexError::new_err(format!("no version {index} is kept")));
        }
        Ok(self.current_model())
    }

    /// The model at the present position.
    #[getter]
    fn current(&self) -> PyModel {
        self.current_model()
    }

    /// The index of the present version.
    #[getter]
    fn position(&self) -> usize {
        self.inner.position()
    }

    /// The label each version was pushed with (`"start"` for the first), oldest first.
    fn labels(&self) -> Vec<String> {
        (0..self.inner.len()).filter_map(|i| self.inner.label(i).map(str::to_string)).collect()
    }

    /// The version at `index`.
    fn __getitem__(&self, index: usize) -> PyResult<PyModel> {
        self.inner
            .get(index)
            .map(|m| PyModel::from(m.clone()))
            .ok_or_else(|| PyIndexError::new_err(format!("no version {index} is kept")))
    }

    /// The number of versions kept.
    fn __len__(&self) -> usize {
        self.inner.len()
    }

    /// The changes from version `start` to version `end`, one line each.
    fn diff(&self, start: usize, end: usize) -> PyResult<Vec<String>> {
        self.inner.diff_lines(start, end).ok_or_else(|| {
            PyIndexError::new_err(format!("versions {start} and {end} are not both kept"))
        })
    }

    fn __repr__(&self) -> String {
        format!("<mjcf.History {} of {}>", self.inner.position(), self.inner.len())
    }
}
