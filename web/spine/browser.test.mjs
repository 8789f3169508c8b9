// ikarus-spine in a browser with no bundler: headless Chromium (as web/static.test.mjs) loads the
// built package as plain files from a static server (python3 -m http.server), the module fetches
// its WebAssembly beside itself (new URL(…, import.meta.url)), and a goal on the hand-made
// skeleton (toy.mjs) is met. Prints apply()'s mean µs in the page over 600 frames (not a test).
//   IKARUS_SPINE_DIR=DIR node --test web/spine/browser.test.mjs   (needs Chromium and e2e's playwright-core)
import { test } from "node:test";
import assert from "node:assert/strict";
import { cpSync, mkdtempSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { fileURLToPath } from "node:url";
import { launch, openPage, staticServer } from "../../e2e/browser.mjs";

const dir = process.env.IKARUS_SPINE_DIR;
if (!dir) throw new Error("IKARUS_SPINE_DIR: the directory `bash web/spine/build DIR` wrote (web/spine/test sets it)");

const page = `<!doctype html><meta charset="utf-8"><title>ikarus-spine</title><link rel="icon" href="data:,">
<script type="module">
import { attach } from "./ikarus-spine/index.js";
import { toySkeleton, tip } from "./toy.mjs";
try {
  const s = toySkeleton();
  const ik = await attach(s);
  ik.goal("hand", 60, 150, { bones: 3 });
  const report = ik.apply();
  const [x, y] = tip(s.findBone("hand"));
  const three = { bones: 3 };
  // The page's clock is coarse (100 µs): the mean over 600 frames, after 600 of warm-up.
  let t0 = 0;
  for (let f = 0; f < 1200; f++) {
    if (f === 600) t0 = performance.now();
    ik.clear();
    ik.goal("hand", 50 + 30 * Math.cos(f / 60), 150 + 30 * Math.sin(f / 60), three);
    ik.pin("foot");
    ik.apply();
  }
  const mean = ((performance.now() - t0) * 1000) / 600;
  window.result = { error: report.goals[0].error, x, y, mean };
} catch (e) {
  window.result = { failed: String(e && e.stack || e) };
}
</script>`;

test("in Chromium, from plain files: the module fetches its WebAssembly beside itself and meets a goal", async () => {
  const root = mkdtempSync(join(tmpdir(), "ikarus-spine-browser-"));
  cpSync(dir, join(root, "ikarus-spine"), { recursive: true });
  cpSync(fileURLToPath(new URL("toy.mjs", import.meta.url)), join(root, "toy.mjs"));
  writeFileSync(join(root, "index.html"), page);
  const host = await staticServer(root);
  const browser = await launch();
  try {
    const { page: tab, errors } = await openPage(browser);
    const wasm = [];
    tab.on("response", (r) => r.url().endsWith(".wasm") && wasm.push(new URL(r.url()).pathname));
    await tab.goto(`${host.url}/index.html`);
    await tab.waitForFunction(() => window.result, null, { timeout: 20000 });
    const r = await tab.evaluate(() => window.result);
    assert.equal(r.failed, undefined, r.failed);
    assert.deepEqual(wasm, ["/ikarus-spine/ikarus_spine_bg.wasm"]);
    assert.ok(r.error <= 1e-3 && Math.hypot(r.x - 60, r.y - 150) <= 1e-3, `the hand's tip at ${r.x}, ${r.y}`);
    assert.deepEqual(errors, []);
    console.log(`# Chromium: apply() on the hand-made skeleton (10 bones, 3-bone goal + pin), mean ${r.mean.toFixed(1)} µs over 600 frames`);
  } finally {
    await browser.close();
    host.child.kill();
    rmSync(root, { recursive: true, force: true });
  }
});
