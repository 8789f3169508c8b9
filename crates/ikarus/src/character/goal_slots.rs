//! The goals of a solve together, at most one per skeleton bone: a later goal on a bone
//! replaces the earlier one and goes last, as a removal and a push would put it, without a scan
//! of the goals (with a goal per constraint, the scan made building a task quadratic).

use crate::solve::RigGoal;

/// The goals of a task in the order they were put, at most one per skeleton bone.
pub(super) struct GoalSlots {
    /// In the order put; `None` where a later goal on the same bone (or a pin) replaced it.
    put: Vec<Option<RigGoal>>,
    /// Per skeleton bone, where its goal is in `put`.
    at: Vec<Option<usize>>,
}

impl GoalSlots {
    pub(super) fn new(bones: usize) -> Self {
        GoalSlots { put: Vec::new(), at: vec![None; bones] }
    }

    /// `goal` on bone `i`, replacing the one there.
    pub(super) fn put(&mut self, i: usize, goal: RigGoal) {
        self.clear(i);
        self.at[i] = Some(self.put.len());
        self.put.push(Some(goal));
    }

    /// No goal on bone `i`.
    pub(super) fn clear(&mut self, i: usize) {
        if let Some(k) = self.at[i].take() {
            self.put[k] = None;
        }
    }

    pub(super) fn goals(self) -> Vec<RigGoal> {
        self.put.into_iter().flatten().collect()
    }
}
