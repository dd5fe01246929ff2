//! Model → MJCF text. The only code that produces XML and resolves names.
//!
//! The output has the reference's shape (dm_control_mjcf.md §6): sections and
//! attributes in schema order, empty singletons left out, the root default class
//! wrapped as `<default><default class="/">…</default></default>`, an explicit `class`
//! on every element that can have one and has no `childclass` above it, and
//! `//unnamed_<namespace>_<i>` names for unnamed elements that have an identifier.
//!
// Implementation notes:
// - The walk is iterative (an explicit stack), so a 100,000-deep body chain writes
//   without growing the call stack.
// - Every name written (an element's own, a frame's, an automatic one, a default
//   class's, a reference's) comes from the walk's naming (`model::naming`): the walk
//   keeps each instance's prefix and counts automatic names as it enters elements; a
//   reference to an element ahead is named by the same rules (`Insts::name_of_id`).

use std::collections::HashMap;
use std::fmt::Write as _;

use crate::error::WriteError;
use crate::id::IdHash;
use crate::model::naming::{RootClass, Written as WrittenName};
use crate::model::settings;
use crate::model::tree::{ElementId, Node};
use crate::model::{ElemMap, Entry, Insts, Item, Model, Step, Walk};
use crate::schema::{AttrType, ElementKind, Multiplicity, Namespace, RefTarget, Role};
use crate::value::{FloatStyle, Reference, Value, is_clean};

/// The output reserved per element of the composed model, before writing: about what
/// an element with a short name and a few attributes takes once indented (a robot
/// fleet takes 35 bytes per element, counting the empty singletons of its default
/// classes, which are not written; a tree of bodies with geoms and joints ~120).
/// Where it is too little, the output grows by doubling; where it is more than twice
/// too much (by over a MiB), the excess is given back at the end.
const BYTES_PER_ELEMENT: usize = 40;

/// At most this much is reserved up front (256 MiB; a larger output grows from it).
const MAX_RESERVE: usize = 1 << 28;

/// The deepest indentation, in levels (deeper elements are indented as much).
const MAX_INDENT: usize = 100;

/// Options for [`Model::to_xml_string_with`].
#[derive(Clone, Debug, PartialEq)]
pub struct WriteOptions {
    /// `None` (the default): floats print as the shortest text that reads back exactly
    /// (`0.1`). `Some(p)`: C `%.{p}g`, as the reference prints them (`Some(17)` gives
    /// its exact output, `0.10000000000000001`).
    pub precision: Option<u32>,
    /// Floats whose magnitude is below this print as `0`.
    pub zero_threshold: f64,
    /// Indent with two spaces per level and end with a newline (default `true`);
    /// otherwise one line. Indentation stops growing at 100 levels, so that the output
    /// of a very deep model stays linear in its size.
    pub pretty_print: bool,
    /// Name files `stem-<sha1>.ext` (default `true`) or `stem.ext`.
    pub filename_with_hash: bool,
    /// Write one key per key name over the whole composed model (default `false`,
    /// as the reference, which keeps each attached model's keys as separate keys that
    /// no longer fit the composed model): the model's key and the attached models'
    /// keys of that name laid out in the composed `qpos`, `qvel`, `act`, `ctrl`,
    /// `mpos` and `mquat` order, MuJoCo's defaults where a model has no key of that
    /// name. Joint types follow default classes; a class's `ref` and activation
    /// settings do not (the element's own are read).
    pub merge_keyframes: bool,
}

impl Default for WriteOptions {
    fn default() -> Self {
        WriteOptions {
            precision: None,
            zero_threshold: 0.0,
            pretty_print: true,
            filename_with_hash: true,
            merge_keyframes: false,
        }
    }
}

impl Model {
    /// Writes the model as MJCF text with default options.
    ///
    /// Time: as [`Model::to_xml_string_with`].
    ///
    /// # Errors
    /// As [`Model::to_xml_string_with`].
    ///
    /// # Examples
    /// ```
    /// let m = mjcf::Model::new("empty");
    /// assert_eq!(
    ///     m.to_xml_string().unwrap(),
    ///     "<mujoco model=\"empty\">\n  <default>\n    <default class=\"/\"/>\n  </default>\n</mujoco>\n"
    /// );
    /// ```
    pub fn to_xml_string(&self) -> Result<String, WriteError> {
        self.to_xml_string_with(&WriteOptions::default())
    }

    /// Writes the model as MJCF text.
    ///
    /// A model with attachments is written as one composed model: every attached
    /// model's names get its scope prefix (`robot/torso`), its default classes become
    /// sibling classes (`robot/`), its section elements follow the parent's own, and
    /// the global settings are merged.
    ///
    /// Time: O(N · log n + L) for a composed model of `N` elements written as `L`
    /// bytes, plus O(a · depth · log n) at the root and at each top-level section
    /// (gathering the attached models' content) and, when the merged settings are
    /// not cached, as much again to fold them. The first reference to an unnamed
    /// element costs one O(n) count of that element's model.
    ///
    /// # Errors
    /// - [`WriteError::MissingRequired`]: a required reference names an element that
    ///   was removed;
    /// - [`WriteError::InvalidCharacter`]: the model name holds a character XML
    ///   cannot hold (such as NUL);
    /// - [`WriteError::Conflict`]: global settings of attached models that cannot be
    ///   merged (every edit refuses to make such a model, so this is not expected).
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, WriteOptions, element};
    /// let mut m = Model::new("m");
    /// m.add_mut(&m.worldbody(), element!("geom", name = "g", size = [0.1]))?;
    /// let one_line = m.to_xml_string_with(&WriteOptions { pretty_print: false, ..WriteOptions::default() })?;
    /// assert!(!one_line.contains('\n'));
    /// let exact = m.to_xml_string_with(&WriteOptions { precision: Some(17), ..WriteOptions::default() })?;
    /// assert!(exact.contains(r#"size="0.10000000000000001""#));
    /// # Ok::<(), mjcf::Error>(())
    /// ```
    pub fn to_xml_string_with(&self, options: &WriteOptions) -> Result<String, WriteError> {
        self.write(options, false).map(|(out, _)| out)
    }

    /// Writes the model as [`Model::to_xml_string_with`] does, and tells where each
    /// element was written: its locator, its tag, and its line and byte offset in the
    /// text. This is the map from what a consumer of the text (MuJoCo's compiler)
    /// reports back, by line, to the element of the model.
    ///
    /// Time: as [`Model::to_xml_string_with`], plus O(E) for the E elements written.
    ///
    /// # Errors
    /// As [`Model::to_xml_string_with`].
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, WriteOptions, element};
    /// let mut m = Model::new("m");
    /// let torso = m.add_mut(&m.worldbody(), element!("body", name = "torso"))?;
    /// let written = m.to_xml_written(&WriteOptions::default())?;
    /// let line = written.elements().iter().find(|e| e.loc == torso).unwrap().line;
    /// assert_eq!(written.xml().lines().nth(line - 1), Some(r#"    <body name="torso"/>"#));
    /// assert_eq!(written.element_at_line(line).map(|e| e.tag), Some("body"));
    /// # Ok::<(), mjcf::Error>(())
    /// ```
    pub fn to_xml_written(&self, options: &WriteOptions) -> Result<Written, WriteError> {
        let (xml, marks) = self.write(options, true)?;
        let mut elements = Vec::with_capacity(marks.len());
        let (mut line, mut scanned) = (1, 0);
        for (offset, loc, tag) in marks {
            line += xml.as_bytes()[scanned..offset].iter().filter(|b| **b == b'\n').count();
            scanned = offset;
            elements.push(WrittenElement { loc, tag, line, offset });
        }
        Ok(Written { xml, elements })
    }

    /// The writer's entry: the text, and with `marks`, where each element starts.
    fn write(
        &self,
        options: &WriteOptions,
        marks: bool,
    ) -> Result<(String, Vec<Mark>), WriteError> {
        // The merged global settings, folded before anything is written.
        let merged = settings::merged(self).map_err(|k| WriteError::Conflict(k.to_string()))?;
        let mut w = Writer {
            marks: marks.then(Vec::new),
            merged: &merged,
            out: String::with_capacity(4096),
            style: FloatStyle {
                precision: options.precision,
                zero_threshold: options.zero_threshold,
            },
            options,
            value: String::new(),
            bad_char: None,
            entries: HashMap::with_hasher(IdHash),
            open: Vec::new(),
            pending: None,
            in_default: false,
        };
        w.run(Walk::new(self).pruned(silent), true)?;
        if let Some((tag, attribute, character)) = w.bad_char {
            return Err(WriteError::InvalidCharacter { tag, attribute, character });
        }
        let marks = w.marks.take().unwrap_or_default();
        let marks = marks
            .into_iter()
            .map(|(offset, frames, node, tag)| {
                (offset, crate::Loc::scoped(frames, node.id(), self.name()), tag)
            })
            .collect();
        let mut out = w.out;
        if out.capacity() > 2 * out.len() && out.capacity() - out.len() > 1 << 20 {
            // The reservation was far too much (elements not written: the empty
            // singletons of many default classes).
            out.shrink_to_fit();
        }
        Ok((out, marks))
    }
}

/// Where an element's start tag begins: byte offset, locator, tag.
type Mark = (usize, crate::Loc, &'static str);

/// A [`Mark`] as the writer takes it: the frames leading to the element's model and
/// the node, made a locator at the end.
type RawMark<'a> = (usize, std::sync::Arc<[ElementId]>, &'a Node, &'static str);

/// MJCF text and where each element of the model was written in it, from
/// [`Model::to_xml_written`].
#[derive(Clone, Debug)]
pub struct Written {
    xml: String,
    elements: Vec<WrittenElement>,
}

/// Where one element was written (see [`Written`]).
#[derive(Clone, Debug)]
#[non_exhaustive]
pub struct WrittenElement {
    /// The element's locator in the model written.
    pub loc: crate::Loc,
    /// The tag it was written with: its element's, or for an attachment frame `body`,
    /// or `frame` where it is written as MuJoCo's `<frame>` (DESIGN D10), which
    /// MuJoCo's compiled model keeps no record of.
    pub tag: &'static str,
    /// The line its start tag begins on (1 for the first).
    pub line: usize,
    /// The byte offset of its `<`.
    pub offset: usize,
}

impl Written {
    /// The text.
    ///
    /// Time: O(1).
    pub fn xml(&self) -> &str {
        &self.xml
    }

    /// The text, taken out.
    ///
    /// Time: O(1).
    pub fn into_xml(self) -> String {
        self.xml
    }

    /// Every element written, in document order.
    ///
    /// Time: O(1).
    pub fn elements(&self) -> &[WrittenElement] {
        &self.elements
    }

    /// The element whose start tag begins on `line`, when exactly one does (one per
    /// line when pretty-printed).
    ///
    /// Time: O(log E).
    pub fn element_at_line(&self, line: usize) -> Option<&WrittenElement> {
        let from = self.elements.partition_point(|e| e.line < line);
        let to = self.elements.partition_point(|e| e.line <= line);
        (to == from + 1).then(|| &self.elements[from])
    }
}

/// An element whose start tag is not finished yet.
enum Pending {
    /// `<tag attrs` is written; `>` or `/>` follows, once it is known whether a child
    /// comes.
    Started,
    /// A top-level section not written at all yet: it is written only if a child
    /// comes or it has attributes of its own.
    Unwritten(Inst0Section),
}

/// A top-level section of the outermost model waiting to be written.
#[derive(Clone, Copy)]
struct Inst0Section {
    depth: usize,
}

/// An open element: its instance, whether its children are under a `childclass`,
/// and its written depth.
struct Open {
    inst: usize,
    child_cc: bool,
    depth: usize,
    /// The tag written (`body` or `frame` for an attachment frame).
    tag: &'static str,
    /// In the world: the worldbody, or a frame written as MuJoCo's `<frame>` there,
    /// whose bodies are top-level bodies for MuJoCo.
    world_level: bool,
    /// Written without tags of its own: the outermost root default class written as
    /// MuJoCo's main class, the `<default>` wrapper itself ([`RootClass::Main`]).
    transparent: bool,
}

struct Writer<'a> {
    /// Where each element's start tag begins (offset, the frames leading to its
    /// model, node, tag written), when asked.
    marks: Option<Vec<RawMark<'a>>>,
    /// The merged settings sections (`compiler`, `option`, ...), written in place of
    /// the root model's own.
    merged: &'a [Node],
    out: String,
    style: FloatStyle,
    options: &'a WriteOptions,
    value: String,
    /// The first character XML cannot hold: (tag, attribute, character).
    bad_char: Option<(&'static str, &'static str, char)>,
    /// The elements entered and not yet left.
    open: Vec<Open>,
    /// The element whose start tag is not finished.
    pending: Option<(Pending, Item<'a>)>,
    /// Inside `<default>`, the wrapper of the root class and the attached models'
    /// root classes (one level deeper than the walk says).
    in_default: bool,
    /// Index entries looked up by references, with the map they came from: an
    /// attached model's elements are looked up again for each attachment of it
    /// (the same shared map), and a class is looked up twice (is it there, its name).
    entries: HashMap<ElementId, (&'a ElemMap<Entry>, Option<&'a Entry>), IdHash>,
}

/// Whether a singleton writes anything: a written attribute, or a child that does.
fn singleton_emits(node: &Node) -> bool {
    let kind = node.kind();
    if facts(kind).class.is_some() || kind.identifier().is_some() {
        return true;
    }
    if node
        .attrs()
        .iter()
        .any(|(i, _)| !matches!(kind.attr(*i as usize).ty, AttrType::Basepath { .. }))
    {
        return true;
    }
    // (Most singletons are empty: no iterator for them.)
    let children = node.children();
    !children.is_empty()
        && children
            .iter()
            .any(|c| c.kind().multiplicity() != Multiplicity::Singleton || singleton_emits(c))
}

/// Whether all the class `node` writes inside it is one class, named `/` (the shape
/// the reader folds into the root class).
fn lone_slash_class(node: &Node) -> bool {
    let (classes, own): (Vec<&Node>, Vec<&Node>) =
        node.children().iter().partition(|c| c.kind().is(Role::DefaultClass));
    matches!(classes[..], [c] if c.identifier() == Some("/")) && !own.into_iter().any(emits)
}

fn emits(node: &Node) -> bool {
    node.kind().multiplicity() != Multiplicity::Singleton || singleton_emits(node)
}

/// An element that writes nothing and is not an attachment frame: below the
/// sections, the writer skips it where it meets it (`enter`), so the walk need not
/// give it (`Walk::pruned`).
fn silent(node: &Node) -> bool {
    node.attached().is_none() && !emits(node)
}

impl<'a> Writer<'a> {
    /// Writes every step of `walk`; `substitute` writes the merged settings in place
    /// of the root model's own settings sections.
    fn run(&mut self, mut walk: Walk<'a>, substitute: bool) -> Result<(), WriteError> {
        while let Some(step) = walk.next() {
            if substitute && matches!(step, Step::Enter(Item { depth: 0, .. })) {
                self.reserve_output(&walk.insts);
            }
            match step {
                Step::Enter(item)
                    if substitute
                        && self.options.merge_keyframes
                        && item.depth == 1
                        && item.node.kind().is(Role::Keyframe) =>
                {
                    walk.skip_subtree();
                    self.write_merged_keys(&walk.insts)?;
                }
                Step::Enter(item) => {
                    if !self.enter(&walk.insts, item, substitute)? {
                        walk.skip_subtree();
                    }
                    if substitute
                        && item.depth == 1
                        && item.inst == 0
                        && settings::is_settings_section(item.node.kind())
                    {
                        // The merged section instead of the model's own.
                        walk.skip_subtree();
                        if let Some(m) = self.merged.iter().find(|m| m.kind() == item.node.kind()) {
                            if emits(m) {
                                let model = walk.insts.list[0].model;
                                self.run(Walk::plain(model, m, 1).pruned(silent), false)?;
                            }
                        }
                    }
                }
                Step::Leave(item) => self.leave(&walk.insts, item),
            }
        }
        Ok(())
    }

    /// Reserves the output's room once every model of the composition is known (the
    /// root's children list them all): `BYTES_PER_ELEMENT` per element of each. Grown
    /// by doubling instead, a large output is copied and its fresh pages touched
    /// again at every step (77 MB allocated for 19 MB of text).
    fn reserve_output(&mut self, insts: &Insts<'a>) {
        let elements: usize = insts.list.iter().map(|i| i.model.index.elems.len()).sum();
        self.out.reserve(elements.saturating_mul(BYTES_PER_ELEMENT).min(MAX_RESERVE));
    }

    /// Writes the composed keys in place of the keyframe section.
    fn write_merged_keys(&mut self, insts: &Insts<'a>) -> Result<(), WriteError> {
        let keys = crate::model::keys::merged_keys(insts.list[0].model);
        if keys.is_empty() {
            return Ok(());
        }
        self.finish_parent(insts)?;
        if self.in_default {
            self.indent(1);
            self.out.push_str("</default>");
            self.newline();
            self.in_default = false;
        }
        self.indent(1);
        self.out.push_str("<keyframe>");
        self.newline();
        for key in keys {
            self.indent(2);
            self.out.push_str("<key");
            if let Some(name) = &key.name {
                self.value.clear();
                self.value.push_str(name);
                self.emit_attr("key", "name");
            }
            if let Some(t) = key.time {
                self.value.clear();
                Value::Float(t).write_plain(&mut self.value, self.style);
                self.emit_attr("key", "time");
            }
            for (field, values) in key.fields {
                self.value.clear();
                Value::Floats(values.into()).write_plain(&mut self.value, self.style);
                self.emit_attr("key", field);
            }
            self.out.push_str("/>");
            self.newline();
        }
        self.indent(1);
        self.out.push_str("</keyframe>");
        self.newline();
        Ok(())
    }

    /// Finishes the start tag of the parent of a child about to be written.
    fn finish_parent(&mut self, insts: &Insts<'a>) -> Result<(), WriteError> {
        match self.pending.take() {
            Some((Pending::Started, _)) => {
                self.out.push('>');
                self.newline();
            }
            Some((Pending::Unwritten(sec), item)) => {
                self.start_tag(insts, &item, sec.depth, false)?;
                self.out.push('>');
                self.newline();
            }
            None => {}
        }
        Ok(())
    }

    /// Writes `<tag attrs` (not closed) at `depth`.
    fn start_tag(
        &mut self,
        insts: &Insts<'a>,
        item: &Item<'a>,
        depth: usize,
        childclass: bool,
    ) -> Result<(), WriteError> {
        let node = item.node;
        self.indent(depth);
        if let Some(marks) = &mut self.marks {
            let written = match node.attached() {
                Some(_) => self.open.last().map_or("body", |o| o.tag),
                None => node.kind().tag(),
            };
            marks.push((self.out.len(), insts.list[item.inst].frames.clone(), node, written));
        }
        self.out.push('<');
        if node.attached().is_some() {
            // `body`, or `frame` (DESIGN D10).
            let tag = self.open.last().map_or("body", |o| o.tag);
            self.out.push_str(tag);
            return self.write_attrs(insts, item, true);
        }
        let kind = node.kind();
        self.out.push_str(kind.tag());
        if kind == ElementKind::ROOT {
            // A model without a name is written with the one the reader gives it.
            if ElementKind::ROOT.attr_index("model").is_some_and(|i| node.attr(i).is_none()) {
                self.out.push_str(" model=\"");
                self.out.push_str(crate::model::UNNAMED);
                self.out.push('"');
            }
        }
        self.write_attrs(insts, item, childclass)
    }

    /// Enters an element; `false` if it is not written (nor its subtree).
    fn enter(
        &mut self,
        insts: &Insts<'a>,
        item: Item<'a>,
        substitute: bool,
    ) -> Result<bool, WriteError> {
        let Item { inst, node, depth, .. } = item;
        let kind = node.kind();
        let top = depth == 1 && inst == 0 && substitute;
        let names = &insts.list[inst].names;
        // The `<default>` wrapper of the root classes opens at the first one and
        // closes before the next section.
        if depth == 1 && substitute {
            let is_default = kind.is(Role::DefaultClass);
            if is_default && !self.in_default {
                self.finish_parent(insts)?;
                self.indent(1);
                // A root class written as MuJoCo's main class says so on the wrapper
                // when it is named `main` (so that it reads back named so, and the
                // text written again is the same), or when its one class is named
                // `/`: `<default><default class="/">` alone reads back as
                // dm_control's shape, `/` folded into the root class (`xml::read`),
                // and the references to `main` would then take `/`'s defaults.
                let named_main = node.identifier() == Some("main");
                if inst == 0
                    && names.root_class == RootClass::Main
                    && (named_main || lone_slash_class(node))
                {
                    self.out.push_str("<default class=\"main\">");
                } else {
                    self.out.push_str("<default>");
                }
                self.newline();
                self.in_default = true;
            } else if !is_default && self.in_default {
                self.indent(1);
                self.out.push_str("</default>");
                self.newline();
                self.in_default = false;
            }
        }
        if top && settings::is_settings_section(kind) {
            return Ok(false);
        }
        if top && kind.is(Role::Worldbody) && !emits(node) {
            return Ok(false);
        }
        if !top && depth > 0 && !item.in_frame && node.attached().is_none() && !emits(node) {
            return Ok(false);
        }
        // The written depth: sections and the root classes at the wrapper's level,
        // everything else one below its parent.
        let depth = match self.open.last() {
            Some(o) if depth > 1 => o.depth + 1,
            _ => depth + usize::from(self.in_default),
        };
        let transparent = inst == 0
            && substitute
            && item.depth == 1
            && kind.is(Role::DefaultClass)
            && names.root_class == RootClass::Main;
        // Whether a `childclass` of the same model is above: attached models start
        // without one.
        let cc_here = self.open.last().is_some_and(|o| o.child_cc && o.inst == inst);
        let child_cc =
            cc_here || (node.attached().is_none() && self.sets_childclass(insts, inst, node));
        let parent_world = self.open.last().is_some_and(|o| o.world_level);
        let as_frame = parent_world && frame_keeps_bodies_top_level(node);
        let tag = match node.attached() {
            Some(_) if as_frame => "frame",
            Some(_) => "body",
            None => kind.tag(),
        };
        // MuJoCo's own `<frame>`s in the world pass the world on too.
        let world_level = (kind.is(Role::Worldbody) && inst == 0 && substitute)
            || as_frame
            || (parent_world && kind.is(Role::Frame));
        let depth = if transparent { depth - 1 } else { depth };
        self.open.push(Open { inst, child_cc, depth, tag, world_level, transparent });
        if transparent {
            return Ok(true);
        }
        if top && !matches!(kind.role(), Some(Role::DefaultClass | Role::Worldbody)) {
            self.finish_parent(insts)?;
            self.pending = Some((Pending::Unwritten(Inst0Section { depth }), item));
            return Ok(true);
        }
        if depth > 0 {
            self.finish_parent(insts)?;
        }
        self.start_tag(insts, &item, depth, cc_here)?;
        self.pending = Some((Pending::Started, item));
        Ok(true)
    }

    fn leave(&mut self, insts: &Insts<'a>, item: Item<'a>) {
        let Some(open) = self.open.pop() else { return };
        if open.transparent {
            return;
        }
        if item.depth == 0 && self.in_default {
            self.indent(1);
            self.out.push_str("</default>");
            self.newline();
            self.in_default = false;
        }
        match self.pending.take() {
            Some((Pending::Started, _)) => {
                self.out.push_str("/>");
                self.newline();
            }
            Some((Pending::Unwritten(sec), item)) => {
                if singleton_emits_attrs(item.node) {
                    // Attributes only: failures are reported by `bad_char` or not at all.
                    let _ = self.start_tag(insts, &item, sec.depth, false);
                    self.out.push_str("/>");
                    self.newline();
                }
            }
            None => {
                self.indent(open.depth);
                self.out.push_str("</");
                self.out.push_str(open.tag);
                self.out.push('>');
                self.newline();
            }
        }
    }

    fn indent(&mut self, depth: usize) {
        if self.options.pretty_print {
            // One copy from a line of spaces (two a level), not one per level.
            const SPACES: &str = match std::str::from_utf8(&[b' '; 2 * MAX_INDENT]) {
                Ok(s) => s,
                Err(_) => "",
            };
            self.out.push_str(&SPACES[..2 * depth.min(MAX_INDENT)]);
        }
    }

    fn newline(&mut self) {
        if self.options.pretty_print {
            self.out.push('\n');
        }
    }

    /// Writes ` name="value"` for every attribute, in schema order, including the
    /// element's name (its own with its prefix, an attachment frame's, a frame
    /// joint's, an automatic one: `model::naming`) and the implicit default class.
    /// `childclass`: a `childclass` of the same model is above (no implicit class).
    fn write_attrs(
        &mut self,
        insts: &Insts<'a>,
        item: &Item<'a>,
        childclass: bool,
    ) -> Result<(), WriteError> {
        let (inst, node) = (item.inst, item.node);
        let kind = node.kind();
        // The identifier slot is always written from the naming rules.
        let name = match kind.identifier() {
            Some(i) => insts.name_of_item(item).map(|w| (i, w)),
            None => None,
        };
        let implicit_class = match facts(kind).class {
            Some(c) if !childclass && !self.has_live(insts, inst, node, c) => Some(c),
            _ => None,
        };
        let mut set = node.attrs().iter().peekable();
        let mut virtuals: [Option<usize>; 2] = [name.map(|a| a.0), implicit_class];
        virtuals.sort_by_key(|v| v.unwrap_or(usize::MAX));
        let mut virt = virtuals.iter().flatten().copied().peekable();
        loop {
            let next_set = set.peek().map(|(i, _)| *i as usize);
            let next_virt = virt.peek().copied();
            let take_virtual = match (next_set, next_virt) {
                (None, None) => break,
                (Some(_), None) => false,
                (None, Some(_)) => true,
                (Some(s), Some(v)) => v <= s,
            };
            self.value.clear();
            if take_virtual {
                let i = virt.next().unwrap_or_default();
                // Skip the stored value at the same slot, if any.
                if next_set == Some(i) {
                    set.next();
                }
                let attr = kind.attr(i).name;
                match name {
                    Some((slot, written)) if slot == i => {
                        self.emit_written(insts, inst, kind.tag(), attr, written);
                    }
                    _ => {
                        // Implicit class: the model's root class.
                        let root = insts.root_class_name(inst);
                        self.emit_written(insts, inst, kind.tag(), attr, root);
                    }
                }
            } else if let Some((i, v)) = set.next() {
                let i = *i as usize;
                let spec = kind.attr(i);
                if matches!(
                    v,
                    Value::Float(_)
                        | Value::Floats(_)
                        | Value::Int(_)
                        | Value::Ints(_)
                        | Value::Keyword(_)
                ) {
                    // Numbers and schema keywords are plain ASCII with nothing to
                    // escape: written straight into the output.
                    self.out.push(' ');
                    self.out.push_str(spec.name);
                    self.out.push_str("=\"");
                    v.write_plain(&mut self.out, self.style);
                    self.out.push('"');
                } else {
                    self.emit_value(insts, inst, node, i, v)?;
                }
            }
        }
        Ok(())
    }

    /// Appends ` attr="…"` for a name in instance `inst`: an element's own name as
    /// prefix and name, each escaped with no copy between; any other spelt first.
    fn emit_written(
        &mut self,
        insts: &Insts<'a>,
        inst: usize,
        tag: &'static str,
        attr: &'static str,
        written: WrittenName<'_>,
    ) {
        let names = &insts.list[inst].names;
        if let WrittenName::Own(n) = written {
            let parts = [names.prefix.as_str(), n];
            emit_parts(&mut self.out, &mut self.bad_char, tag, attr, parts, names.prefix_clean);
            return;
        }
        self.value.clear();
        written.write(&names.prefix, &mut self.value);
        self.emit_attr(tag, attr);
    }

    /// The index entry of `id` in the model of instance `inst`.
    fn entry(&mut self, insts: &Insts<'a>, inst: usize, id: ElementId) -> Option<&'a Entry> {
        let elems = &insts.list[inst].model.index.elems;
        if let Some((m, e)) = self.entries.get(&id) {
            if m.ptr_eq(elems) {
                return *e;
            }
        }
        let e = elems.get(&id);
        self.entries.insert(id, (elems, e));
        e
    }

    fn sets_childclass(&mut self, insts: &Insts<'a>, inst: usize, node: &Node) -> bool {
        facts(node.kind()).childclass.is_some_and(|i| self.has_live(insts, inst, node, i))
    }

    /// Whether attribute `i` of `node` is set and will be written: a reference to an
    /// element that was removed is not (an optional reference; a required one fails).
    fn has_live(&mut self, insts: &Insts<'a>, inst: usize, node: &Node, i: usize) -> bool {
        match node.attr(i) {
            None => false,
            Some(Value::Reference(Reference::Element(id))) => {
                self.entry(insts, inst, *id).is_some()
            }
            Some(_) => true,
        }
    }

    /// Appends ` name="value"` for attribute `i` (holding `v`), if it is written.
    fn emit_value(
        &mut self,
        insts: &Insts<'a>,
        inst: usize,
        node: &Node,
        i: usize,
        v: &Value,
    ) -> Result<(), WriteError> {
        let kind = node.kind();
        let (tag, attr) = (kind.tag(), kind.attr(i).name);
        // Names are written as prefix and name, each escaped, with no copy between.
        let names = &insts.list[inst].names;
        let prefix = names.prefix.as_str();
        let parts = match v {
            Value::Basepath(_) => return Ok(()),
            Value::Reference(Reference::Element(target)) => {
                return self.emit_reference(insts, inst, node, i, *target);
            }
            // (The identifier slot is written by `write_attrs`.)
            Value::Identifier(n) => [prefix, n.as_str()],
            Value::String(n) if kind.attr(i).ty == AttrType::NamePrefix => [prefix, n.as_str()],
            Value::Reference(Reference::Name(n)) => {
                let ty = kind.attr(i).ty;
                // `main` and `/` name the root class unless a class has that name
                // (as the reader resolves them): written as the root class is, so
                // that the text reads back to the same class, in any scope.
                let model = insts.list[inst].model;
                if ty == AttrType::Reference(RefTarget::Fixed(Namespace::Default))
                    && matches!(n.as_str(), "main" | "/")
                    && !model.index.names.contains_key(&(Namespace::Default, n.clone()))
                {
                    let root = insts.root_class_name(inst);
                    self.emit_written(insts, inst, tag, attr, root);
                    return Ok(());
                }
                // The one world body is `world` in every scope; a name in another
                // model (`RefTarget::Unless`) is not this model's.
                let to_body = matches!(ty, AttrType::Reference(RefTarget::Fixed(Namespace::Body)));
                let elsewhere = matches!(ty, AttrType::Reference(RefTarget::Unless(_, k)) if node.attr(k).is_some());
                if elsewhere || to_body && n == "world" {
                    ["", n.as_str()]
                } else {
                    [prefix, n.as_str()]
                }
            }
            Value::File(f) => {
                self.value.push_str(&f.vfs_name(self.options.filename_with_hash));
                self.emit_attr(tag, attr);
                return Ok(());
            }
            _ => {
                v.write_plain(&mut self.value, self.style);
                self.emit_attr(tag, attr);
                return Ok(());
            }
        };
        let clean = names.prefix_clean;
        emit_parts(&mut self.out, &mut self.bad_char, tag, attr, parts, clean);
        Ok(())
    }

    /// Appends ` name="…"` for attribute `i`, a reference to element `target`, if it
    /// is written (an optional reference to a removed element is not).
    fn emit_reference(
        &mut self,
        insts: &Insts<'a>,
        inst: usize,
        node: &Node,
        i: usize,
        target: ElementId,
    ) -> Result<(), WriteError> {
        let kind = node.kind();
        let (tag, attr) = (kind.tag(), kind.attr(i).name);
        let Some(entry) = self.entry(insts, inst, target) else {
            let spec = kind.attr(i);
            if spec.required {
                let model = insts.list[inst].model;
                return Err(WriteError::MissingRequired {
                    tag: kind.tag(),
                    attribute: spec.name,
                    path: model.path_of(node.id()).map(|p| model.describe(&p)).unwrap_or_default(),
                });
            }
            return Ok(());
        };
        if let Some(written) = insts.name_of_entry(inst, target, entry) {
            self.emit_written(insts, inst, tag, attr, written);
        }
        Ok(())
    }

    /// Appends ` name="<escaped self.value>"`.
    fn emit_attr(&mut self, tag: &'static str, name: &'static str) {
        emit_parts(&mut self.out, &mut self.bad_char, tag, name, [&self.value, ""], false);
    }
}

/// Appends ` name="<escaped parts[0] + parts[1]>"` (a prefix and a name, escaped
/// one after the other: escaping goes character by character) and records the first
/// character XML cannot hold in `bad`. `first_clean`: `parts[0]` is known to need no
/// escaping (a scope prefix, checked once per instance).
fn emit_parts(
    out: &mut String,
    bad: &mut Option<(&'static str, &'static str, char)>,
    tag: &'static str,
    name: &'static str,
    parts: [&str; 2],
    first_clean: bool,
) {
    out.reserve(name.len() + parts[0].len() + parts[1].len() + 4);
    out.push(' ');
    out.push_str(name);
    out.push_str("=\"");
    for (k, p) in parts.into_iter().enumerate() {
        if k == 0 && first_clean {
            out.push_str(p);
        } else if let Some(c) = escape_into(out, p) {
            bad.get_or_insert((tag, name, c));
        }
    }
    out.push('"');
}

/// Whether an attachment frame in the world is written as MuJoCo's `<frame>` rather
/// than a `<body>` (DESIGN D10): when the attached model's top-level bodies carry
/// freejoints, which MuJoCo accepts only on top-level bodies, and the frame itself
/// neither moves nor has mass (no joints, no inertial) nor carries body-only
/// attributes (`user`, `mocap`). Any other frame stays a body, as in the reference.
pub(crate) fn frame_keeps_bodies_top_level(frame: &Node) -> bool {
    let Some(a) = frame.attached() else { return false };
    if !frame.children().is_empty() {
        return false;
    }
    let kind = frame.kind();
    let body_only = ["user", "mocap"]
        .iter()
        .any(|n| kind.attr_index(n).is_some_and(|i| frame.attr(i).is_some()));
    if body_only {
        return false;
    }
    let Some(wb) = section_of(&a.model, "worldbody") else { return false };
    wb.children().iter().any(|b| {
        b.kind().is(Role::Body)
            && b.attached().is_none()
            && b.children().iter().any(|j| match j.kind().role() {
                Some(Role::Freejoint) => true,
                Some(Role::Joint) => j
                    .kind()
                    .attr_index("type")
                    .and_then(|i| j.attr(i))
                    .is_some_and(|t| t.as_str() == Some("free")),
                _ => false,
            })
    })
}

/// Whether a container section writes attributes of its own.
fn singleton_emits_attrs(node: &Node) -> bool {
    let kind = node.kind();
    node.attrs()
        .iter()
        .any(|(i, _)| !matches!(kind.attr(*i as usize).ty, AttrType::Basepath { .. }))
}

fn section_of<'m>(model: &'m Model, tag: &str) -> Option<&'m Node> {
    model.root.child_of_kind(ElementKind::ROOT.child(tag)?)
}

/// What the writer asks of every element's kind, looked up by name once per kind.
struct KindFacts {
    /// `kind.class_attr()`.
    class: Option<usize>,
    /// The index of `childclass`.
    childclass: Option<usize>,
}

fn facts(kind: ElementKind) -> &'static KindFacts {
    static FACTS: std::sync::OnceLock<Vec<KindFacts>> = std::sync::OnceLock::new();
    const NONE: KindFacts = KindFacts { class: None, childclass: None };
    let table = FACTS.get_or_init(|| {
        ElementKind::all()
            .map(|k| KindFacts { class: k.class_attr(), childclass: k.attr_index("childclass") })
            .collect()
    });
    table.get(kind.0 as usize).unwrap_or(&NONE)
}

/// Escapes an attribute value as lxml does: `& < > "` as entities, tab, newline and
/// carriage return as character references, and every non-ASCII character as a
/// numeric character reference.
///
/// Returns the first character that XML 1.0 cannot hold at all (most control
/// characters, U+FFFE, U+FFFF), if any; it is written as a reference all the same.
pub(crate) fn escape_into(out: &mut String, s: &str) -> Option<char> {
    if is_clean(s.as_bytes()) {
        out.push_str(s);
        return None;
    }
    let bad = s.chars().find(|c| !crate::value::is_xml_char(*c));
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            ' '..='~' => out.push(c),
            _ => {
                let _ = write!(out, "&#{};", c as u32);
            }
        }
    }
    bad
}
