//! The tree's structure, computed once when a skeleton is built: children, a topological
//! walk, root-to-bone paths, and the cycle that stops a walk.

use super::{Bone, SkeletonError};

/// The children of every bone, flat, with offsets: a counting sort by parent, stable.
pub(super) fn children_of(parents: &[Option<usize>]) -> (Vec<usize>, Vec<usize>) {
    let n = parents.len();
    let mut start = vec![0; n + 1];
    for p in parents.iter().flatten() {
        start[p + 1] += 1;
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let mut next = start.clone();
    let mut children = vec![0; parents.iter().flatten().count()];
    for (i, p) in parents.iter().enumerate() {
        if let Some(p) = *p {
            children[next[p]] = i;
            next[p] += 1;
        }
    }
    (children, start)
}

/// The bones reachable from the roots, depth first, roots and siblings in the order given.
/// Bones on a cycle (or below one) are never reached, so the walk is shorter than `parents`.
pub(super) fn depth_first(parents: &[Option<usize>], children: &[usize], child_start: &[usize]) -> Vec<usize> {
    let n = parents.len();
    let mut order = Vec::with_capacity(n);
    let mut stack: Vec<usize> = (0..n).rev().filter(|&i| parents[i].is_none()).collect();
    // Each bone is pushed at most once (by its only parent, or as a root), so this ends.
    while let Some(i) = stack.pop() {
        order.push(i);
        stack.extend(children[child_start[i]..child_start[i + 1]].iter().rev());
    }
    order
}

/// The cycle through the first bone (in the order given) that lies on one. Called only when
/// the walk from the roots missed a bone: following parents from a missed bone never reaches a
/// root, so within `n` steps it enters a cycle.
pub(super) fn cycle_error(bones: &[Bone], parents: &[Option<usize>], reached: &[usize]) -> SkeletonError {
    let n = bones.len();
    let mut missed = vec![true; n];
    for &i in reached {
        missed[i] = false;
    }
    let on_cycle = |i: usize| {
        let mut j = i;
        for _ in 0..n {
            match parents[j] {
                Some(p) if p == i => return true,
                Some(p) => j = p,
                None => return false,
            }
        }
        false
    };
    let first = (0..n).find(|&i| missed[i] && on_cycle(i)).expect("ikarus: a missed bone lies below a cycle");
    let mut cycle = vec![bones[first].name.clone()];
    let mut j = first;
    // Back to `first` within `n` steps, since it lies on the cycle.
    for _ in 0..n {
        let Some(p) = parents[j] else { break };
        cycle.push(bones[p].name.clone());
        if p == first {
            break;
        }
        j = p;
    }
    SkeletonError::Cycle {
        index: first,
        name: bones[first].name.clone(),
        parent: bones[first].parent.clone().unwrap_or_default(),
        cycle,
    }
}

/// Every bone's root-to-bone path, flat, with offsets (`order` topological, so a parent's path
/// is known before its children's).
pub(super) fn paths_of(parents: &[Option<usize>], order: &[usize]) -> (Vec<usize>, Vec<usize>) {
    let n = parents.len();
    let mut depth = vec![0usize; n];
    for &i in order {
        depth[i] = parents[i].map_or(1, |p| depth[p] + 1);
    }
    let mut start = vec![0; n + 1];
    for i in 0..n {
        start[i + 1] = start[i] + depth[i];
    }
    let mut paths = vec![0; start[n]];
    for &i in order {
        let (s, e) = (start[i], start[i + 1]);
        if let Some(p) = parents[i] {
            let (ps, pe) = (start[p], start[p + 1]);
            paths.copy_within(ps..pe, s);
        }
        paths[e - 1] = i;
    }
    (paths, start)
}
