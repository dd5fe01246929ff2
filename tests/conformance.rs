//! One test per conformance case in `tests/conformance/cases` (see the README there):
//! every case must pass, or differ from dm_control only on ops that carry a
//! `deviation` label (one of our deliberate deviations; the README there says how
//! each label the cases use is replayed, the crate's README what each one is), which
//! count as passed and print `ok (deviation: …)` with the labels seen.
//!
//! The target has `harness = false`: `main` below is a small runner that behaves like
//! libtest as far as cargo and CI need, so each case is a test named after its folder:
//!
//! ```text
//! cargo test rand_001                              # the cases whose name contains rand_001
//! cargo test --test conformance -- --exact hand_001_seed_example
//! cargo test --test conformance -- --list          # `name: test` lines
//! ```
//!
//! It takes libtest's arguments: filters (substrings; any may match), `--exact`,
//! `--skip FILTER`, `--list`, `--ignored` / `--include-ignored` (no case is ignored),
//! `--nocapture`, `--show-output`, `--test-threads N` (or `RUST_TEST_THREADS`),
//! `-q`/`--quiet` or `--format pretty|terse`, `--color auto|always|never`. Other
//! options are ignored with a warning. Results print in case order while cases run on
//! a few threads; a failing run exits with status 101, as libtest does.

#[path = "support/case.rs"]
mod case;
#[path = "support/compare.rs"]
mod compare;
#[path = "support/names.rs"]
mod names;
#[path = "support/replay.rs"]
mod replay;
#[path = "support/text.rs"]
mod text;

use std::cell::RefCell;
use std::collections::BTreeMap;
use std::io::{IsTerminal, Write};
use std::panic::{self, AssertUnwindSafe};
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc;
use std::time::Instant;

use replay::Outcome;

/// The corpus holds this many cases; an unfiltered run that finds fewer fails.
const EXPECTED_CASES: usize = 155;

/// libtest's exit status for failed tests and for bad arguments.
const FAILURE_STATUS: u8 = 101;

/// libtest options that take a value (`--name value` or `--name=value`).
const VALUE_OPTIONS: [&str; 7] =
    ["--test-threads", "--skip", "--format", "--color", "--logfile", "--shuffle-seed", "-Z"];

/// libtest flags without a value that make no difference here.
const IGNORED_FLAGS: [&str; 9] = [
    "--test",
    "--show-output",
    "--force-run-in-process",
    "--exclude-should-panic",
    "--report-time",
    "--ensure-time",
    "--shuffle",
    "--fail-fast",
    "--no-fail-fast",
];

#[derive(Debug, Clone, Copy, PartialEq)]
enum Color {
    Auto,
    Always,
    Never,
}

/// The command line, as libtest reads it.
#[derive(Debug)]
struct Options {
    filters: Vec<String>,
    skip: Vec<String>,
    exact: bool,
    list: bool,
    /// `--ignored`: run only ignored tests (there are none)...
    ignored: bool,
    /// ... unless `--include-ignored` runs them all.
    include_ignored: bool,
    nocapture: bool,
    threads: Option<usize>,
    terse: bool,
    color: Color,
    /// `--bench`: run benchmarks only (there are none).
    bench: bool,
    help: bool,
    /// An unknown flag directly followed by a word: the word is the flag's value
    /// unless it selects a case (decided once the cases are known).
    unknown_with_word: Vec<(String, String)>,
    warnings: Vec<String>,
}

impl Options {
    fn parse(args: impl IntoIterator<Item = String>) -> Result<Options, String> {
        let mut o = Options {
            filters: Vec::new(),
            skip: Vec::new(),
            exact: false,
            list: false,
            ignored: false,
            include_ignored: false,
            nocapture: false,
            threads: None,
            terse: false,
            color: Color::Auto,
            bench: false,
            help: false,
            unknown_with_word: Vec::new(),
            warnings: Vec::new(),
        };
        let mut args = args.into_iter().peekable();
        let mut only_filters = false;
        while let Some(arg) = args.next() {
            if only_filters || !arg.starts_with('-') || arg == "-" {
                o.filters.push(arg);
                continue;
            }
            if arg == "--" {
                only_filters = true;
                continue;
            }
            // `--name=value`, `--name value`, and `-Zvalue` for the short options.
            let (name, inline) = match arg.split_once('=') {
                Some((n, v)) if n.starts_with("--") => (n.to_owned(), Some(v.to_owned())),
                _ if !arg.starts_with("--") && arg.len() > 2 && arg.is_char_boundary(2) => {
                    (arg[..2].to_owned(), Some(arg[2..].to_owned()))
                }
                _ => (arg.clone(), None),
            };
            if VALUE_OPTIONS.contains(&name.as_str()) {
                let value = match inline {
                    Some(v) => v,
                    None => args
                        .next()
                        .ok_or_else(|| format!("Argument to option '{}' missing", &name))?,
                };
                match name.as_str() {
                    "--test-threads" => match value.parse::<usize>() {
                        Ok(n) if n > 0 => o.threads = Some(n),
                        _ => {
                            return Err(format!(
                                "argument for --test-threads must be a number > 0 (error: {value})"
                            ));
                        }
                    },
                    "--skip" => o.skip.push(value),
                    "--format" => match value.as_str() {
                        "pretty" => o.terse = false,
                        "terse" => o.terse = true,
                        _ => {
                            return Err(format!(
                                "argument for --format must be pretty or terse (was {value})"
                            ));
                        }
                    },
                    "--color" => {
                        o.color = match value.as_str() {
                            "auto" => Color::Auto,
                            "always" => Color::Always,
                            "never" => Color::Never,
                            _ => {
                                return Err(format!(
                                    "argument for --color must be auto, always, or never (was {value})"
                                ));
                            }
                        }
                    }
                    _ => o.warnings.push(format!("ignoring option {name} {value}")),
                }
                continue;
            }
            if inline.is_some() && name.starts_with("--") {
                o.warnings.push(format!("ignoring unknown option {arg}"));
                continue;
            }
            match arg.as_str() {
                "--exact" => o.exact = true,
                "--list" => o.list = true,
                "--ignored" => o.ignored = true,
                "--include-ignored" => o.include_ignored = true,
                "--nocapture" | "--no-capture" => o.nocapture = true,
                "-q" | "--quiet" => o.terse = true,
                "--bench" => o.bench = true,
                "-h" | "--help" => o.help = true,
                _ if IGNORED_FLAGS.contains(&arg.as_str()) => {}
                _ => match args.next_if(|next| !next.starts_with('-')) {
                    Some(word) => o.unknown_with_word.push((arg, word)),
                    None => o.warnings.push(format!("ignoring unknown option {arg}")),
                },
            }
        }
        if std::env::var_os("RUST_TEST_NOCAPTURE").is_some_and(|v| v != "0") {
            o.nocapture = true;
        }
        if o.threads.is_none() {
            if let Ok(value) = std::env::var("RUST_TEST_THREADS") {
                match value.parse::<usize>() {
                    Ok(n) if n > 0 => o.threads = Some(n),
                    _ => {
                        return Err(format!(
                            "RUST_TEST_THREADS is `{value}`, should be a positive integer."
                        ));
                    }
                }
            }
        }
        Ok(o)
    }

    /// Settles each unknown flag's following word: a filter if it selects one of
    /// `names`, else the flag's value.
    fn settle_unknown(&mut self, names: &[String]) {
        for (flag, word) in std::mem::take(&mut self.unknown_with_word) {
            if names.iter().any(|name| self.matches(name, &word)) {
                self.warnings
                    .push(format!("ignoring unknown option {flag} (taking {word:?} as a filter)"));
                self.filters.push(word);
            } else {
                self.warnings.push(format!("ignoring unknown option {flag} {word}"));
            }
        }
    }

    fn matches(&self, name: &str, filter: &str) -> bool {
        if self.exact { name == filter } else { name.contains(filter) }
    }

    /// Whether the case `name` is selected (filters, `--skip`, `--ignored`, `--bench`).
    fn selects(&self, name: &str) -> bool {
        let filtered =
            self.filters.is_empty() || self.filters.iter().any(|f| self.matches(name, f));
        let skipped = self.skip.iter().any(|s| self.matches(name, s));
        let only_ignored = self.ignored && !self.include_ignored;
        filtered && !skipped && !only_ignored && !self.bench
    }

    fn use_color(&self) -> bool {
        match self.color {
            Color::Always => true,
            Color::Never => false,
            Color::Auto => !self.nocapture && std::io::stdout().is_terminal(),
        }
    }
}

const HELP: &str = "\
Usage: conformance [OPTIONS] [FILTERS...]

Runs the conformance cases of tests/conformance/cases, one test per case folder.

Options:
        --include-ignored
                        Run ignored and not ignored tests (no case is ignored)
        --ignored       Run only ignored tests (none)
        --exact         Exactly match filters rather than by substring
        --skip FILTER   Skip tests whose names contain FILTER (may be repeated)
        --list          List all tests
        --test-threads n_threads
                        Number of threads used for running tests in parallel
        --nocapture     Show panic messages as they happen
    -q, --quiet         Display one character per test instead of one line
                        (alias to --format=terse)
        --format pretty|terse
        --color auto|always|never
    -h, --help          Display this message
";

/// What running one case gave.
enum Verdict {
    Ok,
    Deviation(Vec<String>),
    Failed(String),
}

thread_local! {
    /// The message of the last panic on this thread (the panic hook stores it).
    static PANIC_MESSAGE: RefCell<Option<String>> = const { RefCell::new(None) };
}

/// Loads and replays one case; a panic is a failure with its message.
fn run_case(dir: &Path) -> Verdict {
    let result = panic::catch_unwind(AssertUnwindSafe(|| {
        let case = case::load_case(dir)?;
        Ok::<_, String>(replay::run_case(&case, None))
    }));
    match result {
        Ok(Ok(Outcome::Pass)) => Verdict::Ok,
        Ok(Ok(Outcome::Deviation(labels))) => Verdict::Deviation(labels),
        Ok(Ok(Outcome::Fail(why))) => Verdict::Failed(why),
        Ok(Err(load_error)) => Verdict::Failed(load_error),
        Err(_) => Verdict::Failed(
            PANIC_MESSAGE.with(|m| m.borrow_mut().take()).unwrap_or_else(|| "panicked".to_owned()),
        ),
    }
}

/// Writes to stdout, ignoring write errors (a closed pipe ends nothing early).
struct Out {
    color: bool,
}

impl Out {
    fn plain(&self, text: &str) {
        let mut out = std::io::stdout().lock();
        let _ = out.write_all(text.as_bytes());
        let _ = out.flush();
    }

    /// `text` in green (`true`) or red, when colors are on.
    fn colored(&self, text: &str, green: bool) {
        if self.color {
            self.plain(&format!("\x1b[{}m{text}\x1b[0m", if green { 32 } else { 31 }));
        } else {
            self.plain(text);
        }
    }
}

fn plural(n: usize, noun: &str) -> String {
    if n == 1 { format!("1 {noun}") } else { format!("{n} {noun}s") }
}

fn main() -> ExitCode {
    let start = Instant::now();
    let mut options = match Options::parse(std::env::args().skip(1)) {
        Ok(o) => o,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(FAILURE_STATUS);
        }
    };
    if options.help {
        print!("{HELP}");
        return ExitCode::SUCCESS;
    }
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/conformance/cases");
    let dirs = match case::list_cases(&root) {
        Ok(dirs) => dirs,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(FAILURE_STATUS);
        }
    };
    let names: Vec<String> = dirs
        .iter()
        .map(|d| d.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default())
        .collect();
    options.settle_unknown(&names);
    for warning in &options.warnings {
        eprintln!("warning: {warning}");
    }
    if options.filters.is_empty() && options.skip.is_empty() && names.len() < EXPECTED_CASES {
        eprintln!(
            "error: expected the {EXPECTED_CASES} cases in {}, found {}",
            root.display(),
            names.len()
        );
        return ExitCode::from(FAILURE_STATUS);
    }
    let selected: Vec<(&String, &PathBuf)> =
        names.iter().zip(&dirs).filter(|(name, _)| options.selects(name)).collect();
    let out = Out { color: options.use_color() };

    if options.list {
        for (name, _) in &selected {
            out.plain(&format!("{name}: test\n"));
        }
        if !options.terse {
            if !selected.is_empty() {
                out.plain("\n");
            }
            out.plain(&format!("{}, 0 benchmarks\n", plural(selected.len(), "test")));
        }
        return ExitCode::SUCCESS;
    }

    // Panics are failures of their case; keep their messages for the report (and
    // also print them at once with --nocapture).
    let default_hook = panic::take_hook();
    let nocapture = options.nocapture;
    panic::set_hook(Box::new(move |info| {
        PANIC_MESSAGE.with(|m| *m.borrow_mut() = Some(info.to_string()));
        if nocapture {
            default_hook(info);
        }
    }));

    let total = selected.len();
    out.plain(&format!("\nrunning {}\n", plural(total, "test")));
    let threads = options
        .threads
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, usize::from))
        .clamp(1, total.max(1));
    let next = AtomicUsize::new(0);
    let (send, receive) = mpsc::channel::<(usize, Verdict)>();
    let mut failures: Vec<(&str, String)> = Vec::new();
    let mut passed = 0;
    std::thread::scope(|scope| {
        for _ in 0..threads {
            let send = send.clone();
            let (next, selected) = (&next, &selected);
            scope.spawn(move || {
                loop {
                    let i = next.fetch_add(1, Ordering::Relaxed);
                    let Some((_, dir)) = selected.get(i) else { break };
                    if send.send((i, run_case(dir))).is_err() {
                        break;
                    }
                }
            });
        }
        drop(send);
        // Report in case order, whatever order the threads finish in.
        let mut done: BTreeMap<usize, Verdict> = BTreeMap::new();
        for (i, (name, _)) in selected.iter().enumerate() {
            if !options.terse {
                out.plain(&format!("test {name} ... "));
            }
            let verdict = loop {
                if let Some(v) = done.remove(&i) {
                    break v;
                }
                match receive.recv() {
                    Ok((j, v)) => {
                        done.insert(j, v);
                    }
                    Err(_) => break Verdict::Failed("the runner lost this case".to_owned()),
                }
            };
            let ok = !matches!(verdict, Verdict::Failed(_));
            if options.terse {
                out.colored(if ok { "." } else { "F" }, ok);
                // libtest breaks terse lines every 88 results.
                if i % 88 == 87 {
                    out.plain(&format!(" {}/{total}\n", i + 1));
                }
            } else {
                out.colored(if ok { "ok" } else { "FAILED" }, ok);
                if let Verdict::Deviation(labels) = &verdict {
                    out.plain(&format!(" (deviation: {})", labels.join(", ")));
                }
                out.plain("\n");
            }
            match verdict {
                Verdict::Ok | Verdict::Deviation(_) => passed += 1,
                Verdict::Failed(why) => failures.push((name.as_str(), why)),
            }
        }
    });
    if !failures.is_empty() {
        out.plain("\nfailures:\n\n");
        for (name, why) in &failures {
            out.plain(&format!("---- {name} stdout ----\n{why}\n\n"));
        }
        out.plain("\nfailures:\n");
        for (name, _) in &failures {
            out.plain(&format!("    {name}\n"));
        }
    }
    out.plain("\ntest result: ");
    out.colored(if failures.is_empty() { "ok" } else { "FAILED" }, failures.is_empty());
    out.plain(&format!(
        ". {passed} passed; {} failed; 0 ignored; 0 measured; {} filtered out; finished in {:.2}s\n\n",
        failures.len(),
        names.len() - total,
        start.elapsed().as_secs_f64()
    ));
    if failures.is_empty() { ExitCode::SUCCESS } else { ExitCode::from(FAILURE_STATUS) }
}
