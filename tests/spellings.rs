//! The lossless writer on every spelling the reader accepts before and around a tag:
//! a byte-order mark, `\r\n` and lone `\r` line endings, tabs, multi-byte UTF-8 in
//! comments, attribute values and names, an XML declaration, comments, processing
//! instructions and a DOCTYPE before the root, and the same in included files and in a
//! scene's part files. For each, an edit (a value set, an element added, removed or
//! renamed) lands in its own tag, through every way in (`from_xml_str`, `read_bytes`,
//! `from_path` with `save`), and the saved text reads back as the edited model. The
//! expected texts are the input with the edited tag replaced by hand, so they do not
//! depend on the offsets the reader records.

use mjcf::{Element, Model, Namespace, ReadOptions, attrs};

use crate::dirs;
use dirs::{temp_dir, write};

/// A model text with one geom to edit, under the worldbody.
struct Case {
    text: String,
    /// The geom's name.
    name: &'static str,
    /// What lies between the end of the tag before the geom and the geom's tag (goes
    /// with the geom when it is removed).
    lead: &'static str,
    /// The line break and indentation a child added after the geom gets.
    sep: &'static str,
}

impl Case {
    /// `prefix`, then a model whose lines end with `nl` and are indented by `indent`,
    /// with `comment` before the geom and `name` as the geom's name.
    fn new(prefix: &str, nl: &'static str, indent: &str, name: &'static str) -> Case {
        let (i1, i2) = (indent.to_string(), indent.repeat(2));
        let text = format!(
            "{prefix}<mujoco model=\"m\">{nl}{i1}<worldbody>{nl}{i2}<geom name=\"{name}\" size=\"0.5\"/>{nl}{i1}</worldbody>{nl}</mujoco>{nl}"
        );
        let lead = leak(format!("{nl}{i2}"));
        Case { text, name, lead, sep: lead }
    }

    fn geom(&self) -> String {
        format!("<geom name=\"{}\" size=\"0.5\"/>", self.name)
    }
}

fn leak(s: String) -> &'static str {
    Box::leak(s.into_boxed_str())
}

/// The edits every case goes through, each with the text it must save: (what, the
/// edit, the expected text).
type Edit = (&'static str, Box<dyn Fn(&Model) -> Model>, String);

fn edits(case: &Case) -> Vec<Edit> {
    let name = case.name;
    let find = move |m: &Model| m.find(Namespace::Geom, name).unwrap();
    let geom = case.geom();
    let set: Box<dyn Fn(&Model) -> Model> =
        Box::new(move |m| m.set(&find(m), attrs!(size = [0.25])).unwrap());
    let add: Box<dyn Fn(&Model) -> Model> = Box::new(|m| {
        m.add(&m.worldbody(), Element::new("site").attr("name", "s\u{e9}")).unwrap().0
    });
    let remove: Box<dyn Fn(&Model) -> Model> = Box::new(move |m| m.remove(&find(m)).unwrap());
    let rename: Box<dyn Fn(&Model) -> Model> =
        Box::new(move |m| m.set(&find(m), attrs!(name = "r\u{1f600}")).unwrap());
    let t = &case.text;
    vec![
        ("set", set, t.replacen(&geom, &geom.replace("\"0.5\"", "\"0.25\""), 1)),
        ("add", add, t.replacen(&geom, &format!("{geom}{}<site name=\"s&#233;\"/>", case.sep), 1)),
        ("remove", remove, t.replacen(&format!("{}{geom}", case.lead), "", 1)),
        (
            "rename",
            rename,
            t.replacen(&geom, &geom.replace(&format!("\"{name}\""), "\"r&#128512;\""), 1),
        ),
    ]
}

/// Every edit of `case`, saved through each way in, gives its expected text, which
/// reads back as the edited model.
fn check(case: &Case) {
    let text = &case.text;
    let from_str = Model::from_xml_str(text).unwrap_or_else(|e| panic!("{e}\n{text:?}"));
    let from_bytes = ReadOptions::new().read_bytes(text.as_bytes()).unwrap();
    let dir = temp_dir("case");
    write(&dir, "model.xml", text);
    for m in [&from_str, &from_bytes] {
        assert_eq!(m.to_source_files().unwrap()[0].text, *text, "unedited");
    }
    for (what, edit, want) in edits(case) {
        for m in [&from_str, &from_bytes] {
            let edited = edit(m);
            let saved = &edited.to_source_files().unwrap()[0];
            assert_eq!(saved.text, want, "{what} of {text:?}");
            assert!(saved.changed);
            let back = Model::from_xml_str(&saved.text).unwrap();
            assert_eq!(back, edited, "{what}: read back differs\n{}", saved.text);
        }
        // From the file, saved in place.
        let path = dir.join("model.xml");
        write(&dir, "model.xml", text);
        let read = Model::from_path(&path).unwrap();
        let edited = edit(&read);
        assert_eq!(edited.save().unwrap(), std::slice::from_ref(&path), "{what}");
        assert_eq!(std::fs::read_to_string(&path).unwrap(), want, "{what} saved to {path:?}");
        let back = Model::from_path(&path).unwrap();
        assert_eq!(back.to_xml_string().unwrap(), edited.to_xml_string().unwrap(), "{what}");
    }
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn an_edit_after_a_byte_order_mark_lands_in_its_tag() {
    // The issue's input: the size was written 3 bytes early, outside the tag.
    let case = Case::new("\u{feff}", "\n", "  ", "g");
    assert!(case.text.starts_with("\u{feff}<mujoco model=\"m\">\n  <worldbody>\n    <geom"));
    check(&case);
}

#[test]
fn an_edit_in_a_crlf_file_lands_in_its_tag_and_new_lines_end_with_crlf() {
    check(&Case::new("", "\r\n", "  ", "g"));
    check(&Case::new("\u{feff}", "\r\n", "  ", "g"));
}

#[test]
fn an_edit_in_a_file_of_lone_cr_lines_lands_in_its_tag_and_new_lines_end_with_cr() {
    check(&Case::new("", "\r", "  ", "g"));
    check(&Case::new("\u{feff}", "\r", "\t", "g"));
}

#[test]
fn an_edit_in_a_tab_indented_file_lands_in_its_tag_indented_with_tabs() {
    check(&Case::new("", "\n", "\t", "g"));
    check(&Case::new("\u{feff}", "\r\n", "\t", "g"));
}

#[test]
fn an_edit_in_a_file_on_one_line_lands_in_its_tag() {
    check(&Case::new("\u{feff}", "", "", "g"));
}

#[test]
fn an_edit_after_multi_byte_text_in_comments_lands_in_its_tag() {
    for prefix in ["<!-- \u{e9}\u{1f600}\u{2211} -->\n", "\u{feff}<!--\u{1f600}-->"] {
        let mut case = Case::new(prefix, "\n", "  ", "g");
        // A comment of four-byte characters right before the geom goes with it.
        case.text = case.text.replace("    <geom", "    <!-- \u{1f600}\u{1f600} -->\n    <geom");
        case.lead = "\n    <!-- \u{1f600}\u{1f600} -->\n    ";
        check(&case);
    }
}

#[test]
fn an_edit_after_multi_byte_attribute_values_lands_in_its_tag() {
    let mut case = Case::new("\u{feff}", "\n", "  ", "g");
    case.text = case.text.replace("model=\"m\"", "model=\"m\u{f6}d\u{e9}l \u{1f916}\"");
    let text = case.text.replace(
        "<worldbody>",
        "<asset>\n    <material name=\"\u{1f7e5}\" rgba=\"1 0 0 1\"/>\n  </asset>\n  <worldbody>",
    );
    case.text = text;
    check(&case);
}

#[test]
fn an_edit_of_an_element_with_a_multi_byte_name_lands_in_its_tag() {
    check(&Case::new("\u{feff}", "\r\n", "  ", "g\u{e9}\u{1f600}"));
    check(&Case::new("", "\n", "\t", "\u{4e16}\u{754c}"));
}

#[test]
fn an_edit_after_an_xml_declaration_and_processing_instructions_lands_in_its_tag() {
    for prefix in [
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n",
        "\u{feff}<?xml version=\"1.0\"?>\r\n<?mujoco \u{e9}t\u{e9}?>\r\n<!-- x -->",
    ] {
        check(&Case::new(prefix, "\n", "  ", "g"));
    }
}

#[test]
fn an_edit_after_a_doctype_lands_in_its_tag() {
    for prefix in [
        "<!DOCTYPE mujoco>\n",
        "\u{feff}<?xml version=\"1.0\"?>\n<!DOCTYPE mujoco [\n  <!ELEMENT mujoco ANY>\n  <!-- <geom> \u{1f600} -->\n]>\n",
    ] {
        check(&Case::new(prefix, "\r\n", "  ", "g"));
    }
}

#[test]
fn a_four_byte_character_before_a_tag_after_a_byte_order_mark_saves_without_panicking() {
    // Offsets 3 bytes early fell inside the character before the tag.
    let mut case = Case::new("\u{feff}", "\n", "  ", "g");
    case.text = case.text.replace("\n    <geom", "\n    \u{1f600}<geom");
    case.lead = "\u{1f600}";
    case.sep = "\n    ";
    let edits = edits(&case);
    let m = Model::from_xml_str(&case.text).unwrap();
    // Set and rename: the tag itself.
    for (what, edit, want) in edits.iter().filter(|e| e.0 == "set" || e.0 == "rename") {
        let edited = edit(&m);
        assert_eq!(edited.to_source_files().unwrap()[0].text, *want, "{what}");
    }
}

#[test]
fn an_edit_in_an_included_file_spelled_otherwise_lands_in_its_tag() {
    let main = "\u{feff}<mujoco model=\"m\">\r\n\t<include file=\"parts.xml\"/>\r\n</mujoco>\r\n";
    let parts = "\u{feff}<?xml version=\"1.0\"?>\r<!-- \u{1f600} -->\r<mujoco>\r\t<worldbody>\r\t\t<geom name=\"g\" size=\"0.5\"/>\r\t</worldbody>\r</mujoco>\r";
    let want = parts.replace("\"0.5\"", "\"0.25\"");
    let set = |m: &Model| m.set(&m.find(Namespace::Geom, "g").unwrap(), attrs!(size = [0.25]));
    // In memory.
    let m =
        ReadOptions::new().asset("parts.xml", parts.as_bytes().to_vec()).read_str(main).unwrap();
    let files = set(&m).unwrap().to_source_files().unwrap();
    assert_eq!((files[0].text.as_str(), files[0].changed), (main, false));
    assert_eq!((files[1].text.as_str(), files[1].changed), (want.as_str(), true));
    // On disk, saved in place: the included file alone.
    let dir = temp_dir("include");
    write(&dir, "main.xml", main);
    write(&dir, "parts.xml", parts);
    let edited = set(&Model::from_path(dir.join("main.xml")).unwrap()).unwrap();
    assert_eq!(edited.save().unwrap(), [dir.join("parts.xml")]);
    assert_eq!(std::fs::read_to_string(dir.join("parts.xml")).unwrap(), want);
    assert_eq!(std::fs::read_to_string(dir.join("main.xml")).unwrap(), main);
    let back = Model::from_path(dir.join("main.xml")).unwrap();
    assert_eq!(back.to_xml_string().unwrap(), edited.to_xml_string().unwrap());
    // An element added to the worldbody: under its tag, in the included file, on a
    // line ending as that file's lines do.
    let (added, _) = edited.add(&edited.worldbody(), Element::new("site")).unwrap();
    let files = added.to_source_files().unwrap();
    assert_eq!(files[0].text, main);
    assert_eq!(files[1].text, want.replace("\"0.25\"/>", "\"0.25\"/>\r\t\t<site/>"));
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn an_edit_in_a_scene_part_spelled_otherwise_lands_in_its_tag() {
    let scene = "\u{feff}<?xml version=\"1.0\"?>\r\n<mujoco model=\"arena\">\r\n  <asset>\r\n    <model name=\"robot\" file=\"robot.xml\"/>\r\n  </asset>\r\n  <worldbody>\r\n    <!-- \u{1f916} -->\r\n    <body name=\"left/\">\r\n      <attach model=\"robot\" prefix=\"left/\"/>\r\n    </body>\r\n  </worldbody>\r\n</mujoco>\r\n";
    let robot = "\u{feff}<mujoco model=\"robot\">\r\t<worldbody>\r\t\t<!-- \u{e9} -->\r\t\t<body name=\"torso\" pos=\"0 0 .5\">\r\t\t\t<geom size=\".1\"/>\r\t\t</body>\r\t</worldbody>\r</mujoco>\r";
    let dir = temp_dir("scene");
    write(&dir, "scene.xml", scene);
    write(&dir, "robot.xml", robot);
    let m = Model::from_path(dir.join("scene.xml")).unwrap();
    assert_eq!(m.scopes().collect::<Vec<_>>(), ["left"]);
    let edited = m
        .edit_attached("left", |r| {
            let t = r.find(Namespace::Body, "torso").unwrap();
            r.set(&t, attrs!(pos = [0, 0, 2]))
        })
        .unwrap();
    assert_eq!(edited.save().unwrap(), [dir.join("robot.xml")]);
    let want = robot.replace("\"0 0 .5\"", "\"0 0 2\"");
    assert_eq!(std::fs::read_to_string(dir.join("robot.xml")).unwrap(), want);
    assert_eq!(std::fs::read_to_string(dir.join("scene.xml")).unwrap(), scene);
    let back = Model::from_path(dir.join("scene.xml")).unwrap();
    assert_eq!(back.to_xml_string().unwrap(), edited.to_xml_string().unwrap());
    // An edit of the scene's own body, in the scene file.
    let left = edited.frame("left").unwrap();
    let moved = edited.set(&left, attrs!(pos = [1, 0, 0])).unwrap();
    assert_eq!(moved.save().unwrap(), [dir.join("scene.xml")]);
    let saved = std::fs::read_to_string(dir.join("scene.xml")).unwrap();
    assert_eq!(
        saved,
        scene.replace("<body name=\"left/\">", "<body name=\"left/\" pos=\"1 0 0\">")
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn errors_after_a_byte_order_mark_are_where_they_are_without_it() {
    for text in [
        "<mujoco>\n  <worldbody>\n    <bogus/>\n  </worldbody>\n</mujoco>",
        "<mujoco><worldbody><geom size=\"x\"/></worldbody></mujoco>",
        "<mujoco>\r\n\t<worldbody></body>",
    ] {
        let plain = Model::from_xml_str(text).unwrap_err();
        let marked = Model::from_xml_str(&format!("\u{feff}{text}")).unwrap_err();
        assert!(plain.pos().is_some(), "{plain}");
        assert_eq!(marked.pos(), plain.pos(), "{marked} / {plain}");
        assert_eq!(marked.to_string(), plain.to_string());
    }
}
