//! Lossless save, for checks from outside: reads `IN_DIR/MODEL_FILE`, optionally sets
//! one attribute of the element `TAG` named `NAME` (the first `TAG` when `NAME` is
//! `-`; elements inside default classes are not looked at), and saves the model's files into `OUT_DIR` with their relative paths.
//!
//!     cargo run --release --example lossless -- IN_DIR MODEL_FILE OUT_DIR [SET TAG NAME ATTR VALUE]
use std::path::Path;

use mjcf::{Attrs, Event, Model};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [in_dir, file, out_dir, rest @ ..] = &args[..] else {
        return Err("usage: lossless IN_DIR MODEL_FILE OUT_DIR [SET TAG NAME ATTR VALUE]".into());
    };
    let mut model = Model::from_path(Path::new(in_dir).join(file))?;
    if let [set, tag, name, attr, value] = rest {
        if !set.eq_ignore_ascii_case("set") {
            return Err(format!("expected SET, got '{set}'").into());
        }
        // In document order, outside default classes (whose elements are defaults).
        let mut in_default = 0usize;
        let target = model.walk().find_map(|e| match e {
            Event::Enter(e) if e.tag() == "default" => {
                in_default += 1;
                None
            }
            Event::Leave(e) if e.tag() == "default" => {
                in_default -= 1;
                None
            }
            Event::Enter(e) if in_default == 0 && e.tag() == tag => {
                (name == "-" || e.identifier() == Some(name.as_str())).then(|| e.loc())
            }
            _ => None,
        });
        let target = target.ok_or(format!("no <{tag}> named '{name}'"))?;
        model = model.set(&target, Attrs::new().set(attr, value.as_str()))?;
    } else if !rest.is_empty() {
        return Err("the edit is SET TAG NAME ATTR VALUE".into());
    }
    // The files' paths are relative to the model file's folder.
    let folder = Path::new(out_dir).join(Path::new(file).parent().unwrap_or(Path::new("")));
    let files = model.to_source_files()?;
    for f in &files {
        let rel = f.path.as_ref().ok_or("a file without a path")?;
        let path = folder.join(rel);
        std::fs::create_dir_all(path.parent().unwrap_or(Path::new(".")))?;
        std::fs::write(&path, &f.text)?;
    }
    let changed = files.iter().filter(|f| f.changed).count();
    println!("{} files written, {changed} changed", files.len());
    Ok(())
}
