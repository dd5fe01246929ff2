"""Lossless save over the real models: for each case of CASES_DIR (its model file is the
`load` op's `file`), with the `lossless` example binary LOSSLESS:

1. no edit: every file saved is byte-identical to its source;
2. one edit, the first of these that the model has an element for (outside default
   classes): `rgba` of the first geom, `rgba` of the first site, `rgb1` of the first
   texture, `gravcomp` of the first body. One file changes, in one block of lines that is
   that element's start tag (the same text once the attribute is set aside), and
   MuJoCo compiles the saved model (in a copy of the case folder, for its assets) to
   the original's numbers but for that attribute's array (`geom_rgba`, ...; every
   row of it that differs holds the value set, for rgba: a geom in a `<replicate>` is
   many geoms).

Usage: python lossless_check.py LOSSLESS CASES_DIR WORK_DIR
Last line: `N passed, M failed`.
"""

import difflib
import json
import os
import re
import shutil
import subprocess
import sys

import numpy as np
import mujoco

# (tag, attribute, value, the compiled array it sets)
EDITS = [
    ("geom", "rgba", "0.25 0.5 0.75 1", "geom_rgba"),
    ("site", "rgba", "0.25 0.5 0.75 1", "site_rgba"),
    ("texture", "rgb1", "0.25 0.5 0.75", "tex_data"),
    ("body", "gravcomp", "0.5", "body_gravcomp"),
]


def model_file(case):
    ops = json.load(open(os.path.join(case, "case.json")))["ops"]
    return next(op["file"] for op in ops if op["op"] == "load")


def run(lossless, case, file, out, *edit):
    return subprocess.run([lossless, case, file, out, *edit], capture_output=True, text=True)


def saved_files(case, out):
    for root, _, files in os.walk(out):
        for f in files:
            rel = os.path.relpath(os.path.join(root, f), out)
            yield rel, os.path.join(case, rel)


def numbers(m):
    out = {}
    for k in dir(m):
        # Where file paths are stored depends on the folder compiled from.
        if k.startswith("_") or k.endswith("pathadr") or k == "paths":
            continue
        try:
            v = getattr(m, k)
        except Exception:
            continue
        if isinstance(v, np.ndarray) and v.dtype.kind in "fiub":
            out[k] = v
    return out


def check(lossless, case, work):
    file = model_file(case)
    out = os.path.join(work, "plain")
    shutil.rmtree(out, ignore_errors=True)
    r = run(lossless, case, file, out)
    if r.returncode:
        return "no edit: " + r.stderr.strip()[-300:]
    for rel, src in saved_files(case, out):
        if open(os.path.join(out, rel), "rb").read() != open(src, "rb").read():
            return f"no edit: {rel} differs"
    # One edit, in a copy of the case (its assets).
    edited = os.path.join(work, "edited")
    shutil.rmtree(edited, ignore_errors=True)
    shutil.copytree(case, edited)
    for tag, attr, value, array in EDITS:
        r = run(lossless, case, file, edited, "set", tag, "-", attr, value)
        if r.returncode == 0 or f"no <{tag}>" not in r.stderr:
            break
    if r.returncode:
        return "edit: " + r.stderr.strip()[-300:]
    changed = [rel for rel, src in saved_files(case, edited)
               if open(os.path.join(edited, rel), "rb").read() != open(src, "rb").read()]
    if len(changed) != 1:
        return f"edit: {len(changed)} files changed"
    a = open(os.path.join(case, changed[0])).read().splitlines()
    b = open(os.path.join(edited, changed[0])).read().splitlines()
    blocks = [op for op in difflib.SequenceMatcher(None, a, b, autojunk=False).get_opcodes() if op[0] != "equal"]
    if len(blocks) != 1:
        return f"edit: {len(blocks)} changed blocks"
    _, i1, i2, j1, j2 = blocks[0]
    old, new = "\n".join(a[i1:i2]), "\n".join(b[j1:j2])
    def strip(t):
        return re.sub(r"""\s+%s\s*=\s*("[^"]*"|'[^']*')""" % attr, "", t)
    if f"<{tag}" not in old or strip(old) != strip(new) or value not in new:
        return f"edit: the lines changed are not the {tag}'s start tag:\n{old}\n->\n{new}"
    m0 = mujoco.MjModel.from_xml_path(os.path.join(case, file))
    m1 = mujoco.MjModel.from_xml_path(os.path.join(edited, file))
    n0, n1 = numbers(m0), numbers(m1)
    for k in n0:
        x, y = n0[k], n1.get(k)
        if y is None or x.shape != y.shape:
            return f"compiled: {k} has another shape"
        same = np.isclose(x, y, rtol=1e-9, atol=0, equal_nan=True) if x.dtype.kind == "f" else x == y
        if same.all():
            continue
        rows = np.unique(np.argwhere(~same)[:, 0]) if same.ndim else [0]
        if k != array:
            return f"compiled: {k} differs in rows {list(rows)[:5]}"
        want = np.array([float(v) for v in value.split()])
        if attr == "rgba" and not all(np.allclose(y[i], want) for i in rows):
            return f"compiled: {k} rows {list(rows)[:5]} do not hold {value}"
    return None


def main():
    lossless, cases, work = sys.argv[1:4]
    passed, failed = 0, 0
    for name in sorted(os.listdir(cases)):
        case = os.path.join(cases, name)
        if not os.path.isfile(os.path.join(case, "case.json")):
            continue
        try:
            problem = check(lossless, case, os.path.join(work, name))
        except Exception as e:  # a model MuJoCo cannot compile, an unreadable file
            problem = f"{type(e).__name__}: {e}"
        if problem:
            failed += 1
            print(f"FAIL {name}: {problem}")
        else:
            passed += 1
        shutil.rmtree(os.path.join(work, name), ignore_errors=True)
    print(f"{passed} passed, {failed} failed")


if __name__ == "__main__":
    main()
