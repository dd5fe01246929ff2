//! Figures and names the documentation states that something else in the repository
//! decides: each test reads both places and fails when one changes alone.
//!
//! - the README's `[dependencies]` line and Rust version are the manifest's;
//! - the real-model floor of `tests/conformance/README.md` is `.ci/run`'s
//!   `realmodels_floor`, and the manual's lossless floor `.ci/run`'s;
//! - the conformance summary of `tests/conformance/README.md` counts every case;
//! - every `deviation` label a conformance case uses is explained in
//!   `tests/conformance/README.md` and is a heading of `src/decisions.md`;
//! - the README is what a newcomer reads to the end: at most 200 non-blank lines;
//! - no comment or document cites a line of code by number (a file name, a colon and
//!   the number, or a `#L` anchor), which goes stale as soon as the code above moves;
//! - the README's quickstart is `examples/quickstart.rs`, and its line counts of the
//!   three user programs are what `rustfmt` with its default settings gives;
//! - every link to a section of the manual (`crate::guide#names`, `#scenes`,
//!   `src/guide.md#versioning`) names a heading of that page, which neither rustdoc
//!   nor GitHub checks;
//! - each rule of the manual is stated once, in its authority (`RULES`), and only
//!   summarized and linked elsewhere.

use std::path::{Path, PathBuf};

fn root() -> &'static Path {
    Path::new(env!("CARGO_MANIFEST_DIR"))
}

fn read(relative: &str) -> String {
    let path = root().join(relative);
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The decimal number that follows the only occurrence of `prefix` in `text`.
fn number_after(text: &str, prefix: &str, what: &str) -> u64 {
    let mut found = text.match_indices(prefix);
    let (at, _) = found.next().unwrap_or_else(|| panic!("{what}: no `{prefix}` found"));
    assert!(found.next().is_none(), "{what}: `{prefix}` occurs more than once");
    let digits: String =
        text[at + prefix.len()..].chars().take_while(|c| c.is_ascii_digit()).collect();
    digits.parse().unwrap_or_else(|_| panic!("{what}: no number after `{prefix}`"))
}

#[test]
fn number_after_reads_the_number_after_its_prefix() {
    assert_eq!(number_after("a floor=179\nb", "floor=", "t"), 179);
    assert_eq!(number_after("fewer than 12 pass", "fewer than ", "t"), 12);
}

#[test]
#[should_panic(expected = "no number after")]
fn number_after_refuses_a_prefix_without_a_number() {
    number_after("floor=x", "floor=", "t");
}

#[test]
#[should_panic(expected = "occurs more than once")]
fn number_after_refuses_an_ambiguous_prefix() {
    number_after("floor=1 floor=2", "floor=", "t");
}

/// The quoted value of `key = "..."` in the only line of `text` that starts with it.
fn quoted_value<'a>(text: &'a str, key: &str, what: &str) -> &'a str {
    let prefix = format!("{key} = \"");
    let mut lines = text.lines().filter(|l| l.starts_with(&prefix));
    let line = lines.next().unwrap_or_else(|| panic!("{what}: no `{key} = \"...\"` line"));
    assert!(lines.next().is_none(), "{what}: more than one `{key} = ` line");
    line[prefix.len()..].split('"').next().unwrap()
}

/// `mjcf = "0.1"` for version 0.1.x, `"1"` for 1.x.y: the requirement that takes every
/// compatible release.
fn caret_requirement(version: &str) -> String {
    let parts: Vec<&str> = version.split('.').collect();
    match parts.as_slice() {
        ["0", minor, ..] => format!("0.{minor}"),
        [major, ..] => (*major).to_string(),
        [] => unreachable!("split gives at least one part"),
    }
}

#[test]
fn caret_requirement_keeps_the_version_that_breaks() {
    assert_eq!(caret_requirement("0.1.0"), "0.1");
    assert_eq!(caret_requirement("0.12.3"), "0.12");
    assert_eq!(caret_requirement("1.4.2"), "1");
}

/// The README's "Use it" section: the dependency line takes the manifest's version,
/// and the Rust version it names is the workspace's `rust-version`.
#[test]
fn readme_dependency_line_and_rust_version_are_the_manifests() {
    let manifest = read("Cargo.toml");
    let readme = read("README.md");
    let version = quoted_value(&manifest, "version", "Cargo.toml");
    let line = format!("\nmjcf = \"{}\"\n", caret_requirement(version));
    assert!(readme.contains(&line), "the README has no `{}` line", line.trim());
    let rust_version = quoted_value(&manifest, "rust-version", "Cargo.toml");
    let stated = format!("Rust {rust_version} or newer");
    assert!(readme.contains(&stated), "the README does not say `{stated}`");
}

/// The conformance README's "Real models" section: the floor it states, and the
/// pass count of its sample run, which is at least that floor.
#[test]
fn real_model_floor_is_the_ci_floor() {
    let ci = number_after(&read(".ci/run"), "\nrealmodels_floor=", ".ci/run");
    let doc = read("tests/conformance/README.md");
    let at = "tests/conformance/README.md, Real models";
    let stated = number_after(&doc, "fails if fewer than ", at);
    assert_eq!(stated, ci, "{at} states a real-model floor of {stated}, .ci/run's is {ci}");
    let sample = number_after(&doc, "../shared/realmodels/cases\n# ", at);
    assert!(sample >= ci, "{at}: the sample run passes {sample}, below the floor {ci}");
}

/// The manual's lossless-save section: the floor it states is `.ci/run`'s.
#[test]
fn lossless_floor_is_the_ci_floor() {
    let ci = number_after(&read(".ci/run"), "\n  lossless_floor=", ".ci/run");
    let stated = number_after(&read("src/guide.md"), "requires all ", "src/guide.md, saving");
    assert_eq!(stated, ci, "the manual states a lossless floor of {stated}, .ci/run's is {ci}");
}

fn case_dirs() -> Vec<PathBuf> {
    let cases = root().join("tests/conformance/cases");
    let mut dirs: Vec<PathBuf> = std::fs::read_dir(&cases)
        .unwrap_or_else(|e| panic!("{}: {e}", cases.display()))
        .map(|e| e.unwrap().path())
        .filter(|p| p.join("case.json").is_file())
        .collect();
    dirs.sort();
    dirs
}

/// `# P passed, 0 failed, K deviations` under the conformance README's runner
/// command: every case passes, and P + K is the number of cases.
#[test]
fn conformance_summary_counts_every_case() {
    let readme = read("tests/conformance/README.md");
    let prefix = "--example conformance -- tests/conformance/cases\n# ";
    let passed = number_after(&readme, prefix, "README.md, Conformance");
    let rest = &readme[readme.find(prefix).unwrap() + prefix.len()..];
    let line = rest.lines().next().unwrap();
    let failed = number_after(line, "passed, ", "README.md, Conformance");
    let deviations = number_after(line, "failed, ", "README.md, Conformance");
    assert!(line.ends_with(" deviations"), "README.md, Conformance: {line}");
    assert_eq!(failed, 0, "README.md, Conformance: {line}");
    let cases = case_dirs().len() as u64;
    assert_eq!(passed + deviations, cases, "README.md says `{line}`, the corpus has {cases} cases");
}

/// The deviation labels the cases use (`"deviation": "D2,D3"` on an op).
fn case_deviation_labels() -> std::collections::BTreeSet<String> {
    let mut labels = std::collections::BTreeSet::new();
    for dir in case_dirs() {
        let text = std::fs::read_to_string(dir.join("case.json")).unwrap();
        let case: serde_json::Value = serde_json::from_str(&text).unwrap();
        for op in case["ops"].as_array().unwrap() {
            if let Some(d) = op.get("deviation").and_then(|d| d.as_str()) {
                labels.extend(
                    d.split(',').map(str::trim).filter(|l| !l.is_empty()).map(String::from),
                );
            }
        }
    }
    labels
}

#[test]
fn every_deviation_label_of_the_cases_is_documented() {
    let labels = case_deviation_labels();
    assert!(labels.contains("D1") && labels.contains("D3"), "labels found: {labels:?}");
    let format = read("tests/conformance/README.md");
    let decisions = read("src/decisions.md");
    for label in &labels {
        assert!(
            format.contains(&format!("\n* `{label}` (")),
            "tests/conformance/README.md does not say how ops marked {label} are replayed"
        );
        assert!(
            decisions.contains(&format!("\n# {label}: ")),
            "src/decisions.md has no heading {label}"
        );
    }
}

/// Where `text` cites a line of a file: a `.rs`, `.py`, `.sh`, `.toml` or `.md` file
/// name followed by a colon and a number, or a link anchor `#L` with a number; one
/// `file: line` entry per citation.
fn line_citations(file: &str, text: &str) -> Vec<String> {
    let mut found = Vec::new();
    for line in text.lines() {
        for ext in [".rs:", ".py:", ".sh:", ".toml:", ".md:", "#L"] {
            for (at, _) in line.match_indices(ext) {
                let after = &line[at + ext.len()..];
                let stem_before = line[..at].chars().next_back().is_some_and(|c| {
                    c.is_ascii_alphanumeric() || c == '_' || c == '-' || c == '/' || c == ')'
                });
                if stem_before && after.starts_with(|c: char| c.is_ascii_digit()) {
                    found.push(format!("{file}: {}", line.trim()));
                }
            }
        }
    }
    found
}

#[test]
fn line_citations_finds_file_line_references_only() {
    // Split so that this file cites nothing itself.
    let citing = concat!(
        "// see src/model/mod.rs",
        ":535 and index.rs",
        ":49-57, write.py",
        ":3, blob#L",
        "10"
    );
    assert_eq!(line_citations("f", citing).len(), 4);
    let plain = "// at 3:5 in line 3; a `.rs:` suffix; Cargo.toml: [lib]; #Loc";
    assert_eq!(line_citations("f", plain), Vec::<String>::new());
}

fn text_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().path())
        .collect();
    entries.sort();
    for path in entries {
        let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
        if path.is_dir() {
            // Build output and data: the conformance cases and the fuzz corpora and
            // findings.
            if !matches!(name, "target" | ".git" | "cases" | "corpus" | "artifacts") {
                text_files(&path, out);
            }
        } else if ["rs", "py", "sh", "md", "toml"]
            .iter()
            .any(|x| path.extension().is_some_and(|e| e == *x))
            || matches!(name, "run" | "mujoco_check")
        {
            out.push(path);
        }
    }
}

#[test]
fn no_comment_or_document_cites_a_line_of_code() {
    let mut files = Vec::new();
    text_files(root(), &mut files);
    for expected in ["src/lib.rs", "tests/docs.rs", ".ci/run", "README.md", "benches/NOTES.md"] {
        assert!(files.contains(&root().join(expected)), "{expected} is not scanned");
    }
    let mut citations = Vec::new();
    for path in &files {
        let relative = path.strip_prefix(root()).unwrap().display().to_string();
        let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{relative}: {e}"));
        citations.extend(line_citations(&relative, &text));
    }
    assert!(citations.is_empty(), "lines of code cited by number:\n{}", citations.join("\n"));
}

/// Non-blank lines of `file` once formatted by `rustfmt` with its default settings, as
/// a user's code is (not the repository's `use_small_heuristics = "Max"`), on a copy.
fn default_rustfmt_lines(file: &str) -> usize {
    let name = format!("mjcf-docs-{}-{}", std::process::id(), file.replace('/', "_"));
    let copy = std::env::temp_dir().join(name);
    std::fs::write(&copy, read(file)).unwrap();
    let status = std::process::Command::new("rustfmt")
        .args(["--edition", "2024", "--config", "use_small_heuristics=Default"])
        .arg(&copy)
        .status()
        .unwrap_or_else(|e| panic!("rustfmt could not run (it ships with rustup): {e}"));
    assert!(status.success(), "rustfmt failed on a copy of {file}");
    let text = std::fs::read_to_string(&copy).unwrap();
    std::fs::remove_file(&copy).unwrap();
    text.lines().filter(|l| !l.trim().is_empty()).count()
}

#[test]
fn readme_quickstart_is_the_example() {
    let block = format!("```rust\n{}```\n", read("examples/quickstart.rs"));
    assert!(read("README.md").contains(&block), "the README's quickstart differs from the example");
}

#[test]
fn readme_line_counts_are_default_rustfmt_counts() {
    let readme = read("README.md");
    for (name, file) in [
        ("seed (`quickstart.rs`)", "examples/quickstart.rs"),
        ("editor (`editor.rs`)", "examples/editor.rs"),
        ("compose (`compose.rs`)", "examples/compose.rs"),
    ] {
        let row = format!("| {name} | ");
        let python = number_after(&readme, &row, name);
        let rust = number_after(&readme, &format!("{row}{python} | "), name);
        assert_eq!(rust as usize, default_rustfmt_lines(file), "{file}: the README's count");
    }
    let quick = default_rustfmt_lines("examples/quickstart.rs");
    let stated = format!("({quick} non-blank lines after\n`rustfmt` with its default settings");
    assert!(readme.contains(&stated), "the README's seed count is not {quick}");
}

/// The headings of `src/decisions.md` (`D10`), each with its section's text.
fn decisions() -> Vec<(String, String)> {
    let text = read("src/decisions.md");
    let mut out: Vec<(String, String)> = Vec::new();
    for line in text.lines() {
        if let Some(rest) = line.strip_prefix("# D") {
            let number: String = rest.chars().take_while(char::is_ascii_digit).collect();
            out.push((format!("D{number}"), String::new()));
        } else if let Some((_, body)) = out.last_mut() {
            body.push_str(line);
            body.push('\n');
        }
    }
    out
}

/// Every `decision D<n>` (or `decisions D<n>`) a comment or document cites is a heading
/// of `src/decisions.md`, and every deviation label of the conformance cases is one; no
/// file cites design notes that are not in the repository.
#[test]
fn every_decision_cited_is_a_heading_of_the_decisions_document() {
    let headings: Vec<String> = decisions().into_iter().map(|(d, _)| d).collect();
    assert!(headings.len() >= 15, "{headings:?}");
    let mut files = Vec::new();
    text_files(root(), &mut files);
    let mut cited = 0;
    // Split so that this file names none of them itself.
    let foreign =
        [concat!("DESIGN", ".md"), concat!("DESIGN", " D"), concat!("dm_control_mjcf", ".md")];
    for path in &files {
        let relative = path.strip_prefix(root()).unwrap().display().to_string();
        let text = std::fs::read_to_string(path).unwrap();
        for f in foreign {
            assert!(!text.contains(f), "{relative} cites {f}, which is not in the repository");
        }
        for word in ["decision D", "decisions D"] {
            for (at, _) in text.match_indices(word) {
                let number: String =
                    text[at + word.len()..].chars().take_while(char::is_ascii_digit).collect();
                if number.is_empty() {
                    continue; // `decision D<n>`, the form itself
                }
                let label = format!("D{number}");
                assert!(
                    headings.contains(&label),
                    "{relative} cites {word}{number}, not a heading"
                );
                cited += 1;
            }
        }
    }
    assert!(cited >= 20, "{cited} citations found");
    for label in case_deviation_labels() {
        for one in label.split(',') {
            assert!(headings.iter().any(|h| h == one.trim()), "deviation {one} is not a decision");
        }
    }
}

/// Each decision names its tests (`` `tests/file.rs` `test_name` ``): every test named
/// is a function of the file named before it.
#[test]
fn every_test_a_decision_names_exists() {
    let mut named = 0;
    for (label, body) in decisions() {
        let tests = body.split("Tests:").nth(1).unwrap_or_else(|| panic!("{label} names no tests"));
        let mut file: Option<String> = None;
        for quoted in tests.split('`').skip(1).step_by(2) {
            if quoted.ends_with(".rs") || quoted.ends_with('/') || quoted.starts_with(".ci/") {
                let path = root().join(quoted);
                assert!(path.exists(), "{label}: {quoted} does not exist");
                file = quoted.ends_with(".rs").then(|| read(quoted));
            } else if quoted
                .chars()
                .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
                && quoted.contains('_')
            {
                let text = file
                    .as_deref()
                    .unwrap_or_else(|| panic!("{label}: `{quoted}` follows no file"));
                assert!(text.contains(&format!("fn {quoted}(")), "{label}: no test `{quoted}`");
                named += 1;
            }
        }
    }
    assert!(named >= 15, "{named} tests named");
}

/// The README is the overview a newcomer reads to the end (the manual is the crate's
/// docs, `src/guide.md`): at most 200 non-blank lines, and every file it links exists
/// (the sections it links are checked with every other link to a section).
#[test]
fn the_readme_is_short_and_its_links_resolve() {
    let readme = read("README.md");
    let lines = readme.lines().filter(|l| !l.trim().is_empty()).count();
    assert!(lines <= 200, "the README has {lines} non-blank lines");
    for (at, _) in readme.match_indices("](") {
        let link: String = readme[at + 2..].chars().take_while(|c| *c != ')').collect();
        let target = link.split('#').next().unwrap_or_default();
        if target.starts_with("http") || target.is_empty() {
            continue;
        }
        assert!(root().join(target).exists(), "the README links {target}, which does not exist");
    }
}

/// The anchor rustdoc and GitHub give a Markdown heading: lower case, spaces as `-`,
/// every other character but letters, digits, `-` and `_` left out
/// (`D13: a `/` in a name` is `d13-a--in-a-name`).
fn heading_anchor(heading: &str) -> String {
    heading
        .trim()
        .chars()
        .filter_map(|c| match c {
            c if c.is_alphanumeric() || c == '-' || c == '_' => Some(c.to_ascii_lowercase()),
            c if c.is_whitespace() => Some('-'),
            _ => None,
        })
        .collect()
}

/// The anchors of the headings of a Markdown text, outside code blocks.
fn heading_anchors(text: &str) -> Vec<String> {
    let mut anchors = Vec::new();
    let mut in_code = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            in_code = !in_code;
        } else if !in_code && line.starts_with('#') {
            let title = line.trim_start_matches('#');
            if title.starts_with(' ') {
                anchors.push(heading_anchor(title));
            }
        }
    }
    anchors
}

#[test]
fn heading_anchor_is_rustdocs() {
    // As rustdoc renders this repository's headings (`target/doc/mjcf/decisions`).
    assert_eq!(heading_anchor(" Simulate (MuJoCo from Rust)"), "simulate-mujoco-from-rust");
    assert_eq!(
        heading_anchor(" D13: a `/` in a name read from MJCF is part of one literal name"),
        "d13-a--in-a-name-read-from-mjcf-is-part-of-one-literal-name"
    );
    assert_eq!(
        heading_anchor(" D12: MuJoCo 4.0's elements are read, edited and written"),
        "d12-mujoco-40s-elements-are-read-edited-and-written"
    );
    assert_eq!(heading_anchors("# A\n```sh\n# not a heading\n```\n## B c\n#no"), ["a", "b-c"]);
}

/// Every link `(target#anchor)` of `text`, read from `file`: the link's target
/// resolved to a Markdown file of the repository (a rustdoc path `crate::guide` or
/// `crate::decisions`, a path relative to `file`, or `file` itself for `#anchor`),
/// and the anchor. Links to other pages (`http`, an item's own page) are left out.
fn anchor_links(file: &str, text: &str) -> Vec<(String, String, String)> {
    let mut links = Vec::new();
    for (at, _) in text.match_indices("](") {
        let target: String = text[at + 2..].chars().take_while(|c| *c != ')').collect();
        let Some((page, anchor)) = target.split_once('#') else { continue };
        let doc = match page {
            "crate::guide" | "mjcf::guide" => "src/guide.md".to_string(),
            "crate::decisions" | "mjcf::decisions" => "src/decisions.md".to_string(),
            "" if file.ends_with(".md") => file.to_string(),
            p if p.ends_with(".md") && !p.starts_with("http") => {
                let base = Path::new(file).parent().unwrap_or(Path::new(""));
                let joined = base.join(p);
                let mut parts: Vec<&std::ffi::OsStr> = Vec::new();
                for c in joined.components() {
                    match c {
                        std::path::Component::ParentDir => {
                            parts.pop();
                        }
                        std::path::Component::CurDir => {}
                        c => parts.push(c.as_os_str()),
                    }
                }
                parts.iter().collect::<PathBuf>().display().to_string()
            }
            _ => continue,
        };
        links.push((doc, anchor.to_string(), target.clone()));
    }
    links
}

#[test]
fn anchor_links_resolve_rustdoc_and_relative_targets() {
    let text = "[a](crate::guide#names), [b](#scenes), [c](../../src/decisions.md#d1-x), \
                [d](crate::Model::attach), [e](https://x.org/a.md#y)";
    let links = anchor_links("tests/conformance/README.md", text);
    let docs: Vec<(&str, &str)> = links.iter().map(|(d, a, _)| (d.as_str(), a.as_str())).collect();
    assert_eq!(
        docs,
        [
            ("src/guide.md", "names"),
            ("tests/conformance/README.md", "scenes"),
            ("src/decisions.md", "d1-x")
        ]
    );
}

/// The files of the manual: the sources of the crate and of the binding (their doc
/// comments, the guide and the decisions) and the repository's Markdown pages.
fn manual_files() -> Vec<String> {
    let mut files = Vec::new();
    text_files(root(), &mut files);
    files
        .iter()
        .map(|p| p.strip_prefix(root()).unwrap().display().to_string())
        .filter(|f| {
            let source = f.starts_with("src/") || f.starts_with("mjcf-mujoco/src/");
            f.ends_with(".md") || (source && f.ends_with(".rs"))
        })
        .collect()
}

/// Every link to a section of the manual (`[Names](crate::guide#names)` in a doc
/// comment, `[D15](crate::decisions#d15-...)`, `[Scenes](#scenes)` in the guide,
/// `[versioning](src/guide.md#versioning)` in the README) names a heading of the
/// page it links: rustdoc checks the page of an intra-doc link but not its anchor, and
/// GitHub checks neither. The guide's and the decisions' headings are unique, so
/// rustdoc gives each the anchor written.
#[test]
fn every_link_to_a_section_names_a_heading() {
    for doc in ["src/guide.md", "src/decisions.md"] {
        let anchors = heading_anchors(&read(doc));
        let mut unique = anchors.clone();
        unique.sort();
        unique.dedup();
        assert_eq!(unique.len(), anchors.len(), "{doc} repeats a heading: {anchors:?}");
    }
    let mut checked = 0;
    let mut broken = Vec::new();
    for file in manual_files() {
        for (doc, anchor, target) in anchor_links(&file, &read(&file)) {
            let Ok(text) = std::fs::read_to_string(root().join(&doc)) else {
                broken.push(format!("{file}: ({target}): no file {doc}"));
                continue;
            };
            if !heading_anchors(&text).contains(&anchor) {
                broken.push(format!("{file}: ({target}): {doc} has no heading #{anchor}"));
            }
            checked += 1;
        }
    }
    assert!(broken.is_empty(), "links to no section:\n{}", broken.join("\n"));
    assert!(checked >= 20, "{checked} section links found");
}

/// The text of the manual in `file`, its lines joined by single spaces: a Markdown
/// page whole; of a source file, its doc comments (`///`, and the `//!` of the
/// public modules: the crate's, `generate`'s and the binding's; a private module's
/// documentation is for maintainers, not part of the manual).
fn manual_text(file: &str, text: &str) -> String {
    let public_module =
        matches!(file, "src/lib.rs" | "src/generate/mod.rs" | "mjcf-mujoco/src/lib.rs");
    let lines: Vec<&str> = if file.ends_with(".md") {
        text.lines().collect()
    } else {
        text.lines()
            .filter_map(|l| {
                let l = l.trim_start();
                l.strip_prefix("///").or_else(|| l.strip_prefix("//!").filter(|_| public_module))
            })
            .collect()
    };
    lines.join(" ").split_whitespace().collect::<Vec<_>>().join(" ")
}

#[test]
fn manual_text_keeps_doc_comments_of_public_modules_only() {
    let source = "//! module\n/// item\n///   docs\nfn f() {} // code";
    assert_eq!(manual_text("src/lib.rs", source), "module item docs");
    assert_eq!(manual_text("src/model/naming.rs", source), "item docs");
    assert_eq!(manual_text("README.md", "a\n  b"), "a b");
}

/// Each rule of the manual is stated in one place, its authority, and linked from
/// the others: a phrase that only a full statement of the rule holds, and where it is
/// stated. A second full statement (the rule written out again in the guide, the
/// README or a decision, instead of a summary and a link) repeats the phrase.
const RULES: [(&str, &str, &str); 24] = [
    // Attaching: Model::attach.
    ("attach frame pose", "for `fromto` its middle and direction", "src/compose/attach.rs"),
    ("attach frame as <frame>", "no `user` and no `mocap`", "src/compose/attach.rs"),
    (
        "scope suffix",
        "a literal name read from MJCF that starts with `name/`",
        "src/compose/attach.rs",
    ),
    ("angle conversion", "a limited hinge's or ball's `range`", "src/compose/attach.rs"),
    // Names: the guide's Names section.
    ("automatic names", "`P/unnamed_<namespace>_<i>`", "src/guide.md"),
    ("names made unique", "the generated one gives way", "src/guide.md"),
    ("root class names", "or as `/1` when attached models' root classes follow", "src/guide.md"),
    // The lossless save: Model::save.
    ("lossless: outside the root", "a byte-order mark, an XML declaration", "src/xml/save/disk.rs"),
    (
        "lossless: changed on disk",
        "A file changed on disk since it was read is not overwritten",
        "src/xml/save/disk.rs",
    ),
    ("lossless: attachments", "changes its name, prefix and pose in place", "src/xml/save/disk.rs"),
    // Scenes: the guide's Scenes section.
    ("scene reopen", "exactly when it has the saved shape", "src/guide.md"),
    ("scene compile", "MuJoCo 4.0.0 compiles the saved scene to what it compiles", "src/guide.md"),
    ("flat files", "changes the model silently", "src/guide.md"),
    // Copying: Model::include_copy.
    ("include_copy source", "A source with attachments is refused", "src/compose/include.rs"),
    // check(): Model::check.
    ("check judged", "finds a problem exactly when it refuses the model", "src/model/check/mod.rs"),
    ("check reach", "760 distinct messages", "src/model/check/mod.rs"),
    ("composition refused", "Composition never turns a model refused", "src/model/check/mod.rs"),
    ("composition remedies", "a user may attach first and fix after", "src/model/check/mod.rs"),
    // Simulating: the binding's crate documentation.
    ("MuJoCo's fatal errors", "through a small C guard", "mjcf-mujoco/src/lib.rs"),
    // Keys, costs, generators, guarantees, versioning.
    ("keys follow", "keeps every value with its element", "src/guide.md"),
    ("costs", "`levels`: the models on the way to that element", "src/lib.rs"),
    ("generators", "skips (or repairs) any step that would make it invalid", "src/generate/mod.rs"),
    ("guarantees", "No panic, no stack overflow, no hang.", "src/guide.md"),
    ("versioning", "a release that breaks anything below raises the minor", "src/guide.md"),
];

#[test]
fn each_rule_is_stated_in_one_place() {
    // The changelog says what changed in each release, not what holds now.
    let files = manual_files().into_iter().filter(|f| f != "CHANGELOG.md");
    let texts: Vec<(String, String)> = files.map(|f| (manual_text(&f, &read(&f)), f)).collect();
    assert!(texts.iter().any(|(_, f)| f == "src/guide.md"), "the guide is not scanned");
    let mut wrong = Vec::new();
    for (rule, phrase, authority) in RULES {
        let places: Vec<&str> = texts
            .iter()
            .flat_map(|(text, file)| text.matches(phrase).map(move |_| file.as_str()))
            .collect();
        if places != [authority] {
            wrong.push(format!("{rule}: `{phrase}` is in {places:?}, not once in {authority}"));
        }
    }
    assert!(wrong.is_empty(), "rules not stated once where they belong:\n{}", wrong.join("\n"));
}
