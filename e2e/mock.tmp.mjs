import { launch, openPage, ready, startServer } from "./browser.mjs";
import { loadSpineboyArt } from "./artpage.mjs";
const server = await startServer();
const browser = await launch();
const { page, errors } = await openPage(browser);
await page.route("**/api/atlas/parse", (r) => r.fulfill({ contentType: "application/json", body: JSON.stringify({ id: "a12ab", pages: [{ file: "spineboy.png", width: 1024, height: 256, pma: false, image: false }], regions: 52 }) }));
await page.route("**/api/pose", async (r) => {
  const body = JSON.parse(r.request().postData());
  const atlas = body.atlas; delete body.atlas;
  const res = await r.fetch({ postData: JSON.stringify(body) });
  const a = await res.json();
  if (atlas && a.bones) {
    a.art = { pages: ["spineboy.png"], slots: a.bones.filter((b) => Math.hypot(b.tip[0]-b.x, b.tip[1]-b.y) > 1).map((b) => {
      const [dx, dy] = [b.tip[0]-b.x, b.tip[1]-b.y]; const l = Math.hypot(dx, dy); const [nx, ny] = [-dy/l*8, dx/l*8];
      return { slot: b.name, attachment: b.name, page: 0, blend: "normal", color: [1,1,1,0.9], dark: null,
        vertices: [b.x+nx, b.y+ny, b.tip[0]+nx, b.tip[1]+ny, b.tip[0]-nx, b.tip[1]-ny, b.x-nx, b.y-ny], uvs: [0,0,0.3,0,0.3,1,0,1], triangles: [0,1,2,0,2,3] }; }) };
  }
  r.fulfill({ status: res.status(), contentType: "application/json", body: JSON.stringify(a) });
});
await page.goto(server.url);
await ready(page);
await loadSpineboyArt(page);
console.log("slots", await page.evaluate(() => window.ikarus.art.slots()));
await page.selectOption("#character-animation", "walk");
await page.waitForTimeout(1500);
await page.click("#play"); await page.waitForTimeout(1500); await page.click("#play");
await page.waitForTimeout(500);
await page.click("#key-mode");
await page.check("#onion");
await page.waitForTimeout(1500);
console.log("slots", await page.evaluate(() => window.ikarus.art.slots()), await page.textContent("#stats"), await page.textContent("#error"));
await page.locator("#canvas-box").screenshot({ path: "/tmp/Pgl/mock.png" });
console.log(errors);
await browser.close(); server.child.kill("SIGINT");
