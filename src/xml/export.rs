//! A model's files ([`Model::assets`]) and export to a folder ([`Model::export`]), as
//! dm_control's `get_assets` and `export_with_assets`.
//!
// Implementation notes:
// - File attributes sit only on repeated elements (`mesh`, `texture`, `hfield`, `skin`,
//   `flexcomp`), which the writer always writes, and never in the global settings
//   sections it merges; so every file attribute of every model of the composition is
//   written, and a scan of each distinct model value's own tree finds exactly the
//   files the XML names.
// - Attached model values are told apart by their root node (`Model::ptr_eq`), found
//   by the root's id first: a value attached many times is scanned once.

use std::collections::{BTreeMap, BTreeSet, HashMap};
use std::io;
use std::path::{Component, Path, PathBuf};

use crate::error::{ExportError, WriteError};
use crate::files::write::{self, Fault};
use crate::id::ElementId;
use crate::model::Model;
use crate::value::{FileAsset, Value};

use super::WriteOptions;
use super::rules;

impl Model {
    /// Every file the MJCF written with `options` names (this model's own, and those
    /// of included and attached models, at any depth), each once, under the name the
    /// writer gives it (the writer's rule "file names": [`FileAsset::vfs_name`] with
    /// `options.filename_with_hash`).
    ///
    /// This is the asset map MuJoCo takes beside the XML
    /// (`MjModel.from_xml_string(xml, assets)`; dm_control's `get_assets()`): name →
    /// file. The [`FileAsset`]s are shared with the model (their bytes are never
    /// copied). Not to be confused with [`Model::asset`], the `<asset>` section.
    ///
    /// Time: O(n + f log f) for the n elements of the distinct model values of the
    /// composition (this model and each distinct attached value once, however often
    /// it is attached) and f file attributes; no file contents are read or hashed.
    ///
    /// # Errors
    /// [`WriteError::FileNameClash`] when two files with different contents would be
    /// written under one name: with `filename_with_hash: false`, two files named
    /// `cube.stl` in different folders or models. (The same file used twice is one
    /// entry.)
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, ReadOptions, WriteOptions};
    /// let robot = ReadOptions::new()
    ///     .asset("cube.stl", b"solid cube".to_vec())
    ///     .read_str(r#"<mujoco model="robot"><asset><mesh file="cube.stl"/></asset></mujoco>"#)?;
    /// let mut arena = Model::new("arena");
    /// arena.attach_mut(&arena.worldbody(), &robot)?;
    /// arena.attach_mut(&arena.worldbody(), &robot)?; // the same file, named once
    ///
    /// let plain = WriteOptions { filename_with_hash: false, ..WriteOptions::default() };
    /// let assets = arena.assets(&plain)?;
    /// assert_eq!(assets.keys().collect::<Vec<_>>(), ["cube.stl"]);
    /// assert_eq!(assets["cube.stl"].contents(), b"solid cube");
    /// assert!(arena.to_xml_string_with(&plain)?.contains(r#"file="cube.stl""#));
    ///
    /// let hashed = arena.assets(&WriteOptions::default())?;
    /// assert!(hashed.keys().all(|name| name.starts_with("cube-") && name.ends_with(".stl")));
    /// # Ok::<(), mjcf::Error>(())
    /// ```
    pub fn assets(
        &self,
        options: &WriteOptions,
    ) -> Result<BTreeMap<String, FileAsset>, WriteError> {
        let mut out: BTreeMap<String, FileAsset> = BTreeMap::new();
        // Attached values met so far, by their root's id (versions of one model share
        // it), then told apart by `ptr_eq`.
        let mut seen: HashMap<ElementId, Vec<&Model>> = HashMap::new();
        let mut todo: Vec<&Model> = vec![self];
        while let Some(model) = todo.pop() {
            for node in model.root.descendants() {
                if let Some(a) = node.attached() {
                    let same_root = seen.entry(a.model.root.id()).or_default();
                    if !same_root.iter().any(|m| m.ptr_eq(&a.model)) {
                        same_root.push(&a.model);
                        todo.push(&a.model);
                    }
                }
                for (_, value) in node.attrs() {
                    if let Value::File(file) = value {
                        add_file(&mut out, rules::file_name(file, options), file)?;
                        // A model file's own files, at their paths relative to it.
                        for (path, companion) in file.companions() {
                            add_file(&mut out, path.to_string(), companion)?;
                        }
                    }
                }
            }
        }
        Ok(out)
    }

    /// Writes the model's MJCF as `dir/xml_file_name` and every file it names
    /// ([`Model::assets`]) into `dir`, each once, so that MuJoCo loads it from there
    /// (`MjModel.from_xml_path`); dm_control's `export_with_assets`. `dir` is created
    /// if missing; files already there under the same names are replaced, except that
    /// a regular file already holding exactly the bytes of a file the model names is
    /// left as it is (its name carries a hash of its contents, so variants exported
    /// into one folder share their meshes, written once). Returns the path of the MJCF
    /// file.
    ///
    /// Every name is checked before anything is written: the MJCF file's name must be
    /// one plain file name, a file's name a file name or a relative path inside `dir`
    /// (a model file's own files keep their folders: `parts/arm.stl`), none holding
    /// NUL or a component over 255 bytes (the limit of common file systems), none
    /// both a file and a folder. Export writes only inside `dir`: the folders of a
    /// path inside it are real folders, found or created (never through a symlink,
    /// which could lead out of `dir`), and a file is written under a fresh temporary
    /// name (never opening an existing file or link) and then renamed into place (a
    /// symlink under the final name is replaced, not followed). `dir` itself is the
    /// caller's to choose: it may be, or pass through, a symlink. (These checks see
    /// the folder as it is; another process changing it during the export is not
    /// guarded against.)
    ///
    /// The MJCF file comes last: an export that fails leaves no MJCF file under
    /// `xml_file_name` (a file there before stays as it was), and no partly written
    /// file under any name the MJCF uses. Exports of several models into one folder
    /// may run concurrently.
    ///
    /// Time: O(n + f log f) as [`Model::assets`], plus writing the MJCF text and the
    /// bytes of every distinct file, plus O(p) file-system checks for the p folder
    /// components of the files' paths.
    ///
    /// # Errors
    /// Before anything is written (the folder not even created):
    /// [`ExportError::Write`] when the model cannot be written
    /// ([`Model::to_xml_string_with`]) or two files would get one name
    /// ([`Model::assets`]; also a file named `xml_file_name`);
    /// [`ExportError::Io`] of kind `InvalidInput` for a name that is not a plain file
    /// name (`xml_file_name`) or a relative path inside `dir` (`..`, an absolute path,
    /// NUL, a component over 255 bytes, a file that is also another file's folder);
    /// [`ExportError::SymlinkedFolder`] when a folder of a file's path inside `dir` is
    /// a symlink; [`ExportError::Io`] of kind `NotADirectory` when it is a file, and
    /// of kind `IsADirectory` when a folder is there under a file's name.
    /// While writing: [`ExportError::Io`], naming the folder or file and the
    /// operating system's reason, when `dir` or a folder in it cannot be created or a
    /// file cannot be written there.
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, ReadOptions, WriteOptions};
    /// let robot = ReadOptions::new()
    ///     .asset("cube.stl", b"solid cube".to_vec())
    ///     .read_str(r#"<mujoco model="robot"><asset><mesh file="cube.stl"/></asset></mujoco>"#)?;
    /// let dir = std::env::temp_dir().join(format!("mjcf-export-doc-{}", std::process::id()));
    /// let plain = WriteOptions { filename_with_hash: false, ..WriteOptions::default() };
    /// let xml = robot.export(&dir, "robot.xml", &plain)?;
    /// assert_eq!(xml, dir.join("robot.xml"));
    /// assert_eq!(std::fs::read(dir.join("cube.stl")).unwrap(), b"solid cube");
    /// let back = Model::from_path(&xml)?; // reads back, and writes the same MJCF
    /// assert_eq!(back.to_xml_string_with(&plain)?, robot.to_xml_string_with(&plain)?);
    /// # std::fs::remove_dir_all(&dir).unwrap();
    /// # Ok::<(), mjcf::Error>(())
    /// ```
    pub fn export(
        &self,
        dir: impl AsRef<Path>,
        xml_file_name: &str,
        options: &WriteOptions,
    ) -> Result<PathBuf, ExportError> {
        let dir = dir.as_ref();
        let xml_path = checked_name(dir, xml_file_name, false)?;
        let xml = self.to_xml_string_with(options)?;
        let assets = self.assets(options)?;
        if assets.contains_key(xml_file_name) {
            return Err(WriteError::FileNameClash { name: xml_file_name.to_string() }.into());
        }
        let files = assets
            .iter()
            .map(|(name, file)| {
                Ok((name.as_str(), checked_name(dir, name, true)?, file.contents()))
            })
            .collect::<Result<Vec<_>, ExportError>>()?;
        // The folders the files need, each once, outer ones first (`a` before `a/b`).
        let mut folders: BTreeSet<&str> = BTreeSet::new();
        for (name, _, _) in &files {
            folders.extend(name.match_indices('/').map(|(i, _)| &name[..i]));
        }
        if let Some(both) = std::iter::once(xml_file_name)
            .chain(files.iter().map(|(name, _, _)| *name))
            .find(|name| folders.contains(name))
        {
            return Err(invalid(dir.join(both), "both a file and a folder of another file"));
        }
        // Those already there must be real folders (checked again when created), and
        // no file may have a folder under its name.
        for folder in &folders {
            write::real_folder(&dir.join(folder), false).map_err(fault)?;
        }
        for path in files.iter().map(|(_, path, _)| path).chain([&xml_path]) {
            if write::is_folder(path) {
                return Err(ExportError::Io {
                    path: path.clone(),
                    kind: io::ErrorKind::IsADirectory,
                    reason: "a folder has this name".to_string(),
                });
            }
        }
        write::make_folder(dir).map_err(fault)?;
        for folder in &folders {
            write::real_folder(&dir.join(folder), true).map_err(fault)?;
        }
        for (_, path, contents) in files {
            if !write::holds(&path, contents) {
                write::write_by_rename(&path, contents).map_err(fault)?;
            }
        }
        write::write_by_rename(&xml_path, xml.as_bytes()).map_err(fault)?;
        Ok(xml_path)
    }
}

/// Adds `file` under its written name; the same contents under one name are one file.
fn add_file(
    out: &mut BTreeMap<String, FileAsset>,
    name: String,
    file: &FileAsset,
) -> Result<(), WriteError> {
    use std::collections::btree_map::Entry;
    match out.entry(name) {
        Entry::Vacant(e) => {
            e.insert(file.clone());
        }
        Entry::Occupied(e) => {
            let other = e.get();
            let same = other.sha1_hex() == file.sha1_hex()
                && other.contents().len() == file.contents().len();
            if !same {
                return Err(WriteError::FileNameClash { name: e.key().clone() });
            }
        }
    }
    Ok(())
}

/// The longest name of one file or folder (`NAME_MAX` of common file systems), in bytes.
const MAX_NAME_BYTES: usize = 255;

/// The longest path given to the operating system, in bytes (Linux's `PATH_MAX`, with
/// the terminating NUL).
const MAX_PATH_BYTES: usize = 4095;

/// `dir/name` for a name checked to be one plain file name, or (`nested`) a relative
/// path inside `dir` (components separated by `/`, none empty, `.` or `..`); no NUL,
/// no component over [`MAX_NAME_BYTES`], and the whole path within [`MAX_PATH_BYTES`].
fn checked_name(dir: &Path, name: &str, nested: bool) -> Result<PathBuf, ExportError> {
    let path = dir.join(name);
    let reason = if name.contains('\0') {
        Some("a name cannot hold NUL")
    } else if !nested && name.contains('/') {
        Some("not a plain file name")
    } else if name.split('/').any(|c| c.is_empty() || c == "." || c == "..") {
        Some(if nested {
            "not a file name or a path inside the folder"
        } else {
            "not a plain file name"
        })
    } else if name.split('/').any(|c| c.len() > MAX_NAME_BYTES) {
        Some("a file name longer than 255 bytes")
    } else if path.as_os_str().len() > MAX_PATH_BYTES {
        Some("a path longer than 4095 bytes")
    } else {
        // A name that is a path on its own (`/x` on Unix, `C:x` on Windows).
        let plain = Path::new(name).components().all(|c| matches!(c, Component::Normal(_)));
        (!plain).then_some("not a file name or a path inside the folder")
    };
    match reason {
        Some(reason) => Err(invalid(path, reason)),
        None => Ok(path),
    }
}

fn invalid(path: PathBuf, reason: &str) -> ExportError {
    ExportError::Io { path, kind: io::ErrorKind::InvalidInput, reason: reason.to_string() }
}

/// The error for a write of the file layer that failed.
fn fault(f: Fault) -> ExportError {
    match f {
        Fault::SymlinkedFolder(path) => ExportError::SymlinkedFolder { path },
        Fault::Io(path, kind, reason) => ExportError::Io { path, kind, reason },
    }
}
