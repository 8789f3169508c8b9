// Limits, durations and the downloads' time (issue 24): limits turned on with the pose outside
// them bring the pose into range (a short motion, said on the chip) instead of failing every
// click with a 422; the API's message for a start pose outside the limits is in degrees with the
// joint numbered from 1; a bad Duration is named and blocks the click; the frames downloaded
// (CSV, JSON, a clicked motion's and a traced path's) carry the seconds the timeline played.
import { test } from "node:test";
import assert from "node:assert/strict";
import { downloadText, ended, openPage, ready, setField, withBrowser } from "./browser.mjs";

/** The `time` column of a frames CSV. */
const csvTimes = (csv) =>
  csv
    .trim()
    .split("\n")
    .slice(1)
    .map((row) => Number(row.split(",")[0]));

test("limits turned on with the pose outside them: the pose glides into range, the chip says so, clicks work", async () => {
  await withBrowser(async ({ url, browser }) => {
    const { page, errors } = await openPage(browser);
    const refused = [];
    page.on("response", async (r) => r.url().includes("/api/") && r.status() >= 400 && refused.push(`${r.url()} ${r.status()} ${await r.text()}`));
    await page.goto(url);
    await ready(page);
    const pose = () => page.evaluate(() => window.ikarus.state.pose_deg);
    const limits = await page.evaluate(() => window.ikarus.state.arm.links.map((l) => l.limits_deg));
    const inside = (p) => p.every((a, i) => a >= limits[i][0] - 1e-9 && a <= limits[i][1] + 1e-9);

    // Without limits, (−2, 3) leaves joint 1 past its 45°.
    await page.evaluate(() => window.ikarus.animateTo(-2, 3));
    await ended(page, 30000);
    const outside = await pose();
    assert.ok(outside[0] > 45, `joint 1 at ${outside[0]}°`);

    // The API refuses that pose with the limits on, in degrees, the joint numbered from 1.
    const arm = await page.evaluate(() => window.ikarus.state.arm);
    const res = await fetch(`${url}/api/animate`, {
      method: "POST",
      headers: { "content-type": "application/json" },
      body: JSON.stringify({ arm, start_deg: outside, goal: { x: 3, y: 2 }, options: { limits: true } }),
    });
    assert.equal(res.status, 422);
    const { error } = await res.json();
    assert.match(error, /^start_deg: joint 1 at \d+(\.\d)?° lies outside its limits \[-45°, 45°\]$/);
    assert.ok(error.includes(`${Number(outside[0].toFixed(1))}°`), error);

    // Limits on: a short motion into range, then the chip names the joints and their angles.
    await page.check("#limits");
    await page.waitForFunction(() => document.body.dataset.playback === "playing", null, { timeout: 15000 });
    await ended(page, 30000);
    const moved = await pose();
    assert.ok(inside(moved), `the pose ${moved} lies inside the limits`);
    assert.equal(moved[0], 45, "joint 1 at its nearest bound");
    assert.match(await page.textContent("#stats"), /^limits on: joints? 1.* moved into (its range|their ranges), \d+(\.\d)?° → 45°/);
    assert.equal(await page.evaluate(() => document.getElementById("chip").dataset.kind), "neutral");
    const frames = await page.evaluate(() => window.ikarus.state.animation.frames.length);
    assert.ok(frames > 5, `drawn as a motion (${frames} frames)`);

    // Clicks work at once.
    await page.evaluate(() => window.ikarus.animateTo(3, 2));
    await ended(page, 30000);
    assert.equal(await page.evaluate(() => document.body.dataset.status), "reached");

    // A click while the glide plays: no request starts outside the limits.
    await page.uncheck("#limits");
    await page.evaluate(() => window.ikarus.animateTo(-2, 3));
    await ended(page, 30000);
    await page.check("#limits");
    await page.evaluate(() => window.ikarus.animateTo(3, 2));
    await ended(page, 30000);
    assert.equal(await page.evaluate(() => document.body.dataset.status), "reached");
    assert.ok(inside(await pose()));
    // Nor a traced shape or the pointer followed.
    await page.uncheck("#limits");
    await page.evaluate(() => window.ikarus.animateTo(-2, 3));
    await ended(page, 30000);
    await page.check("#limits");
    const followed = page.waitForResponse((r) => r.url().endsWith("/api/track"), { timeout: 15000 });
    await page.evaluate(() => window.ikarus.followTo(3, 2));
    assert.equal((await followed).status(), 200);
    assert.deepEqual(refused, []);
    assert.deepEqual(errors, []);
  });
});

test("durations: a bad one is named and blocks the click and Play; a good one is what plays", async () => {
  await withBrowser(async ({ url, browser }) => {
    const { page, errors } = await openPage(browser);
    const requests = [];
    page.on("request", (r) => r.url().includes("/api/") && requests.push(r.url()));
    // The page's clock is the test's (it runs as the wall clock does until paused below).
    await page.clock.install();
    await page.goto(url);
    await ready(page);
    await page.evaluate(() => window.ikarus.animateTo(2, 3));
    await ended(page, 30000);
    for (const bad of ["-2", "1000", "0"]) {
      await setField(page, "#duration", bad);
      const before = requests.length;
      await page.evaluate(() => window.ikarus.animateTo(1, 3));
      const chip = await page.evaluate(() => ({ text: document.getElementById("chip").innerText, kind: document.getElementById("chip").dataset.kind }));
      assert.match(chip.text, /Duration: must be a number from 0\.1 to 60/, `duration ${bad}`);
      assert.equal(chip.kind, "bad");
      assert.equal(await page.getAttribute("#duration", "aria-invalid"), "true");
      assert.equal(requests.length, before, `duration ${bad}: nothing sent`);
      // Play does not play the motion at some other length either.
      await page.click("#play");
      assert.notEqual(await page.evaluate(() => document.body.dataset.playback), "playing", `duration ${bad}: not played`);
    }
    await setField(page, "#duration", "1.5");
    assert.equal(await page.getAttribute("#duration", "aria-invalid"), null);
    assert.equal(await page.evaluate(() => document.getElementById("chip").dataset.kind), "neutral");
    assert.equal(await page.evaluate(() => window.ikarus.duration()), 1.5);
    // The page's clock held still: the click's motion plays while the test moves the clock on,
    // 1.5 s of it and not a frame less.
    await page.clock.pauseAt((await page.evaluate(() => Date.now())) + 1000);
    await page.evaluate(() => window.ikarus.animateTo(1, 3));
    const playback = () => page.evaluate(() => ({ playback: document.body.dataset.playback, u: window.ikarus.state.playback.u }));
    assert.deepEqual(await playback(), { playback: "playing", u: 0 }, "the motion starts at its first frame");
    await page.clock.runFor(1400);
    const at = await playback();
    assert.equal(at.playback, "playing", "still playing after 1.4 s of the 1.5 s chosen");
    assert.ok(Math.abs(at.u - 1400 / 1500) < 0.02, `the playhead at ${at.u}, 1.4 s of 1.5 s`);
    await page.clock.runFor(200);
    assert.equal((await playback()).playback, "ended", "ended once the 1.5 s have passed");
    assert.equal(await page.evaluate(() => document.body.dataset.status), "reached");
    assert.deepEqual(errors, []);
  });
});

test("downloads carry the seconds played: a click's CSV and JSON, a traced path's CSV and JSON", async () => {
  await withBrowser(async ({ url, browser }) => {
    const { page, errors } = await openPage(browser);
    await page.goto(url);
    await ready(page);
    // A click, the default duration (0.6 s + 0.4 s a radian travelled: not 1 s).
    await page.evaluate(() => window.ikarus.animateTo(2, 3));
    await ended(page, 30000);
    const played = await page.evaluate(() => window.ikarus.duration());
    assert.ok(Math.abs(played - 1) > 0.05, `the playback lasts ${played} s`);
    let times = csvTimes(await downloadText(page, "#dl-csv"));
    assert.equal(times.length, 60);
    assert.equal(times[0], 0);
    assert.ok(Math.abs(times.at(-1) - played) < 1e-9, `the CSV ends at ${times.at(-1)} s, the playback at ${played} s`);
    let json = JSON.parse(await downloadText(page, "#dl-json"));
    assert.ok(Math.abs(json.duration - played) < 1e-9, `"duration": ${json.duration}`);
    assert.ok(Math.abs(json.frames.at(-1).time - played) < 1e-9);
    // A chosen duration.
    await setField(page, "#duration", "2.5");
    times = csvTimes(await downloadText(page, "#dl-csv"));
    assert.equal(times.at(-1), 2.5);
    assert.ok(Math.abs(times[30] - (2.5 * 30) / 59) < 1e-9);
    // A traced path plays one sample per 1/25 s: 120 samples, 4.8 s, and so do its downloads.
    await setField(page, "#duration", "");
    await page.evaluate(() => window.ikarus.traceShape("figure8"));
    await page.waitForFunction(() => window.ikarus.state.track, null, { timeout: 15000 });
    const traced = await page.evaluate(() => window.ikarus.duration());
    assert.equal(traced, 4.8);
    times = csvTimes(await downloadText(page, "#dl-csv"));
    assert.equal(times.length, 120);
    assert.ok(Math.abs(times.at(-1) - 4.8) < 1e-9, `the traced path's CSV ends at ${times.at(-1)} s`);
    json = JSON.parse(await downloadText(page, "#dl-json"));
    assert.equal(json.duration, 4.8);
    assert.equal(json.samples.length, 120);
    assert.ok(Math.abs(json.samples[1].time - 4.8 / 119) < 1e-9);
    assert.ok(Math.abs(json.samples.at(-1).time - 4.8) < 1e-9);
    assert.deepEqual(errors, []);
  });
});
