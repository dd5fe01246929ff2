//! The unit tests of the conformance support code (`tests/support/case.rs` and
//! `tests/support/compare.rs`, the `#[cfg(test)]` modules in them). They live in
//! their own target because `tests/conformance.rs`, which replays the cases, has its
//! own runner (`harness = false`) and so does not build them.
