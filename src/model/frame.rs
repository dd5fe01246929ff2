//! The rules of attachment frames: what a frame copies from its site, which of its
//! attributes can be set later, which children it takes, and whether it is written
//! as MuJoCo's `<frame>` (keeping its model's free bodies top level).

use std::collections::HashMap;

use crate::error::ErrorKind;
use crate::schema::{ElementKind, Role};

use super::Model;
use super::layout::{self, JointType};
use super::tree::{Attr, ElementId, Node};

/// The site attributes an attachment frame copies (reference §3.3).
pub(crate) const FRAME_ATTRS: [&str; 7] =
    ["pos", "quat", "axisangle", "xyaxes", "zaxis", "euler", "user"];

/// Whether a frame accepts attribute `name` after the attach: the copied ones and
/// `mocap`.
pub(crate) fn frame_settable(name: &str) -> bool {
    name == "mocap" || FRAME_ATTRS.contains(&name)
}

/// The frame attributes of an attachment at `site` (at `path` in `model`), placing
/// the frame where MuJoCo places the site (decision D15): its own attributes, and where
/// it sets neither a position nor an orientation, those its default classes give it;
/// a `fromto` gives both (its middle, and the direction from its end back to its
/// start as the z axis), as MuJoCo reads it. dm_control copies the site's own
/// attributes only, which puts the frame elsewhere than the site when its class or a
/// `fromto` places it.
///
/// Each element's attributes are read in one pass (a table per kind gives each
/// attribute index its part: [`slotted`]), never looked up by name: an attach is a
/// few thousand instructions, and this is a part of it.
pub(crate) fn placed_frame_attrs(
    model: &super::Model,
    path: &[usize],
    site: &Node,
    body_kind: ElementKind,
) -> Vec<Attr> {
    use crate::value::{Reference, Value};
    let ours = frame_attr_indices(body_kind);
    let own = slotted(site);
    let mut attrs: Vec<Attr> = Vec::with_capacity(FRAME_ATTRS.len());
    if let Some(ft) = own[FROMTO].and_then(Value::as_floats).filter(|f| f.len() == 6) {
        // MuJoCo's z axis points from `to` back to `from`; the site's own orientation
        // attributes give way to it.
        let mid: Vec<f64> = (0..3).map(|i| (ft[i] + ft[i + 3]) / 2.0).collect();
        let dir: Vec<f64> = (0..3).map(|i| ft[i] - ft[i + 3]).collect();
        let placed = [(POS, Value::Floats(mid.into())), (ZAXIS, Value::Floats(dir.into()))];
        let rest = (0..FRAME_ATTRS.len()).filter(|i| !PLACING.contains(i));
        let rest = rest.filter_map(|i| Some((i, own[i]?.clone())));
        attrs.extend(placed.into_iter().chain(rest).filter_map(|(i, v)| Some((ours[i]?, v))));
        attrs.sort_by_key(|(i, _)| *i);
        return attrs;
    }
    for (i, b) in ours.iter().enumerate() {
        if let (Some(b), Some(v)) = (b, own[i]) {
            attrs.push((*b, v.clone()));
        }
    }
    let need_pos = own[POS].is_none();
    let need_orientation = ORIENTATION.iter().all(|&i| own[i].is_none());
    if !(need_pos || need_orientation) {
        return attrs;
    }
    // The class in force: the site's own, else the nearest `childclass` above it, else
    // the model's root class. Its chain is walked once, nearest class first, keeping
    // the nearest value of each attribute.
    let class = match own[CLASS] {
        Some(Value::Reference(Reference::Element(id))) => Some(*id),
        _ => nearest_childclass(model, path),
    };
    let mut given: [Option<&Value>; SLOTS] = [None; SLOTS];
    for d in super::layout::class_defaults_in_force(model, site.kind(), class) {
        for (g, v) in given.iter_mut().zip(slotted(d)) {
            *g = g.or(v);
        }
    }
    let mut give = |i: usize, v: &Value| {
        if let Some(b) = ours[i] {
            attrs.retain(|(j, _)| *j != b);
            attrs.push((b, v.clone()));
        }
    };
    if let Some(v) = given[POS].filter(|_| need_pos) {
        give(POS, v);
    }
    // The first orientation attribute (in MuJoCo's order) that a class gives.
    if let Some(&i) = ORIENTATION.iter().find(|&&i| given[i].is_some()).filter(|_| need_orientation)
    {
        if let Some(v) = given[i] {
            give(i, v);
        }
    }
    attrs.sort_by_key(|(i, _)| *i);
    attrs
}

/// The parts of an element's attributes that place a frame: [`FRAME_ATTRS`] (by their
/// positions there), then `fromto` and the element's `class`.
const FROMTO: usize = FRAME_ATTRS.len();
const CLASS: usize = FROMTO + 1;
const SLOTS: usize = CLASS + 1;

/// The values `node` sets of each part ([`FROMTO`], [`CLASS`], [`FRAME_ATTRS`]), in
/// one pass over its attributes, each given its part by a table made once per kind.
#[inline(always)]
fn slotted(node: &Node) -> [Option<&crate::value::Value>; SLOTS] {
    static TABLE: std::sync::OnceLock<Vec<Box<[u8]>>> = std::sync::OnceLock::new();
    let table = TABLE.get_or_init(|| {
        ElementKind::all()
            .map(|k| {
                let mut parts = vec![u8::MAX; k.spec().attrs.len()];
                let named = frame_attr_indices(k).iter().map(|i| i.map(usize::from)).enumerate();
                let more = [(FROMTO, k.attr_index("fromto")), (CLASS, k.class_attr())];
                for (part, i) in named.chain(more) {
                    if let Some(slot) = i.and_then(|i| parts.get_mut(i)) {
                        *slot = part as u8;
                    }
                }
                parts.into_boxed_slice()
            })
            .collect()
    });
    let mut out = [None; SLOTS];
    let parts = table.get(node.kind().0 as usize).map_or(&[][..], |p| &p[..]);
    for (i, v) in node.attrs() {
        if let Some(slot) = parts.get(usize::from(*i)).and_then(|&p| out.get_mut(usize::from(p))) {
            *slot = Some(v);
        }
    }
    out
}

/// The `childclass` nearest above the element at `path` (its ancestors', the root's
/// included, not its own), found in one walk down the path: O(depth), where looking
/// up each ancestor by its path from the root was O(depth²).
fn nearest_childclass(
    model: &super::Model,
    path: &[usize],
) -> Option<crate::model::tree::ElementId> {
    let mut nearest = None;
    let mut node = &model.root;
    for &i in path {
        nearest = super::layout::childclass_of(node).or(nearest);
        match node.children().get(i) {
            Some(child) => node = child,
            None => break,
        }
    }
    nearest
}

/// The positions in [`FRAME_ATTRS`] of `pos`, of the attributes that orient a site
/// or a frame (in MuJoCo's order of precedence), and of `zaxis`; `PLACING` is both.
const POS: usize = 0;
const ORIENTATION: [usize; 5] = [1, 2, 3, 4, 5];
const ZAXIS: usize = 4;
const PLACING: [usize; 6] = [0, 1, 2, 3, 4, 5];

/// The attributes that orient a site or a frame, in [`FRAME_ATTRS`]' order.
pub(crate) const ORIENTATIONS: [&str; 5] = ["quat", "axisangle", "xyaxes", "zaxis", "euler"];

/// The schema indices of [`FRAME_ATTRS`] in `kind` (`None` where it has no such
/// attribute), from a table computed once for all kinds: an attach asks for two
/// kinds, which by name would be 14 binary searches of attribute names.
fn frame_attr_indices(kind: ElementKind) -> &'static [Option<u16>; FRAME_ATTRS.len()] {
    static TABLE: std::sync::OnceLock<Vec<[Option<u16>; FRAME_ATTRS.len()]>> =
        std::sync::OnceLock::new();
    const NONE: [Option<u16>; FRAME_ATTRS.len()] = [None; FRAME_ATTRS.len()];
    let table = TABLE.get_or_init(|| {
        ElementKind::all()
            .map(|k| FRAME_ATTRS.map(|n| k.attr_index(n).and_then(|i| u16::try_from(i).ok())))
            .collect()
    });
    table.get(kind.0 as usize).unwrap_or(&NONE)
}

/// Checks a new child of an attachment frame: joints, one inertial, and one freejoint
/// if the frame sits directly in the worldbody (`parent` is the frame's parent).
/// `scope` names the frame in errors.
pub(crate) fn check_frame_child(
    parent: Option<&Node>,
    frame: &Node,
    child: &Node,
    scope: &str,
) -> Result<(), ErrorKind> {
    // The frame's joints have a namespace of their own.
    if let (Some(ns), Some(name)) = (child.kind().namespace(), child.identifier()) {
        if frame.children().iter().any(|c| c.identifier() == Some(name)) {
            return Err(ErrorKind::DuplicateIdentifier { namespace: ns, name: name.into() });
        }
    }
    // Unnamed joints are any number: the first is written with the frame's name
    // (`robot/`), the others with their automatic names (`model::naming`). A
    // freejoint beside other joints is MuJoCo's to refuse (more than 6 degrees of
    // freedom), as for any body: `Model::check` reports it.
    let role = child.kind().role();
    match role {
        Some(Role::Joint) => Ok(()),
        Some(Role::Inertial | Role::Freejoint) => {
            let in_world = parent.is_some_and(|p| p.kind().is(Role::Worldbody));
            if role == Some(Role::Freejoint) && !in_world {
                return Err(ErrorKind::FreejointNotTopLevel(scope.into()));
            }
            if frame.children().iter().any(|c| c.kind() == child.kind()) {
                return Err(ErrorKind::DuplicateChild(child.kind().tag()));
            }
            Ok(())
        }
        _ => {
            let tag = child.kind().tag().into();
            Err(ErrorKind::InvalidChild { parent: "body", tag, suggestion: None })
        }
    }
}

/// Whether an attachment frame in the world is written as MuJoCo's
/// `<frame>` rather than a `<body>`: when the attached model has a body with a free
/// joint at its world level, which MuJoCo accepts only on top-level bodies, and the
/// frame itself neither moves nor has mass (no joints, no inertial) nor carries
/// body-only attributes (`user`, `mocap`). Any other frame stays a body, as in the
/// reference. The model's world level is its worldbody's children and, through them,
/// the content of MuJoCo's `<frame>`s and `<replicate>`s and of attachment frames
/// written as `<frame>` in turn; a joint is free by its own `type` or its classes'.
///
/// A one-off answer; a writer asks [`FrameTags::keeps_bodies_top_level`], which keeps
/// the answers.
pub(crate) fn frame_keeps_bodies_top_level(frame: &Node) -> bool {
    FrameTags::default().keeps_bodies_top_level(frame)
}

/// The answers of [`frame_keeps_bodies_top_level`] given so far, per frame node (by
/// address: nodes never change, and they outlive one write that borrows them). An
/// answer follows the attached model's world level into the attachments there,
/// nested to any depth; kept, each frame's world level is looked at once per write,
/// where asking each frame of a chain of nested attachments anew went down the whole
/// chain from each (quadratic in the levels).
#[derive(Default)]
pub(crate) struct FrameTags(HashMap<*const (), bool>);

/// A frame whose answer waits on those of the attachment frames at its model's world
/// level (`nested`, those not asked yet).
struct Waiting<'a> {
    frame: *const (),
    nested: Vec<&'a Node>,
}

impl FrameTags {
    /// [`frame_keeps_bodies_top_level`] of `frame`, each nested frame's answer kept
    /// too. Iterative (frames waiting on their nested frames, on a list), so
    /// attachments nested to any depth are followed without recursion.
    pub(crate) fn keeps_bodies_top_level(&mut self, frame: &Node) -> bool {
        let mut waiting: Vec<Waiting<'_>> = Vec::new();
        let mut answer = self.start(frame, &mut waiting);
        loop {
            if let Some(found) = answer {
                if waiting.is_empty() {
                    return found;
                }
                if found {
                    // The frame waiting on this one holds a free body through it.
                    if let Some(w) = waiting.pop() {
                        self.0.insert(w.frame, true);
                    }
                    continue;
                }
            }
            let Some(w) = waiting.last_mut() else { return false };
            answer = match w.nested.pop() {
                Some(next) => self.start(next, &mut waiting),
                None => {
                    // No nested frame holds one either.
                    let frame = w.frame;
                    waiting.pop();
                    self.0.insert(frame, false);
                    Some(false)
                }
            };
        }
    }

    /// The answer for `frame` if it is known or found at its own model's world level;
    /// else `None`, and the frame waits on the attachment frames there.
    fn start<'a>(&mut self, frame: &'a Node, waiting: &mut Vec<Waiting<'a>>) -> Option<bool> {
        let key = frame.as_ptr();
        if let Some(&known) = self.0.get(&key) {
            return Some(known);
        }
        let mut todo: Vec<WorldLevel<'_>> = Vec::new();
        push_world_level(frame, &mut todo);
        let mut nested = Vec::new();
        while let Some(level) = todo.pop() {
            for c in level.container.children().iter() {
                if c.attached().is_some() {
                    nested.push(c);
                    continue;
                }
                let inherited = layout::childclass_of(c).or(level.childclass);
                match c.kind().role() {
                    Some(Role::Body)
                        if has_free_joint(level.model, c, inherited, level.root_class) =>
                    {
                        self.0.insert(key, true);
                        return Some(true);
                    }
                    Some(Role::Frame | Role::Replicate) => {
                        todo.push(WorldLevel { container: c, childclass: inherited, ..level });
                    }
                    _ => {}
                }
            }
        }
        if nested.is_empty() {
            self.0.insert(key, false);
            return Some(false);
        }
        nested.reverse();
        waiting.push(Waiting { frame: key, nested });
        None
    }
}

/// An element at a model's world level whose children are at that level too (its
/// worldbody, a MuJoCo `<frame>` or `<replicate>` there): `childclass` is the class
/// its children inherit, if any.
#[derive(Clone, Copy)]
struct WorldLevel<'a> {
    model: &'a Model,
    container: &'a Node,
    childclass: Option<ElementId>,
    root_class: Option<ElementId>,
}

/// Adds the world level of `frame`'s model to `todo` if `frame` is an attachment frame
/// that can be written as `<frame>` (empty, without body-only attributes).
fn push_world_level<'a>(frame: &'a Node, todo: &mut Vec<WorldLevel<'a>>) {
    let Some(a) = frame.attached() else { return };
    if !frame.children().is_empty() {
        return;
    }
    let kind = frame.kind();
    let body_only = ["user", "mocap"]
        .iter()
        .any(|n| kind.attr_index(n).is_some_and(|i| frame.attr(i).is_some()));
    if body_only {
        return;
    }
    let Some(wb) = section_of(&a.model, "worldbody") else { return };
    let root_class = section_of(&a.model, "default").map(Node::id);
    todo.push(WorldLevel { model: &a.model, container: wb, childclass: None, root_class });
}

/// Whether `body` (its children inheriting class `inherited`) has a free joint, by
/// the joint's own `type` or its classes'.
fn has_free_joint(
    model: &Model,
    body: &Node,
    inherited: Option<ElementId>,
    root_class: Option<ElementId>,
) -> bool {
    body.children().iter().any(|j| {
        matches!(j.kind().role(), Some(Role::Joint | Role::Freejoint)) && {
            let class = layout::class_of(j).or(inherited).or(root_class);
            layout::joint_type(model, j, class) == JointType::Free
        }
    })
}

fn section_of<'m>(model: &'m Model, tag: &str) -> Option<&'m Node> {
    model.root.child_of_kind(ElementKind::ROOT.child(tag)?)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_placing_positions_name_the_placing_attributes() {
        assert_eq!(FRAME_ATTRS[POS], "pos");
        assert_eq!(FRAME_ATTRS[ZAXIS], "zaxis");
        assert_eq!(ORIENTATION.map(|i| FRAME_ATTRS[i]), ORIENTATIONS);
        assert!(PLACING.iter().all(|i| *i == POS || ORIENTATION.contains(i)));
        assert_eq!(PLACING.len(), ORIENTATION.len() + 1);
    }
}
