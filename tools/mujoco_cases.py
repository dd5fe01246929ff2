#!/usr/bin/env python3
"""Compiles every `X.xml` in a folder with MuJoCo and checks `X.expect.json`.

Usage: tools/mujoco_cases.py DIR   (run with the MuJoCo venv's python)

An expectation maps a field of the compiled model to a value: a count (`nbody`),
a list of names of one kind (`body_names`, `joint_names`, `geom_names`, ...), or an
entry of an array of the compiled model (`actuator_gainprm[0][0]`, `qpos0[2]`),
compared within 1e-9. Prints one FAIL line per difference and a last line
`N passed, M failed`; exits 1 if any failed.
"""

import json
import re
import sys
from pathlib import Path

import mujoco

KINDS = {'body': 'mjOBJ_BODY', 'joint': 'mjOBJ_JOINT', 'geom': 'mjOBJ_GEOM',
         'site': 'mjOBJ_SITE', 'actuator': 'mjOBJ_ACTUATOR', 'sensor': 'mjOBJ_SENSOR',
         'frame': 'mjOBJ_FRAME', 'key': 'mjOBJ_KEY', 'tendon': 'mjOBJ_TENDON'}
COUNT = {'body': 'nbody', 'joint': 'njnt', 'geom': 'ngeom', 'site': 'nsite',
         'actuator': 'nu', 'sensor': 'nsensor', 'key': 'nkey', 'tendon': 'ntendon'}


def value(m, field):
    names = re.fullmatch(r'(\w+)_names', field)
    if names:
        kind = names.group(1)
        obj = getattr(mujoco.mjtObj, KINDS[kind])
        return [mujoco.mj_id2name(m, obj, i) for i in range(getattr(m, COUNT[kind]))]
    base = re.match(r'\w+', field).group(0)
    v = getattr(m, base)
    for i in re.findall(r'\[(\d+)\]', field):
        v = v[int(i)]
    return v


def same(got, want):
    if isinstance(want, list):
        return list(got) == want
    try:
        return abs(float(got) - float(want)) <= 1e-9 * max(1.0, abs(float(want)))
    except (TypeError, ValueError):
        return got == want


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    passed = failed = 0
    for xml in sorted(Path(sys.argv[1]).glob('*.xml')):
        expect = xml.with_name(xml.name[:-len('.xml')] + '.expect.json')
        if not expect.exists():
            continue
        try:
            m = mujoco.MjModel.from_xml_path(str(xml))
        except Exception as e:
            failed += 1
            print(f'FAIL {xml.name}: does not compile: {e}')
            continue
        bad = []
        for field, want in json.loads(expect.read_text()).items():
            got = value(m, field)
            if not same(got, want):
                bad.append(f'{field} = {got!r}, expected {want!r}')
        if bad:
            failed += 1
            print(f'FAIL {xml.name}: ' + '; '.join(bad))
        else:
            passed += 1
    print(f'{passed} passed, {failed} failed')
    sys.exit(1 if failed else 0)


if __name__ == '__main__':
    main()
