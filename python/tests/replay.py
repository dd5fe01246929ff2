"""The conformance cases (tests/conformance/cases/*/case.json) replayed through the
Python API, as tests/support/replay.rs replays them through the crate: the same ops,
error categories and deviation rules, each output read back (write(read(output)) is
the output) and compared with the expected XML by tests/conformance/compare.py.

Not ported: the Rust runner's check that the written names are the walked
full names (tests/support/names.rs), which reads the crate's internals."""

import importlib.util
import json
import os
from pathlib import Path

import mjcf

REPO = Path(__file__).resolve().parents[2]
CASES = REPO / "tests/conformance/cases"


def _compare_module():
    spec = importlib.util.spec_from_file_location("compare", REPO / "tests/conformance/compare.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


compare = _compare_module()

# tests/support/replay.rs's `category`, by the crate's ErrorKind names.
CATEGORY = {
    "Syntax": "parse_error", "InvalidUtf8": "parse_error", "WrongRoot": "parse_error",
    "TooDeep": "parse_error", "IncludeCycle": "parse_error", "IncludedTwice": "parse_error",
    "TooManyFiles": "parse_error", "InvalidChild": "invalid_child",
    "FreejointNotTopLevel": "invalid_child", "DuplicateChild": "duplicate_child",
    "UnknownAttribute": "invalid_attribute", "InvalidValue": "invalid_value",
    "DuplicateIdentifier": "duplicate_identifier", "MissingRequired": "missing_required",
    "FileNotFound": "file_not_found", "FileOutsideRoot": "file_not_found",
    "NotAFile": "file_not_found", "FileTooLarge": "file_not_found", "NotFound": "not_found",
    "AttributeConflict": "attribute_conflict", "CopyConflict": "copy_conflict",
    "InvalidParent": "invalid_parent", "NotAttached": "not_attached",
    "InvalidScope": "not_attached", "StaleLocator": "not_found", "UnknownName": "not_found",
    "AffectsAttachments": "affects_attachments",
    "SourceHasAttachments": "source_has_attachments",
}
FILE_KINDS = {"FileNotFound", "FileOutsideRoot", "NotAFile", "FileTooLarge"}
# The two ValueErrors replay.rs counts as invalid identifiers, by their messages.
IDENTIFIER_WORDS = ("cannot contain '/', which is reserved for scopes", "cannot be named 'world'")


class OpError(Exception):
    """An op's failure, with replay.rs's category."""

    def __init__(self, category, message):
        super().__init__(message)
        self.category = category


def category(e):
    """The category of an exception of the package, as replay.rs names it."""
    if isinstance(e, mjcf.ReadError):
        return "file_not_found" if e.kind in FILE_KINDS else "parse_error"
    if isinstance(e, mjcf.WriteError):
        return "missing_required" if e.kind == "MissingRequired" else "unknown"
    if e.kind == "InvalidValue" and any(w in str(e) for w in IDENTIFIER_WORDS):
        return "invalid_identifier"
    return CATEGORY.get(e.kind, "unknown")


def rewrapped_root_default(text):
    """tests/support/text.rs's rewrapped_root_default."""
    out, inside = [], False
    for line in text.splitlines():
        if not inside and line == "  <default>":
            inside = True
            out.append('  <default>\n    <default class="/">\n')
        elif inside and line == "  </default>":
            inside = False
            out.append("    </default>\n  </default>\n")
        elif inside:
            out.append("  " + line + "\n")
        else:
            out.append(line + "\n")
    return "".join(out)


class State:
    """replay.rs's State: model variables (own, or placed in another's attachment at
    a scope path) and element handles."""

    def __init__(self, case_dir):
        self.dir = case_dir
        self.vars = {}  # name -> ("own", Model) | ("placed", root, [scope names])
        self.handles = {}  # name -> (variable, Element of that variable's model)

    def place(self, var):
        v = self.vars.get(var)
        if v is None:
            raise OpError("unknown", f"no model variable {var!r}")
        return (var, "") if v[0] == "own" else (v[1], "/".join(v[2]))

    def root_model(self, root):
        v = self.vars.get(root)
        if v is None or v[0] != "own":
            raise OpError("unknown", f"no model variable {root!r}")
        return v[1]

    def model(self, var):
        root, path = self.place(var)
        m = self.root_model(root)
        if not path:
            return m
        try:
            return m.attached(path)
        except mjcf.EditError:
            raise OpError("unknown", f"{var} lost its place {path}")

    def set_root(self, root, m):
        self.vars[root] = ("own", m)

    def lift(self, root, path, inner):
        if not path:
            return inner
        try:
            return self.root_model(root).locate_in(path, inner)
        except mjcf.EditError:
            raise OpError("not_found", f"no attachment {path}")

    def resolve(self, var, loc):
        if isinstance(loc, str):
            parts = loc.split(".")
            m = self.model(var)
            el = m.section(parts[0])
            if el is None:
                raise OpError("not_found", f"no section {parts[0]}")
            for tag in parts[1:]:
                el = next((c for c in el.children() if c.tag == tag), None)
                if el is None:
                    raise OpError("not_found", f"no {tag} in {parts[0]}")
            root, scope = self.place(var)
            return root, self.lift(root, scope, el)
        (key, value), = loc.items()
        if key == "find":
            namespace, identifier = value
            try:
                mjcf.Model("x").find(namespace, "x")
            except ValueError:
                raise OpError("invalid_namespace", f"{namespace!r} is not a namespace")
            root, scope = self.place(var)
            full = f"{scope}/{identifier}" if scope else identifier
            el = self.root_model(root).find(namespace, full)
            if el is None:
                raise OpError("not_found", f"no {namespace} named {identifier!r}")
            return root, el
        if key == "handle":
            if value not in self.handles:
                raise OpError("not_found", f"no handle {value}")
            v, inner = self.handles[value]
            root, scope = self.place(v)
            el = self.lift(root, scope, inner)
            if self.root_model(root).scope_path(el) is None:
                raise OpError("not_found", f"handle {value} names a removed element")
            return root, el
        if key == "frame_of":
            root, scope = self.place(value)
            try:
                if not scope:
                    raise mjcf.EditError
                return root, self.root_model(root).frame(scope)
            except mjcf.EditError:
                raise OpError("not_attached", f"{value} is not attached")
        raise OpError("unknown", f"unknown locator {key}")

    def save_handle(self, name, root, el):
        m = self.root_model(root)
        scope = m.scope_path(el)
        if scope is None:
            raise OpError("not_found", "new element vanished")
        inner_model = m.attached(scope) if scope else m
        inner = next((e for e in _walk(inner_model.root()) if _same_place(e, el, scope)), None)
        var = next((v for v in self.vars if _placed_at(self, v, root, scope)), None)
        if var is None or inner is None:
            raise OpError("unknown", "no variable holds the new element")
        self.handles[name] = (var, inner)


def _placed_at(state, var, root, scope):
    try:
        return state.place(var) == (root, scope)
    except OpError:
        return False


def _walk(el):
    yield el
    for c in el.children():
        yield from _walk(c)


def _same_place(inner, outer, scope):
    """Whether `inner` (of the attached model at `scope`) is `outer` lifted."""
    return outer.model.locate_in(scope, inner) == outer if scope else inner == outer


def _edit(f, *args, **kwargs):
    """Calls an edit of the package, its errors as OpErrors with their category."""
    try:
        return f(*args, **kwargs)
    except (mjcf.EditError, mjcf.ReadError, mjcf.WriteError) as e:
        raise OpError(category(e), str(e))


def apply(st, op, skip_compare):
    kind = op["op"]
    if kind == "load":
        st.vars[op["name"]] = ("own", _edit(mjcf.Model.from_path, st.dir / op["file"]))
    elif kind == "new":
        m = mjcf.Model(op.get("model") or "").with_base_dir(st.dir)
        st.vars[op["name"]] = ("own", m)
    elif kind == "add":
        root, parent = st.resolve(op["model"], op["parent"])
        attrs = op.get("attrs") or {}
        if any(v is None for v in attrs.values()):
            raise OpError("unknown", "null in add")
        m, new = _edit(st.root_model(root).add, parent, op["tag"], **attrs)
        st.set_root(root, m)
        if op.get("as"):
            st.save_handle(op["as"], root, new)
    elif kind == "set":
        root, target = st.resolve(op["model"], op["target"])
        st.set_root(root, _edit(st.root_model(root).set, target, **op["attrs"]))
    elif kind == "remove":
        _remove(st, op)
    elif kind == "rename":
        _rename(st, op["model"], op["to"])
    elif kind == "include_copy":
        src = st.model(op["child"])
        root, scope = st.place(op["parent"])
        m, over = st.root_model(root), bool(op.get("override_attributes", False))
        if scope:
            m = _edit(m.edit_attached, scope, lambda c: c.include_copy(src, over))
        else:
            m = _edit(m.include_copy, src, over)
        st.set_root(root, m)
    elif kind == "attach":
        _attach(st, op)
    elif kind == "detach":
        _detach(st, op["child"])
    elif kind == "output":
        _output(st, op, skip_compare)
    else:
        raise OpError("unknown", f"unknown op {kind}")


def _remove(st, op):
    root, target = st.resolve(op["model"], op["target"])
    m = _edit(st.root_model(root).remove, target,
              affect_attachments=bool(op.get("affect_attachments", False)))
    gone = []
    for var, v in list(st.vars.items()):
        if v[0] == "placed" and v[1] == root:
            try:
                m.attached("/".join(v[2]))
            except mjcf.EditError:
                gone.append((var, v[2], st.model(var)))
    st.set_root(root, m)
    for var, path, value in gone:
        outers = [g for g in gone if path[: len(g[1])] == g[1]]
        outer = min(outers, key=lambda g: len(g[1])) if outers else None
        if outer is not None and outer[0] != var:
            st.vars[var] = ("placed", outer[0], path[len(outer[1]):])
        else:
            st.vars[var] = ("own", value)


def _rename(st, var, to):
    root, scope = st.place(var)
    if not scope:
        st.set_root(root, st.root_model(root).with_name(to))
        return
    m = _edit(st.root_model(root).rename_scope, scope, to)
    renamed = scope.rsplit("/", 1)[0] + "/" + to if "/" in scope else to
    m = _edit(m.edit_attached, renamed, lambda c: c.with_name(to))
    st.set_root(root, m)
    depth = len(scope.split("/"))
    for v in st.vars.values():
        if v[0] == "placed" and v[1] == root and len(v[2]) >= depth \
                and "/".join(v[2][:depth]) == scope:
            v[2][depth - 1] = to


def _attach(st, op):
    parent, child = op["parent"], op["child"]
    if "site_loc" in op:
        root, at = st.resolve(parent, op["site_loc"])
    elif op.get("site") is None:
        root, scope = st.place(parent)
        at = st.lift(root, scope, st.model(parent).worldbody())
    else:
        root, at = st.resolve(parent, {"find": ["site", op["site"]]})
    if at.tag not in ("site", "worldbody"):
        raise OpError("invalid_parent", f"cannot attach at a <{at.tag}>")
    v = st.vars.get(child)
    if v is None:
        raise OpError("unknown", f"no model variable {child!r}")
    if v[0] == "placed":
        raise OpError("already_attached", f"{child} is attached")
    if root == child:
        raise OpError("attach_to_self", "a model attached into itself")
    m, attachment = _edit(st.root_model(root).attach, at, v[1])
    scope = attachment.scope  # the whole scope path (`arena/robot_1`)
    st.set_root(root, m)
    child_path = scope.split("/")
    for var, w in list(st.vars.items()):
        if w[0] == "own" and var == child:
            st.vars[var] = ("placed", root, list(child_path))
        elif w[0] == "placed" and w[1] == child:
            st.vars[var] = ("placed", root, child_path + w[2])
    if op.get("as"):
        st.save_handle(op["as"], root, attachment.frame)


def _detach(st, child):
    root, scope = st.place(child)
    if not scope:
        raise OpError("not_attached", f"{child} is not attached")
    m = st.root_model(root)
    try:
        value = m.attached(scope)
    except mjcf.EditError:
        raise OpError("not_attached", scope)
    st.set_root(root, _edit(m.detach, scope))
    depth = len(scope.split("/"))
    for var, v in list(st.vars.items()):
        if v[0] == "placed" and v[1] == root and len(v[2]) >= depth \
                and "/".join(v[2][:depth]) == scope:
            st.vars[var] = ("own", value) if var == child else ("placed", child, v[2][depth:])


def _output(st, op, skip_compare):
    o = op.get("options") or {}
    opts = dict(precision=o.get("precision"), zero_threshold=o.get("zero_threshold"),
                pretty_print=o.get("pretty_print"), filename_with_hash=o.get("filename_with_hash"))
    opts = {k: (int(v) if k == "precision" else v) for k, v in opts.items() if v is not None}
    m = st.model(op["model"])
    xml = _edit(m.to_xml, **opts)
    _read_back(m, xml, opts, op["file"])
    rust_out = os.environ.get("MJCF_RUST_CONFORMANCE_OUT")
    if rust_out:  # the Rust runner's outputs (.ci/run): the very same text
        rust = Path(rust_out) / st.dir.name / op["file"]
        if rust.read_text() != xml:
            raise OpError("output_differs", f"{op['file']}: differs from the Rust runner's {rust}")
    expected_path = st.dir / op["file"]
    if skip_compare or (st.reference_fails and not expected_path.exists()):
        return
    diff = compare.compare_strings(xml, expected_path.read_text())
    if diff is not None:
        raise OpError("output_differs", f"{op['file']}: {diff}")


def _read_back(m, xml, opts, file):
    """replay.rs's read_back: the output reads back, and writing that gives the
    output again (or the same with the root default class rewrapped), a fixed point."""
    assets = m.assets(**opts)
    try:
        w2 = mjcf.Model.from_xml(xml, assets).to_xml(**opts)
        w3 = mjcf.Model.from_xml(w2, assets).to_xml(**opts)
    except mjcf.MjcfError as e:
        raise OpError("read_back", f"{file}: does not read back: {e}")
    if w2 != xml and w2 != rewrapped_root_default(xml):
        raise OpError("read_back", f"{file}: write(read(output)) is not the output")
    if w3 != w2:
        raise OpError("read_back", f"{file}: read-back is not a fixed point")


def run_case(case_dir):
    """('pass', None), ('fail', why) or ('deviation', labels), as replay.rs's run."""
    case = json.loads((case_dir / "case.json").read_text())
    st = State(case_dir)
    st.reference_fails = case.get("reference_fails") is not None
    deviations = []
    for index, op in enumerate(case["ops"]):
        labels = [d.strip() for d in (op.get("deviation") or "").split(",") if d.strip()]
        is_output = op["op"] == "output"
        want = op.get("expect_error")
        if "D1" in labels or (labels and not is_output and want is not None):
            continue
        try:
            apply(st, op, bool(labels) and is_output)
            got = None
        except OpError as e:
            got = e
        if got is not None and got.category == "read_back":
            return "fail", f"op {index} (output): {got}"
        if got is None:
            mismatch = None if want is None else f"op {index} ({op['op']}): expected error {want}, but it succeeded"
        elif want is not None and got.category == want:
            mismatch = None
        elif want is not None:
            mismatch = f"op {index} ({op['op']}): expected error {want}, got {got.category}: {got}"
        else:
            mismatch = f"op {index} ({op['op']}): unexpected error {got.category}: {got}"
        if labels and (is_output or mismatch is not None):
            deviations += [d for d in labels if d not in deviations]
            continue
        if mismatch is not None:
            return "fail", mismatch
    return ("deviation", deviations) if deviations else ("pass", None)
