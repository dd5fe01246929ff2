//! Writing files: the one writer of every file the crate writes (export, save,
//! save_as, scenes), and what a write must know of the disk first.
//!
//! A file is written whole or not at all: its bytes go to a temporary file created
//! new beside it (never an existing file or link: a link planted at the temporary
//! name is not followed), which is then renamed over it. Folders a write creates or
//! passes through below the folder it writes in are real folders, never symlinks
//! (a link there would send the file elsewhere).
//!
//! What a file held when it was read is kept as a [`Fingerprint`], so that a save
//! can tell a file another program changed since from one it may overwrite; so is
//! what this process last wrote to each file (a file it wrote itself is not another
//! program's edit: saving, editing on and saving again works).

use std::collections::HashMap;
use std::io::{self, Write as _};
use std::path::{Component, Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicU64, Ordering};

/// Why a file could not be written.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) enum Fault {
    /// A folder on the way is a symlink.
    SymlinkedFolder(PathBuf),
    /// The system refused (or a name is not a file name): the path, the kind, why.
    Io(PathBuf, io::ErrorKind, String),
}

impl Fault {
    fn io(path: &Path, e: &io::Error) -> Fault {
        Fault::Io(path.to_path_buf(), e.kind(), e.to_string())
    }
}

/// What a file on disk held when it was read (or this process wrote it): its length
/// and a 64-bit keyed hash of its bytes (SipHash, as `std`'s maps hash, with one
/// random key per process). Fingerprints are compared within one process only (a
/// model's, the files it wrote), to tell another program's edit of a file from the
/// text read or written: a key the other program cannot know makes a collision out
/// of reach, and the hash runs several times faster than SHA-1 (every file read is
/// fingerprinted, and every file written: an export of 200 variants spent 5% of its
/// time in SHA-1).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct Fingerprint {
    len: u64,
    hash: u64,
}

impl Fingerprint {
    /// The fingerprint of `bytes`.
    ///
    /// Time: O(bytes).
    pub(crate) fn of(bytes: &[u8]) -> Fingerprint {
        use std::hash::{BuildHasher, Hasher};
        static KEY: std::sync::OnceLock<std::hash::RandomState> = std::sync::OnceLock::new();
        let mut h = KEY.get_or_init(std::hash::RandomState::new).build_hasher();
        h.write(bytes);
        Fingerprint { len: bytes.len() as u64, hash: h.finish() }
    }
}

/// What is at a path now, for a write that must not lose another program's work.
#[derive(Debug, PartialEq, Eq)]
pub(crate) enum OnDisk {
    /// No file (nothing to lose).
    Missing,
    /// A file with exactly the bytes to write (nothing to do).
    Same,
    /// A file that still holds what was read from it.
    AsRead,
    /// A file that holds what this process last wrote to it.
    Ours,
    /// A file (or something else) that holds neither: another program's.
    Changed,
}

/// What `path` holds, compared with the `bytes` about to be written there, with
/// `read`, its fingerprint when it was read (`None`: not read from there), and with
/// what this process last wrote there.
///
/// Time: O(size of the file).
pub(crate) fn on_disk(path: &Path, bytes: &[u8], read: Option<&Fingerprint>) -> OnDisk {
    let current = match std::fs::read(path) {
        Err(e) if e.kind() == io::ErrorKind::NotFound => return OnDisk::Missing,
        Err(_) => return OnDisk::Changed,
        Ok(b) => b,
    };
    if current == bytes {
        return OnDisk::Same;
    }
    let now = Fingerprint::of(&current);
    let ours = || {
        let written = WRITTEN.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
        written.as_ref().and_then(|w| w.get(&super::canonical(path))) == Some(&now)
    };
    if read == Some(&now) {
        OnDisk::AsRead
    } else if ours() {
        OnDisk::Ours
    } else {
        OnDisk::Changed
    }
}

/// What this process last wrote to each file, by its canonical path.
static WRITTEN: Mutex<Option<HashMap<PathBuf, Fingerprint>>> = Mutex::new(None);

/// Records that this process wrote `bytes` to `path`.
fn remember(path: &Path, bytes: &[u8]) {
    let mut written = WRITTEN.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    written.get_or_insert_with(HashMap::new).insert(super::canonical(path), Fingerprint::of(bytes));
}

/// Whether `path` is a regular file (not a link) holding exactly `contents`.
///
/// Time: O(size of the file).
pub(crate) fn holds(path: &Path, contents: &[u8]) -> bool {
    std::fs::symlink_metadata(path)
        .is_ok_and(|m| m.file_type().is_file() && m.len() == contents.len() as u64)
        && std::fs::read(path).is_ok_and(|b| b == contents)
}

/// Whether a folder (not a link to one) is at `path`.
pub(crate) fn is_folder(path: &Path) -> bool {
    std::fs::symlink_metadata(path).is_ok_and(|m| m.is_dir())
}

/// Creates the folder `dir` (and its parents) if missing; the folder a caller names
/// is taken as it is, links and all (it is the caller's choice).
pub(crate) fn make_folder(dir: &Path) -> Result<(), Fault> {
    let dir = if dir.as_os_str().is_empty() { Path::new(".") } else { dir };
    std::fs::create_dir_all(dir).map_err(|e| Fault::io(dir, &e))
}

/// Checks that `folder` is a real folder (not a symlink, whatever it points at),
/// creating it if missing and `create`; without `create`, a missing folder is fine.
pub(crate) fn real_folder(folder: &Path, create: bool) -> Result<(), Fault> {
    // Twice at most: a folder another writer creates between the check and ours is
    // checked again.
    for _ in 0..2 {
        match std::fs::symlink_metadata(folder) {
            Ok(m) if m.file_type().is_symlink() => {
                return Err(Fault::SymlinkedFolder(folder.to_path_buf()));
            }
            Ok(m) if m.is_dir() => return Ok(()),
            Ok(_) => {
                return Err(Fault::Io(
                    folder.to_path_buf(),
                    io::ErrorKind::NotADirectory,
                    "not a folder".to_string(),
                ));
            }
            Err(e) if e.kind() == io::ErrorKind::NotFound && !create => return Ok(()),
            Err(e) if e.kind() == io::ErrorKind::NotFound => match std::fs::create_dir(folder) {
                Ok(()) => return Ok(()),
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists => {}
                Err(e) => return Err(Fault::io(folder, &e)),
            },
            Err(e) => return Err(Fault::io(folder, &e)),
        }
    }
    Err(Fault::Io(
        folder.to_path_buf(),
        io::ErrorKind::AlreadyExists,
        "changed while it was created".to_string(),
    ))
}

/// Checks (without `create`) or makes (with it) each folder of the relative path
/// `rel`'s parent below `root`, outer ones first: each must be a real folder.
/// `rel` must lie inside `root` ([`inside`]).
pub(crate) fn real_folders(root: &Path, rel: &Path, create: bool) -> Result<(), Fault> {
    let mut at = root.to_path_buf();
    let Some(parent) = rel.parent() else { return Ok(()) };
    for c in parent.components() {
        at.push(c);
        real_folder(&at, create)?;
    }
    Ok(())
}

/// `rel` normalised, if it stays inside the folder it is relative to (not absolute,
/// no `..` above it); `None` if it leads out.
pub(crate) fn inside(rel: &Path) -> Option<PathBuf> {
    let normal = PathBuf::from(super::normalize(&rel.to_string_lossy()));
    let leaves = normal.is_absolute()
        || normal
            .components()
            .any(|c| matches!(c, Component::ParentDir | Component::Prefix(_) | Component::RootDir));
    (!leaves).then_some(normal)
}

/// The number of the next temporary file of this process.
static NEXT: AtomicU64 = AtomicU64::new(0);

/// The temporary name of the write numbered `n` beside `folder` (short, so that it
/// fits wherever the final name fits).
fn temporary(folder: &Path, n: u64) -> PathBuf {
    folder.join(format!(".mjcf-{}-{n}.tmp", std::process::id()))
}

/// Writes `contents` to a fresh temporary file beside `path` (created new: never an
/// existing file or link), then renames it to `path`; on failure the temporary file
/// is removed and the error names `path`. The folder must exist.
///
/// Time: O(contents).
pub(crate) fn write_by_rename(path: &Path, contents: &[u8]) -> Result<(), Fault> {
    let folder = path.parent().filter(|d| !d.as_os_str().is_empty()).unwrap_or(Path::new("."));
    loop {
        let tmp = temporary(folder, NEXT.fetch_add(1, Ordering::Relaxed));
        let file = std::fs::OpenOptions::new().write(true).create_new(true).open(&tmp);
        let mut file = match file {
            // Left by an earlier process of the same id, or planted: the next number.
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(Fault::io(path, &e)),
            Ok(f) => f,
        };
        let result = file.write_all(contents).and_then(|()| {
            drop(file);
            std::fs::rename(&tmp, path)
        });
        if result.is_ok() {
            remember(path, contents);
        }
        return result.map_err(|e| {
            let _ = std::fs::remove_file(&tmp);
            Fault::io(path, &e)
        });
    }
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("mjcf-files-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    /// Links placed at the temporary names the next writes would take (say, by
    /// another user of a shared folder) are never opened: each write takes a name
    /// that does not exist yet, and the file the links point at stays as it was.
    #[test]
    fn temporary_files_never_open_an_existing_link() {
        let dir = scratch("links");
        let target = dir.with_extension("target");
        std::fs::write(&target, b"keep").unwrap();
        let first = NEXT.load(Ordering::Relaxed);
        for n in first..first + 20 {
            std::os::unix::fs::symlink(&target, temporary(&dir, n)).unwrap();
        }
        write_by_rename(&dir.join("a.stl"), b"new").unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"keep");
        assert_eq!(std::fs::read(dir.join("a.stl")).unwrap(), b"new");
        assert!(std::fs::symlink_metadata(dir.join("a.stl")).unwrap().file_type().is_file());
        assert!(NEXT.load(Ordering::Relaxed) > first + 20);
        std::fs::remove_dir_all(&dir).unwrap();
        std::fs::remove_file(&target).unwrap();
    }

    #[test]
    fn a_symlinked_folder_below_the_root_is_refused_and_nothing_is_created_through_it() {
        let dir = scratch("folders");
        let outside = dir.with_extension("outside");
        std::fs::create_dir_all(&outside).unwrap();
        std::os::unix::fs::symlink(&outside, dir.join("sub")).unwrap();
        let rel = Path::new("sub/deeper/b.xml");
        assert_eq!(real_folders(&dir, rel, true), Err(Fault::SymlinkedFolder(dir.join("sub"))));
        assert!(!outside.join("deeper").exists());
        assert_eq!(real_folders(&dir, Path::new("new/b.xml"), true), Ok(()));
        assert!(is_folder(&dir.join("new")));
        std::fs::remove_dir_all(&dir).unwrap();
        std::fs::remove_dir_all(&outside).unwrap();
    }

    #[test]
    fn on_disk_tells_a_file_changed_since_it_was_read() {
        let dir = scratch("on-disk");
        let p = dir.join("a.xml");
        assert_eq!(on_disk(&p, b"new", None), OnDisk::Missing);
        std::fs::write(&p, b"read").unwrap();
        let read = Fingerprint::of(b"read");
        assert_eq!(on_disk(&p, b"new", Some(&read)), OnDisk::AsRead);
        assert_eq!(on_disk(&p, b"read", Some(&read)), OnDisk::Same);
        std::fs::write(&p, b"theirs").unwrap();
        assert_eq!(on_disk(&p, b"new", Some(&read)), OnDisk::Changed);
        assert_eq!(on_disk(&p, b"new", None), OnDisk::Changed);
        // What this process wrote itself is not another program's edit.
        write_by_rename(&p, b"ours").unwrap();
        assert_eq!(on_disk(&p, b"newer", Some(&read)), OnDisk::Ours);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn inside_refuses_paths_that_lead_out() {
        assert_eq!(inside(Path::new("a/./b/../c.xml")), Some(PathBuf::from("a/c.xml")));
        assert_eq!(inside(Path::new("../c.xml")), None);
        assert_eq!(inside(Path::new("a/../../c.xml")), None);
        assert_eq!(inside(Path::new("/etc/c.xml")), None);
    }
}
