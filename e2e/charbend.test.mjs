// A character's bend handles (issue 28, point 4, for imported characters), in a real browser:
// spineboy in Key mode shows a handle beside each knee of its two-bone IK constraints
// (front-leg-ik, rear-leg-ik), on the side the knee bends; its front foot target keyed at 0 and
// 0.6 s; a click on the front knee's handle at 0.3 s keys the other side there (`keys.bends`);
// every frame from 0.3 s on has the knee on that side (the shin turned that way from the thigh),
// the frames before the side it had; and the page's frames are `ikarus animate --rig
// spineboy.json --keys … --format json`'s, number for number. Screenshots go to $E2E_ARTIFACTS.
// Run by e2e/run:  node --test e2e/charbend.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { mkdirSync, readFileSync, writeFileSync } from "node:fs";
import { join } from "node:path";
import { artifacts, binary, openPage, ready, withBrowser } from "./browser.mjs";
import { characterSettled, dragTarget, targetAt } from "./charpage.mjs";

const file = join(import.meta.dirname, "..", "examples", "characters", "spine-spineboy-pro.json");

/** The side the shin turns from the thigh in `bones` (/api/pose's): "ccw" or "cw". */
function kneeSide(bones) {
  const at = (n) => bones.find((b) => b.name === n);
  return Math.sin(((at("front-shin").rotation_deg - at("front-thigh").rotation_deg) * Math.PI) / 180) >= 0 ? "ccw" : "cw";
}

/** Drags the character's target `name` by `by` (world units) at the playhead, and waits. */
async function dragBy(page, name, by) {
  const at = await targetAt(page, name);
  await dragTarget(page, at, [at[0] + by[0], at[1] + by[1]]);
}

test("spineboy: a knee's bend handle keys the other side at the playhead, and the frames are the CLI's", async () => {
  mkdirSync(artifacts, { recursive: true });
  await withBrowser(async ({ url, browser }) => {
    const text = readFileSync(file, "utf8");
    const { page, errors } = await openPage(browser);
    await page.goto(url);
    await ready(page);
    await page.setInputFiles("#rig-file", { name: "spineboy.json", mimeType: "application/json", buffer: Buffer.from(text) });
    await page.waitForFunction(() => window.ikarus.state.character && window.ikarus.state.character.posed, null, { timeout: 15000 });
    await characterSettled(page);
    // No handles outside Key mode; in it, one per two-bone constraint, at its lower bone.
    assert.deepEqual(await page.evaluate(() => window.ikarus.keys.handles()), []);
    await page.click("#key-mode");
    const handles = await page.evaluate(() => window.ikarus.keys.handles().map((h) => [h.bone, h.side]));
    const posed = await page.evaluate(() => window.ikarus.state.character.posed);
    assert.deepEqual(handles.map((h) => h[0]).sort(), ["front-shin", "rear-shin"]);
    assert.equal(Object.fromEntries(handles)["front-shin"], kneeSide(posed), "the handle says the side the knee bends");

    await dragBy(page, "front-leg-target", [10, 0]);
    await page.evaluate(() => window.ikarus.keys.seek(0.6));
    await characterSettled(page);
    await dragBy(page, "front-leg-target", [40, 50]);
    const first = await page.evaluate(() => window.ikarus.state.motion.frames[0].bones);
    const start = kneeSide(first);

    // At 0.3 s, a click on the front knee's handle.
    await page.evaluate(() => window.ikarus.keys.seek(0.3));
    await characterSettled(page);
    const handle = await page.evaluate(() => {
      const h = window.ikarus.keys.handles().find((x) => x.bone === "front-shin");
      const r = document.getElementById("plot").getBoundingClientRect();
      return { side: h.side, at: [r.left + h.at[0], r.top + h.at[1]] };
    });
    await page.mouse.move(...handle.at);
    await page.screenshot({ path: join(artifacts, "charbend-hover.png") });
    await page.mouse.click(...handle.at);
    await characterSettled(page);
    const flipped = handle.side === "ccw" ? "cw" : "ccw";
    const keys = await page.evaluate(() => window.ikarus.state.keys);
    assert.deepEqual(keys.bends["front-shin"], [
      { time: 0, bend: start },
      { time: 0.3, bend: flipped },
    ]);
    const frames = await page.evaluate(() => window.ikarus.state.motion.frames);
    assert.equal(frames.length, 61, "to the Length (2 s), past the last key at 0.6 s");
    frames.forEach((f, i) => assert.equal(kneeSide(f.bones), i >= 9 ? flipped : start, `frame ${i} (${f.time} s): the knee's side`));
    const shown = await page.evaluate(() => window.ikarus.state.character.posed);
    assert.equal(kneeSide(shown), flipped, "the frame shown has the knee flipped");
    await page.screenshot({ path: join(artifacts, "charbend-flipped.png") });

    // The same keys through the command line: the same frames, every number.
    const keysFile = join(artifacts, "charbend-keys.json");
    writeFileSync(keysFile, JSON.stringify({ ...keys, duration: 2 }));
    const cli = JSON.parse(execFileSync(binary, ["animate", "--rig", file, "--keys", keysFile, "--format", "json"], { encoding: "utf8", stdio: ["ignore", "pipe", "ignore"] }));
    assert.deepStrictEqual(frames, cli.frames);
    assert.deepEqual(errors, []);
  });
});
