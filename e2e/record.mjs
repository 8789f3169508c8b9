// The README's screen recording of the playground as an animation tool, docs/src/images/keys.gif: run by
// hand (not in CI), after `cargo build --release`, with ImageMagick's `convert` on the PATH:
//
//     cd e2e && node record.mjs            # writes ../docs/src/images/keys.gif (frames in a temporary folder)
//
// It drives the page in headless Chromium: the puppet, Key mode on, the walk keyed by dragging
// both feet and both hands at four key times (e2e/rigpage.mjs's WALK, the test's); the keyed
// motion played with onion skins on; the left knee flipped with its bend handle (limits off);
// a zoom about the flipped knee with the wheel. Each stage is PNG frames (800 × 720), assembled with
// `convert -delay 8 -loop 0 … -layers Optimize`, scaled to 800 px wide. Look at the result
// before committing it.
import { execFileSync } from "node:child_process";
import { mkdtempSync, rmSync, statSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { openPage, ready, withBrowser } from "./browser.mjs";
import { flipBend, keyWalk, keysSettled, seek } from "./rigpage.mjs";

const out = join(import.meta.dirname, "..", "docs", "src", "images", "keys.gif");
const dir = mkdtempSync(join(tmpdir(), "ikarus-keys-"));
let n = 0;

await withBrowser(async ({ url, browser }) => {
  const { page } = await openPage(browser, { width: 800, height: 720 });
  const shot = () => page.screenshot({ path: join(dir, `${String(n++).padStart(4, "0")}.png`) });
  await page.goto(url);
  await ready(page);
  await page.selectOption("#body-kind", "rig:puppet");
  await page.check("#onion");
  await page.click("#panel-toggle");
  await page.click("#key-mode");
  await shot();

  // Keying: every other pointer move of each drag a frame, and one once the motion is back.
  let move = 0;
  await keyWalk(page, shot, async () => (move++ % 8 === 4 ? shot() : undefined));

  // Played with onion skins: every other frame of the keyed motion (37 at 30 fps).
  for (let f = 0; f <= 36; f += 2) {
    await seek(page, f / 30);
    await shot();
  }

  // The left knee flipped at 0.8 s (limits off: with them the puppet's knees bend one way).
  await page.evaluate(() => document.getElementById("limits").click());
  await keysSettled(page);
  await seek(page, 0.8);
  for (let k = 0; k < 3; k++) await shot();
  await flipBend(page, "left_shin", shot);
  for (let k = 0; k < 4; k++) await shot();

  // Zoomed about the knee, a notch at a time, then the flipped motion played there.
  const knee = await page.evaluate(() => {
    const h = window.ikarus.keys.handles().find((x) => x.bone === "left_shin");
    const r = document.getElementById("plot").getBoundingClientRect();
    return [r.left + h.at[0], r.top + h.at[1]];
  });
  await page.mouse.move(...knee);
  for (let k = 0; k < 8; k++) {
    await page.mouse.wheel(0, -100);
    await shot();
  }
  for (let f = 24; f <= 36; f += 2) {
    await seek(page, f / 30);
    await shot();
  }
});

execFileSync("convert", ["-delay", "8", "-loop", "0", join(dir, "*.png"), "-resize", "800x", "-layers", "Optimize", out]);
console.log(`${out}: ${n} frames, ${(statSync(out).size / 1e6).toFixed(2)} MB`);
rmSync(dir, { recursive: true });
