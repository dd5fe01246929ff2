//! Composed scenes saved as MuJoCo reads them (`Model::save_scene`) and reopened
//! composed (`Model::from_path`).

use mjcf::{Model, element};

#[test]
fn scratch() {
    let mut robot = Model::new("robot");
    let t = robot.add_mut(&robot.worldbody(), element!("body", name = "torso")).unwrap();
    robot.add_mut(&t, element!("geom", size = [0.1])).unwrap();
    let mut arena = Model::new("arena");
    let a = arena.attach_mut(&arena.worldbody(), &robot).unwrap();
    arena.attach_mut(&arena.worldbody(), &robot).unwrap();
    arena.add_mut(a.frame(), element!("joint", type = "slide")).unwrap();
    let scene = arena.to_scene("scene.xml").unwrap();
    println!("{}", scene.root().to_xml_string().unwrap());
    for p in scene.parts() {
        println!("{}: {}", p.file_name(), p.model().to_xml_string().unwrap());
    }
}
