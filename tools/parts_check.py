"""Checks examples/parts.rs's output with MuJoCo (run by .ci/run).

Usage: python tools/parts_check.py OUT_DIR ARM_XML GRIPPER_XML GRIPPER_BODY REMOVE_JOINT

OUT_DIR/attached/model.xml must hold exactly the arm's elements plus the gripper
part's (no lights, textures or keys of the gripper's file), every part body named
gripper/<name> and compiled as in its own file (mass, inertia, joint range, damping,
actuator gains), the part's root at its own local pose in the attachment frame; and
OUT_DIR/removed/model.xml lacks REMOVE_JOINT and the actuators that drive it, while
every key keeps each remaining joint's qpos and actuator's ctrl by name.
"""
import os
import sys

import mujoco
import numpy as np

out, arm_xml, gripper_xml, gripper_body, removed_joint = sys.argv[1:6]
attached = mujoco.MjModel.from_xml_path(os.path.join(out, "attached", "model.xml"))
removed = mujoco.MjModel.from_xml_path(os.path.join(out, "removed", "model.xml"))
arm = mujoco.MjModel.from_xml_path(arm_xml)
gripper = mujoco.MjModel.from_xml_path(gripper_xml)
O = mujoco.mjtObj
failures = []


def names(m, obj, count):
    return {mujoco.mj_id2name(m, obj, i) for i in range(count)}


def subtree(m, root):
    rid = mujoco.mj_name2id(m, O.mjOBJ_BODY, root)
    out = [rid]
    for b in range(m.nbody):
        p = b
        while p != 0 and p != rid:
            p = m.body_parentid[p]
        if p == rid and b != rid:
            out.append(b)
    return out


part_bodies = [mujoco.mj_id2name(gripper, O.mjOBJ_BODY, b) for b in subtree(gripper, gripper_body)]
for b in part_bodies:
    i, j = mujoco.mj_name2id(gripper, O.mjOBJ_BODY, b), mujoco.mj_name2id(attached, O.mjOBJ_BODY, "gripper/" + b)
    if j < 0:
        failures.append(f"no body gripper/{b}")
        continue
    for field in ["body_mass", "body_inertia", "body_ipos"]:
        if not np.array_equal(getattr(gripper, field)[i], getattr(attached, field)[j]):
            failures.append(f"gripper/{b}: {field} differs")
root_i = mujoco.mj_name2id(gripper, O.mjOBJ_BODY, gripper_body)
root_j = mujoco.mj_name2id(attached, O.mjOBJ_BODY, "gripper/" + gripper_body)
for field in ["body_pos", "body_quat"]:
    if not np.allclose(getattr(gripper, field)[root_i], getattr(attached, field)[root_j], atol=1e-12):
        failures.append(f"the part's root: {field} is not its own local pose")
expected = {
    "nbody": arm.nbody + 1 + len(part_bodies),  # the attachment frame is a body
    "nlight": arm.nlight,
    "ntex": arm.ntex,
    "nkey": arm.nkey,
}
for k, v in expected.items():
    if getattr(attached, k) != v:
        failures.append(f"attached: {k} = {getattr(attached, k)}, expected {v}")
for j in range(gripper.njnt):
    name = mujoco.mj_id2name(gripper, O.mjOBJ_JOINT, j)
    if gripper.jnt_bodyid[j] not in subtree(gripper, gripper_body):
        continue
    k = mujoco.mj_name2id(attached, O.mjOBJ_JOINT, "gripper/" + name)
    if k < 0:
        failures.append(f"no joint gripper/{name}")
        continue
    if not np.array_equal(gripper.jnt_range[j], attached.jnt_range[k]):
        failures.append(f"gripper/{name}: range differs")
    if gripper.dof_damping[gripper.jnt_dofadr[j]] != attached.dof_damping[attached.jnt_dofadr[k]]:
        failures.append(f"gripper/{name}: damping differs")
for a in range(gripper.nu):
    name = mujoco.mj_id2name(gripper, O.mjOBJ_ACTUATOR, a)
    k = mujoco.mj_name2id(attached, O.mjOBJ_ACTUATOR, "gripper/" + name)
    if k >= 0 and not np.array_equal(gripper.actuator_gainprm[a], attached.actuator_gainprm[k]):
        failures.append(f"gripper/{name}: gains differ")
# The removal.
if mujoco.mj_name2id(removed, O.mjOBJ_JOINT, removed_joint) >= 0:
    failures.append(f"removed: {removed_joint} is still there")
jid = mujoco.mj_name2id(attached, O.mjOBJ_JOINT, removed_joint)
for a in range(attached.nu):
    if attached.actuator_trntype[a] == mujoco.mjtTrn.mjTRN_JOINT and attached.actuator_trnid[a, 0] == jid:
        name = mujoco.mj_id2name(attached, O.mjOBJ_ACTUATOR, a)
        if mujoco.mj_name2id(removed, O.mjOBJ_ACTUATOR, name) >= 0:
            failures.append(f"removed: actuator {name} drives the removed joint")
for key in range(attached.nkey):
    for j in range(removed.njnt):
        name = mujoco.mj_id2name(removed, O.mjOBJ_JOINT, j)
        i = mujoco.mj_name2id(attached, O.mjOBJ_JOINT, name)
        width = {0: 7, 1: 4}.get(int(removed.jnt_type[j]), 1)
        a = attached.key_qpos[key][attached.jnt_qposadr[i]:attached.jnt_qposadr[i] + width]
        b = removed.key_qpos[key][removed.jnt_qposadr[j]:removed.jnt_qposadr[j] + width]
        if not np.array_equal(a, b):
            failures.append(f"key {key}: {name}'s qpos {a} became {b}")
    for u in range(removed.nu):
        name = mujoco.mj_id2name(removed, O.mjOBJ_ACTUATOR, u)
        i = mujoco.mj_name2id(attached, O.mjOBJ_ACTUATOR, name)
        if attached.key_ctrl[key][i] != removed.key_ctrl[key][u]:
            failures.append(f"key {key}: {name}'s ctrl changed")
print(f"parts: attached {attached.nbody} bodies, {attached.njnt} joints, {attached.nu} actuators; "
      f"removed {removed.njnt} joints, {removed.nu} actuators; {len(failures)} failures")
for f in failures:
    print("FAIL", f)
sys.exit(1 if failures else 0)
