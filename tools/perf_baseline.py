#!/usr/bin/env python3
"""Instruction counts of the benchmark workloads against a recorded baseline.

Timings on a busy 2-core machine move by more than 10% from run to run; the number of
instructions a workload executes (valgrind's callgrind) does not, so a change that
slows a workload is seen in the commit that makes it. Each workload of
benches/profile.rs is run twice with different repetition counts, and the
difference divided by the extra repetitions is its cost per repetition (the setup,
reading the robot and the arena, cancels out).

    python3 tools/perf_baseline.py            # compare with benches/baseline.tsv
    python3 tools/perf_baseline.py --record   # write today's counts as the baseline
    python3 tools/perf_baseline.py --binary PATH  # another build's profile binary

Exit status 1 when a workload costs more than 10% over its baseline. Needs valgrind.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BASELINE = os.path.join(ROOT, "benches", "baseline.tsv")
# (name, profile arguments with REPS as {r}, low and high repetition counts)
WORKLOADS = [
    ("build the N=1000 fleet", ["build", "1000", "{r}"], 1, 3),
    ("attach one robot, N=10", ["attach", "10", "{r}"], 1, 201),
    ("attach one robot, N=10000", ["attach", "10000", "{r}"], 1, 201),
    ("detach one robot, N=1000", ["detach", "{r}"], 1, 201),
    ("write the N=1000 fleet", ["write", "1000", "{r}"], 1, 3),
    ("read the realistic 10k-body tree", ["read-rtree", "{r}"], 1, 3),
    ("read the plain 10k-body tree", ["read-tree", "{r}"], 1, 3),
    ("name the N=100 fleet by handles", ["names", "100", "{r}"], 1, 2),
    ("walk the N=100 fleet", ["walk", "100", "{r}"], 1, 2),
    ("name the N=10 fleet by locators", ["full-names", "10", "{r}"], 1, 2),
]
SLOWER = 1.10


def profile_binary():
    out = subprocess.run(
        ["cargo", "bench", "--bench", "profile", "--no-run", "--message-format=json"],
        cwd=ROOT, check=True, capture_output=True, text=True).stdout
    for line in out.splitlines():
        msg = json.loads(line)
        if msg.get("reason") == "compiler-artifact" and msg["target"]["name"] == "profile":
            if msg.get("executable"):
                return msg["executable"]
    sys.exit("no profile binary built")


def instructions(binary, args):
    with tempfile.TemporaryDirectory() as tmp:
        res = subprocess.run(
            ["valgrind", "--tool=callgrind", f"--callgrind-out-file={tmp}/out", binary, *args],
            cwd=os.path.join(ROOT, "benches"), capture_output=True, text=True)
        if res.returncode != 0:
            sys.exit(f"{' '.join(args)} failed:\n{res.stderr[-2000:]}")
        m = re.search(r"Collected : (\d+)", res.stderr)
        return int(m.group(1))


def per_rep(binary, args, lo, hi):
    # The small workloads (an attach, a detach: some 20,000 instructions) move with
    # the hash seeds of each process (imbl's maps take their shape from them), by up
    # to 15% between runs: the median of three pairs of runs is taken for them.
    runs = 3 if hi - lo >= 100 else 1
    counts = []
    for _ in range(runs):
        a = instructions(binary, [x.format(r=lo) for x in args])
        b = instructions(binary, [x.format(r=hi) for x in args])
        counts.append((b - a) // (hi - lo))
    return sorted(counts)[len(counts) // 2]


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--record", action="store_true")
    p.add_argument("--binary")
    opts = p.parse_args()
    binary = os.path.abspath(opts.binary) if opts.binary else profile_binary()
    base = {}
    if os.path.exists(BASELINE):
        for line in open(BASELINE):
            if line.startswith("#") or not line.strip():
                continue
            name, count = line.rstrip("\n").split("\t")
            base[name] = int(count)
    today = {}
    slower = []
    print(f"{'workload':<36} {'baseline':>14} {'today':>14} {'ratio':>7}")
    for name, args, lo, hi in WORKLOADS:
        today[name] = per_rep(binary, args, lo, hi)
        b = base.get(name)
        ratio = today[name] / b if b else float("nan")
        flag = "  SLOWER" if b and ratio > SLOWER else ""
        if flag:
            slower.append(name)
        print(f"{name:<36} {b or '-':>14} {today[name]:>14} {ratio:>7.3f}{flag}", flush=True)
    if opts.record:
        with open(BASELINE, "w") as f:
            f.write("# instructions per repetition (tools/perf_baseline.py --record)\n")
            for name, count in today.items():
                f.write(f"{name}\t{count}\n")
        print(f"recorded {BASELINE}")
    elif slower:
        print(f"more than {SLOWER - 1:.0%} over the baseline: {', '.join(slower)}")
        sys.exit(1)


if __name__ == "__main__":
    main()
