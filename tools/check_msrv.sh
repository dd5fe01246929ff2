#!/usr/bin/env bash
# Checks that the `rust-version` each workspace package declares is true of its
# dependencies: no package it builds against (normal and build dependencies, with
# every feature of ours on, so the optional ones count; transitively, as Cargo.lock
# resolves them) declares a higher `rust-version`. Fails naming each one that does.
#
# Dev-dependencies are reported but not checked: a user of the crate never builds
# them, so they do not bound what the crate needs.
#
#   tools/check_msrv.sh            # from anywhere in the checkout
set -euo pipefail
cd "$(dirname "$0")/.."
metadata="$(mktemp)"
trap 'rm -f "$metadata"' EXIT
cargo metadata --format-version 1 --all-features --quiet >"$metadata"
python3 - "$metadata" <<'PY'
import json, sys

with open(sys.argv[1]) as f:
    meta = json.load(f)
packages = {p['id']: p for p in meta['packages']}
nodes = {n['id']: n for n in meta['resolve']['nodes']}


def version(text):
    """A rust-version ("1.86", "1.85.0") as a comparable tuple."""
    parts = [int(x) for x in text.split(".")]
    return tuple(parts + [0] * (3 - len(parts)))


def label(pid):
    p = packages[pid]
    return f"{p['name']} {p['version']}"


def closure(start, kinds_of_first_step):
    """Packages reached from `start`: the first step through edges of the given kinds,
    then through normal and build edges only (what building those packages needs)."""
    seen, stack, first = set(), [start], True
    while stack:
        pid = stack.pop()
        kinds = kinds_of_first_step if first else {None, "build"}
        first = False
        for dep in nodes[pid]['deps']:
            if any(k['kind'] in kinds for k in dep['dep_kinds']) and dep['pkg'] not in seen:
                seen.add(dep['pkg'])
                stack.append(dep['pkg'])
    seen.discard(start)
    return seen


def highest(pids):
    declared = [(version(packages[p]['rust_version']), p) for p in pids if packages[p]['rust_version']]
    return max(declared, default=None)


failed = False
for member in sorted(meta['workspace_members'], key=label):
    ours_text = packages[member]['rust_version']
    if not ours_text:
        print(f"{label(member)}: no rust-version declared")
        failed = True
        continue
    ours = version(ours_text)
    deps = closure(member, {None, "build"})
    over = sorted((p for p in deps if packages[p]['rust_version'] and version(packages[p]['rust_version']) > ours), key=label)
    top = highest(deps)
    top_text = f"{packages[top[1]]['rust_version']} ({label(top[1])})" if top else "none declared"
    print(f"{label(member)}: rust-version {ours_text}; highest of its {len(deps)} dependencies: {top_text}")
    for p in over:
        print(f"  {label(p)} declares rust-version {packages[p]['rust_version']}, above {ours_text}")
        failed = True
    dev_top = highest(closure(member, {"dev"}) - deps)
    if dev_top and dev_top[0] > ours:
        print(f"  (not checked) dev-dependency {label(dev_top[1])} declares rust-version {packages[dev_top[1]]['rust_version']}")
if failed:
    sys.exit("rust-version check failed: raise rust-version to at least the highest a dependency declares")
PY
