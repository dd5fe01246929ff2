//! The lossless save of a model with attachments: what is kept, added, removed and
//! written anew, and where each attached model goes, is [`Model::save`]'s rule (its
//! scene paragraph); this is how.
//!
//! The model is first *spelled*: brought back to the elements its text spells
//! ([`Source::spelled`]: the model before the reader reopened its `<attach>`es), and
//! the lossless writer writes the spelled model against that text. A frame the
//! reader reopened and no edit touched is the body read (its text kept, `<attach>`
//! included); any other frame is spelled as `xml::scene` writes one, keeping the
//! tags of one the reader reopened; the asset `<model>`s are spelled to match the
//! attachments left; the global settings sections are spelled as the merged ones.
//!
//! A part is one distinct attached model value; of the values read from one file,
//! the first in document order claims it (saved losslessly there), and any other is
//! a second version, written anew.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use smol_str::SmolStr;

use super::tag::Tag;
use super::{Output, Outputs, SaveError, SourceText, unescape};
use crate::error::WriteError;
use crate::files::write::{self, OnDisk};
use crate::model::source::Source;
use crate::model::tree::{ElementId, Node};
use crate::model::{Index, Model};
use crate::schema::{ElementKind, Namespace, Role};
use crate::seq::Seq;
use crate::value::{FileAsset, Reference, Value};
use crate::xml::scene::{
    SpellError, Spelling, attrs_of, file_stem, part_options, spell as spell_scene, write_part,
};

/// A model with attachments, spelled as its scene file is (see the module
/// documentation), and the outputs of its parts.
pub(super) struct Spelled {
    /// The model the scene's own files are written from.
    pub(super) model: Model,
    /// The parts' files, by path relative to the scene's folder.
    pub(super) parts: Outputs,
}

/// How one attached model value is saved.
enum Part {
    /// Into its own files, losslessly; its main file is `rel` from the scene's folder.
    Lossless { rel: PathBuf, outputs: Outputs },
    /// With the plain writer, as the file `name` beside the scene's, with the files
    /// it names.
    Plain { name: String, text: String, files: Vec<(String, Arc<[u8]>)> },
}

/// `model` (read from `src`, with attachments or with reopened ones detached)
/// spelled as its scene file, and its parts saved.
///
/// Time: O(n log n) for the `n` elements of the model (rebuilt and indexed once),
/// plus saving each distinct part (each once, however often it is attached).
pub(super) fn spell(model: &Model, src: &Source, with_assets: bool) -> Result<Spelled, SaveError> {
    let lit = src.spelled();
    let folder = src.files.first().and_then(|f| f.disk.as_deref()).and_then(Path::parent);
    let folder = folder.map(crate::files::canonical);
    let values = distinct_values(model);
    // The asset `<model>` of each value: the one read for its file, or a new one.
    let read_assets = read_asset_models(lit, src);
    let parts = save_parts(&values, src, folder.as_deref(), &read_assets, with_assets)?;
    let mut used: HashSet<SmolStr> = HashSet::new();
    let mut reused: HashSet<ElementId> = HashSet::new();
    let mut new_assets: Vec<Node> = Vec::new();
    let mut asset_of: Vec<(&Model, ElementId)> = Vec::with_capacity(values.len());
    let model_kind = ElementKind::ASSET.child_of_role(Role::AssetModel);
    // The names of the asset models kept are taken for the new ones.
    for part in &parts {
        if let Part::Lossless { rel, .. } = part {
            if let Some(name) = read_assets.get(rel).and_then(Node::identifier) {
                used.insert(SmolStr::from(name));
            }
        }
    }
    for (v, part) in values.iter().zip(&parts) {
        let rel = match part {
            Part::Lossless { rel, .. } => rel.clone(),
            Part::Plain { name, .. } => PathBuf::from(name),
        };
        if let Some(node) = read_assets.get(&rel).filter(|_| matches!(part, Part::Lossless { .. }))
        {
            reused.insert(node.id());
            asset_of.push((v, node.id()));
            continue;
        }
        let kind = model_kind.ok_or_else(|| conflict("the schema has no asset <model>"))?;
        let (stem, ext) = split_name(&rel);
        let contents: Arc<[u8]> = match part {
            Part::Lossless { outputs, .. } => {
                outputs.texts.first().map_or(Arc::from([]), |o| o.text.text.as_bytes().into())
            }
            Part::Plain { text, .. } => text.as_bytes().into(),
        };
        let file = FileAsset::with_fixed_name(&stem, &ext, contents);
        let base = file_stem(rel.file_stem().and_then(|s| s.to_str()).unwrap_or("model"));
        let mut name = SmolStr::from(base.as_str());
        let mut k = 0;
        while used.contains(&name)
            || model.index.names.contains_key(&(Namespace::Model, name.clone()))
        {
            k += 1;
            name = smol_str::format_smolstr!("{base}_{k}");
        }
        used.insert(name.clone());
        let attrs =
            attrs_of(kind, [("name", Value::Identifier(name)), ("file", Value::File(file))]);
        let node = Node::new(ElementId::fresh(), kind, attrs, Seq::default());
        asset_of.push((v, node.id()));
        new_assets.push(node);
    }
    let root = spell_tree(model, src, &asset_of, &reused, &new_assets)?;
    let model = if root.ptr_eq(&lit.root) {
        lit.clone()
    } else {
        let mut index = Index::default();
        index
            .insert_subtree(None, &root, 0)
            .map_err(|d| SaveError::NameTaken { name: d.name.to_string() })?;
        Model::from_parts(root, index, crate::files::FileContext::clone(&model.files))
    };
    Ok(Spelled { model, parts: gather(parts) })
}

/// The error for a scene that cannot be made.
fn conflict(what: &str) -> SaveError {
    SaveError::Write(WriteError::Conflict(what.to_string()))
}

/// A file path's name without its extension (folders kept, `/`-separated) and its
/// extension with the dot.
fn split_name(rel: &Path) -> (String, String) {
    let s = rel.to_string_lossy().replace('\\', "/");
    let file_at = s.rfind('/').map_or(0, |i| i + 1);
    match s[file_at..].rfind('.') {
        Some(i) if i > 0 => (s[..file_at + i].to_string(), s[file_at + i..].to_string()),
        _ => (s, String::new()),
    }
}

/// The distinct model values attached to `model` itself, in document order.
fn distinct_values(model: &Model) -> Vec<&Model> {
    let mut by_root: HashMap<ElementId, Vec<usize>> = HashMap::new();
    let mut out: Vec<&Model> = Vec::new();
    for node in model.root.descendants() {
        let Some(a) = node.attached() else { continue };
        let same = by_root.entry(a.model.root.id()).or_default();
        if !same.iter().any(|&i| out[i].ptr_eq(&a.model)) {
            same.push(out.len());
            out.push(&a.model);
        }
    }
    out
}

/// How each value is saved (see the module documentation).
fn save_parts(
    values: &[&Model],
    src: &Source,
    folder: Option<&Path>,
    read_assets: &HashMap<PathBuf, Node>,
    with_assets: bool,
) -> Result<Vec<Part>, SaveError> {
    // Every path of the scene's own files, and each claimed file, lower case (file
    // systems that ignore case would take two of them for one).
    let key = |p: &Path| p.to_string_lossy().to_lowercase();
    let mut taken: HashSet<String> =
        src.files.iter().filter_map(|f| f.rel.as_deref()).map(key).collect();
    let mut parts: Vec<Option<Part>> = Vec::with_capacity(values.len());
    for v in values {
        let own = own_file(v, folder);
        let inside = own.clone().filter(|rel| !taken.contains(&key(rel)));
        // Read from outside the folder: kept where it is while untouched (not for a
        // save into another folder, which takes every file along).
        let outside = || {
            let kept = own.is_none() && !with_assets;
            read_from(v, folder, read_assets).filter(|_| kept)
        };
        let Some(rel) = inside.clone().or_else(outside) else {
            parts.push(None);
            continue;
        };
        match super::outputs(v, with_assets)? {
            outputs if inside.is_none() && !untouched(&outputs) => parts.push(None),
            outputs => {
                let at = rel.parent().map(Path::to_path_buf).unwrap_or_default();
                for o in &outputs.texts {
                    if let Some(p) = &o.text.path {
                        taken.insert(key(&at.join(p)));
                    }
                }
                taken.insert(key(&rel));
                parts.push(Some(Part::Lossless { rel, outputs: outputs.under(&at) }));
            }
        }
    }
    // The others, named after their models in the names left.
    let mut plain_files: HashMap<String, Arc<[u8]>> = HashMap::new();
    for (v, part) in values.iter().zip(parts.iter_mut()) {
        if part.is_some() {
            continue;
        }
        let stem = file_stem(v.name());
        let mut k = 0;
        let (name, text, files) = loop {
            let name = if k == 0 { format!("{stem}.xml") } else { format!("{stem}_{k}.xml") };
            k += 1;
            if taken.contains(&name.to_lowercase()) {
                continue;
            }
            let scene = v.to_scene(&name).map_err(SaveError::Write)?;
            let text = write_part(scene.root()).map_err(SaveError::Write)?;
            // A file on disk with other bytes, that this process did not write, is
            // not replaced.
            let there = folder.map(|f| write::on_disk(&f.join(&name), text.as_bytes(), None));
            if there == Some(OnDisk::Changed) {
                continue;
            }
            let files: Vec<(String, Arc<[u8]>)> = scene
                .root()
                .assets(&part_options())
                .map_err(SaveError::Write)?
                .into_iter()
                .map(|(n, f)| (n, Arc::from(f.contents())))
                .collect();
            break (name, text, files);
        };
        taken.insert(name.to_lowercase());
        for (n, bytes) in &files {
            // Parts written alike may name one file (a mesh both use): the same bytes.
            let same = plain_files.get(&n.to_lowercase()).is_some_and(|b| b[..] == bytes[..]);
            if !same && !taken.insert(n.to_lowercase()) {
                return Err(SaveError::FileNameTaken(PathBuf::from(n)));
            }
            plain_files.insert(n.to_lowercase(), bytes.clone());
        }
        *part = Some(Part::Plain { name, text, files });
    }
    Ok(parts.into_iter().flatten().collect())
}

/// The path of `v`'s main file from the scene's folder, if it was read from a file
/// in that folder (or below it).
fn own_file(v: &Model, folder: Option<&Path>) -> Option<PathBuf> {
    let src = v.side.source.as_deref()?;
    let disk = src.files.first()?.disk.as_deref()?;
    crate::files::canonical(disk).strip_prefix(folder?).ok().map(Path::to_path_buf)
}

/// The path (as the scene's text writes it) of the asset `<model>` read for `v`'s
/// main file, wherever that file lies, if there is one.
fn read_from(
    v: &Model,
    folder: Option<&Path>,
    read_assets: &HashMap<PathBuf, Node>,
) -> Option<PathBuf> {
    let disk = crate::files::canonical(v.side.source.as_deref()?.files.first()?.disk.as_deref()?);
    let folder = folder?;
    read_assets.keys().find(|p| crate::files::canonical(&folder.join(p)) == disk).cloned()
}

/// Whether saving a part writes nothing: each of its texts as read, no other file.
fn untouched(outputs: &Outputs) -> bool {
    outputs.texts.iter().all(|o| !o.text.changed && o.disk.is_some()) && outputs.files.is_empty()
}

/// The outputs of every part, in order.
fn gather(parts: Vec<Part>) -> Outputs {
    let mut out = Outputs::default();
    for part in parts {
        match part {
            Part::Lossless { outputs, .. } => out.append(outputs),
            Part::Plain { name, text, files } => {
                let path = PathBuf::from(&name);
                out.texts.push(Output {
                    text: SourceText { path: Some(path), text, changed: true },
                    disk: None,
                    read: None,
                });
                out.files.extend(files.into_iter().map(|(n, b)| (PathBuf::from(n), b)));
            }
        }
    }
    out
}

/// The asset `<model>`s of the model as its text spells it, by the path of their file
/// from the scene's folder (as the text writes it; the reader resolves it there).
fn read_asset_models(lit: &Model, src: &Source) -> HashMap<PathBuf, Node> {
    let mut out = HashMap::new();
    let Some(asset) = lit.root.child_of_kind(ElementKind::ASSET) else {
        return out;
    };
    for node in asset.children().iter().filter(|c| c.kind().is(Role::AssetModel)) {
        let written = src.records_of(node.id()).find_map(|r| {
            let rec = &src.records[r as usize];
            if src.files[rec.file as usize].rel.as_deref() != src.files[0].rel.as_deref() {
                return None;
            }
            let text = &src.text_of(r)[rec.start as usize..rec.start_end as usize];
            let t = Tag::parse(text);
            let tok = t.tokens.iter().rev().find(|k| t.name_of(k) == "file")?;
            Some(unescape(&text[tok.value.0..tok.value.1]))
        });
        if let Some(path) = written {
            out.entry(PathBuf::from(crate::files::normalize(&path))).or_insert(node.clone());
        }
    }
    out
}

/// The asset `<model>` the `<attach>` of the body `body` (as read) names.
fn attach_of(body: &Node) -> Option<(&Node, ElementId)> {
    let attach = body.children().iter().next_back().filter(|c| c.kind().is(Role::Attach))?;
    attach.attrs().iter().find_map(|(_, v)| match v {
        Value::Reference(Reference::Element(id)) => Some((attach, *id)),
        _ => None,
    })
}

/// The spelled tree (see the module documentation): the scene's walk
/// (`xml::scene::spell`) keeping the nodes read where nothing changed.
fn spell_tree(
    model: &Model,
    src: &Source,
    asset_of: &[(&Model, ElementId)],
    reused: &HashSet<ElementId>,
    new_assets: &[Node],
) -> Result<Node, SaveError> {
    struct KeepRead<'a> {
        read: &'a Model,
        lit: &'a Model,
        asset_of: &'a [(&'a Model, ElementId)],
        reused: &'a HashSet<ElementId>,
        new_assets: &'a [Node],
    }
    impl Spelling for KeepRead<'_> {
        fn frame(&mut self, frame: &Node, written: Node) -> Option<Node> {
            spell_frame(frame, self.read, self.lit, self.asset_of, written)
        }
        fn assets(&mut self, section: &Node) -> Node {
            spell_assets(section, self.lit, self.reused, self.new_assets)
        }
        fn node(&mut self, n: &Node, kids: Vec<Node>) -> Node {
            if kids.iter().zip(n.children().iter()).all(|(a, b)| a.ptr_eq(b)) {
                return n.clone();
            }
            literal_if_same(n, kids, self.lit)
        }
    }
    let mut how = KeepRead { read: &src.read, lit: src.spelled(), asset_of, reused, new_assets };
    spell_scene(model, asset_of, &mut how).map_err(|e| match e {
        SpellError::Settings(k) => conflict(&k),
        SpellError::NoPart => conflict("an attached model has no part"),
    })
}

/// `n` with the children `kids`: the node of the model as read (`lit`) where that is
/// the same (so that its text is kept).
fn literal_if_same(n: &Node, kids: Vec<Node>, lit: &Model) -> Node {
    if let Some(l) = lit.node_by_id(n.id()) {
        let same = std::ptr::eq(l.attrs(), n.attrs())
            && l.children().len() == kids.len()
            && l.children().iter().zip(&kids).all(|(a, b)| a.ptr_eq(b));
        if same {
            return l.clone();
        }
    }
    n.with_children(kids.into_iter().collect())
}

/// The attachment frame `frame` spelled: the body read where nothing of it changed,
/// else `new` (a new body holding an `<attach>`), keeping the tags read.
fn spell_frame(
    frame: &Node,
    read: &Model,
    lit: &Model,
    asset_of: &[(&Model, ElementId)],
    new: Node,
) -> Option<Node> {
    let a = frame.attached()?;
    let asset = asset_of.iter().find(|(m, _)| m.ptr_eq(&a.model))?.1;
    let was = lit.node_by_id(frame.id());
    if let (Some(r), Some(l)) = (read.node_by_id(frame.id()), was) {
        let same = l.kind() == new.kind()
            && r.attached().is_some_and(|ra| ra.scope == a.scope)
            && std::ptr::eq(r.attrs(), frame.attrs())
            && r.children().len() == frame.children().len()
            && r.children().iter().zip(frame.children().iter()).all(|(x, y)| x.ptr_eq(y))
            && attach_of(l).is_some_and(|(_, id)| id == asset);
        if same {
            return Some(l.clone());
        }
    }
    let Some(l) = was.filter(|l| l.kind() == new.kind()) else {
        // Not read, or read as the other tag: written as new.
        return Some(if was.is_some() {
            Node::new(ElementId::fresh(), new.kind(), new.attrs().to_vec(), new.children().clone())
        } else {
            new
        });
    };
    // The `<attach>` read keeps its tag (its prefix rewritten in place).
    let last = new.children().len().checked_sub(1)?;
    let Some((read_attach, _)) = attach_of(l) else { return Some(new) };
    let attach = new.children().get(last)?;
    let attach = Node::new(
        read_attach.id(),
        attach.kind(),
        attach.attrs().to_vec(),
        attach.children().clone(),
    );
    Some(new.with_child_at(last, attach))
}

/// The asset section `section` with the asset `<model>`s of the scene: those read
/// (`reused`) where they were read, then the new ones; the section read where that is
/// the same.
fn spell_assets(section: &Node, lit: &Model, reused: &HashSet<ElementId>, new: &[Node]) -> Node {
    let mut out: Vec<Node> = section.children().iter().cloned().collect();
    if let Some(read) = lit.node_by_id(section.id()) {
        // Each one read goes after the sibling read before it that is still there.
        let mut after: Option<ElementId> = None;
        for c in read.children().iter() {
            // (One an `<attach>` that stayed an element uses is there already.)
            let there = out.iter().any(|o| o.id() == c.id());
            if reused.contains(&c.id()) && !there {
                let at =
                    after.and_then(|id| out.iter().position(|o| o.id() == id)).map_or(0, |p| p + 1);
                out.insert(at, c.clone());
                after = Some(c.id());
            } else if there {
                after = Some(c.id());
            }
        }
    }
    out.extend(new.iter().cloned());
    if out.len() == section.children().len()
        && out.iter().zip(section.children().iter()).all(|(a, b)| a.ptr_eq(b))
    {
        return section.clone();
    }
    literal_if_same(section, out, lit)
}
