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

test("a character's art: the module's atlas and its pose's drawing are the server's bytes", async () => {
  const atlas = readFileSync(join(root, "examples", "characters", "spineboy.atlas"), "utf8");
  const rig = readFileSync(join(root, "examples", "characters", "spine-spineboy-pro.json"), "utf8");
  const parse = JSON.stringify({ atlas });
  const [n, w] = [await native("atlas/parse", parse), wasm("atlas/parse", parse)];
  assert.equal(n.status, 200, n.text);
  assert.equal(w.text, n.text);
  const id = JSON.parse(w.text).id;
  for (const fields of [{}, { animation: "walk", time: 0.4, targets: [{ bone: "front-leg-target", x: 60, y: 20 }] }]) {
    const body = JSON.stringify({ rig, atlas: id, ...fields });
    const [pn, pw] = [await native("pose", body), wasm("pose", body)];
    assert.equal(pn.status, 200, pn.text);
    assert.ok(JSON.parse(pw.text).art.slots.length > 15, "the art is drawn");
    assert.equal(pw.text, pn.text, `wasm vs server ${firstDifference(pw.text, pn.text)}`);
  }
  // An id neither keeps: the same 404 and line.
  const unknown = JSON.stringify({ rig, atlas: "a0" });
  assert.deepEqual(wasm("pose", unknown), await native("pose", unknown));
});

/** Whether two numbers are the same float64, bit for bit (Object.is tells 0 from -0, and NaN). */
const sameBits = (a, b) => Object.is(a, b);

test("the typed Chain solves as call(\"solve\") answers, bit for bit, and refuses with the server's line", async () => {
  const cases = [
    [undefined, undefined, [[2, 3], [-3, -1], [9, 9], [0.3, 0.2], [4.5, 1]]],
    [undefined, { limits: true }, [[-3, -1], [3.3, -1.7], [2, 3]]],
    [undefined, { method: "fabrik", limits: true, restarts: 4 }, [[3.3, -1.7], [1, 4]]],
    [limited, { limits: true, restarts: 8, restart_seed: 7 }, [[2.5, 4.1], [-3, -1], [1, -4]]],
    [JSON.parse(ikarus.call("arm/parse", seven)).arm, { limits: true }, [[2, 3], [-1, 2.5], [4, -2]]],
  ];
  for (const [arm, options, goals] of cases) {
    const chain = new ikarus.Chain(arm, options);
    const n = chain.joints;
    assert.equal(chain.recordLen, n + 6);
    const out = new Float64Array(chain.recordLen);
    const batch = new Float64Array(goals.length * chain.recordLen);
    chain.solveBatch(Float64Array.from(goals.flat()), batch);
    goals.forEach(([x, y], k) => {
      const what = `${arm ? arm.name : "seed"} ${JSON.stringify(options)} goal ${x},${y}`;
      const code = chain.solve(x, y, out);
      const json = JSON.parse(ikarus.call("solve", JSON.stringify({ arm, options, goal: { x, y } })));
      const want = [...json.angles_deg, json.end_effector.x, json.end_effector.y, json.error, json.iterations, json.restarts, ikarus.STATUS.indexOf(json.status)];
      assert.equal(ikarus.STATUS[code], json.status, what);
      want.forEach((w, i) => assert.ok(sameBits(out[i], w), `${what}: number ${i} is ${out[i]}, the JSON's ${w}`));
      // The batch: the same record per goal (the JSON of /api/solve_batch gives angles, error, iterations, status).
      const record = batch.subarray(k * chain.recordLen, (k + 1) * chain.recordLen);
      record.forEach((v, i) => assert.ok(sameBits(v, out[i]), `${what}: batch number ${i} is ${v}, the solve's ${out[i]}`));
    });
    const json = JSON.parse(ikarus.call("solve_batch", JSON.stringify({ arm, options, goals })));
    goals.forEach((_, k) => {
      const record = batch.subarray(k * chain.recordLen, (k + 1) * chain.recordLen);
      json.angles_deg[k].forEach((w, i) => assert.ok(sameBits(record[i], w), `solve_batch goal ${k} angle ${i}`));
      assert.ok(sameBits(record[n + 2], json.error[k]));
      assert.equal(record[n + 3], json.iterations[k]);
      assert.equal(ikarus.STATUS[record[n + 5]], json.status[k]);
    });
    chain.free();
  }
  // Refusals: the server's status and line for the same arm and options.
  // A value of the wrong kind: the server's line less `request body: ` and the position in the
  // JSON text (which the caller of Chain did not write).
  const unplaced = (text) => JSON.stringify({ error: JSON.parse(text).error.replace(/^request body: /, "").replace(/ at line \d+ column \d+$/, "") });
  const refused = [
    [undefined, { tolerance: 0 }],
    [undefined, { method: "newton" }],
    [undefined, { lambda: "x" }],
    [{ links: [] }, undefined],
    [{ links: [{ length: 0, angle_deg: 0 }] }, undefined],
    [{ links: [{ length: "x" }] }, undefined],
    [{ links: [{ length: 1, colour: 2 }] }, undefined],
  ];
  for (const [arm, options] of refused) {
    const server = await native("solve", JSON.stringify({ arm, options, goal: { x: 2, y: 3 } }));
    assert.throws(() => new ikarus.Chain(arm, options), (e) => e instanceof ikarus.IkarusError && e.status === server.status && JSON.stringify({ error: e.message }) === unplaced(server.text), `${JSON.stringify([arm, options])}: ${server.text}`);
  }
  const chain = new ikarus.Chain();
  assert.throws(() => chain.solve(NaN, 1, new Float64Array(9)), (e) => e instanceof ikarus.IkarusError && e.status === 422 && /^goal\.x/.test(e.message));
  assert.throws(() => chain.solve(1, 1, new Float64Array(8)), /out: shorter than 1 record/);
  assert.throws(() => chain.solveBatch(Float64Array.of(1, 1, 1, Infinity), new Float64Array(18)), /^IkarusError: goals\[1\]: goal\.y/);
});

test("the typed Character poses as call(\"pose\") answers, bit for bit", () => {
  const characters = [
    ["spine-spineboy-pro.json", "walk", ["front-leg-target", 120, 40]],
    ["spine-raptor-pro.json", "walk", ["front-leg-target", 300, 60]],
    ["dragonbones-mecha_1406_ske.json", "walk", ["foot_l", 30, -20]],
  ];
  for (const [file, animation, [bone, x, y]] of characters) {
    const rig = readFileSync(join(root, "examples", "characters", file), "utf8");
    const character = new ikarus.Character(rig);
    assert.deepEqual(character.bones, JSON.parse(ikarus.call("pose", JSON.stringify({ rig }))).bones.map((b) => b.name));
    assert.equal(character.poseLen, 5 * character.bones.length);
    const index = character.bones.indexOf(bone);
    assert.ok(index >= 0, `${file}: no bone ${bone}`);
    const out = new Float64Array(character.poseLen);
    for (const [fields, time] of [[{}, 0], [{ animation, time: 0.4 }, 0.4], [{ targets: [{ bone, x, y }] }, 0], [{ animation, time: 0.4, targets: [{ bone, x, y }] }, 0.4], [{ animation, time: 1.3 }, 1.3]]) {
      character.setAnimation(fields.animation);
      character.pose(time, fields.targets ? Float64Array.of(index, x, y) : new Float64Array(0), out);
      const json = JSON.parse(ikarus.call("pose", JSON.stringify({ rig, ...fields })));
      json.bones.forEach((b, i) => {
        [b.x, b.y, b.rotation_deg, b.tip[0], b.tip[1]].forEach((w, k) =>
          assert.ok(sameBits(out[5 * i + k], w), `${file} ${JSON.stringify(fields)} ${b.name} number ${k}: ${out[5 * i + k]} vs the JSON's ${w}`));
      });
    }
    const server = wasm("pose", JSON.stringify({ rig, animation: "wlk" }));
    assert.throws(() => character.setAnimation("wlk"), (e) => e instanceof ikarus.IkarusError && JSON.stringify({ error: e.message }) === server.text);
    assert.throws(() => character.pose(0, Float64Array.of(1e6, 0, 0), out), /targets\[0\]: bone 1000000/);
    character.free();
  }
  assert.throws(() => new ikarus.Character(puppet), (e) => e instanceof ikarus.IkarusError && JSON.stringify({ error: e.message }) === wasm("pose", JSON.stringify({ rig: puppet })).text);
});

test("the small module's handles answer as the full module's call, bit for bit, in place and copied; the GET files are call's answers", async () => {
  // A second instance of ikarus.js that loads only the small module (ikarus_core_bg.wasm).
  const small = await import(`${pathToFileURL(join(dir, "ikarus.js")).href}?small`);
  await small.initCore(readFileSync(join(dir, "ikarus_core_bg.wasm")));
  assert.equal(small.fullLoaded(), false);
  assert.equal(small.version(), ikarus.version());
  assert.throws(() => small.call("meta"), (e) => e instanceof small.IkarusError && e.status === 500 && /init\(\)/.test(e.message));

  for (const [arm, options] of [[undefined, undefined], [limited, { limits: true, restarts: 8, restart_seed: 7 }], [undefined, { method: "fabrik" }]]) {
    const chain = new small.Chain(arm, options);
    const out = new Float64Array(chain.recordLen + 2).fill(-1);
    for (const [x, y] of [[2, 3], [-3, -1], [9, 9], [2.5, 4.1]]) {
      const json = JSON.parse(ikarus.call("solve", JSON.stringify({ arm, options, goal: { x, y } })));
      const want = [...json.angles_deg, json.end_effector.x, json.end_effector.y, json.error, json.iterations, json.restarts, ikarus.STATUS.indexOf(json.status)];
      const code = chain.solveHere(x, y);
      assert.equal(small.STATUS[code], json.status);
      assert.equal(chain.record.length, chain.recordLen);
      want.forEach((w, i) => assert.ok(sameBits(chain.record[i], w), `in place: number ${i} is ${chain.record[i]}, the JSON's ${w}`));
      assert.equal(chain.solve(x, y, out), code);
      want.forEach((w, i) => assert.ok(sameBits(out[i], w), `copied: number ${i} is ${out[i]}, the JSON's ${w}`));
      assert.deepEqual([...out.subarray(chain.recordLen)], [-1, -1], "nothing written past the record");
    }
    chain.free();
  }
  // A refused value is the server's line; a value of the wrong kind is refused (without its path).
  assert.throws(() => new small.Chain(undefined, { tolerance: 0 }), (e) => e.status === 422 && e.message === JSON.parse(wasm("solve", JSON.stringify({ goal: { x: 2, y: 3 }, options: { tolerance: 0 } })).text).error);
  assert.throws(() => new small.Chain({ links: [{ length: "x" }] }), (e) => e instanceof small.IkarusError && e.status === 422 && e.message === 'arm: invalid type: string "x", expected f64');

  for (const file of ["spine-spineboy-pro.json", "dragonbones-mecha_1406_ske.json"]) {
    const rig = readFileSync(join(root, "examples", "characters", file), "utf8");
    const character = new small.Character(rig);
    assert.deepEqual(character.unsupported, JSON.parse(ikarus.call("pose", JSON.stringify({ rig }))).unsupported);
    const bone = character.bones.length - 1;
    character.setAnimation("walk");
    const out = new Float64Array(character.poseLen);
    for (const time of [0, 0.4, 1.3]) {
      const json = JSON.parse(ikarus.call("pose", JSON.stringify({ rig, animation: "walk", time, targets: [{ bone: character.bones[bone], x: 30, y: 20 }] })));
      const here = character.poseHere(time, Float64Array.of(bone, 30, 20));
      character.pose(time, Float64Array.of(bone, 30, 20), out);
      json.bones.forEach((b, i) =>
        [b.x, b.y, b.rotation_deg, b.tip[0], b.tip[1]].forEach((w, k) => {
          assert.ok(sameBits(here[5 * i + k], w), `${file} ${time} ${b.name} in place number ${k}`);
          assert.ok(sameBits(out[5 * i + k], w), `${file} ${time} ${b.name} copied number ${k}`);
        }));
    }
    assert.throws(() => character.pose(0, Float64Array.of(1e6, 0, 0), out), /targets\[0\]: bone 1000000/);
    character.free();
  }

  for (const [path, file] of [["meta", "api-meta.json"], ["arm/default", "api-arm-default.json"], ["rigs", "api-rigs.json"]])
    assert.equal(readFileSync(join(dir, file), "utf8"), ikarus.call(path, ""), file);
});

test("the typed follow steps as call(\"track\")'s one-sample follow answers, bit for bit, in both modules", async () => {
  const small = await import(`${pathToFileURL(join(dir, "ikarus.js")).href}?follow`);
  await small.initCore(readFileSync(join(dir, "ikarus_core_bg.wasm")));
  const seen = new Set();
  for (const api of [ikarus, small]) {
    for (const [arm, options] of [[undefined, undefined], [limited, { limits: true }]]) {
      const chain = new api.Chain(arm, options);
      const n = chain.joints;
      let pose = JSON.parse(ikarus.call("solve", JSON.stringify({ arm, options, goal: { x: 1, y: 1 } }))).angles_deg.map(() => 0);
      // Each goal asked four times (the page chases a goal the bound cut short); the bound changes halfway.
      const goals = [[2, 3], [-4, 1], [9, 9], [0.5, -3.5], [-2, -2]].flatMap((g) => [g, g, g, g]);
      goals.forEach(([x, y], k) => {
        const bound = k < 10 ? 10 : 30;
        const code = chain.followHere(pose, x, y, bound);
        const body = { arm, options, start_deg: pose, max_step_deg: bound, path: [[x, y]], mode: "follow", bound_first: true };
        const s = JSON.parse(ikarus.call("track", JSON.stringify(body))).samples[0];
        const want = [...s.angles_deg, ...s.joints.flat(), s.error, s.step_deg, api.FOLLOW_STATUS.indexOf(s.status)];
        const got = chain.followRecord;
        assert.equal(got.length, 3 * n + 5);
        assert.equal(api.FOLLOW_STATUS[code], s.status);
        want.forEach((w, i) => assert.ok(sameBits(got[i], w), `${JSON.stringify(options)} goal ${k}: number ${i} is ${got[i]}, the JSON's ${w}`));
        seen.add(s.status);
        pose = Array.from(got.subarray(0, n));
      });
      const refused = wasm("track", JSON.stringify({ arm, options, start_deg: pose, max_step_deg: 0, path: [[1, 1]], mode: "follow", bound_first: true }));
      assert.throws(() => chain.followHere(pose, 1, 1, 0), (e) => e instanceof api.IkarusError && e.status === refused.status && JSON.stringify({ error: e.message }) === refused.text);
      chain.free();
    }
  }
  assert.deepEqual([...seen].sort(), ["limited", "reached", "unreachable"]);
});

test("a call that runs out of memory is answered with a clear error and the module restarts: the next call works", async () => {
  const before = new ikarus.Chain();
  const body = JSON.stringify({ goal: { x: 2, y: 3 } });
  // The instance ikarus.js runs (the glue's initSync hands back the loaded one): all but none of
  // wasm32's 4 GiB taken from under it, so that a request's first large allocation fails, as
  // one whose work grows past 4 GiB does (a wasm32 allocation failure aborts: `unreachable`).
  const glue = await import(pathToFileURL(join(dir, "ikarus_wasm.js")).href);
  const memory = glue.initSync().memory;
  memory.grow(65536 - memory.buffer.byteLength / 65536);
  // 2000 frames of a 64-link arm: megabytes of frames and JSON.
  const arm = { name: "long", links: Array.from({ length: 64 }, () => ({ length: 0.1 })) };
  const big = JSON.stringify({ arm, goal: { x: 3, y: 3 }, frames: 2000 });
  assert.throws(
    () => ikarus.call("animate", big),
    (e) =>
      e instanceof ikarus.IkarusError &&
      e.status === 500 &&
      e.restarted === true &&
      /^the WebAssembly module stopped \(.*out of memory\?\): it was restarted; ask for less work$/.test(e.message),
  );
  // The next call is answered by a fresh instance, as the server answers it.
  assert.equal(untimed(wasm("solve", body).text), untimed((await native("solve", body)).text));
  assert.equal(JSON.parse(ikarus.call("animate", big)).frames.length, 2000, "the same request fits in a fresh memory");
  // Handles of the stopped instance are refused with a line that says why; new ones work.
  assert.throws(() => before.solveHere(2, 3), (e) => e instanceof ikarus.IkarusError && /made before the WebAssembly module restarted/.test(e.message));
  before.free();
  const after = new ikarus.Chain();
  assert.equal(ikarus.STATUS[after.solveHere(2, 3)], "reached");
  after.free();
});

test("a .skel's bytes: the module's answer is the server's /api/rig/parse?text=1, its text the decoded JSON", async () => {
  const skel = readFileSync(join(root, "examples", "characters", "spine-spineboy-pro.skel"));
  const res = await fetch(`${server.url}/api/rig/parse?text=1`, { method: "POST", headers: { "content-type": "application/octet-stream" }, body: skel });
  assert.equal(res.status, 200);
  const served = await res.json();
  assert.deepEqual(ikarus.parseRigBytes(skel), served);
  assert.equal(ikarus.characterText(skel), served.text);
  assert.equal(served.character.bones.length, 67);
  const cut = skel.subarray(0, 2000);
  const refused = await fetch(`${server.url}/api/rig/parse`, { method: "POST", headers: { "content-type": "application/octet-stream" }, body: cut });
  assert.equal(refused.status, 422);
  const { error } = await refused.json();
  assert.match(error, /^rig file: skel: byte \d+: /);
  for (const f of [ikarus.parseRigBytes, ikarus.characterText]) {
    assert.throws(() => f(cut), (e) => e instanceof ikarus.IkarusError && e.status === 422 && e.message === error);
  }
});
