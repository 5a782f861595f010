#!/usr/bin/env bash
# Installs what the 3D replay (replay.html) and its browser test need, each only if missing:
# - Debian's chromium-headless-shell (apt-get; needs root), which the browser test drives;
# - the npm packages pinned in notebooks_export/web/package-lock.json (npm ci): playwright-core,
#   which drives the browser in the test, and three.js and esbuild, from which
#   scripts/check-three-bundle.sh rebuilds the committed bundle to compare.
# The build needs neither: every build inlines the three.js bundle committed in
# notebooks_export/web/vendor/, so replay.html is written without node or a browser.
# Usage: scripts/install-browser.sh
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
web="$root/notebooks_export/web"

if ! command -v chromium-headless-shell >/dev/null 2>&1; then
    if [[ "$(id -u)" -eq 0 ]] && command -v apt-get >/dev/null 2>&1; then
        apt-get update -qq >&2
        DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
            chromium-headless-shell >&2
    else
        echo "note: chromium-headless-shell is not installed and cannot be here (apt-get as root" \
             "is needed): the replay's browser test will be skipped" >&2
    fi
fi

installed="$web/node_modules/.package-lock.json"
if [[ ! -f "$installed" || "$web/package-lock.json" -nt "$installed" ]]; then
    (cd "$web" && npm ci --no-audit --no-fund --loglevel=error >&2)
fi
command -v chromium-headless-shell || true
