//! The lossless save of a model with attachments (`Model::save`, `save_as`,
//! `to_source_files`): a reopened scene keeps every file's text, an edit inside an
//! attachment goes to that part's file only, attachments added or detached in code
//! change only their own lines.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use mjcf::{Model, Namespace, attrs, element};

/// A fresh folder under the system's temp folder (nothing there yet).
fn temp_dir(tag: &str) -> PathBuf {
    static N: AtomicUsize = AtomicUsize::new(0);
    let n = N.fetch_add(1, Ordering::Relaxed);
    let p = std::env::temp_dir().join(format!("mjcf-scene-save-{}-{tag}-{n}", std::process::id()));
    let _ = std::fs::remove_dir_all(&p);
    p
}

/// Writes `files` (path, text) into a fresh folder; returns it.
fn folder(tag: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = temp_dir(tag);
    for (name, text) in files {
        let path = dir.join(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }
    dir
}

/// A scene as an author keeps it: comments, odd spacing and quoting, two attachments
/// of one part file, and a part in a folder of its own with an include.
const SCENE: &str = "<mujoco model=\"arena\">\n  <!-- the parts -->\n  <asset>\n    <texture name='grid' builtin='checker' width='8' height='8' type='2d'/>\n    <model name=\"robot\"   file='parts/robot.xml'/>\n  </asset>\n  <worldbody>\n    <geom name='floor' type=\"plane\" size='5 5 .1'/>\n    <!-- left -->\n    <body name=\"left/\" pos='-1 0 0'>\n      <attach model=\"robot\" prefix=\"left/\"/>\n    </body>\n    <body name=\"right/\" pos=\"1 0 0\">\n      <joint name=\"right/\" type=\"slide\"/>\n      <attach  model='robot' prefix='right/' />\n    </body>\n  </worldbody>\n</mujoco>\n";

const ROBOT: &str = "<mujoco model=\"robot\">\n  <include file=\"robot_body.xml\"/>\n  <actuator>\n    <motor name=\"m\" joint='hinge'/> <!-- the motor -->\n  </actuator>\n</mujoco>\n";

const ROBOT_BODY: &str = "<mujoco>\n  <worldbody>\n    <body name=\"torso\" pos='0 0 .5'>\n      <joint name=\"hinge\"/>\n      <geom size=\".1\"/>\n    </body>\n  </worldbody>\n</mujoco>\n";

const FILES: &[(&str, &str)] =
    &[("scene.xml", SCENE), ("parts/robot.xml", ROBOT), ("parts/robot_body.xml", ROBOT_BODY)];

/// The text of every file under `dir`, by path from it.
fn texts(dir: &Path) -> Vec<(String, String)> {
    let mut out = Vec::new();
    let mut todo = vec![dir.to_path_buf()];
    while let Some(d) = todo.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            if p.is_dir() {
                todo.push(p);
            } else {
                let rel = p.strip_prefix(dir).unwrap().to_string_lossy().replace('\\', "/");
                out.push((rel, std::fs::read_to_string(&p).unwrap()));
            }
        }
    }
    out.sort();
    out
}

#[test]
fn a_reopened_scene_saves_every_file_byte_for_byte() {
    let dir = folder("same", FILES);
    let m = Model::from_path(dir.join("scene.xml")).unwrap();
    assert_eq!(m.scopes().collect::<Vec<_>>(), ["left", "right"]);
    let files = m.to_source_files().unwrap();
    let got: Vec<(String, bool)> = files
        .iter()
        .map(|f| (f.path.as_ref().unwrap().to_string_lossy().replace('\\', "/"), f.changed))
        .collect();
    assert_eq!(
        got,
        [
            ("scene.xml".to_string(), false),
            ("parts/robot.xml".to_string(), false),
            ("parts/robot_body.xml".to_string(), false)
        ]
    );
    for (f, (_, text)) in files.iter().zip(FILES) {
        assert_eq!(f.text, *text);
    }
    assert_eq!(m.save().unwrap(), Vec::<PathBuf>::new(), "nothing to write");
    // save_as: the same files, the same layout; and again from there: a fixed point.
    let out = temp_dir("same-out");
    m.save_as(&out).unwrap();
    let mut want: Vec<(String, String)> =
        FILES.iter().map(|(p, t)| (p.to_string(), t.to_string())).collect();
    want.sort();
    assert_eq!(texts(&out), want);
    let again = Model::from_path(out.join("scene.xml")).unwrap();
    assert_eq!(again.to_xml_string().unwrap(), m.to_xml_string().unwrap());
    let out2 = temp_dir("same-out2");
    again.save_as(&out2).unwrap();
    assert_eq!(texts(&out2), want);
    for d in [dir, out, out2] {
        std::fs::remove_dir_all(d).unwrap();
    }
}

#[test]
fn an_edit_inside_a_reopened_attachment_is_saved_into_that_part_s_file_only() {
    let scene = SCENE.replace(
        "    <body name=\"right/\" pos=\"1 0 0\">\n      <joint name=\"right/\" type=\"slide\"/>\n      <attach  model='robot' prefix='right/' />\n    </body>\n",
        "",
    );
    let dir = folder("edit", &[("scene.xml", &scene), FILES[1], FILES[2]]);
    let m = Model::from_path(dir.join("scene.xml")).unwrap();
    let edited = m
        .edit_attached("left", |r| {
            let t = r.find(Namespace::Body, "torso").unwrap();
            r.set(&t, attrs!(pos = [0, 0, 2]))
        })
        .unwrap();
    let written = edited.save().unwrap();
    assert_eq!(written, [dir.join("parts/robot_body.xml")]);
    assert_eq!(
        std::fs::read_to_string(dir.join("parts/robot_body.xml")).unwrap(),
        ROBOT_BODY.replace("pos='0 0 .5'", "pos='0 0 2'")
    );
    assert_eq!(std::fs::read_to_string(dir.join("scene.xml")).unwrap(), scene);
    assert_eq!(std::fs::read_to_string(dir.join("parts/robot.xml")).unwrap(), ROBOT);
    let back = Model::from_path(dir.join("scene.xml")).unwrap();
    assert_eq!(back.to_xml_string().unwrap(), edited.to_xml_string().unwrap());
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn an_edited_copy_of_a_shared_part_gets_a_file_of_its_own() {
    let dir = folder("shared", FILES);
    let m = Model::from_path(dir.join("scene.xml")).unwrap();
    // `right` is edited: `left` keeps the part file, `right` gets a new one.
    let edited = m
        .edit_attached("right", |r| {
            let t = r.find(Namespace::Body, "torso").unwrap();
            r.set(&t, attrs!(pos = [0, 0, 2]))
        })
        .unwrap();
    edited.save().unwrap();
    assert_eq!(std::fs::read_to_string(dir.join("parts/robot.xml")).unwrap(), ROBOT);
    assert_eq!(std::fs::read_to_string(dir.join("parts/robot_body.xml")).unwrap(), ROBOT_BODY);
    let saved = std::fs::read_to_string(dir.join("scene.xml")).unwrap();
    assert!(saved.contains("<model name=\"robot_1\" file=\"robot.xml\"/>"), "{saved}");
    assert!(saved.contains("<attach  model='robot_1' prefix='right/' />"), "{saved}");
    let back = Model::from_path(dir.join("scene.xml")).unwrap();
    assert_eq!(back.scopes().collect::<Vec<_>>(), ["left", "right"]);
    assert_eq!(back.to_xml_string().unwrap(), edited.to_xml_string().unwrap());
    // Saved again, reopened: nothing changes.
    assert_eq!(back.save().unwrap(), Vec::<PathBuf>::new());
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn an_attachment_added_in_code_is_a_new_body_asset_and_part_file() {
    let dir = folder("added", FILES);
    let m = Model::from_path(dir.join("scene.xml")).unwrap();
    let mut cube = Model::new("cube");
    cube.add_mut(&cube.worldbody(), element!("body", name = "box")).unwrap();
    let floor = m.find(Namespace::Geom, "floor").unwrap();
    let (m, _) = m.attach(&m.worldbody(), &cube).unwrap();
    let _ = floor;
    let written = m.save().unwrap();
    assert_eq!(written, [dir.join("scene.xml"), dir.join("cube.xml")]);
    let saved = std::fs::read_to_string(dir.join("scene.xml")).unwrap();
    let want = SCENE
        .replace(
            "file='parts/robot.xml'/>\n",
            "file='parts/robot.xml'/>\n    <model name=\"cube\" file=\"cube.xml\"/>\n",
        )
        .replace(
            "    </body>\n  </worldbody>",
            "    </body>\n    <body name=\"cube/\">\n      <attach model=\"cube\" prefix=\"cube/\"/>\n    </body>\n  </worldbody>",
        );
    assert_eq!(saved, want);
    let back = Model::from_path(dir.join("scene.xml")).unwrap();
    assert_eq!(back.scopes().collect::<Vec<_>>(), ["left", "right", "cube"]);
    assert_eq!(back.to_xml_string().unwrap(), m.to_xml_string().unwrap());
    // The part read back is saved losslessly in turn: a fixed point.
    assert_eq!(back.save().unwrap(), Vec::<PathBuf>::new());
    // Saving the model in code again writes nothing either (cube.xml is its part).
    assert_eq!(m.save().unwrap(), Vec::<PathBuf>::new());
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_detached_attachment_goes_with_its_asset_model_when_unused() {
    let dir = folder("detach", FILES);
    let m = Model::from_path(dir.join("scene.xml")).unwrap();
    let one = m.detach("left").unwrap();
    let text = &one.to_source_files().unwrap()[0].text;
    let want = SCENE.replace(
        "    <!-- left -->\n    <body name=\"left/\" pos='-1 0 0'>\n      <attach model=\"robot\" prefix=\"left/\"/>\n    </body>\n",
        "",
    );
    assert_eq!(*text, want, "the asset model stays: right uses it");
    let none = one.detach("right").unwrap();
    let text = &none.to_source_files().unwrap()[0].text;
    let want = want
        .replace("    <model name=\"robot\"   file='parts/robot.xml'/>\n", "")
        .replace(
            "    <body name=\"right/\" pos=\"1 0 0\">\n      <joint name=\"right/\" type=\"slide\"/>\n      <attach  model='robot' prefix='right/' />\n    </body>\n",
            "",
        );
    assert_eq!(*text, want);
    assert_eq!(none.to_source_files().unwrap().len(), 1, "no part file");
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_renamed_scope_and_a_moved_frame_change_their_tags_in_place() {
    let dir = folder("rename", FILES);
    let m = Model::from_path(dir.join("scene.xml")).unwrap();
    let renamed = m.rename_scope("right", "far").unwrap();
    let frame = renamed.frame("far").unwrap();
    let renamed = renamed.set(&frame, attrs!(pos = [3, 0, 0])).unwrap();
    let text = &renamed.to_source_files().unwrap()[0].text;
    let want = SCENE
        .replace("<body name=\"right/\" pos=\"1 0 0\">", "<body name=\"far/\" pos=\"3 0 0\">")
        .replace("<joint name=\"right/\" type=\"slide\"/>", "<joint name=\"far/\" type=\"slide\"/>")
        .replace("prefix='right/'", "prefix='far/'");
    assert_eq!(*text, want);
    renamed.save().unwrap();
    let back = Model::from_path(dir.join("scene.xml")).unwrap();
    assert_eq!(back.scopes().collect::<Vec<_>>(), ["left", "far"]);
    assert_eq!(back.to_xml_string().unwrap(), renamed.to_xml_string().unwrap());
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn parts_built_in_code_share_the_files_they_both_name() {
    let dir = folder("shared-mesh", FILES);
    let m = Model::from_path(dir.join("scene.xml")).unwrap();
    let part = |name: &str| {
        let text = format!(
            "<mujoco model=\"{name}\"><asset><mesh name=\"cube\" file=\"cube.stl\"/></asset><worldbody><geom type=\"mesh\" mesh=\"cube\"/></worldbody></mujoco>"
        );
        mjcf::ReadOptions::new().asset("cube.stl", b"solid cube".to_vec()).read_str(&text).unwrap()
    };
    let (m, _) = m.attach(&m.worldbody(), &part("a")).unwrap();
    let (m, _) = m.attach(&m.worldbody(), &part("b")).unwrap();
    let written = m.save().unwrap();
    let names: Vec<String> = written
        .iter()
        .map(|p| p.strip_prefix(&dir).unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(names.len(), 4, "{names:?}");
    assert_eq!(names[..3], ["scene.xml", "a.xml", "b.xml"]);
    assert!(names[3].starts_with("cube-") && names[3].ends_with(".stl"), "{names:?}");
    let back = Model::from_path(dir.join("scene.xml")).unwrap();
    assert_eq!(back.scopes().collect::<Vec<_>>(), ["left", "right", "a", "b"]);
    assert_eq!(back.to_xml_string().unwrap(), m.to_xml_string().unwrap());
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_file_already_there_is_never_replaced_by_a_new_part() {
    let dir = folder("there", FILES);
    std::fs::write(dir.join("cube.xml"), "not ours").unwrap();
    let m = Model::from_path(dir.join("scene.xml")).unwrap();
    let mut cube = Model::new("cube");
    cube.add_mut(&cube.worldbody(), element!("body", name = "box")).unwrap();
    let (m, _) = m.attach(&m.worldbody(), &cube).unwrap();
    let written = m.save().unwrap();
    assert_eq!(written, [dir.join("scene.xml"), dir.join("cube_1.xml")]);
    assert_eq!(std::fs::read_to_string(dir.join("cube.xml")).unwrap(), "not ours");
    let back = Model::from_path(dir.join("scene.xml")).unwrap();
    assert_eq!(back.to_xml_string().unwrap(), m.to_xml_string().unwrap());
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_literal_name_shaped_like_a_frame_body_does_not_clash_with_a_new_one() {
    let scene = SCENE
        .replace("    <geom name='floor'", "    <site name=\"cube/\"/>\n    <geom name='floor'");
    let dir = folder("taken", &[("scene.xml", &scene), FILES[1], FILES[2]]);
    let m = Model::from_path(dir.join("scene.xml")).unwrap();
    let mut cube = Model::new("cube");
    cube.add_mut(&cube.worldbody(), element!("body", name = "box")).unwrap();
    let (m, a) = m.attach(&m.worldbody(), &cube).unwrap();
    assert_ne!(a.scope(), "cube", "the scope steers clear of the literal name");
    m.save().unwrap();
    let back = Model::from_path(dir.join("scene.xml")).unwrap();
    assert_eq!(back.scopes().collect::<Vec<_>>(), ["left", "right", a.scope()]);
    assert_eq!(back.to_xml_string().unwrap(), m.to_xml_string().unwrap());
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_file_without_assets_gets_an_asset_section_for_its_first_attachment() {
    let plain = "<mujoco model=\"arena\">\n  <worldbody>\n    <geom name=\"floor\" type=\"plane\" size=\"5 5 .1\"/>\n  </worldbody>\n</mujoco>\n";
    let dir = folder("no-assets", &[("scene.xml", plain)]);
    let m = Model::from_path(dir.join("scene.xml")).unwrap();
    let mut cube = Model::new("cube");
    cube.add_mut(&cube.worldbody(), element!("body", name = "box")).unwrap();
    let (m, _) = m.attach(&m.worldbody(), &cube).unwrap();
    m.save().unwrap();
    let saved = std::fs::read_to_string(dir.join("scene.xml")).unwrap();
    assert_eq!(
        saved,
        // A new section goes after those read (MuJoCo reads sections in any order).
        "<mujoco model=\"arena\">\n  <worldbody>\n    <geom name=\"floor\" type=\"plane\" size=\"5 5 .1\"/>\n    <body name=\"cube/\">\n      <attach model=\"cube\" prefix=\"cube/\"/>\n    </body>\n  </worldbody>\n  <asset>\n    <model name=\"cube\" file=\"cube.xml\"/>\n  </asset>\n</mujoco>\n"
    );
    let back = Model::from_path(dir.join("scene.xml")).unwrap();
    assert_eq!(back.to_xml_string().unwrap(), m.to_xml_string().unwrap());
    // Detached again: the body and the asset model go; the section read stays, as
    // any section read whose children were all removed does.
    let bare = back.detach("cube").unwrap();
    let want = plain.replace("</worldbody>\n", "</worldbody>\n  <asset>\n  </asset>\n");
    assert_eq!(bare.to_source_files().unwrap()[0].text, want);
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn an_edit_inside_a_nested_attachment_is_saved_into_the_innermost_file_only() {
    let mut hand = Model::new("hand");
    hand.add_mut(&hand.worldbody(), element!("body", name = "palm")).unwrap();
    let mut arm = Model::new("arm");
    let ee = arm.add_mut(&arm.worldbody(), element!("site", name = "ee")).unwrap();
    arm.attach_mut(&ee, &hand).unwrap();
    let mut scene = Model::new("arena");
    scene.attach_mut(&scene.worldbody(), &arm).unwrap();
    let dir = temp_dir("nested");
    let saved = scene.save_scene(&dir, "scene.xml").unwrap();
    let before = texts(&dir);
    let m = Model::from_path(saved.path()).unwrap();
    assert_eq!(m.scope_paths(), ["arm", "arm/hand"]);
    assert_eq!(m.save().unwrap(), Vec::<PathBuf>::new());
    let edited = m
        .edit_attached("arm/hand", |h| {
            let p = h.find(Namespace::Body, "palm").unwrap();
            h.set(&p, attrs!(pos = [0, 0, 0.25]))
        })
        .unwrap();
    assert_eq!(edited.save().unwrap(), [dir.join("hand.xml")]);
    let after = texts(&dir);
    for ((name, a), (_, b)) in before.iter().zip(&after) {
        assert_eq!(a != b, name == "hand.xml", "{name}");
    }
    let back = Model::from_path(saved.path()).unwrap();
    assert_eq!(back.to_xml_string().unwrap(), edited.to_xml_string().unwrap());
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn an_asset_model_also_used_by_an_attach_that_stays_an_element_is_written_once() {
    let scene = SCENE.replace(
        "    <geom name='floor'",
        "    <body name=\"kept\">\n      <attach model=\"robot\" body=\"torso\" prefix=\"k/\"/>\n    </body>\n    <geom name='floor'",
    );
    let dir = folder("kept", &[("scene.xml", &scene), FILES[1], FILES[2]]);
    let m = Model::from_path(dir.join("scene.xml")).unwrap();
    assert_eq!(m.scopes().collect::<Vec<_>>(), ["left", "right"]);
    assert_eq!(m.to_source_files().unwrap()[0].text, scene);
    let edited = m
        .edit_attached("left", |r| {
            let t = r.find(Namespace::Body, "torso").unwrap();
            r.set(&t, attrs!(pos = [0, 0, 2]))
        })
        .unwrap();
    let files = edited.to_source_files().unwrap();
    assert_eq!(files[0].text.matches("<model ").count(), 2, "{}", files[0].text);
    assert_eq!(
        edited.detach("left").unwrap().to_source_files().unwrap()[0]
            .text
            .matches("<model ")
            .count(),
        1
    );
    std::fs::remove_dir_all(dir).unwrap();
}
