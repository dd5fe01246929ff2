//! MJCF text → [`Model`]. The only code that reads XML.
//!
//! What is kept and what is dropped:
//! - comments, processing instructions, the XML declaration, a DOCTYPE and text are
//!   dropped; entities other than XML's five and character references are errors
//!   (nothing is ever expanded);
//! - on the root only `model` is read (the tag may be anything starting with
//!   `mujoco`, as in the reference);
//! - a singleton tag given twice merges (later values win per attribute);
//! - root-level `<include file=…>` is read as its own model (relative to the including
//!   file's folder) and merged with [`Model::include_copy`] after the main content;
//!   one model's include tree includes each file once (MuJoCo's rule);
//! - file attributes are read at once, relative to the model's folder and the
//!   `compiler` folder settings seen so far; a nameless mesh, texture or height field
//!   is named after its file;
//! - every reference that names an existing element is resolved to it, so renaming
//!   the element later renames the reference.
//!
// Implementation notes: elements are collected in an arena while reading (iteratively,
// no recursion) and turned into nodes bottom-up at the end; children always come after
// their parent in the arena.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use crate::seq::Seq;
use quick_xml::events::{BytesStart, Event};
use smol_str::SmolStr;

use crate::error::{ErrorKind, ReadError, TextPos};
use crate::files::{self, FileContext};
use crate::model::tree::{Attr, ElementId, Node, no_attrs, take_attrs};
use crate::model::{
    Basepaths, Input, Model, ModelFiles, ReadIndex, ValueCtx, check_class_named, check_required,
    empty_node, empty_node_with_id, name_from_file,
};
use crate::schema::{AttrType, ElementKind, Multiplicity, PathNamespace};
use crate::value::{Reference, Value};

use super::write::policy;

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
    base_dir: Option<PathBuf>,
    confine: bool,
    max_depth: usize,
    max_file_size: u64,
}

impl Default for ReadOptions {
    fn default() -> Self {
        ReadOptions {
            assets: HashMap::new(),
            base_dir: None,
            confine: false,
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

    fn context(&self, base_dir: Option<PathBuf>) -> FileContext {
        FileContext {
            base_dir,
            assets: if self.assets.is_empty() { None } else { Some(Arc::new(self.assets.clone())) },
            confine: self.confine,
            max_file_size: self.max_file_size,
        }
    }

    /// Reads a model from MJCF text.
    ///
    /// Time: O(L + n · log n) for `L` bytes of text holding `n` elements, plus reading
    /// and hashing the files it names (each asset model file, and the files it names
    /// in turn, read once however often it is named; each include file at most once,
    /// as one model includes a file once), plus O(in-memory files) to copy their table
    /// for the model. Each root-level `<include>` is read the same way and
    /// merged by [`Model::include_copy`] (O(n · log n) each); a model with includes
    /// then resolves references by name again, and a reference that names nothing
    /// costs O(named elements) there.
    ///
    /// # Errors
    /// A [`ReadError`] with the line and column of the problem (and the file, for an
    /// included file); its [`kind`](ReadError::kind):
    /// - [`ErrorKind::Syntax`]: malformed XML (also text outside the root, a second
    ///   root, an unclosed element, an entity other than XML's five);
    /// - [`ErrorKind::WrongRoot`]: the root tag does not start with `mujoco`;
    /// - [`ErrorKind::InvalidChild`], [`ErrorKind::DuplicateChild`]: an element the
    ///   schema does not allow there, or a second on-demand one (`inertial`);
    /// - [`ErrorKind::UnknownAttribute`], [`ErrorKind::InvalidValue`],
    ///   [`ErrorKind::MissingRequired`]: an attribute the element does not have, a
    ///   value that does not fit, a required attribute not given;
    /// - [`ErrorKind::DuplicateIdentifier`]: a name used twice in its namespace
    ///   (also across includes);
    /// - [`ErrorKind::FileNotFound`], [`ErrorKind::FileOutsideRoot`]: a file or
    ///   include that cannot be read, or (confined) lies outside the model's folder;
    /// - [`ErrorKind::InvalidUtf8`]: an included file that is not UTF-8;
    /// - [`ErrorKind::IncludeCycle`]: an include that includes itself;
    /// - [`ErrorKind::IncludedTwice`]: an include of a file the model's include tree
    ///   already includes (anywhere in it, by its canonical path; in-memory files by
    ///   their path as written, normalised), as MuJoCo refuses it;
    /// - [`ErrorKind::TooManyFiles`]: an asset `<model>` file that brings more than
    ///   100,000 files (counting the model files it names, each path once);
    /// - [`ErrorKind::TooDeep`]: elements nested deeper than
    ///   [`max_depth`](ReadOptions::max_depth), includes more than 100 deep, or asset
    ///   model files naming model files more than 16 deep;
    /// - [`ErrorKind::AttributeConflict`]: an include whose global settings disagree
    ///   with the including model's.
    pub fn read_str(&self, text: &str) -> Result<Model, ReadError> {
        let ctx = self.context(self.base_dir.clone());
        // The main text takes the first place in the include tree, as a file does.
        let mut tree = Includes::new(PathBuf::from("<main text>"));
        let model_files = ModelFiles::default();
        read_document(text, None, ctx, self.max_depth, &mut tree, &model_files)
    }

    /// Reads a model from MJCF bytes (which must be UTF-8).
    ///
    /// Time: O(L) to check the encoding, then as [`ReadOptions::read_str`].
    ///
    /// # Errors
    /// [`ErrorKind::InvalidUtf8`] for bytes that are not UTF-8 (at the first bad
    /// byte); otherwise as [`ReadOptions::read_str`].
    pub fn read_bytes(&self, bytes: &[u8]) -> Result<Model, ReadError> {
        let text = utf8(bytes, None)?;
        self.read_str(text)
    }

    /// Reads a model from a file; relative paths in it resolve against its folder.
    ///
    /// Time: reading the file, then as [`ReadOptions::read_bytes`].
    ///
    /// # Errors
    /// [`ErrorKind::FileNotFound`] if the file cannot be read; otherwise as
    /// [`ReadOptions::read_bytes`], with [`ReadError::file`] naming the file (or the
    /// included file) the problem is in.
    pub fn read_path(&self, path: impl AsRef<Path>) -> Result<Model, ReadError> {
        let path = path.as_ref();
        let bytes = files::read_regular(path, path, self.max_file_size)
            .map_err(|k| ReadError::new(k, None, None))?;
        let text = utf8(&bytes, Some(path))?;
        let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
        let ctx = self.context(Some(dir));
        let mut tree = Includes::new(canonical(path));
        let model_files = ModelFiles::default();
        let file = Some(path.to_path_buf());
        read_document(text, file, ctx, self.max_depth, &mut tree, &model_files)
    }
}

impl Model {
    /// Reads a model from MJCF text with default [`ReadOptions`].
    ///
    /// Time: as [`ReadOptions::read_str`]: O(L + n · log n), plus the files it names.
    ///
    /// # Errors
    /// A [`ReadError`] with the line and column of the problem; its kinds are listed
    /// at [`ReadOptions::read_str`].
    ///
    /// # Examples
    /// ```
    /// let m = mjcf::Model::from_xml_str(r#"<mujoco model="m"><worldbody/></mujoco>"#).unwrap();
    /// assert_eq!(m.name(), "m");
    /// let e = mjcf::Model::from_xml_str("<mujoco>\n  <worldbody><bogus/></worldbody>\n</mujoco>").unwrap_err();
    /// assert_eq!(e.pos().map(|p| (p.line, p.column)), Some((2, 14)));
    /// ```
    pub fn from_xml_str(text: &str) -> Result<Model, ReadError> {
        ReadOptions::new().read_str(text)
    }

    /// Reads a model from a file with default [`ReadOptions`]; relative paths in it
    /// (files, includes) resolve against its folder.
    ///
    /// Time: as [`ReadOptions::read_path`].
    ///
    /// # Errors
    /// As [`ReadOptions::read_path`]: [`ErrorKind::FileNotFound`] if the file cannot
    /// be read, else the kinds listed at [`ReadOptions::read_str`].
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, Namespace};
    /// let dir = std::env::temp_dir().join(format!("mjcf-doc-from-path-{}", std::process::id()));
    /// std::fs::create_dir_all(&dir)?;
    /// std::fs::write(dir.join("cube.stl"), b"solid cube")?;
    /// std::fs::write(dir.join("scene.xml"), r#"<mujoco model="scene"><asset><mesh file="cube.stl"/></asset></mujoco>"#)?;
    /// let m = Model::from_path(dir.join("scene.xml"))?;
    /// assert_eq!(m.name(), "scene");
    /// // Read from the file's folder, and named after the file.
    /// assert!(m.find(Namespace::Mesh, "cube").is_some());
    /// let e = Model::from_path(dir.join("missing.xml")).unwrap_err();
    /// assert!(matches!(e.kind(), mjcf::ErrorKind::FileNotFound { .. }));
    /// std::fs::remove_dir_all(&dir)?;
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn from_path(path: impl AsRef<Path>) -> Result<Model, ReadError> {
        ReadOptions::new().read_path(path)
    }
}

/// The files of one model's include tree, for the rules on them: a file includes
/// neither itself (a cycle) nor a file the tree already includes (MuJoCo includes
/// each file once per model), and includes nest at most [`MAX_INCLUDE_DEPTH`] deep.
/// Files are told apart by their canonical path (symlinks followed), in-memory files
/// by their path as written, normalised.
struct Includes {
    /// The main file and the includes above the one being read.
    stack: Vec<PathBuf>,
    /// Every file of the tree so far, the main file too.
    seen: HashSet<PathBuf>,
}

impl Includes {
    fn new(main: PathBuf) -> Includes {
        Includes { seen: HashSet::from([main.clone()]), stack: vec![main] }
    }

    /// Enters the file `key` (checked by [`include_source`]).
    fn push(&mut self, key: PathBuf) {
        self.seen.insert(key.clone());
        self.stack.push(key);
    }

    fn pop(&mut self) {
        self.stack.pop();
    }

    /// The error for including `key` (shown as `shown`) here, if any.
    fn refuse(&self, key: &Path, shown: &Path) -> Option<ErrorKind> {
        if self.stack.iter().any(|k| k == key) {
            Some(ErrorKind::IncludeCycle(shown.to_path_buf()))
        } else if self.seen.contains(key) {
            Some(ErrorKind::IncludedTwice(shown.to_path_buf()))
        } else {
            None
        }
    }
}

fn canonical(path: &Path) -> PathBuf {
    std::fs::canonicalize(path)
        .unwrap_or_else(|_| PathBuf::from(files::normalize(&path.to_string_lossy())))
}

fn utf8<'b>(bytes: &'b [u8], file: Option<&Path>) -> Result<&'b str, ReadError> {
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
    offset: usize,
}

/// No arena entry (the end of a children list).
const NONE: usize = usize::MAX;

impl Pending {
    fn new(kind: ElementKind, attrs: Arc<[Attr]>, offset: usize) -> Pending {
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

struct Reader<'t> {
    text: &'t str,
    file: Option<PathBuf>,
    ctx: FileContext,
    /// The asset model files this read has read.
    model_files: &'t ModelFiles,
    arena: Vec<Pending>,
    basepaths: Basepaths,
    /// Where each global setting (an attribute of an element inside `compiler`,
    /// `option`, `size`, `visual` or `statistic`) was last set in this file, by
    /// element kind and attribute index: an `<include>` that sets it too is merged
    /// as MuJoCo reads includes, the later one in the document winning.
    settings_set_at: HashMap<(ElementKind, u16), usize>,
    /// The attributes of the tag being read: one buffer for all, so that each
    /// element allocates its attributes once, at their final size.
    scratch: Vec<Attr>,
}

impl Reader<'_> {
    fn err(&self, kind: ErrorKind, offset: usize) -> ReadError {
        ReadError::new(kind, self.file.clone(), Some(TextPos::of_offset(self.text, offset)))
    }

    /// Reads the attributes of a tag into `attrs` (later values win), sorted by index.
    fn read_attrs(
        &mut self,
        kind: ElementKind,
        tag: &BytesStart<'_>,
        attrs: &mut Vec<Attr>,
        offset: usize,
    ) -> Result<(), ReadError> {
        let settings = in_settings(kind);
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
            let value = ctx
                .assign_at(kind, index, Some(Input::Text(&raw)))
                .map_err(|k| self.err(k, offset))?;
            let spec = kind.attr(index);
            if let AttrType::Basepath { path_namespace } = spec.ty {
                self.basepaths
                    .set(path_namespace, value.as_ref().and_then(Value::as_str).map(SmolStr::from));
            }
            let i = index as u16;
            if settings {
                self.settings_set_at.insert((kind, i), offset);
            }
            let pos = attrs.iter().position(|(k, _)| *k == i);
            match (pos, value) {
                (Some(p), Some(v)) => attrs[p].1 = v,
                (None, Some(v)) => attrs.push((i, v)),
                (Some(p), None) => {
                    attrs.remove(p);
                }
                (None, None) => {}
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

/// What [`parse`] found besides the arena: root-level includes (read as models, with
/// the offset of their tag) and the model name.
struct Parsed {
    includes: Vec<(Model, usize)>,
    model_name: Option<SmolStr>,
}

/// Reads the events of `r.text` into `r.arena`. The root element becomes an entry of
/// kind `root_kind` (the model's root, or, for a file included inside an element,
/// that element's kind, whose children the file's root's children are).
fn parse(
    r: &mut Reader<'_>,
    root_kind: ElementKind,
    max_depth: usize,
    tree: &mut Includes,
) -> Result<Parsed, ReadError> {
    let mut stack: Vec<usize> = Vec::new();
    let mut xml = quick_xml::Reader::from_str(r.text);
    let text = r.text;
    let mut includes: Vec<(Model, usize)> = Vec::new();
    let mut model_name: Option<SmolStr> = None;
    let mut seen_root = false;
    loop {
        let offset = xml.buffer_position() as usize;
        let event = match xml.read_event() {
            Ok(e) => e,
            Err(e) => {
                let at = xml.error_position() as usize;
                return Err(r.err(ErrorKind::Syntax(e.to_string()), at));
            }
        };
        let (tag, empty) = match event {
            Event::Start(t) => (t, false),
            Event::Empty(t) => (t, true),
            Event::End(_) => {
                stack.pop();
                continue;
            }
            Event::Eof => break,
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
        let qname = tag.name();
        let name: &str = qname.as_ref();
        // The root.
        if stack.is_empty() {
            if seen_root {
                return Err(r.err(ErrorKind::Syntax("more than one root element".into()), offset));
            }
            seen_root = true;
            if !name.starts_with("mujoco") {
                return Err(r.err(ErrorKind::WrongRoot(name.into()), offset));
            }
            for a in tag.attributes() {
                let a = a.map_err(|e| r.err(ErrorKind::Syntax(e.to_string()), offset))?;
                if a.key.as_ref() == "model" {
                    let v = a
                        .normalized_value(quick_xml::XmlVersion::default())
                        .map_err(|e| r.err(ErrorKind::Syntax(e.to_string()), offset))?;
                    model_name = Some(SmolStr::from(v.as_ref()));
                }
            }
            r.arena.push(Pending::new(root_kind, no_attrs(), offset));
            if !empty {
                stack.push(0);
            }
            continue;
        }
        let parent = stack[stack.len() - 1];
        let parent_kind = r.arena[parent].kind;
        if name == "include"
            && parent != usize::MAX
            && (parent != 0 || root_kind != ElementKind::ROOT)
        {
            // Inside an element (MuJoCo accepts `<include>` anywhere): the included
            // file's root's children are read in its place.
            inline_include(r, &tag, offset, parent, max_depth, tree)?;
            if !empty {
                stack.push(usize::MAX);
            }
            continue;
        }
        if parent == 0 && name == "include" {
            let inc = read_include(r, &tag, offset, max_depth, tree)?;
            // The compiler's folders are global in MuJoCo: those the included file
            // sets apply to the files named after the include here too.
            let folders = inc.basepaths();
            for (ns, v) in [
                (PathNamespace::Mesh, folders.mesh),
                (PathNamespace::Texture, folders.texture),
                (PathNamespace::Asset, folders.asset),
            ] {
                if v.is_some() {
                    r.basepaths.set(Some(ns), v);
                }
            }
            includes.push((inc, offset));
            if !empty {
                // An include's content is ignored; track it so its end tag matches.
                stack.push(usize::MAX);
            }
            continue;
        }
        if parent == usize::MAX {
            if !empty {
                stack.push(usize::MAX);
            }
            continue;
        }
        let Some(kind) = parent_kind.child(name) else {
            return Err(r.err(ErrorKind::invalid_child(parent_kind, name), offset));
        };
        if stack.len() >= max_depth {
            return Err(r.err(ErrorKind::TooDeep(max_depth), offset));
        }
        let existing = match kind.multiplicity() {
            Multiplicity::Repeated => None,
            _ => unique_child(&r.arena, parent, kind),
        };
        let index = match (kind.multiplicity(), existing) {
            (Multiplicity::Singleton, Some(e)) => {
                let mut attrs = std::mem::take(&mut r.scratch);
                attrs.clear();
                attrs.extend(r.arena[e].attrs.iter().cloned());
                let res = r.read_attrs(kind, &tag, &mut attrs, offset);
                r.arena[e].attrs = take_attrs(&mut attrs);
                r.scratch = attrs;
                res?;
                e
            }
            (Multiplicity::OnDemand, Some(_)) => {
                return Err(r.err(ErrorKind::DuplicateChild(kind.tag()), offset));
            }
            (m, _) => {
                let mut attrs = std::mem::take(&mut r.scratch);
                attrs.clear();
                r.read_attrs(kind, &tag, &mut attrs, offset)?;
                if m != Multiplicity::Singleton {
                    name_from_file(kind, &mut attrs);
                    check_required(kind, &attrs).map_err(|k| r.err(k, offset))?;
                    check_class_named(parent_kind, kind, &attrs).map_err(|k| r.err(k, offset))?;
                }
                let stored = take_attrs(&mut attrs);
                r.scratch = attrs;
                let attrs = stored;
                let i = r.arena.len();
                r.arena.push(Pending::new(kind, attrs, offset));
                push_child(&mut r.arena, parent, i);
                if m != Multiplicity::Repeated {
                    push_unique(&mut r.arena, parent, i);
                }
                i
            }
        };
        if !empty {
            stack.push(index);
        }
    }
    if !seen_root {
        return Err(r.err(ErrorKind::Syntax("no root element".into()), text.len()));
    }
    if !stack.is_empty() {
        return Err(r.err(ErrorKind::Syntax("unclosed element at end of input".into()), text.len()));
    }
    Ok(Parsed { includes, model_name })
}

fn read_document(
    text: &str,
    file: Option<PathBuf>,
    ctx: FileContext,
    max_depth: usize,
    tree: &mut Includes,
    model_files: &ModelFiles,
) -> Result<Model, ReadError> {
    let mut r = Reader {
        text,
        file,
        ctx,
        model_files,
        arena: Vec::new(),
        basepaths: Basepaths::default(),
        settings_set_at: HashMap::new(),
        scratch: Vec::new(),
    };
    let Parsed { includes, model_name } = parse(&mut r, ElementKind::ROOT, max_depth, tree)?;
    let model = finish(&mut r, model_name)?;
    if includes.is_empty() {
        return Ok(model);
    }
    let mut model = model;
    for (inc, offset) in includes {
        let inc = inc.with_name(model.name());
        let (model2, inc) = settings_in_document_order(&model, &inc, offset, &r.settings_set_at)
            .map_err(|e| r.err(e.kind().clone(), offset))?;
        model = model2.include_copy(&inc, false).map_err(|e| r.err(e.kind().clone(), offset))?;
    }
    Ok(resolve_all(&model))
}

/// An included file: its bytes, its path (for messages), the file context its own
/// files resolve in, and its key on the include stack (for cycles).
type IncludeSource = (Arc<[u8]>, PathBuf, FileContext, PathBuf);

/// The file an `<include>` names.
fn include_source(
    r: &Reader<'_>,
    tag: &BytesStart<'_>,
    offset: usize,
    tree: &Includes,
) -> Result<IncludeSource, ReadError> {
    let mut file: Option<String> = None;
    for a in tag.attributes() {
        let a = a.map_err(|e| r.err(ErrorKind::Syntax(e.to_string()), offset))?;
        let v = a
            .normalized_value(quick_xml::XmlVersion::default())
            .map_err(|e| r.err(ErrorKind::Syntax(e.to_string()), offset))?;
        match a.key.as_ref() {
            "file" => file = Some(v.into_owned()),
            other => {
                return Err(r.err(
                    ErrorKind::UnknownAttribute {
                        tag: "include",
                        attribute: other.into(),
                        suggestion: crate::suggest::closest(other, ["file"]),
                    },
                    offset,
                ));
            }
        }
    }
    let Some(file) = file else {
        return Err(r.err(ErrorKind::MissingRequired { tag: "include", attribute: "file" }, offset));
    };
    // The stack holds the main file and the includes above this one.
    if tree.stack.len() > MAX_INCLUDE_DEPTH {
        return Err(r.err(ErrorKind::TooDeep(MAX_INCLUDE_DEPTH), offset));
    }
    // From the in-memory files first (then relative to nothing), else from disk.
    if let Some(bytes) = r.ctx.assets.as_ref().and_then(|a| a.get(&file)).cloned() {
        let key = PathBuf::from(format!("<asset>{}", files::normalize(&file)));
        if let Some(refused) = tree.refuse(&key, Path::new(&file)) {
            return Err(r.err(refused, offset));
        }
        let ctx = FileContext { base_dir: None, ..r.ctx.clone() };
        return Ok((bytes, PathBuf::from(&file), ctx, key));
    }
    // With confinement, the path is checked with symlinks followed; the file must be
    // a regular file within the size cap.
    let path = r.ctx.disk_path(&file).map_err(|k| r.err(k, offset))?;
    let full = path.full.clone();
    let key = canonical(&full);
    if let Some(refused) = tree.refuse(&key, &full) {
        return Err(r.err(refused, offset));
    }
    let bytes = r.ctx.read_disk(&path).map_err(|k| r.err(k, offset))?;
    let ctx = r.ctx.for_included(&full);
    Ok((bytes.into(), full, ctx, key))
}

/// A root-level `<include>`: the file read as a model of its own, merged later.
fn read_include(
    r: &mut Reader<'_>,
    tag: &BytesStart<'_>,
    offset: usize,
    max_depth: usize,
    tree: &mut Includes,
) -> Result<Model, ReadError> {
    let (bytes, file, ctx, key) = include_source(r, tag, offset, tree)?;
    let text = utf8(&bytes, Some(&file))?;
    tree.push(key);
    let res = read_document(text, Some(file.clone()), ctx, max_depth, tree, r.model_files);
    tree.pop();
    res
}

/// An `<include>` inside an element (at `parent` in the arena): the included file's
/// root's children are read as `parent`'s children in its place, as MuJoCo pastes
/// the file's content there.
fn inline_include(
    r: &mut Reader<'_>,
    tag: &BytesStart<'_>,
    offset: usize,
    parent: usize,
    max_depth: usize,
    tree: &mut Includes,
) -> Result<(), ReadError> {
    let (bytes, file, ctx, key) = include_source(r, tag, offset, tree)?;
    let text = utf8(&bytes, Some(&file))?;
    let mut sub = Reader {
        text,
        file: Some(file),
        ctx,
        model_files: r.model_files,
        arena: Vec::new(),
        basepaths: r.basepaths.clone(),
        settings_set_at: HashMap::new(),
        scratch: Vec::new(),
    };
    tree.push(key);
    let parsed = parse(&mut sub, r.arena[parent].kind, max_depth, tree);
    tree.pop();
    let parsed = parsed?;
    if !parsed.includes.is_empty() {
        // Root-level includes of a file included inside an element cannot happen:
        // its root's children are read inline, `<include>`s among them too.
        return Err(r.err(ErrorKind::Syntax("an include inside an element".into()), offset));
    }
    // Graft: the sub-arena's root is `parent`; its other entries follow ours.
    let base = r.arena.len() - 1;
    let shift = |i: usize| match i {
        NONE => NONE,
        0 => parent,
        i => i + base,
    };
    let root_children: Vec<usize> = children_of(&sub.arena, 0).map(shift).collect();
    let mut entries = sub.arena.into_iter();
    if entries.next().is_none() {
        return Ok(());
    }
    for mut p in entries {
        p.first_child = shift(p.first_child);
        p.last_child = shift(p.last_child);
        p.next_sibling = shift(p.next_sibling);
        p.first_unique = shift(p.first_unique);
        p.next_unique = shift(p.next_unique);
        r.arena.push(p);
    }
    for c in root_children {
        let kind = r.arena[c].kind;
        if kind.multiplicity() != Multiplicity::Repeated {
            if unique_child(&r.arena, parent, kind).is_some() {
                return Err(r.err(ErrorKind::DuplicateChild(kind.tag()), offset));
            }
            push_unique(&mut r.arena, parent, c);
        }
        push_child(&mut r.arena, parent, c);
    }
    Ok(())
}

/// Turns the arena into nodes, indexes them and resolves references.
fn finish(r: &mut Reader<'_>, model_name: Option<SmolStr>) -> Result<Model, ReadError> {
    let (composed, hoisted) = hoist_root_class(&mut r.arena);
    let forget = !composed;
    // One pass over the elements' attributes (cold since they were read): auto names
    // forgotten, the index's names (document order, so that a duplicate is reported at
    // its second occurrence, and first, so that references can be resolved in the
    // arena), each element's identifier kept for its index entry, and which elements
    // hold named references.
    let mut names: imbl::HashMap<(crate::Namespace, SmolStr), ElementId> = imbl::HashMap::new();
    // The names holding a `/`, by the part before it (`Index::slashed`).
    let mut slashed: imbl::HashMap<SmolStr, u32> = imbl::HashMap::new();
    let mut idents: Vec<Option<SmolStr>> = Vec::with_capacity(r.arena.len());
    let mut with_refs: Vec<usize> = Vec::new();
    for (i, p) in r.arena.iter_mut().enumerate() {
        if forget {
            forget_auto_name(p);
        }
        let ident = p.kind.identifier().and_then(|ident| {
            match p.attrs.iter().find(|(k, _)| *k as usize == ident).map(|(_, v)| v) {
                Some(Value::Identifier(n)) => Some(n.clone()),
                _ => None,
            }
        });
        if let (Some(ns), Some(n)) = (p.kind.namespace(), &ident) {
            if names.insert((ns, n.clone()), p.id).is_some() {
                let (kind, offset) =
                    (ErrorKind::DuplicateIdentifier { namespace: ns, name: n.clone() }, p.offset);
                return Err(r.err(kind, offset));
            }
            if let Some(segment) = crate::model::slashed_segment(n) {
                *slashed.entry(segment.into()).or_insert(0) += 1;
            }
        }
        if p.attrs.iter().any(|(_, v)| matches!(v, Value::Reference(Reference::Name(_)))) {
            with_refs.push(i);
        }
        idents.push(ident);
    }
    // `/` (as written by this crate and dm_control) and `main` (MuJoCo's name) both
    // name the root class, unless a class has that name.
    let root_class = r
        .arena
        .iter()
        .find(|p| p.kind.spec().parent == Some(ElementKind::ROOT) && p.kind.tag() == "default")
        .map(|d| d.id);
    let lookup = |ns: crate::Namespace, n: &str| {
        names.get(&(ns, SmolStr::from(n))).copied().or_else(|| {
            (ns == crate::Namespace::Default && crate::model::naming::is_builtin_name(ns, n))
                .then_some(root_class)
                .flatten()
        })
    };
    for i in with_refs {
        // Only lists with a named reference change (and are uniquely owned here).
        let p = &mut r.arena[i];
        resolve_attrs(p.kind, Arc::make_mut(&mut p.attrs), lookup);
    }
    if let Some(i) = ElementKind::ROOT.attr_index("model") {
        // A missing or empty name becomes `unnamed_model`, as in the reference.
        let name =
            model_name.filter(|n| !n.is_empty()).unwrap_or_else(|| crate::model::UNNAMED.into());
        let mut attrs = r.arena[0].attrs.to_vec();
        attrs.retain(|(k, _)| *k as usize != i);
        attrs.push((i as u16, Value::String(name)));
        attrs.sort_by_key(|(k, _)| *k);
        r.arena[0].attrs = attrs.into();
    }
    // Bottom-up: children always have larger arena indices than their parent.
    let mut built: Vec<Option<Node>> = (0..r.arena.len()).map(|_| None).collect();
    // One buffer for every element's children.
    let mut children: Vec<Node> = Vec::new();
    // And for their identifiers, for the index.
    let mut child_idents: Vec<Option<SmolStr>> = Vec::new();
    let empty = no_attrs();
    // The nodes made here (empty singletons), for the size of the index's list.
    let mut made = 0;
    for (i, p) in r.arena.iter().enumerate().filter(|(i, _)| Some(*i) != hoisted) {
        for k in p.kind.singleton_children() {
            if unique_child(&r.arena, i, k).is_none() {
                made += empty_size(k);
            }
        }
    }
    // Indexed as the nodes are made, while they are in cache.
    let mut index = ReadIndex::with_capacity(r.arena.len() + made);
    for i in (0..r.arena.len()).rev() {
        if Some(i) == hoisted {
            // Out of the tree: its content is the root class's now.
            continue;
        }
        let (p, at) = (&r.arena[i], i);
        children.clear();
        child_idents.clear();
        let mut kinds = p.kind.singleton_children().peekable();
        if kinds.peek().is_some() {
            // Singletons in schema order, each with where it was read (its arena
            // entry, in document order, includes included), if it was.
            // The ones not read take one block of ids, so that a class read without
            // any is indexed as one run (`model::index`).
            let first = ElementId::fresh_block(kinds.clone().count());
            let mut singles: Vec<(Node, Option<usize>)> = Vec::new();
            for (i, k) in kinds.enumerate() {
                let found = unique_child(&r.arena, at, k);
                match found.and_then(|c| Some((built[c].take()?, c))) {
                    Some((n, at)) => singles.push((n, Some(at))),
                    None => {
                        let empty = empty_node_with_id(first.nth(i), k);
                        if !empty.children().is_empty() {
                            index.descendants(&empty);
                        }
                        singles.push((empty, None));
                    }
                }
            }
            if p.kind.tag() == "default" {
                // DESIGN D11: the actuator defaults in the order they were read.
                crate::model::defaults::order(&mut singles, |(n, _)| n, |(_, at)| *at);
            }
            // Singletons are few: their identifiers (if any) read from the nodes.
            child_idents.extend(singles.iter().map(|(n, _)| n.identifier().map(SmolStr::from)));
            children.extend(singles.into_iter().map(|(n, _)| n));
        }
        let mut c = p.first_child;
        while c != NONE {
            if let Some(n) = built[c].take() {
                children.push(n);
                child_idents.push(idents[c].take());
            }
            c = r.arena[c].next_sibling;
        }
        let p = &mut r.arena[i];
        let children: Seq<Node> = children.drain(..).collect();
        let node = Node::from_sorted(
            p.id,
            p.kind,
            std::mem::replace(&mut p.attrs, empty.clone()),
            children,
        );
        index.children(&node, &child_idents);
        built[i] = Some(node);
    }
    let root = match built.swap_remove(0) {
        Some(root) => root,
        None => {
            let root = empty_node(ElementKind::ROOT);
            index.descendants(&root);
            root
        }
    };
    // The arena is spent: freed before the index is built, which can reuse its memory.
    drop(std::mem::take(&mut r.arena));
    drop(built);
    let index = index.finish(&root, names, slashed);
    Ok(Model::from_parts(root, index, r.ctx.clone()))
}

/// The number of nodes of an empty singleton of kind `k` (its own empty singletons
/// included, as `empty_node` makes them), from the schema: singletons do not nest
/// deeper than a few levels, so the recursion is shallow.
fn empty_size(k: ElementKind) -> usize {
    1 + k.singleton_children().map(empty_size).sum::<usize>()
}

/// `<default><default class="/">…</default></default>`, the shape this crate and
/// dm_control write a model's root default class in, reads as that root class: the
/// content of the one class `/` becomes the root class's own (the writer's rules
/// "root class wrapper" and "main wrapper", `policy::folds_into_root_class`). Where the root
/// `<default>` holds other classes beside `/` (a composed model written out: the
/// attached models' root classes `robot/` are siblings of `/`, not inside it), `/` is
/// kept as a class of that name, so that the siblings keep inheriting nothing from it.
///
/// Returns whether the file is a composed model written out (a class `/` beside
/// other classes), and the arena entry of the class hoisted (no longer in the tree).
fn hoist_root_class(arena: &mut [Pending]) -> (bool, Option<usize>) {
    let root_default = ElementKind::ROOT.child("default").unwrap_or(ElementKind::ROOT);
    if arena.is_empty() {
        return (false, None);
    }
    let Some(d) = unique_child(arena, 0, root_default) else {
        return (false, None);
    };
    // The writer's rules, asked of what was read (`policy`'s "composed output" and
    // "root class hoisting").
    let as_default_child = |c: usize| {
        let p = &arena[c];
        if p.kind.tag() != "default" {
            return policy::DefaultChild::Setting;
        }
        let ident = p.kind.identifier();
        let name = p.attrs.iter().find(|(k, _)| Some(*k as usize) == ident);
        policy::DefaultChild::Class(name.and_then(|(_, v)| v.as_str()))
    };
    // A class `/` beside other classes, at any level (under a named root class too).
    let composed = arena.iter().enumerate().any(|(i, p)| {
        p.kind.tag() == "default"
            && policy::is_composed_output(children_of(arena, i).map(as_default_child))
    });
    let wrapper_attrs = !arena[d].attrs.is_empty();
    if !policy::folds_into_root_class(wrapper_attrs, children_of(arena, d).map(as_default_child)) {
        return (composed, None);
    }
    let Some(only) = children_of(arena, d).next() else { return (composed, None) };
    let ident = arena[only].kind.identifier();
    let mut attrs = std::mem::take(&mut arena[only].attrs).to_vec();
    attrs.retain(|(k, _)| Some(*k as usize) != ident);
    arena[d].attrs = rekind(arena[only].kind, root_default, attrs).into();
    // The class's children become the root class's (its one child, `only`, goes).
    let children: Vec<usize> = children_of(arena, only).collect();
    arena[d].first_child = arena[only].first_child;
    arena[d].last_child = arena[only].last_child;
    arena[only].first_child = NONE;
    arena[only].last_child = NONE;
    arena[only].first_unique = NONE;
    // The moved children are now children of the root class, whose child kinds are
    // other schema positions (with the same tags and attribute names).
    for &c in &children {
        let old = arena[c].kind;
        if let Some(new) = root_default.child(old.tag()) {
            let attrs = std::mem::take(&mut arena[c].attrs).to_vec();
            arena[c].attrs = rekind(old, new, attrs).into();
            arena[c].kind = new;
        }
    }
    arena[d].first_unique = NONE;
    for &c in &children {
        if arena[c].kind.multiplicity() != Multiplicity::Repeated {
            push_unique(arena, d, c);
        }
    }
    (composed, Some(only))
}

/// Whether elements of `kind` hold global settings (they sit in `compiler`, `option`,
/// `size`, `visual` or `statistic`).
fn in_settings(kind: ElementKind) -> bool {
    let mut k = kind;
    while let Some(p) = k.spec().parent {
        if p == ElementKind::ROOT {
            return crate::model::settings::is_settings_section(k);
        }
        k = p;
    }
    false
}

/// A global setting that both the file and an `<include>` at `offset` set is taken
/// as MuJoCo reads includes (their text in place of the tag): from the one later in
/// the document. Returns the model and the include with the losing values dropped,
/// so that merging them finds no conflict.
fn settings_in_document_order(
    model: &Model,
    inc: &Model,
    offset: usize,
    set_at: &HashMap<(ElementKind, u16), usize>,
) -> Result<(Model, Model), crate::EditError> {
    let (mut model, mut inc) = (model.clone(), inc.clone());
    let sections: Vec<Node> =
        inc.root.children().iter().filter(|c| in_settings(c.kind())).cloned().collect();
    for section in sections {
        for n in section.descendants() {
            let kind = n.kind();
            for (i, v) in n.attrs() {
                let Some(&main_at) = set_at.get(&(kind, *i)) else { continue };
                let own = model
                    .root
                    .children()
                    .iter()
                    .filter(|c| in_settings(c.kind()))
                    .flat_map(Node::descendants)
                    .find(|m| m.kind() == kind);
                let Some(own) = own else { continue };
                let name = kind.attr(*i as usize).name;
                let own_loc = model.scoped_loc(&[], own.id());
                if main_at > offset {
                    // The file's own value comes later: the include's is overridden.
                    let inc_loc = inc.scoped_loc(&[], n.id());
                    inc = inc.clear_attr(&inc_loc, name)?;
                } else {
                    model = model.set(
                        &own_loc,
                        crate::Attrs::new().set(name, crate::AttrInput::Value(v.clone())),
                    )?;
                }
            }
        }
    }
    Ok((model, inc))
}

/// Automatic names (`//unnamed_geom_0`, written by this crate and by dm_control) mean
/// "unnamed": they are derived again when the model is written (the writer's rule
/// "automatic names", `policy::is_auto_name`). (In a composed model written out they
/// are kept: there they were counted over the outer model's own elements, which the
/// flat model read back no longer tells apart.)
fn forget_auto_name(p: &mut Pending) {
    let Some(ident) = p.kind.identifier() else { return };
    let auto = |(k, v): &Attr| *k as usize == ident && v.as_str().is_some_and(policy::is_auto_name);
    if p.attrs.iter().any(auto) {
        let mut attrs = p.attrs.to_vec();
        attrs.retain(|a| !auto(a));
        p.attrs = attrs.into();
    }
}

/// Attributes of an element of kind `from` as attributes of kind `to` (by name).
fn rekind(from: ElementKind, to: ElementKind, attrs: Vec<Attr>) -> Vec<Attr> {
    let mut out: Vec<Attr> = attrs
        .into_iter()
        .filter_map(|(i, v)| Some((to.attr_index(from.attr(i as usize).name)? as u16, v)))
        .collect();
    out.sort_by_key(|(k, _)| *k);
    out
}

/// Replaces every named reference that `lookup` finds by a reference to the element.
fn resolve_attrs(
    kind: ElementKind,
    attrs: &mut [Attr],
    lookup: impl Fn(crate::Namespace, &str) -> Option<ElementId>,
) {
    for j in 0..attrs.len() {
        let (i, v) = &attrs[j];
        let Value::Reference(Reference::Name(n)) = v else { continue };
        let AttrType::Reference(target) = kind.attr(*i as usize).ty else { continue };
        let ns = target.namespace(|k| attrs.iter().find(|(x, _)| *x as usize == k).map(|(_, v)| v));
        if let Some(id) = ns.and_then(|ns| lookup(ns, n)) {
            attrs[j].1 = Value::Reference(Reference::Element(id));
        }
    }
}

/// Resolves named references across a whole model (after includes were merged).
fn resolve_all(model: &Model) -> Model {
    let lookup = |ns, n: &str| model.find(ns, n).map(|l| l.id());
    let root = model.root.rebuild(|n, children| {
        let mut attrs = n.attrs().to_vec();
        resolve_attrs(n.kind(), &mut attrs, lookup);
        n.with_parts(attrs, children)
    });
    model.next(root, model.index.clone())
}
