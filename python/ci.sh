#!/usr/bin/env bash
# The Python package's checks (.ci/run calls this): a fresh virtual environment under
# target/, the package built from ./python by pip (maturin, release, in the workspace's
# target folder, so the crate's release build is reused) and installed with MuJoCo's
# wheel, then its tests (python/tests) and mypy's stubtest of the type stubs.
#
#   python/ci.sh                     # from anywhere in the checkout
#
# .ci/run sets MJCF_RUST_QUICKSTART_XML and MJCF_RUST_CONFORMANCE_OUT to the Rust
# examples' outputs, which the tests then also compare with the Python ones, byte
# for byte.
set -euo pipefail
cd "$(dirname "$0")/.."
mujoco_version="$(cat mjcf-mujoco/MUJOCO_VERSION)"
venv="${MJCF_PYTHON_VENV:-target/python-venv}"
rm -rf "$venv"
python3 -m venv "$venv"
start=$SECONDS
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check \
    ./python "mujoco==$mujoco_version" "pytest==9.2.0" "mypy==2.4.1"
echo "python: venv, wheel built and installed in $((SECONDS - start)) s"
"$venv/bin/python" -m pytest -q -p no:cacheprovider python/tests
# From outside the checkout, so that only the installed package is found.
(cd "$venv" && bin/python -m mypy.stubtest mjcf)
echo "python: done in $((SECONDS - start)) s"
