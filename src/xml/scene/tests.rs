//! Properties of saved scenes over generated composed models with edits
//! (`crate::generate`): saved and reopened, a model has the same scope paths and
//! writes the same composed MJCF. Cases: `PROPTEST_CASES` (default 64) from a fixed
//! seed (`PROPTEST_RNG_SEED` to explore others).

use proptest::strategy::{Strategy, ValueTree};
use proptest::test_runner::{Config, RngSeed, TestRunner};

use crate::Model;
use crate::generate::strategy::{scene_and_edits, scene_recipe};

fn config() -> Config {
    let mut c = Config::default();
    if std::env::var_os("PROPTEST_CASES").is_none() {
        c.cases = 64;
    }
    if std::env::var_os("PROPTEST_RNG_SEED").is_none() {
        c.rng_seed = RngSeed::Fixed(0x7363_656e);
    }
    c.failure_persistence = None;
    c
}

/// A fresh folder for one saved scene.
fn folder(label: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("mjcf-scene-props-{}-{label}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// What saving and reopening `m` found: `Ok(true)` when the reopened model has the
/// same scope paths and writes the same MJCF, `Ok(false)` when its attachments
/// were made out of document order (the documented difference), an error otherwise.
pub(crate) fn round_trip(m: &Model, label: &str) -> Result<bool, String> {
    let dir = folder(label);
    let saved = m.save_scene(&dir, "scene.xml").map_err(|e| format!("save: {e}"))?;
    let back = Model::from_path(saved.path()).map_err(|e| format!("reopen: {e}"))?;
    let _ = std::fs::remove_dir_all(&dir);
    lossless_fixed_point(&back, label)?;
    let (want, got) = (m.scope_paths(), back.scope_paths());
    let (w1, w2) = (
        m.to_xml_string().map_err(|e| e.to_string())?,
        back.to_xml_string().map_err(|e| e.to_string())?,
    );
    if want == got && w1 == w2 {
        return Ok(true);
    }
    let mut sorted = (want.clone(), got.clone());
    sorted.0.sort();
    sorted.1.sort();
    if sorted.0 == sorted.1 && !in_document_order(m) {
        return Ok(false);
    }
    Err(format!("scopes {want:?} vs {got:?}\n--- composed\n{w1}\n--- reopened\n{w2}"))
}

/// The lossless save of the reopened scene `back` (`Model::save_as`): no file
/// changed; reopened from there, the same scope paths and composed MJCF, and the same
/// texts saved again.
fn lossless_fixed_point(back: &Model, label: &str) -> Result<(), String> {
    let texts = back.to_source_files().map_err(|e| format!("lossless save: {e}"))?;
    if let Some(f) = texts.iter().find(|f| f.changed) {
        return Err(format!("{:?} changed on a save without edits:\n{}", f.path, f.text));
    }
    let dir = folder(&format!("{label}-lossless"));
    back.save_as(&dir).map_err(|e| format!("save_as: {e}"))?;
    let again = Model::from_path(dir.join("scene.xml")).map_err(|e| format!("reopen: {e}"));
    let _ = std::fs::remove_dir_all(&dir);
    let again = again?;
    let (w1, w2) = (
        back.to_xml_string().map_err(|e| e.to_string())?,
        again.to_xml_string().map_err(|e| e.to_string())?,
    );
    if again.scope_paths() != back.scope_paths() || w1 != w2 {
        return Err(format!("saved losslessly and reopened:\n{w1}\n---\n{w2}"));
    }
    let again_texts = again.to_source_files().map_err(|e| format!("save again: {e}"))?;
    let key = |t: &[crate::SourceText]| -> Vec<(Option<std::path::PathBuf>, String)> {
        t.iter().map(|f| (f.path.clone(), f.text.clone())).collect()
    };
    if key(&texts) != key(&again_texts) {
        return Err("saved again, the texts differ".to_string());
    }
    Ok(())
}

/// Whether every model of the composition has its attachments in document order.
fn in_document_order(m: &Model) -> bool {
    let mut todo = vec![m];
    while let Some(m) = todo.pop() {
        let doc: Vec<&str> =
            m.root.descendants().filter_map(|n| n.attached().map(|a| a.scope.as_str())).collect();
        if !m.scopes().eq(doc.iter().copied()) {
            return false;
        }
        todo.extend(crate::model::settings::attachments(m));
    }
    true
}

#[test]
fn generated_scenes_with_edits_save_and_reopen_composed() {
    let mut runner = TestRunner::new(config());
    let (scenes, edits) = (scene_recipe(), scene_and_edits());
    let (mut same, mut reordered, mut attachments) = (0, 0, 0);
    let mut failures = Vec::new();
    for i in 0..config().cases {
        let models = if i % 2 == 0 {
            vec![scenes.new_tree(&mut runner).unwrap().current().build()]
        } else {
            let (r, e) = edits.new_tree(&mut runner).unwrap().current();
            e.apply(&r.build())
        };
        for (v, m) in models.iter().enumerate() {
            attachments += m.scope_paths().len();
            match round_trip(m, &format!("{i}-{v}")) {
                Ok(true) => same += 1,
                Ok(false) => reordered += 1,
                Err(e) => failures.push(format!("generated {i} version {v}: {e}")),
            }
        }
    }
    eprintln!(
        "generated scenes: {same} reopened the same, {reordered} attached out of document order, {attachments} attachments, {} failed",
        failures.len()
    );
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
}
