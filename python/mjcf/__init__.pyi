"""Build and compose MuJoCo MJCF models as persistent values.

A `Model` is immutable: every edit returns a new model and leaves the old one as it
was. Element handles hold the model they were taken from.
"""

from collections.abc import Callable, Mapping, Sequence
from os import PathLike
from pathlib import Path
from typing import Any, Optional, SupportsFloat, Union, final

__version__: str

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

_AttrValue = Union[bool, int, float, str, SupportsFloat, Sequence[SupportsFloat]]
"""What an attribute may be set to: a bool, a number, text or a sequence of numbers."""

_StrPath = Union[str, "PathLike[str]"]

class MjcfError(Exception):
    """The base of every error this package raises for a model it cannot read, edit, write or save."""

class ReadError(MjcfError):
    """MJCF text or files that cannot be read; `file`, `line` and `column` say where, `kind` names the error's kind."""

    file: Optional[str]
    line: Optional[int]
    column: Optional[int]
    kind: str

class EditError(MjcfError):
    """An edit or a look-up that cannot be made; `path` is the element it was aimed at, `kind` the error's kind."""

    path: str
    kind: str

class WriteError(MjcfError):
    """A model that cannot be written as MJCF text (a required reference whose target was removed, ...)."""

    kind: str

class SaveError(MjcfError):
    """A model that cannot be saved or exported to files; `path` is the file or folder concerned, if any."""

    path: Optional[str]

@final
class Element:
    """An element of a model, read-only; valid for the model value it was taken from."""

    @property
    def tag(self) -> str:
        """The XML tag (`"body"`, `"geom"`, ...)."""
    @property
    def name(self) -> Optional[str]:
        """The element's own identifier, or None."""
    @property
    def full_name(self) -> Optional[str]:
        """The name in the composed model (`"robot_1/torso"`), or None."""
    @property
    def model(self) -> Model:
        """The model value this handle belongs to."""
    def __getitem__(self, attr: str, /) -> Any:
        """An attribute's value (float, int, str or tuple of numbers); KeyError if unset."""
    def get(self, attr: str, default: Any = None) -> Any:
        """An attribute's value, or `default` if unset."""
    def __contains__(self, attr: str, /) -> bool:
        """Whether the attribute is set."""
    def attrs(self) -> dict[str, Any]:
        """The set attributes, in schema order."""
    def children(self) -> list[Element]:
        """The child elements, in order."""
    def parent(self) -> Optional[Element]:
        """The parent element, or None for the root."""
    def __eq__(self, other: object, /) -> bool:
        """Same element of equal models."""
    def __hash__(self) -> int:
        """A hash consistent with `==`."""
    def __copy__(self) -> Element:
        """The same handle."""
    def __deepcopy__(self, memo: Any, /) -> Element:
        """The same handle."""

@final
class Attachment:
    """A model attached into another."""

    @property
    def frame(self) -> Element:
        """The attachment frame, an element of the composed model."""
    @property
    def scope(self) -> str:
        """The scope the attached model's names take (`"robot"`, `"robot_1"`)."""
    @property
    def child(self) -> Model:
        """The attached model's value."""

@final
class Problem:
    """A problem `Model.check()` found; `str(problem)` says what and where."""

    @property
    def path(self) -> str:
        """The element with the problem as the writer names it (`robot_1/torso`)."""
    @property
    def element(self) -> Element:
        """The element with the problem."""

@final
class Model:
    """A MuJoCo MJCF model as an immutable value; every edit returns a new model."""

    def __new__(cls, name: str = "mujoco") -> Model: ...
    @staticmethod
    def from_path(path: _StrPath) -> Model:
        """Reads a model file and the files it includes and names."""
    @staticmethod
    def from_xml(
        text: str,
        assets: Optional[Mapping[str, bytes]] = None,
        base_dir: Optional[_StrPath] = None,
    ) -> Model:
        """Reads MJCF text; `assets` maps the file names it uses to their bytes."""
    @property
    def name(self) -> str:
        """The model's name."""
    def with_name(self, name: str) -> Model:
        """The same model with another name."""
    def with_base_dir(self, dir: _StrPath) -> Model:
        """The same model, reading the files later edits name from `dir`."""
    def to_xml(
        self,
        *,
        precision: Optional[int] = None,
        zero_threshold: Optional[float] = None,
        pretty_print: Optional[bool] = None,
        filename_with_hash: Optional[bool] = None,
    ) -> str:
        """The composed model as MJCF text."""
    def assets(
        self,
        *,
        precision: Optional[int] = None,
        zero_threshold: Optional[float] = None,
        pretty_print: Optional[bool] = None,
        filename_with_hash: Optional[bool] = None,
    ) -> dict[str, bytes]:
        """The files `to_xml()`'s text names, for `mujoco.MjModel.from_xml_string`."""
    def root(self) -> Element:
        """The root element, `<mujoco>`."""
    def worldbody(self) -> Element:
        """The `<worldbody>`."""
    def section(self, tag: str) -> Optional[Element]:
        """The top-level section with this tag, or None."""
    def find(self, namespace: str, name: str) -> Optional[Element]:
        """The element named `name` in `namespace`, or None."""
    def lookup(self, namespace: str, name: str) -> Element:
        """As `find`, but raises `EditError` with the closest names."""
    def find_all(self, namespace: str) -> list[Element]:
        """Every element of the namespace, in document order."""
    def add(self, parent: Element, tag: str, **attrs: _AttrValue) -> tuple[Model, Element]:
        """Adds a `<tag>` as the last child of `parent`: (new model, new element)."""
    def set(self, element: Element, **attrs: Optional[_AttrValue]) -> Model:
        """Sets attributes (None clears one); returns the new model."""
    def remove(self, element: Element, *, affect_attachments: bool = False) -> Model:
        """Removes an element and its subtree; returns the new model."""
    def attach(
        self, at: Element, child: Model, scope: Optional[str] = None
    ) -> tuple[Model, Attachment]:
        """Attaches `child` at a site or the worldbody: (new model, attachment)."""
    def detach(self, attachment: Union[Attachment, str]) -> Model:
        """Removes an attachment (or the one at a scope path); returns the new model."""
    def scopes(self) -> list[str]:
        """The scope paths of the attachments, at every level."""
    def attached(self, scope: str) -> Model:
        """The model attached at a scope path."""
    def frame(self, scope: str) -> Element:
        """The attachment frame of a scope path."""
    def scope_path(self, element: Element) -> Optional[str]:
        """The scope path of the model an element lies in, or None."""
    def locate_in(self, scope: str, element: Element) -> Element:
        """An element of the model attached at `scope`, as an element of this model."""
    def rename_scope(self, scope: str, to: str) -> Model:
        """Renames the scope of an attachment."""
    def edit_attached(self, scope: str, edit: Callable[[Model], Model]) -> Model:
        """Replaces the model attached at `scope` by `edit(it)`."""
    def include_copy(self, other: Model, override_attributes: bool = False) -> Model:
        """Copies `other`'s elements into this model, as `<include>` would."""
    def check(self) -> list[Problem]:
        """What MuJoCo would refuse or misread; empty for a sound model."""
    def diff(self, other: Model) -> list[str]:
        """The changes from this model to `other`, one line each."""
    def save(self) -> list[Path]:
        """Saves into the files it was read from (lossless); the paths written."""
    def save_as(self, folder: _StrPath) -> list[Path]:
        """Saves the model's files losslessly into `folder`; the paths written."""
    def save_scene(self, folder: _StrPath, file: str) -> Path:
        """Saves as a scene of MuJoCo `<attach>`es; the scene file's path."""
    def export(self, folder: _StrPath, file: str) -> Path:
        """Writes the composed model and its files into `folder`; the text file's path."""
    def __eq__(self, other: object, /) -> bool:
        """Content equality."""
    def __hash__(self) -> int:
        """A hash of the content, consistent with `==`."""
    def __copy__(self) -> Model:
        """The same value."""
    def __deepcopy__(self, memo: Any, /) -> Model:
        """The same value."""
    def __reduce__(self) -> tuple[Any, ...]:
        """Pickles as MJCF text and files; unpickled, `Model.from_xml(m.to_xml(), m.assets())`."""

@final
class History:
    """An undo/redo list of model versions."""

    def __new__(cls, model: Model, limit: Optional[int] = None) -> History: ...
    def push(self, model: Model, label: str = "") -> Model:
        """Records `model` as the next version; returns it."""
    def undo(self) -> Model:
        """Steps back one version if there is one; the model now current."""
    def redo(self) -> Model:
        """Steps forward one version if there is one; the model now current."""
    def go_to(self, index: int) -> Model:
        """Moves to version `index`; the model now current."""
    @property
    def current(self) -> Model:
        """The model at the present position."""
    @property
    def position(self) -> int:
        """The index of the present version."""
    def labels(self) -> list[str]:
        """The label of each version, oldest first."""
    def __getitem__(self, index: int, /) -> Model:
        """The version at `index`."""
    def __len__(self) -> int:
        """The number of versions kept."""
    def diff(self, start: int, end: int) -> list[str]:
        """The changes from version `start` to version `end`, one line each."""
