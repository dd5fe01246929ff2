//! The arena read turned into a model: the root class hoisted, automatic names
//! forgotten, names indexed, references resolved, nodes built bottom-up.

use std::sync::Arc;

use crate::seq::Seq;
use smol_str::SmolStr;

use super::{NONE, Pending, Reader, children_of, push_unique, unique_child};
use crate::error::{ErrorKind, ReadError};
use crate::model::tree::{Attr, ElementId, Node, no_attrs};
use crate::model::{Model, ReadIndex, empty_node, empty_node_with_id};
use crate::schema::{AttrType, ElementKind, Multiplicity, Role};
use crate::value::{Reference, Value};
use crate::xml::rules;

/// Turns the arena into nodes, indexes them and resolves references.
pub(super) fn finish(r: &mut Reader<'_>, model_name: Option<SmolStr>) -> Result<Model, ReadError> {
    let (composed, hoisted) = hoist_root_class(&mut r.arena);
    if let Some(only) = hoisted {
        let root_default = ElementKind::DEFAULT;
        if let Some(d) = unique_child(&r.arena, 0, root_default) {
            r.hoisted = Some((r.arena[only].id, r.arena[d].id));
        }
    }
    let forget = !composed;
    let (names, slashed, mut idents) = index_names(r, forget)?;
    if let Some(i) = ElementKind::ROOT.attr_index("model") {
        // A missing or empty name becomes `unnamed_model`, as in the reference.
        let name =
            model_name.filter(|n| !n.is_empty()).unwrap_or_else(|| crate::model::UNNAMED.into());
        let mut attrs = r.arena[0].attrs.to_vec();
        attrs.retain(|(k, _)| *k as usize != i);
        attrs.push((i as u16, Value::String(name)));
        attrs.sort_by_key(|(k, _)| *k);
        r.arena[0].attrs = attrs.into();
    }
    // Bottom-up: children always have larger arena indices than their parent.
    let mut built: Vec<Option<Node>> = (0..r.arena.len()).map(|_| None).collect();
    // One buffer for every element's children.
    let mut children: Vec<Node> = Vec::new();
    // And for their identifiers, for the index.
    let mut child_idents: Vec<Option<SmolStr>> = Vec::new();
    let empty = no_attrs();
    // The nodes made here (empty singletons), for the size of the index's list.
    let mut made = 0;
    for (i, p) in r.arena.iter().enumerate().filter(|(i, _)| Some(*i) != hoisted) {
        for k in p.kind.singleton_children() {
            if unique_child(&r.arena, i, k).is_none() {
                made += empty_size(k);
            }
        }
    }
    // Indexed as the nodes are made, while they are in cache.
    let mut index = ReadIndex::with_capacity(r.arena.len() + made);
    for i in (0..r.arena.len()).rev() {
        if Some(i) == hoisted {
            // Out of the tree: its content is the root class's now.
            continue;
        }
        let (p, at) = (&r.arena[i], i);
        children.clear();
        child_idents.clear();
        let mut kinds = p.kind.singleton_children().peekable();
        if kinds.peek().is_some() {
            // Singletons in schema order, each with where it was read (its arena
            // entry, in document order, includes included), if it was.
            // The ones not read take one block of ids, so that a class read without
            // any is indexed as one run (`model::index`).
            let first = ElementId::fresh_block(kinds.clone().count());
            let mut singles: Vec<(Node, Option<usize>)> = Vec::new();
            for (i, k) in kinds.enumerate() {
                let found = unique_child(&r.arena, at, k);
                match found.and_then(|c| Some((built[c].take()?, c))) {
                    Some((n, at)) => singles.push((n, Some(at))),
                    None => {
                        let empty = empty_node_with_id(first.nth(i), k);
                        if !empty.children().is_empty() {
                            index.descendants(&empty);
                        }
                        singles.push((empty, None));
                    }
                }
            }
            if p.kind.is(Role::DefaultClass) {
                // decision D11: the actuator defaults in the order they were read.
                crate::model::defaults::order(&mut singles, |(n, _)| n, |(_, at)| *at);
            }
            // Singletons are few: their identifiers (if any) read from the nodes.
            child_idents.extend(singles.iter().map(|(n, _)| n.identifier().map(SmolStr::from)));
            children.extend(singles.into_iter().map(|(n, _)| n));
        }
        let mut c = p.first_child;
        while c != NONE {
            if let Some(n) = built[c].take() {
                children.push(n);
                child_idents.push(idents[c].take());
            }
            c = r.arena[c].next_sibling;
        }
        let p = &mut r.arena[i];
        let children: Seq<Node> = children.drain(..).collect();
        let node = Node::from_sorted(
            p.id,
            p.kind,
            std::mem::replace(&mut p.attrs, empty.clone()),
            children,
        );
        index.children(&node, &child_idents);
        built[i] = Some(node);
    }
    let root = match built.swap_remove(0) {
        Some(root) => root,
        None => {
            let root = empty_node(ElementKind::ROOT);
            index.descendants(&root);
            root
        }
    };
    // The arena is spent: freed before the index is built, which can reuse its memory.
    drop(std::mem::take(&mut r.arena));
    drop(built);
    let index = index.finish(&root, names, slashed);
    Ok(Model::from_parts(root, index, r.ctx.clone()))
}

/// The index's names of the arena (`imbl` maps: by namespace and name; the names
/// holding a `/`, counted by the part before it) and each entry's identifier; named
/// references that name an element read are resolved to it, and (with `forget`)
/// automatic names forgotten.
#[allow(clippy::type_complexity)]
fn index_names(
    r: &mut Reader<'_>,
    forget: bool,
) -> Result<
    (
        imbl::HashMap<(crate::Namespace, SmolStr), ElementId>,
        imbl::HashMap<SmolStr, u32>,
        Vec<Option<SmolStr>>,
    ),
    ReadError,
> {
    // One pass over the elements' attributes (cold since they were read): auto names
    // forgotten, the index's names (document order, so that a duplicate is reported at
    // its second occurrence, and first, so that references can be resolved in the
    // arena), each element's identifier kept for its index entry, and which elements
    // hold named references.
    let mut names: imbl::HashMap<(crate::Namespace, SmolStr), ElementId> = imbl::HashMap::new();
    // The names holding a `/`, by the part before it (`Index::slashed`).
    let mut slashed: imbl::HashMap<SmolStr, u32> = imbl::HashMap::new();
    let mut idents: Vec<Option<SmolStr>> = Vec::with_capacity(r.arena.len());
    let mut with_refs: Vec<usize> = Vec::new();
    for (i, p) in r.arena.iter_mut().enumerate() {
        if forget {
            forget_auto_name(p);
        }
        let ident = p.kind.identifier().and_then(|ident| {
            match p.attrs.iter().find(|(k, _)| *k as usize == ident).map(|(_, v)| v) {
                Some(Value::Identifier(n)) => Some(n.clone()),
                _ => None,
            }
        });
        if let (Some(ns), Some(n)) = (p.kind.namespace(), &ident) {
            if names.insert((ns, n.clone()), p.id).is_some() {
                let kind = ErrorKind::DuplicateIdentifier { namespace: ns, name: n.clone() };
                // In the file its tag is in (an included file's, maybe).
                let (file, offset) = (p.file, p.offset);
                return Err(r.err_in(file, kind, offset));
            }
            if let Some(segment) = crate::model::slashed_segment(n) {
                *slashed.entry(segment.into()).or_insert(0) += 1;
            }
        }
        if p.attrs.iter().any(|(_, v)| matches!(v, Value::Reference(Reference::Name(_)))) {
            with_refs.push(i);
        }
        idents.push(ident);
    }
    // `/` (as written by this crate and dm_control) and `main` (MuJoCo's name) both
    // name the root class, unless a class has that name.
    let root_class = r
        .arena
        .iter()
        .find(|p| p.kind.spec().parent == Some(ElementKind::ROOT) && p.kind.is(Role::DefaultClass))
        .map(|d| d.id);
    let lookup = |ns: crate::Namespace, n: &str| {
        names.get(&(ns, SmolStr::from(n))).copied().or_else(|| {
            (ns == crate::Namespace::Default && crate::model::naming::is_builtin_name(ns, n))
                .then_some(root_class)
                .flatten()
        })
    };
    for i in with_refs {
        // Only lists with a named reference change (and are uniquely owned here).
        let p = &mut r.arena[i];
        resolve_attrs(p.kind, Arc::make_mut(&mut p.attrs), lookup);
    }
    Ok((names, slashed, idents))
}

/// The number of nodes of an empty singleton of kind `k` (its own empty singletons
/// included, as `empty_node` makes them), from the schema: singletons do not nest
/// deeper than a few levels, so the recursion is shallow.
pub(super) fn empty_size(k: ElementKind) -> usize {
    1 + k.singleton_children().map(empty_size).sum::<usize>()
}

/// `<default><default class="/">…</default></default>`, the shape this crate and
/// dm_control write a model's root default class in, reads as that root class: the
/// content of the one class `/` becomes the root class's own (the writer's rules
/// "root class wrapper" and "main wrapper", `rules::folds_into_root_class`). Where the root
/// `<default>` holds other classes beside `/` (a composed model written out: the
/// attached models' root classes `robot/` are siblings of `/`, not inside it), `/` is
/// kept as a class of that name, so that the siblings keep inheriting nothing from it.
///
/// Returns whether the file is a composed model written out (a class `/` beside
/// other classes), and the arena entry of the class hoisted (no longer in the tree).
pub(super) fn hoist_root_class(arena: &mut [Pending]) -> (bool, Option<usize>) {
    let root_default = ElementKind::DEFAULT;
    if arena.is_empty() {
        return (false, None);
    }
    let Some(d) = unique_child(arena, 0, root_default) else {
        return (false, None);
    };
    // The writer's rules, asked of what was read (`policy`'s "composed output" and
    // "root class hoisting").
    let as_default_child = |c: usize| {
        let p = &arena[c];
        if !p.kind.is(Role::DefaultClass) {
            return rules::DefaultChild::Setting;
        }
        let ident = p.kind.identifier();
        let name = p.attrs.iter().find(|(k, _)| Some(*k as usize) == ident);
        rules::DefaultChild::Class(name.and_then(|(_, v)| v.as_str()))
    };
    // A class `/` beside other classes, at any level (under a named root class too).
    let composed = arena.iter().enumerate().any(|(i, p)| {
        p.kind.is(Role::DefaultClass)
            && rules::is_composed_output(children_of(arena, i).map(as_default_child))
    });
    let wrapper_attrs = !arena[d].attrs.is_empty();
    if !rules::folds_into_root_class(wrapper_attrs, children_of(arena, d).map(as_default_child)) {
        return (composed, None);
    }
    let Some(only) = children_of(arena, d).next() else { return (composed, None) };
    let ident = arena[only].kind.identifier();
    let mut attrs = std::mem::take(&mut arena[only].attrs).to_vec();
    attrs.retain(|(k, _)| Some(*k as usize) != ident);
    arena[d].attrs = rekind(arena[only].kind, root_default, attrs).into();
    // The class's children become the root class's (its one child, `only`, goes).
    let children: Vec<usize> = children_of(arena, only).collect();
    arena[d].first_child = arena[only].first_child;
    arena[d].last_child = arena[only].last_child;
    arena[only].first_child = NONE;
    arena[only].last_child = NONE;
    arena[only].first_unique = NONE;
    // The moved children are now children of the root class, whose child kinds are
    // other schema positions (with the same tags and attribute names).
    for &c in &children {
        let old = arena[c].kind;
        if let Some(new) = root_default.child(old.tag()) {
            let attrs = std::mem::take(&mut arena[c].attrs).to_vec();
            arena[c].attrs = rekind(old, new, attrs).into();
            arena[c].kind = new;
        }
    }
    arena[d].first_unique = NONE;
    for &c in &children {
        if arena[c].kind.multiplicity() != Multiplicity::Repeated {
            push_unique(arena, d, c);
        }
    }
    (composed, Some(only))
}

/// Automatic names (`//unnamed_geom_0`, written by this crate and by dm_control) mean
/// "unnamed": they are derived again when the model is written (the writer's rule
/// "automatic names", `rules::is_auto_name`). (In a composed model
/// written out they are kept: there they were counted over the outer model's own
/// elements, which the flat model read back no longer tells apart.)
pub(super) fn forget_auto_name(p: &mut Pending) {
    let Some(ident) = p.kind.identifier() else { return };
    let auto = |(k, v): &Attr| *k as usize == ident && v.as_str().is_some_and(rules::is_auto_name);
    if p.attrs.iter().any(auto) {
        let mut attrs = p.attrs.to_vec();
        attrs.retain(|a| !auto(a));
        p.attrs = attrs.into();
    }
}

/// Attributes of an element of kind `from` as attributes of kind `to` (by name).
pub(super) fn rekind(from: ElementKind, to: ElementKind, attrs: Vec<Attr>) -> Vec<Attr> {
    let mut out: Vec<Attr> = attrs
        .into_iter()
        .filter_map(|(i, v)| Some((to.attr_index(from.attr(i as usize).name)? as u16, v)))
        .collect();
    out.sort_by_key(|(k, _)| *k);
    out
}

/// Replaces every named reference that `lookup` finds by a reference to the element.
pub(super) fn resolve_attrs(
    kind: ElementKind,
    attrs: &mut [Attr],
    lookup: impl Fn(crate::Namespace, &str) -> Option<ElementId>,
) {
    for j in 0..attrs.len() {
        let (i, v) = &attrs[j];
        let Value::Reference(Reference::Name(n)) = v else { continue };
        let AttrType::Reference(target) = kind.attr(*i as usize).ty else { continue };
        let other = target.depends_on().and_then(|k| attrs.iter().find(|(x, _)| *x as usize == k));
        let ns = target.namespace(other.map(|(_, v)| v.as_str().unwrap_or("")));
        if let Some(id) = ns.and_then(|ns| lookup(ns, n)) {
            attrs[j].1 = Value::Reference(Reference::Element(id));
        }
    }
}
