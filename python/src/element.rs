//! Read-only element handles, attachments and check problems.
use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};

use mjcf::{Attachment, ElementRef, Loc, Model};
use pyo3::exceptions::{PyKeyError, PyRuntimeError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::convert;
use crate::model::PyModel;

/// An element of a model, read-only: `tag`, `name`, `full_name`, `element["attr"]`,
/// `children()`. It holds the model value it was taken from, so it stays valid
/// whatever edits follow (they make new models); pass it to that model's or a later
/// version's `add`, `set`, `remove` or `attach`.
#[pyclass(module = "mjcf", name = "Element", frozen)]
#[derive(Clone, Debug)]
pub(crate) struct PyElement {
    pub(crate) model: Model,
    pub(crate) loc: Loc,
}

impl PyElement {
    /// The element handle of `loc` in `model`.
    pub(crate) fn new(model: &Model, loc: Loc) -> PyElement {
        PyElement { model: model.clone(), loc }
    }

    /// The element in its model (always there: the handle holds the model).
    fn element_ref(&self) -> PyResult<ElementRef<'_>> {
        self.model
            .element(&self.loc)
            .ok_or_else(|| PyRuntimeError::new_err("the element is not in its own model"))
    }
}

#[pymethods]
impl PyElement {
    /// The XML tag (`"body"`, `"geom"`, ...).
    #[getter]
    fn tag(&self) -> PyResult<&'static str> {
        Ok(self.element_ref()?.tag())
    }

    /// The element's own identifier (its `name`, or `class` of a default class), or
    /// None.
    #[getter]
    fn name(&self) -> PyResult<Option<String>> {
        Ok(self.element_ref()?.identifier().map(str::to_string))
    }

    /// The name as MuJoCo sees it in the composed model (`"robot_1/torso"` inside an
    /// attachment), or None for an element without a name.
    #[getter]
    fn full_name(&self) -> PyResult<Option<String>> {
        Ok(self.element_ref()?.full_name())
    }

    /// The model value this handle belongs to.
    #[getter]
    fn model(&self) -> PyModel {
        PyModel::from(self.model.clone())
    }

    /// The value of an attribute: `float`, `int`, `str` or a tuple of numbers;
    /// raises KeyError if it is not set.
    fn __getitem__<'py>(&self, py: Python<'py>, attr: &str) -> PyResult<Bound<'py, PyAny>> {
        convert::attr_value(py, &self.element_ref()?, attr)?
            .ok_or_else(|| PyKeyError::new_err(attr.to_string()))
    }

    /// The value of an attribute, or `default` if it is not set.
    #[pyo3(signature = (attr, default=None))]
    fn get<'py>(
        &self,
        py: Python<'py>,
        attr: &str,
        default: Option<Bound<'py, PyAny>>,
    ) -> PyResult<Option<Bound<'py, PyAny>>> {
        Ok(convert::attr_value(py, &self.element_ref()?, attr)?.or(default))
    }

    /// Whether the attribute is set.
    fn __contains__(&self, attr: &str) -> PyResult<bool> {
        Ok(self.element_ref()?.attr(attr).is_some())
    }

    /// The set attributes as a dict, in schema order.
    fn attrs<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let e = self.element_ref()?;
        let out = PyDict::new(py);
        for (name, _) in e.attrs() {
            out.set_item(name, convert::attr_value(py, &e, name)?)?;
        }
        Ok(out)
    }

    /// The child elements, in order (an attachment frame's children include the
    /// attached model's top-level bodies).
    fn children(&self) -> PyResult<Vec<PyElement>> {
        Ok(self.element_ref()?.children().map(|c| PyElement::new(&self.model, c.loc())).collect())
    }

    /// The parent element, or None for the root.
    fn parent(&self) -> PyResult<Option<PyElement>> {
        Ok(self.element_ref()?.parent().map(|p| PyElement::new(&self.model, p.loc())))
    }

    /// The same element (same locator) of equal models; elements of models built
    /// separately are different elements.
    fn __eq__(&self, other: PyRef<'_, PyElement>) -> bool {
        self.loc == other.loc && self.model == other.model
    }

    /// A hash of the element's locator (equal elements have equal locators), O(1).
    fn __hash__(&self) -> u64 {
        let mut h = DefaultHasher::new();
        self.loc.hash(&mut h);
        h.finish()
    }

    /// The same handle (elements are immutable).
    fn __copy__(&self) -> PyElement {
        self.clone()
    }

    /// The same handle (elements are immutable).
    fn __deepcopy__(&self, _memo: &Bound<'_, PyAny>) -> PyElement {
        self.clone()
    }

    fn __repr__(&self) -> PyResult<String> {
        let e = self.element_ref()?;
        Ok(match e.full_name() {
            Some(n) => format!("<mjcf.Element {} {n:?}>", e.tag()),
            None => format!("<mjcf.Element {}>", e.tag()),
        })
    }
}

/// A model attached into another: `frame` is the attachment frame element (in the
/// composed model the attach returned), `scope` the scope its names take.
#[pyclass(module = "mjcf", name = "Attachment", frozen)]
#[derive(Clone, Debug)]
pub(crate) struct PyAttachment {
    pub(crate) model: Model,
    pub(crate) attachment: Attachment,
}

#[pymethods]
impl PyAttachment {
    /// The attachment frame, an element of the composed model.
    #[getter]
    fn frame(&self) -> PyElement {
        PyElement::new(&self.model, self.attachment.frame().clone())
    }

    /// The scope path at attach time, the prefix of the attached model's names
    /// (`"robot"`, `"robot_1"`; `"arena/robot"` inside an attached model).
    #[getter]
    fn scope(&self) -> &str {
        self.attachment.scope()
    }

    /// The attached model's value, as attached.
    #[getter]
    fn child(&self) -> PyResult<PyModel> {
        let m = self
            .model
            .attached(&self.attachment)
            .map_err(|e| Python::attach(|py| crate::errors::edit(py, &e)))?;
        Ok(PyModel::from(m.clone()))
    }

    fn __repr__(&self) -> String {
        format!("<mjcf.Attachment {:?}>", self.attachment.scope())
    }
}

/// A problem `Model.check()` found: `str(problem)` says what and where; `path` is
/// the element as the writer names it (`robot_1/torso`), `element` the element.
#[pyclass(module = "mjcf", name = "Problem", frozen)]
#[derive(Clone, Debug)]
pub(crate) struct PyProblem {
    pub(crate) text: String,
    pub(crate) path: String,
    pub(crate) element: PyElement,
}

#[pymethods]
impl PyProblem {
    /// The element with the problem as the writer names it (`robot_1/torso`,
    /// `//unnamed_geom_3`), or its scope prefix and tag if it has no namespace.
    #[getter]
    fn path(&self) -> &str {
        &self.path
    }

    /// The element with the problem.
    #[getter]
    fn element(&self) -> PyElement {
        self.element.clone()
    }

    fn __str__(&self) -> &str {
        &self.text
    }

    fn __repr__(&self) -> String {
        format!("<mjcf.Problem {:?}>", self.text)
    }
}
