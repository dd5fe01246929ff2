//! An editor-style history: every version is a `Model` value kept in a `Vec`, with a
//! cursor for undo and redo, and a diff of two versions that skips every subtree they
//! share.
//!
//! ```text
//! cargo run --example undo
//! ```
//!
//! Keeping a version costs only what its edit copied (the path from the edited element
//! to the root); the diff walks only the elements an edit touched, comparing shared
//! subtrees by pointer (`ElementRef::ptr_eq`, `Model::ptr_eq`) in O(1).

use std::collections::HashMap;
use std::path::PathBuf;

use mjcf::{Element, ElementId, ElementRef, Error, Model, Namespace};

/// The versions, oldest first, and which one is current.
struct History {
    versions: Vec<(String, Model)>,
    cursor: usize,
}

impl History {
    fn new(model: Model) -> History {
        History { versions: vec![("open".into(), model)], cursor: 0 }
    }

    fn current(&self) -> &Model {
        &self.versions[self.cursor].1
    }

    /// Applies an edit to the current version; versions after the cursor (the redo
    /// branch) are dropped, as in an editor.
    fn edit(
        &mut self,
        label: &str,
        f: impl FnOnce(&Model) -> Result<Model, Error>,
    ) -> Result<(), Error> {
        let next = f(self.current())?;
        self.versions.truncate(self.cursor + 1);
        self.versions.push((label.to_string(), next));
        self.cursor += 1;
        println!("edit  v{}: {label}", self.cursor);
        Ok(())
    }

    fn undo(&mut self) {
        if self.cursor > 0 {
            println!(
                "undo  v{} -> v{} (undoes \"{}\")",
                self.cursor,
                self.cursor - 1,
                self.versions[self.cursor].0
            );
            self.cursor -= 1;
        }
    }

    fn redo(&mut self) {
        if self.cursor + 1 < self.versions.len() {
            self.cursor += 1;
            println!(
                "redo  v{} -> v{} (redoes \"{}\")",
                self.cursor - 1,
                self.cursor,
                self.versions[self.cursor].0
            );
        }
    }
}

/// What a diff found, and how much of the trees it had to look at.
#[derive(Default)]
struct Diff {
    lines: Vec<String>,
    visited: usize,
    shared_subtrees: usize,
}

/// A path step: `tag` or `tag[name]`.
fn step(e: &ElementRef<'_>) -> String {
    match e.identifier() {
        Some(name) => format!("{}[{name}]", e.tag()),
        None => e.tag().to_string(),
    }
}

/// The attachment frames of a model: frame id → scope name.
fn frames(m: &Model) -> HashMap<ElementId, String> {
    m.scopes().filter_map(|s| Some((m.frame(s).ok()?.id(), s.to_string()))).collect()
}

/// Joins a path and a step: `worldbody/body[torso]`; a scope prefix ends with `/`.
fn join(path: &str, step: &str) -> String {
    if path.is_empty() || path.ends_with('/') {
        format!("{path}{step}")
    } else {
        format!("{path}/{step}")
    }
}

/// Two versions of one model (the top one, or one attached in both under `prefix`).
struct Pair<'a> {
    a: &'a Model,
    b: &'a Model,
    frames_a: HashMap<ElementId, String>,
    frames_b: HashMap<ElementId, String>,
    /// The scope prefix of this model's elements: `""`, `quadruped_1/`.
    prefix: String,
}

/// Compares two versions of a model (or of a model attached at `prefix` in both).
fn diff_models(a: &Model, b: &Model, prefix: &str, out: &mut Diff) {
    if a.ptr_eq(b) {
        out.shared_subtrees += 1;
        return;
    }
    let (Some(ra), Some(rb)) = (a.element(&a.root()), b.element(&b.root())) else { return };
    let pair = Pair { a, b, frames_a: frames(a), frames_b: frames(b), prefix: prefix.to_string() };
    pair.diff(ra, rb, prefix, out);
}

impl Pair<'_> {
    /// Compares one element present in both versions (same stable id), then its
    /// children.
    fn diff(&self, a: ElementRef<'_>, b: ElementRef<'_>, path: &str, out: &mut Diff) {
        out.visited += 1;
        if a.ptr_eq(&b) {
            out.shared_subtrees += 1;
            return;
        }
        let old: HashMap<&str, String> = a.attrs().map(|(k, v)| (k, v.to_string())).collect();
        let new: HashMap<&str, String> = b.attrs().map(|(k, v)| (k, v.to_string())).collect();
        for (name, value) in &new {
            match old.get(name) {
                Some(v) if v == value => {}
                Some(v) => out.lines.push(format!("  changed {path} {name}: {v} -> {value}")),
                None => out.lines.push(format!("  changed {path} {name}: (unset) -> {value}")),
            }
        }
        for (name, v) in &old {
            if !new.contains_key(name) {
                out.lines.push(format!("  changed {path} {name}: {v} -> (unset)"));
            }
        }
        // An attachment frame in both versions: compare the models it holds.
        if let (Some(sa), Some(sb)) =
            (self.frames_a.get(&a.loc().id()), self.frames_b.get(&b.loc().id()))
        {
            if let (Ok(x), Ok(y)) = (self.a.attached(sa), self.b.attached(sb)) {
                diff_models(x, y, &format!("{}{sb}/", self.prefix), out);
            }
        }
        // Children, matched by their stable ids.
        let before: HashMap<ElementId, ElementRef<'_>> =
            a.children().map(|c| (c.loc().id(), c)).collect();
        let after: HashMap<ElementId, ElementRef<'_>> =
            b.children().map(|c| (c.loc().id(), c)).collect();
        for c in a.children().filter(|c| !after.contains_key(&c.loc().id())) {
            let what = self
                .frames_a
                .get(&c.loc().id())
                .map_or(String::new(), |s| format!(" (attachment {s})"));
            out.lines.push(format!("  removed {}{what}", join(path, &step(&c))));
        }
        for c in b.children() {
            let child_path = join(path, &step(&c));
            match before.get(&c.loc().id()) {
                Some(old) => self.diff(old.clone(), c, &child_path, out),
                None => {
                    let what = self
                        .frames_b
                        .get(&c.loc().id())
                        .map_or(String::new(), |s| format!(" (attachment {s})"));
                    out.lines.push(format!("  added   {child_path}{what}"));
                }
            }
        }
    }
}

fn show_diff(h: &History, from: usize, to: usize) {
    let mut d = Diff::default();
    diff_models(&h.versions[from].1, &h.versions[to].1, "", &mut d);
    println!(
        "diff v{from} -> v{to}: {} difference(s); looked at {} element(s), skipped {} shared subtree(s)",
        d.lines.len(),
        d.visited,
        d.shared_subtrees
    );
    for l in &d.lines {
        println!("{l}");
    }
}

fn main() -> Result<(), Error> {
    let models =
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("..").join("benches").join("models");
    let robot = Model::from_path(models.join("quadruped_robot.xml"))?;

    let arena = Model::new("arena");
    let (arena, _) = arena.add(
        &arena.worldbody(),
        Element::new("geom")
            .attr("name", "floor")
            .attr("type", "plane")
            .attr("size", [10.0, 10.0, 0.1]),
    )?;
    let (arena, _) = arena.add(
        &arena.worldbody(),
        Element::new("site").attr("name", "spawn_0").attr("pos", [-2.0, 0.0, 0.6]),
    )?;
    let (arena, _) = arena.add(
        &arena.worldbody(),
        Element::new("site").attr("name", "spawn_1").attr("pos", [2.0, 0.0, 0.6]),
    )?;

    let mut h = History::new(arena);
    for site in ["spawn_0", "spawn_1"] {
        h.edit(&format!("attach the quadruped at {site}, with a freejoint"), |m| {
            let at = m.find(Namespace::Site, site).expect("the site exists");
            let (m, frame) = m.attach(&at, &robot)?;
            Ok(m.add(frame.frame(), Element::new("freejoint"))?.0)
        })?;
    }
    h.edit("paint quadruped_1's torso red", |m| {
        let torso = m.find(Namespace::Geom, "quadruped_1/torso").expect("the geom exists");
        Ok(m.set_attr(&torso, "rgba", [0.9, 0.1, 0.1, 1.0])?)
    })?;
    h.edit("move the floor down", |m| {
        let floor = m.find(Namespace::Geom, "floor").expect("the floor exists");
        Ok(m.set_attr(&floor, "pos", [0.0, 0.0, -0.01])?)
    })?;
    h.edit("add a box obstacle", |m| {
        let obstacle =
            Element::new("body").attr("name", "obstacle").attr("pos", [0.0, 3.0, 0.25]).child(
                Element::new("geom")
                    .attr("name", "obstacle")
                    .attr("type", "box")
                    .attr("size", [0.25, 0.25, 0.25]),
            );
        Ok(m.add(&m.worldbody(), obstacle)?.0)
    })?;
    println!();
    show_diff(&h, 2, 3);
    show_diff(&h, 3, 5);
    show_diff(&h, 1, 2);
    println!();

    h.undo();
    h.undo();
    println!(
        "current: v{} (obstacle: {})",
        h.cursor,
        h.current().find(Namespace::Body, "obstacle").is_some()
    );
    h.redo();
    println!("current: v{} (floor moved: {})", h.cursor, {
        let floor = h.current().find(Namespace::Geom, "floor").expect("the floor exists");
        h.current()
            .element(&floor)
            .and_then(|e| e.attr("pos").map(|p| p.to_string()))
            .unwrap_or_default()
    });
    // A new edit after an undo drops the redo branch (v5, the obstacle).
    h.edit("detach quadruped (the first robot)", |m| Ok(m.detach("quadruped")?))?;
    println!("{} versions kept; the redo branch is gone", h.versions.len());
    println!();
    show_diff(&h, 4, 5);
    show_diff(&h, 0, h.cursor);

    // Undo never copies: going back to v3 gives exactly the value that was kept.
    let v3 = h.versions[3].1.clone();
    h.undo();
    h.undo();
    assert!(h.current().ptr_eq(&v3));
    println!("\nundo twice: back at v{}, the very value kept for it (ptr_eq)", h.cursor);
    Ok(())
}
