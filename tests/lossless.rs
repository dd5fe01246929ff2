//! The lossless writer (`Model::to_source_files`, `save`, `save_as`) on files: every
//! conformance input read and saved without an edit gives its bytes back, file by
//! file; edits land in the file they belong to; unchanged files are not touched;
//! what cannot be saved is a typed error.

use std::path::{Path, PathBuf};

use mjcf::{Attrs, Element, Model, Namespace, SaveError};

use crate::dirs;
use dirs::{temp_dir, write};

/// The model files the conformance cases load (`"op": "load"`), by case folder.
fn conformance_inputs() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/conformance/cases");
    let mut out = Vec::new();
    for case in std::fs::read_dir(&root).unwrap().flatten() {
        let Ok(json) = std::fs::read_to_string(case.path().join("case.json")) else { continue };
        let v: serde_json::Value = serde_json::from_str(&json).unwrap();
        for op in v["ops"].as_array().into_iter().flatten() {
            if op["op"] == "load" {
                if let Some(f) = op["file"].as_str() {
                    out.push(case.path().join(f));
                }
            }
        }
    }
    out.sort();
    out
}

#[test]
fn every_conformance_input_saves_byte_for_byte_without_edits() {
    let (mut files, mut models) = (0, 0);
    for path in conformance_inputs() {
        // Inputs that are meant to fail to read have nothing to save.
        let Ok(m) = Model::from_path(&path) else { continue };
        models += 1;
        let dir = path.parent().unwrap();
        for f in m.to_source_files().unwrap() {
            let rel = f.path.unwrap();
            let original = std::fs::read_to_string(dir.join(&rel)).unwrap();
            assert_eq!(f.text, original, "{}", dir.join(&rel).display());
            assert!(!f.changed);
            files += 1;
        }
    }
    // The corpus holds more than a hundred readable inputs.
    assert!(models >= 100 && files >= models, "{models} models, {files} files");
}

const MAIN: &str = r#"<?xml version="1.0"?>
<!-- scene -->
<mujoco model="scene">
  <include file="common/materials.xml"/>
  <asset>
    <material name="blue" rgba="0 0 1 1"/>
  </asset>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 .1" material='red'/>
    <body name="arm" pos="0 0 1">
      <include file="arm.xml"/>
    </body>
  </worldbody>
</mujoco>
"#;

const MATERIALS: &str = "<mujoco>\n  <asset>\n    <!-- warm -->\n    <material name=\"red\"   rgba=\"1 0 0 1\"/>\n  </asset>\n</mujoco>\n";

const ARM: &str =
    "<mujoco>\n\t<joint name=\"shoulder\"/>\n\t<geom name=\"upper\" size=\"0.05\"/>\n</mujoco>\n";

fn scene(name: &str) -> PathBuf {
    let dir = temp_dir(name);
    write(&dir, "scene.xml", MAIN);
    write(&dir, "common/materials.xml", MATERIALS);
    write(&dir, "arm.xml", ARM);
    dir
}

#[test]
fn an_edit_inside_an_included_file_is_saved_into_that_file_alone() {
    let dir = scene("include");
    let m = Model::from_path(dir.join("scene.xml")).unwrap();
    let red = m.find(Namespace::Material, "red").unwrap();
    let m = m.set(&red, Attrs::new().set("rgba", [1.0, 0.5, 0.0, 1.0])).unwrap();
    let files = m.to_source_files().unwrap();
    let paths: Vec<PathBuf> = files.iter().map(|f| f.path.clone().unwrap()).collect();
    assert_eq!(paths, ["scene.xml", "common/materials.xml", "arm.xml"].map(PathBuf::from));
    assert_eq!(files[0].text, MAIN);
    assert_eq!(files[1].text, MATERIALS.replace("\"1 0 0 1\"", "\"1 0.5 0 1\""));
    assert_eq!(files[2].text, ARM);
    assert_eq!([files[0].changed, files[1].changed, files[2].changed], [false, true, false]);
    // An element added inside the body the arm file is included in: into the main
    // file (the body's own tag), indented like the include.
    let arm = m.find(Namespace::Body, "arm").unwrap();
    let (m, _) = m.add(&arm, Element::new("site").attr("name", "tip")).unwrap();
    let upper = m.find(Namespace::Geom, "upper").unwrap();
    let m = m.set(&upper, Attrs::new().set("size", [0.06])).unwrap();
    let files = m.to_source_files().unwrap();
    assert_eq!(
        files[0].text,
        MAIN.replace(
            "<include file=\"arm.xml\"/>",
            "<include file=\"arm.xml\"/>\n      <site name=\"tip\"/>"
        )
    );
    assert_eq!(files[2].text, ARM.replace("\"0.05\"", "\"0.06\""));
}

#[test]
fn save_writes_changed_files_in_place_and_leaves_the_others_untouched() {
    let dir = scene("save");
    let m = Model::from_path(dir.join("scene.xml")).unwrap();
    let mtime = |rel: &str| std::fs::metadata(dir.join(rel)).unwrap().modified().unwrap();
    let before = [mtime("scene.xml"), mtime("arm.xml")];
    assert_eq!(m.save().unwrap(), Vec::<PathBuf>::new(), "nothing changed, nothing written");
    let red = m.find(Namespace::Material, "red").unwrap();
    let edited = m.set(&red, Attrs::new().set("rgba", [0.0, 1.0, 0.0, 1.0])).unwrap();
    let written = edited.save().unwrap();
    assert_eq!(written, [dir.join("common/materials.xml")]);
    assert_eq!(before, [mtime("scene.xml"), mtime("arm.xml")]);
    let back = Model::from_path(dir.join("scene.xml")).unwrap();
    assert_eq!(back, edited);
    // Saving again writes nothing; saving the version before the edit writes it back.
    assert!(edited.save().unwrap().is_empty());
    assert_eq!(m.save().unwrap(), [dir.join("common/materials.xml")]);
    assert_eq!(std::fs::read_to_string(dir.join("common/materials.xml")).unwrap(), MATERIALS);
    // No temporary file is left behind.
    let left: Vec<_> = std::fs::read_dir(dir.join("common")).unwrap().flatten().collect();
    assert_eq!(left.len(), 1);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn save_as_writes_every_file_with_its_relative_path_and_the_assets() {
    let dir = scene("save-as-src");
    write(&dir, "meshes/cube.stl", "solid cube");
    let text = MAIN.replace(
        "<asset>\n",
        "<compiler meshdir=\"meshes\"/>\n  <asset>\n    <mesh file=\"cube.stl\"/>\n",
    );
    write(&dir, "scene.xml", &text);
    let m = Model::from_path(dir.join("scene.xml")).unwrap();
    let out = temp_dir("save-as-out");
    let mut written = m.save_as(&out).unwrap();
    written.sort();
    let want = ["arm.xml", "common/materials.xml", "meshes/cube.stl", "scene.xml"];
    assert_eq!(written, want.map(|p| out.join(p)));
    for p in want {
        assert_eq!(std::fs::read(out.join(p)).unwrap(), std::fs::read(dir.join(p)).unwrap(), "{p}");
    }
    let _ = std::fs::remove_dir_all(&dir);
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn a_removed_element_goes_with_the_comment_before_it() {
    let m = Model::from_path(scene("remove").join("scene.xml")).unwrap();
    let red = m.find(Namespace::Material, "red").unwrap();
    let floor = m.find(Namespace::Geom, "floor").unwrap();
    let m = m.set(&floor, Attrs::new().clear("material")).unwrap();
    let m = m.remove(&red).unwrap();
    let files = m.to_source_files().unwrap();
    assert_eq!(files[1].text, "<mujoco>\n  <asset>\n  </asset>\n</mujoco>\n");
    assert_eq!(files[0].text, MAIN.replace(" material='red'", ""));
}

#[test]
fn renaming_an_element_renames_the_references_to_it_in_every_file() {
    let m = Model::from_path(scene("rename").join("scene.xml")).unwrap();
    let red = m.find(Namespace::Material, "red").unwrap();
    let m = m.set(&red, Attrs::new().set("name", "crimson")).unwrap();
    let files = m.to_source_files().unwrap();
    assert_eq!(files[0].text, MAIN.replace("'red'", "'crimson'"));
    assert_eq!(files[1].text, MATERIALS.replace("\"red\"", "\"crimson\""));
}

#[test]
fn a_singleton_given_twice_changes_where_its_value_wins() {
    let text = "<mujoco>\n  <option timestep=\"0.01\"/>\n  <option timestep=\"0.02\" gravity=\"0 0 -1\"/>\n</mujoco>\n";
    let m = Model::from_xml_str(text).unwrap();
    let option = m.section("option").unwrap();
    let m = m.set(&option, Attrs::new().set("timestep", 0.005).set("integrator", "RK4")).unwrap();
    let saved = &m.to_source_files().unwrap()[0];
    assert_eq!(
        saved.text,
        "<mujoco>\n  <option timestep=\"0.01\" integrator=\"RK4\"/>\n  <option timestep=\"0.005\" gravity=\"0 0 -1\"/>\n</mujoco>\n"
    );
    assert_eq!(Model::from_xml_str(&saved.text).unwrap(), m);
}

#[test]
fn the_root_class_written_as_a_class_slash_takes_new_defaults_inside_it() {
    let text = "<mujoco>\n  <default>\n    <default class=\"/\">\n      <geom size=\"1\"/>\n    </default>\n  </default>\n</mujoco>\n";
    let m = Model::from_xml_str(text).unwrap();
    let (m, _) = m.add(&m.default_class(), Element::new("default").attr("class", "big")).unwrap();
    let saved = &m.to_source_files().unwrap()[0].text;
    assert_eq!(
        saved,
        &text.replace(
            "<geom size=\"1\"/>\n",
            "<geom size=\"1\"/>\n      <default class=\"big\"/>\n"
        )
    );
    assert_eq!(Model::from_xml_str(saved).unwrap(), m);
}

#[test]
fn what_cannot_be_saved_is_a_typed_error() {
    assert_eq!(Model::new("m").to_source_files(), Err(SaveError::NoSource));
    let off = mjcf::ReadOptions::new().keep_source(false).read_str("<mujoco/>").unwrap();
    assert_eq!(off.save(), Err(SaveError::NoSource));
    assert_eq!(off.source_heap_bytes(), 0);
    // From a string: no path to save to once something changed.
    let m = Model::from_xml_str("<mujoco/>").unwrap();
    assert!(m.source_heap_bytes() > 0);
    assert_eq!(m.save(), Err(SaveError::NoPath));
    assert_eq!(m.save_as(std::env::temp_dir()), Err(SaveError::NoPath));
    let mut robot = Model::new("robot");
    robot.add_mut(&robot.worldbody(), Element::new("body").attr("name", "b")).unwrap();
    // With an attachment: the scene's file and the part's (built in code: written
    // with the plain writer beside it); still no path to save to.
    let with = m.attach(&m.worldbody(), &robot).unwrap().0;
    let files = with.to_source_files().unwrap();
    let paths: Vec<_> = files.iter().map(|f| f.path.clone()).collect();
    assert_eq!(paths, [None, Some(PathBuf::from("robot.xml"))]);
    assert!(files[0].text.contains("<attach model=\"robot\" prefix=\"robot/\"/>"));
    assert_eq!(with.save(), Err(SaveError::NoPath));
}

/// MuJoCo's root class is `main`: a file's top-level `<default>` may be named nothing
/// else, and a class inside it may not be named `main`. A root class renamed through
/// the API is saved where the file spells it only when MuJoCo reads that; otherwise
/// the save is a typed error and nothing is written (the plain writer nests it).
#[test]
fn a_renamed_root_class_is_saved_only_where_mujoco_reads_the_name() {
    let top = "<mujoco><default><geom rgba=\"1 0 0 1\"/></default></mujoco>";
    let wrapped = "<mujoco><default><default class=\"/\"><geom rgba=\"1 0 0 1\"/></default></default></mujoco>";
    let renamed = |text: &str, name: &str| {
        let m = Model::from_xml_str(text).unwrap();
        let m = m.set(&m.default_class(), Attrs::new().set("class", name)).unwrap();
        (m.to_source_files().map(|f| f[0].text.clone()), m)
    };
    for (text, name) in [(top, "robot"), (wrapped, "main")] {
        let (saved, m) = renamed(text, name);
        assert_eq!(saved, Err(SaveError::RootClassRenamed(name.into())));
        let message = saved.unwrap_err().to_string();
        assert!(
            message.contains("cannot be renamed")
                && message.contains("repeated default class name")
        );
        // The plain writer nests the class, and what it writes reads back.
        assert_eq!(Model::from_xml_str(&m.to_xml_string().unwrap()).unwrap().check(), []);
    }
    for (text, name, spelled) in
        [(top, "main", "<default class=\"main\">"), (wrapped, "robot", "<default class=\"robot\">")]
    {
        let saved = renamed(text, name).0.unwrap();
        assert!(saved.contains(spelled), "{saved}");
        Model::from_xml_str(&saved).unwrap();
    }
}

#[test]
fn confined_models_and_save_as_write_nothing_outside_their_folder() {
    let dir = temp_dir("outside");
    write(&dir, "inner/scene.xml", "<mujoco>\n  <include file=\"../shared.xml\"/>\n</mujoco>\n");
    write(&dir, "shared.xml", "<mujoco>\n  <option timestep=\"0.01\"/>\n</mujoco>\n");
    let m = Model::from_path(dir.join("inner/scene.xml")).unwrap();
    let out = temp_dir("outside-out");
    assert!(matches!(m.save_as(&out), Err(SaveError::OutsideRoot(_))));
    let _ = std::fs::remove_dir_all(&dir);
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn hostile_spellings_save_as_read_and_edit_in_place() {
    for text in [
        "<mujoco><worldbody><geom name=\"g\" size=\"1\"/></worldbody></mujoco>",
        "<mujoco>\r\n\t<worldbody>\r\n\t\t<geom name = 'g'\r\n size=\"1\" />\r\n\t</worldbody>\r\n</mujoco>\r\n",
        "<?xml version=\"1.0\"?><!DOCTYPE mujoco><mujoco><!-- a -- b --><worldbody><geom name=\"g\" size='&#49;'/><?pi x?></worldbody></mujoco>",
    ] {
        let m = Model::from_xml_str(text).unwrap();
        assert_eq!(m.to_source_files().unwrap()[0].text, text);
        let g = m.find(Namespace::Geom, "g").unwrap();
        let m = m.set(&g, Attrs::new().set("rgba", "1 0 0 1").set("size", [2.0])).unwrap();
        let (m, _) = m.add(&m.worldbody(), Element::new("site").attr("name", "a'\"<")).unwrap();
        let saved = m.to_source_files().unwrap()[0].text.clone();
        assert_eq!(Model::from_xml_str(&saved).unwrap(), m, "{saved}");
    }
}
