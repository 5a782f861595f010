#!/usr/bin/env bash
# Rebuilds the three.js bundle that every replay.html inlines (notebooks_export/web/vendor/:
# three.min.js, three-LICENSE.txt, three-version.txt) from the npm packages pinned in
# notebooks_export/web/package-lock.json, and fails if it differs from the committed one.
# The build itself needs no node: notebooks_export includes the committed files.
# Needs npm and the npm registry (or its cache); works in a temporary copy of web/ (npm ci
# there, then the esbuild command below), so web/node_modules is left as it is.
# Usage: scripts/check-three-bundle.sh          check (exit 1 on a difference)
#        scripts/check-three-bundle.sh --write  rebuild and overwrite the committed files
#                                               (after changing web/src/three-subset.js or
#                                               the pinned versions; commit the result)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
web="$root/notebooks_export/web"
vendor="$web/vendor"
write=false
case "${1:-}" in
    "") ;;
    --write) write=true ;;
    *) echo "usage: $0 [--write]" >&2; exit 2 ;;
esac
command -v npm >/dev/null 2>&1 || { echo "check-three-bundle: npm is not installed" >&2; exit 127; }

work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
cp "$web/package.json" "$web/package-lock.json" "$work/"
mkdir "$work/src" "$work/out"
cp "$web/src/three-subset.js" "$work/src/"
(cd "$work" && npm ci --no-audit --no-fund --loglevel=error >&2)
# The bundle: only the parts of three.js the viewer uses, one script defining the global THREE.
(cd "$work" && node_modules/.bin/esbuild src/three-subset.js --bundle --minify --format=iife \
    --global-name=THREE --legal-comments=none --log-level=warning --outfile=out/three.min.js)
cp "$work/node_modules/three/LICENSE" "$work/out/three-LICENSE.txt"
node -p 'require(process.argv[1]).version' "$work/node_modules/three/package.json" \
    >"$work/out/three-version.txt"

if $write; then
    mkdir -p "$vendor"
    cp "$work/out/three.min.js" "$work/out/three-LICENSE.txt" "$work/out/three-version.txt" "$vendor/"
    echo "check-three-bundle: wrote $vendor (three $(cat "$vendor/three-version.txt"))" >&2
    exit 0
fi
status=0
for f in three.min.js three-LICENSE.txt three-version.txt; do
    if ! cmp -s "$work/out/$f" "$vendor/$f"; then
        echo "check-three-bundle: notebooks_export/web/vendor/$f differs from the bundle rebuilt" \
             "from web/package-lock.json ($(wc -c <"$work/out/$f") bytes rebuilt," \
             "$(wc -c <"$vendor/$f" 2>/dev/null || echo missing) committed);" \
             "run scripts/check-three-bundle.sh --write and commit the result" >&2
        status=1
    fi
done
[[ $status -eq 0 ]] && echo "check-three-bundle: the committed bundle is three $(cat "$vendor/three-version.txt"), as rebuilt" >&2
exit $status
