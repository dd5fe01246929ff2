//! The lossless writer: a model read from MJCF written back into its own files, with
//! every part no edit touched byte for byte as it was read.
//!
//! What is kept is stated in [`Model::save`]; here it is applied per element of each
//! file's tag tree (`xml::source`). The spans of the tags are byte offsets into the
//! whole text as read, a byte-order mark included (`xml::read` reads through one place
//! that counts it).
//!
//! A model with attachments saves as a scene (`scene`): its own files written
//! against the text they were read from, each attached model in files of its own.

mod disk;
mod scene;
mod tag;

pub use disk::SaveOptions;

use std::collections::{HashMap, HashSet};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use crate::error::WriteError;
use crate::files::write::Fingerprint;
use crate::model::Model;
use crate::model::tree::{ElementId, Node};
use crate::schema::{AttrType, ElementKind, Multiplicity, Role};
use crate::value::{FloatStyle, Reference, Value};
use crate::xml::rules::{self, DefaultChild};
use crate::xml::source::{NO_RECORD, RecordKind, Source};
use tag::Tag;

/// Why a model cannot be saved losslessly.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum SaveError {
    /// The model keeps no source text: it was built through the API, or read with
    /// [`ReadOptions::keep_source`](crate::ReadOptions::keep_source) off.
    #[error("the model keeps no source text to save into (write it with to_xml_string)")]
    NoSource,
    /// Saving the model's attachments as MuJoCo `<attach>`es needs a name the model
    /// already uses (a frame body `scope/`, or a joint of one written `scope/j/`).
    #[error("the scene's name '{name}' is taken by an element of the model")]
    NameTaken {
        /// The name.
        name: String,
    },
    /// Two files of the scene would be written under one path (a part written with
    /// the plain writer names a file another part is saved into).
    #[error("two files of the scene would be written as '{}'", .0.display())]
    FileNameTaken(PathBuf),
    /// A part of the scene cannot be written with the plain writer (an attached model
    /// built in code: [`Model::save_scene`]'s errors).
    #[error("a part of the scene cannot be written: {0}")]
    Write(WriteError),
    /// A file of the model has no path to be written to: the main text read from a
    /// string (for [`Model::save`] and [`Model::save_as`]), or an in-memory include.
    #[error("the model's text read from a string or memory has no path to save to")]
    NoPath,
    /// A file to write lies outside the folder it is to be written in (a confined
    /// model's, or the folder given to [`Model::save_as`]).
    #[error("'{}' lies outside the folder it is to be written in", .0.display())]
    OutsideRoot(PathBuf),
    /// A file the save must write changed on disk since it was read (another
    /// program edited or removed it): nothing was written. Save with
    /// [`SaveOptions::overwrite_changed`] to overwrite it on purpose.
    #[error("'{}' changed on disk since it was read; nothing was saved (SaveOptions::overwrite_changed overwrites it)", .0.display())]
    ChangedOnDisk(PathBuf),
    /// A folder a file is to be written in, below the folder written to, is a symlink
    /// (a link there would send the file elsewhere): nothing was written.
    #[error("'{}' is a symlink, not a folder to write in; nothing was saved", .0.display())]
    SymlinkedFolder(PathBuf),
    /// A file could not be written.
    #[error("cannot write '{}': {reason}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The reason the system gives.
        reason: String,
    },
    /// The root default class renamed where the file spells it so that MuJoCo reads
    /// no model: on a top-level `<default>`, any name but `main` ("top-level default
    /// class 'main' cannot be renamed"); on the class inside it (the shape
    /// `<default><default class="/">`), `main` ("repeated default class name").
    /// Nothing was saved; [`Model::to_xml_string`] writes the class as MuJoCo
    /// compiles it.
    #[error(
        "the root default class is renamed '{0}', a name MuJoCo refuses where the file spells the class (a top-level <default> takes only main: \"top-level default class 'main' cannot be renamed\"; a class inside it not main: \"repeated default class name\"); nothing was saved (to_xml_string writes it as MuJoCo compiles it)"
    )]
    RootClassRenamed(String),
    /// A required reference to an element that was removed.
    #[error("attribute '{attribute}' of <{tag}> is required, but the element it named was removed")]
    MissingRequired {
        /// The element's tag.
        tag: &'static str,
        /// The attribute.
        attribute: &'static str,
    },
    /// A reference to an element that has no name to write it by.
    #[error("attribute '{attribute}' of <{tag}> names an element that has no name")]
    UnnamedTarget {
        /// The element's tag.
        tag: &'static str,
        /// The attribute.
        attribute: &'static str,
    },
}

/// One file of a model's source, as [`Model::to_source_files`] writes it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SourceText {
    /// The path relative to the model's folder (the main file's name, an include's
    /// path from there); `None` for the main text of a model read from a string.
    pub path: Option<PathBuf>,
    /// The text.
    pub text: String,
    /// Whether the text differs from the text read.
    pub changed: bool,
}

impl Model {
    /// The model written back into the files it was read from (the main file and its
    /// includes, in the order they were read), losslessly: see
    /// [`Model::save`] for what is kept. Nothing is written to disk. For a model with
    /// attachments, the files of its parts follow (by their paths from the model's
    /// folder; a part written anew is `changed`); the other files of a part written
    /// with the plain writer (its meshes, its own parts) are not texts returned here.
    ///
    /// Time: O(L) for `L` bytes of source text when nothing changed (each file is
    /// copied); with edits, O(L + E · (depth · log n + width)) for `E` edited elements
    /// and their ancestors, plus O(n) once when an edit renamed or removed a named
    /// element (to find the references to it). With attachments, O(n log n) more to
    /// spell the model as its scene file, plus saving each distinct attached model.
    ///
    /// # Errors
    /// - [`SaveError::NoSource`]: the model was not read from MJCF (or was read with
    ///   the source off);
    /// - [`SaveError::NameTaken`], [`SaveError::FileNameTaken`], [`SaveError::Write`]:
    ///   attachments that cannot be written as a scene (see [`Model::save`]);
    /// - [`SaveError::MissingRequired`], [`SaveError::UnnamedTarget`]: a reference
    ///   that cannot be written.
    ///
    /// # Examples
    /// ```
    /// let text = "<mujoco>\n  <!-- the floor -->\n  <worldbody>\n    <geom name='floor' size='1 1 .1'  type=\"plane\"/>\n  </worldbody>\n</mujoco>\n";
    /// let m = mjcf::Model::from_xml_str(text)?;
    /// assert_eq!(m.to_source_files()?[0].text, text); // untouched: byte for byte
    /// let floor = m.find(mjcf::Namespace::Geom, "floor").unwrap();
    /// let m = m.set(&floor, mjcf::Attrs::new().set("size", [2.0, 2.0, 0.1]))?;
    /// let saved = &m.to_source_files()?[0];
    /// assert_eq!(saved.text, text.replace("'1 1 .1'", "'2 2 0.1'"));
    /// assert!(saved.changed);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn to_source_files(&self) -> Result<Vec<SourceText>, SaveError> {
        Ok(outputs(self, false)?.texts.into_iter().map(|o| o.text).collect())
    }

    /// The heap bytes the source kept for [`Model::save`] takes (the text of every file
    /// read and the record of every tag; the model as read is shared with the model),
    /// or 0 for a model that keeps none.
    ///
    /// Time: O(files).
    pub fn source_heap_bytes(&self) -> usize {
        self.side.source.as_deref().map_or(0, Source::heap_bytes)
    }

    /// The asset files the model's elements name, by their path from the model's
    /// folder as the reader resolves them (the compiler's folder settings joined
    /// with the path as written in the element's own file; a file set through the
    /// API by its name, as the lossless writer writes it).
    fn asset_files(&self) -> Vec<(PathBuf, std::sync::Arc<[u8]>)> {
        let Some(src) = self.side.source.as_deref() else { return Vec::new() };
        let base = self.basepaths();
        let mut out = Vec::new();
        for n in self.root.descendants() {
            let kind = n.kind();
            for (i, v) in n.attrs() {
                let (Value::File(f), AttrType::File { path_namespace }) =
                    (v, kind.attr(*i as usize).ty)
                else {
                    continue;
                };
                let name = kind.attr(*i as usize).name;
                // The path as written, in the file that names it, if read.
                let written = src.records_of(n.id()).find_map(|r| {
                    let rec = &src.records[r as usize];
                    let text = &src.text_of(r)[rec.start as usize..rec.start_end as usize];
                    let t = Tag::parse(text);
                    let tok = t.tokens.iter().rev().find(|k| t.name_of(k) == name)?;
                    let folder = src.files[rec.file as usize]
                        .rel
                        .as_ref()
                        .and_then(|p| p.parent().map(Path::to_path_buf))
                        .unwrap_or_default();
                    Some((folder, unescape(&text[tok.value.0..tok.value.1])))
                });
                let (folder, path) = written.unwrap_or_else(|| (PathBuf::new(), f.vfs_name(false)));
                let joined = crate::files::join(base.for_namespace(path_namespace), &path);
                out.push((folder.join(crate::files::normalize(&joined)), f.contents().into()));
            }
        }
        out
    }
}

/// Every file a save writes, by path from the model's folder.
#[derive(Default)]
struct Outputs {
    /// MJCF texts: the model's own files (main first), then its parts'.
    texts: Vec<Output>,
    /// Other files: those of parts written with the plain writer (meshes, their own
    /// parts) and, when asked for, the asset files the lossless files name.
    files: Vec<(PathBuf, std::sync::Arc<[u8]>)>,
}

/// One MJCF text to write.
struct Output {
    text: SourceText,
    /// Where it was read from (`None`: not read; written beside the model's file).
    disk: Option<PathBuf>,
    /// What that file held when it was read.
    read: Option<Fingerprint>,
}

impl Outputs {
    /// The same outputs with their paths under the folder `at`.
    fn under(mut self, at: &Path) -> Outputs {
        for o in &mut self.texts {
            o.text.path = o.text.path.take().map(|p| at.join(p));
        }
        for (p, _) in &mut self.files {
            *p = at.join(&*p);
        }
        self
    }

    fn append(&mut self, other: Outputs) {
        self.texts.extend(other.texts);
        self.files.extend(other.files);
    }
}

/// What saving `model` writes (see [`Model::save`]); with the asset files its files
/// name when `with_assets`.
///
/// Time: as [`Model::to_source_files`].
fn outputs(model: &Model, with_assets: bool) -> Result<Outputs, SaveError> {
    let src = model.side.source.as_deref().ok_or(SaveError::NoSource)?;
    let composed = model.index.attachments().next().is_some() || src.literal.is_some();
    let (spelled, mut out) = if composed {
        let s = scene::spell(model, src, with_assets)?;
        (s.model, s.parts)
    } else {
        (model.clone(), Outputs::default())
    };
    let read = src.spelled();
    let saver = Saver { model: &spelled, read, src, dirty: dirty(&spelled, read) };
    let mut own = Vec::with_capacity(src.files.len());
    for (f, file) in src.files.iter().enumerate() {
        let text = saver.file(f)?;
        let changed = *text != *file.text;
        own.push(Output {
            text: SourceText { path: file.rel.clone(), text, changed },
            disk: file.disk.clone(),
            read: file.read,
        });
    }
    own.append(&mut out.texts);
    out.texts = own;
    if with_assets {
        let mut files = model.asset_files();
        files.append(&mut out.files);
        out.files = files;
    }
    Ok(out)
}

/// The text of an attribute value as written, its entities and character
/// references expanded (the five of XML and numeric ones; anything else is kept).
fn unescape(v: &str) -> String {
    if !v.contains('&') {
        return v.to_string();
    }
    let mut out = String::with_capacity(v.len());
    let mut rest = v;
    while let Some(i) = rest.find('&') {
        out.push_str(&rest[..i]);
        rest = &rest[i..];
        let Some(end) = rest.find(';') else { break };
        let entity = &rest[1..end];
        let c = match entity {
            "amp" => Some('&'),
            "lt" => Some('<'),
            "gt" => Some('>'),
            "quot" => Some('"'),
            "apos" => Some('\''),
            _ => entity
                .strip_prefix("#x")
                .map(|h| u32::from_str_radix(h, 16).ok())
                .or_else(|| entity.strip_prefix('#').map(|d| d.parse().ok()))
                .flatten()
                .and_then(char::from_u32),
        };
        match c {
            Some(c) => {
                out.push(c);
                rest = &rest[end + 1..];
            }
            None => {
                out.push('&');
                rest = &rest[1..];
            }
        }
    }
    out.push_str(rest);
    out
}

/// The elements whose text changes though their node does not: those holding a
/// reference to an element renamed or removed since the read, and their ancestors.
///
/// Time: O(changed part) to find renamed and removed elements; O(n) more if any.
fn dirty(model: &Model, read: &Model) -> HashSet<ElementId> {
    let mut gone: HashSet<ElementId> = HashSet::new();
    // Renamed (in the current tree, below nodes that differ from the read ones).
    let mut stack = vec![&model.root];
    while let Some(n) = stack.pop() {
        match read.node_by_id(n.id()) {
            Some(r) if r.ptr_eq(n) => continue,
            Some(r) if r.identifier() != n.identifier() => {
                gone.insert(n.id());
            }
            _ => {}
        }
        stack.extend(n.children().iter());
    }
    // Removed (in the read tree, below nodes that differ from the current ones).
    let mut stack = vec![&read.root];
    while let Some(r) = stack.pop() {
        match model.node_by_id(r.id()) {
            Some(n) if n.ptr_eq(r) => continue,
            Some(_) => {}
            None => {
                gone.extend(r.descendants().map(Node::id));
                continue;
            }
        }
        stack.extend(r.children().iter());
    }
    let mut out = HashSet::new();
    if gone.is_empty() {
        return out;
    }
    // Every element naming one of them, with its ancestors.
    let mut path: Vec<ElementId> = Vec::new();
    let mut stack = vec![(&model.root, 0usize)];
    while let Some((n, depth)) = stack.pop() {
        path.truncate(depth);
        path.push(n.id());
        let names = n
            .attrs()
            .iter()
            .any(|(_, v)| matches!(v, Value::Reference(Reference::Element(t)) if gone.contains(t)));
        if names {
            out.extend(path.iter().copied());
        }
        stack.extend(n.children().iter().map(|c| (c, depth + 1)));
    }
    out
}

/// What is written, in order.
enum Item {
    /// A span of a file's text.
    Text(u32, u32, u32),
    Str(String),
    /// A recorded tag, with its content and end tag.
    Record(u32),
    /// An element without a record (or moved with several), written in full, with
    /// its children indented by the given text.
    New(Node, String),
}

struct Saver<'a> {
    /// The model to write (a model with attachments spelled as its scene file).
    model: &'a Model,
    /// The model its text spells ([`Source::spelled`]).
    read: &'a Model,
    src: &'a Source,
    /// See [`dirty`].
    dirty: HashSet<ElementId>,
}

impl Saver<'_> {
    /// The text of file `f`.
    fn file(&self, f: usize) -> Result<String, SaveError> {
        let file = &self.src.files[f];
        let text = &file.text;
        if file.root == NO_RECORD {
            return Ok(text.to_string());
        }
        let root = &self.src.records[file.root as usize];
        let nl = newline(text);
        let mut out = String::with_capacity(text.len() + 64);
        out.push_str(&text[..root.start as usize]);
        let mut stack = vec![Item::Record(file.root)];
        while let Some(item) = stack.pop() {
            match item {
                Item::Text(f, a, b) => {
                    out.push_str(&self.src.files[f as usize].text[a as usize..b as usize]);
                }
                Item::Str(s) => out.push_str(&s),
                Item::Record(r) => {
                    let items = self.expand(r, nl)?;
                    stack.extend(items.into_iter().rev());
                }
                Item::New(node, indent) => self.write_new(&node, nl, &indent, &mut out)?,
            }
        }
        out.push_str(&text[root.end_end as usize..]);
        Ok(out)
    }

    /// Whether the element `id` is written as read.
    fn clean(&self, id: ElementId) -> bool {
        match (self.model.node_by_id(id), self.read.node_by_id(id)) {
            (Some(n), Some(r)) => n.ptr_eq(r) && !self.dirty.contains(&id),
            _ => false,
        }
    }

    /// The items of the record `r`: its text as read if its element is clean, else
    /// its start tag (rewritten), its children and its end tag; `nl`: the line break
    /// new lines take (the file's, [`newline`]).
    fn expand(&self, r: u32, nl: &str) -> Result<Vec<Item>, SaveError> {
        let rec = &self.src.records[r as usize];
        let whole = Item::Text(rec.file, rec.start, rec.end_end);
        if rec.kind == RecordKind::Include || self.clean(rec.id) {
            return Ok(vec![whole]);
        }
        let Some(node) = self.model.node_by_id(rec.id) else { return Ok(Vec::new()) };
        let children = self.children(r, node, nl)?;
        let open = rec.self_closing() && !children.is_empty();
        let mut items = vec![Item::Str(self.start_tag(r, node, open)?)];
        let text = self.src.text_of(r);
        if open {
            items.extend(children);
            let name = Tag::parse(&text[rec.start as usize..rec.start_end as usize]).tag_name();
            items.push(Item::Str(format!("{nl}{}</{name}>", indent_of(text, rec.start))));
        } else if !rec.self_closing() {
            items.extend(children);
            // What follows the last child, and the end tag.
            let last = self.src.children(r).last();
            let from = last.map_or(rec.start_end, |c| self.src.records[c as usize].end_end);
            items.push(Item::Text(rec.file, from, rec.end_end));
        }
        Ok(items)
    }

    /// The children of record `r` (of the element `node`) in the model's order: each
    /// child read with the text before it, and the new ones (on lines ending with `nl`
    /// where the text before the children gives no line break).
    fn children(&self, r: u32, node: &Node, nl: &str) -> Result<Vec<Item>, SaveError> {
        let rec = &self.src.records[r as usize];
        let id = rec.id;
        let pos: HashMap<ElementId, usize> =
            node.children().iter().enumerate().map(|(i, c)| (c.id(), i)).collect();
        // (position in the model, position in the text) and the items.
        let mut segments: Vec<((usize, usize), [Item; 2])> = Vec::new();
        let mut waiting: Vec<(usize, [Item; 2])> = Vec::new();
        let mut prev_end = rec.start_end;
        let mut ws: Option<String> = None;
        let mut last_at = 0;
        for (k, c) in self.src.children(r).enumerate() {
            let crec = &self.src.records[c as usize];
            let lead = Item::Text(rec.file, prev_end, crec.start);
            if ws.is_none() && crec.kind != RecordKind::Include {
                ws = line_break(&self.src.text_of(r)[prev_end as usize..crec.start as usize]);
            }
            prev_end = crec.end_end;
            let at = match crec.kind {
                RecordKind::Include => {
                    // Where the elements it brings are (an include inside an element),
                    // else with the next element read.
                    match self.included_at(c, &pos) {
                        Some(at) => segments.push(((at, k), [lead, Item::Record(c)])),
                        None => waiting.push((k, [lead, Item::Record(c)])),
                    }
                    continue;
                }
                // A tag standing for this very element (the root class's `/`).
                _ if crec.id == id => Some(last_at),
                // Singletons keep their place in the text (the model holds them in
                // schema order): with the element before them.
                _ if self.single(crec.id) => pos.contains_key(&crec.id).then_some(last_at),
                _ => pos.get(&crec.id).copied(),
            };
            let Some(at) = at else { continue };
            last_at = at;
            for (j, items) in waiting.drain(..) {
                segments.push(((at, j), items));
            }
            segments.push(((at, k), [lead, Item::Record(c)]));
        }
        for (j, items) in waiting.drain(..) {
            segments.push(((usize::MAX, j), items));
        }
        if self.src.primary(id) == Some(r) {
            let text = self.src.text_of(r);
            let ws = ws.unwrap_or_else(|| format!("{nl}{}  ", indent_of(text, rec.start)));
            for (at, c) in node.children().iter().enumerate() {
                if self.at_home(c.id(), id) || blank(c) {
                    continue;
                }
                let mut own = self.src.records_of(c.id());
                let item = match (own.next(), own.next()) {
                    // Moved here with its one tag: its text, as read (or rewritten).
                    (Some(one), None) => Item::Record(one),
                    _ => Item::New(c.clone(), ws.trim_start_matches(['\n', '\r']).to_string()),
                };
                segments.push(((at, usize::MAX), [Item::Str(ws.clone()), item]));
            }
        }
        segments.sort_by_key(|(key, _)| *key);
        Ok(segments.into_iter().flat_map(|(_, items)| items).collect())
    }

    /// The last position among `pos` of the repeated elements the include `c` brings
    /// (the children of the included file's root, recorded right after the include).
    fn included_at(&self, c: u32, pos: &HashMap<ElementId, usize>) -> Option<usize> {
        let root = c + 1;
        let rec = self.src.records.get(root as usize)?;
        if rec.kind != RecordKind::FileRoot || rec.parent != NO_RECORD {
            return None;
        }
        // Singletons say nothing of the order (the model holds them in schema order).
        let brought = self.src.children(root).map(|k| self.src.records[k as usize].id);
        brought.filter(|id| !self.single(*id)).filter_map(|id| pos.get(&id)).max().copied()
    }

    /// Whether the element `id` is a singleton or on-demand element (not repeated).
    fn single(&self, id: ElementId) -> bool {
        let node = self.model.node_by_id(id);
        node.is_some_and(|n| n.kind().multiplicity() != Multiplicity::Repeated)
    }

    /// Whether the element `child` has a tag under a tag of `parent`.
    fn at_home(&self, child: ElementId, parent: ElementId) -> bool {
        self.src.records_of(child).any(|c| {
            let p = self.src.records[c as usize].parent;
            p != NO_RECORD && self.src.records[p as usize].id == parent
        })
    }

    /// The start tag of record `r` for the element `node`, rewritten where the
    /// element's attributes changed (`open`: a `<x/>` that now has children).
    fn start_tag(&self, r: u32, node: &Node, open: bool) -> Result<String, SaveError> {
        let rec = &self.src.records[r as usize];
        let text = &self.src.text_of(r)[rec.start as usize..rec.start_end as usize];
        let tag = Tag::parse(text);
        let read = self.read.node_by_id(rec.id);
        let unchanged = read.is_some_and(|n| std::ptr::eq(n.attrs(), node.attrs()))
            && !self.dirty.contains(&rec.id);
        // A root `<default>` the reader would fold into the root class says `main`.
        let main = self.folds(r, node).then(|| ("class", "main".to_string()));
        if rec.kind == RecordKind::FileRoot || unchanged {
            return Ok(tag.rewrite(&[], &[], main.as_slice(), open));
        }
        let kind = node.kind();
        let mut indices: Vec<usize> = node.attrs().iter().map(|(i, _)| *i as usize).collect();
        if let Some(read) = read {
            indices.extend(read.attrs().iter().map(|(i, _)| *i as usize));
        }
        indices.sort_unstable();
        indices.dedup();
        let (mut set, mut remove, mut append) = (Vec::new(), Vec::new(), Vec::new());
        let primary = self.src.primary(rec.id) == Some(r);
        for i in indices {
            let before = read.and_then(|n| value_text(self.read, n, i).ok().flatten());
            let now = value_text(self.model, node, i)?;
            if before == now {
                continue;
            }
            let name = kind.attr(i).name;
            let mine = tag.tokens.iter().rposition(|t| attr_of(kind, tag.name_of(t)) == Some(i));
            // The last tag of the element that gives this attribute.
            let last = self.src.records_of(rec.id).filter(|&q| self.gives(q, kind, i)).last();
            match (now, mine) {
                (Some(v), Some(k)) if last == Some(r) => set.push((k, v)),
                (Some(v), _) if last.is_none() && primary => append.push((name, v)),
                (None, Some(_)) => {
                    let all = tag.tokens.iter().enumerate();
                    remove.extend(
                        all.filter(|(_, t)| attr_of(kind, tag.name_of(t)) == Some(i))
                            .map(|(k, _)| k),
                    );
                }
                _ => {}
            }
        }
        // The root class renamed: MuJoCo reads a top-level `<default>` named other
        // than `main`, or a class `main` inside one, as no model.
        if Some(rec.id) == crate::model::layout::root_class(self.model) {
            let class = kind.identifier().map(|i| kind.attr(i).name);
            let named = set.iter().any(|(k, _)| Some(tag.name_of(&tag.tokens[*k])) == class)
                || append.iter().any(|(n, _)| Some(*n) == class);
            let top = self.top_level_default(r);
            match node.identifier() {
                Some(n) if named && !n.is_empty() && (n == "main") != top => {
                    return Err(SaveError::RootClassRenamed(n.into()));
                }
                _ => {}
            }
        }
        append.extend(main);
        Ok(tag.rewrite(&set, &remove, &append, open))
    }

    /// Whether the record `r` is a `<default>` tag at the top level of its file.
    fn top_level_default(&self, r: u32) -> bool {
        let rec = &self.src.records[r as usize];
        self.at_file_top(r)
            && rec.kind == RecordKind::Element
            && self.model.node_by_id(rec.id).is_some_and(|n| n.kind() == ElementKind::DEFAULT)
    }

    /// Whether the record `r` is a child of its file's root tag.
    fn at_file_top(&self, r: u32) -> bool {
        let p = self.src.records[r as usize].parent;
        p != NO_RECORD && self.src.records[p as usize].parent == NO_RECORD
    }

    /// Whether the record `r` is a file's root `<default>` (the root class's outer
    /// tag, `node`) without attributes whose content, as written, the reader would
    /// fold into the root class (one class named `/`: `rules::folds_into_root_class`),
    /// reading another model: a class `/` left alone by an edit where it stood beside
    /// other classes (a composed model written out). Such a tag is written
    /// `class="main"`, as the plain writer writes it (a wrapper with an attribute is
    /// never folded).
    fn folds(&self, r: u32, node: &Node) -> bool {
        let rec = &self.src.records[r as usize];
        if !self.at_file_top(r) || rec.kind != RecordKind::Element || !node.attrs().is_empty() {
            return false;
        }
        if Some(rec.id) != crate::model::layout::root_class(self.model) {
            return false;
        }
        let written = node.children().iter().filter(|c| !blank(c)).map(|c| {
            if c.kind().is(Role::DefaultClass) {
                DefaultChild::Class(c.identifier())
            } else {
                DefaultChild::Setting
            }
        });
        rules::folds_into_root_class(false, written)
    }

    /// Whether the record `q` (an element's own tag) gives the attribute `i`.
    fn gives(&self, q: u32, kind: ElementKind, i: usize) -> bool {
        let rec = &self.src.records[q as usize];
        if rec.kind != RecordKind::Element {
            return false;
        }
        let t = Tag::parse(&self.src.text_of(q)[rec.start as usize..rec.start_end as usize]);
        t.tokens.iter().any(|k| attr_of(kind, t.name_of(k)) == Some(i))
    }

    /// Writes `node` (and its children) in full, indented by `indent`, its lines ending
    /// with `nl`.
    fn write_new(
        &self,
        node: &Node,
        nl: &str,
        indent: &str,
        out: &mut String,
    ) -> Result<(), SaveError> {
        // (node, depth, closing): an explicit stack, so nesting depth costs no stack.
        let mut stack: Vec<(&Node, usize, bool)> = vec![(node, 0, false)];
        let mut first = true;
        while let Some((n, depth, closing)) = stack.pop() {
            if !first {
                out.push_str(nl);
                out.push_str(indent);
                (0..depth).for_each(|_| out.push_str("  "));
            }
            first = false;
            let tag = n.kind().tag();
            if closing {
                let _ = write!(out, "</{tag}>");
                continue;
            }
            out.push('<');
            out.push_str(tag);
            for (i, _) in n.attrs() {
                let Some(v) = value_text(self.model, n, *i as usize)? else { continue };
                let _ = write!(
                    out,
                    " {}=\"{}\"",
                    n.kind().attr(*i as usize).name,
                    tag::escape(&v, b'"')
                );
            }
            let kids: Vec<&Node> = n.children().iter().filter(|c| !blank(c)).collect();
            if kids.is_empty() {
                out.push_str("/>");
                continue;
            }
            out.push('>');
            stack.push((n, depth, true));
            stack.extend(kids.into_iter().rev().map(|c| (c, depth + 1, false)));
        }
        Ok(())
    }
}

/// The whitespace on the line of `at` before it (`""` if anything else is there).
/// Lines end at `\n`, `\r\n` or a `\r` alone, as XML ends them.
fn indent_of(text: &str, at: u32) -> &str {
    let before = &text[..at as usize];
    let line = before.rfind(['\n', '\r']).map_or(before, |i| &before[i + 1..]);
    if line.chars().all(|c| c == ' ' || c == '\t') { line } else { "" }
}

/// The line break and indentation ending `lead` (the text before a child), if it
/// ends with whitespace after its last line break (`\n`, `\r\n` or `\r`, kept as
/// written); `lead` itself if it is all whitespace on one line.
fn line_break(lead: &str) -> Option<String> {
    let at = lead.rfind(['\n', '\r']);
    let indent = at.map_or(lead, |i| &lead[i + 1..]);
    if !indent.chars().all(|c| c == ' ' || c == '\t') {
        return None;
    }
    let from = match at {
        Some(i) if lead[..i].ends_with('\r') && lead[i..].starts_with('\n') => i - 1,
        Some(i) => i,
        None => 0,
    };
    Some(lead[from..].to_string())
}

/// The line break of `text`: its first one (`\n`, `\r\n` or `\r`), or `\n` if it
/// has none.
///
/// Time: O(length of the first line).
fn newline(text: &str) -> &'static str {
    let b = text.as_bytes();
    match b.iter().position(|&c| c == b'\n' || c == b'\r') {
        Some(i) if b[i] == b'\r' && b.get(i + 1) == Some(&b'\n') => "\r\n",
        Some(i) if b[i] == b'\r' => "\r",
        _ => "\n",
    }
}

/// Whether the node is an empty singleton, holding only empty singletons (every
/// model has them; nothing is written for them).
fn blank(n: &Node) -> bool {
    n.descendants().all(|d| {
        d.kind().multiplicity() == Multiplicity::Singleton
            && d.attrs().is_empty()
            && d.attached().is_none()
    })
}

/// The attribute index of the attribute named `name` (`dclass` is `class`).
fn attr_of(kind: ElementKind, name: &str) -> Option<usize> {
    kind.attr_index(if name == "dclass" { "class" } else { name })
}

/// The text of attribute `i` of `node` in `model` (`None`: not written, such as a
/// reference to an element removed).
fn value_text(model: &Model, node: &Node, i: usize) -> Result<Option<String>, SaveError> {
    let Some(v) = node.attr(i) else { return Ok(None) };
    let kind = node.kind();
    let spec = kind.attr(i);
    Ok(Some(match v {
        Value::Reference(Reference::Element(t)) => {
            let Some(target) = model.node_by_id(*t) else {
                if spec.required {
                    return Err(SaveError::MissingRequired {
                        tag: kind.tag(),
                        attribute: spec.name,
                    });
                }
                return Ok(None);
            };
            match target.identifier() {
                Some(n) => n.to_string(),
                None if Some(target.id()) == crate::model::layout::root_class(model) => {
                    "main".to_string()
                }
                None => {
                    return Err(SaveError::UnnamedTarget { tag: kind.tag(), attribute: spec.name });
                }
            }
        }
        Value::File(f) => f.vfs_name(false),
        v => {
            let mut s = String::new();
            v.write_plain(&mut s, FloatStyle::default());
            s
        }
    }))
}

#[cfg(test)]
mod tests;
