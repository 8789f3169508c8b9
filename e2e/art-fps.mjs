// Frames a second of a character's art on the page, in headless Chromium: spineboy loaded with
// its atlas and page, `walk` played in a loop for SECONDS (5 by default), printing the
// requestAnimationFrame callbacks a second, the draws with art a second and the pose answers
// (/api/pose with the atlas, each with its art) a second. A measurement, not a test: it asserts
// nothing about speed.
//   node e2e/art-fps.mjs                 under `ikarus serve` (target/release/ikarus, IKARUS_BIN)
//   node e2e/art-fps.mjs http://HOST/    a page already served (the static WebAssembly build:
//                                        `bash web/build DIR`, `python3 -m http.server -d DIR`)
import { launch, openPage, ready, startServer } from "./browser.mjs";
import { loadSpineboyArt } from "./artpage.mjs";

const seconds = Number(process.env.SECONDS_PLAYED || 5);
const given = process.argv[2];
const server = given ? null : await startServer();
const url = given || server.url;
const browser = await launch();
try {
  const { page, errors } = await openPage(browser);
  await page.goto(url);
  await ready(page);
  const backend = await page.textContent("#backend");
  await loadSpineboyArt(page);
  await page.selectOption("#character-animation", "walk");
  await page.waitForFunction(() => window.ikarus.characters.settled(), null, { timeout: 30000 });
  await page.check("#loop");
  await page.click("#play");
  // A second to start, then the count.
  await page.waitForTimeout(1000);
  const m = await page.evaluate(
    (s) =>
      new Promise((resolve) => {
        const c = window.ikarus.state.character;
        const start = { t: performance.now(), poses: c.poses, draws: window.ikarus.art.draws() };
        let frames = 0;
        const tick = () => {
          frames++;
          const t = performance.now();
          if (t - start.t < s * 1000) return requestAnimationFrame(tick);
          const span = (t - start.t) / 1000;
          resolve({ span, frames: frames / span, draws: (window.ikarus.art.draws() - start.draws) / span, poses: (c.poses - start.poses) / span, slots: window.ikarus.art.slots() });
        };
        requestAnimationFrame(tick);
      }),
    seconds,
  );
  console.log(`${backend.trim()} · spineboy walk with its art, ${m.span.toFixed(2)} s: ${m.frames.toFixed(1)} animation frames/s, ${m.draws.toFixed(1)} draws with art/s, ${m.poses.toFixed(1)} pose answers/s, ${m.slots} slots drawn`);
  if (errors.length) console.log(`page errors: ${errors.join(" | ")}`);
} finally {
  await browser.close();
  if (server) server.child.kill("SIGINT");
}
