// Rigs in the playground (issue 12), in a real browser: choose the puppet instead of the arm
// (only the methods that solve rigs are offered), click both feet to pin them (a click again
// unpins), drag both hands one after the other to points the puppet can reach with its feet
// where they are; the rig follows while the pointer moves (solves sent during the drag, one in
// flight, each from the pose shown, the last one for the pointer's last place), and the last
// answer has every effector reached and the pins held. The PNG/SVG download draws the rig; a
// screenshot is saved. Then a bad rig file is its one-line problem, and the hand loads and
// follows a fingertip. Run by e2e/run (which builds the binary and installs playwright-core).
import { test } from "node:test";
import assert from "node:assert/strict";
import { mkdirSync, readFileSync } from "node:fs";
import { join } from "node:path";
import { artifacts, launch, openPage, startServer } from "./browser.mjs";
import { forPeople } from "../crates/ikarus-cli/src/serve/assets/api.js";
import { bodyForward } from "../crates/ikarus-cli/src/serve/assets/body.js";
import { leafNames } from "../crates/ikarus-cli/src/serve/assets/rig.js";

const ready = (page) => page.waitForFunction(() => window.ikarus && window.ikarus.ready, null, { timeout: 15000 });
const settled = (page) => page.waitForFunction(() => window.ikarus.rigs.settled(), null, { timeout: 15000 });

/** Counts the page's rig solves: how many were in flight at most, and every request with its answer. */
function watchSolves(page) {
  return page.addInitScript(() => {
    const log = (window.rigSolves = { inFlight: 0, most: 0, calls: [] });
    const fetch = window.fetch.bind(window);
    window.fetch = async (input, init) => {
      const body = String(input).endsWith("/api/solve") && init && typeof init.body === "string" ? JSON.parse(init.body) : null;
      if (!body || !body.rig) return fetch(input, init);
      log.inFlight++;
      log.most = Math.max(log.most, log.inFlight);
      try {
        const res = await fetch(input, init);
        log.calls.push({ body, answer: await res.clone().json() });
        return res;
      } finally {
        log.inFlight--;
      }
    };
  });
}

const calls = (page) => page.evaluate(() => window.rigSolves.calls);

/** Client coordinates of bone `name`'s tip as drawn now. */
const tipClient = (page, name) =>
  page.evaluate((n) => {
    const r = window.ikarus.state.rig;
    return window.ikarus.toClient(...r.tips[r.rig.bones.findIndex((b) => b.name === n)]);
  }, name);

/**
 * Drags bone `name`'s tip to the world point `to` in `segments` legs, waiting after each for the
 * rig to settle (so the drag is seen solving before the button is let go), and checks that the
 * last answer of each leg was for the pointer's place then (latest wins). Returns the solves sent.
 */
async function drag(page, name, to, segments = 4) {
  const before = (await calls(page)).length;
  const from = await tipClient(page, name);
  const end = await page.evaluate(([x, y]) => window.ikarus.toClient(x, y), to);
  await page.mouse.move(...from);
  await page.mouse.down();
  let last = before;
  for (let k = 1; k <= segments; k++) {
    const p = [from[0] + ((end[0] - from[0]) * k) / segments, from[1] + ((end[1] - from[1]) * k) / segments];
    await page.mouse.move(...p, { steps: 5 });
    await settled(page);
    const all = await calls(page);
    assert.ok(all.length > last, `${name}: leg ${k} of the drag sent no solve`);
    last = all.length;
    const goal = all[all.length - 1].body.goals.find((g) => g.bone === name);
    const at = await page.evaluate(([x, y]) => window.ikarus.toClient(x, y), [goal.x, goal.y]);
    assert.ok(Math.hypot(at[0] - p[0], at[1] - p[1]) < 0.01, `${name}: the last solve of leg ${k} was for ${at}, the pointer is at ${p}`);
  }
  await page.mouse.up();
  await settled(page);
  return (await calls(page)).slice(before);
}

test("the puppet: both feet pinned, both hands dragged to reachable points, all reached with the pins held", async () => {
  const { child, url } = await startServer();
  const browser = await launch();
  try {
    const { page, errors } = await openPage(browser);
    await watchSolves(page);
    await page.goto(url);
    await ready(page);

    // CCD, chosen for the arm, gives way to the default on a rig: it solves chains only.
    const offeredNow = () => page.evaluate(() => [...document.getElementById("method").options].filter((o) => !o.hidden && !o.disabled).map((o) => o.value));
    const armOffered = await offeredNow();
    assert.ok(armOffered.includes("ccd") && armOffered.includes("fabrik"), `${armOffered}`);
    await page.selectOption("#method", "ccd");
    await page.selectOption("#body-kind", "rig:puppet");
    await page.waitForFunction(() => window.ikarus.state.rig && window.ikarus.state.rig.rig.name === "puppet");
    const rigMethods = await page.evaluate(async () => (await (await fetch("/api/meta")).json()).methods.filter((m) => m.solves_rigs).map((m) => m.name));
    assert.deepEqual(rigMethods.slice().sort(), ["dls", "lm", "pinv", "sdls", "transpose"]);
    assert.deepEqual((await offeredNow()).sort(), rigMethods.slice().sort());
    assert.equal(await page.inputValue("#method"), "lm");
    // A rig is solved inside its joint ranges (the checkbox can turn them off).
    assert.equal(await page.isChecked("#limits"), true);
    // The arm's own controls step aside; the rig's appear, and the timeline plays its keys
    // (keyed.js; without the motions' duration, ease plot and replay).
    assert.equal(await page.isVisible("#links-body"), false);
    assert.equal(await page.isVisible("#timeline"), true);
    assert.equal(await page.isVisible("#keys"), true);
    assert.equal(await page.isVisible("#ease-plot"), false);
    assert.equal(await page.isVisible("#solver"), false);
    assert.equal(await page.isVisible("#clear-goals"), true);

    // Click both feet: pinned. A click again unpins, and once more pins.
    const rig = await page.evaluate(() => window.ikarus.state.rig.rig);
    const start = bodyForward(rig, []);
    const index = (n) => rig.bones.findIndex((b) => b.name === n);
    for (const foot of ["left_foot", "right_foot"]) await page.mouse.click(...(await tipClient(page, foot)));
    assert.deepEqual(await page.evaluate(() => [...window.ikarus.state.rig.pins].sort()), ["left_foot", "right_foot"]);
    await page.mouse.click(...(await tipClient(page, "right_foot")));
    assert.deepEqual(await page.evaluate(() => [...window.ikarus.state.rig.pins]), ["left_foot"]);
    await page.mouse.click(...(await tipClient(page, "right_foot")));
    assert.deepEqual(await page.evaluate(() => [...window.ikarus.state.rig.pins].sort()), ["left_foot", "right_foot"]);
    // Clicks pin; they do not solve.
    assert.equal((await calls(page)).length, 0);

    // Targets both hands reach together with the legs as they stand: the tips of the start pose
    // with the arms raised forward, every angle inside its range.
    const pose = rig.bones.map((b) => b.angle_deg);
    Object.assign(pose, { [index("left_upper_arm")]: -100, [index("left_forearm")]: 40, [index("right_upper_arm")]: -60, [index("right_forearm")]: 30 });
    rig.bones.forEach((b, i) => b.limits_deg && assert.ok(pose[i] >= b.limits_deg[0] && pose[i] <= b.limits_deg[1], b.name));
    const target = bodyForward(rig, pose);
    const rightTo = target.tips[index("right_hand")];
    const leftTo = target.tips[index("left_hand")];

    const rightSolves = await drag(page, "right_hand", rightTo);
    const leftSolves = await drag(page, "left_hand", leftTo);
    const log = await page.evaluate(() => window.rigSolves);
    assert.equal(log.most, 1, "one rig solve in flight at a time");
    // Each solve starts from the pose the one before it left (the pose shown).
    const all = log.calls;
    for (let k = 1; k < all.length; k++) {
      const shown = rig.bones.map((b) => all[k - 1].answer.angles_deg[b.name]);
      assert.deepEqual(all[k].body.start_deg, shown, `solve ${k} starts from the pose shown`);
    }
    // The right hand's goal stays while the left hand is dragged: both are solved together.
    assert.ok(rightSolves.every((c) => c.body.goals.length === 1));
    assert.ok(leftSolves.every((c) => c.body.goals.map((g) => g.bone).join() === "right_hand,left_hand"));
    assert.ok(all.every((c) => c.body.pins.slice().sort().join() === "left_foot,right_foot"));

    // The last answer: every effector (both goals, both pins) reached, the pins held.
    const last = all[all.length - 1].answer;
    assert.equal(last.status, "reached", `the last solve: ${JSON.stringify(last.effectors)}`);
    assert.deepEqual(last.effectors.map((e) => [e.name, e.pinned, e.status]), [
      ["right_hand", false, "reached"],
      ["left_hand", false, "reached"],
      ["left_foot", true, "reached"],
      ["right_foot", true, "reached"],
    ]);
    for (const e of last.effectors) assert.ok(e.error <= last.tolerance, `${e.name}: error ${e.error}`);
    // The drawn pose is the answer's: its hands on their goals, its feet where they were pinned
    // (each solve holds a pin within the tolerance of where that solve started).
    const shown = await page.evaluate(() => {
      const r = window.ikarus.state.rig;
      return { tips: r.tips, goals: [...r.goals], status: document.body.dataset.status, chip: document.getElementById("chip").dataset.kind };
    });
    assert.deepEqual([shown.status, shown.chip], ["reached", "neutral"]);
    for (const [bone, g] of shown.goals) {
      const tip = shown.tips[index(bone)];
      assert.ok(Math.hypot(tip[0] - g.x, tip[1] - g.y) <= last.tolerance + 1e-9, `${bone} drawn off its goal`);
    }
    for (const foot of ["left_foot", "right_foot"]) {
      const [a, b] = [shown.tips[index(foot)], start.tips[index(foot)]];
      assert.ok(Math.hypot(a[0] - b[0], a[1] - b[1]) <= all.length * last.tolerance, `${foot} drifted`);
    }
    assert.match(await page.textContent("#stats"), /^status reached · 2 goals, 2 pins/);

    // The SVG download is the rig as drawn: two pins (blue squares), two goals.
    const [d] = await Promise.all([page.waitForEvent("download"), page.click("#dl-svg")]);
    assert.equal(d.suggestedFilename(), "ikarus-rig.svg");
    const svg = readFileSync(await d.path(), "utf8");
    assert.equal(svg.match(/fill="#2b6cb0"/g).length, 2);
    // The pointer left the canvas for the button: no effector is ringed and named any more.
    assert.ok(!/>(left|right)_hand</.test(svg), "the hover ring of the last drag is in the download");

    mkdirSync(artifacts, { recursive: true });
    await page.screenshot({ path: join(artifacts, "rig-puppet.png") });

    // Clear goals drops them; the pose and the pins stay. Back to the arm: its list and limits.
    await page.click("#clear-goals");
    assert.deepEqual(await page.evaluate(() => [window.ikarus.state.rig.goals.size, window.ikarus.state.rig.pins.size]), [0, 2]);
    await page.selectOption("#body-kind", "arm");
    assert.equal(await page.evaluate(() => window.ikarus.state.rig), null);
    assert.equal(await page.isChecked("#limits"), false);
    assert.equal(await page.isVisible("#links-body"), true);
    assert.deepEqual(await offeredNow(), armOffered);
    assert.deepEqual(errors, [], "console errors");
  } finally {
    await browser.close();
    child.kill("SIGINT");
  }
});

test("a bad rig file is its one-line problem; the hand loads and follows a fingertip", async () => {
  const { child, url } = await startServer();
  const browser = await launch();
  try {
    const { page, errors } = await openPage(browser);
    await watchSolves(page);
    await page.goto(url);
    await ready(page);

    const bad = 'name = "broken"\n[[bones]]\nname = "a"\nlength = 1.0\n[[bones]]\nname = "b"\nparent = "nope"\nlength = 1.0\n';
    const problem = (await (await fetch(`${url}/api/rig/parse`, { method: "POST", headers: { "content-type": "application/toml" }, body: bad })).json()).problem;
    assert.ok(problem && !problem.includes("\n"), `the server's problem: ${problem}`);
    await page.setInputFiles("#rig-file", { name: "broken.toml", mimeType: "application/toml", buffer: Buffer.from(bad) });
    await page.waitForFunction(() => !document.getElementById("error").hidden, null, { timeout: 15000 });
    const message = await page.textContent("#error");
    assert.equal(message, forPeople(problem));
    assert.match(message, /nope/);
    assert.equal(await page.evaluate(() => document.getElementById("chip").dataset.kind), "bad");
    // Nothing changed: the arm is still on the canvas.
    assert.equal(await page.evaluate(() => window.ikarus.state.rig), null);
    assert.equal(await page.inputValue("#body-kind"), "arm");

    // A character file (Spine JSON) is posed as a character (e2e/character.test.mjs tries it).
    const raptor = readFileSync(join(import.meta.dirname, "..", "examples", "characters", "spine-raptor-pro.json"));
    await page.setInputFiles("#rig-file", { name: "raptor.json", mimeType: "application/json", buffer: raptor });
    await page.waitForFunction(() => window.ikarus.state.character && window.ikarus.state.character.name === "raptor.json", null, { timeout: 15000 });
    assert.equal(await page.inputValue("#body-kind"), "character");
    assert.equal(await page.evaluate(() => document.getElementById("error").hidden), true);

    // A good rig file loads as "Rig file: NAME" (the shipped hand, read from disk).
    const hand = readFileSync(join(import.meta.dirname, "..", "examples", "rigs", "hand.toml"));
    await page.setInputFiles("#rig-file", { name: "hand.toml", mimeType: "application/toml", buffer: hand });
    await page.waitForFunction(() => window.ikarus.state.rig && window.ikarus.state.rig.rig.name === "hand", null, { timeout: 15000 });
    assert.equal(await page.inputValue("#body-kind"), "file");
    assert.equal(await page.evaluate(() => window.ikarus.state.character), null);
    assert.equal(await page.evaluate(() => document.getElementById("error").hidden), true);

    // The shipped hand: a wrist, a palm and five fingers of three bones; the fingertips are its effectors.
    await page.selectOption("#body-kind", "rig:hand");
    const rig = await page.evaluate(() => window.ikarus.state.rig.rig);
    assert.equal(rig.bones.length, 17);
    assert.deepEqual(leafNames(rig), ["thumb_distal", "index_distal", "middle_distal", "ring_distal", "little_distal"]);
    const index = (n) => rig.bones.findIndex((b) => b.name === n);
    const pose = rig.bones.map((b) => b.angle_deg);
    Object.assign(pose, { [index("index_proximal")]: -30, [index("index_middle")]: -40, [index("index_distal")]: -20 });
    const to = bodyForward(rig, pose).tips[index("index_distal")];
    const before = await page.evaluate(() => window.ikarus.state.rig.pose_deg.slice());
    const solves = await drag(page, "index_distal", to);
    const last = solves[solves.length - 1].answer;
    assert.equal(last.status, "reached", JSON.stringify(last.effectors));
    assert.deepEqual(last.effectors.map((e) => [e.name, e.status]), [["index_distal", "reached"]]);
    const after = await page.evaluate(() => ({ pose: window.ikarus.state.rig.pose_deg, tip: window.ikarus.state.rig.tips }));
    assert.notDeepEqual(after.pose, before);
    const tip = after.tip[index("index_distal")];
    const goal = solves[solves.length - 1].body.goals[0];
    assert.ok(Math.hypot(tip[0] - goal.x, tip[1] - goal.y) <= last.tolerance + 1e-9);
    await page.screenshot({ path: join(artifacts, "rig-hand.png") });
    assert.deepEqual(errors, [], "console errors");
  } finally {
    await browser.close();
    child.kill("SIGINT");
  }
});

/**
 * Issue 24, point 11: natural rig poses. With both feet pinned, the right hand dragged forward
 * and up (within reach of the arm alone) moves the arm and leaves the torso upright; the same
 * puppet without its rest-pose preference (every `stiffness` removed, loaded as a rig file)
 * leans the whole torso back. Screenshots of both land beside the others (rest-after.png,
 * rest-before.png).
 */
test("the puppet reaches with its arm and keeps its torso upright; without stiffness it leaned back", async () => {
  const { child, url } = await startServer();
  const browser = await launch();
  const torso = ["pelvis", "spine", "neck", "head"];
  /** Pins both feet, drags the right hand forward and up; the torso's largest turn from rest, degrees. */
  async function reach(page) {
    await settled(page);
    for (const foot of ["left_foot", "right_foot"]) await page.mouse.click(...(await tipClient(page, foot)));
    const solves = await drag(page, "right_hand", [0.45, 0.9]);
    const last = solves[solves.length - 1].answer;
    assert.equal(last.status, "reached", JSON.stringify(last.effectors));
    const rig = await page.evaluate(() => window.ikarus.state.rig.rig);
    return Math.max(...torso.map((n) => Math.abs(last.angles_deg[n] - rig.bones.find((b) => b.name === n).angle_deg)));
  }
  try {
    const { page, errors } = await openPage(browser);
    await watchSolves(page);
    await page.goto(url);
    await ready(page);
    mkdirSync(artifacts, { recursive: true });

    await page.selectOption("#body-kind", "rig:puppet");
    await page.waitForFunction(() => window.ikarus.state.rig && window.ikarus.state.rig.rig.name === "puppet");
    assert.ok((await page.evaluate(() => window.ikarus.state.rig.rig.bones.find((b) => b.name === "spine").stiffness)) > 1);
    const upright = await reach(page);
    assert.ok(upright < 3, `the shipped puppet turned its torso ${upright}°`);
    await page.screenshot({ path: join(artifacts, "rest-after.png") });

    const text = readFileSync(join(import.meta.dirname, "..", "examples", "rigs", "puppet.toml"), "utf8");
    const loose = text.replace(/^stiffness = .*\n/gm, "");
    await page.setInputFiles("#rig-file", { name: "loose.toml", mimeType: "application/toml", buffer: Buffer.from(loose) });
    await page.waitForFunction(() => window.ikarus.state.rig && window.ikarus.state.rig.rig.bones.every((b) => !b.stiffness), null, { timeout: 15000 });
    const leaned = await reach(page);
    assert.ok(leaned > 10, `without stiffness the torso turned only ${leaned}°`);
    await page.screenshot({ path: join(artifacts, "rest-before.png") });
    assert.deepEqual(errors, [], "console errors");
  } finally {
    await browser.close();
    child.kill("SIGINT");
  }
});
