"""The Python API: persistence, element handles, errors, composition, saving,
equality, copying, pickling and History."""

import copy
import pickle
import threading
from concurrent.futures import ThreadPoolExecutor

import pytest

import mjcf
from conftest import compile_model


def robot(name="robot"):
    r = mjcf.Model(name)
    r, torso = r.add(r.worldbody(), "body", name="torso")
    r, _ = r.add(torso, "geom", type="box", size=[0.1, 0.1, 0.1], mass=1)
    r, _ = r.add(torso, "joint", name="slide_x", type="slide", axis=(1, 0, 0))
    r, _ = r.add(r.section("actuator"), "motor", name="motor_x", joint="slide_x")
    return r


def arena():
    a = mjcf.Model("arena")
    a, _ = a.add(a.worldbody(), "geom", name="floor", type="plane", size=[5, 5, 0.1])
    a, _ = a.add(a.worldbody(), "site", name="spawn", pos=[0, 0, 0.5])
    return a


def test_edits_return_new_models_and_leave_the_old_unchanged():
    m0 = mjcf.Model("m")
    xml0 = m0.to_xml()
    m1, body = m0.add(m0.worldbody(), "body", name="b", pos=[1, 2, 3])
    assert m0.to_xml() == xml0 and m0.find("body", "b") is None
    m2 = m1.set(body, pos=[4, 5, 6])
    assert m1.lookup("body", "b")["pos"] == (1.0, 2.0, 3.0)
    assert m2.lookup("body", "b")["pos"] == (4.0, 5.0, 6.0)
    m3 = m2.remove(m2.lookup("body", "b"))
    assert m3.find("body", "b") is None and m2.find("body", "b") is not None
    assert m3 == m0 and m1 != m0


def test_an_element_handle_reads_its_own_model_version():
    m1, body = mjcf.Model("m").add(mjcf.Model("m").worldbody(), "body", name="b", pos=[1, 2, 3])
    m2 = m1.set(body, pos=[0, 0, 0])
    assert body["pos"] == (1.0, 2.0, 3.0)  # the handle keeps the version it came from
    assert body.model == m1 and m2.lookup("body", "b")["pos"] == (0.0, 0.0, 0.0)


def test_element_reads_tag_name_attributes_and_children():
    m = arena()
    floor = m.lookup("geom", "floor")
    assert (floor.tag, floor.name, floor.full_name) == ("geom", "floor", "floor")
    assert floor["type"] == "plane" and floor["size"] == (5.0, 5.0, 0.1)
    assert "size" in floor and "pos" not in floor and floor.get("pos") is None
    assert floor.attrs() == {"name": "floor", "type": "plane", "size": (5.0, 5.0, 0.1)}
    with pytest.raises(KeyError):
        floor["pos"]
    assert [c.tag for c in m.worldbody().children()] == ["geom", "site"]
    assert floor.parent() == m.worldbody() and m.root().parent() is None
    with pytest.raises(TypeError):
        floor["size"] = [1, 1, 1]  # read-only: edits go through the model
    with pytest.raises(AttributeError):
        floor.tag = "site"


def test_attribute_values_from_numbers_strings_bools_and_sequences():
    import numpy as np

    m = mjcf.Model("m")
    m, g = m.add(m.worldbody(), "geom", size=np.array([0.1, 0.2]), rgba=(1, 0, 0, 1),
                 contype=3, conaffinity=np.int64(2), friction="1 0.005 0.0001",
                 class_="main")
    assert g["size"] == (0.1, 0.2) and g["rgba"] == (1.0, 0.0, 0.0, 1.0)
    assert g["contype"] == 3 and g["conaffinity"] == 2 and g["class"] == "main"
    assert g["friction"] == (1.0, 0.005, 0.0001)
    m, j = m.add(m.worldbody(), "body", name="b")
    m, j = m.add(j, "joint", limited=True, range=[-1, 1])
    assert j["limited"] == "true"
    m2 = m.set(j, range=None)
    assert m2.find_all("joint")[0].get("range") is None
    with pytest.raises(TypeError):
        m.add(m.worldbody(), "geom", size=["a", "b"])
    with pytest.raises(TypeError):
        m.add(m.worldbody(), "geom", size=None)
    with pytest.raises(TypeError):
        m.add(m.worldbody(), "geom", size={"x": 1})


def test_bad_edits_raise_edit_error_with_the_crate_message_and_path():
    m = arena()
    with pytest.raises(mjcf.EditError) as e:
        m.add(m.worldbody(), "bdy")
    assert "is not a valid child of <worldbody>" in str(e.value)
    assert "did you mean 'body'?" in str(e.value)
    with pytest.raises(mjcf.EditError) as e:
        m.set(m.lookup("geom", "floor"), sise=[1, 1, 1])
    assert "'sise' is not a valid attribute for <geom>" in str(e.value)
    assert e.value.path == "worldbody/geom[name=floor]"
    with pytest.raises(mjcf.EditError) as e:
        m.add(m.worldbody(), "geom", name="floor")
    assert "duplicate identifier 'floor'" in str(e.value)
    assert isinstance(e.value, mjcf.MjcfError)


def test_find_gives_none_and_lookup_raises_with_suggestions():
    m = arena()
    assert m.find("site", "spwan") is None
    with pytest.raises(mjcf.EditError, match=r"no site named 'spwan' \(did you mean 'spawn'\?\)"):
        m.lookup("site", "spwan")
    with pytest.raises(ValueError, match="is not a namespace"):
        m.find("sites", "spawn")


def test_read_errors_carry_file_line_and_column(tmp_path):
    text = "<mujoco>\n  <worldbody>\n    <bdy/>\n  </worldbody>\n</mujoco>\n"
    with pytest.raises(mjcf.ReadError) as e:
        mjcf.Model.from_xml(text)
    assert (e.value.file, e.value.line, e.value.column) == (None, 3, 5)
    assert str(e.value) == "<bdy> is not a valid child of <worldbody> (did you mean 'body'?) at 3:5"
    path = tmp_path / "bad.xml"
    path.write_text(text)
    with pytest.raises(mjcf.ReadError) as e:
        mjcf.Model.from_path(path)
    assert e.value.file == str(path) and (e.value.line, e.value.column) == (3, 5)
    with pytest.raises(mjcf.ReadError, match="cannot read file") as e:
        mjcf.Model.from_path(tmp_path / "missing.xml")
    assert e.value.line is None


def test_the_second_attachment_of_robot_is_scoped_robot_1_and_detach_undoes_it():
    a, r = arena(), robot()
    m1, first = a.attach(a.lookup("site", "spawn"), r)
    m2, second = m1.attach(m1.lookup("site", "spawn"), r)
    assert (first.scope, second.scope) == ("robot", "robot_1")
    assert second.frame.tag == "body" and second.frame.full_name == "robot_1/"
    assert m2.scopes() == ["robot", "robot_1"]
    assert m2.lookup("geom", "floor").full_name == "floor"
    assert m2.lookup("joint", "robot_1/slide_x").name == "slide_x"
    assert second.child == r and m2.attached("robot_1") == r
    assert m2.detach(second) == m1 and m2.detach("robot_1") == m1
    assert m1.detach(first) == a
    m3, named = a.attach(a.worldbody(), r, scope="left")
    assert named.scope == "left" and m3.find("body", "left/torso") is not None
    with pytest.raises(mjcf.EditError, match="no model is attached at scope 'nobody'"):
        m2.detach("nobody")
    with pytest.raises(mjcf.EditError, match="cannot attach at a <geom>"):
        a.attach(a.lookup("geom", "floor"), r)
    model = compile_model(m2)
    assert (model.nbody, model.njnt, model.nu) == (5, 2, 2)


def test_edits_through_an_attachment_frame_and_inside_attached_models():
    a, r = arena(), robot()
    m, att = a.attach(a.lookup("site", "spawn"), r)
    m, free = m.add(att.frame, "freejoint", name="root")
    assert free.full_name == "robot/root/"  # as the writer names it (dm_control's frame scope)
    m = m.set(m.lookup("body", "robot/torso"), pos=[0, 0, 0.2])
    assert m.attached("robot") != r  # the edit made a new version of the attached model
    assert m.scope_path(m.lookup("joint", "robot/slide_x")) == "robot"
    torso = m.locate_in("robot", r.lookup("body", "torso"))
    assert torso.full_name == "robot/torso"
    m2 = m.rename_scope("robot", "dog")
    assert m2.find("body", "dog/torso") is not None and m2.find("body", "robot/torso") is None
    m3 = m.edit_attached("robot", lambda c: c.set(c.lookup("body", "torso"), pos=[0, 0, 1]))
    assert m3.lookup("body", "robot/torso")["pos"] == (0.0, 0.0, 1.0)


def test_include_copy_copies_another_model_in():
    base = arena()
    extra = mjcf.Model("extra")
    extra, _ = extra.add(extra.section("asset"), "material", name="red", rgba=[1, 0, 0, 1])
    extra, ball = extra.add(extra.worldbody(), "geom", name="ball", size=[0.1], material="red")
    m = base.include_copy(extra)
    assert m.find("material", "red") is not None and m.find("geom", "ball") is not None
    assert m.lookup("geom", "ball")["material"] == "red"
    with pytest.raises(mjcf.EditError, match="duplicate identifier 'red' in namespace material"):
        m.include_copy(extra)


def test_check_lists_problems_with_their_paths():
    m = arena()
    assert m.check() == []
    m, _ = m.add(m.worldbody(), "geom", name="g", size=[0.1], material="nothing")
    problems = m.check()
    assert len(problems) == 1
    p = problems[0]
    assert p.path == "g" and p.element.name == "g"
    assert str(p) == "g: 'material' names material 'nothing', which does not exist"


def test_diff_lists_the_changes():
    a = arena()
    b = a.set(a.lookup("geom", "floor"), size=[3, 3, 0.1])
    b, _ = b.add(b.worldbody(), "body", name="box")
    assert sorted(a.diff(b)) == ["+ body box", "~ floor size: 5 5 0.1 -> 3 3 0.1"]
    assert a.diff(a) == []


def test_equality_hash_and_copies_are_by_content():
    a1, a2 = arena(), arena()
    assert a1 == a2 and hash(a1) == hash(a2) and a1 is not a2
    assert len({a1, a2, robot()}) == 2
    assert copy.copy(a1) == a1 and copy.deepcopy(a1) == a1
    assert a1 != "arena" and a1 != 1
    floor = a1.lookup("geom", "floor")
    assert copy.copy(floor) == floor == a1.lookup("geom", "floor")
    assert hash(floor) == hash(a1.lookup("geom", "floor"))
    # Elements of separately built models are different elements, equal models or not.
    assert floor != a2.lookup("geom", "floor")


def test_pickling_gives_the_model_its_text_reads_back_to(repo):
    m = mjcf.Model.from_path(repo / "examples/models/quadruped.xml")
    back = pickle.loads(pickle.dumps(m))
    assert back.to_xml() == m.to_xml() and back.assets() == m.assets()
    a, r = arena(), robot()
    composed, _ = a.attach(a.lookup("site", "spawn"), r)
    back = pickle.loads(pickle.dumps(composed))
    assert back.to_xml() == composed.to_xml() and back.scopes() == []
    with pytest.raises(TypeError):
        pickle.dumps(composed.worldbody())


def test_to_xml_and_assets_compile_in_mujoco_with_meshes(repo):
    case = repo / "tests/conformance/cases/real_02_jaco_arm_with_hand"
    arm = mjcf.Model.from_path(case / "jaco_arm.xml")
    assets = arm.assets()
    assert assets and all(isinstance(v, bytes) for v in assets.values())
    model = compile_model(arm)
    assert model.nmesh == len([n for n in assets if n.endswith(".stl")])
    back = mjcf.Model.from_xml(arm.to_xml(), assets)
    assert back.to_xml() == arm.to_xml()
    with pytest.raises(TypeError, match="expected bytes"):
        mjcf.Model.from_xml(arm.to_xml(), {"x.stl": "text"})


def test_save_save_as_and_save_scene(tmp_path, repo):
    src = (repo / "examples/models/quadruped.xml").read_text()
    (tmp_path / "q.xml").write_text(src)
    m = mjcf.Model.from_path(tmp_path / "q.xml")
    assert m.save() == []  # nothing changed: nothing written
    m2 = m.set(m.lookup("geom", "torso"), mass=20)
    written = m2.save()
    assert written == [tmp_path / "q.xml"]
    assert mjcf.Model.from_path(tmp_path / "q.xml").lookup("geom", "torso")["mass"] == 20.0
    out = m2.save_as(tmp_path / "copy")
    assert out == [tmp_path / "copy" / "q.xml"]
    assert (tmp_path / "copy/q.xml").read_text() == (tmp_path / "q.xml").read_text()
    with pytest.raises(mjcf.SaveError, match="no source text"):
        arena().save()
    a = arena()
    scene, _ = a.attach(a.lookup("site", "spawn"), m2)
    scene, _ = scene.attach(scene.lookup("site", "spawn"), m2)
    path = scene.save_scene(tmp_path / "scene", "scene.xml")
    assert path == tmp_path / "scene" / "scene.xml"
    back = mjcf.Model.from_path(path)
    assert back.scopes() == ["quadruped", "quadruped_1"]
    assert back.to_xml() == scene.to_xml()


def test_history_push_undo_redo():
    a = arena()
    h = mjcf.History(a)
    assert h.current == a and len(h) == 1
    b = a.set(a.lookup("geom", "floor"), size=[1, 1, 0.1])
    assert h.push(b, "shrink") == b
    c, _ = b.add(b.worldbody(), "body", name="x")
    h.push(c, "add x")
    assert h.undo() == b and h.undo() == a and h.undo() == a  # nothing before the first
    assert h.redo() == b and h.current == b and h.position == 1
    d = b.remove(b.lookup("site", "spawn"))
    h.push(d, "remove spawn")  # drops c, which was ahead
    assert len(h) == 3 and h.redo() == d and h.labels() == ["start", "shrink", "remove spawn"]
    assert h[0] == a and h.go_to(0) == a and h.diff(0, 1) == ["~ floor size: 5 5 0.1 -> 1 1 0.1"]
    with pytest.raises(IndexError):
        h.go_to(3)


def test_models_are_read_and_written_from_threads(repo):
    path = repo / "examples/models/quadruped.xml"
    seen = set()

    def job(_):
        seen.add(threading.get_ident())
        m = mjcf.Model.from_path(path)
        return m.to_xml()

    with ThreadPoolExecutor(4) as pool:
        texts = list(pool.map(job, range(16)))
    assert len(set(texts)) == 1


def test_every_public_name_has_a_docstring():
    checked = []
    for name in mjcf.__all__:
        obj = getattr(mjcf, name)
        assert obj.__doc__, name
        for attr, value in vars(obj).items():
            # Methods, static methods and getters; not the exceptions' class-level
            # attribute defaults (None, "").
            if not attr.startswith("_") and (callable(value) or hasattr(value, "__get__")):
                assert value.__doc__, f"{name}.{attr}"
                checked.append(f"{name}.{attr}")
    assert "Model.attach" in checked and "Element.full_name" in checked
    assert "History.current" in checked and len(checked) >= 50


def test_the_readme_example_runs(repo):
    text = (repo / "python/README.md").read_text()
    code = text.split("```python\n", 1)[1].split("```", 1)[0]
    namespace = {}
    exec(compile(code, "python/README.md", "exec"), namespace)
    assert namespace["model"].nbody == 1 + 2 * 2  # the world, two frames with a torso each


def test_bad_inputs_raise_typed_errors_and_leave_models_unchanged():
    a, other = arena(), arena()
    xml = a.to_xml()
    # An element of another model value (built separately) is not in this one.
    with pytest.raises(mjcf.EditError, match="is not in this model") as e:
        a.set(other.lookup("geom", "floor"), size=[1, 1, 1])
    assert e.value.kind == "StaleLocator"
    with pytest.raises(mjcf.EditError, match="cannot be written in XML"):
        mjcf.Model("bad\x01name")
    with pytest.raises(mjcf.EditError, match="cannot be written in XML"):
        a.with_name("bad\x01name")
    with pytest.raises(mjcf.EditError, match="invalid value"):
        a.set(a.lookup("geom", "floor"), type="plnae")
    with pytest.raises(mjcf.EditError, match="invalid scope path"):
        a.attached("")
    with pytest.raises(TypeError):
        a.detach(123)
    with pytest.raises(TypeError):
        a.add("worldbody", "geom")
    with pytest.raises(TypeError):
        mjcf.Model.from_xml(xml, {1: b""})
    with pytest.raises(OverflowError):
        mjcf.History(a).go_to(-1)
    assert a.to_xml() == xml


def _runs_beside(call):
    """Whether another Python thread ran in the middle half of `call()`: it can only
    if the call releases the GIL (the thread wakes every millisecond)."""
    import time

    stamps, stop = [], threading.Event()

    def tick():
        while not stop.is_set():
            stamps.append(time.perf_counter())
            time.sleep(0.001)

    thread = threading.Thread(target=tick)
    thread.start()
    try:
        time.sleep(0.01)
        t0 = time.perf_counter()
        call()
        t1 = time.perf_counter()
    finally:
        stop.set()
        thread.join()
    lo, hi = t0 + 0.25 * (t1 - t0), t0 + 0.75 * (t1 - t0)
    return sum(lo < s < hi for s in stamps), t1 - t0


def test_reading_and_writing_release_the_gil(repo):
    robot = mjcf.Model.from_path(repo / "examples/models/quadruped.xml")
    m = mjcf.Model("many")
    for _ in range(4000):
        m, _ = m.attach(m.worldbody(), robot)
    xml = m.to_xml()  # about 17 MB
    ticks, seconds = _runs_beside(lambda: m.to_xml())
    assert ticks > 0, f"no tick in the middle of a {seconds:.3f} s write"
    ticks, seconds = _runs_beside(lambda: mjcf.Model.from_xml(xml))
    assert ticks > 0, f"no tick in the middle of a {seconds:.3f} s read"
    # A native call that holds the GIL (a list built and sorted in C) lets no tick
    # in: the probe tells the two apart.
    ticks, seconds = _runs_beside(lambda: sorted(range(3_000_000), reverse=True))
    assert ticks == 0, f"{ticks} ticks in {seconds:.3f} s while the GIL was held"
