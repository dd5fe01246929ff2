//! Checks shared by the fuzz targets.

#![allow(dead_code)]

use std::collections::HashSet;
use std::path::PathBuf;

use mjcf::{Model, ReadOptions};
use quick_xml::events::Event;

#[path = "../../tests/support/text.rs"]
mod text;

/// Reading that never touches real files: file access is confined to a folder that
/// does not exist, so every `<include>` and file asset is a typed error.
pub fn confined() -> ReadOptions {
    let dir = no_such_dir();
    assert!(!dir.exists(), "{} must not exist: the fuzzer must not read real files", dir.display());
    ReadOptions::new().confine_to_base_dir(true).base_dir(dir)
}

/// Reads our own output back; it must read.
pub fn reread(options: &ReadOptions, xml: &str, what: &str) -> Model {
    options.read_str(xml).unwrap_or_else(|e| panic!("{what}: our output does not read back: {e}\n{xml}"))
}

/// The fixed point of write∘read, as `tests/properties.rs` states it: after the first
/// write `w1`, reading and writing again gives `w1` exactly, or — the one documented
/// case, a named root default class — `w1` with one more `<default class="/">` level,
/// and the round after that gives the same text again.
pub fn check_fixed_point(options: &ReadOptions, w1: &str) {
    let m2 = reread(options, w1, "round 1");
    let w2 = m2.to_xml_string().unwrap_or_else(|e| panic!("written once, the model no longer writes: {e}\n{w1}"));
    if w2 == w1 {
        return;
    }
    let rewrapped = text::rewrapped_root_default(w1);
    assert!(
        w2 == rewrapped,
        "write(read(w1)) differs from w1 by more than the root-class rewrap\n--- w1\n{w1}\n--- w2\n{w2}"
    );
    let m3 = reread(options, &w2, "round 2");
    let w3 = m3.to_xml_string().unwrap_or_else(|e| panic!("written twice, the model no longer writes: {e}\n{w2}"));
    assert!(w3 == w2, "no fixed point after the root-class rewrap\n--- w2\n{w2}\n--- w3\n{w3}");
}

/// The identifier family of an element, given the top-level section it is in and its
/// parent's tag; `None` for elements whose `name` is not checked.
fn family(section: &str, parent: &str, tag: &str) -> Option<&'static str> {
    match (section, parent, tag) {
        ("worldbody", _, "body") => Some("body"),
        ("worldbody", _, "joint" | "freejoint") => Some("joint"),
        ("worldbody", _, "geom") => Some("geom"),
        ("worldbody", _, "site") => Some("site"),
        ("worldbody", _, "camera") => Some("camera"),
        ("worldbody", _, "light") => Some("light"),
        ("asset", "asset", "material") => Some("material"),
        ("asset", "asset", "mesh") => Some("mesh"),
        ("asset", "asset", "texture") => Some("texture"),
        ("actuator", "actuator", _) => Some("actuator"),
        ("sensor", "sensor", _) => Some("sensor"),
        _ => None,
    }
}

/// Checks that the written text is well-formed and that identifiers are unique per
/// namespace (names per family above; default class names).
pub fn check_unique_identifiers(xml: &str) {
    let mut reader = quick_xml::Reader::from_str(xml);
    let mut stack: Vec<String> = Vec::new();
    let mut seen: HashSet<(&'static str, String)> = HashSet::new();
    loop {
        let event = reader.read_event().unwrap_or_else(|e| panic!("our output is not well-formed: {e}\n{xml}"));
        let (t, empty) = match event {
            Event::Start(t) => (t, false),
            Event::Empty(t) => (t, true),
            Event::End(_) => {
                stack.pop();
                continue;
            }
            Event::Eof => break,
            _ => continue,
        };
        let tag = t.name().as_ref().to_string();
        let section = stack.get(1).map_or(tag.as_str(), String::as_str).to_string();
        let parent = stack.last().map_or("", String::as_str).to_string();
        let (fam, key) = if tag == "default" && parent == "default" {
            (Some("default class"), "class")
        } else {
            (if stack.is_empty() { None } else { family(&section, &parent, &tag) }, "name")
        };
        if let Some(fam) = fam {
            for a in t.attributes() {
                let a = a.unwrap_or_else(|e| panic!("our output has a bad attribute: {e}\n{xml}"));
                if a.key.as_ref() == key {
                    let v = a
                        .normalized_value(quick_xml::XmlVersion::default())
                        .unwrap_or_else(|e| panic!("our output has a bad attribute value: {e}\n{xml}"))
                        .into_owned();
                    assert!(seen.insert((fam, v.clone())), "{fam} identifier {v:?} written twice\n{xml}");
                }
            }
        }
        if !empty {
            stack.push(tag);
        }
    }
    assert!(stack.is_empty(), "our output has unclosed elements\n{xml}");
}

/// Where nothing is: the folder the confined reader resolves against.
pub fn no_such_dir() -> PathBuf {
    std::env::temp_dir().join("mjcf-fuzz-no-such-dir-9f1c2e")
}
