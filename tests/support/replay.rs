//! Replays a conformance case against the library (the adapter).
//!
//! Shared by `tests/conformance.rs` and `examples/conformance.rs`; include it next to
//! `case.rs` and `compare.rs` as sibling modules named `case`, `compare` and `replay`.
//! The rules are those of `tests/conformance/README.md`: case-local variables, locators,
//! expected error categories, and the meaning of `deviation` marks.

use std::collections::HashMap;
use std::path::Path;

use mjcf::{
    Attrs, EditError, Element, ErrorKind, Loc, Model, ReadError, ReadOptions, ValueError, WriteError, WriteOptions,
};

use super::case::{self, AttrValue, Case, Op, OpKind};
use super::compare;

/// The result of one case.
#[derive(Debug, Clone, PartialEq)]
pub enum Outcome {
    /// Every normative op behaved as expected.
    Pass,
    /// The first normative mismatch.
    Fail(String),
    /// Every mismatch was on a deviation-marked op; the labels seen.
    Deviation(Vec<String>),
}

/// An op's failure, as a README category plus a message.
#[derive(Debug)]
struct OpError {
    category: &'static str,
    message: String,
}

impl OpError {
    fn new(category: &'static str, message: impl Into<String>) -> OpError {
        OpError { category, message: message.into() }
    }
}

/// The README category of an error kind.
pub fn category(kind: &ErrorKind) -> &'static str {
    match kind {
        ErrorKind::Syntax(_) | ErrorKind::InvalidUtf8 | ErrorKind::WrongRoot(_) | ErrorKind::TooDeep(_) => {
            "parse_error"
        }
        ErrorKind::IncludeCycle(_) => "parse_error",
        ErrorKind::InvalidChild { .. } => "invalid_child",
        ErrorKind::DuplicateChild(_) => "duplicate_child",
        ErrorKind::UnknownAttribute { .. } => "invalid_attribute",
        ErrorKind::InvalidValue { error: ValueError::SlashInIdentifier | ValueError::WorldBody, .. } => {
            "invalid_identifier"
        }
        ErrorKind::InvalidValue { .. } => "invalid_value",
        ErrorKind::DuplicateIdentifier { .. } => "duplicate_identifier",
        ErrorKind::MissingRequired { .. } => "missing_required",
        ErrorKind::FileNotFound { .. } | ErrorKind::FileOutsideRoot(_) => "file_not_found",
        ErrorKind::NotFound => "not_found",
        ErrorKind::AttributeConflict { .. } => "attribute_conflict",
        ErrorKind::CopyConflict { .. } => "copy_conflict",
        _ => "unknown",
    }
}

fn edit_err(e: EditError) -> OpError {
    OpError::new(category(e.kind()), e.to_string())
}

fn read_err(e: ReadError) -> OpError {
    // Loading fails with `file_not_found` for missing files and `parse_error` for
    // everything else.
    let cat = match e.kind() {
        ErrorKind::FileNotFound { .. } | ErrorKind::FileOutsideRoot(_) => "file_not_found",
        _ => "parse_error",
    };
    OpError::new(cat, e.to_string())
}

fn write_err(e: WriteError) -> OpError {
    match e {
        WriteError::MissingRequired { .. } => OpError::new("missing_required", e.to_string()),
        _ => OpError::new("unknown", e.to_string()),
    }
}

/// The replay state: variables and handles.
struct State<'c> {
    case: &'c Case,
    models: HashMap<String, Model>,
    /// Handle name → (variable, element).
    handles: HashMap<String, (String, Loc)>,
    actual_dir: Option<&'c Path>,
}

/// Runs one case. With `actual_dir`, every output is also written to
/// `actual_dir/<case>/<file>`.
pub fn run_case(case: &Case, actual_dir: Option<&Path>) -> Outcome {
    let mut st = State { case, models: HashMap::new(), handles: HashMap::new(), actual_dir };
    let mut deviations: Vec<String> = Vec::new();
    for op in &case.ops {
        let marked = !op.deviation.is_empty();
        if op.has_deviation("D1") {
            continue;
        }
        let is_output = matches!(op.kind, OpKind::Output { .. });
        if marked && !is_output && op.expect_error.is_some() {
            // dm_control refused it where a persistent implementation accepts it.
            continue;
        }
        let result = st.apply(op, marked && is_output);
        let mismatch = match (&result, &op.expect_error) {
            (Ok(()), None) => None,
            (Ok(()), Some(want)) => {
                Some(format!("op {} ({}): expected error {want}, but it succeeded", op.index, op.op_name()))
            }
            (Err(e), Some(want)) if e.category == want => None,
            (Err(e), Some(want)) => Some(format!(
                "op {} ({}): expected error {want}, got {}: {}",
                op.index,
                op.op_name(),
                e.category,
                e.message
            )),
            (Err(e), None) => {
                Some(format!("op {} ({}): unexpected error {}: {}", op.index, op.op_name(), e.category, e.message))
            }
        };
        if marked && (is_output || mismatch.is_some()) {
            for d in &op.deviation {
                if !deviations.contains(d) {
                    deviations.push(d.clone());
                }
            }
            continue;
        }
        if let Some(m) = mismatch {
            return Outcome::Fail(m);
        }
    }
    if deviations.is_empty() { Outcome::Pass } else { Outcome::Deviation(deviations) }
}

fn numbers(v: &AttrValue) -> Option<mjcf::AttrInput> {
    Some(match v {
        AttrValue::Null => return None,
        AttrValue::Str(s) => s.as_str().into(),
        AttrValue::Number(x) => (*x).into(),
        AttrValue::Bool(b) => (*b).into(),
        AttrValue::Numbers(xs) => xs.clone().into(),
    })
}

impl State<'_> {
    fn model(&self, var: &str) -> Result<&Model, OpError> {
        self.models.get(var).ok_or_else(|| OpError::new("unknown", format!("no model variable {var:?}")))
    }

    fn resolve(&self, var: &str, loc: &case::Loc) -> Result<(String, Loc), OpError> {
        match loc {
            case::Loc::Section(path) => {
                let m = self.model(var)?;
                let first = path.first().map(String::as_str).unwrap_or("");
                let mut l = m.section(first).ok_or_else(|| OpError::new("not_found", format!("no section {first}")))?;
                for tag in &path[1..] {
                    let el = m.element(&l).ok_or_else(|| OpError::new("not_found", "section vanished"))?;
                    let child = el.children().find(|c| c.tag() == tag);
                    l = child
                        .map(|c| c.loc())
                        .ok_or_else(|| OpError::new("not_found", format!("no {tag} in {first}")))?;
                }
                Ok((var.to_string(), l))
            }
            case::Loc::Find { namespace, identifier } => {
                let m = self.model(var)?;
                let ns = mjcf::Namespace::from_name(namespace)
                    .ok_or_else(|| OpError::new("invalid_namespace", format!("{namespace:?} is not a namespace")))?;
                let l = m
                    .find(ns, identifier)
                    .ok_or_else(|| OpError::new("not_found", format!("no {namespace} named {identifier:?}")))?;
                Ok((var.to_string(), l))
            }
            case::Loc::Handle(h) => {
                let (v, l) = self.handles.get(h).ok_or_else(|| OpError::new("not_found", format!("no handle {h}")))?;
                let m = self.model(v)?;
                if m.element(l).is_none() {
                    return Err(OpError::new("not_found", format!("handle {h} names a removed element")));
                }
                Ok((v.clone(), l.clone()))
            }
            case::Loc::FrameOf(v) => Err(OpError::new("not_attached", format!("{v} is not attached"))),
        }
    }

    fn apply(&mut self, op: &Op, skip_compare: bool) -> Result<(), OpError> {
        let dir = &self.case.dir;
        match &op.kind {
            OpKind::Load { name, file } => {
                let m = ReadOptions::new().read_path(dir.join(file)).map_err(read_err)?;
                self.models.insert(name.clone(), m);
            }
            OpKind::New { name, model } => {
                let m = Model::new(model.as_deref().unwrap_or("")).with_base_dir(dir);
                self.models.insert(name.clone(), m);
            }
            OpKind::Add { model, parent, tag, attrs, as_handle } => {
                let (var, loc) = self.resolve(model, parent)?;
                let mut el = Element::new(tag);
                for (k, v) in attrs {
                    match numbers(v) {
                        Some(input) => el = el.attr(k, input),
                        None => return Err(OpError::new("unknown", "null in add")),
                    }
                }
                let (m, new) = self.model(&var)?.add(&loc, el).map_err(edit_err)?;
                self.models.insert(var.clone(), m);
                if let Some(h) = as_handle {
                    self.handles.insert(h.clone(), (var, new));
                }
            }
            OpKind::Set { model, target, attrs } => {
                let (var, loc) = self.resolve(model, target)?;
                let mut a = Attrs::new();
                for (k, v) in attrs {
                    a = match numbers(v) {
                        Some(input) => a.set(k, input),
                        None => a.clear(k),
                    };
                }
                let m = self.model(&var)?.set(&loc, a).map_err(edit_err)?;
                self.models.insert(var, m);
            }
            OpKind::Remove { model, target, affect_attachments: _ } => {
                let (var, loc) = self.resolve(model, target)?;
                let m = self.model(&var)?.remove(&loc).map_err(edit_err)?;
                self.models.insert(var, m);
            }
            OpKind::Rename { model, to } => {
                let m = self.model(model)?.with_name(to);
                self.models.insert(model.clone(), m);
            }
            OpKind::IncludeCopy { parent, child, override_attributes } => {
                let src = self.model(child)?.clone();
                let m = self.model(parent)?.include_copy(&src, *override_attributes).map_err(edit_err)?;
                self.models.insert(parent.clone(), m);
            }
            OpKind::Attach { .. } | OpKind::Detach { .. } => {
                return Err(OpError::new("unsupported", "composition is not implemented yet"));
            }
            OpKind::Output { model, file, options } => {
                let opts = WriteOptions {
                    precision: options.precision,
                    zero_threshold: options.zero_threshold.unwrap_or(0.0),
                    pretty_print: options.pretty_print.unwrap_or(true),
                    filename_with_hash: options.filename_with_hash.unwrap_or(true),
                };
                let xml = self.model(model)?.to_xml_string_with(&opts).map_err(write_err)?;
                if let Some(out) = self.actual_dir {
                    let d = out.join(&self.case.name);
                    std::fs::create_dir_all(&d).map_err(|e| OpError::new("io", e.to_string()))?;
                    std::fs::write(d.join(file), &xml).map_err(|e| OpError::new("io", e.to_string()))?;
                }
                if skip_compare {
                    return Ok(());
                }
                let expected = std::fs::read_to_string(dir.join(file))
                    .map_err(|e| OpError::new("io", format!("cannot read expected {file}: {e}")))?;
                match compare::compare_strings(&xml, &expected) {
                    Ok(None) => {}
                    Ok(Some(diff)) => return Err(OpError::new("output_differs", format!("{file}: {diff}"))),
                    Err(e) => return Err(OpError::new("output_unparseable", format!("{file}: {e}"))),
                }
            }
        }
        Ok(())
    }
}

/// Runs every case under `root`, returning (name, outcome) in name order.
pub fn run_all(root: &Path, actual_dir: Option<&Path>) -> Result<Vec<(String, Outcome)>, String> {
    let mut out = Vec::new();
    for dir in case::list_cases(root)? {
        let c = case::load_case(&dir)?;
        let outcome = run_case(&c, actual_dir);
        out.push((c.name.clone(), outcome));
    }
    Ok(out)
}
