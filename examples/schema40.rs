//! MJCF of MuJoCo 4.0 beyond dm_control's schema (`<frame>`, `<replicate>`, `<dcmotor>`,
//! `<pid>`, `<attach>` with an asset `<model>`, new attributes): outputs for
//! `tools/schema40_check.py`, which compiles them with MuJoCo.
//!
//! ```text
//! cargo run --release --example schema40 -- OUT
//! ```
//!
//! Writes:
//! - `OUT/roundtrip/original.xml`, `roundtrip.xml`: a scene, and what reading and
//!   writing it gives; MuJoCo must compile both to the same model;
//! - `OUT/edited/expected.xml`, `edited.xml`: the scene's text with edits made by hand,
//!   and the scene read, edited the same way through the API (a frame moved, a geom
//!   added in a frame, a replicate's count and a dcmotor's resistance changed) and
//!   written; the same model;
//! - `OUT/attach/arena.xml`, `robot.xml`, `hand.xml`: the parts, and `composed.xml`
//!   (with its files): the robot attached to the arena twice, at a site inside a frame
//!   and to the worldbody. MuJoCo's names in the composed model must be the arena's
//!   and the robot's with `robot/` and `robot_1/` before them (`robot/finger-0` for a
//!   replicated body, `robot/hand_palm` for a body an `<attach>` makes).
//!
//! What every output reads back as must write the same text again: the example fails
//! otherwise.

use std::path::Path;

use mjcf::{Model, Namespace, ReadOptions, WriteOptions, element};

/// A scene with frames (with a childclass, nested, in a body holding a joint),
/// replicates (one of unnamed geoms among many unnamed geoms: their automatic names
/// must stay distinct once MuJoCo numbers the copies), dcmotor and pid actuators, a
/// sensor of a replicated site, and new attributes (`speculative`, `castshadow`,
/// `springyield`).
const SCENE: &str = r#"<mujoco model="scene40">
  <option timestep="0.005">
    <flag speculative="enable"/>
  </option>
  <default>
    <default class="box">
      <geom type="box" size=".05 .05 .05" castshadow="false"/>
    </default>
  </default>
  <worldbody>
    <geom name="floor" type="plane" size="2 2 .1"/>
    <replicate count="9" offset="0 .05 0">
      <geom size=".01" pos="1 1 .01"/>
    </replicate>
    <frame name="shelf" pos="0 0 .5" euler="0 0 30" childclass="box">
      <geom name="plank" pos="0 0 -.1"/>
      <body name="arm" pos=".3 0 0">
        <joint name="hinge" axis="0 0 1" springyield=".5"/>
        <geom size=".02 .02 .1"/>
        <frame name="tip" pos="0 0 .1">
          <site name="tipsite"/>
        </frame>
      </body>
    </frame>
    <body name="stand" pos="-1 0 0">
      <frame euler="0 90 0">
        <joint name="tilt" type="hinge" axis="0 0 1"/>
        <geom type="capsule" size=".02 .2"/>
      </frame>
    </body>
    <replicate count="4" offset=".2 0 0" euler="0 0 10">
      <body name="cube" pos="0 1 .1">
        <freejoint/>
        <geom type="box" size=".03 .03 .03"/>
        <site name="cubesite"/>
      </body>
    </replicate>
    <body name="pile" pos="0 -1 0">
      <geom size=".01" pos="0 0 0"/>
      <geom size=".01" pos="0 0 .02"/>
      <geom size=".01" pos="0 0 .04"/>
      <geom size=".01" pos="0 0 .06"/>
      <geom size=".01" pos="0 0 .08"/>
      <geom size=".01" pos="0 0 .10"/>
      <geom size=".01" pos="0 0 .12"/>
      <geom size=".01" pos="0 0 .14"/>
      <geom size=".01" pos="0 0 .16"/>
      <geom size=".01" pos="0 0 .18"/>
      <geom size=".01" pos="0 0 .20"/>
      <geom size=".01" pos="0 0 .22"/>
      <geom size=".01" pos="0 0 .24"/>
      <geom size=".01" pos="0 0 .26"/>
      <geom size=".01" pos="0 0 .28"/>
      <geom size=".01" pos="0 0 .30"/>
      <geom size=".01" pos="0 0 .32"/>
      <geom size=".01" pos="0 0 .34"/>
      <geom size=".01" pos="0 0 .36"/>
      <geom size=".01" pos="0 0 .38"/>
    </body>
  </worldbody>
  <actuator>
    <dcmotor name="m1" joint="hinge" motorconst="0.05" resistance="2"/>
    <pid name="p1" joint="tilt" kp="10" kv="1"/>
  </actuator>
  <sensor>
    <framepos name="cubepos" objtype="site" objname="cubesite"/>
  </sensor>
</mujoco>
"#;

/// The model an asset `<model>` of the robot holds; the robot attaches its palm.
const HAND: &str = r#"<mujoco model="hand">
  <worldbody>
    <body name="palm">
      <joint name="palm_joint" axis="1 0 0"/>
      <geom name="palm_geom" size=".02"/>
    </body>
  </worldbody>
</mujoco>
"#;

/// A robot with frames (one with a childclass), a replicated finger that an actuator
/// and a sensor refer to, an `<attach>` of an asset model's body inside a frame, and
/// pid and dcmotor actuators.
const ROBOT: &str = r#"<mujoco model="robot">
  <default>
    <default class="link">
      <geom type="capsule" size=".02 .1" rgba=".8 .3 .3 1" castshadow="false"/>
    </default>
    <default class="servo">
      <pid kp="20" kv="1"/>
    </default>
  </default>
  <asset>
    <model name="hand" file="hand.xml"/>
  </asset>
  <worldbody>
    <frame name="mount" pos="0 0 .1" childclass="link">
      <body name="upper" pos="0 0 .1">
        <joint name="shoulder" axis="0 1 0" springyield=".2"/>
        <geom name="upper_geom"/>
        <frame name="wrist" pos="0 0 .2" euler="0 0 30">
          <site name="tool"/>
          <attach model="hand" body="palm" prefix="hand_"/>
        </frame>
      </body>
    </frame>
    <replicate count="3" offset=".1 0 0" sep="-">
      <body name="finger" pos="0 .2 .1">
        <joint name="knuckle" axis="0 1 0"/>
        <geom name="finger_geom" size=".01 .03" type="capsule"/>
        <site name="fingertip" pos="0 0 .03"/>
      </body>
    </replicate>
  </worldbody>
  <actuator>
    <pid name="shoulder_pid" class="servo" joint="shoulder"/>
    <dcmotor name="finger_motor" joint="knuckle" motorconst="0.05" resistance="2"/>
  </actuator>
  <sensor>
    <framepos name="tip_pos" objtype="site" objname="fingertip"/>
    <touch name="tool_touch" site="tool"/>
  </sensor>
</mujoco>
"#;

/// The arena: the robot is attached at `spawn`, a site inside the frame `table`.
const ARENA: &str = r#"<mujoco model="arena">
  <worldbody>
    <geom name="floor" type="plane" size="3 3 .1"/>
    <frame name="table" pos="1 0 0" euler="0 0 45">
      <site name="spawn" pos="0 0 .5"/>
    </frame>
  </worldbody>
</mujoco>
"#;

/// `text` with `from` (which must occur exactly once) replaced by `to`.
fn replace_once(text: &str, from: &str, to: &str) -> Result<String, String> {
    match text.matches(from).count() {
        1 => Ok(text.replacen(from, to, 1)),
        n => Err(format!("{from:?} occurs {n} times")),
    }
}

/// Writes `m` as `dir/name` with its files, after checking that what it reads back as
/// writes text that reads back as itself (a fixed point).
fn write(
    m: &Model,
    read: &ReadOptions,
    dir: &Path,
    name: &str,
) -> Result<(), Box<dyn std::error::Error>> {
    let opts = WriteOptions::default();
    let xml = m.to_xml_string_with(&opts)?;
    let mut read = read.clone();
    for (file, asset) in m.assets(&opts)? {
        read = read.asset(&file, asset.contents().to_vec());
    }
    let w2 = read.read_str(&xml)?.to_xml_string_with(&opts)?;
    let w3 = read.read_str(&w2)?.to_xml_string_with(&opts)?;
    if w2 != w3 {
        let line = w2.lines().zip(w3.lines()).position(|(a, b)| a != b).unwrap_or(0);
        let (a, b) = (w2.lines().nth(line), w3.lines().nth(line));
        return Err(format!(
            "{name}: read back is not a fixed point; line {}: {a:?} vs {b:?}",
            line + 1
        )
        .into());
    }
    m.export(dir, name, &opts)?;
    Ok(())
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out = std::path::PathBuf::from(std::env::args().nth(1).ok_or("usage: schema40 OUT")?);
    let plain = ReadOptions::new();

    // Round trip.
    let dir = out.join("roundtrip");
    std::fs::create_dir_all(&dir)?;
    std::fs::write(dir.join("original.xml"), SCENE)?;
    let scene = Model::from_xml_str(SCENE)?;
    write(&scene, &plain, &dir, "roundtrip.xml")?;

    // Edits through the API, and the same edits made to the text.
    let dir = out.join("edited");
    std::fs::create_dir_all(&dir)?;
    let mut m = scene.clone();
    let shelf = m.lookup(Namespace::Frame, "shelf")?;
    m.set_attr_mut(&shelf, "pos", [0.0, 0.0, 0.6])?;
    let tip = m.lookup(Namespace::Frame, "tip")?;
    m.add_mut(&tip, element!("geom", name = "tipgeom", size = [0.01, 0.01, 0.01]))?;
    let cube = m.lookup(Namespace::Body, "cube")?;
    let replicate = m.get(&cube)?.parent().ok_or("the cube has no parent")?.loc();
    assert_eq!(m.get(&replicate)?.tag(), "replicate");
    m.set_attr_mut(&replicate, "count", 3)?;
    let motor = m.lookup(Namespace::Actuator, "m1")?;
    m.set_attr_mut(&motor, "resistance", 3.0)?;
    write(&m, &plain, &dir, "edited.xml")?;
    let text = replace_once(SCENE, r#"name="shelf" pos="0 0 .5""#, r#"name="shelf" pos="0 0 .6""#)?;
    let text = replace_once(
        &text,
        r#"<site name="tipsite"/>"#,
        r#"<site name="tipsite"/><geom name="tipgeom" size=".01 .01 .01"/>"#,
    )?;
    let text = replace_once(&text, r#"count="4""#, r#"count="3""#)?;
    let text = replace_once(
        &text,
        r#"resistance="2"/>
    <pid"#,
        r#"resistance="3"/>
    <pid"#,
    )?;
    std::fs::write(dir.join("expected.xml"), text)?;

    // The robot attached twice: at a site inside a frame, and to the worldbody.
    let dir = out.join("attach");
    std::fs::create_dir_all(&dir)?;
    std::fs::write(dir.join("arena.xml"), ARENA)?;
    std::fs::write(dir.join("robot.xml"), ROBOT)?;
    std::fs::write(dir.join("hand.xml"), HAND)?;
    let with_hand = ReadOptions::new().asset("hand.xml", HAND.as_bytes().to_vec());
    let robot = with_hand.read_str(ROBOT)?;
    let mut arena = Model::from_xml_str(ARENA)?;
    let spawn = arena.lookup(Namespace::Site, "spawn")?;
    let a = arena.attach_mut(&spawn, &robot)?;
    let b = arena.attach_mut(&arena.worldbody(), &robot)?;
    assert_eq!((a.scope(), b.scope()), ("robot", "robot_1"));
    // The robot's frames and replicated bodies are found by their scoped names.
    assert!(arena.find(Namespace::Frame, "robot/wrist").is_some());
    assert!(arena.find(Namespace::Frame, "robot_1/mount").is_some());
    assert!(arena.find(Namespace::Body, "robot_1/finger").is_some());
    write(&arena, &with_hand, &dir, "composed.xml")?;
    println!("schema40: wrote {}", out.display());
    Ok(())
}
