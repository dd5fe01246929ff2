//! Editing a running simulation (issue 29's example, for checks outside the project):
//! four copies of a floating-base robot on a floor, simulated, then six edits, each
//! followed by `Physics::rebuild`, which keeps the state.
//!
//! ```sh
//! cargo run --release --example rebuild -- ROBOT_XML OUT_DIR
//! ```
//!
//! ROBOT_XML is a floating-base robot with a `home` key (examples/models/quadruped.xml
//! works). Four copies in scopes `r0` to `r3` at (0,0), (1,0), (0,1), (1,1); a floor
//! plane named `floor` (size 0 0 0.05); reset to the composed key `home`; robot k's
//! actuator j (document order within the robot) gets ctrl 0.1 + 0.01·k + 0.001·j; an
//! applied force (0, 0, 5, 0, 0, 0) on r0's base (the first body of ROBOT_XML's
//! worldbody) and 0.2 on r1's first hinge joint; 200 steps. Then the edits, each
//! followed by a rebuild and one step: 0 no edit; 1 numbers only (the floor's sliding
//! friction to 0.5, r1's base mass times 1.5: its inertial's mass, or an inertial
//! added with the compiled frame and inertia); 2 a static body `obstacle` with a box
//! geom at (3, 3, 0.1); 3 r2 detached; 4 undo of that detach; 5 r3's first hinge
//! joint renamed to its name plus `_renamed`.
//!
//! OUT_DIR/i/ holds `model.xml` (the text the rebuild compiled, or for an edit
//! written in place the edited model's text, with its files beside it), `before.json`,
//! `after.json` and `step1.json` (the state just before the rebuild, right after it,
//! and after one step), `report.json` (the rebuild's report), for edit 5
//! `renamed.json` (`{"old full name": "new full name"}`), and OUT_DIR/0/
//! `continued.json` (the old simulation stepped once without a rebuild). A state file
//! is `{"time": t, "joints": {name: {"qpos", "qvel", "qfrc_applied",
//! "qacc_warmstart"}}, "actuators": {name: {"ctrl": x, "act": [...]}}, "bodies":
//! {name: {"xfrc_applied", "mocap_pos", "mocap_quat"}}, "equalities": {name:
//! {"active": 0 or 1}}}` with MuJoCo's names and every number as Rust's `{:?}` of an
//! f64 (it reads back exactly). tools/rebuild_check.py judges the files with MuJoCo.
use std::error::Error;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use mjcf::{History, Loc, Model, WriteOptions, element};
use mjcf_mujoco::{MuJoCo, ObjKind, Physics, RebuildReport};

type Result<T> = std::result::Result<T, Box<dyn Error>>;

fn main() -> Result<()> {
    let mut args = std::env::args().skip(1);
    let (Some(robot_xml), Some(out)) = (args.next(), args.next()) else {
        return Err("usage: rebuild ROBOT_XML OUT_DIR".into());
    };
    let out = PathBuf::from(out);
    let mujoco = MuJoCo::load()?;
    let robot = Model::from_path(&robot_xml)?;
    let base = robot.get(&robot.worldbody())?.children().find(|c| c.tag() == "body");
    let base = base.ok_or("the robot has no body")?.loc();
    let actuators: Vec<Loc> = robot.get(&robot.actuator())?.children().map(|c| c.loc()).collect();
    let hinge = first_hinge(&mujoco, &robot)?;

    let mut arena = Model::new("arena");
    let w = arena.worldbody();
    arena.add_mut(&w, element!("geom", name = "floor", type = "plane", size = [0, 0, 0.05]))?;
    for (k, (x, y)) in [(0.0, 0.0), (1.0, 0.0), (0.0, 1.0), (1.0, 1.0)].into_iter().enumerate() {
        let site =
            arena.add_mut(&w, element!("site", name = format!("spawn_{k}"), pos = [x, y, 0.0]))?;
        arena.attach_as_mut(&site, &robot, &format!("r{k}"))?;
    }
    let options = WriteOptions { merge_keyframes: true, ..WriteOptions::default() };
    let mut history = History::new(arena);
    let mut physics = Physics::new(&mujoco.compile_with(history.current(), &options)?)?;
    physics.reset_to_key("home")?;
    for k in 0..4 {
        for (j, a) in actuators.iter().enumerate() {
            let b = physics.bind(history.current().locate_in(format!("r{k}").as_str(), a)?)?;
            physics.get_mut(&b, "ctrl")?.fill(0.1 + 0.01 * k as f64 + 0.001 * j as f64);
        }
    }
    let b = physics.bind(history.current().locate_in("r0", &base)?)?;
    physics.get_mut(&b, "xfrc_applied")?.copy_from_slice(&[0.0, 0.0, 5.0, 0.0, 0.0, 0.0]);
    let b = physics.bind(history.current().locate_in("r1", &hinge)?)?;
    physics.get_mut(&b, "qfrc_applied")?[0] = 0.2;
    warn(physics.step(200)?);

    for i in 0..6 {
        let dir = out.join(i.to_string());
        std::fs::create_dir_all(&dir)?;
        std::fs::write(dir.join("before.json"), state_json(&physics)?)?;
        if i == 0 {
            let mut continued = Physics::new(physics.model())?;
            copy_state(&physics, &mut continued)?;
            warn(continued.step(1)?);
            std::fs::write(dir.join("continued.json"), state_json(&continued)?)?;
        }
        let renamed = edit(i, &mut history, &physics, &base, &hinge)?;
        let report = physics.rebuild(history.current())?;
        std::fs::write(dir.join("after.json"), state_json(&physics)?)?;
        std::fs::write(dir.join("report.json"), report_json(&report))?;
        write_model(&physics, history.current(), &options, &dir)?;
        if let Some((old, new)) = renamed {
            std::fs::write(
                dir.join("renamed.json"),
                format!("{{{}: {}}}\n", quote(&old), quote(&new)),
            )?;
        }
        warn(physics.step(1)?);
        std::fs::write(dir.join("step1.json"), state_json(&physics)?)?;
        println!("edit {i}: {} in {:.6} s", report.mode.name(), report.seconds);
    }
    Ok(())
}

fn warn(warnings: mjcf_mujoco::Warnings) {
    for w in &warnings {
        eprintln!("warning: {w}");
    }
}

/// The robot's first hinge joint in document order (as MuJoCo compiles it).
fn first_hinge(mujoco: &MuJoCo, robot: &Model) -> Result<Loc> {
    let compiled = mujoco.compile(robot)?;
    for event in robot.walk() {
        let mjcf::Event::Enter(e) = event else { continue };
        if e.tag() != "joint" || e.parent().is_none_or(|p| p.tag() != "body") {
            continue;
        }
        let b = compiled.bind(e.loc())?;
        if compiled.get_ints(&b, "type")? == [3] {
            return Ok(e.loc());
        }
    }
    Err("the robot has no hinge joint".into())
}

/// Applies edit `i` to `history`; for the rename, the old and new full names.
fn edit(
    i: usize,
    history: &mut History,
    physics: &Physics,
    base: &Loc,
    hinge: &Loc,
) -> Result<Option<(String, String)>> {
    let m = history.current().clone();
    match i {
        1 => {
            let floor = m.find(mjcf::Namespace::Geom, "floor").ok_or("no floor")?;
            let mut edited = m.set_attr(&floor, "friction", [0.5])?;
            let at = m.locate_in("r1", base)?;
            let inertial = m.get(&at)?.children().find(|c| c.tag() == "inertial").map(|c| c.loc());
            match inertial {
                Some(inertial) => {
                    let mass = m.float(&inertial, "mass")?;
                    edited.set_attr_mut(&inertial, "mass", 1.5 * mass)?;
                }
                None => {
                    let b = physics.bind(&at)?;
                    let inertial = element!(
                        "inertial",
                        pos = physics.get(&b, "ipos")?,
                        quat = physics.get(&b, "iquat")?,
                        mass = 1.5 * physics.get(&b, "mass")?[0],
                        diaginertia = physics.get(&b, "inertia")?
                    );
                    edited.add_mut(&at, inertial)?;
                }
            }
            history.push("numbers only", edited);
        }
        2 => {
            let mut edited = m.clone();
            let w = edited.worldbody();
            let body =
                edited.add_mut(&w, element!("body", name = "obstacle", pos = [3.0, 3.0, 0.1]))?;
            edited.add_mut(&body, element!("geom", type = "box", size = [0.1, 0.1, 0.1]))?;
            history.push("obstacle", edited);
        }
        3 => history.push("detach r2", m.detach("r2")?),
        4 => {
            history.undo();
        }
        5 => {
            let at = m.locate_in("r3", hinge)?;
            let joint = m.get(&at)?;
            let old = joint.full_name().ok_or("the hinge has no name")?;
            let name = format!("{}_renamed", joint.identifier().unwrap_or("hinge"));
            let edited = m.set_attr(&at, "name", name.as_str())?;
            let new = edited.get(&at)?.full_name().ok_or("the hinge has no name")?;
            history.push("rename", edited);
            return Ok(Some((old, new)));
        }
        _ => {}
    }
    Ok(None)
}

/// Gives `to` (a simulation of the same compiled model) the state of `from`.
fn copy_state(from: &Physics, to: &mut Physics) -> Result<()> {
    to.set_time(from.time());
    for f in [
        "qpos",
        "qvel",
        "act",
        "history",
        "qacc_warmstart",
        "ctrl",
        "qfrc_applied",
        "xfrc_applied",
        "mocap_pos",
        "mocap_quat",
        "userdata",
        "plugin_state",
        "plastic",
    ] {
        to.data_mut(f)?.copy_from_slice(from.data(f)?);
    }
    for e in 0..from.model().count(ObjKind::Equality) {
        let b = from.bind((ObjKind::Equality, e))?;
        to.flags_mut(&b, "active")?.copy_from_slice(from.flags(&b, "active")?);
    }
    Ok(())
}

/// The text the rebuild compiled (or the edited model's, written in place) and its
/// files beside it.
fn write_model(physics: &Physics, model: &Model, options: &WriteOptions, dir: &Path) -> Result<()> {
    let written = physics.model().written().ok_or("no written model")?;
    std::fs::write(dir.join("model.xml"), written.xml())?;
    for (name, asset) in model.assets(options)? {
        let file = dir.join(name);
        if let Some(parent) = file.parent() {
            std::fs::create_dir_all(parent)?;
        }
        std::fs::write(file, asset.contents())?;
    }
    Ok(())
}

fn quote(s: &str) -> String {
    let mut out = String::from("\"");
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

fn numbers(v: &[f64]) -> String {
    let items: Vec<String> = v.iter().map(|x| format!("{x:?}")).collect();
    format!("[{}]", items.join(", "))
}

/// `{name: {field: value}}` of every named element of `kind`.
fn section(
    p: &Physics,
    kind: ObjKind,
    fields: impl Fn(&mjcf_mujoco::Bound) -> Result<Vec<(&'static str, String)>>,
) -> Result<String> {
    let mut entries = Vec::new();
    for id in 0..p.model().count(kind) {
        let Some(name) = p.model().name(kind, id).filter(|n| !n.is_empty()) else { continue };
        let b = p.bind((kind, id))?;
        let fields: Vec<String> =
            fields(&b)?.into_iter().map(|(f, v)| format!("{}: {v}", quote(f))).collect();
        entries.push(format!("    {}: {{{}}}", quote(name), fields.join(", ")));
    }
    Ok(format!("{{\n{}\n  }}", entries.join(",\n")))
}

/// The state file of `p` (see the module's docs).
fn state_json(p: &Physics) -> Result<String> {
    let joints = section(p, ObjKind::Joint, |b| {
        ["qpos", "qvel", "qfrc_applied", "qacc_warmstart"]
            .into_iter()
            .map(|f| Ok((f, numbers(p.get(b, f)?))))
            .collect::<Result<_>>()
    })?;
    let actuators = section(p, ObjKind::Actuator, |b| {
        let ctrl = p.get(b, "ctrl")?;
        let ctrl = if ctrl.len() == 1 { format!("{:?}", ctrl[0]) } else { numbers(ctrl) };
        Ok(vec![("ctrl", ctrl), ("act", numbers(p.get(b, "act")?))])
    })?;
    let mocap = p.model().ints("body_mocapid")?;
    let bodies = section(p, ObjKind::Body, |b| {
        let mut out = vec![("xfrc_applied", numbers(p.get(b, "xfrc_applied")?))];
        if mocap[b.id()] >= 0 {
            out.push(("mocap_pos", numbers(p.get(b, "mocap_pos")?)));
            out.push(("mocap_quat", numbers(p.get(b, "mocap_quat")?)));
        }
        Ok(out)
    })?;
    let equalities = section(p, ObjKind::Equality, |b| {
        Ok(vec![("active", p.flags(b, "active")?[0].to_string())])
    })?;
    Ok(format!(
        "{{\n  \"time\": {:?},\n  \"joints\": {joints},\n  \"actuators\": {actuators},\n  \"bodies\": {bodies},\n  \"equalities\": {equalities}\n}}\n",
        p.time()
    ))
}

/// The rebuild's report as JSON.
fn report_json(r: &RebuildReport) -> String {
    let list = |items: Vec<String>| format!("[{}]", items.join(", "));
    let carried = r
        .carried
        .iter()
        .map(|c| {
            format!(
                "{{\"kind\": {}, \"name\": {}, \"old_name\": {}}}",
                quote(c.kind.name()),
                quote(&c.name),
                quote(&c.old_name)
            )
        })
        .collect();
    let defaulted = r
        .defaulted
        .iter()
        .map(|d| {
            format!(
                "{{\"kind\": {}, \"name\": {}, \"why\": {}}}",
                quote(d.kind.name()),
                quote(&d.name),
                quote(&format!("{:?}", d.why))
            )
        })
        .collect();
    let dropped = r
        .dropped
        .iter()
        .map(|d| format!("{{\"kind\": {}, \"name\": {}}}", quote(d.kind.name()), quote(&d.name)))
        .collect();
    let notes = r.notes.iter().map(|n| quote(n)).collect();
    format!(
        "{{\n  \"mode\": {},\n  \"carried\": {},\n  \"defaulted\": {},\n  \"dropped\": {},\n  \"notes\": {},\n  \"seconds\": {:?}\n}}\n",
        quote(r.mode.name()),
        list(carried),
        list(defaulted),
        list(dropped),
        list(notes),
        r.seconds
    )
}
