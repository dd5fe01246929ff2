//! `<include>`: the include tree's rules (cycles, files included twice, depth), the
//! file an include names, and reading it: at the root as a model merged into the
//! including one, inside an element in place.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::sync::Arc;

use quick_xml::events::BytesStart;

use super::{
    MAX_INCLUDE_DEPTH, NONE, Reader, SrcFile, children_of, in_settings, parse, push_child,
    push_unique, read_document, unique_child, utf8,
};
use crate::error::{ErrorKind, ReadError};
use crate::files::{self, FileContext};
use crate::model::Model;
use crate::model::tree::{ElementId, Node};
use crate::schema::{ElementKind, Multiplicity};
use crate::xml::source::{RecordKind, SourceBuilder};

/// The files of one model's include tree, for the rules on them: a file includes
/// neither itself (a cycle) nor a file the tree already includes (MuJoCo includes
/// each file once per model), and includes nest at most [`MAX_INCLUDE_DEPTH`] deep.
/// Files are told apart by their canonical path (symlinks followed), in-memory files
/// by their path as written, normalised.
pub(super) struct Includes {
    /// The main file and the includes above the one being read.
    stack: Vec<PathBuf>,
    /// Every file of the tree so far, the main file too.
    seen: HashSet<PathBuf>,
    /// The files' text and tags, when the source is kept.
    pub(super) src: Option<SourceBuilder>,
    /// The model's folder, which recorded files' paths are relative to.
    main_dir: Option<PathBuf>,
}

impl Includes {
    /// The tree of the main file `main` (its key), in the folder `main_dir`; the
    /// source is recorded if `keep_source`.
    pub(super) fn new(main: PathBuf, main_dir: Option<PathBuf>, keep_source: bool) -> Includes {
        Includes {
            seen: HashSet::from([main.clone()]),
            stack: vec![main],
            src: keep_source.then(SourceBuilder::default),
            main_dir,
        }
    }

    /// Records a file read (`shown`: its path as read, on disk or, for an in-memory
    /// file, as written) whose root stands for `stands_for` (the main file's: `None`
    /// and `main`). `None` when the source is not kept.
    pub(super) fn record_file(
        &mut self,
        shown: Option<&Path>,
        on_disk: bool,
        text: &str,
        main: bool,
        stands_for: Option<ElementId>,
    ) -> Option<SrcFile> {
        let src = self.src.as_mut()?;
        let rel = shown.map(|p| match (on_disk, &self.main_dir) {
            (true, Some(dir)) => relative_to(p, dir),
            _ => p.to_path_buf(),
        });
        let disk = shown.filter(|_| on_disk).map(Path::to_path_buf);
        let file = src.file(rel, disk, text);
        if file.is_none() {
            // Too long to record: no source is kept for this model.
            self.src = None;
        }
        let root_kind = if main { RecordKind::Element } else { RecordKind::FileRoot };
        Some(SrcFile { file: file?, root_kind, stands_for })
    }

    /// The model read with the source recorded, if it was.
    pub(super) fn attach_source(&mut self, model: Model) -> Model {
        match self.src.take() {
            Some(src) => {
                let source = src.finish(model.clone());
                model.with_source(Some(Arc::new(source)))
            }
            None => model,
        }
    }

    /// Whether the document being read is the main one (no include is open).
    pub(super) fn at_main(&self) -> bool {
        self.stack.len() == 1
    }

    /// Enters the file `key` (checked by [`include_source`]).
    pub(super) fn push(&mut self, key: PathBuf) {
        self.seen.insert(key.clone());
        self.stack.push(key);
    }

    pub(super) fn pop(&mut self) {
        self.stack.pop();
    }

    /// The error for including `key` (shown as `shown`) here, if any.
    pub(super) fn refuse(&self, key: &Path, shown: &Path) -> Option<ErrorKind> {
        if self.stack.iter().any(|k| k == key) {
            Some(ErrorKind::IncludeCycle(shown.to_path_buf()))
        } else if self.seen.contains(key) {
            Some(ErrorKind::IncludedTwice(shown.to_path_buf()))
        } else {
            None
        }
    }
}

/// `path` relative to the folder `dir`, lexically (`..` where it leads out of it).
fn relative_to(path: &Path, dir: &Path) -> PathBuf {
    let norm = |p: &Path| PathBuf::from(files::normalize(&p.to_string_lossy()));
    let (path, dir) = (norm(path), norm(dir));
    if dir == Path::new(".") {
        return path;
    }
    let (a, b): (Vec<_>, Vec<_>) = (path.components().collect(), dir.components().collect());
    let common = a.iter().zip(&b).take_while(|(x, y)| x == y).count();
    let mut out = PathBuf::new();
    for _ in common..b.len() {
        out.push("..");
    }
    for c in &a[common..] {
        out.push(c);
    }
    out
}

pub(super) fn canonical(path: &Path) -> PathBuf {
    std::fs::canonicalize(path)
        .unwrap_or_else(|_| PathBuf::from(files::normalize(&path.to_string_lossy())))
}

/// An included file: its bytes, its path (for messages), the file context its own
/// files resolve in, and its key on the include stack (for cycles).
pub(super) type IncludeSource = (Arc<[u8]>, PathBuf, FileContext, PathBuf, bool);

/// The file an `<include>` names.
pub(super) fn include_source(
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
        return Ok((bytes, PathBuf::from(&file), ctx, key, false));
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
    Ok((bytes.into(), full, ctx, key, true))
}

/// A root-level `<include>`: the file read as a model of its own, merged later.
pub(super) fn read_include(
    r: &mut Reader<'_>,
    tag: &BytesStart<'_>,
    offset: usize,
    max_depth: usize,
    tree: &mut Includes,
) -> Result<Model, ReadError> {
    let (bytes, file, ctx, key, on_disk) = include_source(r, tag, offset, tree)?;
    let text = utf8(&bytes, Some(&file))?;
    let src = tree.record_file(Some(&file), on_disk, text, false, None);
    tree.push(key);
    let res = read_document(text, Some(file.clone()), ctx, max_depth, tree, r.model_files, src);
    tree.pop();
    res
}

/// An `<include>` inside an element (at `parent` in the arena): the included file's
/// root's children are read as `parent`'s children in its place, as MuJoCo pastes
/// the file's content there.
pub(super) fn inline_include(
    r: &mut Reader<'_>,
    tag: &BytesStart<'_>,
    offset: usize,
    parent: usize,
    max_depth: usize,
    tree: &mut Includes,
) -> Result<(), ReadError> {
    let (bytes, file, ctx, key, on_disk) = include_source(r, tag, offset, tree)?;
    let text = utf8(&bytes, Some(&file))?;
    let src = tree.record_file(Some(&file), on_disk, text, false, Some(r.arena[parent].id));
    let mut sub = Reader {
        text,
        file: Some(file),
        ctx,
        model_files: r.model_files,
        arena: Vec::new(),
        basepaths: r.basepaths.clone(),
        settings_set_at: HashMap::new(),
        scratch: Vec::new(),
        src,
        hoisted: None,
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

/// A global setting that both the file and an `<include>` at `offset` set is taken
/// as MuJoCo reads includes (their text in place of the tag): from the one later in
/// the document. Returns the model and the include with the losing values dropped,
/// so that merging them finds no conflict.
pub(super) fn settings_in_document_order(
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
