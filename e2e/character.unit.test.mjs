// The pure parts of the page's characters (character.js), in node: the handles, the requests, the
// view, the bone shapes and what the pointer is on.
import { test } from "node:test";
import assert from "node:assert/strict";
import {
  CHARACTER_VIEW_ROOM,
  boneAt,
  boneShape,
  characterSummary,
  clipSeconds,
  exportName,
  exportRequest,
  fitCharacterView,
  handleAt,
  ikTargets,
  poseRequest,
  characterRef,
  posedBox,
  solverLine,
  surveyTimes,
  unionBox,
  unsupportedLines,
} from "../crates/ikarus-cli/src/serve/assets/character.js";
import { toCanvas } from "../crates/ikarus-cli/src/serve/assets/view.js";

const character = {
  format: "spine",
  bones: [{ name: "root" }, { name: "thigh" }, { name: "shin" }, { name: "foot" }, { name: "target" }],
  ik: [
    { name: "leg", bones: ["thigh", "shin"], target: "target" },
    { name: "foot", bones: ["foot"], target: "target" },
    { name: "other", bones: ["root"], target: "foot" },
  ],
  clips: [
    { name: "walk", duration: 1.25 },
    { name: "still", duration: 0 },
  ],
  unsupported: [{ kind: "clipping attachment", name: "clip (skin default, slot hand)" }],
};

test("the handles are the constraints' targets, each once, in file order", () => {
  assert.deepEqual(ikTargets(character), ["target", "foot"]);
  assert.deepEqual(ikTargets({ bones: [] }), []);
});

test("a clip's seconds; none for an unknown name or no clip", () => {
  assert.equal(clipSeconds(character, "walk"), 1.25);
  assert.equal(clipSeconds(character, "nope"), 0);
  assert.equal(clipSeconds(character, ""), 0);
});

test("the pose request: the clip and its time only with a clip, targets in order, ik only for ikarus", () => {
  const targets = new Map([
    ["target", { x: 1, y: 2 }],
    ["foot", { x: -3, y: 4.5 }],
  ]);
  assert.deepEqual(poseRequest({ text: "T", animation: "", time: 0.7, targets: new Map(), ik: "runtime" }), { rig: "T", targets: [] });
  assert.deepEqual(poseRequest({ text: "T", animation: "walk", time: 0.7, targets, ik: "ikarus" }), {
    rig: "T",
    animation: "walk",
    time: 0.7,
    targets: [
      { bone: "target", x: 1, y: 2 },
      { bone: "foot", x: -3, y: 4.5 },
    ],
    ik: "ikarus",
  });
});

test("a character the backend read is named by its id, not its text, in every request", () => {
  const c = { text: "T".repeat(300_000), character: { id: "c0123456789abcdef0000000a" }, animation: "walk", time: 0.4, targets: new Map([["foot", { x: 1, y: 2 }]]), ik: "runtime" };
  const pose = poseRequest(c);
  assert.deepEqual(pose, { character: "c0123456789abcdef0000000a", animation: "walk", time: 0.4, targets: [{ bone: "foot", x: 1, y: 2 }] });
  assert.ok(JSON.stringify(pose).length < 1024, "a pose of playback is a few bytes, not the file");
  assert.equal(exportRequest(c).character, "c0123456789abcdef0000000a");
  assert.equal(exportRequest(c).rig, undefined);
  assert.deepEqual(characterRef({ text: "T" }), { rig: "T" }, "without an id (not read yet), the text");
});

test("the export request is helper A's contract, and its file name", () => {
  const targets = new Map([["target", { x: 1, y: 2 }]]);
  assert.deepEqual(exportRequest({ text: "T", targets }), {
    rig: "T",
    targets: [{ bone: "target", x: 1, y: 2 }],
    duration: 1.0,
    fps: 30,
    ease: "sine",
    format: "spine",
    animation_name: "ikarus",
  });
  assert.equal(exportName("spineboy.json"), "spineboy-ikarus.json");
  assert.equal(exportName("Raptor.JSON"), "Raptor-ikarus.json");
  assert.equal(exportName(""), "character-ikarus.json");
});

test("the view fits the setup pose's box with room around it, centred, y up", () => {
  const bones = [
    { x: -100, y: 0, tip: [50, 0] },
    { x: 0, y: 0, tip: [0, 600] },
  ];
  const box = posedBox(bones);
  assert.deepEqual(box, { x0: -100, x1: 50, y0: 0, y1: 600 });
  const view = fitCharacterView(box, 800, 700);
  // The taller side fills the height less the room, 12 % of 600 on each side.
  const room = 600 * CHARACTER_VIEW_ROOM;
  assert.ok(Math.abs(view.scale - 700 / (600 + 2 * room)) < 1e-12);
  const [cx, cy] = toCanvas(view, -25, 300);
  assert.ok(Math.abs(cx - 400) < 1e-9 && Math.abs(cy - 350) < 1e-9);
  // y up: the top of the box is higher on the canvas (smaller y) than its bottom.
  assert.ok(toCanvas(view, 0, 600)[1] < toCanvas(view, 0, 0)[1]);
  for (const [x, y] of [
    [-100, 0],
    [50, 600],
  ]) {
    const [px, py] = toCanvas(view, x, y);
    assert.ok(px >= 0 && px <= 800 && py >= 0 && py <= 700);
  }
});

test("a clip's survey: its ends and evenly between; boxes joined", () => {
  assert.deepEqual(surveyTimes(2, 4), [0, 0.5, 1, 1.5, 2]);
  assert.equal(surveyTimes(1.25).length, 9);
  const a = { x0: 0, x1: 1, y0: 0, y1: 1 };
  assert.deepEqual(unionBox(a, { x0: -1, x1: 0.5, y0: 0.5, y1: 3 }), { x0: -1, x1: 1, y0: 0, y1: 3 });
  assert.deepEqual(unionBox(null, a), a);
  assert.deepEqual(unionBox(a, undefined), a);
});

test("a bone is a kite from its origin to its tip, widest a fifth along; no length is a circle", () => {
  const s = boneShape([10, 10], [110, 10], 50);
  assert.equal(s.kind, "kite");
  assert.deepEqual(s.points[0], [10, 10]);
  assert.deepEqual(s.points[2], [110, 10]);
  // The two sides: 20 px along, 7 px (the most) either side of the axis.
  assert.deepEqual(
    [s.points[1], s.points[3]].map(([x, y]) => [Math.round(x * 1e9) / 1e9, Math.round(y * 1e9) / 1e9]).sort((a, b) => a[1] - b[1]),
    [
      [30, 3],
      [30, 17],
    ],
  );
  // A short bone is slimmer (a tenth of its length, at least 1.5 px).
  const short = boneShape([0, 0], [0, 20], 5);
  assert.ok(Math.abs(Math.abs(short.points[1][0]) - 2) < 1e-9);
  assert.deepEqual(boneShape([3, 4], [3, 4], 0), { kind: "circle", at: [3, 4], r: 3.5 });
  // A bone of length in the file but under a pixel on the screen: a circle too.
  assert.equal(boneShape([3, 4], [3.2, 4.2], 0.01).kind, "circle");
});

test("the bone under the pointer: the nearest segment within the radius, the later one on a tie", () => {
  const bones = [
    { o: [0, 0], t: [100, 0] },
    { o: [100, 0], t: [100, 100] },
    { o: [50, 50], t: [50, 50] },
  ];
  assert.equal(boneAt(bones, 50, 3), 0);
  assert.equal(boneAt(bones, 103, 60), 1);
  assert.equal(boneAt(bones, 52, 52), 2);
  assert.equal(boneAt(bones, 50, 20), -1);
  // The corner is on both: the later bone, drawn on top.
  assert.equal(boneAt(bones, 100, 0), 1);
});

test("the handle under the pointer: the nearest within the radius", () => {
  const handles = new Map([
    ["a", [0, 0]],
    ["b", [10, 0]],
  ]);
  assert.equal(handleAt(handles, 4, 0), "a");
  assert.equal(handleAt(handles, 6, 0), "b");
  assert.equal(handleAt(handles, 30, 0), null);
});

test("the solver's line: Spine's rules, or ikarus's status and the constraints it missed", () => {
  assert.equal(solverLine(null), "Spine rules");
  const ik = {
    solver: "ikarus",
    status: "unreachable",
    constraints: [
      { name: "a", active: true, error: 0 },
      { name: "b", active: true, error: 3.4567 },
      { name: "c", active: false, error: 9 },
      { name: "d", active: true, error: 5e-4 },
    ],
  };
  assert.equal(solverLine(ik), "ikarus solver unreachable · b 3.5");
  assert.equal(solverLine({ status: "reached", constraints: [] }), "ikarus solver reached");
});

test("the chip's line and the lines of what ikarus leaves out", () => {
  assert.equal(characterSummary("boy.json", character), "Spine character boy.json · 5 bones · 3 IK constraints");
  assert.equal(characterSummary("m", { format: "dragonbones", bones: [{}], ik: [{}] }), "DragonBones character m · 1 bone · 1 IK constraint");
  const kinds = ["ik", "transform", "transform", "physics"].map((kind) => ({ kind }));
  assert.equal(characterSummary("c", { bones: [{}, {}], constraints: kinds }), "Spine character c · 2 bones · 1 IK, 2 transform, 1 physics constraints");
  assert.equal(characterSummary("c", { bones: [{}], constraints: [] }), "Spine character c · 1 bone · no constraints");
  assert.deepEqual(unsupportedLines(character), ["clipping attachment clip (skin default, slot hand)"]);
  assert.deepEqual(unsupportedLines({}), []);
});

test("the skin and physics choices travel with a pose only when they are not the defaults", () => {
  const base = { text: "{}", character: { clips: [] }, animation: "", time: 0, targets: new Map(), ik: "runtime" };
  assert.equal("skin" in poseRequest(base), false);
  assert.equal("physics" in poseRequest(base), false);
  assert.equal(poseRequest({ ...base, skin: "goblin" }).skin, "goblin");
  assert.equal(poseRequest({ ...base, physics: false }).physics, false);
  assert.equal("physics" in poseRequest({ ...base, physics: true }), false);
});
