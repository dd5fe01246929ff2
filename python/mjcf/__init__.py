"""Build and compose MuJoCo MJCF models as persistent values.

A `Model` is immutable: every edit (`add`, `set`, `remove`, `attach`, `detach`, ...)
returns a new model and leaves the old one as it was; versions share what an edit
did not touch. Element handles hold the model they were taken from. The classes are
those of the Rust extension `mjcf._mjcf`, over the `mjcf` crate.
"""

from ._mjcf import (
    Attachment,
    EditError,
    Element,
    History,
    MjcfError,
    Model,
    Problem,
    ReadError,
    SaveError,
    WriteError,
    __version__,
)

__all__ = [
    "Attachment",
    "EditError",
    "Element",
    "History",
    "MjcfError",
    "Model",
    "Problem",
    "ReadError",
    "SaveError",
    "WriteError",
]
