// The arm keyed on the playground (issue 28: "for chains, rigs and imported characters alike"),
// in a real browser: the seed arm shown, Key mode on, its tip dragged to three reachable points
// at 0, 0.4 and 0.8 s (each drag keys the tip's track, link2, at its drop point); the keyed
// motion (POST /api/animate with `arm` and `keys`) plays to its end; at each key time the drawn
// tip is on its key; the page's frames are `ikarus animate --keys FILE --format json`'s (the
// built-in seed arm) number for number, and its Frames CSV and GIF are the CLI's byte for byte; while
// its keys play, the click motions' controls (duration, ease, replay, via points) step aside, and
// come back out of Key mode; undo and redo take the last key away and back; a rig shown and the
// arm again: the same keys and frames; a saved project, opened on the reloaded page, gives the
// same keys and frames. Run by e2e/run:  node --test e2e/keyarm.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { mkdirSync, readFileSync, writeFileSync } from "node:fs";
import { join } from "node:path";
import { artifacts, binary, downloadText, openPage, ready, reloadUnsaved, withBrowser } from "./browser.mjs";

/** The keys' times and the tip's targets there (the seed arm's links are 3, 2, 1 long). */
const KEYS = [
  [0, [4, 2]],
  [0.4, [2, 4]],
  [0.8, [-1, 3.5]],
];

/** Resolves once no keyed motion is asked and no followed goal is in flight. */
const settled = (page) => page.waitForFunction(() => window.ikarus.keys.settled() && !window.ikarus.state.jobs.followBusy, null, { timeout: 60000 });

const tip = (page) => page.evaluate(() => window.ikarus.state.joints[window.ikarus.state.joints.length - 1]);

/** The arm's click-motion controls that do not apply to its keyed motion. */
const CLICK_CONTROLS = ["#duration", "#ease-plot", "#solver", "#clear-via", "#ease", "#frames", "#dl-gif"];

/** Which of CLICK_CONTROLS are visible. */
const clickControlsShown = async (page) => {
  const shown = [];
  for (const sel of CLICK_CONTROLS) if (await page.isVisible(sel)) shown.push(sel);
  return shown;
};

test("the arm: its tip keyed at three times plays through its keys, frame for frame the CLI's", async () => {
  mkdirSync(artifacts, { recursive: true });
  await withBrowser(async ({ url, browser }) => {
    const { page, errors } = await openPage(browser);
    await page.goto(url);
    await ready(page);
    assert.equal(await page.evaluate(() => !!window.ikarus.state.rig || !!window.ikarus.state.character), false, "the arm is shown");
    // Key mode from the arm's View ("Key the tip"): the keys bar shows, its Key mode pressed.
    assert.equal(await page.isVisible("#key-mode"), false, "no keys bar on the arm before Key mode");
    await page.check("#arm-key-mode");
    assert.equal(await page.getAttribute("#key-mode", "aria-pressed"), "true");
    assert.deepEqual(await clickControlsShown(page), CLICK_CONTROLS, "no keys yet: the click motions' controls stay");
    for (const [t, to] of KEYS) {
      await page.evaluate((s) => window.ikarus.keys.seek(s), t);
      await settled(page);
      const from = await page.evaluate(([x, y]) => window.ikarus.toClient(x, y), await tip(page));
      const end = await page.evaluate(([x, y]) => window.ikarus.toClient(x, y), to);
      await page.mouse.move(...from);
      await page.mouse.down();
      for (let i = 1; i <= 8; i++) await page.mouse.move(from[0] + ((end[0] - from[0]) * i) / 8, from[1] + ((end[1] - from[1]) * i) / 8);
      await page.mouse.up();
      await settled(page);
    }
    const keys = await page.evaluate(() => window.ikarus.state.keys);
    assert.deepEqual(Object.keys(keys.tracks), ["link2"], "the tip's track alone");
    const track = keys.tracks.link2;
    assert.deepEqual(
      track.map((q) => q.time),
      KEYS.map(([t]) => t),
    );
    // Each key at its drop point: the target within a pixel of the point dragged to.
    const scale = await page.evaluate(() => window.ikarus.state.view.scale);
    track.forEach((q, k) => assert.ok(Math.hypot(q.x - KEYS[k][1][0], q.y - KEYS[k][1][1]) <= 1.5 / scale, `key ${k} at ${q.x}, ${q.y}, dragged to ${KEYS[k][1]}`));

    // The motion plays to its end.
    await page.click("#play");
    await page.waitForFunction(() => document.body.dataset.playback === "ended", null, { timeout: 20000 });
    await page.screenshot({ path: join(artifacts, "keys-arm-ended.png") });
    assert.deepEqual(await clickControlsShown(page), [], "the keys play: the click motions' controls step aside");

    // At each key time the drawn tip is on its key.
    for (const [k, q] of track.entries()) {
      await page.evaluate((s) => window.ikarus.keys.seek(s), q.time);
      await settled(page);
      assert.equal(await page.evaluate(() => document.body.dataset.keyFrame), String(Math.round(q.time * keys.fps)));
      const d = await tip(page);
      assert.ok(Math.hypot(d[0] - q.x, d[1] - q.y) < 1e-3, `key ${k} at ${q.time} s: the tip drawn at ${d}, its key at ${q.x}, ${q.y}`);
      if (k === 1) await page.screenshot({ path: join(artifacts, "keys-arm-key1.png") });
    }

    // The page's frames are the CLI's for the same keys (the built-in seed arm).
    const keysFile = join(artifacts, "keys-arm.json");
    // As the page sends them: with the Length (2 s) as their duration.
    writeFileSync(keysFile, JSON.stringify({ ...keys, duration: 2 }));
    const cli = JSON.parse(execFileSync(binary, ["animate", "--keys", keysFile, "--format", "json"], { encoding: "utf8" }));
    const frames = await page.evaluate(() => window.ikarus.state.motion.frames.map(({ time, status, angles_deg, joints }) => ({ time, status, angles_deg, joints })));
    assert.equal(frames.length, Math.round(2 * keys.fps) + 1, "to the Length, past the last key at 0.8 s");
    assert.deepEqual(
      frames,
      cli.frames.map(({ time, status, angles_deg, joints }) => ({ time, status, angles_deg, joints })),
    );

    // Its Frames CSV and GIF: the CLI's, byte for byte (the arm solved as its one-branch rig; the
    // GIF at the canvas's size, as the page asks it).
    const csv = await downloadText(page, "#key-frames-csv");
    assert.equal(csv.trim().split("\n").length, frames.length + 1, "a header and a row a frame");
    assert.equal(csv, execFileSync(binary, ["animate", "--keys", keysFile, "--format", "csv"], { encoding: "utf8" }), "the page's CSV is `ikarus animate --keys … --format csv`");
    const [g] = await Promise.all([page.waitForEvent("download"), page.click("#key-gif")]);
    assert.equal(g.suggestedFilename(), "seed-keys.gif");
    const gif = readFileSync(await g.path());
    const plot = await page.evaluate(() => [document.getElementById("plot").clientWidth, document.getElementById("plot").clientHeight]);
    const gifFile = join(artifacts, "keys-arm-cli.gif");
    execFileSync(binary, ["animate", "--keys", keysFile, "--width", String(plot[0]), "--height", String(plot[1]), "--out", gifFile], { stdio: "ignore" });
    assert.equal(gif.subarray(0, 6).toString(), "GIF89a");
    assert.ok(gif.equals(readFileSync(gifFile)), `the page's GIF (${gif.length} bytes) is \`ikarus animate --keys … --width ${plot[0]} --height ${plot[1]} --out\` (${readFileSync(gifFile).length} bytes)`);

    // Undo takes the last key away (one step), redo brings it back, the motion with it.
    const motionOf = () => page.evaluate(() => window.ikarus.state.motion.frames.map(({ time, angles_deg, joints }) => ({ time, angles_deg, joints })));
    await page.evaluate(() => window.ikarus.project.undo());
    await settled(page);
    assert.deepEqual(await page.evaluate(() => window.ikarus.state.keys.tracks.link2.map((q) => q.time)), [0, 0.4]);
    const undone = await motionOf();
    assert.equal(undone.length, 61, "to the Length still");
    assert.notDeepEqual(undone, frames.map(({ time, angles_deg, joints }) => ({ time, angles_deg, joints })), "the motion without the last key");
    await page.evaluate(() => window.ikarus.project.redo());
    await settled(page);
    assert.deepEqual(await page.evaluate(() => window.ikarus.state.keys), keys);
    assert.deepEqual(await motionOf(), frames.map(({ time, angles_deg, joints }) => ({ time, angles_deg, joints })));

    // A rig shown (it has no keys of its own), then the arm again: the arm's keys and frames.
    await page.selectOption("#body-kind", "rig:puppet");
    await settled(page);
    assert.equal(await page.evaluate(() => window.ikarus.state.keys), null, "the puppet has no keys");
    assert.deepEqual(await clickControlsShown(page), [], "a rig: the arm's controls are away");
    await page.selectOption("#body-kind", "arm");
    await settled(page);
    await page.waitForFunction(() => window.ikarus.state.motion);
    assert.deepEqual(await page.evaluate(() => window.ikarus.state.keys), keys, "the arm's keys back");
    assert.deepEqual(await motionOf(), frames.map(({ time, angles_deg, joints }) => ({ time, angles_deg, joints })));
    await page.evaluate((s) => window.ikarus.keys.seek(s), 0.4);
    await settled(page);
    const back = await tip(page);
    assert.ok(Math.hypot(back[0] - track[1].x, back[1] - track[1].y) < 1e-3, `back on the arm at 0.4 s: the tip drawn at ${back}`);
    assert.deepEqual(await clickControlsShown(page), [], "its keys play again");
    await page.screenshot({ path: join(artifacts, "keys-arm-back.png") });
    // Out of Key mode the click motions take the timeline again, their controls with them.
    await page.uncheck("#arm-key-mode");
    assert.deepEqual(await clickControlsShown(page), CLICK_CONTROLS, "Key mode off: the click motions' controls are back");
    const chip = () => page.evaluate(() => document.getElementById("stats").textContent);
    assert.equal(await chip(), "Key mode off · the arm's keys kept · a click moves the arm");
    await page.screenshot({ path: join(artifacts, "keys-arm-keymode-off.png") });
    await page.check("#arm-key-mode");
    assert.deepEqual(await clickControlsShown(page), []);
    assert.equal(await chip(), `keyed motion · ${frames.length} frames at 30 fps · ${frames.length} reached`, "Key mode on: the keyed motion's line again");

    // Saved, the page reloaded, the file opened: the same keys and the same frames.
    const [d] = await Promise.all([page.waitForEvent("download"), page.click("#save-project")]);
    const saved = readFileSync(await d.path(), "utf8");
    assert.deepEqual(JSON.parse(saved).keys, keys);
    assert.deepEqual((await reloadUnsaved(page)).dialogs, ["beforeunload"]);
    assert.equal(await page.evaluate(() => window.ikarus.state.keys), null, "a fresh page");
    await page.setInputFiles("#project-file", { name: "arm.ikarus.json", mimeType: "application/json", buffer: Buffer.from(saved) });
    await page.waitForFunction(() => /^opened/.test(document.getElementById("stats").textContent) || window.ikarus.state.motion);
    await settled(page);
    await page.waitForFunction(() => window.ikarus.state.motion);
    assert.deepEqual(await page.evaluate(() => window.ikarus.state.keys), keys);
    assert.deepEqual(await motionOf(), frames.map(({ time, angles_deg, joints }) => ({ time, angles_deg, joints })));
    assert.deepEqual(errors, []);
  });
});
