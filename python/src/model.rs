//! `mjcf.Model`: a persistent model value; every edit returns a new one.
use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};
use std::path::PathBuf;

use mjcf::{Attrs, Element, Model, ReadOptions, WriteOptions};
use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyTuple};

use crate::convert;
use crate::element::{PyAttachment, PyElement, PyProblem};
use crate::errors;

/// A MuJoCo MJCF model as an immutable value. Every edit (`add`, `set`, `remove`,
/// `attach`, `detach`, ...) returns a new model and leaves this one as it was;
/// versions share what an edit did not touch, so keeping them is cheap. `==` and
/// `hash` compare content. Pickling writes the model as MJCF text with its files
/// (`to_xml()`, `assets()`); unpickling reads them back (see `__reduce__`).
#[pyclass(module = "mjcf", name = "Model", frozen)]
#[derive(Clone, Debug)]
pub(crate) struct PyModel {
    pub(crate) inner: Model,
}

impl From<Model> for PyModel {
    fn from(inner: Model) -> PyModel {
        PyModel { inner }
    }
}

/// A crate edit result as a Python result.
fn edited<T>(py: Python<'_>, r: Result<T, mjcf::EditError>) -> PyResult<T> {
    r.map_err(|e| errors::edit(py, &e))
}

impl PyModel {
    /// The handle of an element of this model.
    fn element(&self, loc: mjcf::Loc) -> PyElement {
        PyElement::new(&self.inner, loc)
    }

    /// Reads `text` with the files of `assets` (names as the text's `file`
    /// attributes give them), the GIL released.
    fn read(
        py: Python<'_>,
        text: &str,
        assets: Option<&Bound<'_, PyDict>>,
        base_dir: Option<PathBuf>,
    ) -> PyResult<PyModel> {
        let mut read = ReadOptions::new();
        for (name, bytes) in assets.into_iter().flat_map(|d| d.iter()) {
            let name: String = name.extract()?;
            let bytes: Vec<u8> = bytes
                .extract()
                .map_err(|_| PyTypeError::new_err(format!("asset '{name}': expected bytes")))?;
            read = read.asset(&name, bytes);
        }
        if let Some(dir) = base_dir {
            read = read.base_dir(dir);
        }
        let m = py.detach(|| read.read_str(text)).map_err(|e| errors::read(py, &e))?;
        Ok(PyModel::from(m))
    }
}

#[pymethods]
impl PyModel {
    /// An empty model named `name` (MuJoCo's `<mujoco model="name">`).
    #[new]
    #[pyo3(signature = (name = "mujoco"))]
    fn new(py: Python<'_>, name: &str) -> PyResult<PyModel> {
        Ok(PyModel::from(edited(py, Model::try_new(name))?))
    }

    /// Reads a model file and the files it includes and names (meshes, textures,
    /// ...); they are kept as the model's source for `save()`.
    #[staticmethod]
    fn from_path(py: Python<'_>, path: PathBuf) -> PyResult<PyModel> {
        let m = py.detach(|| Model::from_path(&path)).map_err(|e| errors::read(py, &e))?;
        Ok(PyModel::from(m))
    }

    /// Reads MJCF text; `assets` maps the file names the text uses to their bytes
    /// (as `assets()` gives them), `base_dir` is the folder other files are read from.
    #[staticmethod]
    #[pyo3(signature = (text, assets = None, base_dir = None))]
    fn from_xml(
        py: Python<'_>,
        text: &str,
        assets: Option<&Bound<'_, PyDict>>,
        base_dir: Option<PathBuf>,
    ) -> PyResult<PyModel> {
        PyModel::read(py, text, assets, base_dir)
    }

    /// The model's name.
    #[getter]
    fn name(&self) -> &str {
        self.inner.name()
    }

    /// The same model with another name.
    fn with_name(&self, py: Python<'_>, name: &str) -> PyResult<PyModel> {
        Ok(PyModel::from(edited(py, self.inner.try_with_name(name))?))
    }

    /// The same model, reading the files its later edits name from folder `dir`.
    fn with_base_dir(&self, dir: PathBuf) -> PyModel {
        PyModel::from(self.inner.with_base_dir(dir))
    }

    /// The composed model as MJCF text (attached models written in their scopes),
    /// the GIL released. The keywords are the crate's `WriteOptions`.
    #[pyo3(signature = (*, precision = None, zero_threshold = None, pretty_print = None, filename_with_hash = None))]
    fn to_xml(
        &self,
        py: Python<'_>,
        precision: Option<u32>,
        zero_threshold: Option<f64>,
        pretty_print: Option<bool>,
        filename_with_hash: Option<bool>,
    ) -> PyResult<String> {
        let o = convert::write_options(precision, zero_threshold, pretty_print, filename_with_hash);
        py.detach(|| self.inner.to_xml_string_with(&o)).map_err(|e| errors::write(py, &e))
    }

    /// The files `to_xml()`'s text names, by the names it gives them, as bytes:
    /// `mujoco.MjModel.from_xml_string(m.to_xml(), m.assets())` compiles the model.
    /// Takes the same keywords as `to_xml()`.
    #[pyo3(signature = (*, precision = None, zero_threshold = None, pretty_print = None, filename_with_hash = None))]
    fn assets<'py>(
        &self,
        py: Python<'py>,
        precision: Option<u32>,
        zero_threshold: Option<f64>,
        pretty_print: Option<bool>,
        filename_with_hash: Option<bool>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let o = convert::write_options(precision, zero_threshold, pretty_print, filename_with_hash);
        let files = py.detach(|| self.inner.assets(&o)).map_err(|e| errors::write(py, &e))?;
        let out = PyDict::new(py);
        for (name, file) in files {
            out.set_item(name, PyBytes::new(py, file.contents()))?;
        }
        Ok(out)
    }

    /// The root element, `<mujoco>`.
    fn root(&self) -> PyElement {
        self.element(self.inner.root())
    }

    /// The `<worldbody>`.
    fn worldbody(&self) -> PyElement {
        self.element(self.inner.worldbody())
    }

    /// The top-level section with this tag (`"asset"`, `"actuator"`, `"option"`, ...),
    /// or None if the root takes no such child.
    fn section(&self, tag: &str) -> Option<PyElement> {
        self.inner.section(tag).map(|l| self.element(l))
    }

    /// The element named `name` in `namespace` (`"body"`, `"geom"`, `"site"`, ...,
    /// `"attachment_frame"` for a scope), or None. Names inside attachments are
    /// scoped: `"robot_1/torso"`.
    fn find(&self, namespace: &str, name: &str) -> PyResult<Option<PyElement>> {
        let ns = convert::namespace(namespace)?;
        Ok(self.inner.find(ns, name).map(|l| self.element(l)))
    }

    /// As `find`, but raises `EditError` (with the closest names) if there is none.
    fn lookup(&self, py: Python<'_>, namespace: &str, name: &str) -> PyResult<PyElement> {
        let ns = convert::namespace(namespace)?;
        Ok(self.element(edited(py, self.inner.lookup(ns, name))?))
    }

    /// Every element of the namespace, attached models' included, in document order.
    fn find_all(&self, namespace: &str) -> PyResult<Vec<PyElement>> {
        let ns = convert::namespace(namespace)?;
        Ok(self.inner.find_all(ns).into_iter().map(|l| self.element(l)).collect())
    }

    /// Adds a `<tag>` with these attributes as the last child of `parent`; returns
    /// `(new model, new element)`. Values are numbers, strings, bools or sequences of
    /// numbers; `class_=` names `class`.
    #[pyo3(signature = (parent, tag, **attrs))]
    fn add(
        &self,
        py: Python<'_>,
        parent: PyRef<'_, PyElement>,
        tag: &str,
        attrs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<(PyModel, PyElement)> {
        let mut el = Element::new(tag);
        for (name, input) in convert::kwargs(attrs)? {
            let input = input.ok_or_else(|| {
                PyTypeError::new_err(format!("attribute '{name}': None is only for set()"))
            })?;
            el = el.attr(&name, input);
        }
        let (m, loc) = edited(py, self.inner.add(&parent.loc, el))?;
        let new = PyElement::new(&m, loc);
        Ok((PyModel::from(m), new))
    }

    /// Sets attributes of `element` (None clears one); returns the new model.
    #[pyo3(signature = (element, **attrs))]
    fn set(
        &self,
        py: Python<'_>,
        element: PyRef<'_, PyElement>,
        attrs: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<PyModel> {
        let mut a = Attrs::new();
        for (name, input) in convert::kwargs(attrs)? {
            a = match input {
                Some(v) => a.set(&name, v),
                None => a.clear(&name),
            };
        }
        Ok(PyModel::from(edited(py, self.inner.set(&element.loc, a))?))
    }

    /// Removes `element` and its subtree; returns the new model. Removing what holds
    /// an attachment frame needs `affect_attachments=True`.
    #[pyo3(signature = (element, *, affect_attachments = false))]
    fn remove(
        &self,
        py: Python<'_>,
        element: PyRef<'_, PyElement>,
        affect_attachments: bool,
    ) -> PyResult<PyModel> {
        let r = if affect_attachments {
            self.inner.remove_with_attachments(&element.loc)
        } else {
            self.inner.remove(&element.loc)
        };
        Ok(PyModel::from(edited(py, r)?))
    }

    /// Attaches `child` at `at` (a site or the worldbody) as dm_control does: its
    /// names take a scope, the model's name (`robot`, then `robot_1`, ...) or `scope`.
    /// Returns `(new model, attachment)`.
    #[pyo3(signature = (at, child, scope = None))]
    fn attach(
        &self,
        py: Python<'_>,
        at: PyRef<'_, PyElement>,
        child: PyRef<'_, PyModel>,
        scope: Option<&str>,
    ) -> PyResult<(PyModel, PyAttachment)> {
        let r = match scope {
            Some(s) => self.inner.attach_as(&at.loc, &child.inner, s),
            None => self.inner.attach(&at.loc, &child.inner),
        };
        let (model, attachment) = edited(py, r)?;
        Ok((PyModel::from(model.clone()), PyAttachment { model, attachment }))
    }

    /// Removes an attachment (an `Attachment` or a scope path such as
    /// `"robot_1"`); returns the new model.
    fn detach(&self, py: Python<'_>, attachment: &Bound<'_, PyAny>) -> PyResult<PyModel> {
        let r = if let Ok(a) = attachment.cast::<PyAttachment>() {
            self.inner.detach(&a.get().attachment)
        } else {
            let scope: String = attachment.extract()?;
            self.inner.detach(&scope)
        };
        Ok(PyModel::from(edited(py, r)?))
    }

    /// The scope paths of the attachments, at every level (`"arm"`, `"arm/hand"`).
    fn scopes(&self) -> Vec<String> {
        self.inner.scope_paths()
    }

    /// The model attached at a scope path, as attached.
    fn attached(&self, py: Python<'_>, scope: &str) -> PyResult<PyModel> {
        Ok(PyModel::from(edited(py, self.inner.attached(scope))?.clone()))
    }

    /// The attachment frame of a scope path.
    fn frame(&self, py: Python<'_>, scope: &str) -> PyResult<PyElement> {
        Ok(self.element(edited(py, self.inner.frame(scope))?))
    }

    /// The scope path of the model an element lies in (`""` for this model's own),
    /// or None if it is not in this model.
    fn scope_path(&self, element: PyRef<'_, PyElement>) -> Option<String> {
        self.inner.scope_path(&element.loc)
    }

    /// The element of the model attached at `scope` (an element of that model's
    /// value), as an element of this composed model.
    fn locate_in(
        &self,
        py: Python<'_>,
        scope: &str,
        element: PyRef<'_, PyElement>,
    ) -> PyResult<PyElement> {
        Ok(self.element(edited(py, self.inner.locate_in(scope, &element.loc))?))
    }

    /// Renames the scope of an attachment (the last part of `scope`) to `to`.
    fn rename_scope(&self, py: Python<'_>, scope: &str, to: &str) -> PyResult<PyModel> {
        Ok(PyModel::from(edited(py, self.inner.rename_scope(scope, to))?))
    }

    /// Replaces the model attached at `scope` by `edit(attached_model)`, which must
    /// return a model (a version of it); returns the new composed model.
    fn edit_attached(
        &self,
        py: Python<'_>,
        scope: &str,
        edit: &Bound<'_, PyAny>,
    ) -> PyResult<PyModel> {
        let inner = PyModel::from(edited(py, self.inner.attached(scope))?.clone());
        let new: PyModel = edit.call1((inner,))?.extract()?;
        let r = self.inner.edit_attached(scope, |_| Ok(new.inner.clone()));
        Ok(PyModel::from(edited(py, r)?))
    }

    /// Copies `other`'s elements into this model, as MuJoCo's `<include>` of its
    /// file would (dm_control's `include_copy`); returns the new model.
    #[pyo3(signature = (other, override_attributes = false))]
    fn include_copy(
        &self,
        py: Python<'_>,
        other: PyRef<'_, PyModel>,
        override_attributes: bool,
    ) -> PyResult<PyModel> {
        let r = self.inner.include_copy(&other.inner, override_attributes);
        Ok(PyModel::from(edited(py, r)?))
    }

    /// What MuJoCo would refuse or misread: dangling references, missing required
    /// attributes, ... An empty list for a sound model. The GIL is released.
    fn check(&self, py: Python<'_>) -> Vec<PyProblem> {
        let problems = py.detach(|| self.inner.check());
        problems
            .into_iter()
            .map(|p| PyProblem {
                text: p.to_string(),
                path: p.path.clone(),
                element: self.element(p.loc.clone()),
            })
            .collect()
    }

    /// The changes from this model to `other`, one line each.
    fn diff(&self, py: Python<'_>, other: PyRef<'_, PyModel>) -> Vec<String> {
        let (old, new) = (&self.inner, &other.inner);
        py.detach(|| old.diff(new).iter().map(|c| c.display(old, new).to_string()).collect())
    }

    /// Saves the model into the files it was read from, changing only what edits
    /// changed (lossless); returns the paths written.
    fn save(&self, py: Python<'_>) -> PyResult<Vec<PathBuf>> {
        py.detach(|| self.inner.save()).map_err(|e| errors::save(py, &e))
    }

    /// Saves the model's files losslessly into folder `folder`, at the same paths
    /// relative to it; returns the paths written.
    fn save_as(&self, py: Python<'_>, folder: PathBuf) -> PyResult<Vec<PathBuf>> {
        py.detach(|| self.inner.save_as(&folder)).map_err(|e| errors::save(py, &e))
    }

    /// Saves the composed model as a scene: `folder/file` attaches each attached
    /// model, written to its own file, with MuJoCo's `<attach>`; returns the scene
    /// file's path. `Model.from_path` of it reopens the composed model.
    fn save_scene(&self, py: Python<'_>, folder: PathBuf, file: &str) -> PyResult<PathBuf> {
        let saved = py.detach(|| self.inner.save_scene(&folder, file));
        Ok(saved.map_err(|e| errors::export(py, &e))?.path().to_path_buf())
    }

    /// Writes the composed model and its files into `folder` (`file` the model's
    /// text), for `mujoco.MjModel.from_xml_path`; returns the text file's path.
    fn export(&self, py: Python<'_>, folder: PathBuf, file: &str) -> PyResult<PathBuf> {
        let o = WriteOptions::default();
        py.detach(|| self.inner.export(&folder, file, &o)).map_err(|e| errors::export(py, &e))
    }

    /// Content equality.
    fn __eq__(&self, other: PyRef<'_, PyModel>) -> bool {
        self.inner == other.inner
    }

    /// A hash of the content, consistent with `==`.
    fn __hash__(&self) -> u64 {
        let mut h = DefaultHasher::new();
        self.inner.hash(&mut h);
        h.finish()
    }

    /// The same value (models are immutable).
    fn __copy__(&self) -> PyModel {
        self.clone()
    }

    /// The same value (models are immutable).
    fn __deepcopy__(&self, _memo: &Bound<'_, PyAny>) -> PyModel {
        self.clone()
    }

    /// Pickles as MJCF text and files: the unpickled value is
    /// `Model.from_xml(m.to_xml(), m.assets())`, which writes the same MJCF (and so
    /// compiles to the same MuJoCo model), attachments written in their scopes. It
    /// need not equal `m` (`==`): the text spells out what the writer adds (names of
    /// unnamed elements, the scopes' default classes, attachments flattened).
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyTuple>> {
        let xml = self.to_xml(py, None, None, None, None)?.into_pyobject(py)?.into_any();
        let assets = self.assets(py, None, None, None, None)?.into_any();
        let from_xml = py.get_type::<PyModel>().getattr("from_xml")?;
        PyTuple::new(py, [from_xml, PyTuple::new(py, [xml, assets])?.into_any()])
    }

    fn __repr__(&self) -> String {
        format!("<mjcf.Model {:?}>", self.inner.name())
    }
}
