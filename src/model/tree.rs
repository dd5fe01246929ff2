//! Immutable, shared element nodes and path-copying edits.
//!
//! A [`Node`] is an `Arc`: cloning it is a pointer bump. Nodes hold no parent pointer
//! and nothing that depends on where they sit (no prefix, no path, no auto name), so one
//! node can sit in many trees at once. An edit rebuilds only the nodes on the path from
//! the edited node to the root; every other subtree stays shared (`ptr_eq`).
//!
// Implementation notes:
// - Attributes are kept sorted by their schema index, which is also the order they are
//   written in.
// - Invariants: `attrs` holds no duplicate index; every child's kind is a child kind
//   of this node's kind; an element id occurs at most once in a model's own tree.

use std::cell::{Cell, RefCell};
use std::fmt;
use std::sync::Arc;

use crate::seq::Seq;
use smol_str::SmolStr;

pub(crate) use crate::id::ElementId;
use crate::schema::{AttrType, ElementKind, Namespace};
use crate::value::Value;

/// One attribute slot: the schema index of the attribute and its value.
pub(crate) type Attr = (u16, Value);

impl crate::seq::Keyed for Node {
    fn key(&self) -> u64 {
        self.id().get()
    }
}

/// The attributes as stored: no attributes share one allocation (most children of a
/// default class, and every empty singleton, have none).
fn shared_attrs(attrs: Vec<Attr>) -> Arc<[Attr]> {
    if attrs.is_empty() {
        return no_attrs();
    }
    attrs.into()
}

/// The one shared empty attribute list.
pub(crate) fn no_attrs() -> Arc<[Attr]> {
    static EMPTY: std::sync::OnceLock<Arc<[Attr]>> = std::sync::OnceLock::new();
    EMPTY.get_or_init(|| Arc::from(Vec::new())).clone()
}

/// The attributes of `buf` (sorted by index) moved into their stored form, in one
/// allocation of their final size; `buf` is left empty, with its capacity, for reuse.
pub(crate) fn take_attrs(buf: &mut Vec<Attr>) -> Arc<[Attr]> {
    if buf.is_empty() {
        return no_attrs();
    }
    buf.drain(..).collect()
}

/// An immutable element node.
#[derive(Clone)]
pub(crate) struct Node(Arc<NodeData>);

#[derive(Clone)]
pub(crate) struct NodeData {
    pub(crate) id: ElementId,
    pub(crate) kind: ElementKind,
    pub(crate) attrs: Arc<[Attr]>,
    pub(crate) children: Seq<Node>,
    /// Set on an attachment frame: the attached model and its scope name.
    pub(crate) attached: Option<Arc<Attached>>,
}

/// What an attachment frame holds besides its own attributes and children.
#[derive(Clone)]
pub(crate) struct Attached {
    /// The scope name (`robot`, `robot_1`), chosen at attach time.
    pub(crate) scope: SmolStr,
    /// The attached model, unchanged and shared.
    pub(crate) model: super::Model,
}

impl Node {
    /// The namespace the reference attribute `i` names into (an attribute whose
    /// namespace another attribute decides, such as a sensor's `objname` by its
    /// `objtype`, asks it); `None` for an attribute that is not a reference.
    ///
    /// Time: O(1).
    pub(crate) fn reference_namespace(&self, i: usize) -> Option<Namespace> {
        match self.kind().attr(i).ty {
            AttrType::Reference(target) => {
                let other = target.depends_on().and_then(|k| self.attr(k));
                target.namespace(other.map(|v| v.as_str().unwrap_or("")))
            }
            _ => None,
        }
    }

    pub(crate) fn new(
        id: ElementId,
        kind: ElementKind,
        attrs: Vec<Attr>,
        children: Seq<Node>,
    ) -> Node {
        let mut attrs = attrs;
        attrs.sort_by_key(|(i, _)| *i);
        Node(Arc::new(NodeData { id, kind, attrs: shared_attrs(attrs), children, attached: None }))
    }

    /// A node whose attributes are already stored (sorted by index, no duplicates):
    /// the reader builds them in their final form.
    pub(crate) fn from_sorted(
        id: ElementId,
        kind: ElementKind,
        attrs: Arc<[Attr]>,
        children: Seq<Node>,
    ) -> Node {
        debug_assert!(attrs.windows(2).all(|w| w[0].0 < w[1].0));
        Node(Arc::new(NodeData { id, kind, attrs, children, attached: None }))
    }

    /// An attachment frame.
    pub(crate) fn frame(
        id: ElementId,
        kind: ElementKind,
        attrs: Vec<Attr>,
        attached: Attached,
    ) -> Node {
        let mut attrs = attrs;
        attrs.sort_by_key(|(i, _)| *i);
        Node(Arc::new(NodeData {
            id,
            kind,
            attrs: shared_attrs(attrs),
            children: Seq::new(),
            attached: Some(Arc::new(attached)),
        }))
    }

    /// The attachment this node is the frame of.
    pub(crate) fn attached(&self) -> Option<&Attached> {
        self.0.attached.as_deref()
    }

    /// A copy (a frame) holding another attachment.
    pub(crate) fn with_attached(&self, attached: Attached) -> Node {
        let mut data = NodeData::clone(&self.0);
        data.attached = Some(Arc::new(attached));
        Node(Arc::new(data))
    }

    /// A copy with other attributes and children (and the same attachment, if any).
    pub(crate) fn with_parts(&self, attrs: Vec<Attr>, children: Seq<Node>) -> Node {
        let mut attrs = attrs;
        attrs.sort_by_key(|(i, _)| *i);
        let mut data = NodeData::clone(&self.0);
        data.attrs = shared_attrs(attrs);
        data.children = children;
        Node(Arc::new(data))
    }

    pub(crate) fn id(&self) -> ElementId {
        self.0.id
    }

    pub(crate) fn kind(&self) -> ElementKind {
        self.0.kind
    }

    pub(crate) fn attrs(&self) -> &[Attr] {
        &self.0.attrs
    }

    pub(crate) fn children(&self) -> &Seq<Node> {
        &self.0.children
    }

    /// The value of the attribute at schema index `index`.
    pub(crate) fn attr(&self, index: usize) -> Option<&Value> {
        let i = u16::try_from(index).ok()?;
        self.0.attrs.binary_search_by_key(&i, |(k, _)| *k).ok().map(|p| &self.0.attrs[p].1)
    }

    /// The element's identifier, if set.
    pub(crate) fn identifier(&self) -> Option<&str> {
        let idx = self.kind().identifier()?;
        match self.attr(idx)? {
            Value::Identifier(s) => Some(s),
            _ => None,
        }
    }

    /// The node's data, mutable: copied first if another version shares it
    /// (`Arc::make_mut`), so an in-place edit never shows in another value.
    pub(crate) fn make_mut(&mut self) -> &mut NodeData {
        Arc::make_mut(&mut self.0)
    }

    /// A weak handle on the node's allocation, which keeps the address from being
    /// reused while it is held: [`Node::is`] then tells this very node from any
    /// later one, even one made by an in-place edit (`Arc::make_mut` moves a node
    /// that a weak handle points at rather than edit it in place).
    pub(crate) fn downgrade(&self) -> std::sync::Weak<NodeData> {
        Arc::downgrade(&self.0)
    }

    /// Whether `weak` ([`Node::downgrade`]) was taken from this very node.
    pub(crate) fn is(&self, weak: &std::sync::Weak<NodeData>) -> bool {
        std::ptr::eq(weak.as_ptr(), Arc::as_ptr(&self.0))
    }

    /// Whether both are the same shared node.
    /// The node's address, for telling shared nodes apart while they are borrowed.
    pub(crate) fn as_ptr(&self) -> *const () {
        Arc::as_ptr(&self.0).cast()
    }

    pub(crate) fn ptr_eq(&self, other: &Node) -> bool {
        Arc::ptr_eq(&self.0, &other.0)
    }

    /// The position of the child `id` whose slot was `ord` (see `crate::seq`):
    /// O(log width) while the slot holds; else looked for by id around the position
    /// `hint`, O(distance · log width).
    pub(crate) fn child_position(&self, id: ElementId, ord: u64, hint: usize) -> Option<usize> {
        self.0.children.position_of(id.get(), ord, hint)
    }

    /// The first child of this kind.
    pub(crate) fn child_of_kind(&self, kind: ElementKind) -> Option<&Node> {
        self.0.children.find(|c| c.kind() == kind)
    }

    /// A copy with different attributes.
    pub(crate) fn with_attrs(&self, attrs: Vec<Attr>) -> Node {
        let mut data = NodeData::clone(&self.0);
        let mut attrs = attrs;
        attrs.sort_by_key(|(i, _)| *i);
        data.attrs = shared_attrs(attrs);
        Node(Arc::new(data))
    }

    /// A copy with different children.
    pub(crate) fn with_children(&self, children: Seq<Node>) -> Node {
        let mut data = NodeData::clone(&self.0);
        data.children = children;
        Node(Arc::new(data))
    }

    /// A copy with the child at `index` replaced.
    pub(crate) fn with_child_at(&self, index: usize, child: Node) -> Node {
        let mut children = self.0.children.clone();
        children.set(index, child);
        self.with_children(children)
    }

    /// Rebuilds the path `path` (child indices from this node) with `f` applied to the
    /// node at its end. Time: O(depth · √width): at each level the children's chunk
    /// list and one chunk are copied.
    pub(crate) fn update_path<E>(
        &self,
        path: &[usize],
        f: impl FnOnce(&Node) -> Result<Node, E>,
    ) -> Result<Node, E> {
        // Iterative, so deep trees cannot overflow the stack.
        let mut chain: Vec<&Node> = Vec::with_capacity(path.len() + 1);
        chain.push(self);
        for &i in path {
            let last = chain[chain.len() - 1];
            match last.0.children.get(i) {
                Some(c) => chain.push(c),
                None => break,
            }
        }
        let target = chain[chain.len() - 1];
        let mut node = f(target)?;
        for (depth, parent) in chain.iter().enumerate().rev().skip(1) {
            node = parent.with_child_at(path[depth], node);
        }
        Ok(node)
    }

    /// Rebuilds the subtree bottom-up (iteratively): `f` gets each node and its rebuilt
    /// children and returns the node's replacement.
    pub(crate) fn rebuild(&self, mut f: impl FnMut(&Node, Seq<Node>) -> Node) -> Node {
        let mut stack: Vec<(&Node, bool)> = vec![(self, false)];
        let mut built: Vec<Node> = Vec::new();
        while let Some((n, done)) = stack.pop() {
            if !done {
                stack.push((n, true));
                stack.extend(n.children().iter().rev().map(|c| (c, false)));
                continue;
            }
            let children: Seq<Node> =
                built.split_off(built.len() - n.children().len()).into_iter().collect();
            built.push(f(n, children));
        }
        built.pop().unwrap_or_else(|| self.clone())
    }

    /// Every node of the subtree in document order (pre-order), iteratively.
    pub(crate) fn descendants(&self) -> Descendants<'_> {
        Descendants { stack: vec![self] }
    }
}

/// Pre-order iterator over a subtree.
pub(crate) struct Descendants<'a> {
    stack: Vec<&'a Node>,
}

impl<'a> Iterator for Descendants<'a> {
    type Item = &'a Node;
    fn next(&mut self) -> Option<&'a Node> {
        let n = self.stack.pop()?;
        let before = self.stack.len();
        self.stack.extend(n.children().iter());
        self.stack[before..].reverse();
        Some(n)
    }
}

impl fmt::Debug for Node {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "<{} {:?}", self.kind().tag(), self.id())?;
        for (i, v) in self.attrs() {
            write!(f, " {}={:?}", self.kind().attr(*i as usize).name, v.to_string())?;
        }
        write!(f, "> ({} children)", self.children().len())
    }
}

impl PartialEq for Node {
    /// Structural equality (same ids, kinds, attributes and children, and equal
    /// attachments), with a shortcut for shared nodes. Iterative, through attached
    /// models too.
    fn eq(&self, other: &Node) -> bool {
        let mut stack = vec![(self, other)];
        while let Some((a, b)) = stack.pop() {
            if a.ptr_eq(b) {
                continue;
            }
            if a.id() != b.id()
                || a.kind() != b.kind()
                || a.attrs() != b.attrs()
                || a.children().len() != b.children().len()
            {
                return false;
            }
            match (a.attached(), b.attached()) {
                (None, None) => {}
                (Some(x), Some(y)) => {
                    if x.scope != y.scope || x.model.name() != y.model.name() {
                        return false;
                    }
                    stack.push((&x.model.root, &y.model.root));
                }
                _ => return false,
            }
            stack.extend(a.children().iter().zip(b.children().iter()));
        }
        true
    }
}

impl PartialEq for Attached {
    fn eq(&self, other: &Attached) -> bool {
        self.scope == other.scope && self.model == other.model
    }
}

/// How deep drops of nodes nest on one thread before deeper ones are deferred.
const MAX_DROP_DEPTH: usize = 200;

/// What a dropped node owned: its children and its attachment.
type Parts = (Seq<Node>, Option<Arc<Attached>>);

thread_local! {
    static DROP_DEPTH: Cell<usize> = const { Cell::new(0) };
    static DEFERRED: RefCell<Vec<Parts>> = const { RefCell::new(Vec::new()) };
}

impl Drop for NodeData {
    /// Drops the subtree (attached models included) without deep recursion: nested
    /// drops go 200 levels deep, deeper subtrees are deferred to the outermost drop,
    /// which finishes them in a loop. So a very deep tree cannot overflow the stack,
    /// and dropping a version that shares its children with another (the common case)
    /// costs O(1), not O(width).
    fn drop(&mut self) {
        if self.children.is_empty() && self.attached.is_none() {
            return;
        }
        let parts: Parts = (std::mem::take(&mut self.children), self.attached.take());
        let Ok(depth) = DROP_DEPTH.try_with(Cell::get) else { return };
        if depth >= MAX_DROP_DEPTH {
            // If the thread's storage is gone (thread exit), drop in place.
            let _ = DEFERRED.try_with(|d| d.borrow_mut().push(parts));
            return;
        }
        DROP_DEPTH.set(depth + 1);
        drop(parts);
        if depth == 0 {
            // Still one level deep, so that these drops defer rather than drain too.
            while let Some(p) = DEFERRED.try_with(|d| d.borrow_mut().pop()).ok().flatten() {
                drop(p);
            }
        }
        DROP_DEPTH.set(depth);
    }
}
