//! The lossless writer's property over spellings: a generated model written with
//! generated spellings (a byte-order mark, an XML declaration, comments and processing
//! instructions before the root, a DOCTYPE, `\n` / `\r\n` / lone `\r` line endings
//! mixed, indentation by spaces or tabs or none, comments of multi-byte text before
//! elements, multi-byte names, either quote, attributes split over lines, `<x/>`,
//! `<x />` or `<x></x>`), its asset section possibly in an included file spelled
//! otherwise, then edited (attributes set and cleared, elements added, removed and
//! renamed), saves to text that reads back as the edited model, with every byte
//! outside the edited tags kept in order. The spans of the tags are recorded by the
//! generator as it writes them, not taken from the reader.
//!
//! Properties run `PROPTEST_CASES` cases (default 256) from proptest's fixed seed.

use std::collections::HashMap;

use mjcf::{Element, Model, Namespace, ReadOptions, attrs};
use proptest::prelude::*;
use proptest::test_runner::Config;

/// How one file is spelled; the lists are used round robin.
#[derive(Clone, Debug)]
struct Spelling {
    bom: bool,
    declaration: bool,
    /// Before the root: a comment (`false`) or a processing instruction (`true`).
    prolog: Vec<bool>,
    doctype: bool,
    /// `None`: the whole file on one line, unindented.
    lines: Option<Lines>,
    /// Whether a comment comes before an element.
    comments: Vec<bool>,
    /// Single quotes (`true`) or double.
    quotes: Vec<bool>,
    /// Which separator goes before an attribute (see [`SEPS`]).
    seps: Vec<u8>,
    /// How a childless element ends (see [`EMPTY`]).
    empty: Vec<u8>,
}

#[derive(Clone, Debug)]
struct Lines {
    /// Line endings, in turn (see [`NEWLINES`]).
    newlines: Vec<u8>,
    indent: &'static str,
}

const NEWLINES: [&str; 3] = ["\n", "\r\n", "\r"];
const SEPS: [&str; 4] = [" ", "  ", "\n\t ", "\r\n   "];
const EMPTY: [&str; 3] = ["/>", " />", "></>"];
const TEXTS: [&str; 4] =
    ["plain", "\u{e9}t\u{e9}", "\u{1f600}\u{1f916}", "\u{4e16}\u{754c} \u{2211}"];

fn spelling() -> impl Strategy<Value = Spelling> {
    let lines = prop_oneof![
        1 => Just(None),
        5 => (prop::collection::vec(0u8..3, 1..4), prop::sample::select(vec!["  ", "\t", "    ", " "]))
            .prop_map(|(newlines, indent)| Some(Lines { newlines, indent })),
    ];
    (
        (any::<bool>(), any::<bool>(), prop::collection::vec(any::<bool>(), 0..3), any::<bool>()),
        lines,
        prop::collection::vec(prop::bool::weighted(0.3), 1..5),
        prop::collection::vec(any::<bool>(), 1..4),
        prop::collection::vec(0u8..4, 1..4),
        prop::collection::vec(0u8..3, 1..4),
    )
        .prop_map(
            |((bom, declaration, prolog, doctype), lines, comments, quotes, seps, empty)| {
                Spelling { bom, declaration, prolog, doctype, lines, comments, quotes, seps, empty }
            },
        )
}

/// One element of the generated model (named elements are keyed by their name).
#[derive(Clone, Debug)]
struct N {
    tag: &'static str,
    attrs: Vec<(&'static str, String)>,
    kids: Vec<N>,
}

impl N {
    fn name(&self) -> Option<&str> {
        self.attrs.iter().find(|(k, _)| *k == "name").map(|(_, v)| v.as_str())
    }
}

/// The model: how many materials, and the worldbody's items (a geom with an optional
/// material; a body holding geoms (`true`) and sites (`false`)).
#[derive(Clone, Debug)]
struct Spec {
    materials: usize,
    items: Vec<Item>,
    /// The names' multi-byte suffixes, in turn (see [`SUFFIXES`]).
    suffixes: Vec<u8>,
}

#[derive(Clone, Debug)]
enum Item {
    Geom(Option<usize>),
    Body(Vec<bool>),
}

const SUFFIXES: [&str; 4] = ["", "\u{e9}", "\u{1f600}", "\u{4e16}"];

fn spec() -> impl Strategy<Value = Spec> {
    let item = prop_oneof![
        prop::option::of(0usize..3).prop_map(Item::Geom),
        prop::collection::vec(any::<bool>(), 0..4).prop_map(Item::Body),
    ];
    (1usize..4, prop::collection::vec(item, 0..5), prop::collection::vec(0u8..4, 1..4))
        .prop_map(|(materials, items, suffixes)| Spec { materials, items, suffixes })
}

impl Spec {
    /// The asset section and the worldbody.
    fn tree(&self) -> (N, N) {
        let mut k = 0;
        let mut name = |prefix: &str| {
            k += 1;
            let s = SUFFIXES[self.suffixes[k % self.suffixes.len()] as usize];
            format!("{prefix}{k}{s}")
        };
        let leaf = |tag, attrs| N { tag, attrs, kids: Vec::new() };
        let materials: Vec<String> = (0..self.materials).map(|_| name("m")).collect();
        let asset = N {
            tag: "asset",
            attrs: Vec::new(),
            kids: materials
                .iter()
                .map(|m| leaf("material", vec![("name", m.clone()), ("rgba", "1 0 0 1".into())]))
                .collect(),
        };
        let mut world = Vec::new();
        for item in &self.items {
            match item {
                Item::Geom(mat) => {
                    let mut attrs = vec![("name", name("g")), ("size", ".1".to_string())];
                    if let Some(m) = mat.and_then(|m| materials.get(m)) {
                        attrs.push(("material", m.clone()));
                    }
                    world.push(leaf("geom", attrs));
                }
                Item::Body(kids) => {
                    let kids = kids
                        .iter()
                        .map(|&g| match g {
                            true => leaf("geom", vec![("name", name("g")), ("size", ".2".into())]),
                            false => leaf("site", vec![("name", name("s")), ("size", ".3".into())]),
                        })
                        .collect();
                    let attrs = vec![("name", name("b")), ("pos", "0 0 1".into())];
                    world.push(N { tag: "body", attrs, kids });
                }
            }
        }
        (asset, N { tag: "worldbody", attrs: Vec::new(), kids: world })
    }
}

/// Where an element's text is in its file: `lead` (where the text before it starts:
/// the end of the tag before it), its start tag `start..start_end` and its end
/// `end..end_end` (`end == end_end == start_end` for a tag written `<x/>`).
#[derive(Clone, Copy, Debug)]
struct Span {
    file: usize,
    lead: usize,
    start: usize,
    start_end: usize,
    end: usize,
    end_end: usize,
    /// Where the last child ends (`start_end` if none).
    last_child_end: usize,
}

/// Writes files, recording the spans of the named elements (and the worldbody's as
/// `"worldbody"`).
struct Writer<'s> {
    sp: &'s Spelling,
    file: usize,
    out: String,
    turn: usize,
    spans: HashMap<String, Span>,
}

impl Writer<'_> {
    fn pick<T: Copy>(&mut self, v: &[T]) -> T {
        self.turn += 1;
        v[self.turn % v.len()]
    }

    /// A line break and the indentation of `depth`.
    fn line(&mut self, depth: usize) {
        let Some(lines) = &self.sp.lines else { return };
        let (newlines, indent) = (lines.newlines.clone(), lines.indent);
        let nl = NEWLINES[self.pick(&newlines) as usize];
        self.out.push_str(nl);
        self.out.push_str(&indent.repeat(depth));
    }

    fn text(&mut self) -> &'static str {
        TEXTS[self.turn % TEXTS.len()]
    }

    /// The prolog, then `root` holding `kids`.
    fn document(&mut self, root: &str, kids: &[&N]) {
        let sp = self.sp;
        if sp.bom {
            self.out.push('\u{feff}');
        }
        if sp.declaration {
            self.out.push_str("<?xml version=\"1.0\" encoding=\"UTF-8\"?>");
            self.line(0);
        }
        for &pi in &sp.prolog {
            let t = self.text();
            let misc = if pi { format!("<?note {t}?>") } else { format!("<!-- {t} -->") };
            self.out.push_str(&misc);
            self.line(0);
        }
        if sp.doctype {
            self.out.push_str("<!DOCTYPE mujoco [ <!ELEMENT mujoco ANY> <!-- <geom/> --> ]>");
            self.line(0);
        }
        self.out.push_str(root);
        for k in kids {
            self.element(k, 1);
        }
        self.line(0);
        self.out.push_str("</mujoco>");
        self.line(0);
    }

    fn element(&mut self, n: &N, depth: usize) {
        let lead = self.out.len();
        let comments = self.sp.comments.clone();
        if self.pick(&comments) {
            self.line(depth);
            let t = self.text();
            self.out.push_str(&format!("<!-- {t} -->"));
        }
        self.line(depth);
        let start = self.out.len();
        self.out.push('<');
        self.out.push_str(n.tag);
        for (k, v) in &n.attrs {
            let (seps, quotes) = (self.sp.seps.clone(), self.sp.quotes.clone());
            let sep = SEPS[self.pick(&seps) as usize];
            self.out.push_str(sep);
            let q = if self.pick(&quotes) { '\'' } else { '"' };
            self.out.push_str(&format!("{k}={q}{v}{q}"));
        }
        let (start_end, end, end_end, last_child_end);
        if n.kids.is_empty() {
            let empty = self.sp.empty.clone();
            match EMPTY[self.pick(&empty) as usize] {
                "></>" => {
                    self.out.push('>');
                    start_end = self.out.len();
                    end = start_end;
                    self.out.push_str(&format!("</{}>", n.tag));
                }
                e => {
                    self.out.push_str(e);
                    start_end = self.out.len();
                    end = start_end;
                }
            }
            last_child_end = start_end;
        } else {
            self.out.push('>');
            start_end = self.out.len();
            for k in &n.kids {
                self.element(k, depth + 1);
            }
            last_child_end = self.out.len();
            self.line(depth);
            end = self.out.len();
            self.out.push_str(&format!("</{}>", n.tag));
        }
        end_end = self.out.len();
        let key = n.name().unwrap_or(n.tag).to_string();
        let file = self.file;
        let span = Span { file, lead, start, start_end, end, end_end, last_child_end };
        self.spans.insert(key, span);
    }
}

/// The files of a spelled model (the main text, and the asset section's file if
/// `include`), with the spans of their elements.
fn spell(
    spec: &Spec,
    main: &Spelling,
    other: &Spelling,
    include: bool,
) -> (Vec<String>, HashMap<String, Span>) {
    let (asset, world) = spec.tree();
    let mut w = Writer { sp: main, file: 0, out: String::new(), turn: 0, spans: HashMap::new() };
    let mut texts = Vec::new();
    let mut spans = HashMap::new();
    if include {
        let inc =
            N { tag: "include", attrs: vec![("file", "assets.xml".into())], kids: Vec::new() };
        w.document("<mujoco model=\"m\">", &[&inc, &world]);
        let mut w2 =
            Writer { sp: other, file: 1, out: String::new(), turn: 0, spans: HashMap::new() };
        w2.document("<mujoco>", &[&asset]);
        texts.push(std::mem::take(&mut w.out));
        texts.push(w2.out);
        spans.extend(w2.spans);
    } else {
        w.document("<mujoco model=\"m\">", &[&asset, &world]);
        texts.push(std::mem::take(&mut w.out));
    }
    spans.extend(w.spans);
    (texts, spans)
}

/// One edit, of the element picked by the index among the named elements (in name
/// order), or under the body picked (or the worldbody).
#[derive(Clone, Debug)]
enum Op {
    Set(prop::sample::Index, u8),
    Clear(prop::sample::Index),
    Add(prop::sample::Index),
    Remove(prop::sample::Index),
    Rename(prop::sample::Index),
}

fn op() -> impl Strategy<Value = Op> {
    let i = any::<prop::sample::Index>;
    prop_oneof![
        (i(), 1u8..9).prop_map(|(i, v)| Op::Set(i, v)),
        i().prop_map(Op::Clear),
        i().prop_map(Op::Add),
        i().prop_map(Op::Remove),
        i().prop_map(Op::Rename),
    ]
}

/// The namespace of a generated name (by its first letter).
fn namespace(name: &str) -> Namespace {
    match name.as_bytes()[0] {
        b'm' => Namespace::Material,
        b'g' => Namespace::Geom,
        b's' => Namespace::Site,
        _ => Namespace::Body,
    }
}

/// The attribute an edit sets or clears on a generated element.
fn attr_of(name: &str) -> &'static str {
    match name.as_bytes()[0] {
        b'm' => "rgba",
        b'b' => "pos",
        _ => "size",
    }
}

/// Applies `op` to `m` (nothing if its element is gone or renamed); returns the model
/// and the regions of the original files (file, from, to) it may change.
fn apply(
    m: &Model,
    op: &Op,
    k: usize,
    names: &[String],
    spans: &HashMap<String, Span>,
    referrers: &HashMap<String, Vec<String>>,
) -> (Model, Vec<(usize, usize, usize)>) {
    let tag = |s: &Span| (s.file, s.start, s.start_end);
    let refs = |name: &str| referrers.get(name).into_iter().flatten().map(|r| tag(&spans[r]));
    let pick = |i: &prop::sample::Index| {
        let name = &names[i.index(names.len())];
        m.find(namespace(name), name).map(|loc| (name.clone(), loc))
    };
    match op {
        Op::Add(i) => {
            let bodies: Vec<&String> = names.iter().filter(|n| n.starts_with('b')).collect();
            let parent = match i.index(bodies.len() + 1) {
                0 => Some(("worldbody".to_string(), m.worldbody())),
                b => m.find(Namespace::Body, bodies[b - 1]).map(|l| (bodies[b - 1].clone(), l)),
            };
            let Some((key, p)) = parent else { return (m.clone(), Vec::new()) };
            let geom =
                Element::new("geom").attr("name", format!("new{k}\u{e9}")).attr("size", [0.5]);
            let s = spans[&key];
            let region = if s.end == s.end_end && s.last_child_end == s.start_end {
                (s.file, s.start, s.end_end)
            } else {
                (s.file, s.last_child_end, s.end)
            };
            (m.add(&p, geom).unwrap().0, vec![region])
        }
        Op::Set(i, _) | Op::Clear(i) | Op::Remove(i) | Op::Rename(i) => {
            let Some((name, loc)) = pick(i) else { return (m.clone(), Vec::new()) };
            let s = spans[&name];
            let attr = attr_of(&name);
            match op {
                Op::Set(_, v) => {
                    let value = match attr {
                        "rgba" => format!("0 0 {v} 1"),
                        "pos" => format!("0 {v} 1"),
                        _ => format!("0.{v}"),
                    };
                    (m.set_attr(&loc, attr, value.as_str()).unwrap(), vec![tag(&s)])
                }
                Op::Clear(_) => (m.clear_attr(&loc, attr).unwrap(), vec![tag(&s)]),
                Op::Remove(_) => {
                    let mut regions: Vec<_> = refs(&name).collect();
                    regions.push((s.file, s.lead, s.end_end));
                    (m.remove(&loc).unwrap(), regions)
                }
                _ => {
                    let mut regions: Vec<_> = refs(&name).collect();
                    regions.push(tag(&s));
                    let new = format!("{name}r{k}\u{159}");
                    (m.set(&loc, attrs!(name = new.as_str())).unwrap(), regions)
                }
            }
        }
    }
}

/// Whether `saved` holds every byte of `original` outside `regions` (from, to), in
/// order: what precedes the first region as its start, what follows the last as its
/// end, and the text between regions in between, in order.
fn kept_outside(original: &str, saved: &str, regions: &[(usize, usize)]) -> Result<(), String> {
    let mut regions = regions.to_vec();
    regions.sort_unstable();
    // The kept pieces: the complement of the union of the regions.
    let (mut pieces, mut at) = (Vec::new(), 0);
    for (a, b) in regions {
        if a >= at {
            pieces.push(&original[at..a]);
        }
        at = at.max(b);
    }
    let last = &original[at..];
    if pieces.is_empty() {
        return if saved == original { Ok(()) } else { Err("changed with no edit".into()) };
    }
    if !saved.starts_with(pieces[0]) {
        return Err(format!("the text before the first edited tag changed: {:?}", pieces[0]));
    }
    let mut pos = pieces[0].len();
    for p in &pieces[1..] {
        match saved[pos..].find(p) {
            Some(i) => pos += i + p.len(),
            None => return Err(format!("kept text lost or moved: {p:?}")),
        }
    }
    if !saved[pos..].ends_with(last) {
        return Err(format!("the text after the last edited tag changed: {last:?}"));
    }
    Ok(())
}

/// The geoms naming each material.
fn referrers(spec: &Spec) -> HashMap<String, Vec<String>> {
    let (_, world) = spec.tree();
    let mut out: HashMap<String, Vec<String>> = HashMap::new();
    for n in &world.kids {
        if let Some((_, m)) = n.attrs.iter().find(|(k, _)| *k == "material") {
            out.entry(m.clone()).or_default().push(n.name().unwrap().to_string());
        }
    }
    out
}

/// Reads the files of `texts` (the main text first, then the included assets file).
fn read(texts: &[String]) -> Result<Model, mjcf::ReadError> {
    let mut opts = ReadOptions::new();
    if let Some(inc) = texts.get(1) {
        opts = opts.asset("assets.xml", inc.as_bytes().to_vec());
    }
    opts.read_str(&texts[0])
}

fn cases() -> u32 {
    std::env::var("PROPTEST_CASES").ok().and_then(|c| c.parse().ok()).unwrap_or(256)
}

proptest! {
    #![proptest_config(Config { cases: cases(), ..Config::default() })]

    /// Saved and read back: the edited model, every byte outside the edited tags kept.
    #[test]
    fn edits_of_any_spelling_save_in_their_tags_and_read_back_as_edited(
        spec in spec(),
        main in spelling(),
        other in spelling(),
        include in any::<bool>(),
        ops in prop::collection::vec(op(), 1..4),
    ) {
        let (texts, spans) = spell(&spec, &main, &other, include);
        let m = read(&texts).map_err(|e| TestCaseError::fail(format!("{e}\n{texts:?}")))?;
        let unedited: Vec<String> = m.to_source_files().unwrap().into_iter().map(|f| f.text).collect();
        prop_assert_eq!(&unedited, &texts);
        let mut names: Vec<String> = spans.keys().filter(|k| k.as_str() != "worldbody" && k.as_str() != "asset").cloned().collect();
        names.sort();
        prop_assume!(!names.is_empty());
        let referrers = referrers(&spec);
        let (mut edited, mut regions) = (m.clone(), Vec::new());
        for (k, op) in ops.iter().enumerate() {
            let (next, r) = apply(&edited, op, k, &names, &spans, &referrers);
            edited = next;
            regions.extend(r);
        }
        let saved: Vec<String> = edited.to_source_files().unwrap().into_iter().map(|f| f.text).collect();
        prop_assert_eq!(saved.len(), texts.len());
        let back = read(&saved).map_err(|e| TestCaseError::fail(format!("read back: {e}\n{saved:?}")))?;
        let same = back == edited || back.to_xml_string().ok() == edited.to_xml_string().ok();
        prop_assert!(same, "read back differs:\n{:?}\n--- from ---\n{:?}", saved, texts);
        for (f, (original, saved)) in texts.iter().zip(&saved).enumerate() {
            let mine: Vec<(usize, usize)> = regions.iter().filter(|r| r.0 == f).map(|r| (r.1, r.2)).collect();
            if let Err(e) = kept_outside(original, saved, &mine) {
                prop_assert!(false, "{}\n{:?}\n--- saved ---\n{:?}", e, original, saved);
            }
        }
    }
}
