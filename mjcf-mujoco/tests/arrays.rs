//! MuJoCo judges the minimum lengths of array attributes that `Model::check` holds
//! models to (`schema/mujoco-4.0-array-minimums.txt`, `ProblemKind::ArrayTooShort`):
//! every element of the schema is put where it belongs, each of its arrays given 1,
//! 2, ... numbers, and MuJoCo says which lengths it refuses ("attribute '...' does not
//! have enough data"). The table must be exactly that; with `MJCF_WRITE_MINIMUMS=1`
//! the test writes it instead.

use crate::support;

use std::collections::BTreeMap;

use mjcf::{AttrType, ElementKind};
use mjcf_mujoco::{Error, MuJoCo};
use support::mujoco;

/// The tags from `<mujoco>` down to `kind`.
fn path(kind: ElementKind) -> Vec<&'static str> {
    let mut out = vec![kind.tag()];
    let mut cur = kind.spec().parent;
    while let Some(p) = cur {
        out.push(p.tag());
        cur = p.spec().parent;
    }
    out.reverse();
    out
}

/// A value of an attribute's type that parses (for the required attributes).
fn dummy(ty: &AttrType) -> Option<String> {
    Some(match ty {
        AttrType::Float | AttrType::Int => "1".into(),
        AttrType::Keyword(words) => words.first()?.to_string(),
        AttrType::Array { max_len, .. } => vec!["1"; max_len.unwrap_or(1) as usize].join(" "),
        AttrType::String | AttrType::NamePrefix | AttrType::Identifier | AttrType::Reference(_) => {
            "x".into()
        }
        _ => return None,
    })
}

/// The model text with `kind` where it belongs, its required attributes set and `attr`
/// given `len` numbers.
fn host(kind: ElementKind, attr: &str, len: usize) -> Option<String> {
    let tags = path(kind);
    let mut attrs = String::new();
    for i in 0..kind.spec().attrs.len() {
        let spec = kind.attr(i);
        if spec.required && spec.name != attr {
            attrs.push_str(&format!(" {}=\"{}\"", spec.name, dummy(&spec.ty)?));
        }
    }
    let numbers = vec!["1"; len].join(" ");
    let mut text = String::new();
    for t in &tags[..tags.len() - 1] {
        text.push_str(&format!("<{t}>"));
    }
    text.push_str(&format!("<{}{attrs} {attr}=\"{numbers}\"/>", kind.tag()));
    for t in tags[..tags.len() - 1].iter().rev() {
        text.push_str(&format!("</{t}>"));
    }
    Some(text)
}

/// The shortest length of each array MuJoCo accepts, where that is above 1: path
/// (tags joined with '/') and attribute → minimum.
fn probe(mujoco: &MuJoCo) -> BTreeMap<(String, String), usize> {
    let mut out = BTreeMap::new();
    for kind in ElementKind::all() {
        let tags = path(kind);
        if tags.contains(&"default") || tags.len() < 2 {
            continue;
        }
        for i in 0..kind.spec().attrs.len() {
            let spec = kind.attr(i);
            let AttrType::Array { max_len: Some(n), .. } = spec.ty else { continue };
            let refused = |len: usize| -> bool {
                let Some(text) = host(kind, spec.name, len) else { return false };
                let needle = format!("attribute '{}' does not have enough data", spec.name);
                matches!(mujoco.compile_xml(&text, &Default::default()),
                    Err(Error::Compile(e)) if e.message.contains(&needle))
            };
            let min = (1..=n as usize).find(|&len| !refused(len)).unwrap_or(n as usize);
            if min > 1 {
                out.insert((tags.join("/"), spec.name.to_string()), min);
            }
        }
    }
    out
}

const TABLE: &str = "../schema/mujoco-4.0-array-minimums.txt";

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn the_array_minimums_are_mujocos() {
    let probed = probe(&mujoco());
    let mut text = String::from(
        "# The shortest length MuJoCo 4.0.0 accepts for each array attribute, where that is\n\
         # above 1 (mjcf-mujoco/tests/arrays.rs probes MuJoCo and checks this table; with\n\
         # MJCF_WRITE_MINIMUMS=1 it writes it). Model::check reports shorter arrays.\n\
         # element path (tags from <mujoco>), attribute, minimum\n",
    );
    for ((path, attr), min) in &probed {
        text.push_str(&format!("{path} {attr} {min}\n"));
    }
    let file = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(TABLE);
    if std::env::var_os("MJCF_WRITE_MINIMUMS").is_some() {
        std::fs::write(&file, &text).unwrap();
    }
    let committed = std::fs::read_to_string(&file).unwrap_or_default();
    assert!(probed.len() > 50, "only {} arrays probed with a minimum", probed.len());
    assert_eq!(committed, text, "the table is not MuJoCo's (MJCF_WRITE_MINIMUMS=1 rewrites it)");
}
