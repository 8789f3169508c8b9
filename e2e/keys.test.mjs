// Keyframes in the playground (issue 28), in a real browser: on the puppet, Key mode on, both
// feet and both hands keyed over four keys each by dragging them at the playhead (a walk-like
// cycle: the feet alternating forward and back, the hands swinging against them); the keyed
// motion (POST /api/animate with `keys`) plays to its end; at every key time the drawn pose has
// each effector on its key (the answer's `joints`, and the tips drawn); a knee's bend handle
// flips the knee at the playhead (limits off: the puppet's knees bend one way), and the knee's
// angle changes sign there and stays on that side after while the foot still reaches; the
// frames' CSV is the CLI's; a click pins the head for the whole animation. Then spineboy: its
// front foot target keyed over `walk` (four keys), its frames CSV and GIF the CLI's bytes, and
// exported as Spine JSON. Screenshots go to
// $E2E_ARTIFACTS. Run by e2e/run:  node --test e2e/keys.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { mkdirSync, readFileSync, writeFileSync } from "node:fs";
import { join } from "node:path";
import { artifacts, binary, openPage, ready, withBrowser } from "./browser.mjs";
import { characterSettled, dragTarget, targetAt } from "./charpage.mjs";
import { ROW, rowAxis } from "../crates/ikarus-cli/src/serve/assets/drawkeys.js";
import { bodyForward } from "../crates/ikarus-cli/src/serve/assets/body.js";
import { TIMES, TOLERANCE, WALK, flipBend, keyWalk, keyingPuppet, keysSettled as settled, seek, shown, side, tipClient } from "./rigpage.mjs";

test("the puppet: a walk keyed on both feet and both hands plays with every effector on its keys; a knee's bend handle flips it", async () => {
  const dir = artifacts;
  mkdirSync(dir, { recursive: true });
  await withBrowser(async ({ url, browser }) => {
    const { page, errors } = await keyingPuppet(browser, url);
    assert.equal(await page.getAttribute("#key-mode", "aria-pressed"), "true");
    await keyWalk(page);
    const keys = await page.evaluate(() => window.ikarus.state.keys);
    assert.deepEqual(Object.keys(keys.tracks).sort(), Object.keys(WALK).sort());
    for (const [bone, targets] of Object.entries(WALK)) {
      assert.deepEqual(
        keys.tracks[bone].map((q) => q.time),
        TIMES,
        `${bone}: the keys' times`,
      );
      keys.tracks[bone].forEach((q, k) => assert.ok(Math.hypot(q.x - targets[k][0], q.y - targets[k][1]) < 1e-6, `${bone} key ${k} at ${q.x}, ${q.y}, dragged to ${targets[k]}`));
    }
    const motion = await page.evaluate(() => ({ fps: window.ikarus.state.motion.fps, n: window.ikarus.state.motion.frames.length, times: window.ikarus.state.motion.frames.map((f) => f.time) }));
    assert.equal(motion.fps, 30);
    assert.equal(motion.n, 61, "frames 0 to 60: the keys end at 1.2 s, the motion runs to the Length, 2 s");
    motion.times.forEach((t, k) => assert.equal(t, k / 30));
    // The rows: one per keyed effector, four diamonds each.
    await page.screenshot({ path: join(dir, "keys-puppet-walk.png") });

    // Played to its end; the timeline spans the Length, or the keys when they run longer.
    assert.match(await page.textContent("#playtime"), / \/ 2\.00 s$/);
    await page.fill("#key-length", "1");
    await page.dispatchEvent("#key-length", "change");
    assert.match(await page.textContent("#playtime"), / \/ 1\.20 s$/);
    await page.click("#play");
    await page.waitForFunction(() => document.body.dataset.playback === "ended", null, { timeout: 20000 });
    assert.equal(await page.textContent("#playtime"), "1.20 / 1.20 s");
    await page.fill("#key-length", "2");
    await page.dispatchEvent("#key-length", "change");

    // At every key time, every effector drawn on its key.
    for (let k = 0; k < TIMES.length; k++) {
      await seek(page, TIMES[k]);
      const s = await shown(page);
      assert.equal(s.index, Math.round(TIMES[k] * 30));
      for (const [bone, targets] of Object.entries(WALK)) {
        const [x, y] = targets[k];
        const j = s.frame.joints[bone];
        assert.ok(Math.hypot(j[0] - x, j[1] - y) < TOLERANCE, `${bone} at ${TIMES[k]} s: the answer has it at ${j}, its key at ${targets[k]}`);
        const d = s.tips[bone];
        assert.ok(Math.hypot(d[0] - x, d[1] - y) < TOLERANCE, `${bone} at ${TIMES[k]} s: drawn at ${d}, its key at ${targets[k]}`);
      }
    }

    // Editing on the rows (tracks in bone order: left_hand first): the left hand's key at 0.4 s
    // dragged to 0.5 s, copied to 1.6 s and that copy deleted, then eased linear.
    const box = await page.locator("#key-rows").boundingBox();
    const inner = await page.evaluate(() => {
      const c = document.getElementById("key-rows");
      return { w: c.clientWidth, left: c.clientLeft, top: c.clientTop };
    });
    const axis = rowAxis(inner.w, 2);
    const onRow = (t, r) => [box.x + inner.left + axis.x(t), box.y + inner.top + r * ROW.height + ROW.height / 2];
    const hand = () => page.evaluate(() => window.ikarus.state.keys.tracks.left_hand.map((q) => ({ time: q.time, ease: q.ease })));
    await page.mouse.move(...onRow(0.4, 0));
    await page.mouse.down();
    await page.mouse.move(...onRow(0.5, 0), { steps: 4 });
    await page.mouse.up();
    await settled(page);
    assert.deepEqual(
      (await hand()).map((q) => q.time),
      [0, 0.5, 0.8, 1.2],
      "moved to 0.5 s",
    );
    await page.keyboard.press("Control+C");
    await seek(page, 1.6);
    await page.keyboard.press("Control+V");
    await settled(page);
    assert.deepEqual(
      (await hand()).map((q) => q.time),
      [0, 0.5, 0.8, 1.2, 1.6],
      "pasted at 1.6 s",
    );
    assert.equal(await page.evaluate(() => window.ikarus.state.motion.frames.length), 61, "the motion runs to the Length past the pasted key");
    await page.keyboard.press("Delete");
    await settled(page);
    assert.deepEqual(
      (await hand()).map((q) => q.time),
      [0, 0.5, 0.8, 1.2],
      "the pasted key deleted",
    );
    await page.mouse.click(...onRow(0.5, 0));
    await page.selectOption("#key-ease", "linear");
    await settled(page);
    assert.equal((await hand())[1].ease, "linear");
    assert.equal(await page.evaluate(() => window.ikarus.state.motion.frames.length), 61);

    // The knee flipped by its bend handle (limits off: the puppet's knees bend one way only with
    // them; without them the lifted foot's knee bends whichever way the solve takes it).
    await page.click("#limits");
    await settled(page);
    const start = await page.evaluate(() => window.ikarus.state.motion.frames[0].angles_deg.left_shin);
    await seek(page, 0.8);
    const { before, after, handle } = await flipBend(page, "left_shin", () => page.screenshot({ path: join(dir, "keys-puppet-bend-hover.png") }));
    const knee = before.frame.angles_deg.left_shin;
    assert.ok(Math.abs(knee) > 5, `the left knee is bent at 0.8 s (${knee}°)`);
    assert.equal(handle.side, side(knee), "the handle says the side the knee bends");
    const flipped = side(knee) === "ccw" ? "cw" : "ccw";
    const keys2 = await page.evaluate(() => window.ikarus.state.keys);
    assert.deepEqual(keys2.bends.left_shin, [
      { time: 0, bend: side(start) },
      { time: 0.8, bend: flipped },
    ]);
    const knee2 = after.frame.angles_deg.left_shin;
    assert.ok(Math.sign(knee2) === -Math.sign(knee) && Math.abs(knee2) > 5, `the left knee flipped at 0.8 s: ${knee}° → ${knee2}°`);
    const frames = await page.evaluate(() => window.ikarus.state.motion.frames.map((f) => f.angles_deg.left_shin));
    // Every frame's knee within the half-turn its bend key holds (ccw [0°, 180°], cw [−180°, 0°]).
    frames.forEach((a, i) => {
      const want = i >= 24 ? flipped : side(start);
      assert.ok(want === "ccw" ? a >= 0 : a <= 0, `frame ${i}: the knee at ${a}°, bending ${want} by the keys`);
    });
    const [x, y] = WALK.left_foot[2];
    assert.ok(Math.hypot(after.tips.left_foot[0] - x, after.tips.left_foot[1] - y) < TOLERANCE, `the foot still on its key after the flip: ${after.tips.left_foot}`);
    await page.screenshot({ path: join(dir, "keys-puppet-knee-flipped.png") });

    // The frames saved as answered, times in seconds; the CSV is the CLI's, byte for byte, for
    // the same keys (the page's solver settings are the CLI's defaults, limits now off).
    const [d] = await Promise.all([page.waitForEvent("download"), page.click("#key-frames-json")]);
    const saved = JSON.parse(readFileSync(await d.path(), "utf8"));
    assert.equal(saved.frames.length, 61);
    assert.equal(saved.frames[36].time, 1.2);
    assert.equal(saved.frames[60].time, 2);
    const [c] = await Promise.all([page.waitForEvent("download"), page.click("#key-frames-csv")]);
    const csv = readFileSync(await c.path(), "utf8");
    assert.equal(csv.trim().split("\n").length, 62, "a header and 61 rows");
    const keysFile = join(dir, "keys-puppet-walk.json");
    // As the page sends them: with the Length (2 s) as their duration.
    writeFileSync(keysFile, JSON.stringify({ ...keys2, duration: 2 }));
    const rigFile = join(import.meta.dirname, "..", "examples", "rigs", "puppet.toml");
    const cli = execFileSync(binary, ["animate", "--rig", rigFile, "--keys", keysFile, "--no-limits", "--format", "csv"], { encoding: "utf8" });
    assert.equal(csv, cli, "the page's CSV is `ikarus animate --rig puppet.toml --keys … --no-limits --format csv`");
    // The GIF (POST /api/render with the rig and keys, the canvas's size): the CLI's, byte for byte.
    await gifIsTheCli(page, "puppet-keys.gif", ["render", "motion", "--rig", rigFile, "--keys", keysFile, "--no-limits"], join(dir, "keys-puppet-walk-cli.gif"));

    // A click on the head's tip in Key mode pins it for the whole animation: a row of its own,
    // `pins` in the keys, and every frame holds the tip where the start pose has it.
    await page.mouse.click(...(await tipClient(page, "head")));
    await settled(page);
    const keys3 = await page.evaluate(() => window.ikarus.state.keys);
    assert.deepEqual(keys3.pins, ["head"]);
    assert.deepEqual(keys3.tracks, keys2.tracks);
    const rig = await page.evaluate(() => window.ikarus.state.rig.rig);
    const rest = bodyForward(rig, []).tips[rig.bones.findIndex((b) => b.name === "head")];
    const heads = await page.evaluate(() => window.ikarus.state.motion.frames.map((f) => f.joints.head));
    heads.forEach((h, i) => assert.ok(Math.hypot(h[0] - rest[0], h[1] - rest[1]) < TOLERANCE, `frame ${i}: the pinned head at ${h}, the start pose's ${rest}`));
    assert.ok(await page.evaluate(() => document.getElementById("key-rows").clientHeight >= 6 * 18), "a row for the pin");
    assert.deepEqual(errors, []);
  });
});

const examples = join(import.meta.dirname, "..", "examples", "characters");

/**
 * The Keys bar's GIF, downloaded as `name`, is `ikarus ARGS --width W --height H --out FILE`
 * (W × H the canvas's) byte for byte; resolves with its bytes.
 */
async function gifIsTheCli(page, name, args, file) {
  const [g] = await Promise.all([page.waitForEvent("download"), page.click("#key-gif")]);
  assert.equal(g.suggestedFilename(), name);
  const gif = readFileSync(await g.path());
  const plot = await page.evaluate(() => [document.getElementById("plot").clientWidth, document.getElementById("plot").clientHeight]);
  execFileSync(binary, [...args, "--width", String(plot[0]), "--height", String(plot[1]), "--out", file], { stdio: "ignore" });
  assert.equal(gif.subarray(0, 6).toString(), "GIF89a");
  const cli = readFileSync(file);
  assert.ok(gif.equals(cli), `the page's GIF (${gif.length} bytes) is \`ikarus ${args.join(" ")} --width ${plot[0]} --height ${plot[1]}\` (${cli.length} bytes)`);
  return gif;
}

/** Seconds of spineboy's four keys, within `walk` (frames 0, 9, 18, 27 at 30 fps). */
const SPINE_TIMES = [0, 0.3, 0.6, 0.9];

/** Offsets of the front foot target from where `walk` has it at each key, Spine units. */
const SPINE_OFFSETS = [
  [0, 0],
  [30, 25],
  [60, 0],
  [20, -5],
];


test("spineboy: the front foot target keyed over walk (four keys) is on its keys, and exported as Spine JSON", async (t) => {
  mkdirSync(artifacts, { recursive: true });
  await withBrowser(async ({ url, browser }) => {
    const text = readFileSync(join(examples, "spine-spineboy-pro.json"), "utf8");
    const probe = await fetch(`${url}/api/animate`, {
      method: "POST",
      headers: { "content-type": "application/json" },
      body: JSON.stringify({ rig: text, keys: { fps: 30, tracks: { "front-foot-target": [{ time: 0, x: 0, y: 0 }] } }, animation: "walk", format: "json" }),
    });
    if (probe.status >= 400 && probe.status < 500) {
      t.skip(`/api/animate answers ${probe.status} to keys for a character: ${(await probe.json()).error}`);
      return;
    }
    const { page, errors } = await openPage(browser);
    await page.goto(url);
    await ready(page);
    await page.setInputFiles("#rig-file", { name: "spineboy.json", mimeType: "application/json", buffer: Buffer.from(text) });
    await page.waitForFunction(() => window.ikarus.state.character && window.ikarus.state.character.posed, null, { timeout: 15000 });
    await page.selectOption("#character-animation", "walk");
    await characterSettled(page);
    await page.click("#key-mode");
    const name = "front-foot-target";
    const keysWanted = [];
    for (let k = 0; k < SPINE_TIMES.length; k++) {
      if (k > 0) {
        await page.evaluate((s) => window.ikarus.keys.seek(s), SPINE_TIMES[k]);
        await characterSettled(page);
      }
      const at = await targetAt(page, name);
      // At time 0 the first key is where walk has the target (a plain click would not drag).
      const goal = k === 0 ? [at[0] + 10, at[1]] : [at[0] + SPINE_OFFSETS[k][0], at[1] + SPINE_OFFSETS[k][1]];
      await dragTarget(page, at, goal);
      keysWanted.push(goal);
    }
    const keys = await page.evaluate(() => window.ikarus.state.keys);
    assert.deepEqual(
      keys.tracks[name].map((q) => q.time),
      SPINE_TIMES,
    );
    // Where the pointer was let go (to a thousandth of a Spine unit, under a pixel: the pointer's
    // place goes through the browser's event coordinates).
    keys.tracks[name].forEach((q, k) => assert.ok(Math.hypot(q.x - keysWanted[k][0], q.y - keysWanted[k][1]) < 1e-3, `key ${k} at ${q.x}, ${q.y}; dragged to ${keysWanted[k]}`));
    const keyed = keys.tracks[name].map((q) => [q.x, q.y]);
    // At each key time the target bone's origin is on its key.
    for (let k = 0; k < SPINE_TIMES.length; k++) {
      await page.evaluate((s) => window.ikarus.keys.seek(s), SPINE_TIMES[k]);
      await characterSettled(page);
      const b = await page.evaluate((n) => window.ikarus.state.character.posed.find((x) => x.name === n), name);
      const [x, y] = keyed[k];
      assert.ok(Math.hypot(b.x - x, b.y - y) < 1e-6, `${name} at ${SPINE_TIMES[k]} s: at ${b.x}, ${b.y}, its key ${x}, ${y}`);
    }
    await page.screenshot({ path: join(artifacts, "keys-spineboy-walk.png") });
    // The arm shown, then the character again: its keys and keyed motion as they were left.
    const frames = await page.evaluate(() => JSON.stringify(window.ikarus.state.motion.frames));
    await page.selectOption("#body-kind", "arm");
    assert.equal(await page.evaluate(() => window.ikarus.state.keys), null);
    await page.selectOption("#body-kind", "character");
    await page.waitForFunction(() => window.ikarus.state.character && window.ikarus.state.motion, null, { timeout: 15000 });
    await characterSettled(page);
    assert.deepEqual(await page.evaluate(() => window.ikarus.state.keys), keys, "the character's keys kept");
    assert.equal(await page.evaluate(() => JSON.stringify(window.ikarus.state.motion.frames)), frames, "the same keyed frames");
    // Frames CSV and GIF of the keyed character: the server's (/api/animate format csv,
    // /api/render figure motion), the bytes of `ikarus animate --rig spineboy.json --keys …
    // --animation walk --format csv` and `… --width W --height H --out x.gif`.
    assert.equal(await page.isDisabled("#key-frames-csv"), false);
    assert.equal(await page.isDisabled("#key-gif"), false);
    const keysFile = join(artifacts, "keys-spineboy-walk.json");
    writeFileSync(keysFile, JSON.stringify({ fps: keys.fps, tracks: keys.tracks, duration: 2 }));
    const spineboy = join(examples, "spine-spineboy-pro.json");
    const cliArgs = ["animate", "--rig", spineboy, "--keys", keysFile, "--animation", "walk"];
    const [c] = await Promise.all([page.waitForEvent("download"), page.click("#key-frames-csv")]);
    assert.equal(c.suggestedFilename(), "spineboy-keys.csv");
    const csv = readFileSync(await c.path(), "utf8");
    const cliCsv = execFileSync(binary, [...cliArgs, "--format", "csv"], { encoding: "utf8", stdio: ["ignore", "pipe", "ignore"] });
    assert.equal(csv.split("\n")[0], "frame,time,bone,x,y,rotation_deg,tip_x,tip_y");
    assert.equal(csv, cliCsv, "the page's CSV is the CLI's");
    const gif = await gifIsTheCli(page, "spineboy-keys.gif", cliArgs, join(artifacts, "keys-spineboy-walk-cli.gif"));
    writeFileSync(join(artifacts, "keys-spineboy-walk-page.gif"), gif);

    // Export Spine JSON: the file with the `ikarus` animation, which poses the target on its keys
    // (to 1e-2, the export's promise).
    const [d] = await Promise.all([page.waitForEvent("download"), page.click("#export-spine")]);
    assert.equal(d.suggestedFilename(), "spineboy-ikarus.json");
    const exported = readFileSync(await d.path(), "utf8");
    const file = JSON.parse(exported);
    assert.ok(file.animations && file.animations.ikarus, "the export has animations.ikarus");
    // Posed by `ikarus pose` (the file is past the server's body cap) at each key time.
    const exportedFile = join(artifacts, "keys-spineboy-ikarus.json");
    writeFileSync(exportedFile, exported);
    for (let k = 0; k < SPINE_TIMES.length; k++) {
      const posed = JSON.parse(execFileSync(binary, ["pose", "--rig", exportedFile, "--animation", "ikarus", "--time", String(SPINE_TIMES[k]), "--format", "json"], { encoding: "utf8", stdio: ["ignore", "pipe", "ignore"] }));
      const b = posed.bones.find((x) => x.name === name);
      const [x, y] = keyed[k];
      assert.ok(Math.hypot(b.x - x, b.y - y) < 1e-2, `the exported ikarus animation at ${SPINE_TIMES[k]} s has ${name} at ${b.x}, ${b.y}, its key ${x}, ${y}`);
    }
    assert.deepEqual(errors, []);
  });
});
