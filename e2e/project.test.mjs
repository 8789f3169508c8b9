// Undo, redo and project files in the playground (issue 28, points 2 and 6), in a real browser:
// on the puppet, a hand's goal dragged, a foot pinned and a setting changed, each undone and
// redone (Ctrl-Z, Ctrl-Shift-Z, Ctrl-Y and the buttons) with the work checked bit for bit; on
// the arm, a link's length and a clicked goal the same way; 120 edits then 100 undos; the work
// saved as a project file (the download), the page reloaded (the unsaved-work warning shown),
// the file opened again through the file input and by a drop, and the goals, pins, settings
// and pose back bit for bit; a file of a newer version and a broken one refused with their
// one-line messages, nothing changed. Then spineboy: a target placed and a clip chosen, saved
// with the character embedded, opened on a fresh page. Run by e2e/run.
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { join } from "node:path";
import { artifacts, onPlayground, ready, reloadUnsaved, setField } from "./browser.mjs";
import { tipClient } from "./rigpage.mjs";

const settled = (page) => page.waitForFunction(() => !window.ikarus.state.rig || window.ikarus.rigs.settled(), null, { timeout: 15000 });
const characters = join(import.meta.dirname, "..", "examples", "characters");

/** The work the reader sees: body, rig goals, pins and pose, the arm and its pose and goal, every setting. */
const work = (page) =>
  page.evaluate(() => {
    const s = window.ikarus.state;
    const r = s.rig;
    const settings = {};
    for (const el of document.querySelectorAll("#panel-body input[id], #panel-body select[id]")) {
      if (!["file", "radio"].includes(el.type) && !el.closest("#links-body")) settings[el.id] = el.type === "checkbox" ? el.checked : el.value;
    }
    return {
      body: document.getElementById("body-kind").value,
      goals: r ? [...r.goals].map(([b, g]) => [b, g.x, g.y]) : null,
      pins: r ? [...r.pins] : null,
      rigPose: r ? r.pose_deg.slice() : null,
      arm: JSON.parse(JSON.stringify(s.arm)),
      pose: s.pose_deg.slice(),
      goal: s.goal,
      settings,
    };
  });

/** The chip's message (the error line when shown, else the status line). */
const chip = (page) => page.evaluate(() => (document.getElementById("error").hidden ? document.getElementById("stats").textContent : document.getElementById("error").textContent));

/** Key mode, the keys' Length, the camera, the timeline's length and the playhead (seconds) as the page shows them. */
const viewNow = (page) =>
  page.evaluate(() => ({
    mode: document.getElementById("key-mode").getAttribute("aria-pressed"),
    length: document.getElementById("key-length").value,
    camera: { ...window.ikarus.state.camera },
    duration: window.ikarus.duration(),
    playhead: window.ikarus.state.playback.u * window.ikarus.duration(),
  }));

/** Presses `keys` on the canvas (focus outside any field) and waits for the rig to settle. */
async function press(page, keys) {
  await page.focus("#plot");
  await page.keyboard.press(keys);
  await settled(page);
}

test("the puppet and the arm: every edit undone and redone; saved, reloaded with a warning, opened bit for bit", () =>
  onPlayground(async (page) => {
    assert.equal(await page.isDisabled("#undo"), true);
    assert.equal(await page.evaluate(() => document.body.dataset.dirty), "false");

    const steps = [await work(page)];
    await page.selectOption("#body-kind", "rig:puppet");
    await page.waitForFunction(() => window.ikarus.state.rig);
    steps.push(await work(page));

    // A hand's goal dragged (one step at the end of the drag, holding the pose its solve reached).
    const from = await tipClient(page, "right_hand");
    await page.mouse.move(...from);
    await page.mouse.down();
    await page.mouse.move(from[0] + 40, from[1] - 30, { steps: 8 });
    await page.mouse.up();
    await settled(page);
    steps.push(await work(page));
    assert.equal(steps[2].goals.length, 1);
    assert.notDeepEqual(steps[2].rigPose, steps[1].rigPose);
    assert.match(await page.getAttribute("#undo", "title"), /^Undo: Move right_hand goal/);

    // A foot pinned, then a setting changed (the rig solves again with it).
    await page.mouse.click(...(await tipClient(page, "left_foot")));
    await settled(page);
    steps.push(await work(page));
    assert.deepEqual(steps[3].pins, ["left_foot"]);
    await page.selectOption("#method", "dls");
    await settled(page);
    steps.push(await work(page));
    assert.equal(steps[4].settings.method, "dls");
    assert.equal(await page.evaluate(() => document.body.dataset.dirty), "true");

    // Undo each, back to the page as it opened; redo each, by the three ways.
    for (let k = steps.length - 2; k >= 0; k--) {
      await press(page, "Control+z");
      assert.deepEqual(await work(page), steps[k], `undo to step ${k}`);
    }
    assert.equal(await page.isDisabled("#undo"), true);
    assert.equal(await page.evaluate(() => document.body.dataset.dirty), "false", "undone to the saved work: nothing to lose");
    const redo = ["Control+Shift+z", "Control+y", "button", "Control+Shift+Z"];
    for (let k = 1; k < steps.length; k++) {
      if (redo[k - 1] === "button") {
        await page.click("#redo");
        await settled(page);
      } else await press(page, redo[k - 1]);
      assert.deepEqual(await work(page), steps[k], `redo to step ${k}`);
    }
    assert.equal(await page.isDisabled("#redo"), true);
    // In a text field, Ctrl-Z is the field's own: the page's work stays.
    const sizes = await page.evaluate(() => window.ikarus.project.sizes());
    await page.focus("#tolerance");
    await page.keyboard.press("Control+z");
    assert.deepEqual(await page.evaluate(() => window.ikarus.project.sizes()), sizes);
    assert.deepEqual(await work(page), steps[steps.length - 1]);
    await page.screenshot({ path: join(artifacts, "project-puppet.png") });

    // The arm: a link's length (the table), a clicked goal; each undone and redone.
    const rigWork = steps[steps.length - 1];
    await page.selectOption("#body-kind", "arm");
    await page.waitForFunction(() => !window.ikarus.state.rig);
    const arm0 = await work(page);
    await page.fill('[aria-label="Link 1 length"]', "1.5");
    await page.press('[aria-label="Link 1 length"]', "Tab");
    const arm1 = await work(page);
    assert.equal(arm1.arm.links[0].length, 1.5);
    const goal = await page.evaluate(() => window.ikarus.toClient(1.2, 1.4));
    await page.mouse.click(...goal);
    await page.waitForFunction(() => document.body.dataset.playback === "ended", null, { timeout: 15000 });
    const arm2 = await work(page);
    assert.ok(arm2.goal, "the click set a goal");
    assert.notDeepEqual(arm2.pose, arm1.pose);
    for (const [k, want] of [[1, arm1], [0, arm0]]) {
      await page.click("#undo");
      assert.deepEqual(await work(page), want, `arm: undo to step ${k}`);
    }
    assert.equal(await page.inputValue('[aria-label="Link 1 length"]'), String(arm0.arm.links[0].length), "the table shows the length undone");
    for (const want of [arm1, arm2]) {
      await page.click("#redo");
      assert.deepEqual(await work(page), want);
    }

    // 120 edits, then 100 undos: the 20th edit's value is back.
    const values = await page.evaluate(() => {
      const el = document.getElementById("restarts");
      const seen = [];
      for (let k = 1; k <= 120; k++) {
        el.value = String(k % 60);
        el.dispatchEvent(new Event("change", { bubbles: true }));
        seen.push(el.value);
      }
      return seen;
    });
    for (let k = 0; k < 100; k++) await page.evaluate(() => window.ikarus.project.undo());
    assert.equal(await page.inputValue("#restarts"), values[19]);
    assert.deepEqual(await page.evaluate(() => window.ikarus.project.sizes()), { undo: steps.length - 1 + 3 + 20, redo: 100 });
    await page.evaluate(() => window.ikarus.project.redo());
    assert.equal(await page.inputValue("#restarts"), values[20]);
    // A new edit after undo: nothing left to redo.
    await page.fill("#lambda", "0.25");
    await page.press("#lambda", "Tab");
    assert.deepEqual(await page.evaluate(() => window.ikarus.project.sizes()), { undo: steps.length - 1 + 3 + 22, redo: 0 });
    assert.equal(await page.isDisabled("#redo"), true);
    assert.match(await page.getAttribute("#undo", "title"), /^Undo: λ \(damping\)/);

    // Back on the puppet with its work (undo far enough), saved: the download is the project.
    while ((await page.evaluate(() => window.ikarus.project.sizes().undo)) > steps.length - 1) await page.evaluate(() => window.ikarus.project.undo());
    await settled(page);
    assert.deepEqual(await work(page), rigWork);
    const [d] = await Promise.all([page.waitForEvent("download"), page.click("#save-project")]);
    assert.equal(d.suggestedFilename(), "puppet.ikarus.json");
    const saved = readFileSync(await d.path(), "utf8");
    const file = JSON.parse(saved);
    assert.equal(file.ikarus_project, 1);
    assert.match(file.saved_by, /^ikarus \d+\.\d+\.\d+/);
    assert.deepEqual(file.body, { kind: "rig", rig: "puppet" });
    assert.deepEqual(file.rig.pose_deg, rigWork.rigPose);
    assert.equal(await page.evaluate(() => document.body.dataset.dirty), "false");

    // One more edit, then a reload: the page warns that it would be lost.
    assert.deepEqual(await reloadUnsaved(page), { dirty: "true", dialogs: ["beforeunload"] });
    assert.equal(await page.evaluate(() => window.ikarus.state.rig), null, "a fresh page");

    // Opened through the file input: the work saved, bit for bit, and itself one undo step.
    await page.setInputFiles("#project-file", { name: "puppet.ikarus.json", mimeType: "application/json", buffer: Buffer.from(saved) });
    await page.waitForFunction(() => window.ikarus.state.rig && /^opened/.test(document.getElementById("stats").textContent));
    assert.deepEqual(await work(page), rigWork);
    assert.equal(await chip(page), "opened puppet.ikarus.json");
    assert.equal(await page.evaluate(() => document.body.dataset.dirty), "false");
    assert.match(await page.getAttribute("#undo", "title"), /^Undo: Open puppet\.ikarus\.json/);
    await page.screenshot({ path: join(artifacts, "project-opened.png") });

    // Refused files: one line each, nothing changes.
    for (const [text, message] of [
      ['{"ikarus_project": 99, "body": {"kind": "arm"}}', "project file: version 99 is newer than this page reads (1); update ikarus"],
      ['{"ikarus_project": 1, "keys": {"tracks": {"left_foot": [{"time": 0, "x": 0, "y": 0}, {"time": "x", "x": 0, "y": 0}]}}}', 'project file: keys.tracks.left_foot[1].time = "x" is not a number'],
      ['{"ikarus_project": 1, "body": {"kind": "rig", "rig": "puppet"}, "rig": {"pins": ["tail"]}', "project file: not JSON"],
    ]) {
      await page.setInputFiles("#project-file", { name: "bad.ikarus.json", mimeType: "application/json", buffer: Buffer.from(text) });
      await page.waitForFunction(() => !document.getElementById("error").hidden);
      const said = await chip(page);
      assert.ok(said === message || (message.endsWith("not JSON") && said.startsWith(`${message} (`)), `${said} ≠ ${message}`);
      assert.ok(!said.includes("\n"));
      assert.deepEqual(await work(page), rigWork);
    }
    await page.screenshot({ path: join(artifacts, "project-refused.png") });

    // Undo the opening: the fresh page's work; a project dropped on the page opens it again.
    await press(page, "Control+z");
    assert.equal(await page.evaluate(() => window.ikarus.state.rig), null);
    await page.evaluate((text) => {
      const dt = new DataTransfer();
      dt.items.add(new File([text], "walk.ikarus.json", { type: "application/json" }));
      document.dispatchEvent(new DragEvent("drop", { dataTransfer: dt, bubbles: true, cancelable: true }));
    }, saved);
    await page.waitForFunction(() => window.ikarus.state.rig && /^opened walk/.test(document.getElementById("stats").textContent));
    assert.deepEqual(await work(page), rigWork);
  }));

test("spineboy: a placed target and a clip saved with the character embedded, opened on a fresh page", () =>
  onPlayground(async (page) => {
    const text = readFileSync(join(characters, "spine-spineboy-pro.json"), "utf8");
    await page.setInputFiles("#rig-file", { name: "spineboy.json", mimeType: "application/json", buffer: Buffer.from(text) });
    const charSettled = () => page.waitForFunction(() => window.ikarus.state.character && window.ikarus.state.character.posed && window.ikarus.characters.settled(), null, { timeout: 15000 });
    await charSettled();
    await page.selectOption("#character-animation", "walk");
    await charSettled();
    // The front foot's target dragged a little.
    const handle = await page.evaluate(() => {
      const c = window.ikarus.state.character;
      const b = c.posed.find((x) => x.name === "front-leg-target");
      return window.ikarus.toClient(b.x, b.y);
    });
    await page.mouse.move(...handle);
    await page.mouse.down();
    await page.mouse.move(handle[0] + 30, handle[1] - 20, { steps: 6 });
    await page.mouse.up();
    await charSettled();
    const charWork = () =>
      page.evaluate(() => {
        const c = window.ikarus.state.character;
        return { name: c.name, animation: c.animation, ik: c.ik, targets: [...c.targets], list: document.getElementById("character-animation").value };
      });
    const before = await charWork();
    assert.equal(before.targets.length, 1);
    assert.equal(before.animation, "walk");
    assert.match(await page.getAttribute("#undo", "title"), /^Undo: Move front-leg-target target/);

    const [d] = await Promise.all([page.waitForEvent("download"), page.click("#save-project")]);
    assert.equal(d.suggestedFilename(), "spineboy.ikarus.json");
    const saved = readFileSync(await d.path(), "utf8");
    const file = JSON.parse(saved);
    assert.equal(file.body.character.text, text, "the character is embedded");
    assert.equal(file.body.character.size, Buffer.byteLength(text));
    assert.match(file.body.character.sha256, /^[0-9a-f]{64}$/);

    // A fresh page (no character loaded): the project opens alone.
    await page.reload();
    await ready(page);
    await page.setInputFiles("#project-file", { name: "spineboy.ikarus.json", mimeType: "application/json", buffer: Buffer.from(saved) });
    await charSettled();
    assert.deepEqual(await charWork(), before);
    await page.screenshot({ path: join(artifacts, "project-spineboy.png") });

    // Without its text, the project names the character it needs.
    delete file.body.character.text;
    await page.reload();
    await ready(page);
    await page.setInputFiles("#project-file", { name: "ref.ikarus.json", mimeType: "application/json", buffer: Buffer.from(JSON.stringify(file)) });
    await page.waitForFunction(() => !document.getElementById("error").hidden);
    assert.match(await chip(page), /^project file: the character spineboy\.json \(0\.\d MB\) is not embedded and not loaded; load spineboy\.json/);
    // Loaded first, it opens.
    await page.setInputFiles("#rig-file", { name: "spineboy.json", mimeType: "application/json", buffer: Buffer.from(text) });
    await charSettled();
    await page.setInputFiles("#project-file", { name: "ref.ikarus.json", mimeType: "application/json", buffer: Buffer.from(JSON.stringify(file)) });
    await page.waitForFunction(() => /^opened ref/.test(document.getElementById("stats").textContent) || window.ikarus.state.character.targets.size === 1);
    await charSettled();
    assert.deepEqual(await charWork(), before);
  }));

test("the puppet's keys: keyed in Key mode, undone and redone, saved and opened with the same frames", async (t) => {
  await onPlayground(async (page) => {
    // The keyed motion needs POST /api/animate with `keys` (issue 28's rig API); a server without it is said, not failed.
    const api = (path) => new URL(path, page.url());
    const rig = (await (await fetch(api("/api/rigs"))).json()).rigs.find((r) => r.name === "puppet").rig;
    const body = JSON.stringify({ rig, keys: { fps: 30, tracks: { left_foot: [{ time: 0, x: 0, y: -0.9 }] } } });
    const probe = (await fetch(api("/api/animate"), { method: "POST", headers: { "content-type": "application/json" }, body })).status;
    if (probe !== 200) {
      t.skip(`this server does not animate keys (POST /api/animate with keys answered ${probe})`);
      return;
    }
    const keysSettled = () => page.waitForFunction(() => window.ikarus.keys.settled() && window.ikarus.rigs.settled(), null, { timeout: 60000 });
    const seek = async (s) => {
      await page.evaluate((x) => window.ikarus.keys.seek(x), s);
      await keysSettled();
    };
    const dragBy = async (bone, dx, dy) => {
      const from = await tipClient(page, bone);
      await page.mouse.move(...from);
      await page.mouse.down();
      await page.mouse.move(from[0] + dx, from[1] + dy, { steps: 6 });
      await page.mouse.up();
      await keysSettled();
    };
    const keyed = () => page.evaluate(() => ({ keys: window.ikarus.state.keys, frames: window.ikarus.state.motion && window.ikarus.state.motion.frames.map((f) => f.pose) }));

    await page.selectOption("#body-kind", "rig:puppet");
    await page.click("#key-mode");
    await seek(0);
    await dragBy("left_foot", 20, -10);
    await seek(0.5);
    await dragBy("left_foot", -20, -15);
    await dragBy("right_hand", 25, 20);
    const full = await keyed();
    assert.deepEqual(Object.keys(full.keys.tracks).sort(), ["left_foot", "right_hand"]);
    assert.ok(full.frames.length > 1);

    // The last key undone (its track goes), and redone.
    await page.focus("#plot");
    await page.keyboard.press("Control+z");
    await keysSettled();
    assert.deepEqual(Object.keys((await keyed()).keys.tracks), ["left_foot"]);
    await page.keyboard.press("Control+Shift+z");
    await keysSettled();
    assert.deepEqual(await keyed(), full);

    // The view and the timing saved with the work: the Length (an edit), a zoom about a point
    // (not an edit: undo keeps its last step), the playhead at 0.5 s.
    await setField(page, "#key-length", "3");
    assert.match(await page.getAttribute("#undo", "title"), /^Undo: Length 3 s/);
    const box = await page.evaluate(() => {
      const r = document.getElementById("plot").getBoundingClientRect();
      return [r.left + r.width * 0.4, r.top + r.height * 0.35];
    });
    await page.mouse.move(...box);
    for (let i = 0; i < 3; i++) await page.mouse.wheel(0, -240);
    await page.waitForFunction(() => window.ikarus.state.camera.zoom > 1.5);
    assert.match(await page.getAttribute("#undo", "title"), /^Undo: Length 3 s/, "zooming is no undo step");
    await seek(0.5);
    // The keyed motion runs to the Length: 3 s, 91 frames.
    const three = await keyed();
    assert.deepEqual(three.keys, full.keys);
    assert.equal(three.frames.length, 91);
    const view = await viewNow(page);
    assert.equal(view.mode, "true");
    assert.equal(view.length, "3");
    assert.ok(Math.abs(view.playhead - 0.5) < 1e-9, `the playhead at ${view.playhead} s`);
    assert.equal(view.duration, 3);

    const [d] = await Promise.all([page.waitForEvent("download"), page.click("#save-project")]);
    const saved = readFileSync(await d.path(), "utf8");
    const file = JSON.parse(saved);
    assert.deepEqual(file.keys, full.keys);
    assert.deepEqual([file.key_mode, file.key_length, file.camera], [true, 3, view.camera]);
    assert.ok(Math.abs(file.playhead_s - 0.5) < 1e-9, `playhead_s ${file.playhead_s}`);
    assert.equal(file.playhead, undefined, "no fraction in a new file");
    await page.reload();
    await ready(page);
    assert.equal(await page.getAttribute("#key-mode", "aria-pressed"), "false", "a fresh page: Key mode off");
    await page.setInputFiles("#project-file", { name: "keys.ikarus.json", mimeType: "application/json", buffer: Buffer.from(saved) });
    await page.waitForFunction(() => window.ikarus.state.keys && window.ikarus.state.motion);
    await keysSettled();
    assert.deepEqual(await keyed(), three, "the same keys and the same frames (to the Length saved), bit for bit");
    const back = await viewNow(page);
    assert.deepEqual({ ...back, playhead: 0 }, { ...view, playhead: 0 }, "Key mode, Length, camera and timeline back");
    assert.ok(Math.abs(back.playhead - 0.5) < 1e-9, `the playhead back at ${back.playhead} s`);
    assert.equal(await page.textContent("#zoom-level"), `${Math.round(view.camera.zoom * 100)}%`);
    await page.screenshot({ path: join(artifacts, "project-keys.png") });

    // A file of the earlier shape (its playhead a fraction of the timeline; no Length, Key mode
    // or camera) opens: the fraction read, the rest the defaults, named.
    const old = readFileSync(join(import.meta.dirname, "fixtures", "puppet-keys-v1.ikarus.json"), "utf8");
    // (Every line the status says is kept: the keyed motion's answer soon says its own.)
    await page.evaluate(() => {
      const stats = document.getElementById("stats");
      window.said = [];
      new MutationObserver(() => window.said.push(stats.textContent)).observe(stats, { childList: true, characterData: true, subtree: true });
    });
    await page.setInputFiles("#project-file", { name: "old.ikarus.json", mimeType: "application/json", buffer: Buffer.from(old) });
    await page.waitForFunction(() => window.said.some((t) => /^opened old/.test(t)));
    await keysSettled();
    assert.deepEqual(
      (await page.evaluate(() => window.said)).filter((t) => /^opened/.test(t)),
      ["opened old.ikarus.json · defaulted: key_length, key_mode, camera"],
    );
    const opened = await viewNow(page);
    assert.deepEqual([opened.mode, opened.length, opened.camera, opened.duration], ["false", "2", { zoom: 1, x: 0, y: 0 }, 2]);
    assert.ok(Math.abs(opened.playhead - 0.25 * 2) < 1e-9, `the fraction 0.25 of 2 s: ${opened.playhead} s`);
    assert.deepEqual(await page.evaluate(() => window.ikarus.state.keys), JSON.parse(old).keys);
  });
});
