// The motion's GIF is the screen's picture (issue 24, point 9): the page asks /api/render for
// the canvas's size and the layers it shows (the reachable area, the traces, the ghosts), and
// the GIF it gets is that size, with the area's colour and the tip's trace in it. Run by e2e/run.
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync, writeFileSync } from "node:fs";
import { join } from "node:path";
import { artifacts, ended, onPlayground } from "./browser.mjs";


/** The GIF button's request and the downloaded bytes. */
async function gif(page) {
  const [request, d] = await Promise.all([
    page.waitForRequest((r) => r.url().endsWith("/api/render")),
    page.waitForEvent("download"),
    page.click("#dl-gif"),
  ]);
  return { req: JSON.parse(request.postData()), bytes: readFileSync(await d.path()) };
}

/** The GIF's first frame as the browser draws it: its size and how many pixels are near `hex`. */
const firstFrame = (page, bytes, hexes) =>
  page.evaluate(
    async ({ b64, hexes }) => {
      const img = new Image();
      img.src = `data:image/gif;base64,${b64}`;
      await img.decode();
      const c = document.createElement("canvas");
      [c.width, c.height] = [img.naturalWidth, img.naturalHeight];
      const ctx = c.getContext("2d");
      ctx.drawImage(img, 0, 0);
      const d = ctx.getImageData(0, 0, c.width, c.height).data;
      const counts = hexes.map((hex) => {
        const [r, g, b] = [1, 3, 5].map((i) => parseInt(hex.slice(i, i + 2), 16));
        let n = 0;
        for (let i = 0; i < d.length; i += 4) if (Math.abs(d[i] - r) <= 2 && Math.abs(d[i + 1] - g) <= 2 && Math.abs(d[i + 2] - b) <= 2) n++;
        return n;
      });
      return { width: c.width, height: c.height, counts };
    },
    { b64: bytes.toString("base64"), hexes },
  );

test("the GIF is the screen's picture: its size, the shaded area, the traces and ghosts as shown", () =>
  onPlayground(async (page, { url }) => {
    const meta = await (await fetch(`${url}/api/meta`)).json();
    await page.check("#limits");
    await page.check("#show-workspace");
    await page.waitForFunction(() => window.ikarus.state.region || window.ikarus.state.areaOutline, null, { timeout: 15000 });
    await page.evaluate(() => window.ikarus.animateTo(2, 3));
    await ended(page);
    const canvas = await page.evaluate(() => {
      const c = document.getElementById("plot");
      return [c.clientWidth, c.clientHeight];
    });

    const shown = await gif(page);
    // The request carries the screen: its size (not a square), the area, the traces, the ghosts.
    assert.deepEqual([shown.req.width, shown.req.height], canvas);
    assert.notEqual(canvas[0], canvas[1], `the canvas is ${canvas}`);
    assert.deepEqual([shown.req.workspace, shown.req.traces, shown.req.ghosts], [true, true, true]);
    assert.equal(shown.req.options.limits, true);
    // The GIF is that size, and its first frame has the area's colour.
    const frame = await firstFrame(page, shown.bytes, [meta.palette.workspace]);
    assert.deepEqual([frame.width, frame.height], canvas);
    assert.ok(frame.counts[0] > 10000, `${frame.counts[0]} pixels of the area's colour`);
    writeFileSync(join(artifacts, "motion.gif"), shown.bytes);
    await page.screenshot({ path: join(artifacts, "motion-screen.png") });

    // Hidden on the screen, left out of the GIF.
    await page.uncheck("#show-workspace");
    await page.uncheck("#show-traces");
    await page.uncheck("#show-ghosts");
    const bare = await gif(page);
    assert.deepEqual([bare.req.workspace, bare.req.traces, bare.req.ghosts], [false, false, false]);
    const plain = await firstFrame(page, bare.bytes, [meta.palette.workspace]);
    // (a few antialiased edge pixels may round to the area's colour: far fewer than the area paints)
    assert.ok(plain.counts[0] * 100 < frame.counts[0], `no area: ${plain.counts[0]} vs ${frame.counts[0]} pixels`);
  }));
