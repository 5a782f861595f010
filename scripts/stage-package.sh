#!/usr/bin/env bash
# Stages the fairgrasp Python package (python/fairgrasp) for a venv's interpreter; the one place
# the venv scripts (scripts/python-package-test.sh, scripts/rllib-venv.sh,
# python/examples/sb3_venv.sh) do it.
# Usage: scripts/stage-package.sh [--quiet] VENV LIB [DEST]
#   LIB given (a built lib_native.so, e.g. what `cargo test --workspace` leaves in
#   target/debug/deps/; a relative path is read from the current folder): DEST/fairgrasp is
#   replaced by the package's .py files and LIB as _native.abi3.so, so nothing is compiled.
#   DEST defaults to the venv's site-packages; a folder elsewhere is for PYTHONPATH.
#   LIB empty (""): `maturin develop --profile dev --features train` builds the extension with
#   the trainer, as the workspace's test build has it (pyproject.toml leaves it out of maturin's
#   builds by default), and installs the package into VENV (needs maturin in VENV); --quiet is
#   passed on to maturin.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
maturin_args=()
if [[ "${1:-}" == "--quiet" ]]; then
    maturin_args+=(--quiet)
    shift
fi
if [[ $# -lt 2 || $# -gt 3 ]]; then
    echo "usage: scripts/stage-package.sh [--quiet] VENV LIB [DEST]" >&2
    exit 2
fi
venv="$1"
lib="$2"
if [[ -n "$lib" ]]; then
    dest="${3:-$("$venv/bin/python" -c 'import sysconfig; print(sysconfig.get_paths()["purelib"])')}"
    rm -rf "$dest/fairgrasp"
    mkdir -p "$dest/fairgrasp"
    cp "$root"/python/fairgrasp/*.py "$dest/fairgrasp/"
    cp "$lib" "$dest/fairgrasp/_native.abi3.so"
else
    VIRTUAL_ENV="$venv" PATH="$venv/bin:$PATH" "$venv/bin/maturin" develop "${maturin_args[@]}" \
        --profile dev --features train --manifest-path "$root/python/Cargo.toml"
fi
