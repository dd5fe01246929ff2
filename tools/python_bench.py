"""Attaching N robots to an arena and writing the composed MJCF, timed: with this
package (`mjcf`) and with dm_control's `mjcf`, whichever the running Python has.

    target/python-venv/bin/python tools/python_bench.py [ROBOT.xml] [N]   # this package
    /work/venv/bin/python tools/python_bench.py [ROBOT.xml] [N]           # dm_control

Defaults: examples/models/quadruped.xml, N = 1000. A model can be attached once in
dm_control, so it reads the robot N times (timed apart); this package attaches one
value N times. Each phase is timed once, after one warm-up run of the whole job on
N / 10 robots. Prints one line per phase, in seconds, then MuJoCo's counts of the
text written (untimed), where `mujoco` is installed.
"""

import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def with_mjcf(robot_path, n):
    import mjcf

    if not hasattr(mjcf, "Model"):
        return None
    times = {}
    t = time.perf_counter()
    robot = mjcf.Model.from_path(robot_path)
    times["read the robot once"] = time.perf_counter() - t
    arena = mjcf.Model("arena")
    arena, _ = arena.add(arena.worldbody(), "geom", type="plane", size=[50, 50, 0.1])
    sites = []
    for i in range(n):
        arena, s = arena.add(arena.worldbody(), "site", name=f"spawn_{i}",
                             pos=[i % 32, i // 32, 0])
        sites.append(s)
    t = time.perf_counter()
    for s in sites:
        arena, _ = arena.attach(s, robot)
    times[f"attach {n}"] = time.perf_counter() - t
    t = time.perf_counter()
    xml = arena.to_xml()
    times["write (to_xml)"] = time.perf_counter() - t
    return times, xml


def with_dm_control(robot_path, n):
    from dm_control import mjcf

    times = {}
    t = time.perf_counter()
    robots = [mjcf.from_path(str(robot_path)) for _ in range(n)]
    times[f"read the robot {n} times"] = time.perf_counter() - t
    arena = mjcf.RootElement(model="arena")
    arena.worldbody.add("geom", type="plane", size=[50, 50, 0.1])
    sites = [arena.worldbody.add("site", name=f"spawn_{i}", pos=[i % 32, i // 32, 0])
             for i in range(n)]
    t = time.perf_counter()
    for s, r in zip(sites, robots):
        s.attach(r)
    times[f"attach {n}"] = time.perf_counter() - t
    t = time.perf_counter()
    xml = arena.to_xml_string()
    times["write (to_xml_string)"] = time.perf_counter() - t
    return times, xml


def main():
    robot = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "examples/models/quadruped.xml"
    n = int(sys.argv[2]) if len(sys.argv) > 2 else 1000
    try:
        import mjcf
        job, name = (with_mjcf, "mjcf (this package)") if hasattr(mjcf, "Model") else (
            with_dm_control, "dm_control.mjcf")
    except ImportError:
        job, name = with_dm_control, "dm_control.mjcf"
    job(robot, max(1, n // 10))  # warm-up
    times, xml = job(robot, n)
    print(f"{name}: {n} robots of {robot.name}, {len(xml)} bytes of MJCF")
    for phase, seconds in times.items():
        print(f"  {phase}: {seconds:.3f} s")
    print(f"  attach + write: {sum(v for k, v in times.items() if not k.startswith('read')):.3f} s")
    try:
        import mujoco
    except ImportError:
        return
    try:  # untimed: is the text a model MuJoCo takes?
        m = mujoco.MjModel.from_xml_string(xml)
    except ValueError as e:
        print(f"  MuJoCo refuses it: {' '.join(str(e).split())}")
        return
    print(f"  MuJoCo compiles it: {m.nbody} bodies, {m.njnt} joints, {m.nu} actuators")


if __name__ == "__main__":
    main()
