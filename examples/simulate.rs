//! Nine quadrupeds (or N) on a floor, composed from one model file at the sites of a
//! grid 1 m apart, with one composed `home` key; reset to it, stepped and measured in
//! Rust alone, with MuJoCo's library (found through `MUJOCO_LIB`).
//!
//! ```sh
//! cargo run --release --example simulate -- ROBOT_XML N STEPS
//! ```
//!
//! prints `robot_k x y z` per robot (k = 0..N in attach order): its base's position
//! after the steps. Without arguments: examples/models/quadruped.xml, 9, 1000.
use mjcf::{Model, WriteOptions, element};
use mjcf_mujoco::{MuJoCo, Physics};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let robot_xml = args.next().unwrap_or_else(|| "examples/models/quadruped.xml".into());
    let n: usize = args.next().map_or(Ok(9), |s| s.parse())?;
    let steps: usize = args.next().map_or(Ok(1000), |s| s.parse())?;

    let robot = Model::from_path(&robot_xml)?;
    // The robot's base: its first top-level body (the one with the free joint).
    let base = robot.get(&robot.worldbody())?.children().find(|c| c.tag() == "body");
    let base = base.ok_or("the robot has no body")?.loc();

    let mut arena = Model::new("arena");
    let floor = element!("geom", name = "floor", type = "plane", size = [20.0, 20.0, 0.1]);
    arena.add_mut(&arena.worldbody(), floor)?;
    let side = (1..).find(|s| s * s >= n).unwrap_or(1);
    let mut scopes = Vec::new();
    for k in 0..n {
        let (x, y) = ((k % side) as f64, (k / side) as f64);
        let site = element!("site", name = format!("spawn_{k}"), pos = [x, y, 0.0]);
        let site = arena.add_mut(&arena.worldbody(), site)?;
        scopes.push(arena.attach_mut(&site, &robot)?.scope().to_string());
    }

    // One `home` key over the whole fleet: each robot's own, carried to its site.
    let options = WriteOptions { merge_keyframes: true, ..WriteOptions::default() };
    let compiled = MuJoCo::load()?.compile_with(&arena, &options)?;
    let mut physics = Physics::new(&compiled)?;
    if compiled.id(mjcf_mujoco::ObjKind::Key, "home").is_some() {
        physics.reset_to_key("home")?;
    }
    let warnings = physics.step(steps)?;
    for w in &warnings {
        eprintln!("warning: {w}");
    }
    for (k, scope) in scopes.iter().enumerate() {
        let b = physics.bind(&arena.locate_in(scope.as_str(), &base)?)?;
        let p = physics.get(&b, "xpos")?;
        println!("robot_{k} {:.4} {:.4} {:.4}", p[0], p[1], p[2]);
    }
    Ok(())
}
