"""Checks examples/rebuild.rs's output with MuJoCo (run by .ci/run).

Usage: python tools/rebuild_check.py OUT_DIR ROBOT_XML

For edits 0 to 5 (OUT_DIR/i/): edit 0's before.json is the setup run here on its
model.xml (home key, the controls, the applied forces, 200 steps), bit for bit; each
before.json is the previous edit's step1.json; after.json carries before.json's state
exactly for every element the report does not default (under its new name for edit
5's renamed.json), and the defaulted and new ones are at qpos0 and at rest; each edit
is in its model.xml; edit 0 is "none", edit 1 "in_place", edits 2 to 5 "compiled";
one step from after.json in a fresh compile of model.xml is step1.json (bit for bit,
within 1e-12 relative for edit 1, whose numbers were written in place); edit 0's
step1.json is continued.json, bit for bit.
"""
import json
import os
import sys

import mujoco
import numpy as np

out, robot_xml = sys.argv[1:3]
O = mujoco.mjtObj
failures = []


def fail(what):
    failures.append(what)
    print("FAIL", what)


def path(i, name):
    return os.path.join(out, str(i), name)


def load(i, name):
    with open(path(i, name)) as f:
        return json.load(f)


def compiled(i):
    return mujoco.MjModel.from_xml_path(path(i, "model.xml"))


def names(m, obj, count):
    return [mujoco.mj_id2name(m, obj, i) for i in range(count)]


def widths(m, j):
    t = m.jnt_type[j]
    return {0: (7, 6), 1: (4, 3)}.get(int(t), (1, 1))


def state(m, d):
    """The example's state file of (m, d), as Python values."""
    s = {"time": d.time, "joints": {}, "actuators": {}, "bodies": {}, "equalities": {}}
    for j, name in enumerate(names(m, O.mjOBJ_JOINT, m.njnt)):
        if not name:
            continue
        nq, nv = widths(m, j)
        qa, da = m.jnt_qposadr[j], m.jnt_dofadr[j]
        s["joints"][name] = {
            "qpos": list(d.qpos[qa:qa + nq]),
            "qvel": list(d.qvel[da:da + nv]),
            "qfrc_applied": list(d.qfrc_applied[da:da + nv]),
            "qacc_warmstart": list(d.qacc_warmstart[da:da + nv]),
        }
    for a, name in enumerate(names(m, O.mjOBJ_ACTUATOR, m.nu)):
        if not name:
            continue
        n, adr = m.actuator_actnum[a], m.actuator_actadr[a]
        s["actuators"][name] = {"ctrl": d.ctrl[a], "act": list(d.act[adr:adr + n]) if n else []}
    for b, name in enumerate(names(m, O.mjOBJ_BODY, m.nbody)):
        if not name:
            continue
        e = {"xfrc_applied": list(d.xfrc_applied[b])}
        k = m.body_mocapid[b]
        if k >= 0:
            e["mocap_pos"] = list(d.mocap_pos[k])
            e["mocap_quat"] = list(d.mocap_quat[k])
        s["bodies"][name] = e
    for e, name in enumerate(names(m, O.mjOBJ_EQUALITY, m.neq)):
        if name:
            s["equalities"][name] = {"active": int(d.eq_active[e])}
    return s


def set_state(m, d, s):
    d.time = s["time"]
    for name, v in s["joints"].items():
        j = mujoco.mj_name2id(m, O.mjOBJ_JOINT, name)
        nq, nv = widths(m, j)
        qa, da = m.jnt_qposadr[j], m.jnt_dofadr[j]
        d.qpos[qa:qa + nq] = v["qpos"]
        d.qvel[da:da + nv] = v["qvel"]
        d.qfrc_applied[da:da + nv] = v["qfrc_applied"]
        d.qacc_warmstart[da:da + nv] = v["qacc_warmstart"]
    for name, v in s["actuators"].items():
        a = mujoco.mj_name2id(m, O.mjOBJ_ACTUATOR, name)
        d.ctrl[a] = v["ctrl"]
        n, adr = m.actuator_actnum[a], m.actuator_actadr[a]
        if n:
            d.act[adr:adr + n] = v["act"]
    for name, v in s["bodies"].items():
        b = mujoco.mj_name2id(m, O.mjOBJ_BODY, name)
        d.xfrc_applied[b] = v["xfrc_applied"]
        k = m.body_mocapid[b]
        if k >= 0:
            d.mocap_pos[k] = v["mocap_pos"]
            d.mocap_quat[k] = v["mocap_quat"]
    for name, v in s["equalities"].items():
        d.eq_active[mujoco.mj_name2id(m, O.mjOBJ_EQUALITY, name)] = v["active"]


def differ(a, b, rel=0.0, where=""):
    """Where a and b differ (numbers: in any bit, or by more than rel relative)."""
    if isinstance(a, dict):
        if not isinstance(b, dict) or set(a) != set(b):
            return f"{where}: keys {sorted(set(a) ^ set(b))[:5]}"
        for k in a:
            d = differ(a[k], b[k], rel, f"{where}/{k}")
            if d:
                return d
        return None
    if isinstance(a, list):
        if not isinstance(b, list) or len(a) != len(b):
            return f"{where}: lengths"
        for k, (x, y) in enumerate(zip(a, b)):
            d = differ(x, y, rel, f"{where}[{k}]")
            if d:
                return d
        return None
    x, y = float(a), float(b)
    if x == y and np.signbit(x) == np.signbit(y):
        return None
    if rel > 0 and abs(x - y) <= rel * max(abs(x), abs(y)):
        return None
    return f"{where}: {x!r} != {y!r}"


robot = mujoco.MjModel.from_xml_path(robot_xml)
hinge = next(j for j in range(robot.njnt) if robot.jnt_type[j] == mujoco.mjtJoint.mjJNT_HINGE)


def scoped(m, obj, count, k):
    return [i for i, n in enumerate(names(m, obj, count)) if n and n.startswith(f"r{k}/")]


# Edit 0's setup, run here on its model.xml.
m0 = compiled(0)
d0 = mujoco.MjData(m0)
mujoco.mj_resetDataKeyframe(m0, d0, mujoco.mj_name2id(m0, O.mjOBJ_KEY, "home"))
for k in range(4):
    for j, a in enumerate(scoped(m0, O.mjOBJ_ACTUATOR, m0.nu, k)):
        d0.ctrl[a] = 0.1 + 0.01 * k + 0.001 * j
d0.xfrc_applied[scoped(m0, O.mjOBJ_BODY, m0.nbody, 0)[0]] = [0, 0, 5, 0, 0, 0]
d0.qfrc_applied[m0.jnt_dofadr[scoped(m0, O.mjOBJ_JOINT, m0.njnt, 1)[hinge]]] = 0.2
for _ in range(200):
    mujoco.mj_step(m0, d0)
d = differ(state(m0, d0), load(0, "before.json"))
if d:
    fail(f"edit 0: before.json is not the setup run on its model.xml: {d}")

modes = ["none", "in_place", "compiled", "compiled", "compiled", "compiled"]
for i in range(6):
    before, after, step1 = load(i, "before.json"), load(i, "after.json"), load(i, "step1.json")
    report = load(i, "report.json")
    m = compiled(i)
    if report["mode"] != modes[i]:
        fail(f"edit {i}: mode {report['mode']}, expected {modes[i]}")
    if i > 0 and differ(load(i - 1, "step1.json"), before):
        fail(f"edit {i}: before.json is not edit {i - 1}'s step1.json")
    renamed = load(i, "renamed.json") if i == 5 else {}
    old_of = {new: old for old, new in renamed.items()}
    defaulted = {(e["kind"], e["name"]) for e in report["defaulted"]}
    kinds = {"joints": "joint", "actuators": "actuator", "bodies": "body", "equalities": "equality"}
    if after["time"] != before["time"]:
        fail(f"edit {i}: time not carried")
    # Defaults: a fresh data of the model (qpos0, at rest).
    fresh = state(m, mujoco.MjData(m))
    for section, kind in kinds.items():
        for name, value in after[section].items():
            old = old_of.get(name, name)
            if (kind, name) in defaulted or old not in before[section]:
                if (kind, name) not in defaulted:
                    fail(f"edit {i}: {kind} {name} is new and not reported defaulted")
                d = differ(fresh[section][name], value, 0.0, f"{kind} {name}")
                if d:
                    fail(f"edit {i}: new {d} (not at its default)")
            else:
                d = differ(before[section][old], value, 0.0, f"{kind} {name}")
                if d:
                    fail(f"edit {i}: not carried exactly: {d}")
    # One step from after.json in a fresh compile.
    data = mujoco.MjData(m)
    set_state(m, data, after)
    mujoco.mj_step(m, data)
    d = differ(state(m, data), step1, 1e-12 if i == 1 else 0.0)
    if d:
        fail(f"edit {i}: one step from after.json in a fresh compile is not step1.json: {d}")

# Each edit is in its model.xml.
models = [compiled(i) for i in range(6)]


def body(m, name):
    return mujoco.mj_name2id(m, O.mjOBJ_BODY, name)


floor = [mujoco.mj_name2id(m, O.mjOBJ_GEOM, "floor") for m in models]
if models[1].geom_friction[floor[1]][0] != 0.5 or models[0].geom_friction[floor[0]][0] == 0.5:
    fail("edit 1: the floor's sliding friction is not 0.5 in its model.xml")
b0 = scoped(models[0], O.mjOBJ_BODY, models[0].nbody, 1)[0]
b1 = scoped(models[1], O.mjOBJ_BODY, models[1].nbody, 1)[0]
if models[1].body_mass[b1] != 1.5 * models[0].body_mass[b0]:
    fail(f"edit 1: r1's base mass {models[1].body_mass[b1]} is not 1.5 x {models[0].body_mass[b0]}")
ob = body(models[2], "obstacle")
if ob < 0 or list(models[2].body_pos[ob]) != [3.0, 3.0, 0.1] or models[2].body_geomnum[ob] != 1 \
        or models[2].geom_type[models[2].body_geomadr[ob]] != mujoco.mjtGeom.mjGEOM_BOX:
    fail("edit 2: no static body obstacle with a box geom at (3, 3, 0.1)")
if scoped(models[3], O.mjOBJ_BODY, models[3].nbody, 2) or not scoped(models[2], O.mjOBJ_BODY, models[2].nbody, 2):
    fail("edit 3: r2 is not detached")
if names(models[4], O.mjOBJ_JOINT, models[4].njnt) != names(models[2], O.mjOBJ_JOINT, models[2].njnt):
    fail("edit 4: the undo does not bring back edit 2's joints")
for old, new in load(5, "renamed.json").items():
    j5 = names(models[5], O.mjOBJ_JOINT, models[5].njnt)
    if old in j5 or new not in j5 or not new.startswith("r3/") or new != old + "_renamed":
        fail(f"edit 5: {old} is not renamed {new}")
d = differ(load(0, "step1.json"), load(0, "continued.json"))
if d:
    fail(f"edit 0: step1.json is not continued.json: {d}")

print(f"rebuild: {len(failures)} failures; modes", [load(i, "report.json")["mode"] for i in range(6)])
sys.exit(1 if failures else 0)
