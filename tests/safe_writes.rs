//! What the crate's writers never do to a user's files: overwrite a file another
//! program changed since it was read, write a file whose text did not change, open a
//! link planted at a temporary name, write through a symlinked folder, or rewrite a
//! reopened scene's part read from outside its folder when nothing changed. Every
//! writer (`save`, `save_with`, `save_as`, `export`, `save_scene`) goes through one
//! file layer (`src/files/write.rs`); each is tested here.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use mjcf::{Attrs, Model, Namespace, SaveError, SaveOptions, WriteOptions};

/// A fresh folder under the system's temp folder, with `files` (path, text) in it.
fn folder(tag: &str, files: &[(&str, &str)]) -> PathBuf {
    static N: AtomicUsize = AtomicUsize::new(0);
    let n = N.fetch_add(1, Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("mjcf-safe-{}-{tag}-{n}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in files {
        let path = dir.join(name);
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(path, text).unwrap();
    }
    dir
}

fn read(p: &Path) -> String {
    std::fs::read_to_string(p).unwrap()
}

const A: &str =
    "<mujoco model=\"a\">\n  <option timestep=\"0.01\"/>\n  <include file=\"b.xml\"/>\n</mujoco>\n";
const B: &str =
    "<mujoco>\n  <worldbody>\n    <geom name=\"g\" size=\"0.5\"/>\n  </worldbody>\n</mujoco>\n";
const B_THEIRS: &str =
    "<mujoco>\n  <worldbody>\n    <geom name=\"g\" size=\"0.7\"/>\n  </worldbody>\n</mujoco>\n";

fn set_timestep(m: &Model, t: f64) -> Model {
    m.set(&m.section("option").unwrap(), Attrs::new().set("timestep", t)).unwrap()
}

fn set_size(m: &Model, size: f64) -> Model {
    let g = m.find(Namespace::Geom, "g").unwrap();
    m.set(&g, Attrs::new().set("size", [size])).unwrap()
}

#[test]
fn a_file_another_program_changed_is_kept_when_the_model_did_not_change_it() {
    let dir = folder("kept", &[("a.xml", A), ("b.xml", B)]);
    let m = Model::from_path(dir.join("a.xml")).unwrap();
    std::fs::write(dir.join("b.xml"), B_THEIRS).unwrap();
    let written = set_timestep(&m, 0.02).save().unwrap();
    assert_eq!(written, [dir.join("a.xml")]);
    assert_eq!(read(&dir.join("b.xml")), B_THEIRS, "the other program's edit is kept");
    assert!(read(&dir.join("a.xml")).contains("0.02"));
}

#[test]
fn a_file_to_write_that_changed_on_disk_refuses_the_save_and_nothing_is_written() {
    let dir = folder("refused", &[("a.xml", A), ("b.xml", B)]);
    let m = Model::from_path(dir.join("a.xml")).unwrap();
    std::fs::write(dir.join("b.xml"), B_THEIRS).unwrap();
    // Both files must be written; b.xml changed on disk: neither is.
    let edited = set_size(&set_timestep(&m, 0.02), 0.25);
    assert_eq!(edited.save(), Err(SaveError::ChangedOnDisk(dir.join("b.xml"))));
    assert_eq!(read(&dir.join("a.xml")), A);
    assert_eq!(read(&dir.join("b.xml")), B_THEIRS);
    let message = edited.save().unwrap_err().to_string();
    assert!(message.contains("b.xml") && message.contains("overwrite_changed"), "{message}");
    // Overwriting on purpose.
    let written = edited.save_with(&SaveOptions::new().overwrite_changed(true)).unwrap();
    assert_eq!(written.len(), 2);
    assert_eq!(Model::from_path(dir.join("a.xml")).unwrap(), edited);
}

#[test]
fn a_file_removed_since_the_read_counts_as_changed() {
    let dir = folder("removed", &[("a.xml", A), ("b.xml", B)]);
    let m = Model::from_path(dir.join("a.xml")).unwrap();
    std::fs::remove_file(dir.join("b.xml")).unwrap();
    assert_eq!(set_size(&m, 0.25).save(), Err(SaveError::ChangedOnDisk(dir.join("b.xml"))));
    assert!(!dir.join("b.xml").exists());
}

#[test]
fn saving_editing_on_and_saving_again_is_not_a_change_by_another_program() {
    let dir = folder("again", &[("a.xml", A), ("b.xml", B)]);
    let v0 = Model::from_path(dir.join("a.xml")).unwrap();
    let v1 = set_size(&v0, 0.25);
    assert_eq!(v1.save().unwrap(), [dir.join("b.xml")]);
    let v2 = set_size(&v1, 0.125);
    assert_eq!(v2.save().unwrap(), [dir.join("b.xml")]);
    // Undo to the version read: written back over what this process wrote.
    assert_eq!(v0.save().unwrap(), [dir.join("b.xml")]);
    assert_eq!(read(&dir.join("b.xml")), B);
    // Another program's edit after that is refused again.
    std::fs::write(dir.join("b.xml"), B_THEIRS).unwrap();
    assert_eq!(v2.save(), Err(SaveError::ChangedOnDisk(dir.join("b.xml"))));
}

/// Links at every temporary name the writers of this process may take next (and at
/// the names an earlier version took), all pointing at one file outside.
#[cfg(unix)]
fn plant_links(dir: &Path, victim: &Path) {
    let pid = std::process::id();
    for n in 0..3000 {
        let _ = std::os::unix::fs::symlink(victim, dir.join(format!(".mjcf-{pid}-{n}.tmp")));
    }
    for name in ["a.xml", "b.xml", "scene.xml"] {
        for n in 0..20 {
            let _ = std::os::unix::fs::symlink(victim, dir.join(format!(".{name}.{pid}-{n}.tmp")));
        }
    }
}

#[cfg(unix)]
fn assert_regular(p: &Path) {
    assert!(std::fs::symlink_metadata(p).unwrap().file_type().is_file(), "{}", p.display());
}

#[cfg(unix)]
#[test]
fn no_writer_follows_a_link_planted_at_a_temporary_name() {
    let dir = folder("links", &[("a.xml", A), ("b.xml", B)]);
    let victim = dir.with_extension("victim");
    std::fs::write(&victim, "keep").unwrap();
    plant_links(&dir, &victim);
    let m = Model::from_path(dir.join("a.xml")).unwrap();
    // save
    set_size(&set_timestep(&m, 0.02), 0.25).save().unwrap();
    assert_regular(&dir.join("a.xml"));
    assert_regular(&dir.join("b.xml"));
    // save_as
    let out = dir.join("out");
    std::fs::create_dir_all(&out).unwrap();
    plant_links(&out, &victim);
    m.save_as(&out).unwrap();
    assert_regular(&out.join("a.xml"));
    // export
    let exported = dir.join("exported");
    std::fs::create_dir_all(&exported).unwrap();
    plant_links(&exported, &victim);
    m.export(&exported, "a.xml", &WriteOptions::default()).unwrap();
    assert_regular(&exported.join("a.xml"));
    // save_scene
    let mut scene = Model::new("scene");
    scene.attach_mut(&scene.worldbody(), &m).unwrap();
    let scenes = dir.join("scenes");
    std::fs::create_dir_all(&scenes).unwrap();
    plant_links(&scenes, &victim);
    scene.save_scene(&scenes, "scene.xml").unwrap();
    assert_regular(&scenes.join("scene.xml"));
    assert_eq!(read(&victim), "keep");
    std::fs::remove_file(&victim).unwrap();
}

#[cfg(unix)]
#[test]
fn save_as_refuses_a_symlinked_folder_below_its_folder_and_writes_nothing() {
    let a = "<mujoco model=\"a\">\n  <include file=\"sub/b.xml\"/>\n</mujoco>\n";
    let dir = folder("save-as-link", &[("src/a.xml", a), ("src/sub/b.xml", B)]);
    let m = Model::from_path(dir.join("src/a.xml")).unwrap();
    let (out, outside) = (dir.join("out"), dir.join("outside"));
    std::fs::create_dir_all(&out).unwrap();
    std::fs::create_dir_all(&outside).unwrap();
    std::os::unix::fs::symlink("../outside", out.join("sub")).unwrap();
    assert_eq!(m.save_as(&out), Err(SaveError::SymlinkedFolder(out.join("sub"))));
    assert!(!outside.join("b.xml").exists());
    assert!(!out.join("a.xml").exists(), "nothing is written");
    // The export writes the model flat (no sub/ folder): nothing goes through the link
    // (a symlinked folder an export must write in is refused: tests/export.rs).
    m.export(&out, "a.xml", &WriteOptions::default()).unwrap();
    assert!(std::fs::read_dir(&outside).unwrap().next().is_none());
}

/// A scene whose part lives outside the scene's folder.
const OUTSIDE_SCENE: &str = "<mujoco model=\"arena\">\n  <asset>\n    <model name=\"part\" file=\"../outside/robot.xml\"/>\n  </asset>\n  <worldbody>\n    <body name=\"part/\" pos=\"1 0 0\">\n      <attach model=\"part\" prefix=\"part/\"/>\n    </body>\n  </worldbody>\n</mujoco>\n";
const OUTSIDE_ROBOT: &str = "<mujoco model=\"robot\">\n  <worldbody>\n    <body name=\"torso\">\n      <joint name=\"hinge\"/>\n      <geom size=\"0.1\"/>\n    </body>\n  </worldbody>\n</mujoco>\n";

#[test]
fn a_reopened_scene_with_a_part_outside_its_folder_saves_nothing_untouched() {
    let dir =
        folder("outside", &[("scene/a.xml", OUTSIDE_SCENE), ("outside/robot.xml", OUTSIDE_ROBOT)]);
    let m = Model::from_path(dir.join("scene/a.xml")).unwrap();
    assert_eq!(m.scopes().collect::<Vec<_>>(), ["part"], "the part reopens");
    let files = m.to_source_files().unwrap();
    assert!(files.iter().all(|f| !f.changed), "{files:?}");
    assert_eq!(files[0].text, OUTSIDE_SCENE);
    assert_eq!(m.save().unwrap(), Vec::<PathBuf>::new());
    assert_eq!(read(&dir.join("scene/a.xml")), OUTSIDE_SCENE);
    assert_eq!(std::fs::read_dir(dir.join("scene")).unwrap().count(), 1, "no copy written");
    // An edit of the scene's own file keeps the part's reference.
    let edited = m.set(&m.section("option").unwrap(), Attrs::new().set("timestep", 0.005)).unwrap();
    assert_eq!(edited.save().unwrap(), [dir.join("scene/a.xml")]);
    assert!(read(&dir.join("scene/a.xml")).contains("file=\"../outside/robot.xml\""));
}

#[test]
fn an_edited_part_from_outside_is_written_inside_the_scene_folder_and_the_outside_file_kept() {
    let dir = folder(
        "outside-edit",
        &[("scene/a.xml", OUTSIDE_SCENE), ("outside/robot.xml", OUTSIDE_ROBOT)],
    );
    let m = Model::from_path(dir.join("scene/a.xml")).unwrap();
    let edited = m
        .edit_attached("part", |r| {
            let b = r.find(Namespace::Body, "torso").unwrap();
            r.set(&b, Attrs::new().set("pos", [0.0, 0.0, 2.0]))
        })
        .unwrap();
    let written = edited.save().unwrap();
    assert_eq!(read(&dir.join("outside/robot.xml")), OUTSIDE_ROBOT, "the outside file is kept");
    assert!(written.iter().all(|p| p.starts_with(dir.join("scene"))), "{written:?}");
    let scene = read(&dir.join("scene/a.xml"));
    assert!(!scene.contains("../outside/robot.xml"), "{scene}");
    let back = Model::from_path(dir.join("scene/a.xml")).unwrap();
    assert_eq!(back.to_xml_string().unwrap(), edited.to_xml_string().unwrap());
}
