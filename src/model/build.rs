//! Element builders and the checks that turn them into nodes.
//!
//! An [`Element`] is a plain description (tag, attributes, children) that collects
//! whatever the caller gives it; nothing is checked until the element is added to a
//! model, where every problem becomes one [`EditError`](crate::EditError) naming the
//! element's path. So builder calls chain without a `?` after each setter.

use std::cell::RefCell;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

use crate::seq::Seq;
use smol_str::SmolStr;

use super::tree::{Attr, ElementId, Node};
use crate::error::{ErrorKind, ValueError};
pub(crate) use crate::files::Basepaths;
use crate::files::{FileContext, Located};
use crate::schema::{AttrType, ElementKind, Multiplicity, Role};
use crate::value::{self, AttrInput, FileAsset, Value};

/// A set of attribute assignments: values to set and attributes to clear, in order.
///
/// # Examples
/// ```
/// use mjcf::Attrs;
/// let a = Attrs::new().set("rgba", [1.0, 0.0, 0.0, 1.0]).clear("material");
/// assert_eq!(a.len(), 2);
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Attrs {
    items: Vec<(SmolStr, Option<AttrInput>)>,
}

impl Attrs {
    /// No assignments.
    ///
    /// Time: O(1).
    pub fn new() -> Attrs {
        Attrs::default()
    }

    /// Adds an assignment of `value` to the attribute `name` (`"class"` for the
    /// default class). Nothing is checked until the assignments are applied.
    ///
    /// Time: O(1) amortised.
    #[must_use]
    pub fn set(mut self, name: &str, value: impl Into<AttrInput>) -> Attrs {
        self.items.push((name.into(), Some(value.into())));
        self
    }

    /// Adds the clearing of the attribute `name`.
    ///
    /// Time: O(1) amortised.
    #[must_use]
    pub fn clear(mut self, name: &str) -> Attrs {
        self.items.push((name.into(), None));
        self
    }

    /// The number of assignments.
    ///
    /// Time: O(1).
    pub fn len(&self) -> usize {
        self.items.len()
    }

    /// Whether there are no assignments.
    ///
    /// Time: O(1).
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    pub(crate) fn items(&self) -> &[(SmolStr, Option<AttrInput>)] {
        &self.items
    }
}

/// A new element to add to a model: its tag, attributes and children.
///
/// # Examples
/// ```
/// use mjcf::{Element, Model};
/// let m = Model::new("m");
/// let body = Element::new("body")
///     .attr("name", "torso")
///     .attr("pos", [0.0, 0.0, 1.0])
///     .child(Element::new("geom").attr("type", "box").attr("size", [0.1, 0.1, 0.1]));
/// let (m, torso) = m.add(&m.worldbody(), body).unwrap();
/// assert_eq!(m.find(mjcf::Namespace::Body, "torso"), Some(torso));
/// ```
// The element and its descendants are kept flat (an arena with child indices), not as
// nested values: cloning, comparing and dropping never recurse, so an element nested
// any number of levels deep cannot overflow the stack.
#[derive(Clone)]
pub struct Element {
    parts: Vec<Part>,
    /// The index of this element's own part; every index in `parts` is valid.
    root: usize,
}

#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Part {
    pub(crate) tag: SmolStr,
    pub(crate) attrs: Attrs,
    pub(crate) children: Vec<usize>,
}

impl Element {
    /// An element with this tag and nothing else (the tag is checked when the
    /// element is added).
    ///
    /// Time: O(1).
    pub fn new(tag: &str) -> Element {
        Element {
            parts: vec![Part { tag: tag.into(), attrs: Attrs::new(), children: Vec::new() }],
            root: 0,
        }
    }

    /// Sets an attribute (checked when the element is added).
    ///
    /// Time: O(1) amortised.
    #[must_use]
    pub fn attr(mut self, name: &str, value: impl Into<AttrInput>) -> Element {
        let root = self.root;
        let part = &mut self.parts[root];
        part.attrs = std::mem::take(&mut part.attrs).set(name, value);
        self
    }

    /// Sets several attributes.
    ///
    /// Time: O(k) for `k` assignments.
    #[must_use]
    pub fn attrs(mut self, attrs: Attrs) -> Element {
        let root = self.root;
        self.parts[root].attrs.items.extend(attrs.items);
        self
    }

    /// Appends a child element.
    ///
    /// Time: O(size of the smaller of the two), so building a chain of any depth
    /// either way round costs O(n log n).
    #[must_use]
    pub fn child(self, child: Element) -> Element {
        // Move the smaller arena into the larger one.
        let (mut big, small, parent_is_big) = if self.parts.len() >= child.parts.len() {
            (self, child, true)
        } else {
            (child, self, false)
        };
        let offset = big.parts.len();
        big.parts.extend(small.parts.into_iter().map(|mut p| {
            p.children.iter_mut().for_each(|c| *c += offset);
            p
        }));
        let (parent, child) = if parent_is_big {
            (big.root, small.root + offset)
        } else {
            (small.root + offset, big.root)
        };
        big.parts[parent].children.push(child);
        big.root = parent;
        big
    }

    /// The tag.
    ///
    /// Time: O(1).
    pub fn tag(&self) -> &str {
        &self.parts[self.root].tag
    }

    /// This element's own part.
    pub(crate) fn root_part(&self) -> &Part {
        &self.parts[self.root]
    }

    /// The part at `index` (an index taken from another part's children).
    pub(crate) fn part(&self, index: usize) -> &Part {
        &self.parts[index]
    }
}

impl PartialEq for Element {
    /// Structural equality: same tags, attributes and children (iterative).
    fn eq(&self, other: &Element) -> bool {
        let mut stack = vec![(self.root_part(), other.root_part())];
        while let Some((a, b)) = stack.pop() {
            if a.tag != b.tag || a.attrs != b.attrs || a.children.len() != b.children.len() {
                return false;
            }
            stack.extend(
                a.children.iter().zip(&b.children).map(|(x, y)| (self.part(*x), other.part(*y))),
            );
        }
        true
    }
}

impl std::fmt::Debug for Element {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let root = self.root_part();
        f.debug_struct("Element")
            .field("tag", &root.tag)
            .field("attrs", &root.attrs)
            .field("children", &root.children.len())
            .field("descendants", &(self.parts.len() - 1))
            .finish()
    }
}

/// Creates an empty element of `kind` with a fresh id and every singleton child it
/// always has (an `option` gets its `flag`, a default class its `geom`, ...).
pub(crate) fn empty_node(kind: ElementKind) -> Node {
    empty_node_with_id(ElementId::fresh(), kind)
}

/// [`empty_node`] with the id `id`. The singleton children take one block of
/// consecutive ids, so the index keeps them as one run (`model::index`).
pub(crate) fn empty_node_with_id(id: ElementId, kind: ElementKind) -> Node {
    let first = ElementId::fresh_block(kind.singleton_children().count());
    let children: Seq<Node> = kind
        .singleton_children()
        .enumerate()
        .map(|(i, c)| empty_node_with_id(first.nth(i), c))
        .collect();
    Node::new(id, kind, Vec::new(), children)
}

/// Everything needed to turn inputs into checked values.
pub(crate) struct ValueCtx<'a> {
    pub(crate) files: &'a FileContext,
    pub(crate) basepaths: &'a Basepaths,
    /// The asset model files read so far by this read or edit.
    pub(crate) model_files: &'a ModelFiles,
}

/// An attribute value as given: text (read from XML, or given as text through the
/// API) or a typed input.
#[derive(Clone, Copy)]
pub(crate) enum Input<'a> {
    /// Text, parsed by the attribute's type.
    Text(&'a str),
    /// An input given through the API.
    Given(&'a AttrInput),
}

impl Input<'_> {
    fn text(&self) -> Option<&str> {
        match self {
            Input::Text(t) => Some(t),
            Input::Given(AttrInput::Text(t)) => Some(t),
            Input::Given(_) => None,
        }
    }
}

impl ValueCtx<'_> {
    /// Checks one assignment, the same for the reader and the builder: `Ok(None)`
    /// clears the attribute (no input, empty text for a name, reference, string,
    /// folder or file (the reader also reads an automatic name such as
    /// `//unnamed_geom_0` as "unnamed", see `xml::read`), which means
    /// "unnamed"); `dclass` is `class`; a file attribute reads its file; a mesh file
    /// must have an extension MuJoCo reads.
    pub(crate) fn assign(
        &self,
        kind: ElementKind,
        name: &str,
        input: Option<Input<'_>>,
    ) -> Result<(usize, Option<Value>), ErrorKind> {
        let name = if name == "dclass" { "class" } else { name };
        let index =
            kind.attr_index(name).ok_or_else(|| ErrorKind::unknown_attribute(kind, name))?;
        self.assign_at(kind, index, input).map(|v| (index, v))
    }

    /// [`ValueCtx::assign`] to the attribute at `index` of `kind` (the reader finds the
    /// index itself, once).
    pub(crate) fn assign_at(
        &self,
        kind: ElementKind,
        index: usize,
        input: Option<Input<'_>>,
    ) -> Result<Option<Value>, ErrorKind> {
        let spec = kind.attr(index);
        let Some(input) = input else { return Ok(None) };
        let invalid = |error: ValueError| ErrorKind::InvalidValue {
            tag: kind.tag(),
            attribute: spec.name,
            value: match input {
                Input::Text(t) => cut(t),
                Input::Given(i) => input_text(i),
            },
            error,
        };
        if let Some(text) = input.text() {
            // An empty required name prefix (`<attach prefix="">`) is given, as MuJoCo
            // reads it: the part's names are taken as they are.
            let empty_prefix = spec.required && matches!(spec.ty, AttrType::NamePrefix);
            let clears = text.is_empty()
                && !empty_prefix
                && matches!(
                    spec.ty,
                    AttrType::Identifier
                        | AttrType::Reference(_)
                        | AttrType::String
                        | AttrType::NamePrefix
                        | AttrType::Basepath { .. }
                        | AttrType::File { .. }
                );
            if clears {
                return Ok(None);
            }
            if let AttrType::File { path_namespace } = spec.ty {
                let base = self.basepaths.for_namespace(path_namespace);
                let asset = if kind.is(Role::AssetModel) {
                    // A model file brings the files it names (exported beside it).
                    self.model_files.read(self.files, base, text, ElementKind::ROOT, 0)?.0
                } else {
                    FileAsset::from_path_and_contents(text, self.files.read(base, text)?.1)
                };
                if kind.is(Role::Mesh)
                    && !matches!(
                        asset.extension().to_ascii_lowercase().as_str(),
                        ".stl" | ".msh" | ".obj"
                    )
                {
                    return Err(invalid(ValueError::MeshExtension));
                }
                return Ok(Some(Value::File(asset)));
            }
        }
        let value = match input {
            Input::Text(t) => value::parse_text(spec, kind.namespace(), t).map(Some),
            Input::Given(i) => value::from_input(spec, kind.namespace(), i),
        };
        value.map_err(invalid)
    }
}

/// How deep model files may name model files.
const MAX_MODEL_FILE_DEPTH: usize = 16;

/// The most files one model file may bring (with those of the model files it names,
/// each path once).
pub(crate) const MAX_MODEL_FILE_COMPANIONS: usize = 100_000;

/// The asset model files (`<model file>`, and the model files and includes they name
/// in turn) that one read or one edit has read, each read once however often it is
/// named: a folder of files that each name the next several times costs one read of
/// each file, not one per path through them.
#[derive(Debug, Default)]
pub(crate) struct ModelFiles(RefCell<HashMap<(FileKey, ElementKind), ModelFile>>);

/// A model file, told apart by what its companions depend on (with the element kind
/// its root's content is read as, which decides what its elements are): on disk, its canonical
/// path and the canonical folder its own files resolve in (they differ for a
/// symlinked file, whose files are found beside the link); in memory, its contents (by
/// their SHA-1: one file under two keys is one file) and the folder its files on disk
/// resolve in.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
enum FileKey {
    Disk(PathBuf, PathBuf),
    Memory(String, Option<PathBuf>),
}

/// A model file read: the asset (its companions set) and how many model files deep
/// it goes (1 for a file naming none, 0 for one that is not UTF-8, which has none).
#[derive(Clone, Debug)]
struct ModelFile {
    asset: FileAsset,
    levels: usize,
}

impl ModelFiles {
    /// The model file `file` (as written, with the folder setting `dir`; its root's
    /// content read as `read_as`: the root for an asset model file, the element
    /// holding the include for an included file) found from `ctx`, at `depth` model
    /// files below the model being read, with the files it
    /// names (its companions), and how many levels deep it goes. Read and scanned once
    /// per [`ModelFiles`]; a file met again is only named again (and refused as
    /// [`ErrorKind::TooDeep`] if its levels reach too deep from here, as reading it
    /// again would).
    ///
    /// Time: O(1) lookups for a file met before, plus O(length of `file`) to name it;
    /// else reading and scanning it (and, once each, the model files it names).
    fn read(
        &self,
        ctx: &FileContext,
        dir: Option<&str>,
        file: &str,
        read_as: ElementKind,
        depth: usize,
    ) -> Result<(FileAsset, usize), ErrorKind> {
        let (full, located) = ctx.locate(dir, file)?;
        let inner = ctx.for_included(&full);
        let key = match &located {
            Located::Memory { bytes, .. } => {
                let sha1 = sha1_smol::Sha1::from(&bytes[..]).digest().to_string();
                FileKey::Memory(sha1, inner.base_dir.clone())
            }
            Located::Disk(path) => {
                let folder = inner.base_dir.as_deref().unwrap_or(Path::new("."));
                FileKey::Disk(canonical_or_same(&path.open), canonical_or_same(folder))
            }
        };
        let named = |m: &ModelFile| (m.asset.named_as(file), m.levels);
        let key = (key, read_as);
        if let Some(m) = self.0.borrow().get(&key) {
            if m.levels > 0 && depth + m.levels > MAX_MODEL_FILE_DEPTH {
                return Err(ErrorKind::TooDeep(MAX_MODEL_FILE_DEPTH));
            }
            return Ok(named(m));
        }
        let bytes = match located {
            Located::Memory { bytes, .. } => bytes,
            Located::Disk(path) => ctx.read_disk(&path)?.into(),
        };
        let (companions, levels) = self.companions(&inner, &bytes, read_as, depth)?;
        let asset = FileAsset::from_path_and_contents(file, bytes).with_companions(companions);
        let m = ModelFile { asset, levels };
        let out = named(&m);
        self.0.borrow_mut().insert(key, m);
        Ok(out)
    }

    /// The files an MJCF model file names (read from `ctx`, its folder; its root's
    /// content read as `read_as`), by their paths relative to it as MuJoCo resolves
    /// them: its file attributes (found by `files::scan`, as the reader finds them), with
    /// the compiler's `meshdir` (meshes, height fields, skins, flexcomps), `texturedir`
    /// (textures) and `assetdir` (both), the last setting of each applying to every
    /// file as MuJoCo's compiler settings do; model files and includes it names bring
    /// theirs in turn. Each path once (a path named again names the same file). A file
    /// that is not UTF-8 has none, one not well-formed those named before the error
    /// (MuJoCo reports it). Also how many model files deep it goes.
    ///
    /// Time: O(size of the file + its companions), plus reading the files it names
    /// (each model file once per [`ModelFiles`]).
    fn companions(
        &self,
        ctx: &FileContext,
        bytes: &[u8],
        read_as: ElementKind,
        depth: usize,
    ) -> Result<(Vec<(SmolStr, FileAsset)>, usize), ErrorKind> {
        let Ok(text) = std::str::from_utf8(bytes) else { return Ok((Vec::new(), 0)) };
        if depth >= MAX_MODEL_FILE_DEPTH {
            return Err(ErrorKind::TooDeep(MAX_MODEL_FILE_DEPTH));
        }
        let mut out = Companions::default();
        let mut levels = 1;
        for named in crate::files::scan::named_files(text, read_as) {
            let (dir, file) = (named.folder.as_deref(), named.file.as_str());
            let joined = SmolStr::from(crate::files::normalize(&crate::files::join(dir, file)));
            if out.has(&joined) {
                // Named again: the same file, with the same files of its own.
                continue;
            }
            let asset = if let Some(read_as) = named.names_files {
                let (asset, below) = self.read(ctx, dir, file, read_as, depth + 1)?;
                levels = levels.max(below + 1);
                // Its files, relative to it: relative to this one, under its folder.
                let folder = joined.rsplit_once('/').map_or("", |(d, _)| d);
                for (path, f) in asset.companions() {
                    let path = crate::files::normalize(&crate::files::join(Some(folder), path));
                    out.push(path.into(), f)?;
                }
                asset.named_as(&joined).with_companions(Vec::new())
            } else {
                FileAsset::from_path_and_contents(&joined, ctx.read(dir, file)?.1)
            };
            out.push(joined, &asset)?;
        }
        Ok((out.list, levels))
    }
}

/// The files a model file brings, each path once (a second file under one path, with
/// other contents, is kept, for export to report the clash), at most
/// [`MAX_MODEL_FILE_COMPANIONS`].
#[derive(Default)]
struct Companions {
    list: Vec<(SmolStr, FileAsset)>,
    /// Paths in `list`, with the position of the first file under each.
    at: HashMap<SmolStr, usize>,
}

impl Companions {
    fn has(&self, path: &str) -> bool {
        self.at.contains_key(path)
    }

    fn push(&mut self, path: SmolStr, file: &FileAsset) -> Result<(), ErrorKind> {
        if let Some(&i) = self.at.get(&path) {
            if self.list[i].1 == *file {
                return Ok(());
            }
        }
        if self.list.len() >= MAX_MODEL_FILE_COMPANIONS {
            return Err(ErrorKind::TooManyFiles(MAX_MODEL_FILE_COMPANIONS));
        }
        self.at.entry(path.clone()).or_insert(self.list.len());
        self.list.push((path, file.clone()));
        Ok(())
    }
}

/// The canonical path of `p` (symlinks followed), or `p` itself if it has none (a
/// file that does not exist; reading it reports that).
fn canonical_or_same(p: &Path) -> PathBuf {
    std::fs::canonicalize(p).unwrap_or_else(|_| p.to_path_buf())
}

/// The text of an input, for error messages (cut to 200 characters).
pub(crate) fn input_text(input: &AttrInput) -> String {
    let s = match input {
        AttrInput::Text(t) => t.to_string(),
        AttrInput::Number(x) => x.to_string(),
        AttrInput::Numbers(xs) => xs.iter().map(f64::to_string).collect::<Vec<_>>().join(" "),
        AttrInput::Bool(b) => b.to_string(),
        AttrInput::Value(v) => v.to_string(),
    };
    cut(&s)
}

/// A value as errors keep it: [`crate::error::cut`], owned.
pub(crate) fn cut(s: &str) -> String {
    crate::error::cut(s).into_owned()
}

/// Applies assignments to an attribute list, keeping schema order. Returns the
/// identifier change, if any (`Some(None)` clears it).
pub(crate) fn apply_attrs(
    kind: ElementKind,
    attrs: &mut Vec<Attr>,
    changes: Vec<(usize, Option<Value>)>,
) -> Result<(), ErrorKind> {
    for (index, value) in changes {
        let i = index as u16;
        let pos = attrs.binary_search_by_key(&i, |(k, _)| *k);
        match (pos, value) {
            (Ok(p), Some(v)) => attrs[p].1 = v,
            (Err(p), Some(v)) => attrs.insert(p, (i, v)),
            (Ok(p), None) => {
                if kind.attr(index).required {
                    return Err(ErrorKind::MissingRequired {
                        tag: kind.tag(),
                        attribute: kind.attr(index).name,
                    });
                }
                attrs.remove(p);
            }
            (Err(_), None) => {
                if kind.attr(index).required {
                    return Err(ErrorKind::MissingRequired {
                        tag: kind.tag(),
                        attribute: kind.attr(index).name,
                    });
                }
            }
        }
    }
    Ok(())
}

/// Checks that every required attribute is set.
pub(crate) fn check_required(kind: ElementKind, attrs: &[Attr]) -> Result<(), ErrorKind> {
    for (i, spec) in kind.spec().attrs.iter().enumerate() {
        if spec.required && attrs.binary_search_by_key(&(i as u16), |(k, _)| *k).is_err() {
            return Err(ErrorKind::MissingRequired { tag: kind.tag(), attribute: spec.name });
        }
    }
    Ok(())
}

/// Checks that a nested default class has a name: only the root class may be unnamed
/// (MuJoCo refuses an empty class name, and the output would hold two classes `/`).
pub(crate) fn check_class_named(
    parent: ElementKind,
    kind: ElementKind,
    attrs: &[Attr],
) -> Result<(), ErrorKind> {
    if !kind.is(Role::DefaultClass) || !parent.is(Role::DefaultClass) {
        return Ok(());
    }
    let named = kind
        .identifier()
        .is_some_and(|i| attrs.binary_search_by_key(&(i as u16), |(k, _)| *k).is_ok());
    if named {
        Ok(())
    } else {
        Err(ErrorKind::MissingRequired { tag: "default", attribute: "class" })
    }
}

/// Gives a nameless `mesh`, `hfield` or `texture` with a file the file's stem as name,
/// as the reference does; and a nameless asset `model` the name of the model its file
/// holds, as MuJoCo does (`<attach model=…>` names it so).
pub(crate) fn name_from_file(kind: ElementKind, attrs: &mut Vec<Attr>) {
    let from_stem = match kind.role() {
        Some(Role::Mesh | Role::Hfield | Role::Texture) => true,
        Some(Role::AssetModel) => false,
        _ => return,
    };
    let (Some(ident), Some(file)) = (kind.identifier(), kind.attr_index("file")) else { return };
    let has_name = attrs.iter().any(|(i, _)| *i as usize == ident);
    let name = attrs.iter().find_map(|(i, v)| match v {
        Value::File(f) if *i as usize == file => {
            if from_stem {
                Some(SmolStr::from(f.stem()))
            } else {
                crate::files::scan::model_name(f.contents())
            }
        }
        _ => None,
    });
    if let (false, Some(name)) = (has_name, name) {
        if let Ok(v) = value::identifier(&name, kind.namespace()) {
            let i = ident as u16;
            let p = attrs.binary_search_by_key(&i, |(k, _)| *k).unwrap_or_else(|p| p);
            attrs.insert(p, (i, v));
        }
    }
}

/// Builds the node for `el` under a parent of kind `parent`. `path` names the new
/// element in errors; on error it holds the path of the failing element.
pub(crate) fn build(
    ctx: &ValueCtx<'_>,
    parent: ElementKind,
    el: &Element,
    path: &mut String,
) -> Result<Node, ErrorKind> {
    let root = el.root_part();
    let kind =
        parent.child(&root.tag).ok_or_else(|| ErrorKind::invalid_child(parent, &root.tag))?;
    if kind.multiplicity() == Multiplicity::Singleton {
        return Err(ErrorKind::DuplicateChild(kind.tag()));
    }
    push_segment(path, kind.tag(), None);
    fill(ctx, parent, empty_node(kind), el, path)
}

/// A node being filled from a part of an [`Element`].
struct Filling<'e> {
    id: ElementId,
    kind: ElementKind,
    attrs: Vec<Attr>,
    children: Seq<Node>,
    part: &'e Part,
    /// The next of `part`'s children to fill.
    next: usize,
    /// The length of the error path before this element's segment.
    path_len: usize,
    /// Where the finished node goes among its parent's children: replacing the
    /// singleton at this position, or (`None`) appended.
    slot: Option<usize>,
    /// The singleton children `part` gives, in its order (their order as given is
    /// kept for a default class's actuator defaults: DESIGN D11).
    given: Vec<ElementKind>,
}

impl<'e> Filling<'e> {
    /// Applies `part`'s attributes to `node` (of the same kind).
    fn start(
        ctx: &ValueCtx<'_>,
        parent: ElementKind,
        node: &Node,
        part: &'e Part,
        slot: Option<usize>,
        path_len: usize,
    ) -> Result<Filling<'e>, ErrorKind> {
        let kind = node.kind();
        let mut changes = Vec::with_capacity(part.attrs.items.len());
        for (name, input) in &part.attrs.items {
            changes.push(ctx.assign(kind, name, input.as_ref().map(Input::Given))?);
        }
        let mut attrs = node.attrs().to_vec();
        apply_attrs(kind, &mut attrs, changes)?;
        name_from_file(kind, &mut attrs);
        check_required(kind, &attrs)?;
        check_class_named(parent, kind, &attrs)?;
        Ok(Filling {
            id: node.id(),
            kind,
            attrs,
            children: node.children().clone(),
            part,
            next: 0,
            path_len,
            slot,
            given: Vec::new(),
        })
    }
}

/// Applies `el`'s attributes and children to `node` (of the same kind), iteratively.
fn fill(
    ctx: &ValueCtx<'_>,
    parent: ElementKind,
    node: Node,
    el: &Element,
    path: &mut String,
) -> Result<Node, ErrorKind> {
    let mut stack = vec![Filling::start(ctx, parent, &node, el.root_part(), None, path.len())?];
    while let Some(top) = stack.last_mut() {
        if let Some(&index) = top.part.children.get(top.next) {
            top.next += 1;
            let child = el.part(index);
            let Some(child_kind) = top.kind.child(&child.tag) else {
                return Err(ErrorKind::invalid_child(top.kind, &child.tag));
            };
            let path_len = path.len();
            let (existing, slot) = match child_kind.multiplicity() {
                Multiplicity::Singleton => {
                    let pos = top.children.iter().position(|c| c.kind() == child_kind);
                    if !top.given.contains(&child_kind) {
                        top.given.push(child_kind);
                    }
                    (pos.and_then(|p| top.children.get(p).cloned()), pos)
                }
                Multiplicity::OnDemand if top.children.iter().any(|c| c.kind() == child_kind) => {
                    return Err(ErrorKind::DuplicateChild(child_kind.tag()));
                }
                _ => (None, None),
            };
            push_segment(path, child_kind.tag(), None);
            let existing = existing.unwrap_or_else(|| empty_node(child_kind));
            let parent = top.kind;
            stack.push(Filling::start(ctx, parent, &existing, child, slot, path_len)?);
            continue;
        }
        let Some(mut done) = stack.pop() else { break };
        if done.kind.is(Role::DefaultClass) && done.given.len() > 1 {
            // DESIGN D11: the actuator defaults in the order given.
            let mut children: Vec<Node> = done.children.iter().cloned().collect();
            let given = &done.given;
            super::defaults::order(
                &mut children,
                |n| n,
                |n| given.iter().position(|k| *k == n.kind()),
            );
            done.children = children.into_iter().collect();
        }
        let node = Node::new(done.id, done.kind, done.attrs, done.children);
        path.truncate(done.path_len);
        match stack.last_mut() {
            Some(parent) => match done.slot {
                Some(p) => {
                    parent.children.set(p, node);
                }
                None => parent.children.push_back(node),
            },
            None => return Ok(node),
        }
    }
    // The loop returns when the outermost element is finished.
    Ok(node)
}

/// Appends `/tag` or `/tag[name=x]` to an element path.
pub(crate) fn push_segment(path: &mut String, tag: &str, name: Option<&str>) {
    if !path.is_empty() {
        path.push('/');
    }
    path.push_str(tag);
    if let Some(n) = name {
        path.push_str("[name=");
        path.push_str(n);
        path.push(']');
    }
}
