// The ikarus-spine demo page (DIR/spine-demo.html, written by `bash web/build DIR`) in headless
// Chromium, served as static files by `python3 -m http.server`: spineboy walks (the stand-in
// skeleton), the real pointer moves over the canvas along a circle around the fist, and after
// every frame the front fist's tip is on the pointer within 1e-3 (measured on the skeleton's own
// world numbers, not the add-on's report), the rear foot's tip (pinned) within 1e-3 of where the
// walk put it, every bone outside the moved limbs exactly as the walk left it; an unreachable
// pointer is reported at its distance; the page logs no error. Saves target/e2e/spine-demo.png,
// and docs/src/images/spine-demo.png with IKARUS_DOCS_PICTURES=1.
//
//   IKARUS_WEB_DIR=DIR node --test web/spine-demo.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import { copyFileSync, mkdirSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";
import { artifacts, launch, openPage, staticServer } from "../e2e/browser.mjs";

const root = join(dirname(fileURLToPath(import.meta.url)), "..");
const dir = process.env.IKARUS_WEB_DIR;
if (!dir) throw new Error("IKARUS_WEB_DIR: the directory `bash web/build DIR` wrote");

test("the demo page: spineboy's fist follows the real pointer within 1e-3, the rest of the body as the walk left it", async () => {
  mkdirSync(artifacts, { recursive: true });
  const host = await staticServer(dir);
  const browser = await launch();
  try {
    const { page, errors } = await openPage(browser, { width: 900, height: 800 });
    await page.goto(`${host.url}/spine-demo.html?still`);
    await page.waitForFunction(() => window.spineDemo && window.spineDemo.ready, null, { timeout: 20000 });
    const canvasBox = await page.locator("canvas").boundingBox();
    // The circle: about the point 0.55 of the arm's reach from the shoulder toward the fist's
    // tip as the walk puts it 0.25 s in, of radius 0.25 of the reach; the pointer beyond it
    // once at the end (unreachable).
    const { centre, radius, reach } = await page.evaluate(() => {
      const d = window.spineDemo;
      for (let i = 0; i < 15; i++) d.step(1 / 60);
      const reach = ["front-upper-arm", "front-bracer", "front-fist"].reduce((s, n) => s + d.skeleton.findBone(n).data.length, 0);
      const [tx, ty] = d.tip(d.fist);
      const { worldX: sx, worldY: sy } = d.shoulder;
      const l = Math.hypot(tx - sx, ty - sy);
      return { centre: [sx + (0.55 * reach * (tx - sx)) / l, sy + (0.55 * reach * (ty - sy)) / l], radius: 0.25 * reach, reach };
    });
    let checked = 0;
    let worst = { fist: 0, foot: 0 };
    for (let k = 0; k < 40; k++) {
      const a = (2 * Math.PI * k) / 40;
      const world = [centre[0] + radius * Math.cos(a), centre[1] + radius * Math.sin(a)];
      const [cx, cy] = await page.evaluate(([x, y]) => window.spineDemo.toCanvas(x, y), world);
      const r = await page.evaluate(() => devicePixelRatio);
      await page.mouse.move(canvasBox.x + cx / r, canvasBox.y + cy / r);
      const got = await page.evaluate(() => {
        const d = window.spineDemo;
        d.step(1 / 60);
        // The rear foot's tip against where the walk put it this frame (before the add-on).
        const foot = d.tip(d.skeleton.findBone("rear-foot"));
        const footOff = Math.hypot(foot[0] - d.pinnedAt[0], foot[1] - d.pinnedAt[1]);
        // Every bone outside the moved limbs (the bones the report says it turned, and what
        // hangs below them) keeps the runtime's world numbers exactly.
        const arm = new Set();
        const turned = new Set(d.report.moved);
        for (const b of d.skeleton.bones) if (turned.has(b.data.name) || arm.has(b.parent)) arm.add(b);
        let changed = null;
        d.skeleton.bones.forEach((b, i) => {
          const now = [b.a, b.b, b.c, b.d, b.worldX, b.worldY];
          if (!arm.has(b) && now.some((v, k) => v !== d.before[6 * i + k])) changed = b.data.name;
        });
        const shoulderOff = Math.hypot(d.pointer[0] - d.shoulder.worldX, d.pointer[1] - d.shoulder.worldY);
        return { pointer: d.pointer, fist: d.tip(d.fist), footOff, shoulderOff, changed, moved: [...d.report.moved], report: d.report.goals[0]?.error ?? null };
      });
      assert.ok(got.pointer, "the page saw the pointer");
      assert.equal(got.changed, null, `frame ${k}: a bone outside the moved limbs moved`);
      assert.ok(got.moved.includes("front-bracer"), `frame ${k}: moved ${got.moved}`);
      const off = Math.hypot(got.fist[0] - got.pointer[0], got.fist[1] - got.pointer[1]);
      // Reachable: within 0.9 of the arm's reach from the shoulder (the walk moves the shoulder).
      if (got.shoulderOff <= 0.9 * reach) {
        checked++;
        worst.fist = Math.max(worst.fist, off);
        assert.ok(off <= 1e-3, `frame ${k}: the fist's tip is ${off} from the pointer (${got.pointer})`);
        assert.ok(got.report !== null && got.report <= 1e-3, `frame ${k}: the report's error ${got.report}`);
      }
      worst.foot = Math.max(worst.foot, got.footOff);
      assert.ok(got.footOff <= 1e-3, `frame ${k}: the rear foot's tip moved ${got.footOff} from where the walk put it`);
    }
    assert.ok(checked >= 30, `only ${checked} of 40 pointer positions were reachable`);
    // Beyond reach: the arm points at the pointer, the report says how far the tip is from it.
    {
      const far = [centre[0] + 3 * reach, centre[1]];
      const [cx, cy] = await page.evaluate(([x, y]) => window.spineDemo.toCanvas(x, y), far);
      const r = await page.evaluate(() => devicePixelRatio);
      await page.mouse.move(canvasBox.x + Math.min(cx / r, canvasBox.width - 1), canvasBox.y + cy / r);
      const got = await page.evaluate(() => {
        const d = window.spineDemo;
        d.step(1 / 60);
        const t = d.tip(d.fist);
        return { off: Math.hypot(t[0] - d.pointer[0], t[1] - d.pointer[1]), report: d.report.goals[0].error };
      });
      assert.ok(got.off > 1 && Math.abs(got.report - got.off) < 1e-6, `unreachable: ${JSON.stringify(got)}`);
    }
    // A still frame for the picture: the pointer up and forward of the fist.
    const [cx, cy] = await page.evaluate(([x, y]) => window.spineDemo.toCanvas(x, y), [centre[0] + 0.2 * reach, centre[1] + 0.15 * reach]);
    const r = await page.evaluate(() => devicePixelRatio);
    await page.mouse.move(canvasBox.x + cx / r, canvasBox.y + cy / r);
    const readout = await page.evaluate(async () => {
      const d = window.spineDemo;
      for (let i = 0; i < 300; i++) d.step(0);
      d.draw();
      return document.getElementById("readout").textContent;
    });
    const shot = join(artifacts, "spine-demo.png");
    await page.screenshot({ path: shot });
    if (process.env.IKARUS_DOCS_PICTURES) copyFileSync(shot, join(root, "docs", "src", "images", "spine-demo.png"));
    console.log(`spine demo: ${checked} reachable pointer positions, fist off the pointer at most ${worst.fist.toExponential(2)}, rear foot ${worst.foot.toExponential(2)}; readout: ${readout}`);
    assert.deepEqual(errors, []);
  } finally {
    await browser.close();
    host.child.kill();
  }
});
