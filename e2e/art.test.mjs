// A character's art on the page (issue 40), in a real browser: spineboy's skeleton, atlas and
// page picked together through *Load rig or character…*; the art is drawn (opaque pixels where
// the torso is), and zoomed in it follows the view; `walk` plays with the art coming in each pose's answer; stopped at a time, the
// front foot's target dragged and keyed; onion skins of the keyed motion drawn as faded art;
// then, the bones overlay off, the art's canvas is compared with the CLI's picture of the same
// pose (`ikarus pose --atlas … --art-only`): alpha masks cropped to their bounds and scaled to one
// size, overlap ≥ 0.95 and mean colour difference < 6 % (artcompare.mjs). An atlas the backend
// let go (404) is sent again once. A lone atlas, and a page image not given, are one-line notices. Screenshots: target/e2e/art-*.png; with ART_DOCS=1 the README's two
// (docs/src/images/art-page.png, docs/src/images/art-keys.png) are written too.
// Run by e2e/run (which builds the binary and installs playwright-core).
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync, writeFileSync } from "node:fs";
import { join } from "node:path";
import { artifacts, onPlayground, openPage, ready, withBrowser } from "./browser.mjs";
import { characterSettled, dragTarget, targetAt } from "./charpage.mjs";
import { compareArt, maskBounds } from "./artcompare.mjs";
import { artPixels, cliArt, cliArtArgs, examples, loadSpineboyArt, pngPixels, spineboyFiles } from "./artpage.mjs";

const docs = join(import.meta.dirname, "..", "docs", "src", "images");

/** The pixel's alpha of the art's canvas at the world point (x, y). */
const alphaAt = (page, x, y) =>
  page.evaluate(([x, y]) => {
    const v = window.ikarus.state.view;
    const c = document.getElementById("art");
    const k = document.createElement("canvas");
    [k.width, k.height] = [1, 1];
    const ctx = k.getContext("2d");
    const s = c.width / v.w;
    ctx.drawImage(c, Math.round((v.cx + x * v.scale) * s), Math.round((v.cy - y * v.scale) * s), 1, 1, 0, 0, 1, 1);
    return ctx.getImageData(0, 0, 1, 1).data[3];
  }, [x, y]);

/** The art drawn for the pose shown, nothing in flight: the answer's art is the pose's. */
const artSettled = (page) =>
  page.waitForFunction(
    () => {
      const c = window.ikarus.state.character;
      return window.ikarus.characters.settled() && window.ikarus.keys.settled() && c.art && c.artOf === c.posed;
    },
    null,
    { timeout: 30000 },
  );

/** A screenshot of the canvas's box only. */
const shot = (page, path) => page.locator("#canvas-box").screenshot({ path });

/**
 * A README picture: the page from the left edge to `right` CSS pixels past the art's opaque
 * bounds (the canvas with its chip, hint and timeline, the keys under it), the panel left out.
 */
async function docShot(page, path, right = 260) {
  const [, , r] = maskBounds(await artPixels(page));
  const box = await page.locator("#canvas-box").boundingBox();
  const main = await page.locator("#stage").boundingBox();
  await page.screenshot({ path, clip: { x: 0, y: 0, width: Math.min(box.x + box.width, box.x + r + right), height: main.y + main.height } });
}

test("spineboy's art: loaded with its atlas and page, drawn, played, dragged and keyed with onion skins, and the CLI's picture of the pose", () =>
  onPlayground(async (page) => {
    const requests = [];
    page.on("request", (r) => {
      if (r.url().endsWith("/api/pose")) requests.push(JSON.parse(r.postData()));
    });
    await loadSpineboyArt(page);
    await artSettled(page);
    const c = () => page.evaluate(() => window.ikarus.state.character);
    const loaded = await page.evaluate(() => {
      const a = window.ikarus.state.character.atlas;
      return { id: a.id, pages: a.pages.map((p) => p.file), images: a.images.map((i) => !!i), notice: window.ikarus.state.character.artNotice };
    });
    assert.match(loaded.id, /^a[0-9a-f]+$/);
    assert.deepEqual(loaded.pages, ["spineboy.png"]);
    assert.deepEqual(loaded.images, [true]);
    assert.equal(loaded.notice, null);
    assert.ok(requests.some((r) => r.atlas === loaded.id), "the poses carry the atlas");
    // Opaque where the torso is (its origin and tip's midpoint), transparent far from the body.
    const torso = (await c()).posed.find((b) => b.name === "torso");
    assert.ok((await alphaAt(page, (torso.x + torso.tip[0]) / 2, (torso.y + torso.tip[1]) / 2)) > 200, "the torso is drawn");
    assert.equal(await alphaAt(page, torso.x + 2000, torso.y), 0);
    const setup = await artPixels(page);
    const opaque = setup.data.filter((v, i) => i % 4 === 3 && v > 127).length;
    assert.ok(opaque > 5000, `${opaque} opaque pixels`);
    await shot(page, join(artifacts, "art-setup.png"));
    // Zoomed in about the torso (the wheel): the art follows the view, larger.
    await page.mouse.move(...(await page.evaluate(([x, y]) => window.ikarus.toClient(x, y), [torso.x, torso.y])));
    await page.mouse.wheel(0, -400);
    await page.waitForFunction(() => Number(document.getElementById("plot").dataset.zoom) > 1.5);
    await page.evaluate(() => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r))));
    assert.ok((await alphaAt(page, (torso.x + torso.tip[0]) / 2, (torso.y + torso.tip[1]) / 2)) > 200, "the torso is drawn where the zoomed view has it");
    const zoomed = (await artPixels(page)).data.filter((v, i) => i % 4 === 3 && v > 127).length;
    assert.ok(zoomed > 2 * opaque, `zoomed in: ${zoomed} opaque pixels, ${opaque} before`);
    await page.click("#fit");

    // walk plays: poses keep coming, each with its art (its slots' vertices move).
    await page.selectOption("#character-animation", "walk");
    await characterSettled(page);
    const before = await page.evaluate(() => ({ poses: window.ikarus.state.character.poses, v: window.ikarus.state.character.art.slots[0].vertices.slice(0, 2) }));
    await page.click("#play");
    await page.waitForFunction((n) => window.ikarus.state.character.poses >= n + 10, before.poses, { timeout: 30000 });
    await page.click("#play");
    await artSettled(page);
    const played = await page.evaluate(() => ({ time: window.ikarus.state.character.time, v: window.ikarus.state.character.art.slots[0].vertices.slice(0, 2) }));
    assert.ok(played.time > 0);
    assert.notDeepEqual(played.v, before.v, "the art moved with the clip");
    // Stopped at a time: the front foot's target dragged there, in Key mode (a key).
    await page.evaluate(() => window.ikarus.seek(0.4));
    await artSettled(page);
    if (process.env.ART_DOCS) await docShot(page, join(docs, "art-page.png"));
    await page.click("#key-mode");
    const name = "front-foot-target";
    const at = await targetAt(page, name);
    await dragTarget(page, at, [at[0] + 60, at[1] + 45]);
    await artSettled(page);
    const keys = await page.evaluate(() => window.ikarus.state.keys);
    assert.ok(keys.tracks[name].some((k) => Math.abs(k.time - 0.4) < 1e-9), `the drag keyed the target at 0.4 s: ${JSON.stringify(keys.tracks[name])}`);
    await shot(page, join(artifacts, "art-page.png"));

    // Onion skins of the keyed motion: drawn as faded art (more slots than the pose's own).
    await page.check("#onion");
    const own = await page.evaluate(() => window.ikarus.state.character.art.slots.length);
    await page.waitForFunction((n) => window.ikarus.art.slots() > n * 3, own, { timeout: 30000 });
    await shot(page, join(artifacts, "art-keys.png"));
    if (process.env.ART_DOCS) await docShot(page, join(docs, "art-keys.png"));
    await page.uncheck("#onion");

    // The bones overlay off: the art alone, against the CLI's picture of the same request.
    await page.uncheck("#show-bones");
    await artSettled(page);
    await page.waitForFunction((n) => window.ikarus.art.slots() === n, own);
    const req = await page.evaluate(() => window.ikarus.state.character.request);
    assert.equal(req.atlas, loaded.id);
    assert.equal(req.animation, "walk");
    const ours = await artPixels(page);
    await shot(page, join(artifacts, "art-alone.png"));
    const png = cliArt(cliArtArgs(req, ours.width, ours.height, join(artifacts, "art-cli.png")));
    const cmp = compareArt(ours, await pngPixels(page, png));
    console.log(`page vs CLI at walk ${req.time.toFixed(3)} s, ${req.targets.map((t) => t.bone).join(", ")} placed: overlap ${cmp.overlap.toFixed(4)}, mean colour difference ${(100 * cmp.colour).toFixed(2)} %, crop ${cmp.size.join(" × ")}`);
    writeFileSync(join(artifacts, "art-compare.json"), JSON.stringify({ request: { ...req, rig: undefined, character: undefined }, ...cmp }, null, 1));
    assert.ok(cmp.overlap >= 0.95, `overlap ${cmp.overlap}`);
    assert.ok(cmp.colour < 0.06, `colour ${cmp.colour}`);
  }));

test("an atlas the backend let go is sent again once, and the pose retried", () =>
  withBrowser(async ({ url, browser }) => {
    const { page, errors } = await openPage(browser);
    await page.goto(url);
    await ready(page);
    let parses = 0;
    let refused = 0;
    page.on("request", (r) => r.url().endsWith("/api/atlas/parse") && parses++);
    await loadSpineboyArt(page);
    await artSettled(page);
    assert.equal(parses, 1);
    // The next pose with the atlas answered 404 naming it (as a backend that let it go answers).
    await page.route("**/api/pose", (route) => {
      if (refused === 0 && JSON.parse(route.request().postData()).atlas) {
        refused++;
        return route.fulfill({ status: 404, contentType: "application/json", body: JSON.stringify({ error: "atlas: no atlas a0 kept; send it again" }) });
      }
      return route.continue();
    });
    await page.selectOption("#character-animation", "walk");
    await page.evaluate(() => window.ikarus.seek(0.3));
    await artSettled(page);
    assert.equal(refused, 1);
    assert.equal(parses, 2, "the atlas sent again");
    assert.equal(await page.evaluate(() => document.getElementById("error").hidden), true);
    assert.equal(await page.evaluate(() => window.ikarus.state.character.request.time), 0.3);
    // The browser logs the refused request itself; nothing else.
    assert.deepEqual(errors, ["Failed to load resource: the server responded with a status of 404 (Not Found)"]);
  }));

test("an atlas without its skeleton, a page image not given, a region the atlas lacks: one-line notices, the character as bones", () =>
  withBrowser(async ({ url, browser }) => {
    const { page, errors } = await openPage(browser);
    await page.goto(url);
    await ready(page);
    const [png, json, atlas] = spineboyFiles();
    await page.setInputFiles("#rig-file", [atlas, png]);
    await page.waitForFunction(() => !document.getElementById("error").hidden);
    assert.match(await page.textContent("#error"), /^atlas spineboy\.atlas: no skeleton given with it/);
    assert.equal(await page.evaluate(() => window.ikarus.state.character), null);
    // Skeleton and atlas without the page: the character loads as bones, the notice names the page.
    await page.setInputFiles("#rig-file", [json, atlas]);
    await page.waitForFunction(() => window.ikarus.state.character && window.ikarus.state.character.atlas && window.ikarus.state.character.art);
    await characterSettled(page);
    assert.match(await page.textContent("#error"), /^atlas spineboy\.atlas: page image spineboy\.png not given/);
    assert.equal(await page.evaluate(() => window.ikarus.art.slots()), 0);
    assert.ok(Number(await page.evaluate(() => document.getElementById("plot").dataset.bones)) > 0);
    // The raptor with spineboy's atlas: the region it lacks named, the raptor posed as bones.
    const raptor = { name: "spine-raptor-pro.json", mimeType: "application/json", buffer: readFileSync(join(examples, "spine-raptor-pro.json")) };
    await page.setInputFiles("#rig-file", [raptor, atlas, png]);
    await page.waitForFunction(() => /raptor/.test(window.ikarus.state.character.name) && window.ikarus.state.character.artNotice);
    await characterSettled(page);
    assert.match(await page.textContent("#error"), /^atlas: the atlas has no region "[^"]+" \(slot "[^"]+"'s attachment\)/);
    assert.equal(await page.evaluate(() => window.ikarus.state.character.atlas), null);
    assert.equal(await page.evaluate(() => document.body.dataset.status), "ready");
    assert.ok(await page.evaluate(() => window.ikarus.state.character.posed.length > 0), "posed as bones");
    // The browser logs the refused pose itself; nothing else.
    assert.deepEqual(errors, ["Failed to load resource: the server responded with a status of 422 (Unprocessable Entity)"]);
  }));
