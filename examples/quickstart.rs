//! The seed scenario: an arena, two robots attached at its sites, the composed MJCF,
//! and detach giving back the earlier value.
//!
//! ```text
//! cargo run --example quickstart
//! ```

use mjcf::{Element, Model, Namespace};

/// A robot: a torso body with one geom, a slide joint along x and a motor on it.
fn robot(geom: Element) -> Result<Model, mjcf::Error> {
    let robot = Model::new("robot");
    let (robot, _) = robot.add(
        &robot.worldbody(),
        Element::new("body")
            .attr("name", "torso")
            .child(Element::new("joint").attr("name", "slide_x").attr("type", "slide").attr("axis", [1.0, 0.0, 0.0]))
            .child(geom.attr("name", "torso")),
    )?;
    let (robot, _) =
        robot.add(&robot.actuator(), Element::new("motor").attr("name", "motor_x").attr("joint", "slide_x"))?;
    Ok(robot)
}

fn main() -> Result<(), mjcf::Error> {
    // The arena: a ground plane and two spawn sites.
    let arena = Model::new("arena");
    let (arena, _) = arena.add(
        &arena.worldbody(),
        Element::new("geom").attr("name", "ground").attr("type", "plane").attr("size", [5.0, 5.0, 0.1]),
    )?;
    let (arena, spawn) =
        arena.add(&arena.worldbody(), Element::new("site").attr("name", "spawn").attr("pos", [0.0, 0.0, 0.5]))?;
    let (arena, spawn2) =
        arena.add(&arena.worldbody(), Element::new("site").attr("name", "spawn2").attr("pos", [1.0, 0.0, 0.5]))?;

    let boxy = robot(Element::new("geom").attr("type", "box").attr("size", [0.1, 0.1, 0.1]).attr("mass", 1.0))?;
    let ball = robot(Element::new("geom").attr("type", "sphere").attr("size", [0.1]).attr("mass", 0.5))?;

    // Attach the first robot at `spawn` and give its frame a freejoint. The frame is
    // then a moving body of its own, which MuJoCo wants to have some mass.
    let (scene, frame) = arena.attach(&spawn, &boxy)?;
    let (scene, _) = scene.add(frame.frame(), Element::new("freejoint").attr("name", "root"))?;
    let (scene, _) = scene.add(
        frame.frame(),
        Element::new("inertial").attr("pos", [0.0, 0.0, 0.0]).attr("mass", 0.1).attr("diaginertia", [1e-3; 3]),
    )?;
    // The second robot is also named `robot`: its scope becomes `robot_1`.
    let (with_two, _) = scene.attach(&spawn2, &ball)?;

    assert!(with_two.find(Namespace::Body, "robot/torso").is_some());
    assert!(with_two.find(Namespace::Body, "robot_1/torso").is_some());
    print!("{}", with_two.to_xml_string()?);

    // Detaching gives back exactly the earlier value; the robot values never changed.
    assert_eq!(with_two.detach("robot_1")?, scene);
    assert_eq!(scene.detach("robot")?.to_xml_string()?, arena.to_xml_string()?);
    assert_eq!(boxy.name(), "robot");
    eprintln!("detach(\"robot_1\") gives back the one-robot scene; the arena and robots are unchanged.");
    Ok(())
}
