//! The crate's schema against MuJoCo's own declaration of MJCF: MuJoCo's repository
//! declares the language in `src/xml/mjcf.schema`; `tools/mjcf_schema_facts.py`
//! derives its facts as `schema/mjcf-schema-facts.tsv` (one row per attribute of each
//! element under each parent, and one per presence rule). Every attribute MuJoCo
//! declares is one the crate reads, with the same reference namespace, the same
//! array arity and the same `required`, except where MuJoCo 4.0.0 (the release the
//! crate targets, older than that file) differs: those are listed below with what
//! MuJoCo 4.0.0 did when tried.

use std::collections::HashMap;

use mjcf::{AttrSpec, AttrType, ElementKind, RefTarget};

/// One row of the facts: (parent, element, attribute, type, facets).
type Row = [String; 5];

fn rows() -> Vec<Row> {
    let text = include_str!("../schema/mjcf-schema-facts.tsv");
    let rows: Vec<Row> = text
        .lines()
        .skip_while(|l| l.starts_with('#'))
        .skip(1)
        .map(|l| {
            let f: Vec<&str> = l.split('\t').collect();
            std::array::from_fn(|i| f.get(i).copied().unwrap_or("").to_string())
        })
        .collect();
    assert!(rows.len() > 2000, "{} rows", rows.len());
    rows
}

/// The key the facts give `kind`'s parent: `(world)body` for the body grammar (the
/// world body, bodies, frames, replicates), `default` for every default class.
fn parent_key(kind: ElementKind) -> String {
    let Some(p) = kind.spec().parent else { return String::new() };
    match p.tag() {
        "worldbody" | "body" | "frame" | "replicate" => "(world)body".into(),
        t => t.into(),
    }
}

/// The crate's kinds by (parent key, tag).
fn kinds() -> HashMap<(String, String), Vec<ElementKind>> {
    let mut out: HashMap<(String, String), Vec<ElementKind>> = HashMap::new();
    for k in ElementKind::all() {
        out.entry((parent_key(k), k.tag().to_string())).or_default().push(k);
    }
    out
}

/// Attributes the file declares that MuJoCo 4.0.0 does not read: it refuses
/// `<flexcomp><contact internal="true"/>` ("unrecognized attribute: 'internal'").
const NEWER_THAN_4_0_0: &[(&str, &str, &str)] =
    &[("flex", "contact", "internal"), ("flexcomp", "contact", "internal")];

/// Where the crate's `required` is not the file's, because MuJoCo 4.0.0 decides so:
/// an asset `<model>` without `file` makes MuJoCo 4.0.0 fail ("Caught an unknown
/// exception!"), so the crate requires it; a `<text>` may give its data as its
/// content (CDATA) instead of `data`; a material's `<layer>` without `texture` is
/// refused by MuJoCo 4.0.0 ("required attribute missing: 'texture'").
const REQUIRED_DIFFERS: &[(&str, &str, &str)] =
    &[("asset", "model", "file"), ("custom", "text", "data"), ("material", "layer", "texture")];

/// Every (kind, attribute spec, row) the facts declare, the attributes a default class
/// cannot set (`nodefault`, its elements' `name` and `class`) left out, with the rows
/// no kind or attribute of the crate answers.
fn matched() -> (Vec<(ElementKind, &'static AttrSpec, Row)>, Vec<String>) {
    let kinds = kinds();
    let (mut out, mut missing) = (Vec::new(), Vec::new());
    for row in rows() {
        let [parent, element, attr, _, facets] = &row;
        if attr.is_empty() {
            continue; // a presence rule
        }
        let in_default = parent == "default";
        if in_default && (facets.contains("nodefault") || attr == "name" || attr == "class") {
            continue;
        }
        let Some(ks) = kinds.get(&(parent.clone(), element.clone())) else {
            missing.push(format!("{parent} {element}"));
            continue;
        };
        for k in ks {
            match k.attr_index(attr) {
                Some(i) => out.push((*k, k.attr(i), row.clone())),
                None => missing.push(format!("{parent} {element} {attr}")),
            }
        }
    }
    missing.sort();
    missing.dedup();
    (out, missing)
}

#[test]
fn every_attribute_mujoco_declares_is_read_by_the_crate() {
    let (matched, missing) = matched();
    assert!(matched.len() > 1900, "{} matched", matched.len());
    let expected: Vec<String> =
        NEWER_THAN_4_0_0.iter().map(|(p, e, a)| format!("{p} {e} {a}")).collect();
    assert_eq!(missing, expected, "attributes the crate does not read");
}

/// MuJoCo's namespace names where the crate's differ: a plugin `instance` is the
/// crate's `plugin`; a `flex` is the crate's `deformable`.
fn crate_namespace(theirs: &str) -> &str {
    match theirs {
        "instance" => "plugin",
        "flex" => "deformable",
        other => other,
    }
}

#[test]
fn every_reference_names_the_namespace_mujoco_declares() {
    let mut checked = 0;
    for (kind, spec, [parent, element, attr, ty, _]) in matched().0 {
        let Some(theirs) = ty.strip_prefix("ref<").and_then(|t| t.strip_suffix('>')) else {
            continue;
        };
        let ours = match spec.ty {
            AttrType::Reference(RefTarget::Fixed(n) | RefTarget::Unless(n, _)) => n.to_string(),
            ref other => format!("{other:?}"),
        };
        assert_eq!(ours, crate_namespace(theirs), "{parent} {element} {attr} ({kind:?})");
        checked += 1;
    }
    // The file's 139 `ref<…>` declarations, under every parent of their elements
    // (not those a default class cannot set).
    assert!(checked >= 230, "{checked} references checked");
}

#[test]
fn every_array_has_the_arity_mujoco_declares() {
    let mut checked = 0;
    for (kind, spec, [parent, element, attr, ty, _]) in matched().0 {
        let Some(arity) = ty.split_once('[').map(|(_, r)| r.trim_end_matches(']')) else {
            continue;
        };
        if ty.starts_with("chars") {
            // Characters of a text (`eulerseq`, `gridlayout`), read as a string.
            assert!(matches!(spec.ty, AttrType::String), "{parent} {element} {attr}");
            continue;
        }
        let most = match arity.rsplit("..").next().unwrap_or("") {
            "" => None,
            "mjNREF" => Some(2),
            "mjNIMP" => Some(5),
            "mjNDYN" | "mjNGAIN" | "mjNBIAS" => Some(10),
            n => Some(n.parse::<u32>().unwrap_or_else(|_| panic!("{ty}"))),
        };
        let AttrType::Array { max_len, .. } = spec.ty else {
            panic!("{parent} {element} {attr} ({kind:?}): {ty}, the crate reads {:?}", spec.ty)
        };
        assert_eq!(max_len, most, "{parent} {element} {attr}: {ty}");
        checked += 1;
    }
    assert!(checked >= 500, "{checked} arrays checked");
}

#[test]
fn every_required_attribute_is_required_as_mujoco_declares() {
    let mut differs = Vec::new();
    for (_, spec, [parent, element, attr, _, facets]) in matched().0 {
        if facets.split(' ').any(|f| f == "required") != spec.required {
            differs.push((parent, element, attr));
        }
    }
    differs.sort();
    differs.dedup();
    let expected: Vec<(String, String, String)> = REQUIRED_DIFFERS
        .iter()
        .map(|(p, e, a)| (p.to_string(), e.to_string(), a.to_string()))
        .collect();
    assert_eq!(differs, expected);
}
