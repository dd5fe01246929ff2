//! Property tests over random small models built through the API.
//!
//! Every property runs `PROPTEST_CASES` cases (default 256) from a fixed seed (set
//! `PROPTEST_RNG_SEED` to explore others); failures are saved to
//! `proptest-regressions/properties.txt` and replayed first on later runs.
//!
//! The round trip (property a): the writer prints the root default class as
//! `<default><default class="R">…</default></default>` (`R = "/"` when unnamed) and
//! unnamed elements as `//unnamed_<ns>_<i>`, as dm_control does; the reader takes both
//! forms back, so write∘read∘write == write for every generated model with an unnamed
//! root class, and one round later for a named one (see the fixed-point test).
//! The same generated steps are also rendered as MJCF text by a small renderer here, a
//! differential check: reading that text gives the same output as building the model
//! through the API.

use crate::text;

use std::collections::{HashMap, HashSet};

use mjcf::{
    Attrs, EditError, Element, ElementRef, ErrorKind, Loc, Model, Namespace, Reference, Value,
    ValueError, WriteOptions,
};
use proptest::prelude::*;
use proptest::sample::Index;
use proptest::test_runner::{FileFailurePersistence, RngSeed};

// ---------------------------------------------------------------------------------
// Configuration.

fn config() -> ProptestConfig {
    // `default()` reads the PROPTEST_* environment variables.
    let mut c = ProptestConfig::default();
    if std::env::var_os("PROPTEST_CASES").is_none() {
        c.cases = 256;
    }
    if std::env::var_os("PROPTEST_RNG_SEED").is_none() {
        c.rng_seed = RngSeed::Fixed(0x6d6a_6366);
    }
    c.failure_persistence =
        Some(Box::new(FileFailurePersistence::Direct("proptest-regressions/properties.txt")));
    c
}

// ---------------------------------------------------------------------------------
// Generators.

/// Finite floats: ordinary, zero of both signs, tiny, subnormal, huge.
fn float() -> impl Strategy<Value = f64> {
    use proptest::num::f64 as F;
    prop_oneof![
        6 => -10.0..10.0f64,
        1 => Just(0.0),
        1 => Just(-0.0),
        1 => -1e-300..1e-300f64,
        1 => F::SUBNORMAL | F::POSITIVE | F::NEGATIVE,
        2 => F::NORMAL | F::POSITIVE | F::NEGATIVE,
        1 => prop::sample::select(vec![f64::MAX, f64::MIN, f64::MIN_POSITIVE, 5e-324, 1e300, -1e308, 0.1, 1.0 / 3.0, 1e21, 1e-7]),
    ]
}

fn floats<const N: usize>() -> impl Strategy<Value = [f64; N]> {
    prop::array::uniform(float())
}

fn name() -> impl Strategy<Value = String> {
    "[a-z][a-z0-9_]{0,6}"
}

/// A name, or (when `unnamed` is allowed) sometimes none.
fn maybe_name(unnamed: bool) -> BoxedStrategy<Option<String>> {
    if unnamed {
        prop::option::weighted(0.7, name()).boxed()
    } else {
        name().prop_map(Some).boxed()
    }
}

const GEOM_TYPES: &[&str] = &["plane", "sphere", "capsule", "ellipsoid", "cylinder", "box"];
const JOINT_TYPES: &[&str] = &["hinge", "slide", "ball"];

/// One build step. `Index`es pick among what exists when the step runs.
#[derive(Clone, Debug)]
enum Action {
    /// A body under the worldbody or a body.
    Body { parent: Index, name: Option<String>, pos: [f64; 3], childclass: Option<Index> },
    /// A geom under the worldbody or a body.
    Geom {
        parent: Index,
        name: Option<String>,
        ty: &'static str,
        upper: bool,
        size: Vec<f64>,
        class: Option<Index>,
    },
    /// A site under the worldbody or a body.
    Site { parent: Index, name: Option<String>, pos: [f64; 3], size: Vec<f64> },
    /// A joint under a body.
    Joint {
        parent: Index,
        name: Option<String>,
        ty: &'static str,
        upper: bool,
        axis: [f64; 3],
        range: Option<[f64; 2]>,
    },
    /// A motor on a named joint.
    Motor { joint: Index, name: Option<String>, gear: f64 },
    /// A default class under the root class or another class.
    Class { parent: Index, name: String, rgba: [f64; 4], size: Vec<f64> },
}

fn action(unnamed: bool) -> impl Strategy<Value = Action> {
    let n = move || maybe_name(unnamed);
    let size = || prop::collection::vec(float(), 1..=3);
    prop_oneof![
        3 => (any::<Index>(), n(), floats::<3>(), prop::option::weighted(0.3, any::<Index>()))
            .prop_map(|(parent, name, pos, childclass)| Action::Body { parent, name, pos, childclass }),
        3 => (any::<Index>(), n(), prop::sample::select(GEOM_TYPES), any::<bool>(), size(), prop::option::weighted(0.4, any::<Index>()))
            .prop_map(|(parent, name, ty, upper, size, class)| Action::Geom { parent, name, ty, upper, size, class }),
        1 => (any::<Index>(), n(), floats::<3>(), size())
            .prop_map(|(parent, name, pos, size)| Action::Site { parent, name, pos, size }),
        2 => (any::<Index>(), n(), prop::sample::select(JOINT_TYPES), any::<bool>(), floats::<3>(), prop::option::of(floats::<2>()))
            .prop_map(|(parent, name, ty, upper, axis, range)| Action::Joint { parent, name, ty, upper, axis, range }),
        1 => (any::<Index>(), n(), float()).prop_map(|(joint, name, gear)| Action::Motor { joint, name, gear }),
        1 => (any::<Index>(), name(), floats::<4>(), size())
            .prop_map(|(parent, name, rgba, size)| Action::Class { parent, name, rgba, size }),
    ]
}

/// Actions, and the root class name (`None`: unnamed).
fn actions(unnamed: bool) -> impl Strategy<Value = (Option<String>, Vec<Action>)> {
    let root =
        if unnamed { prop::option::of(name()).boxed() } else { name().prop_map(Some).boxed() };
    (root, prop::collection::vec(action(unnamed), 0..32))
}

// ---------------------------------------------------------------------------------
// A mirror of what was built, rendered as MJCF text by hand (for the differential
// check), with a different but equivalent spelling of numbers and keywords.

#[derive(Debug, Default)]
struct XNode {
    tag: &'static str,
    attrs: Vec<(&'static str, String)>,
    children: Vec<usize>,
}

#[derive(Debug, Default)]
struct Mirror {
    nodes: Vec<XNode>,
}

impl Mirror {
    fn push(
        &mut self,
        parent: usize,
        tag: &'static str,
        attrs: Vec<(&'static str, String)>,
    ) -> usize {
        let i = self.nodes.len();
        self.nodes.push(XNode { tag, attrs, children: Vec::new() });
        self.nodes[parent].children.push(i);
        i
    }

    fn render(&self, i: usize, depth: usize, out: &mut String) {
        let n = &self.nodes[i];
        out.push_str(&"\t".repeat(depth));
        out.push('<');
        out.push_str(n.tag);
        for (k, v) in &n.attrs {
            // Single quotes and the spelling `&#38;`, unlike the writer.
            out.push_str(&format!(
                " {k} = '{}'",
                v.replace('&', "&#38;").replace('<', "&lt;").replace('\'', "&apos;")
            ));
        }
        if n.children.is_empty() {
            out.push_str(" />\n");
            return;
        }
        out.push_str(">\n");
        for c in &n.children {
            self.render(*c, depth + 1, out);
        }
        out.push_str(&"\t".repeat(depth));
        out.push_str(&format!("</{}>\n", n.tag));
    }
}

/// A float as other text that reads as the same number (exponent form for some).
fn ftext(x: f64) -> String {
    if x.to_bits() % 3 == 0 { format!("{x:E}") } else { format!("{x:?}") }
}

fn ftexts(xs: &[f64]) -> String {
    xs.iter().map(|x| ftext(*x)).collect::<Vec<_>>().join("  ")
}

fn kw(word: &str, upper: bool) -> String {
    if upper { word.to_ascii_uppercase() } else { word.to_string() }
}

/// A model built from actions, with what the steps need to pick their targets.
struct Built {
    model: Model,
    /// Bodies (not the worldbody), with their mirror nodes.
    bodies: Vec<(Loc, usize)>,
    /// Named joints.
    joints: Vec<String>,
    /// Default classes that can be referenced (named ones), with mirror nodes.
    classes: Vec<(String, usize)>,
    /// Every class that can hold a child class: the root class first.
    class_parents: Vec<(Loc, usize)>,
    mirror: Mirror,
    m_worldbody: usize,
    m_actuator: usize,
    m_default: usize,
    /// Actions refused (an identifier taken).
    refused: usize,
}

impl Built {
    /// The mirror as MJCF text.
    fn text(&self) -> String {
        let mut out =
            String::from("<?xml version='1.0'?>\n<!-- generated -->\n<mujoco model='m'>\n");
        for i in [self.m_default, self.m_worldbody, self.m_actuator] {
            if i == self.m_default || !self.mirror.nodes[i].children.is_empty() {
                self.mirror.render(i, 1, &mut out);
            }
        }
        out.push_str("</mujoco>\n");
        out
    }
}

/// Only a taken identifier (or a body named `world`) may refuse a step.
fn allowed_refusal(e: &EditError) -> bool {
    matches!(
        e.kind(),
        ErrorKind::DuplicateIdentifier { .. }
            | ErrorKind::InvalidValue { error: ValueError::WorldBody, .. }
    )
}

fn build(root_class: &Option<String>, actions: &[Action]) -> Built {
    let model = Model::new("m");
    let mut mirror = Mirror::default();
    mirror.nodes.push(XNode { tag: "mujoco", ..XNode::default() });
    let m_default = mirror.push(0, "default", Vec::new());
    let m_worldbody = mirror.push(0, "worldbody", Vec::new());
    let m_actuator = mirror.push(0, "actuator", Vec::new());
    let mut b = Built {
        bodies: Vec::new(),
        joints: Vec::new(),
        classes: Vec::new(),
        class_parents: vec![(model.default_class(), m_default)],
        model,
        mirror,
        m_worldbody,
        m_actuator,
        m_default,
        refused: 0,
    };
    if let Some(r) = root_class {
        b.model = b.model.set_attr(&b.model.default_class(), "class", r.as_str()).unwrap();
        b.mirror.nodes[m_default].attrs.push(("class", r.clone()));
        b.classes.push((r.clone(), m_default));
    }
    for a in actions {
        apply(&mut b, a);
    }
    b
}

/// The parent picked by `i` among the worldbody and the bodies.
fn body_or_world(b: &Built, i: &Index) -> (Loc, usize) {
    let k = i.index(b.bodies.len() + 1);
    if k == 0 { (b.model.worldbody(), b.m_worldbody) } else { b.bodies[k - 1].clone() }
}

fn named(el: Element, attrs: &mut Vec<(&'static str, String)>, name: &Option<String>) -> Element {
    match name {
        Some(n) => {
            attrs.push(("name", n.clone()));
            el.attr("name", n.as_str())
        }
        None => el,
    }
}

fn apply(b: &mut Built, a: &Action) {
    let mut attrs: Vec<(&'static str, String)> = Vec::new();
    let (parent, m_parent, el, tag) = match a {
        Action::Body { parent, name, pos, childclass } => {
            let (p, mp) = body_or_world(b, parent);
            let mut el = named(Element::new("body"), &mut attrs, name);
            if let Some(c) = childclass.as_ref().filter(|_| !b.classes.is_empty()) {
                let c = &b.classes[c.index(b.classes.len())].0;
                el = el.attr("childclass", c.as_str());
                attrs.push(("childclass", c.clone()));
            }
            attrs.push(("pos", ftexts(pos)));
            (p, mp, el.attr("pos", *pos), "body")
        }
        Action::Geom { parent, name, ty, upper, size, class } => {
            let (p, mp) = body_or_world(b, parent);
            let mut el = named(Element::new("geom"), &mut attrs, name);
            if let Some(c) = class.as_ref().filter(|_| !b.classes.is_empty()) {
                let c = &b.classes[c.index(b.classes.len())].0;
                el = el.attr("class", c.as_str());
                attrs.push(("class", c.clone()));
            }
            attrs.push(("type", kw(ty, *upper)));
            attrs.push(("size", ftexts(size)));
            (p, mp, el.attr("type", kw(ty, *upper)).attr("size", size.clone()), "geom")
        }
        Action::Site { parent, name, pos, size } => {
            let (p, mp) = body_or_world(b, parent);
            let el = named(Element::new("site"), &mut attrs, name);
            attrs.push(("pos", ftexts(pos)));
            attrs.push(("size", ftexts(size)));
            (p, mp, el.attr("pos", *pos).attr("size", size.clone()), "site")
        }
        Action::Joint { parent, name, ty, upper, axis, range } => {
            if b.bodies.is_empty() {
                return;
            }
            let (p, mp) = b.bodies[parent.index(b.bodies.len())].clone();
            let mut el = named(Element::new("joint"), &mut attrs, name)
                .attr("type", kw(ty, *upper))
                .attr("axis", *axis);
            attrs.push(("type", kw(ty, *upper)));
            attrs.push(("axis", ftexts(axis)));
            if let Some(r) = range {
                el = el.attr("range", *r);
                attrs.push(("range", ftexts(r)));
            }
            (p, mp, el, "joint")
        }
        Action::Motor { joint, name, gear } => {
            if b.joints.is_empty() {
                return;
            }
            let j = b.joints[joint.index(b.joints.len())].clone();
            let el = named(Element::new("motor"), &mut attrs, name)
                .attr("joint", j.as_str())
                .attr("gear", [*gear]);
            attrs.push(("joint", j));
            attrs.push(("gear", ftext(*gear)));
            (b.model.actuator(), b.m_actuator, el, "motor")
        }
        Action::Class { parent, name, rgba, size } => {
            let (p, mp) = b.class_parents[parent.index(b.class_parents.len())].clone();
            let el = Element::new("default")
                .attr("class", name.as_str())
                .child(Element::new("geom").attr("rgba", *rgba).attr("size", size.clone()));
            attrs.push(("class", name.clone()));
            match b.model.add(&p, el) {
                Ok((m, loc)) => {
                    b.model = m;
                    let i = b.mirror.push(mp, "default", attrs);
                    b.mirror.push(i, "geom", vec![("rgba", ftexts(rgba)), ("size", ftexts(size))]);
                    b.classes.push((name.clone(), i));
                    b.class_parents.push((loc, i));
                }
                Err(e) => {
                    assert!(allowed_refusal(&e), "{a:?}: {e}");
                    b.refused += 1;
                }
            }
            return;
        }
    };
    match b.model.add(&parent, el) {
        Ok((m, loc)) => {
            b.model = m;
            let i = b.mirror.push(m_parent, tag, attrs);
            match a {
                Action::Body { .. } => b.bodies.push((loc, i)),
                Action::Joint { name: Some(n), .. } => b.joints.push(n.clone()),
                _ => {}
            }
        }
        Err(e) => {
            assert!(allowed_refusal(&e), "{a:?}: {e}");
            b.refused += 1;
        }
    }
}

// ---------------------------------------------------------------------------------
// Helpers over models.

/// Every element with its ancestors (root first), in document order.
fn elements_with_ancestry(model: &Model) -> Vec<(Loc, Vec<Loc>)> {
    fn walk(e: ElementRef<'_>, above: &mut Vec<Loc>, out: &mut Vec<(Loc, Vec<Loc>)>) {
        out.push((e.loc(), above.clone()));
        above.push(e.loc());
        for c in e.children() {
            walk(c, above, out);
        }
        above.pop();
    }
    let mut out = Vec::new();
    walk(model.element(&model.root()).unwrap(), &mut Vec::new(), &mut out);
    out
}

/// Every named element: (namespace, name, loc).
fn names(model: &Model) -> Vec<(Namespace, String, Loc)> {
    elements_with_ancestry(model)
        .into_iter()
        .filter_map(|(l, _)| {
            let e = model.element(&l)?;
            Some((e.kind().namespace()?, e.identifier()?.to_string(), l))
        })
        .collect()
}

/// The elements of the worldbody's subtree (not the worldbody).
fn world_elements(model: &Model) -> Vec<Loc> {
    let wb = model.worldbody();
    elements_with_ancestry(model)
        .into_iter()
        .filter(|(_, above)| above.contains(&wb))
        .map(|(l, _)| l)
        .collect()
}

fn write(model: &Model) -> String {
    model.to_xml_string().unwrap_or_else(|e| panic!("cannot write: {e}"))
}

// ---------------------------------------------------------------------------------
// a. Round trips.

proptest! {
    #![proptest_config(config())]

    /// Reading MJCF text rendered by hand from the same steps (other quoting, tabs,
    /// exponent floats, upper-case keywords, a declaration and a comment) gives the
    /// same output as building the model through the API. A root class named through
    /// the API has no such text: rendered on the top-level `<default>`, it is what
    /// MuJoCo refuses, and so does the reader (decision D16).
    #[test]
    fn reading_rendered_text_equals_building_through_the_api((root, acts) in actions(true)) {
        let b = build(&root, &acts);
        let text = b.text();
        let read = Model::from_xml_str(&text);
        if let Some(name) = root.filter(|r| r != "main") {
            let refused = read.err().map(|e| e.kind().clone());
            prop_assert_eq!(refused, Some(mjcf::ErrorKind::RootClassRenamed(name.into())), "text:\n{}", text);
            return Ok(());
        }
        let read = read.map_err(|e| TestCaseError::fail(format!("{e}\n{text}")))?;
        prop_assert_eq!(write(&read), write(&b.model), "text:\n{}", text);
        let one_line = WriteOptions { pretty_print: false, precision: Some(17), ..WriteOptions::default() };
        prop_assert_eq!(read.to_xml_string_with(&one_line).unwrap(), b.model.to_xml_string_with(&one_line).unwrap());
    }
}

/// The fixed point: write(read(write(m))) == write(m) when the root class is unnamed.
/// A named root class `R` is written, as dm_control writes it, as
/// `<default><default class="R">`, which MJCF reads as a class nested in the unnamed
/// root class; the reader reads it so (guessing would change what hand-written models
/// mean), so the next write gains one level and the one after that is the fixed point.
#[test]
fn write_read_write_is_a_fixed_point() {
    let mut runner = proptest::test_runner::TestRunner::new(config());
    runner
        .run(&actions(true), |(root, acts)| {
            let b = build(&root, &acts);
            let w1 = write(&b.model);
            let w2 = write(
                &Model::from_xml_str(&w1).map_err(|e| TestCaseError::fail(format!("{e}\n{w1}")))?,
            );
            if root.is_none() {
                prop_assert_eq!(w2, w1);
            } else {
                prop_assert_eq!(&w2, &text::rewrapped_root_default(&w1));
                let w3 = write(
                    &Model::from_xml_str(&w2)
                        .map_err(|e| TestCaseError::fail(format!("{e}\n{w2}")))?,
                );
                prop_assert_eq!(w3, w2);
            }
            Ok(())
        })
        .unwrap();
}

/// The smallest instances of the above: an unnamed and a named root class.
#[test]
fn written_empty_models_read_back_unchanged() {
    let m = Model::new("m");
    let w = write(&m);
    assert_eq!(write(&Model::from_xml_str(&w).unwrap()), w);
    let m = m.set_attr(&m.default_class(), "class", "root_class").unwrap();
    let w = write(&m);
    let again = write(&Model::from_xml_str(&w).unwrap());
    assert_eq!(again, text::rewrapped_root_default(&w));
    assert_eq!(write(&Model::from_xml_str(&again).unwrap()), again);
    // A root class named `main` is MuJoCo's main class itself (decision D9): written as
    // the outer `<default class="main">`, it reads back named so, and writes the same.
    let main = m.set_attr(&m.default_class(), "class", "main").unwrap();
    let w = write(&main);
    assert!(w.contains("  <default class=\"main\">\n  </default>"), "{w}");
    assert_eq!(write(&Model::from_xml_str(&w).unwrap()), w);
}

// ---------------------------------------------------------------------------------
// b. Persistence and structural sharing.

#[derive(Clone, Debug)]
enum Edit {
    SetPos { target: Index, pos: [f64; 3] },
    SetRgba { target: Index, rgba: [f64; 4] },
    ClearPos { target: Index },
    Add { parent: Index, name: Option<String>, size: f64 },
    Remove { target: Index },
    Rename { target: Index, name: Option<String> },
    ModelName { name: Option<String> },
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<Index>(), floats::<3>()).prop_map(|(target, pos)| Edit::SetPos { target, pos }),
        (any::<Index>(), floats::<4>()).prop_map(|(target, rgba)| Edit::SetRgba { target, rgba }),
        any::<Index>().prop_map(|target| Edit::ClearPos { target }),
        (any::<Index>(), maybe_name(true), float()).prop_map(|(parent, name, size)| Edit::Add {
            parent,
            name,
            size
        }),
        any::<Index>().prop_map(|target| Edit::Remove { target }),
        (any::<Index>(), maybe_name(true)).prop_map(|(target, name)| Edit::Rename { target, name }),
        maybe_name(true).prop_map(|name| Edit::ModelName { name }),
    ]
}

/// Applies an edit; returns the element whose path to the root the edit copies (the
/// edited element, or the parent for an add), and the result. `None`: nothing to edit.
fn apply_edit(m: &Model, e: &Edit) -> Option<(Loc, Result<Model, EditError>)> {
    let targets = world_elements(m);
    let pick = |i: &Index| (!targets.is_empty()).then(|| targets[i.index(targets.len())].clone());
    Some(match e {
        Edit::SetPos { target, pos } => {
            let t = pick(target)?;
            (t.clone(), m.set_attr(&t, "pos", *pos))
        }
        Edit::SetRgba { target, rgba } => {
            let t = pick(target)?;
            let attrs = match m.element(&t)?.tag() {
                "geom" | "site" => Attrs::new().set("rgba", *rgba).clear("material"),
                _ => Attrs::new().set("pos", [rgba[0], rgba[1], rgba[2]]),
            };
            (t.clone(), m.set(&t, attrs))
        }
        Edit::ClearPos { target } => {
            let t = pick(target)?;
            (t.clone(), m.clear_attr(&t, "pos"))
        }
        Edit::Add { parent, name, size } => {
            let mut parents: Vec<Loc> =
                targets.iter().filter(|l| m.element(l).unwrap().tag() == "body").cloned().collect();
            parents.push(m.worldbody());
            let p = parents[parent.index(parents.len())].clone();
            let mut el = Element::new("geom").attr("size", [*size]);
            if let Some(n) = name {
                el = el.attr("name", n.as_str());
            }
            (p.clone(), m.add(&p, el).map(|(m, _)| m))
        }
        Edit::Remove { target } => {
            let t = pick(target)?;
            (t.clone(), m.remove(&t))
        }
        Edit::Rename { target, name } => {
            let t = pick(target)?;
            let r = match name {
                Some(n) => m.set_attr(&t, "name", n.as_str()),
                None => m.clear_attr(&t, "name"),
            };
            (t, r)
        }
        Edit::ModelName { name } => (m.root(), Ok(m.with_name(name.as_deref().unwrap_or("")))),
    })
}

proptest! {
    #![proptest_config(config())]

    /// Every edit leaves the value it was applied to unchanged (value, text and name
    /// index), and the new value shares every element off the edited path: in
    /// particular, every other top-level body is the same node.
    #[test]
    fn edits_leave_old_values_unchanged_and_share_untouched_subtrees(
        (root, acts) in actions(true),
        edits in prop::collection::vec(edit(), 1..10),
    ) {
        let b = build(&root, &acts);
        let mut history: Vec<(Model, String)> = Vec::new();
        let mut current = b.model.clone();
        for e in &edits {
            let before = current.clone();
            let snapshot = before.clone();
            let text_before = write(&before);
            let names_before = names(&before);
            let Some((anchor, result)) = apply_edit(&before, e) else { continue };

            // The old value is unchanged, whether the edit worked or not.
            prop_assert!(before == snapshot);
            prop_assert!(before.ptr_eq(&snapshot));
            prop_assert_eq!(write(&before), text_before.clone());
            for (ns, name, loc) in &names_before {
                prop_assert_eq!(before.find(*ns, name), Some(loc.clone()));
            }

            let new = match result {
                Ok(m) => m,
                Err(err) => {
                    prop_assert!(allowed_refusal(&err), "{:?}: {}", e, err);
                    continue;
                }
            };

            // Sharing: every element that is neither on the path from the root to the
            // anchor nor (for a remove) inside the removed subtree is the same node.
            let all = elements_with_ancestry(&before);
            let on_path: HashSet<Loc> = all
                .iter()
                .find(|(l, _)| *l == anchor)
                .map(|(l, above)| above.iter().cloned().chain([l.clone()]).collect())
                .unwrap_or_default();
            let removed = matches!(e, Edit::Remove { .. });
            for (l, above) in &all {
                let in_removed = removed && (*l == anchor || above.contains(&anchor));
                let old_el = before.element(l).unwrap();
                match new.element(l) {
                    None => prop_assert!(in_removed, "{:?} lost {:?} ({})", e, l, old_el.tag()),
                    Some(new_el) => {
                        prop_assert!(!in_removed, "{:?} kept {:?}", e, l);
                        if !on_path.contains(l) {
                            prop_assert!(new_el.ptr_eq(&old_el), "{:?}: untouched <{}> {:?} was copied", e, old_el.tag(), l);
                        }
                    }
                }
            }
            // The same, said the way users see it: the other top-level bodies.
            let wb = before.worldbody();
            let top: Vec<Loc> = before.element(&wb).unwrap().children().map(|c| c.loc()).collect();
            for t in &top {
                if on_path.contains(t) {
                    continue;
                }
                let (old_t, new_t) = (before.element(t).unwrap(), new.element(t).unwrap());
                prop_assert!(new_t.ptr_eq(&old_t));
            }
            // What the edit did is visible in the new value only.
            if let Edit::Rename { name: Some(n), .. } = e {
                let ns = new.element(&anchor).unwrap().kind().namespace().unwrap();
                prop_assert_eq!(new.find(ns, n), Some(anchor.clone()));
            }
            history.push((before, text_before));
            current = new;
        }
        // Every version is still what it was.
        for (m, text) in &history {
            prop_assert_eq!(&write(m), text);
        }
    }
}

// ---------------------------------------------------------------------------------
// c. Any legal identifier survives writing and reading.

/// Identifier characters: every character XML 1.0 can hold but '/'. The writer
/// escapes tab, CR and LF as character references (`&#9;`), which attribute-value
/// normalization leaves alone, so they survive. Characters XML cannot hold are
/// refused (see `characters_xml_cannot_hold_are_refused`).
/// XML 1.0's `Char` production.
fn is_xml_char(c: char) -> bool {
    matches!(c, '\t' | '\n' | '\r' | '\u{20}'..='\u{D7FF}' | '\u{E000}'..='\u{FFFD}' | '\u{10000}'..)
}

fn ident_char() -> impl Strategy<Value = char> {
    prop_oneof![
        4 => prop::char::range(' ', '~').prop_filter("no slash", |c| *c != '/'),
        3 => prop::sample::select(vec![' ', '\t', '\n', '\r', '"', '\'', '&', '<', '>', ';', '#', '=', '\\', ':']),
        2 => prop::sample::select(vec!['é', 'ß', 'Ω', '中', '€', '\u{a0}', '\u{2028}', '\u{feff}', '\u{fffd}', '😀', '\u{10ffff}', '\u{7f}', '\u{85}']),
        1 => prop::sample::select(vec!['\u{fffd}', '\u{d7ff}', '\u{e000}', '\u{10000}']),
        1 => any::<char>().prop_filter("legal", |c| *c != '/' && is_xml_char(*c)),
    ]
}

fn identifier() -> impl Strategy<Value = String> {
    prop::collection::vec(ident_char(), 1..12).prop_map(String::from_iter)
}

proptest! {
    #![proptest_config(config())]

    /// A body, geom, joint, motor (naming the joint), root default class and model,
    /// all named with the same random identifier, are found again after writing and
    /// reading, and the references still point at their targets.
    #[test]
    fn any_legal_identifier_survives_write_and_read(id in identifier(), pretty in any::<bool>()) {
        let m = Model::new("m").with_name(&id);
        let m = m.set_attr(&m.default_class(), "class", id.as_str()).unwrap();
        let body_name = if id == "world" { "not world" } else { id.as_str() };
        let (m, _) = m
            .add(
                &m.worldbody(),
                Element::new("body")
                    .attr("name", body_name)
                    .child(Element::new("joint").attr("name", id.as_str()))
                    .child(Element::new("geom").attr("name", id.as_str()).attr("size", [0.1]).attr("class", id.as_str())),
            )
            .unwrap();
        let (m, _) = m.add(&m.actuator(), Element::new("motor").attr("name", id.as_str()).attr("joint", id.as_str())).unwrap();
        let text = m.to_xml_string_with(&WriteOptions { pretty_print: pretty, ..WriteOptions::default() }).unwrap();
        let back = Model::from_xml_str(&text).map_err(|e| TestCaseError::fail(format!("{e}\n{text}")))?;

        prop_assert_eq!(back.name(), id.as_str());
        let body = back.find(Namespace::Body, body_name);
        prop_assert!(body.is_some(), "body {:?} lost in\n{}", body_name, text);
        prop_assert_eq!(back.element(&body.unwrap()).unwrap().identifier(), Some(body_name));
        let mut locs = HashMap::new();
        for ns in [Namespace::Geom, Namespace::Joint, Namespace::Actuator, Namespace::Default] {
            let l = back.find(ns, &id);
            prop_assert!(l.is_some(), "{:?} {:?} lost in\n{}", ns, id, text);
            let l = l.unwrap();
            prop_assert_eq!(back.element(&l).unwrap().identifier(), Some(id.as_str()));
            locs.insert(ns, l);
        }
        // References were resolved to the elements they name.
        let motor = back.element(&locs[&Namespace::Actuator]).unwrap();
        prop_assert_eq!(motor.attr("joint"), Some(&Value::Reference(Reference::Element(locs[&Namespace::Joint].id()))));
        let geom = back.element(&locs[&Namespace::Geom]).unwrap();
        prop_assert_eq!(geom.attr("class"), Some(&Value::Reference(Reference::Element(locs[&Namespace::Default].id()))));
    }
}

/// Characters XML cannot hold (NUL, other control characters, U+FFFF) are refused
/// by edits and by the reader with a typed error, so every value that is set can be
/// written and read back; a model name (which cannot refuse) fails at write time.
#[test]
fn characters_xml_cannot_hold_are_refused() {
    let m = Model::new("m");
    for bad in ["a\0b", "\u{1}", "x\u{1f}", "\u{FFFF}"] {
        let err = m.add(&m.worldbody(), Element::new("body").attr("name", bad)).unwrap_err();
        assert!(
            matches!(
                err.kind(),
                ErrorKind::InvalidValue {
                    attribute: "name",
                    error: ValueError::InvalidCharacter(_),
                    ..
                }
            ),
            "{err}"
        );
        let err = m.set_attr(&m.default_class(), "class", bad).unwrap_err();
        assert!(
            matches!(
                err.kind(),
                ErrorKind::InvalidValue { error: ValueError::InvalidCharacter(_), .. }
            ),
            "{err}"
        );
        let text = format!("<mujoco><worldbody><body name=\"{bad}\"/></worldbody></mujoco>");
        match Model::from_xml_str(&text) {
            Err(e) => assert!(e.pos().is_some(), "{e}"),
            Ok(_) => panic!("{bad:?} was read"),
        }
        let named = m.with_name(bad);
        assert!(matches!(
            named.to_xml_string(),
            Err(mjcf::WriteError::InvalidCharacter { attribute: "model", .. })
        ));
    }
    // Tab, newline and carriage return are XML characters: they survive as references.
    let (m, _) = m.add(&m.worldbody(), Element::new("body").attr("name", "a\tb\nc\rd")).unwrap();
    let text = write(&m);
    assert!(text.contains(r#"name="a&#9;b&#10;c&#13;d""#), "{text}");
    assert!(Model::from_xml_str(&text).unwrap().find(Namespace::Body, "a\tb\nc\rd").is_some());
}

// ---------------------------------------------------------------------------------
// d. Models are shareable across threads.

const _: () = {
    const fn assert_send_sync<T: Send + Sync>() {}
    assert_send_sync::<Model>();
    assert_send_sync::<Loc>();
    assert_send_sync::<ElementRef<'static>>();
    assert_send_sync::<mjcf::ReadError>();
    assert_send_sync::<EditError>();
};

#[test]
fn models_move_between_threads() {
    let m0 = Model::new("m");
    let (m, _) = m0.add(&m0.worldbody(), Element::new("body").attr("name", "b")).unwrap();
    let shared = std::sync::Arc::new(m.clone());
    let handles: Vec<_> = (0..4)
        .map(|i| {
            let s = shared.clone();
            std::thread::spawn(move || {
                let b = s.find(Namespace::Body, "b").unwrap();
                s.set_attr(&b, "pos", [f64::from(i), 0.0, 0.0]).unwrap().to_xml_string().unwrap()
            })
        })
        .collect();
    let texts: Vec<String> = handles.into_iter().map(|h| h.join().unwrap()).collect();
    assert_eq!(texts.iter().collect::<HashSet<_>>().len(), 4);
    assert_eq!(write(&m), write(&shared));
}
