"""Shared fixtures: the repository's root, and MuJoCo's compile of a model value."""

from pathlib import Path

import pytest

REPO = Path(__file__).resolve().parents[2]


@pytest.fixture
def repo() -> Path:
    """The checkout's root folder (examples/, tests/conformance/ are under it)."""
    return REPO


def compile_model(model):
    """MuJoCo's compile of a model value, from its text and its files."""
    import mujoco

    return mujoco.MjModel.from_xml_string(model.to_xml(), model.assets())
