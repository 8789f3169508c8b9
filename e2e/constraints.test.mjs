// Every constraint kind on the page: celestial-circus (transform and physics constraints) loads,
// shows its physics switch, and `swing` at 1 s is drawn as the server poses it with physics played
// from 0 (its bench swinging away from where the clip alone puts it); switched off, the bench is
// where the clip puts it. Stretchyman (transform and path constraints) is drawn as `ikarus pose`
// poses it. Screenshots land in E2E_ARTIFACTS. Run by e2e/run.
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { join } from "node:path";
import { artifacts, onPlayground } from "./browser.mjs";
import { characterSettled } from "./charpage.mjs";

const characters = join(import.meta.dirname, "..", "examples", "characters");

/** Loads `file` through *Load rig or character…* and waits for its setup pose. */
async function load(page, file) {
  const text = readFileSync(join(characters, file), "utf8");
  await page.setInputFiles("#rig-file", { name: file, mimeType: "application/json", buffer: Buffer.from(text) });
  await page.waitForFunction((f) => window.ikarus.state.character?.name === f && window.ikarus.state.character.posed, file, { timeout: 15000 });
  await characterSettled(page);
  return text;
}

/** The bones the page shows, by name. */
const shown = (page) => page.evaluate(() => Object.fromEntries(window.ikarus.state.character.posed.map((b) => [b.name, b])));

/** The server's pose of `body`, bones by name. */
async function posed(url, body) {
  const res = await fetch(`${url}/api/pose`, { method: "POST", headers: { "content-type": "application/json" }, body: JSON.stringify(body) });
  assert.equal(res.status, 200);
  return Object.fromEntries((await res.json()).bones.map((b) => [b.name, b]));
}

/** The largest distance between two poses' bone origins. */
function apart(a, b) {
  let far = 0;
  for (const [name, bone] of Object.entries(a)) far = Math.max(far, Math.hypot(bone.x - b[name].x, bone.y - b[name].y));
  return far;
}

test("celestial-circus swings with physics on the page, and stands still with physics off", () =>
  onPlayground(async (page, { url }) => {
    const text = await load(page, "spine-celestial-circus-pro.json");
    assert.equal(await page.isVisible("#character-physics"), true);
    assert.equal(await page.isChecked("#character-physics"), true);
    assert.deepEqual(await page.evaluate(() => window.ikarus.state.character.character.unsupported), []);
    await page.selectOption("#character-animation", "swing");
    await characterSettled(page);
    // To 1 s on the timeline: the page asks for the clip at that time with physics (the default).
    await page.evaluate(() => window.ikarus.seek(1.0));
    await characterSettled(page);
    const request = await page.evaluate(() => window.ikarus.state.character.request);
    assert.ok(Math.abs(request.time - 1.0) < 1e-9, `${request.time}`);
    assert.equal("physics" in request, false);
    const played = await posed(url, { rig: text, animation: "swing", time: request.time });
    const still = await posed(url, { rig: text, animation: "swing", time: request.time, physics: false });
    assert.ok(apart(played, still) > 1, `physics moves the bench: ${apart(played, still)}`);
    assert.ok(apart(await shown(page), played) < 1e-9, "the page shows the played pose");
    await page.screenshot({ path: join(artifacts, "character-celestial-swing.png") });
    // Physics off: the clip's pose alone.
    await page.uncheck("#character-physics");
    await characterSettled(page);
    assert.equal(await page.evaluate(() => window.ikarus.state.character.request.physics), false);
    assert.ok(apart(await shown(page), still) < 1e-9, "physics off shows the clip's pose");
  }));

test("stretchyman's paths and transform constraints are drawn as ikarus pose poses them", () =>
  onPlayground(async (page, { url }) => {
    const text = await load(page, "spine-stretchyman-pro.json");
    const kinds = await page.evaluate(() => window.ikarus.state.character.character.constraints.map((k) => k.kind));
    assert.deepEqual(kinds.filter((k) => k === "path").length, 4);
    assert.deepEqual(kinds.filter((k) => k === "transform").length, 2);
    assert.equal(await page.isVisible("#character-physics"), false);
    await page.selectOption("#character-animation", "sneak");
    await characterSettled(page);
    await page.evaluate(() => window.ikarus.seek(0.54));
    await characterSettled(page);
    const time = await page.evaluate(() => window.ikarus.state.character.request.time);
    assert.ok(Math.abs(time - 0.54) < 1e-9, `${time}`);
    const want = await posed(url, { rig: text, animation: "sneak", time });
    assert.ok(apart(await shown(page), want) < 1e-9);
    await page.screenshot({ path: join(artifacts, "character-stretchyman-sneak.png") });
  }));
