//! MuJoCo judges `Model::check`: over generated scenes and their mutants (a reference
//! that names nothing, an array shorter than MuJoCo accepts, a moving body without
//! mass, a free joint beside another joint, a key longer than the model), `check()`
//! reports a problem of a kind MuJoCo refuses exactly when MuJoCo refuses the model.
//! (`UncomposedKey` is no such kind: MuJoCo compiles the key, on the wrong joints.)
//! And over scenes of the wide generators (`Palette::Wide`: attachments at sites
//! anywhere, inside moving bodies, `<frame>`s and attached models; attached models
//! with free bodies and planes; frames with mixed joints and freejoints anywhere),
//! the same verdict for every scene as it is generated.

mod support;

use mjcf::{AttrType, Event, Model, ProblemKind, Value, element};
use mjcf_mujoco::{Error, MuJoCo};
use proptest::strategy::{Strategy, ValueTree};
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use support::mujoco;

/// Whether MuJoCo refuses the model; other failures are the test's.
fn refused(mujoco: &MuJoCo, m: &Model) -> Result<bool, String> {
    refusal(mujoco, m).map(|r| r.is_some())
}

/// MuJoCo's message when it refuses the model (its first line); other failures are
/// the test's.
fn refusal(mujoco: &MuJoCo, m: &Model) -> Result<Option<String>, String> {
    match mujoco.compile(m) {
        Ok(_) => Ok(None),
        Err(Error::Compile(e)) => Ok(Some(e.message.lines().next().unwrap_or("").to_string())),
        Err(e) => Err(e.to_string()),
    }
}

/// The mutants of `m`: (what, model), a few of each kind.
fn mutants(m: &Model) -> Vec<(String, Model)> {
    let mut out = Vec::new();
    let (mut refs, mut arrays) = (0, 0);
    for event in m.walk() {
        let Event::Enter(e) = event else { continue };
        // Elements of attached models and default classes are left alone (a
        // default's reference or array is checked where it is used).
        if !e.scope().is_empty() || e.parent().is_some_and(|p| p.tag() == "default") {
            continue;
        }
        for (name, value) in e.attrs() {
            let i = e.kind().attr_index(name).unwrap_or(0);
            let ty = &e.kind().attr(i).ty;
            if refs < 3
                && matches!(ty, AttrType::Reference(_))
                && name != "class"
                && name != "childclass"
            {
                if let Ok(v) = m.set_attr(&e.loc(), name, "no_such_name") {
                    out.push((format!("<{}> {name}=\"no_such_name\"", e.tag()), v));
                    refs += 1;
                }
            }
            let len = match value {
                Value::Floats(xs) => xs.len(),
                _ => continue,
            };
            if arrays < 3 && len > 1 {
                let shorter: Vec<f64> = value.as_floats().unwrap()[..len - 1].to_vec();
                if let Ok(v) = m.set_attr(&e.loc(), name, shorter) {
                    out.push((format!("<{}> {name} cut to {} numbers", e.tag(), len - 1), v));
                    arrays += 1;
                }
            }
        }
    }
    let w = m.worldbody();
    let body = element!("body", name = "mutant_massless", pos = [0.0, 0.0, 5.0])
        .child(element!("joint", name = "mutant_hinge"));
    if let Ok((v, _)) = m.add(&w, body) {
        out.push(("a moving body without mass".into(), v));
    }
    let body = element!("body", name = "mutant_free", pos = [0.0, 0.0, 5.0])
        .child(element!("joint", name = "mutant_slide", type = "slide"))
        .child(element!("freejoint", name = "mutant_freejoint"))
        .child(element!("geom", size = [0.1]));
    if let Ok((v, _)) = m.add(&w, body) {
        out.push(("a free joint beside another joint".into(), v));
    }
    let nq = m.layout().nq;
    let keys = m.section("keyframe").unwrap();
    if let Ok((v, _)) =
        m.add(&keys, element!("key", name = "mutant_long", qpos = vec![0.0; nq + 1]))
    {
        out.push((format!("a key with {} positions for {nq}", nq + 1), v));
    }
    out
}

/// The problems of kinds MuJoCo refuses.
fn refusals(m: &Model) -> Vec<mjcf::Problem> {
    m.check().into_iter().filter(|p| !matches!(p.kind, ProblemKind::UncomposedKey)).collect()
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn check_reports_a_problem_exactly_when_mujoco_refuses() {
    let mujoco = mujoco();
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &[11; 32]);
    let mut runner = TestRunner::new_with_rng(Config::default(), rng);
    let scenes = mjcf::generate::strategy::scene_recipe();
    let (mut judged, mut caught, mut disagreements) = (0, 0, Vec::new());
    let mut by_kind = std::collections::BTreeMap::<&str, usize>::new();
    for i in 0..150 {
        let m = scenes.new_tree(&mut runner).unwrap().current().build();
        assert!(refusals(&m).is_empty() && !refused(&mujoco, &m).unwrap(), "generated {i}");
        for (what, v) in mutants(&m) {
            judged += 1;
            let problems = refusals(&v);
            let refuses = refused(&mujoco, &v).unwrap();
            caught += usize::from(refuses);
            for p in &problems {
                let kind = match p.kind {
                    ProblemKind::DanglingReference { .. } => "dangling reference",
                    ProblemKind::ArrayTooShort { .. } => "array too short",
                    ProblemKind::MasslessMovingBody => "massless moving body",
                    _ => "other",
                };
                *by_kind.entry(kind).or_default() += 1;
            }
            if problems.is_empty() == refuses {
                disagreements.push(format!(
                    "generated {i}, {what}: check says {:?}, MuJoCo {}",
                    problems.iter().map(|p| p.to_string()).collect::<Vec<_>>(),
                    if refuses { "refuses it" } else { "compiles it" }
                ));
            }
        }
    }
    eprintln!(
        "{judged} mutants of 150 generated scenes judged, {caught} refused by MuJoCo; check found {by_kind:?}; {} disagreements",
        disagreements.len()
    );
    assert!(
        disagreements.is_empty(),
        "{}",
        disagreements[..disagreements.len().min(20)].join("\n")
    );
}

/// The MuJoCo refusals that `check` does not report yet, while its rules for them are
/// being written: a free joint below a moving body (an attached model's free body, or
/// an attachment frame's freejoint, inside a moving body) and a plane in a moving
/// body. A scene MuJoCo refuses with one of these messages while `check` finds
/// nothing is counted and shown, and does not fail the test. DELETE THIS CONSTANT
/// (and its one use) when `check` has those rules.
const EXPECTED_UNTIL_CHECK_RULES_LAND: &[&str] =
    &["free joint can only be used on top level", "plane only allowed in static bodies"];

/// How many wide scenes the judge compiles: `MJCF_JUDGE_SCENES`, else 2,000.
fn wide_scene_count() -> usize {
    std::env::var("MJCF_JUDGE_SCENES").ok().and_then(|n| n.parse().ok()).unwrap_or(2000)
}

/// One kind of disagreement: how often, and the smallest scene that shows it.
#[derive(Default)]
struct Class {
    count: usize,
    example: Option<(usize, String)>,
}

/// Every wide scene gets both verdicts, check's and MuJoCo's, and they agree; the
/// summary (run with `--nocapture` to see it when the test passes) counts MuJoCo's
/// refusals by message and the disagreements by class, with the smallest scene of
/// each as MJCF.
#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn check_agrees_with_mujoco_on_every_wide_scene() {
    let mujoco = mujoco();
    let rng = TestRng::from_seed(RngAlgorithm::ChaCha, &[27; 32]);
    let mut runner = TestRunner::new_with_rng(Config::default(), rng);
    let scenes = mjcf::generate::strategy::scene_recipe_in(mjcf::generate::Palette::Wide);
    let n = wide_scene_count();
    let (mut refused_count, mut reported) = (0, 0);
    // Disagreements by what MuJoCo says (or what check says, when MuJoCo compiles).
    let mut classes = std::collections::BTreeMap::<String, Class>::new();
    let mut by_message = std::collections::BTreeMap::<String, usize>::new();
    let mut unexpected = 0;
    for i in 0..n {
        let m = scenes.new_tree(&mut runner).unwrap().current().build();
        let problems = refusals(&m);
        let refusal = refusal(&mujoco, &m).unwrap_or_else(|e| panic!("scene {i}: {e}"));
        refused_count += usize::from(refusal.is_some());
        reported += usize::from(!problems.is_empty());
        if let Some(msg) = &refusal {
            *by_message.entry(msg.clone()).or_default() += 1;
        }
        let key = match (&refusal, problems.first()) {
            (Some(msg), None) => format!("MuJoCo refuses, check finds nothing: {msg}"),
            (None, Some(p)) => format!("MuJoCo compiles, check reports: {:?}", p.kind),
            _ => continue,
        };
        let expected = refusal.as_ref().is_some_and(|msg| {
            problems.is_empty() && EXPECTED_UNTIL_CHECK_RULES_LAND.iter().any(|e| msg.contains(e))
        });
        unexpected += usize::from(!expected);
        let class = classes.entry(key).or_default();
        class.count += 1;
        let xml = m.to_xml_string().unwrap();
        if class.example.as_ref().is_none_or(|(_, x)| xml.len() < x.len()) {
            class.example = Some((i, xml));
        }
    }
    eprintln!(
        "{n} wide scenes: MuJoCo refused {refused_count}, check reported problems in {reported}; \
         MuJoCo's refusals: {by_message:#?}"
    );
    let total: usize = classes.values().map(|c| c.count).sum();
    eprintln!("{total} disagreements ({unexpected} not expected), by class:");
    for (key, c) in &classes {
        eprintln!("  {:5}  {key}", c.count);
    }
    for (key, c) in &classes {
        let (i, xml) = c.example.as_ref().unwrap();
        eprintln!("\n--- {key}: the smallest, scene {i} ---\n{xml}");
    }
    // Both verdicts are judged: the wide scenes reach refusals and compiled models.
    assert!(refused_count > 0 && refused_count < n, "MuJoCo refused {refused_count} of {n}");
    assert_eq!(unexpected, 0, "check disagrees with MuJoCo outside the expected classes");
}
