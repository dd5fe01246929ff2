//! [`Model`]: one MJCF model as an immutable value, with its identifier index.
//!
//! Every edit returns a new `Model` and leaves the old one as it was; the two share
//! every subtree the edit did not touch. Elements are named by a [`Loc`], which keeps
//! pointing at the same element across versions (it holds the element's stable id).

mod build;
pub(crate) mod diff;
mod eq;
mod index;

use std::fmt;
use std::path::PathBuf;
use std::sync::{Arc, OnceLock};

use smol_str::SmolStr;

use crate::error::{EditError, ErrorKind};
use crate::files::FileContext;
use crate::schema::{AttrType, ElementKind, Multiplicity, Namespace};
use crate::tree::{ElementId, Node};
use crate::value::{AttrInput, Value};

pub(crate) use build::push_segment as push_path;
pub use build::{Attrs, Element};
pub(crate) use build::{
    Basepaths, ValueCtx, apply_attrs, check_class_named, check_required, cut, empty_node, name_from_file,
};
pub(crate) use index::{Index, MergedCache};

/// An MJCF model: a `<mujoco>` tree as a persistent value.
///
/// Cloning is O(1) and the clone shares everything. `Model` is `Send + Sync`, so
/// versions can be shared across threads freely.
///
/// # Examples
/// ```
/// use mjcf::{Element, Model, Namespace};
/// let m0 = Model::new("arena");
/// let (m1, _) = m0
///     .add(&m0.worldbody(), Element::new("geom").attr("name", "floor").attr("type", "plane"))
///     .unwrap();
/// assert!(m0.find(Namespace::Geom, "floor").is_none()); // the old value is unchanged
/// assert!(m1.find(Namespace::Geom, "floor").is_some());
/// ```
#[derive(Clone)]
pub struct Model {
    pub(crate) root: Node,
    pub(crate) index: Index,
    pub(crate) files: Arc<FileContext>,
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
#[derive(Clone, PartialEq, Eq, Hash)]
pub struct Loc {
    /// The frames leading to the element's model, outermost first (empty for this
    /// model's own elements).
    scope: Option<Arc<[ElementId]>>,
    id: ElementId,
}

impl Loc {
    pub(crate) fn new(id: ElementId) -> Loc {
        Loc { scope: None, id }
    }

    pub(crate) fn scoped(scope: Arc<[ElementId]>, id: ElementId) -> Loc {
        Loc { scope: if scope.is_empty() { None } else { Some(scope) }, id }
    }

    /// The element's stable id.
    pub fn id(&self) -> ElementId {
        self.id
    }

    /// The attachment frames leading to the element, outermost first.
    pub(crate) fn scope(&self) -> &[ElementId] {
        self.scope.as_deref().unwrap_or(&[])
    }

    /// Whether the element lies inside an attachment.
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

impl Model {
    /// A new, empty model. An empty name becomes `unnamed_model`, as in the reference.
    ///
    /// Time: O(1) (every new model shares one empty tree).
    pub fn new(name: &str) -> Model {
        let (root, index) = template().clone();
        let m = Model { root, index, files: Arc::new(FileContext::default()) };
        m.with_name(name)
    }

    pub(crate) fn from_parts(root: Node, index: Index, files: FileContext) -> Model {
        Model { root, index, files: Arc::new(files) }
    }

    /// The model's name: its `model` attribute (`unnamed_model` if it has none, as in
    /// the reference), unless `include_copy` replaced that attribute, which does not
    /// rename the model.
    pub fn name(&self) -> &str {
        match &self.index.own_name {
            Some(n) => n,
            None => self.root_attr("model").and_then(Value::as_str).filter(|n| !n.is_empty()).unwrap_or(UNNAMED),
        }
    }

    /// The model with another name (its `model` attribute). An empty name becomes
    /// `unnamed_model`.
    #[must_use]
    pub fn with_name(&self, name: &str) -> Model {
        let Some(i) = ElementKind::ROOT.attr_index("model") else { return self.clone() };
        let mut attrs = self.root.attrs().to_vec();
        attrs.retain(|(k, _)| *k as usize != i);
        attrs.push((i as u16, Value::String(if name.is_empty() { UNNAMED } else { name }.into())));
        let mut index = self.index.clone();
        index.own_name = None;
        Model { root: self.root.with_attrs(attrs), index, files: self.files.clone() }
    }

    fn root_attr(&self, name: &str) -> Option<&Value> {
        self.root.attr(ElementKind::ROOT.attr_index(name)?)
    }

    /// The model whose relative file paths (in attributes set later) resolve against
    /// `dir`. Models read from a file start with that file's folder.
    #[must_use]
    pub fn with_base_dir(&self, dir: impl Into<PathBuf>) -> Model {
        let mut files = FileContext::clone(&self.files);
        files.base_dir = Some(dir.into());
        Model { files: Arc::new(files), ..self.clone() }
    }

    /// The `<mujoco>` element.
    pub fn root(&self) -> Loc {
        Loc::new(self.root.id())
    }

    /// The top-level section with this tag (`"worldbody"`, `"asset"`, `"option"`, ...).
    pub fn section(&self, tag: &str) -> Option<Loc> {
        let kind = ElementKind::ROOT.child(tag)?;
        self.root.child_of_kind(kind).map(|n| Loc::new(n.id()))
    }

    fn must_section(&self, tag: &str) -> Loc {
        // Every section is a singleton, created with the model and never removed.
        self.section(tag).unwrap_or_else(|| self.root())
    }

    /// The `<worldbody>`.
    pub fn worldbody(&self) -> Loc {
        self.must_section("worldbody")
    }

    /// The `<asset>` section.
    pub fn asset(&self) -> Loc {
        self.must_section("asset")
    }

    /// The `<actuator>` section.
    pub fn actuator(&self) -> Loc {
        self.must_section("actuator")
    }

    /// The `<sensor>` section.
    pub fn sensor(&self) -> Loc {
        self.must_section("sensor")
    }

    /// The root default class (`<default>`).
    pub fn default_class(&self) -> Loc {
        self.must_section("default")
    }

    /// The element at `loc`, if it exists in this version.
    pub fn element(&self, loc: &Loc) -> Option<ElementRef<'_>> {
        let m = self.scoped_model(loc.scope())?;
        let path = m.path_of(loc.id)?;
        let mut node = &m.root;
        for i in path {
            node = node.children().get(i)?;
        }
        Some(ElementRef { node })
    }

    /// The model attached along `frames` (this model if empty).
    pub(crate) fn scoped_model(&self, frames: &[ElementId]) -> Option<&Model> {
        let mut m = self;
        for f in frames {
            m = &m.node_by_id(*f)?.attached()?.model;
        }
        Some(m)
    }

    /// The node with this id in this model's own tree.
    pub(crate) fn node_by_id(&self, id: ElementId) -> Option<&Node> {
        let path = self.path_of(id)?;
        self.node_at(&path)
    }

    /// Finds the element with this identifier in `namespace`.
    ///
    /// Time: O(log n).
    ///
    /// An identifier with `/` looks inside attachments: `robot/torso` is `torso` in the
    /// model attached as `robot`, `arena/robot_1/hip` goes two levels down. In
    /// [`Namespace::AttachmentFrame`], `robot` finds the frame of that attachment.
    /// Joints on attachment frames are not found by name (their names are unique per
    /// frame only); [`Model::find_all`] lists them.
    pub fn find(&self, namespace: Namespace, identifier: &str) -> Option<Loc> {
        let mut m = self;
        let mut frames: Vec<ElementId> = Vec::new();
        let mut rest = identifier;
        loop {
            match rest.split_once('/') {
                Some((scope, tail)) => {
                    let frame = m.index.frame_of(scope)?;
                    frames.push(frame);
                    m = &m.node_by_id(frame)?.attached()?.model;
                    rest = tail;
                }
                None => {
                    let id = if namespace == Namespace::AttachmentFrame {
                        m.index.frame_of(rest)?
                    } else {
                        *m.index.names.get(&(namespace, SmolStr::from(rest)))?
                    };
                    return Some(Loc::scoped(frames.into(), id));
                }
            }
        }
    }

    /// Every element of `namespace`, in the reference's order: depth first through
    /// this model's own tree, where a frame (which counts as a body) is followed by
    /// its own joints and then the content of the model it holds, and each section is
    /// followed by the same section of each attachment, in attach order.
    ///
    /// Time: O(n) in the size of the composed model.
    pub fn find_all(&self, namespace: Namespace) -> Vec<Loc> {
        let mut out = Vec::new();
        if namespace == Namespace::AttachmentFrame {
            return out;
        }
        // (model, frames leading to it, node, whether to follow the section's
        // attachments after the node's own subtree)
        enum Step<'a> {
            Node(&'a Model, Arc<[ElementId]>, &'a Node),
            Sections(&'a Model, Arc<[ElementId]>, ElementKind),
        }
        let mut stack: Vec<Step<'_>> = Vec::new();
        for section in self.root.children().iter().rev() {
            stack.push(Step::Sections(self, Arc::from([]), section.kind()));
            stack.push(Step::Node(self, Arc::from([]), section));
        }
        while let Some(step) = stack.pop() {
            match step {
                Step::Node(m, scope, n) => {
                    if n.kind().namespace() == Some(namespace) {
                        out.push(Loc::scoped(scope.clone(), n.id()));
                    }
                    if let Some(a) = n.attached() {
                        let mut inner: Vec<ElementId> = scope.to_vec();
                        inner.push(n.id());
                        let inner: Arc<[ElementId]> = inner.into();
                        if let Some(wb) = a
                            .model
                            .root
                            .child_of_kind(a.model.root.kind().child("worldbody").unwrap_or(ElementKind::ROOT))
                        {
                            for c in wb.children().iter().rev() {
                                stack.push(Step::Node(&a.model, inner.clone(), c));
                            }
                        }
                    }
                    for c in n.children().iter().rev() {
                        stack.push(Step::Node(m, scope.clone(), c));
                    }
                }
                Step::Sections(m, scope, kind) => {
                    if kind.tag() == "worldbody" {
                        continue;
                    }
                    // Each attachment's same section (its elements, then its own
                    // attachments' sections), in attach order.
                    for (_, frame) in m.index.scopes.iter().rev() {
                        let Some(a) = m.node_by_id(frame).and_then(Node::attached) else { continue };
                        let mut inner: Vec<ElementId> = scope.to_vec();
                        inner.push(frame);
                        let inner: Arc<[ElementId]> = inner.into();
                        if let Some(sec) = a.model.root.child_of_kind(kind) {
                            stack.push(Step::Sections(&a.model, inner.clone(), kind));
                            if kind.tag() == "default" {
                                // The attachment's root class is a sibling class.
                                stack.push(Step::Node(&a.model, inner.clone(), sec));
                            } else {
                                for c in sec.children().iter().rev() {
                                    stack.push(Step::Node(&a.model, inner.clone(), c));
                                }
                            }
                        }
                    }
                }
            }
        }
        out
    }

    /// Whether both values share the same tree (O(1)).
    pub fn ptr_eq(&self, other: &Model) -> bool {
        self.root.ptr_eq(&other.root)
    }

    /// Child indices from the root to the element, or `None` if it does not exist.
    pub(crate) fn path_of(&self, id: ElementId) -> Option<Vec<usize>> {
        let ids = self.index.ancestry(id)?;
        let mut node = &self.root;
        let (first, rest) = ids.split_first()?;
        if first.0 != node.id() {
            return None;
        }
        let mut path = Vec::with_capacity(ids.len());
        for (id, hint) in rest {
            let i = node.child_position_near(*id, *hint)?;
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

    fn locate(&self, loc: &Loc) -> Result<Vec<usize>, EditError> {
        self.path_of(loc.id).ok_or_else(|| EditError::new(ErrorKind::NotFound, format!("{:?}", loc.id)))
    }

    /// The compiler's folder settings.
    pub(crate) fn basepaths(&self) -> Basepaths {
        let mut b = Basepaths::default();
        let Some(kind) = ElementKind::ROOT.child("compiler") else { return b };
        let Some(compiler) = self.root.child_of_kind(kind) else { return b };
        for (i, v) in compiler.attrs() {
            if let (AttrType::Basepath { path_namespace }, Value::Basepath(p)) = (kind.attr(*i as usize).ty, v) {
                b.set(path_namespace, Some(p.clone()));
            }
        }
        b
    }

    /// Adds `element` as the last child of `parent`; returns the new model and the new
    /// element's locator.
    ///
    /// Fails, leaving `self` unchanged, if the tag is not a valid child of the parent, an
    /// attribute is unknown or has a bad value, a required attribute is missing, a file
    /// cannot be read, or an identifier is taken.
    ///
    /// Time: O(depth · log width + size of the element).
    pub fn add(&self, parent: &Loc, element: Element) -> Result<(Model, Loc), EditError> {
        self.insert_at(parent, None, element)
    }

    /// Inserts `element` at `index` among the parent's repeated and on-demand children
    /// (singletons always come first and are not counted); an index past the end
    /// appends.
    pub fn insert(&self, parent: &Loc, index: usize, element: Element) -> Result<(Model, Loc), EditError> {
        self.insert_at(parent, Some(index), element)
    }

    fn insert_at(&self, parent: &Loc, index: Option<usize>, element: Element) -> Result<(Model, Loc), EditError> {
        let scope = parent.scope();
        let inner = Loc::new(parent.id());
        let (m, new) = self.in_scope(scope, &mut |m: &Model| m.insert_here(&inner, index, &element))?;
        Ok((m, new.within(scope)))
    }

    fn insert_here(&self, parent: &Loc, index: Option<usize>, element: &Element) -> Result<(Model, Loc), EditError> {
        let path = self.locate(parent)?;
        // The element path for errors, made only when there is one: the parent's path
        // (O(width) to describe) and the new element's own part.
        let mut sub = String::new();
        let at = |sub: &str| -> String {
            let outer = self.describe(&path);
            match (outer.is_empty(), sub.is_empty()) {
                (true, _) => sub.to_string(),
                (false, true) => outer,
                (false, false) => format!("{outer}/{sub}"),
            }
        };
        let parent_node = self.node_at(&path).cloned().ok_or_else(|| EditError::new(ErrorKind::NotFound, at("")))?;
        let basepaths = self.basepaths();
        let ctx = ValueCtx { files: &self.files, basepaths: &basepaths };
        let node =
            build::build(&ctx, parent_node.kind(), element, &mut sub).map_err(|k| EditError::new(k, at(&sub)))?;
        if parent_node.attached().is_some() {
            self.check_frame_child(&path, &parent_node, &node).map_err(|k| EditError::new(k, at(&sub)))?;
        }
        if node.kind().multiplicity() == Multiplicity::OnDemand
            && parent_node.children().iter().any(|c| c.kind() == node.kind())
        {
            return Err(EditError::new(ErrorKind::DuplicateChild(node.kind().tag()), at(&sub)));
        }
        let children = parent_node.children();
        let singletons = children.iter().take_while(|c| c.kind().multiplicity() == Multiplicity::Singleton).count();
        let position = match index {
            Some(i) => (singletons + i).min(children.len()),
            None => children.len(),
        };
        let mut index_ = self.index.clone();
        if let Err(d) = index_.insert_subtree(Some(parent_node.id()), &node, position) {
            return Err(EditError::new(
                ErrorKind::DuplicateIdentifier { namespace: d.namespace, name: d.name },
                at(&sub),
            ));
        }
        if self.may_change_settings(&path) {
            index_.merged = MergedCache::default();
        }
        let id = node.id();
        let root = self.root.update_path(&path, |p| -> Result<Node, EditError> {
            let mut children = p.children().clone();
            children.insert(position.min(children.len()), node);
            Ok(p.with_children(children))
        })?;
        Ok((Model { root, index: index_, files: self.files.clone() }, Loc::new(id)))
    }

    /// Sets and clears attributes of the element at `loc`, all or nothing.
    ///
    /// Time: O(depth · log width).
    pub fn set(&self, loc: &Loc, attrs: Attrs) -> Result<Model, EditError> {
        let inner = Loc::new(loc.id());
        let (m, ()) = self.in_scope(loc.scope(), &mut |m: &Model| m.set_here(&inner, &attrs).map(|m| (m, ())))?;
        // An edit of a global setting, on either side of an attachment, may conflict;
        // no other edit takes part in the merge.
        if self.in_settings_section(loc) {
            crate::compose::settings::check(&m).map_err(|k| EditError::new(k, String::new()))?;
        }
        Ok(m)
    }

    /// Whether the element lies in a global settings section (`option`, ...).
    /// Whether an edit at `path` can change the merged settings: an edit of the root
    /// or inside a settings section.
    fn may_change_settings(&self, path: &[usize]) -> bool {
        match path.first() {
            None => true,
            Some(i) => {
                self.root.children().get(*i).is_some_and(|n| crate::compose::settings::is_settings_section(n.kind()))
            }
        }
    }

    fn in_settings_section(&self, loc: &Loc) -> bool {
        let Some(m) = self.scoped_model(loc.scope()) else { return false };
        let Some(section) = m.path_of(loc.id).and_then(|p| p.first().copied()) else { return false };
        m.root.children().get(section).is_some_and(|n| crate::compose::settings::is_settings_section(n.kind()))
    }

    fn set_here(&self, loc: &Loc, attrs: &Attrs) -> Result<Model, EditError> {
        let path = self.locate(loc)?;
        let err = |k: ErrorKind| EditError::new(k, self.describe(&path));
        let node = self.node_at(&path).ok_or_else(|| err(ErrorKind::NotFound))?;
        let kind = node.kind();
        let mut basepaths = self.basepaths();
        let mut changes = Vec::with_capacity(attrs.len());
        for (name, input) in attrs.items() {
            if node.attached().is_some() && !crate::compose::frame_settable(name) {
                return Err(err(ErrorKind::UnknownAttribute { tag: "body", attribute: name.clone() }));
            }
            let ctx = ValueCtx { files: &self.files, basepaths: &basepaths };
            let change = ctx.attr(kind, name, input.as_ref()).map_err(err)?;
            // A folder setting applies to file attributes set after it in the same call.
            if let AttrType::Basepath { path_namespace } = kind.attr(change.0).ty {
                basepaths.set(path_namespace, change.1.as_ref().and_then(Value::as_str).map(SmolStr::from));
            }
            changes.push(change);
        }
        let mut new_attrs = node.attrs().to_vec();
        apply_attrs(kind, &mut new_attrs, changes).map_err(err)?;
        if let Some(parent) = path.split_last().and_then(|(_, p)| self.node_at(p)) {
            check_class_named(parent.kind(), kind, &new_attrs).map_err(err)?;
        }
        let new_node = node.with_attrs(new_attrs);
        let mut index = self.index.clone();
        let old_name = node.identifier();
        let new_name = new_node.identifier();
        if old_name != new_name {
            if let (Some(ns), Some(name)) = (kind.namespace(), new_name) {
                // A frame's joints have a namespace of their own: that frame's joints.
                let frame = path.split_last().and_then(|(_, p)| self.node_at(p)).filter(|p| p.attached().is_some());
                let taken = match frame {
                    Some(f) => f.children().iter().any(|c| c.id() != node.id() && c.identifier() == Some(name)),
                    None => index.names.contains_key(&(ns, SmolStr::from(name))),
                };
                if taken {
                    return Err(err(ErrorKind::DuplicateIdentifier { namespace: ns, name: name.into() }));
                }
            }
            index.rename(node.id(), new_name.map(SmolStr::from));
        }
        if self.may_change_settings(&path) {
            index.merged = MergedCache::default();
        }
        let root = self.root.update_path(&path, |_| Ok::<_, EditError>(new_node))?;
        Ok(Model { root, index, files: self.files.clone() })
    }

    /// Checks a new child of an attachment frame: joints, one inertial, and one
    /// freejoint if the frame sits directly in the worldbody.
    fn check_frame_child(&self, path: &[usize], frame: &Node, child: &Node) -> Result<(), ErrorKind> {
        let tag = child.kind().tag();
        let invalid = || ErrorKind::InvalidChild { parent: "body", tag: tag.into() };
        // The frame's joints have a namespace of their own.
        if let (Some(ns), Some(name)) = (child.kind().namespace(), child.identifier()) {
            if frame.children().iter().any(|c| c.identifier() == Some(name)) {
                return Err(ErrorKind::DuplicateIdentifier { namespace: ns, name: name.into() });
            }
        }
        match tag {
            "joint" => Ok(()),
            "inertial" | "freejoint" => {
                if tag == "freejoint" {
                    let parent = path.split_last().and_then(|(_, p)| self.node_at(p));
                    if parent.is_none_or(|p| p.kind().tag() != "worldbody") {
                        return Err(invalid());
                    }
                }
                if frame.children().iter().any(|c| c.kind() == child.kind()) {
                    return Err(ErrorKind::DuplicateChild(child.kind().tag()));
                }
                Ok(())
            }
            _ => Err(invalid()),
        }
    }

    /// Sets one attribute.
    pub fn set_attr(&self, loc: &Loc, name: &str, value: impl Into<AttrInput>) -> Result<Model, EditError> {
        self.set(loc, Attrs::new().set(name, value))
    }

    /// Clears one attribute.
    pub fn clear_attr(&self, loc: &Loc, name: &str) -> Result<Model, EditError> {
        self.set(loc, Attrs::new().clear(name))
    }

    /// Removes the element at `loc` with its subtree. A singleton (such as `option`)
    /// stays but loses its attributes and children.
    ///
    /// References to removed elements that were resolved (read from XML) become dead:
    /// an optional one is no longer written, a required one makes writing fail. A
    /// reference held as a plain name is written as it is.
    ///
    /// Time: O(depth · log width + size of the subtree).
    ///
    /// # Errors
    /// [`ErrorKind::AffectsAttachments`] if the subtree holds an attachment frame, or
    /// the element is a global section (or part of one) while models are attached: use
    /// [`Model::detach`] first.
    pub fn remove(&self, loc: &Loc) -> Result<Model, EditError> {
        let inner = Loc::new(loc.id());
        let (m, ()) = self.in_scope(loc.scope(), &mut |m: &Model| m.remove_here(&inner, false).map(|m| (m, ())))?;
        Ok(m)
    }

    /// Removes the element at `loc` like [`Model::remove`], together with the
    /// attachments in its subtree (their frames go with it). A global section keeps
    /// merging the attachments' settings: only this model's own are cleared.
    pub fn remove_with_attachments(&self, loc: &Loc) -> Result<Model, EditError> {
        let inner = Loc::new(loc.id());
        let (m, ()) = self.in_scope(loc.scope(), &mut |m: &Model| m.remove_here(&inner, true).map(|m| (m, ())))?;
        Ok(m)
    }

    fn remove_here(&self, loc: &Loc, affect_attachments: bool) -> Result<Model, EditError> {
        let path = self.locate(loc)?;
        let node =
            self.node_at(&path).cloned().ok_or_else(|| EditError::new(ErrorKind::NotFound, self.describe(&path)))?;
        let in_section_chain = {
            let mut n = &self.root;
            path.iter().all(|&i| match n.children().get(i) {
                Some(c) => {
                    n = c;
                    c.kind().multiplicity() == Multiplicity::Singleton
                }
                None => false,
            })
        };
        let holds_frame = !self.index.scopes.is_empty() && node.descendants().any(|n| n.attached().is_some());
        if !affect_attachments
            && (holds_frame || (!self.index.scopes.is_empty() && in_section_chain && node.attached().is_none()))
        {
            return Err(EditError::new(ErrorKind::AffectsAttachments, self.describe(&path)));
        }
        let mut index = self.index.clone();
        index.remove_subtree(&node);
        if holds_frame || self.may_change_settings(&path) {
            index.merged = MergedCache::default();
        }
        let root = if path.is_empty() || node.kind().multiplicity() == Multiplicity::Singleton {
            let parent_id = self.index.elems.get(&node.id()).and_then(|e| e.parent);
            let fresh = Node::new(node.id(), node.kind(), Vec::new(), empty_node(node.kind()).children().clone());
            // The emptied element holds no identifiers, so this finds no duplicate.
            let _ = index.insert_subtree(parent_id, &fresh, path.last().copied().unwrap_or(0));
            self.root.update_path(&path, |_| Ok::<_, EditError>(fresh))?
        } else {
            let (last, parent_path) = match path.split_last() {
                Some((l, p)) => (*l, p),
                None => return Err(EditError::new(ErrorKind::NotFound, String::new())),
            };
            self.root.update_path(parent_path, |p| {
                let mut children = p.children().clone();
                children.remove(last);
                Ok::<_, EditError>(p.with_children(children))
            })?
        };
        Ok(Model { root, index, files: self.files.clone() })
    }
}

impl PartialEq for Model {
    /// Content equality, however and wherever the two models were built: the same
    /// name, tree (kinds, attributes, children in order) and attachments (scope names,
    /// attach order, attached models, recursively). Element ids are not compared, but
    /// resolved references must point at corresponding elements (a dead reference
    /// matches only a dead one).
    ///
    /// Time: proportional to what differs for versions of one model (shared subtrees
    /// are skipped unexamined); O(n) for models built separately (`model/eq.rs`).
    fn eq(&self, other: &Model) -> bool {
        eq::equal(self, other)
    }
}

impl fmt::Debug for Model {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Model").field("name", &self.name()).field("elements", &self.index.elems.len()).finish()
    }
}

/// A read-only view of one element of a model.
#[derive(Clone, Copy)]
pub struct ElementRef<'a> {
    node: &'a Node,
}

impl<'a> ElementRef<'a> {
    /// The element's locator.
    pub fn loc(&self) -> Loc {
        Loc::new(self.node.id())
    }

    /// The XML tag.
    pub fn tag(&self) -> &'static str {
        self.node.kind().tag()
    }

    /// The schema kind.
    pub fn kind(&self) -> ElementKind {
        self.node.kind()
    }

    /// The element's own identifier (no scope prefix), if set.
    pub fn identifier(&self) -> Option<&'a str> {
        self.node.identifier()
    }

    /// The value of attribute `name`, if set.
    pub fn attr(&self, name: &str) -> Option<&'a Value> {
        self.node.attr(self.node.kind().attr_index(name)?)
    }

    /// The set attributes, in schema order.
    pub fn attrs(&self) -> impl Iterator<Item = (&'static str, &'a Value)> + 'a {
        let kind = self.node.kind();
        self.node.attrs().iter().map(move |(i, v)| (kind.attr(*i as usize).name, v))
    }

    /// The child elements, in document order.
    pub fn children(&self) -> impl Iterator<Item = ElementRef<'a>> + 'a {
        self.node.children().iter().map(|node| ElementRef { node })
    }

    /// Whether two views show the same shared node (O(1)); after an edit, every
    /// element the edit did not touch is still the same node.
    pub fn ptr_eq(&self, other: &ElementRef<'_>) -> bool {
        self.node.ptr_eq(other.node)
    }
}

impl fmt::Debug for ElementRef<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(self.node, f)
    }
}

#[cfg(test)]
mod tests;
