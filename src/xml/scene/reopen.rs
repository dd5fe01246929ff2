//! Reading a scene back composed: MuJoCo's `<attach>` of an asset `<model>`, at a
//! frame-shaped body, becomes an attachment of that model again.
//!
//! What reopens as an attachment, what stays an element and why a flat file never
//! reopens composed are the manual's rules ([Scenes](crate::guide#scenes)); this
//! module applies them.

use std::collections::HashMap;
use std::path::PathBuf;
use std::sync::Arc;

use smol_str::SmolStr;

use crate::files::FileContext;
use crate::model::frame::FRAME_ATTRS;
use crate::model::naming::Written;
use crate::model::settings;
use crate::model::tree::{Attached, Attr, ElementId, Node};
use crate::model::{Index, Model, Walk};
use crate::schema::{ElementKind, Role};
use crate::seq::Seq;
use crate::value::{Reference, Value};

/// An asset model's file that reopening needs read: the reader reads it as a model
/// (which may reopen in turn) and hands it to [`reopen`] under `asset`. Reopening
/// never reads a file itself: it is a step after reading.
pub(crate) struct PartFile {
    /// The asset `<model>` that names it.
    pub(crate) asset: ElementId,
    /// Its path, as the model's files locate it.
    pub(crate) path: PathBuf,
    /// Its text.
    pub(crate) text: Arc<str>,
    /// What identifies its content: its canonical path and its contents' SHA-1 (a file
    /// several asset models name is read once).
    pub(crate) key: (PathBuf, String),
    /// The file context its own files resolve in.
    pub(crate) ctx: FileContext,
}

/// The asset model files of `model` (read literally from `text`) that an `<attach>`
/// of a saved scene's shape may use: nothing when the model has no asset `<model>` or
/// `text` has no `<attach`.
///
/// Time: O(assets); with an asset `<model>`, O(L) to look for `<attach` in the `L`
/// bytes of text, and where there is one, O(L) more for the asset models' paths.
pub(crate) fn parts_to_read(model: &Model, text: &str) -> Vec<PartFile> {
    // A scene's `<attach>` names an asset `<model>`: without one (most files), the
    // text is not searched.
    let Some(asset) = model.root.child_of_kind(ElementKind::ASSET) else {
        return Vec::new();
    };
    let is_model = |c: &Node| c.kind().is(Role::AssetModel);
    if !asset.children().iter().any(is_model) || !text.contains("<attach") {
        return Vec::new();
    }
    let paths = asset_model_paths(text);
    let mut out = Vec::new();
    for node in asset.children().iter().filter(|c| c.kind().is(Role::AssetModel)) {
        let kind = node.kind();
        let Some(path) = node.identifier().and_then(|name| paths.get(name)) else { continue };
        let has = |a: &str| kind.attr_index(a).is_some_and(|i| node.attr(i).is_some());
        if has("content_type") {
            continue;
        }
        let Some(Value::File(file)) = kind.attr_index("file").and_then(|i| node.attr(i)) else {
            continue;
        };
        let Ok(text) = std::str::from_utf8(file.contents()) else { continue };
        let Ok((full, _)) = model.files.locate(None, path) else { continue };
        out.push(PartFile {
            asset: node.id(),
            key: (crate::files::canonical(&full), file.sha1_hex().to_string()),
            ctx: model.files.for_included(&full),
            text: text.into(),
            path: full,
        });
    }
    out
}

/// `model` with every `<attach>` that has the shape of a saved scene's reopened as an
/// attachment of the model read from its asset's file (`parts`, by asset `<model>`;
/// see the module documentation); `model` itself when none has.
///
/// Time: O(n log n) for a model of `n` elements (the tree rebuilt and indexed, at
/// most once per attachment that does not reopen) when any part is given; O(1)
/// otherwise.
pub(crate) fn reopen(model: Model, parts: HashMap<ElementId, Model>) -> Model {
    reopened(&model, parts).unwrap_or(model)
}

/// A body that reopens, if the checks after building agree.
#[derive(Clone)]
struct Candidate {
    /// The body (or `<frame>`); its id becomes the frame's.
    id: ElementId,
    scope: SmolStr,
    /// The asset `<model>` its `<attach>` names.
    asset: ElementId,
    /// Written as MuJoCo's `<frame>`.
    as_frame: bool,
}

fn reopened(model: &Model, mut parts: HashMap<ElementId, Model>) -> Option<Model> {
    if parts.is_empty() {
        return None;
    }
    // The parent's own settings must already hold each part's.
    let own: Arc<[Node]> = settings::own_sections(model).into();
    parts.retain(|_, part| {
        settings::merged(part)
            .and_then(|theirs| settings::folded(&own, &theirs))
            .is_ok_and(|f| Arc::ptr_eq(&f, &own))
    });
    let mut candidates = find_candidates(model, &parts);
    // Build; drop what the built model says did not reopen exactly; build again.
    loop {
        if candidates.is_empty() {
            return None;
        }
        let (built, refused) = build(model, &candidates, &parts)?;
        if refused.is_empty() {
            return Some(built);
        }
        candidates.retain(|c| !refused.contains(&c.id));
    }
}

/// The `file` of every asset `<model name=...>` written in `text` itself (not in an
/// include), by name, as the file scan finds them (`files::scan`).
fn asset_model_paths(text: &str) -> HashMap<String, String> {
    crate::files::scan::named_files(text, ElementKind::ROOT)
        .into_iter()
        .filter_map(|f| Some((f.model?, f.file)))
        .collect()
}

/// The bodies and frames with a scene's attachment shape whose model is among
/// `parts` (before the checks that need the built model).
fn find_candidates(model: &Model, parts: &HashMap<ElementId, Model>) -> Vec<Candidate> {
    let Some(wb) = model.root.child_of_kind(ElementKind::WORLDBODY) else {
        return Vec::new();
    };
    let mut out: Vec<Candidate> = Vec::new();
    // (node, whether it is in the world: the worldbody or a `<frame>` there).
    let mut stack: Vec<(&Node, bool)> = vec![(wb, true)];
    while let Some((parent, world)) = stack.pop() {
        for c in parent.children().iter().rev() {
            match c.kind().role() {
                Some(Role::Body) => {
                    if let Some(cand) = candidate(parent, c, world, parts) {
                        out.push(cand);
                    } else {
                        stack.push((c, false));
                    }
                }
                Some(Role::Frame) => {
                    if let Some(cand) = candidate(parent, c, world, parts) {
                        out.push(cand);
                    } else {
                        stack.push((c, world));
                    }
                }
                // A `<replicate>`'s content stays as it is.
                _ => {}
            }
        }
    }
    // Document order (the walk took the last child first).
    out.reverse();
    // A scope used twice is ambiguous: neither reopens.
    let mut count: HashMap<SmolStr, usize> = HashMap::new();
    for c in &out {
        *count.entry(c.scope.clone()).or_default() += 1;
    }
    out.retain(|c| count[&c.scope] == 1);
    out
}

/// `node` (a child of `parent`) as a candidate, if it has the shape.
fn candidate(
    parent: &Node,
    node: &Node,
    world: bool,
    parts: &HashMap<ElementId, Model>,
) -> Option<Candidate> {
    let kind = node.kind();
    let is_frame = kind.is(Role::Frame);
    if is_frame && !world {
        return None;
    }
    let (attach, own) =
        node.children().iter().collect::<Vec<_>>().split_last().map(|(a, o)| (*a, o.to_vec()))?;
    if !attach.kind().is(Role::Attach) {
        return None;
    }
    // The `<attach>`: a model and a prefix `s/`, nothing else.
    let ak = attach.kind();
    let mut asset = None;
    let mut prefix = None;
    for (i, v) in attach.attrs() {
        match (ak.attr(*i as usize).name, v) {
            ("model", Value::Reference(Reference::Element(id))) => asset = Some(*id),
            ("prefix", Value::String(p)) => prefix = Some(p.clone()),
            _ => return None,
        }
    }
    let (asset, prefix) = (asset?, prefix?);
    parts.get(&asset)?;
    let scope = prefix.strip_suffix('/')?;
    if scope.is_empty() || scope.contains('/') || crate::model::check_model_name(scope).is_err() {
        return None;
    }
    if node.identifier() != Some(prefix.as_str()) {
        return None;
    }
    // A frame's attributes only.
    let ok_attr = |name: &str| {
        name == "name"
            || (is_frame && FRAME_ATTRS[..6].contains(&name))
            || (!is_frame && (FRAME_ATTRS.contains(&name) || name == "mocap"))
    };
    if !node.attrs().iter().all(|(i, _)| ok_attr(kind.attr(*i as usize).name)) {
        return None;
    }
    // Joints (a freejoint only in the world) and one inertial, on a body only.
    if is_frame && !own.is_empty() {
        return None;
    }
    let in_world = parent.kind().is(Role::Worldbody) || world;
    let mut inertials = 0;
    for c in &own {
        match c.kind().role() {
            Some(Role::Joint) => {}
            Some(Role::Freejoint) if in_world => {}
            Some(Role::Inertial) => inertials += 1,
            _ => return None,
        }
        if c.kind().namespace().is_some() {
            frame_joint_name(scope, c.identifier())?;
        }
    }
    if inertials > 1 {
        return None;
    }
    Some(Candidate { id: node.id(), scope: scope.into(), asset, as_frame: is_frame })
}

/// What a joint named `name` on the frame body of scope `scope` is named as a frame
/// joint: `Some(None)` for unnamed (`s/`, or no name), `Some(Some(j))` for `s/j/`;
/// `None` for a name no frame joint is written with.
fn frame_joint_name(scope: &str, name: Option<&str>) -> Option<Option<SmolStr>> {
    let Some(name) = name.filter(|n| !n.is_empty()) else { return Some(None) };
    let rest = name.strip_prefix(scope)?.strip_prefix('/')?;
    if rest.is_empty() {
        return Some(None);
    }
    let j = rest.strip_suffix('/')?;
    (!j.is_empty() && !j.contains('/')).then(|| Some(j.into()))
}

/// The model with `candidates` reopened, and the candidates the built model shows
/// did not reopen exactly (their joints' or their tag's written form differs, or a
/// literal name of the file starts with their scope). `None` if the model cannot be
/// indexed (then nothing reopens).
fn build(
    model: &Model,
    candidates: &[Candidate],
    parts: &HashMap<ElementId, Model>,
) -> Option<(Model, Vec<ElementId>)> {
    let by_id: HashMap<ElementId, &Candidate> = candidates.iter().map(|c| (c.id, c)).collect();
    // The names the file gave the joints of each frame body, by joint id.
    let mut literal: HashMap<ElementId, Option<SmolStr>> = HashMap::new();
    let used: Vec<ElementId> = candidates.iter().map(|c| c.asset).collect();
    let root = model.root.rebuild(|n, children| {
        let changed = children.iter().zip(n.children().iter()).any(|(a, b)| !a.ptr_eq(b));
        let mut children: Vec<Node> = children.iter().cloned().collect();
        for c in children.iter_mut() {
            if let Some(cand) = by_id.get(&c.id()) {
                if let Some(frame) = as_frame_node(n, c, cand, parts, &mut literal) {
                    *c = frame;
                }
            }
        }
        let children: Vec<Node> = if n.kind() == ElementKind::ASSET {
            // Asset models only reopened attachments used go.
            children
                .into_iter()
                .filter(|c| !(c.kind().is(Role::AssetModel) && used.contains(&c.id())))
                .collect()
        } else {
            children
        };
        if !changed
            && children.len() == n.children().len()
            && children.iter().zip(n.children().iter()).all(|(a, b)| a.ptr_eq(b))
        {
            return n.clone();
        }
        n.with_children(children.into_iter().collect::<Seq<Node>>())
    });
    // An asset model still named by an `<attach>` that stays is kept: then nothing
    // of it is removed, so build again keeping every asset model.
    let still_used = root.descendants().any(|n| {
        n.kind().is(Role::Attach)
            && n.attrs().iter().any(
                |(_, v)| matches!(v, Value::Reference(Reference::Element(id)) if used.contains(id)),
            )
    });
    let root = if still_used { restore_assets(&root, &model.root) } else { root };
    let mut index = Index::default();
    index.insert_subtree(None, &root, 0).ok()?;
    let mut refused = Vec::new();
    for c in candidates {
        let free = index.free_scope_name(&c.scope);
        if free.name != c.scope || index.has_slashed_segment(&c.scope) {
            refused.push(c.id);
            continue;
        }
        index.scopes.push(&c.scope, free, c.id);
    }
    if !refused.is_empty() {
        return Some((model.clone(), refused));
    }
    let built = Model::from_parts(root, index, FileContext::clone(&model.files));
    settings::check(&built).ok()?;
    // Each frame is written as the file had it: its tag, and its joints' names.
    let walk = Walk::new(&built);
    let mut frame_tags = crate::xml::FrameTags::default();
    for c in candidates {
        let Some(frame) = built.node_by_id(c.id) else {
            refused.push(c.id);
            continue;
        };
        let parent_world = c.as_frame || {
            let parent = built.index.parent(c.id).and_then(|p| built.node_by_id(p));
            parent.is_some_and(|p| p.kind().is(Role::Worldbody))
        };
        if (parent_world && frame_tags.keeps_bodies_top_level(frame)) != c.as_frame {
            refused.push(c.id);
            continue;
        }
        let same = frame.children().iter().filter(|j| j.kind().namespace().is_some()).all(|j| {
            let written = walk.insts.name_of_id(0, j.id());
            match (literal.get(&j.id()), written) {
                (Some(Some(name)), Some(w)) => w.to_string_in("") == name.as_str(),
                (Some(None), Some(Written::Auto { .. })) => true,
                _ => false,
            }
        });
        if !same {
            refused.push(c.id);
        }
    }
    Some((built, refused))
}

/// `root` with the asset models of `original` put back.
fn restore_assets(root: &Node, original: &Node) -> Node {
    let kind = ElementKind::ASSET;
    let (Some(at), Some(asset)) =
        (root.children().iter().position(|c| c.kind() == kind), original.child_of_kind(kind))
    else {
        return root.clone();
    };
    root.with_child_at(at, asset.clone())
}

/// The candidate body `node` (a child of `parent`) as an attachment frame of its
/// part, its joints renamed as frame joints (their names in the file recorded in
/// `literal`).
fn as_frame_node(
    parent: &Node,
    node: &Node,
    cand: &Candidate,
    parts: &HashMap<ElementId, Model>,
    literal: &mut HashMap<ElementId, Option<SmolStr>>,
) -> Option<Node> {
    let part = parts.get(&cand.asset)?;
    let body = parent.kind().child_of_role(Role::Body)?;
    let kind = node.kind();
    let mut attrs: Vec<Attr> = node
        .attrs()
        .iter()
        .filter(|(i, _)| Some(*i as usize) != kind.identifier())
        .filter_map(|(i, v)| {
            Some((body.attr_index(kind.attr(*i as usize).name)? as u16, v.clone()))
        })
        .collect();
    attrs.sort_by_key(|(i, _)| *i);
    let children: Seq<Node> = node
        .children()
        .iter()
        .filter(|c| !c.kind().is(Role::Attach))
        .map(|c| {
            let Some(i) = c.kind().identifier().filter(|_| c.kind().namespace().is_some()) else {
                return c.clone();
            };
            literal.insert(c.id(), c.identifier().filter(|n| !n.is_empty()).map(SmolStr::from));
            let name = frame_joint_name(&cand.scope, c.identifier()).flatten();
            let mut attrs: Vec<Attr> =
                c.attrs().iter().filter(|(k, _)| *k as usize != i).cloned().collect();
            if let Some(n) = name {
                attrs.push((i as u16, Value::Identifier(n)));
            }
            c.with_attrs(attrs)
        })
        .collect();
    let attached = Attached { scope: cand.scope.clone(), model: part.clone() };
    Some(Node::frame(node.id(), body, attrs, attached).with_children(children))
}
