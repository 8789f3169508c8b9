//! The tree's structure, computed once when a skeleton is built: children, a topological
//! walk, each bone's place in it and the end of its subtree there, each bone's root, and the
//! cycle that stops a walk. Everything here is linear in the bones, in time and memory: no
//! bone's path from the root is stored (a chain of n bones would hold n²/2 entries).

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
/// root, so it enters a cycle.
///
/// Linear: each missed bone is walked from once, up to the first bone an earlier walk (or this
/// one) has seen; a walk that meets itself has found a cycle, and marks its bones.
pub(super) fn cycle_error(bones: &[Bone], parents: &[Option<usize>], reached: &[usize]) -> SkeletonError {
    const UNSEEN: usize = usize::MAX;
    let n = bones.len();
    // `walk[i]`: the walk that first saw bone i (`UNSEEN` for none; reached bones count as seen).
    let mut walk = vec![UNSEEN; n];
    for &i in reached {
        walk[i] = n;
    }
    let mut on_cycle = vec![false; n];
    for start in 0..n {
        let mut j = start;
        let closed = loop {
            if walk[j] != UNSEEN {
                break walk[j] == start;
            }
            walk[j] = start;
            match parents[j] {
                Some(p) => j = p,
                // A root (always reached, so not met here).
                None => break false,
            }
        };
        if closed {
            // This walk came back to a bone of its own: j lies on a cycle; mark it round.
            let mut k = j;
            loop {
                on_cycle[k] = true;
                k = parents[k].expect("a bone on a cycle has a parent");
                if k == j {
                    break;
                }
            }
        }
    }
    let first = (0..n).find(|&i| on_cycle[i]).expect("ikarus: a missed bone lies below a cycle");
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

/// Where each bone's subtree lies in the depth-first `order`: bone `i` at `order[enter[i]]`,
/// its descendants right after it, up to (not including) `order[leave[i]]`. Bone `j` lies on
/// bone `i`'s path from the root exactly when `enter[j] <= enter[i] < leave[j]`.
pub(super) fn subtrees_of(parents: &[Option<usize>], order: &[usize]) -> (Vec<usize>, Vec<usize>) {
    let n = parents.len();
    let mut enter = vec![0; n];
    for (k, &i) in order.iter().enumerate() {
        enter[i] = k;
    }
    // Subtree sizes, children before parents.
    let mut size = vec![1usize; n];
    for &i in order.iter().rev() {
        if let Some(p) = parents[i] {
            size[p] += size[i];
        }
    }
    let leave = (0..n).map(|i| enter[i] + size[i]).collect();
    (enter, leave)
}

/// The root above every bone (a root's is itself); `order` topological.
pub(super) fn roots_of(parents: &[Option<usize>], order: &[usize]) -> Vec<usize> {
    let mut root: Vec<usize> = (0..parents.len()).collect();
    for &i in order {
        if let Some(p) = parents[i] {
            root[i] = root[p];
        }
    }
    root
}
