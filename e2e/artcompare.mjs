// Comparing two pictures of a character's art that were fitted differently (the page's canvas
// and the CLI's `ikarus pose --atlas … --art-only` PNG), as crates/ikarus-edge/tests/art_reference.rs
// compares the art with Spine's pictures: the alpha masks (alpha > 0.5) each cropped to its own
// bounds, the second crop scaled to the first's size (nearest pixel centre), then
//  - overlap: intersection over union of the masks (at least 0.95 to agree);
//  - colour: over the pixels opaque in both, the mean |Δ| over R, G and B (straight, 0..1; under
//    0.06 to agree).
// Pictures are {width, height, data} with `data` straight RGBA bytes (ImageData's layout).

/** Bounds [left, top, right, bottom] (inclusive) of the pixels with alpha > 0.5, or null for none. */
export function maskBounds({ width, height, data }) {
  let [l, t, r, b] = [width, height, -1, -1];
  for (let y = 0; y < height; y++) {
    for (let x = 0; x < width; x++) {
      if (data[4 * (y * width + x) + 3] > 127.5) {
        l = Math.min(l, x);
        t = Math.min(t, y);
        r = Math.max(r, x);
        b = Math.max(b, y);
      }
    }
  }
  return r < 0 ? null : [l, t, r, b];
}

/**
 * {overlap, colour, size} of pictures `a` and `b` (see above; `size` the compared crop's
 * [width, height], `a`'s); null when either has no opaque pixel.
 */
export function compareArt(a, b) {
  const ba = maskBounds(a);
  const bb = maskBounds(b);
  if (!ba || !bb) return null;
  const w = ba[2] - ba[0] + 1;
  const h = ba[3] - ba[1] + 1;
  const wb = bb[2] - bb[0] + 1;
  const hb = bb[3] - bb[1] + 1;
  let both = 0;
  let either = 0;
  let diff = 0;
  for (let y = 0; y < h; y++) {
    const yb = bb[1] + Math.min(hb - 1, Math.floor(((y + 0.5) * hb) / h));
    for (let x = 0; x < w; x++) {
      const xb = bb[0] + Math.min(wb - 1, Math.floor(((x + 0.5) * wb) / w));
      const i = 4 * ((ba[1] + y) * a.width + ba[0] + x);
      const j = 4 * (yb * b.width + xb);
      const inA = a.data[i + 3] > 127.5;
      const inB = b.data[j + 3] > 127.5;
      if (inA || inB) either++;
      if (inA && inB) {
        both++;
        diff += (Math.abs(a.data[i] - b.data[j]) + Math.abs(a.data[i + 1] - b.data[j + 1]) + Math.abs(a.data[i + 2] - b.data[j + 2])) / (3 * 255);
      }
    }
  }
  return { overlap: both / either, colour: both ? diff / both : 1, size: [w, h] };
}
