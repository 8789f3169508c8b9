// The WebAssembly API (web/ikarus.js over the module `bash web/build DIR` writes), called from
// node without a browser: every endpoint the page uses answers the native server's bytes for the
// same request (timing fields aside), a refused request throws the server's status and one-line
// message, the same call twice gives the same bytes, and the functions of the JS API return the
// API's objects. The native side is made at test time: a short-lived `ikarus serve --port 0` on
// loopback and `ikarus solve … --format json`.
//
//   IKARUS_WEB_DIR=DIR node --test web/wasm.test.mjs      (web/test runs it after web/build)
//
// IKARUS_BIN is the native binary (target/release/ikarus by default).
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { readFileSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath, pathToFileURL } from "node:url";
import { binary, startServer } from "../e2e/browser.mjs";

const root = join(dirname(fileURLToPath(import.meta.url)), "..");
const dir = process.env.IKARUS_WEB_DIR;
if (!dir) throw new Error("IKARUS_WEB_DIR: the directory `bash web/build DIR` wrote (web/test sets it)");
const ikarus = await import(pathToFileURL(join(dir, "ikarus.js")).href);

/** The answer's text with the timing fields' values (the only ones that may differ) set to 0. */
export const untimed = (text) => text.replace(/"(solve_us|micros)":-?[0-9][0-9.eE+-]*/g, '"$1":0');

let server;
/** The native server's answer to `path` (GET when `body` is undefined): {status, text}. */
async function native(path, body, type = "application/json") {
  const init = body === undefined ? {} : { method: "POST", headers: { "content-type": type }, body };
  const res = await fetch(`${server.url}/api/${path}`, init);
  return { status: res.status, text: await res.text() };
}

/** The module's answer to the same: {status, text}. */
function wasm(path, body) {
  try {
    return { status: 200, text: ikarus.call(path, body ?? "") };
  } catch (e) {
    assert.ok(e instanceof ikarus.IkarusError, `a refusal is an IkarusError: ${e && e.stack}`);
    return { status: e.status, text: JSON.stringify({ error: e.message }) };
  }
}

before(async () => {
  await ikarus.init(readFileSync(join(dir, "ikarus_wasm_bg.wasm")));
  server = await startServer();
});

after(() => server && server.child.kill());

const seven = readFileSync(join(root, "examples", "arms", "seven.toml"), "utf8");
const puppet = readFileSync(join(root, "examples", "rigs", "puppet.toml"), "utf8");
const hand = readFileSync(join(root, "examples", "rigs", "hand.toml"), "utf8");
const limited = { name: "limited", links: [3, 2, 1.5, 1].map((length, i) => ({ length, angle_deg: 10 * i, limits_deg: [-100 + 10 * i, 120 - 5 * i] })) };

/** Requests the page makes (and a few more), as [path, body]: GET endpoints have no body. */
const requests = [
  ["meta"],
  ["arm/default"],
  ["rigs"],
  ["solve", { goal: { x: 2, y: 3 } }],
  ["solve", { goal: { x: 2, y: 3 }, options: { record_every: 100 } }],
  ["solve", { goal: { x: -3, y: -1 }, options: { limits: true } }],
  ["solve", { goal: { x: 1.5, y: 2.5, angle_deg: 90 }, options: { method: "analytic" } }],
  ["solve", { goal: { x: 3.3, y: -1.7 }, options: { method: "fabrik", limits: true, restarts: 4 } }],
  ["solve", { goal: { x: 3.3, y: -1.7 }, options: { method: "ccd", limits: true } }],
  ["solve", { goal: { x: 4, y: 2 }, options: { method: "dls", lambda: 0.3, limits: true, limit_mode: "clamp" } }],
  ["solve", { arm: limited, goal: { x: 2.5, y: 4.1 }, start_deg: [5, 5, 5, 5], options: { limits: true, restarts: 8, restart_seed: 7 } }],
  // A time budget reads the clock (web-time's in WebAssembly: std's would panic); unreachable,
  // so every restart runs, well within the budget.
  ["solve", { goal: { x: -3, y: -1 }, options: { limits: true, restarts: 8, time_budget_ms: 10000, no_closed_form: true } }],
  // A rig: the fork of the README, and the shipped puppet with both hands on goals and its feet pinned.
  ["solve", { rig: { name: "fork", bones: [{ name: "trunk", length: 1, angle_deg: 90 }, { name: "arm.l", parent: "trunk", length: 1, angle_deg: 45 }] }, goals: [{ bone: "arm.l", x: -1, y: 1 }], pins: ["trunk"] }],
  ["solve_batch", { goals: [[2, 3], [1.5, 2.5, 90], [9, 9]] }],
  ["solve_batch", { arm: limited, goals: [[2.5, 4.1], [-3, -1]], start_deg: [5, 5, 5, 5], options: { limits: true, restarts: 8, restart_seed: 7 } }],
  ["animate", { goal: { x: 2, y: 3 }, frames: 5, ease: { kind: "smoothstep" } }],
  ["animate", { goal: { x: -1, y: 4 }, via: [[3, 3], [1, 5]], duration: 1.5, fps: 20, ease: { kind: "parent", k1: 0.4, k2: 0.6 } }],
  ["animate", { goal: { x: 3, y: 1 }, from_solve: true, options: { record_every: 1 } }],
  ["track", { figure8: [4.08, 0, 1.2], samples: 120, mode: "plan", max_step_deg: 10, options: { limits: true } }],
  ["track", { circle: [3, 1, 1.5], samples: 60, mode: "follow", options: { limits: true } }],
  ["track", { path: [[4.5, 0.3]], start_deg: [5, 5, 5], mode: "follow", bound_first: true, max_step_deg: 10, options: { limits: true } }],
  ["workspace", {}],
  ["workspace", { limits: true }],
  ["workspace", { grid: true, resolution: 160, limits: true }],
  ["workspace", { arm: limited, limits: true }],
  // Sampled over the joints before the last two: the path the library spreads over rayon's pool
  // natively, on the calling thread in WebAssembly; the same cells either way.
  ["workspace", { arm: limited, grid: true, resolution: 96, samples: 3000, limits: true }],
  ["reach", { limits: true, points: [[2, 3], [6.5, 0], [-3, -1], [0, 0.5]] }],
  ["reach", { arm: limited, limits: true, point: [1, -4] }],
];

/** Where two texts first differ, with a little context: "at 812: …51.416850259311154]… vs …51.41685025931116]…". */
function firstDifference(a, b) {
  let i = 0;
  while (i < a.length && a[i] === b[i]) i++;
  const around = (t) => t.slice(Math.max(0, i - 40), i + 40);
  return `at ${i}: …${around(a)}… vs …${around(b)}…`;
}

test("every endpoint answers the native server's bytes (timing fields aside)", async () => {
  const differ = [];
  for (const [path, body] of requests) {
    const json = body === undefined ? undefined : JSON.stringify(body);
    const [n, w] = [await native(path, json), wasm(path, json)];
    assert.equal(n.status, 200, `${path} ${json}: the server answered ${n.status} ${n.text}`);
    assert.equal(w.status, 200, `${path} ${json}: ${w.text}`);
    const [a, b] = [untimed(w.text), untimed(n.text)];
    if (a !== b) differ.push(`${path} ${json}: wasm vs native ${firstDifference(a, b)}`);
  }
  assert.ok(differ.length === 0, `${differ.length} of ${requests.length} answers differ:\n${differ.join("\n")}`);
});

test("the files: arm and rig files read and written as the server does", async () => {
  const cases = [
    ["arm/parse", seven, "application/toml"],
    ["arm/parse", "[[links]]\nlength = -1\n", "application/toml"],
    ["arm/parse", "not toml [", "application/toml"],
    ["rig/parse", puppet, "application/toml"],
    ["rig/parse", hand, "application/toml"],
    ["rig/parse", "[[bones]]\nname = 3\n", "application/toml"],
    ["arm/toml", JSON.stringify({ arm: { base: [0.5, -1], ...limited } }), "application/json"],
    ["arm/toml", JSON.stringify({ arm: limited }), "application/json"], // no base: refused
  ];
  for (const [path, body, type] of cases) {
    const [n, w] = [await native(path, body, type), wasm(path, body)];
    assert.deepEqual(w, n, `${path} ${body.slice(0, 40)}`);
  }
  assert.equal(wasm("arm/toml", JSON.stringify({ arm: { base: [0.5, -1], ...limited } })).status, 200);
  // A bad file is the answer's `problem`, not a refusal.
  assert.match(ikarus.parseArm("[[links]]\nlength = -1\n").problem, /length/);
  assert.equal(ikarus.parseArm(seven).arm.links.length, 7);
});

test("a refused request throws the server's status and one-line message", async () => {
  const bad = [
    ["solve", "{"],
    ["solve", "{}"],
    ["solve", JSON.stringify({ goal: { x: "a", y: 3 } })],
    ["solve", JSON.stringify({ goal: { x: 2, y: 3 }, options: { tolerance: 0 } })],
    ["solve", JSON.stringify({ goal: { x: 2, y: 3 }, options: { method: "newton" } })],
    ["solve", JSON.stringify({ goal: { x: 2, y: 3 }, options: { restarts: 65 } })],
    ["solve", JSON.stringify({ goal: { x: 2, y: 3 }, arm: { links: [] } })],
    ["solve", JSON.stringify({ goal: { x: 2, y: 3 }, arm: { links: [{ length: 0, angle_deg: 0 }] } })],
    ["solve", JSON.stringify({ goal: { x: 2, y: 3 }, start_deg: [1, 2] })],
    ["solve", JSON.stringify({ goal: { x: 2, y: 3 }, colour: "red" })],
    ["animate", JSON.stringify({ goal: { x: 2, y: 3 }, frames: 0 })],
    ["animate", JSON.stringify({ goal: { x: 2, y: 3 }, ease: { kind: "bouncy" } })],
    ["track", JSON.stringify({ mode: "plan" })],
    ["track", JSON.stringify({ path: [[1, 2]], mode: "wander" })],
    ["workspace", JSON.stringify({ grid: false, resolution: 64 })],
    ["workspace", JSON.stringify({ resolution: 5000 })],
    ["reach", JSON.stringify({ point: [1] })],
  ];
  for (const [path, body] of bad) {
    const n = await native(path, body);
    assert.ok(n.status >= 400 && n.status < 500, `${path} ${body}: the server answered ${n.status}`);
    let thrown;
    try {
      ikarus.call(path, body);
    } catch (e) {
      thrown = e;
    }
    assert.ok(thrown instanceof ikarus.IkarusError && thrown instanceof Error, `${path} ${body}: threw ${thrown}`);
    assert.equal(thrown.status, n.status, `${path} ${body}: ${thrown.message}`);
    assert.equal(JSON.stringify({ error: thrown.message }), n.text, `${path} ${body}`);
    assert.ok(!thrown.message.includes("\n"), "one line");
  }
  // The typed functions throw the same.
  assert.throws(() => ikarus.solve({ goal: { x: 2, y: "a" } }), (e) => e instanceof ikarus.IkarusError && e.status === 422 && /goal/.test(e.message));
  assert.throws(() => ikarus.call("nowhere", "{}"), (e) => e instanceof ikarus.IkarusError && e.status === 404);
});

test("the same call twice gives the same bytes", () => {
  for (const [path, body] of requests) {
    const json = body === undefined ? "" : JSON.stringify(body);
    assert.equal(untimed(ikarus.call(path, json)), untimed(ikarus.call(path, json)), `${path} ${json}`);
  }
});

test("the JS API's functions return the API's objects; the CLI gives the same angles", async () => {
  const solved = ikarus.solve({ goal: { x: 2, y: 3 } });
  assert.equal(solved.status, "reached");
  assert.equal(typeof solved.solve_us, "number");
  const cli = JSON.parse(execFileSync(binary, ["solve", "--goal", "2,3", "--format", "json"], { encoding: "utf8" }));
  assert.deepEqual(solved.angles_deg, cli.angles_deg);
  assert.deepEqual(solved.joints, cli.joints);
  assert.deepEqual({ ...solved, solve_us: 0 }, { ...cli, solve_us: 0 });

  assert.equal(ikarus.animate({ goal: { x: 2, y: 3 }, frames: 7 }).frames.length, 7);
  const traced = ikarus.track({ figure8: [4.08, 0, 1.2], samples: 40, mode: "plan", options: { limits: true } });
  assert.equal(traced.samples.length, 40);
  assert.equal(ikarus.workspace({}).exact, true);
  assert.deepEqual(ikarus.reach({ limits: true, point: [6.5, 0] }), { reachable: false, distance: 0.5, nearest: [6, 0] });
  assert.equal(ikarus.defaultArm().links.length, 3);
  assert.ok(ikarus.rigs().rigs.some((r) => r.name === "puppet"));
  assert.ok(ikarus.meta().methods.length >= 1);
  assert.equal(ikarus.parseRig(puppet).rig.name, "puppet");
  assert.match(ikarus.armToml({ base: [0, 0], ...limited }), /\[\[links\]\]/);
  assert.equal(ikarus.version(), JSON.parse((await native("health")).text).version);
});

test("a character posed by the module is the bytes of the server and of ikarus pose", async () => {
  // Spineboy (Spine) and the mecha (DragonBones): the setup pose, `walk` at 0.4 s, a target, both.
  const characters = [
    ["spine-spineboy-pro.json", "walk", ["front-leg-target", 120, 40]],
    ["dragonbones-mecha_1406_ske.json", "walk", ["foot_l", 30, -20]],
  ];
  for (const [file, animation, [bone, x, y]] of characters) {
    const path = join("examples", "characters", file);
    const rig = readFileSync(join(root, path), "utf8");
    const cases = [[{}, []]];
    if (animation) cases.push([{ animation, time: 0.4 }, ["--animation", animation, "--time", "0.4"]]);
    cases.push([{ targets: [{ bone, x, y }] }, ["--target", `${bone}=${x},${y}`]]);
    if (animation) cases.push([{ animation, time: 0.4, targets: [{ bone, x, y }] }, ["--animation", animation, "--time", "0.4", "--target", `${bone}=${x},${y}`]]);
    for (const [fields, args] of cases) {
      const body = JSON.stringify({ rig, ...fields });
      const [n, w] = [await native("pose", body), wasm("pose", body)];
      assert.equal(n.status, 200, `${file} ${JSON.stringify(fields)}: ${n.text}`);
      assert.equal(w.status, 200, `${file} ${JSON.stringify(fields)}: ${w.text}`);
      assert.equal(w.text, n.text, `${file} ${JSON.stringify(fields)}: wasm vs server ${firstDifference(w.text, n.text)}`);
      const cli = execFileSync(binary, ["pose", "--rig", path, "--format", "json", ...args], { cwd: root, encoding: "utf8", stdio: ["ignore", "pipe", "ignore"] });
      assert.equal(w.text, cli.trimEnd(), `${file} ${JSON.stringify(fields)}: wasm vs CLI ${firstDifference(w.text, cli)}`);
      assert.deepEqual(ikarus.pose({ rig, ...fields }), JSON.parse(cli));
    }
  }
  // A refusal: the server's status and line.
  const spineboy = readFileSync(join(root, "examples", "characters", "spine-spineboy-pro.json"), "utf8");
  // Goals on bones' tips (ikarus solve --rig CHARACTER.json): the same bytes.
  const goals = JSON.stringify({ rig: spineboy, ik: "ikarus", goals: [{ bone: "front-fist", x: 60, y: 300, bones: 3 }] });
  const solved = wasm("pose", goals);
  assert.equal(solved.status, 200, solved.text);
  const cliSolve = execFileSync(binary, ["solve", "--rig", join("examples", "characters", "spine-spineboy-pro.json"), "--goal", "front-fist=60,300", "--bones", "front-fist=3", "--format", "json"], { cwd: root, encoding: "utf8", stdio: ["ignore", "pipe", "ignore"] });
  assert.equal(solved.text, cliSolve.trimEnd(), `wasm vs CLI solve ${firstDifference(solved.text, cliSolve)}`);
  for (const fields of [{ animation: "wlk" }, { targets: [{ bone: "toe", x: 0, y: 0 }] }, { time: 1 }]) {
    const body = JSON.stringify({ rig: spineboy, ...fields });
    assert.deepEqual(wasm("pose", body), await native("pose", body), JSON.stringify(fields));
  }
  assert.equal(wasm("pose", JSON.stringify({ rig: puppet })).status, 422);
});
