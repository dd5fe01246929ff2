//! An editor session: a `History` of versions (O(1) clones), undo/redo, the library's diff,
//! and the scene saved as MuJoCo composes files, reopened composed.
use mjcf::Namespace::{Body, Geom, Joint, Site};
use mjcf::{History, Model, element};

fn main() -> Result<(), mjcf::Error> {
    let robot = Model::from_path("benches/models/quadruped_robot.xml")?;
    let mut arena = Model::new("arena");
    arena.add_top_mut(element!("geom", name = "floor", type = "plane", size = [10, 10, 0.1]))?;
    for i in 0..4 {
        let site = element!("site", name = format!("spawn_{i}"), pos = [2 * i, 0, 0.6]);
        arena.add_top_mut(site)?;
    }
    let mut history = History::new(arena);

    for i in 0..2 {
        history.edit("add robot", |m| {
            let frame = m.attach_mut(&m.lookup(Site, &format!("spawn_{i}"))?, &robot)?;
            m.add_mut(frame.frame(), element!("freejoint"))
        })?;
    }
    for i in 0..24 {
        history.edit("add box", |m| {
            let pos = [i as f64 * 0.3, 2.0, 0.2];
            let body = element!("body", name = format!("box_{i}"), pos = pos);
            let b = m.add_top_mut(body)?;
            m.add_mut(&b, element!("geom", type = "box", size = [0.1, 0.1, 0.1]))
        })?;
    }
    for i in 0..24 {
        history.edit("paint", |m| {
            let scope = ["quadruped", "quadruped_1"][i % 2];
            let torso = m.lookup(Geom, &format!("{scope}/torso"))?;
            m.set_attr_mut(&torso, "rgba", [i as f64 / 24.0, 0.2, 0.2, 1.0])
        })?;
    }
    history.go_to(history.position() - 10); // undo 10
    history.go_to(history.position() + 5); // redo 5

    let now = history.position();
    for line in history.diff_lines(20, now).unwrap_or_default() {
        println!("{line}");
    }

    history.edit("rename", |m| m.rename_scope_mut("quadruped_1", "dog"))?;
    history.edit("mass", |m| m.set_attr_mut(&m.lookup(Geom, "dog/torso")?, "mass", 20))?;
    history.edit("remove", |m| m.remove_mut(&m.lookup(Joint, "dog/yaw_front_left")?))?;
    let current = history.current(); // saved as MuJoCo's <attach>es, reopened composed:
    let saved = current.save_scene(std::env::temp_dir(), "editor.xml")?;
    let reopened = Model::from_path(saved.path())?.detach("dog")?;
    let bodies = reopened.find_all(Body).len();
    println!("{} versions; reopened: {bodies} bodies", history.len());
    Ok(())
}
