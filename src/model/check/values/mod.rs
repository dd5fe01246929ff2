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
use crate::model::layout::{class_defaults, effective, from_classes};
use crate::model::settings;
use crate::model::tree::Node;
use crate::schema::{ElementKind, Role};
use crate::value::Value;

use super::ProblemKind;
use super::walk::{Event, Rule};

mod assets;
mod camera;
mod custom;
mod flex;
mod frame;
mod geom;
mod global;
mod hull;
pub(crate) mod inertial;
mod inline;
mod joint;
mod links;
mod mesh;
mod numbers;
pub(crate) mod orient;
mod presence;
mod reader;
mod sensor;
mod site;
mod tendon;
mod texture;
mod user;

/// The global settings (the model's merged `<compiler>` and `<size>`) the checks
/// read, MuJoCo's defaults where none is given.
#[derive(Clone, Debug)]
pub(crate) struct Settings {
    /// `size/nuser_body`, `nuser_jnt`, `nuser_geom`, `nuser_site`, `nuser_cam`,
    /// `nuser_tendon`, `nuser_actuator`, `nuser_sensor`, by name (-1: as many as the
    /// longest `user` needs).
    pub(crate) nuser: Vec<(&'static str, i64)>,
    /// `compiler/eulerseq`.
    pub(crate) eulerseq: String,
    /// `compiler/inertiafromgeom`: `auto`, `true` or `false`.
    pub(crate) inertiafromgeom: String,
    /// `compiler/inertiagrouprange`.
    pub(crate) inertiagrouprange: [i64; 2],
    /// `compiler/balanceinertia`.
    pub(crate) balanceinertia: bool,
    /// `compiler/boundinertia`.
    pub(crate) boundinertia: f64,
    /// `compiler/discardvisual`: MuJoCo then drops every material and texture, and
    /// the meshes no collision geom uses, before it judges them (settings that
    /// cannot be merged count as discarding: no check that needs them then fires).
    pub(crate) discard_visual: bool,
}

impl Settings {
    /// The settings of `model` as written (its merged sections).
    pub(crate) fn of(model: &Model) -> Settings {
        let sections = settings::merged(model).ok();
        let section = |tag: &str| {
            let kind = ElementKind::ROOT.child(tag);
            sections.as_ref().and_then(|s| s.iter().find(|n| Some(n.kind()) == kind).cloned())
        };
        let (compiler, size) = (section("compiler"), section("size"));
        let get = |n: &Option<Node>, attr: &str| -> Option<Value> {
            let n = n.as_ref()?;
            n.attr(n.kind().attr_index(attr)?).cloned()
        };
        let text = |attr: &str, default: &str| {
            get(&compiler, attr)
                .and_then(|v| v.as_str().map(str::to_string))
                .unwrap_or(default.into())
        };
        let nuser = NUSER
            .into_iter()
            .map(|a| {
                (
                    a,
                    get(&size, a)
                        .and_then(|v| numbers(&v)?.first().copied())
                        .map_or(-1, |x| x as i64),
                )
            })
            .collect();
        let range = get(&compiler, "inertiagrouprange").and_then(|v| numbers(&v));
        let range = match range.as_deref() {
            Some([a, b, ..]) => [*a as i64, *b as i64],
            _ => [0, 5],
        };
        Settings {
            nuser,
            eulerseq: text("eulerseq", "xyz"),
            inertiafromgeom: text("inertiafromgeom", "auto"),
            inertiagrouprange: range,
            balanceinertia: text("balanceinertia", "false") == "true",
            boundinertia: get(&compiler, "boundinertia")
                .and_then(|v| numbers(&v)?.first().copied())
                .unwrap_or(0.0),
            discard_visual: sections.is_none() || text("discardvisual", "false") == "true",
        }
    }

    /// `size/NAME` (`nuser_geom`), -1 when not given.
    pub(crate) fn nuser(&self, name: &str) -> i64 {
        self.nuser.iter().find(|(n, _)| *n == name).map_or(-1, |(_, v)| *v)
    }
}

/// `<size>`'s user-data counts, one per kind of element with `user` numbers.
pub(crate) const NUSER: [&str; 8] = [
    "nuser_body",
    "nuser_jnt",
    "nuser_geom",
    "nuser_site",
    "nuser_cam",
    "nuser_tendon",
    "nuser_actuator",
    "nuser_sensor",
];

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
    /// The model's global settings.
    pub(crate) settings: &'e Settings,
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

    /// The element's own value of `attr` (not its classes').
    pub(crate) fn own(&self, attr: &str) -> Option<&'m Value> {
        let node = self.e.node;
        node.kind().attr_index(attr).and_then(|i| node.attr(i))
    }

    /// `attr`'s own value as text.
    pub(crate) fn own_str(&self, attr: &str) -> Option<&'m str> {
        self.own(attr).and_then(Value::as_str)
    }

    /// `attr`'s own value as one integer.
    pub(crate) fn own_int(&self, attr: &str) -> Option<i64> {
        match self.own(attr)? {
            Value::Int(i) => Some(*i),
            Value::Ints(v) if v.len() == 1 => Some(v[0]),
            _ => None,
        }
    }

    /// `attr`'s own numbers.
    pub(crate) fn own_floats(&self, attr: &str) -> Option<Vec<f64>> {
        self.own(attr).and_then(numbers)
    }

    /// Where the element's values come from, nearest first: the element, then the
    /// defaults of its tag in its class and each class above it.
    pub(crate) fn levels(&self) -> Vec<&'m Node> {
        let (model, node) = (self.e.model, self.e.node);
        std::iter::once(node).chain(class_defaults(model, node.kind(), self.e.class)).collect()
    }

    /// The name the element has in its model, or `""` (MuJoCo's messages quote it).
    pub(crate) fn name(&self) -> &'m str {
        self.e.node.identifier().unwrap_or("")
    }
}

/// A value's numbers, if it holds numbers.
pub(crate) fn numbers(v: &Value) -> Option<Vec<f64>> {
    match v {
        Value::Floats(v) => Some(v.to_vec()),
        Value::Ints(v) => Some(v.iter().map(|i| *i as f64).collect()),
        Value::Float(x) => Some(vec![*x]),
        Value::Int(i) => Some(vec![*i as f64]),
        _ => None,
    }
}

/// Every table of checks, one per file.
const TABLES: &[&[Check]] = &[
    geom::CHECKS,
    orient::CHECKS,
    user::CHECKS,
    joint::CHECKS,
    site::CHECKS,
    camera::CHECKS,
    frame::CHECKS,
    inertial::CHECKS,
    mesh::CHECKS,
    inline::CHECKS,
    assets::CHECKS,
    texture::CHECKS,
    flex::CHECKS,
    tendon::CHECKS,
    sensor::CHECKS,
    links::CHECKS,
    custom::CHECKS,
    global::CHECKS,
    presence::CHECKS,
    reader::CHECKS,
    numbers::CHECKS,
];

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
    /// The global settings the checks read.
    settings: Settings,
    /// Only the checks of what MuJoCo's reader refuses ([`READER_TABLES`]).
    reader_only: bool,
}

impl<'m> Values<'m> {
    /// The rule for `model` as written (its merged settings).
    pub(super) fn new(model: &'m Model) -> Values<'m> {
        Values { model, merged: None, settings: Settings::of(model), reader_only: false }
    }

    /// The rule for a file `model` that MuJoCo reads but does not compile as it is
    /// (an asset model's): what its XML reader refuses alone.
    pub(super) fn reader(model: &'m Model) -> Values<'m> {
        Values { model, merged: None, settings: Settings::of(model), reader_only: true }
    }

    /// The settings sections as written (a conflict, which attaching refuses, leaves
    /// none to judge).
    fn merged(&mut self) -> Arc<[Node]> {
        let model = self.model;
        self.merged
            .get_or_insert_with(|| settings::merged(model).unwrap_or_else(|_| Arc::from([])))
            .clone()
    }

    /// Every check of `e`'s element's kind (of [`READER_TABLES`] with `reader_only`).
    fn judge(&self, e: &Event<'_>, out: &mut Vec<ProblemKind>) {
        let Some(checks) = by_kind(self.reader_only).get(e.node.kind().index()) else { return };
        let at = At { e, settings: &self.settings };
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

    /// [`Values::judge`] of the written settings element `node` and each element
    /// inside it, as if the walk were at `e`.
    fn judge_written(&self, e: &Event<'_>, node: &Node, out: &mut Vec<ProblemKind>) {
        let at = Event { node, class: None, ..*e };
        self.judge(&at, out);
        for c in node.children().iter() {
            self.judge_written(e, c, out);
        }
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

impl<'m> Rule<'m> for Values<'m> {
    fn enter(&mut self, e: &Event<'m>, out: &mut Vec<ProblemKind>) {
        let kind = e.node.kind();
        if e.inst == 0 && kind == ElementKind::ROOT {
            // The sections only attachments give.
            let merged = self.merged();
            let own = |k: ElementKind| e.node.child_of_kind(k).is_some();
            for section in merged.iter().filter(|s| !own(s.kind())) {
                self.judge_written(e, section, out);
            }
        } else if in_settings(kind) {
            if e.inst == 0 && kind.is(Role::SettingsSection) {
                let merged = self.merged();
                if let Some(section) = merged.iter().find(|s| s.kind() == kind) {
                    self.judge_written(e, section, out);
                }
            }
            return;
        }
        self.judge(e, out);
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

    /// A `<frame>`.
    pub(crate) fn frame(k: ElementKind) -> bool {
        k.is(Role::Frame)
    }

    /// The `<inertial>` of a body.
    pub(crate) fn inertial(k: ElementKind) -> bool {
        k.is(Role::Inertial)
    }

    /// A `<camera>` of a body.
    pub(crate) fn camera(k: ElementKind) -> bool {
        at(k, "(world)body/camera")
    }

    /// A `<light>` of a body.
    pub(crate) fn light(k: ElementKind) -> bool {
        at(k, "(world)body/light")
    }

    /// A `<joint>` of a body.
    pub(crate) fn joint(k: ElementKind) -> bool {
        k.is(Role::Joint)
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

    /// The defaults of `tag` in a default class (`<default><mesh …/>`), at any depth.
    pub(crate) fn default_of(k: ElementKind, tag: &str) -> bool {
        k.spec().parent.is_some_and(|p| p.is(Role::DefaultClass) && p.child(tag) == Some(k))
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
