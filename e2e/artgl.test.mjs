// The art's WebGL drawing (artgl.js) in headless Chromium, against values worked out by hand from
// its rules: a slot covering the whole canvas samples one texel of a 2 × 1 page (uvs on the
// texel's centre), and the drawing buffer is read back premultiplied (gl.readPixels):
//   tint       out.rgb = a·t.rgb·L, out.a = a·t.a
//   dark       out.rgb = a·(t.rgb·L + (t.a − t.rgb)·D)
//   blends     normal ONE/ONE_MINUS_SRC_ALPHA, additive ONE/ONE, multiply
//              DST_COLOR/ONE_MINUS_SRC_ALPHA, screen ONE/ONE_MINUS_SRC_COLOR
//   straight pages premultiplied on upload; the view's transform (a slot off the canvas draws nothing)
// No server: the page's modules are read from the source tree. Within 2 levels of 255 (8 bits).
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { join } from "node:path";
import { launch } from "./browser.mjs";

const assets = join(import.meta.dirname, "..", "crates", "ikarus-cli", "src", "serve", "assets");

/**
 * Draws, in a fresh 8 × 8 canvas, each case's slots (on a page of the two straight texels
 * `texels`, the first slot's colour straight) and reads the centre pixel back, premultiplied.
 */
async function drawCases(page, cases) {
  return page.evaluate(async (cases) => {
    const { artRenderer } = await import("/artgl.js");
    const out = [];
    for (const { texels, slots, view } of cases) {
      const c = document.createElement("canvas");
      const r = artRenderer(c);
      const image = await createImageBitmap(new ImageData(new Uint8ClampedArray(texels.flat()), 2, 1), { premultiplyAlpha: "premultiply", colorSpaceConversion: "none" });
      const atlas = { pages: [{ file: "p.png", pma: false }], byFile: new Map([["p.png", 0]]), images: [image] };
      const art = {
        pages: ["p.png"],
        slots: slots.map(({ texel, color, dark = null, blend = "normal" }) => {
          const u = texel ? 0.75 : 0.25;
          return { page: 0, blend, color, dark, vertices: [-4, -4, 4, -4, 4, 4, -4, 4], uvs: [u, 0.5, u, 0.5, u, 0.5, u, 0.5], triangles: [0, 1, 2, 0, 2, 3] };
        }),
      };
      r.size(8, 8, 1);
      const drawn = r.draw(view || { cx: 4, cy: 4, scale: 1, w: 8, h: 8 }, [{ art, alpha: 1, atlas }]);
      const gl = c.getContext("webgl");
      const px = new Uint8Array(4);
      gl.readPixels(4, 4, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
      out.push({ drawn, px: Array.from(px) });
    }
    return out;
  }, cases);
}

const near = (got, want, what) => assert.ok(got.every((v, i) => Math.abs(v - want[i]) <= 2), `${what}: ${got} against ${want.map((v) => v.toFixed(1))}`);

test("artgl.js: tint, dark colour, premultiplied pages and the four blends, pixel by pixel", async () => {
  const browser = await launch();
  try {
    const page = await browser.newPage();
    await page.route("http://art.test/**", (route) => {
      const name = new URL(route.request().url()).pathname.slice(1);
      if (!name) return route.fulfill({ body: "<!doctype html><title>art</title>", contentType: "text/html" });
      return route.fulfill({ body: readFileSync(join(assets, name)), contentType: "text/javascript" });
    });
    await page.goto("http://art.test/");
    const base = [200, 100, 50, 255];
    const [plain, tint, fade, half, dark, darkHalf, additive, multiply, screen, away] = await drawCases(page, [
      { texels: [base, base], slots: [{ texel: 0, color: [1, 1, 1, 1] }] },
      { texels: [base, base], slots: [{ texel: 0, color: [0.5, 1, 0.25, 1] }] },
      { texels: [base, base], slots: [{ texel: 0, color: [1, 1, 1, 0.5] }] },
      // A straight texel of alpha 102 (0.4): premultiplied on upload.
      { texels: [[250, 125, 50, 102], base], slots: [{ texel: 0, color: [1, 1, 1, 1] }] },
      // Black becomes D, white stays L.
      { texels: [[0, 0, 0, 255], base], slots: [{ texel: 0, color: [1, 0.5, 1, 1], dark: [0.2, 0.4, 0.6] }] },
      { texels: [[51, 102, 204, 255], base], slots: [{ texel: 0, color: [1, 1, 1, 0.5], dark: [1, 0, 0.5] }] },
      { texels: [[100, 0, 0, 255], [0, 100, 0, 255]], slots: [{ texel: 0, color: [1, 1, 1, 1] }, { texel: 1, color: [1, 1, 1, 1], blend: "additive" }] },
      { texels: [base, [128, 255, 0, 255]], slots: [{ texel: 0, color: [1, 1, 1, 1] }, { texel: 1, color: [1, 1, 1, 1], blend: "multiply" }] },
      { texels: [base, [128, 128, 128, 255]], slots: [{ texel: 0, color: [1, 1, 1, 1] }, { texel: 1, color: [1, 1, 1, 1], blend: "screen" }] },
      // The slot 100 units right of the canvas's centre at scale 1: off the 8-pixel canvas.
      { texels: [base, base], slots: [{ texel: 0, color: [1, 1, 1, 1] }], view: { cx: -100, cy: 4, scale: 1, w: 8, h: 8 } },
    ]);
    near(plain.px, base, "an opaque texel, white tint");
    assert.equal(plain.drawn, 1);
    near(tint.px, [100, 100, 12.5, 255], "tinted (0.5, 1, 0.25)");
    near(fade.px, [100, 50, 25, 127.5], "alpha 0.5, premultiplied");
    near(half.px, [250 * 0.4, 125 * 0.4, 50 * 0.4, 102], "a straight texel of alpha 0.4, premultiplied on upload");
    near(dark.px, [0.2 * 255, 0.4 * 255, 0.6 * 255, 255], "black becomes the dark colour");
    // a = 0.5, t = (0.2, 0.4, 0.8), L = 1, D = (1, 0, 0.5): 0.5·(t + (1 − t)·D) = 0.5·(1, 0.4, 0.9).
    near(darkHalf.px, [0.5 * 255, 0.2 * 255, 0.45 * 255, 127.5], "dark colour with alpha 0.5");
    near(additive.px, [100, 100, 0, 255], "additive adds");
    near(multiply.px, [(200 * 128) / 255, 100, 0, 255], "multiply multiplies");
    near(screen.px, [128 + 200 * (127 / 255), 128 + 100 * (127 / 255), 128 + 50 * (127 / 255), 255], "screen lightens");
    near(away.px, [0, 0, 0, 0], "a slot off the canvas");
  } finally {
    await browser.close();
  }
});
