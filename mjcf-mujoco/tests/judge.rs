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
//!   names in order, positions, masses, sizes, ranges, gains, default poses, keys);
//! - composed keys: reset to a key written with `merge_keyframes`, every attached
//!   floating base sits where its frame carries its pose in its own model's key.
//!
//! Each test prints its counts; a model MuJoCo refuses is counted apart (the corpus
//! holds a few whose reference output does not compile either) and never as passed.

use crate::case;
use crate::replay;
use crate::support;

use std::path::{Path, PathBuf};

use mjcf::{Event, Model, Namespace, WriteOptions};
use mjcf_mujoco::{Compiled, Error, MuJoCo, ObjKind, Physics};
use support::mujoco;

/// What judging one model found.
#[derive(Default, Debug)]
struct Tally {
    models: usize,
    refused: usize,
    /// Models MuJoCo compiles on which check() found nothing.
    checked: usize,
    names: usize,
    joints: usize,
    actuators: usize,
    /// Models whose read-back compiles to the same model.
    read_back: usize,
    /// Attached floating bases judged after a reset to a composed key (per key).
    keyed_bases: usize,
    /// Elements inside a `<replicate>`, whose copies MuJoCo names itself.
    replicated: usize,
    /// Models with elements the layout does not expand (`<attach>`, ...).
    unexpanded: usize,
    failures: Vec<String>,
}

impl Tally {
    fn report(&self, what: &str) {
        eprintln!(
            "{what}: {} models ({} refused by MuJoCo, {} with unexpanded elements; {} compiled with \
             an empty check()), {} names, {} joints, \
             {} actuators judged, {} read back to the same compiled model, {} floating bases \
             placed by a composed key; {} replicated elements not judged by name; {} failures",
            self.models,
            self.refused,
            self.unexpanded,
            self.checked,
            self.names,
            self.joints,
            self.actuators,
            self.read_back,
            self.keyed_bases,
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
    // MuJoCo compiles it: check() finds nothing (no false alarm on any model judged:
    // the conformance outputs, the real models and the generated scenes).
    let problems = model.check_with(options);
    if !problems.is_empty() {
        tally.failures.push(format!("{label}: MuJoCo compiles it, check() says {problems:?}"));
    }
    tally.checked += 1;
    judge_names(label, model, &compiled, tally);
    judge_layout(label, model, &compiled, tally);
    judge_read_back(mujoco, label, model, options, &compiled, tally);
    judge_keys(mujoco, label, model, tally);
}

/// A body's pose in the data: position and rotation matrix (row major).
fn pose_of(p: &Physics, b: &mjcf_mujoco::Bound) -> ([f64; 3], [f64; 9]) {
    let x = p.get(b, "xpos").unwrap();
    let r = p.get(b, "xmat").unwrap();
    ([x[0], x[1], x[2]], std::array::from_fn(|i| r[i]))
}

/// `a` then `b`: (pa + Ra pb, Ra Rb).
fn then(a: ([f64; 3], [f64; 9]), b: ([f64; 3], [f64; 9])) -> ([f64; 3], [f64; 9]) {
    let (pa, ra) = a;
    let (pb, rb) = b;
    let pos = std::array::from_fn(|r| pa[r] + (0..3).map(|i| ra[3 * r + i] * pb[i]).sum::<f64>());
    let rot =
        std::array::from_fn(|k| (0..3).map(|i| ra[3 * (k / 3) + i] * rb[3 * i + k % 3]).sum());
    (pos, rot)
}

/// The inverse of a pose.
fn inverse(a: ([f64; 3], [f64; 9])) -> ([f64; 3], [f64; 9]) {
    let (p, r) = a;
    let rt: [f64; 9] = std::array::from_fn(|k| r[3 * (k % 3) + k / 3]);
    let back = std::array::from_fn(|row| -(0..3).map(|i| rt[3 * row + i] * p[i]).sum::<f64>());
    (back, rt)
}

/// Composed keys (`merge_keyframes`) put every attached model's floating base where
/// its frame carries the base's pose in the model's own key: with F the frame's pose
/// (the base's pose in the composed model at rest, times the inverse of its pose in
/// its own model at rest), the base's pose after a reset to key k is F times its pose
/// in its own model after a reset to k.
fn judge_keys(mujoco: &MuJoCo, label: &str, model: &Model, tally: &mut Tally) {
    let merged = WriteOptions { merge_keyframes: true, ..WriteOptions::default() };
    let scopes = model.scope_paths();
    if scopes.is_empty() {
        return;
    }
    let Ok(composed) = mujoco.compile_with(model, &merged) else { return };
    for scope in &scopes {
        let child = model.attached(scope.as_str()).unwrap();
        let keys: Vec<String> = child
            .find_all(Namespace::Key)
            .iter()
            .filter_map(|k| child.get(k).ok()?.identifier().map(str::to_string))
            .collect();
        let layout = child.layout().unwrap();
        let bases: Vec<mjcf::Loc> = layout
            .joints
            .iter()
            .filter(|j| j.joint_type == mjcf::JointType::Free)
            .filter_map(|j| Some(child.get(&j.loc).ok()?.parent()?.loc()))
            .filter(|b| child.scope_path(b).is_some_and(|s| s.is_empty()))
            .collect();
        if keys.is_empty() || bases.is_empty() {
            continue;
        }
        let Ok(alone) = mujoco.compile_with(child, &merged) else { continue };
        let (mut c, mut a) = (Physics::new(&composed).unwrap(), Physics::new(&alone).unwrap());
        for base in &bases {
            let (Ok(bc), Ok(ba)) =
                (c.bind(model.locate_in(scope.as_str(), base).unwrap()), a.bind(base))
            else {
                continue;
            };
            c.reset().unwrap();
            c.forward().unwrap();
            a.reset().unwrap();
            a.forward().unwrap();
            let frame = then(pose_of(&c, &bc), inverse(pose_of(&a, &ba)));
            for k in &keys {
                c.reset_to_key(k).unwrap();
                c.forward().unwrap();
                a.reset_to_key(k).unwrap();
                a.forward().unwrap();
                let (want, got) = (then(frame, pose_of(&a, &ba)), pose_of(&c, &bc));
                let off = want.0.iter().chain(&want.1).zip(got.0.iter().chain(&got.1));
                if off.into_iter().any(|(x, y)| (x - y).abs() > 1e-6) {
                    tally.failures.push(format!(
                        "{label}: {scope}'s base {:?} after key {k}: {got:?}, its frame puts it at {want:?}",
                        bc.name()
                    ));
                }
                tally.keyed_bases += 1;
            }
        }
    }
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
            assert!(compiled.bind(e.loc()).is_err());
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
    let layout = model.layout().unwrap();
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
        let want_type = j.joint_type.mujoco_number();
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

/// `m` with a `home` key in every attached model: each free joint moved by a few
/// decimetres and turned, every other joint at its default.
fn with_home_keys(m: &Model, seed: usize) -> Model {
    let mut out = m.clone();
    for (n, scope) in m.scope_paths().iter().enumerate() {
        let child = m.attached(scope.as_str()).unwrap();
        let mut qpos = Vec::new();
        for (j, joint) in child.layout().unwrap().joints.iter().enumerate() {
            let t = (seed + n + j) as f64;
            match joint.joint_type {
                mjcf::JointType::Free => {
                    let (a, b) = (0.3 * (t * 0.7).sin(), 0.4 * (t * 1.3).cos());
                    let h = (t * 0.9).sin();
                    let (w, z) = (h.cos(), h.sin());
                    qpos.extend([a, b, 0.5 + 0.1 * t.cos(), w * 0.8, 0.6 * w, 0.0, z].map(|x| x));
                    let k = qpos.len();
                    let norm = qpos[k - 4..].iter().map(|x| x * x).sum::<f64>().sqrt();
                    for x in &mut qpos[k - 4..] {
                        *x /= norm;
                    }
                }
                mjcf::JointType::Ball => qpos.extend([1.0, 0.0, 0.0, 0.0]),
                _ => qpos.push(0.0),
            }
        }
        out.edit_attached_mut(scope.as_str(), |c| {
            let keys = c.section("keyframe").unwrap();
            c.add_mut(&keys, mjcf::element!("key", name = "home", qpos = qpos))
        })
        .unwrap();
    }
    out
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
    // The generators make neither keys nor floating bases in attached models: give
    // generated models a floating base and a `home` key that moves and turns it,
    // attach each twice at turned sites, and judge the composed keys.
    let plain = strategy::model_recipe();
    let mut keyed = Tally::default();
    for i in 0..60 {
        let mut child = plain.new_tree(&mut runner).unwrap().current().build();
        let w = child.worldbody();
        let base = mjcf::element!("body", name = "judge_base", pos = [0.0, 0.0, 1.0])
            .child(mjcf::element!("freejoint"))
            .child(mjcf::element!("geom", size = [0.1]));
        if child.add_mut(&w, base).is_err() {
            continue;
        }
        let mut arena = Model::new("arena");
        let w = arena.worldbody();
        let h = i as f64;
        let sites = [
            mjcf::element!(
                "site",
                name = "s0",
                pos = [h, 0.0, 0.0],
                euler = [10.0 * h, 20.0, 30.0]
            ),
            mjcf::element!("site", name = "s1", pos = [0.0, h, 1.0], quat = [0.5, 0.5, 0.5, 0.5]),
        ];
        for site in sites {
            let site = arena.add_mut(&w, site).unwrap();
            arena.attach_mut(&site, &child).unwrap();
        }
        let scene = with_home_keys(&arena, i);
        let label = format!("generated model {i}, floating, attached twice");
        judge(&mujoco, &label, &scene, &WriteOptions::default(), &mut keyed);
    }
    assert!(keyed.keyed_bases >= 100, "composed keys judged on {} bases only", keyed.keyed_bases);
    keyed.report("generated models with floating bases and keys");
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

/// The compiled models' arrays two compiles of the same model must agree on: the
/// support's list, and keyframes.
fn judged_floats() -> Vec<&'static str> {
    let mut floats = support::COMPARED_FLOATS.to_vec();
    floats.extend(["key_qpos", "key_ctrl"]);
    floats
}

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
    support::array_difference(a, b, &judged_floats())
}
