// The playground's paths in a real browser: the figure-8 button and a dragged stroke traced
// (plan) with 0 flips, every sample reached and the tip on the path at the end; following the
// pointer with the seed's limits across the region they cannot reach, no joint moving more than
// the bound between two drawn frames, the arm ending at the last goal's nearest reachable point. Run by e2e/run, beside playground.test.mjs.
import { test } from "node:test";
import assert from "node:assert/strict";
import { mkdirSync } from "node:fs";
import { join } from "node:path";
import { artifacts, launch, openPage, startServer } from "./browser.mjs";

test("paths: a figure-8 and a drawn stroke traced without flips; following never jumps over the bound", async () => {
  const { child, url } = await startServer();
  const browser = await launch();
  try {
    const { page, errors } = await openPage(browser);
    const tracks = [];
    page.on("response", async (r) => {
      if (!r.url().endsWith("/api/track")) return;
      tracks.push({ req: JSON.parse(r.request().postData()), res: await r.json() });
    });
    await page.goto(url);
    await page.waitForFunction(() => window.ikarus && window.ikarus.ready, null, { timeout: 15000 });
    // The paths below are planned with the seed's ranges: limits on (the page starts without,
    // as `ikarus solve` does).
    await page.check("#limits");
    const traced = (what) =>
      page.waitForFunction(
        (what) => {
          const t = window.ikarus.state.track;
          return t && what in t.request && document.body.dataset.playback === "ended";
        },
        what,
        { timeout: 20000 },
      );
    const tip = () => page.evaluate(() => window.ikarus.state.joints.at(-1));
    /** The distance from `p` to the polyline `points`. */
    const offPath = (p, points) => {
      let best = Infinity;
      for (let k = 1; k < points.length; k++) {
        const [a, b] = [points[k - 1], points[k]];
        const [dx, dy] = [b[0] - a[0], b[1] - a[1]];
        const w = Math.min(Math.max(((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy || 1), 0), 1);
        best = Math.min(best, Math.hypot(p[0] - a[0] - w * dx, p[1] - a[1] - w * dy));
      }
      return best;
    };

    // The figure-8 button: planned with the seed's limits, played on the timeline, no flips,
    // every sample reached, the tip on the path at the end.
    await page.click("#trace-figure8");
    // While the tip traces it the chip says so; the summary comes at the end.
    await page.waitForFunction(() => document.body.dataset.playback === "playing", null, { timeout: 20000 });
    assert.equal(await page.evaluate(() => document.body.dataset.status), "moving");
    assert.equal(await page.textContent("#stats"), "moving…");
    await traced("figure8");
    const eight = tracks.at(-1);
    assert.equal(eight.req.mode, "plan");
    assert.equal(eight.req.options.limits, true);
    assert.equal(eight.res.summary.flips, 0, JSON.stringify(eight.res.summary));
    assert.equal(eight.res.summary.reached, eight.res.summary.samples);
    assert.equal(await page.evaluate(() => [document.body.dataset.status, document.body.dataset.flips].join(" ")), "reached 0");
    assert.match(await page.textContent("#stats"), /^plan · 120 of 120 reached · 0 flips/);
    const goals = eight.res.samples.map((s) => s.goal);
    const end = await tip();
    assert.ok(offPath(end, goals) < 1e-4 && Math.hypot(end[0] - goals.at(-1)[0], end[1] - goals.at(-1)[1]) < 1e-4, `tip at ${end}`);
    assert.equal(await page.evaluate(() => window.ikarus.state.animation.frames.length), 120);
    assert.equal(await page.isDisabled("#solver"), true, "a traced path has no solver iterations");

    // Draw a path: a stroke dragged across the front of the arm, resampled and traced.
    await page.click("#draw-path");
    assert.equal(await page.getAttribute("#draw-path", "aria-pressed"), "true");
    const stroke = Array.from({ length: 61 }, (_, k) => {
      const y = -1.3 + (2.6 * k) / 60;
      return [4.1 + 0.6 * Math.sin((Math.PI * y) / 1.3), y];
    });
    const points = await page.evaluate((p) => p.map(([x, y]) => window.ikarus.toClient(x, y)), stroke);
    await page.mouse.move(...points[0]);
    await page.mouse.down();
    for (const p of points.slice(1)) await page.mouse.move(...p);
    await page.mouse.up();
    await traced("path");
    const drawn = tracks.at(-1);
    const path = drawn.req.path;
    assert.ok(path.length >= 50 && path.length <= 200, `${path.length} samples`);
    const gaps = path.slice(1).map((p, k) => Math.hypot(p[0] - path[k][0], p[1] - path[k][1]));
    // Evenly spaced along the stroke: chords across a corner of the pointer's polyline are a little shorter.
    assert.ok(Math.min(...gaps) > 0.98 * Math.max(...gaps), `evenly spaced: ${Math.min(...gaps)} to ${Math.max(...gaps)}`);
    assert.ok(path.every((p) => offPath(p, stroke) < 0.01), "the samples lie on the stroke");
    assert.equal(drawn.res.summary.flips, 0, JSON.stringify(drawn.res.summary));
    assert.equal(drawn.res.summary.reached, path.length);
    const drawnEnd = await tip();
    assert.ok(Math.hypot(drawnEnd[0] - stroke.at(-1)[0], drawnEnd[1] - stroke.at(-1)[1]) < 0.01, `tip at ${drawnEnd}`);
    await page.click("#draw-path");
    mkdirSync(artifacts, { recursive: true });
    await page.screenshot({ path: join(artifacts, "paths.png") });

    // Follow with the seed's limits across the region behind the base they cannot reach: many
    // small pointer moves on a circle of radius 4.5 from 15° to 200°. Every pose drawn, frame
    // after frame, is within the bound of the one before; the traced path's ghosts are gone.
    await page.check("#follow");
    await page.evaluate(() => {
      window.drawnPoses = [];
      const look = () => {
        window.drawnPoses.push(document.getElementById("plot").dataset.pose);
        window.lookFrame = requestAnimationFrame(look);
      };
      look();
    });
    const before = tracks.length;
    const arc = Array.from({ length: 121 }, (_, k) => {
      const a = ((15 + (185 * k) / 120) * Math.PI) / 180;
      return [4.5 * Math.cos(a), 4.5 * Math.sin(a)];
    });
    for (const p of await page.evaluate((a) => a.map(([x, y]) => window.ikarus.toClient(x, y)), arc)) {
      await page.mouse.move(...p);
      await page.waitForTimeout(8);
    }
    // Until the arm has caught up: no request for half a second.
    let seen = -1;
    while (seen !== tracks.length) {
      seen = tracks.length;
      await page.waitForTimeout(500);
    }
    const drawnPoses = await page.evaluate(() => {
      cancelAnimationFrame(window.lookFrame);
      return window.drawnPoses.map((p) => p.split(" ").map(Number));
    });
    const follows = tracks.slice(before);
    assert.ok(follows.length > 20, `${follows.length} follow requests`);
    for (const { req, res } of follows) {
      assert.deepEqual([req.mode, req.bound_first, req.path.length, req.max_step_deg], ["follow", true, 1, 10]);
      assert.ok(res.samples[0].step_deg <= 10 + 1e-9, `step ${res.samples[0].step_deg}`);
    }
    const statuses = new Set(follows.map((f) => f.res.samples[0].status));
    assert.ok(statuses.has("reached") && statuses.size > 1, `statuses ${[...statuses]}`);
    let largest = 0;
    for (let k = 1; k < drawnPoses.length; k++) {
      for (let i = 0; i < 3; i++) largest = Math.max(largest, Math.abs(drawnPoses[k][i] - drawnPoses[k - 1][i]));
    }
    const first = drawnPoses[0];
    const last = drawnPoses.at(-1);
    console.log(`follow: ${follows.length} requests, ${drawnPoses.length} frames, largest frame-to-frame step ${largest.toFixed(6)}°, statuses ${[...statuses]}`);
    assert.ok(largest <= 10 + 1e-5, `a joint jumped ${largest}° between two frames`);
    assert.ok(Math.abs(last[0] - first[0]) > 20, `the arm followed: from ${first} to ${last}`);
    // Where the limits cannot reach, the arm waits at the pose reaching the nearest reachable
    // point of the last goal (the solver's certified verdict): /api/reach's nearest point, in the
    // region's lower lobe (first joint at −45°), and the page says how far the goal is.
    const goal = await page.evaluate(() => window.ikarus.state.goal);
    const arm = await page.evaluate(() => window.ikarus.state.arm);
    const reach = await (
      await fetch(`${url}/api/reach`, {
        method: "POST",
        headers: { "content-type": "application/json" },
        body: JSON.stringify({ arm, limits: true, point: [goal.x, goal.y] }),
      })
    ).json();
    assert.equal(reach.reachable, false);
    const waits = await tip();
    assert.ok(Math.hypot(waits[0] - reach.nearest[0], waits[1] - reach.nearest[1]) < 1e-6, `ended at ${last}, tip ${waits}, nearest ${reach.nearest}`);
    assert.ok(Math.abs(last[0] + 45) < 1e-6, `ended at ${last}`);
    assert.match(await page.textContent("#stats"), new RegExp(`${reach.distance.toFixed(2)} from the reachable region`));
    assert.equal(await page.evaluate(() => window.ikarus.state.animation || window.ikarus.state.track), null);
    assert.match(await page.textContent("#stats"), /^status (stalled|unreachable|limited)/);
    await page.screenshot({ path: join(artifacts, "follow.png") });
    assert.deepEqual(errors, [], "console errors");
  } finally {
    await browser.close();
    child.kill("SIGINT");
  }
});

test("paths: a stroke the limits cut in two is traced without a jump, and the page shows where the arm left it", async () => {
  const { child, url } = await startServer();
  const browser = await launch();
  try {
    const { page, errors } = await openPage(browser);
    const tracks = [];
    page.on("response", async (r) => {
      if (r.url().endsWith("/api/track")) tracks.push({ req: JSON.parse(r.request().postData()), res: await r.json() });
    });
    await page.goto(url);
    await page.waitForFunction(() => window.ikarus && window.ikarus.ready, null, { timeout: 15000 });
    await page.check("#limits");
    // The stroke: a circle of radius 4 from 0° to 216°; the seed's limits reach its
    // start and its end, not the part behind the base.
    await page.click("#draw-path");
    const stroke = Array.from({ length: 217 }, (_, k) => {
      const a = (k * Math.PI) / 180;
      return [4 * Math.cos(a), 4 * Math.sin(a)];
    });
    const points = await page.evaluate((p) => p.map(([x, y]) => window.ikarus.toClient(x, y)), stroke);
    await page.mouse.move(...points[0]);
    await page.mouse.down();
    for (const p of points.slice(1)) await page.mouse.move(...p);
    await page.mouse.up();
    await page.waitForFunction(() => window.ikarus.state.track && document.body.dataset.playback === "ended", null, { timeout: 30000 });
    const { res } = tracks.at(-1);
    const s = res.summary;
    assert.equal(s.samples, 200);
    assert.ok(s.reached < 200 && s.off_path > 0, JSON.stringify(s));
    assert.equal(s.flips, 0);
    assert.ok(s.max_step_deg <= 10 + 1e-9, JSON.stringify(s));
    // Every frame played is within the bound of the one before: no jump from top to bottom.
    const frames = await page.evaluate(() => window.ikarus.state.animation.frames.map((f) => f.angles_deg));
    assert.equal(frames.length, 200 + s.off_path);
    let largest = 0;
    for (let k = 1; k < frames.length; k++) for (let i = 0; i < 3; i++) largest = Math.max(largest, Math.abs(frames[k][i] - frames[k - 1][i]));
    assert.ok(largest <= 10 + 1e-6, `a joint moved ${largest}° between two frames`);
    // The page says it and shows it: the stats line, and the tip's way off the path drawn in red.
    assert.equal(await page.evaluate(() => document.body.dataset.offPath), String(s.off_path));
    assert.match(await page.textContent("#stats"), new RegExp(`^plan · ${s.reached} of 200 reached · ${s.off_path} off path · 0 flips · largest step 10\\.0°`));
    const red = await page.evaluate(() => {
      const { state, toClient } = window.ikarus;
      const canvas = document.getElementById("plot");
      const rect = canvas.getBoundingClientRect();
      const dpr = canvas.width / rect.width;
      const ctx = canvas.getContext("2d");
      let n = 0;
      for (const run of state.track.offPath) {
        for (const [x, y] of run) {
          const [cx, cy] = toClient(x, y);
          const d = ctx.getImageData(Math.round((cx - rect.left) * dpr) - 6, Math.round((cy - rect.top) * dpr) - 6, 13, 13).data;
          for (let i = 0; i < d.length; i += 4) if (d[i] > 190 && d[i + 1] < 80 && d[i + 2] < 80) n++;
        }
      }
      return { runs: state.track.offPath.length, n };
    });
    assert.ok(red.runs >= 1 && red.n > 20, `the off-path run drawn in red: ${JSON.stringify(red)}`);
    mkdirSync(artifacts, { recursive: true });
    await page.screenshot({ path: join(artifacts, "off-path.png") });
    assert.deepEqual(errors, [], "console errors");
  } finally {
    await browser.close();
    child.kill("SIGINT");
  }
});
