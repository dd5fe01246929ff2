//! Drift checks over the crate's source text (no dependencies: the files are read
//! and scanned as text).
//!
//! - element behaviour comes from the schema's roles (`schema/roles.txt`), never
//!   from comparing an element's tag with a string;
//! - no file in `src/` is over 1,000 lines and no function over 120 lines (but for
//!   the exemptions listed, each with the issue item that removes it);
//! - no import circle between the files of `src/`, nor between its top-level
//!   modules (edges from `use crate::…`, `use super::…` and `crate::…`/`super::…`
//!   paths in code).
//!
//! - a joint's type is read in `model/layout.rs` only (`JointType`): no other
//!   library code compares a string with a joint type's keyword.
//!
//! - the file system is touched only in `src/files/` (one canonical path, one
//!   reader with the caps and confinement, one writer for every file written).
//!
//! `tests/docs.rs` holds the checks over documents: no comment or document cites a
//! line of code by number, and the README's real-model floor is `.ci/run`'s.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Every `.rs` file under `src/`, with its text, in path order.
fn sources() -> Vec<(PathBuf, String)> {
    fn walk(dir: &Path, out: &mut Vec<PathBuf>) {
        let mut entries: Vec<PathBuf> =
            std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().path()).collect();
        entries.sort();
        for p in entries {
            if p.is_dir() {
                walk(&p, out);
            } else if p.extension().is_some_and(|e| e == "rs") {
                out.push(p);
            }
        }
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut files = Vec::new();
    walk(&root.join("src"), &mut files);
    assert!(files.len() > 30, "found {} files under src/", files.len());
    files
        .into_iter()
        .map(|p| {
            let text = std::fs::read_to_string(&p).unwrap();
            (p.strip_prefix(root).unwrap().to_path_buf(), text)
        })
        .collect()
}

/// What names a use of the file system in code.
const FILE_SYSTEM: &[&str] = &[
    "std::fs",
    "fs::",
    "File::",
    "OpenOptions",
    "Path::exists",
    ".exists()",
    "metadata(",
    "read_dir",
    "canonicalize",
    "symlink(",
];

/// The file-system uses in the code of `text` (comments, strings and the test
/// module at its end left out), by line.
fn file_system_uses(text: &str) -> Vec<(usize, &'static str)> {
    let code = code_only(text);
    let code = ["#[cfg(test)]", "#[cfg(all(test"]
        .iter()
        .filter_map(|m| code.find(m))
        .min()
        .map_or(code.as_str(), |at| &code[..at]);
    let mut out = Vec::new();
    // A needle that starts a word must start one in the line (`dofs::` is not `fs::`).
    let found = |line: &str, f: &str| {
        line.match_indices(f).any(|(at, _)| {
            let word = f.starts_with(|c: char| c.is_alphanumeric());
            !word || !line[..at].ends_with(|c: char| c.is_alphanumeric() || c == '_')
        })
    };
    for (i, line) in code.lines().enumerate() {
        out.extend(FILE_SYSTEM.iter().filter(|f| found(line, f)).map(|f| (i + 1, *f)));
    }
    out
}

/// The file layer (`src/files/`) is the only library code that touches the file
/// system; test modules (a `tests.rs` file, a `#[cfg(test)]` module) may.
#[test]
fn the_file_system_is_touched_only_in_src_files() {
    let found: Vec<String> = sources()
        .into_iter()
        .map(|(p, t)| (p.display().to_string(), t))
        .filter(|(p, _)| !p.starts_with("src/files/") && !p.ends_with("/tests.rs"))
        .flat_map(|(p, t)| {
            file_system_uses(&t).into_iter().map(move |(line, what)| format!("{p}:{line}: {what}"))
        })
        .collect();
    assert!(found.is_empty(), "touch the file system in src/files/ only: {found:#?}");
    let sample = "/// std::fs::read(p)\nfn f() { let s = \"std::fs\"; std::fs::write(p, b)?; dofs::x(); }\n#[cfg(test)]\nmod tests { fn g() { std::fs::read(p); } }";
    assert_eq!(file_system_uses(sample), [(2, "std::fs"), (2, "fs::")]);
    assert!(file_system_uses("use std::fs;\nfn f() { fs::read(p); }").len() == 2);
}

/// The places in `text` where an element's tag is compared with a string literal:
/// `tag() == "…"`, `tag() != "…"`, `.tag == "…"`, `matches!(….tag(), "…")` and a
/// `match ….tag() {` whose arms are strings.
fn tag_comparisons(text: &str) -> Vec<(usize, String)> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    for (n, line) in lines.iter().enumerate() {
        let squeezed: String = line.split_whitespace().collect::<Vec<_>>().join(" ");
        let compared = ["tag() == \"", "tag() != \"", ".tag == \"", ".tag != \""]
            .iter()
            .any(|p| squeezed.contains(p));
        let in_matches = squeezed.contains("matches!(")
            && squeezed.split("matches!(").skip(1).any(|rest| {
                let arg = rest.split(',').next().unwrap_or("");
                arg.contains("tag") && rest.contains('"')
            });
        // `match x.tag() {` (or `match tag {`) followed by a string arm.
        let match_on_tag = (squeezed.contains("match ") && squeezed.contains("tag() {"))
            && lines[n + 1..].iter().take(3).any(|l| l.trim_start().starts_with('"'));
        if compared || in_matches || match_on_tag {
            out.push((n + 1, line.trim().to_string()));
        }
    }
    out
}

/// Files outside `src/xml/read/` that parse XML, each with why:
/// - `files/scan.rs` finds the files an MJCF file names (what an asset `<model>`
///   file brings with it, and the paths asset `<model>`s are written with, which a
///   reopened scene reads its parts from) by the schema, as the reader would read
///   them; edits of a model need it too, and `model` sits below `xml`, so it lives in
///   the files layer below both (in `xml` it made the circle `model` <-> `xml`).
const XML_PARSED_OUTSIDE_THE_READER: &[(&str, &str)] =
    &[("src/files/scan.rs", "the files a file names, for the model layer")];

/// Whether code (not comments or strings) parses XML: names the XML parser crate.
fn parses_xml(text: &str) -> bool {
    code_only(text).contains("quick_xml")
}

/// `xml/read` is the only XML reader: no other file parses XML but those listed above
/// (the scan of the files an MJCF file names, once in `model/build.rs`, is `files::scan`).
#[test]
fn xml_is_parsed_only_in_xml_read() {
    let found: Vec<String> = sources()
        .into_iter()
        .map(|(p, t)| (p.display().to_string(), t))
        .filter(|(p, t)| !p.starts_with("src/xml/read/") && parses_xml(t))
        .filter(|(p, _)| !XML_PARSED_OUTSIDE_THE_READER.iter().any(|(e, _)| e == p))
        .map(|(p, _)| p)
        .collect();
    assert!(found.is_empty(), "parse XML in src/xml/read/ only: {found:?}");
    assert!(parses_xml("let r = quick_xml::Reader::from_str(t);"));
    assert!(!parses_xml("// quick_xml is not used here\nlet s = \"quick_xml\";"));
}

#[test]
fn no_element_tag_is_compared_with_a_string() {
    let mut found = Vec::new();
    for (path, text) in sources() {
        for (n, line) in tag_comparisons(&text) {
            found.push(format!("{}:{n}: {line}", path.display()));
        }
    }
    assert!(found.is_empty(), "ask the element's role (schema/roles.txt):\n{}", found.join("\n"));
}

#[test]
fn the_tag_comparison_scan_finds_each_form() {
    let forms = [
        "if node.kind().tag() == \"body\" {",
        "let not = kind.tag() != \"default\";",
        "let b = matches!(kind.tag(), \"joint\" | \"freejoint\");",
        "match kind.tag() {\n    \"joint\" => 1,\n    _ => 0,\n}",
        "let x = t.tag == \"mesh\";",
    ];
    for f in forms {
        assert_eq!(tag_comparisons(f).len(), 1, "{f}");
    }
    let fine = [
        "let k = kind.child(\"body\");",
        "match kind.role() {\n    Some(Role::Joint) => 1,\n    _ => 0,\n}",
        "self.children().find(|c| c.tag() == tag)",
    ];
    for f in fine {
        assert!(tag_comparisons(f).is_empty(), "{f}");
    }
}

/// The text with comments, strings and character literals blanked (each replaced by
/// spaces, newlines kept), so that braces and paths are code only.
fn code_only(text: &str) -> String {
    let b: Vec<char> = text.chars().collect();
    let mut out = String::with_capacity(text.len());
    let blank = |c: char| if c == '\n' { '\n' } else { ' ' };
    let mut i = 0;
    while i < b.len() {
        let c = b[i];
        let next = b.get(i + 1).copied();
        if c == '/' && next == Some('/') {
            while i < b.len() && b[i] != '\n' {
                out.push(' ');
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            let mut depth = 0;
            while i < b.len() {
                if b[i] == '/' && b.get(i + 1) == Some(&'*') {
                    depth += 1;
                    out.push_str("  ");
                    i += 2;
                } else if b[i] == '*' && b.get(i + 1) == Some(&'/') {
                    depth -= 1;
                    out.push_str("  ");
                    i += 2;
                    if depth == 0 {
                        break;
                    }
                } else {
                    out.push(blank(b[i]));
                    i += 1;
                }
            }
        } else if c == 'r'
            && (next == Some('"') || next == Some('#'))
            && !ident_char(b.get(i.wrapping_sub(1)).copied())
        {
            // A raw string: r"…", r#"…"#.
            let mut j = i + 1;
            let mut hashes = 0;
            while b.get(j) == Some(&'#') {
                hashes += 1;
                j += 1;
            }
            if b.get(j) != Some(&'"') {
                out.push(c);
                i += 1;
                continue;
            }
            j += 1;
            loop {
                if j >= b.len() {
                    break;
                }
                if b[j] == '"' && (0..hashes).all(|k| b.get(j + 1 + k) == Some(&'#')) {
                    j += 1 + hashes;
                    break;
                }
                j += 1;
            }
            out.extend(b[i..j.min(b.len())].iter().map(|&c| blank(c)));
            i = j;
        } else if c == '"' {
            let mut j = i + 1;
            while j < b.len() && b[j] != '"' {
                j += if b[j] == '\\' { 2 } else { 1 };
            }
            let j = (j + 1).min(b.len());
            out.extend(b[i..j].iter().map(|&c| blank(c)));
            i = j;
        } else if c == '\'' {
            // A character literal ('x', '\n', '\u{7b}'), or a lifetime ('a).
            let end = if next == Some('\\') {
                (i + 2..b.len()).find(|&j| b[j] == '\'')
            } else if b.get(i + 2) == Some(&'\'') {
                Some(i + 2)
            } else {
                None
            };
            match end {
                Some(e) => {
                    out.extend(b[i..=e].iter().map(|&c| blank(c)));
                    i = e + 1;
                }
                None => {
                    out.push(c);
                    i += 1;
                }
            }
        } else {
            out.push(c);
            i += 1;
        }
    }
    out
}

fn ident_char(c: Option<char>) -> bool {
    c.is_some_and(|c| c.is_alphanumeric() || c == '_')
}

/// Every `fn` of the code (as `code_only` gives it) with a body: its name, first line
/// and number of lines (from the `fn` line to its closing brace).
fn functions(code: &str) -> Vec<(String, usize, usize)> {
    let lines: Vec<usize> =
        code.char_indices().filter(|(_, c)| *c == '\n').map(|(i, _)| i).collect();
    let line_of = |pos: usize| lines.partition_point(|&l| l < pos) + 1;
    let bytes = code.as_bytes();
    let mut out = Vec::new();
    let mut at = 0;
    while let Some(found) = code[at..].find("fn ") {
        let start = at + found;
        at = start + 3;
        if start > 0 && ident_char(code[..start].chars().next_back()) {
            continue;
        }
        let name: String = code[at..].chars().take_while(|c| ident_char(Some(*c))).collect();
        if name.is_empty() {
            continue;
        }
        // The body opens at the first `{` outside parentheses, brackets and angle
        // brackets; a `;` first means a declaration without a body.
        let mut depth = 0i32;
        let mut open = None;
        for (k, &ch) in bytes.iter().enumerate().skip(at) {
            match ch {
                b'(' | b'[' => depth += 1,
                b')' | b']' => depth -= 1,
                b';' if depth == 0 => break,
                b'{' if depth == 0 => {
                    open = Some(k);
                    break;
                }
                _ => {}
            }
        }
        let Some(open) = open else { continue };
        let mut level = 0;
        let mut close = None;
        for (k, &ch) in bytes.iter().enumerate().skip(open) {
            match ch {
                b'{' => level += 1,
                b'}' => {
                    level -= 1;
                    if level == 0 {
                        close = Some(k);
                        break;
                    }
                }
                _ => {}
            }
        }
        let Some(close) = close else { continue };
        let first = line_of(start);
        out.push((name, first, line_of(close) - first + 1));
    }
    out
}

/// Files over 1,000 lines today, each with the issue item whose work brings it under.
const LONG_FILES: &[(&str, &str)] = &[];

/// Functions over 120 lines today, by file and name, each with the issue item whose
/// work splits it.
const LONG_FUNCTIONS: &[(&str, &str, &str)] = &[];

/// Circles between top-level modules today, each with the issue item whose work
/// breaks it. None is left: the options `Model::check_with` reads live in the leaf
/// `write_options` (`model_names_the_writer_for_no_options`), the source a model
/// keeps in `model::source`, the scenes in `xml::scene`.
const MODULE_CIRCLES: &[&[&str]] = &[];

#[test]
fn no_file_is_over_1000_lines() {
    let mut found = Vec::new();
    for (path, text) in sources() {
        let path = path.display().to_string();
        let n = text.lines().count();
        if n > 1000 && !LONG_FILES.iter().any(|(p, _)| *p == path) {
            found.push(format!("{path}: {n} lines"));
        }
    }
    assert!(found.is_empty(), "split by concept:\n{}", found.join("\n"));
}

#[test]
fn no_function_is_over_120_lines() {
    let mut found = Vec::new();
    for (path, text) in sources() {
        let path = path.display().to_string();
        for (name, line, n) in functions(&code_only(&text)) {
            let exempt = LONG_FUNCTIONS.iter().any(|(p, f, _)| *p == path && *f == name);
            if n > 120 && !exempt {
                found.push(format!("{path}:{line}: fn {name}: {n} lines"));
            }
        }
    }
    assert!(found.is_empty(), "split by concept:\n{}", found.join("\n"));
}

#[test]
fn the_exemptions_are_still_needed() {
    let texts: BTreeMap<String, String> =
        sources().into_iter().map(|(p, t)| (p.display().to_string(), t)).collect();
    for (path, why) in LONG_FILES {
        let n = texts.get(*path).map_or(0, |t| t.lines().count());
        assert!(n > 1000, "{path} ({why}) has {n} lines: remove it from LONG_FILES");
    }
    for (path, why) in XML_PARSED_OUTSIDE_THE_READER {
        let parses = texts.get(*path).is_some_and(|t| parses_xml(t));
        assert!(
            parses,
            "{path} ({why}) parses no XML: remove it from XML_PARSED_OUTSIDE_THE_READER"
        );
    }
    let found = circles(&top_level(&import_graph()));
    for c in MODULE_CIRCLES {
        assert!(
            found.iter().any(|f| f.iter().map(String::as_str).eq(c.iter().copied())),
            "{c:?} is no circle now: remove it from MODULE_CIRCLES"
        );
    }
    for (path, name, why) in LONG_FUNCTIONS {
        let fns = texts.get(*path).map(|t| functions(&code_only(t))).unwrap_or_default();
        let n = fns.iter().filter(|(f, _, _)| f == name).map(|(_, _, n)| *n).max().unwrap_or(0);
        assert!(n > 120, "{path}: fn {name} ({why}) has {n} lines: remove it");
    }
}

#[test]
fn the_source_scans_see_code_only() {
    let code = code_only(
        "fn a() { let s = \"}{\"; let c = '{'; // }\n /* { */ let r = r#\"}\"#; }\nfn b<'a>(x: &'a str) -> u8 {\n 1\n}\nfn decl();",
    );
    let fns = functions(&code);
    assert_eq!(fns, [("a".to_string(), 1, 2), ("b".to_string(), 3, 3)]);
}

/// The module path of a source file: `src/model/check.rs` is `model::check`,
/// `src/model/mod.rs` is `model`, `src/lib.rs` is the crate (``).
fn module_of(path: &str) -> String {
    let p = path.trim_start_matches("src/").trim_end_matches(".rs");
    let p = p.trim_end_matches("/mod").trim_end_matches("lib");
    p.trim_end_matches('/').replace('/', "::")
}

/// The paths `use` trees name: `a::{b, c::{d, e}}` is `a::b`, `a::c::d`, `a::c::e`.
fn expand_use(tree: &str) -> Vec<String> {
    let tree: String = tree.split_whitespace().collect();
    let Some(open) = tree.find('{') else { return vec![tree] };
    let prefix = &tree[..open];
    let inner = &tree[open + 1..tree.rfind('}').unwrap_or(tree.len())];
    let mut parts = Vec::new();
    let (mut depth, mut start) = (0, 0);
    for (i, c) in inner.char_indices() {
        match c {
            '{' => depth += 1,
            '}' => depth -= 1,
            ',' if depth == 0 => {
                parts.push(&inner[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    parts.push(&inner[start..]);
    parts
        .into_iter()
        .filter(|p| !p.is_empty())
        .flat_map(|p| expand_use(p).into_iter().map(move |q| format!("{prefix}{q}")))
        .collect()
}

/// The paths a file's code names from the crate: `use crate::…`/`use super::…`
/// trees, expanded, and `crate::…`/`super::…` paths in code, each as the segments
/// after `crate` (`super` resolved against `module`).
fn crate_paths(module: &str, is_mod_rs: bool, code: &str) -> Vec<Vec<String>> {
    let mut raw: Vec<String> = Vec::new();
    let mut rest = code;
    while let Some(i) = rest.find("use ") {
        let before = rest[..i].chars().next_back();
        rest = &rest[i + 4..];
        if ident_char(before) {
            continue;
        }
        let end = rest.find(';').unwrap_or(rest.len());
        let tree = &rest[..end];
        if tree.trim_start().starts_with("crate::") || tree.trim_start().starts_with("super::") {
            raw.extend(expand_use(tree));
        }
    }
    // Paths in code (`crate::model::settings::merged(…)`, `super::check::joint_type`).
    for start in ["crate::", "super::"] {
        let mut at = 0;
        while let Some(i) = code[at..].find(start) {
            let pos = at + i;
            at = pos + start.len();
            if ident_char(code[..pos].chars().next_back()) || code[..pos].ends_with("::") {
                continue;
            }
            let path: String =
                code[pos..].chars().take_while(|c| ident_char(Some(*c)) || *c == ':').collect();
            raw.push(path);
        }
    }
    let here: Vec<String> =
        module.split("::").filter(|s| !s.is_empty()).map(str::to_string).collect();
    raw.into_iter()
        .filter_map(|p| {
            let mut segs: Vec<&str> = p.split("::").filter(|s| !s.is_empty()).collect();
            let mut base: Vec<String> = if segs.first() == Some(&"crate") {
                segs.remove(0);
                Vec::new()
            } else {
                // `super` of a file module is its parent; of a `mod.rs`, the parent's.
                let mut b = here.clone();
                if !is_mod_rs && b.is_empty() {
                    return None;
                }
                let _ = is_mod_rs;
                while segs.first() == Some(&"super") {
                    segs.remove(0);
                    b.pop()?;
                }
                b
            };
            base.extend(segs.iter().map(|s| s.to_string()));
            Some(base)
        })
        .collect()
}

/// The import graph of `src/`: per file module, the file modules it names (the
/// longest module prefix of each path), itself left out.
fn import_graph() -> BTreeMap<String, BTreeSet<String>> {
    let files: Vec<(String, String)> =
        sources().into_iter().map(|(p, t)| (p.display().to_string(), t)).collect();
    let modules: BTreeSet<String> = files.iter().map(|(p, _)| module_of(p)).collect();
    let longest = |segs: &[String]| {
        (0..=segs.len()).rev().map(|n| segs[..n].join("::")).find(|m| modules.contains(m))
    };
    // What the crate root re-exports (`pub use crate::model::{Model, …}`): a path
    // `crate::Model` names the module the item comes from, not the root.
    let mut reexports: BTreeMap<String, String> = BTreeMap::new();
    let lib = files.iter().find(|(p, _)| p == "src/lib.rs").map(|(_, t)| code_only(t));
    for segs in crate_paths("", true, lib.as_deref().unwrap_or("")) {
        if let (Some(name), Some(m)) = (segs.last(), longest(&segs)) {
            if !m.is_empty() {
                reexports.insert(name.clone(), m);
            }
        }
    }
    let mut graph = BTreeMap::new();
    for (path, text) in &files {
        let module = module_of(path);
        if module.is_empty() {
            // The crate root declares the modules and re-exports their items.
            continue;
        }
        let mut to = BTreeSet::new();
        // Test modules (`#[cfg(test)] mod tests` in the file, or a tests.rs) are left
        // out: they are not part of the library's structure.
        let code = code_only(text);
        let code = match code.find("#[cfg(test)]\nmod ") {
            Some(i) => &code[..i],
            None => &code[..],
        };
        if path.ends_with("/tests.rs") {
            continue;
        }
        for segs in crate_paths(&module, path.ends_with("mod.rs"), code) {
            let mut target = longest(&segs).unwrap_or_default();
            if target.is_empty() {
                match segs.first().and_then(|n| reexports.get(n)) {
                    Some(m) => target = m.clone(),
                    None => continue,
                }
            }
            if target != module {
                to.insert(target);
            }
        }
        graph.insert(module, to);
    }
    graph
}

/// The circles of a graph: one cycle per strongly connected component of more than
/// one node, as a path.
fn circles(graph: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    let reach = |from: &str| {
        let mut seen = BTreeSet::new();
        let mut todo = vec![from.to_string()];
        while let Some(n) = todo.pop() {
            for m in graph.get(&n).into_iter().flatten() {
                if seen.insert(m.clone()) {
                    todo.push(m.clone());
                }
            }
        }
        seen
    };
    let mut done = BTreeSet::new();
    let mut out = Vec::new();
    for n in graph.keys() {
        if done.contains(n) || !reach(n).contains(n) {
            continue;
        }
        let component: Vec<String> = graph
            .keys()
            .filter(|m| reach(n).contains(*m) && reach(m).contains(n))
            .cloned()
            .collect();
        done.extend(component.iter().cloned());
        out.push(component);
    }
    out
}

/// The graph of the top-level modules (`model`, `xml`, `value`, ...).
fn top_level(graph: &BTreeMap<String, BTreeSet<String>>) -> BTreeMap<String, BTreeSet<String>> {
    let top = |m: &str| m.split("::").next().unwrap_or("").to_string();
    let mut out: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (from, to) in graph {
        let entry = out.entry(top(from)).or_default();
        entry.extend(to.iter().map(|t| top(t)).filter(|t| *t != top(from)));
    }
    out
}

#[test]
fn no_import_circle_between_files() {
    let graph = import_graph();
    assert!(graph.get("model::check").is_some_and(|t| t.contains("model::cursor")), "{graph:?}");
    let found = circles(&graph);
    assert!(found.is_empty(), "import circles between files: {found:?}");
}

/// `model` reads the write options (`Model::check_with`, the composed keyframes)
/// from the leaf module `write_options`, which names nothing of the crate: no file of
/// `model` names anything of `xml` but `xml::Source`, the lossless save's (issue 23),
/// which goes with it.
#[test]
fn model_names_the_writer_for_no_options() {
    let graph = import_graph();
    assert_eq!(graph.get("write_options"), Some(&BTreeSet::new()), "{graph:?}");
    assert!(graph["model::check"].contains("write_options"), "{graph:?}");
    let mut to_xml = Vec::new();
    for (path, text) in sources() {
        let path = path.display().to_string();
        let module = module_of(&path);
        if module.split("::").next() != Some("model") || path.ends_with("/tests.rs") {
            continue;
        }
        for segs in crate_paths(&module, path.ends_with("mod.rs"), &code_only(&text)) {
            if segs.first().is_some_and(|s| s == "xml") {
                to_xml.push(format!("{path}: {}", segs.join("::")));
            }
        }
    }
    assert!(to_xml.is_empty(), "model names xml: {to_xml:?}");
}

#[test]
fn no_import_circle_between_top_level_modules() {
    let found: Vec<Vec<String>> = circles(&top_level(&import_graph()))
        .into_iter()
        .filter(|c| {
            !MODULE_CIRCLES.contains(&c.iter().map(String::as_str).collect::<Vec<_>>().as_slice())
        })
        .collect();
    assert!(found.is_empty(), "import circles between modules: {found:?}");
}

#[test]
fn the_import_scan_reads_use_trees_and_paths() {
    assert_eq!(
        expand_use("crate::model::{check::Problem, Loc, tree::{Attr, Node}}"),
        [
            "crate::model::check::Problem",
            "crate::model::Loc",
            "crate::model::tree::Attr",
            "crate::model::tree::Node"
        ]
    );
    let code = "use super::tree::Node;\nuse crate::value::{Value, number};\nfn f() { crate::schema::x(); super::super::error::E }";
    let paths: BTreeSet<String> =
        crate_paths("model::check", false, code).into_iter().map(|p| p.join("::")).collect();
    let expected =
        ["model::tree::Node", "value", "value::Value", "value::number", "schema::x", "error::E"];
    assert_eq!(paths, expected.iter().map(|p| p.to_string()).collect());
    let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    g.insert("a".into(), ["b".to_string()].into());
    g.insert("b".into(), ["c".to_string()].into());
    g.insert("c".into(), ["a".to_string()].into());
    g.insert("d".into(), ["a".to_string()].into());
    assert_eq!(circles(&g), [["a", "b", "c"]]);
}

/// Reading reopens scenes as a step after reading (`xml::open`): the reader imports
/// nothing of scenes; `xml::scene` names the asset model files it needs and builds
/// the composed model from the models opened for it; it never calls the reader (no
/// callback, no `Model::from_…` of its own).
#[test]
fn the_reader_and_scenes_know_nothing_of_each_other() {
    let graph = import_graph();
    for (module, to) in graph.iter().filter(|(m, _)| m.starts_with("xml::read")) {
        let scenes: Vec<&String> = to.iter().filter(|t| t.starts_with("xml::scene")).collect();
        assert!(scenes.is_empty(), "{module} names scenes: {scenes:?}");
    }
    let scene: Vec<(&String, &BTreeSet<String>)> =
        graph.iter().filter(|(m, _)| m.starts_with("xml::scene")).collect();
    assert!(!scene.is_empty(), "{graph:?}");
    for (module, to) in scene {
        let reader: Vec<&String> = to.iter().filter(|t| t.starts_with("xml::read")).collect();
        assert!(reader.is_empty(), "{module} names the reader: {reader:?}");
    }
    assert!(graph["xml::open"].contains("xml::scene::reopen"), "{graph:?}");
    for (path, text) in sources() {
        let path = path.display().to_string();
        if path.starts_with("src/xml/scene/") && !path.ends_with("/tests.rs") {
            let code = code_only(&text);
            // (A callback that reads would return `ReadError`.)
            for call in ["from_xml_str", "from_path", "ReadOptions", "read_str", "ReadError"] {
                assert!(!code.contains(call), "{path} reads a model ({call})");
            }
        }
    }
}

/// The crate's layers, lowest first: a module names only modules of its own layer or
/// below. Foundations (ids, the schema, persistent sequences, suggestions, errors,
/// the write options); values; the file layer (a model holds the context its files
/// resolve in, so files sit below the model); the model (and its history); reading,
/// writing and composing; the generators.
const LAYERS: &[&[&str]] = &[
    &["id", "schema", "seq", "suggest", "error", "write_options"],
    &["value"],
    &["files"],
    &["model", "history"],
    &["xml", "compose"],
    &["generate"],
];

#[test]
fn modules_name_only_their_own_layer_and_those_below() {
    let graph = top_level(&import_graph());
    let layer = |m: &str| LAYERS.iter().position(|l| l.contains(&m));
    let mut wrong = Vec::new();
    for (module, to) in &graph {
        let Some(own) = layer(module) else {
            wrong.push(format!("{module} is in no layer: add it to LAYERS"));
            continue;
        };
        for t in to {
            match layer(t) {
                Some(l) if l <= own => {}
                _ => wrong.push(format!("{module} (layer {own}) names {t}")),
            }
        }
    }
    assert!(graph.len() >= 12, "{graph:?}");
    assert!(wrong.is_empty(), "{}", wrong.join("\n"));
}

/// The root's sections are named by their constants (`ElementKind::COMPILER`), never
/// looked up by a tag written in the library's code (`ROOT.child("compiler")`).
#[test]
fn sections_are_named_by_their_constants() {
    let mut found = Vec::new();
    for (path, text) in sources() {
        let path = path.display().to_string();
        if path.ends_with("/tests.rs") {
            continue;
        }
        let code = code_only(&text);
        for (n, line) in code.lines().enumerate() {
            if line.contains("ROOT.child(\"") {
                found.push(format!("{path}:{}: {}", n + 1, line.trim()));
            }
        }
    }
    assert!(found.is_empty(), "name the section by its constant:\n{}", found.join("\n"));
}

/// One folder-module style: a module with submodules is a folder holding `mod.rs`,
/// never a file `foo.rs` beside a folder `foo/`.
#[test]
fn modules_with_submodules_are_folders_with_mod_rs() {
    let mut mixed = Vec::new();
    let mut dirs = vec![Path::new(env!("CARGO_MANIFEST_DIR")).join("src")];
    while let Some(dir) = dirs.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                if path.with_extension("rs").is_file() {
                    mixed.push(path.display().to_string());
                }
                dirs.push(path);
            }
        }
    }
    assert!(mixed.is_empty(), "move foo.rs into foo/mod.rs: {mixed:?}");
}

/// The joint types' keywords, as string literals.
const JOINT_TYPE_WORDS: &[&str] = &["\"free\"", "\"ball\"", "\"slide\"", "\"hinge\""];

/// The lines of `text`'s code (comment lines and the test module at its end left
/// out) holding a joint type's keyword as a string literal, but for an XML
/// attribute's value (`type="ball"` written into a model).
fn joint_type_words(text: &str) -> Vec<(usize, String)> {
    let code = ["#[cfg(test)]", "#[cfg(all(test"]
        .iter()
        .filter_map(|m| text.find(m))
        .min()
        .map_or(text, |at| &text[..at]);
    let mut out = Vec::new();
    for (n, line) in code.lines().enumerate() {
        if line.trim_start().starts_with("//") {
            continue;
        }
        let found = JOINT_TYPE_WORDS
            .iter()
            .any(|w| line.match_indices(w).any(|(at, _)| !line[..at].ends_with('=')));
        if found {
            out.push((n + 1, line.trim().to_string()));
        }
    }
    out
}

/// A joint's type (its own `type`, its classes', a `<freejoint>`'s) and what follows
/// from it (`qpos` and `qvel` widths) are `JointType`'s, in `model/layout.rs`: no
/// other library file reads a joint type from its keyword. Test modules may.
#[test]
fn joint_types_are_read_in_the_layout_only() {
    let mut found = Vec::new();
    for (path, text) in sources() {
        let path = path.display().to_string();
        if path == "src/model/layout.rs"
            || path.ends_with("/tests.rs")
            || path.ends_with("_tests.rs")
        {
            continue;
        }
        for (n, line) in joint_type_words(&text) {
            found.push(format!("{path}:{n}: {line}"));
        }
    }
    assert!(
        found.is_empty(),
        "read the type with JointType (model::layout):\n{}",
        found.join("\n")
    );
    let forms = [
        "if e.string(\"type\") == Some(\"ball\") {",
        "match t {\n    \"free\" => 7,\n    _ => 1,\n}",
        "let s = matches!(ty, None | Some(\"hinge\" | \"slide\"));",
    ];
    for f in forms {
        assert_eq!(joint_type_words(f).len(), 1, "{f}");
    }
    let fine = [
        "/// a `\"ball\"` joint",
        "let xml = r#\"<joint type=\"ball\"/>\"#;",
        "#[cfg(test)]\nmod tests { const T: &str = \"free\"; }",
    ];
    for f in fine {
        assert!(joint_type_words(f).is_empty(), "{f}");
    }
}
