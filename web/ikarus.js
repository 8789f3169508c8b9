// ikarus in the browser (or in node): the JSON API of `ikarus serve` without a server. A plain
// ES module, no bundler: it wraps the module that `wasm-bindgen --target web` writes
// (ikarus_wasm.js and ikarus_wasm_bg.wasm, beside this file in the directory `bash web/build DIR`
// fills). Every function takes and returns plain objects in the API's JSON shapes (README:
// "`ikarus serve` (API)"); the answers are the server's bytes for the same request, because the
// module runs the server's own code (`ikarus_edge::edge::call`).
//
//   import * as ikarus from "./ikarus.js";
//   await ikarus.init();
//   const answer = ikarus.solve({ goal: { x: 2, y: 3 } });   // the seed arm, `ikarus solve`'s settings
//   answer.status;                                            // "reached"
//   answer.angles_deg;                                        // [8.4…, 85.7…, 51.4…]
//
// A refused request throws an IkarusError: `.status` is the HTTP status the server answers for
// it (400 malformed JSON, 422 a bad value) and `.message` its one-line message, naming the field
// and the value (`request body: goal.y: invalid type: string "a", expected f64 at line 1 column
// 22`). Calls are synchronous once `init()` has resolved; they run on the calling thread.
//
// A call that traps (out of memory past wasm32's 4 GB, a panic) would leave the module dead:
// instead it throws an IkarusError (500, `restarted: true`) and the module is instantiated afresh
// before it returns, so the next call works; Chains and Characters made before are refused then
// (make new ones). A call cannot be stopped from inside once it runs: a page runs the module in
// a worker and terminates it (the static page does, after a budget per job: web/ikarus-thread.js).
//
// The hot paths have typed handles beside these, without JSON: `Chain` (an arm read once, then
// `solve(x, y, out)` / `solveBatch(goals, out)`, and `followHere(startDeg, x, y, maxStepDeg)`,
// one step of following the pointer) and `Character` (a character file read once,
// then `pose(time, targets, out)`), writing numbers into a Float64Array the caller owns.
//
// Two modules: the full one (ikarus_wasm_bg.wasm, `init()`: every endpoint, TOML, the refusals'
// field paths) and a small one (ikarus_core_bg.wasm, `initCore()`: the typed handles and the
// library, no `call`), which a page loads first. Handles are made in the full module once it is
// loaded, else in the small one; their numbers are the same bit for bit. In the small module a
// value of the wrong kind in an arm, options or character file is refused with serde_json's line
// without the field's path (load the full module for the server's line).

import wasmInit, * as wasm from "./ikarus_wasm.js";
import coreInit, * as core from "./ikarus_core.js";

/** A request the module refused, or a failure inside it: the server's status and one-line message. */
export class IkarusError extends Error {
  /**
   * @param {number} status  the HTTP status `ikarus serve` answers for the same request
   * @param {string} message the one-line message (the server's `{"error": …}`)
   */
  constructor(status, message) {
    super(message);
    this.name = "IkarusError";
    this.status = status;
  }
}

/**
 * The full module once loaded: its glue (`api`) and its memory; `loading` the promise;
 * `generation` how many times it was restarted after a trap (handles remember theirs).
 */
const full = { api: wasm, memory: null, loading: null, generation: 0 };
/** The small module once loaded. */
const small = { api: core, memory: null, loading: null, generation: 0 };
let ready = null;

/** Loads module `m` (full or small) from `source` once; resolves when its memory is known. */
function load(m, start, source) {
  m.loading ??= start(source === undefined ? undefined : { module_or_path: source }).then((exports) => {
    m.memory = exports.memory;
  });
  return m.loading;
}

/**
 * Loads and instantiates the full WebAssembly module (every function here); call (and await)
 * once before anything else. In a page it fetches `ikarus_wasm_bg.wasm` beside this file;
 * elsewhere (node) pass the module's bytes, a `WebAssembly.Module`, a URL or a Response.
 * @param {BufferSource | WebAssembly.Module | URL | string | Response} [source]
 * @returns {Promise<void>}
 */
export function init(source) {
  ready ??= load(full, wasmInit, source);
  return ready;
}

/**
 * Loads the small module (`ikarus_core_bg.wasm`: `Chain`, `Character`, `version`, no `call`),
 * enough for the typed handles; `init()` may follow at any time for the rest.
 * @param {BufferSource | WebAssembly.Module | URL | string | Response} [source]
 * @returns {Promise<void>}
 */
export const initCore = (source) => load(small, coreInit, source);

/** Whether the full module is loaded (`call` and the JSON functions work). */
export const fullLoaded = () => full.memory !== null;

/** The module handles are made in: the full one once loaded, else the small one. */
function handles() {
  if (full.memory) return full;
  if (small.memory) return small;
  throw new IkarusError(500, "ikarus.js: call init() or initCore() (and await it) first");
}

/** A Float64Array view of `len` numbers at byte `ptr` of module `m`'s memory, `view` if still valid. */
function viewOf(m, view, ptr, len) {
  return view && view.buffer === m.memory.buffer ? view : new Float64Array(m.memory.buffer, ptr, len);
}

/** The version of ikarus the module was built from. */
export const version = () => handles().api.version();

/**
 * The raw call: the answer's text for endpoint `path` ("solve", "/api/solve", "arm/default", …)
 * and request `body` (JSON text; TOML text for "arm/parse" and "rig/parse"; "" for the GET
 * endpoints). Throws an IkarusError.
 * @param {string} path
 * @param {string} [body]
 * @returns {string}
 */
export function call(path, body = "") {
  return onFull(() => full.api.call(path, body));
}

/** `run` on the full module, guarded (see `failure`); throws when it is not loaded. */
function onFull(run) {
  if (!full.memory) throw new IkarusError(500, "ikarus.js: call init() (and await it) first");
  return guarded(full, run);
}

/**
 * The IkarusError of what module `m` (default: the full one) threw: a refusal (its Problem), or
 * a trap. A trap (out of memory, a panic: both abort on wasm32, as `unreachable`; a stack
 * overflow) leaves the instance dead for good (every later call would trap), so the module is
 * instantiated afresh at once (`restart`) and the error says so (`restarted: true`); the failed
 * call is not retried.
 */
function failure(e, m = full) {
  if (e instanceof m.api.Problem) {
    const error = new IkarusError(e.status, e.message);
    e.free();
    return error;
  }
  const what = e && e.message ? e.message : String(e);
  if (!(e instanceof WebAssembly.RuntimeError || e instanceof RangeError)) return new IkarusError(500, `internal error: ${what}`);
  // Say the panic's message if the module kept one (asking may trap too: the memory may be full).
  let panic;
  try {
    panic = e instanceof WebAssembly.RuntimeError ? m.api.last_panic() : undefined;
  } catch (_) {
    panic = undefined;
  }
  restart(m);
  const error = new IkarusError(
    500,
    panic
      ? `internal error: ${panic}; the WebAssembly module stopped and was restarted`
      : `the WebAssembly module stopped (${what}: out of memory?): it was restarted; ask for less work`,
  );
  error.restarted = true;
  return error;
}

/**
 * Module `m` instantiated afresh from its compiled code after a trap (the glue's
 * `__wbg_reset_state`, which web/bindgen asks wasm-bindgen for): a new memory, no state of the
 * old instance; handles made before (their generation is older) are refused from now on.
 */
function restart(m) {
  m.api.__wbg_reset_state();
  m.memory = m.api.initSync().memory;
  m.generation++;
}

/** Throws if a handle made in generation `made` of module `m` outlived a restart of it. */
function live(m, made, what) {
  if (made !== m.generation)
    throw new IkarusError(500, `ikarus.js: this ${what} was made before the WebAssembly module restarted (after a trap); make a new one`);
}

/** The typed handle `make(api)` makes in module `m`, or the IkarusError it refused with. */
function handle(m, make) {
  return guarded(m, () => make(m.api));
}

/** What `f()` returns, or the IkarusError of what module `m` threw (`failure`). */
function guarded(m, f) {
  if (m.memory === null) throw new IkarusError(500, "ikarus.js: the WebAssembly module is not loaded");
  try {
    return f();
  } catch (e) {
    throw failure(e, m);
  }
}

/**
 * The status names of a Chain record's last number (its status code).
 * @type {readonly string[]}
 */
export const STATUS = Object.freeze(["reached", "unreachable", "stalled", "iteration_limit", "interrupted"]);

/**
 * The status names of a Chain follow record's last number (`followHere`'s code).
 * @type {readonly string[]}
 */
export const FOLLOW_STATUS = Object.freeze(["reached", "limited", "unreachable", "stalled", "iteration_limit", "interrupted", "off_path"]);

/**
 * An arm read once and solved without JSON (the hot path: following the pointer, many goals).
 * `new Chain(arm?, options?)` takes `/api/solve`'s `arm` and `options` objects (the seed arm
 * and `ikarus solve`'s settings when left out; no frames are recorded) and throws an
 * IkarusError with the server's line for a bad one. Each solve writes a record of
 * `recordLen = joints + 6` numbers into a Float64Array you own: the angles in degrees, the
 * tip's x and y, the error, the iterations, the restarts, and the status code (`STATUS[code]`).
 * The numbers are those of `solve({arm, options, goal: {x, y}})`, bit for bit. Call `free()`
 * when done with it.
 *
 *   const chain = new ikarus.Chain();
 *   const out = new Float64Array(chain.recordLen);
 *   ikarus.STATUS[chain.solve(2, 3, out)];   // "reached"; out[0..3]: the angles in degrees
 */
export class Chain {
  #h;
  #m;
  #gen;
  #ptr;
  #view = null;
  #followPtr;
  #follow = null;
  /**
   * @param {object} [arm]     the API's `arm` object
   * @param {object} [options] the API's `options` object
   */
  constructor(arm, options) {
    this.#m = handles();
    this.#gen = this.#m.generation;
    this.#h = handle(this.#m, (api) => new api.Chain(arm === undefined ? "" : JSON.stringify(arm), options === undefined ? "" : JSON.stringify(options)));
    /** The number of joints. */
    this.joints = this.#h.joints;
    /** The numbers of one record: joints + 6. */
    this.recordLen = this.#h.recordLen;
    this.#ptr = this.#h.recordPtr;
    /** The numbers of one follow record: 3 × joints + 5. */
    this.followLen = this.#h.followLen;
    this.#followPtr = this.#h.followPtr;
  }

  /**
   * Solves the goal (x, y) from the arm's start pose into `out[0 .. recordLen]`; returns the
   * status code. The module writes the record into its own memory and it is copied from there
   * (no array is passed through wasm-bindgen's glue, which would copy it in and out).
   * @param {number} x
   * @param {number} y
   * @param {Float64Array} out
   * @returns {number}
   */
  solve(x, y, out) {
    if (!(out instanceof Float64Array) || out.length < this.recordLen) return this.#solveGlue(x, y, out);
    const code = this.solveHere(x, y);
    out.set(this.#view);
    return code;
  }

  /** `solve` through the glue's copies: what refuses an `out` that is not one, with the module's line. */
  #solveGlue(x, y, out) {
    return this.#run(() => this.#h.solve(x, y, out));
  }

  /**
   * Solves the goal (x, y) into the chain's own record (`record`, a view over the module's
   * memory, valid until the next call on this chain); returns the status code. No copy at all.
   * @param {number} x
   * @param {number} y
   * @returns {number}
   */
  solveHere(x, y) {
    const code = this.#run(() => this.#h.solveHere(x, y));
    this.#view = viewOf(this.#m, this.#view, this.#ptr, this.recordLen);
    return code;
  }

  /** The last `solveHere`'s (or `solve`'s) record: a Float64Array view over the module's memory. */
  get record() {
    live(this.#m, this.#gen, "Chain");
    this.#view = viewOf(this.#m, this.#view, this.#ptr, this.recordLen);
    return this.#view;
  }

  /**
   * Solves each goal of `goals` (flat x, y pairs) from the start pose, through the library's
   * batch path, writing one record per goal into `out` (at least goals.length / 2 records).
   * @param {Float64Array} goals
   * @param {Float64Array} out
   */
  solveBatch(goals, out) {
    this.#run(() => this.#h.solveBatch(goals, out));
  }

  /**
   * One step of following the pointer (the page's follow mode): from the pose `startDeg`
   * (degrees, one per joint) toward (x, y), no joint moving more than `maxStepDeg`. Writes the
   * chain's follow record (`followRecord`, a view over the module's memory valid until the next
   * call on this chain; `followLen = 3 × joints + 5` numbers): the angles in degrees, the joints'
   * x, y pairs from the base to the tip, the error, the step in degrees, and the status code
   * (`FOLLOW_STATUS[code]`: "reached", "limited", "unreachable", …), which it returns. The
   * numbers are those of `track({arm, options, start_deg, max_step_deg, path: [[x, y]], mode:
   * "follow", bound_first: true}).samples[0]`, bit for bit.
   * @param {Float64Array | number[]} startDeg
   * @param {number} x
   * @param {number} y
   * @param {number} maxStepDeg
   * @returns {number}
   */
  followHere(startDeg, x, y, maxStepDeg) {
    const code = this.#run(() => this.#h.followHere(startDeg, x, y, maxStepDeg));
    this.#follow = viewOf(this.#m, this.#follow, this.#followPtr, this.followLen);
    return code;
  }

  /** The last `followHere`'s record: a Float64Array view over the module's memory. */
  get followRecord() {
    live(this.#m, this.#gen, "Chain");
    this.#follow = viewOf(this.#m, this.#follow, this.#followPtr, this.followLen);
    return this.#follow;
  }

  /** `f()` in this chain's module, unless the module restarted since the chain was made. */
  #run(f) {
    live(this.#m, this.#gen, "Chain");
    return guarded(this.#m, f);
  }

  /** Releases the module's memory for this chain (nothing to release once the module restarted). */
  free() {
    if (this.#gen === this.#m.generation) this.#h.free();
  }
}

/**
 * A character file (Spine or DragonBones JSON text) read once and posed without JSON, as
 * `/api/pose` poses it (the runtime's rules). `bones` (the file's order) and `animations` are
 * read once; `setAnimation(name)` picks the animation (undefined: the setup pose); `pose(time,
 * targets, out)` writes `poseLen = 5 × bones` numbers into a Float64Array you own, per bone:
 * the world origin's x and y, the rotation in degrees and the tip's x and y — those of
 * `pose({rig, animation, time, targets})`, bit for bit. `targets` is a Float64Array of flat
 * `bone index, x, y` triples (the bone's origin put at (x, y) before the constraints).
 */
export class Character {
  #h;
  #m;
  #gen;
  #ptr;
  #view = null;
  /** @param {string} text the character file's text */
  constructor(text) {
    this.#m = handles();
    this.#gen = this.#m.generation;
    this.#h = handle(this.#m, (api) => new api.Character(text));
    /** @type {string[]} the bones' names, the pose's order */
    this.bones = this.#h.bones();
    /** @type {string[]} */
    this.animations = this.#h.animations();
    /** The numbers of one pose: 5 × bones. */
    this.poseLen = this.#h.poseLen;
    const flat = this.#h.unsupported();
    /** @type {{kind: string, name: string}[]} the constraints left inactive (`/api/pose`'s `unsupported`) */
    this.unsupported = [];
    for (let i = 0; i < flat.length; i += 2) this.unsupported.push({ kind: flat[i], name: flat[i + 1] });
    this.#ptr = this.#h.numbersPtr;
  }

  /** @param {string | undefined} name the animation sampled from now on (undefined: none) */
  setAnimation(name) {
    this.#run(() => this.#h.setAnimation(name));
  }

  /**
   * Poses the character into `out` (copied from the module's memory, as `poseHere` leaves it).
   * @param {number} time          seconds into the animation (ignored without one)
   * @param {Float64Array} targets bone index, x, y triples
   * @param {Float64Array} out     at least poseLen numbers
   */
  pose(time, targets, out) {
    if (!(out instanceof Float64Array) || out.length < this.poseLen) {
      this.#run(() => this.#h.pose(time, targets, out));
      return;
    }
    out.set(this.poseHere(time, targets));
  }

  /**
   * Poses the character into its own numbers and returns them: a Float64Array view over the
   * module's memory (poseLen numbers), valid until the next call on this character.
   * @param {number} time          seconds into the animation (ignored without one)
   * @param {Float64Array} targets bone index, x, y triples
   * @returns {Float64Array}
   */
  poseHere(time, targets) {
    this.#run(() => this.#h.poseHere(time, targets));
    this.#view = viewOf(this.#m, this.#view, this.#ptr, this.poseLen);
    return this.#view;
  }

  /** `f()` in this character's module, unless the module restarted since the character was made. */
  #run(f) {
    live(this.#m, this.#gen, "Character");
    return guarded(this.#m, f);
  }

  /** Releases the module's memory for this character (nothing to release once the module restarted). */
  free() {
    if (this.#gen === this.#m.generation) this.#h.free();
  }
}

const json = (path, request) => JSON.parse(call(path, request === undefined ? "" : JSON.stringify(request)));

/**
 * Solves a goal: `{goal: {x, y, angle_deg?}, arm?, start_deg?, options?}` → `{status,
 * iterations, restarts, error, end_effector, angles_deg, joints, frames, solve_us, …}` (POST
 * /api/solve). With `rig` and `goals` instead of `arm` and `goal` it solves a skeleton (README:
 * "The API with rigs").
 * @param {object} request
 * @returns {object}
 */
export const solve = (request) => json("solve", request);

/**
 * A motion to a goal: `{goal, arm?, options?, ease?, frames?, duration?, via?, …}` → `{frames:
 * [{time, angles_deg, joints}], …}` (POST /api/animate).
 * @param {object} request
 * @returns {object}
 */
export const animate = (request) => json("animate", request);

/**
 * The tip along a path: `{path: [[x, y], …] | shape, mode: "plan" | "follow", arm?, options?,
 * max_step_deg?, …}` → per-sample poses and a summary with the flips (POST /api/track).
 * @param {object} request
 * @returns {object}
 */
export const track = (request) => json("track", request);

/**
 * Where the tip can go: `{arm?, limits?}` → the exact region (`area`, `boundary`, `exact:
 * true`); with `grid: true` or any of `resolution`, `samples`, `seed`, the sampled grid instead
 * (POST /api/workspace).
 * @param {object} request
 * @returns {object}
 */
export const workspace = (request) => json("workspace", request);

/**
 * Whether a point can be reached: `{point: [x, y], arm?, limits?, tolerance?}` → `{reachable,
 * distance, nearest}`; with `points: [[x, y], …]`, an array of those (POST /api/reach).
 * @param {object} request
 * @returns {object}
 */
export const reach = (request) => json("reach", request);

/**
 * A character posed as its runtime does: `{rig: "<the Spine or DragonBones file's text>",
 * animation?, time?, targets?: [{bone, x, y}]}` → `{bones: [{name, x, y, rotation_deg, tip}],
 * unsupported}`, the JSON of `ikarus pose --format json` (POST /api/pose).
 * @param {object} request
 * @returns {object}
 */
export const pose = (request) => json("pose", request);

/** The methods, limit modes, eases, defaults and palette the page's lists use (GET /api/meta). */
export const meta = () => json("meta");

/** The built-in seed arm, an `arm` object (GET /api/arm/default). */
export const defaultArm = () => json("arm/default");

/** The shipped rigs: `{rigs: [{name, rig}, …]}` (GET /api/rigs). */
export const rigs = () => json("rigs");

/**
 * Reads an arm file (TOML, the format of `ikarus --arm`): `{arm}`, or `{problem}` with the
 * CLI's one-line error for a bad file (POST /api/arm/parse).
 * @param {string} text
 * @returns {{arm?: object, problem?: string}}
 */
export const parseArm = (text) => JSON.parse(call("arm/parse", text));

/**
 * Reads a rig file (TOML, the format of `ikarus --rig`): `{rig}`, or `{problem}` (POST
 * /api/rig/parse).
 * @param {string} text
 * @returns {{rig?: object, problem?: string}}
 */
export const parseRig = (text) => JSON.parse(call("rig/parse", text));

/** A character file's bytes (Uint8Array, ArrayBuffer) as JSON text: a Spine `.skel`'s decoded as `ikarus pose --rig FILE.skel` reads it. */
export const characterText = (bytes) => onFull(() => full.api.characterText(new Uint8Array(bytes)));
/** A file's bytes read as POST /api/rig/parse?text=1 reads them (application/octet-stream): `{character, text}` or `{rig}`; a bad file throws (422). */
export const parseRigBytes = (bytes) => JSON.parse(onFull(() => full.api.parseRigBytes(new Uint8Array(bytes))));

/**
 * The arm file (TOML text) of an `arm` object (POST /api/arm/toml).
 * @param {object} arm
 * @returns {string}
 */
export const armToml = (arm) => call("arm/toml", JSON.stringify({ arm }));
