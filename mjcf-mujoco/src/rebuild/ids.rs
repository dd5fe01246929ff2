//! Which compiled element each element of the `mjcf` model became, by locator, and
//! which element of an old compiled model each element of a new one continues.

use std::collections::HashMap;
use std::sync::Arc;

use mjcf::Loc;

use crate::bind::ObjKind;
use crate::model::Compiled;

/// Each compiled element of a model compiled from an `mjcf` model, by locator.
#[derive(Debug, Default)]
pub(crate) struct Ids {
    pub(crate) by_loc: HashMap<Loc, (ObjKind, usize)>,
}

/// The name an element's start tag at `offset` of `xml` gives it, unescaped.
pub(crate) fn written_name(xml: &str, offset: usize) -> Option<String> {
    let b = xml.as_bytes();
    let mut i = offset + 1;
    while i < b.len() && !b[i].is_ascii_whitespace() && b[i] != b'>' && b[i] != b'/' {
        i += 1;
    }
    loop {
        while i < b.len() && b[i].is_ascii_whitespace() {
            i += 1;
        }
        if i >= b.len() || b[i] == b'>' || b[i] == b'/' {
            return None;
        }
        let start = i;
        while i < b.len() && b[i] != b'=' && !b[i].is_ascii_whitespace() {
            i += 1;
        }
        let attr = &xml[start..i];
        while i < b.len() && (b[i] == b'=' || b[i].is_ascii_whitespace()) {
            i += 1;
        }
        let quote = *b.get(i)?;
        if quote != b'"' && quote != b'\'' {
            return None;
        }
        let from = i + 1;
        let to = from + xml[from..].find(quote as char)?;
        if attr == "name" {
            return Some(unescape(&xml[from..to]));
        }
        i = to + 1;
    }
}

/// XML's entities in an attribute value.
fn unescape(s: &str) -> String {
    if !s.contains('&') {
        return s.to_string();
    }
    let mut out = String::with_capacity(s.len());
    let mut rest = s;
    while let Some(at) = rest.find('&') {
        out.push_str(&rest[..at]);
        let Some(end) = rest[at..].find(';') else {
            out.push_str(&rest[at..]);
            return out;
        };
        let entity = &rest[at + 1..at + end];
        let c = match entity {
            "amp" => Some('&'),
            "lt" => Some('<'),
            "gt" => Some('>'),
            "quot" => Some('"'),
            "apos" => Some('\''),
            e if e.starts_with("#x") => {
                u32::from_str_radix(&e[2..], 16).ok().and_then(char::from_u32)
            }
            e if e.starts_with('#') => e[1..].parse().ok().and_then(char::from_u32),
            _ => None,
        };
        match c {
            Some(c) => out.push(c),
            None => out.push_str(&rest[at..=at + end]),
        }
        rest = &rest[at + end + 1..];
    }
    out.push_str(rest);
    out
}

/// The compiled elements of `compiled` by locator (`None` without a source model).
///
/// Time: O(E log n) the first time (each written element's kind, its name read from
/// its start tag, MuJoCo's lookup), O(1) after.
pub(crate) fn ids(compiled: &Compiled) -> Option<Arc<Ids>> {
    let source = compiled.inner.source.as_deref()?;
    if let Some(ids) = source.ids.get() {
        return Some(ids.clone());
    }
    let written = source.written()?;
    let mut by_loc = HashMap::with_capacity(written.elements().len());
    for w in written.elements() {
        let kind = match w.tag {
            // Kinds a rebuild neither carries nor writes in place.
            "frame" | "site" | "camera" | "light" | "default" | "mesh" | "texture" | "material"
            | "hfield" | "key" | "pair" | "exclude" | "numeric" | "text" | "tuple" | "spatial"
            | "fixed" => continue,
            // Tags of one kind (an attachment frame written as a body is a body).
            "body" => Some(ObjKind::Body),
            "geom" => Some(ObjKind::Geom),
            "freejoint" => Some(ObjKind::Joint),
            // Tags only the actuator section (and default classes, unnamed) has.
            "general" | "motor" | "position" | "velocity" | "intvelocity" | "damper"
            | "cylinder" | "muscle" | "adhesion" | "orientation" => Some(ObjKind::Actuator),
            "connect" | "weld" => Some(ObjKind::Equality),
            // Others (a `<joint>` of a body or of the equalities, actuators, ...).
            _ => source.model.element(&w.loc).and_then(|e| ObjKind::of(&e)),
        };
        let Some(kind) = kind else { continue };
        let Some(name) = written_name(written.xml(), w.offset) else { continue };
        if let Some(id) = compiled.id(kind, &name) {
            by_loc.insert(w.loc.clone(), (kind, id));
        }
    }
    Some(source.ids.get_or_init(|| Arc::new(Ids { by_loc })).clone())
}

/// For each element of `kind` of `new`, the element of `old` it continues, if any:
/// by identity (the same element of the `mjcf` model: a renamed element continues)
/// when both were compiled from versions of one `mjcf` model, else by full name.
pub(crate) struct Matching {
    /// Per kind's id in `new`, the old id.
    pub(crate) old_of: Vec<Option<usize>>,
}

/// Whether `old` and `new` are versions of one `mjcf` model (they share an element).
pub(crate) fn related(old: Option<&Ids>, new: Option<&Ids>) -> bool {
    match (old, new) {
        (Some(o), Some(n)) => n.by_loc.keys().any(|l| o.by_loc.contains_key(l)),
        _ => false,
    }
}

/// The [`Matching`] of `kind`.
pub(crate) fn matching(
    old: &Compiled,
    new: &Compiled,
    kind: ObjKind,
    ids: Option<(&Ids, &Ids)>,
) -> Matching {
    let n = new.count(kind);
    let mut old_of = vec![None; n];
    // The world body is always the world body.
    if kind == ObjKind::Body && n > 0 && old.count(kind) > 0 {
        old_of[0] = Some(0);
    }
    match ids {
        Some((o, nw)) => {
            for (loc, &(k, id)) in &nw.by_loc {
                if k != kind {
                    continue;
                }
                if let Some(&(ok, oid)) = o.by_loc.get(loc) {
                    if ok == kind {
                        old_of[id] = Some(oid);
                    }
                }
            }
        }
        None => {
            for (id, slot) in old_of.iter_mut().enumerate() {
                if slot.is_some() {
                    continue;
                }
                if let Some(name) = new.name(kind, id).filter(|n| !n.is_empty()) {
                    *slot = old.id(kind, name);
                }
            }
        }
    }
    Matching { old_of }
}

#[cfg(test)]
mod tests {
    use super::written_name;

    #[test]
    fn the_name_is_read_from_the_start_tag_unescaped() {
        let xml = r#"<mujoco><body pos="0 0 1" name="a&amp;b"><joint name='j'/></body></mujoco>"#;
        assert_eq!(written_name(xml, 8).as_deref(), Some("a&b"));
        assert_eq!(written_name(xml, xml.find("<joint").unwrap()).as_deref(), Some("j"));
        assert_eq!(written_name(xml, 0), None);
    }
}
