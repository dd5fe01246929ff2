//! Builds a small scene through the API and prints its MJCF.
//!
//! ```text
//! cargo run --example quickstart
//! ```

use mjcf::{Attrs, Element, Model, Namespace};

fn main() -> Result<(), mjcf::Error> {
    // An arena: a ground plane, a light and a spawn site.
    let arena = Model::new("arena");
    let (arena, _) = arena.add(
        &arena.worldbody(),
        Element::new("geom").attr("name", "floor").attr("type", "plane").attr("size", [5.0, 5.0, 0.1]),
    )?;
    let (arena, _) =
        arena.add(&arena.worldbody(), Element::new("light").attr("name", "top").attr("pos", [0.0, 0.0, 3.0]))?;
    let (arena, _) =
        arena.add(&arena.worldbody(), Element::new("site").attr("name", "spawn").attr("pos", [0.0, 0.0, 0.5]))?;

    // A robot body with a box torso, a slide joint and a motor on it: one `add` per
    // subtree, errors reported once, at the add.
    let robot = Element::new("body")
        .attr("name", "torso")
        .attr("pos", [0.0, 0.0, 0.5])
        .child(Element::new("joint").attr("name", "slide_x").attr("type", "slide").attr("axis", [1.0, 0.0, 0.0]))
        .child(
            Element::new("geom")
                .attr("name", "torso")
                .attr("type", "box")
                .attr("size", [0.1, 0.1, 0.1])
                .attr("mass", 1.0),
        );
    let (scene, torso) = arena.add(&arena.worldbody(), robot)?;
    let (scene, _) = scene.add(
        &scene.actuator(),
        Element::new("motor").attr("name", "motor_x").attr("joint", "slide_x").attr("gear", 10),
    )?;

    // Every edit is a new value; the old one stays as it was.
    let moved = scene.set(&torso, Attrs::new().set("pos", [0.0, 0.0, 0.6]))?;
    assert!(scene.find(Namespace::Body, "torso").is_some());
    assert_ne!(moved, scene);
    assert!(arena.find(Namespace::Body, "torso").is_none());

    print!("{}", moved.to_xml_string()?);
    Ok(())
}
