use super::*;

#[test]
fn new_models_share_one_empty_tree() {
    let a = Model::new("a");
    let b = Model::new("b");
    assert_eq!(a.worldbody(), b.worldbody());
    assert_eq!(a.name(), "a");
    assert_eq!(Model::new("").name(), "unnamed_model");
}

/// Every element of `m`'s own tree is indexed with its parent, kind and name, and
/// found by its id, whether it has an entry of its own or belongs to a run of
/// singletons (`index.rs`); the index holds nothing else.
fn assert_index_exact(m: &Model) {
    let mut stack = vec![(None, &m.root)];
    let mut count = 0;
    while let Some((parent, n)) = stack.pop() {
        let e = m.index.entry(n.id()).unwrap_or_else(|| panic!("{:?} is indexed", n.id()));
        assert_eq!(
            (e.parent, e.kind, e.name().map(smol_str::SmolStr::as_str)),
            (parent, n.kind(), n.identifier())
        );
        let found = m.path_of(n.id()).and_then(|p| m.node_at(&p).map(Node::id));
        assert_eq!(found, Some(n.id()));
        count += 1;
        stack.extend(n.children().iter().map(|c| (Some(n.id()), c)));
    }
    assert_eq!(m.index.len(), count);
}

#[test]
fn singletons_indexed_as_runs_are_found_like_any_element_through_edits() {
    let xml = r#"<mujoco model="m">
      <visual><map znear="0.01"/></visual>
      <default>
        <default class="a"><default class="b"><default class="c"/></default></default>
        <default class="d"><geom rgba="1 0 0 1"/></default>
      </default>
      <worldbody><body name="b"><geom class="a" size="0.1"/></body></worldbody>
    </mujoco>"#;
    let m = Model::from_xml_str(xml).unwrap();
    assert_index_exact(&m);
    // Classes read without singletons are runs; `d` (its geom was read) and `visual`
    // (its map was read) are not.
    assert!(m.index.runs.len() >= 4, "{} runs", m.index.runs.len());
    let class = |m: &Model, name| m.find(Namespace::Default, name).unwrap();
    let geom_of = |m: &Model, class: &Loc| m.child(class, "geom").unwrap();
    // An edit of a member of a run, then a removal of the class holding it.
    let g = geom_of(&m, &class(&m, "b"));
    let m = m.set_attr(&g, "rgba", [0.0, 1.0, 0.0, 1.0]).unwrap();
    assert_index_exact(&m);
    assert_eq!(m.floats(&g, "rgba").unwrap(), [0.0, 1.0, 0.0, 1.0]);
    let m = m.remove(&class(&m, "c")).unwrap();
    assert_index_exact(&m);
    // A singleton section reset by removal, a class added, a model included.
    let m = m.remove(&m.section("visual").unwrap()).unwrap();
    assert_index_exact(&m);
    let (m, e) =
        m.add(&m.default_class(), crate::Element::new("default").attr("class", "e")).unwrap();
    assert_index_exact(&m);
    let m = m.set_attr(&geom_of(&m, &e), "size", [0.2]).unwrap();
    assert_index_exact(&m);
    let other =
        Model::from_xml_str(r#"<mujoco><default><default class="f"/></default></mujoco>"#).unwrap();
    let m = m.include_copy(&other, false).unwrap();
    assert_index_exact(&m);
    let (m, _) = m.attach(&m.worldbody(), &other).unwrap();
    assert_index_exact(&m);
    assert!(m.find(Namespace::Default, "f").is_some());
}

/// The reader indexes the nodes as it makes them (`ReadIndex`): every model of the
/// conformance cases that reads (without its includes, which are merged by edits)
/// is indexed exactly as the tree says.
#[test]
fn read_models_are_indexed_exactly() {
    let cases = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/conformance/cases");
    let mut read = 0;
    for case in std::fs::read_dir(cases).unwrap() {
        for file in std::fs::read_dir(case.unwrap().path()).unwrap() {
            let path = file.unwrap().path();
            if path.extension().is_some_and(|e| e == "xml") {
                if let Ok(m) = Model::from_path(&path) {
                    assert_index_exact(&m);
                    read += 1;
                }
            }
        }
    }
    assert!(read > 100, "{read} models read");
    let xml = r#"<mujoco model="m">
      <default><default class="/"><geom size="1"/><default class="x"/></default></default>
      <worldbody>
        <body name="//unnamed_body_0"><geom name="g" class="x" size="0.1"/></body>
        <body name="b"><joint name="j"/><geom size="0.1"/></body>
      </worldbody>
      <actuator><motor joint="j"/></actuator>
    </mujoco>"#;
    assert_index_exact(&Model::from_xml_str(xml).unwrap());
}

/// A model is held by value in each of its attachments (a fleet of 1,000 robots holds
/// 1,000 copies of the robot's `Model`), so what a model value holds beside its tree,
/// index and files sits behind one pointer (`Side`, `Slashed`, `own_name`): the value
/// is kept at the size it had before they were added.
#[test]
fn a_model_value_stays_at_its_size() {
    assert!(std::mem::size_of::<Model>() <= 208, "{}", std::mem::size_of::<Model>());
}

#[test]
fn elements_deeper_than_the_ancestry_kept_on_the_stack_are_found() {
    // `path_of` keeps the nearest 24 ancestors on the stack and any farther in a
    // list: every depth on both sides of that, and the element itself, is found.
    let depth = 40;
    let mut xml = String::from("<mujoco><worldbody>");
    for i in 0..depth {
        xml.push_str(&format!("<body name=\"b{i}\"><geom size=\"0.1\"/>"));
    }
    xml.push_str(&"</body>".repeat(depth));
    xml.push_str("</worldbody></mujoco>");
    let m = Model::from_xml_str(&xml).unwrap();
    assert_index_exact(&m);
    let key = (Namespace::Body, SmolStr::from(format!("b{}", depth - 1)));
    let path = m.path_of(m.index.names[&key]).unwrap();
    // worldbody, then one body per level.
    assert_eq!(path.len(), depth + 1);
}
