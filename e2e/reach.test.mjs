// Certified reach in the playground (issue 13): with the seed arm and its limits on, the page
// shades the exact reachable region from the workspace answer's `boundary` (arcs, not a
// staircase), a click outside it says "unreachable · d from the reachable region" at once (the
// page's own region decides before any answer) and draws the nearest reachable point, which is
// /api/reach's and where the solve's pose puts the tip; a click inside reaches. The figure
// downloads draw the region with SVG arcs. Where the server cannot build the region, the page
// asks for the grid and draws its outline, and the solve's answer alone marks a goal out of
// reach. Run by e2e/run; the screenshot lands in target/e2e/reach.png.
import { test } from "node:test";
import assert from "node:assert/strict";
import { mkdirSync } from "node:fs";
import { join } from "node:path";
import { artifacts, launch, openPage, startServer } from "./browser.mjs";
import { regionArea, regionOf, verdict } from "../crates/ikarus-cli/src/serve/assets/region.js";

const ready = (page) => page.waitForFunction(() => window.ikarus && window.ikarus.ready, null, { timeout: 15000 });
/** The motion has played to its end and its stats are shown. */
const settled = (page) =>
  page.waitForFunction(() => document.body.dataset.playback === "ended" && /^status /.test(document.getElementById("stats").textContent), null, {
    timeout: 15000,
  });
const post = async (url, path, body) => {
  const res = await fetch(`${url}${path}`, { method: "POST", headers: { "content-type": "application/json" }, body: JSON.stringify(body) });
  assert.equal(res.status, 200, `${path}: ${await res.clone().text()}`);
  return res.json();
};

/** The canvas's pixels (RGBA, device pixels) in a square of `half` CSS pixels around the world point (x, y). */
const pixelsAround = (page, x, y, half) =>
  page.evaluate(
    ([x, y, half]) => {
      const canvas = document.getElementById("plot");
      const dpr = canvas.width / canvas.clientWidth;
      const v = window.ikarus.state.view;
      const px = (v.cx + x * v.scale) * dpr;
      const py = (v.cy - y * v.scale) * dpr;
      const h = Math.round(half * dpr);
      return Array.from(canvas.getContext("2d").getImageData(Math.round(px) - h, Math.round(py) - h, 2 * h + 1, 2 * h + 1).data);
    },
    [x, y, half],
  );
/** Redraws the canvas (the page redraws on a resize) and waits for the frame. */
const redraw = (page) =>
  page.evaluate(() => {
    window.dispatchEvent(new Event("resize"));
    return new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));
  });

test("the exact region is drawn, a goal outside it is told at once with its nearest reachable point, one inside reaches", async () => {
  const { child, url } = await startServer();
  const browser = await launch();
  try {
    const { page, errors } = await openPage(browser);
    const asked = [];
    page.on("request", (r) => r.url().includes("/api/") && asked.push(new URL(r.url()).pathname));
    await page.goto(url);
    await ready(page);
    const arm = await (await fetch(`${url}/api/arm/default`)).json();
    const meta = await (await fetch(`${url}/api/meta`)).json();

    // Limits on: the page asks for the region (to judge goals) even before it is shown.
    await page.check("#limits");
    await page.waitForFunction(() => window.ikarus.state.region, null, { timeout: 15000 });
    const ws = await page.evaluate(() => window.ikarus.state.workspace);
    assert.equal(ws.exact, true);
    assert.ok(Array.isArray(ws.boundary) && ws.boundary.length > 0, "the answer's boundary");
    const arcs = ws.boundary.flat().filter((s) => s.arc).length;
    assert.ok(arcs >= 4, `${arcs} arcs in the seed arm's boundary`);
    // The page's area of the loops is the server's exact area.
    const region = regionOf(ws.boundary);
    assert.ok(Math.abs(regionArea(region) - ws.area) <= 1e-9 * ws.area, `area ${regionArea(region)} vs ${ws.area}`);

    // Shown: the region is shaded. A point inside has the area's colour, one outside the plot's.
    await page.check("#show-workspace");
    await redraw(page);
    const inside = [3.3, -1.7];
    const outside = [-3.7, 1.3];
    assert.equal(verdict(region, inside).reachable, true);
    assert.equal(verdict(region, outside).reachable, false);
    const [ir, ig, ib] = await pixelsAround(page, ...inside, 0);
    const [or, og, ob] = await pixelsAround(page, ...outside, 0);
    assert.deepEqual([or, og, ob], [255, 255, 255], "outside: the plot's white");
    assert.ok(ig > ir + 5 && ig > ib && ig < 250, `inside: the area's green, got ${[ir, ig, ib]}`);
    // The region's outline in the figure (drawn by the page's drawScene): SVG arcs, nonzero fill.
    const svg = await page.evaluate(async () => (await import("/export.js")).figureSvg(window.ikarus.state));
    const area = new RegExp(`<path d="([^"]*)" fill="${meta.palette.workspace}" fill-rule="nonzero"`).exec(svg);
    assert.ok(area, "the region's fill in the SVG");
    assert.ok((area[1].match(/A/g) || []).length >= arcs, `the region's arcs: ${area[1].slice(0, 200)}`);

    // A click outside (the (−3, −1)): the chip says so before any answer comes back.
    const goal = [-3, -1];
    const reach = await post(url, "/api/reach", { arm, limits: true, point: goal });
    assert.equal(reach.reachable, false);
    const held = [];
    await page.route(/\/api\/(solve|animate)$/, (route) => held.push(route));
    asked.length = 0;
    const [cx, cy] = await page.evaluate(([x, y]) => window.ikarus.toClient(x, y), goal);
    await page.mouse.click(cx, cy);
    await page.waitForFunction(() => document.body.dataset.reach === "outside", null, { timeout: 5000 });
    const early = await page.evaluate(() => ({
      text: document.getElementById("stats").textContent,
      status: document.body.dataset.status,
      chip: document.getElementById("chip").dataset.kind,
      miss: window.ikarus.state.reachMiss,
      goal: window.ikarus.state.goal,
    }));
    assert.equal(early.status, "unreachable");
    assert.equal(early.chip, "bad");
    // The page's verdict is the server's (/api/reach, the Rust library's) for the point clicked.
    const clicked = [early.goal.x, early.goal.y];
    const server = await post(url, "/api/reach", { arm, limits: true, point: clicked });
    assert.equal(early.text, `unreachable · ${server.distance.toFixed(2)} from the reachable region`);
    assert.ok(Math.abs(early.miss.distance - server.distance) < 1e-9, `distance ${early.miss.distance} vs ${server.distance}`);
    assert.ok(Math.hypot(early.miss.nearest[0] - server.nearest[0], early.miss.nearest[1] - server.nearest[1]) < 1e-9, "nearest");
    // While the motion's requests are held, and without asking /api/reach: the page's own region decided.
    assert.ok(asked.includes("/api/solve") && asked.includes("/api/animate") && !asked.includes("/api/reach"), `asked ${asked}`);
    assert.equal(held.length, 2, "the solve and the motion are still held");

    // The solve (the authority for the pose): `unreachable` at once, no restarts, its tip on the
    // nearest reachable point, its reach_distance the verdict's.
    const solveAnswer = page.waitForResponse((r) => r.url().endsWith("/api/solve"));
    for (const route of held) await route.continue();
    await page.unroute(/\/api\/(solve|animate)$/);
    const solved = await (await solveAnswer).json();
    assert.equal(solved.status, "unreachable");
    assert.equal(solved.restarts, 0);
    assert.ok(Math.abs(solved.reach_distance - server.distance) < 1e-6, `reach_distance ${solved.reach_distance} vs ${server.distance}`);
    const tipMiss = Math.hypot(solved.end_effector.x - server.nearest[0], solved.end_effector.y - server.nearest[1]);
    assert.ok(tipMiss < 1e-6, `the pose's tip is ${tipMiss} from the nearest reachable point`);
    await settled(page);
    const done = await page.evaluate(() => ({
      text: document.getElementById("stats").textContent,
      status: document.body.dataset.status,
      miss: window.ikarus.state.reachMiss,
      tip: window.ikarus.state.joints.at(-1),
    }));
    assert.equal(done.status, "unreachable");
    assert.match(done.text, new RegExp(`^status unreachable · ${server.distance.toFixed(2)} from the reachable region · `));
    assert.ok(Math.hypot(done.tip[0] - server.nearest[0], done.tip[1] - server.nearest[1]) < 1e-6, `the arm ends at ${done.tip}`);

    // The nearest point is drawn: without the marker the pixels around it differ.
    await redraw(page);
    const marked = await pixelsAround(page, ...done.miss.nearest, 10);
    await page.evaluate(() => {
      window.savedMiss = window.ikarus.state.reachMiss;
      window.ikarus.state.reachMiss = null;
    });
    await redraw(page);
    const bare = await pixelsAround(page, ...done.miss.nearest, 10);
    await page.evaluate(() => (window.ikarus.state.reachMiss = window.savedMiss));
    await redraw(page);
    let changed = 0;
    for (let i = 0; i < marked.length; i += 4) if (Math.abs(marked[i] - bare[i]) + Math.abs(marked[i + 1] - bare[i + 1]) > 30) changed++;
    assert.ok(changed >= 40, `${changed} pixels changed by the marker`);
    // And in the figure: the dashed line from the goal and the diamond in the reach colour.
    const figure = await page.evaluate(async () => (await import("/export.js")).figureSvg(window.ikarus.state));
    assert.match(figure, new RegExp(`stroke="${meta.palette.goal}" stroke-width="1.5"[^>]*stroke-dasharray="5 4"`), "the dashed line");
    assert.match(figure, new RegExp(`<path d="M[^"]*Z" fill="none" stroke="${meta.palette.reach}" stroke-width="2.5"`), "the diamond");

    mkdirSync(artifacts, { recursive: true });
    await page.screenshot({ path: join(artifacts, "reach.png") });

    // A click inside reaches: no miss, a calm chip.
    await page.evaluate(() => {
      window.ikarus.animateTo(3.3, -1.7);
    });
    await page.waitForFunction(() => document.body.dataset.status === "reached" && document.body.dataset.playback === "ended", null, { timeout: 15000 });
    const inside2 = await page.evaluate(() => ({
      status: document.body.dataset.status,
      reach: document.body.dataset.reach,
      chip: document.getElementById("chip").dataset.kind,
      text: document.getElementById("stats").textContent,
    }));
    assert.deepEqual([inside2.status, inside2.reach, inside2.chip], ["reached", undefined, "neutral"]);
    assert.doesNotMatch(inside2.text, /reachable region/);

    // Following the pointer out of the region says so at once too.
    await page.evaluate(() => window.ikarus.followTo(-3, -1));
    assert.equal(await page.evaluate(() => document.body.dataset.reach), "outside");
    assert.match(await page.textContent("#stats"), /unreachable · \d+\.\d\d from the reachable region/);
    await page.evaluate(() => window.ikarus.resetPose());
    assert.equal(await page.evaluate(() => document.body.dataset.reach), undefined);
    assert.deepEqual(errors, [], "console errors");
  } finally {
    await browser.close();
    child.kill("SIGINT");
  }
});

test("no exact region (the server cannot build it, or predates it): the grid's outline, and the solve alone tells a goal out of reach", async () => {
  const { child, url } = await startServer();
  const browser = await launch();
  try {
    const { page, errors } = await openPage(browser);
    // The exact region fails (as the server answers an arm whose region the library cannot
    // build): the page asks for the grid instead, and gets what a server from before the exact
    // region sends, the grid without a boundary.
    const bodies = [];
    await page.route(/\/api\/workspace$/, async (route) => {
      const body = JSON.parse(route.request().postData());
      bodies.push(body);
      if (!body.grid) {
        await route.fulfill({ status: 500, json: { error: "the library could not build the exact region (a test's stand-in)" } });
        return;
      }
      const res = await route.fetch();
      const ws = await res.json();
      assert.ok(ws.grid && !ws.boundary);
      delete ws.exact;
      await route.fulfill({ response: res, json: ws });
    });
    await page.goto(url);
    await ready(page);
    await page.check("#limits");
    await page.check("#show-workspace");
    await page.waitForFunction(() => window.ikarus.state.areaOutline, null, { timeout: 15000 });
    assert.equal(await page.evaluate(() => window.ikarus.state.region), null);
    assert.ok(await page.evaluate(() => window.ikarus.state.areaOutline.length) > 0, "the grid's outline");
    assert.deepEqual(
      bodies.slice(0, 2).map((b) => [b.limits, b.grid, b.resolution]),
      [
        [true, undefined, undefined],
        [true, true, 160],
      ],
    );
    assert.equal(await page.evaluate(() => document.getElementById("error").hidden), true, "no error shown");
    // No region to judge by: the page waits for the solve, which says it. The status is read in
    // the same turn as the click (a fast server's answer could otherwise land before a second
    // evaluate and start the motion: the test once read "moving" that way).
    const atOnce = await page.evaluate(() => {
      window.ikarus.animateTo(-3, -1);
      return document.body.dataset.status;
    });
    assert.equal(atOnce, "solving");
    await settled(page);
    const s = await page.evaluate(() => ({
      status: document.body.dataset.status,
      reach: document.body.dataset.reach,
      text: document.getElementById("stats").textContent,
      miss: window.ikarus.state.reachMiss,
      tip: window.ikarus.state.joints.at(-1),
    }));
    assert.equal(s.status, "unreachable");
    assert.equal(s.reach, "outside");
    assert.match(s.text, /^status unreachable · \d+\.\d\d from the reachable region · /);
    assert.ok(Math.hypot(s.miss.nearest[0] - s.tip[0], s.miss.nearest[1] - s.tip[1]) < 1e-9, "the marker is on the tip");
    // The browser logs the failed answer; nothing else.
    assert.deepEqual(
      errors.filter((e) => !/status of 500/.test(e)),
      [],
      "console errors",
    );
  } finally {
    await browser.close();
    child.kill("SIGINT");
  }
});
