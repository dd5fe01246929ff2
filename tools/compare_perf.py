#!/usr/bin/env python3
"""Runs the performance workloads W1-W4 and W8 with mjcf, dm_control and MuJoCo's MjSpec
in one run and prints one table (see benches/workloads/mod.rs for the workloads).

Usage:

        tools/compare_perf.py                 # ours + dm_control up to N=1000, MjSpec up to N=100
        tools/compare_perf.py --quick         # N <= 100 everywhere (about a minute)
        tools/compare_perf.py --full          # MjSpec up to N=1000 as well (several minutes)
        tools/compare_perf.py --sizes 1,10,100 --mjspec-max-n 10 --dmc-max-n 100
        tools/compare_perf.py --ours-json FILE   # reuse `cargo bench --bench figures` output
        tools/compare_perf.py --only w8       # some workloads (w1, w2, w3, w8; W4 runs with w1)

Our figures come from `cargo bench --bench figures` (release build), which prints
one JSON line per workload; the generated models (arenas for N other than 100 and
1000, the 10,000-body tree and chain) are written by the same binary
(`-- --dump-dir DIR --dump-only`) so that every side reads the same files.

The references run in a virtual environment holding dm_control and mujoco: --venv,
else target/perf-venv if it imports both, else /tmp/dmc if it does, else
target/perf-venv is created (`python3 -m venv`, then `pip install --find-links
/opt/wheels dm_control==1.0.50 mujoco`). Each reference workload runs in its own
process of that venv's python (this script with --worker), so that its memory is
measured alone and a crash or a timeout only fails that workload, printed as
"fails (<reason>)".

Measured as:
- dm_control W1: `mjcf.from_path` of the robot once; per copy `copy.deepcopy(robot)`
    (dm_control attaches a given model only once), `site.attach(copy)`,
    `frame.add('freejoint')`; `to_xml_string()`; memory = growth of the process's
    resident set (VmRSS) during the build. W2: one more version = `copy.deepcopy` of
    the fleet (refused by dm_control for a model with attachments). W4: `copy.detach()`.
- MjSpec W1: `MjSpec.from_file` of the robot once; `copy_during_attach = True` on
    the arena (else a spec can be attached once); per copy a body at the site's
    pose with a freejoint and a frame, `spec.attach(robot, frame=frame,
    prefix='quadruped_i/')`; `spec.to_xml()`; memory = VmRSS growth. W2: one more
    version = `spec.copy()` plus one rgba edit; memory = VmRSS growth over 20 copies
    / 20. W4: `spec.delete(body)` of one robot's frame body.
- ours: time = median of repeated runs; memory = heap bytes held (counting
    allocator), the fleet including the arena and robot it shares.
- W8 (dm_control only): `benches/dm_control/compose.py` (the user program of the
    composition issue: the jaco arm and hand read, two arms and ten props in an
    arena, 200 randomized variants exported with `export_with_assets`), timed whole,
    run in a temporary folder; ours is `examples/compose.rs` (the same job, its 200
    variants) timed whole by the figures binary.
- W3: reading the XML text from memory (`Model::from_xml_str`,
    `mjcf.from_xml_string`, `MjSpec.from_string`); W5 (ours only): quick-xml reading
    the same text into events and writing them back, the floor.

Only the standard library is used outside the venv.
"""

import argparse
import gc
import json
import os
from pathlib import Path
import subprocess
import sys
import time

REPO_ROOT = Path(__file__).resolve().parent.parent
MODELS_DIR = REPO_ROOT / 'benches' / 'models'
DEFAULT_VENV = REPO_ROOT / 'target' / 'perf-venv'
FALLBACK_VENVS = (Path('/tmp/dmc'),)
WHEELS_DIR = Path('/opt/wheels')
# MuJoCo pinned to the binding crate's version (mjcf-mujoco/MUJOCO_VERSION).
PIP_PACKAGES = ('dm_control==1.0.50', 'mujoco==' + (REPO_ROOT / 'mjcf-mujoco' / 'MUJOCO_VERSION').read_text().strip())
DEFAULT_SIZES = (1, 10, 100, 1000)
UNDO_ROBOTS = 100
DETACH_ROBOTS = 1000
MJSPEC_COPIES = 20


# --------------------------------------------------------------------------
# Worker side: runs inside the venv, one workload per process, prints JSON.
# --------------------------------------------------------------------------

def _rss_bytes(field='VmRSS'):
    with open('/proc/self/status') as f:
        for line in f:
            if line.startswith(field + ':'):
                return int(line.split()[1]) * 1024
    return 0


def _emit(**kw):
    print(json.dumps(kw), flush=True)


def _site_pose(spec, i):
    site = spec.site(f'spawn_{i}')
    return site.pos, site.quat


def worker_dmc(task, n, models):
    import copy
    from dm_control import mjcf
    robot_path = MODELS_DIR / 'quadruped_robot.xml'
    if task == 'w1':
        robot = mjcf.from_path(str(robot_path))
        arena = mjcf.from_path(str(models / f'arena_{n}.xml'))
        gc.collect()
        rss0 = _rss_bytes()
        t = time.perf_counter()
        copies = []
        for i in range(n):
            site = arena.find('site', f'spawn_{i}')
            r = copy.deepcopy(robot)
            frame = site.attach(r)
            frame.add('freejoint')
            copies.append(r)
        build = time.perf_counter() - t
        gc.collect()
        _emit(key=f'w1_build_{n}', seconds=build, live_bytes=_rss_bytes() - rss0)
        t = time.perf_counter()
        xml = arena.to_xml_string()
        _emit(key=f'w1_write_{n}', seconds=time.perf_counter() - t, bytes=len(xml.encode()))
        if n == DETACH_ROBOTS:
            t = time.perf_counter()
            copies[n // 2].detach()
            _emit(key='w4_detach', seconds=time.perf_counter() - t)
    elif task == 'w2':
        robot = mjcf.from_path(str(robot_path))
        arena = mjcf.from_path(str(models / f'arena_{n}.xml'))
        for i in range(n):
            frame = arena.find('site', f'spawn_{i}').attach(copy.deepcopy(robot))
            frame.add('freejoint')
        t = time.perf_counter()
        copy.deepcopy(arena)  # dm_control refuses: NotImplementedError
        _emit(key='w2_one_version', seconds=time.perf_counter() - t)
    elif task == 'w3':
        read_w3(lambda xml: mjcf.from_xml_string(xml), models)
    elif task == 'w8':
        import runpy
        import tempfile
        import numpy  # noqa: F401  (imported before the clock starts, as dm_control is)
        with tempfile.TemporaryDirectory() as d:
            # The script reads tests/conformance/cases/... and writes variants/, both
            # relative to where it runs.
            os.symlink(REPO_ROOT / 'tests', Path(d) / 'tests')
            os.chdir(d)
            t = time.perf_counter()
            runpy.run_path(str(REPO_ROOT / 'benches' / 'dm_control' / 'compose.py'))
            _emit(key='w8_compose', seconds=time.perf_counter() - t, files=len(os.listdir('variants')))
    else:
        raise ValueError(task)


def worker_mjspec(task, n, models):
    import mujoco
    robot_path = MODELS_DIR / 'quadruped_robot.xml'

    def fleet(n):
        robot = mujoco.MjSpec.from_file(str(robot_path))
        spec = mujoco.MjSpec.from_file(str(models / f'arena_{n}.xml'))
        spec.copy_during_attach = True
        gc.collect()
        rss0 = _rss_bytes()
        t = time.perf_counter()
        bodies = []
        for i in range(n):
            pos, quat = _site_pose(spec, i)
            body = spec.worldbody.add_body(pos=pos, quat=quat)
            body.add_freejoint()
            frame = body.add_frame()
            spec.attach(robot, frame=frame, prefix=f'quadruped_{i}/')
            bodies.append(body)
        return spec, bodies, time.perf_counter() - t, _rss_bytes() - rss0

    if task == 'w1':
        spec, bodies, build, mem = fleet(n)
        _emit(key=f'w1_build_{n}', seconds=build, live_bytes=mem)
        t = time.perf_counter()
        xml = spec.to_xml()
        _emit(key=f'w1_write_{n}', seconds=time.perf_counter() - t, bytes=len(xml.encode()))
        t = time.perf_counter()
        spec.delete(bodies[n // 2])
        _emit(key='w4_detach', seconds=time.perf_counter() - t, n=n)
    elif task == 'w2':
        spec, _, _, _ = fleet(n)
        versions = [spec]
        gc.collect()
        rss0 = _rss_bytes()
        times = []
        for k in range(MJSPEC_COPIES):
            t = time.perf_counter()
            v = versions[-1].copy()
            v.geom(f'quadruped_{(k * 37) % n}/torso').rgba = [k / MJSPEC_COPIES, 0.5, 0.5, 1]
            times.append(time.perf_counter() - t)
            versions.append(v)
        gc.collect()
        times.sort()
        _emit(key='w2_one_version', seconds=times[len(times) // 2],
              live_bytes=(_rss_bytes() - rss0) / MJSPEC_COPIES)
    elif task == 'w3':
        read_w3(mujoco.MjSpec.from_string, models)
    else:
        raise ValueError(task)


def read_w3(read, models):
    which = os.environ.get('COMPARE_PERF_W3', 'tree,humanoid,chain').split(',')
    files = {'tree': 'tree_10k.xml', 'humanoid': 'humanoid_CMU.xml', 'chain': 'chain_10k.xml'}
    for w in which:
        xml = (models / files[w]).read_text()
        t = time.perf_counter()
        read(xml)
        _emit(key=f'w3_{w}_read', seconds=time.perf_counter() - t, bytes=len(xml.encode()))


def worker_main(argv):
    p = argparse.ArgumentParser()
    p.add_argument('--worker', choices=('dmc', 'mjspec'))
    p.add_argument('--task')
    p.add_argument('--n', type=int, default=0)
    p.add_argument('--models', type=Path)
    a = p.parse_args(argv)
    os.environ.setdefault('MUJOCO_GL', 'disable')
    (worker_dmc if a.worker == 'dmc' else worker_mjspec)(a.task, a.n, a.models)


# --------------------------------------------------------------------------
# Driver side.
# --------------------------------------------------------------------------

def venv_python(venv):
    return Path(venv) / 'bin' / 'python'


def venv_ok(venv):
    py = venv_python(venv)
    if not py.exists():
        return False
    r = subprocess.run([str(py), '-c', 'import dm_control.mjcf, mujoco'], capture_output=True,
                       env=dict(os.environ, MUJOCO_GL='disable'))
    return r.returncode == 0


def ensure_venv(requested):
    candidates = [Path(requested)] if requested else [DEFAULT_VENV, *FALLBACK_VENVS]
    for c in candidates:
        if venv_ok(c):
            return c
    venv = candidates[0]
    print(f'creating {venv} with {" ".join(PIP_PACKAGES)} ...', file=sys.stderr, flush=True)
    subprocess.run([sys.executable, '-m', 'venv', str(venv)], check=True)
    pip = [str(venv_python(venv)), '-m', 'pip', 'install', '--quiet']
    if WHEELS_DIR.is_dir():
        pip += ['--find-links', str(WHEELS_DIR)]
    subprocess.run(pip + list(PIP_PACKAGES), check=True)
    if not venv_ok(venv):
        sys.exit(f'{venv} cannot import dm_control and mujoco')
    return venv


def parse_records(text):
    out = {}
    for line in text.splitlines():
        line = line.strip()
        if line.startswith('{'):
            rec = json.loads(line)
            out[rec['key']] = rec
    return out


def figures_cmd(*args):
    return ['cargo', 'bench', '--quiet', '--bench', 'figures', '--', *args]


def dump_models(sizes, models):
    """Writes the arenas, the generated W3 models and the humanoid to `models`."""
    sizes = sorted(set(sizes) | {UNDO_ROBOTS, DETACH_ROBOTS})
    cmd = figures_cmd('--sizes', ','.join(map(str, sizes)), '--dump-dir', str(models), '--dump-only')
    print('running: ' + ' '.join(cmd), file=sys.stderr, flush=True)
    r = subprocess.run(cmd, cwd=REPO_ROOT, capture_output=True, text=True)
    if r.returncode != 0:
        sys.exit(f'cannot build or run the figures binary:\n{r.stderr[-3000:]}')


def run_ours(args):
    """Runs the figures binary; returns ({key: record}, failure reason or None)."""
    if args.ours_json:
        return parse_records(Path(args.ours_json).read_text()), None
    only = ['--only', ','.join(sorted(args.only | ({'w4'} if 'w1' in args.only else set())))] if args.only else []
    cmd = figures_cmd('--sizes', ','.join(map(str, args.sizes)), *only)
    print('running: ' + ' '.join(cmd), file=sys.stderr, flush=True)
    r = subprocess.run(cmd, cwd=REPO_ROOT, capture_output=True, text=True)
    reason = None
    if r.returncode != 0:
        print(f'our figures binary exited with {r.returncode}:\n{r.stderr[-3000:]}', file=sys.stderr)
        reason = failure_reason(r.stderr, r.returncode)
    return parse_records(r.stdout), reason


def run_worker(venv, side, task, n, models, timeout, env_extra=None):
    """Runs one reference workload; returns ({key: record}, failure reason or None)."""
    cmd = [str(venv_python(venv)), str(Path(__file__).resolve()), '--worker', side, '--task', task,
           '--n', str(n), '--models', str(models)]
    env = dict(os.environ, **(env_extra or {}))
    env.setdefault('MUJOCO_GL', 'disable')
    print(f'running {side} {task} N={n} {env_extra or ""}...', file=sys.stderr, flush=True)
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout, env=env)
        stdout = r.stdout
        reason = None if r.returncode == 0 else failure_reason(r.stderr, r.returncode)
    except subprocess.TimeoutExpired as e:
        stdout = e.stdout.decode() if isinstance(e.stdout, bytes) else (e.stdout or '')
        reason = f'timeout after {timeout:.0f} s'
    return parse_records(stdout), reason


def failure_reason(stderr, code):
    """The last error line of a failed process (module paths dropped), or its status."""
    lines = [l.strip() for l in stderr.strip().splitlines() if l.strip()]
    for l in reversed(lines):
        if 'Error' in l or 'error' in l or 'Exception' in l:
            head, sep, tail = l.partition(': ')
            if sep and ' ' not in head:
                l = head.rsplit('.', 1)[-1] + ': ' + tail  # lxml.etree.XMLSyntaxError -> XMLSyntaxError
            return l[:200]
    if code < 0:
        return f'killed by signal {-code}'
    return lines[-1][:200] if lines else f'exit status {code}'


def fmt_time(s):
    if s < 1e-3:
        return f'{s * 1e6:.1f} µs'
    if s < 1:
        return f'{s * 1e3:.1f} ms'
    return f'{s:.2f} s'


def fmt_bytes(b):
    b = float(b)
    for unit, f in (('GiB', 2**30), ('MiB', 2**20), ('KiB', 2**10)):
        if abs(b) >= f:
            return f'{b / f:.1f} {unit}'
    return f'{b:.0f} B'


class Cell:
    """One table cell: a value (for ratios) and its text, a failure, or nothing."""

    def __init__(self, value=None, text=None, fail=None):
        self.value, self.text, self.fail = value, text, fail


class Side:
    """The records of one side and the failures of the workloads it could not run."""

    def __init__(self, records=None, failures=None):
        self.records = records or {}
        self.failures = failures or {}

    def time(self, key, with_rate=False, note=''):
        r = self.records.get(key)
        if r is None or 'seconds' not in r:
            fail = self.failures.get(key) or (r or {}).get('error')
            return Cell(fail=fail)
        s = r['seconds']
        text = fmt_time(s)
        if with_rate and r.get('bytes') and s > 0:
            text += f' ({r["bytes"] / s / 1e6:.1f} MB/s)'
        return Cell(s, text + note)

    def mem(self, key, field, note=''):
        r = self.records.get(key)
        if r is None or r.get(field) is None:
            return Cell(fail=self.failures.get(key) or (r or {}).get('error'))
        return Cell(r[field], fmt_bytes(r[field]) + note)


class MissingIsFailure(dict):
    """Failures of our side: every key fails with the figures binary's reason."""

    def __init__(self, reason):
        super().__init__()
        self.reason = reason

    def get(self, key, default=None):
        return self.reason


def ratio(theirs, ours):
    if theirs.value is None or ours.value is None or ours.value <= 0:
        return ''
    x = theirs.value / ours.value
    return f'{x:,.0f}x' if x >= 100 else f'{x:.1f}x'


def table(args, ours, dmc, mjs):
    rows = []  # (workload, ours, dm_control, MjSpec)
    sides = (ours, dmc, mjs)

    def times(key, with_rate=False, notes=('', '', '')):
        return [s.time(key, with_rate, n) for s, n in zip(sides, notes)]

    for n in args.sizes:
        rows.append((f'W1 build N={n}', *times(f'w1_build_{n}')))
    for n in args.sizes:
        rows.append((f'W1 write N={n}', *times(f'w1_write_{n}', with_rate=True)))
    for n in args.sizes:
        rows.append((f'W1 memory N={n}', ours.mem(f'w1_build_{n}', 'live_bytes_with_inputs'),
                     dmc.mem(f'w1_build_{n}', 'live_bytes', ' RSS'), mjs.mem(f'w1_build_{n}', 'live_bytes', ' RSS')))
    rows.append(('W2 one more version (N=100): time', *times('w2_one_version')))
    rows.append(('W2 one more version (N=100): memory', ours.mem('w2_history', 'live_bytes_per_version'),
                 dmc.mem('w2_one_version', 'live_bytes', ' RSS'), mjs.mem('w2_one_version', 'live_bytes', ' RSS')))
    w2 = ours.records.get('w2_history', {})
    if 'seconds_per_edit' in w2:
        rows.append(('W2 1000 edits kept, per edit', Cell(w2['seconds_per_edit'], fmt_time(w2['seconds_per_edit'])),
                     Cell(), Cell()))
    rows.append(('W3 read 10,000-body tree', *times('w3_tree_read', with_rate=True)))
    rows.append(('W3 read 10,000-deep chain', *times('w3_chain_read', with_rate=True)))
    rows.append(('W3 read CMU humanoid', *times('w3_humanoid_read', with_rate=True)))
    for key, name in (('w3_tree_write', 'W3 write 10,000-body tree'), ('w3_chain_write', 'W3 write 10,000-deep chain')):
        rows.append((name, ours.time(key, True), Cell(), Cell()))
    mj_n = mjs.records.get('w4_detach', {}).get('n')
    mj_note = f' (N={mj_n})' if mj_n and mj_n != DETACH_ROBOTS else ''
    rows.append(('W4 detach one robot (N=1000)', *times('w4_detach', notes=('', '', mj_note))))
    rows.append(('W8 compose.py/compose.rs: read, compose, 200 variants exported', *times('w8_compose')))
    for key, name in (('w5_fleet_1000_roundtrip', 'W5 quick-xml read+write, W1 N=1000 XML'),
                      ('w5_fleet_1000_read', 'W5 quick-xml read, W1 N=1000 XML'),
                      ('w5_tree_roundtrip', 'W5 quick-xml read+write, W3 tree'),
                      ('w5_tree_read', 'W5 quick-xml read, W3 tree')):
        rows.append((name, ours.time(key, True), Cell(), Cell()))

    reasons = []  # failure texts, printed as notes under the table

    def show(cell):
        if cell.fail:
            if cell.fail not in reasons:
                reasons.append(cell.fail)
            return f'fails [{reasons.index(cell.fail) + 1}]'
        return cell.text if cell.text is not None else '-'

    out = [('workload', 'ours (mjcf)', 'dm_control', 'ratio', 'MjSpec', 'ratio')]
    for name, o, d, m in rows:
        out.append((name, show(o), show(d), ratio(d, o), show(m), ratio(m, o)))
    widths = [max(len(r[i]) for r in out) for i in range(len(out[0]))]
    lines = []
    for i, r in enumerate(out):
        lines.append('  '.join(c.ljust(w) for c, w in zip(r, widths)).rstrip())
        if i == 0:
            lines.append('  '.join('-' * w for w in widths))
    for i, r in enumerate(reasons):
        lines.append(f'[{i + 1}] fails ({r})')
    lines.append('')
    lines.append('ratio = theirs / ours: how many times the time or memory of ours the reference takes.')
    lines.append('memory: ours = heap bytes held (counting allocator); references = growth of resident set (RSS).')
    if mj_note:
        lines.append(f'MjSpec detach was measured on its largest fleet, N={mj_n} (--full: 1000).')
    return lines


def targets(ours):
    """The performance targets (the checks below) and the ratios against quick-xml, met or missed."""
    rec = ours.records

    def get(key, field='seconds'):
        return rec.get(key, {}).get(field)

    def rate(key):
        r = rec.get(key, {})
        return r['bytes'] / r['seconds'] / 1e6 if r.get('bytes') and r.get('seconds') else None

    checks = [
        ('W1 build N=1000 < 5 ms', get('w1_build_1000'), 5e-3, 'lt', fmt_time),
        ('W1 write N=1000 >= 300 MB/s', rate('w1_write_1000'), 300, 'ge', lambda v: f'{v:.0f} MB/s'),
        ('W3 10,000-body tree read <= 20 ms', get('w3_tree_read'), 20e-3, 'le', fmt_time),
        ('W2 one more version <= 10 µs', get('w2_one_version'), 10e-6, 'le', fmt_time),
        ('W2 one more version <= 10 KiB', get('w2_history', 'live_bytes_per_version'), 10 * 1024, 'le', fmt_bytes),
        ('W4 detach <= 10 µs', get('w4_detach'), 10e-6, 'le', fmt_time),
        ('W1 N=1000 fleet < 50 MiB before writing', get('w1_build_1000', 'live_bytes_with_inputs'), 50 * 2**20, 'lt',
         fmt_bytes),
    ]
    out = []
    for name, v, limit, op, fmt in checks:
        if v is None:
            out.append(f'{name}: not measured')
            continue
        if {'lt': v < limit, 'le': v <= limit, 'ge': v >= limit}[op]:
            out.append(f'{name}: met ({fmt(v)})')
        else:
            factor = limit / v if op == 'ge' else v / limit
            out.append(f'{name}: MISSED ({fmt(v)}, {factor:.1f}x off)')
    w, f = get('w1_write_1000'), get('w5_fleet_1000_roundtrip')
    if w and f:
        out.append(f'to_xml within 3x of quick-xml (W1 N=1000 write / quick-xml read+write of it): {w / f:.1f}x, '
                   + ('met' if w / f <= 3 else 'MISSED'))
    r, f = get('w3_tree_read'), get('w5_tree_read')
    if r and f:
        out.append(f'parse within 3x of quick-xml (W3 tree read / quick-xml read): {r / f:.1f}x, '
                   + ('met' if r / f <= 3 else 'MISSED'))
    h, b = get('w2_history', 'live_bytes'), get('w1_build_100', 'live_bytes_with_inputs')
    if h is not None and b:
        out.append(f'1000 versions of the 100-robot fleet < 2x the memory of one: {(b + h) / b:.2f}x, '
                   + ('met' if (b + h) / b < 2 else 'MISSED')
                   + f' (one fleet = {fmt_bytes(b)}, as its 100 robots share one value; 1000 versions add '
                   + f'{fmt_bytes(h)})')
    return out


def main():
    if '--worker' in sys.argv:
        worker_main(sys.argv[1:])
        return
    p = argparse.ArgumentParser(description=__doc__.split('\n\n')[0],
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument('--sizes', default=','.join(map(str, DEFAULT_SIZES)),
                   help='W1 fleet sizes (default 1,10,100,1000)')
    p.add_argument('--dmc-max-n', type=int, default=1000, help='largest N run with dm_control (default 1000)')
    p.add_argument('--mjspec-max-n', type=int, default=100, help='largest N run with MjSpec (default 100)')
    p.add_argument('--full', action='store_true', help='N up to 1000 for every side')
    p.add_argument('--quick', action='store_true', help='N up to 100 for every side')
    p.add_argument('--skip-dmc', action='store_true', help='do not run dm_control')
    p.add_argument('--skip-mjspec', action='store_true', help='do not run MjSpec')
    p.add_argument('--venv', help='a venv with dm_control and mujoco (default: see above)')
    p.add_argument('--timeout', type=float, default=1800, help='seconds per reference workload (default 1800)')
    p.add_argument('--ours-json', help='our figures (JSON lines) instead of running cargo bench')
    p.add_argument('--theirs-json', help="the references' figures from an earlier --json-out instead of running them")
    p.add_argument('--models-dir', type=Path, default=REPO_ROOT / 'target' / 'perf-models',
                   help='where the generated models are written (default target/perf-models)')
    p.add_argument('--json-out', type=Path, help='also write every record as JSON here')
    p.add_argument('--only', help='these workloads only (comma-separated: w1, w2, w3, w8)')
    args = p.parse_args()
    args.only = set(args.only.split(',')) if args.only else None
    args.sizes = sorted({int(s) for s in args.sizes.split(',') if s.strip()})
    if args.full:
        args.dmc_max_n = args.mjspec_max_n = max(args.sizes)
    if args.quick:
        args.sizes = [n for n in args.sizes if n <= 100] or [1, 10, 100]
        args.dmc_max_n = min(args.dmc_max_n, 100)
        args.mjspec_max_n = min(args.mjspec_max_n, 100)

    models = args.models_dir
    dump_models(args.sizes, models)
    ours_records, ours_failure = run_ours(args)
    ours = Side(ours_records, MissingIsFailure(ours_failure) if ours_failure else {})

    dmc, mjs = Side(), Side()
    if args.theirs_json:
        old = json.loads(Path(args.theirs_json).read_text())
        dmc = Side(old['dm_control'], old['dm_control_failures'])
        mjs = Side(old['mjspec'], old['mjspec_failures'])
    else:
        runs = [(s, m) for s, m, skip in (('dmc', args.dmc_max_n, args.skip_dmc),
                                          ('mjspec', args.mjspec_max_n, args.skip_mjspec)) if not skip]
        venv = ensure_venv(args.venv) if runs else None
        if venv:
            print(f'reference venv: {venv}', file=sys.stderr, flush=True)
        for side_name, max_n in runs:
            side = dmc if side_name == 'dmc' else mjs

            def reference(task, n, keys, env_extra=None):
                got, reason = run_worker(venv, side_name, task, n, models, args.timeout, env_extra)
                side.records.update(got)
                for k in keys:
                    if reason and k not in got:
                        side.failures[k] = reason

            wants = lambda w: args.only is None or w in args.only  # noqa: E731
            sizes = [n for n in args.sizes if n <= max_n] if wants('w1') else []
            for n in sizes:
                keys = [f'w1_build_{n}', f'w1_write_{n}']
                # dm_control detaches from its 1000-robot fleet; MjSpec from each fleet
                # it builds, and the largest one is kept.
                if n == DETACH_ROBOTS or (side_name == 'mjspec' and n == sizes[-1]):
                    keys.append('w4_detach')
                reference('w1', n, keys)
            if wants('w2'):
                reference('w2', UNDO_ROBOTS, ['w2_one_version'])
            # Each W3 file in its own process: a reader may crash on the chain.
            for w in ('tree', 'humanoid', 'chain') if wants('w3') else ():
                reference('w3', 0, [f'w3_{w}_read'], {'COMPARE_PERF_W3': w})
            if side_name == 'dmc' and wants('w8'):
                reference('w8', 0, ['w8_compose'])

    print()
    for line in table(args, ours, dmc, mjs):
        print(line)
    print("\nTargets:")
    for line in targets(ours):
        print('  ' + line)
    if args.json_out:
        args.json_out.write_text(json.dumps({
            'ours': ours.records, 'ours_failure': ours_failure,
            'dm_control': dmc.records, 'dm_control_failures': dmc.failures,
            'mjspec': mjs.records, 'mjspec_failures': mjs.failures}, indent=1))


if __name__ == '__main__':
    main()
