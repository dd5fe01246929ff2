//! Error types: what went wrong, and where.
//!
//! - [`ValueError`]: a value that does not fit its attribute (no position).
//! - [`ReadError`]: reading MJCF text or files; carries the file and a 1-based
//!   line:column.
//! - [`EditError`]: an edit of a model value; carries the path of the element the edit
//!   was aimed at (`worldbody/body[name=torso]/geom[2]`).
//! - [`WriteError`]: a model that cannot be written (a required reference whose target
//!   was removed).
//! - [`ExportError`]: a model and its files that cannot be exported to a folder; an
//!   I/O failure carries the path and the operating system's reason.
//!
//! Reading and editing fail for the same reasons, so both carry an [`ErrorKind`].
//! Every failing operation leaves every model value unchanged. Messages quote each
//! name or value a caller or a file supplied cut to 200 characters (the fields keep
//! them whole, but for [`ErrorKind::InvalidValue`]'s value).

use std::borrow::Cow;
use std::fmt;
use std::path::{Path, PathBuf};

use smol_str::SmolStr;

use crate::id::ElementId;
use crate::schema::{ElementKind, Namespace};

/// What is wrong with a value, independent of where it was found.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum ValueError {
    /// Not a number.
    #[error("expected a float")]
    NotFloat,
    /// Not an integral number.
    #[error("expected an integer")]
    NotInt,
    /// Not one of the keywords.
    #[error("expected one of: {}", .valid.join(", "))]
    NotKeyword {
        /// The accepted keywords.
        valid: &'static [&'static str],
    },
    /// An array entry is not a number.
    #[error("expected whitespace-separated floats")]
    NotFloatArray,
    /// An array entry is not an integral number.
    #[error("expected whitespace-separated integers")]
    NotIntArray,
    /// More entries than the attribute allows.
    #[error("expected at most {max} entries, got {len}")]
    TooLong {
        /// Most entries allowed.
        max: u32,
        /// Entries given.
        len: usize,
    },
    /// An identifier with `/`, which is reserved for scopes.
    #[error("an identifier cannot contain '/', which is reserved for scopes")]
    SlashInIdentifier,
    /// A character that XML 1.0 cannot hold (most control characters, U+FFFE, U+FFFF).
    #[error("{} (U+{:04X}) cannot be written in XML", .0.escape_debug(), *.0 as u32)]
    InvalidCharacter(char),
    /// A body named `world`.
    #[error("a body cannot be named 'world'")]
    WorldBody,
    /// A value of a type the attribute cannot hold.
    #[error("a value of the wrong type for this attribute")]
    WrongType,
    /// A file attribute given as text where no file can be loaded.
    #[error("a file attribute needs a file to load")]
    FileNeedsLoading,
    /// A mesh file whose extension MuJoCo does not read.
    #[error("mesh files must end in .stl, .msh or .obj")]
    MeshExtension,
}

/// Why reading or editing failed.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ErrorKind {
    /// The text is not well-formed XML.
    #[error("malformed XML: {}", cut_quoted(.0))]
    Syntax(String),
    /// The bytes are not UTF-8.
    #[error("the text is not valid UTF-8")]
    InvalidUtf8,
    /// The root element is not `<mujoco>`.
    #[error("the root element should be <mujoco>, got <{}>", cut(.0))]
    WrongRoot(SmolStr),
    /// An element the schema does not allow here.
    #[error("<{}> is not a valid child of <{parent}>{}", cut(.tag), hint_one(*.suggestion))]
    InvalidChild {
        /// The parent's tag.
        parent: &'static str,
        /// The child's tag.
        tag: SmolStr,
        /// The nearest valid child tag, if one is close.
        suggestion: Option<&'static str>,
    },
    /// An element with no child of the tag asked for
    /// ([`Model::child`](crate::Model::child)).
    #[error("<{parent}> has no <{}> child", cut(.tag))]
    NoChild {
        /// The parent's tag.
        parent: &'static str,
        /// The tag looked for.
        tag: SmolStr,
    },
    /// A tag that no single top-level section takes
    /// ([`Model::add_top`](crate::Model::add_top)).
    #[error("no single top-level section takes <{}>: add it under its parent", cut(.tag))]
    NoSection {
        /// The element's tag.
        tag: SmolStr,
    },
    /// A second singleton or on-demand child.
    #[error("a <{0}> child already exists")]
    DuplicateChild(&'static str),
    /// A top-level `<default>` read with a `class` other than `main`, which MuJoCo
    /// refuses in its own words ("top-level default class 'main' cannot be
    /// renamed"). The root class may be named in a model built through the API: the
    /// writer nests it (`<default><default class="name">`), which MuJoCo compiles.
    #[error(
        "the top-level <default> is named '{}': MuJoCo refuses it (\"top-level default class 'main' cannot be renamed\"); leave it unnamed or name it main, and put the named class inside it",
        cut(.0)
    )]
    RootClassRenamed(SmolStr),
    /// An attribute the schema does not define for this element.
    #[error("'{}' is not a valid attribute for <{tag}>{}", cut(.attribute), hint_one(*.suggestion))]
    UnknownAttribute {
        /// The element's tag.
        tag: &'static str,
        /// The attribute.
        attribute: SmolStr,
        /// The nearest valid attribute, if one is close.
        suggestion: Option<&'static str>,
    },
    /// A value that does not fit its attribute.
    #[error(
        "invalid value {:?} for attribute '{attribute}' of <{tag}>: {error}{}",
        cut(.value),
        keyword_hint(value, error)
    )]
    InvalidValue {
        /// The element's tag.
        tag: &'static str,
        /// The attribute.
        attribute: &'static str,
        /// The value as given (cut to 200 characters).
        value: String,
        /// What is wrong with it.
        error: ValueError,
    },
    /// An identifier already taken in its namespace.
    #[error("duplicate identifier '{}' in namespace {namespace}", cut(.name))]
    DuplicateIdentifier {
        /// The namespace.
        namespace: Namespace,
        /// The identifier.
        name: SmolStr,
    },
    /// A required attribute that is missing or would be cleared (a nested default
    /// class's `class`, which MuJoCo calls an "empty class name", included).
    #[error("attribute '{attribute}' of <{tag}> is required{}", mujoco_words(tag, attribute))]
    MissingRequired {
        /// The element's tag.
        tag: &'static str,
        /// The attribute.
        attribute: &'static str,
    },
    /// A file that does not exist (or cannot be read).
    #[error("cannot read file {:?}: {reason}", cut_path(.path))]
    FileNotFound {
        /// The path as resolved.
        path: PathBuf,
        /// The operating system's reason.
        reason: String,
    },
    /// A file outside the folder that file access is confined to.
    #[error("file {:?} is outside the model's folder", cut_path(.0))]
    FileOutsideRoot(PathBuf),
    /// A file larger than the cap on the size of one file
    /// ([`ReadOptions::max_file_size`](crate::ReadOptions::max_file_size), 1 GiB by
    /// default).
    #[error("file {:?} is larger than the limit of {limit} bytes", cut_path(.path))]
    FileTooLarge {
        /// The path as resolved.
        path: PathBuf,
        /// The cap, in bytes.
        limit: u64,
    },
    /// A path that names something other than a regular file once symlinks are
    /// followed: a folder, a FIFO, a socket or a device such as `/dev/zero`.
    #[error("{:?} is not a regular file", cut_path(.0))]
    NotAFile(PathBuf),
    /// An `<include>` that includes itself, directly or not.
    #[error("include cycle through {:?}", cut_path(.0))]
    IncludeCycle(PathBuf),
    /// An `<include>` of a file the model's include tree already includes (beside it,
    /// in another branch, or the main file), which MuJoCo refuses too ("File '...'
    /// already included").
    #[error(
        "file {:?} is already included in this model (a file can be included once)",
        cut_path(.0)
    )]
    IncludedTwice(PathBuf),
    /// An asset model file that brings more files than the reader takes (counting the
    /// files of the model files it names, each path once).
    #[error("a model file names more than {0} files (with those of the model files it names)")]
    TooManyFiles(usize),
    /// An element nested deeper than the reader allows.
    #[error("elements nested deeper than {0} levels")]
    TooDeep(usize),
    /// A size counted from the model's values (`<replicate>` counts, nested ones
    /// multiplied) that is past what the crate lists one by one: `what` is counted
    /// (`size`, saturated at `usize::MAX`), `limit` is the most it lists.
    #[error("{what}: {size} is more than the {limit} this crate lists one by one")]
    TooLarge {
        /// What was counted.
        what: &'static str,
        /// Its size.
        size: usize,
        /// The most allowed.
        limit: usize,
    },
    /// `include_copy` with override found a same-named element under another parent.
    #[error("{namespace} '{}' is already a child of another element", cut(.name))]
    CopyConflict {
        /// The namespace.
        namespace: Namespace,
        /// The identifier.
        name: SmolStr,
    },
    /// An attribute read (with [`Model::float`](crate::Model::float) and the like)
    /// that is not set.
    #[error("attribute '{attribute}' of <{tag}> is not set")]
    Unset {
        /// The element's tag.
        tag: &'static str,
        /// The attribute.
        attribute: &'static str,
    },
    /// An attribute read as a type it does not have (`floats` of a keyword).
    #[error("attribute '{attribute}' of <{tag}> does not hold a value of the type asked for")]
    WrongType {
        /// The element's tag.
        tag: &'static str,
        /// The attribute.
        attribute: &'static str,
    },
    /// A locator that names no element of this model.
    #[error("no such element")]
    NotFound,
    /// A locator of an element that is not in this model: it was removed, or the
    /// locator comes from another model.
    #[error(
        "element {id:?} of model '{}' is not in this model (removed, or a locator of another model)",
        cut(.origin)
    )]
    StaleLocator {
        /// The element's id.
        id: ElementId,
        /// The name of the model the locator was taken from.
        origin: SmolStr,
    },
    /// A name that [`Model::lookup`](crate::Model::lookup) did not find.
    #[error(
        "no {namespace} named '{}'{}{}",
        cut(.name),
        in_scope(scope),
        hint(suggestions)
    )]
    UnknownName {
        /// The namespace looked in.
        namespace: Namespace,
        /// The identifier looked for (without its scope).
        name: SmolStr,
        /// The scope path looked in (empty for the model itself).
        scope: SmolStr,
        /// The nearest existing names in that namespace and scope.
        suggestions: Vec<SmolStr>,
    },
    /// A scope path with a leading or trailing `/` or an empty segment.
    #[error(
        "invalid scope path '{}': scope names are separated by single '/', with none at the start or end",
        cut(.0)
    )]
    InvalidScope(SmolStr),
    /// A freejoint on an attachment frame that does not sit directly in the worldbody.
    #[error(
        "the frame of '{}' cannot take a freejoint: only a frame directly in the worldbody can (attach at a site of the worldbody)",
        cut(.0)
    )]
    FreejointNotTopLevel(SmolStr),
    /// A global setting that differs between two models being merged.
    #[error(
        "conflicting values for attribute '{attribute}' of <{tag}>: {} vs {}",
        cut(.ours),
        cut(.theirs)
    )]
    AttributeConflict {
        /// The element's tag.
        tag: &'static str,
        /// The attribute.
        attribute: &'static str,
        /// The receiving model's value.
        ours: String,
        /// The other model's value.
        theirs: String,
    },
    /// `attach` at an element that is neither a site nor a worldbody (`attach_in` at
    /// one that is neither a body nor a `<frame>`, or at an attachment frame).
    #[error(
        "cannot attach at a <{0}>: attach takes a site or the worldbody, attach_in a body or a <frame>"
    )]
    InvalidParent(&'static str),
    /// A scope path that names no attachment.
    #[error("no model is attached at scope '{}'{}", cut(.scope), attached_list(attached))]
    NotAttached {
        /// The scope path asked for.
        scope: SmolStr,
        /// The scopes attached where the search stopped (nearest first, then the rest).
        attached: Vec<SmolStr>,
    },
    /// A removal refused because elements refer to what it would remove
    /// ([`Model::remove_with`](crate::Model::remove_with) with `Referrers::Refuse`).
    #[error("cannot remove: referred to by {}; remove them first, or cascade (Referrers::Cascade)", .by.join(", "))]
    Referenced {
        /// Each referring element and attribute (`m: joint`).
        by: Vec<String>,
    },
    /// A removal that would take attached content with it.
    #[error("removing this element affects attached models; remove with attachments explicitly")]
    AffectsAttachments,
    /// `include_copy` of a model that has attachments.
    #[error("cannot copy from a model with attachments")]
    SourceHasAttachments,
    /// A `<text>` of `<custom>` that gives its data both as its `data` attribute
    /// (even empty) and as a CDATA section; MuJoCo refuses it.
    #[error(
        "<text> gives its data both as 'data' and as CDATA (MuJoCo: \"text field data cannot be \
         specified as both attribute and CDATA\"); keep one"
    )]
    TextDataTwice,
    /// A `<text>` of `<custom>` with more than one CDATA section; MuJoCo refuses it.
    #[error(
        "<text> has more than one CDATA section (MuJoCo: \"text field cannot have multiple CDATA \
         sections\"); join them in one"
    )]
    TextCdataTwice,
}

/// The most characters of one name or value (a tag, an attribute, an identifier, a
/// scope, a file name, a value) an error message quotes.
pub(crate) const QUOTE_LIMIT: usize = 200;

/// `s` as error messages quote a name or value: whole up to [`QUOTE_LIMIT`]
/// characters, else its first [`QUOTE_LIMIT`] and `...`. Every message quoting
/// something a caller or a file supplied goes through here (or through
/// [`cut_path`] and [`cut_quoted`], which apply it per name).
pub(crate) fn cut(s: &str) -> Cow<'_, str> {
    match s.char_indices().nth(QUOTE_LIMIT) {
        Some((i, _)) => Cow::Owned(format!("{}...", &s[..i])),
        None => Cow::Borrowed(s),
    }
}

/// A file path as error messages show it: each name in it [`cut`] ([`cut_segments`]).
pub(crate) fn cut_path(path: &Path) -> String {
    cut_segments(&path.to_string_lossy()).into_owned()
}

/// A path (of a file, of an element: `worldbody/body[name=torso]`, of scopes) as
/// error messages show it: each `/`-separated part [`cut`], so a long path of
/// ordinary names stays whole and a huge name in it does not.
pub(crate) fn cut_segments(path: &str) -> Cow<'_, str> {
    if path.split('/').all(|s| matches!(cut(s), Cow::Borrowed(_))) {
        return Cow::Borrowed(path);
    }
    Cow::Owned(path.split('/').map(cut).collect::<Vec<_>>().join("/"))
}

/// A message quoting names between backquotes (quick-xml's syntax errors:
/// ``expected `</a>`, but `</b>` was found``) with each quoted part [`cut`].
fn cut_quoted(message: &str) -> String {
    message.split('`').map(cut).collect::<Vec<_>>().join("`")
}

fn hint_one(suggestion: Option<&str>) -> String {
    hint(suggestion.as_slice())
}

/// ` (did you mean 'a', 'b'?)`, or nothing: the suggestions of [`crate::suggest`] as
/// messages show them, each [`cut`].
pub(crate) fn hint(suggestions: &[impl AsRef<str>]) -> String {
    if suggestions.is_empty() {
        return String::new();
    }
    let list: Vec<String> = suggestions.iter().map(|s| format!("'{}'", cut(s.as_ref()))).collect();
    format!(" (did you mean {}?)", list.join(", "))
}

fn in_scope(scope: &str) -> String {
    if scope.is_empty() { String::new() } else { format!(" in scope '{}'", cut(scope)) }
}

fn attached_list(attached: &[SmolStr]) -> String {
    if attached.is_empty() {
        "; nothing is attached there".to_string()
    } else {
        let list: Vec<String> = attached.iter().map(|s| format!("'{}'", cut(s))).collect();
        format!("; attached there: {}", list.join(", "))
    }
}

/// For a misspelt keyword, the nearest valid one.
fn keyword_hint(value: &str, error: &ValueError) -> String {
    match error {
        ValueError::NotKeyword { valid } => {
            hint_one(crate::suggest::closest(value, valid.iter().copied()))
        }
        _ => String::new(),
    }
}

impl ErrorKind {
    /// An unknown attribute of `kind`, with the nearest valid one.
    pub(crate) fn unknown_attribute(kind: ElementKind, attribute: &str) -> ErrorKind {
        let names = kind.spec().attrs.iter().map(|a| a.name);
        ErrorKind::UnknownAttribute {
            tag: kind.tag(),
            attribute: attribute.into(),
            suggestion: crate::suggest::closest(attribute, names),
        }
    }

    /// A child tag that `parent` does not allow, with the nearest valid one.
    pub(crate) fn invalid_child(parent: ElementKind, tag: &str) -> ErrorKind {
        let tags = parent.spec().children.iter().map(|c| c.tag());
        ErrorKind::InvalidChild {
            parent: parent.tag(),
            tag: tag.into(),
            suggestion: crate::suggest::closest(tag, tags),
        }
    }
}

/// A 1-based position in XML text.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct TextPos {
    /// Line, from 1.
    pub line: u32,
    /// Column in characters, from 1.
    pub column: u32,
}

impl TextPos {
    /// The position of byte offset `offset` in `text`. Lines end as XML ends them
    /// (XML 1.0 §2.11): at `\n`, `\r\n` or a `\r` alone, each one line break, so a
    /// place in a file gets one position whichever of the three its lines end with.
    /// A byte-order mark starting the text is no column (editors do not show it).
    ///
    /// Time: O(offset).
    pub(crate) fn of_offset(text: &str, offset: usize) -> TextPos {
        let mut offset = offset.min(text.len());
        while !text.is_char_boundary(offset) {
            offset -= 1;
        }
        let bytes = text.as_bytes();
        // The `\n` of a `\r\n` is where its `\r` is: the one place of the break.
        if offset > 0 && bytes[offset - 1] == b'\r' && bytes.get(offset) == Some(&b'\n') {
            offset -= 1;
        }
        let bom = if text.starts_with('\u{feff}') { '\u{feff}'.len_utf8().min(offset) } else { 0 };
        let (mut line, mut line_start) = (1usize, bom);
        for (i, b) in bytes[..offset].iter().enumerate() {
            // A `\r` followed by `\n` (even past `offset`) is not a break itself: the
            // `\n` is.
            let breaks = *b == b'\n' || (*b == b'\r' && bytes.get(i + 1) != Some(&b'\n'));
            if breaks {
                line += 1;
                line_start = i + 1;
            }
        }
        let column = text[line_start..offset].chars().count() + 1;
        TextPos {
            line: line.min(u32::MAX as usize) as u32,
            column: column.min(u32::MAX as usize) as u32,
        }
    }
}

impl fmt::Display for TextPos {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.line, self.column)
    }
}

/// Reading MJCF failed. (One pointer wide; the details are boxed.)
#[derive(Clone, Debug, PartialEq)]
pub struct ReadError(Box<ReadErrorData>);

#[derive(Clone, Debug, PartialEq)]
struct ReadErrorData {
    kind: ErrorKind,
    file: Option<PathBuf>,
    pos: Option<TextPos>,
}

impl ReadError {
    pub(crate) fn new(kind: ErrorKind, file: Option<PathBuf>, pos: Option<TextPos>) -> ReadError {
        ReadError(Box::new(ReadErrorData { kind, file, pos }))
    }

    /// What went wrong.
    ///
    /// Time: O(1).
    pub fn kind(&self) -> &ErrorKind {
        &self.0.kind
    }

    /// The file being read, when reading from a file (for an error inside an
    /// included file, the included file).
    ///
    /// Time: O(1).
    pub fn file(&self) -> Option<&std::path::Path> {
        self.0.file.as_deref()
    }

    /// Where in the text, when the error is tied to a place in it.
    ///
    /// Time: O(1).
    pub fn pos(&self) -> Option<TextPos> {
        self.0.pos
    }
}

impl fmt::Display for ReadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.0.kind)?;
        match (&self.0.file, self.0.pos) {
            (Some(file), Some(pos)) => write!(f, " at {}:{pos}", cut_path(file)),
            (Some(file), None) => write!(f, " in {}", cut_path(file)),
            (None, Some(pos)) => write!(f, " at {pos}"),
            (None, None) => Ok(()),
        }
    }
}

impl std::error::Error for ReadError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.0.kind)
    }
}

/// An edit of a model failed; the model is unchanged. (One pointer wide; the details
/// are boxed.)
#[derive(Clone, Debug, PartialEq)]
pub struct EditError(Box<EditErrorData>);

#[derive(Clone, Debug, PartialEq)]
struct EditErrorData {
    kind: ErrorKind,
    path: String,
}

impl EditError {
    pub(crate) fn new(kind: ErrorKind, path: String) -> EditError {
        EditError(Box::new(EditErrorData { kind, path }))
    }

    /// What went wrong.
    ///
    /// Time: O(1).
    pub fn kind(&self) -> &ErrorKind {
        &self.0.kind
    }

    /// The path of the element the edit was aimed at, such as
    /// `worldbody/body[name=torso]/geom[2]` (empty for the model's root).
    ///
    /// Time: O(1).
    pub fn path(&self) -> &str {
        &self.0.path
    }
}

impl fmt::Display for EditError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.0.path.is_empty() {
            write!(f, "{} at <mujoco>", self.0.kind)
        } else {
            write!(f, "{} at {}", self.0.kind, cut_segments(&self.0.path))
        }
    }
}

impl std::error::Error for EditError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.0.kind)
    }
}

/// A model cannot be written.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum WriteError {
    /// A required reference whose target was removed.
    #[error(
        "attribute '{attribute}' of <{tag}> at {} is required, but the element it named was removed",
        cut_segments(.path)
    )]
    MissingRequired {
        /// The element's tag.
        tag: &'static str,
        /// The attribute.
        attribute: &'static str,
        /// The element's path.
        path: String,
    },
    /// Global settings of attached models that cannot be merged (only reachable
    /// through values built before a conflict check existed; edits refuse them).
    #[error("cannot merge settings: {0}")]
    Conflict(String),
    /// A character that XML 1.0 cannot hold (such as NUL), which only the model name
    /// can carry: attribute values refuse it when they are set or read.
    #[error("attribute '{attribute}' of <{tag}> holds {} (U+{:04X}), which XML cannot hold", character.escape_debug(), *character as u32)]
    InvalidCharacter {
        /// The element's tag.
        tag: &'static str,
        /// The attribute.
        attribute: &'static str,
        /// The character.
        character: char,
    },
    /// A size to write counted from the model's values (the composed keys of
    /// [`WriteOptions::merge_keyframes`](crate::WriteOptions) over `<replicate>`
    /// copies, an `actdim`) past what the writer writes: `what` is counted (`size`,
    /// saturated at `usize::MAX`), `limit` is the most it writes.
    #[error("{what}: {size} is more than the {limit} the writer writes")]
    TooLarge {
        /// What was counted.
        what: &'static str,
        /// Its size.
        size: usize,
        /// The most allowed.
        limit: usize,
    },
    /// Two different files that would be written under one name, which is possible
    /// only when files are named without their hash (`filename_with_hash: false`), or
    /// an exported file named like the exported MJCF file.
    #[error(
        "two different files would both be written as '{}' (name files with their hash to tell them apart)",
        cut(.name)
    )]
    FileNameClash {
        /// The file name.
        name: String,
    },
}

/// Exporting a model with its files to a folder failed.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum ExportError {
    /// The model cannot be written (including two different files that would get one
    /// name); nothing was written.
    #[error(transparent)]
    Write(#[from] WriteError),
    /// A folder of a file's path inside the export folder is a symlink: export never
    /// writes through one (it could lead out of the folder); nothing was written.
    #[error(
        "cannot write through {}: it is a symbolic link, and export writes only into real folders inside its folder",
        cut_path(.path)
    )]
    SymlinkedFolder {
        /// The folder (the export folder joined with the path's components up to it).
        path: PathBuf,
    },
    /// A folder or file could not be created or written, or a name is not a plain
    /// file name or a path inside the folder (`InvalidInput`, before anything is
    /// written).
    #[error("cannot write {}: {reason}", cut_path(.path))]
    Io {
        /// The folder, or the file as named in the folder (never a temporary name).
        path: PathBuf,
        /// The kind of the operating system's error.
        kind: std::io::ErrorKind,
        /// The operating system's reason.
        reason: String,
    },
}

/// Any error of this crate, for callers that just want `?`.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// Reading failed.
    #[error(transparent)]
    Read(#[from] ReadError),
    /// An edit failed.
    #[error(transparent)]
    Edit(#[from] EditError),
    /// Writing failed.
    #[error(transparent)]
    Write(#[from] WriteError),
    /// Exporting to a folder failed.
    #[error(transparent)]
    Export(#[from] ExportError),
}

/// MuJoCo's own words for a missing attribute, where they differ from the crate's: a
/// nested default class without a `class` is MuJoCo 4.0.0's "empty class name".
fn mujoco_words(tag: &str, attribute: &str) -> &'static str {
    match (tag, attribute) {
        ("default", "class") => " (MuJoCo: \"empty class name\")",
        _ => "",
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hints_quote_each_suggestion_cut() {
        assert_eq!(hint(&["a", "b"]), " (did you mean 'a', 'b'?)");
        assert_eq!(hint(&[] as &[&str]), "");
        let long = "x".repeat(QUOTE_LIMIT + 5);
        assert_eq!(
            hint(&[long.as_str()]),
            format!(" (did you mean '{}...'?)", &long[..QUOTE_LIMIT])
        );
    }

    #[test]
    fn positions_count_lines_and_characters() {
        let t = "ab\ncdé\nf";
        assert_eq!(TextPos::of_offset(t, 0), TextPos { line: 1, column: 1 });
        assert_eq!(TextPos::of_offset(t, 3), TextPos { line: 2, column: 1 });
        assert_eq!(TextPos::of_offset(t, 7), TextPos { line: 2, column: 4 });
        assert_eq!(TextPos::of_offset(t, 100), TextPos { line: 3, column: 2 });
    }

    /// `\n`, `\r\n` and a lone `\r` each end one line: every place of a text gets
    /// the same position whichever of them the text uses (also a mix of them).
    #[test]
    fn positions_are_the_same_for_every_line_ending() {
        let lines = ["<mujoco>", "  <worldbody>", "", "    <bogus/>", "é</mujoco>"];
        let texts: Vec<String> = ["\n", "\r\n", "\r"].iter().map(|e| lines.join(e)).collect();
        // (A `\r` then an empty line then `\n` would be one `\r\n`.)
        let mixed =
            format!("{}\r\n{}\n{}\r{}\r\n{}", lines[0], lines[1], lines[2], lines[3], lines[4]);
        // Each character's position, skipping the line breaks themselves.
        let positions = |t: &str| -> Vec<TextPos> {
            t.char_indices()
                .filter(|(_, c)| !matches!(c, '\r' | '\n'))
                .map(|(i, _)| TextPos::of_offset(t, i))
                .collect()
        };
        let want = positions(&texts[0]);
        assert_eq!(want.len(), lines.iter().map(|l| l.chars().count()).sum::<usize>());
        assert_eq!(want.last(), Some(&TextPos { line: 5, column: 10 }));
        assert!(want.contains(&TextPos { line: 4, column: 5 }));
        for t in texts.iter().skip(1).chain([&mixed]) {
            assert_eq!(positions(t), want, "{t:?}");
        }
        // The end of the text, and an offset between the two bytes of a `\r\n`: at
        // the end of the line, as the offset of the `\n` alone in the `\n` text.
        assert_eq!(TextPos::of_offset(&texts[1], 9), TextPos::of_offset(&texts[0], 8));
        assert_eq!(TextPos::of_offset(&texts[1], 9), TextPos { line: 1, column: 9 });
        for t in &texts {
            assert_eq!(TextPos::of_offset(t, t.len()), TextPos { line: 5, column: 11 });
        }
    }

    /// A byte-order mark is no column: every place after it has the position it has
    /// in the text without it.
    #[test]
    fn positions_after_a_byte_order_mark_are_those_without_it() {
        let t = "<mujoco>\r\n  <bogus/>\né";
        let marked = format!("\u{feff}{t}");
        for (i, _) in t.char_indices().chain([(t.len(), ' ')]) {
            assert_eq!(TextPos::of_offset(&marked, i + 3), TextPos::of_offset(t, i), "{i}");
        }
        for inside in 0..3 {
            assert_eq!(TextPos::of_offset(&marked, inside), TextPos { line: 1, column: 1 });
        }
    }

    #[test]
    fn names_are_cut_at_200_characters_each() {
        let at = "é".repeat(200);
        assert_eq!(cut(&at), at, "200 characters stay whole");
        assert!(matches!(cut(&at), Cow::Borrowed(_)));
        assert_eq!(cut(&format!("{at}x")), format!("{at}..."));
        assert_eq!(cut(&cut(&"y".repeat(1000))), cut(&"y".repeat(1000)));
        let long = "n".repeat(1000);
        let path = format!("a/{long}/b");
        assert_eq!(cut_segments(&path), format!("a/{}.../b", &long[..200]));
        assert!(matches!(cut_segments("worldbody/body[name=torso]"), Cow::Borrowed(_)));
        assert_eq!(cut_path(Path::new(&path)), format!("a/{}.../b", &long[..200]));
        assert_eq!(
            cut_quoted(&format!("expected `{long}`, found `x`")),
            format!("expected `{}...`, found `x`", &long[..200])
        );
    }

    #[test]
    fn errors_stay_small() {
        assert!(std::mem::size_of::<ErrorKind>() <= 88, "{}", std::mem::size_of::<ErrorKind>());
        assert_eq!(std::mem::size_of::<ReadError>(), std::mem::size_of::<usize>());
        assert_eq!(std::mem::size_of::<EditError>(), std::mem::size_of::<usize>());
        assert!(std::mem::size_of::<Error>() <= 64, "{}", std::mem::size_of::<Error>());
    }

    #[test]
    fn messages_say_what_then_where() {
        let e = ReadError::new(
            ErrorKind::UnknownAttribute { tag: "geom", attribute: "foo".into(), suggestion: None },
            Some("m.xml".into()),
            Some(TextPos { line: 3, column: 5 }),
        );
        assert_eq!(e.to_string(), "'foo' is not a valid attribute for <geom> at m.xml:3:5");
        let e = EditError::new(ErrorKind::NotFound, "worldbody/body[name=torso]".into());
        assert_eq!(e.to_string(), "no such element at worldbody/body[name=torso]");
    }
}
