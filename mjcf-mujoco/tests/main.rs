//! The binding's tests, one test binary (each file a module: one release build and
//! link of the crate and MuJoCo's bindings for all, where a binary per file built and
//! linked the same code nineteen times). The tests that need MuJoCo are ignored in a
//! plain `cargo test`; `.ci/run` runs them with `--include-ignored` and `MUJOCO_LIB`
//! set to the pinned wheel's library.

// Shared by several files: loaded once, each file `use`s it.
#[path = "support/augment.rs"]
mod augment;
#[path = "../../tests/support/case.rs"]
mod case;
#[path = "../../tests/support/compare.rs"]
mod compare;
#[path = "../../tests/support/names.rs"]
mod names;
#[path = "../../tests/support/replay.rs"]
#[allow(dead_code)]
mod replay;
#[path = "support/state.rs"]
mod state;
#[path = "../../tests/support/text.rs"]
mod text;

mod support;

mod angles;
mod arrays;
mod attach_in;
mod bind_named;
mod binding;
mod check;
mod judge;
mod keys;
mod keys_follow;
mod part;
mod rebuild;
mod rebuild_props;
mod reference_kinds;
mod refusals;
mod remove_with;
mod scenes;
mod simulates;
mod warnings;
mod written;
