//! Model → MJCF text. The only code that produces XML and resolves names.
//!
//! The output has dm_control's shape (what it writes, observed): sections and
//! attributes in schema order, empty singletons left out, the root default class
//! wrapped as `<default><default class="/">…</default></default>`, an explicit `class`
//! on every element that can have one and has no `childclass` above it, and
//! `//unnamed_<namespace>_<i>` names for unnamed elements that have an identifier.
//!
//! # The writer's rules
//!
//! Each rule is one function of [`rules`] (`xml::rules`, which the reader, the saver
//! and scenes ask too; or of the module named), asked as the
//! writer walks the composed model; each is inverted by a rule of the reader
//! (`xml::read`), and round-tripped by a test of `tests/write_rules.rs` (write, read
//! back: what the rule wrote reads back as the table says, writing that gives the
//! same text, and reading that gives the same model). Where the reader asks the
//! same question, it asks the same function.
//!
//! | Rule | Function | Writes | Read back by | Test |
//! |---|---|---|---|---|
//! | names | `model::naming` | every name slot from the naming rules: own names with the instance's prefix (`robot/torso`), attachment frames and their joints by scope (`robot/`) | literal names, `/` included (decision D13) | `scoped_names_read_back_as_literal_names` |
//! | automatic names | [`rules::is_auto_name`] | `//unnamed_<ns>_<i>` for an unnamed element with a name slot (`naming::Written::Auto`) | `forget_auto_name`: no name, derived again when written | `automatic_names_are_forgotten_and_derived_again` |
//! | replicate suffix | [`rules::is_auto_name`] | `_` after an automatic name inside a `<replicate>` (MuJoCo appends the copy's number) | `forget_auto_name`, as any automatic name | `automatic_names_in_a_replicate_end_in_an_underscore` |
//! | composed output | [`rules::is_composed_output`] | the root class `/` (or `/1`) beside the attached models' root classes `robot/` | `hoist_root_class` tells it; the automatic names are kept as literal names | `a_composed_output_keeps_its_automatic_names` |
//! | root class wrapper | [`rules::in_root_wrapper`] | one `<default>` around the root classes (`/`, then `robot/`, ...), closed before the next section | `hoist_root_class`: a wrapper holding only `<default class="/">` is the root class ([`rules::folds_into_root_class`]) | `root_classes_share_one_wrapper` |
//! | root class as main (decision D9) | [`rules::root_class_is_wrapper`] | a root class named `main`, or beside a class named `/`: its content in the wrapper itself | the wrapper's content is the root class's | `a_root_class_named_main_is_the_wrapper` |
//! | main wrapper | [`rules::wrapper_says_main`] | `<default class="main">` for such a root class named `main` or holding a lone class `/` | `hoist_root_class` folds no wrapper with an attribute ([`rules::folds_into_root_class`]) | `a_lone_slash_class_in_the_main_class_stays_a_class` |
//! | numbered root class | `naming::RootClass::Numbered` | `/1` (the first free `/k`) for the root class when a class is named `/` and attached root classes follow | a class of that name | `a_root_class_beside_a_class_named_slash_is_numbered` |
//! | implicit class | [`rules::implicit_class`] | `class="/"` (the root class's name) where an element can have a class and has none, nor a `childclass` above | `/` and `main` resolve to the root class | `elements_without_a_class_name_the_root_class` |
//! | childclass scope | [`rules::childclass_above`], [`rules::childclass_below`] | no implicit class under a written `childclass` of the element's own model; an attached model starts outside it | MuJoCo's own `childclass` rule | `an_attached_model_is_outside_its_frames_childclass` |
//! | references by name | [`rules::named_reference`] | `main` and `/` as the root class is named, `world` (decision D5) and names in another model bare, the rest prefixed | `/` and `main` resolve to the root class | `named_references_keep_their_meaning` |
//! | removed references | [`rules::removed_reference`] | nothing for an optional reference to a removed element; `MissingRequired` for a required one | the element without it | `references_to_removed_elements_are_left_out_or_refused` |
//! | silent elements | [`rules::is_silent`] | nothing for an empty singleton below the sections | `finish` makes every singleton not read, empty | `empty_singletons_are_left_out_and_made_again` |
//! | sections on demand | [`rules::section_presence`] | a section once it holds something (a child, an attribute); no empty worldbody | every section not read, made empty | `empty_sections_are_left_out_and_made_again` |
//! | merged settings | [`rules::writes_merged_settings`] | the settings merged over the composition, in place of the outermost model's | the model's own settings | `settings_are_written_merged` |
//! | merged keys | [`rules::merges_keys`] | with `merge_keyframes`, one key per name laid out over the composed model | plain keys, which fit the model read back | `merged_keys_read_back_as_keys_that_fit` |
//! | attachment frame tag | [`rules::written_tag`] | an attachment frame as `<body name="robot/">` with its site's pose | a body with a literal name (decision D13) | `an_attachment_frame_reads_back_as_a_body` |
//! | frames keeping bodies top level (decision D10) | [`rules::frame_keeps_bodies_top_level`], [`rules::passes_world_on`] | `<frame>` for a frame in the world over bodies with freejoints | MuJoCo's `<frame>` (decision D12) | `a_frame_over_free_bodies_is_written_as_a_frame` |
//! | file names | [`rules::file_name`] | `stem-<sha1>.ext` (or `stem.ext` without `filename_with_hash`) | `FileAsset::named_as` drops `-<sha1>` | `files_read_back_under_their_names` |
//! | base paths | [`rules::writes_attr`] | no `meshdir`, `texturedir`, `assetdir` (files are named as written) | files read by their written names | `base_paths_are_not_written` |
//! | unnamed model | [`rules::implicit_model_name`] | `model="unnamed_model"` for a model without a name | a model read without a name is named so | `an_unnamed_model_reads_back_unnamed` |
//! | escaping | [`text::escape_into`] | `& < > "` as entities, tab, line ends and non-ASCII as character references (as lxml) | quick-xml unescapes | `names_with_markup_characters_read_back` |
//!
// Implementation notes:
// - The walk is iterative (an explicit stack), so a 100,000-deep body chain writes
//   without growing the call stack.
// - Every name written (an element's own, a frame's, an automatic one, a default
//   class's, a reference's) comes from the walk's naming (`model::naming`): the walk
//   keeps each instance's prefix and counts automatic names as it enters elements; a
//   reference to an element ahead is named by the same rules (`Insts::name_of_id`).
// - The rules decide, the writer spells: `xml::rules` (what is written, and as what),
//   `attrs` (an element's attributes), `text` (indentation and escaping), `written`
//   (where each element was written).

mod attrs;
pub(crate) mod text;
mod written;

use std::collections::HashMap;

use crate::error::WriteError;
use crate::id::IdHash;
use crate::model::settings;
use crate::model::tree::{ElementId, Node};
use crate::model::{ElemMap, Entry, Insts, Item, Model, Step, Walk};
use crate::schema::Role;
use crate::value::{FloatStyle, Value};

pub use crate::write_options::WriteOptions;
use crate::xml::rules::{self, Presence};
use text::Text;
use written::RawMark;
pub use written::{Written, WrittenElement};

/// The output reserved per element of the composed model, before writing: about what
/// an element with a short name and a few attributes takes once indented (a robot
/// fleet takes 35 bytes per element, counting the empty singletons of its default
/// classes, which are not written; a tree of bodies with geoms and joints ~120).
/// Where it is too little, the output grows by doubling; where it is more than twice
/// too much (by over a MiB), the excess is given back at the end.
const BYTES_PER_ELEMENT: usize = 40;

/// At most this much is reserved up front (256 MiB; a larger output grows from it).
const MAX_RESERVE: usize = 1 << 28;

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

    /// The writer's entry: the text, and with `marks`, where each element starts.
    fn write(
        &self,
        options: &WriteOptions,
        marks: bool,
    ) -> Result<(String, Vec<written::Mark>), WriteError> {
        // The merged global settings, folded before anything is written.
        let merged = settings::merged(self).map_err(|k| WriteError::Conflict(k.to_string()))?;
        let style =
            FloatStyle { precision: options.precision, zero_threshold: options.zero_threshold };
        let mut w = Writer {
            text: Text::new(style, options.pretty_print),
            options,
            merged: &merged,
            marks: marks.then(Vec::new),
            open: Vec::new(),
            pending: None,
            in_wrapper: false,
            entries: HashMap::with_hasher(IdHash),
            frame_tags: rules::FrameTags::default(),
        };
        w.run(Walk::new(self).pruned(rules::is_silent), true)?;
        if let Some((tag, attribute, character)) = w.text.bad_char {
            return Err(WriteError::InvalidCharacter { tag, attribute, character });
        }
        let marks = written::located(self, w.marks.take().unwrap_or_default());
        let mut out = w.text.out;
        if out.capacity() > 2 * out.len() && out.capacity() - out.len() > 1 << 20 {
            // The reservation was far too much (elements not written: the empty
            // singletons of many default classes).
            out.shrink_to_fit();
        }
        Ok((out, marks))
    }
}

/// An element whose start tag is not finished yet.
enum Pending {
    /// `<tag attrs` is written; `>` or `/>` follows, once it is known whether a child
    /// comes.
    Started,
    /// A top-level section not written at all yet ([`Presence::OnDemand`]), to be
    /// written at `depth`: once a child comes, or at its end if it has attributes of
    /// its own.
    OnDemand { depth: usize },
}

/// The rules' decisions for one element, taken as the writer enters it.
#[derive(Clone, Copy)]
struct Decisions {
    /// How it appears ([`rules::presence`]).
    presence: Presence,
    /// The tag written ([`rules::written_tag`]).
    tag: &'static str,
    /// The depth written at ([`Writer::written_depth`]).
    depth: usize,
    /// A `childclass` of its own model is above it ([`rules::childclass_above`]).
    childclass_above: bool,
    /// Its children are under one ([`rules::childclass_below`]).
    childclass_below: bool,
    /// Its children are in MuJoCo's world ([`rules::passes_world_on`]).
    world_below: bool,
}

/// An element entered and not yet left: its instance, and the decisions taken for
/// it (its children's rules ask them; its end tag is written from them).
struct Open {
    inst: usize,
    d: Decisions,
}

/// The writer: the text so far, and where it stands in the composed walk.
struct Writer<'a> {
    text: Text,
    options: &'a WriteOptions,
    /// The merged settings sections (`compiler`, `option`, ...), written in place of
    /// the root model's own ([`rules::writes_merged_settings`]).
    merged: &'a [Node],
    /// Where each element's start tag begins (offset, the frames leading to its
    /// model, node, tag written), when asked.
    marks: Option<Vec<RawMark<'a>>>,
    /// The elements entered and not yet left.
    open: Vec<Open>,
    /// The element whose start tag is not finished.
    pending: Option<(Pending, Item<'a>)>,
    /// Inside the `<default>` wrapper of the root classes ([`rules::in_root_wrapper`]),
    /// one level deeper than the walk says.
    in_wrapper: bool,
    /// Index entries looked up by references, with the map they came from: an
    /// attached model's elements are looked up again for each attachment of it
    /// (the same shared map), and a class is looked up twice (is it there, its name).
    entries: HashMap<ElementId, (&'a ElemMap<Entry>, Option<&'a Entry>), IdHash>,
    /// Which attachment frames in the world are written as `<frame>`, as asked.
    frame_tags: rules::FrameTags,
}

impl<'a> Writer<'a> {
    /// Writes every step of `walk`: the composed walk (`composed`), or the walk of a
    /// merged settings section written in place of the outermost model's own.
    fn run(&mut self, mut walk: Walk<'a>, composed: bool) -> Result<(), WriteError> {
        while let Some(step) = walk.next() {
            let item = match step {
                Step::Enter(item) => item,
                Step::Leave(item) => {
                    self.leave(&walk.insts, item);
                    continue;
                }
            };
            if composed && item.depth == 0 {
                self.reserve_output(&walk.insts);
            }
            let section = rules::is_section(&item, composed);
            let kind = item.node.kind();
            if section && rules::merges_keys(self.options, kind) {
                walk.skip_subtree();
                self.write_merged_keys(&walk.insts)?;
                continue;
            }
            if !self.enter(&walk.insts, item, composed)? {
                walk.skip_subtree();
            }
            if section && rules::writes_merged_settings(kind) {
                walk.skip_subtree();
                if let Some(m) = self.merged.iter().find(|m| m.kind() == kind) {
                    if rules::emits(m) {
                        let model = walk.insts.list[0].model;
                        self.run(Walk::plain(model, m, 1).pruned(rules::is_silent), false)?;
                    }
                }
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
        self.text.out.reserve(elements.saturating_mul(BYTES_PER_ELEMENT).min(MAX_RESERVE));
    }

    /// Enters an element; `false` if it is not written (nor its subtree).
    fn enter(
        &mut self,
        insts: &Insts<'a>,
        item: Item<'a>,
        composed: bool,
    ) -> Result<bool, WriteError> {
        if composed && item.depth == 1 {
            self.place_in_wrapper(insts, &item)?;
        }
        let section = rules::is_section(&item, composed);
        let presence = rules::presence(&item, section, insts.list[item.inst].names.root_class);
        if presence == Presence::Omitted {
            return Ok(false);
        }
        let d = self.decide(insts, &item, section, presence);
        self.open.push(Open { inst: item.inst, d });
        match presence {
            Presence::Omitted | Presence::Transparent => {}
            Presence::OnDemand => {
                self.finish_parent(insts)?;
                self.pending = Some((Pending::OnDemand { depth: d.depth }, item));
            }
            Presence::Written => {
                if d.depth > 0 {
                    self.finish_parent(insts)?;
                }
                self.start_tag(insts, &item, d.tag, d.depth, d.childclass_above)?;
                self.pending = Some((Pending::Started, item));
            }
        }
        Ok(true)
    }

    /// The rules' decisions for `item` (to be written: `presence`), under the element
    /// entered last.
    fn decide(
        &mut self,
        insts: &Insts<'a>,
        item: &Item<'a>,
        section: bool,
        presence: Presence,
    ) -> Decisions {
        let (inst, node) = (item.inst, item.node);
        let parent = self.open.last().map(|o| (o.inst, o.d));
        let childclass_above =
            rules::childclass_above(parent.map(|(i, d)| (i, d.childclass_below)), inst);
        let childclass_below = rules::childclass_below(childclass_above, || {
            node.attached().is_none() && self.sets_childclass(insts, inst, node)
        });
        let parent_in_world = parent.is_some_and(|(_, d)| d.world_below);
        let tag = rules::written_tag(node, parent_in_world, &mut self.frame_tags);
        let worldbody = section && node.kind().is(Role::Worldbody);
        Decisions {
            presence,
            tag,
            depth: self.written_depth(item.depth, presence == Presence::Transparent),
            childclass_above,
            childclass_below,
            world_below: rules::passes_world_on(worldbody, parent_in_world, tag),
        }
    }

    /// The depth an element at `walk_depth` is written at, under the element entered
    /// last: the sections and the root classes at the wrapper's level (one deeper
    /// inside it), everything else one below its parent; an element written without
    /// tags (`transparent`) one level up, so that its children are written where it
    /// would be.
    fn written_depth(&self, walk_depth: usize, transparent: bool) -> usize {
        let depth = match self.open.last() {
            Some(o) if walk_depth > 1 => o.d.depth + 1,
            _ => walk_depth + usize::from(self.in_wrapper),
        };
        if transparent { depth.saturating_sub(1) } else { depth }
    }

    /// Opens the `<default>` wrapper of the root classes at the first of them (`item`
    /// at depth 1), or closes it at the first section after them
    /// ([`rules::in_root_wrapper`], [`rules::wrapper_says_main`]).
    fn place_in_wrapper(&mut self, insts: &Insts<'a>, item: &Item<'a>) -> Result<(), WriteError> {
        let inside = rules::in_root_wrapper(item.node.kind());
        if inside && !self.in_wrapper {
            self.finish_parent(insts)?;
            // (Only the outermost model's root class, the first, can be its main class.)
            let root_class = insts.list[item.inst].names.root_class;
            let says_main = rules::wrapper_says_main(root_class, item.node);
            self.text.line(1, if says_main { "<default class=\"main\">" } else { "<default>" });
            self.in_wrapper = true;
        } else if !inside {
            self.close_wrapper();
        }
        Ok(())
    }

    /// Closes the `<default>` wrapper of the root classes, if it is open.
    fn close_wrapper(&mut self) {
        if self.in_wrapper {
            self.text.line(1, "</default>");
            self.in_wrapper = false;
        }
    }

    fn leave(&mut self, insts: &Insts<'a>, item: Item<'a>) {
        let Some(open) = self.open.pop() else { return };
        if open.d.presence == Presence::Transparent {
            return;
        }
        if item.depth == 0 {
            self.close_wrapper();
        }
        match self.pending.take() {
            Some((Pending::Started, _)) => {
                self.text.out.push_str("/>");
                self.text.newline();
            }
            Some((Pending::OnDemand { depth }, item)) => {
                if rules::writes_own_attrs(item.node) {
                    // Attributes only: failures are reported by `bad_char` or not at all.
                    let tag = item.node.kind().tag();
                    let _ = self.start_tag(insts, &item, tag, depth, false);
                    self.text.out.push_str("/>");
                    self.text.newline();
                }
            }
            None => {
                self.text.indent(open.d.depth);
                self.text.out.push_str("</");
                self.text.out.push_str(open.d.tag);
                self.text.out.push('>');
                self.text.newline();
            }
        }
    }

    /// Finishes the start tag of the parent of a child about to be written.
    fn finish_parent(&mut self, insts: &Insts<'a>) -> Result<(), WriteError> {
        match self.pending.take() {
            Some((Pending::Started, _)) => {
                self.text.out.push('>');
                self.text.newline();
            }
            Some((Pending::OnDemand { depth }, item)) => {
                self.start_tag(insts, &item, item.node.kind().tag(), depth, false)?;
                self.text.out.push('>');
                self.text.newline();
            }
            None => {}
        }
        Ok(())
    }

    /// Writes `<tag attrs` (not closed) at `depth`. `childclass_above`: as
    /// [`Writer::write_attrs`] takes it.
    fn start_tag(
        &mut self,
        insts: &Insts<'a>,
        item: &Item<'a>,
        tag: &'static str,
        depth: usize,
        childclass_above: bool,
    ) -> Result<(), WriteError> {
        let node = item.node;
        self.text.indent(depth);
        if let Some(marks) = &mut self.marks {
            let frames = insts.list[item.inst].frames.clone();
            marks.push((self.text.out.len(), frames, node, tag));
        }
        self.text.out.push('<');
        self.text.out.push_str(tag);
        if node.attached().is_some() {
            // An attachment frame is a body of its parent's model, which has no class.
            return self.write_attrs(insts, item, true);
        }
        if let Some(name) = rules::implicit_model_name(node) {
            self.text.out.push_str(" model=\"");
            self.text.out.push_str(name);
            self.text.out.push('"');
        }
        self.write_attrs(insts, item, childclass_above)
    }

    /// Writes the composed keys in place of the keyframe section
    /// ([`rules::merges_keys`]).
    fn write_merged_keys(&mut self, insts: &Insts<'a>) -> Result<(), WriteError> {
        let keys = crate::model::keys::merged_keys(insts.list[0].model)?;
        if keys.is_empty() {
            return Ok(());
        }
        self.finish_parent(insts)?;
        self.close_wrapper();
        self.text.line(1, "<keyframe>");
        for key in keys {
            let text = &mut self.text;
            text.indent(2);
            text.out.push_str("<key");
            if let Some(name) = &key.name {
                text.value.clear();
                text.value.push_str(name);
                text.value_attr("key", "name");
            }
            if let Some(t) = key.time {
                text.value.clear();
                Value::Float(t).write_plain(&mut text.value, text.style);
                text.value_attr("key", "time");
            }
            for (field, values) in key.fields {
                text.value.clear();
                Value::Floats(values.into()).write_plain(&mut text.value, text.style);
                text.value_attr("key", field);
            }
            text.out.push_str("/>");
            text.newline();
        }
        self.text.line(1, "</keyframe>");
        Ok(())
    }
}
