"""The jobs of examples/quickstart.rs, editor.rs and compose.rs, done through the
Python API; MuJoCo compiles every composed model, and the counts are those the Rust
examples give (.ci/run checks the same counts of the Rust examples' outputs)."""

import os
import tempfile

import pytest

import mjcf
from conftest import compile_model


def quickstart_robot(geom):
    robot = mjcf.Model("robot")
    robot, torso = robot.add(robot.worldbody(), "body", name="torso")
    robot, _ = robot.add(torso, "geom", **geom)
    robot, _ = robot.add(torso, "joint", name="slide_x", type="slide", axis=[1, 0, 0])
    robot, _ = robot.add(robot.section("actuator"), "motor", name="motor_x", joint="slide_x")
    return robot


def test_quickstart_composes_two_robots_that_mujoco_compiles():
    arena = mjcf.Model("arena")
    arena, _ = arena.add(arena.worldbody(), "geom", type="plane", size=[5, 5, 0.1])
    arena, spawn = arena.add(arena.worldbody(), "site", name="spawn", pos=[0, 0, 0.5])
    arena, spawn2 = arena.add(arena.worldbody(), "site", name="spawn2", pos=[1, 0, 0.5])
    robot1 = quickstart_robot(dict(type="box", size=[0.1, 0.1, 0.1], mass=1))
    robot2 = quickstart_robot(dict(type="sphere", size=[0.1], mass=0.5))

    before = arena
    arena, frame = arena.attach(spawn, robot1)
    arena, _ = arena.add(frame.frame, "freejoint", name="root")
    arena, _ = arena.add(frame.frame, "inertial", pos=[0, 0, 0], mass=0.1,
                         diaginertia=[1e-3] * 3)
    arena, second = arena.attach(spawn2, robot2)
    assert (frame.scope, second.scope) == ("robot", "robot_1")
    xml = arena.to_xml()
    rust = os.environ.get("MJCF_RUST_QUICKSTART_XML")
    if rust:  # .ci/run passes the Rust example's output: the same text
        with open(rust) as f:
            assert xml == f.read()
    m = compile_model(arena)
    # examples/quickstart.rs's model compiles to 5 bodies, 3 joints, 2 actuators.
    assert (m.nbody, m.njnt, m.nu) == (5, 3, 2)

    detached = arena.detach(frame)
    m = compile_model(detached)
    assert (m.nbody, m.njnt, m.nu) == (3, 1, 1)
    assert detached.scopes() == ["robot_1"] and before.scopes() == []


def test_editor_session_with_history_undo_redo_diff_and_a_reopened_scene(repo):
    robot = mjcf.Model.from_path(repo / "benches/models/quadruped_robot.xml")
    arena = mjcf.Model("arena")
    arena, _ = arena.add(arena.worldbody(), "geom", name="floor", type="plane", size=[10, 10, 0.1])
    for i in range(4):
        arena, _ = arena.add(arena.worldbody(), "site", name=f"spawn_{i}", pos=[2 * i, 0, 0.6])
    history = mjcf.History(arena)

    def edit(label, f):
        history.push(f(history.current), label)

    def add_robot(i):
        def f(m):
            m, frame = m.attach(m.lookup("site", f"spawn_{i}"), robot)
            return m.add(frame.frame, "freejoint")[0]
        return f

    def add_box(i):
        def f(m):
            m, b = m.add(m.worldbody(), "body", name=f"box_{i}", pos=[i * 0.3, 2.0, 0.2])
            return m.add(b, "geom", type="box", size=[0.1, 0.1, 0.1])[0]
        return f

    def paint(i):
        def f(m):
            scope = ["quadruped", "quadruped_1"][i % 2]
            return m.set(m.lookup("geom", f"{scope}/torso"), rgba=[i / 24.0, 0.2, 0.2, 1.0])
        return f

    for i in range(2):
        edit("add robot", add_robot(i))
    for i in range(24):
        edit("add box", add_box(i))
    for i in range(24):
        edit("paint", paint(i))
    history.go_to(history.position - 10)  # undo 10
    history.go_to(history.position + 5)  # redo 5
    lines = history.diff(20, history.position)
    # examples/editor.rs prints these eight lines.
    assert lines == [f"+ body box_{i}" for i in range(18, 24)] + [
        "~ quadruped/torso rgba: (unset) -> 0.75 0.2 0.2 1",
        "~ quadruped_1/torso rgba: (unset) -> 0.7083333333333334 0.2 0.2 1",
    ]
    compile_model(history.current)

    edit("rename", lambda m: m.rename_scope("quadruped_1", "dog"))
    edit("mass", lambda m: m.set(m.lookup("geom", "dog/torso"), mass=20))
    edit("remove", lambda m: m.remove(m.lookup("joint", "dog/yaw_front_left")))
    current = history.current
    # The removed joint's actuator is left naming it: check() says so, and MuJoCo
    # refuses the model (as it does the Rust example's), until the robot is detached.
    problems = [str(p) for p in current.check()]
    assert any("dog/yaw_front_left" in p for p in problems), problems
    with pytest.raises(ValueError, match="missing transmission target"):
        compile_model(current)
    with tempfile.TemporaryDirectory() as tmp:
        saved = current.save_scene(tmp, "editor.xml")
        reopened = mjcf.Model.from_path(saved).detach("dog")
    # examples/editor.rs: "49 versions; reopened: 42 bodies".
    assert (len(history), len(reopened.find_all("body"))) == (49, 42)
    assert reopened.check() == []
    m = compile_model(reopened)
    q = compile_model(robot)
    # The arena's world body, its 24 boxes and one robot with its frame.
    assert m.nbody == 1 + 24 + (q.nbody - 1) + 1 and m.nu == q.nu


def lcg(state, lo, hi):
    """examples/compose.rs's random numbers (Knuth's LCG), the same sequence."""
    state[0] = (state[0] * 6364136223846793005 + 1442695040888963407) % (1 << 64)
    return lo + (hi - lo) * (state[0] >> 11) / (1 << 53)


def test_compose_two_arms_with_hands_and_200_variants(repo, tmp_path):
    import mujoco

    case = repo / "tests/conformance/cases/real_02_jaco_arm_with_hand"
    arm = mjcf.Model.from_path(case / "jaco_arm.xml")
    for i in range(1, 7):
        arm, _ = arm.add(arm.section("actuator"), "motor", name=f"m{i}", joint=f"joint_{i}",
                         gear=[10])
    hand = mjcf.Model.from_path(case / "jaco_hand.xml")
    arm, _ = arm.attach(arm.lookup("site", "wristsite"), hand)

    arena, s, props = mjcf.Model("arena"), [1], []
    arena, _ = arena.add(arena.worldbody(), "light", pos=[0, 0, 3], directional=True)
    arena, _ = arena.add(arena.worldbody(), "geom", name="floor", type="plane", size=[3, 3, 0.1])
    arena, left = arena.add(arena.worldbody(), "site", name="left", pos=[-0.6, 0, 0])
    arena, right = arena.add(arena.worldbody(), "site", name="right", pos=[0.6, 0, 0],
                             euler=[0, 0, 3.141592653589793])
    arena, _ = arena.attach(left, arm)  # one arm value attached twice
    arena, _ = arena.attach(right, arm)
    for n in (f"prop_{i}" for i in range(10)):
        arena, body = arena.add(arena.worldbody(), "body", name=n,
                                pos=[lcg(s, -1, 1), lcg(s, -1, 1), 0.5])
        arena, _ = arena.add(body, "freejoint", name=n)
        arena, geom = arena.add(body, "geom", name=n, type="box", size=[0.03] * 3, mass=0.1)
        props.append((body, geom))
    ring = arena.lookup("geom", "jaco_arm_1/ring_2")

    out = tmp_path / "variants"
    compiled = 0
    for v in range(200):
        m, st = arena, [v]
        for body, geom in props:
            m = m.set(body, pos=[lcg(st, -1, 1), lcg(st, -1, 1), 0.5])
            m = m.set(geom, rgba=[lcg(st, 0, 1), lcg(st, 0, 1), lcg(st, 0, 1), 1])
        m = m.set(ring, size=[lcg(st, 0.03, 0.06), 0.011])
        m.export(out, f"variant_{v:03}.xml")
        if v % 40 == 0:  # every composed model compiles from its text and files
            c = compile_model(m)
            assert (c.nbody, c.njnt, c.nu) == (43, 28, 12)
            compiled += 1
    assert compiled == 5
    # .ci/run's counts for examples/compose.rs's export: the first variant compiles
    # from its folder to 43 bodies, 28 joints, 12 actuators; 200 texts and 9 meshes.
    m = mujoco.MjModel.from_xml_path(str(out / "variant_000.xml"))
    assert (m.nbody, m.njnt, m.nu) == (43, 28, 12)
    assert len(os.listdir(out)) == 200 + 9
