//! The merged global settings of a model with attachments (reference §3.4–§3.5).
//!
//! `compiler`, `option`, `size`, `visual` and `statistic` (with their singleton
//! sub-elements) of a composed model are a fold over the model's own values and each
//! attachment's merged values, in attach order, depth first. Only explicitly set values
//! take part; `min`, `max` and `max_bytes` combine, `replace` attributes (the compiler's
//! folders) are never taken from an attachment, and every other attribute must agree.
//!
//! Nothing of this is stored: the writer folds when it writes, and every operation
//! that can change the fold (attach, an edit of a setting on either side) folds once
//! to refuse a conflict before it returns the new value.

use crate::error::ErrorKind;
use crate::model::Model;
use crate::schema::{AttrType, ElementKind, Merge, Multiplicity};
use crate::tree::{Attr, Node};

use super::include::combine;

/// Whether a root section takes part in the settings fold: a singleton whose whole
/// subtree is made of singletons (`compiler`, `option`, `size`, `visual`, `statistic`).
pub(crate) fn is_settings_section(kind: ElementKind) -> bool {
    if kind.tag() == "default" || kind.tag() == "worldbody" || kind.multiplicity() != Multiplicity::Singleton {
        return false;
    }
    let mut stack = vec![kind];
    while let Some(k) = stack.pop() {
        for c in k.spec().children {
            if c.multiplicity() != Multiplicity::Singleton || *c == k {
                return false;
            }
            stack.push(*c);
        }
    }
    true
}

/// Folds `theirs` (an attachment's merged section) into `ours`, by the merge rules.
pub(crate) fn fold(ours: &Node, theirs: &Node) -> Result<Node, ErrorKind> {
    let kind = ours.kind();
    let mut attrs: Vec<Attr> = ours.attrs().to_vec();
    let mut changed = false;
    for (i, v) in theirs.attrs() {
        let spec = kind.attr(*i as usize);
        if spec.merge == Merge::Replace || matches!(spec.ty, AttrType::Basepath { .. }) {
            continue;
        }
        match attrs.binary_search_by_key(i, |(k, _)| *k) {
            Ok(p) => {
                let new = combine(kind, *i as usize, &attrs[p].1, v, spec.merge)?;
                if new != attrs[p].1 {
                    attrs[p].1 = new;
                    changed = true;
                }
            }
            Err(p) => {
                attrs.insert(p, (*i, v.clone()));
                changed = true;
            }
        }
    }
    let mut children = ours.children().clone();
    for (p, c) in ours.children().iter().enumerate() {
        if let Some(t) = theirs.child_of_kind(c.kind()) {
            let merged = fold(c, t)?;
            if !merged.ptr_eq(c) {
                children.set(p, merged);
                changed = true;
            }
        }
    }
    Ok(if changed { ours.with_parts(attrs, children) } else { ours.clone() })
}

/// The merged section `kind` of `model`: its own, folded with each attachment's merged
/// section in attach order. Iterative over the attachment tree.
pub(crate) fn merged_section(model: &Model, kind: ElementKind) -> Result<Option<Node>, ErrorKind> {
    let Some(own) = model.root.child_of_kind(kind) else { return Ok(None) };
    if model.index.scopes.is_empty() {
        return Ok(Some(own.clone()));
    }
    // Post-order over the attachment tree: each model's result is its own section
    // folded with its attachments' results, in attach order.
    enum Step<'a> {
        Enter(&'a Model),
        Fold(&'a Model, usize),
    }
    let mut stack = vec![Step::Enter(model)];
    let mut results: Vec<Node> = Vec::new();
    while let Some(step) = stack.pop() {
        match step {
            Step::Enter(m) => {
                let children = attachments(m);
                stack.push(Step::Fold(m, children.len()));
                for c in children.into_iter().rev() {
                    stack.push(Step::Enter(c));
                }
            }
            Step::Fold(m, n) => {
                let theirs = results.split_off(results.len() - n);
                let mut acc = match m.root.child_of_kind(kind) {
                    Some(s) => s.clone(),
                    None => continue,
                };
                for t in &theirs {
                    acc = fold(&acc, t)?;
                }
                results.push(acc);
            }
        }
    }
    Ok(results.pop())
}

/// The models attached to `model` itself, in attach order.
pub(crate) fn attachments(model: &Model) -> Vec<&Model> {
    model
        .index
        .scopes
        .iter()
        .filter_map(|(_, frame)| model.node_by_id(*frame).and_then(|n| n.attached()).map(|a| &a.model))
        .collect()
}

/// Refuses a model whose settings cannot be merged (reports the first conflict).
pub(crate) fn check(model: &Model) -> Result<(), ErrorKind> {
    if model.index.scopes.is_empty() {
        return Ok(());
    }
    for c in model.root.children() {
        if is_settings_section(c.kind()) {
            merged_section(model, c.kind())?;
        }
    }
    Ok(())
}
