//! N robots from one model file on a floor, saved as a scene that references its parts
//! (MuJoCo's `<attach>`), reopened composed, and one attachment detached.
//!
//! ```sh
//! cargo run --release --example reopen -- ROBOT_XML N OUT_DIR
//! ```
//!
//! composes N copies of ROBOT_XML at the sites of a grid 1 m apart in an arena with a
//! floor, saves the scene into OUT_DIR (`OUT_DIR/scene.xml` and the files it
//! references), reopens `OUT_DIR/scene.xml`, prints `scopes: <scope> <scope> ...` (the
//! reopened model's, in attach order), detaches the last attachment and exports that
//! model with its files into `OUT_DIR/detached/` as `detached.xml`.
use mjcf::{Model, WriteOptions, element};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [robot_xml, n, out] = &args[..] else {
        return Err("usage: reopen ROBOT_XML N OUT_DIR".into());
    };
    let n: usize = n.parse()?;
    let robot = Model::from_path(robot_xml)?;

    let mut arena = Model::new("arena");
    let floor = element!("geom", name = "floor", type = "plane", size = [20, 20, 0.1]);
    arena.add_mut(&arena.worldbody(), floor)?;
    let side = (1..).find(|s| s * s >= n).unwrap_or(1);
    for k in 0..n {
        let (x, y) = ((k % side) as f64, (k / side) as f64);
        let site = element!("site", name = format!("spawn_{k}"), pos = [x, y, 0.0]);
        let site = arena.add_mut(&arena.worldbody(), site)?;
        arena.attach_mut(&site, &robot)?;
    }

    let saved = arena.save_scene(out, "scene.xml")?;
    let mut scene = Model::from_path(saved.path())?;
    let scopes: Vec<String> = scene.scopes().map(str::to_string).collect();
    println!("scopes: {}", scopes.join(" "));
    let last = scopes.last().ok_or("nothing is attached")?;
    scene.detach_mut(last.as_str())?;
    let dir = std::path::Path::new(out).join("detached");
    scene.export(&dir, "detached.xml", &WriteOptions::default())?;
    Ok(())
}
