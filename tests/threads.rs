//! Versions shared across threads: one base value, 1000 variants built from it in
//! parallel, each checked against the same variant built on one thread, and the base
//! unchanged afterwards.

use std::thread;

use mjcf::{Element, Model, Namespace};

use crate::robot;
use robot::robot;

const VARIANTS: usize = 1000;
const THREADS: usize = 8;

fn assert_send_sync<T: Send + Sync>() {}

#[test]
fn models_locators_and_errors_are_send_and_sync() {
    assert_send_sync::<Model>();
    assert_send_sync::<mjcf::Loc>();
    assert_send_sync::<Element>();
    assert_send_sync::<mjcf::Error>();
}

/// An arena with 10 sites and a robot attached at each of the first five.
fn base() -> Model {
    let mut m = Model::new("arena");
    for i in 0..10 {
        let site = Element::new("site")
            .attr("name", format!("spawn_{i}").as_str())
            .attr("pos", [i as f64, 0.0, 0.5]);
        m = m.add(&m.worldbody(), site).unwrap().0;
    }
    let r = robot("robot");
    for i in 0..5 {
        let site = m.find(Namespace::Site, &format!("spawn_{i}")).unwrap();
        let (next, frame) = m.attach(&site, &r).unwrap();
        m = next.add(frame.frame(), Element::new("freejoint")).unwrap().0;
    }
    m
}

/// Variant `i`: recolour one robot, move another's torso, attach one more robot,
/// detach one of the first five, and write.
fn variant(base: &Model, i: usize) -> (Model, String) {
    let scope = |k: usize| if k == 0 { "robot".to_string() } else { format!("robot_{k}") };
    let geom = base.find(Namespace::Geom, &format!("{}/torso", scope(i % 5))).unwrap();
    let m = base.set_attr(&geom, "rgba", [i as f64 / VARIANTS as f64, 0.5, 0.5, 1.0]).unwrap();
    let torso = m.find(Namespace::Body, &format!("{}/torso", scope((i + 1) % 5))).unwrap();
    let m = m.set_attr(&torso, "pos", [0.0, 0.0, i as f64]).unwrap();
    let site = m.find(Namespace::Site, &format!("spawn_{}", 5 + i % 5)).unwrap();
    let (m, _) = m.attach(&site, &robot("robot")).unwrap();
    let m = m.detach(scope((i + 2) % 5)).unwrap();
    let xml = m.to_xml_string().unwrap();
    (m, xml)
}

#[test]
fn a_thousand_variants_built_in_parallel_from_one_base() {
    let base = base();
    let base_xml = base.to_xml_string().unwrap();
    let results: Vec<(usize, Model, String)> = thread::scope(|s| {
        let handles: Vec<_> = (0..THREADS)
            .map(|t| {
                let base = &base;
                s.spawn(move || {
                    (t..VARIANTS)
                        .step_by(THREADS)
                        .map(|i| {
                            let (m, xml) = variant(base, i);
                            (i, m, xml)
                        })
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        handles.into_iter().flat_map(|h| h.join().unwrap()).collect()
    });
    assert_eq!(results.len(), VARIANTS);
    // The base is untouched and still shared by every variant's unchanged parts.
    assert_eq!(base.to_xml_string().unwrap(), base_xml);
    for (i, m, xml) in &results {
        // Each variant is exactly what one thread alone builds.
        let (serial, serial_xml) = variant(&base, *i);
        assert_eq!(xml, &serial_xml, "variant {i}");
        assert_eq!(m.to_xml_string().unwrap(), serial_xml, "variant {i}");
        // Edits landed where they should.
        assert_eq!(m.scopes().count(), 5);
        assert!(m.attached("robot_5").is_ok(), "variant {i}: the extra robot takes scope robot_5");
        let detached =
            if (i + 2) % 5 == 0 { "robot".to_string() } else { format!("robot_{}", (i + 2) % 5) };
        assert!(m.attached(&detached).is_err(), "variant {i}");
        assert!(!xml.contains(&format!("\"{detached}/torso\"")), "variant {i}");
        // Locators stay valid across threads and versions: the spawn sites are the base's.
        let site = base.find(Namespace::Site, "spawn_9").unwrap();
        assert!(m.element(&site).unwrap().ptr_eq(&serial.element(&site).unwrap()));
    }
    let distinct: std::collections::HashSet<&String> = results.iter().map(|(_, _, x)| x).collect();
    assert_eq!(distinct.len(), VARIANTS, "every variant differs (its rgba or pos)");
}
