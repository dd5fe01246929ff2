//! Where a model's files come from: its folder on disk and an optional in-memory map.
//!
//! The only module that touches the file system (`tests/architecture.rs` checks it):
//! reading with the size cap and folder confinement, one canonical path, the scan
//! of the files an MJCF file names ([`scan`]), the asset model files one read or
//! edit reads ([`model_files`]) and the one writer of every file the crate writes
//! ([`write`](mod@write)). File attributes are read when they are set, so a model
//! value never reads files later.

use std::collections::HashMap;
use std::io::Read;
use std::path::{Component, Path, PathBuf};
use std::sync::Arc;

use crate::error::ErrorKind;

pub(crate) mod model_files;
/// The default cap on the size of one file read from disk: 1 GiB, far above any real
/// mesh, texture or model file.
pub(crate) mod scan;
pub(crate) mod write;

pub(crate) use scan::Basepaths;

pub(crate) const DEFAULT_MAX_FILE_SIZE: u64 = 1 << 30;

/// How a model finds the files its attributes and `<include>`s name.
#[derive(Clone, Debug)]
pub(crate) struct FileContext {
    /// The folder relative paths resolve against (`None`: the process's working
    /// directory).
    pub(crate) base_dir: Option<PathBuf>,
    /// In-memory files, looked up before the disk by the path as written and by the
    /// path joined with the folder setting.
    pub(crate) assets: Option<Arc<HashMap<String, Arc<[u8]>>>>,
    /// Refuse paths that leave `base_dir`: absolute paths, `..` above it, and paths
    /// that leave it once symlinks are followed.
    pub(crate) confine: bool,
    /// The largest file read from disk, in bytes.
    pub(crate) max_file_size: u64,
}

impl Default for FileContext {
    fn default() -> Self {
        FileContext {
            base_dir: None,
            assets: None,
            confine: false,
            max_file_size: DEFAULT_MAX_FILE_SIZE,
        }
    }
}

/// A file on disk: the path as resolved from the model's folder (for messages and
/// include cycles) and the path to open (with confinement, the canonical path that
/// was checked, so a symlink is not followed a second time).
#[derive(Clone, Debug)]
pub(crate) struct DiskPath {
    pub(crate) full: PathBuf,
    pub(crate) open: PathBuf,
}

/// Reads the regular file `open` (named `shown` in errors), refusing anything else
/// (a folder, a FIFO, a device) before opening it, and anything over `limit` bytes.
/// The read is bounded, so a file that grows or a device that never ends stops at
/// `limit + 1` bytes.
///
/// Time: O(size of the file), at most O(limit).
pub(crate) fn read_regular(open: &Path, shown: &Path, limit: u64) -> Result<Vec<u8>, ErrorKind> {
    let not_found = |e: std::io::Error| ErrorKind::FileNotFound {
        path: shown.to_path_buf(),
        reason: e.to_string(),
    };
    let too_large = || ErrorKind::FileTooLarge { path: shown.to_path_buf(), limit };
    // `metadata` follows symlinks: what is checked is what `open` would open. A FIFO
    // without a writer would block `open` forever, so this comes first.
    let meta = std::fs::metadata(open).map_err(not_found)?;
    if !meta.is_file() {
        return Err(ErrorKind::NotAFile(shown.to_path_buf()));
    }
    if meta.len() > limit {
        return Err(too_large());
    }
    let file = std::fs::File::open(open).map_err(not_found)?;
    // The size is a hint only (it may change, and some files report 0).
    let mut bytes = Vec::with_capacity(usize::try_from(meta.len()).unwrap_or(0));
    file.take(limit.saturating_add(1)).read_to_end(&mut bytes).map_err(not_found)?;
    if bytes.len() as u64 > limit {
        return Err(too_large());
    }
    Ok(bytes)
}

/// The canonical path of `path`: absolute, with every symlink followed and `.`
/// and `..` resolved. For a path that does not exist (yet), its nearest existing
/// folder's canonical path joined with the rest, normalised. The one answer to
/// whether two paths name one file.
///
/// Time: O(length of the path) system calls.
pub(crate) fn canonical(path: &Path) -> PathBuf {
    if let Ok(p) = std::fs::canonicalize(path) {
        return p;
    }
    let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
    let absolute = PathBuf::from(normalize(&absolute.to_string_lossy()));
    let mut rest: Vec<&std::ffi::OsStr> = Vec::new();
    let mut at = absolute.as_path();
    loop {
        if let Ok(found) = std::fs::canonicalize(at) {
            return rest.iter().rev().fold(found, |p, c| p.join(c));
        }
        match (at.parent(), at.file_name()) {
            (Some(parent), Some(name)) => {
                rest.push(name);
                at = parent;
            }
            _ => return absolute,
        }
    }
}

/// Joins a folder setting (`meshdir`) and a path as MJCF does.
pub(crate) fn join(basepath: Option<&str>, path: &str) -> String {
    match basepath {
        Some(b) if !b.is_empty() && !Path::new(path).is_absolute() => {
            let mut s = b.trim_end_matches('/').to_string();
            s.push('/');
            s.push_str(path);
            s
        }
        _ => path.to_string(),
    }
}

/// Normalises `a/./b/../c` to `a/c` (textually, like Python's `os.path.normpath`).
pub(crate) fn normalize(path: &str) -> String {
    let p = Path::new(path);
    let mut parts: Vec<Component<'_>> = Vec::new();
    for c in p.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => match parts.last() {
                Some(Component::Normal(_)) => {
                    parts.pop();
                }
                Some(Component::RootDir) => {}
                _ => parts.push(c),
            },
            _ => parts.push(c),
        }
    }
    let buf: PathBuf = parts.iter().collect();
    let s = buf.to_string_lossy().into_owned();
    if s.is_empty() { ".".to_string() } else { s }
}

/// Where a file named in MJCF is, found but not read yet.
#[derive(Clone, Debug)]
pub(crate) enum Located {
    /// An in-memory file: its contents.
    Memory { bytes: Arc<[u8]> },
    /// A file on disk.
    Disk(DiskPath),
}

impl FileContext {
    /// Reads the file `path` (as written in MJCF), with the folder setting `basepath`
    /// already chosen by the caller. Returns the path as resolved and the contents.
    pub(crate) fn read(
        &self,
        basepath: Option<&str>,
        path: &str,
    ) -> Result<(PathBuf, Arc<[u8]>), ErrorKind> {
        let (full, located) = self.locate(basepath, path)?;
        match located {
            Located::Memory { bytes, .. } => Ok((full, bytes)),
            Located::Disk(path) => Ok((full, self.read_disk(&path)?.into())),
        }
    }

    /// Finds the file `path` (as written in MJCF, with the folder setting `basepath`)
    /// as [`FileContext::read`] does, without reading a file on disk (confinement is
    /// checked). Returns the path as resolved and where the file is.
    pub(crate) fn locate(
        &self,
        basepath: Option<&str>,
        path: &str,
    ) -> Result<(PathBuf, Located), ErrorKind> {
        let joined = join(basepath, path);
        if let Some(assets) = &self.assets {
            if let Some(bytes) = assets.get(path).or_else(|| assets.get(&normalize(&joined))) {
                let located = Located::Memory { bytes: bytes.clone() };
                return Ok((PathBuf::from(&joined), located));
            }
        }
        let path = self.disk_path(&joined)?;
        Ok((path.full.clone(), Located::Disk(path)))
    }

    /// Reads a file on disk found by [`FileContext::disk_path`], within the size cap.
    pub(crate) fn read_disk(&self, path: &DiskPath) -> Result<Vec<u8>, ErrorKind> {
        read_regular(&path.open, &path.full, self.max_file_size)
    }

    /// The path on disk for a joined MJCF path, checking confinement: with it, the
    /// path must not be absolute nor lead out of the folder with `..`, and once every
    /// symlink is followed (of the file and of the folder) it must still be inside the
    /// folder.
    pub(crate) fn disk_path(&self, joined: &str) -> Result<DiskPath, ErrorKind> {
        let rel = Path::new(joined);
        let outside = || ErrorKind::FileOutsideRoot(rel.to_path_buf());
        if self.confine {
            let normal = normalize(joined);
            let escapes = rel.is_absolute()
                || Path::new(&normal).components().next() == Some(Component::ParentDir);
            if escapes {
                return Err(outside());
            }
        }
        let full = match &self.base_dir {
            Some(dir) => dir.join(rel),
            None => rel.to_path_buf(),
        };
        if !self.confine {
            return Ok(DiskPath { open: full.clone(), full });
        }
        let dir = match &self.base_dir {
            Some(dir) if !dir.as_os_str().is_empty() => dir.as_path(),
            _ => Path::new("."),
        };
        let canonical = |p: &Path| {
            std::fs::canonicalize(p)
                .map_err(|e| ErrorKind::FileNotFound { path: full.clone(), reason: e.to_string() })
        };
        let root = canonical(dir)?;
        let open = canonical(&full)?;
        if !open.starts_with(&root) {
            return Err(outside());
        }
        Ok(DiskPath { full, open })
    }

    /// The context for a file included from `path` (its folder becomes the base).
    pub(crate) fn for_included(&self, full_path: &Path) -> FileContext {
        FileContext {
            base_dir: Some(full_path.parent().map(Path::to_path_buf).unwrap_or_default()),
            ..self.clone()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn joins_and_normalises() {
        assert_eq!(join(Some("meshes"), "cube.stl"), "meshes/cube.stl");
        assert_eq!(join(Some("meshes/"), "cube.stl"), "meshes/cube.stl");
        assert_eq!(join(None, "cube.stl"), "cube.stl");
        assert_eq!(join(Some("m"), "/abs/cube.stl"), "/abs/cube.stl");
        assert_eq!(normalize("a/./b/../c"), "a/c");
        assert_eq!(normalize("../x"), "../x");
    }

    #[test]
    fn confinement_refuses_paths_that_leave_the_folder() {
        let ctx = FileContext {
            base_dir: Some("/tmp/m".into()),
            confine: true,
            ..FileContext::default()
        };
        assert!(matches!(ctx.disk_path("../etc/passwd"), Err(ErrorKind::FileOutsideRoot(_))));
        assert!(matches!(ctx.disk_path("/etc/passwd"), Err(ErrorKind::FileOutsideRoot(_))));
        // Without confinement the path is only joined.
        let open = FileContext { confine: false, ..ctx };
        assert_eq!(open.disk_path("a/../b.stl").unwrap().full, PathBuf::from("/tmp/m/a/../b.stl"));
    }

    /// The cap holds while reading, not only by the size the file reports: files in
    /// `/proc` are regular files that report size 0.
    #[cfg(target_os = "linux")]
    #[test]
    fn the_size_cap_bounds_the_read_itself() {
        let p = Path::new("/proc/self/status");
        if std::fs::metadata(p).is_ok_and(|m| m.is_file() && m.len() == 0) {
            assert!(matches!(
                read_regular(p, p, 10),
                Err(ErrorKind::FileTooLarge { limit: 10, .. })
            ));
            assert!(read_regular(p, p, 1 << 20).is_ok_and(|b| b.len() > 10));
        }
    }
}
