//! MJCF of MuJoCo 4.0 beyond dm_control's schema: every element and attribute of
//! MuJoCo 4.0's printed schema (`schema/mujoco-4.0.0-schema.txt`) reads, edits and
//! writes back; `<frame>` and `<replicate>` are elements found, edited and written in
//! place; attaching a model that has them prefixes their names and every reference.
//! (`tools/schema40_check.py` compiles the same kinds of output with MuJoCo; see
//! `examples/schema40.rs`.)

use mjcf::{
    AttrType, EditError, ElementKind, Loc, Model, Namespace, ReadOptions, RefTarget, element,
};

/// MuJoCo 4.0's printed schema: (path of tags below `<mujoco>`, attribute names).
fn printed_schema() -> Vec<(Vec<String>, Vec<String>)> {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/schema/mujoco-4.0.0-schema.txt");
    let text = std::fs::read_to_string(path).expect("the printed schema");
    let mut out: Vec<(Vec<String>, Vec<String>)> = Vec::new();
    let mut stack: Vec<String> = Vec::new();
    for line in text.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        if words.is_empty() {
            continue;
        }
        let indent = line.len() - line.trim_start().len();
        let is_element =
            indent < 30 && words.get(1).is_some_and(|m| m.len() == 3 && m.starts_with('('));
        if is_element {
            stack.truncate(indent / 3);
            stack.push(words[0].to_string());
            // `(world)body` is the body element, inside the worldbody.
            let tags: Vec<String> = stack[1..]
                .iter()
                .flat_map(|t| match t.as_str() {
                    "(world)body" => vec!["worldbody".to_string(), "body".to_string()],
                    t => vec![t.to_string()],
                })
                .collect();
            out.push((tags, words[2..].iter().map(|w| w.to_string()).collect()));
        } else if let Some(last) = out.last_mut() {
            last.1.extend(words.iter().map(|w| w.to_string()));
        }
    }
    out
}

/// The file an element's file attribute reads in these tests, and its contents.
fn file_for(tag: &str, second: bool) -> (String, &'static [u8]) {
    let stem = if second { "b" } else { "a" };
    let (ext, contents): (&str, &[u8]) = match tag {
        "mesh" => ("stl", b"solid a"),
        "skin" => ("skn", b"skin"),
        "model" => ("xml", b"<mujoco model=\"m\"/>"),
        "flexcomp" => ("obj", b"v 0 0 0"),
        _ => ("png", b"png"),
    };
    (format!("{stem}.{ext}"), contents)
}

/// A value of the attribute's type, as text, and how it is written back (a file is
/// written under its content-hash name, which starts with its stem).
fn value_for(kind: ElementKind, name: &str, second: bool) -> Option<(String, String)> {
    let spec = kind.attr(kind.attr_index(name)?);
    let pick = |a: &str, b: &str| if second { b.to_string() } else { a.to_string() };
    let text = match spec.ty {
        AttrType::Float => pick("1.5", "2.5"),
        AttrType::Int => pick("2", "3"),
        AttrType::String | AttrType::NamePrefix => pick("s1", "s2"),
        AttrType::Keyword(valid) => pick(valid[0], valid[valid.len() - 1]),
        AttrType::Array { max_len, .. } => {
            let n = max_len.unwrap_or(2) as usize;
            let v: Vec<String> = (1..=n).map(|i| (i + usize::from(second)).to_string()).collect();
            v.join(" ")
        }
        AttrType::Identifier => pick("n1", "n2"),
        AttrType::Reference(_) => pick("r1", "r2"),
        AttrType::File { .. } => {
            let (file, _) = file_for(kind.tag(), second);
            let stem = file.split('.').next().unwrap_or_default().to_string();
            return Some((file, format!("{stem}-")));
        }
        AttrType::Basepath { .. } => pick("dir1", "dir2"),
    };
    Some((text.clone(), text))
}

/// The required attributes of `kind` (other than `skip`) as XML.
fn required(kind: ElementKind, skip: &str) -> String {
    let mut out = String::new();
    for a in kind.spec().attrs.iter().filter(|a| a.required && a.name != skip) {
        if let Some((text, _)) = value_for(kind, a.name, false) {
            out.push_str(&format!(" {}=\"{text}\"", a.name));
        }
    }
    out
}

/// The element at the end of `tags`, found from the root.
fn locate(m: &Model, tags: &[String]) -> Loc {
    let mut loc = m.root();
    for t in tags {
        let e = m.get(&loc).unwrap();
        loc = e.children().find(|c| c.tag() == t).unwrap_or_else(|| panic!("no {t}")).loc();
    }
    loc
}

#[test]
fn every_element_and_attribute_of_mujoco_40_reads_edits_and_writes_back() {
    let mut checked = 0;
    for (tags, attrs) in printed_schema() {
        if tags.is_empty() {
            continue; // <mujoco model>: the model's name
        }
        let mut kinds = vec![ElementKind::ROOT];
        for t in &tags {
            let k = kinds.last().unwrap().child(t);
            kinds.push(k.unwrap_or_else(|| panic!("{} has no kind", tags.join("/"))));
        }
        let kind = *kinds.last().unwrap();
        for attr in &attrs {
            let (text, written) = value_for(kind, attr, false)
                .unwrap_or_else(|| panic!("{}@{attr} has no type", tags.join("/")));
            let mut xml = String::from("<mujoco>");
            for (i, t) in tags.iter().enumerate() {
                let k = kinds[i + 1];
                let own =
                    if i + 1 == tags.len() { format!(" {attr}=\"{text}\"") } else { String::new() };
                xml.push_str(&format!("<{t}{}{own}>", required(k, attr)));
            }
            for t in tags.iter().rev() {
                xml.push_str(&format!("</{t}>"));
            }
            xml.push_str("</mujoco>");
            let mut read = ReadOptions::new();
            for second in [false, true] {
                let (file, contents) = file_for(kind.tag(), second);
                read = read.asset(&file, contents.to_vec());
            }
            let what = format!("{}@{attr} = {text:?} in {xml}", tags.join("/"));
            let m = if tags == ["default"] && attr == "class" {
                // The root class named in a file is what MuJoCo refuses (decision
                // D16); named through the API, it is written nested.
                let e = read.read_str(&xml).expect_err(&what);
                assert!(matches!(e.kind(), mjcf::ErrorKind::RootClassRenamed(_)), "{what}: {e}");
                let m = Model::from_xml_str("<mujoco><default/></mujoco>").unwrap();
                m.set_attr(&m.default_class(), attr, text.as_str()).unwrap()
            } else {
                read.read_str(&xml).unwrap_or_else(|e| panic!("{what}: {e}"))
            };
            let loc = locate(&m, &tags);
            assert!(m.get(&loc).unwrap().attr(attr).is_some(), "{what}: not kept");
            if matches!(kind.attr(kind.attr_index(attr).unwrap()).ty, AttrType::Basepath { .. }) {
                checked += 1;
                continue; // a folder setting: used while reading, never written
            }
            let out = m.to_xml_string().unwrap_or_else(|e| panic!("{what}: {e}"));
            assert!(out.contains(&format!(" {attr}=\"{written}")), "{what}: not written in {out}");
            let (text2, written2) = value_for(kind, attr, true).unwrap();
            let edited =
                m.set_attr(&loc, attr, text2.as_str()).unwrap_or_else(|e| panic!("{what}: {e}"));
            let out = edited.to_xml_string().unwrap();
            assert!(
                out.contains(&format!(" {attr}=\"{written2}")),
                "{what}: edit not written in {out}"
            );
            checked += 1;
        }
    }
    assert!(checked > 1500, "only {checked} attributes checked");
}

const SCENE: &str = r#"<mujoco model="scene">
  <default>
    <default class="box"><geom type="box" size=".1 .1 .1"/></default>
  </default>
  <worldbody>
    <geom name="floor" type="plane" size="1 1 .1"/>
    <frame name="shelf" pos="0 0 .5" childclass="box">
      <geom name="plank"/>
      <body name="arm">
        <joint name="hinge"/>
        <frame name="tip" pos="0 0 .1"><site name="tipsite"/></frame>
      </body>
    </frame>
    <body name="stand">
      <frame euler="0 90 0"><joint name="tilt"/><geom size=".1"/></frame>
    </body>
    <replicate count="3" offset=".2 0 0" sep="-">
      <body name="cube"><freejoint/><geom size=".1"/><site name="cubesite"/></body>
      <replicate count="2" offset="0 .2 0"><geom size=".05"/></replicate>
    </replicate>
  </worldbody>
  <actuator>
    <dcmotor name="m1" joint="hinge" motorconst="0.05" resistance="2"/>
    <pid name="p1" joint="tilt" kp="10"/>
  </actuator>
</mujoco>"#;

#[test]
fn frames_are_found_edited_and_written_in_place() -> Result<(), Box<dyn std::error::Error>> {
    let m = Model::from_xml_str(SCENE)?;
    let out = m.to_xml_string()?;
    // Written back where they were, with their content.
    let shelf = out.find(r#"<frame name="shelf""#).ok_or("no shelf")?;
    assert!(out.find(r#"<geom name="floor""#).unwrap() < shelf);
    assert!(shelf < out.find(r#"<geom name="plank""#).unwrap());
    assert!(out.contains(r#"<frame name="tip" pos="0 0 0.1">"#));
    // Under its childclass an element gets no explicit class; elsewhere it does.
    assert!(out.contains(r#"<geom name="plank"/>"#), "{out}");
    assert!(out.contains(r#"<geom name="floor" class="/""#));
    // Read back, it writes the same text.
    assert_eq!(Model::from_xml_str(&out)?.to_xml_string()?, out);

    // Found by name; edited and added to like a body.
    let tip = m.lookup(Namespace::Frame, "tip")?;
    assert_eq!(m.get(&tip)?.tag(), "frame");
    assert_eq!(m.get(&tip)?.parent().map(|p| p.tag()), Some("body"));
    let (m2, g) = m.add(&tip, element!("geom", name = "tipgeom", size = [0.01]))?;
    let m2 = m2.set_attr(&tip, "pos", [0.0, 0.0, 0.2])?;
    let m2 = m2.set_attr(&m2.lookup(Namespace::Frame, "shelf")?, "name", "rack")?;
    assert!(m2.find(Namespace::Frame, "shelf").is_none());
    assert_eq!(m2.get(&g)?.parent().and_then(|p| p.identifier()), Some("tip"));
    let out2 = m2.to_xml_string()?;
    assert!(out2.contains(
        r#"<frame name="tip" pos="0 0 0.2">
          <site name="tipsite"/>
          <geom name="tipgeom" size="0.01"/>
        </frame>"#
    ));
    assert!(out2.contains(r#"<frame name="rack" childclass="box" pos="0 0 0.5">"#), "{out2}");
    // Frame names are unique in their namespace, and a frame holds what a body holds.
    assert!(m.add(&m.worldbody(), element!("frame", name = "tip")).is_err());
    assert!(m.add(&tip, element!("body", name = "b2")).is_ok());
    assert!(m.add(&tip, element!("frame")).is_ok());
    assert!(m.add(&tip, element!("replicate", count = 2)).is_ok());
    Ok(())
}

#[test]
fn replicates_keep_their_content_and_automatic_names_stay_distinct_once_numbered()
-> Result<(), Box<dyn std::error::Error>> {
    let m = Model::from_xml_str(SCENE)?;
    let out = m.to_xml_string()?;
    assert!(out.contains(r#"<replicate count="3" sep="-" offset="0.2 0 0">"#), "{out}");
    // MuJoCo appends the copy's number to every name inside: an automatic name there
    // ends in `_`, so that `//unnamed_geom_2_` + `0` is no other element's name.
    assert!(out.contains(r#"<freejoint name="//unnamed_joint_2_"/>"#), "{out}");
    assert!(out.contains(r#"<geom name="//unnamed_geom_3_" class="/" size="0.1"/>"#), "{out}");
    assert!(out.contains(r#"<geom name="//unnamed_geom_4_" class="/" size="0.05"/>"#), "{out}");
    assert!(out.contains(r#"<geom name="//unnamed_geom_2" class="/" size="0.1"/>"#), "{out}");
    // A replicate needs its count, and holds no joints of its own.
    let cube = m.lookup(Namespace::Body, "cube")?;
    let rep = m.get(&cube)?.parent().ok_or("no parent")?.loc();
    assert_eq!(m.get(&rep)?.tag(), "replicate");
    assert!(m.add(&m.worldbody(), element!("replicate", offset = [1, 0, 0])).is_err());
    assert!(m.add(&rep, element!("joint")).is_err());
    assert_eq!(m.set_attr(&rep, "count", 5)?.int(&rep, "count")?, 5);
    // The nested one.
    let inner = m.get(&rep)?.children().find(|c| c.tag() == "replicate").ok_or("no inner")?;
    assert_eq!(inner.int("count"), Some(2));
    Ok(())
}

#[test]
fn attach_references_name_the_asset_model_or_this_model() {
    let body = ElementKind::ROOT.child("worldbody").and_then(|w| w.child("body")).unwrap();
    let attach = body.child("attach").unwrap();
    let model = attach.attr_index("model").unwrap();
    let b = attach.attr(attach.attr_index("body").unwrap());
    assert_eq!(b.ty, AttrType::Reference(RefTarget::Unless(Namespace::Body, model)));
    let p = attach.attr(attach.attr_index("prefix").unwrap());
    assert_eq!(p.ty, AttrType::NamePrefix);
}

const ROBOT: &str = r#"<mujoco model="robot">
  <default><default class="link"><geom size=".02"/></default></default>
  <asset><model name="hand" file="hand.xml"/></asset>
  <worldbody>
    <body name="base">
      <frame name="mount" childclass="link">
        <body name="upper"><joint name="shoulder"/><geom name="upper_geom"/></body>
        <frame name="wrist"><site name="tool"/></frame>
        <attach model="hand" body="palm" prefix="hand_"/>
        <attach body="upper" prefix="copy_"/>
        <attach frame="wrist" prefix="w_"/>
      </frame>
    </body>
    <replicate count="3" sep="-">
      <body name="finger"><joint name="knuckle"/><geom size=".01"/></body>
    </replicate>
  </worldbody>
  <actuator>
    <pid name="servo" joint="shoulder" kp="5"/>
    <dcmotor name="motor" joint="knuckle" motorconst="0.05" resistance="2"/>
  </actuator>
</mujoco>"#;

const HAND: &str = r#"<mujoco model="hand"><worldbody><body name="palm"><geom size=".01"/></body></worldbody></mujoco>"#;

#[test]
fn attaching_prefixes_frames_replicated_names_and_every_reference()
-> Result<(), Box<dyn std::error::Error>> {
    let robot = ReadOptions::new().asset("hand.xml", HAND.as_bytes().to_vec()).read_str(ROBOT)?;
    // A nameless asset model is named after the model its file holds.
    let nameless =
        ROBOT.replace(r#"<model name="hand" file="hand.xml"/>"#, r#"<model file="hand.xml"/>"#);
    let m = ReadOptions::new().asset("hand.xml", HAND.as_bytes().to_vec()).read_str(&nameless)?;
    assert!(m.find(Namespace::Model, "hand").is_some());

    let mut arena = Model::from_xml_str(
        r#"<mujoco model="arena"><worldbody><frame name="table"><site name="spawn"/></frame></worldbody></mujoco>"#,
    )?;
    // At a site inside a frame: the attachment sits in the frame, right after the site.
    let spawn = arena.lookup(Namespace::Site, "spawn")?;
    let a = arena.attach_mut(&spawn, &robot)?;
    assert_eq!(arena.get(a.frame())?.parent().and_then(|p| p.identifier()), Some("table"));
    let b = arena.attach_mut(&arena.worldbody(), &robot)?;
    assert_eq!(b.scope(), "robot_1");
    assert!(arena.find(Namespace::Frame, "robot/mount").is_some());
    assert!(arena.find(Namespace::Frame, "robot_1/wrist").is_some());
    assert!(arena.find(Namespace::Model, "robot_1/hand").is_some());
    let out = arena.to_xml_string()?;
    for s in ["robot", "robot_1"] {
        for want in [
            format!(r#"<model name="{s}/hand" file="hand-"#),
            format!(r#"<frame name="{s}/mount" childclass="{s}/link">"#),
            format!(r#"<frame name="{s}/wrist">"#),
            // The asset model's body is named in the asset model: not prefixed. The
            // names the attach makes start with the scope.
            format!(r#"<attach model="{s}/hand" body="palm" prefix="{s}/hand_"/>"#),
            // This model's body and frame are.
            format!(r#"<attach body="{s}/upper" prefix="{s}/copy_"/>"#),
            format!(r#"<attach frame="{s}/wrist" prefix="{s}/w_"/>"#),
            format!(r#"<body name="{s}/finger">"#),
            format!(r#"<pid name="{s}/servo" class="{s}/" joint="{s}/shoulder" kp="5"/>"#),
            format!(r#"<dcmotor name="{s}/motor" class="{s}/" joint="{s}/knuckle""#),
        ] {
            assert!(out.contains(&want), "no {want} in {out}");
        }
    }
    assert!(out.contains(
        r#"<frame name="table">
      <site name="spawn" class="/"/>
      <body name="robot/">"#
    ));
    // Detaching gives the arena back.
    let back = arena.detach(&b)?.detach(&a)?;
    assert!(back.find(Namespace::Frame, "robot/mount").is_none());
    Ok(())
}

#[test]
fn edits_are_checked_against_the_new_types() -> Result<(), EditError> {
    let m = Model::from_xml_str(SCENE).unwrap();
    let motor = m.lookup(Namespace::Actuator, "m1")?;
    assert!(m.set_attr(&motor, "lugre", [1.0, 2.0, 3.0, 4.0, 5.0]).is_ok());
    assert!(m.set_attr(&motor, "lugre", [1.0, 2.0, 3.0, 4.0, 5.0, 6.0]).is_err());
    assert!(m.set_attr(&motor, "motorconst", "fast").is_err());
    let shelf = m.lookup(Namespace::Frame, "shelf")?;
    assert!(m.set_attr(&shelf, "scaling", "geometry").is_ok());
    assert!(m.set_attr(&shelf, "scaling", "bigger").is_err());
    assert!(m.set_attr(&shelf, "mass", 1.0).is_err());
    Ok(())
}
