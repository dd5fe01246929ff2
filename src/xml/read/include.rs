//! `<include>`: the include tree's rules (cycles, files included twice, depth), the
//! file an include names, and reading it as MuJoCo does: its root's content in place
//! of the tag, into the including file's elements (at the root, a singleton section
//! given again merges into the one read before, later values winning).

use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use quick_xml::events::BytesStart;

use super::{
    FileRead, MAX_INCLUDE_DEPTH, NONE, Pending, Place, Reader, Spot, SrcFile, Text, children_of,
    parse, utf8,
};
use crate::error::{ErrorKind, ReadError};
use crate::files::write::Fingerprint;
use crate::files::{self, FileContext};
use crate::model::Model;
use crate::model::tree::ElementId;
use crate::schema::Multiplicity;
use crate::xml::source::{RecordKind, SourceBuilder};

/// The files of one model's include tree, for the rules on them: a file includes
/// neither itself (a cycle) nor a file the tree already includes (MuJoCo includes
/// each file once per model), and includes nest at most [`MAX_INCLUDE_DEPTH`] deep.
/// Files are told apart by their canonical path (symlinks followed), in-memory files
/// by their path as written, normalised.
pub(crate) struct Includes {
    /// The main file and the includes above the one being read.
    stack: Vec<PathBuf>,
    /// Every file of the tree so far, the main file too.
    seen: HashSet<PathBuf>,
    /// The files' text and tags, when the source is kept.
    pub(crate) src: Option<SourceBuilder>,
    /// The model's folder, which recorded files' paths are relative to.
    main_dir: Option<PathBuf>,
}

impl Includes {
    /// The tree of the main file `main` (its key), in the folder `main_dir`; the
    /// source is recorded if `keep_source`.
    pub(crate) fn new(main: PathBuf, main_dir: Option<PathBuf>, keep_source: bool) -> Includes {
        Includes {
            seen: HashSet::from([main.clone()]),
            stack: vec![main],
            src: keep_source.then(SourceBuilder::default),
            main_dir,
        }
    }

    /// Records a file read (`shown`: its path as read, on disk or, for an in-memory
    /// file, as written; `on_disk`: for a file read from disk, what it held) whose
    /// root stands for `stands_for` (the main file's: `None` and `main`). `None` when
    /// the source is not kept.
    pub(crate) fn record_file(
        &mut self,
        shown: Option<&Path>,
        on_disk: Option<Fingerprint>,
        text: &str,
        main: bool,
        stands_for: Option<ElementId>,
    ) -> Option<SrcFile> {
        let src = self.src.as_mut()?;
        let rel = shown.map(|p| match (on_disk, &self.main_dir) {
            (Some(_), Some(dir)) => relative_to(p, dir),
            _ => p.to_path_buf(),
        });
        let disk = shown.filter(|_| on_disk.is_some()).map(Path::to_path_buf);
        let file = src.file(rel, disk, on_disk, text);
        if file.is_none() {
            // Too long to record: no source is kept for this model.
            self.src = None;
        }
        let root_kind = if main { RecordKind::Element } else { RecordKind::FileRoot };
        Some(SrcFile { file: file?, root_kind, stands_for })
    }

    /// The model read with the source recorded, if it was.
    pub(crate) fn attach_source(&mut self, model: Model) -> Model {
        match self.src.take() {
            Some(src) => {
                let source = src.finish(model.clone());
                model.with_source(Some(Arc::new(source)))
            }
            None => model,
        }
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
    let key = files::canonical(&full);
    if let Some(refused) = tree.refuse(&key, &full) {
        return Err(r.err(refused, offset));
    }
    let bytes = r.ctx.read_disk(&path).map_err(|k| r.err(k, offset))?;
    let ctx = r.ctx.for_included(&full);
    Ok((bytes.into(), full, ctx, key, true))
}

/// An `<include>` (its tag at `offset`) in the element at `spot`: the included file's
/// root's content is read as that element's children in the include's place, into
/// the same arena (one id space, one name index, one resolution of references), with
/// the file's own path in errors and its own folder for the files it names. Its
/// elements nest at the include's depth, and a singleton it gives that the element
/// was given already is given twice in one tag. The compiler's folder settings carry
/// in and out, as they are global in MuJoCo.
pub(super) fn splice_include(
    r: &mut Reader<'_>,
    tag: &BytesStart<'_>,
    offset: usize,
    spot: Spot,
    max_depth: usize,
    tree: &mut Includes,
) -> Result<(), ReadError> {
    let (bytes, file, ctx, key, on_disk) = include_source(r, tag, offset, tree)?;
    let text = utf8(&bytes, Some(&file))?;
    let entry = spot.entry;
    let read = on_disk.then(|| Fingerprint::of(&bytes));
    let src = tree.record_file(Some(&file), read, text, false, Some(r.arena[entry].id));
    // Each file is included once: more than 2^32 of them do not fit in memory.
    let too_many = || r.err(ErrorKind::TooManyFiles(u32::MAX as usize), offset);
    let at = u32::try_from(r.files.len()).map_err(|_| too_many())?;
    // At the root, the file's elements are ordered as its own group (see
    // `order_as_reference`); inside an element, in place, as its includer's.
    let group = if entry == 0 { at } else { r.files[r.at as usize].group };
    let text = Text::Included(Arc::from(text));
    r.files.push(FileRead { text, path: Some(file), group });
    let outer = (std::mem::replace(&mut r.at, at), std::mem::replace(&mut r.ctx, ctx));
    let outer_src = std::mem::replace(&mut r.src, src);
    tree.push(key);
    let res = parse(r, Place::Entry(spot), max_depth, tree);
    tree.pop();
    (r.at, r.ctx) = outer;
    r.src = outer_src;
    res.map(|_| ())
}

/// Orders the content of root-level includes as the reference (dm_control) does, which
/// reads each such file as a model of its own and `include_copy`s it after the
/// including file's content: in every element merged across files (the root and its
/// singletons, at any depth), the repeated children are ordered by the group of the
/// file their tag is in (stably, document order within a group). Groups are the
/// files' indices, met in document order, so a file's own content comes before that
/// of the files it includes at its root, and those in the order of their includes.
/// Content included inside an element stays in place (the reference reads no such
/// include; MuJoCo pastes it there). Settings are not moved: a singleton given again
/// merges where it is read, the later value winning, as MuJoCo reads includes.
///
/// Time: O(m · log m) for the `m` children of the merged elements, when there is a
/// root-level include; O(files read) otherwise.
pub(super) fn order_as_reference(arena: &mut [Pending], files: &[FileRead<'_>]) {
    if files.iter().all(|f| f.group == 0) || arena.is_empty() {
        return;
    }
    let group = |arena: &[Pending], c: usize| files[arena[c].file as usize].group;
    let mut merged = vec![0];
    while let Some(e) = merged.pop() {
        let mut kids: Vec<usize> = children_of(arena, e).collect();
        merged.extend(
            kids.iter().filter(|&&c| arena[c].kind.multiplicity() != Multiplicity::Repeated),
        );
        if kids.is_sorted_by_key(|&c| group(arena, c)) {
            continue;
        }
        kids.sort_by_key(|&c| group(arena, c));
        arena[e].first_child = kids[0];
        for w in kids.windows(2) {
            arena[w[0]].next_sibling = w[1];
        }
        let last = kids[kids.len() - 1];
        arena[last].next_sibling = NONE;
        arena[e].last_child = last;
    }
}
