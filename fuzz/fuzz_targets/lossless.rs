//! Lossless save (`Model::to_source_files`, in memory): MJCF text read (file access
//! confined to a folder that does not exist, as in `read_xml`), edited, saved, read
//! back.
//!
//! The input is the text, then a NUL byte, then the bytes the edits are drawn from
//! (`arbitrary`); without a NUL, the edits are drawn from the text itself (so every
//! model file of the seed corpus gets edits at once). Up to `MAX_EDITS` edits of the
//! elements the text names uniquely (one start tag `<tag name="n">`, or
//! `<default class="c">`, and one element of that tag and identifier in the model):
//! attributes set or cleared (the identifier too: a rename), elements removed, and
//! elements added under a named body or the worldbody. A refused edit changes nothing.
//!
//! Checks: the unedited model saves its text byte for byte; the edited one saves (or
//! refuses with `SaveError::MissingRequired` / `UnnamedTarget`, a reference left to an
//! element removed or unnamed, or `RootClassRenamed`, a root class renamed where the
//! file spells it so that MuJoCo would refuse the text), its text reads back as the edited model (equal, or
//! written alike), saving what was read back gives the same text, and every byte of
//! the text outside the tags the edits may change is kept, in order. Those tags are
//! found by this target's own reading of the text (quick-xml, positions counted from
//! the start of the text, a byte-order mark included), not from the source the crate
//! records: an edited element's start tag; for a removal, the element with the text
//! between it and the tag before it; for an addition, the parent's content after its
//! last child (its whole tag if it was `<x/>`); and for a removal or a change of an
//! identifier, every start tag with an attribute value equal to a name removed or
//! changed (the references to it), for a default class the root `<default>`'s
//! start tag (written `class="main"` when a class `/` is left alone in it), and for
//! a section of the root given in several tags (a root `<default class=…>` given
//! twice) its other tags (their start tags; for a removal, the whole of them).

#![no_main]

mod common;

use std::sync::OnceLock;

use arbitrary::{Arbitrary, Unstructured};
use libfuzzer_sys::fuzz_target;
use mjcf::{Element, Event as Walk, Loc, Model, ReadOptions, SaveError};
use quick_xml::events::Event;

/// Edits per input.
const MAX_EDITS: usize = 4;

fn options() -> &'static ReadOptions {
    static OPTIONS: OnceLock<ReadOptions> = OnceLock::new();
    OPTIONS.get_or_init(common::confined)
}

const NAMES: &[&str] = &["a", "b", "torso", "world", "main", "x y", "é", "😀", "<&'\">", "", "/", "a/b", "0"];
const ATTRS: &[&str] = &[
    "name", "class", "childclass", "pos", "size", "rgba", "type", "quat", "euler", "mass", "range", "material", "joint",
    "site", "body1", "fromto", "user", "gravity", "timestep",
];
const NUMBERS: &[f64] = &[0.0, -0.0, 1.0, -1.5, 0.1, 1.0 / 3.0, 1e-300, 1e300, f64::NAN, f64::INFINITY];

#[derive(Arbitrary, Debug, Clone)]
enum Val {
    Name(u8),
    Number(u8),
    Numbers(Vec<u8>),
    Text(String),
}

impl Val {
    fn set(&self, m: &Model, loc: &Loc, attr: &str) -> Option<Model> {
        let r = match self {
            Val::Name(i) => m.set_attr(loc, attr, NAMES[*i as usize % NAMES.len()]),
            Val::Number(i) => m.set_attr(loc, attr, NUMBERS[*i as usize % NUMBERS.len()]),
            Val::Numbers(v) => {
                let v: Vec<f64> = v.iter().take(6).map(|i| NUMBERS[*i as usize % NUMBERS.len()]).collect();
                m.set_attr(loc, attr, v)
            }
            Val::Text(s) => m.set_attr(loc, attr, s.chars().take(12).collect::<String>().as_str()),
        };
        r.ok()
    }
}

#[derive(Arbitrary, Debug, Clone)]
enum New {
    Geom { name: u8, size: u8 },
    Site { name: u8 },
    Body { name: u8, geom: bool },
    Joint { name: u8 },
}

impl New {
    fn build(&self) -> Element {
        let name = |i: &u8| NAMES[*i as usize % NAMES.len()];
        match self {
            New::Geom { name: n, size } => {
                Element::new("geom").attr("name", name(n)).attr("size", [NUMBERS[*size as usize % NUMBERS.len()]])
            }
            New::Site { name: n } => Element::new("site").attr("name", name(n)),
            New::Body { name: n, geom } => {
                let b = Element::new("body").attr("name", name(n));
                if *geom { b.child(Element::new("geom").attr("size", [0.1])) } else { b }
            }
            New::Joint { name: n } => Element::new("joint").attr("name", name(n)),
        }
    }
}

#[derive(Arbitrary, Debug, Clone)]
enum Edit {
    Set { target: u16, attr: u8, value: Val },
    Clear { target: u16, attr: u8 },
    Remove { target: u16 },
    /// Under a named body, or (`None`) the worldbody.
    Add { parent: Option<u16>, element: New },
}

/// A start tag of the text and where its element is (byte offsets into the text).
#[derive(Debug, Clone)]
struct Tag {
    tag: String,
    /// Its `name` (`class` for a `<default>`), unescaped.
    ident: Option<String>,
    /// Every attribute value, unescaped.
    values: Vec<String>,
    depth: usize,
    /// Where the text before it starts: the end of the tag before it.
    lead: usize,
    start: usize,
    start_end: usize,
    end: usize,
    end_end: usize,
    last_child_end: usize,
}

/// The start tags of `text`, in document order (the crate read it: quick-xml refusing
/// it is a finding).
fn tags(text: &str) -> Vec<Tag> {
    // quick-xml drops a byte-order mark and counts from after it.
    let base = if text.starts_with('\u{feff}') { 3 } else { 0 };
    let mut xml = quick_xml::Reader::from_str(text);
    let mut out: Vec<Tag> = Vec::new();
    let mut open: Vec<usize> = Vec::new();
    loop {
        let at = base + xml.buffer_position() as usize;
        let event = xml.read_event().unwrap_or_else(|e| panic!("read by the crate, refused by quick-xml: {e}"));
        let after = base + xml.buffer_position() as usize;
        let (t, empty) = match event {
            Event::Start(t) => (t, false),
            Event::Empty(t) => (t, true),
            Event::End(_) => {
                let i = open.pop().expect("balanced");
                out[i].end = at;
                out[i].end_end = after;
                if let Some(&p) = open.last() {
                    out[p].last_child_end = after;
                }
                continue;
            }
            Event::Eof => return out,
            _ => continue,
        };
        let qname = t.name();
        let tag: &str = qname.as_ref();
        let key = if tag == "default" { "class" } else { "name" };
        let (mut ident, mut values) = (None, Vec::new());
        for a in t.attributes().flatten() {
            let Ok(v) = a.normalized_value(quick_xml::XmlVersion::default()) else { continue };
            if a.key.as_ref() == key {
                ident = Some(v.to_string());
            }
            values.push(v.into_owned());
        }
        let lead = open.last().map_or(at, |&p| out[p].last_child_end);
        out.push(Tag {
            tag: tag.to_string(),
            ident,
            values,
            depth: open.len(),
            lead,
            start: at,
            start_end: after,
            end: after,
            end_end: after,
            last_child_end: after,
        });
        if empty {
            if let Some(&p) = open.last() {
                out[p].last_child_end = after;
            }
        } else {
            open.push(out.len() - 1);
        }
    }
}

/// The element of `m` with this tag and identifier, if there is exactly one.
fn find(m: &Model, tag: &str, ident: &str) -> Option<Loc> {
    let mut found = m.walk().filter_map(|e| match e {
        Walk::Enter(el) if el.tag() == tag && el.identifier() == Some(ident) => Some(el.loc()),
        _ => None,
    });
    let first = found.next()?;
    found.next().is_none().then_some(first)
}

/// The tags named uniquely in the text (by tag and identifier).
fn targets(tags: &[Tag]) -> Vec<usize> {
    (0..tags.len())
        .filter(|&i| {
            let t = &tags[i];
            t.ident.is_some() && tags.iter().filter(|u| u.tag == t.tag && u.ident == t.ident).count() == 1
        })
        .collect()
}

/// For an edit of a default class (`t`), the start tags of the root `<default>`s: a
/// class `/` left alone there makes the saver write `class="main"` on it (else the
/// reader would fold the class into the root class).
fn root_defaults<'t>(tags: &'t [Tag], t: &Tag) -> impl Iterator<Item = (usize, usize)> + 't {
    let class = t.tag == "default";
    tags.iter().filter(move |u| class && u.tag == "default" && u.depth == 1).map(|u| (u.start, u.start_end))
}

/// For an edit of a section of the root (`t`, such as a root `<default>` with a
/// `class`), the other tags of that section: a section given twice is one element
/// (removing it empties every tag of it; a value is set where it wins), as
/// `(start, end_end)` when `whole`, else their start tags.
fn same_section<'t>(tags: &'t [Tag], t: &'t Tag, whole: bool) -> impl Iterator<Item = (usize, usize)> + 't {
    let at_root = t.depth == 1;
    tags.iter()
        .filter(move |u| at_root && u.depth == 1 && u.tag == t.tag)
        .map(move |u| (u.start, if whole { u.end_end } else { u.start_end }))
}

/// The start tags naming any of `names` (the references to them).
fn referrers<'t>(tags: &'t [Tag], names: &[String]) -> impl Iterator<Item = (usize, usize)> + 't {
    let names = names.to_vec();
    tags.iter().filter(move |t| t.values.iter().any(|v| names.contains(v))).map(|t| (t.start, t.start_end))
}

/// Applies `edit`; returns the model and the regions of the text it may change.
fn apply(m: &Model, edit: &Edit, tags: &[Tag], targets: &[usize]) -> Option<(Model, Vec<(usize, usize)>)> {
    let pick = |i: u16| -> Option<(&Tag, Loc)> {
        let t = &tags[*targets.get(i as usize % targets.len().max(1))?];
        Some((t, find(m, &t.tag, t.ident.as_deref()?)?))
    };
    match edit {
        Edit::Set { target, attr, value } if !targets.is_empty() => {
            let (t, loc) = pick(*target)?;
            let attr = ATTRS[*attr as usize % ATTRS.len()];
            Some((value.set(m, &loc, attr)?, attr_regions(tags, t, attr)?))
        }
        Edit::Clear { target, attr } if !targets.is_empty() => {
            let (t, loc) = pick(*target)?;
            let attr = ATTRS[*attr as usize % ATTRS.len()];
            Some((m.clear_attr(&loc, attr).ok()?, attr_regions(tags, t, attr)?))
        }
        Edit::Remove { target } if !targets.is_empty() => {
            let (t, loc) = pick(*target)?;
            let next = m.remove(&loc).ok()?;
            // Every name inside it (inside every tag of it, for a section of the root
            // given in several tags) goes with it.
            let spans: Vec<(usize, usize)> =
                same_section(tags, t, true).chain([(t.start, t.end_end)]).collect();
            let inside: Vec<String> = tags
                .iter()
                .filter(|u| spans.iter().any(|&(a, b)| u.start >= a && u.end_end <= b))
                .filter_map(|u| u.ident.clone())
                .collect();
            let mut regions: Vec<(usize, usize)> = referrers(tags, &inside).collect();
            regions.extend(root_defaults(tags, t));
            regions.extend(same_section(tags, t, true));
            regions.push((t.lead, t.end_end));
            Some((next, regions))
        }
        Edit::Add { parent, element } => {
            let (t, loc) = match parent {
                Some(i) => {
                    let bodies: Vec<usize> = targets.iter().copied().filter(|&k| tags[k].tag == "body").collect();
                    let t = &tags[*bodies.get(*i as usize % bodies.len().max(1))?];
                    (t, find(m, "body", t.ident.as_deref()?)?)
                }
                None => {
                    let mut worlds = tags.iter().filter(|t| t.tag == "worldbody" && t.depth == 1);
                    let t = worlds.next()?;
                    if worlds.next().is_some() {
                        return None;
                    }
                    (t, m.worldbody())
                }
            };
            let next = m.add(&loc, element.build()).ok()?.0;
            let region = if t.end == t.end_end { (t.start, t.end_end) } else { (t.last_child_end, t.end) };
            Some((next, vec![region]))
        }
        _ => None,
    }
}

/// What setting or clearing `attr` of the element of `t` may change: its start tag,
/// and for its identifier the references to it.
fn attr_regions(tags: &[Tag], t: &Tag, attr: &str) -> Option<Vec<(usize, usize)>> {
    let mut regions = vec![(t.start, t.start_end)];
    regions.extend(same_section(tags, t, false));
    let key = if t.tag == "default" { "class" } else { "name" };
    if attr == key {
        regions.extend(referrers(tags, &[t.ident.clone()?]));
        regions.extend(root_defaults(tags, t));
    }
    Some(regions)
}

/// Panics unless `saved` holds every byte of `original` outside `regions`, in order
/// (what precedes the first region as its start, what follows the last as its end).
fn check_kept(original: &str, saved: &str, regions: &[(usize, usize)]) {
    let mut regions = regions.to_vec();
    regions.sort_unstable();
    let (mut pieces, mut at) = (Vec::new(), 0);
    for (a, b) in regions {
        if a >= at {
            pieces.push(&original[at..a]);
        }
        at = at.max(b);
    }
    let last = &original[at..];
    if pieces.is_empty() {
        assert!(saved == original, "saved with no edit, changed\n--- read\n{original}\n--- saved\n{saved}");
        return;
    }
    let fail = |what: &str, piece: &str| -> ! {
        panic!("{what}: {piece:?}\n--- read\n{original}\n--- saved\n{saved}");
    };
    if !saved.starts_with(pieces[0]) {
        fail("the text before the first edited tag changed", pieces[0]);
    }
    let mut pos = pieces[0].len();
    for p in &pieces[1..] {
        match saved[pos..].find(p) {
            Some(i) => pos += i + p.len(),
            None => fail("text outside the edited tags lost or moved", p),
        }
    }
    if !saved[pos..].ends_with(last) {
        fail("the text after the last edited tag changed", last);
    }
}

fn run(text: &str, edits: &mut Unstructured<'_>) {
    let Ok(model) = options().read_str(text) else { return };
    let files = model.to_source_files().unwrap_or_else(|e| panic!("an unedited model does not save: {e}"));
    assert_eq!(files.len(), 1, "a confined model read from text has one file");
    assert!(files[0].text == text && !files[0].changed, "unedited, saved otherwise:\n{}", files[0].text);
    let tags = tags(text);
    let targets = targets(&tags);
    let (mut m, mut regions) = (model.clone(), Vec::new());
    for _ in 0..MAX_EDITS {
        let Ok(edit) = Edit::arbitrary(edits) else { break };
        if let Some((next, r)) = apply(&m, &edit, &tags, &targets) {
            m = next;
            regions.extend(r);
        }
    }
    let saved = match m.to_source_files() {
        Ok(f) => f,
        Err(
            SaveError::MissingRequired { .. }
            | SaveError::UnnamedTarget { .. }
            | SaveError::RootClassRenamed(_),
        ) => return,
        Err(e) => panic!("an edited model does not save: {e}"),
    };
    let out = &saved[0].text;
    let back = options().read_str(out).unwrap_or_else(|e| panic!("saved text does not read back: {e}\n{out}"));
    let same = back == m || back.to_xml_string().ok() == m.to_xml_string().ok();
    assert!(same, "saved text reads back as another model\n--- read\n{text}\n--- saved\n{out}");
    let again = back.to_source_files().unwrap_or_else(|e| panic!("read back, does not save: {e}"));
    assert_eq!(&again[0].text, out);
    check_kept(text, out, &regions);
}

fuzz_target!(|data: &[u8]| {
    let (text, rest) = match data.iter().rposition(|&b| b == 0) {
        Some(i) => (&data[..i], &data[i + 1..]),
        None => (data, data),
    };
    let Ok(text) = std::str::from_utf8(text) else { return };
    run(text, &mut Unstructured::new(rest));
});
