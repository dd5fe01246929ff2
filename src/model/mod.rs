//! [`Model`]: one MJCF model as an immutable value, with its identifier index.
//!
//! Every edit returns a new `Model` and leaves the old one as it was; the two share
//! every subtree the edit did not touch. Elements are named by a [`Loc`], which keeps
//! pointing at the same element across versions (it holds the element's stable id).

mod build;
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
pub(crate) use build::{Basepaths, ValueCtx, apply_attrs, check_required, cut, empty_node, name_from_file};
pub(crate) use index::Index;

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
#[derive(Clone, PartialEq, Eq, Hash)]
pub struct Loc {
    id: ElementId,
}

impl Loc {
    pub(crate) fn new(id: ElementId) -> Loc {
        Loc { id }
    }

    /// The element's stable id.
    pub fn id(&self) -> ElementId {
        self.id
    }
}

impl fmt::Debug for Loc {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "Loc({:?})", self.id)
    }
}

/// The shared empty model every `Model::new` starts from.
fn template() -> &'static (Node, Index) {
    static TEMPLATE: OnceLock<(Node, Index)> = OnceLock::new();
    TEMPLATE.get_or_init(|| {
        let root = empty_node(ElementKind::ROOT);
        let mut index = Index::default();
        // A fresh tree has no identifiers, so this cannot find a duplicate.
        let _ = index.insert_subtree(None, &root);
        (root, index)
    })
}

impl Model {
    /// A new, empty model. An empty name becomes `unnamed_model`, as in the reference.
    ///
    /// Time: O(1) (every new model shares one empty tree).
    pub fn new(name: &str) -> Model {
        let (root, index) = template().clone();
        let m = Model { root, index, files: Arc::new(FileContext::default()) };
        m.with_name(if name.is_empty() { "unnamed_model" } else { name })
    }

    pub(crate) fn from_parts(root: Node, index: Index, files: FileContext) -> Model {
        Model { root, index, files: Arc::new(files) }
    }

    /// The model's name (its `model` attribute; empty if it has none).
    pub fn name(&self) -> &str {
        self.root_attr("model").and_then(Value::as_str).unwrap_or("")
    }

    /// The model with another name. An empty name removes the `model` attribute.
    #[must_use]
    pub fn with_name(&self, name: &str) -> Model {
        let Some(i) = ElementKind::ROOT.attr_index("model") else { return self.clone() };
        let mut attrs = self.root.attrs().to_vec();
        attrs.retain(|(k, _)| *k as usize != i);
        if !name.is_empty() {
            attrs.push((i as u16, Value::String(name.into())));
        }
        Model { root: self.root.with_attrs(attrs), ..self.clone() }
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
        let path = self.path_of(loc.id)?;
        let mut node = &self.root;
        for i in path {
            node = node.children().get(i)?;
        }
        Some(ElementRef { node })
    }

    /// Finds the element with this identifier in `namespace`.
    ///
    /// Time: O(log n).
    pub fn find(&self, namespace: Namespace, identifier: &str) -> Option<Loc> {
        self.index.names.get(&(namespace, SmolStr::from(identifier))).map(|id| Loc::new(*id))
    }

    /// Every element of `namespace`, in document order.
    ///
    /// Time: O(n).
    pub fn find_all(&self, namespace: Namespace) -> Vec<Loc> {
        self.root.descendants().filter(|n| n.kind().namespace() == Some(namespace)).map(|n| Loc::new(n.id())).collect()
    }

    /// Whether both values share the same tree (O(1)).
    pub fn ptr_eq(&self, other: &Model) -> bool {
        self.root.ptr_eq(&other.root)
    }

    /// Child indices from the root to the element, or `None` if it does not exist.
    pub(crate) fn path_of(&self, id: ElementId) -> Option<Vec<usize>> {
        let ids = self.index.ancestry(id)?;
        let mut node = &self.root;
        if ids.first() != Some(&node.id()) {
            return None;
        }
        let mut path = Vec::with_capacity(ids.len());
        for id in &ids[1..] {
            let i = node.child_position(*id)?;
            path.push(i);
            node = &node.children()[i];
        }
        Some(path)
    }

    fn node_at(&self, path: &[usize]) -> Option<&Node> {
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
        let path = self.locate(parent)?;
        let mut where_ = self.describe(&path);
        let parent_node =
            self.node_at(&path).cloned().ok_or_else(|| EditError::new(ErrorKind::NotFound, where_.clone()))?;
        let basepaths = self.basepaths();
        let ctx = ValueCtx { files: &self.files, basepaths: &basepaths };
        let node = build::build(&ctx, parent_node.kind(), &element, &mut where_)
            .map_err(|k| EditError::new(k, where_.clone()))?;
        if node.kind().multiplicity() == Multiplicity::OnDemand
            && parent_node.children().iter().any(|c| c.kind() == node.kind())
        {
            return Err(EditError::new(ErrorKind::DuplicateChild(node.kind().tag()), where_));
        }
        let mut index_ = self.index.clone();
        if let Err(d) = index_.insert_subtree(Some(parent_node.id()), &node) {
            return Err(EditError::new(
                ErrorKind::DuplicateIdentifier { namespace: d.namespace, name: d.name },
                where_,
            ));
        }
        let id = node.id();
        let root = self.root.update_path(&path, |p| -> Result<Node, EditError> {
            let mut children = p.children().clone();
            let singletons = children.iter().take_while(|c| c.kind().multiplicity() == Multiplicity::Singleton).count();
            let at = match index {
                Some(i) => (singletons + i).min(children.len()),
                None => children.len(),
            };
            children.insert(at, node);
            Ok(p.with_children(children))
        })?;
        Ok((Model { root, index: index_, files: self.files.clone() }, Loc::new(id)))
    }

    /// Sets and clears attributes of the element at `loc`, all or nothing.
    ///
    /// Time: O(depth · log width).
    pub fn set(&self, loc: &Loc, attrs: Attrs) -> Result<Model, EditError> {
        let path = self.locate(loc)?;
        let where_ = self.describe(&path);
        let err = |k: ErrorKind| EditError::new(k, where_.clone());
        let node = self.node_at(&path).ok_or_else(|| err(ErrorKind::NotFound))?;
        let kind = node.kind();
        let mut basepaths = self.basepaths();
        let mut changes = Vec::with_capacity(attrs.len());
        for (name, input) in attrs.items() {
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
        let new_node = node.with_attrs(new_attrs);
        let mut index = self.index.clone();
        let old_name = node.identifier();
        let new_name = new_node.identifier();
        if old_name != new_name {
            if let (Some(ns), Some(name)) = (kind.namespace(), new_name) {
                if index.names.contains_key(&(ns, SmolStr::from(name))) {
                    return Err(err(ErrorKind::DuplicateIdentifier { namespace: ns, name: name.into() }));
                }
            }
            index.rename(node.id(), new_name.map(SmolStr::from));
        }
        let root = self.root.update_path(&path, |_| Ok::<_, EditError>(new_node))?;
        Ok(Model { root, index, files: self.files.clone() })
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
    pub fn remove(&self, loc: &Loc) -> Result<Model, EditError> {
        let path = self.locate(loc)?;
        let node =
            self.node_at(&path).cloned().ok_or_else(|| EditError::new(ErrorKind::NotFound, self.describe(&path)))?;
        let mut index = self.index.clone();
        index.remove_subtree(&node);
        let root = if path.is_empty() || node.kind().multiplicity() == Multiplicity::Singleton {
            let parent_id = self.index.elems.get(&node.id()).and_then(|e| e.parent);
            let fresh = Node::new(node.id(), node.kind(), Vec::new(), empty_node(node.kind()).children().clone());
            // The emptied element holds no identifiers, so this finds no duplicate.
            let _ = index.insert_subtree(parent_id, &fresh);
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
    /// Two models are equal when their trees are (same elements with the same ids,
    /// attributes and children). Versions derived from each other compare in time
    /// proportional to what differs.
    fn eq(&self, other: &Model) -> bool {
        self.root == other.root
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
