//! An editor session: versions (O(1) clones), undo/redo as a cursor, the library's diff.
use mjcf::Namespace::{Body, Geom, Joint, Site};
use mjcf::{EditError, Model, element};

fn edit(
    versions: &mut Vec<Model>,
    cursor: &mut usize,
    change: impl FnOnce(&mut Model) -> Result<(), EditError>,
) -> Result<(), EditError> {
    let mut model = versions[*cursor].clone();
    change(&mut model)?;
    versions.truncate(*cursor + 1);
    versions.push(model);
    *cursor += 1;
    Ok(())
}

fn main() -> Result<(), mjcf::Error> {
    let robot = Model::from_path("benches/models/quadruped_robot.xml")?;
    let mut arena = Model::new("arena");
    let world = arena.worldbody();
    arena.add_mut(
        &world,
        element!("geom", name = "floor", type = "plane", size = [10.0, 10.0, 0.1]),
    )?;
    for i in 0..4 {
        let pos = [2.0 * i as f64, 0.0, 0.6];
        arena.add_mut(&world, element!("site", name = format!("spawn_{i}"), pos = pos))?;
    }
    let (mut versions, mut cursor) = (vec![arena], 0);

    for i in 0..2 {
        edit(&mut versions, &mut cursor, |m| {
            let frame = m.attach_mut(&m.lookup(Site, &format!("spawn_{i}"))?, &robot)?;
            m.add_mut(frame.frame(), element!("freejoint")).map(drop)
        })?;
    }
    for i in 0..24 {
        edit(&mut versions, &mut cursor, |m| {
            let pos = [i as f64 * 0.3, 2.0, 0.2];
            let b =
                m.add_mut(&m.worldbody(), element!("body", name = format!("box_{i}"), pos = pos))?;
            m.add_mut(&b, element!("geom", type = "box", size = [0.1, 0.1, 0.1])).map(drop)
        })?;
    }
    for i in 0..24 {
        edit(&mut versions, &mut cursor, |m| {
            let scope = if i % 2 == 0 { "quadruped" } else { "quadruped_1" };
            let torso = m.lookup(Geom, &format!("{scope}/torso"))?;
            m.set_attr_mut(&torso, "rgba", [i as f64 / 24.0, 0.2, 0.2, 1.0])
        })?;
    }
    cursor -= 10; // undo 10
    cursor += 5; // redo 5

    let (old, new) = (&versions[20], &versions[cursor]);
    for change in old.diff(new) {
        println!("{}", change.display(old, new));
    }

    edit(&mut versions, &mut cursor, |m| m.rename_scope_mut("quadruped_1", "dog"))?;
    edit(&mut versions, &mut cursor, |m| {
        m.set_attr_mut(&m.lookup(Geom, "dog/torso")?, "mass", 20)
    })?;
    edit(&mut versions, &mut cursor, |m| m.remove_mut(&m.lookup(Joint, "dog/yaw_front_left")?))?;
    let again = Model::from_xml_str(&versions[cursor].to_xml_string()?)?; // names with '/' read
    println!("{} versions; read back: {} bodies", versions.len(), again.find_all(Body).len());
    Ok(())
}
