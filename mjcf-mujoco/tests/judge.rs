//! MuJoCo judges the facts the crate derives without it, over every conformance
//! output, generated scenes with edits (`mjcf::generate`) and the real models
//! (`../shared/realmodels` beside the checkout, as CI has it):
//!
//! - names: every element's `full_name` resolves with `mj_name2id` to an element of
//!   its kind, and `from_full_name` gives the element back;
//! - the physics layout (`Model::layout`, which composed keys and `check` use): each
//!   joint's `qpos` and `qvel` addresses and type are MuJoCo's `jnt_qposadr`,
//!   `jnt_dofadr`, `jnt_type`; each actuator's control and activation addresses are
//!   `actuator_ctrladr`, `actuator_actadr`; `nq`, `nv`, `nu`, `na` agree.
//!
//! - read-back: what the written text reads back as compiles to the same model (sizes,
//!   names in order, positions, masses, sizes, ranges, gains, default poses, keys).
//!
//! Each test prints its counts; a model MuJoCo refuses is counted apart (the corpus
//! holds a few whose reference output does not compile either) and never as passed.

#[path = "../../tests/support/case.rs"]
mod case;
#[path = "../../tests/support/compare.rs"]
mod compare;
#[path = "../../tests/support/names.rs"]
mod names;
#[path = "../../tests/support/replay.rs"]
#[allow(dead_code)]
mod replay;
mod support;
#[path = "../../tests/support/text.rs"]
mod text;

use std::path::{Path, PathBuf};

use mjcf::{Event, Model, Namespace, WriteOptions};
use mjcf_mujoco::{Compiled, Error, MuJoCo, ObjKind};
use support::mujoco;

/// What judging one model found.
#[derive(Default, Debug)]
struct Tally {
    models: usize,
    refused: usize,
    names: usize,
    joints: usize,
    actuators: usize,
    /// Models whose read-back compiles to the same model.
    read_back: usize,
    /// Elements inside a `<replicate>`, whose copies MuJoCo names itself.
    replicated: usize,
    /// Models with elements the layout does not expand (`<attach>`, ...).
    unexpanded: usize,
    failures: Vec<String>,
}

impl Tally {
    fn report(&self, what: &str) {
        eprintln!(
            "{what}: {} models ({} refused by MuJoCo, {} with unexpanded elements), {} names, {} joints, \
             {} actuators judged, {} read back to the same compiled model; {} replicated elements \
             not judged by name; {} failures",
            self.models,
            self.refused,
            self.unexpanded,
            self.names,
            self.joints,
            self.actuators,
            self.read_back,
            self.replicated,
            self.failures.len()
        );
        let shown: Vec<&String> = self.failures.iter().take(30).collect();
        assert!(
            self.failures.is_empty(),
            "{what}: {} failures, the first:\n{}",
            self.failures.len(),
            shown.iter().map(|s| s.as_str()).collect::<Vec<_>>().join("\n")
        );
    }
}

/// Whether the element lies inside a default class or a `<replicate>`.
fn inside(e: &mjcf::ElementRef<'_>, tag: &str) -> bool {
    let mut cur = e.parent();
    while let Some(p) = cur {
        if p.tag() == tag {
            return true;
        }
        cur = p.parent();
    }
    false
}

fn judge(mujoco: &MuJoCo, label: &str, model: &Model, options: &WriteOptions, tally: &mut Tally) {
    tally.models += 1;
    let compiled = match mujoco.compile_with(model, options) {
        Ok(c) => c,
        Err(Error::Compile(_)) => {
            tally.refused += 1;
            return;
        }
        Err(e) => {
            tally.failures.push(format!("{label}: {e}"));
            return;
        }
    };
    judge_names(label, model, &compiled, tally);
    judge_layout(label, model, &compiled, tally);
    judge_read_back(mujoco, label, model, options, &compiled, tally);
}

/// What the written text reads back as compiles to the same model (what
/// tools/readback_check.py checked).
fn judge_read_back(
    mujoco: &MuJoCo,
    label: &str,
    model: &Model,
    options: &WriteOptions,
    compiled: &Compiled,
    tally: &mut Tally,
) {
    let mut read = mjcf::ReadOptions::new();
    for (name, file) in model.assets(options).unwrap() {
        read = read.asset(&name, file.contents().to_vec());
    }
    let back = match read.read_str(compiled.written().unwrap().xml()) {
        Ok(back) => back,
        Err(e) => return tally.failures.push(format!("{label}: does not read back: {e}")),
    };
    match mujoco.compile_with(&back, options) {
        Ok(again) => match compiled_difference(compiled, &again) {
            None => tally.read_back += 1,
            Some(d) => {
                tally.failures.push(format!("{label}: its read-back compiles otherwise: {d}"))
            }
        },
        Err(e) => tally.failures.push(format!("{label}: its read-back does not compile: {e}")),
    }
}

fn judge_names(label: &str, model: &Model, compiled: &Compiled, tally: &mut Tally) {
    let written = compiled.written().unwrap();
    let as_frame: std::collections::HashSet<mjcf::Loc> =
        written.elements().iter().filter(|w| w.tag == "frame").map(|w| w.loc.clone()).collect();
    // `discardvisual` removes visual-only assets and geoms: they have no names there.
    let discards = written.xml().contains("discardvisual=\"true\"");
    let replicates = written.elements().iter().any(|w| w.tag == "replicate");
    for event in model.walk() {
        let Event::Enter(e) = event else { continue };
        let Some(kind) = ObjKind::of(&e) else { continue };
        if e.is_frame() && as_frame.contains(&e.loc()) {
            // Written as MuJoCo's <frame>: not compiled (and not bound).
            assert!(compiled.bind(&e.loc()).is_err());
            continue;
        }
        if discards
            && matches!(kind, ObjKind::Geom | ObjKind::Mesh | ObjKind::Texture | ObjKind::Material)
        {
            continue;
        }
        if inside(&e, "default") {
            continue;
        }
        if inside(&e, "replicate") || e.tag() == "replicate" {
            tally.replicated += 1;
            continue;
        }
        let Some(name) = e.full_name() else {
            tally.failures.push(format!("{label}: a <{}> has no full_name", e.tag()));
            continue;
        };
        // MuJoCo copies what refers to a replicated element too (a tendon through
        // replicated sites), appending the copy's number to its name, padded to the
        // digits of the count (`0`, `00`, ...).
        let copied =
            ["0", "00", "000"].iter().any(|z| compiled.id(kind, &format!("{name}{z}")).is_some());
        if replicates && compiled.id(kind, &name).is_none() && copied {
            tally.replicated += 1;
            continue;
        }
        tally.names += 1;
        if compiled.id(kind, &name).is_none() {
            tally.failures.push(format!("{label}: MuJoCo has no {} named {name:?}", kind.name()));
        }
        let ns = if e.is_frame() {
            Namespace::AttachmentFrame
        } else {
            e.kind().namespace().unwrap_or(Namespace::Body)
        };
        let back = if e.is_frame() {
            model.from_full_name(Namespace::Body, &name)
        } else {
            model.from_full_name(ns, &name)
        };
        if back.as_ref() != Some(&e.loc()) {
            tally.failures.push(format!(
                "{label}: from_full_name({ns:?}, {name:?}) is {back:?}, not the <{}>",
                e.tag()
            ));
        }
    }
}

fn judge_layout(label: &str, model: &Model, compiled: &Compiled, tally: &mut Tally) {
    let layout = model.layout();
    if !layout.unexpanded.is_empty() {
        tally.unexpanded += 1;
        return;
    }
    let s = compiled.sizes();
    let ours = (layout.nq, layout.nv, layout.nu, layout.na);
    if ours != (s.nq, s.nv, s.nu, s.na) {
        tally.failures.push(format!(
            "{label}: layout (nq, nv, nu, na) = {ours:?}, MuJoCo's {:?}",
            (s.nq, s.nv, s.nu, s.na)
        ));
        return;
    }
    let (qposadr, dofadr, types) = (
        compiled.ints("jnt_qposadr").unwrap(),
        compiled.ints("jnt_dofadr").unwrap(),
        compiled.ints("jnt_type").unwrap(),
    );
    for j in &layout.joints {
        let e = model.get(&j.loc).unwrap();
        if inside(&e, "replicate") {
            continue;
        }
        let Ok(b) = compiled.bind(&j.loc) else {
            tally.failures.push(format!("{label}: joint {:?} not bound", e.full_name()));
            continue;
        };
        tally.joints += 1;
        let want_type = match j.joint_type {
            mjcf::JointType::Free => 0,
            mjcf::JointType::Ball => 1,
            mjcf::JointType::Slide => 2,
            mjcf::JointType::Hinge => 3,
        };
        let got = (qposadr[b.id()] as usize, dofadr[b.id()] as usize, types[b.id()]);
        if got != (j.qpos, j.dof, want_type) {
            tally.failures.push(format!(
                "{label}: joint {}: ours (qpos, dof, type) {:?}, MuJoCo's {got:?}",
                b.name(),
                (j.qpos, j.dof, want_type)
            ));
        }
    }
    let (ctrladr, actadr, actnum) = (
        compiled.ints("actuator_ctrladr").unwrap(),
        compiled.ints("actuator_actadr").unwrap(),
        compiled.ints("actuator_actnum").unwrap(),
    );
    for a in &layout.actuators {
        let Ok(b) = compiled.bind(&a.loc) else {
            tally.failures.push(format!("{label}: actuator at {:?} not bound", a.loc));
            continue;
        };
        tally.actuators += 1;
        let act = if a.nact == 0 { -1 } else { a.act as i32 };
        let got = (ctrladr[b.id()], actadr[b.id()], actnum[b.id()]);
        if got != (a.ctrl as i32, act, a.nact as i32) {
            tally.failures.push(format!(
                "{label}: actuator {}: ours (ctrl, act, nact) {:?}, MuJoCo's {got:?}",
                b.name(),
                (a.ctrl, act, a.nact)
            ));
        }
    }
}

fn repo() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn mujoco_agrees_with_names_and_layout_of_every_conformance_output() {
    let mujoco = mujoco();
    let mut tally = Tally::default();
    for dir in case::list_cases(&repo().join("tests/conformance/cases")).unwrap() {
        let c = case::load_case(&dir).unwrap();
        let (_, outputs) = replay::run_case_collecting(&c, None);
        for (file, model, options) in outputs {
            judge(&mujoco, &format!("{}/{file}", c.name), &model, &options, &mut tally);
        }
    }
    assert!(tally.models > 200, "{tally:?}");
    tally.report("conformance outputs");
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn mujoco_agrees_with_names_and_layout_of_generated_scenes() {
    use mjcf::generate::strategy;
    use proptest::strategy::{Strategy, ValueTree};
    use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
    let mujoco = mujoco();
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &[7; 32]);
    let mut runner = TestRunner::new_with_rng(Config::default(), rng);
    let (scenes, edits) = (strategy::scene_recipe(), strategy::scene_and_edits());
    let mut tally = Tally::default();
    for i in 0..300 {
        let models = if i % 2 == 0 {
            vec![scenes.new_tree(&mut runner).unwrap().current().build()]
        } else {
            let (r, e) = edits.new_tree(&mut runner).unwrap().current();
            e.apply(&r.build())
        };
        for (v, m) in models.iter().enumerate() {
            judge(
                &mujoco,
                &format!("generated {i} version {v}"),
                m,
                &WriteOptions::default(),
                &mut tally,
            );
        }
    }
    // Generated models are valid by construction: MuJoCo compiles every one.
    assert_eq!(tally.refused, 0, "{tally:?}");
    tally.report("generated scenes");
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn mujoco_agrees_with_names_and_layout_of_the_real_models() {
    let root = repo().join("../shared/realmodels/cases");
    assert!(root.is_dir(), "the real models are beside the checkout, in {}", root.display());
    let mujoco = mujoco();
    let mut tally = Tally::default();
    for dir in case::list_cases(&root).unwrap() {
        let c = case::load_case(&dir).unwrap();
        let (_, outputs) = replay::run_case_collecting(&c, None);
        for (file, model, options) in outputs {
            judge(&mujoco, &format!("{}/{file}", c.name), &model, &options, &mut tally);
        }
    }
    assert!(tally.models >= 179, "{tally:?}");
    tally.report("real models");
}

/// The compiled models' arrays two compiles of the same model must agree on (those
/// tools/readback_check.py compared): positions, orientations, masses and inertias,
/// sizes, joint ranges and axes, gains and biases, default poses, keyframes.
const FLOATS: &[&str] = &[
    "body_pos",
    "body_quat",
    "body_ipos",
    "body_iquat",
    "body_mass",
    "body_inertia",
    "jnt_pos",
    "jnt_axis",
    "jnt_range",
    "dof_damping",
    "dof_armature",
    "dof_frictionloss",
    "geom_size",
    "geom_pos",
    "geom_quat",
    "geom_friction",
    "site_pos",
    "site_size",
    "actuator_gear",
    "actuator_gainprm",
    "actuator_biasprm",
    "actuator_ctrlrange",
    "qpos0",
    "key_qpos",
    "key_ctrl",
    "tendon_stiffness",
];
const INTS: &[&str] = &[
    "body_parentid",
    "jnt_type",
    "geom_type",
    "geom_contype",
    "geom_conaffinity",
    "actuator_trntype",
    "actuator_trnid",
    "sensor_type",
    "sensor_objid",
];

/// The first difference between two compiled models, as MuJoCo sees them: sizes, the
/// names of every kind of element in order, and the arrays above, exactly.
pub(crate) fn compiled_difference(a: &Compiled, b: &Compiled) -> Option<String> {
    if a.sizes() != b.sizes() {
        return Some(format!("sizes {:?} vs {:?}", a.sizes(), b.sizes()));
    }
    for kind in ObjKind::ALL {
        let names = |m: &Compiled| -> Vec<Option<String>> {
            (0..m.count(kind)).map(|i| m.name(kind, i).map(str::to_string)).collect()
        };
        if a.count(kind) != b.count(kind) || names(a) != names(b) {
            return Some(format!("{} names: {:?} vs {:?}", kind.name(), names(a), names(b)));
        }
    }
    for field in FLOATS {
        let (x, y) = (a.floats(field).ok()?, b.floats(field).ok()?);
        if x.iter()
            .zip(y)
            .any(|(p, q)| p.to_bits() != q.to_bits() && (p - q).abs() > 1e-12 * p.abs().max(1.0))
        {
            return Some(format!("{field}: {x:?} vs {y:?}"));
        }
    }
    if a.floats32("geom_rgba").ok()? != b.floats32("geom_rgba").ok()? {
        return Some("geom_rgba differs".into());
    }
    for field in INTS {
        if a.ints(field).ok()? != b.ints(field).ok()? {
            return Some(format!("{field} differs"));
        }
    }
    None
}
