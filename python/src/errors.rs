//! The exceptions: `MjcfError` and one subclass per kind of failure, each with the
//! crate's message.
use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

create_exception!(
    mjcf,
    MjcfError,
    PyException,
    "The base of every error this package raises for a model it cannot read, edit, write or save."
);
create_exception!(
    mjcf,
    ReadError,
    MjcfError,
    "MJCF text or files that cannot be read; `file`, `line` and `column` say where (each may be None), `kind` names the crate's ErrorKind (`\"InvalidChild\"`)."
);
create_exception!(
    mjcf,
    EditError,
    MjcfError,
    "An edit or a look-up that cannot be made; `path` is the element it was aimed at, `kind` names the crate's ErrorKind (`\"UnknownName\"`). The model is unchanged."
);
create_exception!(
    mjcf,
    WriteError,
    MjcfError,
    "A model that cannot be written as MJCF text (a required reference whose target was removed, ...); `kind` names the crate's WriteError variant."
);
create_exception!(
    mjcf,
    SaveError,
    MjcfError,
    "A model that cannot be saved or exported to files; `path` is the file or folder concerned, if any."
);

/// Adds the exception classes to the module, with their attributes' class-level
/// defaults (None), so that every attribute exists on every instance.
pub(crate) fn register(py: Python<'_>, m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("MjcfError", py.get_type::<MjcfError>())?;
    let read = py.get_type::<ReadError>();
    for name in ["file", "line", "column"] {
        read.setattr(name, py.None())?;
    }
    read.setattr("kind", "")?;
    m.add("ReadError", read)?;
    let edit = py.get_type::<EditError>();
    edit.setattr("path", "")?;
    edit.setattr("kind", "")?;
    m.add("EditError", edit)?;
    let write = py.get_type::<WriteError>();
    write.setattr("kind", "")?;
    m.add("WriteError", write)?;
    let save = py.get_type::<SaveError>();
    save.setattr("path", py.None())?;
    m.add("SaveError", save)?;
    Ok(())
}

/// A `ReadError` with the crate's message, file and 1-based line and column.
pub(crate) fn read(py: Python<'_>, e: &mjcf::ReadError) -> PyErr {
    let err = ReadError::new_err(e.to_string());
    let value = err.value(py);
    let file = e.file().map(|f| f.to_string_lossy().into_owned());
    let pos = e.pos();
    // Setting attributes on a fresh exception instance cannot fail.
    let _ = value.setattr("file", file);
    let _ = value.setattr("line", pos.map(|p| p.line));
    let _ = value.setattr("column", pos.map(|p| p.column));
    let _ = value.setattr("kind", kind_name(e.kind()));
    err
}

/// The name of an error's kind: its variant's name (`"UnknownName"`,
/// `"DuplicateIdentifier"`), from its derived `Debug` text.
fn kind_name(kind: &impl std::fmt::Debug) -> String {
    let debug = format!("{kind:?}");
    debug.split(|c: char| !c.is_alphanumeric()).next().unwrap_or_default().to_string()
}

/// An `EditError` with the crate's message and the element path.
pub(crate) fn edit(py: Python<'_>, e: &mjcf::EditError) -> PyErr {
    let err = EditError::new_err(e.to_string());
    let value = err.value(py);
    let _ = value.setattr("path", e.path());
    let _ = value.setattr("kind", kind_name(e.kind()));
    err
}

/// A `WriteError` with the crate's message and kind.
pub(crate) fn write(py: Python<'_>, e: &mjcf::WriteError) -> PyErr {
    let err = WriteError::new_err(e.to_string());
    let _ = err.value(py).setattr("kind", kind_name(e));
    err
}

/// A `SaveError` with a message and the path concerned.
fn save_with_path(py: Python<'_>, message: String, path: Option<&std::path::Path>) -> PyErr {
    let err = SaveError::new_err(message);
    let _ = err.value(py).setattr("path", path.map(|p| p.to_string_lossy().into_owned()));
    err
}

/// A `SaveError` for a failed lossless save.
pub(crate) fn save(py: Python<'_>, e: &mjcf::SaveError) -> PyErr {
    use mjcf::SaveError as S;
    let path = match e {
        S::FileNameTaken(p)
        | S::OutsideRoot(p)
        | S::ChangedOnDisk(p)
        | S::SymlinkedFolder(p)
        | S::Io { path: p, .. } => Some(p.as_path()),
        _ => None,
    };
    save_with_path(py, e.to_string(), path)
}

/// A `SaveError` for a failed export or scene save (a `WriteError` for a model that
/// cannot be written).
pub(crate) fn export(py: Python<'_>, e: &mjcf::ExportError) -> PyErr {
    use mjcf::ExportError as X;
    match e {
        X::Write(w) => write(py, w),
        X::SymlinkedFolder { path } | X::Io { path, .. } => {
            save_with_path(py, e.to_string(), Some(path))
        }
        _ => save_with_path(py, e.to_string(), None),
    }
}
