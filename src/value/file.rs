//! File assets: the contents of a mesh, texture, height field or skin file, named by
//! their hash when written.

use std::fmt;
use std::sync::Arc;

use smol_str::SmolStr;

/// The contents of a file attribute (`mesh/@file`, `texture/@file`, ...).
///
/// The bytes are read when the attribute is set (or the model is read), so a model
/// value never depends on the file system afterwards. Cloning is O(1). Two assets are
/// equal when their names and contents are equal.
#[derive(Clone)]
pub struct FileAsset(Arc<FileData>);

#[derive(Clone)]
struct FileData {
    stem: SmolStr,
    extension: SmolStr,
    contents: Arc<[u8]>,
    sha1: String,
    /// For a model file (asset `<model file>`): the files it names, by their path
    /// relative to it.
    companions: Arc<[(SmolStr, FileAsset)]>,
    /// Written as `stem.ext` whatever the writer's hash option: a file whose name was
    /// chosen (a part of a saved scene, `xml::scene`), never one read.
    fixed_name: bool,
}

impl FileAsset {
    /// Creates an asset from a file stem (`"cube"`), an extension with its dot
    /// (`".stl"`) and the contents.
    ///
    /// Time: O(size of `contents`): the SHA-1 of the contents is computed (and a
    /// `Vec` is copied into an `Arc`).
    pub fn new(stem: &str, extension: &str, contents: impl Into<Arc<[u8]>>) -> FileAsset {
        let contents = contents.into();
        let sha1 = sha1_smol::Sha1::from(&contents[..]).digest().to_string();
        FileAsset(Arc::new(FileData {
            stem: stem.into(),
            extension: extension.into(),
            contents,
            sha1,
            companions: Arc::from([]),
            fixed_name: false,
        }))
    }

    /// A file written under exactly `stem` + `extension`, with or without the
    /// writer's hash option: the parts of a saved scene, named by the scene.
    ///
    /// Time: as [`FileAsset::new`].
    pub(crate) fn with_fixed_name(
        stem: &str,
        extension: &str,
        contents: impl Into<Arc<[u8]>>,
    ) -> FileAsset {
        let mut file = FileAsset::new(stem, extension, contents);
        Arc::make_mut(&mut file.0).fixed_name = true;
        file
    }

    /// Creates an asset from a path as written in MJCF and the file's contents: the
    /// stem and extension come from the path's last component. A stem that ends in
    /// `-` and the SHA-1 of the contents (a name the writer gave the file) is read
    /// without that suffix, so a written model reads back with its files' names.
    ///
    /// Time: as [`FileAsset::new`].
    pub fn from_path_and_contents(path: &str, contents: impl Into<Arc<[u8]>>) -> FileAsset {
        FileAsset::new("", "", contents).named_as(path)
    }

    /// The same file (contents, hash, companions) under the name `path` gives it, as
    /// [`FileAsset::from_path_and_contents`] names a file; the contents are not hashed
    /// again.
    ///
    /// Time: O(length of `path`), and a copy of the companions' list handle.
    pub(crate) fn named_as(&self, path: &str) -> FileAsset {
        let file = path.rsplit(['/', '\\']).next().unwrap_or(path);
        let (stem, ext) = match file.rfind('.') {
            Some(i) if i > 0 => (&file[..i], &file[i..]),
            _ => (file, ""),
        };
        // A name this crate (or dm_control) wrote, `stem-<sha1 of the contents>`, is
        // read as `stem`, so writing it again gives the same name, not a second hash.
        let stem = match stem.strip_suffix(self.sha1_hex()).and_then(|s| s.strip_suffix('-')) {
            Some(original) if !original.is_empty() => original,
            _ => stem,
        };
        if *self.0.stem == *stem && *self.0.extension == *ext && !self.0.fixed_name {
            return self.clone();
        }
        FileAsset(Arc::new(FileData {
            stem: stem.into(),
            extension: ext.into(),
            fixed_name: false,
            ..FileData::clone(&self.0)
        }))
    }

    /// For a model file (an asset `<model file="child.xml">`), the files the model
    /// names (its meshes, textures, ..., and the model files it names in turn), by
    /// their paths relative to it, as MuJoCo resolves them (with its compiler folder
    /// settings). Export writes them at those paths beside it. Empty for other files.
    ///
    /// Time: O(1).
    pub fn companions(&self) -> &[(SmolStr, FileAsset)] {
        &self.0.companions
    }

    /// The same file with these companions.
    pub(crate) fn with_companions(
        &self,
        companions: impl Into<Arc<[(SmolStr, FileAsset)]>>,
    ) -> FileAsset {
        FileAsset(Arc::new(FileData { companions: companions.into(), ..FileData::clone(&self.0) }))
    }

    /// The file stem (`"cube"`).
    ///
    /// Time: O(1).
    pub fn stem(&self) -> &str {
        &self.0.stem
    }

    /// The extension with its dot (`".stl"`), or empty.
    ///
    /// Time: O(1).
    pub fn extension(&self) -> &str {
        &self.0.extension
    }

    /// The file's bytes.
    ///
    /// Time: O(1).
    pub fn contents(&self) -> &[u8] {
        &self.0.contents
    }

    /// The SHA-1 of the contents, as 40 lower-case hex digits.
    ///
    /// Time: O(1) (computed when the asset is made).
    pub fn sha1_hex(&self) -> &str {
        &self.0.sha1
    }

    /// The name the file gets in written MJCF: `stem-<sha1>.ext` with the hash, or
    /// `stem.ext` without (a file without a stem is named by its hash either way).
    ///
    /// Time: O(length of the name).
    pub fn vfs_name(&self, with_hash: bool) -> String {
        let d = &self.0;
        if d.fixed_name {
            return format!("{}{}", d.stem, d.extension);
        }
        match (d.stem.is_empty(), with_hash) {
            (true, _) => format!("{}{}", d.sha1, d.extension),
            (false, true) => {
                // The reference keeps names within MuJoCo's 998-byte VFS limit by
                // cutting the stem.
                let room = 998usize.saturating_sub(d.sha1.len() + d.extension.len() + 1);
                let mut end = d.stem.len().min(room);
                while !d.stem.is_char_boundary(end) {
                    end -= 1;
                }
                format!("{}-{}{}", &d.stem[..end], d.sha1, d.extension)
            }
            (false, false) => format!("{}{}", d.stem, d.extension),
        }
    }
}

impl PartialEq for FileAsset {
    fn eq(&self, other: &Self) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
            || (self.0.sha1 == other.0.sha1
                && self.0.stem == other.0.stem
                && self.0.extension == other.0.extension
                && self.0.fixed_name == other.0.fixed_name)
    }
}

impl Eq for FileAsset {}

impl std::hash::Hash for FileAsset {
    /// Consistent with equality: the name and the contents' hash.
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        self.0.sha1.hash(state);
        self.0.stem.hash(state);
        self.0.extension.hash(state);
        self.0.fixed_name.hash(state);
    }
}

impl fmt::Debug for FileAsset {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "FileAsset({} bytes, {})", self.0.contents.len(), self.vfs_name(true))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_carry_the_sha1_of_the_contents() {
        let a = FileAsset::from_path_and_contents("meshes/cube.stl", b"abc".to_vec());
        assert_eq!(a.sha1_hex(), "a9993e364706816aba3e25717850c26c9cd0d89d");
        assert_eq!(a.vfs_name(true), "cube-a9993e364706816aba3e25717850c26c9cd0d89d.stl");
        assert_eq!(a.vfs_name(false), "cube.stl");
        let b = FileAsset::new("", ".png", b"abc".to_vec());
        assert_eq!(b.vfs_name(false), "a9993e364706816aba3e25717850c26c9cd0d89d.png");
    }
}
