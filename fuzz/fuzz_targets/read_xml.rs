//! Arbitrary bytes → `ReadOptions::read_bytes` (file access confined to a folder that
//! does not exist, default nesting limit).
//!
//! On a model that reads: writing it must not panic (a `WriteError` is a typed
//! refusal, fine); if it writes, the output must be well-formed with unique
//! identifiers, must read back, and write∘read must reach its fixed point (exactly, or
//! one round later for a named root default class, see `common::check_fixed_point`).

#![no_main]

mod common;

use std::sync::OnceLock;

use libfuzzer_sys::fuzz_target;
use mjcf::{ReadOptions, WriteOptions};

fn options() -> &'static ReadOptions {
    static OPTIONS: OnceLock<ReadOptions> = OnceLock::new();
    OPTIONS.get_or_init(common::confined)
}

fuzz_target!(|data: &[u8]| {
    let model = match options().read_bytes(data) {
        Ok(m) => m,
        Err(e) => {
            // Messages and positions must not panic either.
            let _ = e.to_string();
            let _ = e.pos();
            return;
        }
    };
    let w1 = match model.to_xml_string() {
        Ok(w) => w,
        Err(e) => {
            let _ = e.to_string();
            return;
        }
    };
    // The other writer settings must not panic either (their output is not checked).
    let other =
        WriteOptions {
            precision: Some(17),
            zero_threshold: 1e-9,
            pretty_print: false,
            filename_with_hash: false,
            merge_keyframes: true,
        };
    let _ = model.to_xml_string_with(&other);
    common::check_unique_identifiers(&w1);
    common::check_fixed_point(options(), &w1);
});
