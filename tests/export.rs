//! A model's files (`Model::assets`) and export to a folder (`Model::export`): each file
//! once, under the names the writer uses, written so that a failure leaves no MJCF file.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};

use mjcf::{ExportError, Model, Namespace, ReadOptions, WriteError, WriteOptions, element};

const JACO: &str = "tests/conformance/cases/real_02_jaco_arm_with_hand";

/// A fresh path under the system's temp folder (nothing there yet).
fn temp_path(tag: &str) -> PathBuf {
    static N: AtomicUsize = AtomicUsize::new(0);
    let n = N.fetch_add(1, Ordering::Relaxed);
    let p = std::env::temp_dir().join(format!("mjcf-export-{}-{tag}-{n}", std::process::id()));
    let _ = std::fs::remove_dir_all(&p);
    let _ = std::fs::remove_file(&p);
    p
}

fn plain() -> WriteOptions {
    WriteOptions { filename_with_hash: false, ..WriteOptions::default() }
}

/// A model named `name` with one mesh read from an in-memory `cube.stl`.
fn robot(name: &str, contents: &[u8]) -> Model {
    let text = format!(
        r#"<mujoco model="{name}"><asset><mesh name="cube" file="cube.stl"/></asset>
           <worldbody><body name="torso"><geom type="mesh" mesh="cube"/></body></worldbody></mujoco>"#
    );
    ReadOptions::new().asset("cube.stl", contents.to_vec()).read_str(&text).unwrap()
}

/// The `file*="..."` values of written MJCF, as a set.
fn written_file_names(xml: &str) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    for part in xml.split(" file").skip(1) {
        let value = part.split_once("=\"").map(|(_, v)| v).unwrap_or_default();
        out.insert(value.split('"').next().unwrap_or_default().to_string());
    }
    out
}

/// The file names in `dir`.
fn listing(dir: &Path) -> BTreeSet<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect()
}

/// The jaco arm with the hand at its wrist (nine meshes, two of them included files).
fn jaco_arm() -> Model {
    let mut arm = Model::from_path(format!("{JACO}/jaco_arm.xml")).unwrap();
    let hand = Model::from_path(format!("{JACO}/jaco_hand.xml")).unwrap();
    let wrist = arm.lookup(Namespace::Site, "wristsite").unwrap();
    arm.attach_mut(&wrist, &hand).unwrap();
    arm
}

#[test]
fn a_mesh_attached_twice_is_one_asset() {
    let r = robot("robot", b"solid cube");
    let mut arena = Model::new("arena");
    let world = arena.worldbody();
    arena.attach_mut(&world, &r).unwrap();
    arena.attach_mut(&world, &r).unwrap();
    // The same value again, nested two levels down.
    let mut mid = Model::new("mid");
    mid.attach_mut(&mid.worldbody(), &r).unwrap();
    arena.attach_mut(&world, &mid).unwrap();
    // The bytes are shared with the model, not copied.
    let own = r.assets(&plain()).unwrap();
    let composed = arena.assets(&plain()).unwrap();
    assert!(std::ptr::eq(own["cube.stl"].contents(), composed["cube.stl"].contents()));
    // A separately read robot with the same file is the same file.
    arena.attach_mut(&world, &robot("other", b"solid cube")).unwrap();
    for options in [WriteOptions::default(), plain()] {
        let assets = arena.assets(&options).unwrap();
        assert_eq!(assets.len(), 1, "{assets:?}");
        let (name, file) = assets.iter().next().unwrap();
        assert_eq!(name, &file.vfs_name(options.filename_with_hash));
        assert_eq!(file.contents(), b"solid cube");
        assert_eq!(written_file_names(&arena.to_xml_string_with(&options).unwrap()).len(), 1);
    }
}

#[test]
fn asset_names_are_the_names_the_writer_writes() {
    let arm = jaco_arm();
    let mut arena = Model::new("arena");
    let world = arena.worldbody();
    let left = arena.add_mut(&world, element!("site", name = "left")).unwrap();
    let right = arena.add_mut(&world, element!("site", name = "right")).unwrap();
    arena.attach_mut(&left, &arm).unwrap();
    arena.attach_mut(&right, &jaco_arm()).unwrap();
    for options in [WriteOptions::default(), plain()] {
        let assets = arena.assets(&options).unwrap();
        let names: BTreeSet<String> = assets.keys().cloned().collect();
        assert_eq!(names.len(), 9, "{names:?}");
        assert_eq!(names, written_file_names(&arena.to_xml_string_with(&options).unwrap()));
        assert!(names.contains(if options.filename_with_hash {
            "base-1e944fe900397431c653654e0d1b789a06d4b042.stl"
        } else {
            "base.stl"
        }));
        for (name, file) in &assets {
            let disk = std::fs::read(format!(
                "{JACO}/meshes_decimated/{}{}",
                file.stem(),
                file.extension()
            ))
            .unwrap();
            assert_eq!(file.contents(), &disk[..], "{name}");
        }
    }
    assert!(Model::new("empty").assets(&WriteOptions::default()).unwrap().is_empty());
}

#[test]
fn export_writes_the_xml_and_each_file_once() {
    let arm = jaco_arm();
    let mut arena = Model::new("arena");
    let world = arena.worldbody();
    arena
        .add_mut(&world, element!("geom", name = "floor", type = "plane", size = [1.0, 1.0, 0.1]))
        .unwrap();
    let left = arena.add_mut(&world, element!("site", name = "left")).unwrap();
    let right = arena.add_mut(&world, element!("site", name = "right")).unwrap();
    arena.attach_mut(&left, &arm).unwrap();
    arena.attach_mut(&right, &arm).unwrap();
    for options in [WriteOptions::default(), plain()] {
        let dir = temp_path("roundtrip").join("created/on/demand");
        let xml = arena.export(&dir, "scene.xml", &options).unwrap();
        assert_eq!(xml, dir.join("scene.xml"));
        let assets = arena.assets(&options).unwrap();
        let mut expected: BTreeSet<String> = assets.keys().cloned().collect();
        expected.insert("scene.xml".to_string());
        assert_eq!(listing(&dir), expected, "no temporary files are left");
        assert_eq!(
            std::fs::read_to_string(&xml).unwrap(),
            arena.to_xml_string_with(&options).unwrap()
        );
        for (name, file) in &assets {
            assert_eq!(std::fs::read(dir.join(name)).unwrap(), file.contents(), "{name}");
        }
        // Exporting again (a newer version) replaces the files.
        let smaller = arena.remove(&arena.lookup(Namespace::Geom, "floor").unwrap()).unwrap();
        smaller.export(&dir, "scene.xml", &options).unwrap();
        assert_eq!(listing(&dir), expected);
        assert_eq!(
            std::fs::read_to_string(&xml).unwrap(),
            smaller.to_xml_string_with(&options).unwrap()
        );
        std::fs::remove_dir_all(temp_path_root(&dir)).unwrap();
    }
}

/// The folder `temp_path` made, above `dir`.
fn temp_path_root(dir: &Path) -> PathBuf {
    dir.ancestors().nth(3).unwrap().to_path_buf()
}

#[test]
fn exports_into_one_folder_can_run_concurrently() {
    let dir = temp_path("threads");
    let r = robot("robot", b"solid cube");
    std::thread::scope(|s| {
        for t in 0..2 {
            let (dir, r) = (&dir, &r);
            s.spawn(move || {
                for i in 0..20 {
                    let m = r.with_name(&format!("robot_{t}_{i}"));
                    m.export(dir, &format!("m_{t}_{i}.xml"), &WriteOptions::default()).unwrap();
                }
            });
        }
    });
    assert_eq!(listing(&dir).len(), 41);
    std::fs::remove_dir_all(&dir).unwrap();
}

fn io_path(e: &ExportError) -> &Path {
    match e {
        ExportError::Io { path, .. } => path,
        other => panic!("expected an I/O error, got {other:?}"),
    }
}

#[test]
fn a_failed_export_names_the_path_and_leaves_no_xml() {
    let r = robot("robot", b"solid cube");

    // `dir` is a file.
    let file = temp_path("is-a-file");
    std::fs::write(&file, "not a folder").unwrap();
    let e = r.export(&file, "robot.xml", &plain()).unwrap_err();
    assert_eq!(io_path(&e), file);
    assert!(e.to_string().starts_with(&format!("cannot write {}: ", file.display())), "{e}");
    let any: mjcf::Error = e.into();
    assert!(any.to_string().contains(&file.display().to_string()));
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "not a folder");
    std::fs::remove_file(&file).unwrap();

    // A file cannot be written (a folder holds its name): refused before anything is
    // written, and an older MJCF file under the target name stays as it was.
    let dir = temp_path("blocked");
    std::fs::create_dir_all(dir.join("cube.stl")).unwrap();
    let e = r.export(&dir, "robot.xml", &plain()).unwrap_err();
    assert_eq!(io_path(&e), dir.join("cube.stl"));
    assert!(matches!(e, ExportError::Io { kind: std::io::ErrorKind::IsADirectory, .. }), "{e:?}");
    // The same for a folder under the MJCF file's name: not even the mesh is written.
    let xml_blocked = temp_path("xml-blocked");
    std::fs::create_dir_all(xml_blocked.join("robot.xml")).unwrap();
    let e = r.export(&xml_blocked, "robot.xml", &plain()).unwrap_err();
    assert_eq!(io_path(&e), xml_blocked.join("robot.xml"));
    assert_eq!(listing(&xml_blocked), BTreeSet::from(["robot.xml".to_string()]));
    std::fs::remove_dir_all(&xml_blocked).unwrap();
    assert_eq!(listing(&dir), BTreeSet::from(["cube.stl".to_string()]), "no temporary files");
    std::fs::write(dir.join("robot.xml"), "old").unwrap();
    r.export(&dir, "robot.xml", &plain()).unwrap_err();
    assert_eq!(std::fs::read_to_string(dir.join("robot.xml")).unwrap(), "old");
    std::fs::remove_dir_all(&dir).unwrap();

    // A read-only folder (not enforced for the superuser, who can write anyway).
    let dir = temp_path("read-only");
    std::fs::create_dir_all(&dir).unwrap();
    let mut perms = std::fs::metadata(&dir).unwrap().permissions();
    perms.set_readonly(true);
    std::fs::set_permissions(&dir, perms.clone()).unwrap();
    if std::fs::write(dir.join("probe"), "").is_err() {
        let e = r.export(&dir, "robot.xml", &plain()).unwrap_err();
        assert_eq!(io_path(&e), dir.join("cube.stl"));
        assert!(matches!(e, ExportError::Io { kind: std::io::ErrorKind::PermissionDenied, .. }));
        assert!(listing(&dir).is_empty());
    }
    #[allow(clippy::permissions_set_readonly_false)]
    perms.set_readonly(false);
    std::fs::set_permissions(&dir, perms).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn names_that_are_not_plain_file_names_are_refused_before_writing() {
    let r = robot("robot", b"solid cube");
    let dir = temp_path("names");
    for bad in ["", ".", "..", "sub/robot.xml", "../robot.xml", "/tmp/robot.xml"] {
        let e = r.export(&dir, bad, &plain()).unwrap_err();
        assert!(
            matches!(e, ExportError::Io { kind: std::io::ErrorKind::InvalidInput, .. }),
            "{bad:?}: {e:?}"
        );
        assert!(!dir.exists(), "{bad:?}");
    }
    // A file whose name would climb out of the folder.
    let text = r#"<mujoco><asset><mesh file="x.stl"/></asset></mujoco>"#;
    let evil = ReadOptions::new().asset("x.stl", b"x".to_vec()).read_str(text).unwrap();
    let escaping = mjcf::Value::File(mjcf::FileAsset::new("../escaped", ".stl", b"x".to_vec()));
    let evil = evil.set_attr(&evil.find_all(Namespace::Mesh)[0], "file", escaping).unwrap();
    let e = evil.export(&dir, "m.xml", &plain()).unwrap_err();
    assert_eq!(io_path(&e), dir.join("../escaped.stl"));
    assert!(!dir.exists());
    // A file named like the MJCF file.
    let e = r.export(&dir, "cube.stl", &plain()).unwrap_err();
    assert_eq!(e, ExportError::Write(WriteError::FileNameClash { name: "cube.stl".into() }));
    assert!(!dir.exists());
}

#[test]
fn different_files_with_one_name_clash_without_the_hash() {
    let mut arena = Model::new("arena");
    let world = arena.worldbody();
    arena.attach_mut(&world, &robot("a", b"solid a")).unwrap();
    arena.attach_mut(&world, &robot("b", b"solid b")).unwrap();
    let e = arena.assets(&plain()).unwrap_err();
    assert_eq!(e, WriteError::FileNameClash { name: "cube.stl".into() });
    assert!(e.to_string().contains("'cube.stl'"), "{e}");
    // With the hash the names differ.
    assert_eq!(arena.assets(&WriteOptions::default()).unwrap().len(), 2);
    // Export refuses before writing anything.
    let dir = temp_path("clash");
    let e = arena.export(&dir, "arena.xml", &plain()).unwrap_err();
    assert_eq!(e, ExportError::Write(WriteError::FileNameClash { name: "cube.stl".into() }));
    assert!(!dir.exists());
    arena.export(&dir, "arena.xml", &WriteOptions::default()).unwrap();
    assert_eq!(listing(&dir).len(), 3);
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn an_exported_model_reads_back() {
    let mut arm = Model::from_path(format!("{JACO}/jaco_arm.xml")).unwrap();
    for i in 1..=6 {
        let motor = element!("motor", name = format!("m{i}"), joint = format!("joint_{i}"));
        arm.add_mut(&arm.actuator(), motor).unwrap();
    }
    for options in [WriteOptions::default(), plain()] {
        let dir = temp_path("read-back");
        let xml = arm.export(&dir, "arm.xml", &options).unwrap();
        let back = Model::from_path(&xml).unwrap();
        assert_eq!(back.find_all(Namespace::Mesh).len(), 5);
        assert_eq!(back.find_all(Namespace::Actuator).len(), 6);
        let files: BTreeSet<Vec<u8>> =
            back.assets(&options).unwrap().values().map(|f| f.contents().to_vec()).collect();
        let original: BTreeSet<Vec<u8>> =
            arm.assets(&options).unwrap().values().map(|f| f.contents().to_vec()).collect();
        assert_eq!(files, original);
        if !options.filename_with_hash {
            // Without the hash the names read back as they were written.
            assert_eq!(back.to_xml_string_with(&options), arm.to_xml_string_with(&options));
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

/// The file's inode: a rename over it gives another one.
#[cfg(unix)]
fn inode(path: &Path) -> u64 {
    std::os::unix::fs::MetadataExt::ino(&std::fs::symlink_metadata(path).unwrap())
}

#[cfg(unix)]
#[test]
fn a_file_already_holding_the_same_bytes_is_left_and_any_other_replaced() {
    let dir = temp_path("same-bytes");
    robot("r", b"solid cube").export(&dir, "a.xml", &plain()).unwrap();
    let mesh = dir.join("cube.stl");
    let (mesh_inode, xml_inode) = (inode(&mesh), inode(&dir.join("a.xml")));
    // A second export of the same model: the mesh is the same file, the MJCF is new.
    robot("r", b"solid cube").export(&dir, "a.xml", &plain()).unwrap();
    assert_eq!(inode(&mesh), mesh_inode);
    assert_ne!(inode(&dir.join("a.xml")), xml_inode);
    // Other bytes under that name (same length, then another length) are replaced.
    std::fs::write(&mesh, b"solid cubf").unwrap();
    robot("r", b"solid cube").export(&dir, "a.xml", &plain()).unwrap();
    assert_eq!(std::fs::read(&mesh).unwrap(), b"solid cube");
    std::fs::write(&mesh, b"solid").unwrap();
    robot("r", b"solid cube").export(&dir, "a.xml", &plain()).unwrap();
    assert_eq!(std::fs::read(&mesh).unwrap(), b"solid cube");
    // A link to a file with the same bytes is replaced by a file of its own.
    let elsewhere = temp_path("same-bytes-target");
    std::fs::write(&elsewhere, b"solid cube").unwrap();
    std::fs::remove_file(&mesh).unwrap();
    std::os::unix::fs::symlink(&elsewhere, &mesh).unwrap();
    robot("r", b"solid cube").export(&dir, "a.xml", &plain()).unwrap();
    assert!(std::fs::symlink_metadata(&mesh).unwrap().file_type().is_file());
    assert_eq!(std::fs::read(&mesh).unwrap(), b"solid cube");
    std::fs::remove_dir_all(&dir).unwrap();
    std::fs::remove_file(&elsewhere).unwrap();
}

// ---- writing only inside the folder -------------------------------------------------------

/// A model whose asset `<model>` file names `parts/p.stl` (so export writes
/// `parts/p.stl` beside it) and, with `deeper`, `parts/deep/q.stl`.
fn model_with_parts() -> Model {
    let robot = r#"<mujoco model="r"><asset><mesh file="parts/p.stl"/><mesh file="parts/deep/q.stl"/></asset></mujoco>"#;
    ReadOptions::new()
        .asset("robot.xml", robot.as_bytes().to_vec())
        .asset("parts/p.stl", b"solid p".to_vec())
        .asset("parts/deep/q.stl", b"solid q".to_vec())
        .read_str(
            r#"<mujoco model="scene"><asset><model name="r" file="robot.xml"/></asset></mujoco>"#,
        )
        .unwrap()
}

/// Every file under `dir`, as paths relative to it (symlinks listed, not followed).
fn tree(dir: &Path) -> BTreeSet<String> {
    let mut out = BTreeSet::new();
    let mut todo = vec![dir.to_path_buf()];
    while let Some(d) = todo.pop() {
        for e in std::fs::read_dir(&d).unwrap() {
            let p = e.unwrap().path();
            let rel = p.strip_prefix(dir).unwrap().to_string_lossy().into_owned();
            if std::fs::symlink_metadata(&p).unwrap().is_dir() {
                todo.push(p);
                out.insert(format!("{rel}/"));
            } else {
                out.insert(rel);
            }
        }
    }
    out
}

#[test]
fn a_model_files_own_files_are_written_in_real_subfolders() {
    let m = model_with_parts();
    let dir = temp_path("parts");
    m.export(&dir, "scene.xml", &plain()).unwrap();
    let want =
        ["parts/", "parts/deep/", "parts/deep/q.stl", "parts/p.stl", "robot.xml", "scene.xml"];
    assert_eq!(tree(&dir), want.iter().map(|s| s.to_string()).collect());
    assert!(std::fs::symlink_metadata(dir.join("parts")).unwrap().is_dir());
    assert_eq!(std::fs::read(dir.join("parts/deep/q.stl")).unwrap(), b"solid q");
    // Again, into the folders now there.
    m.export(&dir, "scene.xml", &plain()).unwrap();
    assert_eq!(tree(&dir).len(), want.len());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `out/parts` a symlink to a folder outside `out/`: the export would write
/// `parts/p.stl` there. It is refused before anything is written, and the folder
/// outside stays empty; the same for a symlink to a folder inside `out/` (export
/// writes only into real folders) and for a symlink deeper down (`parts/deep`).
#[cfg(unix)]
#[test]
fn a_symlinked_subfolder_is_refused_before_anything_is_written() {
    let m = model_with_parts();
    for (link, target_inside) in [("parts", false), ("parts", true), ("parts/deep", false)] {
        let dir = temp_path("symlinked-parts");
        let outside = temp_path("outside");
        std::fs::create_dir_all(&outside).unwrap();
        std::fs::create_dir_all(dir.join("real")).unwrap();
        if link == "parts/deep" {
            std::fs::create_dir_all(dir.join("parts")).unwrap();
        }
        let target = if target_inside { dir.join("real") } else { outside.clone() };
        std::os::unix::fs::symlink(&target, dir.join(link)).unwrap();
        let before = tree(&dir);
        let e = m.export(&dir, "scene.xml", &plain()).unwrap_err();
        assert_eq!(e, ExportError::SymlinkedFolder { path: dir.join(link) }, "{link}");
        assert!(e.to_string().contains("symbolic link"), "{e}");
        assert_eq!(tree(&dir), before, "{link}: nothing written");
        assert!(tree(&outside).is_empty(), "{link}: nothing written outside");
        assert!(tree(&dir.join("real")).is_empty());
        std::fs::remove_dir_all(&dir).unwrap();
        std::fs::remove_dir_all(&outside).unwrap();
    }
}

/// A file where a folder of a path should be: refused before anything is written.
#[test]
fn a_file_in_place_of_a_subfolder_is_refused_before_anything_is_written() {
    let m = model_with_parts();
    let dir = temp_path("file-for-folder");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("parts"), "a file").unwrap();
    let e = m.export(&dir, "scene.xml", &plain()).unwrap_err();
    assert!(
        matches!(&e, ExportError::Io { path, kind: std::io::ErrorKind::NotADirectory, .. } if *path == dir.join("parts")),
        "{e:?}"
    );
    assert_eq!(listing(&dir), BTreeSet::from(["parts".to_string()]));
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The export folder itself is the caller's: given as a symlink (or a path through
/// one), it is written through, into the folder it points at.
#[cfg(unix)]
#[test]
fn the_export_folder_itself_may_be_a_symlink() {
    let m = model_with_parts();
    let real = temp_path("real-out");
    std::fs::create_dir_all(&real).unwrap();
    let link = temp_path("link-out");
    std::os::unix::fs::symlink(&real, &link).unwrap();
    let xml = m.export(link.join("sub"), "scene.xml", &plain()).unwrap();
    assert_eq!(xml, link.join("sub/scene.xml"));
    assert!(tree(&real).contains("sub/parts/p.stl"));
    std::fs::remove_file(&link).unwrap();
    std::fs::remove_dir_all(&real).unwrap();
}

/// A bad MJCF file name (NUL, 300 characters) or file name among the model's files
/// (NUL, a 300-byte stem, a file that is also a folder) is refused before anything
/// is written: the folder is not even created.
#[test]
fn bad_names_are_refused_before_any_file_is_written() {
    let m = model_with_parts();
    let dir = temp_path("bad-names");
    let long = format!("{}.xml", "x".repeat(300));
    for bad in ["a\0b.xml", long.as_str()] {
        let e = m.export(&dir, bad, &plain()).unwrap_err();
        assert!(
            matches!(&e, ExportError::Io { kind: std::io::ErrorKind::InvalidInput, path, .. } if *path == dir.join(bad)),
            "{e:?}"
        );
        assert!(!dir.exists(), "{bad:?}");
    }
    // 255 bytes is fine.
    let longest = format!("{}.xml", "x".repeat(251));
    m.export(&dir, &longest, &plain()).unwrap();
    assert!(dir.join(&longest).is_file());
    std::fs::remove_dir_all(&dir).unwrap();

    // A file of the model under a bad name, beside good ones.
    let mesh = |m: &Model, i: usize| m.find_all(Namespace::Mesh)[i].clone();
    let base = ReadOptions::new()
        .asset("a.stl", b"solid a".to_vec())
        .asset("b.stl", b"solid b".to_vec())
        .read_str(r#"<mujoco><asset><mesh file="a.stl"/><mesh file="b.stl"/></asset></mujoco>"#)
        .unwrap();
    for stem in ["n\0ul", &"y".repeat(300)] {
        let file = mjcf::Value::File(mjcf::FileAsset::new(stem, ".stl", b"solid bad".to_vec()));
        let bad = base.set_attr(&mesh(&base, 1), "file", file).unwrap();
        for options in [plain(), WriteOptions::default()] {
            let e = bad.export(&dir, "m.xml", &options).unwrap_err();
            if stem.contains('\0') {
                // The writer refuses it in the MJCF already.
                assert!(
                    matches!(
                        e,
                        ExportError::Write(WriteError::InvalidCharacter { character: '\0', .. })
                    ),
                    "{e:?}"
                );
            } else {
                assert!(
                    matches!(&e, ExportError::Io { kind: std::io::ErrorKind::InvalidInput, reason, .. } if reason.contains("255 bytes")),
                    "{e:?}"
                );
            }
            assert!(!dir.exists(), "{stem:?}");
        }
    }
    // NUL in a name the writer does not write: a model file's own file (read from
    // the model file's text, where MuJoCo would report it).
    let robot = "<mujoco><asset><mesh file=\"p\0.stl\"/><mesh file=\"ok.stl\"/></asset></mujoco>";
    let nul = ReadOptions::new()
        .asset("robot.xml", robot.as_bytes().to_vec())
        .asset("p\0.stl", b"solid p".to_vec())
        .asset("ok.stl", b"solid ok".to_vec())
        .read_str(r#"<mujoco><asset><model name="r" file="robot.xml"/></asset></mujoco>"#)
        .unwrap();
    let e = nul.export(&dir, "m.xml", &plain()).unwrap_err();
    assert!(
        matches!(&e, ExportError::Io { kind: std::io::ErrorKind::InvalidInput, path, .. } if *path == dir.join("p\0.stl")),
        "{e:?}"
    );
    assert!(!dir.exists());
    // A model file's own file named like another file's folder: `parts` and
    // `parts/p.stl`.
    let clash = model_with_parts();
    let file = mjcf::Value::File(mjcf::FileAsset::new("parts", "", b"a file".to_vec()));
    let clash = clash
        .add(&clash.asset(), mjcf::Element::new("hfield").attr("name", "h").attr("size", [1.0; 4]))
        .unwrap()
        .0;
    let h = clash.lookup(Namespace::Hfield, "h").unwrap();
    let clash = clash.set_attr(&h, "file", file).unwrap();
    let e = clash.export(&dir, "m.xml", &plain()).unwrap_err();
    assert!(
        matches!(&e, ExportError::Io { kind: std::io::ErrorKind::InvalidInput, path, .. } if *path == dir.join("parts")),
        "{e:?}"
    );
    assert!(!dir.exists());
}
