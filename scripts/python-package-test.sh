#!/usr/bin/env bash
# Runs the Python package's pytest tests (python/tests) in a virtual environment of their own.
# Usage: scripts/python-package-test.sh [PYTEST_ARGS...]
#   venv: $FAIRGRASP_PY_VENV (default target/python-package-venv), created on first use by
#   scripts/python-env.sh from scripts/requirements-python-package.txt (needs python3 with venv
#   and PyPI the first time).
#   A suite with packages of its own sets FAIRGRASP_PY_REQUIREMENTS (a requirements file; give it
#   its own FAIRGRASP_PY_VENV too) and FAIRGRASP_PY_TESTS (the folder pytest runs; default
#   python/tests).
#   The extension: with FAIRGRASP_NATIVE_LIB=path/to/lib_native.so (what `cargo test
#   --workspace` builds; tests/python_package.rs passes it) the package is staged from python/
#   with that library into target/python-package-stage, put on PYTHONPATH, so nothing is compiled
#   again; without it, `maturin develop --profile dev --features train` builds and installs it into the
#   venv (both by scripts/stage-package.sh), with the trainer either way, as the tests need.
#   `pip install ./python` and scripts/build-wheel.sh build release wheels without it.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
venv="${FAIRGRASP_PY_VENV:-$root/target/python-package-venv}"
requirements="${FAIRGRASP_PY_REQUIREMENTS:-$root/scripts/requirements-python-package.txt}"
python="$("$root/scripts/python-env.sh" "$venv" "$requirements")"
cd "$root"
if [[ -n "${FAIRGRASP_NATIVE_LIB:-}" ]]; then
    stage="$root/target/python-package-stage"
    scripts/stage-package.sh "$venv" "$FAIRGRASP_NATIVE_LIB" "$stage"
    export PYTHONPATH="$stage${PYTHONPATH:+:$PYTHONPATH}"
else
    scripts/stage-package.sh --quiet "$venv" "" >&2
fi
exec "$python" -m pytest -q -p no:cacheprovider "${FAIRGRASP_PY_TESTS:-python/tests}" "$@"
