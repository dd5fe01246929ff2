//! Names MuJoCo makes when it expands what the model keeps as written: the copies
//! of a `<replicate>` and the elements of a part an `<attach>` brings in. A reference
//! to such a name resolves (rule *references resolve*), and a part's welded bodies
//! give mass (rule *moving bodies have mass*).

use std::cell::RefCell;
use std::collections::HashMap;
use std::rc::Rc;

use crate::model::Model;
use crate::model::tree::Node;
use crate::schema::{Namespace, Role};
use crate::value::{Reference, Value};

/// Whether MuJoCo makes the name `name` of namespace `ns` when it expands an element
/// of `m` that the model keeps as written: a copy of a `<replicate>` (an element `j`
/// inside `<replicate count="3">` gives `j0`, `j1`, `j2`: its name, then for each
/// replicate around it, innermost first, the replicate's `sep` and the copy's index
/// padded with zeros to the digits of its count), or an element of a part that an
/// `<attach>` of `m` brings in (the attach's `prefix`, which may be empty, then a name
/// of the part's model file, found the same way; a part that cannot be read on its
/// own, or one attached inside a replicate, is taken to hold any name with that
/// prefix).
///
/// Time: O(N) for `m` of N elements, plus reading the part of an attach whose prefix
/// `name` starts with (called only for a name found nowhere else).
pub(super) fn named_by_expansion(m: &Model, ns: Namespace, name: &str) -> bool {
    let Some(root) = m.node_by_id(m.root().id()) else { return false };
    let mut levels = Vec::new();
    expansion_makes(m, root, ns, name, &mut levels)
}

/// [`named_by_expansion`] below `node`, with `levels` the (count, sep) of the
/// replicates around it, outermost first.
fn expansion_makes<'n>(
    m: &Model,
    node: &'n Node,
    ns: Namespace,
    name: &str,
    levels: &mut Vec<(i64, &'n str)>,
) -> bool {
    let kind = node.kind();
    let text = |attr: &str| kind.attr_index(attr).and_then(|i| node.attr(i));
    match kind.role() {
        Some(Role::Attach) => {
            let prefix = text("prefix").and_then(Value::as_str).unwrap_or("");
            if let Some(inner) = name.strip_prefix(prefix) {
                // Inside a replicate the part's names take suffixes too: not
                // looked into.
                if !levels.is_empty() {
                    return true;
                }
                match attached_part(m, text("model")) {
                    Some(part) => {
                        if part.find(ns, inner).is_some() || named_by_expansion(&part, ns, inner) {
                            return true;
                        }
                    }
                    // A part that cannot be read here: its names are unknown.
                    None => return true,
                }
            }
        }
        Some(Role::Replicate) => {
            let count = text("count").and_then(Value::as_int).unwrap_or(0);
            let sep = text("sep").and_then(Value::as_str).unwrap_or("");
            levels.push((count, sep));
            let found = node.children().iter().any(|c| expansion_makes(m, c, ns, name, levels));
            levels.pop();
            return found;
        }
        _ => {}
    }
    if !levels.is_empty()
        && kind.namespace() == Some(ns)
        && node.identifier().is_some_and(|base| is_replicated_name(name, base, levels))
    {
        return true;
    }
    node.children().iter().any(|c| expansion_makes(m, c, ns, name, levels))
}

/// The part an `<attach model="...">` of `m` brings in: its asset `<model>`'s file,
/// read on its own; `None` when it cannot be read here (its own files are not at
/// hand, say). Within [`parts_read_once`] each file is read once.
pub(super) fn attached_part(m: &Model, model: Option<&Value>) -> Option<Rc<Model>> {
    let asset = match model? {
        Value::Reference(Reference::Name(n)) => m.node_by_id(m.find(Namespace::Model, n)?.id())?,
        Value::Reference(Reference::Element(id)) => m.node_by_id(*id)?,
        _ => return None,
    };
    part_file(asset)
}

/// The model of the asset `<model>` `asset`'s file, read on its own (as
/// [`attached_part`]).
pub(super) fn part_file(asset: &Node) -> Option<Rc<Model>> {
    let kind = asset.kind();
    let Some(Value::File(file)) = kind.attr_index("file").and_then(|i| asset.attr(i)) else {
        return None;
    };
    let contents = file.contents();
    let read = || {
        let text = std::str::from_utf8(contents).ok()?;
        Model::from_xml_str(text).ok().map(Rc::new)
    };
    // The file's bytes are the model's while it is checked: their address names them.
    let key = (contents.as_ptr() as usize, contents.len());
    PARTS.with(|parts| {
        if let Some(known) = parts.borrow().as_ref().and_then(|p| p.get(&key)) {
            return known.clone();
        }
        let part = read();
        if let Some(p) = parts.borrow_mut().as_mut() {
            p.insert(key, part.clone());
        }
        part
    })
}

/// The parts read, by the address and length of their file's bytes.
type Parts = HashMap<(usize, usize), Option<Rc<Model>>>;

thread_local! {
    /// The parts read while [`parts_read_once`] runs.
    static PARTS: RefCell<Option<Parts>> = const { RefCell::new(None) };
}

/// Runs `f` (one [`Model::check`]) with each attached part's file read once: the
/// rules ask for a part many times (each name it may hold, each body it may weld),
/// and the model does not change meanwhile.
pub(super) fn parts_read_once<R>(f: impl FnOnce() -> R) -> R {
    let outer = PARTS.with(|p| p.borrow_mut().replace(HashMap::new()));
    let out = f();
    PARTS.with(|p| *p.borrow_mut() = outer);
    out
}

/// Whether `name` is the name of a copy of `base` made by the replicates `levels`
/// (count, sep; outermost first): `base`, then each level's `sep` and index (padded
/// with zeros to the digits of its count), innermost first, so the outermost last.
/// The names of the inner levels alone (`j05` for `j05-1` of a replicate of 10 inside
/// one of 2 with `sep="-"`) compile too: MuJoCo copies what refers to them with the
/// outer levels.
fn is_replicated_name(name: &str, base: &str, levels: &[(i64, &str)]) -> bool {
    (0..=levels.len()).any(|outer| strips_to(name, base, &levels[outer..]))
}

/// Whether `name` is `base` followed by the suffixes of `levels` (outermost first:
/// its suffix is the last).
fn strips_to(name: &str, base: &str, levels: &[(i64, &str)]) -> bool {
    let mut rest = name;
    for (count, sep) in levels {
        let digits = count.max(&1).to_string().len();
        let Some(cut) = rest.len().checked_sub(digits) else { return false };
        let Some(index) = rest.get(cut..) else { return false };
        if !index.bytes().all(|b| b.is_ascii_digit())
            || index.parse::<i64>().map_or(true, |i| i >= *count)
        {
            return false;
        }
        let Some(before) = rest[..cut].strip_suffix(sep) else { return false };
        rest = before;
    }
    rest == base
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_part_is_read_once_within_one_check_and_afresh_outside() {
        let part =
            r#"<mujoco><worldbody><body name="b"><geom size="1"/></body></worldbody></mujoco>"#;
        let m = crate::ReadOptions::new()
            .asset("part.xml", part.as_bytes().to_vec())
            .read_str(r#"<mujoco><asset><model name="part" file="part.xml"/></asset><worldbody><attach model="part" body="b" prefix="p-"/></worldbody></mujoco>"#)
            .unwrap();
        let model = Value::Reference(Reference::Name("part".into()));
        let read = || attached_part(&m, Some(&model)).expect("the part reads");
        let (a, b) = parts_read_once(|| (read(), read()));
        assert!(Rc::ptr_eq(&a, &b));
        assert!(!Rc::ptr_eq(&read(), &read()));
    }

    #[test]
    fn a_replicated_name_is_the_base_then_each_level_s_sep_and_padded_index() {
        // As MuJoCo 4.0.0 names them (checked with the wheel).
        assert!(is_replicated_name("j0", "j", &[(3, "")]));
        assert!(is_replicated_name("j2", "j", &[(3, "")]));
        assert!(!is_replicated_name("j3", "j", &[(3, "")]));
        assert!(is_replicated_name("j07", "j", &[(10, "")]));
        assert!(!is_replicated_name("j7", "j", &[(10, "")]));
        assert!(is_replicated_name("j-1", "j", &[(2, "-")]));
        // Nested (outer 2 with sep "-", inner 10): the inner index first, the outer
        // last; the inner levels alone name copies too.
        let nested = [(2, "-"), (10, "")];
        assert!(is_replicated_name("j09-1", "j", &nested));
        assert!(is_replicated_name("j05", "j", &nested));
        assert!(!is_replicated_name("j00-2", "j", &nested));
        assert!(!is_replicated_name("j9-0", "j", &nested));
        assert!(!is_replicated_name("j-1", "j", &nested));
        assert!(!is_replicated_name("j0", "j", &nested));
        assert!(!is_replicated_name("k0", "j", &[(3, "")]));
    }
}
