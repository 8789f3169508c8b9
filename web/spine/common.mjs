// What the package's spineboy tests and speed.mjs share: the built package, the stand-in skeleton
// (web/spine/standin/: spine-core's documented API posed by ikarus's own runtime-exact code in
// the playground's small module), and a walk at 60 Hz with the game's own update each frame.
//   IKARUS_SPINE_DIR: what `bash web/spine/build DIR` wrote; IKARUS_WEB_DIR: what `bash web/build DIR` wrote.
import { readFileSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath, pathToFileURL } from "node:url";
import { loadStandIn } from "./standin/index.js";

export const root = join(dirname(fileURLToPath(import.meta.url)), "..", "..");

/** An environment variable naming a directory, or an Error saying which build writes it. */
function dirOf(name, build) {
  const dir = process.env[name];
  if (!dir) throw new Error(`${name}: the directory \`${build} DIR\` wrote (web/spine/test sets it)`);
  return dir;
}

/** The package's module (index.js of the built package). */
export async function spinePackage() {
  return import(pathToFileURL(join(dirOf("IKARUS_SPINE_DIR", "bash web/spine/build"), "index.js")).href);
}

let core = null;
/** The playground's small module, initialised (the stand-in poses with it). */
export async function coreModule() {
  if (!core) {
    const dir = dirOf("IKARUS_WEB_DIR", "bash web/build");
    core = await import(pathToFileURL(join(dir, "ikarus_core.js")).href);
    await core.default({ module_or_path: readFileSync(join(dir, "ikarus_core_bg.wasm")) });
  }
  return core;
}

/** A stand-in skeleton of examples/characters/NAME.json playing `animation`, looped: { skeleton, state }. */
export async function standIn(name, animation) {
  const json = readFileSync(join(root, "examples", "characters", `${name}.json`), "utf8");
  const made = await loadStandIn(json, { core: await coreModule() });
  made.state.setAnimation(0, animation, true);
  return made;
}

/** Spine's Physics.update (none, reset, update, pose): the game's own update of a frame. */
export const PHYSICS_UPDATE = 2;

/** The game's own update of one frame of `dt` seconds, as the runtime's examples do it. */
export function gameUpdate({ skeleton, state }, dt) {
  state.update(dt);
  state.apply(skeleton);
  skeleton.updateWorldTransform(PHYSICS_UPDATE);
}

/** The tip of `bone` (origin plus length along its x axis), world coordinates. */
export function tip(bone) {
  const l = bone.data.length;
  return [bone.worldX + bone.a * l, bone.worldY + bone.c * l];
}

/** Every bone's world numbers (a b c d worldX worldY), a copy. */
export function worlds(skeleton) {
  return skeleton.bones.map((b) => [b.a, b.b, b.c, b.d, b.worldX, b.worldY]);
}

/** The indices of `names` and of every bone below one of them. */
export function withDescendants(skeleton, names) {
  const out = new Set();
  skeleton.bones.forEach((b, i) => {
    for (let p = b; p; p = p.parent) if (names.includes(p.data.name)) out.add(i);
  });
  return out;
}
