//! Writing a save to disk: [`Model::save`], [`Model::save_with`] and
//! [`Model::save_as`], through the file layer's one writer (`files::write`): every
//! check made before the first file is written, a file changed on disk since the
//! read never overwritten unless asked, folders real (never symlinks).

use std::path::{Path, PathBuf};

use super::{SaveError, outputs};
use crate::files::write::{self, Fault, OnDisk};
use crate::model::Model;

/// How [`Model::save_with`] saves.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
#[non_exhaustive]
pub struct SaveOptions {
    overwrite_changed: bool,
}

impl SaveOptions {
    /// The default options: a file changed on disk since the read is not overwritten.
    pub fn new() -> SaveOptions {
        SaveOptions::default()
    }

    /// Overwrite a file that changed on disk since it was read, instead of refusing
    /// the save with [`SaveError::ChangedOnDisk`]. Default: off.
    #[must_use]
    pub fn overwrite_changed(mut self, yes: bool) -> SaveOptions {
        self.overwrite_changed = yes;
        self
    }
}

impl Model {
    /// Saves the model into the files it was read from, losslessly, with default
    /// [`SaveOptions`]: each file whose text changes is written in place (atomically:
    /// a temporary file created new beside it, then renamed over it), the others are
    /// never written (same bytes, same modification time), even when their file on
    /// disk differs from the text read (another program's edit is kept; a save of an
    /// earlier version undoes what a save of this process wrote there). What is
    /// kept:
    /// - an element no edit touched (nor renamed or removed anything it names) is
    ///   written byte for byte, its content and all;
    /// - an edited element keeps its untouched attributes' text, quoting and order; a
    ///   changed value is replaced in place (formatted as [`Model::to_xml_string`]
    ///   formats values; a value given twice, in a singleton given twice, is changed
    ///   where it wins: its last mention), a new attribute is appended, a removed one
    ///   goes with its spacing;
    /// - children read keep their text and the whitespace and comments before them; a
    ///   removed element goes with the comments directly before it; a child moved from
    ///   elsewhere keeps its text; a new element is indented like its siblings, on
    ///   lines ending as the file's do (its first line break: `\n`, `\r\n` or `\r`),
    ///   with no class or automatic name added and files named `stem.ext`; an empty
    ///   singleton is not written;
    /// - nothing is renamed, file attributes and compiler folders stay as written
    ///   (meshes keep their paths, `meshdir` stays); a byte-order mark, an XML
    ///   declaration, a DOCTYPE and whatever else precedes the root stay as they are.
    ///
    /// An edit inside an included file is saved into that file. A confined model
    /// ([`ReadOptions::confine_to_base_dir`](crate::ReadOptions::confine_to_base_dir))
    /// writes no file outside its folder. Returns the files written.
    ///
    /// **A file changed on disk since it was read is not overwritten**: when a file
    /// the save must write no longer holds what was read from it (another program
    /// edited it, by its content), nothing at all is written and the save returns
    /// [`SaveError::ChangedOnDisk`] naming it; [`SaveOptions::overwrite_changed`]
    /// overwrites such files on purpose ([`Model::save_with`]).
    ///
    /// The model keeps the source it was read from: saving a later version writes
    /// what changed since the read (so saving twice writes once).
    ///
    /// A model with attachments saves as a scene (MuJoCo's `<attach>` of an asset
    /// `<model>`, as [`Model::save_scene`] writes one): its own files as above, an
    /// attachment the reader reopened and no edit touched as it was read (its asset
    /// `<model file=...>` as written, wherever its file lies, and nothing written for
    /// it), one added in code as a new `<body name="s/">` holding an `<attach>`, with
    /// a new asset `<model>`; a detached one goes with its asset `<model>` when nothing
    /// else uses it; a renamed scope or a moved frame changes its name, prefix and pose
    /// in place. Each attached model read from a file in the model's folder (or
    /// below it) is saved losslessly into its own files (an edit through
    /// [`Model::edit_attached`] goes there); one built in code, an edited one read from
    /// outside the model's folder (its file there is never changed), or a second
    /// version of a file another attachment uses is written with the plain writer as
    /// [`Model::save_scene`] writes a part, into a new file beside the model's (named
    /// after the model; a file already there with other bytes is never replaced), and
    /// its `<model file=...>` names that file. How a scene is written and reopened:
    /// [Scenes](crate::guide#scenes).
    ///
    /// Time: as [`Model::to_source_files`], plus reading each file to write on disk
    /// (to compare) and writing the changed ones.
    ///
    /// # Errors
    /// As [`Model::to_source_files`], and [`SaveError::NoPath`] when a file to write
    /// was not read from disk (or, for a part written anew, when the model's was not),
    /// [`SaveError::OutsideRoot`] when (confined) it leads out of the model's folder,
    /// [`SaveError::ChangedOnDisk`] when a file to write changed on disk since it was
    /// read, [`SaveError::SymlinkedFolder`] when a folder a new file of the scene goes
    /// in is a symlink, [`SaveError::Io`] when a file cannot be written. Every check
    /// is made before the first file is written; a failure of the system while
    /// writing leaves the files written before it written.
    pub fn save(&self) -> Result<Vec<PathBuf>, SaveError> {
        self.save_with(&SaveOptions::default())
    }

    /// [`Model::save`] with `options`.
    ///
    /// Time: as [`Model::save`].
    ///
    /// # Errors
    /// As [`Model::save`]; with [`SaveOptions::overwrite_changed`], never
    /// [`SaveError::ChangedOnDisk`].
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, SaveError, SaveOptions};
    /// let dir = std::env::temp_dir().join(format!("mjcf-doc-save-with-{}", std::process::id()));
    /// std::fs::create_dir_all(&dir)?;
    /// let path = dir.join("a.xml");
    /// std::fs::write(&path, "<mujoco>\n  <option timestep=\"0.01\"/>\n</mujoco>\n")?;
    /// let m = Model::from_path(&path)?;
    /// // Another program edits the file after the read.
    /// std::fs::write(&path, "<mujoco>\n  <option timestep=\"0.02\"/>\n</mujoco>\n")?;
    /// let option = m.section("option").unwrap();
    /// let edited = m.set(&option, mjcf::Attrs::new().set("timestep", 0.005))?;
    /// assert!(matches!(edited.save(), Err(SaveError::ChangedOnDisk(p)) if p == path));
    /// // Overwriting on purpose.
    /// edited.save_with(&SaveOptions::new().overwrite_changed(true))?;
    /// assert!(std::fs::read_to_string(&path)?.contains("0.005"));
    /// # std::fs::remove_dir_all(&dir)?;
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn save_with(&self, options: &SaveOptions) -> Result<Vec<PathBuf>, SaveError> {
        let src = self.side.source.as_deref().ok_or(SaveError::NoSource)?;
        let out = outputs(self, false)?;
        let folder = src.files.first().and_then(|f| f.disk.as_deref()).and_then(Path::parent);
        // What to write, every check made first: nothing is written if one fails.
        let mut plan: Vec<(PathBuf, Option<PathBuf>, &[u8])> = Vec::new();
        for o in &out.texts {
            let bytes = o.text.text.as_bytes();
            let (path, new) = match (&o.disk, folder, &o.text.path) {
                (Some(disk), _, _) => (disk.clone(), None),
                (None, Some(folder), Some(rel)) => (folder.join(rel), Some(rel.clone())),
                _ => return Err(SaveError::NoPath),
            };
            let read = o.read.as_ref();
            match write::on_disk(&path, bytes, read) {
                OnDisk::Same => continue,
                // A file whose text did not change since the read is written only
                // back over what an earlier save of this process put there.
                OnDisk::Ours => {}
                _ if o.disk.is_some() && !o.text.changed => continue,
                OnDisk::Changed | OnDisk::Missing
                    if read.is_some() && !options.overwrite_changed =>
                {
                    return Err(SaveError::ChangedOnDisk(path));
                }
                _ => {}
            }
            self.confined(o.text.path.as_deref(), &path)?;
            plan.push((path, new, bytes));
        }
        for (rel, bytes) in &out.files {
            let Some(path) = folder.map(|f| f.join(rel)) else { return Err(SaveError::NoPath) };
            let planned = plan.iter().any(|(p, _, _)| *p == path);
            if planned || write::on_disk(&path, bytes, None) == OnDisk::Same {
                continue;
            }
            self.confined(Some(rel), &path)?;
            plan.push((path, Some(rel.clone()), bytes));
        }
        let folder = folder.unwrap_or(Path::new(""));
        for (_, new, _) in &plan {
            if let Some(rel) = new {
                let rel = write::inside(rel).ok_or_else(|| SaveError::OutsideRoot(rel.clone()))?;
                write::real_folders(folder, &rel, false).map_err(fault)?;
            }
        }
        let mut written = Vec::with_capacity(plan.len());
        for (path, new, bytes) in plan {
            if let Some(rel) = new.as_deref().and_then(write::inside) {
                write::real_folders(folder, &rel, true).map_err(fault)?;
            }
            write::write_by_rename(&path, bytes).map_err(fault)?;
            written.push(path);
        }
        Ok(written)
    }

    /// For a confined model, refuses a file `rel` (from the model's folder; written at
    /// `path`) that leads out of its folder.
    fn confined(&self, rel: Option<&Path>, path: &Path) -> Result<(), SaveError> {
        if !self.files.confine {
            return Ok(());
        }
        let rel = rel.ok_or(SaveError::NoPath)?.to_string_lossy();
        self.files.disk_path(&rel).map_err(|_| SaveError::OutsideRoot(path.to_path_buf()))?;
        Ok(())
    }

    /// Saves the model's files into the folder `dir`, with the same relative paths
    /// as they had from the model's folder (every file, changed or not), losslessly
    /// as [`Model::save`], with the asset files their elements name (meshes,
    /// textures, ...) at the paths they are named by. `dir` is created if missing;
    /// below it, every folder a file goes in is a real folder (found or created),
    /// never a symlink, and each file is written as [`Model::save`] writes one (a
    /// temporary file created new, renamed over it). Returns the files written.
    ///
    /// Time: as [`Model::to_source_files`], plus writing the files and assets.
    ///
    /// # Errors
    /// As [`Model::to_source_files`]; [`SaveError::NoPath`] for a model read from a
    /// string or with an in-memory include; [`SaveError::OutsideRoot`] for a file
    /// whose relative path leads out of `dir` (an include or asset named through
    /// `..`); [`SaveError::SymlinkedFolder`] when a folder below `dir` that a file goes
    /// in is a symlink (nothing is written then); [`SaveError::Io`] when a file cannot
    /// be written.
    pub fn save_as(&self, dir: impl AsRef<Path>) -> Result<Vec<PathBuf>, SaveError> {
        let dir = dir.as_ref();
        let out = outputs(self, true)?;
        let mut plan: Vec<(PathBuf, &[u8])> = Vec::new();
        let texts = out.texts.iter().map(|o| {
            let rel = o.text.path.as_ref().ok_or(SaveError::NoPath)?;
            Ok((rel, o.text.text.as_bytes()))
        });
        let files = out.files.iter().map(|(rel, bytes)| Ok((rel, &bytes[..])));
        for item in texts.chain(files) {
            let (rel, bytes) = item?;
            let rel = write::inside(rel).ok_or_else(|| SaveError::OutsideRoot(rel.clone()))?;
            if !plan.iter().any(|(p, _)| *p == rel) {
                plan.push((rel, bytes));
            }
        }
        for (rel, _) in &plan {
            write::real_folders(dir, rel, false).map_err(fault)?;
        }
        write::make_folder(dir).map_err(fault)?;
        let mut written = Vec::with_capacity(plan.len());
        for (rel, bytes) in plan {
            write::real_folders(dir, &rel, true).map_err(fault)?;
            let path = dir.join(rel);
            write::write_by_rename(&path, bytes).map_err(fault)?;
            written.push(path);
        }
        Ok(written)
    }
}

/// The error for a write of the file layer that failed.
fn fault(f: Fault) -> SaveError {
    match f {
        Fault::SymlinkedFolder(path) => SaveError::SymlinkedFolder(path),
        Fault::Io(path, _, reason) => SaveError::Io { path, reason },
    }
}
