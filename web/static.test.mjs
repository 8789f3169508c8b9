// The static playground (the directory `bash web/build DIR` writes) in headless Chromium, served
// by a plain static file server (python3 -m http.server on loopback) with no ikarus server
// running: the page says it runs in the browser, asks no /api/ path of anyone, and the solver
// answers in the page: a clicked goal moves the arm there, following the pointer answers every
// move, a drawn path is traced, the reachable area is shaded, the shipped puppet follows a dragged
// hand, spineboy walks with an IK target dragged; the motion-GIF button says it needs
// `ikarus serve`. Afterwards a native `ikarus serve` answers the page's own requests, and its
// answers must equal the page's, number for number (the WebAssembly module runs the server's
// code). Prints the solves per second measured in the page. Screenshots: target/e2e/static-*.png.
//
//   IKARUS_WEB_DIR=DIR node --test web/static.test.mjs    (web/test runs it after web/build)
import { test } from "node:test";
import assert from "node:assert/strict";
import { mkdirSync, readFileSync } from "node:fs";
import { join } from "node:path";
import { artifacts, binary, launch, openPage, startServer, staticServer } from "../e2e/browser.mjs";

const dir = process.env.IKARUS_WEB_DIR;
if (!dir) throw new Error("IKARUS_WEB_DIR: the directory `bash web/build DIR` wrote (web/test sets it)");

test("the static build runs the playground with no ikarus server", async () => {
  mkdirSync(artifacts, { recursive: true });
  const host = await staticServer(dir);
  const browser = await launch();
  const seen = {}; // what the page did, checked against the native server after the browser is closed
  try {
    const { page, errors } = await openPage(browser);
    const requests = [];
    const wasmTypes = [];
    page.on("request", (r) => requests.push(r.url()));
    const wasmPaths = [];
    page.on("response", (r) => r.url().endsWith(".wasm") && wasmTypes.push(r.headers()["content-type"]) && wasmPaths.push(new URL(r.url()).pathname));
    await page.goto(`${host.url}/`);
    await page.waitForFunction(() => window.ikarus && window.ikarus.ready, null, { timeout: 20000 });

    // The page says where it runs; the GIF (rendered by the server) says it needs one.
    await page.waitForFunction(() => document.body.dataset.backend, null, { timeout: 5000 });
    assert.equal(await page.evaluate(() => document.body.dataset.backend), "wasm");
    assert.equal(await page.textContent("#backend"), "running in your browser (WebAssembly)");
    assert.equal(await page.isDisabled("#dl-gif"), true);
    assert.match(await page.getAttribute("#dl-gif", "title"), /needs `ikarus serve`/);
    // The worker loads the small module first (the full one follows on the first call that needs it).
    assert.ok(wasmTypes.length >= 1 && wasmTypes.every((t) => t === "application/wasm"), `${wasmTypes}`);
    assert.equal(wasmPaths[0], "/ikarus_core_bg.wasm");
    await page.locator("#backend").scrollIntoViewIfNeeded();
    await page.screenshot({ path: join(artifacts, "static-panel.png") });
    await page.evaluate(() => document.getElementById("panel").scrollTo(0, 0));
    const methods = await page.evaluate(() => [...document.getElementById("method").options].map((o) => o.value));
    assert.ok(methods.includes("lm") && methods.includes("fabrik"), `methods from meta: ${methods}`);

    // Click (2, 3): the arm solves in the page and plays its motion to the goal.
    const [cx, cy] = await page.evaluate(() => window.ikarus.toClient(2, 3));
    await page.mouse.click(cx, cy);
    await page.waitForFunction(() => document.body.dataset.status === "reached" && document.body.dataset.playback === "ended", null, {
      timeout: 15000,
    });
    const click = await page.evaluate(() => {
      const s = window.ikarus.state;
      return { goal: s.goal, tip: s.joints.at(-1), pose: s.pose_deg, request: s.animationRequest, answer: s.animation, stats: document.getElementById("stats").textContent };
    });
    assert.ok(Math.hypot(click.goal.x - 2, click.goal.y - 3) < 0.05, `the click landed at ${JSON.stringify(click.goal)}`);
    assert.ok(Math.hypot(click.tip[0] - click.goal.x, click.tip[1] - click.goal.y) <= 1e-5, `tip ${click.tip}`);
    assert.match(click.stats, /^status reached · \d+ iterations?/);
    await page.screenshot({ path: join(artifacts, "static-click.png") });
    seen.click = click;

    // Follow the pointer: a dozen moves along an arc, each answered (the pose moves each time)
    // and the tip ends on the last point.
    await page.check("#follow");
    const poses = [];
    const arc = Array.from({ length: 12 }, (_, k) => [4 * Math.cos(0.3 + 0.12 * k), 4 * Math.sin(0.3 + 0.12 * k)]);
    for (const [x, y] of arc) {
      const before = JSON.stringify(await page.evaluate(() => window.ikarus.state.pose_deg));
      const [px, py] = await page.evaluate(([x, y]) => window.ikarus.toClient(x, y), [x, y]);
      await page.mouse.move(px, py);
      await page.waitForFunction((b) => JSON.stringify(window.ikarus.state.pose_deg) !== b, before, { timeout: 5000 });
      poses.push(await page.evaluate(() => window.ikarus.state.pose_deg.slice()));
    }
    await page.waitForFunction(() => !window.ikarus.state.jobs.followBusy && !window.ikarus.state.jobs.followGoal, null, { timeout: 5000 });
    const followed = await page.evaluate(() => ({ tip: window.ikarus.state.joints.at(-1), goal: window.ikarus.state.goal, stats: document.getElementById("stats").textContent }));
    assert.equal(poses.length, arc.length);
    assert.ok(Math.hypot(followed.tip[0] - followed.goal.x, followed.tip[1] - followed.goal.y) < 1e-4, `followed to ${followed.tip}, goal ${JSON.stringify(followed.goal)}`);
    assert.match(followed.stats, /^status reached · step /);
    // Each step went through the worker's typed ikarus.Chain (Chain.followHere), not /api/track's JSON.
    const typedFollows = await page.evaluate(async () => (await import("./api.js")).typed.follows);
    assert.ok(typedFollows >= arc.length, `follow steps by the typed path: ${typedFollows}`);
    await page.uncheck("#follow");

    // Draw a path: a stroke dragged in front of the arm, traced with plan, no flips.
    await page.click("#draw-path");
    const stroke = Array.from({ length: 41 }, (_, k) => [3.2 + 1.2 * Math.sin((Math.PI * k) / 20), -1.5 + (3 * k) / 40]);
    const points = await page.evaluate((p) => p.map(([x, y]) => window.ikarus.toClient(x, y)), stroke);
    await page.mouse.move(...points[0]);
    await page.mouse.down();
    for (const p of points.slice(1)) await page.mouse.move(...p);
    await page.mouse.up();
    await page.waitForFunction(() => window.ikarus.state.track && "path" in window.ikarus.state.track.request && document.body.dataset.playback === "ended", null, {
      timeout: 20000,
    });
    const traced = await page.evaluate(() => ({ request: window.ikarus.state.track.request, answer: window.ikarus.state.track.answer, tip: window.ikarus.state.joints.at(-1) }));
    assert.equal(traced.request.mode, "plan");
    assert.equal(traced.answer.summary.flips, 0);
    assert.equal(traced.answer.summary.reached, traced.answer.summary.samples);
    const last = traced.answer.samples.at(-1).goal;
    assert.ok(Math.hypot(traced.tip[0] - last[0], traced.tip[1] - last[1]) < 1e-4, `tip ${traced.tip}, last goal ${last}`);
    await page.screenshot({ path: join(artifacts, "static-path.png") });
    seen.traced = traced;
    await page.click("#draw-path");

    // The reachable area: shaded where the canvas was blank (a point behind the base, in reach).
    const pixel = () =>
      page.evaluate(() => {
        const canvas = document.getElementById("plot");
        const [px, py] = window.ikarus.toClient(-3.5, -3.5);
        const r = canvas.getBoundingClientRect();
        const k = canvas.width / r.width;
        return [...canvas.getContext("2d").getImageData(Math.round((px - r.left) * k), Math.round((py - r.top) * k), 1, 1).data];
      });
    const blank = await pixel();
    await page.check("#show-workspace");
    await page.waitForFunction(() => window.ikarus.state.workspace && window.ikarus.state.region, null, { timeout: 15000 });
    await page.waitForTimeout(200);
    const shaded = await pixel();
    assert.notDeepEqual(shaded, blank, `the pixel at (-3.5, -3.5) is ${shaded} with the area shown, ${blank} without`);
    seen.workspace = await page.evaluate(async () => {
      const { armForRequest } = await import("./controls.js");
      const s = window.ikarus.state;
      return { request: { arm: armForRequest(s.arm), limits: !!s.options.limits }, answer: s.workspace };
    });
    await page.screenshot({ path: join(artifacts, "static-workspace.png") });

    // A shipped rig (GET /api/rigs, answered by the module): the puppet, its right hand dragged
    // up a little; the rig follows, solved in the page.
    const bodies = await page.evaluate(() => [...document.getElementById("body-kind").options].map((o) => o.value));
    assert.ok(bodies.includes("rig:puppet") && bodies.includes("rig:hand"), `the Body list: ${bodies}`);
    await page.evaluate(() => window.ikarus.rigs.use("rig:puppet"));
    // Showing a rig changes the panel (the rig's controls replace the arm's), and the canvas is
    // laid out and fitted again in the frames after: the hand is found where it is drawn once the
    // layout has settled (its place the same two frames running), and grabbed once the page
    // says the pointer is over it.
    const hand = await page.evaluate(async () => {
      const frame = () => new Promise((done) => requestAnimationFrame(() => done()));
      const where = () => {
        const r = window.ikarus.state.rig;
        const tip = r.tips[r.rig.bones.findIndex((b) => b.name === "right_hand")];
        return { from: window.ikarus.toClient(...tip), to: window.ikarus.toClient(tip[0] + 0.05, tip[1] + 0.1) };
      };
      let last = null;
      for (let k = 0; k < 60; k++) {
        await frame();
        const now = where();
        if (last && JSON.stringify(now) === JSON.stringify(last)) return now;
        last = now;
      }
      return last;
    });
    await page.mouse.move(...hand.from);
    await page.waitForFunction(() => window.ikarus.state.rig.hover, null, { timeout: 5000 });
    await page.mouse.down();
    await page.mouse.move(...hand.to, { steps: 6 });
    await page.mouse.up();
    await page.waitForFunction(() => window.ikarus.rigs.settled() && window.ikarus.state.rig.answer, null, { timeout: 15000 });
    seen.rig = await page.evaluate(() => ({ request: window.ikarus.state.rig.request, answer: window.ikarus.state.rig.answer }));
    assert.equal(seen.rig.answer.status, "reached", JSON.stringify(seen.rig.answer.effectors));
    await page.screenshot({ path: join(artifacts, "static-rig.png") });
    await page.evaluate(() => window.ikarus.rigs.use("arm"));

    // A character (spineboy, read and posed by the module): its walk at 0.4 s, the IK target at
    // its front leg's target dragged (there the rear foot's is on it: the nearest handle is
    // taken); the pose drawn is the module's answer, the native server's to the number.
    const spineboy = readFileSync(join(import.meta.dirname, "..", "examples", "characters", "spine-spineboy-pro.json"));
    await page.setInputFiles("#rig-file", { name: "spineboy.json", mimeType: "application/json", buffer: spineboy });
    await page.waitForFunction(() => window.ikarus.state.character && window.ikarus.state.character.posed && window.ikarus.characters.settled(), null, { timeout: 15000 });
    await page.selectOption("#character-animation", "walk");
    await page.waitForFunction(() => window.ikarus.characters.settled());
    await page.fill("#scrubber", "400");
    await page.dispatchEvent("#scrubber", "input");
    const target = await page.evaluate(() => window.ikarus.state.character.posed.find((b) => b.name === "front-leg-target"));
    await page.mouse.move(...(await page.evaluate(([x, y]) => window.ikarus.toClient(x, y), [target.x, target.y])));
    await page.mouse.down();
    await page.mouse.move(...(await page.evaluate(([x, y]) => window.ikarus.toClient(x, y), [target.x + 30, target.y + 40])), { steps: 4 });
    await page.mouse.up();
    await page.waitForFunction(() => window.ikarus.characters.settled());
    seen.character = await page.evaluate(() => ({ request: window.ikarus.state.character.request, posed: window.ikarus.state.character.posed }));
    assert.equal(seen.character.request.animation, "walk");
    assert.equal(seen.character.request.targets.length, 1);
    assert.equal(seen.character.posed.length, 67);
    // The playback went through the module's typed path (ikarus.Character in the worker), not JSON.
    const typedPoses = await page.evaluate(async () => (await import("./api.js")).typed.poses);
    assert.ok(typedPoses >= 3, `poses by the typed path: ${typedPoses}`);
    await page.screenshot({ path: join(artifacts, "static-character.png") });
    await page.selectOption("#body-kind", "arm");

    // Solves per second in the page: the seed arm's solves through the JS API on the page's
    // thread (JSON in, JSON out), and through api.js, the page's own way (the worker: a message
    // each way). Timed over the whole run: the page's clock is coarse (100 µs) in Chromium.
    const speed = await page.evaluate(async () => {
      const ikarus = await import("./ikarus.js");
      const api = await import("./api.js");
      await ikarus.init();
      const goal = (k) => {
        const a = (k * 2.399963) % (2 * Math.PI);
        const r = 1.5 + (k % 7) * 0.55;
        return { x: r * Math.cos(a), y: r * Math.sin(a) };
      };
      const run = async (solve, n) => {
        const t = performance.now();
        for (let k = 0; k < n; k++) await solve({ goal: goal(k), options: { record_every: 1000000 } });
        const ms = performance.now() - t;
        return { per_second: Math.round((n / ms) * 1000), call_us: (ms * 1000) / n };
      };
      await run(ikarus.solve, 50); // warm up
      const direct = await run(ikarus.solve, 2000);
      const worker = await run(api.solve, 2000);
      // The typed paths on the page's thread: the seed arm's Chain.solve, spineboy's walk posed.
      const chain = new ikarus.Chain();
      const record = new Float64Array(chain.recordLen);
      const timed = (f, n) => {
        for (let k = 0; k < 200; k++) f(k);
        const t = performance.now();
        for (let k = 0; k < n; k++) f(k);
        return ((performance.now() - t) * 1000) / n;
      };
      const typedSolve = timed((k) => { const g = goal(k); chain.solve(g.x, g.y, record); }, 20000);
      // A follow step through the worker, as the page follows the pointer: the typed path
      // (api.follow) and /api/track's JSON (api.track), alternated in rounds of 250.
      const arm = await api.defaultArm();
      const step = (k) => ({ arm, options: {}, start_deg: [5, 5, 5], max_step_deg: 10, ...goal(k) });
      const asJson = ({ x, y, ...b }) => api.track({ ...b, path: [[x, y]], mode: "follow", bound_first: true });
      const follows = { typed: 0, json: 0 };
      for (let k = 0; k < 50; k++) await api.follow(step(k)), await asJson(step(k));
      for (let round = 0; round < 8; round++) {
        for (const [name, f] of [["typed", api.follow], ["json", asJson]]) {
          const t = performance.now();
          for (let k = 0; k < 250; k++) await f(step(k));
          follows[name] += performance.now() - t;
        }
      }
      return { direct, worker, typedSolve, followTyped: follows.typed / 2, followJson: follows.json / 2 };
    });
    // spineboy's walk posed three ways, interleaved in rounds of 1000: Character.pose (the
    // numbers copied out of the module's memory), Character.poseHere (read in place) and the
    // glue's own pose(time, targets, out) (which copies the arrays in and out of the module).
    const pose = await page.evaluate(async (text) => {
      const ikarus = await import("./ikarus.js");
      const glue = await import("./ikarus_wasm.js");
      const c = new ikarus.Character(text);
      const g = new glue.Character(text);
      c.setAnimation("walk");
      g.setAnimation("walk");
      const targets = Float64Array.of(c.bones.indexOf("front-leg-target"), 120, 40);
      const out = new Float64Array(c.poseLen);
      const kinds = {
        copied: (k) => c.pose((k % 100) * 0.0123, targets, out),
        here: (k) => c.poseHere((k % 100) * 0.0123, targets),
        glue: (k) => g.pose((k % 100) * 0.0123, targets, out),
      };
      const ms = { copied: 0, here: 0, glue: 0 };
      for (const f of Object.values(kinds)) for (let k = 0; k < 200; k++) f(k);
      const n = 20000;
      for (let start = 0; start < n; start += 1000) {
        for (const [name, f] of Object.entries(kinds)) {
          const t = performance.now();
          for (let k = start; k < start + 1000; k++) f(k);
          ms[name] += performance.now() - t;
        }
      }
      return Object.fromEntries(Object.entries(ms).map(([name, v]) => [name, (v * 1000) / n]));
    }, spineboy.toString("utf8"));
    console.log(
      `in-page typed calls: Chain.solve (seed arm) ${speed.typedSolve.toFixed(2)} µs a call; spineboy walk, one target: Character.pose ${pose.copied.toFixed(2)} µs, poseHere ${pose.here.toFixed(2)} µs, the glue's pose ${pose.glue.toFixed(2)} µs a call`,
    );
    console.log(
      `a follow step through the worker (seed arm, 2000 goals): typed (Chain.followHere) ${speed.followTyped.toFixed(1)} µs a step; /api/track's JSON ${speed.followJson.toFixed(1)} µs a step`,
    );
    console.log(
      `in-page solves, seed arm (LM, up to 16 restarts), 2000 goals: on the page's thread ${speed.direct.per_second}/s (${speed.direct.call_us.toFixed(1)} µs a call); through api.js and the worker ${speed.worker.per_second}/s (${speed.worker.call_us.toFixed(1)} µs a call)`,
    );
    assert.ok(speed.direct.per_second > 0 && speed.worker.per_second > 0);

    // Nothing but the static files was asked for: no /api/, no other host.
    assert.deepEqual(requests.filter((u) => !u.startsWith(`${host.url}/`) && !u.startsWith("data:")), []);
    assert.deepEqual(requests.filter((u) => new URL(u).pathname.startsWith("/api/")), []);
    // The worker's modules, each once: the small one first, the full one when the page first
    // asked a JSON job; then the full one again for the timings above (ikarus.init() on the
    // page's own thread).
    assert.deepEqual(wasmPaths, ["/ikarus_core_bg.wasm", "/ikarus_wasm_bg.wasm", "/ikarus_wasm_bg.wasm"]);
    assert.deepEqual(errors, []);
  } finally {
    await browser.close();
    host.child.kill();
  }

  // The native server's answers to the page's requests equal the page's (parsed: deepStrictEqual
  // compares numbers with Object.is, so every double is the same; the solve time aside).
  const { child, url } = await startServer();
  try {
    const post = async (path, body) => {
      const res = await fetch(`${url}/api/${path}`, { method: "POST", headers: { "content-type": "application/json" }, body: JSON.stringify(body) });
      assert.equal(res.status, 200, `${path}: ${res.status}`);
      return res.json();
    };
    const differ = [];
    const same = (what, native, page) => {
      try {
        assert.deepStrictEqual(page, native);
      } catch (e) {
        differ.push(`${what}: the page's answer is not the native one:\n${e.message.split("\n").slice(0, 24).join("\n")}`);
      }
    };
    same("the click's motion (animate)", await post("animate", seen.click.request), seen.click.answer);
    const solved = await post("solve", { ...seen.click.request, frames: undefined, ease: undefined });
    same("the click's pose (solve)", solved.angles_deg, seen.click.pose);
    same("the drawn path (track)", await post("track", seen.traced.request), seen.traced.answer);
    same("the reachable area (workspace)", await post("workspace", seen.workspace.request), seen.workspace.answer);
    same("the dragged rig (solve)", { ...(await post("solve", seen.rig.request)), solve_us: 0 }, { ...seen.rig.answer, solve_us: 0 });
    // The page named the character by the id its module answered when it read the file (the
    // module keeps it); the native server, a process of its own, is sent the file's text.
    const { character: id, ...asked } = seen.character.request;
    assert.equal(typeof id, "string", "the page names the character by its id");
    const text = readFileSync(join(import.meta.dirname, "..", "examples", "characters", "spine-spineboy-pro.json"), "utf8");
    same("the character's pose (pose)", (await post("pose", { ...asked, rig: text })).bones, seen.character.posed);
    assert.ok(differ.length === 0, differ.join("\n"));
  } finally {
    child.kill();
  }
});

test("a job over the page's budget is stopped: answered 503 naming the budget, the worker replaced, the next job answered", async () => {
  const host = await staticServer(dir);
  const browser = await launch();
  try {
    const { page, errors } = await openPage(browser);
    await page.goto(`${host.url}/?budget_ms=1500`);
    await page.waitForFunction(() => window.ikarus && window.ikarus.ready, null, { timeout: 20000 });
    // A solve that runs for minutes: a heading the limited arm cannot take, no test that could end
    // an attempt early, every attempt to the server's caps (iterations, restarts).
    // (64 stiff links: 6,000 iterations take 2 s in node, the 6.5 million asked for half an hour.)
    const links = Array.from({ length: 64 }, () => ({ length: 0.1, limits_deg: [-1, 1] }));
    const endless = {
      arm: { name: "stiff", links },
      goal: { x: 6, y: 1, angle_deg: -170 },
      options: { limits: true, tolerance: 1e-300, angle_tolerance_deg: 1e-300, max_iterations: 100000, restarts: 64, stall_window: 100000, stall_epsilon_deg: 1e-300, backtrack: 0, method: "transpose", no_closed_form: true },
    };
    const boy = readFileSync(join(import.meta.dirname, "..", "examples", "characters", "spine-spineboy-pro.json"), "utf8");
    const seen = await page.evaluate(
      async ({ endless, boy }) => {
        const api = await import("./api.js");
        // A pose first: the worker then holds spineboy's file (api.js sends it once).
        const ask = { rig: boy, animation: "walk", time: 0.4, targets: [{ bone: "front-leg-target", x: 120, y: 40 }] };
        const first = await api.pose(ask);
        // The only clock: "it is answered at all" (without the budget the solve runs for minutes).
        const bound = new Promise((done) => setTimeout(() => done("no answer within 60 s"), 60000));
        const stopped = await Promise.race([api.solve(endless).then((a) => `answered ${a.status}`, (e) => e.message), bound]);
        const next = await api.solve({ goal: { x: 2, y: 3 } });
        // The new worker holds no file: api.js sends it again, and the typed pose is the same.
        const again = await api.pose(ask);
        return { stopped, next: next.status, same: JSON.stringify(again) === JSON.stringify(first), typed: api.typed.poses };
      },
      { endless, boy },
    );
    assert.match(seen.stopped, /^request stopped: it took longer than the budget of 1500 ms \(budget_ms in the page's address\); the WebAssembly solver was restarted; ask for less work/);
    assert.equal(seen.next, "reached");
    assert.equal(seen.same, true);
    assert.equal(seen.typed, 2);
    assert.deepEqual(errors, []);
  } finally {
    await browser.close();
    host.child.kill();
  }
});

test("the static page loads a Spine .skel: decoded by the module, the character the native server reads from it", async () => {
  const host = await staticServer(dir);
  const native = await startServer();
  const browser = await launch();
  try {
    const { page, errors } = await openPage(browser);
    const apiRequests = [];
    page.on("request", (r) => new URL(r.url()).pathname.startsWith("/api/") && apiRequests.push(r.url()));
    await page.goto(`${host.url}/`);
    await page.waitForFunction(() => window.ikarus && window.ikarus.ready, null, { timeout: 20000 });
    const skel = readFileSync(join(import.meta.dirname, "..", "examples", "characters", "spine-spineboy-pro.skel"));
    await page.setInputFiles("#rig-file", { name: "spineboy.skel", mimeType: "application/octet-stream", buffer: skel });
    await page.waitForFunction(() => window.ikarus.state.character && window.ikarus.state.character.posed && window.ikarus.characters.settled(), null, { timeout: 20000 });
    const seen = await page.evaluate(() => ({ text: window.ikarus.state.character.text, character: window.ikarus.state.character.character, posed: window.ikarus.state.character.posed }));
    assert.equal(seen.character.bones.length, 67);
    assert.equal(seen.posed.length, 67);
    // The native server decodes the same bytes into the same text and character, and poses it so.
    const res = await fetch(`${native.url}/api/rig/parse?text=1`, { method: "POST", headers: { "content-type": "application/octet-stream" }, body: skel });
    const parsed = await res.json();
    assert.equal(seen.text, parsed.text);
    assert.deepEqual(seen.character, parsed.character);
    const posed = await fetch(`${native.url}/api/pose`, { method: "POST", headers: { "content-type": "application/json" }, body: JSON.stringify({ rig: parsed.text }) });
    assert.deepEqual(seen.posed, (await posed.json()).bones);
    // A truncated one: the module's one line, as the server's.
    await page.setInputFiles("#rig-file", { name: "cut.skel", mimeType: "application/octet-stream", buffer: skel.subarray(0, 2000) });
    await page.waitForFunction(() => !document.getElementById("error").hidden, null, { timeout: 15000 });
    const cut = await fetch(`${native.url}/api/rig/parse`, { method: "POST", headers: { "content-type": "application/octet-stream" }, body: skel.subarray(0, 2000) });
    assert.equal(await page.textContent("#error"), (await cut.json()).error);
    assert.deepEqual(apiRequests, [], "no request left the page");
    assert.deepEqual(errors, []);
  } finally {
    await browser.close();
    host.child.kill();
    native.child.kill();
  }
});
