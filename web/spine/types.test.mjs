// ikarus-spine's hand-written types (index.d.ts) checked by TypeScript itself: a program using
// the whole API as the README shows it compiles under --strict, and a wrong call does not
// (@ts-expect-error lines, which tsc refuses when the error they expect does not come).
//   IKARUS_SPINE_DIR=DIR node --test web/spine/types.test.mjs   (tsc: web/node_modules, `(cd web && npm ci)`)
import { test } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { copyFileSync, existsSync, mkdtempSync, rmSync, writeFileSync } from "node:fs";
import { tmpdir } from "node:os";
import { join } from "node:path";
import { fileURLToPath } from "node:url";

const dir = process.env.IKARUS_SPINE_DIR;
if (!dir) throw new Error("IKARUS_SPINE_DIR: the directory `bash web/spine/build DIR` wrote (web/spine/test sets it)");
const tsc = fileURLToPath(new URL("../node_modules/.bin/tsc", import.meta.url));

const program = `
import { attach, load, DEFAULT_BONES, PHYSICS_POSE, Ik, type SpineSkeleton, type Report, type GoalReport } from "./index.js";
declare const skeleton: SpineSkeleton;
export async function frame(x: number, y: number): Promise<number> {
  await load();
  const ik: Ik = await attach(skeleton, { limits: { "front-bracer": [-40, 120] }, physics: PHYSICS_POSE });
  ik.clear();
  ik.goal("front-fist", x, y, { bones: 3, angle: 10, weight: 2, priority: "secondary", bend: "positive" });
  ik.goal(skeleton.bones[0], x, y);
  ik.pin("rear-foot");
  ik.pin("rear-foot", { bones: 3 });
  const report: Report = ik.apply();
  const first: GoalReport = report.goals[0];
  const moved: string[] = report.moved;
  // @ts-expect-error a priority is "primary" or "secondary"
  ik.goal("front-fist", x, y, { priority: "first" });
  // @ts-expect-error x is a number
  ik.goal("front-fist", "1", y);
  // @ts-expect-error a limit is [min, max]
  await attach(skeleton, { limits: { "front-bracer": 40 } });
  // @ts-expect-error a pin's bones is a number
  ik.pin("rear-foot", { bones: "3" });
  // @ts-expect-error the report's goals are read, not replaced
  ik.report = report;
  ik.dispose();
  return first.error + moved.length + DEFAULT_BONES;
}
`;

test("index.d.ts: the API as the README uses it compiles under tsc --strict; wrong calls do not", () => {
  assert.ok(existsSync(tsc), `no tsc at ${tsc}: (cd web && npm ci) installs it (web/package.json)`);
  const work = mkdtempSync(join(tmpdir(), "ikarus-spine-types-"));
  try {
    copyFileSync(join(dir, "index.d.ts"), join(work, "index.d.ts"));
    writeFileSync(join(work, "use.ts"), program);
    const args = ["--noEmit", "--strict", "--target", "es2022", "--module", "nodenext", "--moduleResolution", "nodenext", "--lib", "es2022,dom", join(work, "use.ts")];
    let out = "";
    try {
      out = execFileSync(tsc, args, { encoding: "utf8" });
    } catch (e) {
      out = `${e.stdout}${e.stderr}`;
    }
    assert.equal(out.trim(), "", `tsc: ${out}`);
  } finally {
    rmSync(work, { recursive: true, force: true });
  }
});
