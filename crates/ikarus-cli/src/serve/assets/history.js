// Undo and redo of the page's work: a stack of snapshots (project.js's `snapshot`), the pure part.
// `present` is the work as it stands after the last edit; each edit pushes the one before it with
// the edit's label ("Move left_hand goal"), so that undo goes back to it and redo forward again.
// A new edit after undo drops what could be redone; restoring a snapshot does not push. The
// stack keeps the last `cap` steps (200 by default; the oldest are forgotten). No coalescing:
// each committed change (a field's change event: Enter or leaving the field, a drag's end, a
// click) is one step. No DOM: node tests it (e2e/project.unit.test.mjs); projects.js wires it.

/** Steps kept by default (the issue asks for at least 100). */
export const HISTORY_CAP = 200;

/**
 * A fresh history whose present is `present`, comparing snapshots by `key(snapshot)` (a string:
 * an edit that changes nothing is not a step). Returns {record(snapshot, label), amend(snapshot),
 * undo(), redo(), reset(present), present(), undoLabel(), redoLabel(), sizes()}.
 */
export function newHistory(present, key = JSON.stringify, cap = HISTORY_CAP) {
  let now = present;
  const back = [];
  const ahead = [];

  /** One step from the stack `from` to the stack `to`: its snapshot becomes the present. */
  function move(from, to) {
    const step = from.pop();
    if (!step) return null;
    to.push({ snapshot: now, label: step.label });
    now = step.snapshot;
    return step;
  }

  return {
    /** An edit made the work `snapshot`: the work before it can be undone. False when nothing changed. */
    record(snapshot, label) {
      if (now !== null && key(snapshot) === key(now)) return false;
      back.push({ snapshot: now, label });
      if (back.length > cap) back.splice(0, back.length - cap);
      ahead.length = 0;
      now = snapshot;
      return true;
    },
    /** What the last edit led to, as it settled (a solve came back): no new step. */
    amend(snapshot) {
      now = snapshot;
    },
    /** Back one step: the snapshot to restore (now the present), or null when there is none. */
    undo: () => move(back, ahead),
    /** Forward one step: the snapshot to restore, or null. */
    redo: () => move(ahead, back),
    /** Forgets every step: `present` is the work. */
    reset(present) {
      now = present;
      back.length = 0;
      ahead.length = 0;
    },
    present: () => now,
    /** The label of what undo would undo, or null. */
    undoLabel: () => (back.length ? back[back.length - 1].label : null),
    /** The label of what redo would redo, or null. */
    redoLabel: () => (ahead.length ? ahead[ahead.length - 1].label : null),
    sizes: () => ({ undo: back.length, redo: ahead.length }),
  };
}
