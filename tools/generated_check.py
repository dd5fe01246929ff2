#!/usr/bin/env python3
"""Compiles generated models with MuJoCo: every one must compile.

Usage: tools/generated_check.py DIR

DIR holds the models `examples/generated.rs` writes (`gen_NNNN.xml`, each with its
`gen_NNNN.readback.xml`, which tools/readback_check.py compares). Every `*.xml` that
is not a read-back is compiled with `mujoco.MjModel.from_xml_path` and stepped once
(`mj_forward`, then `mj_step`). A model MuJoCo rejects is a bug of the generators
(mjcf::generate): each is printed as `REJECTED file: MuJoCo's error`. MuJoCo's
run-time warnings (which MuJoCo itself prints) are silenced and
counted per kind instead: they are about the simulation (such as a nearly singular
inertia matrix), not about the model being accepted. Prints totals and a last line
`generated: N passed, M failed`; exits 1 if any was rejected. Run it with the MuJoCo
venv's python (see tools/mujoco_check.py).
"""

import collections
import contextlib
import os
import sys
from pathlib import Path

import mujoco


@contextlib.contextmanager
def quiet_stdout():
    """Sends what C code prints (file descriptors 1 and 2) to /dev/null meanwhile."""
    sys.stdout.flush()
    sys.stderr.flush()
    saved = [os.dup(1), os.dup(2)]
    devnull = os.open(os.devnull, os.O_WRONLY)
    os.dup2(devnull, 1)
    os.dup2(devnull, 2)
    try:
        yield
    finally:
        os.dup2(saved[0], 1)
        os.dup2(saved[1], 2)
        os.close(devnull)
        for fd in saved:
            os.close(fd)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    root = Path(sys.argv[1])
    files = sorted(p for p in root.rglob('*.xml') if not p.name.endswith('.readback.xml'))
    if not files:
        sys.exit(f'no generated models in {root}')
    passed = failed = 0
    totals = dict(nbody=0, njnt=0, ngeom=0, nu=0, nsensor=0, ntendon=0, neq=0, nmesh=0)
    free = 0
    warnings = collections.Counter()
    for path in files:
        try:
            with quiet_stdout():
                m = mujoco.MjModel.from_xml_path(str(path))
                d = mujoco.MjData(m)
                mujoco.mj_forward(m, d)
                mujoco.mj_step(m, d)
            for i in range(int(mujoco.mjtWarning.mjNWARNING)):
                if d.warning[i].number:
                    warnings[mujoco.mjtWarning(i).name] += 1
        except Exception as e:  # MuJoCo raises ValueError; report anything.
            failed += 1
            print(f'REJECTED {path.relative_to(root)}: {" ".join(str(e).split())}')
            continue
        passed += 1
        for k in totals:
            totals[k] += getattr(m, k)
        free += int((m.jnt_type == mujoco.mjtJoint.mjJNT_FREE).sum())
    print('compiled: ' + ', '.join(f'{v} {k[1:]}' for k, v in totals.items())
          + f', {free} free joints')
    if warnings:
        print('models with run-time warnings: '
              + ', '.join(f'{n} {k}' for k, n in sorted(warnings.items())))
    print(f'generated: {passed} passed, {failed} failed')
    sys.exit(1 if failed else 0)


if __name__ == '__main__':
    main()
