// Opens a replay.html from disk in Debian's chromium-headless-shell (software WebGL) through
// playwright-core, and prints one JSON object with what it saw; the Rust test
// (tests/replay_browser.rs) asserts on it. Usage:
//   node replay-browser.mjs CHROMIUM REPLAY.html [SCREENSHOT.png]
// It checks nothing itself beyond getting the page to run; every request the page makes is
// logged (the page must make none but its own file).
import { chromium } from "playwright-core";
import { pathToFileURL } from "node:url";
import { mkdtempSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";

const [executablePath, file, screenshot] = process.argv.slice(2);
const profile = mkdtempSync(join(tmpdir(), "fairgrasp-replay-profile-"));
const browser = await chromium.launchPersistentContext(profile, {
  executablePath,
  headless: true,
  viewport: { width: 1200, height: 900 },
  args: [
    "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
    "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
  ],
});
const out = { requests: [], errors: [], console: [] };
try {
  const page = browser.pages()[0] || (await browser.newPage());
  page.on("request", (r) => out.requests.push(r.url().slice(0, 200)));
  page.on("pageerror", (e) => out.errors.push(String(e)));
  page.on("console", (m) => m.type() === "error" && out.console.push(m.text()));
  const url = pathToFileURL(file).href;
  out.url = url;
  await page.goto(`${url}#episode=0&t=0`);
  await page.waitForFunction(() => window.fairgraspReplay && "ready" in window.fairgraspReplay, null, { timeout: 60000 });
  out.ready = await page.evaluate(() => window.fairgraspReplay.ready);
  if (!out.ready) throw new Error(await page.evaluate(() => window.fairgraspReplay.error));
  const look = () => page.evaluate(() => ({ state: window.fairgraspReplay.state(), pixels: window.fairgraspReplay.pixels() }));
  out.count = await page.evaluate(() => window.fairgraspReplay.count);
  out.start = await look();
  // A later moment through the URL fragment, as a link would open it.
  const end = out.start.state.duration;
  await page.evaluate((t) => { location.hash = `#episode=0&t=${t}`; }, end);
  await page.waitForFunction((t) => Math.abs(window.fairgraspReplay.state().time - t) < 1e-6, end);
  out.end = await look();
  if (screenshot) await page.screenshot({ path: screenshot });
  // The selector: the next entry, chosen as a person would.
  if (out.count > 1) {
    await page.selectOption("#episode", "1");
    out.switched = await look();
    // Side by side: the first partner the second selector offers.
    const partners = await page.$$eval("#partner option", (os) => os.map((o) => o.value).filter((v) => v !== "-1"));
    if (partners.length) {
      await page.selectOption("#partner", partners[0]);
      out.sideBySide = await page.evaluate(() => window.fairgraspReplay.state());
    }
  }
  // Playing advances the time.
  await page.evaluate(() => { window.fairgraspReplay.seek(0); window.fairgraspReplay.play(); });
  await page.waitForTimeout(700);
  out.played = await page.evaluate(() => window.fairgraspReplay.state().time);
} catch (e) {
  out.failure = String(e && e.stack || e);
} finally {
  await browser.close();
  rmSync(profile, { recursive: true, force: true });
}
process.stdout.write(JSON.stringify(out) + "\n");
