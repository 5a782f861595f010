#!/usr/bin/env bash
# Screenshot of an episode in Rerun's web viewer (docs/img/rerun.png): `fairgrasp replay --json`
# records two methods on one scenario, `python -m fairgrasp.rerun` writes the .rrd, the Rerun CLI
# of the venv serves its web viewer on 127.0.0.1, and Debian's chromium-headless-shell (software
# WebGL through SwiftShader), driven by playwright-core, opens it and takes the picture. Every
# request that does not go to 127.0.0.1 is aborted (the viewer's page asks for web fonts), and the
# viewer's usage analytics are switched off first (`rerun analytics disable`).
# Usage: scripts/rerun-screenshot.sh OUT.png [STEP]
#   STEP: the moment shown, typed into the viewer's time field (default 45: lifting).
#   needs: target/debug/fairgrasp (cargo build), target/python-rerun-venv (made by
#   scripts/python-package-test.sh with FAIRGRASP_PY_REQUIREMENTS=scripts/requirements-rerun.txt),
#   target/debug/lib_native.so, and scripts/install-browser.sh's Chromium and playwright-core.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out="$(realpath -m "${1:?usage: scripts/rerun-screenshot.sh OUT.png [STEP]}")"
step="${2:-45}"
venv="$root/target/python-rerun-venv"
work="$(mktemp -d)"
server=""
files=""
cleanup() {
    # The rerun command is a Python launcher of the viewer binary: end its whole process group.
    if [[ -n "$server" ]]; then kill -- "-$server" 2>/dev/null || true; fi
    if [[ -n "$files" ]]; then kill "$files" 2>/dev/null || true; fi
    rm -rf "$work"
}
trap cleanup EXIT

"$root/target/debug/fairgrasp" replay --policy open_loop --policy oracle --json "$work/episode.json" >&2
mkdir -p "$work/stage/fairgrasp"
cp "$root"/python/fairgrasp/*.py "$work/stage/fairgrasp/"
cp "$root/target/debug/lib_native.so" "$work/stage/fairgrasp/_native.abi3.so"
PYTHONPATH="$work/stage" "$venv/bin/python" -m fairgrasp.rerun "$work/episode.json" \
    --rrd "$work/episode.rrd" >&2

"$venv/bin/rerun" analytics disable >/dev/null
if curl -sf -o /dev/null http://127.0.0.1:19090/; then
    echo "port 19090 is taken (another viewer?): nothing done" >&2
    exit 1
fi
setsid "$venv/bin/rerun" --serve-web --bind 127.0.0.1 --port 19876 --web-viewer-port 19090 \
    >"$work/server.log" 2>&1 &
server=$!
# The .rrd over HTTP (with CORS, the viewer is on another port): the viewer opens it as a file,
# so the recording's blueprint (camera, paused timeline) applies.
"$venv/bin/python" -c '
import functools, http.server as h, sys
class H(h.SimpleHTTPRequestHandler):
    def end_headers(self):
        self.send_header("Access-Control-Allow-Origin", "*")
        super().end_headers()
handler = functools.partial(H, directory=sys.argv[1])
h.ThreadingHTTPServer(("127.0.0.1", 19091), handler).serve_forever()
' "$work" >"$work/files.log" 2>&1 &
files=$!
for _ in $(seq 50); do
    curl -sf -o /dev/null http://127.0.0.1:19090/ && curl -sf -o /dev/null \
        http://127.0.0.1:19091/episode.rrd && break
    sleep 0.2
done

cd "$root/notebooks_export/web"
node --input-type=module - "$(command -v chromium-headless-shell)" "$out" "$step" <<'EOF'
import { createRequire } from "node:module";
const require = createRequire(process.cwd() + "/package.json");
const { chromium } = require("playwright-core");
const [executablePath, out, step] = process.argv.slice(2);
const browser = await chromium.launch({
  executablePath,
  headless: true,
  args: ["--no-sandbox", "--disable-quic", "--no-first-run", "--disable-background-networking",
         "--disable-component-update", "--disable-sync", "--use-angle=swiftshader",
         "--enable-unsafe-swiftshader", "--enable-webgl", "--ignore-gpu-blocklist"],
});
const page = await browser.newPage({ viewport: { width: 1600, height: 900 } });
const log = [];
page.on("console", (m) => log.push(`${m.type()}: ${m.text()}`.slice(0, 300)));
page.on("pageerror", (e) => log.push(`pageerror: ${e}`));
await page.route("**/*", (r) => {
  const local = /^(http|ws)s?:\/\/(127\.0\.0\.1|localhost)(:|\/)/.test(r.request().url());
  return local ? r.continue() : r.abort();
});
const rrd = encodeURIComponent("http://127.0.0.1:19091/episode.rrd");
await page.goto(`http://127.0.0.1:19090/?url=${rrd}`);
await page.waitForTimeout(15000);
// The time field at the right end of the time bar: type the step, as a person would.
const { width, height } = page.viewportSize();
await page.mouse.dblclick(width - 45, height - 14);
await page.keyboard.press("Control+A");
await page.keyboard.type(String(step));
await page.keyboard.press("Enter");
await page.mouse.move(width / 4, height / 2);
await page.waitForTimeout(5000);
await page.screenshot({ path: out });
const errors = log.filter((l) => /^(error|pageerror)/.test(l));
if (errors.length) console.error(errors.join("\n"));
await browser.close();
EOF
echo "Written $out (step $step)" >&2
