//! The seed scenario: two robots attached to an arena (the second is also named
//! `robot`, so its scope is `robot_1`), a freejoint, the composed MJCF, and detach.
use mjcf::{Element, Model, element};

fn robot(geom: Element) -> Result<Model, mjcf::Error> {
    let mut robot = Model::new("robot");
    let joint = element!("joint", name = "slide_x", type = "slide", axis = [1, 0, 0]);
    let torso = element!("body", name = "torso").child(geom).child(joint);
    robot.add_top_mut(torso)?;
    robot.add_top_mut(element!("motor", name = "motor_x", joint = "slide_x"))?;
    Ok(robot)
}

fn main() -> Result<(), mjcf::Error> {
    let mut arena = Model::new("arena");
    arena.add_top_mut(element!("geom", type = "plane", size = [5, 5, 0.1]))?;
    let spawn = arena.add_top_mut(element!("site", name = "spawn", pos = [0, 0, 0.5]))?;
    let spawn2 = arena.add_top_mut(element!("site", name = "spawn2", pos = [1, 0, 0.5]))?;

    let robot1 = robot(element!("geom", type = "box", size = [0.1, 0.1, 0.1], mass = 1))?;
    let robot2 = robot(element!("geom", type = "sphere", size = [0.1], mass = 0.5))?;

    let frame = arena.attach_mut(&spawn, &robot1)?;
    arena.add_mut(frame.frame(), element!("freejoint", name = "root"))?;
    // MuJoCo wants mass on a body that moves freely: the frame is one.
    let inertia = [1e-3; 3];
    let inertial = element!("inertial", pos = [0; 3], mass = 0.1, diaginertia = inertia);
    arena.add_mut(frame.frame(), inertial)?;
    arena.attach_mut(&spawn2, &robot2)?; // scope robot_1
    print!("{}", arena.to_xml_string()?);
    arena.detach_mut(&frame)?;
    Ok(())
}
