//! Repairs after a remove: what referred to the removed elements is cleared or
//! removed in turn, so that an edit leaves no more problems than before.

use crate::model::{Attrs, Loc, Model, ProblemKind};
use crate::schema::{ElementKind, Role};

/// Removes `loc`, then repairs what referred to anything removed: optional
/// references in the body tree and in assets are cleared, other referring elements
/// removed (a tendon's joint takes its tendon along). `None` if that does not bring
/// the problems back to `allowed`.
pub(super) fn remove_repaired(m: &Model, loc: &Loc, allowed: usize) -> Option<Model> {
    let mut cur = m.remove(loc).ok()?;
    for _ in 0..16 {
        let problems = cur.check();
        if problems.len() <= allowed {
            return Some(cur);
        }
        let p = problems.into_iter().find(|p| {
            matches!(
                p.kind,
                ProblemKind::DanglingReference { .. }
                    | ProblemKind::RemovedReference { .. }
                    | ProblemKind::MissingRequired { .. }
            )
        })?;
        let e = cur.element(&p.loc)?;
        let parent = e.parent()?;
        let attribute = match p.kind {
            ProblemKind::DanglingReference { attribute, .. }
            | ProblemKind::RemovedReference { attribute }
            | ProblemKind::MissingRequired { attribute } => attribute,
            _ => return None,
        };
        let optional = !e.kind().attr(e.kind().attr_index(attribute)?).required;
        let in_tendon = parent.kind().is(Role::Tendon);
        let in_tree = !in_tendon && (in_body_tree(e.kind()) || in_assets(e.kind()));
        cur = if e.kind().is(Role::Geom) && attribute == "mesh" {
            // A mesh geom without its mesh becomes a sphere.
            let attrs = Attrs::new().clear("mesh").set("type", "sphere").set("size", [0.1]);
            cur.set(&p.loc, attrs).ok()?
        } else if optional && in_tree {
            cur.clear_attr(&p.loc, attribute).ok()?
        } else if in_tendon {
            cur.remove(&parent.loc()).ok()?
        } else {
            cur.remove(&p.loc).ok()?
        };
    }
    None
}

/// Whether elements of `kind` are in the kinematic tree (below the worldbody).
pub(super) fn in_body_tree(kind: ElementKind) -> bool {
    let mut cur = kind.spec().parent;
    while let Some(k) = cur {
        if k.is(Role::Worldbody) {
            return true;
        }
        cur = k.spec().parent;
    }
    false
}

/// Whether elements of `kind` are assets (children of the `<asset>` section).
pub(super) fn in_assets(kind: ElementKind) -> bool {
    kind.spec().parent == Some(ElementKind::ASSET)
}
