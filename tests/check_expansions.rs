//! `check()` on what MuJoCo expands at compile time and the model keeps as written:
//! the copies of a `<replicate>` and the parts of an `<attach>` (each verdict below
//! was checked with MuJoCo 4.0.0: the models it compiles draw no problem, those it
//! refuses draw the problem that stands for its message).

use std::path::PathBuf;

use mjcf::{Model, ProblemKind};

/// A fresh folder holding `files` (name, text).
fn folder(label: &str, files: &[(&str, &str)]) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("mjcf-check-exp-{}-{label}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in files {
        std::fs::write(dir.join(name), text).unwrap();
    }
    dir
}

/// The kinds of `check()`'s problems on the model file `main.xml` among `files`.
fn problems(label: &str, files: &[(&str, &str)]) -> Vec<ProblemKind> {
    let dir = folder(label, files);
    let m = Model::from_path(dir.join("main.xml")).unwrap();
    let out = m.check().into_iter().map(|p| p.kind).collect();
    std::fs::remove_dir_all(&dir).unwrap();
    out
}

fn dangling(kinds: &[ProblemKind]) -> Vec<String> {
    kinds
        .iter()
        .filter_map(|k| match k {
            ProblemKind::DanglingReference { name, .. } => Some(name.to_string()),
            _ => None,
        })
        .collect()
}

const REPLICATED: &str = r#"<mujoco><worldbody>
  <replicate count="2" offset="1 0 0" sep="-">
    <replicate count="10" offset="0 1 0">
      <body name="b"><joint name="j"/><geom size=".1"/><site name="s"/></body>
    </replicate>
  </replicate></worldbody>"#;

#[test]
fn references_to_replicated_copies_resolve_and_past_the_count_dangle() {
    // MuJoCo 4.0.0 names the copies j00-0 .. j09-0, j00-1 .. j09-1 (inner index
    // padded to the digits of 10, then the outer sep and index); `j` and the inner
    // copies' names (`j05`) compile too (what refers to them is copied with them).
    let ok = format!(
        "{REPLICATED}<actuator><motor joint=\"j00-0\"/><motor joint=\"j09-1\"/><motor joint=\"j\"/>\
         <motor joint=\"j05\"/></actuator>\
         <sensor><framepos objtype=\"site\" objname=\"s05-1\"/></sensor></mujoco>"
    );
    assert_eq!(problems("rep-ok", &[("main.xml", &ok)]), []);
    // MuJoCo refuses each: unknown transmission target.
    for name in ["j10-0", "j00-2", "j9-0", "j0", "j05-", "j-1"] {
        let bad = format!("{REPLICATED}<actuator><motor joint=\"{name}\"/></actuator></mujoco>");
        assert_eq!(dangling(&problems("rep-bad", &[("main.xml", &bad)])), [name], "{name}");
    }
}

const PART: &str = r#"<mujoco><worldbody><body name="b"><joint name="j"/><geom size=".1"/>
  <site name="s"/></body></worldbody></mujoco>"#;

fn host(refs: &str) -> String {
    format!(
        r#"<mujoco><asset><model name="part" file="part.xml"/></asset>
        <worldbody><attach model="part" body="b" prefix="p-"/></worldbody>{refs}</mujoco>"#
    )
}

#[test]
fn references_into_an_attached_part_resolve_by_its_prefix_and_names() {
    let ok = host(
        r#"<actuator><motor joint="p-j"/></actuator>
        <sensor><framepos objtype="site" objname="p-s"/></sensor>"#,
    );
    assert_eq!(problems("att-ok", &[("main.xml", &ok), ("part.xml", PART)]), []);
    // MuJoCo refuses both: unknown transmission target, unrecognized name.
    let bad = host(
        r#"<actuator><motor joint="p-x"/></actuator>
        <sensor><framepos objtype="site" objname="q-s"/></sensor>"#,
    );
    let found = dangling(&problems("att-bad", &[("main.xml", &bad), ("part.xml", PART)]));
    assert_eq!(found, ["p-x", "q-s"]);
    // An empty prefix (MuJoCo 4.0.0 compiles it, with a warning): the part's names
    // as they are.
    let bare = host(r#"<actuator><motor joint="j"/><motor joint="x"/></actuator>"#)
        .replace(r#"prefix="p-""#, r#"prefix="""#);
    let found = dangling(&problems("att-bare", &[("main.xml", &bare), ("part.xml", PART)]));
    assert_eq!(found, ["x"]);
}

fn mover(part: &str) -> [(&'static str, String); 2] {
    let main = r#"<mujoco><asset><model name="part" file="part.xml"/></asset>
      <worldbody><body name="mover"><joint name="h"/>
        <attach model="part" body="w" prefix="p-"/></body></worldbody></mujoco>"#;
    [("main.xml", main.to_string()), ("part.xml", part.to_string())]
}

fn massless(label: &str, part: &str) -> bool {
    let files = mover(part);
    let files: Vec<(&str, &str)> = files.iter().map(|(n, t)| (*n, t.as_str())).collect();
    problems(label, &files).contains(&ProblemKind::MasslessMovingBody)
}

#[test]
fn a_moving_body_has_the_mass_its_attached_part_welds_to_it() {
    // MuJoCo 4.0.0 compiles these two: the attached body, or a body welded below it,
    // has a geom.
    let own = r#"<mujoco><worldbody><body name="w"><geom size=".1"/></body></worldbody></mujoco>"#;
    assert!(!massless("mass-own", own));
    let deep = r#"<mujoco><worldbody><body name="w"><body name="inner"><geom size=".1"/></body>
      </body></worldbody></mujoco>"#;
    assert!(!massless("mass-deep", deep));
    // And refuses these ("mass and inertia of moving bodies must be larger than
    // mjMINVAL"): no mass, or the mass on a body that moves on its own.
    let none = r#"<mujoco><worldbody><body name="w"><site name="s"/></body></worldbody></mujoco>"#;
    assert!(massless("mass-none", none));
    let moving = r#"<mujoco><worldbody><body name="w"><joint name="own"/><geom size=".1"/>
      </body></worldbody></mujoco>"#;
    assert!(massless("mass-moving", moving));
}

#[test]
fn a_replicate_s_childclass_is_read_and_written() {
    // MuJoCo 4.0.0 reads it: the copies' geoms take the class's size.
    let text = r#"<mujoco><default><default class="c"><geom size=".2"/></default></default>
      <worldbody><replicate count="2" offset="1 0 0" childclass="c">
        <body name="b"><joint name="j"/><geom/></body></replicate></worldbody></mujoco>"#;
    let m = Model::from_xml_str(text).unwrap();
    assert_eq!(m.check(), []);
    assert!(m.to_xml_string().unwrap().contains(r#"childclass="c""#));
    // An unknown class MuJoCo refuses ("unknown default childclass").
    let bad = Model::from_xml_str(&text.replace(r#"childclass="c""#, r#"childclass="nope""#));
    let dangles = bad.map(|m| dangling(&m.check().into_iter().map(|p| p.kind).collect::<Vec<_>>()));
    assert_eq!(dangles.ok(), Some(vec!["nope".to_string()]));
}

#[test]
fn an_empty_attach_prefix_is_read_and_written() {
    // MuJoCo 4.0.0 compiles `prefix=""` (and refuses the attribute's absence).
    let main = host("").replace(r#"prefix="p-""#, r#"prefix="""#);
    let dir = folder("att-empty", &[("main.xml", &main), ("part.xml", PART)]);
    let m = Model::from_path(dir.join("main.xml")).unwrap();
    assert!(m.to_xml_string().unwrap().contains(r#"prefix="""#));
    let missing = main.replace(r#" prefix="""#, "");
    std::fs::write(dir.join("main.xml"), missing).unwrap();
    assert!(Model::from_path(dir.join("main.xml")).is_err());
    std::fs::remove_dir_all(&dir).unwrap();
}
