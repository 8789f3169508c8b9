// A character's skin and physics switch are its work (issue 39): chosen on the page, they are one
// undo step each, saved in the project file (`character.skin`, `character.physics`) and put back
// when it opens on a fresh page, the list and the switch showing them and the poses asked with
// them. A project saved before they were opens with the file's default skin and physics on,
// without naming them as defaulted; a skin the character does not have is refused in one line.
// The character is a small synthetic one: an arm swung by a physics constraint, and a cape that
// only the skin `hero` turns on. Run by e2e/run.
import { test } from "node:test";
import assert from "node:assert/strict";
import { readFileSync } from "node:fs";
import { join } from "node:path";
import { artifacts, onPlayground, ready } from "./browser.mjs";
import { characterSettled } from "./charpage.mjs";

const TEXT = JSON.stringify({
  skeleton: { spine: "4.2.43" },
  bones: [
    { name: "root" },
    { name: "arm", parent: "root", length: 50, rotation: 30 },
    { name: "cape", parent: "root", x: 20, length: 30, skin: true },
  ],
  physics: [{ name: "sway", bone: "arm", rotate: 1 }],
  skins: [{ name: "default" }, { name: "hero", bones: ["cape"] }],
});

/** What the page shows of the character's choices, and what its last pose asked. */
const choices = (page) =>
  page.evaluate(() => {
    const c = window.ikarus.state.character;
    const cape = c.posed.find((b) => b.name === "cape");
    return {
      skin: c.skin,
      physics: c.physics,
      list: document.getElementById("character-skin").value,
      listShown: !document.getElementById("character-skin-box").hidden,
      switchOn: document.getElementById("character-physics").checked,
      asked: { skin: c.request.skin ?? null, physics: c.request.physics ?? null },
      capeActive: cape.active !== false,
    };
  });

/** Opens the project file `file` (an object) as `name` and waits for the character's poses. */
async function open(page, name, file) {
  await page.setInputFiles("#project-file", { name, mimeType: "application/json", buffer: Buffer.from(JSON.stringify(file)) });
  await page.waitForFunction((n) => window.said.some((t) => t.startsWith(`opened ${n}`)), name);
  await characterSettled(page);
}

/** Keeps every line the status says (the poses' answers soon say their own). */
const listen = (page) =>
  page.evaluate(() => {
    const stats = document.getElementById("stats");
    window.said = [];
    if (window.listening) return;
    window.listening = true;
    new MutationObserver(() => window.said.push(stats.textContent)).observe(stats, { childList: true, characterData: true, subtree: true });
  });

test("a character's skin and physics switch: undone, saved, opened on a fresh page; an older project opens with the defaults", () =>
  onPlayground(async (page) => {
    await page.setInputFiles("#rig-file", { name: "caped.json", mimeType: "application/json", buffer: Buffer.from(TEXT) });
    await page.waitForFunction(() => window.ikarus.state.character?.posed, null, { timeout: 15000 });
    await characterSettled(page);
    const defaults = {
      skin: null,
      physics: true,
      list: "default",
      listShown: true,
      switchOn: true,
      asked: { skin: null, physics: null },
      capeActive: false,
    };
    assert.deepEqual(await choices(page), defaults);

    // The skin hero (the cape turns on), then physics off: two steps.
    await page.selectOption("#character-skin", "hero");
    await characterSettled(page);
    await page.uncheck("#character-physics");
    await characterSettled(page);
    const chosen = { skin: "hero", physics: false, list: "hero", listShown: true, switchOn: false, asked: { skin: "hero", physics: false }, capeActive: true };
    assert.deepEqual(await choices(page), chosen);
    assert.match(await page.getAttribute("#undo", "title"), /^Undo: Physics off/);
    // Undone one at a time, and redone.
    await page.click("#undo");
    await characterSettled(page);
    assert.deepEqual(await choices(page), { ...chosen, physics: true, switchOn: true, asked: { skin: "hero", physics: null } });
    await page.click("#undo");
    await characterSettled(page);
    assert.deepEqual(await choices(page), defaults);
    await page.click("#redo");
    await page.click("#redo");
    await characterSettled(page);
    assert.deepEqual(await choices(page), chosen);

    // Saved: the file holds them with the character's work.
    const [d] = await Promise.all([page.waitForEvent("download"), page.click("#save-project")]);
    const file = JSON.parse(readFileSync(await d.path(), "utf8"));
    assert.equal(file.character.skin, "hero");
    assert.equal(file.character.physics, false);

    // A fresh page: the project opens alone, with the skin and the switch as saved.
    await page.reload();
    await ready(page);
    await listen(page);
    await open(page, "caped.ikarus.json", file);
    assert.deepEqual(await choices(page), chosen);
    assert.deepEqual((await page.evaluate(() => window.said)).filter((t) => /^opened/.test(t)), ["opened caped.ikarus.json"]);
    await page.screenshot({ path: join(artifacts, "character-project-skin.png") });

    // A project saved before skins and physics were saved: the default skin, physics on, and
    // nothing more said to be defaulted than such a file already was.
    const old = JSON.parse(JSON.stringify(file));
    delete old.character.skin;
    delete old.character.physics;
    await listen(page);
    await open(page, "old.ikarus.json", old);
    assert.deepEqual(await choices(page), defaults);
    assert.deepEqual((await page.evaluate(() => window.said)).filter((t) => /^opened/.test(t)), ["opened old.ikarus.json"]);

    // A skin the character does not have, or a switch that is not true or false: one line, nothing changed.
    for (const [field, value, message] of [
      ["skin", "villain", 'project file: character.skin = "villain" is not one of the character\'s skins (default, hero)'],
      ["physics", "off", 'project file: character.physics = "off" is not true or false'],
    ]) {
      const bad = JSON.parse(JSON.stringify(file));
      bad.character[field] = value;
      await page.setInputFiles("#project-file", { name: "bad.ikarus.json", mimeType: "application/json", buffer: Buffer.from(JSON.stringify(bad)) });
      await page.waitForFunction((m) => {
        const e = document.getElementById("error");
        return !e.hidden && e.textContent.length > 0 && (e.textContent === m || !e.textContent.startsWith("project file"));
      }, message);
      assert.equal(await page.textContent("#error"), message);
      assert.deepEqual(await choices(page), defaults);
    }
  }));
