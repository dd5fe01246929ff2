//! The names MuJoCo sees (issue 19 items 2, 5 and 8; decision D14): every name the
//! writer writes is the element's `full_name`, `from_full_name` gives the element
//! back, and no name is written twice in a namespace, however the names were made:
//! frames and their joints, automatic names inside `<replicate>`, scopes beside
//! literal names read from a composed file, root classes beside a class named `/`.
//! `tools/mujoco_cases.py` compiles the same shapes in MuJoCo
//! (`examples/mujoco_cases.rs`).
//!
//! Issue 20 item 1 over every model at hand: every conformance output, every
//! conformance file read on its own (the inputs, dm_control's expected outputs),
//! the real models beside the checkout (`../shared/realmodels`; the test is ignored,
//! saying so, without them), and the generated models and scenes
//! (`src/generate/tests.rs`, through the same `support/names.rs`).

use crate::case;
use crate::names;
use crate::replay;

use std::path::{Path, PathBuf};

use mjcf::{Element, ErrorKind, Model, Namespace, ProblemKind, ReadOptions, WriteOptions, element};

fn write(m: &Model) -> String {
    m.to_xml_string().unwrap_or_else(|e| panic!("cannot write: {e}"))
}

fn read(xml: &str) -> Model {
    Model::from_xml_str(xml).unwrap_or_else(|e| panic!("{e}\n{xml}"))
}

/// The names checked, and what the output reads back as checked too; write, read,
/// write is a fixed point.
fn names_hold(m: &Model) -> String {
    let xml = write(m);
    names::check_names(m, &xml).unwrap_or_else(|e| panic!("{e}\n{xml}"));
    let back = read(&xml);
    let again = write(&back);
    names::check_names(&back, &again).unwrap_or_else(|e| panic!("read back: {e}\n{again}"));
    assert_eq!(again, xml, "write, read, write is no fixed point");
    xml
}

fn robot(name: &str) -> Model {
    let mut m = Model::new(name);
    let b = m.add_mut(&m.worldbody(), element!("body", name = "torso")).unwrap();
    m.add_mut(&b, element!("geom", size = [0.1])).unwrap();
    m.add_mut(&b, element!("joint", name = "hip")).unwrap();
    m
}

fn inertial() -> Element {
    element!("inertial", pos = [0, 0, 0], mass = 0.1, diaginertia = [0.001, 0.001, 0.001])
}

/// The checker itself finds a name that is not the element's full name, and a name
/// written twice.
#[test]
fn the_name_checker_finds_what_it_is_for() {
    let m = robot("robot");
    let xml = write(&m);
    assert!(names::check_names(&m, &xml).is_ok());
    let renamed = xml.replace(r#"name="//unnamed_geom_0""#, r#"name="//unnamed_geom_7""#);
    assert!(names::check_names(&m, &renamed).is_err(), "{renamed}");
    let mut twice = Model::new("m");
    twice.add_mut(&twice.worldbody(), element!("geom", name = "g", size = [0.1])).unwrap();
    twice.add_mut(&twice.worldbody(), element!("geom", name = "h", size = [0.1])).unwrap();
    let xml = write(&twice).replace(r#"name="h""#, r#"name="g""#);
    assert!(names::check_names(&twice, &xml).is_err(), "{xml}");
}

/// Item 5: an unnamed element inside a `<replicate>` is written with a `_` after its
/// automatic name (MuJoCo appends the copy's number), and that is its full name,
/// which `from_full_name` takes back; the same for an attached model whose frame
/// lies inside a `<replicate>` (MuJoCo replicates it too).
#[test]
fn replicated_unnamed_elements_are_named_as_written() {
    let m = read(
        r#"<mujoco model="arena"><worldbody>
             <geom size="1"/>
             <replicate count="2" offset="1 0 0"><geom size="1"/><site name="s"/></replicate>
           </worldbody></mujoco>"#,
    );
    let geoms = m.find_all(Namespace::Geom);
    assert_eq!(m.full_name(&geoms[0]).as_deref(), Some("//unnamed_geom_0"));
    assert_eq!(m.full_name(&geoms[1]).as_deref(), Some("//unnamed_geom_1_"));
    assert_eq!(m.from_full_name(Namespace::Geom, "//unnamed_geom_1_"), Some(geoms[1].clone()));
    assert_eq!(m.from_full_name(Namespace::Geom, "//unnamed_geom_1"), None);
    names_hold(&m);
    // Attached at the site inside the replicate.
    let mut scene = m.clone();
    let site = scene.find(Namespace::Site, "s").unwrap();
    scene.attach_mut(&site, &robot("robot")).unwrap();
    let geom = scene.from_full_name(Namespace::Geom, "robot//unnamed_geom_0_").unwrap();
    assert_eq!(scene.full_name(&geom).as_deref(), Some("robot//unnamed_geom_0_"));
    let xml = names_hold(&scene);
    assert!(xml.contains(r#"<geom name="robot//unnamed_geom_0_""#), "{xml}");
}

/// Item 2: a frame takes any number of unnamed joints; the first is written with the
/// frame's name, the others with their automatic names.
#[test]
fn unnamed_frame_joints_are_written_apart() {
    let mut scene = Model::new("arena");
    let a = scene.attach_mut(&scene.worldbody(), &robot("robot")).unwrap();
    scene.add_mut(a.frame(), element!("joint", type = "hinge")).unwrap();
    scene.add_mut(a.frame(), element!("joint", type = "slide")).unwrap();
    scene.add_mut(a.frame(), element!("joint", name = "root")).unwrap();
    scene.add_mut(a.frame(), inertial()).unwrap();
    let xml = names_hold(&scene);
    assert!(xml.contains(r#"<joint name="robot/" class="/" type="hinge"/>"#), "{xml}");
    assert!(xml.contains(r#"<joint name="//unnamed_joint_1" class="/" type="slide"/>"#), "{xml}");
    assert!(xml.contains(r#"<joint name="robot/root/" class="/"/>"#), "{xml}");
    assert!(scene.check().is_empty(), "{:?}", scene.check());
}

/// Item 2: a freejoint beside another joint (on a frame or on a body), more than 6
/// degrees of freedom, and a rotation after a ball joint are what MuJoCo refuses:
/// `check` reports them on the body.
#[test]
fn check_reports_the_joints_mujoco_refuses_in_one_body() {
    let mut scene = Model::new("arena");
    let a = scene.attach_mut(&scene.worldbody(), &robot("robot")).unwrap();
    scene.add_mut(a.frame(), element!("joint", type = "hinge")).unwrap();
    scene.add_mut(a.frame(), Element::new("freejoint")).unwrap();
    scene.add_mut(a.frame(), inertial()).unwrap();
    let kinds: Vec<(String, ProblemKind)> =
        scene.check().into_iter().map(|p| (p.path, p.kind)).collect();
    assert_eq!(kinds, [("robot/".to_string(), ProblemKind::TooManyDofs { dofs: 7 })]);

    let body = |joints: &[&str]| {
        let mut m = Model::new("m");
        let b = m.add_mut(&m.worldbody(), element!("body", name = "b")).unwrap();
        m.add_mut(&b, element!("geom", size = [0.1])).unwrap();
        for t in joints {
            let j =
                if *t == "free" { Element::new("freejoint") } else { element!("joint", type = *t) };
            m.add_mut(&b, j).unwrap();
        }
        m.check().into_iter().map(|p| (p.path, p.kind)).collect::<Vec<_>>()
    };
    let b = || "b".to_string();
    assert_eq!(body(&["free", "slide"]), [(b(), ProblemKind::TooManyDofs { dofs: 7 })]);
    assert_eq!(body(&["ball", "ball", "ball"])[0], (b(), ProblemKind::TooManyDofs { dofs: 9 }));
    assert_eq!(body(&["ball", "hinge"]), [(b(), ProblemKind::RotationAfterBall)]);
    assert_eq!(body(&["hinge"; 7]), [(b(), ProblemKind::TooManyDofs { dofs: 7 })]);
    for fine in [&["hinge", "ball"][..], &["ball", "slide"], &["hinge"; 6], &["free"]] {
        assert_eq!(body(fine), [], "{fine:?}");
    }
    let p = &scene.check()[0];
    assert!(p.to_string().starts_with("robot/: its joints have 7 degrees of freedom"), "{p}");
}

/// D14: a joint named `a` on the frame of scope `hand`, and the unnamed joint on the
/// frame of an attachment scoped `a` inside `hand`, would both be written `hand/a/`
/// (dm_control writes both so, and MuJoCo refuses it); the unnamed one is written with
/// its automatic name. One level deeper too.
#[test]
fn a_frame_joint_named_as_a_scope_inside_is_told_apart() {
    let mut hand = Model::new("hand");
    let inner = hand.attach_mut(&hand.worldbody(), &robot("a")).unwrap();
    hand.add_mut(inner.frame(), Element::new("joint")).unwrap();
    hand.add_mut(inner.frame(), inertial()).unwrap();
    let mut arm = Model::new("arm");
    let h = arm.attach_mut(&arm.worldbody(), &hand).unwrap();
    arm.add_mut(h.frame(), element!("joint", name = "a")).unwrap();
    arm.add_mut(h.frame(), inertial()).unwrap();
    let xml = names_hold(&arm);
    assert!(xml.contains(r#"<joint name="hand/a/" class="/"/>"#), "{xml}");
    assert!(xml.contains(r#"<joint name="hand//unnamed_joint_0" class="hand/"/>"#), "{xml}");
    // Attached once more (`arm` in a scene, twice: `arm`, `arm_1`).
    let mut scene = Model::new("scene");
    scene.attach_mut(&scene.worldbody(), &arm).unwrap();
    scene.attach_mut(&scene.worldbody(), &arm).unwrap();
    let xml = names_hold(&scene);
    assert!(xml.contains(r#"<joint name="arm_1/hand/a/" class="arm_1/"/>"#), "{xml}");
    assert!(xml.contains(r#"name="arm_1/hand//unnamed_joint_0""#), "{xml}");
}

/// D14: a named frame joint `j` whose attached model holds the literal joint `j/`
/// (read from MJCF) would be written as it is; the frame joint takes its automatic
/// name.
#[test]
fn a_named_frame_joint_yields_to_a_literal_joint_of_its_model() {
    let robot = read(
        r#"<mujoco model="robot"><worldbody><body name="b"><joint name="j/"/><geom size="0.1"/></body></worldbody></mujoco>"#,
    );
    let mut scene = Model::new("arena");
    let a = scene.attach_mut(&scene.worldbody(), &robot).unwrap();
    let j = scene.add_mut(a.frame(), element!("joint", name = "j")).unwrap();
    scene.add_mut(a.frame(), inertial()).unwrap();
    let xml = names_hold(&scene);
    assert!(xml.contains(r#"<joint name="robot/j/" class="robot/"/>"#), "{xml}");
    assert_eq!(scene.full_name(&j).as_deref(), Some("//unnamed_joint_0"));
}

/// Item 8: a composed model read back holds the literal names `robot/`,
/// `robot/torso` and the class `robot/`; attaching a model named `robot` to it takes
/// the scope `robot_1`, renaming a scope to `robot` is refused, and so is copying in
/// a literal name `robot_1/x` beside the attachment `robot_1`.
#[test]
fn scopes_skip_the_literal_names_of_a_composed_model_read_back() {
    let mut scene = Model::new("arena");
    let a = scene.attach_mut(&scene.worldbody(), &robot("robot")).unwrap();
    scene.add_mut(a.frame(), Element::new("freejoint")).unwrap();
    scene.add_mut(a.frame(), inertial()).unwrap();
    let mut back = read(&write(&scene));
    assert!(back.find(Namespace::Body, "robot/torso").is_some(), "a literal name");
    let again = back.attach_mut(&back.worldbody(), &robot("robot")).unwrap();
    assert_eq!(again.scope(), "robot_1");
    let xml = names_hold(&back);
    assert_eq!(xml.matches(r#"<default class="robot/""#).count(), 1, "{xml}");
    assert_eq!(xml.matches(r#"<default class="robot_1/""#).count(), 1, "{xml}");
    let other = back.attach_mut(&back.worldbody(), &robot("arm")).unwrap();
    let e = back.rename_scope(&other, "robot").unwrap_err();
    assert!(matches!(e.kind(), ErrorKind::DuplicateIdentifier { .. }), "{e}");
    assert!(back.rename_scope(&other, "robot_2").is_ok());
    let literal = read(
        r#"<mujoco model="x"><worldbody><body name="robot_1/x"><geom size="0.1"/></body></worldbody></mujoco>"#,
    );
    let e = back.include_copy(&literal, false).unwrap_err();
    assert!(
        matches!(e.kind(), ErrorKind::DuplicateIdentifier { name, .. } if name == "robot_1/x"),
        "{e}"
    );
    // After the detach, the name is free to copy in.
    let free = back.detach(&again).unwrap();
    assert!(free.include_copy(&literal, false).is_ok());
}

/// Item 8: `<default class="a"><default class="/"/></default>` (MuJoCo compiles it):
/// the root class is not written `/` as well. Alone, it is written as MuJoCo's main
/// class (the `<default>` itself, referred to as `main`); with attached models, whose
/// root classes must not inherit from it, as `/1`.
#[test]
fn a_class_named_slash_leaves_the_root_class_another_name() {
    let m = read(
        r#"<mujoco model="m">
             <default><geom rgba="1 0 0 1"/><default class="a"><default class="/"><geom rgba="0 1 0 1"/></default></default></default>
             <worldbody><geom size="1"/><geom class="/" size="1"/></worldbody>
           </mujoco>"#,
    );
    let xml = names_hold(&m);
    assert!(
        xml.contains("<default>\n    <geom rgba=\"1 0 0 1\"/>\n    <default class=\"a\">"),
        "{xml}"
    );
    assert!(xml.contains(r#"<geom name="//unnamed_geom_0" class="main" size="1"/>"#), "{xml}");
    assert!(xml.contains(r#"<geom name="//unnamed_geom_1" class="/" size="1"/>"#), "{xml}");
    let mut scene = m.clone();
    scene.attach_mut(&scene.worldbody(), &robot("robot")).unwrap();
    let xml = names_hold(&scene);
    assert!(
        xml.contains("<default>\n    <default class=\"/1\">\n      <geom rgba=\"1 0 0 1\"/>"),
        "{xml}"
    );
    assert!(xml.contains("<default class=\"robot/\"/>"), "{xml}");
    assert!(xml.contains(r#"<geom name="//unnamed_geom_0" class="/1" size="1"/>"#), "{xml}");
}

/// A root class named `main` (decision D9) is written as MuJoCo's main class, the
/// `<default class="main">` itself; with attached models it is a class `/`, a sibling
/// of theirs: written as the main class, the attached root classes inside it
/// inherited its defaults.
#[test]
fn a_root_class_named_main_passes_nothing_on_to_attached_models() {
    let arena = read(
        r#"<mujoco model="arena"><default class="main"><geom rgba="1 0 0 1"/></default><worldbody><geom size="1"/></worldbody></mujoco>"#,
    );
    // Alone, as MuJoCo's main class, named so (written, read and written again, the
    // same text).
    let xml = names_hold(&arena);
    assert!(
        xml.starts_with("<mujoco model=\"arena\">\n  <default class=\"main\">\n    <geom rgba"),
        "{xml}"
    );
    let mut scene = arena.clone();
    scene.attach_mut(&scene.worldbody(), &robot("robot")).unwrap();
    let xml = names_hold(&scene);
    assert!(xml.contains("<default>\n    <default class=\"/\">\n      <geom rgba=\"1 0 0 1\"/>\n    </default>\n    <default class=\"robot/\"/>"), "{xml}");
}

/// Item 8: a composed model read back keeps its automatic names as literal names
/// (`//unnamed_geom_0`); an unnamed element added before them, whose automatic name
/// one of them holds, is written with `~1` after it.
#[test]
fn automatic_names_avoid_literal_automatic_names() {
    let mut scene = Model::new("arena");
    scene.add_mut(&scene.worldbody(), element!("geom", size = [1])).unwrap();
    scene.attach_mut(&scene.worldbody(), &robot("robot")).unwrap();
    let mut back = read(&write(&scene));
    assert!(back.find(Namespace::Geom, "//unnamed_geom_0").is_some(), "a literal name");
    let g = back.insert_mut(&back.worldbody(), 0, element!("geom", size = [0.5])).unwrap();
    assert_eq!(back.full_name(&g).as_deref(), Some("//unnamed_geom_0~1"));
    let xml = names_hold(&back);
    // (Its class is the read-back model's root class, MuJoCo's main class: the class
    // `/` is a literal one.)
    assert!(xml.contains(r#"<geom name="//unnamed_geom_0~1" class="main" size="0.5"/>"#), "{xml}");
    // In an attached model, its own literal names count (`/unnamed_geom_0` there).
    let inner = read(
        r#"<mujoco model="inner"><worldbody><geom name="/unnamed_geom_0" size="1"/><geom size="1"/></worldbody></mujoco>"#,
    );
    let mut outer = Model::new("outer");
    outer.attach_mut(&outer.worldbody(), &inner).unwrap();
    let g = &outer.find_all(Namespace::Geom)[1];
    assert_eq!(outer.full_name(g).as_deref(), Some("inner//unnamed_geom_1"));
    let mut shifted = inner.clone();
    shifted.insert_mut(&shifted.worldbody(), 0, element!("geom", size = [0.5])).unwrap();
    let mut outer = Model::new("outer");
    outer.attach_mut(&outer.worldbody(), &shifted).unwrap();
    let g = &outer.find_all(Namespace::Geom)[0];
    assert_eq!(outer.full_name(g).as_deref(), Some("inner//unnamed_geom_0~1"));
    names_hold(&outer);
}

/// Item 4: a composed model written, read and written again is the same text: an
/// attachment frame's name is written at its schema place (first), as the body (or
/// MuJoCo `<frame>`, decision D10) it reads back as is written, not after the pose
/// copied from its site.
#[test]
fn a_composed_model_written_read_and_written_again_is_the_same_text() {
    let mut ball = Model::new("ball");
    let b = ball.add_mut(&ball.worldbody(), element!("body", name = "ball")).unwrap();
    ball.add_mut(&b, Element::new("freejoint")).unwrap();
    ball.add_mut(&b, element!("geom", size = [0.1])).unwrap();
    let mut scene = Model::new("scene");
    let s = element!("site", name = "s", pos = [1, 2, 3], euler = [0, 0, 90]);
    let s = scene.add_mut(&scene.worldbody(), s).unwrap();
    let a = scene.attach_mut(&s, &robot("robot")).unwrap();
    scene.add_mut(a.frame(), element!("joint", name = "root", type = "slide")).unwrap();
    scene.add_mut(a.frame(), inertial()).unwrap();
    scene.attach_mut(&s, &ball).unwrap();
    let xml = names_hold(&scene);
    assert!(xml.contains(r#"<body name="robot/" pos="1 2 3" euler="0 0 90">"#), "{xml}");
    assert!(xml.contains(r#"<frame name="ball/" pos="1 2 3" euler="0 0 90">"#), "{xml}");
}

/// The names of `m` written with `options` hold (`names::check_names`), and so do
/// those of what the text reads back as (with the files it names), written again.
fn names_hold_with(m: &Model, options: &WriteOptions) -> Result<(), String> {
    let xml = m.to_xml_string_with(options).map_err(|e| format!("cannot write: {e}"))?;
    names::check_names(m, &xml)?;
    let mut read = ReadOptions::new();
    for (name, file) in m.assets(options).map_err(|e| e.to_string())? {
        read = read.asset(&name, file.contents().to_vec());
    }
    let back = read.read_str(&xml).map_err(|e| format!("does not read back: {e}"))?;
    let again = back.to_xml_string_with(options).map_err(|e| e.to_string())?;
    names::check_names(&back, &again).map_err(|e| format!("read back: {e}"))
}

/// What [`check_case_folders`] checked.
#[derive(Debug, Default)]
struct Checked {
    cases: usize,
    /// The models the cases' `output` ops write.
    outputs: usize,
    /// The `.xml` files of the case folders that read on their own.
    files: usize,
    /// Those that do not (a file the case expects to fail to read).
    unreadable: usize,
    failures: Vec<String>,
}

/// Checks the names of every case under `root` (`tests/conformance/README.md`'s
/// format): of every model its ops output, and of every `.xml` file in its folder
/// that reads on its own.
fn check_case_folders(root: &Path) -> Checked {
    let mut checked = Checked::default();
    for dir in case::list_cases(root).unwrap_or_else(|e| panic!("{e}")) {
        let c = case::load_case(&dir).unwrap_or_else(|e| panic!("{e}"));
        checked.cases += 1;
        let (_, outputs) = replay::run_case_collecting(&c, None);
        for (file, model, options) in outputs {
            checked.outputs += 1;
            if let Err(e) = names_hold_with(&model, &options) {
                checked.failures.push(format!("{}: output {file}: {e}", c.name));
            }
        }
        let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)
            .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
            .map(|e| e.unwrap().path())
            .filter(|p| p.extension().is_some_and(|x| x == "xml"))
            .collect();
        files.sort();
        for f in files {
            let Some(model) = read_case_file(&dir, &f) else {
                checked.unreadable += 1;
                continue;
            };
            checked.files += 1;
            if let Err(e) = names_hold_with(&model, &WriteOptions::default()) {
                checked.failures.push(format!("{}: {e}", f.display()));
            }
        }
    }
    checked
}

/// `file` of the case folder `dir` read on its own, if it reads: as it is, or with
/// the folder's other files (its subfolders' too) also under the names the writer
/// gives them (`stem-<sha1>.ext`), as dm_control's expected outputs name them.
fn read_case_file(dir: &Path, file: &Path) -> Option<Model> {
    if let Ok(m) = Model::from_path(file) {
        return Some(m);
    }
    let mut read = ReadOptions::new();
    let mut folders = vec![dir.to_path_buf()];
    while let Some(folder) = folders.pop() {
        for entry in std::fs::read_dir(&folder).ok()? {
            let path = entry.ok()?.path();
            if path.is_dir() {
                folders.push(path);
                continue;
            }
            if path.extension().is_some_and(|x| x == "xml" || x == "json") {
                continue;
            }
            let contents = std::fs::read(&path).ok()?;
            let name = path.file_name()?.to_str()?;
            let asset = mjcf::FileAsset::from_path_and_contents(name, contents.clone());
            read = read.asset(&asset.vfs_name(true), contents);
        }
    }
    read.read_path(file).ok()
}

fn assert_checked(what: &str, checked: &Checked, cases: usize, files: usize) {
    eprintln!("{what}: {checked:?}");
    assert!(checked.failures.is_empty(), "{what}: {:#?}", checked.failures);
    assert!(checked.cases >= cases, "{what}: {} cases, fewer than {cases}", checked.cases);
    assert!(checked.outputs >= cases, "{what}: {} outputs checked", checked.outputs);
    assert!(checked.files >= files, "{what}: {} files read, fewer than {files}", checked.files);
}

/// Item 1 over the conformance corpus: every output, and every file of it read on
/// its own (the inputs and dm_control's expected outputs, composed ones included,
/// whose names read back as literal names).
#[test]
fn every_conformance_output_and_file_read_is_named_as_written() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/conformance/cases");
    let checked = check_case_folders(&root);
    assert_checked("conformance", &checked, 155, FLOOR_CONFORMANCE_FILES);
}

/// Item 1 over the real models (`../shared/realmodels`): every output of their cases
/// (each model read and written, as `.ci/run` runs them), and every file of their
/// folders that reads on its own.
#[test]
#[cfg_attr(not(mjcf_realmodels), ignore = "../shared/realmodels is not beside the checkout")]
fn every_real_model_is_named_as_written() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/realmodels/cases");
    let checked = check_case_folders(&root);
    assert_checked("real models", &checked, 179, FLOOR_REAL_MODEL_FILES);
}

/// The conformance files that read on their own (the 7 others are the inputs of the
/// cases that expect reading them to fail); fewer means files stopped reading.
const FLOOR_CONFORMANCE_FILES: usize = 468;

/// The real models' files (every one reads on its own).
const FLOOR_REAL_MODEL_FILES: usize = 346;
