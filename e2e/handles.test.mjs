// What a character's handles do, and posing by hand, in a real browser. spineboy: the crosshair's
// handle names the bone it drags (aim-constraint-target, by aim-torso-ik; its transform
// constraints then aim the torso, head and arms where the clip mixes them in), a leg target's names
// the bones it drags; stretchyman's arm targets drag the IK bones that shape the paths of its path
// constraints, and the arm follows the path. A drag on spineboy's head (a bone
// no IK constraint moves) turns it about its origin and it keeps turned; in Key mode the turn is
// keyed (at 0, then at the playhead at 0.3 s) (`keys.rotations`) and the keyed motion reproduces it, frame for frame the
// CLI's. Export Spine JSON says it exports the keys; on a DragonBones character it is disabled
// with the reason. Ticking onion skins is no undo step. Screenshots go to $E2E_ARTIFACTS.
// Run by e2e/run:  node --test e2e/handles.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { mkdirSync, readFileSync, writeFileSync } from "node:fs";
import { join } from "node:path";
import { artifacts, binary, openPage, ready, withBrowser } from "./browser.mjs";
import { characterSettled, dragTarget } from "./charpage.mjs";

const examples = join(import.meta.dirname, "..", "examples", "characters");

async function load(page, file, name) {
  await page.setInputFiles("#rig-file", { name, mimeType: "application/json", buffer: readFileSync(join(examples, file)) });
  await page.waitForFunction((n) => window.ikarus.state.character && window.ikarus.state.character.name === n && window.ikarus.state.character.posed, name, { timeout: 15000 });
  await characterSettled(page);
}

const bone = (page, name) => page.evaluate((n) => window.ikarus.state.character.posed.find((b) => b.name === n), name);

/** The client point a fraction `u` along bone `name` (origin to tip). */
async function alongBone(page, name, u) {
  const b = await bone(page, name);
  return page.evaluate(([x, y]) => window.ikarus.toClient(x, y), [b.x + u * (b.tip[0] - b.x), b.y + u * (b.tip[1] - b.y)]);
}

/** Drags bone `name` from 80% along it round its origin by `deg`, and waits. */
async function turnBone(page, name, deg) {
  await page.mouse.move(...(await alongBone(page, name, 0.8)));
  await page.mouse.down();
  for (let k = 1; k <= 6; k++) await page.mouse.move(...(await turnedTipFrom(page, name, (deg * k) / 6)));
  await page.mouse.up();
  await characterSettled(page);
}

let grabbed = null;
/** The client point 80% along bone `name` turned by `deg` about its origin, from where the bone was when the drag began (it turns under the pointer). */
async function turnedTipFrom(page, name, deg) {
  if (deg === 0 || !grabbed || grabbed.name !== name) grabbed = { name, b: await bone(page, name) };
  const { b } = grabbed;
  const a = (deg * Math.PI) / 180;
  const [dx, dy] = [0.8 * (b.tip[0] - b.x), 0.8 * (b.tip[1] - b.y)];
  return page.evaluate(([x, y]) => window.ikarus.toClient(x, y), [b.x + dx * Math.cos(a) - dy * Math.sin(a), b.y + dx * Math.sin(a) + dy * Math.cos(a)]);
}

const turn = (a, b) => ((((a - b + 180) % 360) + 360) % 360) - 180;

test("handles say what they drag or why they do nothing; a plain bone turns by hand and keys its turn; DragonBones cannot export; onion skins are no undo step", async () => {
  mkdirSync(artifacts, { recursive: true });
  await withBrowser(async ({ url, browser }) => {
    const { page, errors } = await openPage(browser);
    await page.goto(url);
    await ready(page);

    // Onion skins: a view setting, no undo step.
    assert.equal(await page.isDisabled("#undo"), true);
    await page.check("#onion");
    assert.equal(await page.isDisabled("#undo"), true, "ticking onion skins is no undo step");
    await page.uncheck("#onion");

    await load(page, "spine-spineboy-pro.json", "spineboy.json");
    const notes = await page.evaluate(() => Object.fromEntries([...window.ikarus.state.character.notes].map(([k, v]) => [k, v])));
    assert.equal(notes.crosshair.inactive, false);
    assert.equal(notes.crosshair.note, "crosshair: drags aim-constraint-target (IK constraint aim-torso-ik)");
    assert.equal(notes["front-leg-target"].inactive, false);
    assert.equal(notes["front-leg-target"].note, "front-leg-target: drags front-thigh, front-shin (IK constraint front-leg-ik)");
    // The hover text is the note; the crosshair drawn apart.
    const cross = await bone(page, "crosshair");
    await page.mouse.move(...(await page.evaluate(([x, y]) => window.ikarus.toClient(x, y), [cross.x, cross.y])));
    assert.equal(await page.getAttribute("#plot", "title"), notes.crosshair.note);
    await page.screenshot({ path: join(artifacts, "handles-crosshair.png") });

    // The head turned by hand about its origin, kept turned.
    const head0 = await bone(page, "head");
    await turnBone(page, "head", 30);
    const head1 = await bone(page, "head");
    assert.ok(Math.abs(turn(head1.rotation_deg, head0.rotation_deg) - 30) < 2, `the head turned ${turn(head1.rotation_deg, head0.rotation_deg)}°`);
    assert.ok(Math.hypot(head1.x - head0.x, head1.y - head0.y) < 1e-9, "about its origin");
    await page.waitForTimeout(200);
    assert.deepEqual(await bone(page, "head"), head1, "it keeps turned");
    await page.screenshot({ path: join(artifacts, "handles-head-turned.png") });

    // Key mode: the turn keyed at 0.3 s over the setup pose; playback reproduces it.
    await page.click("#key-mode");
    await turnBone(page, "head", -40);
    await page.evaluate(() => window.ikarus.keys.seek(0.3));
    await characterSettled(page);
    await turnBone(page, "head", 60);
    const keys = await page.evaluate(() => window.ikarus.keys.sent());
    assert.deepEqual(keys.rotations.head.map((q) => q.time), [0, 0.3]);
    const keyed = keys.rotations.head[1].angle_deg;
    const frames = await page.evaluate(() => window.ikarus.state.motion.frames);
    assert.equal(frames.length, 61, "to the Length");
    const headAt = (f) => f.bones.find((b) => b.name === "head");
    const neckAt = (f) => f.bones.find((b) => b.name === "neck");
    assert.ok(Math.abs(turn(headAt(frames[9]).rotation_deg - neckAt(frames[9]).rotation_deg, keyed)) < 1e-6, "the frame at 0.3 s has the head at its key");
    assert.ok(Math.abs(turn(headAt(frames[40]).rotation_deg - neckAt(frames[40]).rotation_deg, keyed)) < 1e-6, "held after its last key");
    await page.evaluate(() => window.ikarus.keys.seek(0));
    await characterSettled(page);
    await page.evaluate(() => window.ikarus.keys.seek(0.3));
    await characterSettled(page);
    assert.ok(Math.abs(turn((await bone(page, "head")).rotation_deg, headAt(frames[9]).rotation_deg)) < 1e-9, "played back: the head turned as keyed");
    const keysFile = join(artifacts, "handles-spineboy-keys.json");
    writeFileSync(keysFile, JSON.stringify(keys));
    const cli = JSON.parse(execFileSync(binary, ["animate", "--rig", join(examples, "spine-spineboy-pro.json"), "--keys", keysFile, "--format", "json"], { encoding: "utf8", stdio: ["ignore", "pipe", "ignore"] }));
    assert.deepStrictEqual(frames, cli.frames, "the page's frames are the CLI's");
    assert.match(await page.getAttribute("#export-spine", "title"), /made of your 2 keys \(2\.00 s, the Length, at 30 fps/);
    assert.equal(await page.isDisabled("#export-spine"), false);

    // stretchyman: its arm targets drag the IK bones whose weights shape its arms' paths.
    await load(page, "spine-stretchyman-pro.json", "stretchyman.json");
    const stretchy = await page.evaluate(() => Object.fromEntries([...window.ikarus.state.character.notes].map(([k, v]) => [k, v])));
    assert.equal(stretchy["back-arm-ik-target"].inactive, false);
    assert.match(stretchy["back-arm-ik-target"].note, /^back-arm-ik-target: drags back-arm-ik1, back-arm-ik2 \(IK constraint /);
    // Dragged, the arm (path-constrained bones) follows.
    const arm = async () => (await page.evaluate(() => window.ikarus.state.character.posed.find((b) => b.name === "back-arm5")));
    const before = await arm();
    const at = await page.evaluate(() => { const b = window.ikarus.state.character.posed.find((x) => x.name === "back-arm-ik-target"); return [b.x, b.y]; });
    await dragTarget(page, at, [at[0] - 60, at[1] + 40]);
    const after = await arm();
    assert.ok(Math.hypot(after.x - before.x, after.y - before.y) > 5, `the arm follows its path: ${JSON.stringify([before, after])}`);
    await page.screenshot({ path: join(artifacts, "handles-stretchyman.png") });

    // DragonBones: no Spine export, and why.
    await load(page, "dragonbones-mecha_1406_ske.json", "mecha.json");
    assert.equal(await page.isDisabled("#export-spine"), true);
    assert.equal(await page.getAttribute("#export-spine", "title"), "The Spine export takes a Spine file; this is a DragonBones character");
    assert.deepEqual(errors, []);
  });
});
