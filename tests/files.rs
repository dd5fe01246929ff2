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

// ---- DAGs of files ----------------------------------------------------------------------

/// A chain of `n` include files on disk, each including the next twice (at the root,
/// or inside `<worldbody>`), the last adding a geom; returns the first.
fn includes_twice(d: &TempDir, n: usize, inline: bool) -> PathBuf {
    for i in 1..=n {
        let body = if i < n {
            let inc = format!(r#"<include file="inc{}.xml"/>"#, i + 1);
            format!("\n{inc}\n{inc}\n")
        } else {
            r#"<geom size="1"/>"#.to_string()
        };
        let text = match (inline, i < n) {
            (true, _) => format!("<mujoco>{body}</mujoco>"),
            (false, true) => format!("<mujoco>{body}</mujoco>"),
            (false, false) => format!("<mujoco><worldbody>{body}</worldbody></mujoco>"),
        };
        d.write(&format!("inc{i}.xml"), &text);
    }
    d.path().join("inc1.xml")
}

/// 30 files each including the next twice would paste 2^29 copies of the last; as
/// MuJoCo does, the second include of a file already included is refused, at once
/// (the first include read all 30 files once), naming the file and the place.
#[test]
fn includes_each_including_the_next_twice_stop_at_the_first_file_included_twice() {
    for inline in [false, true] {
        let d = TempDir::new("include-dag");
        includes_twice(&d, 30, inline);
        let main = if inline {
            d.write(
                "main.xml",
                r#"<mujoco><worldbody><include file="inc1.xml"/></worldbody></mujoco>"#,
            )
        } else {
            d.write("main.xml", r#"<mujoco><include file="inc1.xml"/></mujoco>"#)
        };
        let err = within(60, move || Model::from_path(main).unwrap_err());
        assert!(
            matches!(err.kind(), ErrorKind::IncludedTwice(p) if p.ends_with("inc30.xml")),
            "{err}"
        );
        assert!(err.file().is_some_and(|f| f.ends_with("inc29.xml")), "{err}");
        assert_eq!(err.pos().map(|p| (p.line, p.column)), Some((3, 1)), "{err}");
    }
    // The same from in-memory files.
    let mut opts = ReadOptions::new();
    for i in 1..30 {
        let inc = format!(r#"<include file="inc{}.xml"/>"#, i + 1);
        opts = opts.asset(
            &format!("inc{i}.xml"),
            format!("<mujoco>\n{inc}\n{inc}\n</mujoco>").into_bytes(),
        );
    }
    let opts = opts.asset(
        "inc30.xml",
        r#"<mujoco><worldbody><geom size="1"/></worldbody></mujoco>"#.as_bytes().to_vec(),
    );
    let err = within(60, move || {
        opts.read_str(r#"<mujoco><include file="inc1.xml"/></mujoco>"#).unwrap_err()
    });
    assert!(matches!(err.kind(), ErrorKind::IncludedTwice(p) if p.ends_with("inc30.xml")), "{err}");
    assert!(err.file().is_some_and(|f| f.ends_with("inc29.xml")), "{err}");
    assert_eq!(err.pos().map(|p| (p.line, p.column)), Some((3, 1)), "{err}");
}

/// The files an asset `<model>` brings (its companions), as a set of paths.
fn companions(m: &Model) -> std::collections::BTreeSet<String> {
    let loc = &m.find_all(Namespace::Model)[0];
    let element = m.element(loc).unwrap();
    let Some(mjcf::Value::File(f)) = element.attr("file") else { panic!("no model file") };
    f.companions().iter().map(|(p, _)| p.to_string()).collect()
}

/// The names other than `fK.xml` the next file is named by: symlinks to it on disk,
/// other keys with the same bytes in memory.
const ALIASES: [char; 3] = ['g', 'h', 'i'];

/// `f1.xml` … `f{n}.xml`, each naming the next four times as an asset model, by four
/// paths: `./fK.xml`, `gK.xml`, `hK.xml` and `x/../iK.xml` (and `fK.xml` once more);
/// the last names a mesh. Returns the files and the paths the first one brings.
fn model_chain(n: usize) -> (Vec<(String, String)>, std::collections::BTreeSet<String>) {
    let mut files = Vec::new();
    let mut want = std::collections::BTreeSet::from(["m.stl".to_string()]);
    for i in 1..=n {
        let text = if i < n {
            let k = i + 1;
            want.extend(["f", "g", "h", "i"].map(|c| format!("{c}{k}.xml")));
            format!(
                r#"<mujoco><asset><model name="a" file="./f{k}.xml"/><model name="b" file="g{k}.xml"/><model name="c" file="h{k}.xml"/><model name="d" file="x/../i{k}.xml"/><model name="e" file="f{k}.xml"/></asset></mujoco>"#
            )
        } else {
            r#"<mujoco><asset><mesh file="m.stl"/></asset></mujoco>"#.to_string()
        };
        files.push((format!("f{i}.xml"), text));
    }
    (files, want)
}

const MAIN_WITH_MODEL: &str = r#"<mujoco><asset><model name="m" file="f1.xml"/></asset></mujoco>"#;

/// Each model file names the next four times, by four paths (three of them symlinks):
/// 16 levels, as deep as model files go, would read the last file 4^15 times. Each
/// file is read once per read (by canonical path, or by contents for in-memory files),
/// and brings each path once. An edit that sets the file reads it the same way.
#[cfg(unix)]
#[test]
fn asset_model_files_naming_the_next_four_times_are_read_once_each() {
    let (files, want) = model_chain(16);
    assert_eq!(want.len(), 61);
    let d = TempDir::new("model-dag");
    d.write("m.stl", STL);
    d.write("x/.keep", "");
    for (name, text) in &files {
        d.write(name, text);
        if name != "f1.xml" {
            for c in ALIASES {
                d.symlink(name, &name.replacen('f', &c.to_string(), 1));
            }
        }
    }
    let main = d.write("main.xml", MAIN_WITH_MODEL);
    let m = within(60, move || Model::from_path(main).unwrap());
    assert_eq!(companions(&m), want);
    // Through an edit: the model file set again, from the same folder.
    let loc = m.find_all(Namespace::Model)[0].clone();
    let edited = within(60, move || m.set_attr(&loc, "file", "./f1.xml").unwrap());
    assert_eq!(companions(&edited), want);

    // In memory, `gK.xml` being another key with the same bytes.
    let mut opts = ReadOptions::new().asset("m.stl", STL.as_bytes().to_vec());
    for (name, text) in &files {
        opts = opts.asset(name, text.as_bytes().to_vec());
        for c in ALIASES {
            opts = opts.asset(&name.replacen('f', &c.to_string(), 1), text.as_bytes().to_vec());
        }
    }
    let m = within(60, move || opts.read_str(MAIN_WITH_MODEL).unwrap());
    assert_eq!(companions(&m), want);
}

/// Model files nest at most 16 deep. Whether a file read before (and not read again)
/// reaches too deep from where it is named again does not depend on the order: a file
/// 12 levels deep is refused named 6 levels down, also after it was read from the top.
#[test]
fn the_model_file_depth_limit_does_not_depend_on_what_was_read_first() {
    let (files, _) = model_chain(12);
    let mut opts = ReadOptions::new().asset("m.stl", STL.as_bytes().to_vec());
    for (name, text) in &files {
        opts = opts.asset(&name.replacen('f', "q", 1), text.as_bytes().to_vec());
        for c in ALIASES {
            opts = opts.asset(&name.replacen('f', &c.to_string(), 1), text.as_bytes().to_vec());
        }
    }
    // p1 … p6 lead to q1 (the chain's first file), six levels down.
    for i in 1..=6 {
        let next = if i < 6 { format!("p{}.xml", i + 1) } else { "q1.xml".to_string() };
        let text = format!(r#"<mujoco><asset><model name="n" file="{next}"/></asset></mujoco>"#);
        opts = opts.asset(&format!("p{i}.xml"), text.into_bytes());
    }
    // The chain from the top, alone: 12 levels, fine. Its first file is q1.xml; the
    // files name f*.xml and the aliases, which hold the same bytes as the q*.xml files.
    for (name, text) in &files {
        opts = opts.asset(name, text.as_bytes().to_vec());
    }
    let top = r#"<model name="top" file="q1.xml"/>"#;
    let deep = r#"<model name="deep" file="p1.xml"/>"#;
    let read = |assets: &str| opts.read_str(&format!("<mujoco><asset>{assets}</asset></mujoco>"));
    assert!(read(top).is_ok());
    for assets in [deep.to_string(), format!("{top}{deep}"), format!("{deep}{top}")] {
        let err = read(&assets).unwrap_err();
        assert_eq!(err.kind(), &ErrorKind::TooDeep(16), "{assets}: {err}");
    }
}

/// Folders that are symlinks to their own folder make each model file's files reachable
/// under ever more paths (`d1/d2/…/f.xml`): a file is still read once, and a model
/// file that brings more than 100,000 paths is refused with a typed error, at once.
#[cfg(unix)]
#[test]
fn model_files_reached_under_exponentially_many_paths_are_refused() {
    let d = TempDir::new("model-paths");
    for link in ["d1", "d2", "d3", "d4"] {
        d.symlink(".", link);
    }
    for i in 1..=16 {
        let text = if i < 16 {
            let k = i + 1;
            format!(
                r#"<mujoco><asset><model name="a" file="d1/f{k}.xml"/><model name="b" file="d2/f{k}.xml"/><model name="c" file="d3/f{k}.xml"/><model name="d" file="d4/f{k}.xml"/></asset></mujoco>"#
            )
        } else {
            "<mujoco/>".to_string()
        };
        d.write(&format!("f{i}.xml"), &text);
    }
    let main = d.write("main.xml", MAIN_WITH_MODEL);
    let err = within(60, move || Model::from_path(main).unwrap_err());
    assert_eq!(err.kind(), &ErrorKind::TooManyFiles(100_000), "{err}");
    // Fewer paths are fine: 4 + 16 + 64 + 256 from four levels.
    d.write("f5.xml", "<mujoco/>");
    let main = d.path().join("main.xml");
    let m = within(60, move || Model::from_path(main).unwrap());
    assert_eq!(companions(&m).len(), 4 + 16 + 64 + 256);
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

/// An asset `<model>` file brings every file its elements name as the reader finds
/// them (the schema's file attributes, not only those named `file`: a cube map's six
/// sides), with the folder each one's type names, and the files of an include inside a
/// section read as that section's content.
#[test]
fn an_asset_model_file_brings_every_file_attribute_and_its_includes_files() {
    let png = b"\x89PNG".to_vec();
    let robot = r#"<mujoco><compiler texturedir="tex"/><asset>
        <texture name="sky" type="skybox" fileright="r.png" fileleft="l.png" fileup="u.png" filedown="d.png" filefront="f.png" fileback="b.png"/>
        <include file="meshes.xml"/></asset></mujoco>"#;
    let meshes = r#"<mujoco><mesh file="arm.stl"/></mujoco>"#;
    let mut opts = ReadOptions::new()
        .asset("robot.xml", robot.as_bytes().to_vec())
        .asset("meshes.xml", meshes.as_bytes().to_vec())
        .asset("arm.stl", STL.as_bytes().to_vec());
    for side in ["r", "l", "u", "d", "f", "b"] {
        opts = opts.asset(&format!("tex/{side}.png"), png.clone());
    }
    let m = opts
        .read_str(r#"<mujoco><asset><model name="robot" file="robot.xml"/></asset></mujoco>"#)
        .unwrap();
    let mut want: std::collections::BTreeSet<String> =
        ["r", "l", "u", "d", "f", "b"].iter().map(|s| format!("tex/{s}.png")).collect();
    want.extend(["meshes.xml".to_string(), "arm.stl".to_string()]);
    assert_eq!(companions(&m), want);
}
