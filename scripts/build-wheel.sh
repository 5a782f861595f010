#!/usr/bin/env bash
# Builds the fairgrasp Python package as one abi3 wheel (CPython 3.10 and later, this platform)
# that installs with pip and no Rust toolchain: `pip install target/wheels/fairgrasp-*.whl`.
# Usage: scripts/build-wheel.sh [--features train] [--out DIR]
#   --features train: the wheel has `fairgrasp.train` (the Rust trainer; compiles burn, most of a
#     cold build); without it the wheel has everything else (pyproject.toml: no-default-features).
#   --out DIR: where the wheel goes (default target/wheels; its earlier wheel of the same name is
#     replaced, nothing else there is touched). Prints the wheel's path on stdout.
# maturin comes from the venv of the Python package's tests (scripts/python-env.sh with
# scripts/requirements-python-package.txt, made on first use). The build is cargo's release
# profile in the workspace's target/ (target/release/deps/lib_native.so is the wheel's; the test
# build's extension in target/debug/deps/ is never touched), so a second run compiles nothing.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
features=()
out="$root/target/wheels"
while [[ $# -gt 0 ]]; do
    case "$1" in
        --features)
            if [[ "${2:-}" != "train" ]]; then
                echo "scripts/build-wheel.sh: --features takes \`train\` (the only optional feature), got '${2:-}'" >&2
                exit 2
            fi
            features=(--features train)
            shift 2
            ;;
        --out)
            if [[ -z "${2:-}" ]]; then
                echo "scripts/build-wheel.sh: --out needs a folder" >&2
                exit 2
            fi
            out="$2"
            shift 2
            ;;
        *)
            echo "usage: scripts/build-wheel.sh [--features train] [--out DIR]  (unknown argument '$1')" >&2
            exit 2
            ;;
    esac
done
venv="${FAIRGRASP_PY_VENV:-$root/target/python-package-venv}"
python="$("$root/scripts/python-env.sh" "$venv" "$root/scripts/requirements-python-package.txt")"
mkdir -p "$out" "$root/target"
# maturin writes into a fresh folder; the wheel is then renamed into --out (whole or not at all).
staging="$(mktemp -d "$root/target/wheel-build.XXXXXX")"
trap 'rm -rf "$staging"' EXIT
VIRTUAL_ENV="$venv" PATH="$venv/bin:$PATH" "$venv/bin/maturin" build --release --locked \
    --manifest-path "$root/python/Cargo.toml" --interpreter "$python" \
    "${features[@]}" --out "$staging" >&2
wheels=("$staging"/fairgrasp-*-abi3-*.whl)
if [[ ${#wheels[@]} -ne 1 || ! -f "${wheels[0]}" ]]; then
    echo "scripts/build-wheel.sh: expected one abi3 wheel from maturin in $staging, found: ${wheels[*]}" >&2
    exit 1
fi
wheel="$out/$(basename "${wheels[0]}")"
mv -f "${wheels[0]}" "$wheel"
echo "$wheel"
