// What a new user trips on (issue 11, the playground): the page starts with the CLI's defaults
// and its first solve of (2, 3) gives `ikarus solve --goal 2,3`'s angles; errors show on a chip
// on the canvas at every width, the bad field is marked and focused, messages number links from
// 1 and name the control, and no request is rejected (so the console stays clean); start angles,
// the base and ranges can be edited (the pose moves into a new range); methods that cannot solve
// the arm are hidden and the closed form works with a goal angle; "reached" only once the arm
// stops; Reset pose drops the goal; hidden controls give the canvas the whole width; the
// reachable area stays drawn while it recomputes; "Replay every" changes the solver's replay.
import { test } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { binary, ended, launch, onPlayground, openPage, ready, startServer } from "./browser.mjs";

/** The chip's text, colour kind and whether it is on screen. */
const chip = (page) =>
  page.evaluate(() => {
    const el = document.getElementById("chip");
    const r = el.getBoundingClientRect();
    const visible = r.width > 0 && r.height > 0 && r.top >= 0 && r.left >= 0 && r.bottom <= innerHeight && r.right <= innerWidth;
    return { text: el.innerText, kind: el.dataset.kind, visible };
  });
const setField = async (page, selector, value) => {
  await page.fill(selector, value);
  await page.dispatchEvent(selector, "change");
};

test("the page's first solve of (2, 3) gives the CLI's angles (the same defaults)", () => {
  const cli = JSON.parse(execFileSync(binary, ["solve", "--goal", "2,3", "--format", "json"], { encoding: "utf8" }));
  const answers = [];
  return onPlayground(
    async (page) => {
      await page.evaluate(() => window.ikarus.animateTo(2, 3));
      await ended(page);
      assert.equal(answers.length, 1);
      assert.equal(answers[0].status, cli.status);
      cli.angles_deg.forEach((a, i) => assert.ok(Math.abs(answers[0].angles_deg[i] - a) < 1e-9, `joint ${i + 1}: ${answers[0].angles_deg[i]} vs the CLI's ${a}`));
      const drawn = (await page.evaluate(() => document.getElementById("plot").dataset.pose)).split(" ").map(Number);
      cli.angles_deg.forEach((a, i) => assert.ok(Math.abs(drawn[i] - a) < 1e-5, `drawn joint ${i + 1}: ${drawn[i]} vs ${a}`));
    },
    { before: (page) => page.on("response", async (r) => r.url().endsWith("/api/solve") && answers.push(await r.json())) },
  );
});

test("errors: a chip on the canvas at every width, the field marked and focused, no rejected request", async () => {
  const { child, url } = await startServer();
  const browser = await launch();
  try {
    for (const viewport of [
      { width: 1280, height: 800 },
      { width: 400, height: 800 },
      { width: 375, height: 667 },
    ]) {
      const { page, errors } = await openPage(browser, viewport);
      const requests = [];
      page.on("request", (r) => r.url().includes("/api/") && requests.push(r.url()));
      await page.goto(url);
      await ready(page);
      const status = await chip(page);
      assert.ok(status.visible, `${viewport.width} px: the chip is on screen`);
      assert.equal(status.kind, "neutral");

      // Restarts = −3, then a click on the canvas: nothing is sent, the chip turns red and says
      // which control and why, the field is marked, focused and in view.
      const before = requests.length;
      await page.evaluate(() => document.body.classList.contains("collapsed") && document.getElementById("panel-toggle").click());
      await setField(page, "#restarts", "-3");
      // Scroll the field out of view first (the Motion section in view), and hide the panel
      // on narrow screens, as a reader would have it.
      await page.evaluate(() => document.getElementById("frames").scrollIntoView());
      if (viewport.width < 720) await page.click("#panel-toggle");
      await page.evaluate(() => document.getElementById("plot").focus());
      const [cx, cy] = await page.evaluate(() => window.ikarus.toClient(2, 3));
      await page.mouse.click(cx, cy);
      const bad = await chip(page);
      assert.ok(bad.visible, `${viewport.width} px: the chip is on screen`);
      assert.equal(bad.kind, "bad");
      assert.match(bad.text, /Restarts: must be a whole number from 0 to 64/);
      assert.doesNotMatch(bad.text, /expected u32|line 1 column/);
      const field = await page.evaluate(() => {
        const el = document.getElementById("restarts");
        const r = el.getBoundingClientRect();
        const panel = document.getElementById("panel").getBoundingClientRect();
        return {
          invalid: el.getAttribute("aria-invalid"),
          focused: document.activeElement === el,
          inView: r.height > 0 && r.top >= Math.max(0, panel.top) && r.bottom <= Math.min(innerHeight, panel.bottom),
        };
      });
      assert.deepEqual(field, { invalid: "true", focused: true, inView: true }, `${viewport.width} px`);
      // Nor from tracing a shape or following the pointer.
      await page.evaluate(() => document.getElementById("trace-circle").click());
      await page.evaluate(() => window.ikarus.followTo(1, 4));
      assert.equal(requests.length, before, `no request with a bad field: ${requests.slice(before)}`);
      assert.notEqual(await page.evaluate(() => window.ikarus.state.goal), "moved");

      // Fixed, the mark and the message go and a click solves.
      await setField(page, "#restarts", "4");
      assert.equal(await page.getAttribute("#restarts", "aria-invalid"), null);
      assert.equal((await chip(page)).kind, "neutral");
      await page.evaluate(() => window.ikarus.animateTo(2, 3));
      await ended(page);
      assert.equal(await page.evaluate(() => document.body.dataset.status), "reached");

      // Frames = 1, min > max: named for people, links from 1.
      await setField(page, "#frames", "1");
      await page.evaluate(() => window.ikarus.animateTo(1, 3));
      assert.match((await chip(page)).text, /Frames: must be a whole number from 2 to 2000/);
      await setField(page, "#frames", "60");
      await setField(page, "#links-body tr:nth-child(2) td:nth-child(4) input", "100");
      assert.match((await chip(page)).text, /Link 2 range: the minimum 100° is more than the maximum 90°/);
      assert.equal(await page.getAttribute("#links-body tr:nth-child(2) td:nth-child(4) input", "aria-invalid"), "true");
      await setField(page, "#links-body tr:nth-child(2) td:nth-child(4) input", "-90");
      assert.equal((await chip(page)).kind, "neutral");
      assert.deepEqual(errors, [], `${viewport.width} px: console errors`);
      await page.close();
    }
  } finally {
    await browser.close();
    child.kill("SIGINT");
  }
});

test("start angles, base and ranges: editable, and a new range takes the pose in", () =>
  onPlayground(async (page) => {
    await page.check("#limits");
    const cell = (row, col) => `#links-body tr:nth-child(${row}) td:nth-child(${col}) input`;
    // Joint 1's range [10°, 45°]: the start angle (5°) and the pose move to 10°, and solves work.
    await setField(page, cell(1, 4), "10");
    assert.deepEqual(await page.evaluate(() => window.ikarus.state.arm.links[0].limits_deg), [10, 45]);
    assert.equal(await page.evaluate(() => window.ikarus.state.arm.links[0].angle_deg), 10);
    assert.equal(await page.inputValue(cell(1, 3)), "10");
    assert.equal(await page.evaluate(() => window.ikarus.state.pose_deg[0]), 10);
    await page.evaluate(() => window.ikarus.animateTo(2, 3));
    await ended(page);
    assert.equal((await chip(page)).kind, "neutral");
    assert.equal(await page.evaluate(() => document.body.dataset.status), "reached");
    const p = await page.evaluate(() => window.ikarus.state.pose_deg[0]);
    assert.ok(p >= 10 - 1e-9 && p <= 45 + 1e-9, `joint 1 at ${p}°`);

    // Clearing one bound keeps the other: the cell shows the open end.
    await setField(page, cell(1, 5), "");
    assert.deepEqual(await page.evaluate(() => window.ikarus.state.arm.links[0].limits_deg), [10, 180]);
    assert.equal(await page.inputValue(cell(1, 5)), "180");

    // Start angles and the base are edited in the table and the base fields.
    await page.click("#reset");
    await setField(page, cell(2, 3), "30");
    assert.equal(await page.evaluate(() => window.ikarus.state.pose_deg[1]), 30);
    await setField(page, cell(2, 3), "95");
    assert.match((await chip(page)).text, /Link 2 start angle: 95° is outside its range \[-90°, 90°\]/);
    await setField(page, cell(2, 3), "30");
    await setField(page, "#base-x", "1");
    await setField(page, "#base-y", "-0.5");
    const joints = await page.evaluate(() => window.ikarus.state.joints);
    assert.deepEqual(joints[0], [1, -0.5]);
    await page.evaluate(() => window.ikarus.animateTo(3, 2));
    await ended(page);
    const tip = await page.evaluate(() => window.ikarus.state.joints.at(-1));
    assert.ok(Math.hypot(tip[0] - 3, tip[1] - 2) < 1e-5, `tip at ${tip}`);
  }));

test("controls: methods that apply, a goal angle, limit modes, reached at the end, reset, layout, the area kept", () =>
  onPlayground(async (page, { url }) => {
    const offered = () => page.evaluate(() => [...document.getElementById("method").options].filter((o) => !o.disabled).map((o) => o.value));

    // Three links: no closed form until a goal angle is set; then it solves (2, 3) pointing at 90°.
    assert.ok(!(await offered()).includes("analytic"));
    await page.check("#use-goal-angle");
    await setField(page, "#goal-angle", "90");
    assert.ok((await offered()).includes("analytic"));
    await page.selectOption("#method", "analytic");
    const solves = [];
    page.on("request", (r) => r.url().endsWith("/api/solve") && solves.push(JSON.parse(r.postData())));
    await page.evaluate(() => window.ikarus.animateTo(2, 3));
    // "moving" while the arm moves; "reached" only once it stops.
    await page.waitForFunction(() => document.body.dataset.playback === "playing", null, { timeout: 15000 });
    assert.equal(await page.evaluate(() => document.body.dataset.status), "moving");
    assert.doesNotMatch(await page.textContent("#stats"), /reached/);
    await ended(page);
    assert.equal(await page.evaluate(() => document.body.dataset.status), "reached");
    assert.match(await page.textContent("#stats"), /status reached/);
    assert.deepEqual(solves.at(-1).goal, { x: 2, y: 3, angle_deg: 90 });
    const joints = await page.evaluate(() => window.ikarus.state.joints);
    const [a, b] = joints.slice(-2);
    assert.ok(Math.abs((Math.atan2(b[1] - a[1], b[0] - a[0]) * 180) / Math.PI - 90) < 1e-3);
    // Without the goal angle the closed form gives way to the default method.
    await page.uncheck("#use-goal-angle");
    assert.equal(await page.inputValue("#method"), "lm");
    // Two links: the closed form is offered.
    await page.click("#links-body tr:nth-child(3) button");
    assert.ok((await offered()).includes("analytic"));

    // Method names are not cut off.
    const cut = await page.evaluate(() => {
      const el = document.getElementById("method");
      const c = document.createElement("canvas").getContext("2d");
      c.font = getComputedStyle(el).font;
      const widest = Math.max(...[...el.options].map((o) => c.measureText(o.text).width));
      return { widest, room: el.clientWidth - 30 };
    });
    assert.ok(cut.widest <= cut.room, `the longest name needs ${cut.widest} px, the list has ${cut.room}`);

    // Reset pose drops the goal marker.
    assert.notEqual(await page.evaluate(() => window.ikarus.state.goal), null);
    await page.click("#reset");
    assert.equal(await page.evaluate(() => window.ikarus.state.goal), null);

    // The reachable area stays drawn while the next one is computed.
    await page.check("#show-workspace");
    // The area drawn: the exact region (a server that sends its boundary) or the grid's edge.
    await page.waitForFunction(() => window.ikarus.state.region || window.ikarus.state.areaOutline, null, { timeout: 15000 });
    let release;
    const held = new Promise((r) => (release = r));
    await page.route("**/api/workspace", async (route) => {
      await held;
      await route.continue();
    });
    await page.check("#limits");
    await page.waitForTimeout(400);
    assert.ok(
      await page.evaluate(() => (window.ikarus.state.region || { loops: window.ikarus.state.areaOutline || [] }).loops.length > 0),
      "the old area is kept",
    );
    const old = await page.evaluate(() => window.ikarus.state.workspace.limits);
    assert.equal(old, false);
    release();
    await page.waitForFunction(() => window.ikarus.state.workspace.limits === true, null, { timeout: 15000 });
    await page.unroute("**/api/workspace");

    // Hidden controls give the canvas the whole width.
    await page.click("#panel-toggle");
    await page.waitForTimeout(100);
    const width = await page.evaluate(() => document.getElementById("plot").getBoundingClientRect().width);
    assert.equal(Math.round(width), 1280);
    await page.click("#panel-toggle");
  }));

test("limit modes are fixed for CCD and FABRIK; Replay every shapes the solver's replay", () => {
  const animates = [];
  return onPlayground(
    async (page) => {
      await page.check("#limits");
      for (const [method, disabled] of [["ccd", true], ["fabrik", true], ["lm", false], ["dls", false]]) {
        await page.selectOption("#method", method);
        assert.equal(await page.isDisabled("#limit-mode"), disabled, method);
      }
      await page.selectOption("#method", "transpose");
      await page.evaluate(() => window.ikarus.animateTo(2, 3));
      await ended(page);
      await page.click("#solver");
      await page.waitForFunction(() => document.getElementById("timeline").dataset.source === "solver", null, { timeout: 15000 });
      await ended(page);
      const every1 = await page.evaluate(() => window.ikarus.state.animation.frames.length);
      const iterations = await page.evaluate(() => window.ikarus.state.animation.solves[0].iterations);
      assert.equal(animates.at(-1).options.record_every, 1);
      // One frame per recorded pose: every iteration and the start.
      assert.equal(every1, iterations + 1);
      assert.match(await page.textContent("#stats"), new RegExp(`${every1} poses replayed`));
      await setField(page, "#record-every", "10");
      await page.waitForFunction((n) => window.ikarus.state.animation.frames.length < n && document.body.dataset.playback === "ended", every1, { timeout: 15000 });
      const every10 = await page.evaluate(() => window.ikarus.state.animation.frames.length);
      assert.equal(animates.at(-1).options.record_every, 10);
      assert.equal(every10, Math.ceil(iterations / 10) + 1, `${every10} poses every 10 iterations, ${every1} every one`);
      // The eased motion does not carry it.
      assert.equal(animates[0].options.record_every, undefined);
    },
    { before: (page) => page.on("request", (r) => r.url().endsWith("/api/animate") && animates.push(JSON.parse(r.postData()))) },
  );
});
