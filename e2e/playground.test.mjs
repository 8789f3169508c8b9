// The playground in a real browser: load the page and see its select lists filled from
// /api/meta, click a goal and see the arm play a motion and end on it, pick CCD and see the
// limit-mode list offer only what CCD supports, turn the joint limits on and see the reachable
// area shrink, with no console errors; save a screenshot. Run by e2e/run (which builds the
// binary and installs playwright-core).
import { test } from "node:test";
import assert from "node:assert/strict";
import { spawn } from "node:child_process";
import { mkdirSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";
import { chromium } from "playwright-core";

const here = dirname(fileURLToPath(import.meta.url));
const binary = process.env.IKARUS_BIN ?? join(here, "..", "target", "release", "ikarus");
const browserPath = process.env.CHROMIUM ?? "/usr/bin/chromium";
const artifacts = process.env.E2E_ARTIFACTS ?? join(here, "..", "target", "e2e");

/** Starts `ikarus serve --port 0` and resolves with its URL once it listens. */
function startServer() {
  const child = spawn(binary, ["serve", "--port", "0"], { stdio: ["ignore", "pipe", "inherit"] });
  return new Promise((resolve, reject) => {
    let out = "";
    const timer = setTimeout(() => reject(new Error(`no address from the server: ${out}`)), 15000);
    child.on("error", reject);
    child.stdout.on("data", (chunk) => {
      out += chunk;
      const m = out.match(/listening on (http:\/\/\S+)/);
      if (m) {
        clearTimeout(timer);
        resolve({ child, url: m[1] });
      }
    });
  });
}

test("the playground moves the arm to a clicked goal and shows the reachable area", async () => {
  const { child, url } = await startServer();
  const browser = await chromium.launch({
    executablePath: browserPath,
    args: [
      "--no-sandbox",
      "--disable-gpu",
      "--disable-quic",
      "--no-first-run",
      "--disable-background-networking",
      "--disable-component-update",
      "--disable-sync",
    ],
  });
  try {
    const page = await browser.newPage({ viewport: { width: 1280, height: 800 } });
    const errors = [];
    page.on("console", (m) => m.type() === "error" && errors.push(m.text()));
    page.on("pageerror", (e) => errors.push(e.message));

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
    await page.waitForFunction(() => window.ikarus.state.playing, null, { timeout: 15000 });
    await page.waitForFunction(
      () => document.body.dataset.status === "reached" && !window.ikarus.state.playing,
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

    // The page starts with the library's robust default: limits on, Levenberg–Marquardt,
    // clamp and lock, 16 restarts (what `ikarus solve --limits` uses).
    const start = await page.evaluate(() => ({
      limits: document.getElementById("limits").checked,
      method: document.getElementById("method").value,
      mode: document.getElementById("limit-mode").value,
      restarts: document.getElementById("restarts").value,
    }));
    assert.deepEqual(start, { limits: true, method: "lm", mode: "lock", restarts: "16" });
    assert.deepEqual(
      { method: solves[0].options.method, limits: solves[0].options.limits, mode: solves[0].options.limit_mode },
      { method: "lm", limits: true, mode: "lock" },
    );

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
    const [kx, ky] = await page.evaluate(() => window.ikarus.toClient(1, 4));
    await page.mouse.click(kx, ky);
    await page.waitForFunction(() => window.ikarus.state.playing, null, { timeout: 15000 });
    await page.waitForFunction(
      () =>
        !["solving", "ready"].includes(document.body.dataset.status) &&
        !window.ikarus.state.playing &&
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
        !window.ikarus.state.playing &&
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
