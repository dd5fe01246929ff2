//! Runs conformance cases and prints one line per case.
//!
//! ```text
//! cargo run --release --example conformance -- [--actual-dir OUT] DIR...
//! ```
//! Every folder with a `case.json` directly under each `DIR` is a case. Prints
//! `PASS name`, `FAIL name: <first difference>` or `DEVIATION name: <labels>`, then
//! `N passed, M failed, K deviations`; exits with status 1 if any case failed. With
//! `--actual-dir`, writes every output produced to `OUT/<case>/<file>`.

#[path = "../tests/support/case.rs"]
mod case;
#[path = "../tests/support/compare.rs"]
mod compare;
#[path = "../tests/support/names.rs"]
mod names;
#[path = "../tests/support/replay.rs"]
mod replay;
#[path = "../tests/support/text.rs"]
mod text;

use std::path::PathBuf;
use std::process::ExitCode;

use replay::Outcome;

fn main() -> ExitCode {
    let mut args = std::env::args().skip(1);
    let mut actual_dir: Option<PathBuf> = None;
    let mut dirs: Vec<PathBuf> = Vec::new();
    while let Some(a) = args.next() {
        if a == "--actual-dir" {
            match args.next() {
                Some(d) => actual_dir = Some(d.into()),
                None => {
                    eprintln!("--actual-dir needs a folder");
                    return ExitCode::from(2);
                }
            }
        } else {
            dirs.push(a.into());
        }
    }
    if dirs.is_empty() {
        eprintln!("usage: conformance [--actual-dir OUT] DIR...");
        return ExitCode::from(2);
    }
    let (mut passed, mut failed, mut deviations) = (0, 0, 0);
    for dir in &dirs {
        let results = match replay::run_all(dir, actual_dir.as_deref()) {
            Ok(r) => r,
            Err(e) => {
                eprintln!("error: {e}");
                return ExitCode::from(2);
            }
        };
        for (name, outcome) in results {
            match outcome {
                Outcome::Pass => {
                    passed += 1;
                    println!("PASS {name}");
                }
                Outcome::Fail(why) => {
                    failed += 1;
                    println!("FAIL {name}: {why}");
                }
                Outcome::Deviation(labels) => {
                    deviations += 1;
                    println!("DEVIATION {name}: {}", labels.join(","));
                }
            }
        }
    }
    println!("{passed} passed, {failed} failed, {deviations} deviations");
    if failed == 0 { ExitCode::SUCCESS } else { ExitCode::FAILURE }
}
