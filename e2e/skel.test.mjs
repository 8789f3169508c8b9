// A Spine binary export in the playground (issue 39, point 6): spineboy's `.skel` loads through
// the file input of *Load rig or character…* (sent as its bytes, application/octet-stream, to
// /api/rig/parse?text=1), shows its 67 bones in the setup pose of its JSON export (within 0.15:
// the JSON rounds the editor's floats), plays `walk`, and exports a `.json` (ikarus writes JSON).
// A truncated `.skel` is the server's one line. Run by e2e/run.
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { join } from "node:path";
import { launch, openPage, ready, startServer } from "./browser.mjs";
import { characterSettled, dragTarget, targetAt } from "./charpage.mjs";

const characters = join(import.meta.dirname, "..", "examples", "characters");

test("spineboy's .skel: loaded as bytes, the JSON's setup pose, walk played, exported as JSON", async () => {
  const { child, url } = await startServer();
  const browser = await launch();
  try {
    const { page, errors } = await openPage(browser);
    const sent = [];
    page.on("request", (r) => r.url().includes("/api/rig/parse") && sent.push([r.url(), r.headers()["content-type"]]));
    await page.goto(url);
    await ready(page);
    assert.match(await page.getAttribute("#rig-file", "accept"), /\.skel/);

    const skel = readFileSync(join(characters, "spine-spineboy-pro.skel"));
    await page.setInputFiles("#rig-file", { name: "spineboy.skel", mimeType: "application/octet-stream", buffer: skel });
    await page.waitForFunction(() => window.ikarus.state.character && window.ikarus.state.character.posed, null, { timeout: 15000 });
    await characterSettled(page);
    assert.deepEqual(sent, [[`${url}/api/rig/parse?text=1`, "application/octet-stream"]]);
    assert.equal(await page.evaluate(() => document.getElementById("plot").dataset.bones), "67");
    const c = await page.evaluate(() => ({ name: window.ikarus.state.character.name, text: window.ikarus.state.character.text, bones: window.ikarus.state.character.character.bones.length, posed: window.ikarus.state.character.posed }));
    assert.equal(c.name, "spineboy.skel");
    assert.equal(c.bones, 67);
    assert.ok(c.text.startsWith("{"), "the page keeps the decoded JSON text");
    assert.match(await page.textContent("#stats"), /^Spine character spineboy\.skel · 67 bones · 7 IK, 8 transform constraints · setup pose · Spine rules$/);

    // The setup pose: the JSON export's (posed by the server from the JSON file) within 0.15.
    const json = readFileSync(join(characters, "spine-spineboy-pro.json"), "utf8");
    const res = await fetch(`${url}/api/pose`, { method: "POST", headers: { "content-type": "application/json" }, body: JSON.stringify({ rig: json }) });
    const want = new Map((await res.json()).bones.map((b) => [b.name, b]));
    assert.equal(c.posed.length, want.size);
    let far = 0;
    for (const b of c.posed) far = Math.max(far, Math.hypot(b.x - want.get(b.name).x, b.y - want.get(b.name).y));
    assert.ok(far < 0.15, `the setup pose is ${far} from the JSON's`);

    // `walk` plays to its end.
    await page.selectOption("#character-animation", "walk");
    await characterSettled(page);
    await page.click("#play");
    await page.waitForFunction(() => document.body.dataset.playback === "ended", null, { timeout: 15000 });
    await characterSettled(page);
    assert.equal(await page.textContent("#playtime"), "1.00 / 1.00 s");

    // A target dragged, then *Export Spine JSON*: a .json named after the file, with `ikarus`.
    const at = await targetAt(page, "front-leg-target");
    await dragTarget(page, at, [at[0] + 40, at[1] + 60]);
    const [d] = await Promise.all([page.waitForEvent("download"), page.click("#export-spine")]);
    assert.equal(d.suggestedFilename(), "spineboy-ikarus.json");
    const exported = JSON.parse(readFileSync(await d.path(), "utf8"));
    assert.ok(exported.animations && exported.animations.ikarus, "the export has animations.ikarus");
    assert.equal(exported.bones.length, 67);

    // A truncated .skel: the server's one line, and the character stays.
    await page.setInputFiles("#rig-file", { name: "cut.skel", mimeType: "application/octet-stream", buffer: skel.subarray(0, 2000) });
    await page.waitForFunction(() => !document.getElementById("error").hidden, null, { timeout: 15000 });
    assert.match(await page.textContent("#error"), /^rig file: skel: byte \d+: /);
    assert.equal(await page.evaluate(() => window.ikarus.state.character.name), "spineboy.skel");
    // Chromium logs the refused request (the 422) on the console; nothing else may be logged.
    assert.deepEqual(errors.filter((e) => !/status of 422/.test(e)), []);
  } finally {
    await browser.close();
    child.kill();
  }
});
