//! In-place edits (`add_mut`, `insert_mut`, `attach_mut`) edit the nodes a model owns
//! alone where they are: they must give the same model as the functional edits, never
//! change a clone taken before, and leave the model as it was when they fail (a
//! duplicate name found deep in an added subtree included).
//!
//! Properties run `PROPTEST_CASES` cases (default 128) from proptest's fixed seed.

use mjcf::{Element, ErrorKind, Loc, Model, Namespace};
use proptest::prelude::*;
use proptest::test_runner::Config;

use crate::robot;
use robot::robot;

/// One edit, applied both ways.
#[derive(Clone, Debug)]
enum Op {
    /// A geom named `g{name}` (names repeat, so some adds are refused).
    Geom { parent: prop::sample::Index, name: u8 },
    /// A body `b{name}` holding a geom `g{inner}` and a geom `g{dup}`: refused when a
    /// name is taken, after part of the subtree was indexed.
    Body { parent: prop::sample::Index, name: u8, inner: u8, dup: u8 },
    /// A site `s{name}` inserted at `index` among the parent's children.
    Site { parent: prop::sample::Index, index: usize, name: u8 },
    /// The robot attached at a site (or the worldbody if there is none).
    Attach { site: prop::sample::Index, which: bool },
    /// A freejoint on an attachment frame (a second one is refused).
    Freejoint { frame: prop::sample::Index },
}

fn op() -> impl Strategy<Value = Op> {
    let name = 0u8..6;
    prop_oneof![
        (any::<prop::sample::Index>(), name.clone())
            .prop_map(|(parent, name)| Op::Geom { parent, name }),
        (any::<prop::sample::Index>(), name.clone(), name.clone(), name.clone())
            .prop_map(|(parent, name, inner, dup)| Op::Body { parent, name, inner, dup }),
        (any::<prop::sample::Index>(), 0usize..4, name)
            .prop_map(|(parent, index, name)| Op::Site { parent, index, name }),
        (any::<prop::sample::Index>(), any::<bool>())
            .prop_map(|(site, which)| Op::Attach { site, which }),
        any::<prop::sample::Index>().prop_map(|frame| Op::Freejoint { frame }),
    ]
}

/// The worldbody and the model's own bodies, in document order.
fn parents(m: &Model) -> Vec<Loc> {
    let mut v = vec![m.worldbody()];
    v.extend(m.find_all(Namespace::Body).into_iter().filter(|l| !l.is_scoped()));
    v
}

fn pick(v: &[Loc], i: &prop::sample::Index) -> Option<Loc> {
    (!v.is_empty()).then(|| v[i.index(v.len())].clone())
}

/// `op` on `m`, functionally.
fn functional(m: &Model, op: &Op, robots: &[Model; 2]) -> Result<Model, mjcf::EditError> {
    Ok(match op {
        Op::Geom { parent, name } => {
            let p = pick(&parents(m), parent).unwrap_or_else(|| m.worldbody());
            m.add(&p, geom(*name))?.0
        }
        Op::Body { parent, name, inner, dup } => {
            let p = pick(&parents(m), parent).unwrap_or_else(|| m.worldbody());
            m.add(&p, body(*name, *inner, *dup))?.0
        }
        Op::Site { parent, index, name } => {
            let p = pick(&parents(m), parent).unwrap_or_else(|| m.worldbody());
            m.insert(&p, *index, Element::new("site").attr("name", format!("s{name}")))?.0
        }
        Op::Attach { site, which } => {
            let at = pick(&own_sites(m), site).unwrap_or_else(|| m.worldbody());
            m.attach(&at, &robots[usize::from(*which)])?.0
        }
        Op::Freejoint { frame } => {
            let Some(f) = pick(&frames(m), frame) else { return Ok(m.clone()) };
            m.add(&f, Element::new("freejoint"))?.0
        }
    })
}

/// `op` on `m`, in place.
fn in_place(m: &mut Model, op: &Op, robots: &[Model; 2]) -> Result<(), mjcf::EditError> {
    match op {
        Op::Geom { parent, name } => {
            let p = pick(&parents(m), parent).unwrap_or_else(|| m.worldbody());
            m.add_mut(&p, geom(*name))?;
        }
        Op::Body { parent, name, inner, dup } => {
            let p = pick(&parents(m), parent).unwrap_or_else(|| m.worldbody());
            m.add_mut(&p, body(*name, *inner, *dup))?;
        }
        Op::Site { parent, index, name } => {
            let p = pick(&parents(m), parent).unwrap_or_else(|| m.worldbody());
            m.insert_mut(&p, *index, Element::new("site").attr("name", format!("s{name}")))?;
        }
        Op::Attach { site, which } => {
            let at = pick(&own_sites(m), site).unwrap_or_else(|| m.worldbody());
            m.attach_mut(&at, &robots[usize::from(*which)])?;
        }
        Op::Freejoint { frame } => {
            if let Some(f) = pick(&frames(m), frame) {
                m.add_mut(&f, Element::new("freejoint"))?;
            }
        }
    }
    Ok(())
}

fn geom(name: u8) -> Element {
    Element::new("geom").attr("name", format!("g{name}")).attr("size", [0.1])
}

fn body(name: u8, inner: u8, dup: u8) -> Element {
    Element::new("body")
        .attr("name", format!("b{name}"))
        .child(geom(inner))
        .child(Element::new("body").child(geom(dup)))
}

fn own_sites(m: &Model) -> Vec<Loc> {
    m.find_all(Namespace::Site).into_iter().filter(|l| !l.is_scoped()).collect()
}

fn frames(m: &Model) -> Vec<Loc> {
    m.scopes().map(|s| m.frame(s).unwrap()).collect()
}

proptest! {
    #![proptest_config(Config { cases: std::env::var("PROPTEST_CASES").ok().and_then(|c| c.parse().ok()).unwrap_or(128), ..Config::default() })]

    #[test]
    fn in_place_edits_equal_functional_ones_and_spare_clones(ops in prop::collection::vec(op(), 1..40)) {
        let robots = [robot("robot"), robot("arm")];
        let mut a = Model::new("arena");
        a.add_mut(&a.worldbody(), Element::new("site").attr("name", "spawn")).unwrap();
        let mut f = a.clone();
        let mut kept: Vec<(Model, String)> = Vec::new();
        for op in &ops {
            let before = f.clone();
            let xml_before = before.to_xml_string().unwrap();
            kept.push((a.clone(), xml_before.clone()));
            let want = functional(&f, op, &robots);
            let got = in_place(&mut a, op, &robots);
            match (want, got) {
                (Ok(next), Ok(())) => f = next,
                (Err(e), Err(g)) => {
                    prop_assert_eq!(e.to_string(), g.to_string());
                    // Refused: nothing changed, the index included.
                    prop_assert_eq!(&a, &before);
                    prop_assert_eq!(a.to_xml_string().unwrap(), xml_before);
                }
                (w, g) => prop_assert!(false, "functional {:?}, in place {:?}", w.map(|_| ()), g),
            }
            prop_assert_eq!(&a, &f);
            prop_assert_eq!(a.to_xml_string().unwrap(), f.to_xml_string().unwrap());
            // The index agrees with the tree: every name found is where the tree has it.
            for ns in [Namespace::Geom, Namespace::Body, Namespace::Site] {
                let mine: Vec<String> = a.find_all(ns).iter().filter(|l| !l.is_scoped())
                    .filter_map(|l| a.get(l).ok().and_then(|e| e.identifier().map(str::to_string))).collect();
                for n in &mine {
                    prop_assert!(a.find(ns, n).is_some(), "{} not found", n);
                }
            }
        }
        // Clones taken before in-place edits kept their content.
        for (m, xml) in &kept {
            prop_assert_eq!(&m.to_xml_string().unwrap(), xml);
        }
        for (r, n) in robots.iter().zip(["robot", "arm"]) {
            prop_assert_eq!(r.to_xml_string().unwrap(), robot(n).to_xml_string().unwrap());
        }
    }
}

#[test]
fn a_duplicate_deep_in_an_added_subtree_leaves_the_model_as_it_was() {
    let mut m = Model::new("m");
    m.add_mut(&m.worldbody(), geom(9)).unwrap();
    let before = m.clone();
    let xml = m.to_xml_string().unwrap();
    // `b1` and `g1` are indexed before `g9` is found taken.
    let err = m.add_mut(&m.worldbody(), body(1, 1, 9)).unwrap_err();
    assert!(matches!(err.kind(), ErrorKind::DuplicateIdentifier { .. }), "{err}");
    assert_eq!(m, before);
    assert_eq!(m.to_xml_string().unwrap(), xml);
    assert!(m.find(Namespace::Body, "b1").is_none());
    assert!(m.find(Namespace::Geom, "g1").is_none());
    // The names are free: the same body without the duplicate goes in.
    let b = m.add_mut(&m.worldbody(), body(1, 1, 2)).unwrap();
    assert_eq!(m.find(Namespace::Body, "b1"), Some(b));
    assert!(m.find(Namespace::Geom, "g1").is_some());
}

#[test]
fn a_fleet_built_in_place_folds_settings_as_the_functional_one() {
    let robot_a = robot("a");
    let robot_a = robot_a.set_attr(&robot_a.section("option").unwrap(), "timestep", 0.002).unwrap();
    let robot_a =
        robot_a.set_attr(&robot_a.section("compiler").unwrap(), "angle", "radian").unwrap();
    let robot_a =
        robot_a.set_attr(&robot_a.section("compiler").unwrap(), "autolimits", true).unwrap();
    let robot_b = robot("b");
    let robot_b = robot_b.set_attr(&robot_b.section("size").unwrap(), "memory", "1M").unwrap();
    let clash = robot("c");
    // (A unit that differs is converted, decision D17; `autolimits` must agree.)
    let clash = clash.set_attr(&clash.section("compiler").unwrap(), "autolimits", false).unwrap();
    let mut m = Model::new("arena");
    let mut f = m.clone();
    // a, a, a (the fold of a's settings is known to change nothing after the first),
    // then b (which adds a setting), then a again, then the clash, refused every time.
    for r in [&robot_a, &robot_a, &robot_a, &robot_b, &robot_a, &clash, &robot_a, &clash] {
        let got = m.attach_mut(&m.worldbody(), r);
        let want = f.attach_to_world(r);
        match (got, want) {
            (Ok(_), Ok((next, _))) => f = next,
            (Err(g), Err(w)) => {
                assert!(matches!(g.kind(), ErrorKind::AttributeConflict { .. }), "{g}");
                assert_eq!(g.to_string(), w.to_string());
            }
            (g, w) => panic!("in place {g:?}, functional {:?}", w.map(|_| ())),
        }
        assert_eq!(m, f);
    }
    let xml = m.to_xml_string().unwrap();
    assert_eq!(xml, f.to_xml_string().unwrap());
    assert!(xml.contains(r#"timestep="0.002""#) && xml.contains(r#"memory="1M""#), "{xml}");
    assert!(xml.contains(r#"angle="radian""#), "{xml}");
    assert_eq!(m.scopes().count(), 6);
}
