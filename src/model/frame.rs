//! The rules of attachment frames: what a frame copies from its site, which of its
//! attributes can be set later, and which children it takes.

use crate::error::ErrorKind;
use crate::schema::ElementKind;

use super::tree::{Attr, Node};

/// The site attributes an attachment frame copies (reference §3.3).
pub(crate) const FRAME_ATTRS: [&str; 7] =
    ["pos", "quat", "axisangle", "xyaxes", "zaxis", "euler", "user"];

/// Whether a frame accepts attribute `name` after the attach: the copied ones and
/// `mocap`.
pub(crate) fn frame_settable(name: &str) -> bool {
    name == "mocap" || FRAME_ATTRS.contains(&name)
}

/// The frame attributes copied from a site, as attributes of `body_kind`.
pub(crate) fn frame_attrs(site: &Node, body_kind: ElementKind) -> Vec<Attr> {
    let theirs = frame_attr_indices(site.kind());
    let ours = frame_attr_indices(body_kind);
    theirs
        .iter()
        .zip(ours)
        .filter_map(|(s, b)| Some(((*b)?, site.attr(usize::from((*s)?))?.clone())))
        .collect()
}

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
    let tag = child.kind().tag();
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
    match tag {
        "joint" => Ok(()),
        "inertial" | "freejoint" => {
            if tag == "freejoint" && parent.is_none_or(|p| p.kind().tag() != "worldbody") {
                return Err(ErrorKind::FreejointNotTopLevel(scope.into()));
            }
            if frame.children().iter().any(|c| c.kind() == child.kind()) {
                return Err(ErrorKind::DuplicateChild(child.kind().tag()));
            }
            Ok(())
        }
        _ => Err(ErrorKind::InvalidChild { parent: "body", tag: tag.into(), suggestion: None }),
    }
}
