// The canvas's layout (issue 24): the axis labels never overlap each other (the "x" name and the
// "8" tick at 1280 px, "1x6" in the rig view) nor sit under the status chip; the canvas keeps its
// size (and the drawing its scale) while the timeline's contents change; the arrow keys and
// Enter work wherever the focus is but in a field or on a button.
import { test } from "node:test";
import assert from "node:assert/strict";
import { mkdirSync } from "node:fs";
import { join } from "node:path";
import { artifacts, ended, openPage, ready, setField, withBrowser } from "./browser.mjs";

const VIEWPORTS = [
  { width: 1280, height: 800 },
  { width: 400, height: 800 },
  { width: 375, height: 667 },
];

/**
 * The labels drawn last ({text, x, y, w, h}, canvas pixels) and the chip's box in the same
 * pixels, after the next frames (the page redraws when the chip changes size).
 */
async function labelsAndChip(page) {
  await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
  return page.evaluate(() => {
    const c = document.getElementById("plot").getBoundingClientRect();
    const r = document.getElementById("chip").getBoundingClientRect();
    return { labels: window.ikarus.state.view.labels, chip: { x: r.left - c.left, y: r.top - c.top, w: r.width, h: r.height } };
  });
}

const overlap = (a, b) => a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h;
const show = (l) => `"${l.text}" at (${l.x.toFixed(1)}, ${l.y.toFixed(1)}) ${l.w.toFixed(1)}×${l.h}`;

/** Every label clear of every other and of the chip; the axis names and some ticks drawn. */
function assertClear({ labels, chip }, what) {
  assert.ok(labels.some((l) => l.text === "x") && labels.some((l) => l.text === "y"), `${what}: the axis names are drawn`);
  assert.ok(labels.length >= 8, `${what}: ${labels.length} labels`);
  for (const [i, a] of labels.entries()) {
    assert.ok(!overlap(a, chip), `${what}: ${show(a)} is under the chip (${JSON.stringify(chip)})`);
    for (const b of labels.slice(i + 1)) assert.ok(!overlap(a, b), `${what}: ${show(a)} overlaps ${show(b)}`);
  }
}

test("axis labels: clear of each other and of the chip, for the arm and the rig, at every width", async () => {
  await withBrowser(async ({ url, browser }) => {
    for (const viewport of VIEWPORTS) {
      const { page, errors } = await openPage(browser, viewport);
      await page.goto(url);
      await ready(page);
      const what = `${viewport.width} px`;
      assertClear(await labelsAndChip(page), what);
      // At 1280 px the "x" sits above the axis at its right end, clear of the "8" under it.
      const first = await labelsAndChip(page);
      if (viewport.width === 1280) assert.ok(first.labels.some((l) => l.text === "8"), "the 8 tick is drawn");
      // A wide chip (a status line and a message) over the top of the y axis.
      await page.evaluate(() => window.ikarus.animateTo(-2, 3));
      await ended(page);
      // (Typed in as the panel's field would be, the panel staying as it is.)
      const restarts = (v) => page.evaluate((v) => {
        const el = document.getElementById("restarts");
        el.value = v;
        el.dispatchEvent(new Event("change"));
      }, v);
      await restarts("-3");
      await page.evaluate(() => window.ikarus.animateTo(1, 3));
      // (The click opened the panel at the field; a narrow window hides it again.)
      if (viewport.width < 720) await page.click("#panel-toggle");
      const wide = await labelsAndChip(page);
      assert.ok(wide.chip.h > 30, `${what}: the chip holds two lines`);
      assertClear(wide, `${what} with a message`);
      await restarts("4");
      // The rig's view: labels of tenths ("1x6" was the x name over "1.6").
      await page.evaluate(() => window.ikarus.rigs.use("rig:puppet"));
      await page.waitForFunction(() => window.ikarus.rigs.settled() && window.ikarus.state.rig, null, { timeout: 15000 });
      assertClear(await labelsAndChip(page), `${what}, the puppet`);
      assert.deepEqual(errors, [], `${what}: console errors`);
      await page.close();
    }
  });
});

test("the canvas keeps its size while the timeline's contents change; its rows follow the width alone", async () => {
  await withBrowser(async ({ url, browser }) => {
    for (const viewport of [...VIEWPORTS, { width: 1262, height: 800 }, { width: 1100, height: 800 }]) {
      const { page, errors } = await openPage(browser, viewport);
      await page.goto(url);
      await ready(page);
      const sizes = () =>
        page.evaluate(() => {
          const c = document.getElementById("plot").getBoundingClientRect();
          return { canvas: [c.width, c.height], scale: window.ikarus.state.view.scale, timeline: document.getElementById("timeline").getBoundingClientRect().height };
        });
      const what = `${viewport.width} px`;
      const before = await sizes();
      // A motion, two via points ("Clear 2 via points"), a long duration ("0.31 / 12.50 s"), playing ("Pause").
      await page.evaluate(() => window.ikarus.animateTo(-2, 3));
      await ended(page);
      assert.deepEqual(await sizes(), before, `${what}: after a motion`);
      const [x, y] = await page.evaluate(() => window.ikarus.toClient(1, 4));
      await page.keyboard.down("Shift");
      await page.mouse.click(x, y);
      await page.mouse.click(x + 30, y);
      await page.keyboard.up("Shift");
      assert.match(await page.textContent("#clear-via"), /Clear 2 via points/);
      assert.deepEqual(await sizes(), before, `${what}: with via points`);
      await setField(page, "#duration", "12.5");
      await page.evaluate(() => window.ikarus.animateTo(2, 3));
      await page.waitForFunction(() => document.body.dataset.playback === "playing", null, { timeout: 15000 });
      await page.waitForTimeout(200);
      assert.match(await page.textContent("#playtime"), /\/ 12\.50 s/);
      assert.deepEqual(await sizes(), before, `${what}: playing a 12.5 s motion`);
      // Nothing in the bar is cut off or spills out of it.
      const spill = await page.evaluate(() => {
        const bar = document.getElementById("timeline").getBoundingClientRect();
        return [...document.querySelectorAll("#timeline > *")]
          .filter((el) => el.scrollWidth > el.clientWidth + 1 || el.getBoundingClientRect().right > bar.right + 0.5)
          .map((el) => el.id || el.className);
      });
      assert.deepEqual(spill, [], `${what}: cut off`);
      assert.deepEqual(errors, [], `${what}: console errors`);
      await page.close();
    }
  });
});

test("arrow keys and Enter work with the focus anywhere but in a field or on a button", async () => {
  await withBrowser(async ({ url, browser }) => {
    const { page, errors } = await openPage(browser);
    await page.goto(url);
    await ready(page);
    const goal = () => page.evaluate(() => window.ikarus.state.goal);
    const tip = await page.evaluate(() => window.ikarus.state.joints.at(-1));
    // The focus on the page itself (nothing focused): ArrowUp moves the goal a 40th of the reach (6) up.
    await page.evaluate(() => document.activeElement && document.activeElement.blur());
    assert.equal(await page.evaluate(() => document.activeElement === document.body), true);
    await page.keyboard.press("ArrowUp");
    await page.keyboard.press("ArrowLeft");
    const g = await goal();
    assert.ok(g, "ArrowUp with the focus on the page moves the goal");
    assert.ok(Math.abs(g.x - (tip[0] - 0.15)) < 1e-9 && Math.abs(g.y - (tip[1] + 0.15)) < 1e-9, `goal ${JSON.stringify(g)}, tip ${tip}`);
    // Enter moves the arm there.
    await page.keyboard.press("Enter");
    await ended(page);
    const end = await page.evaluate(() => window.ikarus.state.joints.at(-1));
    assert.ok(Math.hypot(end[0] - g.x, end[1] - g.y) < 1e-5, `tip at ${end}, goal ${JSON.stringify(g)}`);
    // A click on the panel's background (not a field) leaves the keys to the page too.
    await page.mouse.click(1270, 790);
    await page.keyboard.press("ArrowDown");
    assert.ok(Math.abs((await goal()).y - (g.y - 0.15)) < 1e-9, "ArrowDown after a click on the panel");
    // In a field the keys are the field's: the goal stays.
    const held = await goal();
    await page.focus("#restarts");
    await page.keyboard.press("ArrowUp");
    assert.deepEqual(await goal(), held);
    assert.equal(await page.inputValue("#restarts"), "17", "the field took the key");
    // On a button too.
    await page.focus("#reset");
    await page.keyboard.press("ArrowLeft");
    assert.deepEqual(await goal(), held);
    // And on the scrubber the arrows move the playhead, not the goal.
    await page.focus("#scrubber");
    await page.keyboard.press("ArrowLeft");
    assert.deepEqual(await goal(), held);
    assert.deepEqual(errors, []);
  });
});

test("a narrow window: opening the controls leaves the canvas a usable size, the controls below it scrolling", async () => {
  mkdirSync(artifacts, { recursive: true });
  await withBrowser(async ({ url, browser }) => {
    for (const viewport of [
      { width: 400, height: 800 },
      { width: 375, height: 667 },
    ]) {
      const { page, errors } = await openPage(browser, viewport);
      await page.goto(url);
      await ready(page);
      const what = `${viewport.width}×${viewport.height}`;
      const box = (id) => page.evaluate((i) => JSON.parse(JSON.stringify(document.getElementById(i).getBoundingClientRect())), id);
      const closed = await box("plot");
      if (!(await page.evaluate(() => document.body.classList.contains("collapsed")))) await page.click("#panel-toggle");
      await page.click("#panel-toggle");
      assert.equal(await page.evaluate(() => document.body.classList.contains("collapsed")), false, `${what}: the controls open`);
      await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
      await page.screenshot({ path: join(artifacts, `layout-narrow-${viewport.width}-open.png`) });
      const open = await box("plot");
      const panel = await box("panel");
      assert.ok(open.height >= 0.45 * viewport.height, `${what}: the canvas is ${open.height} px tall with the controls open (${closed.height} px closed)`);
      assert.ok(open.width >= viewport.width - 1, `${what}: the canvas keeps the window's width (${open.width} px)`);
      assert.ok(panel.top >= open.bottom - 0.5 && panel.height >= 120, `${what}: the controls below the canvas (${JSON.stringify(panel)})`);
      assert.ok(panel.bottom <= viewport.height + 0.5, `${what}: the controls inside the window`);
      assert.ok(await page.evaluate(() => getComputedStyle(document.getElementById("panel")).overflowY === "auto"), `${what}: the controls scroll`);
      // A rig: the keys bar shows under the timeline too; the canvas keeps its height.
      await page.evaluate(() => window.ikarus.rigs.use("rig:puppet"));
      await page.waitForFunction(() => window.ikarus.rigs.settled() && window.ikarus.state.rig, null, { timeout: 15000 });
      if (await page.evaluate(() => document.body.classList.contains("collapsed"))) await page.click("#panel-toggle");
      await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
      await page.screenshot({ path: join(artifacts, `layout-narrow-${viewport.width}-rig-open.png`) });
      const rig = await box("plot");
      assert.ok(rig.height >= 0.45 * viewport.height, `${what}: with a rig the canvas is ${rig.height} px tall with the controls open`);
      assert.deepEqual(errors, [], `${what}: console errors`);
      await page.close();
    }
  });
});
