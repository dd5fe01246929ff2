//! Composed scenes saved as MuJoCo reads them (`Model::save_scene`) and reopened
//! composed (`Model::from_path`): the rules of what reopens and what stays an element,
//! flat files that stay literal, and the round trip over every conformance output
//! with attachments. (Generated scenes with edits: `src/xml/scene/tests.rs`.)

use crate::case;
use crate::replay;

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use mjcf::{Event, ExportError, Model, Namespace, attrs, element};

/// A fresh folder under the system's temp folder (nothing there yet).
fn temp_dir(tag: &str) -> PathBuf {
    static N: AtomicUsize = AtomicUsize::new(0);
    let n = N.fetch_add(1, Ordering::Relaxed);
    let p = std::env::temp_dir().join(format!("mjcf-scenes-{}-{tag}-{n}", std::process::id()));
    let _ = std::fs::remove_dir_all(&p);
    p
}

/// A robot with a body, a joint, a geom, an actuator and a key.
fn robot(name: &str) -> Model {
    let mut m = Model::new(name);
    let torso =
        m.add_mut(&m.worldbody(), element!("body", name = "torso", pos = [0, 0, 1])).unwrap();
    m.add_mut(&torso, element!("joint", name = "hinge", axis = [0, 0, 1])).unwrap();
    m.add_mut(&torso, element!("geom", size = [0.1])).unwrap();
    m.add_mut(&m.actuator(), element!("motor", name = "m", joint = "hinge")).unwrap();
    m
}

/// An arena with a floor and `n` sites on a line.
fn arena(n: usize) -> (Model, Vec<mjcf::Loc>) {
    let mut a = Model::new("arena");
    a.add_mut(&a.worldbody(), element!("geom", name = "floor", type = "plane", size = [5, 5, 0.1]))
        .unwrap();
    let sites = (0..n)
        .map(|i| {
            let site = element!("site", name = format!("s{i}"), pos = [i as f64, 0.0, 0.0]);
            a.add_mut(&a.worldbody(), site).unwrap()
        })
        .collect();
    (a, sites)
}

/// Saves `m` as a scene in a fresh folder and reads it back.
fn save_and_reopen(m: &Model, tag: &str) -> (Model, PathBuf) {
    let dir = temp_dir(tag);
    let saved = m.save_scene(&dir, "scene.xml").unwrap();
    assert_eq!(saved.path(), dir.join("scene.xml"));
    let back = Model::from_path(saved.path()).unwrap();
    (back, dir)
}

/// The scope paths of the composition in document order (the frames in the order the
/// walk meets them).
fn document_order(m: &Model) -> Vec<String> {
    m.walk()
        .filter_map(|e| match e {
            Event::Enter(e) if e.is_frame() => {
                e.full_name().map(|n| n.trim_end_matches('/').to_string())
            }
            _ => None,
        })
        .collect()
}

/// Whether every model of the composition has its attachments in document order.
fn attached_in_document_order(m: &Model) -> bool {
    let doc = document_order(m);
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

/// Whether a model of the composition has a root default class with a name of its
/// own, which a part file written by the plain writer keeps as a class inside an
/// unnamed root class (README, "Scenes").
fn named_root_class(m: &Model) -> bool {
    let named = |m: &Model| m.get(&m.default_class()).unwrap().identifier().is_some();
    named(m) || m.scope_paths().iter().any(|p| named(m.attached(p.as_str()).unwrap()))
}

/// The round trip of item 4: `Ok(true)` when the reopened model has the same scope
/// paths and writes the same composed MJCF; `Ok(false)` when the model attached out
/// of document order (then the reopened model holds the same scopes, attached in
/// document order) or has a named root class (then saving the reopened model and
/// reopening it is a fixed point); `Err` otherwise.
fn round_trip(m: &Model, tag: &str) -> Result<bool, String> {
    let (back, dir) = save_and_reopen(m, tag);
    std::fs::remove_dir_all(&dir).unwrap();
    lossless_fixed_point(&back, tag)?;
    let (w1, w2) = (m.to_xml_string().unwrap(), back.to_xml_string().unwrap());
    if m.scope_paths() == back.scope_paths() && w1 == w2 {
        return Ok(true);
    }
    if m.scope_paths() == back.scope_paths() && named_root_class(m) {
        let (again, dir) = save_and_reopen(&back, tag);
        std::fs::remove_dir_all(&dir).unwrap();
        if again.scope_paths() == back.scope_paths() && again.to_xml_string().unwrap() == w2 {
            return Ok(false);
        }
    }
    let (mut a, mut b) = (m.scope_paths(), back.scope_paths());
    a.sort();
    b.sort();
    if a == b && !attached_in_document_order(m) && document_order(&back) == document_order(m) {
        return Ok(false);
    }
    Err(format!("scopes {:?} vs {:?}\n{w1}\n---\n{w2}", m.scope_paths(), back.scope_paths()))
}

/// The lossless save of a reopened scene: every file as read (`changed` false), and
/// saved elsewhere (`save_as`) it reopens with the same scope paths and composed
/// MJCF, and saves the same texts again.
fn lossless_fixed_point(back: &Model, tag: &str) -> Result<(), String> {
    let texts = back.to_source_files().map_err(|e| format!("lossless save: {e}"))?;
    if let Some(f) = texts.iter().find(|f| f.changed) {
        return Err(format!("{:?} changed on a save without edits:\n{}", f.path, f.text));
    }
    let dir = temp_dir(&format!("{tag}-lossless"));
    back.save_as(&dir).map_err(|e| format!("save_as: {e}"))?;
    let again = Model::from_path(dir.join("scene.xml")).map_err(|e| format!("reopen: {e}"))?;
    let again_texts = again.to_source_files().map_err(|e| format!("save again: {e}"));
    std::fs::remove_dir_all(&dir).unwrap();
    let (w1, w2) = (back.to_xml_string().unwrap(), again.to_xml_string().unwrap());
    if again.scope_paths() != back.scope_paths() || w1 != w2 {
        return Err(format!("saved losslessly and reopened:\n{w1}\n---\n{w2}"));
    }
    let same = |a: &[mjcf::SourceText], b: &[mjcf::SourceText]| {
        a.iter().map(|f| (&f.path, &f.text)).eq(b.iter().map(|f| (&f.path, &f.text)))
    };
    if !same(&texts, &again_texts?) {
        return Err("saved again, the texts differ".to_string());
    }
    Ok(())
}

#[test]
fn every_conformance_output_with_attachments_saves_and_reopens_composed() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/conformance/cases");
    let (mut same, mut reordered, mut scopes) = (0, 0, 0);
    let mut failures = Vec::new();
    for dir in case::list_cases(&root).unwrap() {
        let c = case::load_case(&dir).unwrap();
        let (_, outputs) = replay::run_case_collecting(&c, None);
        for (file, model, _) in outputs {
            if model.scope_paths().is_empty() {
                continue;
            }
            scopes += model.scope_paths().len();
            match round_trip(&model, &c.name) {
                Ok(true) => same += 1,
                Ok(false) => reordered += 1,
                Err(e) => failures.push(format!("{}/{file}: {e}", c.name)),
            }
        }
    }
    eprintln!(
        "conformance outputs with attachments: {same} reopened the same, {reordered} attached out of document order or with a named root class, {scopes} attachments, {} failed",
        failures.len()
    );
    assert!(failures.is_empty(), "{}", failures.join("\n\n"));
    assert!(same > 50, "only {same} outputs with attachments");
}

#[test]
fn reopened_scene_detaches_renames_and_edits_its_attachments() {
    let r = robot("robot");
    let (mut scene, sites) = arena(3);
    for s in &sites {
        scene.attach_mut(s, &r).unwrap();
    }
    let (back, dir) = save_and_reopen(&scene, "edits");
    assert_eq!(back.scopes().collect::<Vec<_>>(), ["robot", "robot_1", "robot_2"]);
    // One file, one value: the three attachments share it.
    assert!(back.attached("robot").unwrap().ptr_eq(back.attached("robot_2").unwrap()));
    assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 2, "scene.xml and robot.xml");
    // detach gives the model without it, as detaching from the original does.
    let detached = back.detach("robot_1").unwrap();
    assert_eq!(
        detached.to_xml_string().unwrap(),
        scene.detach("robot_1").unwrap().to_xml_string().unwrap()
    );
    // rename_scope renames every name of the attachment.
    let renamed = back.rename_scope("robot_2", "left").unwrap();
    assert!(renamed.find(Namespace::Body, "left/torso").is_some());
    assert!(renamed.find(Namespace::Body, "robot_2/torso").is_none());
    // edit_attached reaches into the reopened value (the others keep theirs).
    let edited = back
        .edit_attached("robot", |m| {
            let t = m.find(Namespace::Body, "torso").unwrap();
            m.set(&t, attrs!(pos = [0, 0, 2]))
        })
        .unwrap();
    let changes = back.diff(&edited);
    assert_eq!(changes.len(), 1, "{changes:?}");
    let torso = back.find(Namespace::Body, "robot/torso").unwrap();
    assert!(
        matches!(&changes[0], mjcf::Change::AttrChanged { loc, attribute: "pos", .. } if *loc == torso),
        "{changes:?}"
    );
    assert_eq!(
        edited.floats(&edited.find(Namespace::Body, "robot_1/torso").unwrap(), "pos").unwrap(),
        [0.0, 0.0, 1.0]
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn nested_scenes_nest_and_shared_values_share_one_file() {
    let mut hand = Model::new("hand");
    hand.add_mut(&hand.worldbody(), element!("body", name = "palm")).unwrap();
    let mut arm = Model::new("arm");
    let ee = arm.add_mut(&arm.worldbody(), element!("site", name = "ee")).unwrap();
    arm.attach_mut(&ee, &hand).unwrap();
    let (mut scene, sites) = arena(2);
    for s in &sites {
        let a = scene.attach_mut(s, &arm).unwrap();
        scene.add_mut(a.frame(), element!("joint", type = "slide")).unwrap();
    }
    // A second, different value named `arm`: its own file.
    let other = arm.with_name("arm");
    let other = other.add(&other.worldbody(), element!("geom", size = [0.2])).unwrap().0;
    scene.attach_mut(&scene.worldbody(), &other).unwrap();
    let dir = temp_dir("nested");
    let saved = scene.save_scene(&dir, "scene.xml").unwrap();
    let names: Vec<String> = saved
        .parts()
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names, ["arm.xml", "arm_1.xml", "hand.xml"]);
    let back = Model::from_path(saved.path()).unwrap();
    assert_eq!(back.scope_paths(), scene.scope_paths());
    assert_eq!(back.to_xml_string().unwrap(), scene.to_xml_string().unwrap());
    // Both arms hold the one hand value, as before saving.
    let h0 = back.attached("arm/hand").unwrap();
    assert!(h0.ptr_eq(back.attached("arm_2/hand").unwrap()));
    assert!(!back.attached("arm").unwrap().ptr_eq(back.attached("arm_2").unwrap()));
    assert!(back.attached("arm").unwrap().ptr_eq(back.attached("arm_1").unwrap()));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn the_parent_carries_the_merged_settings_and_the_parts_their_own() {
    let r = robot("robot");
    let opt = r.section("option").unwrap();
    let r = r.set(&opt, attrs!(impratio = 100, cone = "elliptic")).unwrap();
    let (mut scene, sites) = arena(1);
    scene.attach_mut(&sites[0], &r).unwrap();
    let parts = scene.to_scene("scene.xml").unwrap();
    let root = parts.root().to_xml_string().unwrap();
    assert!(root.contains(r#"<option impratio="100" cone="elliptic"/>"#), "{root}");
    let part = parts.parts()[0].model().to_xml_string().unwrap();
    assert!(part.contains(r#"<option impratio="100" cone="elliptic"/>"#), "{part}");
    let (back, dir) = save_and_reopen(&scene, "settings");
    assert_eq!(back.to_xml_string().unwrap(), scene.to_xml_string().unwrap());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_floating_model_is_attached_in_a_mujoco_frame_and_reopens() {
    let mut ball = Model::new("ball");
    let b = ball.add_mut(&ball.worldbody(), element!("body", name = "b", pos = [0, 0, 1])).unwrap();
    ball.add_mut(&b, element!("freejoint")).unwrap();
    ball.add_mut(&b, element!("geom", size = [0.1])).unwrap();
    let (mut scene, sites) = arena(2);
    scene.attach_mut(&sites[0], &ball).unwrap();
    let a = scene.attach_mut(&sites[1], &ball).unwrap();
    // A frame with a freejoint is a body (the ball's bodies below it).
    let mut robot_scene = scene.clone();
    robot_scene.attach_mut(&robot_scene.worldbody(), &robot("robot")).unwrap();
    let r = robot_scene.scopes().last().unwrap().to_string();
    robot_scene
        .add_mut(
            &robot_scene.lookup(Namespace::AttachmentFrame, &r).unwrap(),
            element!("freejoint"),
        )
        .unwrap();
    let root = robot_scene.to_scene("scene.xml").unwrap().root().to_xml_string().unwrap();
    assert!(root.contains(r#"<frame name="ball/" pos="0 0 0">"#), "{root}");
    assert!(root.contains("<body name=\"robot/\">\n      <freejoint name=\"robot/\"/>"), "{root}");
    assert_eq!(round_trip(&robot_scene, "frame"), Ok(true));
    let _ = a;
}

/// Writes `files` (name, text) into a fresh folder and reads `scene.xml` from it.
fn read_scene(tag: &str, files: &[(&str, &str)]) -> Model {
    let dir = temp_dir(tag);
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    let m = Model::from_path(dir.join("scene.xml")).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    m
}

const CHILD: &str = r#"<mujoco model="robot">
  <worldbody><body name="torso"><joint name="hinge"/><geom size="0.1"/></body></worldbody>
</mujoco>"#;

/// A scene holding `body` (an element of the worldbody) and the asset model `robot`.
fn scene_with(body: &str) -> String {
    format!(
        r#"<mujoco model="arena"><asset><model name="robot" file="robot.xml"/></asset>
  <worldbody>{body}</worldbody></mujoco>"#
    )
}

#[test]
fn what_reopens_has_exactly_the_saved_shape() {
    let ok = r#"<body name="r/" pos="1 0 0"><joint name="r/" type="slide"/><joint name="r/j/"/><attach model="robot" prefix="r/"/></body>"#;
    let m = read_scene("shape", &[("scene.xml", &scene_with(ok)), ("robot.xml", CHILD)]);
    assert_eq!(m.scopes().collect::<Vec<_>>(), ["r"]);
    assert!(m.find(Namespace::Body, "r/torso").is_some());
    let xml = m.to_xml_string().unwrap();
    assert!(xml.contains(r#"<joint name="r/" class="/" type="slide"/>"#), "{xml}");
    assert!(xml.contains(r#"<joint name="r/j/" class="/"/>"#), "{xml}");
    // The asset model only the attachment used is gone.
    assert!(!xml.contains("<model "), "{xml}");
}

/// Each `<attach>` our attachments cannot express stays an element: the model reads
/// as it always did, with its literal names and no attachment.
#[test]
fn attaches_that_attachments_cannot_express_stay_elements() {
    let cases = [
        (
            "a body= subtree",
            r#"<body name="r/"><attach model="robot" body="torso" prefix="r/"/></body>"#,
        ),
        ("a prefix without /", r#"<body name="r"><attach model="robot" prefix="r"/></body>"#),
        (
            "a prefix that is a path",
            r#"<body name="a/r/"><attach model="robot" prefix="a/r/"/></body>"#,
        ),
        (
            "a prefix unlike the body's name",
            r#"<body name="x/"><attach model="robot" prefix="r/"/></body>"#,
        ),
        (
            "other content in the body",
            r#"<body name="r/"><geom size="1"/><attach model="robot" prefix="r/"/></body>"#,
        ),
        (
            "a second attach",
            r#"<body name="r/"><attach model="robot" prefix="r/"/><attach model="robot" prefix="r/"/></body>"#,
        ),
        (
            "a body attribute a frame has not",
            r#"<body name="r/" gravcomp="1"><attach model="robot" prefix="r/"/></body>"#,
        ),
        (
            "a joint no frame joint is named",
            r#"<body name="r/"><joint name="knee"/><attach model="robot" prefix="r/"/></body>"#,
        ),
        (
            "an unnamed joint before the one named r/",
            r#"<body name="r/"><joint/><joint name="r/"/><attach model="robot" prefix="r/"/></body>"#,
        ),
        (
            "joints after the attach",
            r#"<body name="r/"><attach model="robot" prefix="r/"/><joint name="r/"/></body>"#,
        ),
        ("an attach in the worldbody", r#"<attach model="robot" prefix="r/"/>"#),
        (
            "a frame where the writer writes a body",
            r#"<frame name="r/"><attach model="robot" prefix="r/"/></frame>"#,
        ),
        (
            "a literal name in the scope",
            r#"<body name="r/"><attach model="robot" prefix="r/"/></body><geom name="r/g" size="1"/>"#,
        ),
        (
            "inside a replicate",
            r#"<replicate count="2" offset="1 0 0"><body name="r/"><attach model="robot" prefix="r/"/></body></replicate>"#,
        ),
    ];
    for (what, body) in cases {
        let m = read_scene("literal", &[("scene.xml", &scene_with(body)), ("robot.xml", CHILD)]);
        assert_eq!(m.scopes().count(), 0, "{what}: reopened");
        let xml = m.to_xml_string().unwrap();
        assert!(xml.contains("<attach "), "{what}: the attach is gone\n{xml}");
        assert!(xml.contains(r#"<model name="robot""#), "{what}: the asset is gone\n{xml}");
    }
}

/// MuJoCo keeps the parent's settings where a child's differ; a composition would
/// merge the child's into the parent's. A scene whose parent does not already hold
/// them stays as it is.
#[test]
fn a_part_whose_settings_the_parent_does_not_hold_stays_an_element() {
    let child = r#"<mujoco model="robot"><option impratio="100"/>
  <worldbody><body name="torso"><geom size="0.1"/></body></worldbody></mujoco>"#;
    let body = r#"<body name="r/"><attach model="robot" prefix="r/"/></body>"#;
    let m = read_scene("settings-no", &[("scene.xml", &scene_with(body)), ("robot.xml", child)]);
    assert_eq!(m.scopes().count(), 0);
    let held = scene_with(body).replace("<asset>", r#"<option impratio="100"/><asset>"#);
    let m = read_scene("settings-yes", &[("scene.xml", &held), ("robot.xml", child)]);
    assert_eq!(m.scopes().collect::<Vec<_>>(), ["r"]);
}

/// A composed model written as one flat file reads back as one model with literal
/// names: never as attachments (the module documentation of `xml::scene::reopen` says
/// why), so no edit can take the parent's own `robot/...` names for an attachment's.
#[test]
fn a_flat_file_never_reopens_composed() {
    let (mut scene, sites) = arena(2);
    let r = robot("robot");
    scene.attach_mut(&sites[0], &r).unwrap();
    scene.attach_mut(&sites[1], &r).unwrap();
    let flat = scene.to_xml_string().unwrap();
    let back = Model::from_xml_str(&flat).unwrap();
    assert_eq!(back.scopes().count(), 0);
    assert!(back.detach("robot").is_err());
    let torso = back.find(Namespace::Body, "robot/torso").unwrap();
    assert!(!torso.is_scoped(), "a literal name of the flat model");
    assert_eq!(back.to_xml_string().unwrap(), flat);
    // Written to a file and read from its path: the same.
    let dir = temp_dir("flat");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("flat.xml"), &flat).unwrap();
    let back = Model::from_path(dir.join("flat.xml")).unwrap();
    assert_eq!(back.scopes().count(), 0);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn part_file_names_are_distinct_and_never_the_scene_s() {
    let mut scene = Model::new("arena");
    // A model named like the scene's file, one with characters no file name takes,
    // and two different values of one name.
    for name in ["scene", "a b/../c", "robot"] {
        scene.attach_mut(&scene.worldbody(), &Model::new(&name.replace('/', "_"))).unwrap();
    }
    let other = Model::new("robot").with_name("robot");
    let other = other.add(&other.worldbody(), element!("geom", size = [1])).unwrap().0;
    scene.attach_mut(&scene.worldbody(), &other).unwrap();
    let s = scene.to_scene("scene.xml").unwrap();
    let names: Vec<&str> = s.parts().iter().map(|p| p.file_name()).collect();
    assert_eq!(names, ["scene_1.xml", "a_b_.._c.xml", "robot.xml", "robot_1.xml"]);
    assert_eq!(round_trip(&scene, "names"), Ok(true));
}

#[test]
fn saving_refuses_a_bad_file_name_and_writes_nothing() {
    let (mut scene, sites) = arena(1);
    scene.attach_mut(&sites[0], &robot("robot")).unwrap();
    let dir = temp_dir("bad-name");
    for bad in ["", "../scene.xml", "a/scene.xml", ".", "a\0.xml"] {
        let e = scene.save_scene(&dir, bad).unwrap_err();
        assert!(
            matches!(
                e,
                ExportError::Io { kind: std::io::ErrorKind::InvalidInput, .. }
                    | ExportError::Write(_)
            ),
            "{bad}: {e:?}"
        );
        assert!(!dir.exists(), "{bad}: the folder was created");
    }
    // The scene may take a part's name: the part takes another.
    let saved = scene.save_scene(&dir, "robot.xml").unwrap();
    assert_eq!(saved.parts(), [dir.join("robot_1.xml")]);
    assert_eq!(Model::from_path(saved.path()).unwrap().scopes().collect::<Vec<_>>(), ["robot"]);
    std::fs::remove_dir_all(&dir).unwrap();
}
