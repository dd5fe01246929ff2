//! The merged global settings of a model with attachments (reference §3.4–§3.5).
//!
//! `compiler`, `option`, `size`, `visual` and `statistic` (with their singleton
//! sub-elements) of a composed model are a fold over the model's own values and each
//! attachment's merged values, in attach order, depth first. Only explicitly set values
//! take part; `min`, `max` and `max_bytes` combine, `replace` attributes (the compiler's
//! folders) are never taken from an attachment, and every other attribute must agree.
//! (The compiler's `angle` and `eulerseq` agree by construction where both models set
//! them: `attach` and `include_copy` convert an incoming model into the receiving
//! model's conventions first, `compose::angles`; an edit that makes them disagree
//! afterwards is refused here, as any conflict.)
//!
//! The fold is derived, never edited: each model value caches its result (shared by
//! the versions that cannot differ in it), every operation that can change the fold
//! (attach, an edit of a setting on either side) folds to refuse a conflict before it
//! returns the new value, and the writer writes the folded sections.

use std::sync::Arc;

use super::Model;
use super::tree::{Attr, Node};
use crate::error::ErrorKind;
use crate::schema::{AttrType, ElementKind, Merge, Role};

use crate::value::{Value, number};

/// Whether a root section takes part in the settings fold: a singleton whose whole
/// subtree is made of singletons (`compiler`, `option`, `size`, `visual`, `statistic`;
/// [`Role::SettingsSection`]). Time: O(1) (every edit asks, through `Model::next`).
pub(crate) fn is_settings_section(kind: ElementKind) -> bool {
    kind.is(Role::SettingsSection)
}

/// Folds `theirs` (an attachment's merged section) into `ours`, by the merge rules.
/// `ours` itself (shared) when the fold changes nothing, as in a fleet of one robot
/// after the first attach: no copy is made until the first change.
pub(crate) fn fold(ours: &Node, theirs: &Node) -> Result<Node, ErrorKind> {
    let kind = ours.kind();
    // A copy of our attributes, made at the first change.
    let mut attrs: Option<Vec<Attr>> = None;
    for (i, v) in theirs.attrs() {
        let spec = kind.attr(*i as usize);
        if spec.merge == Merge::Replace || matches!(spec.ty, AttrType::Basepath { .. }) {
            continue;
        }
        let now = attrs.as_deref().unwrap_or(ours.attrs());
        match now.binary_search_by_key(i, |(k, _)| *k) {
            Ok(p) => {
                if let Some(new) = combined(kind, *i as usize, &now[p].1, v, spec.merge)? {
                    attrs.get_or_insert_with(|| ours.attrs().to_vec())[p].1 = new;
                }
            }
            Err(p) => attrs.get_or_insert_with(|| ours.attrs().to_vec()).insert(p, (*i, v.clone())),
        }
    }
    let mut children = None;
    for (p, c) in ours.children().iter().enumerate() {
        if let Some(t) = theirs.child_of_kind(c.kind()) {
            let merged = fold(c, t)?;
            if !merged.ptr_eq(c) {
                children.get_or_insert_with(|| ours.children().clone()).set(p, merged);
            }
        }
    }
    Ok(match (attrs, children) {
        (None, None) => ours.clone(),
        (attrs, children) => ours.with_parts(
            attrs.unwrap_or_else(|| ours.attrs().to_vec()),
            children.unwrap_or_else(|| ours.children().clone()),
        ),
    })
}

/// `ours` with `theirs` folded in (both merged sections in root order): `ours` itself
/// (shared) when that changes nothing.
pub(crate) fn folded(ours: &Arc<[Node]>, theirs: &[Node]) -> Result<Arc<[Node]>, ErrorKind> {
    let mut acc: Option<Vec<Node>> = None;
    for (k, o) in ours.iter().enumerate() {
        if let Some(t) = theirs.iter().find(|t| t.kind() == o.kind()) {
            let f = fold(o, t)?;
            if !f.ptr_eq(o) {
                acc.get_or_insert_with(|| ours.to_vec())[k] = f;
            }
        }
    }
    Ok(acc.map_or_else(|| ours.clone(), Arc::from))
}

/// The merged settings sections of `model` (root order): its own, each folded with
/// every attachment's merged sections in attach order. Cached in the model's index:
/// only models whose cache is empty are folded (iteratively, post-order over the
/// attachment tree), so a fold after an attach costs O(1) folds.
pub(crate) fn merged(model: &Model) -> Result<Arc<[Node]>, ErrorKind> {
    if let Some(known) = model.index.merged.get() {
        return Ok(known.clone());
    }
    enum Step<'a> {
        Enter(&'a Model),
        Fold(&'a Model, usize),
    }
    let mut stack = vec![Step::Enter(model)];
    let mut results: Vec<Arc<[Node]>> = Vec::new();
    while let Some(step) = stack.pop() {
        match step {
            Step::Enter(m) => match m.index.merged.get() {
                Some(known) => results.push(known.clone()),
                None => {
                    let children = attachments(m);
                    stack.push(Step::Fold(m, children.len()));
                    stack.extend(children.into_iter().rev().map(Step::Enter));
                }
            },
            Step::Fold(m, n) => {
                let theirs = results.split_off(results.len().saturating_sub(n));
                let mut acc = own_sections(m);
                for t in &theirs {
                    fold_sections(&mut acc, t)?;
                }
                results.push(m.index.merged.fill(acc.into()));
            }
        }
    }
    Ok(results.pop().unwrap_or_else(|| own_sections(model).into()))
}

/// The model's own settings sections, in root order.
pub(crate) fn own_sections(model: &Model) -> Vec<Node> {
    model.root.children().iter().filter(|c| is_settings_section(c.kind())).cloned().collect()
}

/// Folds `theirs` (merged sections) into `ours`, section by section.
pub(crate) fn fold_sections(ours: &mut [Node], theirs: &[Node]) -> Result<(), ErrorKind> {
    for o in ours.iter_mut() {
        if let Some(t) = theirs.iter().find(|t| t.kind() == o.kind()) {
            *o = fold(o, t)?;
        }
    }
    Ok(())
}

/// The models attached to `model` itself, in attach order.
pub(crate) fn attachments(model: &Model) -> Vec<&Model> {
    model
        .index
        .attachments()
        .filter_map(|(_, frame)| {
            model.node_by_id(frame).and_then(|n| n.attached()).map(|a| &a.model)
        })
        .collect()
}

/// Refuses a model whose settings cannot be merged (reports the first conflict).
pub(crate) fn check(model: &Model) -> Result<(), ErrorKind> {
    merged(model).map(|_| ())
}

/// [`combine`] for a fold: `None` when the result is `ours` (no copy made).
fn combined(
    kind: ElementKind,
    i: usize,
    ours: &Value,
    theirs: &Value,
    merge: Merge,
) -> Result<Option<Value>, ErrorKind> {
    // The cases where `combine` gives back `ours` (an equal value), told without
    // cloning; every other case (NaN included) goes through `combine`.
    let keep = match (merge, ours, theirs) {
        (Merge::MustAgree, a, b) => values_agree(a, b),
        (Merge::Min, Value::Float(a), Value::Float(b)) => b >= a,
        (Merge::Max, Value::Float(a), Value::Float(b)) => b <= a,
        (Merge::Min, Value::Int(a), Value::Int(b)) => b >= a,
        (Merge::Max, Value::Int(a), Value::Int(b)) => b <= a,
        _ => false,
    };
    if keep {
        return Ok(None);
    }
    let new = combine(kind, i, ours, theirs, merge)?;
    Ok((new != *ours).then_some(new))
}

/// Combines two set values of one attribute by its merge rule (the copying variant:
/// `Replace` takes the incoming value).
pub(crate) fn combine(
    kind: ElementKind,
    i: usize,
    ours: &Value,
    theirs: &Value,
    merge: Merge,
) -> Result<Value, ErrorKind> {
    let spec = kind.attr(i);
    let conflict = || ErrorKind::AttributeConflict {
        tag: kind.tag(),
        attribute: spec.name,
        ours: ours.to_string(),
        theirs: theirs.to_string(),
    };
    match merge {
        Merge::Replace => Ok(theirs.clone()),
        Merge::MustAgree => {
            if values_agree(ours, theirs) {
                Ok(ours.clone())
            } else {
                Err(conflict())
            }
        }
        Merge::Min | Merge::Max => {
            let pick_theirs = match (ours, theirs) {
                (Value::Float(a), Value::Float(b)) => (merge == Merge::Min) == (b < a),
                (Value::Int(a), Value::Int(b)) => (merge == Merge::Min) == (b < a),
                _ => return Err(conflict()),
            };
            Ok(if pick_theirs { theirs.clone() } else { ours.clone() })
        }
        Merge::MaxBytes => {
            let (Some(a), Some(b)) = (ours.as_str(), theirs.as_str()) else {
                return Err(conflict());
            };
            let (Some(x), Some(y)) = (number::parse_bytes(a), number::parse_bytes(b)) else {
                return Err(conflict());
            };
            Ok(Value::String(x.max(y).to_string().into()))
        }
    }
}

/// Equality as the reference checks it: exact, with a one-entry array agreeing with
/// any array made only of that entry; floats compared as numbers, as the reference
/// compares them (`0` agrees with `-0`, NaN with nothing), not as `Value`'s equality
/// does.
fn values_agree(a: &Value, b: &Value) -> bool {
    match (a, b) {
        (Value::Float(x), Value::Float(y)) => x == y,
        (Value::Floats(x), Value::Floats(y)) => {
            x == y
                || (x.len() == 1 && y.iter().all(|v| *v == x[0]))
                || (y.len() == 1 && x.iter().all(|v| *v == y[0]))
        }
        (Value::Ints(x), Value::Ints(y)) => {
            x == y
                || (x.len() == 1 && y.iter().all(|v| *v == x[0]))
                || (y.len() == 1 && x.iter().all(|v| *v == y[0]))
        }
        _ => a == b,
    }
}
