//! Rule *values MuJoCo takes* ([`ProblemKind::Refused`]): what MuJoCo 4.0.0 refuses
//! in one element's own values (an attribute out of its range, a zero axis, two
//! attributes that exclude each other, a keyword another one rules out), found by
//! the checks of the tables below, one table per file, each check one entry.
//!
//! A check reads the element's values as MuJoCo reads them: its own, else its default
//! classes' (its `class`, the `childclass` in force, the root class), so a fact given
//! by a class is judged as one given literally; elements inside `<default>` are not
//! judged (MuJoCo judges the elements that use them). Each check is proved by the
//! refused model and twin of `mjcf-mujoco/refusals` that carry its message.

use std::sync::{Arc, OnceLock};

use crate::model::Model;
use crate::model::layout::{effective, from_classes};
use crate::model::settings;
use crate::model::tree::Node;
use crate::schema::{ElementKind, Role};
use crate::value::Value;

use super::ProblemKind;
use super::walk::{Event, Rule};

mod geom;
mod global;
mod numbers;
mod presence;
mod reader;

/// One check: its name, the elements it judges, the test, and what to do.
pub(crate) struct Check {
    /// Its name, stable (`geom-size-positive`): [`ProblemKind::Refused`]'s `rule`.
    pub(crate) name: &'static str,
    /// Whether it judges elements of this kind.
    pub(crate) on: fn(ElementKind) -> bool,
    /// What MuJoCo refuses of the element, if anything.
    pub(crate) test: fn(&At<'_, '_>) -> Option<Found>,
    /// What to do about it.
    pub(crate) fix: &'static str,
}

/// What a check found: the attribute at fault (if one is) and MuJoCo's message, its
/// names and numbers filled in (MuJoCo's numeric ids left out).
pub(crate) struct Found {
    pub(crate) attribute: Option<&'static str>,
    pub(crate) mujoco: String,
}

/// A finding on `attribute` with MuJoCo's `mujoco`.
pub(crate) fn found(attribute: &'static str, mujoco: impl Into<String>) -> Option<Found> {
    Some(Found { attribute: Some(attribute), mujoco: mujoco.into() })
}

/// A finding on the element as a whole.
pub(crate) fn found_element(mujoco: impl Into<String>) -> Option<Found> {
    Some(Found { attribute: None, mujoco: mujoco.into() })
}

/// The element a check judges, its values as MuJoCo reads them.
pub(crate) struct At<'e, 'm> {
    pub(crate) e: &'e Event<'m>,
}

impl<'m> At<'_, 'm> {
    /// Its kind.
    pub(crate) fn kind(&self) -> ElementKind {
        self.e.node.kind()
    }

    /// The value of `attr`: its own, else its classes'.
    pub(crate) fn get(&self, attr: &str) -> Option<&'m Value> {
        effective(self.e.model, self.e.node, self.e.class, attr)
    }

    /// Whether `attr` is given (by the element or its classes).
    pub(crate) fn has(&self, attr: &str) -> bool {
        self.get(attr).is_some()
    }

    /// Whether the element itself gives `attr` (its classes aside).
    pub(crate) fn own(&self, attr: &str) -> bool {
        self.kind().attr_index(attr).is_some_and(|i| self.e.node.attr(i).is_some())
    }

    /// `attr` as text (a keyword, string or name).
    pub(crate) fn str(&self, attr: &str) -> Option<&'m str> {
        self.get(attr).and_then(Value::as_str)
    }

    /// `attr` as one number (a float or an int).
    pub(crate) fn float(&self, attr: &str) -> Option<f64> {
        match self.get(attr)? {
            Value::Float(x) => Some(*x),
            Value::Int(i) => Some(*i as f64),
            Value::Floats(v) if v.len() == 1 => Some(v[0]),
            Value::Ints(v) if v.len() == 1 => Some(v[0] as f64),
            _ => None,
        }
    }

    /// `attr` as one integer.
    pub(crate) fn int(&self, attr: &str) -> Option<i64> {
        match self.get(attr)? {
            Value::Int(i) => Some(*i),
            Value::Ints(v) if v.len() == 1 => Some(v[0]),
            _ => None,
        }
    }

    /// `attr` as numbers, as MuJoCo reads an array: the class's numbers, the
    /// element's own written over the first ones (`size="2"` over a class's `1 1 1`
    /// is `2 1 1`); an int array or one number widened.
    pub(crate) fn floats(&self, attr: &str) -> Option<Vec<f64>> {
        let (model, node, class) = (self.e.model, self.e.node, self.e.class);
        let own = node.kind().attr_index(attr).and_then(|i| node.attr(i)).and_then(numbers);
        let inherited = from_classes(model, node.kind(), class, attr).and_then(numbers);
        match (own, inherited) {
            (Some(mut own), Some(inherited)) => {
                own.extend(inherited.into_iter().skip(own.len()));
                Some(own)
            }
            (own, inherited) => own.or(inherited),
        }
    }

    /// The name the element has in its model, or `""` (MuJoCo's messages quote it).
    pub(crate) fn name(&self) -> &'m str {
        self.e.node.identifier().unwrap_or("")
    }
}

/// A value's numbers, if it holds numbers.
fn numbers(v: &Value) -> Option<Vec<f64>> {
    match v {
        Value::Floats(v) => Some(v.to_vec()),
        Value::Ints(v) => Some(v.iter().map(|i| *i as f64).collect()),
        Value::Float(x) => Some(vec![*x]),
        Value::Int(i) => Some(vec![*i as f64]),
        _ => None,
    }
}

/// Every table of checks, one per file.
const TABLES: &[&[Check]] =
    &[geom::CHECKS, global::CHECKS, presence::CHECKS, reader::CHECKS, numbers::CHECKS];

/// The tables of what MuJoCo's XML reader refuses as it reads a file: judged of a
/// whole file MuJoCo reads but does not compile as it is (an asset model's).
const READER_TABLES: &[&[Check]] =
    &[global::CHECKS, presence::CHECKS, reader::CHECKS, numbers::CHECKS];

/// The checks of `tables` for each element kind (by kind index).
fn gather(tables: &[&'static [Check]]) -> Vec<Vec<&'static Check>> {
    let mut out: Vec<Vec<&'static Check>> = Vec::new();
    for kind in ElementKind::all() {
        let i = kind.index();
        if out.len() <= i {
            out.resize_with(i + 1, Vec::new);
        }
        out[i] = tables.iter().flat_map(|t| t.iter()).filter(|c| (c.on)(kind)).collect();
    }
    out
}

/// The checks of each element kind (by kind index), gathered once: of every table,
/// or with `reader_only` of [`READER_TABLES`].
fn by_kind(reader_only: bool) -> &'static Vec<Vec<&'static Check>> {
    static BY_KIND: OnceLock<Vec<Vec<&'static Check>>> = OnceLock::new();
    static READER: OnceLock<Vec<Vec<&'static Check>>> = OnceLock::new();
    match reader_only {
        false => BY_KIND.get_or_init(|| gather(TABLES)),
        true => READER.get_or_init(|| gather(READER_TABLES)),
    }
}

/// The rule: every check of the element's kind. The global settings are judged as
/// written: the sections merged across attachments (where the models give an
/// attribute different values, the fold takes one: the least `znear`, the greatest
/// `njmax`), each with its sub-elements, said on the outermost model's section (or on
/// its root, for a section only attachments give).
pub(super) struct Values<'m> {
    /// The model checked (the outermost).
    model: &'m Model,
    /// Its settings sections as written, once asked.
    merged: Option<Arc<[Node]>>,
    /// Only the checks of what MuJoCo's reader refuses ([`READER_TABLES`]).
    reader_only: bool,
}

impl<'m> Values<'m> {
    /// The rule for `model`.
    pub(super) fn new(model: &'m Model) -> Values<'m> {
        Values { model, merged: None, reader_only: false }
    }

    /// The rule for a file `model` that MuJoCo reads but does not compile as it is
    /// (an asset model's): what its XML reader refuses alone.
    pub(super) fn reader(model: &'m Model) -> Values<'m> {
        Values { model, merged: None, reader_only: true }
    }

    /// The settings sections as written (a conflict, which attaching refuses, leaves
    /// none to judge).
    fn merged(&mut self) -> Arc<[Node]> {
        let model = self.model;
        self.merged
            .get_or_insert_with(|| settings::merged(model).unwrap_or_else(|_| Arc::from([])))
            .clone()
    }
}

/// Whether `kind` is a settings section or inside one.
fn in_settings(kind: ElementKind) -> bool {
    let mut k = Some(kind);
    while let Some(kind) = k {
        if kind.is(Role::SettingsSection) {
            return true;
        }
        k = kind.spec().parent;
    }
    false
}

/// Every check of `e`'s element's kind (of [`READER_TABLES`] with `reader_only`).
fn judge(e: &Event<'_>, reader_only: bool, out: &mut Vec<ProblemKind>) {
    let Some(checks) = by_kind(reader_only).get(e.node.kind().index()) else { return };
    let at = At { e };
    for check in checks {
        if let Some(f) = (check.test)(&at) {
            out.push(ProblemKind::Refused {
                rule: check.name,
                attribute: f.attribute,
                mujoco: f.mujoco,
                fix: check.fix,
            });
        }
    }
}

/// [`judge`] of the written settings element `node` and each element inside it, as
/// if the walk were at `e`.
fn judge_written(e: &Event<'_>, node: &Node, reader_only: bool, out: &mut Vec<ProblemKind>) {
    let at = Event { node, class: None, ..*e };
    judge(&at, reader_only, out);
    for c in node.children().iter() {
        judge_written(e, c, reader_only, out);
    }
}

impl<'m> Rule<'m> for Values<'m> {
    fn enter(&mut self, e: &Event<'m>, out: &mut Vec<ProblemKind>) {
        let kind = e.node.kind();
        if e.inst == 0 && kind == ElementKind::ROOT {
            // The sections only attachments give.
            let merged = self.merged();
            let own = |k: ElementKind| e.node.child_of_kind(k).is_some();
            for section in merged.iter().filter(|s| !own(s.kind())) {
                judge_written(e, section, self.reader_only, out);
            }
        } else if in_settings(kind) {
            if e.inst == 0 && kind.is(Role::SettingsSection) {
                let merged = self.merged();
                if let Some(section) = merged.iter().find(|s| s.kind() == kind) {
                    judge_written(e, section, self.reader_only, out);
                }
            }
            return;
        }
        judge(e, self.reader_only, out);
    }
}

/// Selectors for [`Check::on`].
pub(crate) mod on {
    use super::*;

    /// A `<geom>` of a body.
    pub(crate) fn geom(k: ElementKind) -> bool {
        k.is(Role::Geom)
    }

    /// A `<site>` of a body.
    pub(crate) fn site(k: ElementKind) -> bool {
        k.is(Role::Site)
    }

    /// A `<body>`.
    pub(crate) fn body(k: ElementKind) -> bool {
        k.is(Role::Body)
    }

    /// A `<joint>` of a body.
    pub(crate) fn joint(k: ElementKind) -> bool {
        k.is(Role::Joint)
    }

    /// An actuator of any kind.
    pub(crate) fn actuator(k: ElementKind) -> bool {
        k.role().is_some_and(Role::is_actuator)
    }

    /// A tendon (`<fixed>`, `<spatial>`).
    pub(crate) fn tendon(k: ElementKind) -> bool {
        k.is(Role::Tendon)
    }

    /// An element of the root's section `section` (`sensor`, `asset`, ...).
    pub(crate) fn in_section(k: ElementKind, section: &str) -> bool {
        k.spec()
            .parent
            .is_some_and(|p| p.tag() == section && p.spec().parent == Some(ElementKind::ROOT))
    }

    /// The element whose schema path is `path` (`actuator/general`, `(world)body/camera`;
    /// `default/camera` in any default class).
    pub(crate) fn at(k: ElementKind, path: &str) -> bool {
        let (parent, tag) = path.rsplit_once('/').unwrap_or(("", path));
        if k.tag() != tag {
            return false;
        }
        let p = k.spec().parent;
        match parent {
            "" => p == Some(ElementKind::ROOT),
            "default" => p.is_some_and(|p| p.is(Role::DefaultClass)),
            "(world)body" => p.is_some_and(|p| {
                p.is(Role::Body)
                    || p.is(Role::Worldbody)
                    || p.is(Role::Frame)
                    || p.is(Role::Replicate)
            }),
            section => {
                p.is_some_and(|p| p.tag() == section && p.spec().parent == Some(ElementKind::ROOT))
            }
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use crate::model::Model;
    use crate::model::check::ProblemKind;
    use crate::model::check::tests::kinds_of;

    use super::Values;

    /// The names of the checks that find a problem in `xml`.
    pub(crate) fn refused(xml: &str) -> Vec<&'static str> {
        let m = Model::from_xml_str(xml).unwrap_or_else(|e| panic!("{e}: {xml}"));
        kinds_of(&m, Values::new(&m))
            .into_iter()
            .filter_map(|k| match k {
                ProblemKind::Refused { rule, .. } => Some(rule),
                _ => None,
            })
            .collect()
    }

    /// `(refused, compiled)` pairs, each judged by MuJoCo 4.0.0: the first gets
    /// exactly `rule`, the second nothing.
    pub(crate) fn assert_pairs(rule: &str, pairs: &[(&str, &str)]) {
        for (bad, good) in pairs {
            assert_eq!(refused(bad), [rule], "refused: {bad}");
            assert_eq!(refused(good), Vec::<&str>::new(), "compiled: {good}");
        }
    }
}
