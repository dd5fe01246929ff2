//! Conversions between Python values and the crate's attribute values, namespaces
//! and write options.
use mjcf::{AttrInput, ElementRef, Namespace, Value, WriteOptions};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyInt, PyString, PyTuple};

/// The largest integer every `f64` holds exactly (2^53).
const EXACT_INT: i64 = 1 << 53;

/// An MJCF attribute name from a Python keyword: one trailing underscore is dropped,
/// so that `class_=` names `class` (no MJCF attribute ends in `_`).
pub(crate) fn attr_name(key: &str) -> &str {
    key.strip_suffix('_').unwrap_or(key)
}

/// A Python value as an attribute input: `bool` (`true`/`false`), `int`, `float`
/// (or anything with `__float__`), `str`, or a sequence of numbers.
pub(crate) fn attr_input(name: &str, value: &Bound<'_, PyAny>) -> PyResult<AttrInput> {
    if let Ok(b) = value.cast::<PyBool>() {
        return Ok(AttrInput::Bool(b.is_true()));
    }
    if let Ok(i) = value.cast::<PyInt>() {
        // Integers beyond 2^53 go as text, which the attribute's type parses exactly.
        return Ok(match i.extract::<i64>() {
            Ok(n) if (-EXACT_INT..=EXACT_INT).contains(&n) => AttrInput::Number(n as f64),
            _ => AttrInput::Text(i.str()?.extract::<String>()?.into()),
        });
    }
    if let Ok(s) = value.cast::<PyString>() {
        return Ok(AttrInput::Text(s.extract::<String>()?.into()));
    }
    if let Ok(x) = value.extract::<f64>() {
        return Ok(AttrInput::Number(x));
    }
    if let Ok(iter) = value.try_iter() {
        let mut out = Vec::new();
        for item in iter {
            let item = item?;
            let x = item.extract::<f64>().map_err(|_| {
                PyTypeError::new_err(format!(
                    "attribute '{name}': a sequence must hold numbers, got {}",
                    item.get_type().name().map(|n| n.to_string()).unwrap_or_default()
                ))
            })?;
            out.push(x);
        }
        return Ok(AttrInput::Numbers(out));
    }
    Err(PyTypeError::new_err(format!(
        "attribute '{name}': expected a number, a string, a bool or a sequence of numbers, got {}",
        value.get_type().name().map(|n| n.to_string()).unwrap_or_default()
    )))
}

/// The `(name, value)` pairs of keyword arguments, in the order given; a value of
/// `None` is `None` here (an attribute to clear).
pub(crate) fn kwargs(
    attrs: Option<&Bound<'_, PyDict>>,
) -> PyResult<Vec<(String, Option<AttrInput>)>> {
    let mut out = Vec::new();
    for (k, v) in attrs.into_iter().flat_map(|d| d.iter()) {
        let key: String = k.extract()?;
        let name = attr_name(&key).to_string();
        let input = if v.is_none() { None } else { Some(attr_input(&name, &v)?) };
        out.push((name, input));
    }
    Ok(out)
}

/// The value of attribute `name` of an element, as Python sees it: `float`, `int`,
/// `str` (text, keywords, names, and the name a reference gives), or a tuple of
/// numbers; `None` if unset.
pub(crate) fn attr_value<'py>(
    py: Python<'py>,
    element: &ElementRef<'_>,
    name: &str,
) -> PyResult<Option<Bound<'py, PyAny>>> {
    let Some(value) = element.attr(name) else { return Ok(None) };
    let obj = match value {
        Value::Float(x) => x.into_pyobject(py)?.into_any(),
        Value::Int(i) => i.into_pyobject(py)?.into_any(),
        Value::Floats(xs) => PyTuple::new(py, xs.iter())?.into_any(),
        Value::Ints(xs) => PyTuple::new(py, xs.iter())?.into_any(),
        other => match element.string(name) {
            Some(s) => PyString::new(py, s).into_any(),
            None => PyString::new(py, &other.to_string()).into_any(),
        },
    };
    Ok(Some(obj))
}

/// The namespace with this MJCF name (`"body"`, `"geom"`, `"attachment_frame"`).
pub(crate) fn namespace(name: &str) -> PyResult<Namespace> {
    Namespace::from_name(name).ok_or_else(|| {
        let all: Vec<&str> = Namespace::ALL.iter().map(|n| n.as_str()).collect();
        PyValueError::new_err(format!(
            "'{name}' is not a namespace; the namespaces are: {}",
            all.join(", ")
        ))
    })
}

/// Write options from keyword arguments (None keeps each default).
pub(crate) fn write_options(
    precision: Option<u32>,
    zero_threshold: Option<f64>,
    pretty_print: Option<bool>,
    filename_with_hash: Option<bool>,
) -> WriteOptions {
    let mut o = WriteOptions::default();
    if precision.is_some() {
        o.precision = precision;
    }
    if let Some(z) = zero_threshold {
        o.zero_threshold = z;
    }
    if let Some(p) = pretty_print {
        o.pretty_print = p;
    }
    if let Some(f) = filename_with_hash {
        o.filename_with_hash = f;
    }
    o
}
