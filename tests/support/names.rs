//! The names a written model holds, checked against the model: every element's
//! `full_name` is exactly the name the writer wrote for it (`name=`, or `class=` for
//! a default class), `from_full_name` gives the element back, and no name is written
//! twice in a namespace.
//!
//! Shared by `tests/support/replay.rs` (every conformance output), `tests/naming.rs`
//! and the generators' property tests (`src/generate/tests.rs`, through
//! `#[path]`, where `mjcf` is the crate itself).

// Shared by several targets that each use only part of it.
#![allow(dead_code)]

use std::collections::HashSet;

use mjcf::{Event, Model, Namespace};

/// The identifier values of the elements of `xml`, in document order: `class` of a
/// `<default>` (none for the unnamed wrapper), `name` of any other element but the
/// root.
pub(crate) fn written_names(xml: &str) -> Result<Vec<String>, String> {
    let mut reader = quick_xml::Reader::from_str(xml);
    let mut out = Vec::new();
    let mut depth = 0usize;
    loop {
        let event = reader.read_event().map_err(|e| format!("unreadable output: {e}"))?;
        let (start, closes) = match &event {
            quick_xml::events::Event::Start(s) => (s, false),
            quick_xml::events::Event::Empty(s) => (s, true),
            quick_xml::events::Event::End(_) => {
                depth = depth.saturating_sub(1);
                continue;
            }
            quick_xml::events::Event::Eof => break,
            _ => continue,
        };
        let tag = start.name();
        let key = if tag.as_ref() == "default" { "class" } else { "name" };
        if depth > 0 {
            for a in start.attributes() {
                let a = a.map_err(|e| format!("bad attribute: {e}"))?;
                if a.key.as_ref() == key {
                    let v = a
                        .normalized_value(quick_xml::XmlVersion::default())
                        .map_err(|e| format!("bad value: {e}"))?;
                    out.push(v.into_owned());
                }
            }
        }
        if !closes {
            depth += 1;
        }
    }
    Ok(out)
}

/// Checks the names of `m` against `xml`, its output (see the module docs).
///
/// The walk's elements with a namespace, in walk order, are the written elements
/// with a name, in document order; the outermost root class written as MuJoCo's
/// main class (`<default>` itself, `main`) is taken out of both.
pub(crate) fn check_names(m: &Model, xml: &str) -> Result<(), String> {
    let mut written = written_names(xml)?;
    // `<default class="main">`: the wrapper, MuJoCo's main class.
    if written.first().is_some_and(|n| n == "main") && xml.contains("<default class=\"main\">") {
        written.remove(0);
    }
    let mut walked = Vec::new();
    for event in m.walk() {
        let Event::Enter(e) = event else { continue };
        let Some(ns) = e.kind().namespace() else { continue };
        let full = e.full_name().ok_or_else(|| format!("no full_name for a {}", e.tag()))?;
        let root_class = e.tag() == "default" && e.parent().is_some_and(|p| p.tag() == "mujoco");
        if root_class && full == "main" {
            continue;
        }
        walked.push((ns, full, e.loc()));
    }
    let names: Vec<&str> = walked.iter().map(|(_, n, _)| n.as_str()).collect();
    if names != written {
        let at = names.iter().zip(&written).position(|(a, b)| a != b).unwrap_or(names.len());
        return Err(format!(
            "full names differ from the written names at {at}: {:?} vs {:?} ({} vs {} names)",
            names.get(at),
            written.get(at),
            names.len(),
            written.len()
        ));
    }
    let mut seen: HashSet<(Namespace, &str)> = HashSet::new();
    for (ns, name, loc) in &walked {
        if !seen.insert((*ns, name)) {
            return Err(format!("{ns} '{name}' written twice"));
        }
        match m.from_full_name(*ns, name) {
            Some(found) if found == *loc => {}
            other => {
                return Err(format!("from_full_name({ns}, {name:?}) is {other:?}, not {loc:?}"));
            }
        }
    }
    Ok(())
}
