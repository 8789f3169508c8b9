// What ikarus-spine allocates per frame, by the file of the function that allocated it: V8's
// sampling heap profiler (every object, garbage included, sampled about once per 64 bytes) over
// 20000 frames of clear, goal (3 bones), pin, apply on the hand-made skeleton (toy.mjs; its own
// updateWorldTransform replaced by one doing nothing, so that only the add-on is measured), after
// 20000 frames of warm-up. Prints JSON: bytes per frame per file, whether the module grew its
// memory, and whether the module has applyFrame (apply's glue allocates, applyFrame's does not).
//   IKARUS_SPINE_DIR=DIR node web/spine/alloc.mjs     (attach.test.mjs runs it)
import { Session } from "node:inspector/promises";
import { join } from "node:path";
import { pathToFileURL } from "node:url";
import { toySkeleton } from "./toy.mjs";

const spine = await import(pathToFileURL(join(process.env.IKARUS_SPINE_DIR, "index.js")).href);
const s = toySkeleton();
const ik = await spine.attach(s);
s.updateWorldTransform = () => {};
const three = { bones: 3 }; // the caller's options, made once
const frame = (f) => {
  const t = f / 60;
  ik.clear();
  ik.goal("hand", 50 + 30 * Math.cos(t), 150 + 30 * Math.sin(t), three);
  ik.pin("foot");
  ik.apply();
};
const frames = 20000;
for (let f = 0; f < frames; f++) frame(f);
const memory = (await spine.load()).memory;
const bytes = memory.buffer.byteLength;
const session = new Session();
session.connect();
await session.post("HeapProfiler.startSampling", { samplingInterval: 64, includeObjectsCollectedByMajorGC: true, includeObjectsCollectedByMinorGC: true });
for (let f = frames; f < 2 * frames; f++) frame(f);
const { profile } = await session.post("HeapProfiler.stopSampling");
session.disconnect();
const by = {};
const walk = (node) => {
  const file = node.callFrame.url.split("/").pop() || "(native)";
  if (node.selfSize && (file === "index.js" || file === "ikarus_spine.js" || file === "alloc.mjs")) by[file] = (by[file] ?? 0) + node.selfSize / frames;
  node.children.forEach(walk);
};
walk(profile.head);
console.log(JSON.stringify({ frames, bytesPerFrame: by, moduleMemoryGrew: memory.buffer.byteLength - bytes, applyFrame: typeof ik.rig.applyFrame === "function" }));
