//! The small robot the composition tests attach (`tests/composition.rs`,
//! `tests/threads.rs`, and the `ops` fuzz target); include with
//! `#[path = "support/robot.rs"] mod robot;`.

use mjcf::{Element, Model};

/// A robot named `name`: a body `torso` with a hinge joint `hip`, a geom `torso`, an
/// unnamed geom and a site `mount`, and a motor `m` on the joint.
pub(crate) fn robot(name: &str) -> Model {
    let m = Model::new(name);
    let (m, _) = m
        .add(
            &m.worldbody(),
            Element::new("body")
                .attr("name", "torso")
                .child(Element::new("joint").attr("name", "hip").attr("type", "hinge"))
                .child(Element::new("geom").attr("name", "torso").attr("size", [0.1]))
                .child(Element::new("geom").attr("size", [0.05]))
                .child(Element::new("site").attr("name", "mount")),
        )
        .unwrap();
    let (m, _) =
        m.add(&m.actuator(), Element::new("motor").attr("name", "m").attr("joint", "hip")).unwrap();
    m
}
