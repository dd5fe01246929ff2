//! Reads every `*.xml` file of the conformance corpus (`tests/conformance/cases`),
//! writes every model that reads, checks that the output is well-formed XML and that it
//! reads back to a model that writes the same text; plus malformed-input tests that pin
//! the exact error kind and line:column.
//!
//! How input files are classified (derived from the cases, not from file names):
//! - a file that a case `load`s without `expect_error` must read;
//! - a file that a case `load`s with `expect_error: parse_error` must fail with a
//!   positioned error (any kind but a missing file); with `expect_error:
//!   file_not_found` it must fail with [`ErrorKind::FileNotFound`];
//! - a file that no case loads but that another file `<include>`s must read, unless
//!   every file including it is expected to fail (then it may fail, as the deliberately
//!   broken `broken_part.xml` and the `inner.xml` that names a missing mesh do);
//! - any other input file is a test failure (a new kind of file to classify).
//!
//! `expected_*.xml` files are dm_control's output. They hold `/` in identifiers (the
//! root default class `<default class="/">`, scoped names such as `robot/torso`, auto
//! names `//unnamed_geom_0`), which the reader accepts as literal names, so each must
//! read, except those that name an asset file by dm_control's hashed name
//! (`cube-<sha1>.stl`: dm_control writes those files beside its output, and the corpus
//! does not hold them), which must fail with [`ErrorKind::FileNotFound`] for that name.
//!
//! Every model that reads (inputs and dm_control outputs alike) must write, and its
//! output must read back, with each file it holds supplied by the name the writer gave
//! it, to a model that writes the same text; and again with its root default class
//! named, where the only difference is that class's extra level.
//!
//! The counts of each kind of file are floors (the corpus as of writing): a corpus
//! that lost files, or a walk that no longer finds them, fails the test; adding cases
//! does not.

use crate::text;

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use mjcf::{
    ElementRef, ErrorKind, Model, ReadError, ReadOptions, TextPos, Value, ValueError, WriteOptions,
};
use quick_xml::events::Event;

fn cases_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/conformance/cases")
}

fn xml_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for p in entries {
        if p.is_dir() {
            xml_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "xml") {
            out.push(p);
        }
    }
}

/// Removes `.` and `..` components without touching the disk.
fn normalize(p: &Path) -> PathBuf {
    let mut out = PathBuf::new();
    for c in p.components() {
        match c {
            std::path::Component::CurDir => {}
            std::path::Component::ParentDir => {
                out.pop();
            }
            c => out.push(c),
        }
    }
    out
}

fn is_expected_output(p: &Path) -> bool {
    p.file_name().and_then(|n| n.to_str()).is_some_and(|n| n.starts_with("expected_"))
}

/// Every file a case loads, with the error category the case expects (None: must read).
fn case_loads() -> BTreeMap<PathBuf, Option<String>> {
    let mut loads: BTreeMap<PathBuf, Option<String>> = BTreeMap::new();
    let mut dirs: Vec<PathBuf> =
        std::fs::read_dir(cases_dir()).unwrap().map(|e| e.unwrap().path()).collect();
    dirs.sort();
    for dir in dirs {
        let json = dir.join("case.json");
        let Ok(text) = std::fs::read_to_string(&json) else { continue };
        let case: serde_json::Value =
            serde_json::from_str(&text).unwrap_or_else(|e| panic!("{}: {e}", json.display()));
        let ops = case["ops"].as_array().unwrap_or_else(|| panic!("{}: no ops", json.display()));
        for op in ops.iter().filter(|op| op["op"] == "load") {
            let file = op["file"]
                .as_str()
                .unwrap_or_else(|| panic!("{}: load without file", json.display()));
            let expect = op.get("expect_error").and_then(|e| e.as_str()).map(str::to_string);
            let path = normalize(&dir.join(file));
            if let Some(previous) = loads.insert(path.clone(), expect.clone()) {
                assert_eq!(
                    previous,
                    expect,
                    "{} is loaded with different expectations",
                    path.display()
                );
            }
        }
    }
    loads
}

/// The files named by `<include file=…>` in `text` (relative to the file's folder).
fn includes_of(path: &Path, text: &str) -> Vec<PathBuf> {
    let mut reader = quick_xml::Reader::from_str(text);
    let mut out = Vec::new();
    loop {
        match reader.read_event() {
            Ok(Event::Start(t) | Event::Empty(t)) if t.name().as_ref() == "include" => {
                for a in t.attributes().flatten() {
                    if a.key.as_ref() == "file" {
                        let v = a.normalized_value(quick_xml::XmlVersion::default()).unwrap();
                        out.push(normalize(&path.parent().unwrap().join(v.as_ref())));
                    }
                }
            }
            Ok(Event::Eof) | Err(_) => break,
            Ok(_) => {}
        }
    }
    out
}

/// Parses `text` with quick-xml over all events and all attribute values; returns the
/// number of elements. Panics on any XML error.
fn assert_well_formed(text: &str, what: &str) -> usize {
    let mut reader = quick_xml::Reader::from_str(text);
    let mut elements = 0;
    let mut depth = 0usize;
    let mut roots = 0;
    loop {
        let (tag, opens) = match reader.read_event() {
            Ok(Event::Start(t)) => (t, true),
            Ok(Event::Empty(t)) => (t, false),
            Ok(Event::End(_)) => {
                depth -= 1;
                continue;
            }
            Ok(Event::Eof) => break,
            Ok(_) => continue,
            Err(e) => {
                panic!("{what}: output is not well-formed XML at {}: {e}", reader.error_position())
            }
        };
        elements += 1;
        roots += usize::from(depth == 0);
        depth += usize::from(opens);
        for a in tag.attributes() {
            let a = a.unwrap_or_else(|e| panic!("{what}: bad attribute: {e}"));
            a.normalized_value(quick_xml::XmlVersion::default())
                .unwrap_or_else(|e| panic!("{what}: bad attribute value: {e}"));
        }
    }
    assert_eq!(depth, 0, "{what}: unbalanced output");
    assert_eq!(roots, 1, "{what}: output must have exactly one root element");
    elements
}

/// Whether the last component of `path` is dm_control's hashed asset file name,
/// `stem-<40 hex digits>.ext`.
fn is_hashed_file_name(path: &Path) -> bool {
    let stem = path.file_stem().and_then(|s| s.to_str()).unwrap_or("");
    stem.rsplit_once('-').is_some_and(|(head, hash)| {
        !head.is_empty() && hash.len() == 40 && hash.bytes().all(|b| b.is_ascii_hexdigit())
    })
}

#[test]
fn is_hashed_file_name_knows_dm_control_asset_names() {
    let hashed = |p: &str| is_hashed_file_name(Path::new(p));
    assert!(hashed("/c/cube-3c02070cac597a650269d1d12dd7380c7efedfcc.stl"));
    assert!(hashed("a-b-3c02070cac597a650269d1d12dd7380c7efedfcc"));
    assert!(!hashed("/c/cube.stl"));
    assert!(!hashed("/c/-3c02070cac597a650269d1d12dd7380c7efedfcc.stl"));
    assert!(!hashed("/c/cube-3c02070cac597a650269d1d12dd7380c7efedfc.stl"));
    assert!(!hashed("/c/cube-3c02070cac597a650269d1d12dd7380c7efedfcz.stl"));
    assert!(!hashed("/c-3c02070cac597a650269d1d12dd7380c7efedfcc/cube.stl"));
}

/// Every file held by the model, by the name the writer gives it.
fn file_assets(model: &Model, options: &WriteOptions) -> BTreeMap<String, Vec<u8>> {
    fn walk(e: ElementRef<'_>, with_hash: bool, out: &mut BTreeMap<String, Vec<u8>>) {
        for (_, v) in e.attrs() {
            if let Value::File(f) = v {
                out.insert(f.vfs_name(with_hash), f.contents().to_vec());
            }
        }
        for c in e.children() {
            walk(c, with_hash, out);
        }
    }
    let mut out = BTreeMap::new();
    walk(model.element(&model.root()).unwrap(), options.filename_with_hash, &mut out);
    out
}

/// Read options that supply every file `model` holds, by the name the writer gives it
/// with `options`.
fn read_options_with_files(model: &Model, options: &WriteOptions) -> ReadOptions {
    let mut read = ReadOptions::new();
    for (file, contents) in file_assets(model, options) {
        read = read.asset(&file, contents);
    }
    read
}

#[derive(Debug, Default)]
struct Counts {
    inputs: usize,
    inputs_read: usize,
    inputs_failed_as_expected: usize,
    included_only_failed: usize,
    outputs_of_dm_control: usize,
    outputs_of_dm_control_read: usize,
    outputs_of_dm_control_missing_hashed_file: usize,
    written: usize,
    reread_as_written: usize,
    rewritten_after_naming_root_class: usize,
    written_elements: usize,
}

#[test]
fn every_corpus_file_reads_or_fails_as_its_case_expects_and_every_model_writes_and_reads_back() {
    let mut files = Vec::new();
    xml_files(&cases_dir(), &mut files);
    let loads = case_loads();

    // Who includes whom (input files only).
    let mut included_by: BTreeMap<PathBuf, Vec<PathBuf>> = BTreeMap::new();
    for f in files.iter().filter(|f| !is_expected_output(f)) {
        let text = std::fs::read_to_string(f).unwrap();
        for inc in includes_of(f, &text) {
            included_by.entry(inc).or_default().push(normalize(f));
        }
    }
    let expected_to_fail = |p: &Path| loads.get(p).is_some_and(|e| e.is_some());

    let mut c = Counts::default();
    let mut must_read = 0usize;
    let mut may_fail = BTreeSet::new();
    for f in &files {
        let key = normalize(f);
        let name = key.strip_prefix(cases_dir()).unwrap_or(&key).display().to_string();
        let result = Model::from_path(f);
        let model = if is_expected_output(f) {
            c.outputs_of_dm_control += 1;
            match result {
                Ok(m) => {
                    c.outputs_of_dm_control_read += 1;
                    m
                }
                Err(e) => {
                    assert!(
                        matches!(e.kind(), ErrorKind::FileNotFound { path, .. } if is_hashed_file_name(path)),
                        "{name}: dm_control output failed for another reason than a missing asset file of a hashed name: {e} ({:?})",
                        e.kind()
                    );
                    c.outputs_of_dm_control_missing_hashed_file += 1;
                    continue;
                }
            }
        } else {
            c.inputs += 1;
            let expectation = match loads.get(&key) {
                Some(e) => e.clone(),
                None => {
                    let includers = included_by.get(&key).unwrap_or_else(|| {
                        panic!(
                            "{name}: neither loaded by a case nor included by a file; classify it"
                        )
                    });
                    if includers.iter().all(|i| expected_to_fail(i)) {
                        may_fail.insert(name.clone());
                        Some("may_fail".to_string())
                    } else {
                        None
                    }
                }
            };
            match (expectation.as_deref(), result) {
                (None, Ok(m)) => {
                    must_read += 1;
                    c.inputs_read += 1;
                    m
                }
                (None, Err(e)) => panic!("{name}: should read, got {e} ({:?})", e.kind()),
                (Some("may_fail"), Ok(m)) => {
                    c.inputs_read += 1;
                    m
                }
                (Some("may_fail"), Err(e)) => {
                    assert!(
                        e.pos().is_some() || matches!(e.kind(), ErrorKind::FileNotFound { .. }),
                        "{name}: error without a position: {e}"
                    );
                    c.included_only_failed += 1;
                    continue;
                }
                (Some(cat), Ok(_)) => panic!("{name}: the case expects {cat}, but it read"),
                (Some("file_not_found"), Err(e)) => {
                    assert!(
                        matches!(e.kind(), ErrorKind::FileNotFound { .. }),
                        "{name}: expected a missing file, got {e}"
                    );
                    c.inputs_failed_as_expected += 1;
                    continue;
                }
                (Some(cat), Err(e)) => {
                    assert_eq!(cat, "parse_error", "{name}: unexpected load expectation");
                    assert!(
                        !matches!(
                            e.kind(),
                            ErrorKind::FileNotFound { .. } | ErrorKind::FileOutsideRoot(_)
                        ),
                        "{name}: expected a parse error, got {e}"
                    );
                    assert!(e.pos().is_some(), "{name}: a parse error must carry line:column: {e}");
                    c.inputs_failed_as_expected += 1;
                    continue;
                }
            }
        };

        // Write it, and check the output is well-formed XML.
        let out = model.to_xml_string().unwrap_or_else(|e| panic!("{name}: cannot write: {e}"));
        c.written_elements += assert_well_formed(&out, &name);
        let one_line = model
            .to_xml_string_with(&WriteOptions { pretty_print: false, ..WriteOptions::default() })
            .unwrap_or_else(|e| panic!("{name}: cannot write: {e}"));
        assert_well_formed(&one_line, &name);
        assert_eq!(one_line.lines().count(), 1, "{name}");
        c.written += 1;

        // The output reads back (every file supplied by the name the writer gave it)
        // and writes the same text again: the root class `<default class="/">`, the
        // scoped names and the auto names read back as they were written.
        let reread = read_options_with_files(&model, &WriteOptions::default())
            .read_str(&out)
            .unwrap_or_else(|e| panic!("{name}: the output does not read back: {e}"));
        let rewritten = reread.to_xml_string().unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(rewritten, out, "{name}: write(read(write(m))) differs");
        c.reread_as_written += 1;

        // With the root class named, writing it again gives the same text but for the
        // extra class level in the defaults (none when a class is named `/`: see below).
        let root_class = "corpus_root_class";
        let named = model
            .set_attr(&model.default_class(), "class", root_class)
            .unwrap_or_else(|e| panic!("{name}: naming the root class: {e}"));
        // Without the hash in file names: a hashed name read back is a new stem, so
        // it would get a second hash when written again.
        let options = WriteOptions { filename_with_hash: false, ..WriteOptions::default() };
        let w1 = named.to_xml_string_with(&options).unwrap();
        let m2 = read_options_with_files(&named, &options)
            .read_str(&w1)
            .unwrap_or_else(|e| panic!("{name}: with the root class named: {e}"));
        let w2 = m2.to_xml_string_with(&options).unwrap();
        // Read back, the root class is unnamed: written `/`, one level more; or, when a
        // class of the model is named `/` (a composed model written out), as MuJoCo's
        // main class, the same text.
        let expected = if m2.find(mjcf::Namespace::Default, "/").is_some() {
            w1.clone()
        } else {
            text::rewrapped_root_default(&w1)
        };
        assert_eq!(
            w2, expected,
            "{name}: with the root class named, write(read(write(m))) differs"
        );
        c.rewritten_after_naming_root_class += 1;
    }

    println!("{c:#?}");
    println!("input files that may fail (only included by files expected to fail): {may_fail:?}");
    let expected_failures = loads.values().filter(|e| e.is_some()).count();
    assert!(c.inputs > 0 && c.inputs_read > 0 && c.written > 0 && c.outputs_of_dm_control > 0);
    assert_eq!(
        c.inputs_failed_as_expected, expected_failures,
        "every expected load failure happened"
    );
    assert_eq!(c.inputs_read, must_read + (may_fail.len() - c.included_only_failed));
    assert_eq!(c.inputs, c.inputs_read + c.inputs_failed_as_expected + c.included_only_failed);
    assert_eq!(
        c.written,
        c.inputs_read + c.outputs_of_dm_control_read,
        "every model that reads also writes"
    );
    assert_eq!(
        c.outputs_of_dm_control,
        c.outputs_of_dm_control_read + c.outputs_of_dm_control_missing_hashed_file
    );
    // The corpus as of writing: 221 input files (214 read; 5 loads expected to fail;
    // `broken_part.xml` and `inner.xml` fail as only their failing includers use them)
    // and 263 dm_control outputs (228 read; 35 name a hashed asset file the corpus does
    // not hold). Every one of the 442 models that read writes, reads back and writes
    // the same text (checked per model above).
    assert!(c.inputs >= 221 && c.inputs_read >= 214, "{c:?}");
    assert!(c.inputs_failed_as_expected >= 5 && c.included_only_failed >= 2, "{c:?}");
    assert!(c.outputs_of_dm_control >= 263 && c.outputs_of_dm_control_read >= 228, "{c:?}");
}

// ---------------------------------------------------------------------------------
// Malformed input: exact error kind and 1-based line:column.

fn read_err(text: &str) -> ReadError {
    match Model::from_xml_str(text) {
        Ok(m) => {
            panic!("expected an error, got a model:\n{}", m.to_xml_string().unwrap_or_default())
        }
        Err(e) => e,
    }
}

fn at(line: u32, column: u32) -> Option<TextPos> {
    Some(TextPos { line, column })
}

#[test]
fn unclosed_element_at_end_of_input() {
    let e = read_err("<mujoco>\n  <worldbody>\n    <body>\n");
    assert!(matches!(e.kind(), ErrorKind::Syntax(m) if m.contains("unclosed")), "{e:?}");
    // Reported at the end of the input.
    assert_eq!(e.pos(), at(4, 1));
}

#[test]
fn end_tag_that_closes_the_wrong_element() {
    let e = read_err("<mujoco>\n  <worldbody>\n    <body>\n  </worldbody>\n</mujoco>");
    assert!(matches!(e.kind(), ErrorKind::Syntax(m) if m.contains("</body>")), "{e:?}");
    assert_eq!(e.pos(), at(4, 3));
}

#[test]
fn start_tag_that_is_never_finished() {
    let e = read_err("<mujoco>\n  <worldbody\n</mujoco>");
    assert!(matches!(e.kind(), ErrorKind::Syntax(_)), "{e:?}");
    assert_eq!(e.pos(), at(2, 3));
}

#[test]
fn bad_float_array_value() {
    let e = read_err(
        "<mujoco>\n  <worldbody>\n    <geom size=\"0.1 big\"/>\n  </worldbody>\n</mujoco>",
    );
    assert_eq!(
        e.kind(),
        &ErrorKind::InvalidValue {
            tag: "geom",
            attribute: "size",
            value: "0.1 big".into(),
            error: ValueError::NotFloatArray
        }
    );
    assert_eq!(e.pos(), at(3, 5));
}

#[test]
fn bad_keyword_value() {
    let e = read_err(
        "<mujoco>\n  <worldbody>\n    <body>\n      <geom type=\"blob\"/>\n    </body>\n  </worldbody>\n</mujoco>",
    );
    assert!(
        matches!(
            e.kind(),
            ErrorKind::InvalidValue { tag: "geom", attribute: "type", value, error: ValueError::NotKeyword { valid } }
                if value == "blob" && valid.contains(&"box")
        ),
        "{e:?}"
    );
    assert_eq!(e.pos(), at(4, 7));
}

#[test]
fn too_many_entries() {
    let e = read_err("<mujoco>\n<worldbody><site pos=\"0 0 0 0\"/></worldbody>\n</mujoco>");
    assert_eq!(
        e.kind(),
        &ErrorKind::InvalidValue {
            tag: "site",
            attribute: "pos",
            value: "0 0 0 0".into(),
            error: ValueError::TooLong { max: 3, len: 4 }
        }
    );
    assert_eq!(e.pos(), at(2, 12));
}

#[test]
fn unknown_element() {
    let e = read_err(
        "<mujoco>\n  <worldbody>\n    <body>\n      <bogus/>\n    </body>\n  </worldbody>\n</mujoco>",
    );
    assert_eq!(
        e.kind(),
        &ErrorKind::InvalidChild { parent: "body", tag: "bogus".into(), suggestion: None }
    );
    assert_eq!(e.pos(), at(4, 7));
}

#[test]
fn unknown_section() {
    let e = read_err("<mujoco model=\"m\">\n  <scene/>\n</mujoco>");
    assert_eq!(
        e.kind(),
        &ErrorKind::InvalidChild { parent: "mujoco", tag: "scene".into(), suggestion: None }
    );
    assert_eq!(e.pos(), at(2, 3));
}

#[test]
fn unknown_attribute() {
    let e = read_err(
        "<mujoco>\n  <worldbody>\n    <geom size=\"1\" colour=\"red\"/>\n  </worldbody>\n</mujoco>",
    );
    assert_eq!(
        e.kind(),
        &ErrorKind::UnknownAttribute { tag: "geom", attribute: "colour".into(), suggestion: None }
    );
    assert_eq!(e.pos(), at(3, 5));
}

#[test]
fn wrong_root() {
    let e = read_err("<?xml version=\"1.0\"?>\n<robot name=\"r\">\n</robot>");
    assert_eq!(e.kind(), &ErrorKind::WrongRoot("robot".into()));
    assert_eq!(e.pos(), at(2, 1));
}

#[test]
fn invalid_utf8_bytes() {
    // `é` is fine; the lone 0xFF byte after it is the 18th character of line 3.
    let e = ReadOptions::new()
        .read_bytes(b"<mujoco>\n  <worldbody>\n    <body name=\"\xc3\xa9\xff\"/>\n  </worldbody>\n</mujoco>")
        .unwrap_err();
    assert_eq!(e.kind(), &ErrorKind::InvalidUtf8);
    assert_eq!(e.pos(), at(3, 18));
}

#[test]
fn doctype_entities_are_never_expanded() {
    // In an identifier.
    let text = "<!DOCTYPE mujoco [\n  <!ENTITY n \"evil\">\n]>\n<mujoco>\n  <worldbody>\n    <body name=\"&n;\"/>\n  </worldbody>\n</mujoco>";
    let e = read_err(text);
    assert!(matches!(e.kind(), ErrorKind::Syntax(m) if m.contains("entity")), "{e:?}");
    assert_eq!(e.pos(), at(6, 5));
    // In the model name on the root.
    let e = read_err("<!DOCTYPE mujoco [<!ENTITY n \"evil\">]>\n<mujoco model=\"&n;\"/>");
    assert!(matches!(e.kind(), ErrorKind::Syntax(m) if m.contains("entity")), "{e:?}");
    assert_eq!(e.pos(), at(2, 1));
    // A DOCTYPE whose entity is never used is dropped, and the predefined entities and
    // character references still work.
    let m = Model::from_xml_str(
        "<!DOCTYPE mujoco [<!ENTITY n \"evil\">]>\n<mujoco model=\"a&amp;b\">\n<worldbody><body name=\"&lt;&#65;&gt;\"/></worldbody></mujoco>",
    )
    .unwrap();
    assert_eq!(m.name(), "a&b");
    assert!(m.find(mjcf::Namespace::Body, "<A>").is_some());
    assert!(!m.to_xml_string().unwrap().contains("evil"));
}

#[test]
fn a_slash_in_a_name_read_from_xml_is_one_literal_name() {
    // MuJoCo accepts `/` in names; a file this crate wrote holds `robot/torso`.
    let m = Model::from_xml_str(
        "<mujoco>\n  <worldbody>\n    <geom name=\"a/b\" size=\"1\"/>\n  </worldbody>\n</mujoco>",
    )
    .unwrap();
    let g = m.find(mjcf::Namespace::Geom, "a/b").expect("found by its literal name");
    assert_eq!(m.get(&g).unwrap().full_name().as_deref(), Some("a/b"));
    assert!(m.scopes().next().is_none(), "no scopes: a flat model");
    // Given through the API, a name with `/` is refused: there `/` separates scopes.
    let e = m.set_attr(&g, "name", "c/d").unwrap_err();
    assert!(matches!(
        e.kind(),
        ErrorKind::InvalidValue { error: ValueError::SlashInIdentifier, .. }
    ));
}

#[test]
fn duplicate_identifier_points_at_the_second_element() {
    let e = read_err(
        "<mujoco>\n  <worldbody>\n    <geom name=\"g\" size=\"1\"/>\n    <geom name=\"g\" size=\"2\"/>\n  </worldbody>\n</mujoco>",
    );
    assert!(
        matches!(e.kind(), ErrorKind::DuplicateIdentifier { name, .. } if name == "g"),
        "{e:?}"
    );
    assert_eq!(e.pos(), at(4, 5));
}

#[test]
fn missing_file_has_a_position_in_text() {
    let dir = cases_dir().join("hand_112_err_file_not_found_more");
    let e = ReadOptions::new()
        .base_dir(&dir)
        .read_str("<mujoco>\n  <asset>\n    <mesh name=\"gone\" file=\"gone.stl\"/>\n  </asset>\n</mujoco>")
        .unwrap_err();
    assert!(
        matches!(e.kind(), ErrorKind::FileNotFound { path, .. } if path.ends_with("gone.stl")),
        "{e:?}"
    );
    assert_eq!(e.pos(), at(3, 5));
    // A model file that does not exist has no position.
    let e = Model::from_path(dir.join("no_such_model.xml")).unwrap_err();
    assert!(matches!(e.kind(), ErrorKind::FileNotFound { .. }), "{e:?}");
    assert_eq!(e.pos(), None);
}
