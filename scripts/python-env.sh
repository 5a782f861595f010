#!/usr/bin/env bash
# Creates (once) a Python virtual environment with the packages fairgrasp's tests use, and prints
# its interpreter's path. Usage: scripts/python-env.sh [VENV_DIR [REQUIREMENTS]]
# (defaults: target/python-venv, scripts/requirements-test.txt; the TensorBoard test uses its own
# venv with scripts/requirements-tensorboard.txt)
#
# The notebook test calls this itself; nothing has to be installed by hand. Needs python3 with
# the venv module and access to PyPI on the first run.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
venv="${1:-$root/target/python-venv}"
requirements="${2:-$root/scripts/requirements-test.txt}"
python="$venv/bin/python"
stamp="$venv/.fairgrasp-requirements"
if [[ -x "$python" && -f "$stamp" ]] && cmp -s "$stamp" "$requirements"; then
    echo "$python"
    exit 0
fi
mkdir -p "$(dirname "$venv")"
python3 -m venv "$venv" >&2
"$python" -m pip install --quiet --disable-pip-version-check -r "$requirements" >&2
cp "$requirements" "$stamp"
echo "$python"
