//! Hostile input: each test feeds something an attacker or a fuzzer could produce and
//! expects a typed error (or the correct result), never a panic, a stack overflow or a
//! hang. The limits these tests check are listed in the guide's "Guarantees and
//! limits" (`src/guide.md`).

use std::path::{Path, PathBuf};

use crate::dirs::temp_dir;

use mjcf::{
    Element, ErrorKind, MAX_LAYOUT_ENTRIES, Model, Namespace, ProblemKind, ReadOptions, Value,
    WriteError, WriteOptions,
};

fn write(dir: &Path, name: &str, text: &str) -> PathBuf {
    let p = dir.join(name);
    if let Some(parent) = p.parent() {
        std::fs::create_dir_all(parent).unwrap();
    }
    std::fs::write(&p, text).unwrap();
    p
}

fn kind_of(r: Result<Model, mjcf::ReadError>) -> ErrorKind {
    r.expect_err("expected an error").kind().clone()
}

// ---- includes -----------------------------------------------------------------------

#[test]
fn include_cycle_a_b_a_is_an_error_on_disk() {
    let dir = temp_dir("cycle");
    let a = write(&dir, "a.xml", r#"<mujoco><include file="b.xml"/><worldbody/></mujoco>"#);
    write(&dir, "b.xml", r#"<mujoco><include file="a.xml"/></mujoco>"#);
    let err = Model::from_path(&a).unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::IncludeCycle(p) if p.ends_with("a.xml")), "{err}");
    // Reported in b.xml, at the include that closes the cycle.
    assert!(err.file().is_some_and(|f| f.ends_with("b.xml")), "{err}");
    assert_eq!(err.pos().map(|p| (p.line, p.column)), Some((1, 9)));
}

#[test]
fn include_cycle_a_b_a_is_an_error_in_memory() {
    let err = ReadOptions::new()
        .asset("a.xml", br#"<mujoco><include file="b.xml"/></mujoco>"#.to_vec())
        .asset("b.xml", br#"<mujoco><include file="a.xml"/></mujoco>"#.to_vec())
        .read_str(r#"<mujoco><include file="a.xml"/></mujoco>"#)
        .unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::IncludeCycle(p) if p.ends_with("a.xml")), "{err}");
}

/// MuJoCo 4.0.0 reads every top-level `<default>` as its one root class `main` and
/// refuses one named otherwise ("top-level default class 'main' cannot be renamed"),
/// in the main file, given a second time, or in an included file; `main` and an empty
/// name are accepted (each shape compiled with MuJoCo 4.0.0). The reader refuses
/// them too, with MuJoCo's words and the place.
#[test]
fn a_top_level_default_named_other_than_main_is_refused_where_it_stands() {
    for (text, at) in [
        ("<mujoco><default class=\"top\"/></mujoco>", (1, 9)),
        (
            "<mujoco>\n<default/>\n  <default class=\"top\"><geom size=\"1\"/></default>\n</mujoco>",
            (3, 3),
        ),
    ] {
        let err = Model::from_xml_str(text).unwrap_err();
        assert_eq!(err.kind(), &ErrorKind::RootClassRenamed("top".into()), "{text}");
        assert_eq!(err.pos().map(|p| (p.line, p.column)), Some(at), "{text}");
        assert!(err.to_string().contains("top-level default class 'main' cannot be renamed"));
    }
    let included = ReadOptions::new()
        .asset("d.xml", br#"<mujoco><default class="top"/></mujoco>"#.to_vec())
        .read_str(r#"<mujoco><include file="d.xml"/></mujoco>"#)
        .unwrap_err();
    assert_eq!(included.kind(), &ErrorKind::RootClassRenamed("top".into()));
    assert!(included.file().is_some_and(|f| f.ends_with("d.xml")), "{included}");
    for fine in
        ["<mujoco><default class=\"main\"/></mujoco>", "<mujoco><default class=\"\"/></mujoco>"]
    {
        let m = Model::from_xml_str(fine).unwrap();
        assert_eq!(m.check(), [], "{fine}");
    }
}

/// The kind, file name and line:column of the error reading `main` (a path).
fn where_refused(main: &Path) -> (ErrorKind, String, (u32, u32)) {
    let err = Model::from_path(main).unwrap_err();
    let file = err.file().and_then(Path::file_name).unwrap().to_string_lossy().into_owned();
    (err.kind().clone(), file, err.pos().map(|p| (p.line, p.column)).unwrap())
}

/// MuJoCo 4.0 refuses a file included twice within one model's include tree ("File
/// 'a.xml' already included"), wherever the two includes are: side by side, in other
/// elements, in other branches of the tree, spelled differently (`./a.xml`,
/// `sub/../a.xml`), or the main file itself (a cycle). Each case below was compiled
/// with MuJoCo 4.0 from files like these, and refused.
#[test]
fn a_file_included_twice_in_one_include_tree_is_refused_as_mujoco_does() {
    let geoms = r#"<mujoco><worldbody><geom size="1"/></worldbody></mujoco>"#;
    let twice = |main: &str| {
        let dir = temp_dir("twice");
        write(&dir, "a.xml", geoms);
        write(&dir, "g.xml", r#"<mujoco><geom size="1"/></mujoco>"#);
        write(&dir, "e.xml", r#"<mujoco><site name="s"/></mujoco>"#);
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        where_refused(&write(&dir, "main.xml", main))
    };
    for (main, twice_included, pos) in [
        // Side by side at the root, and spelled otherwise.
        (
            "<mujoco>\n<include file=\"a.xml\"/>\n<include file=\"a.xml\"/></mujoco>",
            "a.xml",
            (3, 1),
        ),
        (
            "<mujoco>\n<include file=\"a.xml\"/><include file=\"./a.xml\"/></mujoco>",
            "a.xml",
            (2, 24),
        ),
        (
            "<mujoco><include file=\"a.xml\"/><include file=\"sub/../a.xml\"/></mujoco>",
            "a.xml",
            (1, 32),
        ),
        // Inside an element, and in two different elements.
        (
            "<mujoco><worldbody>\n  <include file=\"g.xml\"/>\n  <include file=\"g.xml\"/></worldbody></mujoco>",
            "g.xml",
            (3, 3),
        ),
        // One inside an element, one at the root.
        (
            "<mujoco><worldbody><include file=\"e.xml\"/></worldbody><include file=\"e.xml\"/></mujoco>",
            "e.xml",
            (1, 55),
        ),
    ] {
        let (kind, file, at) = twice(main);
        assert!(
            matches!(&kind, ErrorKind::IncludedTwice(p) if p.ends_with(twice_included)),
            "{main}: {kind}"
        );
        assert_eq!((file.as_str(), at), ("main.xml", pos), "{main}");
    }
    let (kind, file, at) = twice(
        r#"<mujoco><worldbody><body><include file="g.xml"/></body><body><include file="g.xml"/></body></worldbody></mujoco>"#,
    );
    assert!(matches!(&kind, ErrorKind::IncludedTwice(p) if p.ends_with("g.xml")), "{kind}");
    assert_eq!((file.as_str(), at), ("main.xml", (1, 62)));

    // In two branches: main includes x and y, each includes common; refused in y.
    let dir = temp_dir("branches");
    write(
        &dir,
        "x.xml",
        r#"<mujoco><include file="common.xml"/><worldbody><body name="x"/></worldbody></mujoco>"#,
    );
    write(&dir, "y.xml", "<mujoco>\n  <include file=\"common.xml\"/></mujoco>");
    write(&dir, "common.xml", r#"<mujoco><compiler angle="radian"/></mujoco>"#);
    let main = write(
        &dir,
        "main.xml",
        r#"<mujoco><include file="x.xml"/><include file="y.xml"/></mujoco>"#,
    );
    let (kind, file, at) = where_refused(&main);
    assert!(matches!(&kind, ErrorKind::IncludedTwice(p) if p.ends_with("common.xml")), "{kind}");
    assert_eq!((file.as_str(), at), ("y.xml", (2, 3)));
    // The message says which file, and where.
    let err = Model::from_path(&main).unwrap_err().to_string();
    assert!(
        err.contains("common.xml")
            && err.contains("already included")
            && err.ends_with("y.xml:2:3"),
        "{err}"
    );

    // The main file included again from an included file is a cycle.
    let dir = temp_dir("main-again");
    write(&dir, "b.xml", r#"<mujoco><include file="main.xml"/></mujoco>"#);
    let main = write(&dir, "main.xml", r#"<mujoco><include file="b.xml"/></mujoco>"#);
    let (kind, file, _) = where_refused(&main);
    assert!(matches!(&kind, ErrorKind::IncludeCycle(p) if p.ends_with("main.xml")), "{kind}");
    assert_eq!(file, "b.xml");

    // In-memory files follow the same rule (by their path as written, normalised).
    for main in [
        r#"<mujoco><include file="a.xml"/><include file="a.xml"/></mujoco>"#,
        r#"<mujoco><include file="a.xml"/><include file="./a.xml"/></mujoco>"#,
        r#"<mujoco><include file="a.xml"/><include file="b.xml"/></mujoco>"#,
    ] {
        let err = ReadOptions::new()
            .asset("a.xml", geoms.as_bytes().to_vec())
            .asset("./a.xml", geoms.as_bytes().to_vec())
            .asset("b.xml", br#"<mujoco><include file="a.xml"/></mujoco>"#.to_vec())
            .read_str(main)
            .unwrap_err();
        assert!(
            matches!(err.kind(), ErrorKind::IncludedTwice(p) if p.ends_with("a.xml")),
            "{main}: {err}"
        );
    }
}

/// What MuJoCo 4.0 accepts stays accepted: one file included once and also named as
/// an asset `<model>` (its own include tree), two asset models that each include the
/// same file, and a file included by one model read twice.
#[test]
fn a_file_in_several_include_trees_is_fine() {
    let dir = temp_dir("trees");
    write(&dir, "a.xml", r#"<mujoco><worldbody><geom size="1"/></worldbody></mujoco>"#);
    write(&dir, "b.xml", r#"<mujoco><include file="a.xml"/></mujoco>"#);
    write(&dir, "c.xml", r#"<mujoco><include file="a.xml"/></mujoco>"#);
    let main = write(
        &dir,
        "main.xml",
        r#"<mujoco><include file="a.xml"/><asset><model name="m1" file="b.xml"/><model name="m2" file="c.xml"/><model name="m3" file="a.xml"/></asset></mujoco>"#,
    );
    let m = Model::from_path(&main).unwrap();
    assert_eq!(m.find_all(Namespace::Geom).len(), 1);
    assert_eq!(m.find_all(Namespace::Model).len(), 3);
    // Reading again is a new include tree.
    assert_eq!(Model::from_path(&main).unwrap(), m);
}

/// Told apart by canonical path, a file reached through a symlink is the file it
/// points at: included under both names it is refused (MuJoCo compares the paths as
/// written and reads it twice), so that no spelling reads a file twice.
#[cfg(unix)]
#[test]
fn a_file_included_again_through_a_symlink_is_included_twice() {
    let dir = temp_dir("symlinked-include");
    write(&dir, "a.xml", r#"<mujoco><worldbody><geom size="1"/></worldbody></mujoco>"#);
    std::os::unix::fs::symlink("a.xml", dir.join("l.xml")).unwrap();
    let main = write(
        &dir,
        "main.xml",
        r#"<mujoco><include file="a.xml"/><include file="l.xml"/></mujoco>"#,
    );
    let (kind, file, at) = where_refused(&main);
    assert!(matches!(&kind, ErrorKind::IncludedTwice(p) if p.ends_with("l.xml")), "{kind}");
    assert_eq!((file.as_str(), at), ("main.xml", (1, 32)));
}

/// A chain main → inc1 → … → incN, each adding one body.
fn include_chain(dir: &Path, n: usize) -> PathBuf {
    for i in 1..=n {
        let next =
            if i < n { format!(r#"<include file="inc{}.xml"/>"#, i + 1) } else { String::new() };
        write(
            dir,
            &format!("inc{i}.xml"),
            &format!(r#"<mujoco>{next}<worldbody><body name="b{i}"/></worldbody></mujoco>"#),
        );
    }
    write(dir, "main.xml", r#"<mujoco><include file="inc1.xml"/><worldbody/></mujoco>"#)
}

#[test]
fn includes_nest_100_deep_and_no_deeper() {
    let dir = temp_dir("depth100");
    let m = Model::from_path(include_chain(&dir, 100)).unwrap();
    assert_eq!(m.find_all(Namespace::Body).len(), 100);
    assert!(m.find(Namespace::Body, "b100").is_some());

    let dir = temp_dir("depth101");
    let err = Model::from_path(include_chain(&dir, 101)).unwrap_err();
    assert_eq!(err.kind(), &ErrorKind::TooDeep(100), "{err}");
    assert!(err.file().is_some_and(|f| f.ends_with("inc100.xml")), "{err}");
}

#[test]
fn include_depth_counts_the_same_from_a_string() {
    let dir = temp_dir("depthstr");
    include_chain(&dir, 100);
    let m = ReadOptions::new()
        .base_dir(&dir)
        .read_str(r#"<mujoco><include file="inc1.xml"/></mujoco>"#)
        .unwrap();
    assert_eq!(m.find_all(Namespace::Body).len(), 100);
}

// ---- file confinement -----------------------------------------------------------------

#[test]
fn paths_leaving_the_model_folder_are_allowed_by_default_and_refused_when_confined() {
    let dir = temp_dir("confine");
    write(&dir, "shared/box.stl", "solid box\nendsolid box\n");
    write(
        &dir,
        "shared/part.xml",
        r#"<mujoco><worldbody><body name="part"/></worldbody></mujoco>"#,
    );
    let main = write(
        &dir,
        "model/main.xml",
        r#"<mujoco>
  <include file="../shared/part.xml"/>
  <asset><mesh file="../shared/box.stl"/></asset>
</mujoco>"#,
    );
    // The default: MJCF models commonly share assets through `../`.
    let m = Model::from_path(&main).unwrap();
    assert!(m.find(Namespace::Body, "part").is_some());
    assert!(m.find(Namespace::Mesh, "box").is_some());

    let confined = ReadOptions::new().confine_to_base_dir(true);
    let err = confined.read_path(&main).unwrap_err();
    assert!(
        matches!(err.kind(), ErrorKind::FileOutsideRoot(p) if p.ends_with("../shared/part.xml")),
        "{err}"
    );
    assert_eq!(err.pos().map(|p| p.line), Some(2));

    // The mesh alone, without the include.
    let main2 = write(
        &dir,
        "model/mesh.xml",
        r#"<mujoco><asset><mesh file="../shared/box.stl"/></asset></mujoco>"#,
    );
    let err = confined.read_path(&main2).unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::FileOutsideRoot(_)), "{err}");

    // Absolute paths leave the folder too.
    let abs = dir.join("shared/box.stl");
    let text = format!(r#"<mujoco><asset><mesh file="{}"/></asset></mujoco>"#, abs.display());
    let err = confined.clone().base_dir(dir.join("model")).read_str(&text).unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::FileOutsideRoot(_)), "{err}");

    // Inside the folder is fine, `..` included as long as it stays inside.
    write(&dir, "model/meshes/box.stl", "solid box\nendsolid box\n");
    let main3 = write(
        &dir,
        "model/in.xml",
        r#"<mujoco><asset><mesh file="meshes/../meshes/box.stl"/></asset></mujoco>"#,
    );
    assert!(confined.read_path(&main3).unwrap().find(Namespace::Mesh, "box").is_some());
}

#[test]
fn confinement_also_applies_to_files_set_by_edits() {
    let dir = temp_dir("confine-edit");
    write(&dir, "box.stl", "solid box\nendsolid box\n");
    let model_dir = dir.join("model");
    std::fs::create_dir_all(&model_dir).unwrap();
    let m = ReadOptions::new()
        .confine_to_base_dir(true)
        .base_dir(&model_dir)
        .read_str("<mujoco/>")
        .unwrap();
    let err = m.add(&m.asset(), Element::new("mesh").attr("file", "../box.stl")).unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::FileOutsideRoot(_)), "{err}");
}

// ---- nesting and width ------------------------------------------------------------------

#[test]
fn nesting_100_000_deep_reads_writes_and_edits_without_overflow() {
    let depth = 100_000;
    let mut text = String::from("<mujoco><worldbody>");
    for _ in 0..depth {
        text.push_str("<body>");
    }
    text.push_str(r#"<geom name="deepest" size="1"/>"#);
    for _ in 0..depth {
        text.push_str("</body>");
    }
    text.push_str("</worldbody></mujoco>");
    let m = Model::from_xml_str(&text).unwrap();
    let deepest = m.find(Namespace::Geom, "deepest").unwrap();
    let m2 = m.set_attr(&deepest, "size", [2.0]).unwrap();
    assert_eq!(
        m2.element(&deepest).unwrap().attr("size").and_then(Value::as_floats),
        Some(&[2.0][..])
    );
    assert_ne!(m, m2);
    let out = m2.to_xml_string().unwrap();
    assert_eq!(out.matches("<body name=\"//unnamed_body_").count(), depth);
    // Indentation stops growing at 100 levels, so the output stays linear in size.
    assert!(out.len() < 500 * depth, "{} bytes", out.len());
    let back = Model::from_xml_str(&out).unwrap();
    assert_eq!(back.to_xml_string().unwrap(), out);
    let m3 = m2.remove(&deepest).unwrap();
    assert!(m3.find(Namespace::Geom, "deepest").is_none());
    // A copy of the deep model into another one.
    let merged = Model::new("other").include_copy(&m2, false).unwrap();
    assert!(merged.find(Namespace::Geom, "deepest").is_some());
    drop((m, m2, m3, back, merged));
}

#[test]
fn max_depth_refuses_deeper_input_with_its_own_error() {
    let text = "<mujoco><worldbody><body><body><body/></body></body></worldbody></mujoco>";
    let err = ReadOptions::new().max_depth(3).read_str(text).unwrap_err();
    assert_eq!(err.kind(), &ErrorKind::TooDeep(3));
    // Levels count from the root: mujoco, worldbody, body; the second body is refused.
    assert_eq!(err.pos().map(|p| p.column), Some(26));
    assert!(ReadOptions::new().max_depth(5).read_str(text).is_ok());
}

#[test]
fn an_element_built_100_000_deep_adds_compares_and_drops_without_overflow() {
    let mut body = Element::new("body")
        .child(Element::new("geom").attr("name", "deepest").attr("size", [1.0]));
    for _ in 1..100_000 {
        body = Element::new("body").child(body);
    }
    let copy = body.clone();
    assert_eq!(copy, body);
    assert_ne!(copy.clone().attr("name", "x"), body);
    let m = Model::new("m");
    let (m, _) = m.add(&m.worldbody(), body).unwrap();
    assert!(m.find(Namespace::Geom, "deepest").is_some());
    // Built the other way round (parent first) gives an equal element.
    let mut top = Element::new("body");
    let mut chain = Vec::new();
    for _ in 0..3 {
        chain.push(Element::new("body"));
    }
    for c in chain {
        top = top.child(c);
    }
    assert_eq!(
        top,
        Element::new("body")
            .child(Element::new("body"))
            .child(Element::new("body"))
            .child(Element::new("body"))
    );
    drop(copy);
}

#[test]
fn attachments_nested_1000_deep_write_and_drop_without_overflow() {
    let mut m = Model::new("leaf");
    let (leaf, _) =
        m.add(&m.worldbody(), Element::new("geom").attr("name", "g").attr("size", [1.0])).unwrap();
    m = leaf;
    for i in 0..1000 {
        let outer = Model::new(&format!("m{i}"));
        m = outer.attach_to_world(&m).unwrap().0;
    }
    let xml = m.to_xml_string().unwrap();
    let scoped: String = (0..999).rev().map(|i| format!("m{i}/")).collect::<String>() + "leaf/g";
    assert!(m.find(Namespace::Geom, &scoped).is_some(), "{scoped}");
    assert!(xml.contains(&format!(r#"name="{scoped}""#)));
    drop(m);
}

/// Whether an attachment frame in the world is written as MuJoCo's `<frame>` (its
/// model has a free body at its world level) is found by following the attached
/// model's MuJoCo `<frame>`s and its own attachments at that level: without
/// recursion, so 100,000 nested `<frame>`s in an attached model's worldbody, and
/// 5,000 nested attachments over a free body, write (each overflowed the stack).
/// Each frame's answer is kept for the write: asking each frame of the chain anew
/// went down the rest of the chain from each (56 s for the 5,000 levels in a debug
/// build; about 2 s now, most of it the names, each holding the whole scope path).
#[test]
fn frames_and_attachments_nested_at_the_world_level_write_without_overflow() {
    let depth = 100_000;
    let mut text = String::from(r#"<mujoco model="deep"><worldbody>"#);
    text.push_str(&"<frame>".repeat(depth));
    text.push_str(r#"<body name="free"><freejoint/><geom size="1"/></body>"#);
    text.push_str(&"</frame>".repeat(depth));
    text.push_str("</worldbody></mujoco>");
    let deep = Model::from_xml_str(&text).unwrap();
    let (outer, _) = Model::new("outer").attach_to_world(&deep).unwrap();
    let out = outer.to_xml_string().unwrap();
    assert!(out.contains(r#"<frame name="deep/">"#), "written as a frame: its body is free");
    assert_eq!(out.matches("<frame").count(), depth + 1);
    drop((outer, deep));

    // One-letter scopes keep the names (the whole scope path each) short.
    let levels = 5_000;
    let mut m = Model::from_xml_str(
        r#"<mujoco model="b"><worldbody><body name="free"><freejoint/><geom size="1"/></body></worldbody></mujoco>"#,
    )
    .unwrap();
    for _ in 0..levels {
        m = Model::new("m").attach_to_world(&m).unwrap().0;
    }
    let out = m.to_xml_string().unwrap();
    // Every level's frame is written as a frame, the body under them all.
    assert_eq!(out.matches("<frame name=").count(), levels);
    let free = format!("{}b/free", "m/".repeat(levels - 1));
    assert!(out.contains(&format!(r#"<body name="{free}">"#)));
    drop(m);
}

#[test]
fn a_million_siblings_read_write_and_edit() {
    let n = 1_000_000;
    let mut text = String::with_capacity(n * 8 + 64);
    text.push_str("<mujoco><worldbody>");
    for _ in 0..n {
        text.push_str("<site/>");
    }
    text.push_str(r#"<site name="last"/></worldbody></mujoco>"#);
    let m = Model::from_xml_str(&text).unwrap();
    let last = m.find(Namespace::Site, "last").unwrap();
    let m2 = m.set_attr(&last, "pos", [1.0, 2.0, 3.0]).unwrap();
    let (m3, _) =
        m2.insert(&m2.worldbody(), 500_000, Element::new("site").attr("name", "middle")).unwrap();
    let out = m3.to_xml_string().unwrap();
    assert_eq!(out.matches("<site").count(), n + 2);
    // Auto names count every site in document order, so `middle` takes index 500000.
    assert!(out.contains(r#"<site name="//unnamed_site_499999" class="/"/>"#));
    assert!(!out.contains(r#""//unnamed_site_500000""#));
    assert!(out.contains(r#"<site name="//unnamed_site_500001" class="/"/>"#));
    assert!(out.contains(r#"<site name="middle" class="/"/>"#));
    assert!(out.contains(r#"<site name="last" class="/" pos="1 2 3"/>"#));
}

// ---- DOCTYPE and entities ---------------------------------------------------------------

#[test]
fn a_doctype_is_skipped_and_entities_are_never_expanded() {
    // A DOCTYPE alone is dropped.
    let m = Model::from_xml_str(r#"<?xml version="1.0"?><!DOCTYPE mujoco><mujoco model="m"/>"#)
        .unwrap();
    assert_eq!(m.name(), "m");
    // The billion laughs: declared entities are not expanded; using one is an error.
    let mut bomb =
        String::from("<?xml version=\"1.0\"?>\n<!DOCTYPE mujoco [\n  <!ENTITY lol \"lol\">\n");
    for i in 1..10 {
        let prev = if i == 1 { "lol".to_string() } else { format!("lol{}", i - 1) };
        bomb.push_str(&format!("  <!ENTITY lol{i} \"{}\">\n", format!("&{prev};").repeat(10)));
    }
    bomb.push_str("]>\n<mujoco model=\"&lol9;\"/>\n");
    let err = Model::from_xml_str(&bomb).unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::Syntax(s) if s.contains("lol9")), "{err}");
    assert_eq!(err.pos().map(|p| p.line), Some(14));
    // A declared-but-unused bomb reads fine and leaves no trace.
    let unused = bomb.replace("&lol9;", "m");
    assert_eq!(Model::from_xml_str(&unused).unwrap().name(), "m");
    // External entities (XXE) are not fetched either.
    let xxe =
        "<!DOCTYPE mujoco [<!ENTITY x SYSTEM \"file:///etc/passwd\">]><mujoco model=\"&x;\"/>";
    assert!(matches!(kind_of(Model::from_xml_str(xxe)), ErrorKind::Syntax(_)));
    // Entities in element content (text is dropped) and in attribute values.
    let in_geom = "<!DOCTYPE m [<!ENTITY e \"1\">]><mujoco><worldbody><geom size=\"&e;\"/></worldbody></mujoco>";
    assert!(matches!(kind_of(Model::from_xml_str(in_geom)), ErrorKind::Syntax(_)));
    // XML's own five and character references are fine.
    let m = Model::from_xml_str(r#"<mujoco model="a&amp;b&#x41;&#66;&lt;"/>"#).unwrap();
    assert_eq!(m.name(), "a&bAB<");
}

// ---- big and odd values -----------------------------------------------------------------

#[test]
fn a_100_mb_attribute_value_reads_and_writes() {
    let big = "x".repeat(100 * 1024 * 1024);
    let text = format!(r#"<mujoco><worldbody><geom name="{big}" size="1"/></worldbody></mujoco>"#);
    let m = Model::from_xml_str(&text).unwrap();
    assert!(m.find(Namespace::Geom, &big).is_some());
    let out = m.to_xml_string().unwrap();
    assert!(out.len() > big.len());
    // The same size as a number list is refused (too many numbers), with a short message.
    let numbers = "1 ".repeat(1024 * 1024);
    let text = format!(r#"<mujoco><worldbody><geom size="{numbers}"/></worldbody></mujoco>"#);
    let err = Model::from_xml_str(&text).unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::InvalidValue { attribute: "size", .. }), "{err}");
    assert!(err.to_string().len() < 1000, "the message repeats the whole value");
}

#[test]
fn nan_inf_overflow_and_negative_zero_follow_the_reference() {
    let m = Model::from_xml_str(
        r#"<mujoco><worldbody><geom name="g" size="nan inf -inf"/><geom name="h" size="1e400 -0 -1e400"/><geom name="k" size="0.1" mass="-0"/></worldbody></mujoco>"#,
    )
    .unwrap();
    let g = m.element(&m.find(Namespace::Geom, "g").unwrap()).unwrap();
    let xs = g.attr("size").and_then(Value::as_floats).unwrap();
    assert!(xs[0].is_nan() && xs[1] == f64::INFINITY && xs[2] == f64::NEG_INFINITY);
    let h = m.element(&m.find(Namespace::Geom, "h").unwrap()).unwrap();
    let xs = h.attr("size").and_then(Value::as_floats).unwrap();
    // 1e400 overflows to infinity, as Python's float() does.
    assert_eq!(xs[0], f64::INFINITY);
    assert!(xs[1] == 0.0 && xs[1].is_sign_negative());
    assert_eq!(xs[2], f64::NEG_INFINITY);
    let out = m.to_xml_string().unwrap();
    assert!(out.contains(r#"size="nan inf -inf""#), "{out}");
    assert!(out.contains(r#"size="inf -0 -inf""#), "{out}");
    assert!(out.contains(r#"mass="-0""#), "{out}");
    // The same through edits.
    let g = m.find(Namespace::Geom, "g").unwrap();
    let m2 = m.set_attr(&g, "pos", [f64::NAN, -0.0, f64::INFINITY]).unwrap();
    assert!(m2.to_xml_string().unwrap().contains(r#"pos="nan -0 inf""#));
    // Integers do not overflow silently.
    let err = Model::from_xml_str(
        r#"<mujoco><option><flag/></option><size nconmax="99999999999999999999"/></mujoco>"#,
    )
    .unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::InvalidValue { attribute: "nconmax", .. }), "{err}");
}

#[test]
fn arrays_longer_or_shorter_than_allowed_are_refused_with_a_position() {
    let err = Model::from_xml_str(
        "<mujoco>\n<worldbody>\n  <body pos=\"1 2 3 4\"/>\n</worldbody></mujoco>",
    )
    .unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::InvalidValue { attribute: "pos", .. }), "{err}");
    assert_eq!(err.pos().map(|p| (p.line, p.column)), Some((3, 3)));
    let err =
        Model::from_xml_str(r#"<mujoco><worldbody><body quat="1 0 0 0 0"/></worldbody></mujoco>"#)
            .unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::InvalidValue { attribute: "quat", .. }), "{err}");
    // Shorter arrays are accepted, as in the reference (MuJoCo decides what they mean).
    assert!(
        Model::from_xml_str(r#"<mujoco><worldbody><body quat="1 0 0"/></worldbody></mujoco>"#)
            .is_ok()
    );
    let m = Model::new("m");
    let err = m.add(&m.worldbody(), Element::new("geom").attr("rgba", [1.0; 5])).unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::InvalidValue { attribute: "rgba", .. }), "{err}");
    assert_eq!(err.path(), "worldbody/geom");
}

#[test]
fn invalid_utf8_is_an_error_with_a_position() {
    let mut bytes = b"<mujoco>\n  <worldbody><geom name=\"ab".to_vec();
    bytes.extend_from_slice(&[0xff, 0xfe]);
    bytes.extend_from_slice(b"\"/></worldbody></mujoco>");
    let err = ReadOptions::new().read_bytes(&bytes).unwrap_err();
    assert_eq!(err.kind(), &ErrorKind::InvalidUtf8);
    assert_eq!(err.pos().map(|p| (p.line, p.column)), Some((2, 28)));
    // Also in an included file.
    let err = ReadOptions::new()
        .asset("bad.xml", vec![b'<', 0xc3, 0x28])
        .read_str(r#"<mujoco><include file="bad.xml"/></mujoco>"#)
        .unwrap_err();
    assert_eq!(err.kind(), &ErrorKind::InvalidUtf8);
    assert!(err.file().is_some_and(|f| f.ends_with("bad.xml")));
}

#[test]
fn slashes_in_names_are_refused_everywhere_they_could_confuse_scopes() {
    // `/` separates scopes in the API, so no identifier given there may hold one: not
    // when set, not as a model name that becomes a scope, not as a new scope name. Read
    // from MJCF, `robot/torso` is one literal name (MuJoCo accepts it, and composed
    // output holds such names): a flat model, no scopes.
    let read = Model::from_xml_str(
        r#"<mujoco><worldbody><body name="robot/torso"/></worldbody></mujoco>"#,
    )
    .unwrap();
    assert!(read.find(Namespace::Body, "robot/torso").is_some());
    assert!(read.scopes().next().is_none());
    let m = Model::new("m");
    let err = m.add(&m.worldbody(), Element::new("site").attr("name", "a/b")).unwrap_err();
    assert!(matches!(
        err.kind(),
        ErrorKind::InvalidValue { error: mjcf::ValueError::SlashInIdentifier, .. }
    ));
    let err = m.add(&m.default_class(), Element::new("default").attr("class", "x/")).unwrap_err();
    assert!(matches!(
        err.kind(),
        ErrorKind::InvalidValue { error: mjcf::ValueError::SlashInIdentifier, .. }
    ));

    let robot = Model::new("robot");
    let (robot, _) =
        robot.add(&robot.worldbody(), Element::new("body").attr("name", "torso")).unwrap();
    let err = Model::new("p").attach_to_world(&robot.with_name("a/b")).unwrap_err();
    assert!(
        matches!(
            err.kind(),
            ErrorKind::InvalidValue { error: mjcf::ValueError::SlashInIdentifier, .. }
        ),
        "{err}"
    );
    let (p, _) = Model::new("p").attach_to_world(&robot).unwrap();
    let err = p.rename_scope("robot", "x/y").unwrap_err();
    assert!(
        matches!(
            err.kind(),
            ErrorKind::InvalidValue { error: mjcf::ValueError::SlashInIdentifier, .. }
        ),
        "{err}"
    );
    // Scoped lookups of names that do not exist are simply absent.
    assert!(p.find(Namespace::Body, "robot/torso").is_some());
    assert!(p.find(Namespace::Body, "robot//torso").is_none());
    assert!(p.find(Namespace::Body, "/robot/torso").is_none());
    assert!(p.find(Namespace::Body, "robot/").is_none());
    assert!(p.find(Namespace::Body, "/").is_none());
}

#[test]
fn include_copy_merges_a_20_000_deep_chain_without_overflow() {
    // With override, same-named bodies merge level by level, as deep as they go.
    let chain = |depth: usize, attr: &str| {
        let mut text = String::from("<mujoco><worldbody>");
        for i in 0..depth {
            text.push_str(&format!(r#"<body name="b{i}" {attr}>"#));
        }
        for _ in 0..depth {
            text.push_str("</body>");
        }
        text.push_str("</worldbody></mujoco>");
        Model::from_xml_str(&text).unwrap()
    };
    let deep = chain(20_000, "");
    let moved = chain(20_000, r#"pos="1 0 0""#);
    let merged = deep.include_copy(&moved, true).unwrap();
    assert_eq!(merged.find_all(Namespace::Body).len(), 20_000);
    let last = merged.element(&merged.find(Namespace::Body, "b19999").unwrap()).unwrap();
    assert_eq!(last.attr("pos").and_then(Value::as_floats), Some(&[1.0, 0.0, 0.0][..]));
    // Without override the bodies clash by name; with other names they are copied.
    let err = deep.include_copy(&moved, false).unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::DuplicateIdentifier { .. }), "{err}");
    let copied = Model::new("m").include_copy(&deep, false).unwrap();
    assert_eq!(copied.find_all(Namespace::Body).len(), 20_000);
}

// ---- line endings -----------------------------------------------------------------------

/// The position of the error reading `lines` joined by each of `\n`, `\r\n` and a lone
/// `\r`: the same for all three (asserted), returned with its kind.
fn position_for_every_line_ending(lines: &[&str]) -> (ErrorKind, (u32, u32)) {
    let mut seen: Vec<(ErrorKind, (u32, u32))> = Vec::new();
    for ending in ["\n", "\r\n", "\r"] {
        let text = lines.join(ending);
        let err = ReadOptions::new()
            .asset("inc.xml", text.clone().into_bytes())
            .read_bytes(text.as_bytes())
            .unwrap_err();
        let pos = err.pos().map(|p| (p.line, p.column)).expect("a position");
        seen.push((err.kind().clone(), pos));
        // The same text as an included file: the same position, in that file.
        let err = ReadOptions::new()
            .asset("inc.xml", text.into_bytes())
            .read_str("<mujoco>\n<include file=\"inc.xml\"/></mujoco>")
            .unwrap_err();
        assert!(err.file().is_some_and(|f| f.ends_with("inc.xml")), "{err}");
        seen.push((err.kind().clone(), err.pos().map(|p| (p.line, p.column)).unwrap()));
    }
    assert!(seen.windows(2).all(|w| w[0] == w[1]), "{lines:?}: {seen:?}");
    seen.swap_remove(0)
}

#[test]
fn error_positions_are_the_same_for_lf_crlf_and_cr_line_endings() {
    // A syntax error (quick-xml's position), an unknown attribute, a bad value, an
    // invalid child, a duplicate name, invalid UTF-8 and an unclosed element (at the
    // end of the text), each after lines of every kind, one of them empty.
    let head = ["<mujoco>", "", "  <worldbody>", "    <body name=\"é\">"];
    let cases: [(&str, (u32, u32)); 5] = [
        ("      <geom size=\"1\"></body>", (5, 22)),
        ("      <geom bogus=\"1\"/>", (5, 7)),
        ("      <geom size=\"1 x\"/>", (5, 7)),
        ("      <bogus/>", (5, 7)),
        ("      <body name=\"é\"/>", (5, 7)),
    ];
    for (line, want) in cases {
        let mut lines = head.to_vec();
        lines.extend([line, "    </body>", "  </worldbody>", "</mujoco>"]);
        let (kind, pos) = position_for_every_line_ending(&lines);
        assert_eq!(pos, want, "{line}: {kind}");
    }
    let (kind, pos) = position_for_every_line_ending(&head);
    assert!(matches!(kind, ErrorKind::Syntax(_)), "{kind}");
    assert_eq!(pos, (4, 20), "{kind}");
    // Invalid UTF-8 (found before any XML is read).
    for ending in ["\n", "\r\n", "\r"] {
        let mut bytes = head.join(ending).into_bytes();
        bytes.extend_from_slice(ending.as_bytes());
        bytes.extend_from_slice(b"  <geom name=\"");
        bytes.push(0xff);
        let err = ReadOptions::new().read_bytes(&bytes).unwrap_err();
        assert_eq!(err.kind(), &ErrorKind::InvalidUtf8);
        assert_eq!(err.pos().map(|p| (p.line, p.column)), Some((5, 15)), "{ending:?}");
    }
}

// ---- error messages -----------------------------------------------------------------------

/// Every error message quotes a huge name or value (a tag, an attribute, an
/// identifier, a scope, a model name, a file name, a value) cut to its first 200
/// characters and `...`, as values always were: the message stays short and still
/// says which name.
#[test]
fn error_messages_cut_every_huge_name_at_200_characters() {
    let n = "n".repeat(1_000_000);
    // The name's first 200 characters (less what is quoted with it, such as `</`),
    // never more, and the mark of the cut.
    let check = |what: &str, message: String| {
        assert!(message.len() < 1500, "{what}: {} bytes: {}", message.len(), &message[..300]);
        assert!(message.contains(&format!("{}...", &n[..190])), "{what}: {message}");
        assert!(!message.contains(&n[..201]), "{what}: {message}");
    };
    let read = |text: String| Model::from_xml_str(&text).unwrap_err().to_string();
    let reads = [
        ("root tag", format!("<{n}/>")),
        ("child tag", format!("<mujoco><{n}/></mujoco>")),
        ("attribute", format!(r#"<mujoco><worldbody><geom {n}="1"/></worldbody></mujoco>"#)),
        ("value", format!(r#"<mujoco><worldbody><geom size="{n}"/></worldbody></mujoco>"#)),
        ("keyword", format!(r#"<mujoco><worldbody><geom type="{n}"/></worldbody></mujoco>"#)),
        (
            "identifier",
            format!(
                r#"<mujoco><worldbody><body name="{n}"/><body name="{n}"/></worldbody></mujoco>"#
            ),
        ),
        ("end tag", format!("<mujoco></{n}>")),
        ("entity", format!(r#"<mujoco model="&{n};"/>"#)),
        ("file", format!(r#"<mujoco><asset><mesh file="{n}.stl"/></asset></mujoco>"#)),
        ("include", format!(r#"<mujoco><include file="{n}.xml"/></mujoco>"#)),
    ];
    for (what, text) in reads {
        check(what, read(text));
    }
    // A file included twice, under a huge in-memory name.
    let err = ReadOptions::new()
        .asset(&n, b"<mujoco/>".to_vec())
        .read_str(&format!(r#"<mujoco><include file="{n}"/><include file="{n}"/></mujoco>"#))
        .unwrap_err();
    check("included twice", err.to_string());

    // Edits.
    let m = Model::new("m");
    let world = m.worldbody();
    check("lookup", m.lookup(Namespace::Body, &n).unwrap_err().to_string());
    check("added tag", m.add(&world, Element::new(&n)).unwrap_err().to_string());
    let e = m.add(&world, Element::new("geom").attr(n.as_str(), 1.0)).unwrap_err();
    check("added attribute", e.to_string());
    let (named, _) = m.add(&world, Element::new("body").attr("name", n.as_str())).unwrap();
    let e =
        named.add(&named.worldbody(), Element::new("body").attr("name", n.as_str())).unwrap_err();
    check("added identifier", e.to_string());
    // The element path of an edit error names the element by its (cut) name.
    let body = named.lookup(Namespace::Body, &n).unwrap();
    let e = named.add(&body, Element::new("bogus")).unwrap_err();
    check("element path", e.to_string());
    check("scope", m.detach(&n).unwrap_err().to_string());
    check("scope path", m.detach(format!("{n}//x")).unwrap_err().to_string());
    // A locator of a model with a huge name, used on another model.
    let other = Model::new(&n);
    let (other, g) = other.add(&other.worldbody(), Element::new("geom")).unwrap();
    check("model name", m.remove(&g).unwrap_err().to_string());
    // A freejoint on the frame of a robot with a huge name, attached inside a body.
    let (arena, site) = {
        let a = Model::new("arena");
        let (a, b) = a.add(&a.worldbody(), Element::new("body").attr("name", "b")).unwrap();
        let (a, s) = a.add(&b, Element::new("site").attr("name", "s")).unwrap();
        (a, s)
    };
    let (arena, frame) = arena.attach(&site, &other).unwrap();
    let e = arena.add(&frame.frame().clone(), Element::new("freejoint")).unwrap_err();
    check("frame scope", e.to_string());

    // Writing and exporting.
    let file = |bytes: &[u8]| Value::File(mjcf::FileAsset::new(&n, ".stl", bytes.to_vec()));
    let plain = mjcf::WriteOptions { filename_with_hash: false, ..mjcf::WriteOptions::default() };
    let (x, _) =
        m.add(&m.asset(), Element::new("mesh").attr("name", "a").attr("file", file(b"a"))).unwrap();
    let (x, _) =
        x.add(&x.asset(), Element::new("mesh").attr("name", "b").attr("file", file(b"b"))).unwrap();
    check("file name clash", x.assets(&plain).unwrap_err().to_string());
    let dir = temp_dir("long-names");
    check("export name", m.export(&dir, &n, &plain).unwrap_err().to_string());
}

// ---- counts -------------------------------------------------------------------------------

/// The model of `body` (a worldbody's content) with `extra` sections after it.
fn counted(body: &str, extra: &str) -> Model {
    Model::from_xml_str(&format!(
        r#"<mujoco model="counted"><worldbody>{body}</worldbody>{extra}</mujoco>"#
    ))
    .unwrap()
}

const KEY: &str = r#"<keyframe><key name="k" qpos="0.5"/></keyframe>"#;

fn merged() -> WriteOptions {
    WriteOptions { merge_keyframes: true, ..WriteOptions::default() }
}

/// What every model with huge counts does without listing the copies: it writes,
/// reads back, checks (`problems` the kinds expected), is walked, and is attached
/// and written again inside another model.
fn handles_without_copies(m: &Model, problems: usize) {
    let out = m.to_xml_string().unwrap();
    assert_eq!(Model::from_xml_str(&out).unwrap().to_xml_string().unwrap(), out);
    assert_eq!(m.check().len(), problems, "{:?}", m.check());
    assert!(m.walk().count() < 1000, "{}", m.walk().count());
    let (outer, _) = Model::new("outer").attach_to_world(m).unwrap();
    assert!(outer.to_xml_string().unwrap().contains("counted/"));
    assert!(outer.walk().count() < 1000, "{}", outer.walk().count());
}

/// The layout's refusal: its count, saturated, and its limit.
fn too_large(m: &Model) -> usize {
    match m.layout().unwrap_err().kind() {
        ErrorKind::TooLarge { size, limit, .. } => {
            assert_eq!(*limit, MAX_LAYOUT_ENTRIES);
            *size
        }
        other => panic!("{other}"),
    }
}

/// The merged write's refusal: what it counted.
fn too_large_to_merge(m: &Model) -> (&'static str, usize) {
    match m.to_xml_string_with(&merged()).unwrap_err() {
        WriteError::TooLarge { what, size, .. } => (what, size),
        other => panic!("{other}"),
    }
}

/// A `<replicate count="1000000000">` (MuJoCo 4.0's, read as written) aborted the
/// process: the layout made every copy's transform first (56 GB). Copies holding no
/// joint and no mocap body are not made at all: the layout is empty, and keys merge.
#[test]
fn a_billion_copies_of_bodies_without_joints_are_never_made() {
    let m = counted(
        r#"<replicate count="1000000000" offset="1 0 0"><body><geom size="1"/></body></replicate>
           <body name="b"><joint name="j"/><geom size="1"/></body>"#,
        KEY,
    );
    handles_without_copies(&m, 0);
    let layout = m.layout().unwrap();
    assert_eq!((layout.joints.len(), layout.nq), (1, 1));
    let out = m.to_xml_string_with(&merged()).unwrap();
    assert!(out.contains(r#"<key name="k" qpos="0.5"/>"#), "{out}");
}

/// A billion copies of a joint: read, written, checked (the key's length against the
/// counted size, no copy made), walked and attached; the layout, which would list
/// each copy, is refused with its count, and so is a merged write (its keys would
/// hold a billion values), but not one without keys.
#[test]
fn a_billion_copies_of_a_joint_are_counted_and_listing_them_is_refused() {
    let body = r#"<replicate count="1000000000"><body><joint/><geom size="1"/></body></replicate>"#;
    let m = counted(body, KEY);
    handles_without_copies(&m, 0);
    assert_eq!(too_large(&m), 1_000_000_000);
    assert_eq!(too_large_to_merge(&m), ("composed keys' qpos", 1_000_000_000));
    assert!(counted(body, "").to_xml_string_with(&merged()).is_ok());
}

/// Nested replicates multiply: 100,000 × 100,000 copies of a joint are counted as
/// 10^10; 10^9 cubed copies of a free joint (7 · 10^27 positions) saturate, and a
/// key longer than the counted size is still reported without overflow.
#[test]
fn nested_replicates_multiply_their_counts_without_overflow() {
    let m = counted(
        r#"<replicate count="100000"><replicate count="100000">
             <body><joint/><geom size="1"/></body></replicate></replicate>"#,
        KEY,
    );
    handles_without_copies(&m, 0);
    assert_eq!(too_large(&m), 10_000_000_000);
    assert_eq!(too_large_to_merge(&m), ("composed keys' qpos", 10_000_000_000));
    let cubed = counted(
        r#"<replicate count="1000000000"><replicate count="1000000000"><replicate count="1000000000">
             <body mocap="true"><geom size="1"/></body>
             <body><freejoint/><geom size="1"/></body></replicate></replicate></replicate>"#,
        KEY,
    );
    handles_without_copies(&cubed, 0);
    assert_eq!(too_large(&cubed), usize::MAX);
    assert_eq!(too_large_to_merge(&cubed), ("composed keys' qpos", usize::MAX));
}

/// `nuser_jnt` (and the other `nuser_*` of `<size>`), `<flexcomp>` and `<composite>`
/// counts are kept as written and never expanded: models with huge ones read, write,
/// check, lay out (the generated elements listed as not expanded) and merge keys.
#[test]
fn huge_user_sizes_and_flexcomp_and_composite_counts_are_never_expanded() {
    let size =
        r#"<size nuser_jnt="1000000000000" nuser_body="1000000000000" nuser_geom="2000000000"/>"#;
    let m = counted(r#"<body name="b"><joint/><geom size="1"/></body>"#, &format!("{size}{KEY}"));
    // MuJoCo 4.0.0 refuses the counts beyond a C int ("number is too large in
    // attribute 'nuser_body'"): check() says it once, for the <size>.
    handles_without_copies(&m, 1);
    assert!(m.check()[0].to_string().contains("number is too large in attribute 'nuser_"));
    assert_eq!(m.layout().unwrap().nq, 1);
    assert!(m.to_xml_string_with(&merged()).unwrap().contains(r#"nuser_jnt="1000000000000""#));
    let generated = counted(
        r#"<flexcomp name="f" type="grid" count="1000000000 1000000000 1000000000" spacing="1 1 1" dim="3"/>
           <body name="c"><composite type="cable" count="1000000000 1 1"><geom type="capsule" size="0.1"/></composite></body>"#,
        KEY,
    );
    let layout = generated.layout().unwrap();
    assert_eq!((layout.nq, layout.unexpanded.len()), (0, 2));
    assert!(generated.to_xml_string_with(&merged()).is_ok());
    assert!(
        generated.to_xml_string().unwrap().contains(r#"count="1000000000 1000000000 1000000000""#)
    );
}

/// A key with a million values for a model of one joint is reported by `check`
/// (its length against the model's) and merged to the model's one value; an
/// `actdim` of 10^12 is counted (checked, laid out as a number) and a merged key
/// that would hold that many activations is refused before any is made.
#[test]
fn huge_keys_and_activation_counts_are_checked_and_bounded() {
    let values = vec!["0"; 1_000_000].join(" ");
    let m = counted(
        r#"<body name="b"><joint name="j"/><geom size="1"/></body>"#,
        &format!(r#"<keyframe><key name="k" qpos="{values}"/></keyframe>"#),
    );
    let problems = m.check();
    assert!(
        matches!(
            problems.as_slice(),
            [p] if matches!(p.kind, ProblemKind::KeyLength { attribute: "qpos", expected: 1, found: 1_000_000 })
        ),
        "{problems:?}"
    );
    assert!(m.to_xml_string_with(&merged()).unwrap().contains(r#"<key name="k" qpos="0"/>"#));
    let actuator =
        r#"<actuator><general joint="j" dyntype="user" actdim="1000000000000"/></actuator>"#;
    let body = r#"<body name="b"><joint name="j"/><geom size="1"/></body>"#;
    let m = counted(body, &format!("{actuator}{KEY}"));
    // MuJoCo 4.0.0 refuses the actdim beyond a C int ("number is too large in
    // attribute 'actdim'"): check() says so.
    handles_without_copies(&m, 1);
    assert!(m.check()[0].to_string().contains("number is too large in attribute 'actdim'"));
    assert_eq!(m.layout().unwrap().na, 1_000_000_000_000);
    assert_eq!(too_large_to_merge(&m), ("composed keys' act", 1_000_000_000_000));
    assert!(counted(body, actuator).to_xml_string_with(&merged()).is_ok());
}

/// `check()` on numbers at the ends of what the reader takes (the largest integers,
/// infinities, nan) in the attributes its rules compute with: a result, never a panic
/// (an overflow would panic in a debug build).
#[test]
fn check_computes_with_extreme_numbers_without_panicking() {
    let big = i64::MAX.to_string();
    let models = [
        format!(r#"<mujoco><asset><hfield name="h" nrow="{big}" ncol="{big}" size="1 1 1 1" elevation="1 2"/></asset></mujoco>"#),
        format!(r#"<mujoco><asset><texture name="t" type="cube" builtin="flat" width="{big}" height="{big}"/></asset></mujoco>"#),
        format!(r#"<mujoco><size nuser_body="{big}" nconmax="-{big}"/><worldbody><body user="1"/></worldbody></mujoco>"#),
        r#"<mujoco><asset><mesh name="m" builtin="grid" params="1e300 1e300 1e300 1 1 1"/></asset></mujoco>"#.to_string(),
        r#"<mujoco><worldbody><body><inertial pos="0 0 0" mass="inf" fullinertia="nan inf -inf 1e308 1e308 1e308"/></body></worldbody></mujoco>"#.to_string(),
        format!(r#"<mujoco><worldbody><body><joint name="j"/><geom size="1"/></body></worldbody><actuator><general joint="j" actdim="{big}" nsample="{big}"/></actuator><sensor><jointpos joint="j" nsample="{big}" interval="inf -inf"/></sensor></mujoco>"#),
    ];
    for text in &models {
        // Read, or refused with a typed error; when read, check() answers.
        if let Ok(m) = mjcf::Model::from_xml_str(text) {
            let _ = m.check();
        }
    }
}

/// The same for every element kind a model's sections and bodies hold: each with all
/// its numeric attributes at one extreme (the largest integers, infinities, nan, the
/// largest and smallest doubles), alone in a body or its section: read or refused
/// with a typed error, and when read `check()` answers.
#[test]
fn check_answers_every_element_with_extreme_numbers() {
    use mjcf::{ArrayType, AttrType, ElementKind};
    let extremes = [
        (i64::MAX.to_string(), "1.7976931348623157e308"),
        (i64::MIN.to_string(), "-1.7976931348623157e308"),
        ("2147483648".to_string(), "inf"),
        ("-2147483649".to_string(), "-inf"),
        ("0".to_string(), "nan"),
        ("-1".to_string(), "5e-324"),
    ];
    let worldbody = ElementKind::ROOT.child("worldbody").unwrap();
    let body = worldbody.child("body").unwrap();
    let mut places: Vec<(ElementKind, Option<&str>)> =
        body.spec().children.iter().map(|k| (*k, None)).collect();
    for section in ElementKind::ROOT.spec().children {
        if *section == worldbody {
            continue;
        }
        places.push((*section, None));
        for k in section.spec().children {
            places.push((*k, Some(section.tag())));
        }
    }
    let mut read = 0;
    for (kind, section) in places {
        for (int, float) in &extremes {
            let mut attrs = String::new();
            for a in kind.spec().attrs {
                let value = match a.ty {
                    AttrType::Int => int.clone(),
                    AttrType::Float => float.to_string(),
                    AttrType::Array { elem, max_len } => {
                        let one = if elem == ArrayType::Int { int.as_str() } else { float };
                        vec![one; max_len.unwrap_or(6) as usize].join(" ")
                    }
                    _ => continue,
                };
                attrs.push_str(&format!(r#" {}="{value}""#, a.name));
            }
            let element = format!("<{}{attrs}/>", kind.tag());
            let text = match section {
                Some(s) => format!("<mujoco><{s}>{element}</{s}></mujoco>"),
                None if kind.spec().parent == Some(ElementKind::ROOT) => {
                    format!("<mujoco>{element}</mujoco>")
                }
                None => format!(
                    r#"<mujoco><worldbody><body name="b"><geom size="1"/>{element}</body></worldbody></mujoco>"#
                ),
            };
            if let Ok(m) = mjcf::Model::from_xml_str(&text) {
                let _ = m.check();
                let _ = m.advice();
                read += 1;
            }
        }
    }
    assert!(read > 100, "{read} models read");
}

#[test]
fn a_class_given_twice_in_one_tag_keeps_the_later_or_none() {
    // `class` and `dclass` are one attribute: the later replaces the earlier, and an
    // empty later one clears it.
    let xml = r#"<mujoco><default><default class="a"/><default class="b"/></default>
      <worldbody>
        <geom name="g" dclass="a" class="b" size="1"/>
        <geom name="h" class="a" dclass="" size="1"/>
        <geom name="k" class="b" size="1"/>
      </worldbody></mujoco>"#;
    let m = Model::from_xml_str(xml).unwrap();
    let class = |g: &str| m.get(&m.find(Namespace::Geom, g).unwrap()).unwrap().attr("class");
    assert_eq!(class("g"), class("k"));
    assert!(class("g").is_some());
    assert_eq!(class("h"), None);
}
