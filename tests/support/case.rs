//! Loading conformance case folders (`tests/conformance/cases/*/case.json`),
//! in the format described in `tests/conformance/README.md`.
//!
//! This file is shared by integration tests and an example via
//! `#[path = "..."] mod case;`; it needs only std and `serde_json` (a
//! dev-dependency). serde_json's `preserve_order` feature is required: it
//! keeps objects in document order, so the `attrs` of an op are returned in
//! the order the case file lists them (without it they would be sorted by
//! key).
//!
//! Its unit tests run in the `tests` binary (`tests/main.rs`).
//!
//! Loading is strict: an unknown op kind, an unknown field, a field of the
//! wrong type, an unknown error category or a `null` attribute value outside
//! `set` is an error naming the case and the op index. Repeated keys in one
//! object are not detected: serde_json keeps the last value (at the first
//! key's position).

// Shared by several targets that each use only part of the API.
#![allow(dead_code)]

use std::path::{Path, PathBuf};

use serde_json::{Map, Value};

/// The error categories of README.md ("Expected errors").
pub(crate) const ERROR_CATEGORIES: [&str; 20] = [
    "attach_to_self",
    "already_attached",
    "cyclic_attachment",
    "attribute_conflict",
    "duplicate_identifier",
    "invalid_identifier",
    "invalid_attribute",
    "invalid_value",
    "invalid_child",
    "duplicate_child",
    "missing_required",
    "invalid_parent",
    "invalid_namespace",
    "not_found",
    "not_attached",
    "affects_attachments",
    "source_has_attachments",
    "copy_conflict",
    "parse_error",
    "file_not_found",
];

/// One conformance case.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Case {
    /// The case folder's name, e.g. `hand_001_seed_example`.
    pub name: String,
    /// The case folder; ops run with it as the working directory.
    pub dir: PathBuf,
    /// One line saying what the case exercises.
    pub description: String,
    /// The ops, in execution order.
    pub ops: Vec<Op>,
    /// Why dm_control cannot read or write the model (the real-model corpus's
    /// `reference_fails`): such a case has no expected text of dm_control's, and MuJoCo
    /// judges its outputs instead.
    pub reference_fails: Option<String>,
}

/// One op of a case.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Op {
    /// What the op does.
    pub kind: OpKind,
    /// The error category the op must fail with (`expect_error`).
    pub expect_error: Option<String>,
    /// The deviation labels (`"D2,D3"` -> `["D2", "D3"]`); empty if none.
    pub deviation: Vec<String>,
    /// What dm_control raised (`observed_error`); for orientation only.
    pub observed_error: Option<ObservedError>,
    /// The op's index in the case's `ops` array (0-based).
    pub index: usize,
}

impl Op {
    /// True when the op carries the deviation label `label` (e.g. `"D1"`).
    pub(crate) fn has_deviation(&self, label: &str) -> bool {
        self.deviation.iter().any(|d| d == label)
    }

    /// The op's name in case.json (`"load"`, `"include_copy"`, ...).
    pub(crate) fn op_name(&self) -> &'static str {
        self.kind.op_name()
    }
}

/// The `observed_error` record of an op with `expect_error`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ObservedError {
    /// The Python exception class.
    pub type_name: String,
    /// The exception message (object ids replaced by `?`).
    pub message: String,
    /// False when dm_control had already modified some model.
    pub state_unchanged: bool,
}

/// The kinds of op, with their fields. Variables (`name`, `model`, `parent`,
/// `child`) are case-local model names.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum OpKind {
    /// `name = mjcf.from_path(file)`.
    Load { name: String, file: String },
    /// `name = mjcf.RootElement(model=model)`.
    New { name: String, model: Option<String> },
    /// `parent.add(tag, **attrs)`, optionally saved as handle `as_handle`.
    Add {
        model: String,
        parent: Loc,
        tag: String,
        attrs: Vec<(String, AttrValue)>,
        as_handle: Option<String>,
    },
    /// `parent.find("site", site).attach(child)` (or at the worldbody, or at
    /// a located element); the frame optionally saved as handle `as_handle`.
    Attach { parent: String, site: AttachSite, child: String, as_handle: Option<String> },
    /// `parent.include_copy(child, override_attributes=...)`.
    IncludeCopy { parent: String, child: String, override_attributes: bool },
    /// `child.detach()`.
    Detach { child: String },
    /// `target.set_attributes(**attrs)`; `AttrValue::Null` clears.
    Set { model: String, target: Loc, attrs: Vec<(String, AttrValue)> },
    /// `target.remove(affect_attachments=...)`.
    Remove { model: String, target: Loc, affect_attachments: bool },
    /// `model.model = to`.
    Rename { model: String, to: String },
    /// Write `model.to_xml_string(**options)` to `file`.
    Output { model: String, file: String, options: OutputOptions },
}

impl OpKind {
    /// The op's name in case.json.
    pub(crate) fn op_name(&self) -> &'static str {
        match self {
            OpKind::Load { .. } => "load",
            OpKind::New { .. } => "new",
            OpKind::Add { .. } => "add",
            OpKind::Attach { .. } => "attach",
            OpKind::IncludeCopy { .. } => "include_copy",
            OpKind::Detach { .. } => "detach",
            OpKind::Set { .. } => "set",
            OpKind::Remove { .. } => "remove",
            OpKind::Rename { .. } => "rename",
            OpKind::Output { .. } => "output",
        }
    }
}

/// Where an `attach` puts the child.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum AttachSite {
    /// `"site": null`: the parent's worldbody.
    World,
    /// `"site": "name"`: the site found by that name in the parent.
    Name(String),
    /// `"site_loc": LOC`: any located element, resolved in the parent.
    Loc(Loc),
}

/// A locator (README "Locators").
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Loc {
    /// A section of the root: `"option.flag"` -> `["option", "flag"]`.
    Section(Vec<String>),
    /// `{"find": [namespace, identifier]}`.
    Find { namespace: String, identifier: String },
    /// `{"handle": "h"}`: an element saved earlier with `"as": "h"`.
    Handle(String),
    /// `{"frame_of": VAR}`: the attachment frame of model VAR.
    FrameOf(String),
}

/// An attribute value given in `add`/`set`.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum AttrValue {
    /// `null`: clears the attribute (only in `set`).
    Null,
    /// A JSON string.
    Str(String),
    /// A JSON number.
    Number(f64),
    /// A JSON boolean.
    Bool(bool),
    /// A JSON array of numbers.
    Numbers(Vec<f64>),
}

impl AttrValue {
    /// The value as MJCF attribute text: strings as they are, numbers as the
    /// shortest decimal text that reads back as the same `f64` (`4` -> "4",
    /// `0.1` -> "0.1", `1e-16` -> "1e-16"), arrays joined by single spaces,
    /// booleans as "true"/"false"; `None` for `null`.
    pub(crate) fn to_mjcf_text(&self) -> Option<String> {
        match self {
            AttrValue::Null => None,
            AttrValue::Str(text) => Some(text.clone()),
            AttrValue::Number(value) => Some(format_number(*value)),
            AttrValue::Bool(value) => Some(value.to_string()),
            AttrValue::Numbers(values) => {
                Some(values.iter().map(|v| format_number(*v)).collect::<Vec<_>>().join(" "))
            }
        }
    }
}

/// Options of an `output` op (keyword arguments of `to_xml_string`).
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct OutputOptions {
    pub precision: Option<u32>,
    pub zero_threshold: Option<f64>,
    pub pretty_print: Option<bool>,
    pub filename_with_hash: Option<bool>,
}

/// Loads the case in folder `dir` (its `case.json`); the case name is the
/// folder name.
pub(crate) fn load_case(dir: &Path) -> Result<Case, String> {
    let name = dir
        .file_name()
        .and_then(|n| n.to_str())
        .ok_or_else(|| format!("{}: not a case folder name", dir.display()))?
        .to_owned();
    let path = dir.join("case.json");
    let text = std::fs::read_to_string(&path)
        .map_err(|e| format!("case {name}: cannot read {}: {e}", path.display()))?;
    parse_case(&name, dir, &text)
}

/// Parses the text of a `case.json` for the case `name` in folder `dir`.
pub(crate) fn parse_case(name: &str, dir: &Path, json: &str) -> Result<Case, String> {
    let fail = |message: String| format!("case {name}: {message}");
    let root: Value = serde_json::from_str(json).map_err(|e| fail(format!("case.json: {e}")))?;
    let root = Fields::new(&root, "case.json").map_err(fail)?;
    root.check_keys(&["description", "ops", "source", "roundtrip", "reference_fails"])
        .map_err(fail)?;
    let description = root.req_str("description").map_err(fail)?;
    let ops_json = match root.get("ops") {
        Some(Value::Array(items)) => items,
        Some(_) => return Err(fail("\"ops\" must be an array".to_owned())),
        None => return Err(fail("missing \"ops\"".to_owned())),
    };
    let mut ops = Vec::with_capacity(ops_json.len());
    for (index, op) in ops_json.iter().enumerate() {
        let op_name = op.get("op").and_then(Value::as_str);
        let op = parse_op(op, index).map_err(|e| match op_name {
            Some(op_name) => format!("case {name}, op {index} ({op_name}): {e}"),
            None => format!("case {name}, op {index}: {e}"),
        })?;
        ops.push(op);
    }
    let reference_fails = root.opt_str("reference_fails").map_err(fail)?;
    Ok(Case { name: name.to_owned(), dir: dir.to_path_buf(), description, ops, reference_fails })
}

/// Every immediate subfolder of `root` that holds a `case.json`, sorted by
/// name.
pub(crate) fn list_cases(root: &Path) -> Result<Vec<PathBuf>, String> {
    let entries =
        std::fs::read_dir(root).map_err(|e| format!("cannot list {}: {e}", root.display()))?;
    let mut dirs = Vec::new();
    for entry in entries {
        let entry = entry.map_err(|e| format!("cannot list {}: {e}", root.display()))?;
        let path = entry.path();
        if path.is_dir() && path.join("case.json").is_file() {
            dirs.push(path);
        }
    }
    dirs.sort_by(|a, b| a.file_name().cmp(&b.file_name()));
    Ok(dirs)
}

fn parse_op(json: &Value, index: usize) -> Result<Op, String> {
    const COMMON: [&str; 4] = ["op", "expect_error", "observed_error", "deviation"];
    let op = Fields::new(json, "an op")?;
    let op_name = op.req_str("op")?;
    let specific: &[&str] = match op_name.as_str() {
        "load" => &["name", "file"],
        "new" => &["name", "model"],
        "add" => &["model", "parent", "tag", "attrs", "as"],
        "attach" => &["parent", "site", "site_loc", "child", "as"],
        "include_copy" => &["parent", "child", "override_attributes"],
        "detach" => &["child"],
        "set" => &["model", "target", "attrs"],
        "remove" => &["model", "target", "affect_attachments"],
        "rename" => &["model", "to"],
        "output" => &["model", "file", "options"],
        other => return Err(format!("unknown op kind {other:?}")),
    };
    let allowed: Vec<&str> = COMMON.iter().chain(specific).copied().collect();
    op.check_keys(&allowed)?;

    let kind = match op_name.as_str() {
        "load" => OpKind::Load { name: op.req_str("name")?, file: op.req_str("file")? },
        "new" => OpKind::New { name: op.req_str("name")?, model: op.opt_str("model")? },
        "add" => OpKind::Add {
            model: op.req_str("model")?,
            parent: parse_loc(op.req("parent")?).map_err(|e| format!("\"parent\": {e}"))?,
            tag: op.req_str("tag")?,
            attrs: match op.get("attrs") {
                None | Some(Value::Null) => Vec::new(),
                Some(attrs) => parse_attrs(attrs, false)?,
            },
            as_handle: op.opt_str("as")?,
        },
        "attach" => {
            let site = match (op.get("site"), op.get("site_loc")) {
                (Some(_), Some(_)) => {
                    return Err("both \"site\" and \"site_loc\" given".to_owned());
                }
                (Some(Value::Null), None) => AttachSite::World,
                (Some(Value::String(name)), None) => AttachSite::Name(name.clone()),
                (Some(_), None) => return Err("\"site\" must be a string or null".to_owned()),
                (None, Some(loc)) => {
                    AttachSite::Loc(parse_loc(loc).map_err(|e| format!("\"site_loc\": {e}"))?)
                }
                (None, None) => return Err("missing \"site\" or \"site_loc\"".to_owned()),
            };
            OpKind::Attach {
                parent: op.req_str("parent")?,
                site,
                child: op.req_str("child")?,
                as_handle: op.opt_str("as")?,
            }
        }
        "include_copy" => OpKind::IncludeCopy {
            parent: op.req_str("parent")?,
            child: op.req_str("child")?,
            override_attributes: op.opt_bool("override_attributes")?.unwrap_or(false),
        },
        "detach" => OpKind::Detach { child: op.req_str("child")? },
        "set" => OpKind::Set {
            model: op.req_str("model")?,
            target: parse_loc(op.req("target")?).map_err(|e| format!("\"target\": {e}"))?,
            attrs: parse_attrs(op.req("attrs")?, true)?,
        },
        "remove" => OpKind::Remove {
            model: op.req_str("model")?,
            target: parse_loc(op.req("target")?).map_err(|e| format!("\"target\": {e}"))?,
            affect_attachments: op.opt_bool("affect_attachments")?.unwrap_or(false),
        },
        "rename" => OpKind::Rename { model: op.req_str("model")?, to: op.req_str("to")? },
        "output" => OpKind::Output {
            model: op.req_str("model")?,
            file: op.req_str("file")?,
            options: match op.get("options") {
                None | Some(Value::Null) => OutputOptions::default(),
                Some(options) => {
                    parse_output_options(options).map_err(|e| format!("\"options\": {e}"))?
                }
            },
        },
        // All kinds were matched above.
        other => return Err(format!("unknown op kind {other:?}")),
    };

    let expect_error = op.opt_str("expect_error")?;
    if let Some(category) = &expect_error {
        if !ERROR_CATEGORIES.contains(&category.as_str()) {
            return Err(format!("unknown error category {category:?}"));
        }
    }
    let deviation = match op.opt_str("deviation")? {
        None => Vec::new(),
        Some(text) => text
            .split(',')
            .map(str::trim)
            .filter(|label| !label.is_empty())
            .map(str::to_owned)
            .collect(),
    };
    let observed_error = match op.get("observed_error") {
        None | Some(Value::Null) => None,
        Some(json) => {
            Some(parse_observed_error(json).map_err(|e| format!("\"observed_error\": {e}"))?)
        }
    };
    Ok(Op { kind, expect_error, deviation, observed_error, index })
}

fn parse_loc(json: &Value) -> Result<Loc, String> {
    match json {
        Value::String(text) => {
            let parts: Vec<String> = text.split('.').map(str::to_owned).collect();
            if parts.iter().any(String::is_empty) {
                return Err(format!("bad section locator {text:?}"));
            }
            Ok(Loc::Section(parts))
        }
        Value::Object(entries) => {
            let (Some((key, value)), 1) = (entries.iter().next(), entries.len()) else {
                return Err("a locator object must have exactly one key".to_owned());
            };
            match (key.as_str(), value) {
                ("find", Value::Array(items)) => match items.as_slice() {
                    [Value::String(namespace), Value::String(identifier)] => Ok(Loc::Find {
                        namespace: namespace.clone(),
                        identifier: identifier.clone(),
                    }),
                    _ => Err("\"find\" must be [namespace, identifier] strings".to_owned()),
                },
                ("handle", Value::String(handle)) => Ok(Loc::Handle(handle.clone())),
                ("frame_of", Value::String(var)) => Ok(Loc::FrameOf(var.clone())),
                ("find" | "handle" | "frame_of", _) => {
                    Err(format!("bad value for locator {key:?}"))
                }
                _ => Err(format!("unknown locator {key:?}")),
            }
        }
        _ => Err("a locator must be a string or an object".to_owned()),
    }
}

/// The value of a JSON number as an `f64`; `None` for any other value.
fn number(json: &Value) -> Option<f64> {
    match json {
        // Without serde_json's `arbitrary_precision`, every number converts.
        Value::Number(n) => n.as_f64(),
        _ => None,
    }
}

fn parse_attrs(json: &Value, allow_null: bool) -> Result<Vec<(String, AttrValue)>, String> {
    let Value::Object(entries) = json else {
        return Err("\"attrs\" must be an object".to_owned());
    };
    let mut attrs: Vec<(String, AttrValue)> = Vec::with_capacity(entries.len());
    // In document order (serde_json's `preserve_order`).
    for (key, value) in entries {
        let value = match value {
            Value::Null if allow_null => AttrValue::Null,
            Value::Null => return Err(format!("attribute {key:?}: null is only allowed in set")),
            Value::Bool(b) => AttrValue::Bool(*b),
            Value::Number(_) => AttrValue::Number(
                number(value).ok_or_else(|| format!("attribute {key:?}: number out of range"))?,
            ),
            Value::String(s) => AttrValue::Str(s.clone()),
            Value::Array(items) => AttrValue::Numbers(
                items
                    .iter()
                    .map(|item| {
                        number(item).ok_or_else(|| {
                            format!("attribute {key:?}: arrays must hold only numbers")
                        })
                    })
                    .collect::<Result<_, _>>()?,
            ),
            Value::Object(_) => return Err(format!("attribute {key:?}: objects are not allowed")),
        };
        attrs.push((key.clone(), value));
    }
    Ok(attrs)
}

fn parse_output_options(json: &Value) -> Result<OutputOptions, String> {
    let fields = Fields::new(json, "options")?;
    fields.check_keys(&["precision", "zero_threshold", "pretty_print", "filename_with_hash"])?;
    let precision = match fields.get("precision") {
        None | Some(Value::Null) => None,
        // `5` and `5.0` alike.
        Some(value) => match number(value) {
            Some(n) if n.fract() == 0.0 && (0.0..=f64::from(u32::MAX)).contains(&n) => {
                // Integral and in range, so the conversion is exact.
                Some(n as u32)
            }
            _ => return Err("\"precision\" must be a non-negative integer".to_owned()),
        },
    };
    let zero_threshold = match fields.get("zero_threshold") {
        None | Some(Value::Null) => None,
        Some(value) => Some(number(value).ok_or("\"zero_threshold\" must be a number")?),
    };
    Ok(OutputOptions {
        precision,
        zero_threshold,
        pretty_print: fields.opt_bool("pretty_print")?,
        filename_with_hash: fields.opt_bool("filename_with_hash")?,
    })
}

fn parse_observed_error(json: &Value) -> Result<ObservedError, String> {
    let fields = Fields::new(json, "observed_error")?;
    fields.check_keys(&["type", "message", "state_unchanged"])?;
    Ok(ObservedError {
        type_name: fields.req_str("type")?,
        message: fields.req_str("message")?,
        state_unchanged: fields.opt_bool("state_unchanged")?.unwrap_or(true),
    })
}

/// Shortest decimal text that reads back as `value`: plain notation for
/// magnitudes in [1e-4, 1e16) (and zero), exponent notation otherwise.
fn format_number(value: f64) -> String {
    let magnitude = value.abs();
    if value == 0.0 || !value.is_finite() || (1e-4..1e16).contains(&magnitude) {
        format!("{value}")
    } else {
        format!("{value:e}")
    }
}

/// Field access on a JSON object with strict key checking.
struct Fields<'a> {
    entries: &'a Map<String, Value>,
}

impl<'a> Fields<'a> {
    fn new(json: &'a Value, what: &str) -> Result<Self, String> {
        match json {
            Value::Object(entries) => Ok(Fields { entries }),
            _ => Err(format!("{what} must be an object")),
        }
    }

    /// Errors on keys not in `allowed`.
    fn check_keys(&self, allowed: &[&str]) -> Result<(), String> {
        match self.entries.keys().find(|key| !allowed.contains(&key.as_str())) {
            Some(key) => Err(format!("unknown field {key:?}")),
            None => Ok(()),
        }
    }

    fn get(&self, key: &str) -> Option<&'a Value> {
        self.entries.get(key)
    }

    fn req(&self, key: &str) -> Result<&'a Value, String> {
        self.get(key).ok_or_else(|| format!("missing field {key:?}"))
    }

    fn req_str(&self, key: &str) -> Result<String, String> {
        match self.req(key)? {
            Value::String(s) => Ok(s.clone()),
            _ => Err(format!("field {key:?} must be a string")),
        }
    }

    /// A string field; absent or `null` is `None`.
    fn opt_str(&self, key: &str) -> Result<Option<String>, String> {
        match self.get(key) {
            None | Some(Value::Null) => Ok(None),
            Some(Value::String(s)) => Ok(Some(s.clone())),
            Some(_) => Err(format!("field {key:?} must be a string")),
        }
    }

    /// A boolean field; absent or `null` is `None`.
    fn opt_bool(&self, key: &str) -> Result<Option<bool>, String> {
        match self.get(key) {
            None | Some(Value::Null) => Ok(None),
            Some(Value::Bool(b)) => Ok(Some(*b)),
            Some(_) => Err(format!("field {key:?} must be a boolean")),
        }
    }
}

// These modules' own tests run in the mjcf crate's test targets, not in the binding
// crate's, which include them too (its build script sets `mjcf_mujoco`).
#[cfg(all(test, not(mjcf_mujoco)))]
mod tests {
    use super::*;

    fn cases_root() -> PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/conformance/cases")
    }

    fn load(name: &str) -> Case {
        load_case(&cases_root().join(name)).unwrap_or_else(|e| panic!("{e}"))
    }

    fn parse(json: &str) -> Result<Case, String> {
        parse_case("t", Path::new("/nowhere/t"), json)
    }

    fn parse_ops(ops: &str) -> Result<Vec<Op>, String> {
        parse(&format!(r#"{{"description": "d", "ops": [{ops}]}}"#)).map(|case| case.ops)
    }

    #[test]
    fn every_corpus_case_loads() {
        let dirs = list_cases(&cases_root()).unwrap_or_else(|e| panic!("{e}"));
        assert!(dirs.len() >= 155, "found {} cases", dirs.len());
        let names: Vec<_> = dirs.iter().map(|d| d.file_name()).collect();
        assert!(names.is_sorted());
        let mut ops = 0;
        let mut expected_errors = 0;
        for dir in &dirs {
            let case = load_case(dir).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(Some(case.name.as_str()), dir.file_name().and_then(|n| n.to_str()));
            assert!(!case.description.is_empty(), "{}", case.name);
            assert!(!case.ops.is_empty(), "{}", case.name);
            for (i, op) in case.ops.iter().enumerate() {
                assert_eq!(op.index, i);
                assert_eq!(op.expect_error.is_some(), op.observed_error.is_some());
                expected_errors += usize::from(op.expect_error.is_some());
            }
            ops += case.ops.len();
        }
        assert!(ops > 1000, "{ops} ops");
        assert!(expected_errors > 100, "{expected_errors} expected errors");
    }

    #[test]
    fn json_syntax_errors_are_errors() {
        let deep = format!("{}{}", "[".repeat(1000), "]".repeat(1000));
        for bad in [
            "",
            "{",
            "[1,]",
            "{\"a\":1,}",
            "01",
            "1.",
            "+1",
            "1e999",
            "NaN",
            "\"\\ud800\"",
            "{a: 1}",
            "{} 2",
            &deep,
        ] {
            let e = parse(bad).map_or_else(|e| e, |case| panic!("{bad:?} loaded: {case:?}"));
            assert!(e.starts_with("case t: case.json: "), "{e}");
        }
    }

    /// serde_json keeps the last of repeated keys (at the first one's position);
    /// they are not reported.
    #[test]
    fn repeated_keys_keep_the_last_value() {
        let ops = parse_ops(
            r#"{"op": "add", "model": "m", "parent": "worldbody", "tag": "g", "attrs": {"a": 1, "b": 2, "a": 3}},
               {"op": "load", "name": "x", "name": "y", "file": "f"}"#,
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let OpKind::Add { attrs, .. } = &ops[0].kind else { panic!("{:?}", ops[0]) };
        assert_eq!(
            attrs,
            &[("a".to_owned(), AttrValue::Number(3.0)), ("b".to_owned(), AttrValue::Number(2.0))]
        );
        assert_eq!(ops[1].kind, OpKind::Load { name: "y".to_owned(), file: "f".to_owned() });
    }

    #[test]
    fn seed_example() {
        let case = load("hand_001_seed_example");
        assert_eq!(case.name, "hand_001_seed_example");
        assert!(case.dir.ends_with("hand_001_seed_example"));
        assert_eq!(case.ops.len(), 10);
        assert_eq!(
            case.ops[0].kind,
            OpKind::Load { name: "arena".to_owned(), file: "arena.xml".to_owned() }
        );
        assert_eq!(
            case.ops[3].kind,
            OpKind::Attach {
                parent: "arena".to_owned(),
                site: AttachSite::Name("spawn".to_owned()),
                child: "robot".to_owned(),
                as_handle: None,
            }
        );
        assert_eq!(
            case.ops[4].kind,
            OpKind::Add {
                model: "arena".to_owned(),
                parent: Loc::FrameOf("robot".to_owned()),
                tag: "freejoint".to_owned(),
                attrs: Vec::new(),
                as_handle: None,
            }
        );
        assert!(matches!(
            &case.ops[5].kind,
            OpKind::Attach { site: AttachSite::World, child, .. } if child == "robot2"
        ));
        assert_eq!(case.ops[7].kind, OpKind::Detach { child: "robot2".to_owned() });
        let last = &case.ops[9];
        assert_eq!(last.deviation, vec!["D2".to_owned()]);
        assert!(last.has_deviation("D2") && !last.has_deviation("D3"));
        assert_eq!(last.op_name(), "output");
        assert_eq!(
            last.kind,
            OpKind::Output {
                model: "robot2".to_owned(),
                file: "expected_robot2_detached.xml".to_owned(),
                options: OutputOptions::default(),
            }
        );
    }

    #[test]
    fn attrs_keep_json_order() {
        let case = load("hand_002_attach_worldbody_built");
        assert_eq!(
            case.ops[0].kind,
            OpKind::New { name: "world".to_owned(), model: Some("world_model".to_owned()) }
        );
        let OpKind::Add { model, parent, tag, attrs, as_handle } = &case.ops[1].kind else {
            panic!("{:?}", case.ops[1]);
        };
        assert_eq!((model.as_str(), tag.as_str()), ("world", "geom"));
        assert_eq!(parent, &Loc::Section(vec!["worldbody".to_owned()]));
        assert_eq!(as_handle, &None);
        let keys: Vec<&str> = attrs.iter().map(|(k, _)| k.as_str()).collect();
        assert_eq!(keys, ["name", "type", "size"]);
        assert_eq!(attrs[2].1, AttrValue::Numbers(vec![2.0, 2.0, 0.1]));
        assert_eq!(attrs[2].1.to_mjcf_text().as_deref(), Some("2 2 0.1"));
        let OpKind::Add { as_handle, .. } = &case.ops[3].kind else {
            panic!("{:?}", case.ops[3]);
        };
        assert_eq!(as_handle.as_deref(), Some("base"));
        assert!(matches!(
            &case.ops[4].kind,
            OpKind::Add { parent: Loc::Handle(h), .. } if h == "base"
        ));
    }

    #[test]
    fn float_formatting_case() {
        let case = load("hand_081_float_formatting");
        let OpKind::Add { attrs, .. } = &case.ops[1].kind else {
            panic!("{:?}", case.ops[1]);
        };
        let texts: Vec<_> = attrs.iter().map(|(_, v)| v.to_mjcf_text()).collect();
        assert_eq!(
            texts,
            [Some("a".to_owned()), Some("1e-16 2 3e20".to_owned()), Some("-0 0.5 100".to_owned())]
        );
        let OpKind::Add { attrs, .. } = &case.ops[2].kind else {
            panic!("{:?}", case.ops[2]);
        };
        assert_eq!(attrs[2], ("mass".to_owned(), AttrValue::Number(1e-9)));
        assert_eq!(attrs[3].1.to_mjcf_text().as_deref(), Some("4"));
    }

    #[test]
    fn site_loc_and_observed_error() {
        let case = load("rand_013");
        let op = &case.ops[88];
        assert_eq!(
            op.kind,
            OpKind::Attach {
                parent: "m3".to_owned(),
                site: AttachSite::Loc(Loc::Find {
                    namespace: "body".to_owned(),
                    identifier: "prop/wheel2_5".to_owned()
                }),
                child: "m1".to_owned(),
                as_handle: None,
            }
        );
        assert_eq!(op.expect_error.as_deref(), Some("invalid_parent"));
        assert_eq!(
            op.observed_error,
            Some(ObservedError {
                type_name: "AttributeError".to_owned(),
                message: "object has no attribute: attach".to_owned(),
                state_unchanged: true,
            })
        );
    }

    #[test]
    fn to_mjcf_text() {
        let text = |v: AttrValue| v.to_mjcf_text();
        assert_eq!(text(AttrValue::Null), None);
        assert_eq!(text(AttrValue::Str("1 2".to_owned())).as_deref(), Some("1 2"));
        assert_eq!(text(AttrValue::Bool(true)).as_deref(), Some("true"));
        assert_eq!(text(AttrValue::Bool(false)).as_deref(), Some("false"));
        assert_eq!(text(AttrValue::Numbers(Vec::new())).as_deref(), Some(""));
        for (value, expected) in [
            (4.0, "4"),
            (-4.0, "-4"),
            (0.0, "0"),
            (0.1, "0.1"),
            (1e-4, "0.0001"),
            (1e-5, "1e-5"),
            (1e-16, "1e-16"),
            (3e20, "3e20"),
            (1e15, "1000000000000000"),
            (1e16, "1e16"),
            (0.30000000000000004, "0.30000000000000004"),
            (123456.789, "123456.789"),
            (-2.5e-300, "-2.5e-300"),
        ] {
            assert_eq!(text(AttrValue::Number(value)).as_deref(), Some(expected));
        }
        // Round trip.
        for value in [1.0 / 3.0, 2.0f64.sqrt() * 1e-7, 6.02214076e23, f64::MIN_POSITIVE, f64::MAX] {
            let rendered = format_number(value);
            assert_eq!(rendered.parse::<f64>().ok(), Some(value), "{rendered}");
        }
    }

    #[test]
    fn all_op_kinds() {
        let ops = parse_ops(
            r#"
            {"op": "new", "name": "a"},
            {"op": "new", "name": "b", "model": "bee"},
            {"op": "add", "model": "a", "parent": "option.flag", "tag": "x",
             "attrs": {"z": 1, "a": "s", "m": [1, 2.5], "b": false}, "as": "h"},
            {"op": "attach", "parent": "a", "site": null, "child": "b", "as": "f"},
            {"op": "include_copy", "parent": "a", "child": "b", "override_attributes": true},
            {"op": "include_copy", "parent": "a", "child": "b"},
            {"op": "detach", "child": "b", "expect_error": "not_attached"},
            {"op": "set", "model": "a", "target": {"find": ["body", "r/t"]},
             "attrs": {"pos": null, "name": "n"}, "deviation": " D2 , D3,"},
            {"op": "remove", "model": "a", "target": {"handle": "h"}},
            {"op": "remove", "model": "a", "target": {"frame_of": "b"}, "affect_attachments": true},
            {"op": "rename", "model": "a", "to": "c"},
            {"op": "output", "model": "a", "file": "expected_a.xml",
             "options": {"precision": 5, "zero_threshold": 1e-6, "pretty_print": false,
                         "filename_with_hash": true}}
            "#,
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let kinds: Vec<_> = ops.iter().map(Op::op_name).collect();
        assert_eq!(
            kinds,
            [
                "new",
                "new",
                "add",
                "attach",
                "include_copy",
                "include_copy",
                "detach",
                "set",
                "remove",
                "remove",
                "rename",
                "output"
            ]
        );
        assert_eq!(ops[0].kind, OpKind::New { name: "a".to_owned(), model: None });
        assert_eq!(
            ops[2].kind,
            OpKind::Add {
                model: "a".to_owned(),
                parent: Loc::Section(vec!["option".to_owned(), "flag".to_owned()]),
                tag: "x".to_owned(),
                attrs: vec![
                    ("z".to_owned(), AttrValue::Number(1.0)),
                    ("a".to_owned(), AttrValue::Str("s".to_owned())),
                    ("m".to_owned(), AttrValue::Numbers(vec![1.0, 2.5])),
                    ("b".to_owned(), AttrValue::Bool(false)),
                ],
                as_handle: Some("h".to_owned()),
            }
        );
        assert_eq!(
            ops[3].kind,
            OpKind::Attach {
                parent: "a".to_owned(),
                site: AttachSite::World,
                child: "b".to_owned(),
                as_handle: Some("f".to_owned()),
            }
        );
        assert!(matches!(ops[4].kind, OpKind::IncludeCopy { override_attributes: true, .. }));
        assert!(matches!(ops[5].kind, OpKind::IncludeCopy { override_attributes: false, .. }));
        assert_eq!(ops[6].expect_error.as_deref(), Some("not_attached"));
        assert_eq!(ops[6].observed_error, None);
        assert_eq!(
            ops[7].kind,
            OpKind::Set {
                model: "a".to_owned(),
                target: Loc::Find { namespace: "body".to_owned(), identifier: "r/t".to_owned() },
                attrs: vec![
                    ("pos".to_owned(), AttrValue::Null),
                    ("name".to_owned(), AttrValue::Str("n".to_owned())),
                ],
            }
        );
        assert_eq!(ops[7].deviation, ["D2", "D3"]);
        assert!(matches!(
            &ops[8].kind,
            OpKind::Remove { target: Loc::Handle(h), affect_attachments: false, .. } if h == "h"
        ));
        assert!(matches!(
            &ops[9].kind,
            OpKind::Remove { target: Loc::FrameOf(v), affect_attachments: true, .. } if v == "b"
        ));
        assert_eq!(ops[10].kind, OpKind::Rename { model: "a".to_owned(), to: "c".to_owned() });
        assert_eq!(
            ops[11].kind,
            OpKind::Output {
                model: "a".to_owned(),
                file: "expected_a.xml".to_owned(),
                options: OutputOptions {
                    precision: Some(5),
                    zero_threshold: Some(1e-6),
                    pretty_print: Some(false),
                    filename_with_hash: Some(true),
                },
            }
        );
        assert_eq!(ops[11].index, 11);
    }

    #[test]
    fn malformed_ops_are_errors() {
        let cases: &[(&str, &str)] = &[
            (r#"{"op": "frobnicate"}"#, "op 1 (frobnicate): unknown op kind \"frobnicate\""),
            (r#"{"name": "x"}"#, "op 1: missing field \"op\""),
            (r#"[]"#, "op 1: an op must be an object"),
            (r#"{"op": "load", "name": "x"}"#, "op 1 (load): missing field \"file\""),
            (
                r#"{"op": "load", "name": "x", "file": "f", "extra": 1}"#,
                "op 1 (load): unknown field \"extra\"",
            ),
            (r#"{"op": "load", "name": 3, "file": "f"}"#, "field \"name\" must be a string"),
            (
                r#"{"op": "detach", "child": "c", "expect_error": "oops"}"#,
                "unknown error category \"oops\"",
            ),
            (
                r#"{"op": "add", "model": "m", "parent": "worldbody", "tag": "g", "attrs": {"a": null}}"#,
                "null is only allowed in set",
            ),
            (
                r#"{"op": "add", "model": "m", "parent": "worldbody", "tag": "g", "attrs": {"a": ["x"]}}"#,
                "arrays must hold only numbers",
            ),
            (
                r#"{"op": "add", "model": "m", "parent": "option..flag", "tag": "g"}"#,
                "bad section locator",
            ),
            (
                r#"{"op": "add", "model": "m", "parent": {"find": ["body"]}, "tag": "g"}"#,
                "\"find\" must be [namespace, identifier] strings",
            ),
            (
                r#"{"op": "add", "model": "m", "parent": {"handle": "h", "find": ["a", "b"]}, "tag": "g"}"#,
                "exactly one key",
            ),
            (
                r#"{"op": "add", "model": "m", "parent": {"nearest": "h"}, "tag": "g"}"#,
                "unknown locator \"nearest\"",
            ),
            (r#"{"op": "set", "model": "m", "target": "worldbody"}"#, "missing field \"attrs\""),
            (
                r#"{"op": "attach", "parent": "p", "child": "c"}"#,
                "missing \"site\" or \"site_loc\"",
            ),
            (
                r#"{"op": "attach", "parent": "p", "child": "c", "site": null, "site_loc": "worldbody"}"#,
                "both \"site\" and \"site_loc\" given",
            ),
            (
                r#"{"op": "attach", "parent": "p", "child": "c", "site": 1}"#,
                "must be a string or null",
            ),
            (
                r#"{"op": "include_copy", "parent": "p", "child": "c", "override_attributes": 1}"#,
                "must be a boolean",
            ),
            (
                r#"{"op": "output", "model": "m", "file": "f", "options": {"precision": 1.5}}"#,
                "non-negative integer",
            ),
            (
                r#"{"op": "output", "model": "m", "file": "f", "options": {"indent": 2}}"#,
                "unknown field \"indent\"",
            ),
        ];
        for (op, message) in cases {
            let json = format!(
                r#"{{"description": "d", "ops": [{{"op": "detach", "child": "c"}}, {op}]}}"#
            );
            match parse(&json) {
                Ok(case) => panic!("{op} loaded: {case:?}"),
                Err(e) => {
                    assert!(e.starts_with("case t, op 1"), "{e}");
                    assert!(e.contains(message), "{e:?} should contain {message:?}");
                }
            }
        }
        for json in [
            "",
            "[]",
            r#"{"ops": []}"#,
            r#"{"description": "d"}"#,
            r#"{"description": "d", "ops": {}}"#,
            r#"{"description": "d", "ops": [], "x": 1}"#,
        ] {
            let e = parse(json).map_or_else(|e| e, |case| panic!("{json} loaded: {case:?}"));
            assert!(e.starts_with("case t: "), "{e}");
        }
    }

    #[test]
    fn missing_folders_are_errors() {
        let nowhere = cases_root().join("no_such_case");
        let e = load_case(&nowhere).map_or_else(|e| e, |case| panic!("{case:?}"));
        assert!(e.contains("no_such_case"), "{e}");
        assert!(list_cases(&nowhere).is_err());
    }
}
