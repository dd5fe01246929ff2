#!/usr/bin/env python3
"""Checks that our conformance outputs compile in MuJoCo like the references.

Usage:

    cargo run --release --example conformance -- \\
        --actual-dir /tmp/actual tests/conformance/cases
    tools/mujoco_check [-v] [--allow-missing] ACTUAL_DIR [CASES_DIR]

ACTUAL_DIR holds our output for every `output` op as ACTUAL_DIR/<case>/<file>
(the layout that `--actual-dir` writes); CASES_DIR defaults to
tests/conformance/cases of this repository.

For every case folder in CASES_DIR and every `expected_NAME.model.json` in it
(the result of compiling the reference output with MuJoCo), the script
compiles our ACTUAL_DIR/<case>/expected_NAME.xml with
`mujoco.MjModel.from_xml_string`, giving it the asset files listed in the
json, and compares with the json: the number and the sorted names of bodies,
joints, geoms, sites, actuators and sensors, then nq, nv and nkey. The first
difference is reported. References that did not compile are skipped.

Output, one line per checked file (skipped ones only with -v):

    OK case/file
    FAIL case/file: <first difference, or MuJoCo's compile error>
    MISSING case/file
    N compiled and matched, M failed, K missing, S skipped (reference does not compile), D deviation-marked

Outputs of ops marked `deviation` in case.json are not checked: the reference
is dm_control's result there, which our semantics differ from by design.

Exit status 0 when nothing failed and nothing is missing (missing files are
allowed with --allow-missing), 1 otherwise, 2 on a usage or set-up error.

MuJoCo comes from a virtual environment, target/mujoco-venv under the repo
root unless the environment variable MJCF_MUJOCO_VENV names another folder.
When it does not exist or cannot import mujoco, it is created with
`python3 -m venv` and `pip install mujoco==<mjcf-mujoco/MUJOCO_VERSION>`; the script then re-executes
itself with the venv's python. Only the standard library is used otherwise.
"""

import argparse
import collections
import json
import os
from pathlib import Path
import subprocess
import sys

REPO_ROOT = Path(__file__).resolve().parent.parent
DEFAULT_CASES_DIR = REPO_ROOT / 'tests' / 'conformance' / 'cases'
DEFAULT_VENV = REPO_ROOT / 'target' / 'mujoco-venv'
VENV_ENV_VAR = 'MJCF_MUJOCO_VENV'
# Set when the script re-executes itself inside the venv, so that it never
# loops if mujoco still cannot be imported there.
IN_VENV_ENV_VAR = 'MJCF_MUJOCO_CHECK_IN_VENV'

# (json name list, count field of both the json and MjModel, mjtObj member).
OBJECT_KINDS = (
    ('bodies', 'nbody', 'mjOBJ_BODY'),
    ('joints', 'njnt', 'mjOBJ_JOINT'),
    ('geoms', 'ngeom', 'mjOBJ_GEOM'),
    ('sites', 'nsite', 'mjOBJ_SITE'),
    ('actuators', 'nu', 'mjOBJ_ACTUATOR'),
    ('sensors', 'nsensor', 'mjOBJ_SENSOR'),
)
SIZE_FIELDS = ('nq', 'nv', 'nkey')


class SetupError(Exception):
  """The MuJoCo environment could not be prepared."""


def parse_args(argv):
  parser = argparse.ArgumentParser(
      description='Compile conformance outputs with MuJoCo and compare them '
      'with the reference expected_*.model.json files.')
  parser.add_argument('actual_dir', metavar='ACTUAL_DIR', type=Path,
                      help='our outputs, as ACTUAL_DIR/<case>/<file>.xml')
  parser.add_argument('cases_dir', metavar='CASES_DIR', type=Path, nargs='?',
                      default=DEFAULT_CASES_DIR,
                      help='the conformance cases (default: %(default)s)')
  parser.add_argument('--allow-missing', action='store_true',
                      help='exit 0 even if some outputs are missing')
  parser.add_argument('-v', '--verbose', action='store_true',
                      help='also list the skipped references')
  return parser.parse_args(argv)


def venv_dir():
  return Path(os.environ.get(VENV_ENV_VAR) or DEFAULT_VENV)


# The one MuJoCo version the project is checked against (the binding crate's, whose
# struct layouts are those of this release): mjcf-mujoco/MUJOCO_VERSION.
MUJOCO_VERSION = (REPO_ROOT / 'mjcf-mujoco' / 'MUJOCO_VERSION').read_text().strip()


def venv_has_mujoco(python):
  """Whether `python` imports mujoco of exactly the pinned version."""
  if not python.exists():
    return False
  result = subprocess.run(
      [str(python), '-c',
       'import mujoco, sys; sys.exit(mujoco.__version__ != sys.argv[1])',
       MUJOCO_VERSION],
      stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
  return result.returncode == 0


def create_venv(venv, python):
  """Creates `venv` and installs mujoco into it; prints the version."""
  print('creating a MuJoCo virtual environment in {}'.format(venv),
        file=sys.stderr)
  try:
    subprocess.run([sys.executable, '-m', 'venv', str(venv)], check=True,
                   stdout=sys.stderr)
    subprocess.run([str(python), '-m', 'pip', 'install',
                    'mujoco==' + MUJOCO_VERSION],
                   check=True, stdout=sys.stderr)
    version = subprocess.run(
        [str(python), '-c', 'import mujoco; print(mujoco.__version__)'],
        check=True, stdout=subprocess.PIPE, text=True).stdout.strip()
  except subprocess.CalledProcessError as e:
    raise SetupError('{} failed with status {}'.format(
        ' '.join(e.cmd), e.returncode)) from e
  print('installed mujoco {}'.format(version), file=sys.stderr)


def reexec_in_venv(argv):
  """Replaces this process by the script run with the venv's python.

  Creates the venv first if it is missing or cannot import mujoco.
  """
  venv = venv_dir()
  python = venv / 'bin' / 'python'
  if not venv_has_mujoco(python):
    create_venv(venv, python)
  env = dict(os.environ, **{IN_VENV_ENV_VAR: '1'})
  script = str(Path(__file__).resolve())
  os.execve(str(python), [str(python), script] + argv[1:], env)


def read_assets(case_dir, asset_map):
  """Maps every VFS name of the json's `assets` to the bytes of its file."""
  return {name: (case_dir / path).read_bytes()
          for name, path in asset_map.items()}


def one_line(message):
  return '; '.join(line.strip() for line in message.splitlines()
                   if line.strip())


def names(mujoco, model, obj_type, count):
  obj = getattr(mujoco.mjtObj, obj_type)
  return sorted(mujoco.mj_id2name(model, obj, i) or '' for i in range(count))


def name_difference(actual, expected):
  """Describes how two name lists differ, as multisets."""
  missing = sorted((collections.Counter(expected) -
                    collections.Counter(actual)).elements())
  extra = sorted((collections.Counter(actual) -
                  collections.Counter(expected)).elements())
  parts = []
  if missing:
    parts.append('missing {}'.format(missing))
  if extra:
    parts.append('unexpected {}'.format(extra))
  return '; '.join(parts)


def first_difference(mujoco, model, reference):
  """Returns the first difference between `model` and the json, or None."""
  for list_key, count_key, obj_type in OBJECT_KINDS:
    count = getattr(model, count_key)
    if count != reference[count_key]:
      return '{} is {}, expected {}'.format(count_key, count,
                                            reference[count_key])
    actual = names(mujoco, model, obj_type, count)
    if actual != sorted(reference[list_key]):
      return '{} differ: {}'.format(
          list_key, name_difference(actual, reference[list_key]))
  for field in SIZE_FIELDS:
    value = getattr(model, field)
    if value != reference[field]:
      return '{} is {}, expected {}'.format(field, value, reference[field])
  return None


def check_output(mujoco, xml_path, case_dir, reference):
  """Compiles our output; returns None if it matches, else the problem."""
  try:
    assets = read_assets(case_dir, reference['assets'])
  except OSError as e:
    return 'cannot read asset: {}'.format(e)
  # The reference compiled with the case folder as working directory (files that
  # are not in the asset map, such as unhashed names, were found there).
  cwd = os.getcwd()
  try:
    os.chdir(case_dir)
    model = mujoco.MjModel.from_xml_string(xml_path.resolve().read_text(), assets)
  except ValueError as e:
    return 'does not compile: {}'.format(one_line(str(e)))
  finally:
    os.chdir(cwd)
  return first_difference(mujoco, model, reference)


def deviation_outputs(case_dir):
  """The output files of ops marked as a deviation (their reference differs by design)."""
  case = json.loads((case_dir / 'case.json').read_text())
  return {op['file'] for op in case['ops']
          if op.get('op') == 'output' and op.get('deviation')}


def run(mujoco, args):
  """Checks every reference json; prints the report and returns the status."""
  matched = failed = missing = skipped = deviations = 0
  case_dirs = sorted(p for p in args.cases_dir.iterdir() if p.is_dir())
  for case_dir in case_dirs:
    marked = deviation_outputs(case_dir)
    for json_path in sorted(case_dir.glob('expected_*.model.json')):
      reference = json.loads(json_path.read_text())
      file_name = json_path.name[:-len('.model.json')] + '.xml'
      label = '{}/{}'.format(case_dir.name, file_name)
      xml_path = args.actual_dir / case_dir.name / file_name
      if file_name in marked:
        deviations += 1
        if args.verbose:
          print('SKIP {}: deviation-marked output'.format(label))
      elif not reference['compiles']:
        skipped += 1
        if args.verbose:
          print('SKIP {}: reference does not compile: {}'.format(
              label, one_line(reference['error'])))
      elif not xml_path.is_file():
        missing += 1
        print('MISSING {}'.format(label))
      else:
        problem = check_output(mujoco, xml_path, case_dir, reference)
        if problem is None:
          matched += 1
          print('OK {}'.format(label))
        else:
          failed += 1
          print('FAIL {}: {}'.format(label, problem))
  print('{} compiled and matched, {} failed, {} missing, {} skipped '
        '(reference does not compile), {} deviation-marked'.format(
            matched, failed, missing, skipped, deviations))
  return 0 if failed == 0 and (missing == 0 or args.allow_missing) else 1


def main(argv):
  args = parse_args(argv[1:])
  for path in (args.actual_dir, args.cases_dir):
    if not path.is_dir():
      print('error: {} is not a folder'.format(path), file=sys.stderr)
      return 2
  if not os.environ.get(IN_VENV_ENV_VAR):
    try:
      reexec_in_venv(argv)
    except (SetupError, OSError) as e:
      print('error: {}'.format(e), file=sys.stderr)
      return 2
  try:
    import mujoco  # pylint: disable=import-outside-toplevel
  except ImportError as e:
    print('error: {} (python {})'.format(e, sys.executable), file=sys.stderr)
    return 2
  return run(mujoco, args)


if __name__ == '__main__':
  sys.exit(main(sys.argv))
