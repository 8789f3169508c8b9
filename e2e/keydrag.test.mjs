// Key mode as an animator uses it on a character (issue 44, points 5 and 6), in a real browser.
// spineboy: both feet keyed at 0 and 0.6 s and the front knee's bend flipped at 0.3 s; at 0.3 s
// a drag of the front foot poses with every key applied: during the drag and after the drop the
// rear foot stays on its keyed place (within 1e-3) and the front knee on its keyed side, and the
// key lands where the foot was dropped. Then the keyed motion runs to the Length (2 s, past the
// last key at 0.6 s): 61 frames, playback passes 0.6 s, Loop plays it again from the start, and
// `.`, `,` and the arrow keys step exactly one frame. Screenshots go to $E2E_ARTIFACTS.
// Run by e2e/run:  node --test e2e/keydrag.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import { mkdirSync, readFileSync } from "node:fs";
import { join } from "node:path";
import { artifacts, openPage, ready, withBrowser } from "./browser.mjs";
import { characterSettled, dragTarget, targetAt } from "./charpage.mjs";

const file = join(import.meta.dirname, "..", "examples", "characters", "spine-spineboy-pro.json");

/** The side the front shin turns from the front thigh in `bones` (/api/pose's): "ccw" or "cw". */
function kneeSide(bones) {
  const at = (n) => bones.find((b) => b.name === n);
  return Math.sin(((at("front-shin").rotation_deg - at("front-thigh").rotation_deg) * Math.PI) / 180) >= 0 ? "ccw" : "cw";
}

const origin = (bones, name) => {
  const b = bones.find((x) => x.name === name);
  return [b.x, b.y];
};

async function dragBy(page, name, by) {
  const at = await targetAt(page, name);
  await dragTarget(page, at, [at[0] + by[0], at[1] + by[1]]);
}

async function seek(page, t) {
  await page.evaluate((s) => window.ikarus.keys.seek(s), t);
  await characterSettled(page);
}

const keyFrame = (page) => page.evaluate(() => Number(document.body.dataset.keyFrame));

test("spineboy in Key mode: a drag poses with every key applied, the key lands where dropped; the motion runs to its Length, loops and steps by frames", async () => {
  mkdirSync(artifacts, { recursive: true });
  await withBrowser(async ({ url, browser }) => {
    const { page, errors } = await openPage(browser);
    await page.goto(url);
    await ready(page);
    await page.setInputFiles("#rig-file", { name: "spineboy.json", mimeType: "application/json", buffer: readFileSync(file) });
    await page.waitForFunction(() => window.ikarus.state.character && window.ikarus.state.character.posed, null, { timeout: 15000 });
    await characterSettled(page);
    await page.click("#key-mode");

    // Both feet keyed at 0 and 0.6 s, the front knee flipped at 0.3 s.
    await dragBy(page, "front-leg-target", [10, 0]);
    await dragBy(page, "rear-leg-target", [-10, 0]);
    await seek(page, 0.6);
    await dragBy(page, "front-leg-target", [40, 50]);
    await dragBy(page, "rear-leg-target", [-60, 40]);
    await seek(page, 0.3);
    const handle = await page.evaluate(() => {
      const h = window.ikarus.keys.handles().find((x) => x.bone === "front-shin");
      const r = document.getElementById("plot").getBoundingClientRect();
      return { side: h.side, at: [r.left + h.at[0], r.top + h.at[1]] };
    });
    await page.mouse.click(...handle.at);
    await characterSettled(page);
    const flipped = handle.side === "ccw" ? "cw" : "ccw";
    assert.equal((await page.evaluate(() => window.ikarus.state.keys)).bends["front-shin"].at(-1).bend, flipped);

    // The frame at 0.3 s: the rear foot's keyed place and the knee's keyed side.
    const frame = await page.evaluate(() => window.ikarus.state.motion.frames[9].bones);
    const rear = origin(frame, "rear-leg-target");
    assert.equal(kneeSide(frame), flipped);

    // A drag of the front foot, held: every pose on the way keeps the other keys.
    const front = origin(frame, "front-leg-target");
    const goal = [front[0] + 30, front[1] - 25];
    const from = await page.evaluate(([x, y]) => window.ikarus.toClient(x, y), front);
    const to = await page.evaluate(([x, y]) => window.ikarus.toClient(x, y), goal);
    await page.mouse.move(...from);
    await page.mouse.down();
    await page.mouse.move(...to, { steps: 6 });
    await characterSettled(page);
    const during = await page.evaluate(() => ({ posed: window.ikarus.state.character.posed, poses: window.ikarus.state.character.poses }));
    await page.screenshot({ path: join(artifacts, "keydrag-during.png") });
    const d = Math.hypot(...origin(during.posed, "rear-leg-target").map((v, k) => v - rear[k]));
    assert.ok(d < 1e-3, `during the drag the rear foot is ${d} from its key at ${rear}`);
    assert.equal(kneeSide(during.posed), flipped, "during the drag the front knee stays on its keyed side");
    const dropped = await page.evaluate(() => window.ikarus.state.character.targets.get("front-leg-target"));
    assert.ok(Math.hypot(...origin(during.posed, "front-leg-target").map((v, k) => v - [dropped.x, dropped.y][k])) < 1e-6, "the dragged foot is where the pointer is");
    await page.mouse.up();
    await characterSettled(page);

    // After the drop: the key is where the foot was dropped, the rear foot and the knee hold.
    const keys = await page.evaluate(() => window.ikarus.state.keys);
    const key = keys.tracks["front-leg-target"].find((q) => q.time === 0.3);
    assert.ok(key, `a key at 0.3 s: ${JSON.stringify(keys.tracks["front-leg-target"])}`);
    assert.ok(Math.hypot(key.x - dropped.x, key.y - dropped.y) < 1e-9, `the key at ${key.x}, ${key.y}, dropped at ${dropped.x}, ${dropped.y}`);
    const after = await page.evaluate(() => window.ikarus.state.character.posed);
    assert.ok(Math.hypot(...origin(after, "rear-leg-target").map((v, k) => v - rear[k])) < 1e-3, "after the drop the rear foot stays on its key");
    assert.ok(Math.hypot(...origin(after, "front-leg-target").map((v, k) => v - [key.x, key.y][k])) < 1e-6, "after the drop the front foot is on its new key");
    assert.equal(kneeSide(after), flipped);
    await page.screenshot({ path: join(artifacts, "keydrag-dropped.png") });

    // The motion runs to the Length (2 s) past the last key (0.6 s).
    const motion = await page.evaluate(() => ({ n: window.ikarus.state.motion.frames.length, last: window.ikarus.state.motion.frames.at(-1).time }));
    assert.deepEqual(motion, { n: 61, last: 2 });
    assert.equal(await page.evaluate(() => window.ikarus.keys.sent().duration), 2);
    await page.fill("#key-length", "1");
    await page.dispatchEvent("#key-length", "change");
    await characterSettled(page);
    assert.equal(await page.evaluate(() => window.ikarus.state.motion.frames.length), 31, "Length 1 s: 31 frames");
    await seek(page, 0);
    await page.click("#play");
    await page.waitForFunction(() => Number(document.body.dataset.keyFrame) > 24, null, { timeout: 20000 });
    await page.waitForFunction(() => document.body.dataset.playback === "ended", null, { timeout: 20000 });
    assert.equal(await keyFrame(page), 30, "played to the Length's frame");

    // Loop: it plays on from the start.
    await page.check("#loop");
    await page.click("#play");
    await page.waitForFunction(() => Number(document.body.dataset.loops || 0) >= 1, null, { timeout: 20000 });
    assert.equal(await page.evaluate(() => document.body.dataset.playback), "playing", "looping, it does not stop at the end");
    await page.click("#play");
    await page.uncheck("#loop");

    // Stepping: one frame at a time, in Key mode and out.
    await seek(page, 0.5);
    assert.equal(await keyFrame(page), 15);
    await page.focus("#plot");
    await page.keyboard.press(".");
    assert.equal(await keyFrame(page), 16);
    await page.keyboard.press(",");
    await page.keyboard.press(",");
    assert.equal(await keyFrame(page), 14);
    await page.click("#key-mode");
    assert.equal(await page.getAttribute("#key-mode", "aria-pressed"), "false");
    await page.focus("#plot");
    await page.keyboard.press("ArrowRight");
    assert.equal(await keyFrame(page), 15);
    await page.keyboard.press("ArrowLeft");
    assert.equal(await keyFrame(page), 14);
    assert.match(await page.textContent("#playtime"), /^0\.47 \/ 1\.00 s$/);
    assert.deepEqual(errors, []);
  });
});
