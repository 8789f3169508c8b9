// The playground in a real browser: load the page and see its select lists filled from
// /api/meta, click a goal and see the arm play a motion and end on it, pick CCD and see the
// limit-mode list offer only what CCD supports, turn the joint limits on and see the reachable
// area shrink, with no console errors; save a screenshot. Then the timeline: play, pause with
// Space, scrub and see the drawn pose follow the scrubber, replay over the chosen duration with
// more poses than frames, shift-click two via points and move through them, replay the solver's
// iterations; and the timeline fits under the canvas in a narrow window. Run by e2e/run (which
// builds the binary and installs playwright-core); paths.test.mjs drives the traced paths and
// following.
import { test } from "node:test";
import assert from "node:assert/strict";
import { mkdirSync } from "node:fs";
import { join } from "node:path";
import { artifacts, launch, openPage, startServer } from "./browser.mjs";
import { autoDuration, forward, freeJoints, jointDistance, poseAt } from "../crates/ikarus-cli/src/serve/assets/view.js";

test("the playground moves the arm to a clicked goal and shows the reachable area", async () => {
  const { child, url } = await startServer();
  const browser = await launch();
  try {
    const { page, errors } = await openPage(browser);

    const solves = [];
    page.on("request", (r) => r.url().endsWith("/api/solve") && solves.push(JSON.parse(r.postData())));

    await page.goto(url);
    await page.waitForFunction(() => window.ikarus && window.ikarus.ready, null, { timeout: 15000 });

    // The select lists come from /api/meta: every method and ease, every limit mode but
    // "ignore" (the limits checkbox stands for it), each with the server's default selected.
    const meta = await (await fetch(`${url}/api/meta`)).json();
    const lists = await page.evaluate(() => {
      const list = (id) => {
        const el = document.getElementById(id);
        return { names: [...el.options].map((o) => o.value), labels: [...el.options].map((o) => o.text), value: el.value };
      };
      const k = (id) => document.getElementById(id).value;
      return { method: list("method"), mode: list("limit-mode"), ease: list("ease"), k1: k("k1"), k2: k("k2") };
    });
    assert.equal(lists.method.names.length, 8, `methods: ${lists.method.names}`);
    assert.deepEqual(lists.method.names, meta.methods.map((m) => m.name));
    assert.deepEqual(lists.method.labels, meta.methods.map((m) => m.label));
    assert.equal(lists.method.value, "lm");
    assert.equal(lists.method.value, meta.default_method);
    const modes = meta.limit_modes.filter((m) => m.name !== "ignore");
    assert.deepEqual(lists.mode.names, modes.map((m) => m.name));
    assert.deepEqual(lists.mode.labels, modes.map((m) => m.label));
    assert.ok(!lists.mode.names.includes("ignore"));
    assert.equal(lists.mode.value, meta.default_limit_mode);
    assert.deepEqual(lists.ease.names, meta.eases.map((e) => e.name));
    assert.equal(lists.ease.value, meta.default_ease);
    assert.deepEqual([Number(lists.k1), Number(lists.k2)], [meta.default_k1, meta.default_k2]);

    // Click the world point (2, 3): the arm solves, plays the motion, and ends on the goal.
    const [cx, cy] = await page.evaluate(() => window.ikarus.toClient(2, 3));
    await page.mouse.click(cx, cy);
    await page.waitForFunction(() => document.body.dataset.playback === "playing", null, { timeout: 15000 });
    await page.waitForFunction(
      () => document.body.dataset.status === "reached" && document.body.dataset.playback === "ended",
      null,
      { timeout: 15000 },
    );
    const { goal, tip } = await page.evaluate(() => ({
      goal: window.ikarus.state.goal,
      tip: window.ikarus.state.joints[window.ikarus.state.joints.length - 1],
    }));
    assert.ok(Math.hypot(goal.x - 2, goal.y - 3) < 0.05, `the click landed at (${goal.x}, ${goal.y})`);
    const miss = Math.hypot(tip[0] - goal.x, tip[1] - goal.y);
    assert.ok(miss <= 1e-5, `the tip ended ${miss} from the goal`);

    // The page starts with the CLI's defaults (/api/meta's): limits off, Levenberg–Marquardt,
    // 16 restarts (what `ikarus solve` uses; defaults.test.mjs compares the angles).
    const start = await page.evaluate(() => ({
      limits: document.getElementById("limits").checked,
      method: document.getElementById("method").value,
      mode: document.getElementById("limit-mode").value,
      restarts: document.getElementById("restarts").value,
    }));
    assert.deepEqual(start, { limits: meta.defaults.limits, method: "lm", mode: "lock", restarts: String(meta.defaults.restarts) });
    assert.deepEqual(start, { limits: false, method: "lm", mode: "lock", restarts: "16" });
    assert.deepEqual(
      { method: solves[0].options.method, limits: solves[0].options.limits, mode: solves[0].options.limit_mode },
      { method: "lm", limits: false, mode: undefined },
    );

    // With the limits on, the limit mode is the method's choice.
    await page.check("#limits");

    // CCD only clamps: the list switches to clamp and disables the rest, the request says
    // clamp, and a click still plays a motion. Back on LM, the reader's lock comes back.
    await page.selectOption("#method", "ccd");
    const ccdModes = await page.evaluate(() => {
      const el = document.getElementById("limit-mode");
      return { value: el.value, enabled: [...el.options].filter((o) => !o.disabled).map((o) => o.value) };
    });
    assert.deepEqual(ccdModes, {
      value: meta.methods.find((m) => m.name === "ccd").default_limit_mode,
      enabled: modes.map((m) => m.name).filter((m) => meta.methods.find((x) => x.name === "ccd").limit_modes.includes(m)),
    });
    assert.equal(ccdModes.value, "clamp");
    // CCD has one way of keeping joints in range: the list offers no choice.
    assert.equal(await page.isDisabled("#limit-mode"), true);
    const [kx, ky] = await page.evaluate(() => window.ikarus.toClient(1, 4));
    await page.mouse.click(kx, ky);
    await page.waitForFunction(() => document.body.dataset.playback === "playing", null, { timeout: 15000 });
    await page.waitForFunction(
      () =>
        !["solving", "ready"].includes(document.body.dataset.status) &&
        document.body.dataset.playback === "ended" &&
        Math.hypot(window.ikarus.state.goal.x - 1, window.ikarus.state.goal.y - 4) < 0.05,
      null,
      { timeout: 15000 },
    );
    const ccd = await page.evaluate(() => ({
      status: document.body.dataset.status,
      error: document.getElementById("error").hidden ? null : document.getElementById("error").textContent,
      frames: window.ikarus.state.animation.frames.length,
    }));
    assert.equal(ccd.error, null);
    assert.notEqual(ccd.status, "error");
    assert.ok(ccd.frames > 1, `${ccd.frames} frames`);
    const last = solves[solves.length - 1].options;
    assert.deepEqual({ method: last.method, mode: last.limit_mode }, { method: "ccd", mode: "clamp" });
    await page.selectOption("#method", "lm");
    const lmModes = await page.evaluate(() => {
      const el = document.getElementById("limit-mode");
      return { value: el.value, disabled: [...el.options].filter((o) => o.disabled).length };
    });
    assert.deepEqual(lmModes, { value: "lock", disabled: 0 });

    // The reachable area with the seed's joint limits, then without: it must grow.
    await page.check("#show-workspace");
    await page.waitForFunction(() => window.ikarus.state.workspace && window.ikarus.state.workspace.limits, null, {
      timeout: 15000,
    });
    const limited = await page.evaluate(() => window.ikarus.state.workspace.area);
    await page.uncheck("#limits");
    await page.waitForFunction(() => window.ikarus.state.workspace && !window.ikarus.state.workspace.limits, null, {
      timeout: 15000,
    });
    const free = await page.evaluate(() => window.ikarus.state.workspace.area);
    assert.ok(limited < 0.9 * free, `limits should shrink the area: ${limited} vs ${free}`);

    // Another method from the list reaches a goal too: FABRIK, clicked at (-2, 1).
    await page.selectOption("#method", "fabrik");
    const [fx, fy] = await page.evaluate(() => window.ikarus.toClient(-2, 1));
    await page.mouse.click(fx, fy);
    await page.waitForFunction(
      () =>
        document.body.dataset.status === "reached" &&
        document.body.dataset.playback === "ended" &&
        Math.hypot(window.ikarus.state.goal.x + 2, window.ikarus.state.goal.y - 1) < 0.05,
      null,
      { timeout: 15000 },
    );

    mkdirSync(artifacts, { recursive: true });
    await page.screenshot({ path: join(artifacts, "playground.png") });
    assert.deepEqual(errors, [], "console errors");
  } finally {
    await browser.close();
    child.kill("SIGINT");
  }
});

test("the timeline plays, pauses, scrubs and replays; via points and the solver's iterations", async () => {
  const { child, url } = await startServer();
  const browser = await launch();
  try {
    const { page, errors } = await openPage(browser);
    const animates = [];
    page.on("request", (r) => r.url().endsWith("/api/animate") && animates.push(JSON.parse(r.postData())));
    // The page's clock is the test's (it runs as the wall clock does until the replay holds it).
    await page.clock.install();
    await page.goto(url);
    await page.waitForFunction(() => window.ikarus && window.ikarus.ready, null, { timeout: 15000 });
    assert.equal(await page.evaluate(() => document.body.dataset.playback), "none");
    assert.equal(await page.isDisabled("#play"), true);

    const playback = () => page.evaluate(() => document.body.dataset.playback);
    const u = async () => Number(await page.evaluate(() => document.getElementById("timeline").dataset.u));
    const drawnPose = async () => (await page.evaluate(() => document.getElementById("plot").dataset.pose)).split(" ").map(Number);
    const motion = () => page.evaluate(() => ({ anim: window.ikarus.state.animation, req: window.ikarus.state.animationRequest }));
    /** The pose view.js interpolates at playhead `at` of the motion the page holds. */
    const expected = async (at) => {
      const { anim, req } = await motion();
      return poseAt(anim.frames, at, freeJoints(req.arm, req.options.limits)).angles;
    };
    const assertPose = (got, want, what) =>
      want.forEach((a, i) => assert.ok(Math.abs(got[i] - a) <= 2e-6, `${what}: joint ${i + 1} drawn at ${got[i]}°, expected ${a}°`));
    const click = async (x, y, shift = false) => {
      const [cx, cy] = await page.evaluate(([x, y]) => window.ikarus.toClient(x, y), [x, y]);
      if (shift) await page.keyboard.down("Shift");
      await page.mouse.click(cx, cy);
      if (shift) await page.keyboard.up("Shift");
    };

    // Five frames over a chosen 3 s: the motion plays, Space pauses it mid-way.
    await page.fill("#frames", "5");
    await page.dispatchEvent("#frames", "change");
    await page.fill("#duration", "3");
    await page.dispatchEvent("#duration", "change");
    await click(2, 3);
    await page.waitForFunction(() => document.body.dataset.playback === "playing", null, { timeout: 15000 });
    await page.waitForFunction(() => Number(document.getElementById("timeline").dataset.u) > 0.3, null, { timeout: 15000 });
    await page.keyboard.press(" ");
    assert.equal(await playback(), "paused");
    const paused = await u();
    assert.ok(paused > 0.3 && paused < 0.95, `paused at ${paused}`);
    await page.waitForTimeout(300);
    assert.equal(await u(), paused, "the playhead stays put while paused");
    assertPose(await drawnPose(), await expected(paused), `paused at ${paused}`);
    const { anim: five } = await motion();
    assert.equal(five.frames.length, 5);
    assert.equal(animates[0].frames, 5);

    // Space in a text field types; it does not play.
    await page.focus("#duration");
    await page.keyboard.press(" ");
    assert.equal(await playback(), "paused");

    // The scrubber moves the pose: typed, then dragged with the mouse, each between two frames.
    await page.locator("#scrubber").fill("375");
    assert.equal(await playback(), "paused");
    assert.equal(await u(), 0.375);
    assertPose(await drawnPose(), await expected(0.375), "scrubbed to 0.375");
    assert.equal(await page.textContent("#playtime"), "1.13 / 3.00 s");
    const between = await drawnPose();
    five.frames.forEach((f) => assert.ok(f.angles_deg.some((a, i) => Math.abs(a - between[i]) > 1e-3), "a pose between frames"));
    const box = await page.locator("#scrubber").boundingBox();
    await page.mouse.click(box.x + box.width * 0.8, box.y + box.height / 2);
    const dragged = await u();
    assert.ok(Math.abs(dragged - 0.8) < 0.06, `clicked the scrubber at 80%: playhead ${dragged}`);
    assertPose(await drawnPose(), await expected(dragged), `scrubbed to ${dragged}`);
    const [a, b] = [forward(SEED_ARM, between).at(-1), forward(SEED_ARM, await drawnPose()).at(-1)];
    assert.ok(Math.hypot(a[0] - b[0], a[1] - b[1]) > 0.05, "the tip moved with the scrubber");

    // Replay: from the start, over the 3 s chosen (the page's clock, held and moved on by the
    // test), many more poses drawn than the 5 frames, and the end exactly on the last frame, the
    // tip on the goal.
    await page.clock.pauseAt((await page.evaluate(() => Date.now())) + 1000);
    await page.click("#replay");
    const replayed = page.evaluate(
      () =>
        new Promise((resolve) => {
          const poses = new Set();
          const t0 = performance.now();
          const first = Number(document.getElementById("timeline").dataset.u);
          const look = () => {
            poses.add(document.getElementById("plot").dataset.pose);
            if (document.body.dataset.playback === "ended") resolve({ seconds: (performance.now() - t0) / 1000, poses: poses.size, first });
            else requestAnimationFrame(look);
          };
          look();
        }),
    );
    // (A replay that never ends fails below instead of waiting for it: the clock stays held.)
    replayed.catch(() => {});
    await page.clock.runFor(2900);
    assert.equal(await playback(), "playing", "still playing 2.9 s into the 3 s");
    await page.clock.runFor(200);
    assert.equal(await playback(), "ended", "ended 3.1 s into the 3 s");
    const replay = await replayed;
    await page.clock.resume();
    assert.ok(replay.first < 0.05, `replay starts at the start: ${replay.first}`);
    assert.ok(replay.seconds >= 3 && replay.seconds < 3.05, `the replay took ${replay.seconds} s of the page's clock for a 3 s duration`);
    assert.ok(replay.poses > 20, `${replay.poses} distinct poses drawn from 5 frames`);
    assert.equal(await u(), 1);
    assertPose(await drawnPose(), five.frames[4].angles_deg, "the end");
    const tip = five.frames[4].joints.at(-1);
    assert.ok(Math.hypot(tip[0] - 2, tip[1] - 3) < 0.05);

    // An empty duration is the default: 0.6 s + 0.4 s per radian, shown in the time.
    await page.fill("#duration", "");
    await page.dispatchEvent("#duration", "change");
    const auto = autoDuration(jointDistance(five.frames));
    assert.equal(await page.textContent("#playtime"), `${auto.toFixed(2)} / ${auto.toFixed(2)} s`);
    // Space plays again from the start when the motion has ended.
    await page.focus("#plot");
    await page.keyboard.press(" ");
    assert.equal(await playback(), "playing");
    await page.waitForFunction(() => document.body.dataset.playback === "ended", null, { timeout: 15000 });

    // Keyframes: two shift-clicks add numbered via points, a click moves through them.
    await page.fill("#frames", "60");
    await page.dispatchEvent("#frames", "change");
    const via = [[4, 2], [3, 3.5]];
    for (const [x, y] of via) await click(x, y, true);
    assert.equal(await page.textContent("#clear-via"), "Clear 2 via points");
    assert.equal(animates.length, 1, "a shift-click asks for nothing");
    await click(0.5, 4);
    await page.waitForFunction(() => document.body.dataset.playback === "playing", null, { timeout: 15000 });
    await page.waitForFunction(() => document.body.dataset.playback === "ended", null, { timeout: 15000 });
    const keyed = animates.at(-1);
    assert.equal(keyed.via.length, 2);
    keyed.via.forEach(([x, y], i) => assert.ok(Math.hypot(x - via[i][0], y - via[i][1]) < 0.05, `via ${i + 1} at (${x}, ${y})`));
    const { anim: through } = await motion();
    assert.equal(through.solves.length, 3);
    assert.ok(through.solves.every((s) => s.status === "reached"), JSON.stringify(through.solves));
    for (const [x, y] of via) {
      const nearest = Math.min(...through.frames.map((f) => Math.hypot(f.joints[3][0] - x, f.joints[3][1] - y)));
      assert.ok(nearest < 0.3, `the tip passes (${x}, ${y}) within ${nearest}`);
    }
    assert.equal(await page.evaluate(() => document.body.dataset.status), "reached");
    // They stay for the next motion until cleared.
    assert.equal(await page.textContent("#clear-via"), "Clear 2 via points");
    await page.click("#clear-via");
    assert.equal(await page.textContent("#clear-via"), "No via points");
    assert.equal(await page.isDisabled("#clear-via"), true);

    // The solver's iterations: the last motion's request with from_solve, from its start pose.
    await page.click("#solver");
    await page.waitForFunction(() => document.getElementById("timeline").dataset.source === "solver", null, { timeout: 15000 });
    await page.waitForFunction(() => document.body.dataset.playback === "ended", null, { timeout: 15000 });
    const solverReq = animates.at(-1);
    assert.equal(solverReq.from_solve, true);
    assert.deepEqual(solverReq.via, keyed.via);
    assert.deepEqual(solverReq.start_deg, keyed.start_deg);
    const { anim: recorded } = await motion();
    assert.ok(recorded.frames.length > 1);
    assertPose(recorded.frames[0].angles_deg, keyed.start_deg, "the solver starts where the motion did");
    assert.equal(await page.getAttribute("#solver", "aria-pressed"), "true");
    // Pressed again: the eased motion.
    await page.click("#solver");
    await page.waitForFunction(() => document.getElementById("timeline").dataset.source === "motion", null, { timeout: 15000 });
    assert.equal(animates.at(-1).from_solve, undefined);

    // A narrow window: the timeline sits under the canvas, inside the window, usable, with the
    // controls' drawer open and closed.
    await page.setViewportSize({ width: 400, height: 800 });
    for (const [drawer, minHeight] of [["open", 250], ["closed", 450]]) {
      if (drawer === "closed") await page.click("#panel-toggle");
      await page.waitForTimeout(200);
      const layout = await page.evaluate(() => {
        const r = (id) => document.getElementById(id).getBoundingClientRect();
        return { plot: r("plot"), bar: r("timeline"), scrub: r("scrubber"), solver: r("solver") };
      });
      const what = `drawer ${drawer}: ${JSON.stringify(layout)}`;
      assert.ok(layout.plot.bottom <= layout.bar.top + 1, `the canvas runs under the timeline; ${what}`);
      assert.ok(layout.bar.bottom <= 800 && layout.bar.right <= 400 && layout.solver.right <= 400, what);
      assert.ok(layout.scrub.width >= 90, `the scrubber is too narrow; ${what}`);
      assert.ok(layout.plot.height >= minHeight, `the canvas is too low; ${what}`);
    }
    await page.locator("#scrubber").fill("500");
    assertPose(await drawnPose(), await expected(0.5), "scrubbed at 400 px");

    assert.deepEqual(errors, [], "console errors");
  } finally {
    await browser.close();
    child.kill("SIGINT");
  }
});

// The server's seed arm (GET /api/arm/default), for forward kinematics of drawn poses.
const SEED_ARM = {
  base: [0, 0],
  links: [
    { length: 3, angle_deg: 5 },
    { length: 2, angle_deg: 5 },
    { length: 1, angle_deg: 5 },
  ],
};
