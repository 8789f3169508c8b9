// Rigs (skeletons: trees of bones), the pure parts (their forward kinematics is body.js's, the
// page's one): the view that fits a rig, its effectors (tips without children), which tip the
// pointer is on, the goals and pins the page keeps and the /api/solve request made of them, and
// an answer's one-line summary naming the effectors that failed. No DOM and no state of its own:
// node tests it (e2e/rig.unit.test.mjs). The page's wiring is rigs.js.

import { bodyForward, boneOrder, isPrismatic, restValue } from "./body.js";
import { fitBox, solveTime } from "./view.js";

/**
 * Whether `method` (a /api/meta method) solves rigs: its `solves_rigs`, the library's
 * `Method::solves_rigs` (the Jacobian methods; CCD, FABRIK and the closed form solve chains
 * only).
 */
export const solvesRigs = (method) => method.solves_rigs === true;

/** A pointer press within this many CSS pixels of a bone's tip grabs it. */
export const GRAB_PIXELS = 14;

/** Each bone's children's indices (file order), by bone index. */
export function rigChildren(rig) {
  const index = new Map(rig.bones.map((b, i) => [b.name, i]));
  const children = rig.bones.map(() => []);
  rig.bones.forEach((b, i) => {
    const p = b.parent === undefined || b.parent === null ? undefined : index.get(b.parent);
    if (p !== undefined) children[p].push(i);
  });
  return children;
}

/** The longest path of bone lengths from the base to a tip: nothing of the rig reaches farther. */
export function rigReach(rig) {
  const index = new Map(rig.bones.map((b, i) => [b.name, i]));
  const reach = new Array(rig.bones.length).fill(0);
  let most = 0;
  for (const i of boneOrder(rig)) {
    const b = rig.bones[i];
    const p = b.parent === undefined || b.parent === null ? undefined : index.get(b.parent);
    reach[i] = (p === undefined ? 0 : reach[p]) + Math.max(0, Number(b.length) || 0);
    most = Math.max(most, reach[i]);
  }
  return most;
}

/** The margin around a rig's start pose in its view, as a share of its reach (room to drag in). */
export const RIG_VIEW_ROOM = 0.35;

/**
 * The transform that fits the rig's start pose (its bounding box, the base included, with
 * RIG_VIEW_ROOM of its reach around it) into a `w` × `h` canvas, centred: canvas = (cx + x·scale,
 * cy − y·scale). It depends on the rig only, never on the pose shown, so the view stays still
 * while the rig moves.
 */
export function fitRigView(rig, w, h) {
  const { tips } = bodyForward(rig, []);
  const base = rig.base || [0, 0];
  const xs = [base[0], ...tips.map((t) => t[0])];
  const ys = [base[1], ...tips.map((t) => t[1])];
  const [x0, x1, y0, y1] = [Math.min(...xs), Math.max(...xs), Math.min(...ys), Math.max(...ys)];
  return fitBox({ x0, x1, y0, y1 }, Math.max(rigReach(rig), 1e-3) * RIG_VIEW_ROOM, w, h);
}

/** The names of the bones whose tips have no children: the rig's effectors (file order). */
export function leafNames(rig) {
  const children = rigChildren(rig);
  return rig.bones.filter((_, i) => children[i].length === 0).map((b) => b.name);
}

/**
 * The effectors drawn and grabbable as such: every leaf tip, then every other bone the reader
 * gave a goal or a pin (a grabbed inner tip becomes an effector), in file order.
 */
export function shownEffectors(rig, goals, pins) {
  const leaves = new Set(leafNames(rig));
  return rig.bones.map((b) => b.name).filter((name) => leaves.has(name) || goals.has(name) || pins.has(name));
}

/**
 * The bone whose tip is nearest the canvas point (px, py) within `radius` pixels, or null.
 * `tipsPx` are the tips in canvas pixels (bone order). On a tie (tips drawn on top of each
 * other) the effector wins (`preferred`, a Set of names), then the later bone, which is drawn last.
 */
export function tipAt(rig, tipsPx, px, py, preferred = new Set(), radius = GRAB_PIXELS) {
  let best = null;
  let bestD = Infinity;
  tipsPx.forEach(([x, y], i) => {
    const d = Math.hypot(x - px, y - py);
    if (d > radius) return;
    const name = rig.bones[i].name;
    const better = d < bestD - 1e-9 || (Math.abs(d - bestD) <= 1e-9 && (preferred.has(name) || !preferred.has(best)));
    if (better) {
      best = name;
      bestD = d;
    }
  });
  return best;
}

/**
 * A click (no drag) on an effector pins it, or unpins it. Pinning drops its goal (a pin holds
 * the tip where it is; a goal there would pull it away). Returns new {goals, pins}.
 */
export function togglePin(goals, pins, name) {
  const g = new Map(goals);
  const p = new Set(pins);
  if (p.has(name)) p.delete(name);
  else {
    p.add(name);
    g.delete(name);
  }
  return { goals: g, pins: p };
}

/**
 * A drag of effector `name` to (x, y): its goal is there (it keeps its place among the goals;
 * a new one goes last), and it is no longer pinned (the reader moves it). Returns new {goals, pins}.
 */
export function dragGoal(goals, pins, name, x, y) {
  const g = new Map(goals);
  const p = new Set(pins);
  g.set(name, { x, y });
  p.delete(name);
  return { goals: g, pins: p };
}

/** The rig as a request sends it: the file's name, base and bones (no `[solver]`: the page's controls rule). */
export function rigForRequest(rig) {
  return {
    name: rig.name,
    base: rig.base || [0, 0],
    bones: rig.bones.map((b) => ({
      name: b.name,
      ...(b.parent !== undefined && b.parent !== null ? { parent: b.parent } : {}),
      ...(b.offset ? { offset: b.offset } : {}),
      length: b.length,
      angle_deg: b.angle_deg,
      ...(b.limits_deg ? { limits_deg: b.limits_deg } : {}),
      // A prismatic joint (absent: revolute), its slide, extension and limits in length units.
      ...(b.joint ? { joint: b.joint } : {}),
      ...(b.slide ? { slide: b.slide } : {}),
      ...(b.extension !== undefined && b.extension !== null ? { extension: b.extension } : {}),
      ...(b.limits ? { limits: b.limits } : {}),
      // The rest-pose preference: a stiff bone turns less and is pulled back to its rest angle.
      ...(b.stiffness !== undefined && b.stiffness !== null ? { stiffness: b.stiffness } : {}),
      ...(b.rest_deg !== undefined && b.rest_deg !== null ? { rest_deg: b.rest_deg } : {}),
    })),
  };
}

/**
 * The /api/solve body of a rig: from the pose shown (`pose`, body.js's joint values in bone
 * order: `start_deg` holds the revolute bones' angles, and each prismatic bone starts from its
 * value as the rig's `extension`, keeping its fixed angle in `start_deg`), every goal (in the
 * order they were first made) and every pin (file order), with the page's solver options.
 * Arm-only options (the joint rates, one per link) are left out.
 */
export function rigSolveRequest(rig, pose, goals, pins, options) {
  const { rates: _rates, ...opts } = options || {};
  const names = rig.bones.map((b) => b.name);
  const sent = rigForRequest(rig);
  rig.bones.forEach((b, i) => {
    if (isPrismatic(b) && Number.isFinite(pose[i])) sent.bones[i].extension = pose[i];
  });
  return {
    rig: sent,
    start_deg: rig.bones.map((b, i) => (isPrismatic(b) ? b.angle_deg : pose[i])),
    goals: [...goals].map(([bone, g]) => ({ bone, x: g.x, y: g.y })),
    pins: names.filter((n) => pins.has(n)),
    options: opts,
  };
}

/**
 * The pose of an answer in bone order (body.js's joint values): `angles_deg` (an object bone →
 * degrees) for the revolute bones, `extensions` (bone → length) for the prismatic ones; a
 * missing bone keeps `fallback`'s value, else its own.
 */
export function answerPose(rig, answer, fallback = []) {
  const a = answer.angles_deg || {};
  const e = answer.extensions || {};
  return rig.bones.map((b, i) => {
    const v = (isPrismatic(b) ? e : a)[b.name];
    return Number.isFinite(v) ? v : fallback[i] ?? restValue(b);
  });
}

/**
 * An answer's line for the status chip: the overall status, then on failure each effector not
 * reached with its status and error (`left_hand unreachable 2.1e-1`), else the effectors
 * counted, and the iterations, the largest error and the time. `failed` lists those effectors' names.
 */
export function rigSummary(answer) {
  const effectors = answer.effectors || [];
  // The overall status is `reached` only if every effector is (the API's contract), so a reached
  // answer names no effector, whatever their own statuses say (the release build's solver, as
  // of the core's first commit, leaves them unjudged when the whole solve is reached).
  const failed = answer.status === "reached" ? [] : effectors.filter((e) => e.status !== "reached");
  const parts = [`status ${answer.status}`];
  if (failed.length) {
    parts.push(failed.map((e) => `${e.name}${e.pinned ? " (pin)" : ""} ${e.status} ${Number(e.error).toExponential(1)}`).join(", "));
  } else {
    const pins = effectors.filter((e) => e.pinned).length;
    const goals = effectors.length - pins;
    parts.push(`${goals} goal${goals === 1 ? "" : "s"}${pins ? `, ${pins} pin${pins === 1 ? "" : "s"}` : ""}`);
  }
  if (answer.iterations !== undefined) parts.push(`${answer.iterations} iterations`);
  if (answer.error !== undefined) parts.push(`error ${Number(answer.error).toExponential(2)}`);
  if (answer.solve_us !== undefined) parts.push(solveTime(answer.solve_us));
  return { status: answer.status, failed: failed.map((e) => e.name), text: parts.join(" · ") };
}
