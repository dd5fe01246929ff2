#!/usr/bin/env python3
"""Judges the refusal pairs with MuJoCo: each refused.xml is refused with its
catalog message, each twin.xml compiles.

Usage: tools/mujoco_refusal_pairs.py [mjcf-mujoco/refusals]   (the MuJoCo venv's python)

A pair is a folder mjcf-mujoco/refusals/cases/CASE named in the catalog's `case`
column (a row may name several, separated by spaces): refused.xml, twin.xml and the files they read (an attached part). A message
matches when its pieces between printf specifiers (`%s`, `%d`) appear in MuJoCo's
error in order. Prints a FAIL line per wrong pair and `N pairs, M failed`; exits 1 if
any failed. (mjcf-mujoco/tests/refusals.rs judges the same pairs through the binding.)
"""

import csv
import re
import sys
from pathlib import Path

import mujoco


def contains(error, message):
    pos = 0
    for piece in re.split(r'%[-0-9.]*[sdfgiu]', message):
        i = error.find(piece, pos)
        if i < 0:
            return False
        pos = i + len(piece)
    return True


def error_of(path):
    try:
        mujoco.MjModel.from_xml_path(str(path))
        return None
    except Exception as e:  # MuJoCo's refusal
        return str(e)


def main():
    root = Path(sys.argv[1] if len(sys.argv) > 1 else 'mjcf-mujoco/refusals')
    with open(root / 'catalog.tsv', newline='') as f:
        rows = [r for r in csv.DictReader(f, delimiter='\t', quoting=csv.QUOTE_NONE) if r['case']]
    failed = 0
    rows = [(r, c) for r in rows for c in r['case'].split()]
    for r, name in rows:
        case = root / 'cases' / name
        refused, twin = error_of(case / 'refused.xml'), error_of(case / 'twin.xml')
        if refused is None or not contains(refused, r['message']) or twin is not None:
            failed += 1
            print(f"FAIL {name}: refused: {refused!r}; twin: {twin!r}")
    print(f'{len(rows)} pairs, {failed} failed')
    sys.exit(1 if failed else 0)


if __name__ == '__main__':
    main()
