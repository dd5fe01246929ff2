//! MuJoCo judges `Model::check`: over generated scenes and their mutants (a reference
//! that names nothing, an array shorter than MuJoCo accepts, a moving body without
//! mass, a free joint beside another joint, a key longer than the model, and the
//! shapes composition makes: a model with a free body, a plane or a mocap body
//! attached at a site inside a moving body, inside a static body or in the world,
//! welded or not, each beside its accepted twin), `check()` reports a problem
//! exactly when MuJoCo refuses the model. (`advice()` is no such thing: MuJoCo
//! compiles what it points at.)
//! And over scenes of the wide generators (`Palette::Wide`: attachments at sites
//! anywhere, inside moving bodies, `<frame>`s and attached models; attached models
//! with free bodies and planes; frames with mixed joints and freejoints anywhere),
//! the same verdict for every scene as it is generated.

use crate::support;

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
    let nq = m.layout().unwrap().nq;
    let keys = m.section("keyframe").unwrap();
    if let Ok((v, _)) =
        m.add(&keys, element!("key", name = "mutant_long", qpos = vec![0.0; nq + 1]))
    {
        out.push((format!("a key with {} positions for {nq}", nq + 1), v));
    }
    out.extend(composed_mutants(m));
    out
}

/// The problems `check()` finds: each one MuJoCo refuses.
fn refusals(m: &Model) -> Vec<mjcf::Problem> {
    m.check()
}

/// A small model named `name` whose one top-level body holds `content` (and a geom).
fn part(name: &str, body: mjcf::Element) -> Model {
    let mut m = Model::new(name);
    m.add_mut(&m.worldbody(), body).expect("a body in the worldbody");
    m
}

/// The mutants composition makes of `m`: models attached at a site inside a moving
/// body, inside a static body and in the world; welded and not.
fn composed_mutants(m: &Model) -> Vec<(String, Model)> {
    let free = part(
        "mutant_ball",
        element!("body", name = "ball")
            .child(element!("freejoint"))
            .child(element!("geom", size = [0.1])),
    );
    let free_by_class = Model::from_xml_str(
        r#"<mujoco model="mutant_classy"><default><joint type="free"/></default>
           <worldbody><frame><body name="b"><joint/><geom size="0.1"/></body></frame></worldbody></mujoco>"#,
    )
    .expect("the model reads");
    let plane = part(
        "mutant_floor",
        element!("body", name = "floor")
            .child(element!("geom", type = "plane", size = [1.0, 1.0, 0.1])),
    );
    let mocap = part(
        "mutant_target",
        element!("body", name = "target", mocap = "true").child(element!("geom", size = [0.1])),
    );
    let w = m.worldbody();
    let mut out = Vec::new();
    let moving = element!("body", name = "mutant_arm", pos = [0.0, 0.0, 5.0])
        .child(element!("joint", name = "mutant_shoulder"))
        .child(element!("geom", size = [0.1]))
        .child(element!("site", name = "mutant_moving_site"));
    let still = element!("body", name = "mutant_post", pos = [0.0, 0.0, 5.0])
        .child(element!("geom", size = [0.1]))
        .child(element!("site", name = "mutant_still_site"));
    let world_site = element!("site", name = "mutant_world_site", pos = [0.0, 0.0, 5.0]);
    let Ok((m, _)) = m.add(&w, moving) else { return out };
    let Ok((m, _)) = m.add(&w, still) else { return out };
    let Ok((m, _)) = m.add(&w, world_site) else { return out };
    let at = |name: &str| m.find(mjcf::Namespace::Site, name).expect("the site was added");
    let parts = [
        ("a free body", &free),
        ("a body free by its class", &free_by_class),
        ("a plane", &plane),
        ("a mocap body", &mocap),
    ];
    for (what, child) in parts {
        for (place, site) in [
            ("a moving body", "mutant_moving_site"),
            ("a static body", "mutant_still_site"),
            ("the world", "mutant_world_site"),
        ] {
            if let Ok((v, _)) = m.attach(&at(site), child) {
                out.push((format!("{what} attached at a site of {place}"), v));
            }
            if let Ok((v, _)) = m.attach_welded(&at(site), child) {
                out.push((format!("{what} attached welded at a site of {place}"), v));
            }
        }
    }
    // Attachment frames are bodies: a mocap flag or joints given to one.
    let empty =
        part("mutant_empty", element!("body", name = "e").child(element!("geom", size = [0.1])));
    for (place, site) in
        [("a moving body", "mutant_moving_site"), ("the world", "mutant_world_site")]
    {
        let Ok((v, a)) = m.attach(&at(site), &empty) else { continue };
        if let Ok(v) = v.set_attr(a.frame(), "mocap", "true") {
            out.push((format!("a mocap attachment frame at a site of {place}"), v));
        }
        let ball_hinge = v
            .add(a.frame(), element!("joint", type = "ball"))
            .and_then(|(v, _)| v.add(a.frame(), element!("joint")));
        if let Ok((v, _)) = ball_hinge {
            out.push((
                format!("a ball then a hinge on an attachment frame at a site of {place}"),
                v,
            ));
        }
        if let Ok((v, _)) = v.add(a.frame(), element!("joint", type = "free")) {
            out.push((format!("a free joint on an attachment frame at a site of {place}"), v));
        }
    }
    // The same shapes written directly.
    let plane_in =
        |body: mjcf::Element| body.child(element!("geom", type = "plane", size = [1.0, 1.0, 0.1]));
    let shapes = [
        (
            "a plane in a moving body",
            plane_in(
                element!("body", name = "mutant_p")
                    .child(element!("joint"))
                    .child(element!("geom", size = [0.1])),
            ),
        ),
        ("a plane in a static body", plane_in(element!("body", name = "mutant_p"))),
        (
            "a free body in a body",
            element!("body", name = "mutant_p").child(
                element!("body").child(element!("freejoint")).child(element!("geom", size = [0.1])),
            ),
        ),
        (
            "a mocap body in a body",
            element!("body", name = "mutant_p")
                .child(element!("body", mocap = "true").child(element!("geom", size = [0.1]))),
        ),
        (
            "a mocap body in the world",
            element!("body", name = "mutant_p", mocap = "true")
                .child(element!("geom", size = [0.1])),
        ),
    ];
    for (what, body) in shapes {
        if let Ok((v, _)) = m.add(&w, body) {
            out.push((what.to_string(), v));
        }
    }
    out
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
                    ProblemKind::FreeJointNotTopLevel => "free joint not at top level",
                    ProblemKind::PlaneInMovingBody => "plane in a moving body",
                    ProblemKind::MocapNotFixedChildOfWorld => {
                        "mocap body not a fixed child of world"
                    }
                    ProblemKind::RotationAfterBall => "rotation after a ball joint",
                    ProblemKind::TooManyDofs { .. } => "too many dofs",
                    ProblemKind::KeyLength { .. } => "key too long",
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

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn models_attached_welded_inside_a_moving_body_compile_and_attached_plainly_are_refused() {
    let mujoco = mujoco();
    let arm = Model::from_xml_str(
        r#"<mujoco model="arm"><worldbody><body name="link"><joint/><geom size="0.1"/>
             <site name="tip"/></body></worldbody></mujoco>"#,
    )
    .unwrap();
    let tip = arm.find(mjcf::Namespace::Site, "tip").unwrap();
    let ball = part(
        "ball",
        element!("body", name = "b")
            .child(element!("freejoint"))
            .child(element!("geom", size = [0.1])),
    );
    let target = part(
        "target",
        element!("body", name = "t", mocap = "true").child(element!("geom", size = [0.1])),
    );
    for child in [&ball, &target] {
        let (plain, _) = arm.attach(&tip, child).unwrap();
        assert!(refused(&mujoco, &plain).unwrap() && !plain.check().is_empty(), "{}", child.name());
        let (welded, _) = arm.attach_welded(&tip, child).unwrap();
        assert!(!refused(&mujoco, &welded).unwrap(), "{} welded", child.name());
        assert!(welded.check().is_empty(), "{} welded", child.name());
    }
}

#[test]
#[ignore = "needs MuJoCo: set MUJOCO_LIB"]
fn check_agrees_with_mujoco_on_free_bodies_attached_inside_frames_and_replicates() {
    let mujoco = mujoco();
    let arena = Model::from_xml_str(
        r#"<mujoco model="arena"><worldbody>
             <frame pos="1 0 0"><site name="in_frame"/></frame>
             <replicate count="2" offset="1 0 0"><site name="in_replicate"/></replicate>
             <body name="post"><frame><site name="in_body_frame"/></frame></body>
           </worldbody></mujoco>"#,
    )
    .unwrap();
    let ball = part(
        "ball",
        element!("body", name = "b")
            .child(element!("freejoint"))
            .child(element!("geom", size = [0.1])),
    );
    let mut verdicts = Vec::new();
    for site in ["in_frame", "in_replicate", "in_body_frame"] {
        let at = arena.find(mjcf::Namespace::Site, site).unwrap();
        let (scene, _) = arena.attach(&at, &ball).unwrap();
        let refuses = refused(&mujoco, &scene).unwrap();
        assert_eq!(!scene.check().is_empty(), refuses, "{site}: {:?}", scene.check());
        verdicts.push((site, refuses));
    }
    // MuJoCo 4.0.0's verdicts: a world <frame> keeps the body top level; the writer
    // writes an attachment frame inside a <replicate> or a body as a body.
    assert_eq!(verdicts, [("in_frame", false), ("in_replicate", true), ("in_body_frame", true)]);
}

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
    eprintln!("{total} disagreements, by class:");
    for (key, c) in &classes {
        eprintln!("  {:5}  {key}", c.count);
    }
    for (key, c) in &classes {
        let (i, xml) = c.example.as_ref().unwrap();
        eprintln!("\n--- {key}: the smallest, scene {i} ---\n{xml}");
    }
    // Both verdicts are judged: the wide scenes reach refusals and compiled models.
    assert!(refused_count > 0 && refused_count < n, "MuJoCo refused {refused_count} of {n}");
    assert_eq!(total, 0, "check disagrees with MuJoCo on {total} wide scenes");
}
