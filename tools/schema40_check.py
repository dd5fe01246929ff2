#!/usr/bin/env python3
"""Compiles the outputs of `examples/schema40.rs` with MuJoCo and checks them.

Usage: tools/schema40_check.py OUT

- OUT/roundtrip: original.xml (MJCF with <frame>, <replicate>, <dcmotor>, <pid> and
  MuJoCo 4.0's newer attributes) and roundtrip.xml (what this crate reads and writes
  back) compile to the same model;
- OUT/edited: expected.xml (the text edited by hand) and edited.xml (the model edited
  through the API) compile to the same model;
- OUT/attach: composed.xml (robot.xml attached to arena.xml twice) compiles, and its
  names of every kind are arena.xml's and robot.xml's with `robot/` and `robot_1/`
  before them (plus the attachment frames' bodies `robot/` and `robot_1/`): names
  MuJoCo makes for replicated copies (`robot/finger-0`) and for what an <attach> of an
  asset model makes (`robot/hand_palm`) included. Every <frame> of composed.xml is named
  inside its scope, and its counts (nq, nv, nu, nsensor) are the arena's plus twice
  the robot's.

"The same model": the same counts, the same names of every kind of object (in order;
an automatic name `//unnamed_...` counts as no name) and the same compiled numbers
(positions, orientations, masses, sizes, joint and actuator parameters, default pose).
Prints one line per check and exits 1 if any fails. Run it with the MuJoCo venv's
python (see tools/mujoco_check.py).
"""

import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import mujoco
import numpy as np

KINDS = {
    'body': 'nbody', 'joint': 'njnt', 'geom': 'ngeom', 'site': 'nsite', 'camera': 'ncam',
    'light': 'nlight', 'tendon': 'ntendon', 'actuator': 'nu', 'sensor': 'nsensor',
    'equality': 'neq', 'mesh': 'nmesh', 'material': 'nmat', 'key': 'nkey',
}
COUNTS = ('nq', 'nv', 'nu', 'na', 'nkey', 'nbody', 'njnt', 'ngeom', 'nsite', 'nsensor',
          'ntendon', 'neq', 'nplastic')
ARRAYS = ('body_parentid', 'body_pos', 'body_quat', 'body_ipos', 'body_iquat', 'body_mass',
          'body_inertia', 'jnt_type', 'jnt_pos', 'jnt_axis', 'jnt_range', 'jnt_stiffness',
          'geom_type', 'geom_size', 'geom_pos', 'geom_quat', 'geom_rgba', 'geom_friction',
          'site_pos', 'site_quat', 'site_size', 'actuator_trntype', 'actuator_trnid',
          'actuator_dyntype', 'actuator_gaintype', 'actuator_biastype', 'actuator_gear',
          'actuator_dynprm', 'actuator_gainprm', 'actuator_biasprm', 'actuator_ctrlrange',
          'sensor_type', 'sensor_objid', 'qpos0', 'opt.timestep')


def names(m, kind):
    obj = getattr(mujoco.mjtObj, 'mjOBJ_' + kind.upper())
    out = []
    for i in range(getattr(m, KINDS[kind])):
        n = mujoco.mj_id2name(m, obj, i) or ''
        out.append('' if '//unnamed_' in n else n)
    return out


def array(m, field):
    obj = m
    for part in field.split('.'):
        obj = getattr(obj, part, None)
        if obj is None:
            return None
    return np.asarray(obj)


def same_model(a, b):
    """None if a and b are the same model, else what differs."""
    for c in COUNTS:
        if getattr(a, c, None) != getattr(b, c, None):
            return f'{c}: {getattr(a, c, None)} vs {getattr(b, c, None)}'
    for kind in KINDS:
        if names(a, kind) != names(b, kind):
            return f'{kind} names: {names(a, kind)} vs {names(b, kind)}'
    for field in ARRAYS:
        x, y = array(a, field), array(b, field)
        if x is None and y is None:
            continue
        if x is None or y is None or x.shape != y.shape or not np.allclose(x, y, rtol=1e-12, atol=1e-12, equal_nan=True):
            return f'{field} differs'
    return None


def compile_path(path):
    return mujoco.MjModel.from_xml_path(str(path))


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = Path(sys.argv[1])
    failures = []

    def check(label, why):
        print(f'{"FAIL" if why else "ok  "} {label}{": " + why if why else ""}')
        if why:
            failures.append(label)

    for folder, want, got in (('roundtrip', 'original.xml', 'roundtrip.xml'),
                              ('edited', 'expected.xml', 'edited.xml')):
        try:
            a, b = compile_path(out / folder / want), compile_path(out / folder / got)
            why = same_model(a, b)
        except Exception as e:  # noqa: BLE001 -- a compile error is the finding
            why = 'does not compile: ' + str(e).splitlines()[0]
        check(f'{folder}: {got} compiles to the same model as {want}', why)
        if folder == 'roundtrip' and not why:
            print(f'     {b.nbody} bodies, {b.ngeom} geoms, {b.nu} actuators '
                  f'(types {sorted(set(b.actuator_dyntype.tolist()))}), {b.nsensor} sensors')

    att = out / 'attach'
    try:
        arena, robot = compile_path(att / 'arena.xml'), compile_path(att / 'robot.xml')
        comp = compile_path(att / 'composed.xml')
    except Exception as e:  # noqa: BLE001
        check('attach: composed.xml compiles', 'does not compile: ' + str(e).splitlines()[0])
        sys.exit(1)
    scopes = ('robot/', 'robot_1/')
    for kind in KINDS:
        own = [n for n in names(robot, kind) if not (kind == 'body' and n == 'world')]
        want = names(arena, kind) + [s + n if n else '' for s in scopes for n in own]
        if kind == 'body':
            want += list(scopes)
        got = names(comp, kind)
        why = None if sorted(got) == sorted(want) else f'got {sorted(got)}, want {sorted(want)}'
        check(f'attach: {kind} names are the arena\'s and the robot\'s prefixed ({len(got)})', why)
    for c in ('nq', 'nv', 'nu', 'nsensor', 'ntendon'):
        g, w = getattr(comp, c), getattr(arena, c) + 2 * getattr(robot, c)
        check(f'attach: {c} = {g}', None if g == w else f'want {w}')
    frames = [f.get('name') for f in ET.parse(att / 'composed.xml').iter('frame')]
    own = [f.get('name') for f in ET.parse(att / 'robot.xml').iter('frame')]
    arena_frames = [f.get('name') for f in ET.parse(att / 'arena.xml').iter('frame')]
    want = arena_frames + [s + n for s in scopes for n in own]
    check(f'attach: frames {frames} are named in their scopes',
          None if sorted(frames) == sorted(want) else f'want {sorted(want)}')
    print(f'{"FAILED" if failures else "all passed"}: {len(failures)} failed')
    sys.exit(1 if failures else 0)


if __name__ == '__main__':
    main()
