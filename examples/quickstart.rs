//! The seed scenario: two robots attached to an arena (the second is also named
//! `robot`, so its scope is `robot_1`), a freejoint, the composed MJCF, and detach.
use mjcf::{Element, Model, element};

fn robot(geom: Element) -> Result<Model, mjcf::Error> {
    let mut robot = Model::new("robot");
    let torso = robot.add_mut(&robot.worldbody(), element!("body", name = "torso"))?;
    robot.add_mut(&torso, geom)?;
    robot.add_mut(&torso, element!("joint", name = "slide_x", type = "slide", axis = [1, 0, 0]))?;
    robot.add_mut(&robot.actuator(), element!("motor", name = "motor_x", joint = "slide_x"))?;
    Ok(robot)
}

fn main() -> Result<(), mjcf::Error> {
    let mut arena = Model::new("arena");
    let world = arena.worldbody();
    arena.add_mut(&world, element!("geom", type = "plane", size = [5.0, 5.0, 0.1]))?;
    let spawn = arena.add_mut(&world, element!("site", name = "spawn", pos = [0.0, 0.0, 0.5]))?;
    let spawn2 = arena.add_mut(&world, element!("site", name = "spawn2", pos = [1.0, 0.0, 0.5]))?;

    let robot1 = robot(element!("geom", type = "box", size = [0.1, 0.1, 0.1], mass = 1.0))?;
    let robot2 = robot(element!("geom", type = "sphere", size = [0.1], mass = 0.5))?;

    let frame = arena.attach_mut(&spawn, &robot1)?;
    arena.add_mut(frame.frame(), element!("freejoint", name = "root"))?;
    // MuJoCo wants mass on a body that moves freely: the frame is one.
    let inertial = element!("inertial", pos = [0, 0, 0], mass = 0.1, diaginertia = [1e-3; 3]);
    arena.add_mut(frame.frame(), inertial)?;
    arena.attach_mut(&spawn2, &robot2)?; // scope robot_1
    print!("{}", arena.to_xml_string()?);
    arena.detach_mut(&frame)?;
    Ok(())
}
