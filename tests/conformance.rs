//! Runs every conformance case in `tests/conformance/cases` (see the README there).
//!
//! Cases that need composition (attach, detach) are expected to fail until that is
//! built; they are listed one per line in `tests/conformance/expected_failures.txt`.
//! The test fails if a listed case passes (the list must shrink) or an unlisted case
//! fails.

#[path = "support/case.rs"]
mod case;
#[path = "support/compare.rs"]
mod compare;
#[path = "support/replay.rs"]
mod replay;

use std::path::Path;

use replay::Outcome;

#[test]
fn conformance_cases() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/conformance");
    let listed_text = std::fs::read_to_string(root.join("expected_failures.txt")).unwrap_or_default();
    let listed: Vec<&str> =
        listed_text.lines().map(str::trim).filter(|l| !l.is_empty() && !l.starts_with('#')).collect();
    let results = replay::run_all(&root.join("cases"), None).expect("cases load");
    assert!(!results.is_empty(), "no conformance cases found");
    let (mut passed, mut failed, mut deviations) = (0, 0, 0);
    let mut problems = Vec::new();
    for (name, outcome) in &results {
        let expected_to_fail = listed.contains(&name.as_str());
        match outcome {
            Outcome::Pass | Outcome::Deviation(_) => {
                if matches!(outcome, Outcome::Pass) {
                    passed += 1;
                } else {
                    deviations += 1;
                }
                if expected_to_fail {
                    problems
                        .push(format!("{name} is listed as expected to fail but now passes: remove it from the list"));
                }
            }
            Outcome::Fail(why) => {
                failed += 1;
                if !expected_to_fail {
                    problems.push(format!("FAIL {name}: {why}"));
                }
            }
        }
    }
    for name in &listed {
        assert!(results.iter().any(|(n, _)| n == name), "expected_failures.txt names unknown case {name}");
    }
    println!("conformance: {passed} passed, {failed} failed ({} expected), {deviations} deviations", listed.len());
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}
