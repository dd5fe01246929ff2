//! MuJoCo compiles a composed model saved as a scene (`Model::save_scene`: each
//! attachment a MuJoCo `<attach>` of an asset `<model>`) to the model it compiles from
//! the composed text (`Model::to_xml_string`): the same sizes, names of every kind in
//! order, numbers, and options (both simulate the same steps), but for the
//! differences `xml::scene` documents: the keys of attached models (MuJoCo lays
//! them out at their joints; names and number are the same), each file's own compiler
//! settings, attached sections in document order (models attached out of document
//! order are counted apart), and automatic names (an unnamed element of a part is
//! written `//unnamed_geom_0` in its file, which MuJoCo prefixes `robot///...`; the
//! composed text writes `robot//unnamed_geom_0`).

use crate::case;
use crate::replay;
use crate::support;

use std::path::{Path, PathBuf};

use mjcf::{Event, Model};
use mjcf_mujoco::{Compiled, MuJoCo, ObjKind, Physics};
use support::mujoco;

/// A name as compared: an automatic name (`robot//unnamed_geom_0` or, from a part's
/// file, `robot///unnamed_geom_0`) as the scope it is in.
fn compared(name: Option<&str>) -> Option<String> {
    let n = name?;
    Some(match n.find("/unnamed_") {
        Some(i) => format!("{}/<auto>", n[..i].trim_end_matches('/')),
        None => n.to_string(),
    })
}

/// The first difference between the scene's compile and the composed text's.
fn difference(scene: &Compiled, composed: &Compiled) -> Option<String> {
    if scene.sizes() != composed.sizes() {
        return Some(format!("sizes {:?} vs {:?}", scene.sizes(), composed.sizes()));
    }
    for kind in ObjKind::ALL {
        let names = |m: &Compiled| -> Vec<Option<String>> {
            (0..m.count(kind))
                .map(|i| compared(m.name(kind, i)))
                // MuJoCo names the keys of a part's own attachments by their scope
                // alone (`prop/init`, where the composed text writes `arm/prop/init`):
                // keys compare by their last scope and name.
                .map(|n| match n {
                    Some(n) if kind == ObjKind::Key => {
                        let cut = n.rmatch_indices('/').nth(1).map_or(0, |(i, _)| i + 1);
                        Some(n[cut..].to_string())
                    }
                    n => n,
                })
                .collect()
        };
        if names(scene) != names(composed) {
            return Some(format!(
                "{} names: {:?} vs {:?}",
                kind.name(),
                names(scene),
                names(composed)
            ));
        }
    }
    // The arrays of the judge's read-back comparison, without the keys' values.
    if let Some(d) = support::array_difference(scene, composed, support::COMPARED_FLOATS) {
        return Some(d);
    }
    // The options: both simulate the same steps.
    let run = |c: &Compiled| -> Option<Vec<f64>> {
        let mut p = Physics::new(c).ok()?;
        // Both warn alike, or not at all: the states compared say it.
        let _warnings = p.step(20).ok()?;
        Some(p.qpos().iter().chain(p.qvel()).copied().collect())
    };
    let (a, b) = (run(scene)?, run(composed)?);
    if a.iter().zip(&b).any(|(p, q)| p.to_bits() != q.to_bits() && (p - q).abs() > 1e-9) {
        return Some(format!("20 steps: {a:?} vs {b:?}"));
    }
    None
}

/// Whether every model of the composition has its attachments in document order.
fn attached_in_document_order(m: &Model) -> bool {
    let doc: Vec<String> = m
        .walk()
        .filter_map(|e| match e {
            Event::Enter(e) if e.is_frame() => {
                e.full_name().map(|n| n.trim_end_matches('/').to_string())
            }
            _ => None,
        })
        .collect();
    let at = |p: &str| doc.iter().position(|d| d == p);
    let mut levels = vec![String::new()];
    levels.extend(m.scope_paths());
    levels.iter().all(|level| {
        let model = if level.is_empty() { m } else { m.attached(level.as_str()).unwrap() };
        let pos: Vec<Option<usize>> = model
            .scopes()
            .map(|s| at(&if level.is_empty() { s.to_string() } else { format!("{level}/{s}") }))
            .collect();
        pos.windows(2).all(|w| w[0] < w[1])
    })
}

/// The compiler settings of `m` (its own `<compiler>`, as written).
fn compiler(m: &Model) -> Vec<String> {
    let c = m.section("compiler").unwrap();
    let c = m.get(&c).unwrap();
    let mut out: Vec<String> = c.attrs().map(|(n, v)| format!("{n}={v}")).collect();
    for child in c.children() {
        out.extend(child.attrs().map(|(n, v)| format!("{}/{n}={v}", child.tag())));
    }
    out
}

/// Whether the models of the composition set different compiler settings: each file
/// of the scene is compiled with its own, the composed text with the merged ones.
fn compilers_differ(m: &Model) -> bool {
    let own = compiler(m);
    m.scope_paths().iter().any(|p| compiler(m.attached(p.as_str()).unwrap()) != own)
}

/// Whether a model of the composition has a default class named `main` below its
/// root class: MuJoCo refuses it written alone ("repeated default class name"), as
/// dm_control writes it, so its part file too; the composed text prefixes it.
fn class_named_main(m: &Model) -> bool {
    let has = |m: &Model| {
        m.find(mjcf::Namespace::Default, "main").is_some_and(|c| c != m.default_class())
    };
    has(m) || m.scope_paths().iter().any(|p| has(m.attached(p.as_str()).unwrap()))
}

/// What comparing found.
#[derive(Default, Debug)]
struct Tally {
    same: usize,
    out_of_order: usize,
    compilers: usize,
    main_class: usize,
    refused: usize,
    failures: Vec<String>,
}

fn judge(mujoco: &MuJoCo, label: &str, m: &Model, tally: &mut Tally) {
    if m.scope_paths().is_empty() {
        return;
    }
    if !attached_in_document_order(m) {
        tally.out_of_order += 1;
        return;
    }
    if class_named_main(m) {
        tally.main_class += 1;
        return;
    }
    let Ok(composed) = mujoco.compile(m) else {
        tally.refused += 1;
        return;
    };
    let dir = std::env::temp_dir().join(format!(
        "mjcf-mujoco-scenes-{}-{}",
        std::process::id(),
        tally.same
    ));
    let _ = std::fs::remove_dir_all(&dir);
    let saved = m.save_scene(&dir, "scene.xml").unwrap();
    let scene = mujoco.compile_path(saved.path());
    let _ = std::fs::remove_dir_all(&dir);
    let scene = match scene {
        Ok(s) => s,
        Err(e) => {
            tally.failures.push(format!("{label}: the scene does not compile: {e}"));
            return;
        }
    };
    match difference(&scene, &composed) {
        None => tally.same += 1,
        Some(_) if compilers_differ(m) => tally.compilers += 1,
        Some(d) => tally.failures.push(format!("{label}: {d}")),
    }
}

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn mujoco_compiles_saved_scenes_as_the_composed_text() {
    use mjcf::generate::strategy;
    use proptest::strategy::{Strategy, ValueTree};
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
    let mujoco = mujoco();
    let mut tally = Tally::default();
    for dir in case::list_cases(&repo().join("tests/conformance/cases")).unwrap() {
        let c = case::load_case(&dir).unwrap();
        let (_, outputs) = replay::run_case_collecting(&c, None);
        for (file, model, _) in outputs {
            judge(&mujoco, &format!("{}/{file}", c.name), &model, &mut tally);
        }
    }
    let conformance = std::mem::take(&mut tally);
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &[23; 32]);
    let mut runner = TestRunner::new_with_rng(Config::default(), rng);
    let (scenes, edits) = (strategy::scene_recipe(), strategy::scene_and_edits());
    for i in 0..200 {
        let models = if i % 2 == 0 {
            vec![scenes.new_tree(&mut runner).unwrap().current().build()]
        } else {
            let (r, e) = edits.new_tree(&mut runner).unwrap().current();
            e.apply(&r.build())
        };
        for (v, m) in models.iter().enumerate() {
            judge(&mujoco, &format!("generated {i} version {v}"), m, &mut tally);
        }
    }
    for (what, t) in [("conformance outputs", &conformance), ("generated scenes", &tally)] {
        eprintln!(
            "{what} with attachments: {} scenes compile as the composed text, {} differ where their files' compiler settings differ, {} attached out of document order and {} with a class named main (not compared), {} composed texts MuJoCo refuses, {} failed",
            t.same,
            t.compilers,
            t.out_of_order,
            t.main_class,
            t.refused,
            t.failures.len()
        );
    }
    let failures: Vec<&String> = conformance.failures.iter().chain(&tally.failures).collect();
    assert!(failures.is_empty(), "{failures:#?}");
    assert!(conformance.same > 50 && tally.same > 200, "{conformance:?} {tally:?}");
}
