//! Fresh folders and files for the tests that read and save models on disk
//! (`tests/lossless.rs`, `tests/spellings.rs`, `tests/hostile.rs`), loaded once by
//! `tests/main.rs`: `use crate::dirs;`.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

/// A fresh, empty folder under the system's temp folder, named after this module,
/// `tag`, the process and a counter (so that tests running at once never share one).
pub(crate) fn temp_dir(tag: &str) -> PathBuf {
    static N: AtomicUsize = AtomicUsize::new(0);
    let n = N.fetch_add(1, Ordering::Relaxed);
    // `tests-dirs`: the one test binary's module.
    let test = module_path!().replace("::", "-");
    let d = std::env::temp_dir().join(format!("mjcf-{test}-{tag}-{}-{n}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Writes `text` to `rel` under `dir`, making its folders.
pub(crate) fn write(dir: &Path, rel: &str, text: &str) {
    let p = dir.join(rel);
    std::fs::create_dir_all(p.parent().unwrap()).unwrap();
    std::fs::write(p, text).unwrap();
}
