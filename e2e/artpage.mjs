// Helpers of the browser scripts that show a character's art on the page (art.test.mjs,
// art-fps.mjs): loading spineboy with its atlas and page through the file input, reading the
// art's canvas, and the CLI's picture of the same pose.
import { execFileSync } from "node:child_process";
import { readFileSync } from "node:fs";
import { join } from "node:path";
import { binary } from "./browser.mjs";

export const examples = join(import.meta.dirname, "..", "examples", "characters");

/** Spineboy's skeleton, atlas and page, as the file input takes them (in no particular order). */
export const spineboyFiles = () =>
  [
    ["spineboy.png", "image/png"],
    ["spine-spineboy-pro.json", "application/json"],
    ["spineboy.atlas", "text/plain"],
  ].map(([name, mimeType]) => ({ name, mimeType, buffer: readFileSync(join(examples, name)) }));

/** Loads spineboy with its art through *Load rig or character…* and waits for the art drawn. */
export async function loadSpineboyArt(page) {
  await page.setInputFiles("#rig-file", spineboyFiles());
  await page.waitForFunction(() => window.ikarus.state.character && window.ikarus.state.character.art && window.ikarus.art.slots() > 0, null, { timeout: 30000 });
}

/**
 * The art canvas's pixels: {width, height, data} with `data` straight RGBA bytes (the canvas
 * drawn into a 2D canvas and read back).
 */
export async function artPixels(page) {
  const p = await page.evaluate(() => {
    const c = document.getElementById("art");
    const k = document.createElement("canvas");
    [k.width, k.height] = [c.width, c.height];
    const ctx = k.getContext("2d", { willReadFrequently: true });
    ctx.drawImage(c, 0, 0);
    return pixelsOf(ctx, k);
    function pixelsOf(ctx, k) {
      const d = ctx.getImageData(0, 0, k.width, k.height);
      const u = new Uint8Array(d.data.buffer);
      let s = "";
      for (let i = 0; i < u.length; i += 0x8000) s += String.fromCharCode(...u.subarray(i, i + 0x8000));
      return { width: d.width, height: d.height, data: btoa(s) };
    }
  });
  return { width: p.width, height: p.height, data: new Uint8Array(Buffer.from(p.data, "base64")) };
}

/** A PNG's pixels decoded by the page (straight RGBA bytes), as artPixels gives them. */
export async function pngPixels(page, png) {
  const p = await page.evaluate(async (b64) => {
    const image = new Image();
    image.src = `data:image/png;base64,${b64}`;
    await image.decode();
    const k = document.createElement("canvas");
    [k.width, k.height] = [image.naturalWidth, image.naturalHeight];
    const ctx = k.getContext("2d", { willReadFrequently: true });
    ctx.drawImage(image, 0, 0);
    const d = ctx.getImageData(0, 0, k.width, k.height);
    const u = new Uint8Array(d.data.buffer);
    let s = "";
    for (let i = 0; i < u.length; i += 0x8000) s += String.fromCharCode(...u.subarray(i, i + 0x8000));
    return { width: d.width, height: d.height, data: btoa(s) };
  }, png.toString("base64"));
  return { width: p.width, height: p.height, data: new Uint8Array(Buffer.from(p.data, "base64")) };
}

/**
 * The arguments of `ikarus pose` drawing the art alone of the page's pose request `req`
 * (/api/pose's body: animation, time, targets, rotations), `width` × `height`, into `out`.
 */
export function cliArtArgs(req, width, height, out) {
  const args = ["pose", "--rig", join(examples, "spine-spineboy-pro.json"), "--atlas", join(examples, "spineboy.atlas")];
  if (req.animation) args.push("--animation", req.animation, "--time", String(req.time));
  for (const t of req.targets || []) args.push("--target", `${t.bone}=${t.x},${t.y}`);
  return [...args, "--art-only", "--width", String(width), "--height", String(height), "--out", out];
}

/** Runs `ikarus pose` with `args` (cliArtArgs's) and resolves with the PNG's bytes. */
export function cliArt(args) {
  execFileSync(binary, args, { stdio: ["ignore", "ignore", "pipe"] });
  return readFileSync(args[args.length - 1]);
}
