// Files of the playground (issue 11): arm files load (every examples/arms/*.toml) and save in the
// CLI's format, the last arm survives a reload and "Default arm" brings the built-in one back; a
// bad file is the CLI's one-line error with no console error; the downloads are what the screen
// shows (ghosts, traces, ranges, the reachable area, in the screen's palette, which is the
// pictures' palette), the GIF lasts as long as the page's playback, and the CSV has the CLI's
// columns.
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync, readdirSync } from "node:fs";
import { join } from "node:path";
import { execFileSync } from "node:child_process";
import { artifacts, binary, ended, onPlayground, ready } from "./browser.mjs";

const arms = join(import.meta.dirname, "..", "examples", "arms");

/** Clicks `button` and resolves with the download's file name and text (or bytes). */
async function download(page, button, binary = false) {
  const [d] = await Promise.all([page.waitForEvent("download"), page.click(button)]);
  const path = await d.path();
  return { name: d.suggestedFilename(), body: binary ? readFileSync(path) : readFileSync(path, "utf8") };
}

/** The delays of a GIF's frames, hundredths of a second (its graphic control extensions). */
function gifDelays(bytes) {
  const delays = [];
  for (let i = 0; i + 5 < bytes.length; i++) {
    if (bytes[i] === 0x21 && bytes[i + 1] === 0xf9 && bytes[i + 2] === 0x04) delays.push(bytes[i + 4] | (bytes[i + 5] << 8));
  }
  return delays;
}

test("arm files: every example loads, a saved arm is the CLI's format, the arm survives a reload", () =>
  onPlayground(async (page) => {
    // An arm with joint keys (rrp.toml's slide) is a one-branch rig, which the page's arm
    // editor refuses (the CLI answers it as a rig): the chains only.
    const jointKeys = /^(offset|joint|slide|extension|limits) =/m;
    const files = readdirSync(arms)
      .filter((f) => f.endsWith(".toml") && !jointKeys.test(readFileSync(join(arms, f), "utf8")))
      .sort();
    assert.ok(files.length >= 3, `${files}`);
    for (const f of files) {
      const cli = JSON.parse(execFileSync(binary, ["solve", "--arm", join(arms, f), "--goal", "1,1", "--format", "json"], { encoding: "utf8" }));
      await page.evaluate(() => (window.ikarus.state.arm.name = "before the file"));
      await page.setInputFiles("#arm-file", join(arms, f));
      await page.waitForFunction((name) => window.ikarus.state.arm.name === name, cli.arm, { timeout: 15000 });
      const shown = await page.evaluate(() => ({
        rows: document.querySelectorAll("#links-body tr").length,
        pose: window.ikarus.state.pose_deg,
        start: window.ikarus.state.arm.links.map((l) => l.angle_deg),
      }));
      assert.equal(shown.rows, cli.angles_deg.length, f);
      assert.deepEqual(shown.pose, shown.start, `${f}: the arm stands at its start pose`);
      // And it moves: a solve of the loaded arm.
      await page.evaluate(() => window.ikarus.animateTo(1, 1));
      await ended(page);
      assert.equal(await page.evaluate(() => document.getElementById("chip").dataset.kind), "neutral", f);
    }

    // Save: the CLI reads the file back as the same arm.
    await page.fill("#links-body tr:nth-child(1) td:nth-child(2) input", "2.5");
    await page.dispatchEvent("#links-body tr:nth-child(1) td:nth-child(2) input", "change");
    const saved = await download(page, "#save-arm");
    assert.match(saved.name, /\.toml$/);
    const savedPath = join(artifacts, saved.name);
    execFileSync("sh", ["-c", 'cat > "$1"', "sh", savedPath], { input: saved.body });
    const back = JSON.parse(execFileSync(binary, ["solve", "--arm", savedPath, "--goal", "1,1", "--format", "json"], { encoding: "utf8" }));
    const arm = await page.evaluate(() => window.ikarus.state.arm);
    assert.equal(back.arm, arm.name);
    assert.equal(back.angles_deg.length, arm.links.length);
    assert.match(saved.body, /length = 2\.5/);

    // A reload keeps the arm; "Default arm" brings the built-in one back.
    await page.reload();
    await ready(page);
    assert.deepEqual(await page.evaluate(() => window.ikarus.state.arm), arm);
    await page.click("#default-arm");
    await page.waitForFunction(() => window.ikarus.state.arm.name === "seed", null, { timeout: 15000 });
    assert.equal(await page.evaluate(() => window.ikarus.state.arm.links.length), 3);

    // A bad file: the CLI's one-line message on the chip, the arm unchanged.
    const bad = join(artifacts, "bad-arm.toml");
    execFileSync("sh", ["-c", 'printf "[[links]]\\nlength = -1.0\\n" > "$1"', "sh", bad]);
    await page.setInputFiles("#arm-file", bad);
    await page.waitForFunction(() => !document.getElementById("error").hidden, null, { timeout: 15000 });
    const message = await page.textContent("#error");
    assert.match(message, /^arm file: link 1 length/);
    assert.equal(await page.evaluate(() => document.getElementById("chip").dataset.kind), "bad");
    assert.equal(await page.evaluate(() => window.ikarus.state.arm.name), "seed");
  }));

test("downloads are the screen: ghosts, traces, ranges and area in one palette; the GIF's length; the CLI's columns", () =>
  onPlayground(async (page, { url }) => {
    // One palette: the page draws with the pictures' colours (/api/meta's palette).
    const meta = await (await fetch(`${url}/api/meta`)).json();
    const colors = await page.evaluate(async () => (await import("/paint.js")).COLORS);
    for (const [name, value] of Object.entries(meta.palette)) assert.deepEqual(colors[name], value, name);

    await page.check("#limits");
    await page.check("#show-workspace");
    await page.waitForFunction(() => window.ikarus.state.region || window.ikarus.state.areaOutline, null, { timeout: 15000 });
    const exact = await page.evaluate(() => !!window.ikarus.state.region);
    await page.evaluate(() => window.ikarus.animateTo(2, 3));
    await ended(page);

    // SVG: the ghosts (faint arms), the joints' traces and the tip's, the ranges, the area.
    const svg = (await download(page, "#dl-svg")).body;
    const strokes = (colour) => (svg.match(new RegExp(`stroke="${colour}"`, "g")) || []).length;
    const ghosts = (svg.match(new RegExp(`stroke="${meta.palette.ink}" stroke-width="5"[^>]*opacity="0\\.\\d+"`, "g")) || []).length;
    assert.ok(ghosts >= 10, `${ghosts} ghosts in the SVG`);
    assert.ok(strokes(meta.palette.path) >= 1, "the tip's trace");
    assert.ok(strokes(meta.palette.joints[0]) >= 1, "joint 1's trace");
    // The reachable area: the exact region's loops (arcs, nonzero) or the sampled grid's edge.
    assert.ok(svg.includes(`fill="${meta.palette.workspace}" fill-rule="${exact ? "nonzero" : "evenodd"}"`), "the reachable area");
    if (exact) {
      const area = new RegExp(`<path d="([^"]*)" fill="${meta.palette.workspace}" fill-rule="nonzero"`).exec(svg)[1];
      assert.match(area, /^M[^A]*A/, "the region's arcs are SVG arcs");
    }
    // The ranges: one wedge per limited joint (the seed's three) with the limits on, as on screen.
    const wedges = (text) => (text.match(new RegExp(`<path d="M[^"]*A[^"]*Z" fill="${meta.palette.ink}" fill-rule="nonzero" opacity="0.1"/>`, "g")) || []).length;
    assert.equal(wedges(svg), 3);
    assert.ok(svg.includes(`stroke="${meta.palette.goal}"`), "the goal");
    // With the ghosts and traces hidden on screen, the download has none either.
    await page.uncheck("#show-ghosts");
    await page.uncheck("#show-traces");
    const bare = (await download(page, "#dl-svg")).body;
    assert.ok(!bare.includes(`stroke="${meta.palette.path}"`), "no tip trace");
    assert.ok(!/stroke-width="5"[^>]*opacity/.test(bare), "no ghosts");
    await page.check("#show-ghosts");
    await page.check("#show-traces");
    await page.uncheck("#limits");
    assert.equal(wedges((await download(page, "#dl-svg")).body), 0, "no ranges with the limits off");
    await page.check("#limits");

    // PNG: the screen's picture at 800 × 800, with the tip's trace colour in it.
    const png = await download(page, "#dl-png", true);
    assert.equal(png.name, "ikarus-arm.png");
    assert.equal(png.body.readUInt32BE(16), 800);
    const orange = await page.evaluate(async (b64) => {
      const img = new Image();
      img.src = `data:image/png;base64,${b64}`;
      await img.decode();
      const c = document.createElement("canvas");
      c.width = img.width;
      c.height = img.height;
      const ctx = c.getContext("2d");
      ctx.drawImage(img, 0, 0);
      const d = ctx.getImageData(0, 0, c.width, c.height).data;
      let n = 0;
      for (let i = 0; i < d.length; i += 4) if (Math.abs(d[i] - 0xec) < 8 && Math.abs(d[i + 1] - 0x7f) < 8 && Math.abs(d[i + 2] - 0x2d) < 8) n++;
      return n;
    }, png.body.toString("base64"));
    assert.ok(orange > 100, `${orange} pixels of the tip's trace`);

    // GIF: as long as the page plays the motion (within one frame's rounding).
    const seconds = await page.evaluate(() => window.ikarus.duration());
    const gif = await download(page, "#dl-gif", true);
    const delays = gifDelays(gif.body);
    const total = delays.reduce((a, b) => a + b, 0) / 100;
    assert.ok(delays.length > 10, `${delays.length} frames`);
    assert.ok(Math.abs(total - seconds) <= 0.04 + 1e-9, `the GIF lasts ${total} s, the page plays ${seconds} s`);

    // CSV: the columns of `ikarus animate --format csv`.
    const csv = (await download(page, "#dl-csv")).body;
    const cliCsv = execFileSync(binary, ["animate", "--goal", "2,3", "--format", "csv"], { encoding: "utf8" });
    assert.equal(csv.split("\n")[0], cliCsv.split("\n")[0]);
    assert.match(csv.split("\n")[0], /^time,theta1_deg,theta2_deg,theta3_deg,x0,y0/);
  }));
