// Unit tests of the character's art on the page: sorting the files loaded together (artfiles.js),
// the notices of what is left out, and the shader's world → clip transform and blend table
// (artgl.js); no browser, no server. Run by .ci/run:
//   node --test e2e/art.unit.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import { artNotice, baseName, groupFiles, matchPages, pageImage } from "../crates/ikarus-cli/src/serve/assets/artfiles.js";
import { BLENDS, clipTransform } from "../crates/ikarus-cli/src/serve/assets/artgl.js";
import { toCanvas } from "../crates/ikarus-cli/src/serve/assets/view.js";
import { compareArt, maskBounds } from "./artcompare.mjs";

const f = (name) => ({ name });

test("files loaded together sort into skeleton, atlas and images in any order", () => {
  const g = groupFiles([f("spineboy.png"), f("spineboy.atlas"), f("spine-spineboy-pro.json")]);
  assert.equal(g.skeleton.name, "spine-spineboy-pro.json");
  assert.equal(g.atlas.name, "spineboy.atlas");
  assert.deepEqual(g.images.map((x) => x.name), ["spineboy.png"]);
  assert.deepEqual(g.others, []);
  const skel = groupFiles([f("A.PNG"), f("raptor.skel"), f("b.png"), f("raptor.atlas"), f("other.json"), f("second.atlas")]);
  assert.equal(skel.skeleton.name, "raptor.skel");
  assert.equal(skel.atlas.name, "raptor.atlas");
  assert.deepEqual(skel.images.map((x) => x.name), ["A.PNG", "b.png"]);
  assert.deepEqual(skel.others.map((x) => x.name), ["other.json", "second.atlas"]);
  assert.deepEqual(groupFiles([]), { skeleton: null, atlas: null, images: [], others: [] });
});

test("an atlas page is matched by file name, exactly first, then ignoring case, a folder left out", () => {
  assert.equal(baseName("images/spineboy.png"), "spineboy.png");
  assert.equal(baseName("a\\b\\c.png"), "c.png");
  const exact = f("Page.png");
  const lower = f("page.png");
  assert.equal(pageImage("page.png", [exact, lower]), lower);
  assert.equal(pageImage("Page.png", [lower, exact]), exact);
  assert.equal(pageImage("PAGE.PNG", [exact]), exact);
  assert.equal(pageImage("dir/page.png", [lower]), lower);
  assert.equal(pageImage("page2.png", [exact, lower]), null);
  const m = matchPages([{ file: "a.png" }, { file: "b.png" }], [f("b.png"), f("c.png")]);
  assert.deepEqual(m.matched.map((x) => x && x.name), [null, "b.png"]);
  assert.deepEqual(m.missing, ["a.png"]);
  assert.deepEqual(m.unused, ["c.png"]);
});

test("the notice names what is left out, one line, and is null when everything is used", () => {
  const all = groupFiles([f("s.json"), f("s.atlas"), f("s.png")]);
  assert.equal(artNotice(all, matchPages([{ file: "s.png" }], all.images)), null);
  const missing = artNotice(all, matchPages([{ file: "s.png" }, { file: "s2.png" }], all.images));
  assert.match(missing, /^atlas s\.atlas: page image s2\.png not given/);
  const lone = artNotice(groupFiles([f("s.atlas"), f("s.png")]), null);
  assert.match(lone, /^atlas s\.atlas: no skeleton given with it/);
  assert.match(artNotice(groupFiles([f("s.json"), f("s.png")]), null), /^s\.png: no atlas given with it/);
  for (const n of [missing, lone]) assert.ok(!n.includes("\n"));
});

test("the shader's transform puts world points where the 2D canvas draws them", () => {
  const view = { cx: 412.5, cy: 300.25, scale: 1.75, w: 800, h: 600 };
  const [sx, ox, sy, oy] = clipTransform(view);
  for (const [x, y] of [[0, 0], [100, -40], [-230.5, 170]]) {
    const [px, py] = toCanvas(view, x, y);
    // clip space: x from -1 (left) to 1 (right), y from -1 (bottom) to 1 (top).
    assert.ok(Math.abs(x * sx + ox - ((2 * px) / view.w - 1)) < 1e-12);
    assert.ok(Math.abs(y * sy + oy - (1 - (2 * py) / view.h)) < 1e-12);
  }
});

test("the blend modes' factors are the premultiplied ones", () => {
  assert.deepEqual(BLENDS.normal, ["ONE", "ONE_MINUS_SRC_ALPHA"]);
  assert.deepEqual(BLENDS.additive, ["ONE", "ONE"]);
  assert.deepEqual(BLENDS.multiply, ["DST_COLOR", "ONE_MINUS_SRC_ALPHA"]);
  assert.deepEqual(BLENDS.screen, ["ONE", "ONE_MINUS_SRC_COLOR"]);
});

test("two pictures of the same art fitted differently agree; a moved or recoloured part does not", () => {
  // A 40 × 20 two-colour bar at (5, 7) in a 60 × 40 picture, and twice as large elsewhere in a 120 × 80 one.
  const picture = (width, height, [x0, y0], k, colourOf) => {
    const data = new Uint8ClampedArray(width * height * 4);
    for (let y = 0; y < 20 * k; y++) {
      for (let x = 0; x < 40 * k; x++) {
        const i = 4 * ((y0 + y) * width + x0 + x);
        data.set([...colourOf(Math.floor(x / k), Math.floor(y / k)), 255], i);
      }
    }
    return { width, height, data };
  };
  const colours = (x) => (x < 20 ? [200, 0, 0] : [0, 0, 200]);
  const a = picture(60, 40, [5, 7], 1, colours);
  const b = picture(120, 80, [30, 11], 2, colours);
  assert.deepEqual(maskBounds(a), [5, 7, 44, 26]);
  assert.deepEqual(maskBounds(b), [30, 11, 109, 50]);
  const same = compareArt(a, b);
  assert.deepEqual(same, { overlap: 1, colour: 0, size: [40, 20] });
  // The halves' colours swapped: every pixel differs by 400/3 of 255.
  const swapped = compareArt(a, picture(120, 80, [30, 11], 2, (x) => colours(39 - x)));
  assert.ok(Math.abs(swapped.colour - 400 / 3 / 255) < 1e-12, String(swapped.colour));
  // The top left quarter of the bar gone from b (its bounds the same): three quarters overlap.
  const cut = picture(120, 80, [30, 11], 2, colours);
  for (let y = 11; y < 31; y++) for (let x = 30; x < 70; x++) cut.data[4 * (y * 120 + x) + 3] = 0;
  assert.deepEqual(compareArt(a, cut), { overlap: 0.75, colour: 0, size: [40, 20] });
  assert.equal(compareArt(a, { width: 2, height: 2, data: new Uint8ClampedArray(16) }), null);
});
