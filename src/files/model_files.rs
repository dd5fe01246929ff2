//! The asset model files (`<model file>`, and the model files and includes they name
//! in turn) that one read or one edit reads, each once.

use std::cell::RefCell;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

use smol_str::SmolStr;

use super::{FileContext, Located};
use crate::error::ErrorKind;
use crate::schema::ElementKind;
use crate::value::FileAsset;

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
    pub(crate) fn read(
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
                FileKey::Disk(super::canonical(&path.open), super::canonical(folder))
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
