#!/usr/bin/env bash
# A build with nothing changed rebuilds nothing: run after the test suite (.ci/run does), this
# builds what `cargo test --workspace --locked --features fairgrasp/train` built, in the same
# profile, and fails if cargo compiled any unit again (a build script whose rerun-if-changed
# names a missing file, or a test that writes into what a build reads, would make every build
# slow), naming the units.
# Usage: scripts/check-noop-build.sh [extra cargo build arguments]
set -euo pipefail
cd "$(dirname "$0")/.."
json="$(mktemp)"
trap 'rm -f "$json"' EXIT
cargo build --workspace --locked --features fairgrasp/train --tests --message-format json "$@" >"$json"
python3 - "$json" <<'PY'
import json, sys

rebuilt, fresh = [], 0
with open(sys.argv[1]) as f:
    for line in f:
        if not line.startswith("{"):
            continue
        m = json.loads(line)
        if m.get("reason") != "compiler-artifact":
            continue
        if m.get("fresh"):
            fresh += 1
        else:
            t = m["target"]
            rebuilt.append(f'{m["package_id"].split("#")[-1]} {",".join(t["kind"])} {t["name"]}')
if rebuilt:
    print(f"check-noop-build: {len(rebuilt)} unit(s) rebuilt although nothing changed:", file=sys.stderr)
    for r in rebuilt:
        print(f"  {r}", file=sys.stderr)
    sys.exit(1)
print(f"check-noop-build: all {fresh} units fresh", file=sys.stderr)
PY
