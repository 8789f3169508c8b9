// Issue 28's "done means", one flow in a real browser, as an animator works: on the puppet, Key
// mode on, a walk keyed by real drags (two feet and two hands over four keys each); the last key
// edits undone (Ctrl-Z) and redone (Ctrl-Shift-Z), the keys checked each time; the hand rig
// chosen and zoomed ×20 about a fingertip with the wheel, the fingertip dragged (its key is the
// world point under the pointer); the puppet chosen again, its keys and motion still there (the
// page keeps each rig's work); a knee flipped with its bend handle (its angle changes sign at the
// playhead, the foot still on its key); the project saved, the page reloaded (the unsaved-work
// warning seen), the file opened, and the keyed motion's frames the same, every number of every
// frame. Screenshots of each stage go to $E2E_ARTIFACTS. Run: cd e2e && node --test animator.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import { mkdirSync, readFileSync } from "node:fs";
import { join } from "node:path";
import { artifacts, reloadUnsaved, withBrowser } from "./browser.mjs";
import { TIMES, TOLERANCE, WALK, flipBend, keyWalk, keyingPuppet, keysSettled, seek, side, tipClient, worldAt } from "./rigpage.mjs";

/** The keys and the keyed motion's frames as the page holds them (plain JSON). */
const work = (page) => page.evaluate(() => JSON.parse(JSON.stringify({ keys: window.ikarus.state.keys, frames: window.ikarus.state.motion && window.ikarus.state.motion.frames })));

/** Presses `keys` with the focus on the canvas (outside any field) and waits for the motion. */
async function press(page, keys) {
  await page.focus("#plot");
  await page.keyboard.press(keys);
  await keysSettled(page);
}

test("the animator's flow: a walk keyed on the puppet, undone and redone, the hand zoomed and keyed, a knee flipped, saved, reloaded and opened with the same frames", async () => {
  mkdirSync(artifacts, { recursive: true });
  const shot = (page, name) => page.screenshot({ path: join(artifacts, `animator-${name}.png`) });
  await withBrowser(async ({ url, browser }) => {
    // The walk, keyed by dragging the four effectors at each key time; the keys after each drag kept.
    const { page, errors } = await keyingPuppet(browser, url);
    const after = [];
    await keyWalk(page, async () => after.push((await work(page)).keys));
    const walked = await work(page);
    assert.deepEqual(Object.keys(walked.keys.tracks).sort(), Object.keys(WALK).sort());
    for (const [bone, targets] of Object.entries(WALK)) {
      assert.deepEqual(
        walked.keys.tracks[bone].map((q) => q.time),
        TIMES,
      );
      walked.keys.tracks[bone].forEach((q, k) => assert.ok(Math.hypot(q.x - targets[k][0], q.y - targets[k][1]) < 1e-6, `${bone} key ${k} at ${q.x}, ${q.y}, dragged to ${targets[k]}`));
    }
    assert.equal(walked.frames.length, 61, "frames 0 to 60 at 30 fps: to the Length, 2 s");
    await shot(page, "1-walk");

    // The last three key edits undone one by one, the keys as they were before each; redone.
    const n = after.length;
    for (let u = 1; u <= 3; u++) {
      await press(page, "Control+z");
      assert.deepEqual((await work(page)).keys, after[n - 1 - u], `undo ${u}: the keys before the edit`);
    }
    assert.equal(walked.keys.tracks.left_hand.length - (await work(page)).keys.tracks.left_hand.length, 1, "the left hand's last key undone");
    await shot(page, "2-undone");
    for (let u = 2; u >= 0; u--) {
      await press(page, "Control+Shift+z");
      assert.deepEqual((await work(page)).keys, after[n - 1 - u], `redo back to ${3 - u} edits undone`);
    }
    assert.deepEqual(await work(page), walked, "redone: the same keys and the same frames");

    // The hand rig, zoomed ×20 about the index fingertip (whole pixels: the browser's events
    // carry whole pixels), the tip dragged 10 pixels: its key is the world point under the pointer.
    await page.selectOption("#body-kind", "rig:hand");
    await page.waitForFunction(() => window.ikarus.state.rig.rig.name === "hand");
    await keysSettled(page);
    const tip = (await tipClient(page, "index_distal")).map(Math.round);
    await page.mouse.move(...tip);
    for (let k = 0; k < 15; k++) await page.mouse.wheel(0, -100);
    await page.waitForFunction(() => Number(document.getElementById("plot").dataset.zoom) > 20, null, { timeout: 5000 });
    const to = [tip[0] + 6, tip[1] - 8];
    await page.mouse.down();
    await page.mouse.move(tip[0] + 3, tip[1] - 4);
    await page.mouse.move(...to);
    const want = await worldAt(page, ...to);
    await page.mouse.up();
    await keysSettled(page);
    const handKeys = (await work(page)).keys;
    assert.deepEqual(Object.keys(handKeys.tracks), ["index_distal"]);
    const [key] = handKeys.tracks.index_distal;
    const d = Math.max(Math.abs(key.x - want[0]), Math.abs(key.y - want[1]));
    assert.ok(d <= 1e-9 * Math.max(Math.abs(want[0]), Math.abs(want[1])), `the key at ${key.x}, ${key.y}; the pointer over ${want}`);
    const goal = await page.evaluate(() => window.ikarus.state.rig.goals.get("index_distal"));
    assert.deepEqual([goal.x, goal.y], [key.x, key.y], "the goal shown is the key");
    await shot(page, "3-hand-zoomed");

    // The puppet again: its keys and its motion as they were left.
    await page.selectOption("#body-kind", "rig:puppet");
    await page.waitForFunction(() => window.ikarus.state.rig.rig.name === "puppet" && window.ikarus.state.motion);
    await keysSettled(page);
    assert.deepEqual(await work(page), walked, "the puppet's keys and frames kept while the hand was shown");
    await shot(page, "4-puppet-back");

    // The left knee flipped by its bend handle at 0.8 s (limits off: with them the puppet's
    // knees bend one way only): its angle changes sign there, the foot still on its key.
    await page.click("#limits");
    await keysSettled(page);
    await seek(page, 0.8);
    const { before, after: flippedShown } = await flipBend(page, "left_shin");
    const knee = before.frame.angles_deg.left_shin;
    const knee2 = flippedShown.frame.angles_deg.left_shin;
    assert.ok(Math.abs(knee) > 5, `the left knee is bent at 0.8 s (${knee}°)`);
    assert.ok(side(knee2) !== side(knee) && Math.abs(knee2) > 5, `the left knee flipped at 0.8 s: ${knee}° → ${knee2}°`);
    const [fx, fy] = WALK.left_foot[2];
    const foot = flippedShown.frame.joints.left_foot;
    assert.ok(Math.hypot(foot[0] - fx, foot[1] - fy) < TOLERANCE, `the foot on its key after the flip: ${foot}`);
    await shot(page, "5-knee-flipped");
    const final = await work(page);
    assert.ok(final.keys.bends.left_shin.some((b) => b.time === 0.8));

    // Saved (the download is the project), one more edit, reloaded: the page warns.
    const [download] = await Promise.all([page.waitForEvent("download"), page.click("#save-project")]);
    const saved = readFileSync(await download.path(), "utf8");
    assert.deepEqual(JSON.parse(saved).keys, final.keys);
    assert.deepEqual(await reloadUnsaved(page), { dirty: "true", dialogs: ["beforeunload"] }, "the unsaved-work warning");
    assert.equal(await page.evaluate(() => window.ikarus.state.keys), null, "a fresh page");

    // Opened: the same keys and the same frames, every number of every frame.
    await page.setInputFiles("#project-file", { name: "walk.ikarus.json", mimeType: "application/json", buffer: Buffer.from(saved) });
    await page.waitForFunction(() => window.ikarus.state.keys && window.ikarus.state.motion);
    await keysSettled(page);
    const opened = await work(page);
    assert.deepEqual(opened.keys, final.keys);
    assert.equal(opened.frames.length, final.frames.length);
    opened.frames.forEach((f, i) => assert.deepStrictEqual(f, final.frames[i], `frame ${i}`));
    await shot(page, "6-opened");
    assert.deepEqual(errors, []);
  });
});
