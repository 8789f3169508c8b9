// Unit tests of the playground's rig module (rig.js; no browser, no server): forward kinematics
// of a tree in any bone order, the view, the effectors, grabbing a tip, pins and goals, the
// request and the chip's summary. Run by e2e/run and .ci/run:
//   node --test e2e/rig.unit.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { join } from "node:path";
import {
  answerPose,
  dragGoal,
  fitRigView,
  leafNames,
  rigForRequest,
  rigReach,
  rigSolveRequest,
  rigSummary,
  shownEffectors,
  solvesRigs,
  tipAt,
  togglePin,
} from "../crates/ikarus-cli/src/serve/assets/rig.js";
import { toCanvas } from "../crates/ikarus-cli/src/serve/assets/view.js";
import { bodyForward as rigForward, boneOrder as rigOrder } from "../crates/ikarus-cli/src/serve/assets/body.js";

const close = (a, b, eps = 1e-12) => Math.abs(a - b) <= eps;
const closePoint = (p, q, eps = 1e-12) => assert.ok(close(p[0], q[0], eps) && close(p[1], q[1], eps), `${p} is not ${q}`);

// A small tree written children first: a trunk of two bones with two branches on its tip.
const tree = {
  name: "tree",
  base: [1, 2],
  bones: [
    { name: "left", parent: "top", length: 1, angle_deg: 90 },
    { name: "right", parent: "top", length: 2, angle_deg: -90, limits_deg: [-120, 0] },
    { name: "top", parent: "trunk", length: 1, angle_deg: 0 },
    { name: "trunk", parent: null, length: 1, angle_deg: 90 },
  ],
};

test("the order puts every parent before its children, whatever the file's order", () => {
  const order = rigOrder(tree);
  assert.deepEqual(order, [3, 2, 0, 1]);
  // The puppet's file order is already a parent-first one, and stays as written.
  const puppet = { bones: [{ name: "a" }, { name: "b", parent: "a" }, { name: "c" }, { name: "d", parent: "b" }] };
  assert.deepEqual(rigOrder(puppet), [0, 1, 3, 2]);
});

test("forward kinematics: angles relative to the parent, a root's to +x, from the base", () => {
  const f = rigForward(tree, []);
  closePoint(f.tips[3], [1, 3]);
  closePoint(f.tips[2], [1, 4]);
  // left turns 90° counter-clockwise from up: points to −x.
  closePoint(f.tips[0], [0, 4]);
  // right turns 90° clockwise from up: points to +x.
  closePoint(f.tips[1], [3, 4]);
  closePoint(f.starts[0], [1, 4]);
  closePoint(f.starts[3], [1, 2]);
  assert.deepEqual(f.headings, [180, 0, 90, 90]);
  assert.deepEqual(f.parentHeadings, [90, 90, 90, 0]);
  // A pose overrides the start angles; a missing angle is the bone's own.
  const g = rigForward(tree, [0, -90, 0, 0]);
  closePoint(g.tips[3], [2, 2]);
  closePoint(g.tips[2], [3, 2]);
  closePoint(g.tips[0], [4, 2]);
  closePoint(g.tips[1], [3, 0]);
});

test("the reach is the longest path of lengths; the view fits the start pose with room around it", () => {
  assert.equal(rigReach(tree), 4);
  // The start pose spans x 0..3, y 2..4 (the base at (1, 2)); the room is 0.35 × 4 = 1.4 on each side.
  const v = fitRigView(tree, 800, 600);
  const [mx, my] = toCanvas(v, 1.5, 3);
  assert.ok(close(mx, 400) && close(my, 300), `${mx}, ${my}`);
  assert.ok(close(v.scale, Math.min(800 / (3 + 2.8), 600 / (2 + 2.8))), `${v.scale}`);
  // The view is the rig's, whatever the pose shown: it is computed from the file alone.
  assert.deepEqual(fitRigView(tree, 800, 600), v);
});

test("effectors: the leaves, then any grabbed (goal) or pinned inner tip", () => {
  assert.deepEqual(leafNames(tree), ["left", "right"]);
  assert.deepEqual(shownEffectors(tree, new Map(), new Set()), ["left", "right"]);
  assert.deepEqual(shownEffectors(tree, new Map([["trunk", { x: 0, y: 0 }]]), new Set(["top"])), ["left", "right", "top", "trunk"]);
});

test("the shipped puppet has the four limbs' ends and the head as effectors", () => {
  const toml = readFileSync(join(import.meta.dirname, "..", "examples", "rigs", "puppet.toml"), "utf8");
  // The bones' names and parents, read from the file the simple way (one key per line).
  const bones = [];
  for (const line of toml.split("\n")) {
    if (line.startsWith("[[bones]]")) bones.push({ length: 1, angle_deg: 0 });
    const m = /^(name|parent) = "(.*)"/.exec(line);
    if (m && bones.length) bones[bones.length - 1][m[1]] = m[2];
  }
  assert.deepEqual(leafNames({ bones }).sort(), ["head", "left_foot", "left_hand", "right_foot", "right_hand"]);
});

test("a press grabs the nearest tip within the grab radius, effectors first on a tie", () => {
  const px = [[10, 10], [40, 10], [10, 10], [100, 100]];
  assert.equal(tipAt(tree, px, 12, 11), "top");
  assert.equal(tipAt(tree, px, 12, 11, new Set(["left"])), "left");
  assert.equal(tipAt(tree, px, 38, 12), "right");
  assert.equal(tipAt(tree, px, 70, 70), null);
  assert.equal(tipAt(tree, px, 100 + 14, 100), "trunk");
  assert.equal(tipAt(tree, px, 100 + 14.1, 100), null);
});

test("a click pins or unpins; pinning drops the goal; a drag makes a goal and unpins", () => {
  let goals = new Map([["left", { x: 1, y: 1 }]]);
  let pins = new Set();
  ({ goals, pins } = togglePin(goals, pins, "left"));
  assert.deepEqual([...pins], ["left"]);
  assert.equal(goals.size, 0);
  ({ goals, pins } = togglePin(goals, pins, "left"));
  assert.equal(pins.size, 0);
  ({ goals, pins } = dragGoal(goals, new Set(["right"]), "right", 2, 3));
  ({ goals, pins } = dragGoal(goals, pins, "left", 4, 5));
  ({ goals, pins } = dragGoal(goals, pins, "right", 6, 7));
  // The goals keep the order they were made in; the dragged pin is free.
  assert.deepEqual([...goals], [["right", { x: 6, y: 7 }], ["left", { x: 4, y: 5 }]]);
  assert.equal(pins.size, 0);
});

test("the request: the rig's fields, the pose, every goal and pin, no arm-only options", () => {
  const goals = new Map([["right", { x: 2, y: 3 }], ["left", { x: 0, y: 4 }]]);
  const pins = new Set(["trunk", "top"]);
  const req = rigSolveRequest({ ...tree, solver: { method: "dls" } }, [1, 2, 3, 4], goals, pins, { method: "lm", limits: true, rates: [1, 1] });
  assert.deepEqual(req, {
    rig: rigForRequest(tree),
    start_deg: [1, 2, 3, 4],
    goals: [{ bone: "right", x: 2, y: 3 }, { bone: "left", x: 0, y: 4 }],
    pins: ["top", "trunk"],
    options: { method: "lm", limits: true },
  });
  assert.equal(req.rig.solver, undefined);
  assert.equal("parent" in req.rig.bones[3], false);
  assert.deepEqual(req.rig.bones[1].limits_deg, [-120, 0]);
  assert.equal("stiffness" in req.rig.bones[1], false);
  // The rest-pose preference travels with the rig (without it the server would solve the
  // shipped rigs without their stiff spine).
  const stiff = { ...tree, bones: tree.bones.map((b) => (b.name === "top" ? { ...b, stiffness: 4, rest_deg: 5 } : b)) };
  const sent = rigForRequest(stiff).bones[2];
  assert.equal(sent.stiffness, 4);
  assert.equal(sent.rest_deg, 5);
});

test("an answer's pose in bone order, and the chip's line naming what failed", () => {
  assert.deepEqual(answerPose(tree, { angles_deg: { trunk: 10, left: 20, right: 30, top: 40 } }), [20, 30, 40, 10]);
  assert.deepEqual(answerPose(tree, { angles_deg: { left: 5 } }, [1, 2, 3, 4]), [5, 2, 3, 4]);
  const ok = rigSummary({
    status: "reached",
    iterations: 7,
    error: 1e-7,
    solve_us: 12,
    effectors: [
      { name: "left", pinned: false, status: "reached", error: 1e-7 },
      { name: "trunk", pinned: true, status: "reached", error: 0 },
    ],
  });
  assert.deepEqual(ok.failed, []);
  // A reached answer names no effector, even one whose own status was left unjudged.
  const unjudged = rigSummary({ status: "reached", effectors: [{ name: "left", pinned: false, status: "iteration_limit", error: 1e-9 }] });
  assert.deepEqual([unjudged.failed, unjudged.text], [[], "status reached · 1 goal"]);
  assert.equal(ok.text, "status reached · 1 goal, 1 pin · 7 iterations · error 1.00e-7 · 0.012 ms");
  const bad = rigSummary({
    status: "unreachable",
    iterations: 30,
    error: 0.21,
    effectors: [
      { name: "left", pinned: false, status: "unreachable", error: 0.21 },
      { name: "right", pinned: false, status: "reached", error: 1e-8 },
      { name: "trunk", pinned: true, status: "iteration_limit", error: 1e-3 },
    ],
  });
  assert.deepEqual(bad.failed, ["left", "trunk"]);
  assert.equal(bad.text, "status unreachable · left unreachable 2.1e-1, trunk (pin) iteration_limit 1.0e-3 · 30 iterations · error 2.10e-1");
});

test("the methods that solve rigs: what /api/meta says of each", () => {
  assert.equal(solvesRigs({ name: "lm", solves_rigs: true }), true);
  assert.equal(solvesRigs({ name: "ccd", solves_rigs: false }), false);
  assert.equal(solvesRigs({ name: "lm" }), false, "a method without the flag is not offered for rigs");
});

test("the method list of a rig: the methods that solve rigs, whatever the closed form's shapes", async () => {
  const { methodApplies } = await import("../crates/ikarus-cli/src/serve/assets/controls.js");
  const analytic = { name: "analytic", shapes: [[2, false], [3, true]] };
  assert.equal(methodApplies(analytic, 2, false), true);
  assert.equal(methodApplies(analytic, 2, false, true), false);
  assert.equal(methodApplies({ name: "ccd" }, 17, false, true), false);
  assert.equal(methodApplies({ name: "ccd" }, 17, false), true);
  assert.equal(methodApplies({ name: "sdls", solves_rigs: true }, 17, false, true), true);
});
