// The Keys bar's GIF on the static page (issue 44, point 9): the GIF is rendered by the server,
// so where the page runs on its WebAssembly module (no server) the button is disabled and says
// it needs `ikarus serve`, as the panel's motion GIF does. The static build is played here by
// the server's page with the static build's marker (<meta name="ikarus-backend" content="wasm">)
// and a stand-in worker (started by the static build's own solver thread, web/ikarus-thread.js)
// that answers every call through the server; only the backend the page
// believes it has matters. Run by e2e/run:  node --test e2e/keygif.test.mjs
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { openPage, ready, withBrowser } from "./browser.mjs";

/** A worker in ikarus-worker.js's place: ready at once, every `{id, path, body}` asked of the server. */
const WORKER = `
postMessage({ ready: true });
onmessage = async ({ data }) => {
  const init = data.body ? { method: "POST", body: data.body, headers: { "content-type": "application/json" } } : {};
  const r = await fetch(data.path, init);
  postMessage({ id: data.id, status: r.status, text: await r.text() });
};`;

test("the static page: the keys' GIF is disabled and says it needs the server; with a server it is not", async () => {
  await withBrowser(async ({ url, browser }) => {
    const { page, errors } = await openPage(browser);
    await page.route("**/ikarus-worker.js", (route) => route.fulfill({ status: 200, contentType: "text/javascript", body: WORKER }));
    // The static build's solver thread (web/ikarus-thread.js, beside the worker there), which
    // starts the worker and holds each job to its budget: `ikarus serve` does not serve it.
    const THREAD = readFileSync(new URL("../web/ikarus-thread.js", import.meta.url), "utf8");
    await page.route("**/ikarus-thread.js", (route) => route.fulfill({ status: 200, contentType: "text/javascript", body: THREAD }));
    await page.route(`${url}/`, async (route) => {
      const res = await route.fetch();
      const html = (await res.text()).replace("<head>", '<head><meta name="ikarus-backend" content="wasm">');
      await route.fulfill({ response: res, body: html });
    });
    await page.goto(`${url}/`);
    await ready(page);
    await page.waitForFunction(() => document.body.dataset.backend === "wasm", null, { timeout: 10000 });
    assert.equal(await page.isDisabled("#dl-gif"), true, "the panel's motion GIF (as before)");
    assert.equal(await page.isDisabled("#key-gif"), true);
    assert.match(await page.getAttribute("#key-gif", "title"), /^needs `ikarus serve`: the keyed motion's GIF is rendered by the server/);
    assert.deepEqual(errors, []);

    // With the server: the title says what it makes.
    const served = await openPage(browser);
    await served.page.goto(url);
    await ready(served.page);
    assert.match(await served.page.getAttribute("#key-gif", "title"), /^The keyed motion/);
  });
});
