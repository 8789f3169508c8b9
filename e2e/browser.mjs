// What the browser tests share: the ikarus server on a free port, headless Chromium, where the
// screenshots go, and a fresh playground to run a test on (onPlayground).
import assert from "node:assert/strict";
import { spawn } from "node:child_process";
import { mkdirSync, readFileSync } from "node:fs";
import { dirname, join } from "node:path";
import { fileURLToPath } from "node:url";
import { chromium } from "playwright-core";

const here = dirname(fileURLToPath(import.meta.url));
export const binary = process.env.IKARUS_BIN ?? join(here, "..", "target", "release", "ikarus");
const browserPath = process.env.CHROMIUM ?? "/usr/bin/chromium";
export const artifacts = process.env.E2E_ARTIFACTS ?? join(here, "..", "target", "e2e");

/** Starts `ikarus serve --port 0` and resolves with its URL once it listens. */
export function startServer() {
  const child = spawn(binary, ["serve", "--port", "0"], { stdio: ["ignore", "pipe", "inherit"] });
  return new Promise((resolve, reject) => {
    let out = "";
    const timer = setTimeout(() => reject(new Error(`no address from the server: ${out}`)), 15000);
    child.on("error", reject);
    child.stdout.on("data", (chunk) => {
      out += chunk;
      const m = out.match(/listening on (http:\/\/\S+)/);
      if (m) {
        clearTimeout(timer);
        resolve({ child, url: m[1] });
      }
    });
  });
}

/** `python3 -m http.server` on a free loopback port serving `dir` (static files, no ikarus
 * server): {child, url}; kill `child` when done. */
export function staticServer(dir) {
  const child = spawn("python3", ["-u", "-m", "http.server", "--bind", "127.0.0.1", "--directory", dir, "0"], {
    stdio: ["ignore", "pipe", "pipe"],
  });
  child.stderr.on("data", () => {}); // its request log
  return new Promise((resolve, reject) => {
    let out = "";
    const timer = setTimeout(() => reject(new Error(`no address from http.server: ${out}`)), 15000);
    child.on("error", reject);
    child.stdout.on("data", (chunk) => {
      out += chunk;
      const m = out.match(/port (\d+)/);
      if (m) {
        clearTimeout(timer);
        resolve({ child, url: `http://127.0.0.1:${m[1]}` });
      }
    });
  });
}

export const launch = () =>
  chromium.launch({
    executablePath: browserPath,
    args: [
      "--no-sandbox",
      "--disable-gpu",
      "--disable-quic",
      "--no-first-run",
      "--disable-background-networking",
      "--disable-component-update",
      "--disable-sync",
    ],
  });

/** A new page of `browser` at `viewport`, and the console and page errors it logs from then on. */
export async function openPage(browser, viewport = { width: 1280, height: 800 }) {
  const page = await browser.newPage({ viewport });
  const errors = [];
  page.on("console", (m) => m.type() === "error" && errors.push(m.text()));
  page.on("pageerror", (e) => errors.push(e.message));
  return { page, errors };
}

/** Resolves once the page has loaded its settings and drawn the arm. */
export const ready = (page) => page.waitForFunction(() => window.ikarus && window.ikarus.ready, null, { timeout: 15000 });

/** Resolves once the motion played has ended and the page has settled (not solving or moving). */
export const ended = (page, timeout = 15000) =>
  page.waitForFunction(() => document.body.dataset.playback === "ended" && !["solving", "moving"].includes(document.body.dataset.status), null, { timeout });

/**
 * One edit left unsaved (the tolerance changed), then the page reloaded: resolves with whether
 * the page was dirty before and the dialogs it showed (["beforeunload"] when it warned).
 */
export async function reloadUnsaved(page) {
  await page.fill("#tolerance", "0.001");
  await page.press("#tolerance", "Tab");
  const dirty = await page.evaluate(() => document.body.dataset.dirty);
  const dialogs = [];
  const accept = (dialog) => {
    dialogs.push(dialog.type());
    dialog.accept();
  };
  page.on("dialog", accept);
  await page.reload();
  await ready(page);
  page.off("dialog", accept);
  return { dirty, dialogs };
}

/** Types `value` into the field `selector` and commits it, as leaving the field does. */
export async function setField(page, selector, value) {
  await page.fill(selector, value);
  await page.dispatchEvent(selector, "change");
}

/** Clicks `button` and resolves with the text of the file it downloads. */
export async function downloadText(page, button) {
  const [d] = await Promise.all([page.waitForEvent("download"), page.click(button)]);
  return readFileSync(await d.path(), "utf8");
}

/** Runs `fn({url, browser})` with a fresh server and browser, and stops both afterwards. */
export async function withBrowser(fn) {
  const { child, url } = await startServer();
  const browser = await launch();
  try {
    await fn({ url, browser });
  } finally {
    await browser.close();
    child.kill("SIGINT");
  }
}

/**
 * Runs `body(page, {url, browser})` on a fresh playground: its own server and browser, a page
 * (of `viewport`) at `url` and ready, the screenshots' folder made; then checks that the page
 * logged no error. `before(page)` runs before the page loads (listeners of its requests, say).
 */
export function onPlayground(body, { before = () => {}, viewport } = {}) {
  return withBrowser(async ({ url, browser }) => {
    const { page, errors } = await openPage(browser, viewport);
    before(page);
    await page.goto(url);
    await ready(page);
    mkdirSync(artifacts, { recursive: true });
    await body(page, { url, browser });
    assert.deepEqual(errors, [], "console errors");
  });
}
