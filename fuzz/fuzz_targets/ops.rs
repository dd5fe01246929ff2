//! Structured fuzzing of the editing and composition API: a sequence of operations
//! (add, set, remove, attach, detach, rename_scope, include_copy, ...) applied to a
//! model, keeping every version produced. The model starts as a small arena, or as a
//! model built from a generated recipe (`mjcf::generate::ModelRecipe`, feature
//! `arbitrary`); operations include hostile ones (names with `/`, NaN, unknown
//! keywords) and the generators' own edits (`mjcf::generate::Edit`) and recipes.
//!
//! After every step, at a cost of O(size of the model), not O(history × size):
//! (a) earlier versions still write what they wrote when they were made (values are
//!     persistent): in turn, the version the step started from, or one earlier
//!     version picked at random, is written again and compared with the hash of its
//!     first output;
//! (b) the new version's output, if it writes, reads back (`Model::from_xml_str`;
//!     a composed model's scoped names such as `robot/torso` read as literal names)
//!     and write∘read reaches its fixed point (`common::check_fixed_point` for a model
//!     without attachments; for a composed one, the text written from the read-back
//!     is written again unchanged). Reading back costs about three writes, so it is
//!     checked every `READ_BACK_EVERY` steps and for the version the input ends with
//!     (every prefix of an input is an input libFuzzer tries too);
//! (c) identifiers in the output are unique per namespace;
//! (d) a failed operation changed nothing: the model it was applied to writes as
//!     before;
//! (e) a model built from a recipe, and what the generators' edits make of a model
//!     without problems, has no `Model::check` problems.
//! Also: writing never fails with `WriteError::Conflict` (edits refuse conflicting
//! settings), and detaching a fresh attachment gives back the model before the
//! attach.

#![no_main]

mod common;
#[path = "../../tests/support/robot.rs"]
mod shared_robot;

use std::collections::hash_map::DefaultHasher;
use std::hash::{Hash, Hasher};

use arbitrary::Arbitrary;
use libfuzzer_sys::fuzz_target;
use mjcf::generate::{Edit, EditRecipe, ModelRecipe, Step};
use mjcf::{Attrs, EditError, Element, Loc, Model, Namespace, ReadOptions, WriteError};

/// Steps per input.
const MAX_OPS: usize = 8;
/// The new version's read-back (b) is checked every this many steps, and for the
/// version an input ends with.
const READ_BACK_EVERY: usize = 4;
/// Outputs above this size end the input (attaching a model to itself doubles it).
const MAX_XML: usize = 64 * 1024;

const NAMES: &[&str] = &[
    "",
    "a",
    "b",
    "torso",
    "hip",
    "mount",
    "robot",
    "robot_1",
    "arm",
    "world",
    "main",
    "/",
    "a/b",
    "robot/",
    "//unnamed_geom_0",
    "unnamed_model",
    "x y",
    "é",
    "<&'\">",
    "\u{0}",
    "\t",
    "0",
];

const NUMBERS: &[f64] = &[
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.1,
    0.5,
    2.0,
    1.0 / 3.0,
    1e-300,
    5e-324,
    1e300,
    1e21,
    f64::MAX,
    f64::MIN,
    f64::MIN_POSITIVE,
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
];

#[derive(Arbitrary, Debug, Clone)]
enum Name {
    Pick(u8),
    Free(String),
}

impl Name {
    fn get(&self) -> String {
        match self {
            Name::Pick(i) => NAMES[*i as usize % NAMES.len()].to_string(),
            Name::Free(s) => s.chars().take(8).collect(),
        }
    }
}

#[derive(Arbitrary, Debug, Clone, Copy)]
enum Num {
    Pick(u8),
    Raw(f64),
}

impl Num {
    fn get(self) -> f64 {
        match self {
            Num::Pick(i) => NUMBERS[i as usize % NUMBERS.len()],
            Num::Raw(x) => x,
        }
    }
}

#[derive(Arbitrary, Debug, Clone)]
enum Val {
    Text(Name),
    Number(Num),
    Numbers(Vec<Num>),
    Bool(bool),
    Clear,
}

#[derive(Arbitrary, Debug, Clone, Copy)]
enum AttrName {
    Pos,
    Size,
    Rgba,
    Name,
    Type,
    Class,
    Childclass,
    Joint,
    Site,
    Quat,
    Euler,
    Mass,
    Range,
    Mocap,
    Material,
    Timestep,
    Angle,
    Model,
}

impl AttrName {
    fn get(self) -> &'static str {
        match self {
            AttrName::Pos => "pos",
            AttrName::Size => "size",
            AttrName::Rgba => "rgba",
            AttrName::Name => "name",
            AttrName::Type => "type",
            AttrName::Class => "class",
            AttrName::Childclass => "childclass",
            AttrName::Joint => "joint",
            AttrName::Site => "site",
            AttrName::Quat => "quat",
            AttrName::Euler => "euler",
            AttrName::Mass => "mass",
            AttrName::Range => "range",
            AttrName::Mocap => "mocap",
            AttrName::Material => "material",
            AttrName::Timestep => "timestep",
            AttrName::Angle => "angle",
            AttrName::Model => "model",
        }
    }
}

const TYPES: &[&str] = &["sphere", "box", "capsule", "plane", "hinge", "slide", "ball", "free", "BOX", "bogus", ""];

#[derive(Arbitrary, Debug, Clone)]
enum NewElement {
    Body { name: Name, geom: bool },
    Geom { name: Name, ty: u8, size: Num },
    Site { name: Name },
    Joint { name: Name, ty: u8 },
    Freejoint { name: Name },
    Inertial { mass: Num },
    Camera { name: Name },
    Motor { name: Name, joint: Name },
    Position { name: Name, joint: Name },
    Touch { name: Name, site: Name },
    Material { name: Name },
    DefaultClass { class: Name },
}

impl NewElement {
    fn build(&self) -> Element {
        match self {
            NewElement::Body { name, geom } => {
                let b = Element::new("body").attr("name", name.get());
                if *geom { b.child(Element::new("geom").attr("size", [0.1])) } else { b }
            }
            NewElement::Geom { name, ty, size } => Element::new("geom")
                .attr("name", name.get())
                .attr("type", TYPES[*ty as usize % TYPES.len()])
                .attr("size", [size.get()]),
            NewElement::Site { name } => Element::new("site").attr("name", name.get()),
            NewElement::Joint { name, ty } => {
                Element::new("joint").attr("name", name.get()).attr("type", TYPES[*ty as usize % TYPES.len()])
            }
            NewElement::Freejoint { name } => Element::new("freejoint").attr("name", name.get()),
            NewElement::Inertial { mass } => {
                Element::new("inertial").attr("pos", [0.0, 0.0, 0.0]).attr("mass", mass.get())
            }
            NewElement::Camera { name } => Element::new("camera").attr("name", name.get()),
            NewElement::Motor { name, joint } => {
                Element::new("motor").attr("name", name.get()).attr("joint", joint.get())
            }
            NewElement::Position { name, joint } => {
                Element::new("position").attr("name", name.get()).attr("joint", joint.get()).attr("kp", 10.0)
            }
            NewElement::Touch { name, site } => Element::new("touch").attr("name", name.get()).attr("site", site.get()),
            NewElement::Material { name } => Element::new("material").attr("name", name.get()),
            NewElement::DefaultClass { class } => Element::new("default")
                .attr("class", class.get())
                .child(Element::new("geom").attr("rgba", [1.0, 0.0, 0.0, 1.0])),
        }
    }
}

#[derive(Arbitrary, Debug, Clone)]
enum Op {
    /// Add an element to a container chosen by index.
    Add {
        parent: u16,
        element: NewElement,
    },
    /// Insert at a position among the parent's children.
    Insert {
        parent: u16,
        index: u8,
        element: NewElement,
    },
    /// Set or clear up to a few attributes of an element chosen by index.
    Set {
        target: u16,
        attrs: Vec<(AttrName, Val)>,
    },
    /// Remove an element chosen by index.
    Remove {
        target: u16,
        with_attachments: bool,
    },
    /// Attach one of the robots at a site chosen by index, or at the world.
    Attach {
        robot: u8,
        at: Option<u16>,
    },
    /// Attach an earlier version (possibly with attachments of its own).
    AttachVersion {
        version: u16,
        at: Option<u16>,
    },
    /// Detach a scope path chosen by index.
    Detach {
        scope: u16,
    },
    RenameScope {
        scope: u16,
        to: Name,
    },
    /// include_copy one of the small source models.
    IncludeCopy {
        source: u8,
        override_attributes: bool,
    },
    /// include_copy an earlier version (refused if it has attachments).
    IncludeCopyVersion {
        version: u16,
        override_attributes: bool,
    },
    /// An edit inside an attachment through `edit_attached`.
    EditAttached {
        scope: u16,
        element: NewElement,
    },
    WithName {
        name: Name,
    },
    /// Go on from an earlier version.
    Revert {
        version: u16,
    },
    /// Write with other options (must not panic).
    Write {
        pretty: bool,
        precision: Option<u8>,
    },
    /// One edit of the generators (`mjcf::generate::Edit`).
    Generated(Edit),
    /// Attach a model built from a recipe at a site chosen by index, or at the world.
    AttachRecipe {
        recipe: ModelRecipe,
        at: Option<u16>,
    },
}

/// The input: where to start (a fixed arena, or a model built from a recipe) and the
/// operations.
#[derive(Arbitrary, Debug)]
struct Input {
    base: Option<ModelRecipe>,
    ops: Vec<Op>,
}

/// Steps kept of a recipe, at every level (so one input builds in bounded time).
const RECIPE_STEPS: usize = 12;

/// The recipe with at most `RECIPE_STEPS` steps at each level, attached recipes too.
fn clip(r: &ModelRecipe) -> ModelRecipe {
    let mut r = r.clone();
    r.steps.truncate(RECIPE_STEPS);
    for s in &mut r.steps {
        if let Step::Attach { child, .. } = s {
            **child = clip(child);
        }
    }
    r
}

fn clip_edit(e: &Edit) -> Edit {
    match e {
        Edit::Add(Step::Attach { at, child, frame }) => {
            Edit::Add(Step::Attach { at: *at, child: Box::new(clip(child)), frame: frame.clone() })
        }
        Edit::IncludeCopy { source, override_attributes } => {
            Edit::IncludeCopy { source: clip(source), override_attributes: *override_attributes }
        }
        e => e.clone(),
    }
}

/// The shared test robot (`tests/support/robot.rs`) with a touch sensor on its site.
fn robot(name: &str) -> Model {
    let m = shared_robot::robot(name);
    let (m, _) = m.add(&m.sensor(), Element::new("touch").attr("name", "t").attr("site", "mount")).unwrap();
    m
}

/// The models `Attach` picks from.
fn robots() -> Vec<Model> {
    let arm = robot("arm");
    let arm = arm.set_attr(&arm.section("option").unwrap(), "timestep", 0.002).unwrap();
    let (arm, _) = arm
        .add(
            &arm.default_class(),
            Element::new("default").attr("class", "arm").child(Element::new("geom").attr("rgba", [0.0, 1.0, 0.0, 1.0])),
        )
        .unwrap();
    let radian = Model::new("radian");
    let radian = radian.set_attr(&radian.section("compiler").unwrap(), "angle", "radian").unwrap();
    let degree = Model::new("degree");
    let degree = degree.set_attr(&degree.section("compiler").unwrap(), "angle", "degree").unwrap();
    let named_root = robot("named");
    let named_root = named_root.set_attr(&named_root.default_class(), "class", "main").unwrap();
    let site_only = Model::new("robot");
    let (site_only, _) = site_only.add(&site_only.worldbody(), Element::new("site").attr("name", "spot")).unwrap();
    let read = Model::from_xml_str(READ_ROBOT).unwrap();
    vec![robot("robot"), arm, Model::new(""), radian, degree, named_root, site_only, read, Model::new("bad/name")]
}

/// A robot read from text: its references are resolved to elements, so removing a
/// target leaves a dead reference.
const READ_ROBOT: &str = r#"<mujoco model="leg">
  <default><default class="leg"><joint damping="1"/></default></default>
  <worldbody>
    <body name="thigh" childclass="leg">
      <joint name="knee" type="hinge"/>
      <geom name="shin" size="0.1"/>
      <site name="foot"/>
    </body>
  </worldbody>
  <actuator><motor name="knee" joint="knee"/></actuator>
  <sensor><touch site="foot"/></sensor>
</mujoco>"#;

/// The models `IncludeCopy` picks from.
fn sources() -> Vec<Model> {
    let inc = Model::new("inc");
    let (inc, _) = inc.add(&inc.worldbody(), Element::new("geom").attr("name", "inc").attr("size", [0.2])).unwrap();
    let mat = Model::new("mat");
    let (mat, _) = mat.add(&mat.asset(), Element::new("material").attr("name", "red")).unwrap();
    let (mat, _) = mat
        .add(&mat.worldbody(), Element::new("geom").attr("name", "painted").attr("material", "red").attr("size", [1.0]))
        .unwrap();
    let opt = Model::new("opt");
    let opt = opt.set_attr(&opt.section("option").unwrap(), "timestep", 0.01).unwrap();
    let class = Model::new("class");
    let (class, _) = class
        .add(&class.default_class(), Element::new("default").attr("class", "main").child(Element::new("geom")))
        .unwrap();
    let named = Model::new("named");
    let named = named.set_attr(&named.default_class(), "class", "top").unwrap();
    vec![inc, mat, opt, class, named, Model::from_xml_str(READ_ROBOT).unwrap(), robot("robot")]
}

const SECTIONS: &[&str] = &["worldbody", "actuator", "sensor", "asset", "default", "option", "compiler", "size"];

/// The sections of the model and of every model attached to it.
fn sections(m: &Model) -> Vec<Loc> {
    let mut out: Vec<Loc> = SECTIONS.iter().filter_map(|s| m.section(s)).collect();
    for scope in m.scope_paths() {
        let Ok(inner) = m.attached(&scope) else { continue };
        for s in SECTIONS {
            if let Some(l) = inner.section(s).and_then(|l| m.locate_in(&scope, &l).ok()) {
                out.push(l);
            }
        }
    }
    out
}

/// Places to add elements: sections, bodies (frames included) and default classes.
fn containers(m: &Model) -> Vec<Loc> {
    let mut out = sections(m);
    out.extend(in_namespaces(m, &[Namespace::Body, Namespace::Default]));
    out
}

/// Elements to set or remove: the root, the sections and the elements of the main
/// namespaces, inside attachments too.
fn elements(m: &Model) -> Vec<Loc> {
    let mut out = vec![m.root()];
    out.extend(sections(m));
    out.extend(in_namespaces(
        m,
        &[
            Namespace::Body,
            Namespace::Joint,
            Namespace::Geom,
            Namespace::Site,
            Namespace::Camera,
            Namespace::Actuator,
            Namespace::Sensor,
            Namespace::Material,
            Namespace::Default,
        ],
    ));
    out
}

/// The elements of these namespaces (frames count as bodies), in walk order: one
/// walk, where `find_all` per namespace would take one each.
fn in_namespaces(m: &Model, namespaces: &[Namespace]) -> Vec<Loc> {
    m.walk()
        .filter_map(|e| match e {
            mjcf::Event::Enter(e) if e.kind().namespace().is_some_and(|ns| namespaces.contains(&ns)) => Some(e.loc()),
            _ => None,
        })
        .collect()
}

fn pick<T: Clone>(items: &[T], i: u16) -> Option<T> {
    if items.is_empty() { None } else { Some(items[i as usize % items.len()].clone()) }
}

/// A version, and the hash of what it wrote when it was made.
struct Version {
    model: Model,
    hash: Result<u64, String>,
    /// The size of its output, for `AttachVersion`.
    len: usize,
}

fn written(m: &Model) -> Result<String, WriteError> {
    let xml = m.to_xml_string();
    if let Err(e @ WriteError::Conflict(_)) = &xml {
        panic!("a value built by edits has conflicting settings: {e}");
    }
    xml
}

/// The hash of an output (or its error's text).
fn hash_of(xml: &Result<String, WriteError>) -> Result<u64, String> {
    match xml {
        Ok(x) => {
            let mut h = DefaultHasher::new();
            x.hash(&mut h);
            Ok(h.finish())
        }
        Err(e) => Err(e.to_string()),
    }
}

impl Version {
    fn new(model: Model, xml: &Result<String, WriteError>) -> Version {
        Version { model, hash: hash_of(xml), len: xml.as_ref().map_or(0, String::len) }
    }

    /// Writes the version again: it must write what it wrote when it was made.
    fn check(&self, what: &str) {
        assert!(hash_of(&written(&self.model)) == self.hash, "{what} changed: it no longer writes what it wrote");
    }
}

/// The models `Attach` and `IncludeCopy` pick from, built once, with their outputs,
/// and the arena most inputs start from, with its output.
struct Fixtures {
    robots: Vec<Model>,
    sources: Vec<Model>,
    written: Vec<Result<String, WriteError>>,
    arena: Model,
    arena_xml: Result<String, WriteError>,
}

fn fixtures() -> &'static Fixtures {
    static FIXTURES: std::sync::OnceLock<Fixtures> = std::sync::OnceLock::new();
    FIXTURES.get_or_init(|| {
        let (robots, sources) = (robots(), sources());
        let written: Vec<_> = robots.iter().chain(&sources).map(Model::to_xml_string).collect();
        let arena = Model::new("arena");
        let arena = arena.add(&arena.worldbody(), Element::new("site").attr("name", "spawn")).unwrap().0;
        let arena_xml = arena.to_xml_string();
        Fixtures { robots, sources, written, arena, arena_xml }
    })
}

struct Run {
    robots: &'static [Model],
    sources: &'static [Model],
    versions: Vec<Version>,
    options: ReadOptions,
}

impl Run {
    /// Applies one op to `m`: `Ok(None)` when the op does not apply (nothing to pick).
    fn apply(&self, m: &Model, op: &Op) -> Result<Option<Model>, EditError> {
        let at_site = |at: &Option<u16>| -> Loc {
            match at {
                Some(i) => pick(&m.find_all(Namespace::Site), *i).unwrap_or_else(|| m.worldbody()),
                None => m.worldbody(),
            }
        };
        Ok(Some(match op {
            Op::Add { parent, element } => {
                let Some(p) = pick(&containers(m), *parent) else { return Ok(None) };
                m.add(&p, element.build())?.0
            }
            Op::Insert { parent, index, element } => {
                let Some(p) = pick(&containers(m), *parent) else { return Ok(None) };
                m.insert(&p, *index as usize, element.build())?.0
            }
            Op::Set { target, attrs } => {
                let Some(t) = pick(&elements(m), *target) else { return Ok(None) };
                let mut a = Attrs::new();
                for (name, v) in attrs.iter().take(3) {
                    let name = name.get();
                    a = match v {
                        Val::Text(s) => a.set(name, s.get()),
                        Val::Number(x) => a.set(name, x.get()),
                        Val::Numbers(xs) => a.set(name, xs.iter().take(6).map(|x| x.get()).collect::<Vec<f64>>()),
                        Val::Bool(b) => a.set(name, *b),
                        Val::Clear => a.clear(name),
                    };
                }
                m.set(&t, a)?
            }
            Op::Remove { target, with_attachments } => {
                let Some(t) = pick(&elements(m), *target) else { return Ok(None) };
                if *with_attachments { m.remove_with_attachments(&t)? } else { m.remove(&t)? }
            }
            Op::Attach { robot, at } => {
                let child = &self.robots[*robot as usize % self.robots.len()];
                self.attach(m, &at_site(at), child)?
            }
            Op::AttachVersion { version, at } => {
                let Some(v) = self.versions.get(*version as usize % self.versions.len()) else { return Ok(None) };
                if v.len > MAX_XML / 4 {
                    return Ok(None);
                }
                let child = v.model.clone();
                self.attach(m, &at_site(at), &child)?
            }
            Op::Detach { scope } => {
                let Some(s) = pick(&m.scope_paths(), *scope) else { return Ok(None) };
                m.detach(&s)?
            }
            Op::RenameScope { scope, to } => {
                let Some(s) = pick(&m.scope_paths(), *scope) else { return Ok(None) };
                m.rename_scope(&s, &to.get())?
            }
            Op::IncludeCopy { source, override_attributes } => {
                m.include_copy(&self.sources[*source as usize % self.sources.len()], *override_attributes)?
            }
            Op::IncludeCopyVersion { version, override_attributes } => {
                let v = &self.versions[*version as usize % self.versions.len()];
                m.include_copy(&v.model, *override_attributes)?
            }
            Op::EditAttached { scope, element } => {
                let Some(s) = pick(&m.scope_paths(), *scope) else { return Ok(None) };
                let el = element.build();
                m.edit_attached(&s, |inner| inner.add(&inner.worldbody(), el).map(|(m, _)| m))?
            }
            Op::WithName { name } => m.with_name(&name.get()),
            Op::Generated(edit) => {
                let clean = m.check().is_empty();
                let versions = EditRecipe { edits: vec![clip_edit(edit)] }.apply(m);
                let Some(next) = versions.get(1) else { return Ok(None) };
                // (e) The generators keep a model without problems so.
                if clean {
                    let problems: Vec<String> = next.check().iter().map(ToString::to_string).collect();
                    assert!(problems.is_empty(), "the generated {edit:?} made problems: {problems:?}");
                }
                next.clone()
            }
            Op::AttachRecipe { recipe, at } => {
                let child = clip(recipe).build();
                assert!(child.check().is_empty(), "a model built from a recipe has problems: {:?}", child.check());
                self.attach(m, &at_site(at), &child)?
            }
            Op::Revert { .. } | Op::Write { .. } => return Ok(None),
        }))
    }

    /// Attaches, and checks that detaching the new scope gives back `m` exactly.
    fn attach(&self, m: &Model, at: &Loc, child: &Model) -> Result<Model, EditError> {
        let (next, frame) = m.attach(at, child)?;
        let scope = next.scope_of_frame(frame.frame()).expect("the new frame has a scope");
        let back = next.detach(&scope).unwrap_or_else(|e| panic!("cannot detach the new scope {scope:?}: {e}"));
        assert!(back == *m, "detach({scope:?}) after attach does not give back the model");
        Ok(next)
    }

    /// (a) at O(size): one earlier version, in turn the version the step started
    /// from (`from`, the one the step could have touched) and one picked at random by
    /// `step` (versions are immutable values: a change anywhere shows in the sample
    /// over a run).
    fn check_history(&self, from: usize, step: usize) {
        let i = if step % 2 == 0 { from } else { step.wrapping_mul(0x9E37_79B9) % self.versions.len() };
        if let Some(v) = self.versions.get(i) {
            v.check(&format!("version {i}"));
        }
    }

    fn check_current(&self, m: &Model, xml: &Result<String, WriteError>) {
        let Ok(xml) = xml else { return };
        common::check_unique_identifiers(xml);
        self.check_read_back(m, xml);
    }

    fn check_read_back(&self, m: &Model, xml: &str) {
        if m.scopes().next().is_some() {
            // A composed model's output holds scoped names (`robot/torso`), which read
            // back as literal names: a flat model that writes itself again unchanged.
            let back = common::reread(&self.options, xml, "composed");
            let w2 = back.to_xml_string().unwrap_or_else(|e| panic!("the read-back does not write: {e}\n{xml}"));
            if w2 == xml {
                return;
            }
            let w3 = common::reread(&self.options, &w2, "composed, round 2").to_xml_string().unwrap();
            assert!(w3 == w2, "no fixed point after reading a composed output\n--- w1\n{xml}\n--- w2\n{w2}\n--- w3\n{w3}");
            return;
        }
        common::check_fixed_point(&self.options, xml);
    }
}

fuzz_target!(|input: Input| {
    let f = fixtures();
    let (base, xml) = match &input.base {
        None => (f.arena.clone(), f.arena_xml.clone()),
        Some(recipe) => {
            let m = clip(recipe).build();
            assert!(m.check().is_empty(), "a model built from a recipe has problems: {:?}", m.check());
            let xml = written(&m);
            (m, xml)
        }
    };
    let mut run = Run { robots: &f.robots, sources: &f.sources, versions: Vec::new(), options: common::confined() };
    if input.base.is_some() {
        run.check_current(&base, &xml);
    }
    run.versions.push(Version::new(base.clone(), &xml));
    let mut current = base;
    let mut current_index = 0;
    let mut current_hash = run.versions[0].hash.clone();
    // The version whose read-back was checked last (the base's is checked above when it
    // is built from a recipe; the fixed arena's in every run that keeps it).
    let mut read_back = 0;
    for (step, op) in input.ops.iter().take(MAX_OPS).enumerate() {
        match op {
            Op::Revert { version } => {
                current_index = *version as usize % run.versions.len();
                let v = &run.versions[current_index];
                current = v.model.clone();
                current_hash = v.hash.clone();
                continue;
            }
            Op::Write { pretty, precision } => {
                let options = mjcf::WriteOptions {
                    pretty_print: *pretty,
                    precision: precision.map(u32::from),
                    ..mjcf::WriteOptions::default()
                };
                let _ = current.to_xml_string_with(&options);
                continue;
            }
            _ => {}
        }
        let snapshot = current.clone();
        match run.apply(&current, op) {
            Ok(None) => {}
            Ok(Some(next)) => {
                let xml = written(&next);
                if xml.as_ref().is_ok_and(|x| x.len() > MAX_XML) {
                    return;
                }
                if let Ok(x) = &xml {
                    common::check_unique_identifiers(x);
                    if step % READ_BACK_EVERY == READ_BACK_EVERY - 1 {
                        run.check_read_back(&next, x);
                        read_back = run.versions.len();
                    }
                }
                run.check_history(current_index, step);
                run.versions.push(Version::new(next.clone(), &xml));
                current = next;
                current_index = run.versions.len() - 1;
                current_hash = run.versions[current_index].hash.clone();
            }
            Err(e) => {
                let _ = e.to_string();
                // (d) The failed edit left the value as it was.
                assert!(snapshot == current, "a failed {op:?} changed the model");
                assert!(hash_of(&written(&current)) == current_hash, "a failed {op:?} changed the model's output: {e}");
            }
        }
    }
    // (b) for the version the input ends with.
    if current_index != read_back {
        if let Ok(x) = written(&current) {
            run.check_read_back(&current, &x);
        }
    }
    // The robots and sources were never changed by being attached or copied: one of
    // them every 8 inputs, in turn (they are immutable values, so over a run every one
    // is checked after inputs of every kind).
    static TURN: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let turn = TURN.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    if turn % 8 == 0 {
        let i = turn / 8 % f.written.len();
        let m = f.robots.iter().chain(&f.sources).nth(i).expect("one per output");
        assert!(written(m) == f.written[i], "an attached or copied model changed");
    }
});
