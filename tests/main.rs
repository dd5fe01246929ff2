//! The crate's integration tests, one test binary: each file here is a module (one
//! build and link for all, where a binary per file built and linked the crate's code
//! once per file), but `conformance.rs`, which has its own runner (`harness = false`).
//! Run one file's tests by its module path: `cargo test --test tests hostile::`.

// Shared by several files: loaded once, each file `use`s it (and their own unit
// tests, such as the case reader's and the comparison's, run here).
#[path = "support/case.rs"]
mod case;
#[path = "support/compare.rs"]
mod compare;
#[path = "support/dirs.rs"]
mod dirs;
#[path = "support/names.rs"]
mod names;
#[path = "support/replay.rs"]
mod replay;
#[path = "support/robot.rs"]
mod robot;
#[path = "support/text.rs"]
mod text;

mod actuator_defaults;
mod angles;
mod api;
mod architecture;
mod attach_in;
mod check;
mod check_expansions;
mod composition;
mod corpus;
mod docs;
mod export;
mod files;
mod frictions;
mod fuzz_regressions;
mod hostile;
mod in_place;
mod includes;
mod keys_follow;
mod lossless;
mod model_based;
mod naming;
mod part;
mod properties;
mod remove_with;
mod safe_writes;
mod scale;
mod scene_save;
mod scenes;
mod schema40;
mod schema_facts;
mod spelling_edits;
mod spellings;
mod threads;
mod write_rules;
