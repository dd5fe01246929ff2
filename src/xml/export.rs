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

use std::collections::{BTreeMap, HashMap};
use std::io;
use std::path::{Component, Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use crate::error::{ExportError, WriteError};
use crate::id::ElementId;
use crate::model::Model;
use crate::value::{FileAsset, Value};

use super::WriteOptions;

impl Model {
    /// Every file the MJCF written with `options` names (this model's own, and those
    /// of included and attached models, at any depth), each once, under the name the
    /// writer gives it ([`FileAsset::vfs_name`] with `options.filename_with_hash`).
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
                        add_file(&mut out, file.vfs_name(options.filename_with_hash), file)?;
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
    /// Each file is written under a temporary name in `dir` and then renamed, and the
    /// MJCF file comes last: an export that fails leaves no MJCF file under
    /// `xml_file_name` (a file there before stays as it was), and no partly written
    /// file under any name the MJCF uses. Exports of several models into one folder
    /// may run concurrently.
    ///
    /// Time: O(n + f log f) as [`Model::assets`], plus writing the MJCF text and the
    /// bytes of every distinct file.
    ///
    /// # Errors
    /// [`ExportError::Write`] when the model cannot be written
    /// ([`Model::to_xml_string_with`]) or two files would get one name
    /// ([`Model::assets`]; also a file named `xml_file_name`); nothing is written then.
    /// [`ExportError::Io`], naming the folder or file and the operating system's
    /// reason, when `dir` cannot be created or a file cannot be written there;
    /// `xml_file_name` or a file's name that is not a plain file name (a path, `..`)
    /// is refused the same way (kind `InvalidInput`) before anything is written.
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
        let xml_path = plain_file(dir, xml_file_name)?;
        let xml = self.to_xml_string_with(options)?;
        let assets = self.assets(options)?;
        if assets.contains_key(xml_file_name) {
            return Err(WriteError::FileNameClash { name: xml_file_name.to_string() }.into());
        }
        let files = assets
            .iter()
            .map(|(name, file)| Ok((relative_file(dir, name)?, file.contents())))
            .collect::<Result<Vec<_>, ExportError>>()?;
        std::fs::create_dir_all(dir).map_err(|e| io_error(dir, &e))?;
        for (path, contents) in files {
            if let Some(folder) = path.parent().filter(|f| *f != dir) {
                std::fs::create_dir_all(folder).map_err(|e| io_error(folder, &e))?;
            }
            if !holds(&path, contents) {
                write_by_rename(dir, &path, contents)?;
            }
        }
        write_by_rename(dir, &xml_path, xml.as_bytes())?;
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

/// `dir/name`, if `name` is one plain file name (no folder, not `.` or `..`).
fn plain_file(dir: &Path, name: &str) -> Result<PathBuf, ExportError> {
    let mut parts = Path::new(name).components();
    match (parts.next(), parts.next()) {
        (Some(Component::Normal(n)), None) if n == name => Ok(dir.join(name)),
        _ => Err(ExportError::Io {
            path: dir.join(name),
            kind: io::ErrorKind::InvalidInput,
            reason: "not a plain file name".to_string(),
        }),
    }
}

/// `dir/name` for a file name or a relative path inside `dir` (a model file's own
/// files keep their folders: `assets/arm.stl`); no `..`, no absolute path.
fn relative_file(dir: &Path, name: &str) -> Result<PathBuf, ExportError> {
    let inside =
        !name.is_empty() && Path::new(name).components().all(|c| matches!(c, Component::Normal(_)));
    if inside {
        Ok(dir.join(name))
    } else {
        Err(ExportError::Io {
            path: dir.join(name),
            kind: io::ErrorKind::InvalidInput,
            reason: "not a file name or a path inside the folder".to_string(),
        })
    }
}

fn io_error(path: &Path, e: &io::Error) -> ExportError {
    ExportError::Io { path: path.to_path_buf(), kind: e.kind(), reason: e.to_string() }
}

/// Whether `path` is a regular file (not a link) holding exactly `contents`.
fn holds(path: &Path, contents: &[u8]) -> bool {
    std::fs::symlink_metadata(path)
        .is_ok_and(|m| m.file_type().is_file() && m.len() == contents.len() as u64)
        && std::fs::read(path).is_ok_and(|b| b == contents)
}

/// Writes `contents` to a fresh temporary file in `dir`, then renames it to `path`
/// (which is in `dir`); on failure the temporary file is removed and the error names
/// `path`.
fn write_by_rename(dir: &Path, path: &Path, contents: &[u8]) -> Result<(), ExportError> {
    static NEXT: AtomicU64 = AtomicU64::new(0);
    let n = NEXT.fetch_add(1, Ordering::Relaxed);
    // Short, so that it fits wherever the final name fits.
    let tmp = dir.join(format!(".mjcf-export-{}-{n}.tmp", std::process::id()));
    let result = std::fs::write(&tmp, contents).and_then(|()| std::fs::rename(&tmp, path));
    result.map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        io_error(path, &e)
    })
}
