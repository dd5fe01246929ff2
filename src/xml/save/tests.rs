//! The lossless writer's properties over generated models and edit sequences: a
//! model read (from the plain writer's text of a generated model; a composed model's
//! text, with a class `/` beside the attached models' classes, is left out: removing
//! the attached classes by edits makes text that reads as another model), edited by
//! `mjcf::generate`'s edits and saved, reads back as the edited model; every part
//! no edit touched is in the saved text as it was read; the first version saves the
//! text read.

use proptest::prelude::*;
use proptest::test_runner::{Config, RngSeed, TestCaseError};

use super::*;
use crate::generate::strategy::{edit_recipe, model_recipe};

fn config() -> Config {
    let mut c = Config::default();
    if std::env::var_os("PROPTEST_CASES").is_none() {
        c.cases = 96;
    }
    if std::env::var_os("PROPTEST_RNG_SEED").is_none() {
        c.rng_seed = RngSeed::Fixed(0x6c6f_7373);
    }
    c.failure_persistence = None;
    c
}

fn fail(what: &str, e: impl std::fmt::Display, text: &str) -> TestCaseError {
    TestCaseError::fail(format!("{what}: {e}\n{text}"))
}

/// The texts of the largest untouched elements of `m` (clean, under an element that
/// is not), by the saver's own test of cleanness.
fn untouched_texts(m: &Model) -> Vec<String> {
    let Some(src) = m.side.source.as_deref() else { return Vec::new() };
    let saver = Saver { model: m, read: &src.read, src, dirty: dirty(m, &src.read) };
    let mut out = Vec::new();
    for (i, rec) in src.records.iter().enumerate() {
        let parent_clean =
            rec.parent != NO_RECORD && saver.clean(src.records[rec.parent as usize].id);
        if rec.kind == RecordKind::Element && saver.clean(rec.id) && !parent_clean {
            let text = src.text_of(i as u32);
            out.push(text[rec.start as usize..rec.end_end as usize].to_string());
        }
    }
    out
}

proptest! {
    #![proptest_config(config())]

    /// Saved, read back: the edited model; untouched parts byte for byte; the first
    /// version: the text read.
    #[test]
    fn edits_saved_read_back_as_the_edited_model(scene in model_recipe(), edits in edit_recipe()) {
        let text = scene.build().to_xml_string().map_err(|e| fail("write", e, ""))?;
        let base = Model::from_xml_str(&text).map_err(|e| fail("read", e, &text))?;
        let versions = edits.apply(&base);
        for m in &versions {
            let saved = m.to_source_files().map_err(|e| fail("save", e, &text))?;
            if m.scopes().next().is_some() {
                // A scene: its file and one per attached model (the round trip of
                // scenes is `xml::scene::tests`'s).
                prop_assert!(saved.len() > 1);
                continue;
            }
            prop_assert_eq!(saved.len(), 1);
            let out = &saved[0].text;
            let back = Model::from_xml_str(out).map_err(|e| fail("read back", e, out))?;
            // Equal, or (a reference an edit left as a name, `robot/a` that the API
            // does not take as a literal name, reads back resolved) written alike.
            let same = back == *m || back.to_xml_string().ok() == m.to_xml_string().ok();
            prop_assert!(same, "read back differs:\n{}\n--- from ---\n{}", out, text);
            for piece in untouched_texts(m) {
                prop_assert!(out.contains(&piece), "untouched text lost: {}\n{}", piece, out);
            }
        }
        let first = &versions[0].to_source_files().map_err(|e| fail("save", e, &text))?[0];
        prop_assert_eq!(&first.text, &text);
        prop_assert!(!first.changed);
    }
}
