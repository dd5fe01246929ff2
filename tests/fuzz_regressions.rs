//! Regression tests for what the fuzz targets in `fuzz/` (`read_xml`, `ops`, `lossless`; see
//! `fuzz/README.md`) found: each test is the minimized reproducer of one finding,
//! written against the public API, asserting the outcome the documentation (or
//! MuJoCo, where the crate follows it) promises.

use mjcf::{Element, ErrorKind, Model, Namespace};

fn write(m: &Model) -> String {
    m.to_xml_string().unwrap_or_else(|e| panic!("cannot write: {e}"))
}

fn read(xml: &str) -> Model {
    Model::from_xml_str(xml).unwrap_or_else(|e| panic!("cannot read back: {e}\n{xml}"))
}

// ---------------------------------------------------------------------------------
// Finding 1: a model without a `model` attribute.

/// `ops`: `[WithName { name: "" }]`, and `[IncludeCopy, Remove { root }]`.
///
/// A model whose root has no `model` attribute (`with_name("")`, the attribute set
/// to "" or cleared, the root removed) is written as `<mujoco>`, which reads back as
/// `model="unnamed_model"` (as `Model::new("")` and the reader name a nameless
/// model), so write∘read∘write ≠ write. Whatever the fix (never leave a model
/// without a name, or write the name the reader will give it), the output must be a
/// fixed point.
#[test]
fn ops_model_without_a_name_attribute_writes_a_fixed_point() {
    let m = Model::new("m");
    let mut cases = vec![("with_name(\"\")", m.with_name(""))];
    // These edits may also be refused; if they succeed, the result must round-trip.
    cases.extend(m.set_attr(&m.root(), "model", "").ok().map(|x| ("set model=\"\"", x)));
    cases.extend(m.clear_attr(&m.root(), "model").ok().map(|x| ("clear model", x)));
    cases.extend(m.remove(&m.root()).ok().map(|x| ("remove root", x)));
    let copied = m.include_copy(&Model::new("other"), false).unwrap();
    cases.extend(copied.remove(&copied.root()).ok().map(|x| ("include_copy, remove root", x)));
    for (what, model) in cases {
        let w1 = write(&model);
        let w2 = write(&read(&w1));
        assert_eq!(w2, w1, "{what}: write(read(w1)) differs from w1");
    }
}

/// `ops` (found by reasoning from the finding above, then checked): attaching a model
/// whose `name()` is empty uses the empty scope, so the composed output has a body
/// named `/`, a second default class `/` (the parent's root class), and does not
/// read back. The scope must not be empty (dm_control scopes a nameless model as
/// `unnamed_model`), or the attach must be refused with a typed error.
#[test]
fn ops_model_without_a_name_attaches_under_a_nonempty_scope() {
    let child = Model::new("robot");
    let (child, _) =
        child.add(&child.worldbody(), Element::new("body").attr("name", "torso")).unwrap();
    let arena = Model::new("arena");
    let mut cases = vec![("with_name(\"\")", child.with_name(""))];
    cases.extend(child.clear_attr(&child.root(), "model").ok().map(|x| ("clear model", x)));
    for (what, nameless) in cases {
        // A model without a name is `unnamed_model`, as a read or new one is.
        assert_eq!(nameless.name(), "unnamed_model", "{what}");
        match arena.attach_to_world(&nameless) {
            Ok((scene, frame)) => {
                let scope = scene.scope_of_frame(frame.frame()).unwrap();
                assert!(!scope.is_empty() && !scope.contains('/'), "{what}: scope {scope:?}");
                assert!(scene.find(Namespace::Body, &format!("{scope}/torso")).is_some(), "{what}");
                let xml = write(&scene);
                assert!(
                    xml.contains(&format!(r#"<body name="{scope}/torso"/>"#)),
                    "{what}:\n{xml}"
                );
                assert_eq!(
                    xml.matches(r#"<default class="/""#).count(),
                    1,
                    "{what}: two classes named /:\n{xml}"
                );
                assert!(!xml.contains(r#"name="/""#), "{what}:\n{xml}");
                assert_eq!(scene.detach(&scope).unwrap(), arena, "{what}");
            }
            Err(e) => assert!(
                matches!(
                    e.kind(),
                    ErrorKind::InvalidValue { tag: "mujoco", attribute: "model", .. }
                ),
                "{what}: refused, but not as an invalid model name: {e}"
            ),
        }
    }
}

// ---------------------------------------------------------------------------------
// Finding 2: a nested default class without a class name.

/// `ops`: `[Add { parent: <root default class>, element: DefaultClass { class: "" } }]`.
///
/// A nested `<default>` without `class` is written with the root class's name
/// (`<default class="/"><default class="/">`), so the output has two classes named
/// `/`, and reading it back silently merges the nested class into the root class.
/// MuJoCo refuses such a class ("empty class name", `mjXReader::Default`): the edit
/// must be refused, as a missing required attribute.
#[test]
fn ops_nested_default_class_without_a_name_is_refused() {
    let m = Model::new("m");
    let missing = |e: &mjcf::EditError| {
        matches!(e.kind(), ErrorKind::MissingRequired { tag: "default", attribute: "class" })
    };
    let e = m.add(&m.default_class(), Element::new("default")).unwrap_err();
    assert!(missing(&e), "{e}");
    let e = m.add(&m.default_class(), Element::new("default").attr("class", "")).unwrap_err();
    assert!(missing(&e), "{e}");
    let (named, class) =
        m.add(&m.default_class(), Element::new("default").attr("class", "c")).unwrap();
    let e = named.clear_attr(&class, "class").unwrap_err();
    assert!(missing(&e), "{e}");
    // The root class itself may stay unnamed.
    assert!(m.clear_attr(&m.default_class(), "class").is_ok());
}

/// `read_xml`, the same finding reached through the reader: the nested class is read,
/// written as a second `/` class, and read back as part of the root class.
#[test]
fn read_xml_nested_default_class_without_a_name_is_refused() {
    let e = Model::from_xml_str(
        r#"<mujoco><default><default><geom size="1"/></default></default></mujoco>"#,
    )
    .unwrap_err();
    assert!(
        matches!(e.kind(), ErrorKind::MissingRequired { tag: "default", attribute: "class" }),
        "{e}"
    );
    assert_eq!(e.pos().map(|p| (p.line, p.column)), Some((1, 18)), "{e}");
}

// ---------------------------------------------------------------------------------
// Finding 3: a class reference to a removed default class.

/// `ops`: `[IncludeCopy { <the read robot with childclass="leg"> }, Remove { <class
/// leg> }, Add { .. }]`.
///
/// Removing a default class that an element's `class` or a body's `childclass`
/// refers to leaves a dead reference, which is not written (as documented for
/// optional references), but the writer still counts the attribute as set, so the
/// element (or every element below the body) loses its implicit `class="/"`: the next
/// round writes it, and write∘read∘write ≠ write.
#[test]
fn ops_removed_default_class_leaves_the_implicit_class() {
    for (what, xml) in [
        (
            "class",
            r#"<mujoco model="m"><default><default class="c"/></default><worldbody><geom class="c" size="1"/></worldbody></mujoco>"#,
        ),
        (
            "childclass",
            r#"<mujoco model="m"><default><default class="c"/></default><worldbody><body name="b" childclass="c"><geom size="1"/></body></worldbody></mujoco>"#,
        ),
    ] {
        let m = read(xml);
        let m = m.remove(&m.find(Namespace::Default, "c").unwrap()).unwrap();
        let w1 = write(&m);
        assert!(
            w1.contains(r#"<geom name="//unnamed_geom_0" class="/" size="1"/>"#),
            "{what}:\n{w1}"
        );
        assert_eq!(write(&read(&w1)), w1, "{what}");
    }
}

// ---------------------------------------------------------------------------------
// Finding 4 (reported by the fuzzing helper from reading the reader, not a crash): a
// second `<default class="/">` inside the root-class wrapper.

/// `<default><default class="/"><default class="/">…` merged the inner class into the
/// root class. Only the outermost wrapper is the root class; inside it, `/` is a nested
/// class's name (names read from XML may hold `/`), kept as that class. The root class
/// is then written as MuJoCo's main class, so the name `/` is not given twice.
#[test]
fn read_xml_nested_slash_class_inside_the_root_wrapper_is_a_class() {
    let m = Model::from_xml_str(
        r#"<mujoco><default><default class="/"><geom rgba="1 0 0 1"/><default class="/"><geom size="1"/></default></default></default><worldbody><geom class="/"/></worldbody></mujoco>"#,
    )
    .unwrap();
    let inner = m.find(Namespace::Default, "/").expect("the nested class named /");
    assert_eq!(m.get(&inner).unwrap().children().filter(|c| c.attrs().next().is_some()).count(), 1);
    let w1 = write(&m);
    assert_eq!(w1.matches(r#"class="/">"#).count(), 1, "one class named /:\n{w1}");
    assert!(
        w1.contains("<default>\n    <geom rgba=\"1 0 0 1\"/>"),
        "the root class as main:\n{w1}"
    );
    assert_eq!(write(&read(&w1)), w1);
}

// ---------------------------------------------------------------------------------
// Finding 5 (the generators of `mjcf::generate`, issue 14): two unnamed joints on one
// attachment frame.

/// A scene recipe whose frame got two unnamed joints (`FrameRecipe { joints: [hinge,
/// slide] }`, both without a name).
///
/// An unnamed joint of an attachment frame is written with the frame's own name
/// (`robot/`), so two of them were written as two joints named `robot/`: MuJoCo
/// refuses the file ("repeated name"). A frame took one unnamed joint at most, but
/// dm_control takes any number and MuJoCo compiles them (issue 19): the first is
/// written `robot/`, the others with their automatic names (`model::naming`). A
/// freejoint beside them is MuJoCo's to refuse (more than 6 degrees of freedom):
/// `check` reports it.
#[test]
fn generated_frame_takes_unnamed_joints_written_apart() {
    let arena = Model::new("arena");
    let (scene, a) = arena.attach_to_world(&Model::new("robot")).unwrap();
    let (scene, _) = scene.add(a.frame(), Element::new("joint").attr("type", "slide")).unwrap();
    let (scene, _) = scene.add(a.frame(), Element::new("joint")).unwrap();
    let (scene, j) = scene.add(a.frame(), Element::new("joint").attr("name", "j")).unwrap();
    // A named one may lose its name too.
    let scene = scene.clear_attr(&j, "name").unwrap();
    let w1 = write(&scene);
    assert!(w1.contains(r#"<joint name="robot/" class="/" type="slide"/>"#), "{w1}");
    assert!(w1.contains(r#"<joint name="//unnamed_joint_1" class="/"/>"#), "{w1}");
    assert!(w1.contains(r#"<joint name="//unnamed_joint_2" class="/"/>"#), "{w1}");
    assert_eq!(write(&read(&w1)), w1);
    // A freejoint beside them: added (as dm_control does), reported by `check`.
    let (free, _) = scene.add(a.frame(), Element::new("freejoint")).unwrap();
    let problems = free.check();
    assert!(
        problems
            .iter()
            .any(|p| p.path == "robot/"
                && matches!(p.kind, mjcf::ProblemKind::TooManyDofs { dofs: 9 })),
        "{problems:?}"
    );
}

// ---------------------------------------------------------------------------------
// Finding 6 (the generators of `mjcf::generate` with MuJoCo, issue 14): a moving body
// whose only mass is below another joint.

/// An edit recipe removed a frame's inertial (and, in another case, a body's only
/// geom); the mass left below them was in bodies with joints of their own.
///
/// `check()` counted any mass below a moving body, but MuJoCo counts only the bodies
/// fixed to it (no joint in between): it refuses such a body ("mass and inertia of
/// moving bodies must be larger than mjMINVAL") while `check()` found nothing. Mass
/// below a joint no longer counts for the bodies above it.
#[test]
fn generated_mass_below_another_joint_does_not_count() {
    let m = Model::new("m");
    let (m, b) = m.add(&m.worldbody(), Element::new("body").attr("name", "b")).unwrap();
    let (m, _) = m.add(&b, Element::new("joint").attr("name", "hinge")).unwrap();
    let (m, c) = m.add(&b, Element::new("body").attr("name", "c")).unwrap();
    let (m, _) = m.add(&c, Element::new("geom").attr("size", [0.1])).unwrap();
    // A child fixed to `b` carries its mass: MuJoCo compiles this.
    assert!(m.check().is_empty(), "{:?}", m.check());
    // Once the child has a joint of its own, `b` has no mass (MuJoCo refuses it).
    let (m, _) =
        m.add(&c, Element::new("joint").attr("name", "slide").attr("type", "slide")).unwrap();
    let problems = m.check();
    assert_eq!(problems.len(), 1, "{problems:?}");
    assert_eq!(problems[0].path, "b");
    assert_eq!(problems[0].kind, mjcf::ProblemKind::MasslessMovingBody);
    // A body two levels below, fixed through a body without mass, still counts.
    let (m, g) = m.add(&b, Element::new("body").attr("name", "d")).unwrap();
    let (m, e) = m.add(&g, Element::new("body").attr("name", "e")).unwrap();
    let (m, _) = m.add(&e, Element::new("geom").attr("size", [0.1])).unwrap();
    assert!(m.check().is_empty(), "{:?}", m.check());
}

/// Found by the `read_xml` fuzz target: merged keyframes read a body's `pos` as three
/// numbers, but arrays may be shorter than their schema length.
#[test]
fn read_xml_merged_keys_with_a_short_pos_do_not_panic() {
    let m = Model::from_xml_str(
        r#"<mujoco><worldbody><body pos="1"><freejoint/><geom size="1"/></body></worldbody><keyframe><key qpos="0 0 0 1 0 0 0"/></keyframe></mujoco>"#,
    )
    .unwrap();
    let merge = mjcf::WriteOptions { merge_keyframes: true, ..mjcf::WriteOptions::default() };
    let xml = m.to_xml_string_with(&merge).unwrap();
    assert!(xml.contains("<key qpos=\"0 0 0 1 0 0 0\"/>"), "{xml}");
}

/// `ops` (found by the CI smoke run): a root class written as MuJoCo's main class
/// (named `main`, or unnamed) whose one class is named `/` was written as
/// `<default><default class="/">`, which reads back as dm_control's shape: `/` folded
/// into the root class, so that the references to `main` took `/`'s defaults. The
/// wrapper now says `class="main"`, and the text is a fixed point.
#[test]
fn ops_root_class_whose_one_class_is_slash_keeps_both_classes() {
    for named in [true, false] {
        let xml = r#"<mujoco model="inc"><default><default class="/"><geom size="0.2"/></default>
            <default class="a"/></default></mujoco>"#;
        let mut m = read(xml);
        let a = m.find(Namespace::Default, "a").unwrap();
        m.remove_mut(&a).unwrap();
        if named {
            let root = m.default_class();
            m.set_attr_mut(&root, "class", "main").unwrap();
        }
        let world = m.worldbody();
        let body = Element::new("body").attr("name", "tip").attr("childclass", "main");
        let body = m.add_mut(&world, body).unwrap();
        m.add_mut(&body, Element::new("geom").attr("class", "/").attr("size", [0.1])).unwrap();
        let w1 = write(&m);
        assert!(w1.contains("<default class=\"main\">"), "{w1}");
        let back = read(&w1);
        assert_eq!(write(&back), w1);
        // `/` is still a class of its own, inside the root class.
        let slash = back.find(Namespace::Default, "/").unwrap();
        assert_ne!(slash, back.default_class());
    }
}

/// `ops` (found by the CI smoke run): a class reference given as `main` (MuJoCo's
/// name for the root class) in a model without a class of that name was written as
/// `main` while the root class was written as `/`; read back, it was `/`. It is now
/// written as the root class is, in the model's own scope and inside an attachment
/// (`robot/`, not `robot/main`).
#[test]
fn ops_class_reference_named_main_is_written_as_the_root_class() {
    let mut m = Model::new("inc");
    let world = m.worldbody();
    let body = Element::new("body").attr("name", "tip").attr("childclass", "main");
    let body = m.add_mut(&world, body).unwrap();
    m.add_mut(&body, Element::new("geom").attr("class", "/").attr("size", [0.1])).unwrap();
    m.add_mut(&world, Element::new("site").attr("name", "spawn")).unwrap();
    let w1 = write(&m);
    assert!(!w1.contains("\"main\""), "{w1}");
    assert_eq!(write(&read(&w1)), w1);
    let mut arena = Model::new("arena");
    arena.attach_mut(&arena.worldbody(), &m).unwrap();
    let composed = write(&arena);
    assert!(composed.contains(r#"childclass="inc/""#), "{composed}");
    assert!(!composed.contains("inc/main"), "{composed}");
}

// ---------------------------------------------------------------------------------
// Found by the `lossless` target (issue 28).

/// `lossless`: a root `<default>` holding a class `/` beside an attached model's root
/// class `robot/` (a composed model written out: `/` is a class of that name), the
/// class `robot/` removed and the model saved. The saved `<default><default
/// class="/"/></default>` read as the root class written in its wrapper (the reader
/// folds a lone class `/` into the root class), another model. The root `<default>` is
/// now written `class="main"` when what it holds would fold, as the plain writer
/// writes it, and saved text reads back as the edited model.
#[test]
fn lossless_a_lone_class_slash_left_by_a_removal_does_not_fold_into_the_root_class() {
    let text = "<mujoco model=\"arena\">\n  <default>\n    <default class=\"/\">\n      <geom size=\"1\"/>\n    </default>\n    <default class=\"robot/\"/>\n  </default>\n  <worldbody>\n    <geom class=\"/\" size=\"2\"/>\n  </worldbody>\n</mujoco>\n";
    let m = Model::from_xml_str(text).unwrap();
    let robot = m.find(Namespace::Default, "robot/").unwrap();
    let m = m.remove(&robot).unwrap();
    let saved = m.to_source_files().unwrap()[0].text.clone();
    assert_eq!(
        saved,
        text.replace("  <default>\n", "  <default class=\"main\">\n")
            .replace("\n    <default class=\"robot/\"/>", "")
    );
    let back = read(&saved);
    assert_eq!(write(&back), write(&m), "{saved}");
    assert!(back.find(Namespace::Default, "/").is_some(), "{saved}");
    // Saved again from what was read back: the same text.
    assert_eq!(back.to_source_files().unwrap()[0].text, saved);
}

/// `lossless`: `<body name="b "pos="…">` (the reader takes attributes written
/// without whitespace between them), its name cleared and saved: the name went with
/// the whitespace before it, and `<bodypos="…">` did not read back. The whitespace
/// stays when the next attribute follows without any.
#[test]
fn lossless_a_removed_attribute_glued_to_the_next_keeps_the_tag_readable() {
    let text = "<mujoco>\n  <worldbody>\n    <body name=\"b \"pos=\"0 0 1\">\n      <geom size=\"1\"/>\n    </body>\n  </worldbody>\n</mujoco>\n";
    let m = Model::from_xml_str(text).unwrap();
    let b = m.find(Namespace::Body, "b ").unwrap();
    let m = m.clear_attr(&b, "name").unwrap();
    let saved = m.to_source_files().unwrap()[0].text.clone();
    assert_eq!(saved, text.replace("<body name=\"b \"pos=", "<body pos="));
    assert_eq!(write(&read(&saved)), write(&m));
}

/// A nested default class without a name is refused in MuJoCo 4.0.0's words too
/// ("empty class name", for `<default/>` and for `class=""` alike).
#[test]
fn a_nameless_nested_class_is_refused_in_mujoco_s_words() {
    for text in [
        "<mujoco><default><default/></default></mujoco>",
        r#"<mujoco><default><default class=""/></default></mujoco>"#,
    ] {
        let e = mjcf::Model::from_xml_str(text).unwrap_err();
        assert!(e.to_string().contains("(MuJoCo: \"empty class name\")"), "{e}");
    }
}
