//! [`Model`]: one MJCF model as an immutable value, with its identifier index.
//!
//! Every edit returns a new `Model` and leaves the old one as it was; the two share
//! every subtree the edit did not touch. Elements are named by a [`Loc`], which keeps
//! pointing at the same element across versions (it holds the element's stable id).

mod arrays;
mod build;
mod cascade;
pub(crate) mod check;
mod cursor;
pub(crate) mod defaults;
pub(crate) mod diff;
mod edit;
mod elems;
mod eq;
pub(crate) mod follow;
pub(crate) mod frame;
mod handle;
mod index;
pub(crate) mod keys;
pub(crate) mod layout;
pub(crate) mod naming;
pub(crate) mod pose;
mod reach;
mod scope;
pub(crate) mod settings;
pub(crate) mod source;
mod top;
pub(crate) mod tree;

use std::fmt;
use std::path::PathBuf;
use std::sync::{Arc, OnceLock};

use smol_str::SmolStr;

use crate::error::{EditError, ErrorKind};
use crate::files::FileContext;
use crate::schema::{AttrType, ElementKind, Multiplicity, Namespace};
use crate::value::Value;
use tree::{ElementId, Node};

pub(crate) use build::push_segment as push_path;
pub use build::{Attrs, Element};
pub(crate) use build::{
    Basepaths, Input, ModelFiles, ValueCtx, check_class_named, check_required,
    check_root_class_name, empty_node, empty_node_with_id, name_from_file,
};
pub use cascade::{Referrers, Removal};
pub use check::{Advice, AdviceKind, Problem, ProblemKind};
pub(crate) use cursor::{Insts, Item, Step, Walk};
pub(crate) use elems::ElemMap;
pub use handle::{ElementRef, Event, Preorder};
pub(crate) use index::{Entry, Index, MergedCache, ReadIndex, slashed_segment};
pub use layout::{JointType, Layout, LayoutActuator, LayoutJoint, LayoutMocap, MAX_LAYOUT_ENTRIES};
pub(crate) use scope::not_attached as scope_not_attached;
pub use scope::{Attachment, ScopeRef};

/// An MJCF model: a `<mujoco>` tree as a persistent value.
///
/// Cloning is O(1) and the clone shares everything. `Model` is `Send + Sync`, so
/// versions can be shared across threads freely.
///
/// # Examples
/// ```
/// use mjcf::{Model, Namespace, element};
/// let m0 = Model::new("arena");
/// let (m1, _) = m0.add(&m0.worldbody(), element!("geom", name = "floor", type = "plane"))?;
/// assert!(m0.find(Namespace::Geom, "floor").is_none()); // the old value is unchanged
/// assert!(m1.find(Namespace::Geom, "floor").is_some());
/// # Ok::<(), mjcf::EditError>(())
/// ```
///
/// A model read from MJCF keeps the text it was read from (its files, and where each
/// element's tags are in them), for [`Model::save`]; every later version keeps it.
/// Formatting is not content: `==`, [`Hash`] and [`Model::diff`] ignore it, so a model
/// read and the same model built through the API are equal.
#[derive(Clone)]
pub struct Model {
    pub(crate) root: Node,
    pub(crate) index: Index,
    pub(crate) files: Arc<FileContext>,
    /// The text read and the automatic-name count, shared by the versions made from
    /// one another.
    pub(crate) side: Arc<Side>,
}

/// What a model value carries beside its tree and index, kept behind one pointer so
/// that a model (held by value in each of its attachments) stays small.
#[derive(Default)]
pub(crate) struct Side {
    /// The text read (`xml::source`); `None` for a model built through the API.
    pub(crate) source: Option<Arc<source::Source>>,
    /// The automatic-name positions of the last version counted
    /// ([`Model::auto_positions`]).
    pub(crate) auto: cursor::AutoCache,
}

/// Points at one element of a model, across versions.
///
/// A `Loc` stays valid while the element exists: edits elsewhere, renames and moves of
/// its siblings do not change it. Taken from a model, it can be used with every later
/// version of that model.
///
/// An element inside an attachment (found as `robot/torso`) is located through the
/// frames of the attachments that lead to it; edits through such a locator copy the
/// path through those attachments.
#[derive(Clone)]
pub struct Loc {
    /// The frames leading to the element's model, outermost first (empty for this
    /// model's own elements).
    scope: Option<Arc<[ElementId]>>,
    id: ElementId,
    /// The name of the model the locator was taken from, for error messages only
    /// (not compared).
    origin: SmolStr,
}

impl PartialEq for Loc {
    fn eq(&self, other: &Loc) -> bool {
        self.id == other.id && self.scope() == other.scope()
    }
}

impl Eq for Loc {}

impl std::hash::Hash for Loc {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        self.id.hash(state);
        self.scope().hash(state);
    }
}

impl Loc {
    pub(crate) fn scoped(scope: Arc<[ElementId]>, id: ElementId, origin: &str) -> Loc {
        Loc { scope: if scope.is_empty() { None } else { Some(scope) }, id, origin: origin.into() }
    }

    /// The element's stable id.
    ///
    /// Time: O(1).
    pub fn id(&self) -> ElementId {
        self.id
    }

    /// The attachment frames leading to the element, outermost first.
    pub(crate) fn scope(&self) -> &[ElementId] {
        self.scope.as_deref().unwrap_or(&[])
    }

    /// Whether the element lies inside an attachment.
    ///
    /// Time: O(1).
    pub fn is_scoped(&self) -> bool {
        self.scope.is_some()
    }
}

impl fmt::Debug for Loc {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Loc(")?;
        for s in self.scope() {
            write!(f, "{s:?}/")?;
        }
        write!(f, "{:?})", self.id)
    }
}

/// The shared empty model every `Model::new` starts from.
fn template() -> &'static (Node, Index) {
    static TEMPLATE: OnceLock<(Node, Index)> = OnceLock::new();
    TEMPLATE.get_or_init(|| {
        let root = empty_node(ElementKind::ROOT);
        let mut index = Index::default();
        // A fresh tree has no identifiers, so this cannot find a duplicate.
        let _ = index.insert_subtree(None, &root, 0);
        (root, index)
    })
}

/// The name of a model without one, as in the reference.
pub(crate) const UNNAMED: &str = "unnamed_model";

/// Refuses a model name with a character XML cannot hold (NUL, other C0 controls,
/// U+FFFE, U+FFFF), which no written model could carry.
pub(crate) fn check_model_name(name: &str) -> Result<(), ErrorKind> {
    match name.chars().find(|c| !crate::value::is_xml_char(*c)) {
        Some(c) => Err(ErrorKind::InvalidValue {
            tag: "mujoco",
            attribute: "model",
            value: build::cut(name),
            error: crate::error::ValueError::InvalidCharacter(c),
        }),
        None => Ok(()),
    }
}

impl Model {
    /// A new, empty model. An empty name becomes `unnamed_model`, as in the reference.
    ///
    /// The name is taken as given: one with a character XML cannot hold (such as NUL)
    /// makes writing the model fail with
    /// [`WriteError::InvalidCharacter`](crate::WriteError::InvalidCharacter) (never a
    /// panic). [`Model::try_new`] refuses such a name at once; use it for names that
    /// come from outside the program.
    ///
    /// Time: O(1) (every new model shares one empty tree).
    ///
    /// # Examples
    /// ```
    /// use mjcf::Model;
    /// let m = Model::new("arena");
    /// assert_eq!(m.name(), "arena");
    /// assert_eq!(Model::new("").name(), "unnamed_model");
    /// assert!(m.to_xml_string()?.starts_with(r#"<mujoco model="arena">"#));
    /// # Ok::<(), mjcf::WriteError>(())
    /// ```
    pub fn new(name: &str) -> Model {
        let (root, index) = template().clone();
        let (files, side) = (Arc::new(FileContext::default()), Arc::default());
        let m = Model { root, index, files, side };
        m.with_name(name)
    }

    /// [`Model::new`], refusing a name with a character XML cannot hold (NUL, other C0
    /// controls, U+FFFE, U+FFFF).
    ///
    /// Time: O(length of the name).
    ///
    /// # Errors
    /// [`ErrorKind::InvalidValue`] with
    /// [`ValueError::InvalidCharacter`](crate::ValueError::InvalidCharacter) (at the
    /// root, path `""`).
    ///
    /// # Examples
    /// ```
    /// assert_eq!(mjcf::Model::try_new("arm").unwrap().name(), "arm");
    /// assert!(mjcf::Model::try_new("a\0b").is_err());
    /// ```
    pub fn try_new(name: &str) -> Result<Model, EditError> {
        check_model_name(name).map_err(|k| EditError::new(k, String::new()))?;
        Ok(Model::new(name))
    }

    pub(crate) fn from_parts(root: Node, index: Index, files: FileContext) -> Model {
        Model { root, index, files: Arc::new(files), side: Arc::default() }
    }

    /// The same model with the source `source` (the reader's).
    pub(crate) fn with_source(&self, source: Option<Arc<source::Source>>) -> Model {
        let side = Arc::new(Side { source, auto: Default::default() });
        Model { side, ..self.clone() }
    }

    /// The next version of this model: `root` and `index` after an edit (`index`
    /// starts as a copy of this model's). The one place that decides whether the
    /// merged-settings memo survives: only when every global settings section is
    /// the same node and the attachments are the same. (An edit inside an
    /// attachment that gives it another memo resets ours before: `in_scope`. The
    /// in-place edits, `attach_here` and `insert_here`, decide it themselves.)
    pub(crate) fn next(&self, root: Node, mut index: Index) -> Model {
        let settings_same = {
            let old = self.root.children().iter();
            let new = root.children().iter();
            old.zip(new)
                .take_while(|(o, _)| o.kind().multiplicity() == Multiplicity::Singleton)
                .filter(|(o, _)| settings::is_settings_section(o.kind()))
                .all(|(o, n)| o.ptr_eq(n))
        };
        let memo_same = index.merged.same(&self.index.merged);
        if !(settings_same && memo_same && index.scopes.same(&self.index.scopes)) {
            index.merged = MergedCache::default();
        }
        let (files, side) = (self.files.clone(), self.side.clone());
        Model { root, index, files, side }
    }

    /// The model's name: its `model` attribute (`unnamed_model` if it has none, as in
    /// the reference), unless `include_copy` replaced that attribute, which does not
    /// rename the model.
    ///
    /// Time: O(1).
    pub fn name(&self) -> &str {
        match self.index.own_name.as_deref() {
            Some(n) => n,
            None => self
                .root_attr("model")
                .and_then(Value::as_str)
                .filter(|n| !n.is_empty())
                .unwrap_or(UNNAMED),
        }
    }

    /// The model with another name (its `model` attribute). An empty name becomes
    /// `unnamed_model`. The name is taken as given, as in [`Model::new`];
    /// [`Model::try_with_name`] refuses characters XML cannot hold.
    ///
    /// Time: O(1).
    #[must_use]
    pub fn with_name(&self, name: &str) -> Model {
        let Some(i) = ElementKind::ROOT.attr_index("model") else { return self.clone() };
        let mut attrs = self.root.attrs().to_vec();
        attrs.retain(|(k, _)| *k as usize != i);
        attrs.push((i as u16, Value::String(if name.is_empty() { UNNAMED } else { name }.into())));
        let mut index = self.index.clone();
        index.own_name = None;
        self.next(self.root.with_attrs(attrs), index)
    }

    /// [`Model::with_name`], refusing a name with a character XML cannot hold (NUL,
    /// other C0 controls, U+FFFE, U+FFFF).
    ///
    /// Time: O(length of the name + number of root attributes).
    ///
    /// # Errors
    /// [`ErrorKind::InvalidValue`] with
    /// [`ValueError::InvalidCharacter`](crate::ValueError::InvalidCharacter) (at the
    /// root, path `""`); `self` is unchanged.
    pub fn try_with_name(&self, name: &str) -> Result<Model, EditError> {
        check_model_name(name).map_err(|k| EditError::new(k, String::new()))?;
        Ok(self.with_name(name))
    }

    fn root_attr(&self, name: &str) -> Option<&Value> {
        self.root.attr(ElementKind::ROOT.attr_index(name)?)
    }

    /// The model whose relative file paths (in attributes set later) resolve against
    /// `dir`. Models read from a file start with that file's folder.
    ///
    /// Time: O(1).
    #[must_use]
    pub fn with_base_dir(&self, dir: impl Into<PathBuf>) -> Model {
        let mut files = FileContext::clone(&self.files);
        files.base_dir = Some(dir.into());
        Model { files: Arc::new(files), ..self.clone() }
    }

    /// The `<mujoco>` element.
    ///
    /// Time: O(1).
    pub fn root(&self) -> Loc {
        self.scoped_loc(&[], self.root.id())
    }

    /// The top-level section with this tag (`"worldbody"`, `"asset"`, `"option"`, ...),
    /// or `None` if the schema has no such section.
    ///
    /// Time: O(1) (a scan of the schema's fixed list of sections).
    pub fn section(&self, tag: &str) -> Option<Loc> {
        let kind = ElementKind::ROOT.child(tag)?;
        self.root.child_of_kind(kind).map(|n| self.scoped_loc(&[], n.id()))
    }

    pub(crate) fn must_section(&self, tag: &str) -> Loc {
        // Every section is a singleton, created with the model and never removed.
        self.section(tag).unwrap_or_else(|| self.root())
    }

    /// The `<worldbody>`.
    ///
    /// Time: O(1).
    pub fn worldbody(&self) -> Loc {
        self.must_section("worldbody")
    }

    /// The `<asset>` section.
    ///
    /// Time: O(1).
    pub fn asset(&self) -> Loc {
        self.must_section("asset")
    }

    /// The `<actuator>` section.
    ///
    /// Time: O(1).
    pub fn actuator(&self) -> Loc {
        self.must_section("actuator")
    }

    /// The `<sensor>` section.
    ///
    /// Time: O(1).
    pub fn sensor(&self) -> Loc {
        self.must_section("sensor")
    }

    /// The root default class (`<default>`).
    ///
    /// Time: O(1).
    pub fn default_class(&self) -> Loc {
        self.must_section("default")
    }

    /// The node with this id in this model's own tree.
    pub(crate) fn node_by_id(&self, id: ElementId) -> Option<&Node> {
        let path = self.path_of(id)?;
        self.node_at(&path)
    }

    /// Finds the element with this identifier in `namespace`.
    ///
    /// An identifier with `/` looks inside attachments: `robot/torso` is `torso` in the
    /// model attached as `robot`, `arena/robot_1/hip` goes two levels down. In
    /// [`Namespace::AttachmentFrame`], `robot` finds the frame of that attachment.
    /// Joints on attachment frames are not found by name (their names are unique per
    /// frame only); [`Model::find_all`] lists them.
    ///
    /// Time: O(log n) for a name of this model, O(levels · depth · log n) for one with
    /// a scope path, a hit or a miss alike (a miss makes no suggestions; see
    /// [`Model::lookup`] for those).
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, Namespace, element};
    /// let mut arena = Model::new("arena");
    /// let floor = arena.add_mut(&arena.worldbody(), element!("geom", name = "floor", type = "plane"))?;
    /// assert_eq!(arena.find(Namespace::Geom, "floor"), Some(floor));
    /// assert_eq!(arena.find(Namespace::Body, "floor"), None); // another namespace
    ///
    /// let mut robot = Model::new("robot");
    /// let torso = robot.add_mut(&robot.worldbody(), element!("body", name = "torso"))?;
    /// arena.attach_mut(&arena.worldbody(), &robot)?;
    /// let found = arena.find(Namespace::Body, "robot/torso").unwrap();
    /// assert_eq!(found.id(), torso.id()); // the same element, seen through the attachment
    /// assert!(found.is_scoped());
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn find(&self, namespace: Namespace, identifier: &str) -> Option<Loc> {
        self.resolve(namespace, identifier).ok()?.ok()
    }

    /// [`Model::find`] that explains a miss: the error names the namespace, the
    /// identifier, the scope it was looked for in and the nearest existing names
    /// there ("did you mean").
    ///
    /// Time: O(log n) for a name of this model, O(levels · depth · log n) for one with
    /// a scope path; a miss also ranks the `c` names of that namespace in the model
    /// looked in for suggestions, O(c log c), and compares the name with at most 16
    /// of them (those next to it in alphabetical order, of the texts and of the
    /// texts reversed).
    ///
    /// # Errors
    /// [`ErrorKind::UnknownName`] when nothing has that name;
    /// [`ErrorKind::InvalidScope`] when the scope part of the identifier is malformed
    /// (`/torso`, `robot//torso`); [`ErrorKind::NotAttached`] when it names no
    /// attachment.
    ///
    /// # Examples
    /// ```
    /// use mjcf::{Model, Namespace, element};
    /// let mut m = Model::new("m");
    /// m.add_mut(&m.worldbody(), element!("body", name = "torso"))?;
    /// let e = m.lookup(Namespace::Body, "torsoo").unwrap_err();
    /// assert_eq!(e.to_string(), "no body named 'torsoo' (did you mean 'torso'?) at <mujoco>");
    /// # Ok::<(), mjcf::EditError>(())
    /// ```
    pub fn lookup(&self, namespace: Namespace, identifier: &str) -> Result<Loc, EditError> {
        let (m, scope, rest) = match self.resolve(namespace, identifier)? {
            Ok(loc) => return Ok(loc),
            Err(miss) => miss,
        };
        let candidates: Vec<&str> = if namespace == Namespace::AttachmentFrame {
            m.index.attachments().map(|(s, _)| s.as_str()).collect()
        } else {
            m.index
                .names
                .keys()
                .filter(|(ns, _)| *ns == namespace)
                .map(|(_, n)| n.as_str())
                .collect()
        };
        let suggestions =
            crate::suggest::nearest(rest, candidates, 3).into_iter().map(SmolStr::from).collect();
        Err(EditError::new(
            ErrorKind::UnknownName {
                namespace,
                name: rest.into(),
                scope: scope.into(),
                suggestions,
            },
            String::new(),
        ))
    }

    /// The element named `identifier`, or where the search stopped: the model, the
    /// scope path looked in and the part of the name not found there. At each level
    /// a literal name comes first (a model read from a file may hold `robot/torso` as
    /// one name), then the first segment as an attachment's scope.
    #[allow(clippy::type_complexity)]
    fn resolve<'a, 'i>(
        &'a self,
        namespace: Namespace,
        identifier: &'i str,
    ) -> Result<Result<Loc, (&'a Model, &'i str, &'i str)>, EditError> {
        let own = |m: &Model, name: &str| {
            if namespace == Namespace::AttachmentFrame {
                m.index.frame_of(name)
            } else {
                m.index.names.get(&(namespace, SmolStr::from(name))).copied()
            }
        };
        let mut m = self;
        let mut frames: Vec<ElementId> = Vec::new();
        let mut rest = identifier;
        loop {
            // A literal name with a `/` is looked for only where the model holds one
            // starting with the same segment: hashing the whole rest at each level
            // was quadratic in the levels of a scoped name.
            let literal =
                index::slashed_segment(rest).is_none_or(|s| m.index.slashed.contains_key(s));
            if let Some(id) = literal.then(|| own(m, rest)).flatten() {
                return Ok(Ok(self.scoped_loc(&frames, id)));
            }
            let Some((scope, tail)) = rest.split_once('/') else { break };
            if frames.is_empty() {
                scope::check_scope_path(identifier)?;
            }
            let Some(frame) = m.index.frame_of(scope) else {
                if m.index.scopes.is_empty() {
                    break; // a misspelt literal name
                }
                let upto = identifier.len() - tail.len() - 1;
                return Err(scope::not_attached(m, &identifier[..upto]));
            };
            frames.push(frame);
            m = &m
                .node_by_id(frame)
                .and_then(Node::attached)
                .ok_or_else(|| self.stale_id(frame))?
                .model;
            rest = tail;
        }
        let scope = &identifier[..identifier.len() - rest.len()];
        Ok(Err((m, scope.strip_suffix('/').unwrap_or(scope), rest)))
    }

    /// Whether both values share the same tree.
    ///
    /// Time: O(1).
    pub fn ptr_eq(&self, other: &Model) -> bool {
        self.root.ptr_eq(&other.root)
    }

    /// Child indices from the root to the element, or `None` if it does not exist.
    pub(crate) fn path_of(&self, id: ElementId) -> Option<Vec<usize>> {
        // The ancestry, nearest first: the nearest `NEAR` on the stack (most paths
        // entirely: no allocation but the path's), any farther in a list.
        const NEAR: usize = 24;
        let mut near = [None; NEAR];
        let (mut far, mut depth) = (Vec::new(), 0);
        self.index.ancestry(id, |id, hint, ord| {
            match near.get_mut(depth) {
                Some(slot) => *slot = Some((id, hint, ord)),
                None => far.push((id, hint, ord)),
            }
            depth += 1;
        })?;
        let near = near.iter().take(depth).flatten();
        let mut down = far.iter().rev().chain(near.rev());
        let mut node = &self.root;
        if down.next()?.0 != node.id() {
            return None;
        }
        let mut path = Vec::with_capacity(depth - 1);
        for &(id, hint, ord) in down {
            let i = node.child_position(id, ord, hint)?;
            path.push(i);
            node = node.children().get(i)?;
        }
        Some(path)
    }

    pub(crate) fn node_at(&self, path: &[usize]) -> Option<&Node> {
        let mut node = &self.root;
        for &i in path {
            node = node.children().get(i)?;
        }
        Some(node)
    }

    /// The node at `path`, mutable, for an in-place edit: each node on the path that
    /// another version shares is copied first (path copying, done only where needed),
    /// so a model built by in-place edits reuses the nodes it owns alone.
    pub(crate) fn node_at_mut(&mut self, path: &[usize]) -> Option<&mut tree::NodeData> {
        let mut node = &mut self.root;
        for &i in path {
            node = node.make_mut().children.get_mut(i)?;
        }
        Some(node.make_mut())
    }

    /// The element path used in error messages: `worldbody/body[name=torso]/geom[2]`.
    pub(crate) fn describe(&self, path: &[usize]) -> String {
        let mut out = String::new();
        let mut node = &self.root;
        for &i in path {
            let Some(child) = node.children().get(i) else { break };
            let kind = child.kind();
            match (child.identifier(), kind.multiplicity()) {
                (Some(name), _) => build::push_segment(&mut out, kind.tag(), Some(name)),
                (None, Multiplicity::Repeated) => {
                    let n = node.children().iter().take(i).filter(|c| c.kind() == kind).count();
                    build::push_segment(&mut out, kind.tag(), None);
                    out.push_str(&format!("[{n}]"));
                }
                (None, _) => build::push_segment(&mut out, kind.tag(), None),
            }
            node = child;
        }
        out
    }

    /// The path of `loc`'s element in this model's own tree.
    fn locate(&self, loc: &Loc) -> Result<Vec<usize>, EditError> {
        self.path_of(loc.id).ok_or_else(|| self.stale(loc))
    }

    /// The error for a frame id that names nothing here.
    fn stale_id(&self, id: ElementId) -> EditError {
        EditError::new(ErrorKind::StaleLocator { id, origin: self.name().into() }, String::new())
    }

    /// The error for a locator that names nothing here.
    pub(crate) fn stale(&self, loc: &Loc) -> EditError {
        let origin =
            if loc.origin.is_empty() { SmolStr::from(self.name()) } else { loc.origin.clone() };
        EditError::new(ErrorKind::StaleLocator { id: loc.id, origin }, String::new())
    }

    /// The compiler's folder settings.
    pub(crate) fn basepaths(&self) -> Basepaths {
        let mut b = Basepaths::default();
        let Some(compiler) = self.root.child_of_kind(ElementKind::COMPILER) else { return b };
        for (i, v) in compiler.attrs() {
            if let (AttrType::Basepath { path_namespace }, Value::Basepath(p)) =
                (ElementKind::COMPILER.attr(*i as usize).ty, v)
            {
                b.set(path_namespace, Some(p.clone()));
            }
        }
        b
    }
}

impl PartialEq for Model {
    /// Content equality, however and wherever the two models were built: the same
    /// name, tree (kinds, attributes, children in order) and attachments (scope names,
    /// attach order, attached models, recursively). Element ids are not compared, but
    /// resolved references must point at corresponding elements (a dead reference
    /// matches only a dead one). Floats compare as the writer writes them: by their
    /// bits, every NaN being one value (two versions that set the same NaN are
    /// equal; `0` and `-0` differ), as [`Value`]'s equality, [`Hash`] and
    /// [`Model::diff`] do.
    ///
    /// Time: proportional to what differs for versions of one model (shared subtrees
    /// are skipped unexamined); O(n) for models built separately (`model/eq.rs`).
    fn eq(&self, other: &Model) -> bool {
        eq::equal(self, other)
    }
}

/// Content equality is an equivalence: every value equals itself (NaN included).
impl Eq for Model {}

impl std::hash::Hash for Model {
    /// A hash of the content, consistent with `==` (equal models hash alike): the
    /// name, the tree, the attachments (scope names and attached models), floats by
    /// their bits with every NaN one value. Resolved references count without their
    /// targets and the attach order is left out, so models that differ only there
    /// hash alike (and compare unequal). Not cached: each call walks the model.
    ///
    /// Time: O(n) for the n elements of the distinct model values of the composition
    /// (each attached value once, however often it is attached).
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        state.write_u64(eq::content_hash(self));
    }
}

impl fmt::Debug for Model {
    /// `Model { name, elements }`; the alternate form (`{:#?}`, what proptest prints
    /// for a failing input) is the model's MJCF text ([`Model::to_xml_string`]), after
    /// a line with its name and size.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if f.alternate() {
            if let Ok(xml) = self.to_xml_string() {
                let n = self.index.len();
                return write!(
                    f,
                    "Model {:?} ({n} elements), as MJCF:\n{}",
                    self.name(),
                    xml.trim_end()
                );
            }
        }
        f.debug_struct("Model")
            .field("name", &self.name())
            .field("elements", &self.index.len())
            .finish()
    }
}

#[cfg(test)]
mod handle_tests;
#[cfg(test)]
mod tests;
