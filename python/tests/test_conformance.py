"""The conformance cases replayed through the Python API (replay.py): every case
that attaches, detaches or copies a model in (the attach/detach/include_copy cases),
and the others too. A case whose ops the reference marks as a deviation is skipped,
with its labels as the reason, as the Rust runner counts it apart."""

import json

import pytest

from replay import CASES, run_case

ALL = sorted(p.parent for p in CASES.glob("*/case.json"))
COMPOSING = {"attach", "detach", "include_copy"}


def composes(case_dir):
    ops = json.loads((case_dir / "case.json").read_text())["ops"]
    return any(op["op"] in COMPOSING for op in ops)


@pytest.mark.parametrize("case_dir", ALL, ids=[p.name for p in ALL])
def test_case(case_dir):
    outcome, detail = run_case(case_dir)
    if outcome == "deviation":
        pytest.skip(f"deviation {','.join(detail)}")
    assert outcome == "pass", detail


def test_the_composing_cases_are_most_of_the_corpus():
    assert len(ALL) == 155
    assert sum(map(composes, ALL)) >= 100
