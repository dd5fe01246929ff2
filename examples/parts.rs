//! A part of one model attached at a body of another, then a joint removed with what
//! drives it: MjSpec's `attach` of a body, without a site and without the rest of
//! the gripper's file.
//!
//! `cargo run --release --example parts -- ARM_XML ARM_BODY GRIPPER_XML GRIPPER_BODY REMOVE_JOINT OUT_DIR`
//!
//! Takes GRIPPER_BODY's subtree out of GRIPPER_XML (`Model::part`: its classes,
//! assets, actuators, sensors, tendons, equalities and contact rules, not the file's
//! floor, lights, skybox, keys or options), attaches it inside ARM_XML's body
//! ARM_BODY under the scope `gripper` (`Model::attach_in_as`), and writes the result
//! with its assets to OUT_DIR/attached/model.xml; then removes the arm's joint
//! REMOVE_JOINT with what drives it (`Referrers::Cascade`) and writes
//! OUT_DIR/removed/model.xml. Keys are written composed (`merge_keyframes`) and follow
//! the removal by name.

use std::path::PathBuf;

use mjcf::{Model, Namespace, Referrers, WriteOptions};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let [arm, arm_body, gripper, gripper_body, joint, out] = &args[..] else {
        return Err(
            "usage: parts ARM_XML ARM_BODY GRIPPER_XML GRIPPER_BODY REMOVE_JOINT OUT_DIR".into()
        );
    };
    let (arm, out) = (Model::from_path(arm)?, PathBuf::from(out));
    let part = Model::from_path(gripper)?.part(gripper_body)?;
    println!("left out of the part: {:?}", part.left_out);
    let at = arm.lookup(Namespace::Body, arm_body)?;
    let (attached, _) = arm.attach_in_as(&at, &part.model, "gripper")?;
    let options = WriteOptions { merge_keyframes: true, ..WriteOptions::default() };
    attached.export(out.join("attached"), "model.xml", &options)?;
    let removal =
        attached.remove_with(&attached.lookup(Namespace::Joint, joint)?, Referrers::Cascade)?;
    println!("removed with {joint}: {:?}", removal.removed);
    removal.model.export(out.join("removed"), "model.xml", &options)?;
    Ok(())
}
