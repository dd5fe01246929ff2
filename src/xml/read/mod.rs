//! MJCF text → [`Model`]. The only code that reads XML.
//!
//! What is kept and what is dropped:
//! - comments, processing instructions, the XML declaration, a DOCTYPE and text are
//!   dropped, and CDATA but a `<text>`'s, which is its data as MuJoCo reads it
//!   (`cdata`); entities other than XML's five and character references are errors
//!   (nothing is ever expanded);
//! - on the root only `model` is read (the tag may be anything starting with
//!   `mujoco`, as in the reference);
//! - a section given twice at the root merges (later values win per attribute), as
//!   MuJoCo merges them; any other singleton given twice in one element is
//!   [`ErrorKind::DuplicateChild`], as MuJoCo refuses it (a singleton in a section
//!   given twice merges as its section does);
//! - `<include file=…>` (relative to the including file's folder) is read as MuJoCo
//!   reads it, the file's root's content in place of the tag, into the same elements:
//!   at the root, a singleton section the file gives again merges (the later value
//!   winning per attribute, wherever the include is), and the elements a file
//!   included at the root adds to a section come after the including file's own, in
//!   the reference's order (`include::order_as_reference`); one model's include tree
//!   includes each file once (MuJoCo's rule);
//! - file attributes are read at once, relative to the model's folder and the
//!   `compiler` folder settings seen so far; a nameless mesh, texture or height field
//!   is named after its file;
//! - every reference that names an existing element is resolved to it, so renaming
//!   the element later renames the reference.
//!
// Implementation notes: elements are collected in an arena while reading (iteratively,
// no recursion) and turned into nodes bottom-up at the end; children always come after
// their parent in the arena.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use quick_xml::events::{BytesStart, Event};
use smol_str::SmolStr;

use crate::error::{ErrorKind, ReadError, TextPos};
use crate::files::{self, FileContext};
use crate::model::tree::{Attr, ElementId, no_attrs, take_attrs};
use crate::model::{
    Basepaths, Input, Model, ModelFiles, ValueCtx, check_class_named, check_required,
    check_root_class_name, name_from_file,
};
use crate::schema::{AttrType, ElementKind, Multiplicity};
use crate::value::Value;
use crate::xml::source::{NO_RECORD, RecordKind};

mod cdata;
mod events;
mod finish;
mod include;

use events::Events;
use finish::finish;
pub(crate) use include::Includes;
use include::{order_as_reference, splice_include};

/// The tag of an include, which is no element: the file it names is read in its place.
use crate::files::scan::INCLUDE;

/// How many `<include>`s may nest inside each other.
pub(crate) const MAX_INCLUDE_DEPTH: usize = 100;

/// How to read MJCF.
///
/// # Examples
/// ```
/// let xml = r#"<mujoco><asset><mesh file="box.stl"/></asset></mujoco>"#;
/// let m = mjcf::ReadOptions::new().asset("box.stl", b"solid box".to_vec()).read_str(xml).unwrap();
/// assert!(m.find(mjcf::Namespace::Mesh, "box").is_some());
/// ```
#[derive(Clone, Debug)]
pub struct ReadOptions {
    assets: HashMap<String, Arc<[u8]>>,
    pub(crate) base_dir: Option<PathBuf>,
    confine: bool,
    pub(crate) keep_source: bool,
    pub(crate) max_depth: usize,
    pub(crate) max_file_size: u64,
}

impl Default for ReadOptions {
    fn default() -> Self {
        ReadOptions {
            assets: HashMap::new(),
            base_dir: None,
            confine: false,
            keep_source: true,
            max_depth: 1_000_000,
            max_file_size: files::DEFAULT_MAX_FILE_SIZE,
        }
    }
}

impl ReadOptions {
    /// Default options: files from disk relative to the model's folder, no limit on
    /// where they are, nesting up to 1,000,000 levels, files up to 1 GiB each.
    ///
    /// Time: O(1).
    pub fn new() -> ReadOptions {
        ReadOptions::default()
    }

    /// Adds an in-memory file, found by the path as written in MJCF (or joined with
    /// the compiler's folder setting) before the disk is tried. Root-level
    /// `<include file=…>`s are looked for here too, by the path as written.
    ///
    /// Time: O(size of `contents`) when given as a `Vec<u8>` or slice (copied into an
    /// `Arc`), O(1) for an `Arc<[u8]>`; plus O(length of `path`).
    #[must_use]
    pub fn asset(mut self, path: &str, contents: impl Into<Arc<[u8]>>) -> ReadOptions {
        self.assets.insert(path.to_string(), contents.into());
        self
    }

    /// The folder relative paths resolve against when reading from a string (default:
    /// the working directory). `read_path` uses the file's folder.
    ///
    /// Time: O(1).
    #[must_use]
    pub fn base_dir(mut self, dir: impl Into<PathBuf>) -> ReadOptions {
        self.base_dir = Some(dir.into());
        self
    }

    /// Refuses files outside the model's folder, for models from untrusted sources:
    /// absolute paths, `..` leading out of it, and paths that leave it once symlinks
    /// are followed (a symlinked file or folder pointing outside; one that stays inside
    /// is fine). Applies to `<include>`s and every file attribute, when reading and on
    /// later edits of the model read ([`ErrorKind::FileOutsideRoot`]). An included
    /// file's folder is the folder for the files it names. In-memory files
    /// ([`ReadOptions::asset`]) are not affected. Off by default, as MJCF models
    /// commonly share assets through `../`.
    ///
    /// Time: O(1).
    #[must_use]
    pub fn confine_to_base_dir(mut self, confine: bool) -> ReadOptions {
        self.confine = confine;
        self
    }

    /// Keeps the text read (default `true`): every file's text and where each element's
    /// tags are in it, so that [`Model::save`] and [`Model::to_source_files`] write
    /// untouched parts back byte for byte. Off, a model read keeps nothing of its
    /// text (as one built through the API), and those refuse to write it.
    ///
    /// Time: O(1).
    #[must_use]
    pub fn keep_source(mut self, keep: bool) -> ReadOptions {
        self.keep_source = keep;
        self
    }

    /// The deepest element nesting accepted (default 1,000,000); deeper input is a
    /// [`ErrorKind::TooDeep`] error.
    ///
    /// Time: O(1).
    #[must_use]
    pub fn max_depth(mut self, depth: usize) -> ReadOptions {
        self.max_depth = depth;
        self
    }

    /// The largest file read from disk, in bytes (default 1 GiB, which real models
    /// never reach): the model file, `<include>`s and file attributes, when reading and
    /// on later edits of the model read. A larger file is a
    /// [`ErrorKind::FileTooLarge`] error; the read is bounded, so a file that grows
    /// while being read stops at the cap. Whatever the cap, only regular files are
    /// read: a folder, a FIFO or a device (`/dev/zero`) is a [`ErrorKind::NotAFile`]
    /// error, found before the file is opened.
    ///
    /// Time: O(1).
    #[must_use]
    pub fn max_file_size(mut self, bytes: u64) -> ReadOptions {
        self.max_file_size = bytes;
        self
    }

    pub(crate) fn context(&self, base_dir: Option<PathBuf>) -> FileContext {
        FileContext {
            base_dir,
            assets: if self.assets.is_empty() { None } else { Some(Arc::new(self.assets.clone())) },
            confine: self.confine,
            max_file_size: self.max_file_size,
        }
    }
}

pub(crate) fn utf8<'b>(bytes: &'b [u8], file: Option<&Path>) -> Result<&'b str, ReadError> {
    std::str::from_utf8(bytes).map_err(|e| {
        let good = &bytes[..e.valid_up_to()];
        // The valid prefix is UTF-8 by definition.
        let prefix = std::str::from_utf8(good).unwrap_or("");
        ReadError::new(
            ErrorKind::InvalidUtf8,
            file.map(Path::to_path_buf),
            Some(TextPos::of_offset(prefix, prefix.len())),
        )
    })
}

/// An element being read.
struct Pending {
    kind: ElementKind,
    id: ElementId,
    /// In their final form (sorted, one allocation), as the node will hold them.
    attrs: Arc<[Attr]>,
    /// The children, in document order, as a list through the arena (no allocation
    /// per element): the first and last child, and the next sibling (or [`NONE`]).
    first_child: usize,
    last_child: usize,
    next_sibling: usize,
    /// The singleton and on-demand children read so far (few), found without
    /// scanning the children, which may be many: a second list through the arena
    /// (its first entry here, the next one in each child), so that an element
    /// allocates nothing for it.
    first_unique: usize,
    next_unique: usize,
    /// Where its (first) tag is: the offset in the text of `Reader::files[file]`.
    offset: usize,
    file: u32,
    /// The tag of its parent it was last given in (`Open::tag`), for a singleton
    /// given twice in one tag.
    given_in: u32,
}

/// No arena entry (the end of a children list).
const NONE: usize = usize::MAX;

impl Pending {
    fn new(kind: ElementKind, attrs: Arc<[Attr]>, (file, offset): (u32, usize)) -> Pending {
        Pending {
            kind,
            id: ElementId::fresh(),
            attrs,
            first_child: NONE,
            last_child: NONE,
            next_sibling: NONE,
            first_unique: NONE,
            next_unique: NONE,
            offset,
            file,
            given_in: 0,
        }
    }
}

/// Appends the entry `c` to the children of `parent`.
fn push_child(arena: &mut [Pending], parent: usize, c: usize) {
    arena[c].next_sibling = NONE;
    match arena[parent].last_child {
        NONE => arena[parent].first_child = c,
        last => arena[last].next_sibling = c,
    }
    arena[parent].last_child = c;
}

/// The singleton or on-demand child of kind `kind` of the entry `parent`, if read.
fn unique_child(arena: &[Pending], parent: usize, kind: ElementKind) -> Option<usize> {
    let mut c = arena[parent].first_unique;
    while c != NONE {
        if arena[c].kind == kind {
            return Some(c);
        }
        c = arena[c].next_unique;
    }
    None
}

/// Adds the entry `c` (a singleton or on-demand child) to the unique children of
/// `parent` (at the front: they are found by kind, in no order).
fn push_unique(arena: &mut [Pending], parent: usize, c: usize) {
    arena[c].next_unique = arena[parent].first_unique;
    arena[parent].first_unique = c;
}

/// The children of the entry `i`, in document order.
fn children_of(arena: &[Pending], i: usize) -> impl Iterator<Item = usize> + '_ {
    let first = Some(arena[i].first_child).filter(|&c| c != NONE);
    std::iter::successors(first, move |&c| Some(arena[c].next_sibling).filter(|&n| n != NONE))
}

/// The text of a file read: the main text as given, an included file's as read.
#[derive(Clone)]
enum Text<'t> {
    Given(&'t str),
    Included(Arc<str>),
}

impl std::ops::Deref for Text<'_> {
    type Target = str;
    fn deref(&self) -> &str {
        match self {
            Text::Given(t) => t,
            Text::Included(t) => t,
        }
    }
}

/// A file read: its text and path (for the positions of errors found after reading),
/// and the group its elements are ordered in (`include::order_as_reference`).
struct FileRead<'t> {
    text: Text<'t>,
    path: Option<PathBuf>,
    /// The main text's and each file included at the root have their own group (its
    /// index in `Reader::files`: the order they are met in), a file included inside an
    /// element its includer's.
    group: u32,
}

/// Reads one document and the files it includes, into one arena. What belongs to the
/// file being read (`at`, `ctx`, `src`) is swapped while an include is read.
struct Reader<'t> {
    /// Every file read so far, the main text first.
    files: Vec<FileRead<'t>>,
    /// The file being read, in `files`.
    at: u32,
    /// Where the files the file being read names are.
    ctx: FileContext,
    /// The asset model files this read has read.
    model_files: &'t ModelFiles,
    arena: Vec<Pending>,
    /// How many tags were opened (`next_tag`).
    tags: u32,
    /// The compiler's folder settings read so far (global in MuJoCo: those an
    /// included file sets apply after its include too, and the other way round).
    basepaths: Basepaths,
    /// The attributes of the tag being read: one buffer for all, so that each
    /// element allocates its attributes once, at their final size.
    scratch: Vec<Attr>,
    /// Where the tags of the file being read are recorded (`xml::source`), if the
    /// source is kept.
    src: Option<SrcFile>,
    /// The class `/` folded into the root class (`finish::hoist_root_class`): its
    /// element and the root class's.
    hoisted: Option<(ElementId, ElementId)>,
    /// The `<text>`s read, for their CDATA (`cdata`).
    text_fields: cdata::TextFields,
}

/// How a text's tags are recorded: its file in the source, and what its root tag
/// stands for.
#[derive(Clone, Copy)]
pub(crate) struct SrcFile {
    file: u32,
    /// `Element` for the main file; `FileRoot` for an included file.
    root_kind: RecordKind,
    /// The element an included file's root stands for (the element holding the
    /// `<include>`); `None` for the main text's root, which stands for itself.
    stands_for: Option<ElementId>,
}

impl Reader<'_> {
    /// A number for a tag opened now, told apart from those opened before.
    fn next_tag(&mut self) -> u32 {
        // Wrapping after 2^32 tags: a singleton then given again in a tag that many
        // tags before can be taken as given twice in one tag, in an input of 2^32 tags.
        self.tags = self.tags.wrapping_add(1);
        self.tags
    }

    /// The error `kind` at `offset` in the file being read.
    fn err(&self, kind: ErrorKind, offset: usize) -> ReadError {
        self.err_in(self.at, kind, offset)
    }

    /// The error `kind` at `offset` in the file `files[file]`.
    fn err_in(&self, file: u32, kind: ErrorKind, offset: usize) -> ReadError {
        let f = &self.files[file as usize];
        ReadError::new(kind, f.path.clone(), Some(TextPos::of_offset(&f.text, offset)))
    }

    /// Reads the attributes of a tag into `attrs` (later values win), sorted by index.
    fn read_attrs(
        &mut self,
        kind: ElementKind,
        tag: &BytesStart<'_>,
        attrs: &mut Vec<Attr>,
        offset: usize,
    ) -> Result<(), ReadError> {
        // Duplicate names are found by attribute index here (a bit per index below
        // 256), not by quick-xml's check, which compares every name with every earlier
        // one and allocates a list of them per tag. Two names with one index are
        // `class` and `dclass`, or a duplicate: for those (and any syntax error) the
        // tag's attributes are iterated again with quick-xml's checks, which report the
        // error exactly as they always did (or none, for `class` and `dclass`).
        let mut seen = [0u64; 4];
        let mut attributes = tag.attributes();
        attributes.with_checks(false);
        for (n, a) in attributes.enumerate() {
            let Ok(a) = a else { return Err(self.checked_attrs_error(tag, n + 1, offset)) };
            let name: &str = a.key.as_ref();
            let name = if name == "dclass" { "class" } else { name };
            let found = kind.attr_index(name);
            if let Some(index) = found {
                let (word, bit) = (index / 64, 1u64 << (index % 64));
                if seen.get(word).is_none_or(|w| w & bit != 0) {
                    self.check_attrs(tag, n + 1, offset)?;
                }
                if let Some(w) = seen.get_mut(word) {
                    *w |= bit;
                }
            }
            let raw = a
                .normalized_value(quick_xml::XmlVersion::default())
                .map_err(|e| self.err(ErrorKind::Syntax(e.to_string()), offset))?;
            let Some(index) = found else {
                return Err(self.err(ErrorKind::unknown_attribute(kind, name), offset));
            };
            let ctx = ValueCtx {
                files: &self.ctx,
                basepaths: &self.basepaths,
                model_files: self.model_files,
            };
            // The value is parsed into its place at the end of the list (returned, it
            // was copied in parts and read back whole, a stalled load per attribute).
            let i = index as u16;
            let pos = attrs.iter().position(|(k, _)| *k == i);
            attrs.push((i, Value::Int(0)));
            let last = attrs.len() - 1;
            let set = match ctx.assign_text_into(kind, index, &raw, &mut attrs[last].1) {
                Ok(set) => set,
                Err(k) => {
                    attrs.pop();
                    return Err(self.err(k, offset));
                }
            };
            if let AttrType::Basepath { path_namespace } = kind.attr(index).ty {
                let folder = attrs[last].1.as_str().filter(|_| set).map(SmolStr::from);
                self.basepaths.set(path_namespace, folder);
            }
            match (pos, set) {
                (None, true) => {}
                (None, false) => {
                    attrs.pop();
                }
                // Given again (`class` and `dclass`): the later value replaces it.
                (Some(p), true) => {
                    if let Some((_, v)) = attrs.pop() {
                        attrs[p].1 = v;
                    }
                }
                (Some(p), false) => {
                    attrs.pop();
                    attrs.remove(p);
                }
            }
        }
        // Indices are unique here: an unstable sort orders them alike, in place.
        attrs.sort_unstable_by_key(|(k, _)| *k);
        Ok(())
    }

    /// The first error quick-xml's checked iteration of the tag's first `upto`
    /// attributes finds (a syntax error or a duplicate name), as reading always
    /// reported it.
    fn check_attrs(
        &self,
        tag: &BytesStart<'_>,
        upto: usize,
        offset: usize,
    ) -> Result<(), ReadError> {
        match tag.attributes().take(upto).find_map(Result::err) {
            Some(e) => Err(self.err(ErrorKind::Syntax(e.to_string()), offset)),
            None => Ok(()),
        }
    }

    /// The error of a tag whose unchecked attribute iteration failed at attribute
    /// `upto - 1`: the checked one fails there too (with a duplicate name there, it
    /// reports that first).
    fn checked_attrs_error(&self, tag: &BytesStart<'_>, upto: usize, offset: usize) -> ReadError {
        match self.check_attrs(tag, upto, offset) {
            Err(e) => e,
            // Cannot happen: both iterations parse alike.
            Ok(()) => self.err(ErrorKind::Syntax("malformed attributes".into()), offset),
        }
    }
}

/// A tag being read: where it is in the text and the record of its parent.
#[derive(Clone, Copy)]
struct At {
    offset: usize,
    /// Just after the tag.
    after: usize,
    parent_rec: u32,
    /// The parent's tag (`Open::tag`).
    parent_tag: u32,
    /// How many elements are open around it (an included file's root counting as
    /// the element it is read into).
    depth: usize,
}

/// An open tag: its arena entry (`usize::MAX` for content that is not read: an
/// include's content), its record (`NO_RECORD` when not recorded), and the tag it is
/// (`Reader::tags` when it was opened; an included file's root is the tag of the
/// `<include>`'s parent, whose content it continues).
#[derive(Clone, Copy)]
struct Open {
    entry: usize,
    rec: u32,
    tag: u32,
}

/// Where [`parse`] reads a file's content: the main text's into a new root entry;
/// an included file's into the arena entry `entry` (the element holding the
/// `<include>`: see [`Spot`]).
#[derive(Clone, Copy)]
enum Place {
    Root,
    Entry(Spot),
}

/// Where an included file's content goes: the arena entry of the element holding the
/// `<include>`, that element's tag (`Open::tag`) and how many elements are open
/// around it.
#[derive(Clone, Copy)]
struct Spot {
    entry: usize,
    tag: u32,
    depth: usize,
}

/// Reads the events of the file being read (`r.at`) into `r.arena`, in the place
/// `into` says; returns the `model` attribute of the main text's root.
fn parse(
    r: &mut Reader<'_>,
    into: Place,
    max_depth: usize,
    tree: &mut Includes,
) -> Result<Option<SmolStr>, ReadError> {
    let mut stack: Vec<Open> = Vec::new();
    // A shared copy: `r` stays free to be changed while the text is read.
    let text = r.files[r.at as usize].text.clone();
    let mut xml = Events::new(&text);
    let (mut model_name, mut seen_root) = (None, false);
    // How many elements are open around the file's root.
    let outer = match into {
        Place::Root => 0,
        Place::Entry(spot) => spot.depth,
    };
    loop {
        let offset = xml.position();
        let event = match xml.read_event() {
            Ok(e) => e,
            Err(e) => {
                let at = xml.error_position();
                return Err(r.err(ErrorKind::Syntax(e.to_string()), at));
            }
        };
        let (tag, empty) = match event {
            Event::Start(t) => (t, false),
            Event::Empty(t) => (t, true),
            Event::End(_) => {
                if let (Some(open), Some(src)) = (stack.pop(), tree.src.as_mut()) {
                    src.close(open.rec, offset, xml.position());
                }
                continue;
            }
            Event::Eof => break,
            Event::CData(t) => {
                cdata::read(r, stack.last(), t.as_ref(), offset)?;
                continue;
            }
            Event::Text(t) => {
                if stack.is_empty() && !t.as_ref().trim().is_empty() {
                    return Err(
                        r.err(ErrorKind::Syntax("text outside the root element".into()), offset)
                    );
                }
                continue;
            }
            _ => continue,
        };
        let after = xml.position();
        let Some(&parent) = stack.last() else {
            if seen_root {
                return Err(r.err(ErrorKind::Syntax("more than one root element".into()), offset));
            }
            seen_root = true;
            let (open, name) = read_root(r, &tag, into, tree, (offset, after))?;
            model_name = name;
            if !empty {
                stack.push(open);
            }
            continue;
        };
        let depth = outer + stack.len();
        let at = At { offset, after, parent_rec: parent.rec, parent_tag: parent.tag, depth };
        let open = read_tag(r, &tag, parent.entry, at, max_depth, tree)?;
        if !empty {
            stack.push(open);
        }
    }
    if !seen_root {
        return Err(r.err(ErrorKind::Syntax("no root element".into()), text.len()));
    }
    if !stack.is_empty() {
        return Err(r.err(ErrorKind::Syntax("unclosed element at end of input".into()), text.len()));
    }
    Ok(model_name)
}

/// Records a tag (`kind`, standing for the element `id`) under the record
/// `parent_rec`, if this text is recorded.
fn record(r: &Reader<'_>, tree: &mut Includes, kind: RecordKind, id: ElementId, at: At) -> u32 {
    match (r.src, tree.src.as_mut()) {
        (Some(f), Some(src)) if at.parent_rec != NO_RECORD => {
            src.open(f.file, kind, id, at.parent_rec, at.offset, at.after)
        }
        _ => NO_RECORD,
    }
}

/// The root tag: its name is checked; the main text's root becomes the arena's first
/// entry, its `model` attribute returned; an included file's root stands for the
/// entry it is read into (its `model` attribute is not read, as in MuJoCo).
fn read_root(
    r: &mut Reader<'_>,
    tag: &BytesStart<'_>,
    into: Place,
    tree: &mut Includes,
    (offset, after): (usize, usize),
) -> Result<(Open, Option<SmolStr>), ReadError> {
    let qname = tag.name();
    let name: &str = qname.as_ref();
    if !name.starts_with("mujoco") {
        return Err(r.err(ErrorKind::WrongRoot(name.into()), offset));
    }
    let mut model_name = None;
    for a in tag.attributes() {
        let a = a.map_err(|e| r.err(ErrorKind::Syntax(e.to_string()), offset))?;
        if a.key.as_ref() == "model" && matches!(into, Place::Root) {
            let v = a
                .normalized_value(quick_xml::XmlVersion::default())
                .map_err(|e| r.err(ErrorKind::Syntax(e.to_string()), offset))?;
            model_name = Some(SmolStr::from(v.as_ref()));
        }
    }
    let (entry, open_tag) = match into {
        Place::Root => {
            r.arena.push(Pending::new(ElementKind::ROOT, no_attrs(), (r.at, offset)));
            (0, r.next_tag())
        }
        Place::Entry(spot) => (spot.entry, spot.tag),
    };
    let rec = match (r.src, tree.src.as_mut()) {
        (Some(f), Some(src)) => {
            let id = f.stands_for.unwrap_or(r.arena[entry].id);
            src.open(f.file, f.root_kind, id, NO_RECORD, offset, after)
        }
        _ => NO_RECORD,
    };
    Ok((Open { entry, rec, tag: open_tag }, model_name))
}

/// A tag under the root: an `<include>`, content that is not read, or an element.
fn read_tag(
    r: &mut Reader<'_>,
    tag: &BytesStart<'_>,
    parent: usize,
    at: At,
    max_depth: usize,
    tree: &mut Includes,
) -> Result<Open, ReadError> {
    let qname = tag.name();
    let name: &str = qname.as_ref();
    let offset = at.offset;
    if parent == usize::MAX {
        return Ok(Open { entry: usize::MAX, rec: NO_RECORD, tag: at.parent_tag });
    }
    if name == INCLUDE {
        let rec = record(r, tree, RecordKind::Include, r.arena[parent].id, at);
        // MuJoCo accepts `<include>` anywhere: the included file's root's content is
        // read in its place, as children of `parent`.
        // The file's root stands for `parent`, which has `at.depth - 1` elements open
        // around it.
        let spot = Spot { entry: parent, tag: at.parent_tag, depth: at.depth - 1 };
        splice_include(r, tag, offset, spot, max_depth, tree)?;
        // An include's content is ignored; tracked so that its end tag matches.
        return Ok(Open { entry: usize::MAX, rec, tag: at.parent_tag });
    }
    let parent_kind = r.arena[parent].kind;
    let Some(kind) = parent_kind.child(name) else {
        return Err(r.err(ErrorKind::invalid_child(parent_kind, name), offset));
    };
    if at.depth >= max_depth {
        return Err(r.err(ErrorKind::TooDeep(max_depth), offset));
    }
    let index = read_element(r, tag, (parent, at.parent_tag), kind, offset)?;
    if kind.is(crate::schema::Role::TextField) {
        r.text_fields.opened(index, tag);
    }
    let rec = record(r, tree, RecordKind::Element, r.arena[index].id, at);
    Ok(Open { entry: index, rec, tag: r.next_tag() })
}

/// An element of `kind` under the arena entry `parent` (in its tag `parent_tag`): a
/// new entry, or (a section given again at the root, or a singleton of a section
/// given again) the entry read before, its attributes updated. Returns the entry.
fn read_element(
    r: &mut Reader<'_>,
    tag: &BytesStart<'_>,
    (parent, parent_tag): (usize, u32),
    kind: ElementKind,
    offset: usize,
) -> Result<usize, ReadError> {
    let parent_kind = r.arena[parent].kind;
    let existing = match kind.multiplicity() {
        Multiplicity::Repeated => None,
        _ => unique_child(&r.arena, parent, kind),
    };
    let mut attrs = std::mem::take(&mut r.scratch);
    attrs.clear();
    match (kind.multiplicity(), existing) {
        // MuJoCo merges sections given again at the root, and refuses any other
        // singleton given twice in one tag (an included file's content in it too).
        (Multiplicity::Singleton, Some(e)) if parent == 0 || r.arena[e].given_in != parent_tag => {
            r.arena[e].given_in = parent_tag;
            attrs.extend(r.arena[e].attrs.iter().cloned());
            let res = r.read_attrs(kind, tag, &mut attrs, offset).and_then(|()| {
                check_root_class_name(parent_kind, kind, &attrs).map_err(|k| r.err(k, offset))
            });
            r.arena[e].attrs = take_attrs(&mut attrs);
            r.scratch = attrs;
            res?;
            Ok(e)
        }
        (_, Some(_)) => {
            r.scratch = attrs;
            Err(r.err(ErrorKind::DuplicateChild(kind.tag()), offset))
        }
        (m, _) => {
            r.read_attrs(kind, tag, &mut attrs, offset)?;
            check_root_class_name(parent_kind, kind, &attrs).map_err(|k| r.err(k, offset))?;
            if m != Multiplicity::Singleton {
                name_from_file(kind, &mut attrs);
                check_required(kind, &attrs).map_err(|k| r.err(k, offset))?;
                check_class_named(parent_kind, kind, &attrs).map_err(|k| r.err(k, offset))?;
            }
            let stored = take_attrs(&mut attrs);
            r.scratch = attrs;
            let i = r.arena.len();
            r.arena.push(Pending::new(kind, stored, (r.at, offset)));
            r.arena[i].given_in = parent_tag;
            push_child(&mut r.arena, parent, i);
            if m != Multiplicity::Repeated {
                push_unique(&mut r.arena, parent, i);
            }
            Ok(i)
        }
    }
}

/// Reads one document as its text spells it (includes spliced in as they are read):
/// the reader's whole job; reopening scenes is a step after it (`xml::open`).
pub(crate) fn read_literal(
    text: &str,
    file: Option<PathBuf>,
    ctx: FileContext,
    max_depth: usize,
    tree: &mut Includes,
    model_files: &ModelFiles,
    src: Option<SrcFile>,
) -> Result<Model, ReadError> {
    let mut r = Reader {
        files: vec![FileRead { text: Text::Given(text), path: file, group: 0 }],
        at: 0,
        tags: 0,
        ctx,
        model_files,
        arena: Vec::new(),
        basepaths: Basepaths::default(),
        scratch: Vec::new(),
        src,
        hoisted: None,
        text_fields: cdata::TextFields::default(),
    };
    let first = tree.src.as_ref().map_or(0, |s| s.records.len());
    let model_name = parse(&mut r, Place::Root, max_depth, tree)?;
    order_as_reference(&mut r.arena, &r.files);
    let model = finish(&mut r, model_name)?;
    if let (Some((from, to)), Some(src)) = (r.hoisted, tree.src.as_mut()) {
        // The class `/` folded into the root class: its tag stands for the root class.
        src.remap(first, &HashMap::from([(from, to)]));
    }
    Ok(model)
}
