//! Files a model names on disk: confinement with symlinks followed, the size cap on one
//! file, files that are not regular files (devices, FIFOs, folders), and characters
//! XML cannot hold in model names. Each case must give a typed error at once (never a
//! hang or a panic). README "Guarantees and limits" lists these limits.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

use mjcf::{Element, ErrorKind, Model, Namespace, ReadOptions, ValueError, WriteError};

/// A fresh empty folder under the system's temp folder, removed when dropped.
struct TempDir(PathBuf);

impl TempDir {
    fn new(tag: &str) -> TempDir {
        static N: AtomicUsize = AtomicUsize::new(0);
        let dir = std::env::temp_dir().join(format!(
            "mjcf-files-{}-{}-{}",
            std::process::id(),
            tag,
            N.fetch_add(1, Ordering::Relaxed)
        ));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        TempDir(dir)
    }

    fn path(&self) -> &Path {
        &self.0
    }

    /// Writes `text` to `name` (creating folders) and returns its path.
    fn write(&self, name: &str, text: &str) -> PathBuf {
        let p = self.0.join(name);
        if let Some(parent) = p.parent() {
            std::fs::create_dir_all(parent).unwrap();
        }
        std::fs::write(&p, text).unwrap();
        p
    }

    /// A symlink at `name` (inside this folder) pointing at `target` as written.
    #[cfg(unix)]
    fn symlink(&self, target: &str, name: &str) {
        let p = self.0.join(name);
        if let Some(parent) = p.parent() {
            std::fs::create_dir_all(parent).unwrap();
        }
        std::os::unix::fs::symlink(target, &p).unwrap();
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

const STL: &str = "solid box\nendsolid box\n";

fn confined() -> ReadOptions {
    ReadOptions::new().confine_to_base_dir(true)
}

fn kind_of(r: Result<Model, mjcf::ReadError>) -> ErrorKind {
    r.expect_err("expected an error").kind().clone()
}

/// Runs `f` on another thread and fails the test if it does not finish in time, so a
/// blocking `open` shows as a failure instead of a hung test run.
fn within<T: Send + 'static>(secs: u64, f: impl FnOnce() -> T + Send + 'static) -> T {
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let _ = tx.send(f());
    });
    match rx.recv_timeout(Duration::from_secs(secs)) {
        Ok(v) => v,
        Err(_) => panic!("did not finish within {secs} s (blocked on a file?)"),
    }
}

// ---- symlinks and confinement -----------------------------------------------------------

#[cfg(unix)]
#[test]
fn symlinked_file_leaving_the_folder_is_refused_when_confined_and_read_without() {
    let d = TempDir::new("link-out");
    d.write("outside.stl", STL);
    d.symlink("../outside.stl", "model/link.stl");
    let main = d
        .write("model/main.xml", "<mujoco>\n  <asset><mesh file=\"link.stl\"/></asset>\n</mujoco>");

    let err = confined().read_path(&main).unwrap_err();
    assert!(
        matches!(err.kind(), ErrorKind::FileOutsideRoot(p) if p.ends_with("link.stl")),
        "{err}"
    );
    assert_eq!(err.pos().map(|p| p.line), Some(2));

    // Without confinement the symlink is followed, as before.
    let m = Model::from_path(&main).unwrap();
    assert!(m.find(Namespace::Mesh, "link").is_some());
}

#[cfg(unix)]
#[test]
fn symlinked_folder_leaving_the_folder_is_refused_for_every_file_attribute() {
    let d = TempDir::new("dir-out");
    d.write("elsewhere/box.stl", STL);
    d.write("elsewhere/t.png", "not really a png");
    d.write("elsewhere/h.png", "not really a png");
    d.write("elsewhere/s.skn", "skin");
    d.symlink("../elsewhere", "model/sub");
    let cases = [
        r#"<mesh file="sub/box.stl"/>"#,
        r#"<texture name="t" type="2d" file="sub/t.png"/>"#,
        r#"<hfield name="h" size="1 1 1 1" file="sub/h.png"/>"#,
        r#"<skin name="s" file="sub/s.skn"/>"#,
    ];
    for (i, asset) in cases.iter().enumerate() {
        let main = d
            .write(&format!("model/m{i}.xml"), &format!("<mujoco><asset>{asset}</asset></mujoco>"));
        let err = kind_of(confined().read_path(&main));
        assert!(matches!(err, ErrorKind::FileOutsideRoot(_)), "{asset}: {err}");
        Model::from_path(&main).unwrap_or_else(|e| panic!("{asset} without confinement: {e}"));
    }

    // `..` after a symlinked folder: textually inside (`model/box.stl`), but the system
    // resolves it from the symlink's target, outside the folder.
    d.write("elsewhere/inner/.keep", "");
    d.symlink("../elsewhere/inner", "model/deep");
    let main = d.write(
        "model/dotdot.xml",
        r#"<mujoco><asset><mesh file="deep/../box.stl"/></asset></mujoco>"#,
    );
    assert!(matches!(kind_of(confined().read_path(&main)), ErrorKind::FileOutsideRoot(_)));
}

#[cfg(unix)]
#[test]
fn symlinks_staying_inside_the_folder_are_accepted_when_confined() {
    let d = TempDir::new("link-in");
    d.write("model/real/box.stl", STL);
    d.symlink("real/box.stl", "model/link.stl");
    d.symlink("real", "model/alias");
    // An absolute symlink target inside the folder is fine too.
    let abs = d.path().join("model/real/box.stl");
    d.symlink(abs.to_str().unwrap(), "model/abs.stl");
    let main = d.write(
        "model/main.xml",
        r#"<mujoco><asset>
  <mesh file="link.stl"/>
  <mesh name="aliased" file="alias/box.stl"/>
  <mesh file="abs.stl"/>
</asset></mujoco>"#,
    );
    let m = confined().read_path(&main).unwrap();
    for name in ["link", "aliased", "abs"] {
        assert!(m.find(Namespace::Mesh, name).is_some(), "{name}");
    }
    // The model's own folder may be reached through a symlink as well.
    d.symlink("model", "model-link");
    let m = confined().read_path(d.path().join("model-link/main.xml")).unwrap();
    assert!(m.find(Namespace::Mesh, "aliased").is_some());
}

#[cfg(unix)]
#[test]
fn include_through_a_symlink_leaving_the_folder_is_refused_when_confined() {
    let d = TempDir::new("include-out");
    d.write("outside.xml", r#"<mujoco><worldbody><body name="stolen"/></worldbody></mujoco>"#);
    d.write("outside.stl", STL);
    d.symlink("../outside.xml", "model/inc.xml");
    let main = d.write("model/main.xml", "<mujoco>\n  <include file=\"inc.xml\"/>\n</mujoco>");
    let err = confined().read_path(&main).unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::FileOutsideRoot(p) if p.ends_with("inc.xml")), "{err}");
    assert_eq!(err.pos().map(|p| p.line), Some(2));
    assert!(Model::from_path(&main).unwrap().find(Namespace::Body, "stolen").is_some());

    // A file named inside an included file is checked too (against that file's folder).
    d.write("model/parts/part.xml", r#"<mujoco><asset><mesh file="link.stl"/></asset></mujoco>"#);
    d.symlink("../../outside.stl", "model/parts/link.stl");
    let main = d.write("model/main2.xml", r#"<mujoco><include file="parts/part.xml"/></mujoco>"#);
    let err = confined().read_path(&main).unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::FileOutsideRoot(_)), "{err}");
    assert!(err.file().is_some_and(|f| f.ends_with("part.xml")), "{err}");
    assert!(Model::from_path(&main).unwrap().find(Namespace::Mesh, "link").is_some());
}

#[cfg(unix)]
#[test]
fn later_edit_through_a_symlink_leaving_the_folder_is_refused_on_a_confined_model() {
    let d = TempDir::new("edit-out");
    d.write("outside.stl", STL);
    d.write("model/real.stl", STL);
    d.symlink("../outside.stl", "model/link.stl");
    d.symlink("real.stl", "model/inside.stl");
    let main = d.write("model/main.xml", "<mujoco/>");

    let m = confined().read_path(&main).unwrap();
    let err = m.add(&m.asset(), Element::new("mesh").attr("file", "link.stl")).unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::FileOutsideRoot(_)), "{err}");
    let (m2, _) = m.add(&m.asset(), Element::new("mesh").attr("file", "inside.stl")).unwrap();
    assert!(m2.find(Namespace::Mesh, "inside").is_some());

    // The same edit on a model read without confinement follows the symlink.
    let open = Model::from_path(&main).unwrap();
    assert!(open.add(&open.asset(), Element::new("mesh").attr("file", "link.stl")).is_ok());
}

// ---- files that are not regular files ------------------------------------------------

#[cfg(unix)]
#[test]
fn dev_zero_as_include_and_as_mesh_file_is_a_typed_error_at_once() {
    if !Path::new("/dev/zero").exists() {
        println!("skipped: no /dev/zero on this system");
        return;
    }
    let d = TempDir::new("dev-zero");
    d.symlink("/dev/zero", "model/zero.stl");
    d.symlink("/dev/zero", "model/zero.xml");
    let dir = d.path().join("model");
    let start = Instant::now();
    let include = r#"<mujoco><include file="/dev/zero"/></mujoco>"#;
    let mesh = r#"<mujoco><asset><mesh file="/dev/zero"/></asset></mujoco>"#;
    for text in [include, mesh] {
        let err = kind_of(ReadOptions::new().base_dir(&dir).read_str(text));
        assert!(matches!(&err, ErrorKind::NotAFile(p) if p.ends_with("zero")), "{text}: {err}");
    }
    // Through a symlink inside the folder: outside it when confined, and not a regular
    // file either way.
    for file in ["zero.stl", "zero.xml"] {
        let text = if file.ends_with(".xml") {
            format!(r#"<mujoco><include file="{file}"/></mujoco>"#)
        } else {
            format!(r#"<mujoco><asset><mesh file="{file}"/></asset></mujoco>"#)
        };
        let err = kind_of(ReadOptions::new().base_dir(&dir).read_str(&text));
        assert!(matches!(err, ErrorKind::NotAFile(_)), "{file}: {err}");
        let err = kind_of(confined().base_dir(&dir).read_str(&text));
        assert!(matches!(err, ErrorKind::FileOutsideRoot(_)), "{file}: {err}");
    }
    // As the model file itself, and in a later edit.
    assert!(matches!(kind_of(Model::from_path("/dev/zero")), ErrorKind::NotAFile(_)));
    let m = ReadOptions::new().base_dir(&dir).read_str("<mujoco/>").unwrap();
    let err = m.add(&m.asset(), Element::new("mesh").attr("file", "zero.stl")).unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::NotAFile(_)), "{err}");
    assert!(start.elapsed() < Duration::from_secs(5), "took {:?}", start.elapsed());
}

#[cfg(unix)]
#[test]
fn fifo_as_include_and_as_mesh_file_is_a_typed_error_without_hanging() {
    let d = TempDir::new("fifo");
    let model = d.path().join("model");
    std::fs::create_dir_all(&model).unwrap();
    for name in ["pipe.stl", "pipe.xml"] {
        let made = std::process::Command::new("mkfifo").arg(model.join(name)).status();
        if !made.is_ok_and(|s| s.success()) {
            println!("skipped: mkfifo is not available, so no FIFO to read");
            return;
        }
    }
    for (text, file) in [
        (r#"<mujoco><include file="pipe.xml"/></mujoco>"#, "pipe.xml"),
        (r#"<mujoco><asset><mesh file="pipe.stl"/></asset></mujoco>"#, "pipe.stl"),
    ] {
        for confine in [false, true] {
            let opts = ReadOptions::new().confine_to_base_dir(confine).base_dir(&model);
            let err = within(10, move || kind_of(opts.read_str(text)));
            assert!(
                matches!(&err, ErrorKind::NotAFile(p) if p.ends_with(file)),
                "{text} (confined: {confine}): {err}"
            );
        }
    }
    let pipe = model.join("pipe.xml");
    let err = within(10, move || kind_of(Model::from_path(pipe)));
    assert!(matches!(err, ErrorKind::NotAFile(_)), "{err}");
}

#[test]
fn folder_named_as_a_file_is_not_a_file() {
    let d = TempDir::new("folder");
    std::fs::create_dir_all(d.path().join("model/dir.stl")).unwrap();
    std::fs::create_dir_all(d.path().join("model/dir.xml")).unwrap();
    let model = d.path().join("model");
    let mesh = r#"<mujoco><asset><mesh file="dir.stl"/></asset></mujoco>"#;
    let include = r#"<mujoco><include file="dir.xml"/></mujoco>"#;
    for text in [mesh, include] {
        let err = kind_of(ReadOptions::new().base_dir(&model).read_str(text));
        assert!(matches!(err, ErrorKind::NotAFile(_)), "{text}: {err}");
    }
    assert!(matches!(kind_of(Model::from_path(model.join("dir.xml"))), ErrorKind::NotAFile(_)));
}

// ---- the size cap ------------------------------------------------------------------------

#[test]
fn file_over_max_file_size_is_too_large() {
    let d = TempDir::new("cap");
    let big = "x".repeat(100);
    d.write("model/big.stl", &big);
    d.write("model/parts/part.xml", r#"<mujoco><asset><mesh file="../big.stl"/></asset></mujoco>"#);
    let main =
        d.write("model/main.xml", r#"<mujoco><asset><mesh file="big.stl"/></asset></mujoco>"#);
    let model = d.path().join("model");

    // A file attribute over the cap; at the cap is fine.
    let err = kind_of(ReadOptions::new().max_file_size(99).read_path(&main));
    assert!(
        matches!(&err, ErrorKind::FileTooLarge { path, limit: 99 } if path.ends_with("big.stl")),
        "{err}"
    );
    assert!(ReadOptions::new().max_file_size(100).read_path(&main).is_ok());

    // The model file itself.
    let err = kind_of(ReadOptions::new().max_file_size(10).read_path(&main));
    assert!(matches!(err, ErrorKind::FileTooLarge { limit: 10, .. }), "{err}");

    // An include over the cap, and a file named inside an include (the cap carries in).
    let pad = format!("<mujoco><!-- {} --></mujoco>", "p".repeat(200));
    d.write("model/padded.xml", &pad);
    let opts = ReadOptions::new().max_file_size(150).base_dir(&model);
    let err = kind_of(opts.read_str(r#"<mujoco><include file="padded.xml"/></mujoco>"#));
    assert!(matches!(&err, ErrorKind::FileTooLarge { path, .. } if path.ends_with("padded.xml")));
    let err = kind_of(
        ReadOptions::new()
            .max_file_size(99)
            .base_dir(&model)
            .read_str(r#"<mujoco><include file="parts/part.xml"/></mujoco>"#),
    );
    assert!(matches!(err, ErrorKind::FileTooLarge { limit: 99, .. }), "{err}");

    // The cap carries into later edits of the model read.
    let m = ReadOptions::new().max_file_size(99).base_dir(&model).read_str("<mujoco/>").unwrap();
    let err = m.add(&m.asset(), Element::new("mesh").attr("file", "big.stl")).unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::FileTooLarge { limit: 99, .. }), "{err}");

    // In-memory files are not files on disk: no cap.
    let m = ReadOptions::new()
        .max_file_size(1)
        .asset("mem.stl", big.into_bytes())
        .read_str(r#"<mujoco><asset><mesh file="mem.stl"/></asset></mujoco>"#)
        .unwrap();
    assert!(m.find(Namespace::Mesh, "mem").is_some());
}

// ---- model names ---------------------------------------------------------------------------

fn invalid_character(e: &mjcf::EditError) -> Option<char> {
    match e.kind() {
        ErrorKind::InvalidValue { error: ValueError::InvalidCharacter(c), .. } => Some(*c),
        _ => None,
    }
}

#[test]
fn nul_and_other_non_xml_characters_in_model_names_are_refused_by_try_new_and_try_with_name() {
    for (name, bad) in [("a\0b", '\0'), ("\u{1}", '\u{1}'), ("x\u{FFFE}", '\u{FFFE}')] {
        let e = Model::try_new(name).unwrap_err();
        assert_eq!(invalid_character(&e), Some(bad), "{e}");
        let m = Model::new("ok");
        let e = m.try_with_name(name).unwrap_err();
        assert_eq!(invalid_character(&e), Some(bad), "{e}");
        assert_eq!(m.name(), "ok");
    }
    // Tab, newline, non-ASCII and the empty name are fine.
    assert_eq!(Model::try_new("a\tb é").unwrap().name(), "a\tb é");
    assert_eq!(Model::try_new("").unwrap().name(), "unnamed_model");
    assert_eq!(Model::new("x").try_with_name("y").unwrap().name(), "y");
}

#[test]
fn nul_in_a_model_name_given_to_new_makes_writing_a_typed_error_not_a_panic() {
    let m = Model::new("a\0b");
    assert!(matches!(m.to_xml_string(), Err(WriteError::InvalidCharacter { character: '\0', .. })));
    let m = Model::new("ok").with_name("a\0b");
    assert!(matches!(m.to_xml_string(), Err(WriteError::InvalidCharacter { character: '\0', .. })));
    // Attached under such a name, the scope prefix carries it into written names.
    let child = Model::new("r\0");
    let (child, _) =
        child.add(&child.worldbody(), Element::new("body").attr("name", "torso")).unwrap();
    let (scene, _) = Model::new("arena").attach_to_world(&child).unwrap();
    assert!(matches!(scene.to_xml_string(), Err(WriteError::InvalidCharacter { .. })));
}

#[test]
fn nul_in_a_scope_name_is_refused_by_rename_scope() {
    let robot = Model::new("robot");
    let (scene, _) = Model::new("arena").attach_to_world(&robot).unwrap();
    let e = scene.rename_scope("robot", "r\0").unwrap_err();
    assert_eq!(invalid_character(&e), Some('\0'), "{e}");
    let e = scene.rename_scope("robot", "\u{FFFF}").unwrap_err();
    assert_eq!(invalid_character(&e), Some('\u{FFFF}'), "{e}");
    let mut m = scene.clone();
    assert!(m.rename_scope_mut("robot", "a\u{8}").is_err());
    assert_eq!(m, scene);
    assert!(scene.rename_scope("robot", "arm").is_ok());
}
