// Helpers of the browser tests that drive a character on the page (keys.test.mjs,
// charbend.test.mjs): waiting for its poses and keyed motion, and dragging its IK targets.

/** Waits until the character's pose and the keyed motion have landed. */
export const characterSettled = (page) =>
  page.waitForFunction(() => window.ikarus.characters.settled() && window.ikarus.keys.settled(), null, { timeout: 60000 });

/** Where the character's target bone `name` is now: where it was put, else where it is posed. */
export const targetAt = (page, name) =>
  page.evaluate((n) => {
    const c = window.ikarus.state.character;
    const g = c.targets.get(n);
    const b = c.posed.find((x) => x.name === n);
    return g ? [g.x, g.y] : [b.x, b.y];
  }, name);

/** Drags the character's target `name` from `at` to the world point `goal` and waits. */
export async function dragTarget(page, at, goal) {
  const from = await page.evaluate(([x, y]) => window.ikarus.toClient(x, y), at);
  const to = await page.evaluate(([x, y]) => window.ikarus.toClient(x, y), goal);
  await page.mouse.move(...from);
  await page.mouse.down();
  await page.mouse.move(...to, { steps: 6 });
  await page.mouse.up();
  await characterSettled(page);
}
