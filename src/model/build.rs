//! Element builders and the checks that turn them into nodes.
//!
//! An [`Element`] is a plain description (tag, attributes, children) that collects
//! whatever the caller gives it; nothing is checked until the element is added to a
//! model, where every problem becomes one [`EditError`](crate::EditError) naming the
//! element's path. So builder calls chain without a `?` after each setter.

use crate::seq::Seq;
use smol_str::SmolStr;

use super::tree::{Attr, ElementId, Node};
use crate::error::{ErrorKind, ValueError};
pub(crate) use crate::files::Basepaths;
use crate::files::FileContext;
pub(crate) use crate::files::model_files::ModelFiles;
use crate::schema::{AttrType, ElementKind, Multiplicity, Role};
use crate::value::{self, AttrInput, FileAsset, Value};

/// A set of attribute assignments: values to set and attributes to clear, in order.
///
/// # Examples
/// ```
/// use mjcf::Attrs;
/// let a = Attrs::new().set("rgba", [1.0, 0.0, 0.0, 1.0]).clear("material");
/// assert_eq!(a.len(), 2);
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Attrs {
    items: Vec<(SmolStr, Option<AttrInput>)>,
}

impl Attrs {
    /// No assignments.
    ///
    /// Time: O(1).
    pub fn new() -> Attrs {
        Attrs::default()
    }

    /// Adds an assignment of `value` to the attribute `name` (`"class"` for the
    /// default class). Nothing is checked until the assignments are applied.
    ///
    /// Time: O(1) amortised.
    #[must_use]
    pub fn set(mut self, name: &str, value: impl Into<AttrInput>) -> Attrs {
        self.items.push((name.into(), Some(value.into())));
        self
    }

    /// Adds the clearing of the attribute `name`.
    ///
    /// Time: O(1) amortised.
    #[must_use]
    pub fn clear(mut self, name: &str) -> Attrs {
        self.items.push((name.into(), None));
        self
    }

    /// The number of assignments.
    ///
    /// Time: O(1).
    pub fn len(&self) -> usize {
        self.items.len()
    }

    /// Whether there are no assignments.
    ///
    /// Time: O(1).
    pub fn is_empty(&self) -> bool {
        self.items.is_empty()
    }

    pub(crate) fn items(&self) -> &[(SmolStr, Option<AttrInput>)] {
        &self.items
    }
}

/// A new element to add to a model: its tag, attributes and children.
///
/// # Examples
/// ```
/// use mjcf::{Element, Model};
/// let m = Model::new("m");
/// let body = Element::new("body")
///     .attr("name", "torso")
///     .attr("pos", [0.0, 0.0, 1.0])
///     .child(Element::new("geom").attr("type", "box").attr("size", [0.1, 0.1, 0.1]));
/// let (m, torso) = m.add(&m.worldbody(), body).unwrap();
/// assert_eq!(m.find(mjcf::Namespace::Body, "torso"), Some(torso));
/// ```
// The element and its descendants are kept flat (an arena with child indices), not as
// nested values: cloning, comparing and dropping never recurse, so an element nested
// any number of levels deep cannot overflow the stack.
#[derive(Clone)]
pub struct Element {
    parts: Vec<Part>,
    /// The index of this element's own part; every index in `parts` is valid.
    root: usize,
}

#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Part {
    pub(crate) tag: SmolStr,
    pub(crate) attrs: Attrs,
    pub(crate) children: Vec<usize>,
}

impl Element {
    /// An element with this tag and nothing else (the tag is checked when the
    /// element is added).
    ///
    /// Time: O(1).
    pub fn new(tag: &str) -> Element {
        Element {
            parts: vec![Part { tag: tag.into(), attrs: Attrs::new(), children: Vec::new() }],
            root: 0,
        }
    }

    /// Sets an attribute (checked when the element is added).
    ///
    /// Time: O(1) amortised.
    #[must_use]
    pub fn attr(mut self, name: &str, value: impl Into<AttrInput>) -> Element {
        let root = self.root;
        let part = &mut self.parts[root];
        part.attrs = std::mem::take(&mut part.attrs).set(name, value);
        self
    }

    /// Sets several attributes.
    ///
    /// Time: O(k) for `k` assignments.
    #[must_use]
    pub fn attrs(mut self, attrs: Attrs) -> Element {
        let root = self.root;
        self.parts[root].attrs.items.extend(attrs.items);
        self
    }

    /// Appends a child element.
    ///
    /// Time: O(size of the smaller of the two), so building a chain of any depth
    /// either way round costs O(n log n).
    #[must_use]
    pub fn child(self, child: Element) -> Element {
        // Move the smaller arena into the larger one.
        let (mut big, small, parent_is_big) = if self.parts.len() >= child.parts.len() {
            (self, child, true)
        } else {
            (child, self, false)
        };
        let offset = big.parts.len();
        big.parts.extend(small.parts.into_iter().map(|mut p| {
            p.children.iter_mut().for_each(|c| *c += offset);
            p
        }));
        let (parent, child) = if parent_is_big {
            (big.root, small.root + offset)
        } else {
            (small.root + offset, big.root)
        };
        big.parts[parent].children.push(child);
        big.root = parent;
        big
    }

    /// The tag.
    ///
    /// Time: O(1).
    pub fn tag(&self) -> &str {
        &self.parts[self.root].tag
    }

    /// This element's own part.
    pub(crate) fn root_part(&self) -> &Part {
        &self.parts[self.root]
    }

    /// The part at `index` (an index taken from another part's children).
    pub(crate) fn part(&self, index: usize) -> &Part {
        &self.parts[index]
    }
}

impl PartialEq for Element {
    /// Structural equality: same tags, attributes and children (iterative).
    fn eq(&self, other: &Element) -> bool {
        let mut stack = vec![(self.root_part(), other.root_part())];
        while let Some((a, b)) = stack.pop() {
            if a.tag != b.tag || a.attrs != b.attrs || a.children.len() != b.children.len() {
                return false;
            }
            stack.extend(
                a.children.iter().zip(&b.children).map(|(x, y)| (self.part(*x), other.part(*y))),
            );
        }
        true
    }
}

impl std::fmt::Debug for Element {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let root = self.root_part();
        f.debug_struct("Element")
            .field("tag", &root.tag)
            .field("attrs", &root.attrs)
            .field("children", &root.children.len())
            .field("descendants", &(self.parts.len() - 1))
            .finish()
    }
}

/// Creates an empty element of `kind` with a fresh id and every singleton child it
/// always has (an `option` gets its `flag`, a default class its `geom`, ...).
pub(crate) fn empty_node(kind: ElementKind) -> Node {
    empty_node_with_id(ElementId::fresh(), kind)
}

/// [`empty_node`] with the id `id`. The singleton children take one block of
/// consecutive ids, so the index keeps them as one run (`model::index`).
pub(crate) fn empty_node_with_id(id: ElementId, kind: ElementKind) -> Node {
    let first = ElementId::fresh_block(kind.singleton_children().count());
    let children: Seq<Node> = kind
        .singleton_children()
        .enumerate()
        .map(|(i, c)| empty_node_with_id(first.nth(i), c))
        .collect();
    Node::new(id, kind, Vec::new(), children)
}

/// Everything needed to turn inputs into checked values.
pub(crate) struct ValueCtx<'a> {
    pub(crate) files: &'a FileContext,
    pub(crate) basepaths: &'a Basepaths,
    /// The asset model files read so far by this read or edit.
    pub(crate) model_files: &'a ModelFiles,
}

/// An attribute value as given: text (read from XML, or given as text through the
/// API) or a typed input.
#[derive(Clone, Copy)]
pub(crate) enum Input<'a> {
    /// Text, parsed by the attribute's type.
    Text(&'a str),
    /// An input given through the API.
    Given(&'a AttrInput),
}

/// What a text gives before it is parsed ([`ValueCtx::before_parsing`]).
enum Before {
    /// Nothing: the attribute is cleared.
    Clears,
    /// A file, read.
    File(FileAsset),
}

impl ValueCtx<'_> {
    /// Checks one assignment, the same for the reader and the builder: `Ok(None)`
    /// clears the attribute (no input, empty text for a name, reference, string,
    /// folder or file (the reader also reads an automatic name such as
    /// `//unnamed_geom_0` as "unnamed", see `xml::read`), which means
    /// "unnamed"); `dclass` is `class`; a file attribute reads its file; a mesh file
    /// must have an extension MuJoCo reads.
    pub(crate) fn assign(
        &self,
        kind: ElementKind,
        name: &str,
        input: Option<Input<'_>>,
    ) -> Result<(usize, Option<Value>), ErrorKind> {
        let name = if name == "dclass" { "class" } else { name };
        let index =
            kind.attr_index(name).ok_or_else(|| ErrorKind::unknown_attribute(kind, name))?;
        self.assign_at(kind, index, input).map(|v| (index, v))
    }

    /// [`ValueCtx::assign`] to the attribute at `index` of `kind` (the reader finds the
    /// index itself, once).
    pub(crate) fn assign_at(
        &self,
        kind: ElementKind,
        index: usize,
        input: Option<Input<'_>>,
    ) -> Result<Option<Value>, ErrorKind> {
        let given = match input {
            None => return Ok(None),
            Some(Input::Text(text)) => {
                let mut value = Value::Int(0);
                let set = self.assign_text_into(kind, index, text, &mut value)?;
                return Ok(set.then_some(value));
            }
            Some(Input::Given(given)) => given,
        };
        if let AttrInput::Text(text) = given {
            match self.before_parsing(kind, index, text)? {
                Some(Before::Clears) => return Ok(None),
                Some(Before::File(asset)) => return Ok(Some(Value::File(asset))),
                None => {}
            }
        }
        let spec = kind.attr(index);
        value::from_input(spec, kind.namespace(), given).map_err(|error| ErrorKind::InvalidValue {
            tag: kind.tag(),
            attribute: spec.name,
            value: input_text(given),
            error,
        })
    }

    /// [`ValueCtx::assign_at`] of a text, into `dst`, where the value is to stay
    /// ([`value::parse_text_into`] says why); `false` when the text clears the
    /// attribute (`dst` is then unspecified, as on an error).
    pub(crate) fn assign_text_into(
        &self,
        kind: ElementKind,
        index: usize,
        text: &str,
        dst: &mut Value,
    ) -> Result<bool, ErrorKind> {
        match self.before_parsing(kind, index, text)? {
            Some(Before::Clears) => return Ok(false),
            Some(Before::File(asset)) => {
                *dst = Value::File(asset);
                return Ok(true);
            }
            None => {}
        }
        let spec = kind.attr(index);
        value::parse_text_into(spec, kind.namespace(), text, dst).map_err(|error| {
            ErrorKind::InvalidValue {
                tag: kind.tag(),
                attribute: spec.name,
                value: cut(text),
                error,
            }
        })?;
        Ok(true)
    }

    /// What a text gives before it is parsed as the attribute's type, if anything:
    /// empty, it clears a name, reference, string, folder or file; a file is read.
    fn before_parsing(
        &self,
        kind: ElementKind,
        index: usize,
        text: &str,
    ) -> Result<Option<Before>, ErrorKind> {
        let spec = kind.attr(index);
        // An empty required name prefix (`<attach prefix="">`) is given, as MuJoCo
        // reads it: the part's names are taken as they are.
        let empty_prefix = spec.required && matches!(spec.ty, AttrType::NamePrefix);
        let clears = text.is_empty()
            && !empty_prefix
            && matches!(
                spec.ty,
                AttrType::Identifier
                    | AttrType::Reference(_)
                    | AttrType::String
                    | AttrType::NamePrefix
                    | AttrType::Basepath { .. }
                    | AttrType::File { .. }
            );
        if clears {
            return Ok(Some(Before::Clears));
        }
        let AttrType::File { path_namespace } = spec.ty else { return Ok(None) };
        let base = self.basepaths.for_namespace(path_namespace);
        let asset = if kind.is(Role::AssetModel) {
            // A model file brings the files it names (exported beside it).
            self.model_files.read(self.files, base, text, ElementKind::ROOT, 0)?.0
        } else {
            FileAsset::from_path_and_contents(text, self.files.read(base, text)?.1)
        };
        let ext = asset.extension().to_ascii_lowercase();
        if kind.is(Role::Mesh) && !matches!(ext.as_str(), ".stl" | ".msh" | ".obj") {
            let error = ValueError::MeshExtension;
            return Err(ErrorKind::InvalidValue {
                tag: kind.tag(),
                attribute: spec.name,
                value: cut(text),
                error,
            });
        }
        Ok(Some(Before::File(asset)))
    }
}

/// The text of an input, for error messages (cut to 200 characters).
pub(crate) fn input_text(input: &AttrInput) -> String {
    let s = match input {
        AttrInput::Text(t) => t.to_string(),
        AttrInput::Number(x) => x.to_string(),
        AttrInput::Numbers(xs) => xs.iter().map(f64::to_string).collect::<Vec<_>>().join(" "),
        AttrInput::Bool(b) => b.to_string(),
        AttrInput::Value(v) => v.to_string(),
    };
    cut(&s)
}

/// A value as errors keep it: [`crate::error::cut`], owned.
pub(crate) fn cut(s: &str) -> String {
    crate::error::cut(s).into_owned()
}

/// Applies assignments to an attribute list, keeping schema order. Returns the
/// identifier change, if any (`Some(None)` clears it).
pub(crate) fn apply_attrs(
    kind: ElementKind,
    attrs: &mut Vec<Attr>,
    changes: Vec<(usize, Option<Value>)>,
) -> Result<(), ErrorKind> {
    for (index, value) in changes {
        let i = index as u16;
        let pos = attrs.binary_search_by_key(&i, |(k, _)| *k);
        match (pos, value) {
            (Ok(p), Some(v)) => attrs[p].1 = v,
            (Err(p), Some(v)) => attrs.insert(p, (i, v)),
            (Ok(p), None) => {
                if kind.attr(index).required {
                    return Err(ErrorKind::MissingRequired {
                        tag: kind.tag(),
                        attribute: kind.attr(index).name,
                    });
                }
                attrs.remove(p);
            }
            (Err(_), None) => {
                if kind.attr(index).required {
                    return Err(ErrorKind::MissingRequired {
                        tag: kind.tag(),
                        attribute: kind.attr(index).name,
                    });
                }
            }
        }
    }
    Ok(())
}

/// Checks that every required attribute is set.
pub(crate) fn check_required(kind: ElementKind, attrs: &[Attr]) -> Result<(), ErrorKind> {
    for &i in kind.required_attrs() {
        if attrs.binary_search_by_key(&i, |(k, _)| *k).is_err() {
            let attribute = kind.attr(usize::from(i)).name;
            return Err(ErrorKind::MissingRequired { tag: kind.tag(), attribute });
        }
    }
    Ok(())
}

/// Checks that a nested default class has a name: only the root class may be unnamed
/// (MuJoCo refuses an empty class name, and the output would hold two classes `/`).
pub(crate) fn check_class_named(
    parent: ElementKind,
    kind: ElementKind,
    attrs: &[Attr],
) -> Result<(), ErrorKind> {
    if !kind.is(Role::DefaultClass) || !parent.is(Role::DefaultClass) {
        return Ok(());
    }
    let named = kind
        .identifier()
        .is_some_and(|i| attrs.binary_search_by_key(&(i as u16), |(k, _)| *k).is_ok());
    if named {
        Ok(())
    } else {
        Err(ErrorKind::MissingRequired { tag: "default", attribute: "class" })
    }
}

/// Checks that a top-level `<default>` read from text is unnamed or named `main`, as
/// MuJoCo's reader requires (its root class is always `main`); a file naming it
/// otherwise is one MuJoCo refuses, though the API may name the root class (the
/// writer nests it).
pub(crate) fn check_root_class_name(
    parent: ElementKind,
    kind: ElementKind,
    attrs: &[Attr],
) -> Result<(), ErrorKind> {
    if parent != ElementKind::ROOT || kind != ElementKind::DEFAULT {
        return Ok(());
    }
    let Some(i) = kind.identifier() else { return Ok(()) };
    let name = attrs.iter().find(|(k, _)| *k as usize == i).and_then(|(_, v)| v.as_str());
    match name {
        Some(n) if !n.is_empty() && n != "main" => Err(ErrorKind::RootClassRenamed(n.into())),
        _ => Ok(()),
    }
}

/// Gives a nameless `mesh`, `hfield` or `texture` with a file the file's stem as name,
/// as the reference does; and a nameless asset `model` the name of the model its file
/// holds, as MuJoCo does (`<attach model=…>` names it so).
pub(crate) fn name_from_file(kind: ElementKind, attrs: &mut Vec<Attr>) {
    let from_stem = match kind.role() {
        Some(Role::Mesh | Role::Hfield | Role::Texture) => true,
        Some(Role::AssetModel) => false,
        _ => return,
    };
    let (Some(ident), Some(file)) = (kind.identifier(), kind.attr_index("file")) else { return };
    let has_name = attrs.iter().any(|(i, _)| *i as usize == ident);
    let name = attrs.iter().find_map(|(i, v)| match v {
        Value::File(f) if *i as usize == file => {
            if from_stem {
                Some(SmolStr::from(f.stem()))
            } else {
                crate::files::scan::model_name(f.contents())
            }
        }
        _ => None,
    });
    if let (false, Some(name)) = (has_name, name) {
        if let Ok(v) = value::identifier(&name, kind.namespace()) {
            let i = ident as u16;
            let p = attrs.binary_search_by_key(&i, |(k, _)| *k).unwrap_or_else(|p| p);
            attrs.insert(p, (i, v));
        }
    }
}

/// Builds the node for `el` under a parent of kind `parent`. `path` names the new
/// element in errors; on error it holds the path of the failing element.
pub(crate) fn build(
    ctx: &ValueCtx<'_>,
    parent: ElementKind,
    el: &Element,
    path: &mut String,
) -> Result<Node, ErrorKind> {
    let root = el.root_part();
    let kind =
        parent.child(&root.tag).ok_or_else(|| ErrorKind::invalid_child(parent, &root.tag))?;
    if kind.multiplicity() == Multiplicity::Singleton {
        return Err(ErrorKind::DuplicateChild(kind.tag()));
    }
    push_segment(path, kind.tag(), None);
    fill(ctx, parent, empty_node(kind), el, path)
}

/// A node being filled from a part of an [`Element`].
struct Filling<'e> {
    id: ElementId,
    kind: ElementKind,
    attrs: Vec<Attr>,
    children: Seq<Node>,
    part: &'e Part,
    /// The next of `part`'s children to fill.
    next: usize,
    /// The length of the error path before this element's segment.
    path_len: usize,
    /// Where the finished node goes among its parent's children: replacing the
    /// singleton at this position, or (`None`) appended.
    slot: Option<usize>,
    /// The singleton children `part` gives, in its order (their order as given is
    /// kept for a default class's actuator defaults: decision D11).
    given: Vec<ElementKind>,
}

impl<'e> Filling<'e> {
    /// Applies `part`'s attributes to `node` (of the same kind).
    fn start(
        ctx: &ValueCtx<'_>,
        parent: ElementKind,
        node: &Node,
        part: &'e Part,
        slot: Option<usize>,
        path_len: usize,
    ) -> Result<Filling<'e>, ErrorKind> {
        let kind = node.kind();
        let mut changes = Vec::with_capacity(part.attrs.items.len());
        for (name, input) in &part.attrs.items {
            changes.push(ctx.assign(kind, name, input.as_ref().map(Input::Given))?);
        }
        let mut attrs = node.attrs().to_vec();
        apply_attrs(kind, &mut attrs, changes)?;
        name_from_file(kind, &mut attrs);
        check_required(kind, &attrs)?;
        check_class_named(parent, kind, &attrs)?;
        Ok(Filling {
            id: node.id(),
            kind,
            attrs,
            children: node.children().clone(),
            part,
            next: 0,
            path_len,
            slot,
            given: Vec::new(),
        })
    }
}

/// Applies `el`'s attributes and children to `node` (of the same kind), iteratively.
fn fill(
    ctx: &ValueCtx<'_>,
    parent: ElementKind,
    node: Node,
    el: &Element,
    path: &mut String,
) -> Result<Node, ErrorKind> {
    let mut stack = vec![Filling::start(ctx, parent, &node, el.root_part(), None, path.len())?];
    while let Some(top) = stack.last_mut() {
        if let Some(&index) = top.part.children.get(top.next) {
            top.next += 1;
            let child = el.part(index);
            let Some(child_kind) = top.kind.child(&child.tag) else {
                return Err(ErrorKind::invalid_child(top.kind, &child.tag));
            };
            let path_len = path.len();
            let (existing, slot) = match child_kind.multiplicity() {
                Multiplicity::Singleton => {
                    let pos = top.children.iter().position(|c| c.kind() == child_kind);
                    if !top.given.contains(&child_kind) {
                        top.given.push(child_kind);
                    }
                    (pos.and_then(|p| top.children.get(p).cloned()), pos)
                }
                Multiplicity::OnDemand if top.children.iter().any(|c| c.kind() == child_kind) => {
                    return Err(ErrorKind::DuplicateChild(child_kind.tag()));
                }
                _ => (None, None),
            };
            push_segment(path, child_kind.tag(), None);
            let existing = existing.unwrap_or_else(|| empty_node(child_kind));
            let parent = top.kind;
            stack.push(Filling::start(ctx, parent, &existing, child, slot, path_len)?);
            continue;
        }
        let Some(mut done) = stack.pop() else { break };
        if done.kind.is(Role::DefaultClass) && done.given.len() > 1 {
            // decision D11: the actuator defaults in the order given.
            let mut children: Vec<Node> = done.children.iter().cloned().collect();
            let given = &done.given;
            super::defaults::order(
                &mut children,
                |n| n,
                |n| given.iter().position(|k| *k == n.kind()),
            );
            done.children = children.into_iter().collect();
        }
        let node = Node::new(done.id, done.kind, done.attrs, done.children);
        path.truncate(done.path_len);
        match stack.last_mut() {
            Some(parent) => match done.slot {
                Some(p) => {
                    parent.children.set(p, node);
                }
                None => parent.children.push_back(node),
            },
            None => return Ok(node),
        }
    }
    // The loop returns when the outermost element is finished.
    Ok(node)
}

/// Appends `/tag` or `/tag[name=x]` to an element path.
pub(crate) fn push_segment(path: &mut String, tag: &str, name: Option<&str>) {
    if !path.is_empty() {
        path.push('/');
    }
    path.push_str(tag);
    if let Some(n) = name {
        path.push_str("[name=");
        path.push_str(n);
        path.push(']');
    }
}
