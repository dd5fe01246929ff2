//! Runs every conformance case in `tests/conformance/cases` (see the README there):
//! every case must pass, or differ from dm_control only on ops marked as one of our
//! deliberate deviations (DESIGN D1–D3).

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
    let results = replay::run_all(&root.join("cases"), None).expect("cases load");
    assert!(results.len() >= 155, "expected the 155 cases, found {}", results.len());
    let (mut passed, mut deviations) = (0, 0);
    let mut failures = Vec::new();
    for (name, outcome) in &results {
        match outcome {
            Outcome::Pass => passed += 1,
            Outcome::Deviation(_) => deviations += 1,
            Outcome::Fail(why) => failures.push(format!("FAIL {name}: {why}")),
        }
    }
    println!("conformance: {passed} passed, {} failed, {deviations} deviations", failures.len());
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}
