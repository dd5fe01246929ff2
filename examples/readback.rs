//! Writes composed models and what they read back as, in pairs for
//! `tools/readback_check.py` (MuJoCo compiles both to the same model).
//!
//! ```text
//! cargo run --release --example readback -- OUT [XML...]
//! ```
//!
//! Each XML file given (such as the quickstart's output) is read and written back as
//! `OUT/files/<stem>.xml` and `<stem>.readback.xml`; a fleet of 10 and one of 100
//! quadrupeds of `benches/models` on free frames are written to
//! `OUT/fleets` the same way. Writing a read-back again must give the same text: the
//! example fails otherwise.

use std::path::{Path, PathBuf};

use mjcf::{Model, Namespace, ReadOptions, WriteOptions, element};

/// Writes `m` as `dir/name.xml` with its files, and what that text reads back as as
/// `dir/name.readback.xml`, checking that writing the read-back is a fixed point.
fn pair(m: &Model, dir: &Path, name: &str) -> Result<(), Box<dyn std::error::Error>> {
    let opts = WriteOptions::default();
    m.export(dir, &format!("{name}.xml"), &opts)?;
    let xml = m.to_xml_string_with(&opts)?;
    let mut read = ReadOptions::new();
    for (file, asset) in m.assets(&opts)? {
        read = read.asset(&file, asset.contents().to_vec());
    }
    let back = read.read_str(&xml)?;
    let w2 = back.to_xml_string_with(&opts)?;
    let w3 = read.read_str(&w2)?.to_xml_string_with(&opts)?;
    if w2 != w3 {
        return Err(format!("{name}: writing the read-back again gives other text").into());
    }
    back.export(dir, &format!("{name}.readback.xml"), &opts)?;
    println!("{name}: {} bytes, read back and written again identically", xml.len());
    Ok(())
}

fn fleet(n: usize) -> Result<Model, Box<dyn std::error::Error>> {
    let robot = Model::from_path("benches/models/quadruped_robot.xml")?;
    let mut arena = Model::new("arena");
    arena
        .add_mut(&arena.worldbody(), element!("geom", type = "plane", size = [50.0, 50.0, 0.1]))?;
    for i in 0..n {
        let pos = [(i % 10) as f64 * 2.0, (i / 10) as f64 * 2.0, 1.0];
        let site = arena
            .add_mut(&arena.worldbody(), element!("site", name = format!("s{i}"), pos = pos))?;
        let a = arena.attach_mut(&site, &robot)?;
        arena.add_mut(a.frame(), element!("freejoint"))?;
    }
    // One unnamed geom after the attachments: its automatic name counts the arena's
    // own geoms only.
    arena.add_mut(&arena.worldbody(), element!("geom", size = [0.1], pos = [0, 0, 5]))?;
    let first = arena.from_full_name(Namespace::Body, "quadruped/").ok_or("no frame")?;
    assert!(arena.get(&first)?.is_frame());
    Ok(arena)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
    let out = PathBuf::from(args.next().ok_or("usage: readback OUT [XML...]")?);
    for file in args {
        let m = Model::from_path(&file)?;
        let stem = Path::new(&file).file_stem().and_then(|s| s.to_str()).unwrap_or("model");
        pair(&m, &out.join("files"), stem)?;
    }
    for n in [10, 100] {
        pair(&fleet(n)?, &out.join("fleets"), &format!("fleet_{n}"))?;
    }
    Ok(())
}
