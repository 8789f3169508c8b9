// ikarus-spine: ikarus's whole-body IK on a Spine 4.2 skeleton (spine-core's `Skeleton`), every
// frame. `attach(skeleton, options)` once; each frame, after the runtime's own update:
// `ik.clear()`, `ik.goal(…)`, `ik.pin(…)`, `ik.apply()`. Written against Spine's public runtime
// API (Skeleton.bones, ikConstraints, updateWorldTransform; Bone.data, parent, x … shearY, a b c d
// worldX worldY); it contains no part of Spine's runtime.
//
// Per frame nothing is allocated: the bones' numbers go into Float64Array views of the module's
// memory (made again only when that memory grows), the report object is the same every frame.
import init, { SpineRig } from "./ikarus_spine.js";

const NO_OPTIONS = Object.freeze({});
const NUMBERS = 13; // per bone: world a b c d worldX worldY, local x y rotation scaleX scaleY shearX shearY
const GOAL = 8; // per goal: bone, x, y, bones, angle, weight, priority, bend
const INHERITS = ["normal", "onlytranslation", "norotationorreflection", "noscale", "noscaleorreflection"];
/** A goal's priority code (0 primary, 1 secondary) from its option, −9 when unknown. */
const priorityOf = (p) => (p === undefined || p === "primary" ? 0 : p === "secondary" ? 1 : -9);
/** A goal's bend code (0 any, 1 positive: counter-clockwise, −1 negative) from its option, −9 when unknown. */
const bendOf = (b) => (b === undefined || b === "any" ? 0 : b === "positive" ? 1 : b === "negative" ? -1 : -9);

/** The bones a goal moves when its options name none: the bone and its parent (see README). */
export const DEFAULT_BONES = 2;
/** Spine's `Physics.pose` (none, reset, update, pose): constraints apply, physics does not step. */
export const PHYSICS_POSE = 3;

let loading = null;

/**
 * Loads the WebAssembly once (later calls share it): `source` as wasm-bindgen's init takes it
 * (bytes, a URL, a Response, a WebAssembly.Module), else the file beside this module: fetched in
 * browsers, read from disk in node (whose fetch has no file: URLs).
 */
export function load(source) {
  if (!loading) {
    loading = (async () => {
      let from = source;
      if (from === undefined) {
        from = new URL("./ikarus_spine_bg.wasm", import.meta.url);
        if (from.protocol === "file:") {
          const fs = "node:fs/promises"; // a variable: bundlers leave it to node
          const { readFile } = await import(/* @vite-ignore */ /* webpackIgnore: true */ fs);
          from = await readFile(from);
        }
      }
      return init({ module_or_path: from });
    })();
    loading.catch(() => {
      loading = null;
    });
  }
  return loading;
}

const fail = (message) => new Error(`ikarus-spine: ${message}`);
const show = (v) => (typeof v === "string" ? JSON.stringify(v) : String(v));
const finite = (v) => typeof v === "number" && Number.isFinite(v);

/** The inherit code (0 normal … 4 noScaleOrReflection, Spine's Inherit order) of bone data. */
function inheritOf(data) {
  const v = data.inherit ?? data.transformMode ?? 0;
  if (typeof v === "number" && Number.isInteger(v) && v >= 0 && v < INHERITS.length) return v;
  const i = typeof v === "string" ? INHERITS.indexOf(v.toLowerCase()) : -1;
  if (i < 0) throw fail(`bones["${data.name}"].data.inherit: unknown inherit mode ${show(v)}`);
  return i;
}

/**
 * Attaches ikarus to `skeleton` (a spine-core 4.2 Skeleton, or an object with its API).
 * options.limits: { boneName: [minDeg, maxDeg] }, the range of the bone's local `rotation` when
 * ikarus moves it. options.physics: what `apply()` passes to `skeleton.updateWorldTransform`
 * (default 3, Spine's Physics.pose: the frame's physics already stepped in the game's update).
 * options.wasm: where the WebAssembly comes from (see `load`). Resolves to an `Ik`.
 */
export async function attach(skeleton, options = {}) {
  const exports = await load(options.wasm);
  return new Ik(skeleton, options, exports.memory);
}

/** ikarus on one skeleton: goals and pins each frame, `apply()` solves them. */
export class Ik {
  constructor(skeleton, options, memory) {
    if (!skeleton || !Array.isArray(skeleton.bones) || typeof skeleton.updateWorldTransform !== "function")
      throw fail("skeleton: must be a Spine Skeleton (bones, updateWorldTransform), got " + show(skeleton));
    const bones = skeleton.bones;
    const n = bones.length;
    if (n === 0) throw fail("skeleton.bones: the skeleton has no bones");
    const physics = options.physics ?? PHYSICS_POSE;
    if (!Number.isInteger(physics)) throw fail(`physics: must be one of Spine's Physics values (0 to 3), got ${show(physics)}`);
    this.skeleton = skeleton;
    this.physics = physics;
    this.bones = bones;
    this.names = bones.map((b) => b.data.name);
    this.byName = new Map(this.names.map((name, i) => [name, i]));
    this.byBone = new Map(bones.map((b, i) => [b, i]));
    const parents = new Int32Array(n);
    const lengths = new Float64Array(n);
    const inherits = new Uint8Array(n);
    this.depths = new Int32Array(n); // bones from this one up to its root, itself included
    for (let i = 0; i < n; i++) {
      const b = bones[i];
      const p = b.parent == null ? -1 : this.byBone.get(b.parent) ?? -2;
      if (p === -2 || p >= i) throw fail(`bones["${this.names[i]}"].parent: not a bone listed before it`);
      parents[i] = p;
      lengths[i] = b.data.length ?? 0;
      inherits[i] = inheritOf(b.data);
      this.depths[i] = p < 0 ? 1 : this.depths[p] + 1;
    }
    const limits = new Float64Array(2 * n).fill(NaN);
    for (const [name, range] of Object.entries(options.limits ?? {})) {
      const i = this.byName.get(name);
      if (i === undefined) throw fail(`limits: no bone named ${show(name)} in the skeleton`);
      if (!Array.isArray(range) || range.length !== 2 || !finite(range[0]) || !finite(range[1]) || range[0] > range[1])
        throw fail(`limits[${show(name)}]: must be [minDeg, maxDeg] with min <= max, got ${show(JSON.stringify(range))}`);
      limits[2 * i] = range[0];
      limits[2 * i + 1] = range[1];
    }
    this.limits = limits;
    this.parents = parents;
    try {
      this.rig = new SpineRig(parents, lengths, inherits, limits);
    } catch (e) {
      throw fail(e && e.message ? e.message : String(e));
    }
    this.fast = typeof this.rig.applyFrame === "function";
    this.memory = memory;
    this.buffer = null;
    this.max = this.rig.maxGoals;
    // The Spine IK constraints, as bone indices, and what apply() keeps of each.
    const iks = skeleton.ikConstraints ?? [];
    this.iks = iks;
    this.ikBones = iks.map((c) => Int32Array.from(c.bones, (b) => this.byBone.get(b) ?? -1));
    this.savedMix = new Float64Array(iks.length);
    this.zeroed = new Uint8Array(iks.length);
    // Per bone, the apply() that last marked it moving (goal chains, pins) / whose solve moved
    // it / that gave it its applied transform (stepAside); the bones so held.
    this.marked = new Uint32Array(n);
    this.movedAt = new Uint32Array(n);
    this.heldAt = new Uint32Array(n);
    this.heldList = new Int32Array(n);
    this.stamp = 0;
    this.goalCount = 0;
    this.pinCount = 0;
    this.goalX = new Float64Array(this.max);
    this.pinGoal = new Uint8Array(this.max); // 1: a goal that is a pin of several bones (not reported)
    this.goalY = new Float64Array(this.max);
    this.goalBone = new Int32Array(this.max);
    this.pool = Array.from({ length: this.max }, () => ({ bone: "", error: 0 }));
    /** The report apply() returns: the same object every frame, overwritten by the next apply(). */
    this.report = { goals: [], moved: [] };
    this.views();
  }

  /** Makes the Float64Array views again when the module's memory grew (its buffer changed). */
  views() {
    const buffer = this.memory.buffer;
    if (buffer === this.buffer) return;
    const n = this.bones.length;
    const rig = this.rig;
    this.buffer = buffer;
    this.frame = new Float64Array(buffer, rig.framePtr, n * NUMBERS);
    this.goals = new Float64Array(buffer, rig.goalsPtr, this.max * GOAL);
    this.pins = new Float64Array(buffer, rig.pinsPtr, this.max);
    this.rotations = new Float64Array(buffer, rig.rotationsPtr, n);
    this.moved = new Float64Array(buffer, rig.movedPtr, n);
    this.errors = new Float64Array(buffer, rig.errorsPtr, this.max);
  }

  /** A bone's index from its name or its Bone object; `what` names the call in errors. */
  index(bone, what) {
    const i = typeof bone === "string" ? this.byName.get(bone) : this.byBone.get(bone);
    if (i === undefined)
      throw fail(
        typeof bone === "string"
          ? `${what}: bone: no bone named ${show(bone)} in the skeleton`
          : `${what}: bone: must be a bone's name or one of skeleton.bones, got ${show(bone && bone.data ? bone.data.name : bone)}`,
      );
    if (this.bones[i].active === false) throw fail(`${what}: bone: ${show(this.names[i])} is not active (not in the skin)`);
    return i;
  }

  /** Drops the goals and pins given since the last clear(). */
  clear() {
    this.goalCount = 0;
    this.pinCount = 0;
  }

  /**
   * A goal: `bone`'s tip (its origin plus its length along its x axis) to (x, y) in the skeleton's
   * world coordinates. options: bones (how many bones, from this one up, move; default 2), angle
   * (degrees, the bone's world direction), weight (> 0, default 1), priority ("primary" |
   * "secondary"), bend ("any" | "positive" | "negative").
   */
  goal(bone, x, y, options) {
    // Small, so that a hot caller's JIT can inline it (then its numbers are not boxed on the
    // way in): the checks in one test, the messages in refuseGoal.
    const i = typeof bone === "string" ? this.byName.get(bone) : this.byBone.get(bone);
    const o = options ?? NO_OPTIONS;
    const bones = o.bones ?? DEFAULT_BONES;
    const angle = o.angle ?? NaN;
    const weight = o.weight ?? 1;
    const priority = priorityOf(o.priority);
    const bend = bendOf(o.bend);
    const k = this.goalCount;
    if (
      i === undefined ||
      !(x - x === 0 && y - y === 0 && weight - weight === 0 && weight > 0) ||
      !(bones >= 1 && bones <= this.depths[i] && bones % 1 === 0) ||
      (o.angle !== undefined && !(angle - angle === 0)) ||
      priority === -9 ||
      bend === -9 ||
      k >= this.max ||
      this.bones[i].active === false
    )
      this.refuseGoal(bone, x, y, o);
    this.write(k, i, x, y, bones, angle, weight, priority, bend);
    this.pinGoal[k] = 0;
  }

  /** Writes goal `k` (checked) into the module's goal buffer; the goals are then k + 1. */
  write(k, i, x, y, bones, angle, weight, priority, bend) {
    this.views();
    const g = this.goals;
    const at = k * GOAL;
    g[at] = i;
    g[at + 1] = x;
    g[at + 2] = y;
    g[at + 3] = bones;
    g[at + 4] = angle;
    g[at + 5] = weight;
    g[at + 6] = priority;
    g[at + 7] = bend;
    this.goalBone[k] = i;
    this.goalX[k] = x;
    this.goalY[k] = y;
    this.goalCount = k + 1;
  }

  /** Throws the Error saying what of goal(bone, x, y, o) is wrong. */
  refuseGoal(bone, x, y, o) {
    const i = this.index(bone, "goal");
    const name = this.names[i];
    if (!finite(x)) throw fail(`goal(${name}): x: must be a finite number, got ${show(x)}`);
    if (!finite(y)) throw fail(`goal(${name}): y: must be a finite number, got ${show(y)}`);
    const bones = o.bones ?? DEFAULT_BONES;
    if (!Number.isInteger(bones) || bones < 1) throw fail(`goal(${name}): bones: must be a whole number >= 1, got ${show(bones)}`);
    if (bones > this.depths[i])
      throw fail(`goal(${name}): bones: ${bones} goes past the root (${name} has ${this.depths[i]} bones up to it)`);
    if (o.angle !== undefined && !finite(o.angle)) throw fail(`goal(${name}): angle: must be a finite number of degrees, got ${show(o.angle)}`);
    const weight = o.weight ?? 1;
    if (!finite(weight) || weight <= 0) throw fail(`goal(${name}): weight: must be a number > 0, got ${show(weight)}`);
    if (priorityOf(o.priority) === -9) throw fail(`goal(${name}): priority: must be "primary" or "secondary", got ${show(o.priority)}`);
    if (bendOf(o.bend) === -9) throw fail(`goal(${name}): bend: must be "any", "positive" or "negative", got ${show(o.bend)}`);
    throw fail(`goal(${name}): too many goals this frame (at most ${this.max}, one per bone)`);
  }

  /**
   * A pin: `bone`'s tip (position and direction) stays where the animation put it this frame.
   * options.bones (default 1): how many bones, from this one up, may move to keep it there (a
   * foot kept on the ground by its leg while a goal moves the hip: 3). With 1 the bone alone
   * turns (a rig pin); with more, the pin is a primary goal at the tip's place and direction.
   */
  pin(bone, options) {
    const i = this.index(bone, "pin");
    const bones = options?.bones ?? 1;
    if (!(bones >= 1 && bones <= this.depths[i] && bones % 1 === 0))
      throw fail(
        bones > this.depths[i]
          ? `pin(${this.names[i]}): bones: ${bones} goes past the root (${this.names[i]} has ${this.depths[i]} bones up to it)`
          : `pin(${this.names[i]}): bones: must be a whole number >= 1, got ${show(bones)}`,
      );
    if (bones > 1) {
      const b = this.bones[i];
      const length = b.data.length ?? 0;
      const k = this.goalCount;
      if (k >= this.max) throw fail(`pin(${this.names[i]}): too many goals and pins this frame (at most ${this.max}, one per bone)`);
      const x = b.worldX + b.a * length;
      const y = b.worldY + b.c * length;
      if (!(x - x === 0 && y - y === 0)) throw fail(`pin(${this.names[i]}): the bone's tip is not finite (${x}, ${y})`);
      this.write(k, i, x, y, bones, Math.atan2(b.c, b.a) * (180 / Math.PI), 1, 0, 0);
      this.pinGoal[k] = 1;
      return;
    }
    if (this.pinCount >= this.max) throw fail(`pin(${this.names[i]}): too many pins this frame (at most ${this.max}, one per bone)`);
    this.views();
    this.pins[this.pinCount++] = i;
  }

  /**
   * Solves this frame's goals and pins on the skeleton's current pose, writes the moved bones'
   * `rotation`, and runs `skeleton.updateWorldTransform(physics)` with the Spine IK constraints on
   * moved bones at mix 0 (restored right after; their bones first take the applied transform
   * the constraint gave them, see stepAside). Returns the report (the same object every frame):
   * goals [{ bone, error }] (error: the distance of the bone's tip, on the skeleton's world
   * numbers after the update, from its target), moved [names of the bones whose local transform
   * it wrote].
   */
  apply() {
    const { skeleton, bones, iks, ikBones } = this;
    const n = bones.length;
    this.views();
    const stamp = ++this.stamp;
    const held = this.stepAside(stamp);
    const f = this.frame;
    for (let i = 0, o = 0; i < n; i++, o += NUMBERS) {
      const b = bones[i];
      f[o] = b.a;
      f[o + 1] = b.b;
      f[o + 2] = b.c;
      f[o + 3] = b.d;
      f[o + 4] = b.worldX;
      f[o + 5] = b.worldY;
      f[o + 6] = b.x;
      f[o + 7] = b.y;
      f[o + 8] = b.rotation;
      f[o + 9] = b.scaleX;
      f[o + 10] = b.scaleY;
      f[o + 11] = b.shearX;
      f[o + 12] = b.shearY;
    }
    const m = this.solve(skeleton.x ?? 0, skeleton.y ?? 0, skeleton.scaleX ?? 1, skeleton.scaleY ?? 1);
    this.views();
    const { movedAt, heldAt, moved, rotations, limits, zeroed } = this;
    const names = this.report.moved;
    let written = 0;
    for (let k = 0; k < m; k++) {
      const i = moved[k];
      let r = rotations[i];
      // The turn the limits name (the same pose, 360° apart) when the solve's is another.
      const lo = limits[2 * i];
      const hi = limits[2 * i + 1];
      if (r < lo || r > hi) {
        const w = r + 360 * Math.ceil((lo - r) / 360); // the first turn of r at or above lo
        if (w <= hi) r = w;
      }
      bones[i].rotation = r;
      movedAt[i] = stamp;
      names[written++] = this.names[i];
    }
    for (let k = 0; k < held; k++) {
      const i = this.heldList[k];
      if (movedAt[i] !== stamp) names[written++] = this.names[i];
    }
    if (names.length !== written) names.length = written;
    for (let c = 0; c < iks.length; c++) if (zeroed[c]) iks[c].mix = 0;
    try {
      skeleton.updateWorldTransform(this.physics);
    } finally {
      for (let c = 0; c < iks.length; c++) if (zeroed[c]) iks[c].mix = this.savedMix[c];
    }
    return this.reported();
  }

  /**
   * Before the solve: marks the bones it moves (each goal's chain, each pin) and finds the Spine
   * IK constraints on them, which step aside (mix 0) for this frame's update so that the goal
   * wins there. Their bones take as local transform the applied one the constraint gave them
   * this frame (Spine's `ax, ay, arotation, ascaleX, ascaleY, ashearX, ashearY`: a stretch
   * included), so that with mix 0 the update puts the bones the solve leaves where the
   * constraint had them, and the solve starts from that pose. Returns how many bones it so held
   * (listed in heldList).
   */
  stepAside(stamp) {
    const { iks, ikBones, marked, heldAt, parents, goals, pins, bones } = this;
    for (let k = 0; k < this.goalCount; k++) {
      let i = goals[k * GOAL];
      for (let left = goals[k * GOAL + 3]; left > 0 && i >= 0; left--, i = parents[i]) marked[i] = stamp;
    }
    // A pin moves only under a moving bone (the rig's rule: nothing above it turns otherwise),
    // and nothing moves without a goal.
    for (let k = 0; k < this.pinCount && this.goalCount > 0; k++) {
      let q = pins[k];
      while (q >= 0 && marked[q] !== stamp) q = parents[q];
      if (q >= 0) marked[pins[k]] = stamp;
    }
    let held = 0;
    for (let c = 0; c < iks.length; c++) {
      const list = ikBones[c];
      let touched = 0;
      for (let j = 0; j < list.length; j++) if (list[j] >= 0 && marked[list[j]] === stamp) touched = 1;
      this.zeroed[c] = touched;
      if (!touched) continue;
      this.savedMix[c] = iks[c].mix;
      for (let j = 0; j < list.length; j++) {
        const i = list[j];
        if (i < 0 || heldAt[i] === stamp) continue;
        const b = bones[i];
        if (typeof b.arotation !== "number") continue; // not a Spine Bone: its own locals stay
        b.x = b.ax;
        b.y = b.ay;
        b.rotation = b.arotation;
        b.scaleX = b.ascaleX;
        b.scaleY = b.ascaleY;
        b.shearX = b.ashearX;
        b.shearY = b.ashearY;
        heldAt[i] = stamp;
        this.heldList[held++] = i;
      }
    }
    return held;
  }

  /**
   * The module's solve of the frame written at framePtr: how many bones moved. `applyFrame`
   * (one plain number back, −1 on bad input) when the module has it: `apply`'s glue receives a
   * `Result` as a wasm multi-value return, a fresh JS array every call.
   */
  solve(x, y, sx, sy) {
    const rig = this.rig;
    if (this.fast) {
      const m = rig.applyFrame(x, y, sx, sy, this.goalCount, this.pinCount);
      if (m < 0) throw fail(rig.lastError);
      return m;
    }
    try {
      return rig.apply(x, y, sx, sy, this.goalCount, this.pinCount);
    } catch (e) {
      throw fail(e && e.message ? e.message : String(e));
    }
  }

  /** Fills the report's goals from the skeleton's world numbers after the update. */
  reported() {
    const goals = this.report.goals;
    let count = 0;
    for (let k = 0; k < this.goalCount; k++) if (!this.pinGoal[k]) count++;
    if (goals.length !== count) goals.length = count;
    for (let k = 0, g = 0; k < this.goalCount; k++) {
      if (this.pinGoal[k]) continue;
      const i = this.goalBone[k];
      const b = this.bones[i];
      const length = b.data.length ?? 0;
      const entry = this.pool[g];
      entry.bone = this.names[i];
      const dx = b.worldX + b.a * length - this.goalX[k];
      const dy = b.worldY + b.c * length - this.goalY[k];
      entry.error = Math.sqrt(dx * dx + dy * dy); // not Math.hypot: a builtin call, its answer boxed
      goals[g++] = entry;
    }
    return this.report;
  }

  /** Frees the module's memory for this skeleton; the Ik is unusable afterwards. */
  dispose() {
    this.rig.free();
    this.rig = null;
  }
}
