#!/usr/bin/env python3
"""Checks that composed outputs read back as the same model, as MuJoCo sees it.

Usage: tools/readback_check.py PAIRS_DIR

PAIRS_DIR holds, in folders at any depth, pairs written by the conformance runner
(`--actual-dir OUT` writes them to OUT/readback): `X.xml`, an output of this crate
with its files, and `X.readback.xml`, what writing `read(X.xml)` gives. Both are
compiled with MuJoCo from their folder and compared: the count and the names (in
order) of every kind of object, nq, nv, nu, nkey, and the numbers of the compiled
model (positions, orientations, masses and inertias, sizes, joint ranges and axes,
gains and biases, default poses, keyframes), exactly.

Pairs whose original does not compile are skipped (counted); a read-back that does
not compile while its original does is a failure. Prints one FAIL line per
difference and a last line `N passed, M failed, S skipped (original does not
compile)`; exits 1 if any failed. Run it with the MuJoCo venv's python (see
tools/mujoco_check.py).
"""

import sys
from pathlib import Path

import mujoco
import numpy as np

OBJECTS = ('body', 'joint', 'geom', 'site', 'camera', 'light', 'mesh', 'material',
           'texture', 'hfield', 'tendon', 'actuator', 'sensor', 'equality', 'key',
           'numeric', 'text', 'tuple', 'exclude', 'pair', 'skin')
COUNTS = ('nq', 'nv', 'nu', 'na', 'nkey', 'nmocap', 'nbody', 'njnt', 'ngeom', 'nsite',
          'nmesh', 'ntendon', 'nsensor', 'neq')
ARRAYS = ('body_parentid', 'body_pos', 'body_quat', 'body_ipos', 'body_iquat',
          'body_mass', 'body_inertia', 'jnt_type', 'jnt_pos', 'jnt_axis', 'jnt_range',
          'jnt_limited', 'dof_damping', 'dof_armature', 'dof_frictionloss',
          'geom_type', 'geom_size', 'geom_pos', 'geom_quat', 'geom_rgba',
          'geom_friction', 'geom_contype', 'geom_conaffinity', 'site_pos', 'site_size',
          'actuator_trntype', 'actuator_trnid', 'actuator_gear', 'actuator_gainprm',
          'actuator_biasprm', 'actuator_ctrlrange', 'qpos0', 'key_qpos', 'key_ctrl',
          'tendon_stiffness', 'sensor_type', 'sensor_objid')


def names(m, kind):
    n = getattr(m, 'n' + kind, 0)
    obj = getattr(mujoco.mjtObj, 'mjOBJ_' + kind.upper(), None)
    if obj is None:
        return []
    return [mujoco.mj_id2name(m, obj, i) for i in range(n)]


def compare(a, b):
    for c in COUNTS:
        if getattr(a, c) != getattr(b, c):
            return f'{c}: {getattr(a, c)} vs {getattr(b, c)}'
    for kind in OBJECTS:
        if names(a, kind) != names(b, kind):
            return f'{kind} names differ: {names(a, kind)} vs {names(b, kind)}'
    for field in ARRAYS:
        x, y = getattr(a, field, None), getattr(b, field, None)
        if x is None:
            continue
        if x.shape != y.shape or not np.array_equal(x, y, equal_nan=True):
            return f'{field} differs'
    return None


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    root = Path(sys.argv[1])
    passed = failed = skipped = 0
    for back in sorted(root.rglob('*.readback.xml')):
        orig = back.with_name(back.name.replace('.readback.xml', '.xml'))
        try:
            a = mujoco.MjModel.from_xml_path(str(orig))
        except Exception:
            skipped += 1
            continue
        try:
            b = mujoco.MjModel.from_xml_path(str(back))
        except Exception as e:
            failed += 1
            print(f'FAIL {back.relative_to(root)}: does not compile: {e}')
            continue
        diff = compare(a, b)
        if diff:
            failed += 1
            print(f'FAIL {back.relative_to(root)}: {diff}')
        else:
            passed += 1
    print(f'{passed} passed, {failed} failed, {skipped} skipped (original does not compile)')
    sys.exit(1 if failed else 0)


if __name__ == '__main__':
    main()
