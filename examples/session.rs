//! A file session: open a model file, edit, undo and redo, save in place, reopen.
//! Only the edited lines of the file change (`git diff` shows them alone).
//!
//!     cargo run --example session -- [MODEL_FILE]
//!
//! (default: a copy of examples/models/quadruped.xml in a temporary folder; the file
//! needs a body `base` and a geom `torso`).
use mjcf::{History, Model, Namespace};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = match std::env::args().nth(1) {
        Some(p) => std::path::PathBuf::from(p),
        None => {
            let dir = std::env::temp_dir().join(format!("mjcf-session-{}", std::process::id()));
            std::fs::create_dir_all(&dir)?;
            std::fs::copy("examples/models/quadruped.xml", dir.join("quadruped.xml"))?;
            dir.join("quadruped.xml")
        }
    };
    let mut history = History::new(Model::from_path(&path)?);
    let base = history.current().find(Namespace::Body, "base").ok_or("no body 'base'")?;
    let torso = history.current().find(Namespace::Geom, "torso").ok_or("no geom 'torso'")?;
    history.edit("raise", |m| m.set_attr_mut(&base, "pos", [0.0, 0.0, 0.4]))?;
    history.edit("tint", |m| m.set_attr_mut(&torso, "rgba", [0.8, 0.2, 0.2, 1.0]))?;
    history.undo(); // the tint goes
    history.redo(); // and comes back
    history.undo(); // keep the raise alone
    let written = history.current().save()?;
    println!("saved {} file(s): {written:?}", written.len());
    let reopened = Model::from_path(&path)?;
    assert_eq!(&reopened, history.current());
    let base = reopened.find(Namespace::Body, "base").ok_or("no body 'base'")?;
    let pos = reopened.get(&base)?.attr("pos").map(ToString::to_string);
    println!("reopened: base at {pos:?}");
    Ok(())
}
