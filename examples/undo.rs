//! An editor-style history with `mjcf::History`: every version is a `Model` value,
//! undo and redo move a cursor, and the diff of two versions skips every subtree they
//! share.
//!
//! ```text
//! cargo run --example undo
//! ```
//!
//! Keeping a version costs only what its edit copied (the path from the edited element
//! to the root); `Model::diff` walks only the elements an edit touched, comparing
//! shared subtrees by pointer in O(1).

use std::path::PathBuf;

use mjcf::Namespace::{Body, Geom, Site};
use mjcf::{Error, History, Model, element};

fn show_diff(h: &History, from: usize, to: usize) {
    let lines = h.diff_lines(from, to).unwrap_or_default();
    println!("diff v{from} -> v{to}: {} difference(s)", lines.len());
    for line in lines {
        println!("  {line}");
    }
}

fn main() -> Result<(), Error> {
    let models = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../benches/models");
    let robot = Model::from_path(models.join("quadruped_robot.xml"))?;

    let mut arena = Model::new("arena");
    arena.add_top_mut(element!("geom", name = "floor", type = "plane", size = [10, 10, 0.1]))?;
    arena.add_top_mut(element!("site", name = "spawn_0", pos = [-2, 0, 0.6]))?;
    arena.add_top_mut(element!("site", name = "spawn_1", pos = [2, 0, 0.6]))?;

    let mut h = History::new(arena);
    for site in ["spawn_0", "spawn_1"] {
        h.edit(format!("attach the quadruped at {site}, with a freejoint"), |m| {
            let frame = m.attach_mut(&m.lookup(Site, site)?, &robot)?;
            m.add_mut(frame.frame(), element!("freejoint"))
        })?;
    }
    h.edit("paint quadruped_1's torso red", |m| {
        m.set_attr_mut(&m.lookup(Geom, "quadruped_1/torso")?, "rgba", [0.9, 0.1, 0.1, 1.0])
    })?;
    // The persistent forms fit too: a new version made from the current one, pushed.
    let floor = h.current().lookup(Geom, "floor")?;
    h.push("move the floor down", h.current().set_attr(&floor, "pos", [0.0, 0.0, -0.01])?);
    h.edit("add a box obstacle", |m| {
        let geom = element!("geom", name = "obstacle", type = "box", size = [0.25; 3]);
        m.add_top_mut(element!("body", name = "obstacle", pos = [0, 3, 0.25]).child(geom))
    })?;
    for (from, to) in [(2, 3), (3, 5), (1, 2)] {
        show_diff(&h, from, to);
    }

    h.undo();
    h.undo();
    let obstacle = h.current().find(Body, "obstacle").is_some();
    println!("current: v{} (obstacle: {obstacle})", h.position());
    h.redo();
    let pos = h.current().floats(&floor, "pos")?.to_vec();
    println!("current: v{} (floor at {pos:?})", h.position());
    // A new edit after an undo drops the redo branch (v5, the obstacle).
    h.edit("detach quadruped (the first robot)", |m| m.detach_mut("quadruped"))?;
    println!("{} versions kept; the redo branch is gone", h.len());
    show_diff(&h, 4, 5);
    show_diff(&h, 0, h.position());

    // Undo never copies: going back to v3 gives exactly the value that was kept.
    let v3 = h.get(3).expect("v3 is kept").clone();
    h.undo();
    h.undo();
    assert!(h.current().ptr_eq(&v3));
    println!("undo twice: back at v{}, the very value kept for it (ptr_eq)", h.position());
    Ok(())
}
