//! Opening MJCF: the document read as its text spells it (`xml::read`), then, as a
//! step after reading, the `<attach>`es that have a saved scene's shape reopened as
//! attachments (`xml::scene::reopen`): reopening names the asset model files it
//! needs, which are opened here as documents in turn (each with its own source kept,
//! so that it saves losslessly), and builds the composed model from them. The reader
//! knows nothing of scenes, and scenes never call the reader.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

#[cfg(doc)]
use crate::error::ErrorKind;
use crate::error::ReadError;
use crate::files::write::Fingerprint;
use crate::files::{self, FileContext};
use crate::model::{Model, ModelFiles};
use crate::xml::read::{Includes, ReadOptions, SrcFile, read_literal, utf8};
use crate::xml::scene::reopen;

impl ReadOptions {
    /// Reads a model from MJCF text.
    ///
    /// Time: O(L + n · log n) for `L` bytes of text holding `n` elements, plus reading
    /// and hashing the files it names (each asset model file, and the files it names
    /// in turn, read once however often it is named; each include file at most once,
    /// as one model includes a file once), plus O(in-memory files) to copy their table
    /// for the model. An `<include>`d file's text counts in `L` and its elements in
    /// `n`, plus O(its length) to keep a copy of its text while reading; with a file
    /// included at the root, O(m · log m) more to order the `m` elements of the
    /// sections files share.
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
    ///   (also across includes: reported at the later one, in its file);
    /// - [`ErrorKind::FileNotFound`], [`ErrorKind::FileOutsideRoot`]: a file or
    ///   include that cannot be read, or (confined) lies outside the model's folder;
    /// - [`ErrorKind::InvalidUtf8`]: an included file that is not UTF-8;
    /// - [`ErrorKind::IncludeCycle`]: an include that includes itself;
    /// - [`ErrorKind::IncludedTwice`]: an include of a file the model's include tree
    ///   already includes (anywhere in it, by its canonical path; in-memory files by
    ///   their path as written, normalised), as MuJoCo refuses it;
    /// - [`ErrorKind::TooManyFiles`]: an asset `<model>` file that brings more than
    ///   100,000 files (counting the model files it names, each path once);
    /// - [`ErrorKind::TextDataTwice`], [`ErrorKind::TextCdataTwice`]: a `<text>` of
    ///   `<custom>` whose data is given both as `data` and as CDATA, or as two CDATA
    ///   sections, as MuJoCo refuses them;
    /// - [`ErrorKind::TooDeep`]: elements nested deeper than
    ///   [`max_depth`](ReadOptions::max_depth), includes more than 100 deep, or asset
    ///   model files naming model files more than 16 deep (an included file's
    ///   elements count at the depth of the `<include>`, as if pasted there).
    pub fn read_str(&self, text: &str) -> Result<Model, ReadError> {
        let ctx = self.context(self.base_dir.clone());
        // The main text takes the first place in the include tree, as a file does.
        let dir = self.base_dir.clone();
        let mut tree = Includes::new(PathBuf::from("<main text>"), dir, self.keep_source);
        let model_files = ModelFiles::default();
        let src = tree.record_file(None, None, text, true, None);
        let m = read_document(text, None, ctx, self.max_depth, &mut tree, &model_files, src)?;
        Ok(tree.attach_source(m))
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
        let ctx = self.context(Some(dir.clone()));
        let mut tree = Includes::new(files::canonical(path), Some(dir), self.keep_source);
        let model_files = ModelFiles::default();
        let file = Some(path.to_path_buf());
        let read = Some(Fingerprint::of(&bytes));
        let src = tree.record_file(Some(path), read, text, true, None);
        let m = read_document(text, file, ctx, self.max_depth, &mut tree, &model_files, src)?;
        Ok(tree.attach_source(m))
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
    /// (files, includes) resolve against its folder. A scene saved by
    /// [`Model::save_scene`] (or [`Model::save`]) reopens with its attachments as
    /// attachments, as the [scene rules](crate::guide#scenes) say.
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

/// Reads the main document (includes are spliced into it as it is read), then
/// reopens the `<attach>`es that have a saved scene's shape as attachments
/// (`xml::scene::reopen`, a step after reading: it names the asset model files it
/// needs, read here as documents in turn, each with its own source kept so that it
/// saves losslessly), and keeps the model as the text spells it in the source beside
/// the reopened one.
fn read_document(
    text: &str,
    file: Option<PathBuf>,
    ctx: FileContext,
    max_depth: usize,
    tree: &mut Includes,
    model_files: &ModelFiles,
    src: Option<SrcFile>,
) -> Result<Model, ReadError> {
    let keep_source = tree.src.is_some();
    let model = read_literal(text, file, ctx, max_depth, tree, model_files, src)?;
    let wanted = reopen::parts_to_read(&model, text);
    if wanted.is_empty() {
        return Ok(model);
    }
    let depth = PARTS.with(|p| p.borrow().depth);
    if depth >= MAX_SCENE_NESTING {
        return Ok(model);
    }
    PARTS.with(|p| p.borrow_mut().depth = depth + 1);
    let mut parts = HashMap::new();
    for part in wanted {
        let read = PARTS.with(|p| p.borrow().read.get(&part.key).cloned()).or_else(|| {
            let m = read_part(&part, max_depth, keep_source, model_files).ok()?;
            PARTS.with(|p| p.borrow_mut().read.insert(part.key.clone(), m.clone()));
            Some(m)
        });
        if let Some(m) = read {
            parts.insert(part.asset, m);
        }
    }
    PARTS.with(|p| {
        let mut p = p.borrow_mut();
        p.depth = depth;
        if depth == 0 {
            p.read.clear();
        }
    });
    let reopened = reopen::reopen(model.clone(), parts);
    // The text spells the model before reopening: the lossless writer writes the
    // scene's own file against it (`xml::save`).
    if let Some(src) = tree.src.as_mut().filter(|_| !reopened.ptr_eq(&model)) {
        src.literal = Some(model);
    }
    Ok(reopened)
}

/// How deep reopened scenes may nest (as asset model files may: `model::build`).
const MAX_SCENE_NESTING: usize = 16;

/// The scene parts being read on this thread: how deep, and those read so far by the
/// outermost document (a part that several parts attach is read once and shared, as
/// it was before saving; forgotten when the outermost document is read).
#[derive(Default)]
struct PartsRead {
    depth: usize,
    read: HashMap<(PathBuf, String), Model>,
}

thread_local! {
    static PARTS: std::cell::RefCell<PartsRead> = std::cell::RefCell::new(PartsRead::default());
}

/// Reads a scene part's file as a document of its own (its own include tree and
/// source), reopened in turn.
fn read_part(
    part: &reopen::PartFile,
    max_depth: usize,
    keep_source: bool,
    model_files: &ModelFiles,
) -> Result<Model, ReadError> {
    let path = &part.path;
    let dir = path.parent().map(Path::to_path_buf).unwrap_or_default();
    let mut tree = Includes::new(files::canonical(path), Some(dir), keep_source);
    // A part's text is its file's bytes (read as UTF-8 as they are).
    let read = Some(Fingerprint::of(part.text.as_bytes()));
    let src = tree.record_file(Some(path), read, &part.text, true, None);
    let file = Some(path.to_path_buf());
    let m =
        read_document(&part.text, file, part.ctx.clone(), max_depth, &mut tree, model_files, src)?;
    Ok(tree.attach_source(m))
}
