// Zoom, pan and Fit on the playground's canvas, and the onion skins (issue 28, points 3 and 5),
// in a real browser: the hand rig zoomed ×20 with the wheel over a fingertip (the world point
// under the pointer stays under it), the fingertip dragged by a few pixels (the goal sent is the
// world point under the pointer), a drag on empty space pans, a two-finger pinch zooms, Fit and F
// go back; the grid's labels at 200× and 0.05× have the decimals they need and do not overlap;
// the arm zoomed out and clicked (the goal solved is the world point of the click), Space held
// pans without playing, a tap of Space plays; onion skins on the arm's motion shown (2 each
// side) and hidden. Screenshots go to $E2E_ARTIFACTS. Run: cd e2e && node --test zoom.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import { mkdirSync, readFileSync } from "node:fs";
import { join } from "node:path";
import { artifacts, ended, openPage, ready, withBrowser } from "./browser.mjs";
import { tipClient, worldAt } from "./rigpage.mjs";

/** Records the bodies of the page's /api/solve and /api/animate requests (window.sent). */
const watchRequests = (page) =>
  page.addInitScript(() => {
    window.sent = [];
    const fetch = window.fetch.bind(window);
    window.fetch = (input, init) => {
      const path = String(input);
      if (/\/api\/(solve|animate)$/.test(path) && init && typeof init.body === "string") window.sent.push({ path, body: JSON.parse(init.body) });
      return fetch(input, init);
    };
  });

const sent = (page) => page.evaluate(() => window.sent);
const settled = (page) => page.waitForFunction(() => window.ikarus.rigs.settled(), null, { timeout: 15000 });

const zoom = (page) => page.evaluate(() => Number(document.getElementById("plot").dataset.zoom));
const camera = (page) => page.evaluate(() => ({ ...window.ikarus.state.camera }));

/** |a − b| within `rel` of the larger magnitude of the two points' coordinates. */
function assertNear(p, q, rel, what) {
  const scale = Math.max(...p.map(Math.abs), ...q.map(Math.abs), 1e-300);
  const d = Math.max(Math.abs(p[0] - q[0]), Math.abs(p[1] - q[1]));
  assert.ok(d <= rel * scale, `${what}: ${p} is not ${q} (off by ${d})`);
}

/** After the next two frames (a redraw asked for has happened). */
const frames = (page) => page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));

const overlap = (a, b) => a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h;

/**
 * The axis labels drawn now: clear of each other, several numbers on each axis, each axis's
 * numbers all different (too few decimals would print neighbours alike) and printed with the
 * decimals their step needs. Returns the labels.
 */
async function assertLabels(page, what) {
  await frames(page);
  const labels = await page.evaluate(() => window.ikarus.state.view.labels);
  for (const [i, a] of labels.entries()) for (const b of labels.slice(i + 1)) assert.ok(!overlap(a, b), `${what}: "${a.text}" overlaps "${b.text}"`);
  const numbers = labels.filter((l) => l.text !== "x" && l.text !== "y");
  // x ticks share a row (the same y), y ticks a column.
  const rows = new Map();
  for (const l of numbers) rows.set(l.y, [...(rows.get(l.y) || []), l]);
  const xs = [...rows.values()].sort((a, b) => b.length - a.length)[0] || [];
  assert.ok(xs.length >= 3, `${what}: ${xs.length} x labels (${numbers.map((l) => l.text)})`);
  for (const axis of [xs, numbers.filter((l) => !xs.includes(l))]) {
    const texts = axis.map((l) => l.text);
    assert.equal(new Set(texts).size, texts.length, `${what}: labels printed alike: ${texts}`);
    const values = texts.map(Number).sort((a, b) => a - b);
    assert.ok(values.every(Number.isFinite), `${what}: ${texts}`);
    // Neighbouring ticks differ by the step: printed with its decimals, each label is exact.
    const step = Math.min(...values.slice(1).map((v, i) => v - values[i]));
    for (const t of texts) {
      const decimals = (t.split(".")[1] || "").length;
      assert.ok(Math.abs(Number(t) / step - Math.round(Number(t) / step)) < 1e-6, `${what}: ${t} is not a multiple of the step ${step}`);
      assert.ok(10 ** -decimals <= step * (1 + 1e-9), `${what}: ${t} has more decimals than the step ${step} needs`);
    }
  }
  return labels;
}

/** Runs `fn(page)` on the playground, loaded and ready, its requests recorded; no console errors after. */
async function onPage(fn) {
  mkdirSync(artifacts, { recursive: true });
  await withBrowser(async ({ url, browser }) => {
    const { page, errors } = await openPage(browser);
    await watchRequests(page);
    await page.goto(url);
    await ready(page);
    await fn(page);
    assert.deepEqual(errors, []);
  });
}

/** The canvas's box in client pixels. */
const canvasBox = (page) =>
  page.evaluate(() => {
    const r = document.getElementById("plot").getBoundingClientRect();
    return { x: r.left, y: r.top, w: r.width, h: r.height };
  });

test("the hand zoomed ×20 over a fingertip: the point stays under the pointer, a drag's goal is the world point under it; pan, pinch, Fit", async () => {
  await onPage(async (page) => {
    await page.selectOption("#body-kind", "rig:hand");
    await page.waitForFunction(() => window.ikarus.state.rig && window.ikarus.state.rig.rig.name === "hand");
    assert.equal(await zoom(page), 1);
    assert.equal(await page.isDisabled("#fit"), true);

    // Fifteen notches up over the index fingertip: e^3, about ×20. (The pointer on a whole
    // pixel: the browser's events carry whole pixels.)
    const tip = (await tipClient(page, "index_distal")).map(Math.round);
    await page.mouse.move(...tip);
    const under = await worldAt(page, ...tip);
    for (let k = 0; k < 15; k++) await page.mouse.wheel(0, -100);
    await page.waitForFunction(() => Number(document.getElementById("plot").dataset.zoom) > 20, null, { timeout: 5000 });
    assert.ok(Math.abs((await zoom(page)) - Math.exp(3)) < 1e-9, `zoom ${await zoom(page)}`);
    assertNear(await worldAt(page, ...tip), under, 1e-9, "the world point under the pointer after zooming");
    const grown = await tipClient(page, "index_distal");
    assert.ok(Math.hypot(grown[0] - tip[0], grown[1] - tip[1]) < 14, `the fingertip at ${grown}, the pointer at ${tip}`);
    assert.equal(await page.isDisabled("#fit"), false);
    assert.equal(await page.textContent("#zoom-level"), "2,009%");
    await page.screenshot({ path: join(artifacts, "zoom-hand-x20.png") });
    await assertLabels(page, "the hand at ×20");

    // Drag the fingertip by a few pixels: the goal sent is the world point under the pointer.
    const before = (await sent(page)).length;
    const cam = await camera(page);
    const to = [tip[0] + 6, tip[1] - 8];
    await page.mouse.down();
    await page.mouse.move(tip[0] + 3, tip[1] - 4);
    await page.mouse.move(...to);
    await settled(page);
    const want = await worldAt(page, ...to);
    await page.mouse.up();
    await settled(page);
    const solves = (await sent(page)).slice(before).filter((s) => s.body.rig);
    assert.ok(solves.length >= 1, "the drag sent a solve");
    const goal = solves.at(-1).body.goals.find((g) => g.bone === "index_distal");
    assertNear([goal.x, goal.y], want, 1e-9, "the goal sent");
    assert.deepEqual(await camera(page), cam, "a drag on an effector does not pan");
    // The goal is 10 pixels from where the tip was: 10 / (scale) world units.
    const scale = await page.evaluate(() => window.ikarus.state.view.scale);
    const pixels = Math.hypot(goal.x - under[0], goal.y - under[1]) * scale;
    assert.ok(Math.abs(pixels - 10) < 1e-6, `the goal is ${pixels} pixels from the pointer's press`);

    // A drag on empty space (the canvas's lower left, no tip within reach) pans: the world follows the pointer.
    const box = await canvasBox(page);
    const from = [box.x + 60, box.y + box.h - 90];
    const anchor = await worldAt(page, ...from);
    const goalsBefore = await page.evaluate(() => JSON.stringify([...window.ikarus.state.rig.goals]));
    const solvesBefore = (await sent(page)).length;
    await page.mouse.move(...from);
    await page.mouse.down();
    await page.mouse.move(from[0] + 40, from[1] - 30, { steps: 4 });
    await page.mouse.move(from[0] + 80, from[1] - 55, { steps: 4 });
    await page.mouse.up();
    assertNear(await worldAt(page, from[0] + 80, from[1] - 55), anchor, 1e-9, "the world point dragged");
    assert.equal((await camera(page)).zoom, cam.zoom, "a pan keeps the zoom");
    assert.equal(await page.evaluate(() => JSON.stringify([...window.ikarus.state.rig.goals])), goalsBefore, "a pan moves no goal");
    assert.equal((await sent(page)).length, solvesBefore, "a pan solves nothing");

    // A two-finger pinch on empty space: the spread doubles, so does the zoom; the point under the
    // first midpoint goes under the second.
    const z0 = await zoom(page);
    const [a, b] = [[box.x + 100, box.y + 300], [box.x + 200, box.y + 300]];
    const midWorld = await worldAt(page, 150 + box.x, 300 + box.y);
    await page.evaluate(
      ([a, b]) => {
        const canvas = document.getElementById("plot");
        const ev = (type, id, [x, y]) => canvas.dispatchEvent(new PointerEvent(type, { pointerId: id, pointerType: "touch", isPrimary: id === 11, clientX: x, clientY: y, button: type === "pointermove" ? -1 : 0, bubbles: true, cancelable: true }));
        ev("pointerdown", 11, a);
        ev("pointerdown", 12, b);
        ev("pointermove", 12, [b[0] + 50, b[1]]);
        ev("pointermove", 12, [b[0] + 100, b[1]]);
        ev("pointerup", 12, [b[0] + 100, b[1]]);
        ev("pointerup", 11, a);
      },
      [a, b],
    );
    assert.ok(Math.abs((await zoom(page)) / z0 - 2) < 1e-9, `pinch: ${z0} → ${await zoom(page)}`);
    assertNear(await worldAt(page, box.x + 200, box.y + 300), midWorld, 1e-9, "the pinch's midpoint");

    // Fit, and F, go back to the fitted view.
    await page.click("#fit");
    assert.equal(await zoom(page), 1);
    assert.deepEqual(await camera(page), { zoom: 1, x: 0, y: 0 });
    await page.mouse.move(...tip);
    await page.mouse.wheel(0, -300);
    assert.ok((await zoom(page)) > 1);
    await page.focus("#plot");
    await page.keyboard.press("f");
    assert.equal(await zoom(page), 1);
    // + and - zoom about the canvas's centre.
    const centreWorld = () => page.evaluate(() => {
      const v = window.ikarus.state.view;
      return [(v.w / 2 - v.cx) / v.scale, (v.cy - v.h / 2) / v.scale];
    });
    const mid = await centreWorld();
    await page.keyboard.press("+");
    await page.keyboard.press("+");
    assert.ok(Math.abs((await zoom(page)) - 1.5625) < 1e-12, `+ +: ${await zoom(page)}`);
    await page.keyboard.press("-");
    assert.ok(Math.abs((await zoom(page)) - 1.25) < 1e-12, `+ + -: ${await zoom(page)}`);
    assertNear(await centreWorld(), mid, 1e-9, "the centre after + and -");
    await page.keyboard.press("f");
    // F typed in a field is a letter, not Fit.
    await page.mouse.wheel(0, -300);
    await page.focus("#restarts");
    await page.keyboard.press("f");
    assert.ok((await zoom(page)) > 1, "F in a field");
    await page.click("#fit");

    // The grid at the ends of the zoom: 200× about the wrist and 0.05×.
    const wrist = (await tipClient(page, "wrist")).map(Math.round);
    await page.mouse.move(...wrist);
    for (let k = 0; k < 60; k++) await page.mouse.wheel(0, -100);
    assert.equal(await zoom(page), 200);
    await assertLabels(page, "the hand at 200×");
    await page.screenshot({ path: join(artifacts, "zoom-hand-x200.png") });
    for (let k = 0; k < 100; k++) await page.mouse.wheel(0, 100);
    assert.equal(await zoom(page), 0.05);
    await assertLabels(page, "the hand at 0.05×");
    await page.screenshot({ path: join(artifacts, "zoom-hand-x005.png") });

    // Another body resets the camera.
    await page.selectOption("#body-kind", "rig:puppet");
    await page.waitForFunction(() => window.ikarus.state.rig.rig.name === "puppet");
    await frames(page);
    assert.equal(await zoom(page), 1);
  });
});

test("the arm zoomed out: a click's goal is the world point clicked; Space held pans without playing, a tap plays; onion skins", async () => {
  await onPage(async (page) => {
    const box = await canvasBox(page);
    const centre = [Math.round(box.x + box.w / 2), Math.round(box.y + box.h / 2)];
    // Eight frames: the skins stand apart.
    await page.fill("#frames", "8");
    await page.dispatchEvent("#frames", "change");
    await page.mouse.move(...centre);
    for (let k = 0; k < 10; k++) await page.mouse.wheel(0, 100);
    assert.ok(Math.abs((await zoom(page)) - Math.exp(-2)) < 1e-9);

    // A click sets the goal at the world point under it, exactly.
    const click = [centre[0] + 37, centre[1] - 21];
    const want = await worldAt(page, ...click);
    await page.mouse.click(...click);
    await ended(page);
    const animate = (await sent(page)).filter((s) => s.path.endsWith("/api/animate")).at(-1);
    assertNear([animate.body.goal.x, animate.body.goal.y], want, 1e-9, "the goal solved");
    const goal = await page.evaluate(() => window.ikarus.state.goal);
    assertNear([goal.x, goal.y], want, 1e-9, "the goal drawn");

    // Space held + drag pans: no goal, no play; the world follows the pointer.
    const requests = (await sent(page)).length;
    const anchor = await worldAt(page, box.x + 200, box.y + 200);
    await page.mouse.move(box.x + 200, box.y + 200);
    await page.keyboard.down(" ");
    await page.mouse.down();
    await page.mouse.move(box.x + 260, box.y + 240, { steps: 5 });
    await page.mouse.up();
    await page.keyboard.up(" ");
    assertNear(await worldAt(page, box.x + 260, box.y + 240), anchor, 1e-9, "Space + drag");
    assert.equal((await sent(page)).length, requests, "a pan asks nothing");
    assert.equal(await page.evaluate(() => document.body.dataset.playback), "ended", "Space held to pan does not play");
    // The middle button pans too.
    const anchor2 = await worldAt(page, box.x + 300, box.y + 300);
    await page.mouse.move(box.x + 300, box.y + 300);
    await page.mouse.down({ button: "middle" });
    await page.mouse.move(box.x + 280, box.y + 330, { steps: 3 });
    await page.mouse.up({ button: "middle" });
    assertNear(await worldAt(page, box.x + 280, box.y + 330), anchor2, 1e-9, "middle drag");
    assert.equal((await sent(page)).length, requests, "a middle-button pan asks nothing");
    // A trackpad's pinch (ctrl + wheel) zooms about the pointer, in finer steps.
    const z0 = await zoom(page);
    const under = await worldAt(page, box.x + 300, box.y + 300);
    await page.mouse.move(box.x + 300, box.y + 300);
    await page.keyboard.down("Control");
    await page.mouse.wheel(0, -20);
    await page.keyboard.up("Control");
    assert.ok(Math.abs((await zoom(page)) / z0 - Math.exp(0.2)) < 1e-9, `ctrl+wheel: ${z0} → ${await zoom(page)}`);
    assertNear(await worldAt(page, box.x + 300, box.y + 300), under, 1e-9, "ctrl + wheel");
    // The camera stays while the arm moves and plays; a tap of Space plays.
    const cam = await camera(page);
    await page.focus("#plot");
    await page.keyboard.press(" ");
    await page.waitForFunction(() => document.body.dataset.playback !== "ended", null, { timeout: 5000 });
    await ended(page);
    assert.deepEqual(await camera(page), cam);
    await page.screenshot({ path: join(artifacts, "zoom-arm.png") });

    // Onion skins, 2 each side, at the middle of the motion: drawn; off: gone, the canvas as before.
    await page.click("#fit");
    await page.evaluate(() => {
      const s = document.getElementById("scrubber");
      s.value = "500";
      s.dispatchEvent(new Event("input"));
    });
    await frames(page);
    const pixels = () => page.evaluate(() => document.getElementById("plot").toDataURL());
    const plain = await pixels();
    assert.equal(await page.evaluate(() => document.getElementById("plot").dataset.onion), "0 0");
    await page.check("#onion");
    await page.fill("#onion-count", "2");
    await page.dispatchEvent("#onion-count", "change");
    await frames(page);
    assert.equal(await page.evaluate(() => document.getElementById("plot").dataset.onion), "2 2");
    const onion = await pixels();
    assert.notEqual(onion, plain, "the skins change the canvas");
    // How many pixels the skins changed, read back from the canvas.
    const changed = await page.evaluate(async ([a, b]) => {
      const load = (src) => new Promise((r) => Object.assign(new Image(), { src, onload() { r(this); } }));
      const [ia, ib] = await Promise.all([load(a), load(b)]);
      const data = (img) => {
        const c = Object.assign(document.createElement("canvas"), { width: img.width, height: img.height });
        const g = c.getContext("2d");
        g.drawImage(img, 0, 0);
        return g.getImageData(0, 0, img.width, img.height).data;
      };
      const [da, db] = [data(ia), data(ib)];
      let n = 0;
      for (let i = 0; i < da.length; i += 4) if (Math.abs(da[i] - db[i]) + Math.abs(da[i + 1] - db[i + 1]) + Math.abs(da[i + 2] - db[i + 2]) > 30) n++;
      return n;
    }, [plain, onion]);
    assert.ok(changed > 500, `${changed} pixels changed by the skins`);
    await page.screenshot({ path: join(artifacts, "onion-arm.png") });
    // A bad count is named; the skins keep the last good one.
    await page.fill("#onion-count", "11");
    await page.dispatchEvent("#onion-count", "change");
    assert.match(await page.textContent("#error"), /Onion skins: must be a whole number from 1 to 10/);
    await page.fill("#onion-count", "2");
    await page.dispatchEvent("#onion-count", "change");
    assert.equal(await page.isVisible("#error"), false);
    await page.uncheck("#onion");
    await frames(page);
    assert.equal(await page.evaluate(() => document.getElementById("plot").dataset.onion), "0 0");
    assert.equal(await pixels(), plain, "off: the canvas as it was");
  });
});

test("spineboy zoomed ×4 about its front leg's target: the target dragged lands on the world point under the pointer; empty space pans", async () => {
  await onPage(async (page) => {
    const text = readFileSync(join(import.meta.dirname, "..", "examples", "characters", "spine-spineboy-pro.json"));
    await page.setInputFiles("#rig-file", { name: "spineboy.json", mimeType: "application/json", buffer: text });
    await page.waitForFunction(() => window.ikarus.state.character && window.ikarus.state.character.posed && window.ikarus.characters.settled(), null, { timeout: 15000 });
    await frames(page);
    const handle = () =>
      page.evaluate(() => {
        const b = window.ikarus.state.character.posed.find((b) => b.name === "front-leg-target");
        return window.ikarus.toClient(b.x, b.y).map(Math.round);
      });
    const at = await handle();
    await page.mouse.move(...at);
    const under = await worldAt(page, ...at);
    for (let k = 0; k < 7; k++) await page.mouse.wheel(0, -100);
    assert.ok(Math.abs((await zoom(page)) - Math.exp(1.4)) < 1e-9);
    assertNear(await worldAt(page, ...at), under, 1e-9, "the point under the pointer");
    // The handle is still under the pointer (within its ring): a drag moves the target.
    await page.mouse.down();
    await page.mouse.move(at[0] + 4, at[1] + 4);
    await page.mouse.move(at[0] + 9, at[1] + 12);
    const want = await worldAt(page, at[0] + 9, at[1] + 12);
    await page.mouse.up();
    await page.waitForFunction(() => window.ikarus.characters.settled(), null, { timeout: 15000 });
    const put = await page.evaluate(() => window.ikarus.state.character.targets.get("front-leg-target"));
    assertNear([put.x, put.y], want, 1e-9, "the target put");
    // A press on empty space (the upper left, no handle there) pans and moves no target.
    const box = await canvasBox(page);
    const from = [box.x + 40, box.y + 120];
    const anchor = await worldAt(page, ...from);
    await page.mouse.move(...from);
    await page.mouse.down();
    await page.mouse.move(from[0] + 50, from[1] + 70, { steps: 5 });
    await page.mouse.up();
    assertNear(await worldAt(page, from[0] + 50, from[1] + 70), anchor, 1e-9, "the pan");
    const still = await page.evaluate(() => window.ikarus.state.character.targets.get("front-leg-target"));
    assert.deepEqual(still, put);
    await page.screenshot({ path: join(artifacts, "zoom-spineboy.png") });
    // Back to the arm: the camera is the arm's fit.
    await page.selectOption("#body-kind", "arm");
    await frames(page);
    assert.equal(await zoom(page), 1);
  });
});
