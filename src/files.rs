//! Where a model's files come from: its folder on disk and an optional in-memory map.
//!
//! The only module besides the reader that touches the file system. File attributes
//! are read when they are set, so a model value never reads files later.

use std::collections::HashMap;
use std::path::{Component, Path, PathBuf};
use std::sync::Arc;

use crate::error::ErrorKind;

/// How a model finds the files its attributes and `<include>`s name.
#[derive(Clone, Debug, Default)]
pub(crate) struct FileContext {
    /// The folder relative paths resolve against (`None`: the process's working
    /// directory).
    pub(crate) base_dir: Option<PathBuf>,
    /// In-memory files, looked up before the disk by the path as written and by the
    /// path joined with the folder setting.
    pub(crate) assets: Option<Arc<HashMap<String, Arc<[u8]>>>>,
    /// Refuse paths that leave `base_dir` (absolute paths, `..` above it).
    pub(crate) confine: bool,
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

impl FileContext {
    /// Reads the file `path` (as written in MJCF), with the folder setting `basepath`
    /// already chosen by the caller. Returns the path as resolved and the contents.
    pub(crate) fn read(
        &self,
        basepath: Option<&str>,
        path: &str,
    ) -> Result<(PathBuf, Arc<[u8]>), ErrorKind> {
        let joined = join(basepath, path);
        if let Some(assets) = &self.assets {
            if let Some(bytes) = assets.get(path).or_else(|| assets.get(&normalize(&joined))) {
                return Ok((PathBuf::from(&joined), bytes.clone()));
            }
        }
        let full = self.disk_path(&joined)?;
        match std::fs::read(&full) {
            Ok(bytes) => Ok((full, bytes.into())),
            Err(e) => Err(ErrorKind::FileNotFound { path: full, reason: e.to_string() }),
        }
    }

    /// The path on disk for a joined MJCF path, checking confinement.
    pub(crate) fn disk_path(&self, joined: &str) -> Result<PathBuf, ErrorKind> {
        let rel = Path::new(joined);
        if self.confine {
            let normal = normalize(joined);
            let escapes = rel.is_absolute()
                || Path::new(&normal).components().next() == Some(Component::ParentDir);
            if escapes {
                return Err(ErrorKind::FileOutsideRoot(rel.to_path_buf()));
            }
        }
        Ok(match &self.base_dir {
            Some(dir) => dir.join(rel),
            None => rel.to_path_buf(),
        })
    }

    /// The context for a file included from `path` (its folder becomes the base).
    pub(crate) fn for_included(&self, full_path: &Path) -> FileContext {
        FileContext {
            base_dir: Some(full_path.parent().map(Path::to_path_buf).unwrap_or_default()),
            assets: self.assets.clone(),
            confine: self.confine,
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
        let ctx = FileContext { base_dir: Some("/tmp/m".into()), assets: None, confine: true };
        assert!(matches!(ctx.disk_path("../etc/passwd"), Err(ErrorKind::FileOutsideRoot(_))));
        assert!(matches!(ctx.disk_path("/etc/passwd"), Err(ErrorKind::FileOutsideRoot(_))));
        assert_eq!(ctx.disk_path("a/../b.stl").unwrap(), PathBuf::from("/tmp/m/a/../b.stl"));
    }
}
