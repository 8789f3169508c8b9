//! What posing reads of a character, laid out flat once when the character is made: each
//! bone's parent and inherit mode side by side (a world update reads nothing else of the
//! bone), the setup pose's local transforms, lengths and constraint settings (a pose starts by
//! copying them), and, per constraint, its top bone and every bone below it in update order
//! (the bones its update recomputes, found once instead of by a scan of the bones after it).
//!
//! The lists are kept while they stay small: a chain with a constraint on every bone would
//! need n²/2 entries (200 MB for 10,000 bones), so past [`LISTED_PER_BONE`] entries a bone in
//! all, a constraint's update scans the bones after its top instead, which is the same bones in
//! the same order. Making the lists is linear in the bones and constraints.

use super::{CharacterBone, Inherit, LocalTransform};

/// A root bone's parent.
pub(crate) const ROOT: u32 = u32::MAX;

/// What a world update reads of a bone: its parent's index ([`ROOT`] for none) and its inherit
/// mode.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Link {
    pub(crate) parent: u32,
    pub(crate) inherit: Inherit,
}

/// A character's bones and constraints as posing reads them (see the module's doc).
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct Flat {
    pub(crate) links: Vec<Link>,
    pub(crate) setup: Vec<LocalTransform>,
    pub(crate) length: Vec<f64>,
    /// The subtrees, one after another.
    below: Vec<u32>,
    /// The top bones of the constraints whose updates are found by a scan of the bones strictly
    /// below them, one list after another.
    tops: Vec<u32>,
    /// Per constraint, the bones posing recomputes after it.
    steps: Vec<Step>,
}

/// Where a constraint's update is: its bones listed in `below[start..end]`, a top bone whose
/// subtree is found by a scan, or the bones strictly below `tops[start..end]` found by a scan.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Step {
    Listed(u32, u32),
    Subtree(u32),
    Under(u32, u32),
}

/// Which bones posing recomputes after a constraint has applied.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Updates<'a> {
    /// This bone and every bone below it (the constraint changed local transforms only).
    Subtree(usize),
    /// Every bone strictly below these (the constraint set these bones' world transforms).
    Below(&'a [usize]),
}

/// At most this many subtree entries a bone are kept (see the module's doc).
pub(crate) const LISTED_PER_BONE: usize = 16;

/// The bones posing recomputes after a constraint: listed, or found by a scan.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Subtree<'a> {
    /// The bones, in update order.
    Listed(&'a [u32]),
    /// A top bone; it and the bones below it are found by a scan of the bones after it.
    Below(usize),
    /// The bones strictly below these, found by a scan.
    Under(&'a [u32]),
}

impl Flat {
    /// The flat view of `bones` (parent first) and `constraints`.
    pub(crate) fn of<'a>(bones: &[CharacterBone], updates: impl IntoIterator<Item = Updates<'a>>) -> Flat {
        Flat::within(bones, updates, LISTED_PER_BONE * bones.len())
    }

    /// [`Flat::of`] keeping at most `budget` subtree entries.
    pub(crate) fn within<'a>(
        bones: &[CharacterBone],
        updates: impl IntoIterator<Item = Updates<'a>>,
        budget: usize,
    ) -> Flat {
        let mut flat = Flat {
            links: bones
                .iter()
                .map(|b| Link { parent: b.parent.map_or(ROOT, |p| p as u32), inherit: b.inherit })
                .collect(),
            setup: bones.iter().map(|b| b.setup).collect(),
            length: bones.iter().map(|b| b.length).collect(),
            ..Flat::default()
        };
        // Every bone's subtree size, children before parents.
        let mut size = vec![1usize; bones.len()];
        for (j, b) in bones.iter().enumerate().rev() {
            if let Some(p) = b.parent {
                size[p] += size[j];
            }
        }
        // Per bone, its subtree's range once listed; `Some(None)` once refused for the budget.
        let mut listed: Vec<Option<Option<(u32, u32)>>> = vec![None; bones.len()];
        for update in updates {
            match update {
                Updates::Subtree(top) => {
                    let range = *listed[top].get_or_insert_with(|| {
                        (flat.below.len() + size[top] <= budget).then(|| {
                            let start = flat.below.len() as u32;
                            flat.below.extend(subtree(&flat.links, top));
                            (start, flat.below.len() as u32)
                        })
                    });
                    flat.steps.push(range.map_or(Step::Subtree(top as u32), |(a, b)| Step::Listed(a, b)));
                }
                Updates::Below(tops) => {
                    let under = strictly_below(&flat.links, tops);
                    let range = (flat.below.len() + under.len() <= budget).then(|| {
                        let start = flat.below.len() as u32;
                        flat.below.extend(under);
                        (start, flat.below.len() as u32)
                    });
                    let step = range.map_or_else(
                        || {
                            let start = flat.tops.len() as u32;
                            flat.tops.extend(tops.iter().map(|&b| b as u32));
                            Step::Under(start, flat.tops.len() as u32)
                        },
                        |(a, b)| Step::Listed(a, b),
                    );
                    flat.steps.push(step);
                }
            }
        }
        flat
    }

    /// How many subtree entries are kept.
    #[cfg(test)]
    pub(crate) fn listed(&self) -> usize {
        self.below.len()
    }

    /// The bones posing recomputes after constraint `k`, in update order: an IK constraint's
    /// top bone (its one bone, or the parent of its two) and every bone below it; for a kind
    /// that sets world transforms, the bones strictly below its bones.
    #[inline]
    pub(crate) fn below(&self, k: usize) -> Subtree<'_> {
        match self.steps[k] {
            Step::Listed(start, end) => Subtree::Listed(&self.below[start as usize..end as usize]),
            Step::Subtree(top) => Subtree::Below(top as usize),
            Step::Under(start, end) => Subtree::Under(&self.tops[start as usize..end as usize]),
        }
    }
}

/// Bone `top` and every bone below it, in the bones' order (parents first): a bone is below
/// `top` when its parent is `top` or below it.
pub(crate) fn subtree(links: &[Link], top: usize) -> Vec<u32> {
    let mut below = vec![false; links.len()];
    below[top] = true;
    let mut out = vec![top as u32];
    for (j, link) in links.iter().enumerate().skip(top + 1) {
        let p = link.parent as usize;
        if link.parent != ROOT && p >= top && below[p] {
            below[j] = true;
            out.push(j as u32);
        }
    }
    out
}

/// Every bone strictly below one of `tops`, in the bones' order: a bone whose parent is one of
/// `tops` or strictly below one (a bone of `tops` below another one is listed).
pub(crate) fn strictly_below(links: &[Link], tops: &[usize]) -> Vec<u32> {
    let Some(&first) = tops.iter().min() else { return Vec::new() };
    let mut marked = vec![false; links.len()];
    for &t in tops {
        marked[t] = true;
    }
    let mut below = vec![false; links.len()];
    let mut out = Vec::new();
    for (j, link) in links.iter().enumerate().skip(first + 1) {
        let p = link.parent as usize;
        if link.parent != ROOT && p >= first && (marked[p] || below[p]) {
            below[j] = true;
            out.push(j as u32);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::character::world::{Bones, Trig, world_transform};
    use crate::character::{Affine, Placement};
    use crate::rng::SplitMix64;

    /// A random tree of `n` bones (parents earlier), every inherit mode.
    fn random_links(rng: &mut SplitMix64, n: usize) -> Vec<Link> {
        (0..n)
            .map(|i| Link {
                parent: if i == 0 || rng.chance(0.1) { ROOT } else { (rng.next_u64() % i as u64) as u32 },
                inherit: Inherit::ALL[(rng.next_u64() % 5) as usize],
            })
            .collect()
    }

    #[test]
    fn a_subtree_is_every_bone_whose_ancestors_reach_the_top_in_order() {
        let mut rng = SplitMix64(2027);
        for _ in 0..500 {
            let n = 1 + (rng.next_u64() % 40) as usize;
            let links = random_links(&mut rng, n);
            for top in 0..n {
                // By walking up from each bone, not by the scan.
                let reaches = |mut j: usize| loop {
                    if j == top {
                        return true;
                    }
                    match links[j].parent {
                        ROOT => return false,
                        p => j = p as usize,
                    }
                };
                let want: Vec<u32> = (0..n).filter(|&j| reaches(j)).map(|j| j as u32).collect();
                assert_eq!(subtree(&links, top), want, "top {top} of {links:?}");
            }
        }
    }

    #[test]
    fn a_bone_update_is_world_transform_bit_for_bit() {
        // Every bone of random trees, every inherit mode, random local transforms, a mirrored
        // and moved skeleton, memos warmed on the poses before: the lean update gives the bits
        // of `world_transform` applied parent first.
        let mut rng = SplitMix64(27);
        for round in 0..300 {
            let n = 1 + (rng.next_u64() % 30) as usize;
            let links = random_links(&mut rng, n);
            let placement = if round % 3 == 0 {
                Placement { position: [3.0, -1.0], scale: [-1.5, 0.75] }
            } else {
                Placement::default()
            };
            let (mut world, mut below, mut trig) =
                (vec![Affine::default(); n], vec![false; n], vec![[Trig::ZERO; 3]; n]);
            for _ in 0..3 {
                let mut local: Vec<LocalTransform> = (0..n)
                    .map(|_| LocalTransform {
                        x: rng.range(-5.0, 5.0),
                        y: rng.range(-5.0, 5.0),
                        rotation: if rng.chance(0.3) { 0.25 } else { rng.range(-4.0, 4.0) },
                        scale_x: rng.range(-2.0, 2.0),
                        scale_y: rng.range(-2.0, 2.0),
                        shear_x: if rng.chance(0.5) { 0.0 } else { rng.range(-1.0, 1.0) },
                        shear_y: if rng.chance(0.5) { 0.0 } else { rng.range(-1.0, 1.0) },
                    })
                    .collect();
                let mut bones = Bones {
                    bones: &[],
                    links: &links,
                    placement,
                    local: &mut local,
                    world: &mut world,
                    below: &mut below,
                    trig: &mut trig,
                };
                bones.update_all();
                let mut want: Vec<Affine> = Vec::with_capacity(n);
                for (i, link) in links.iter().enumerate() {
                    let parent = (link.parent != ROOT).then(|| want[link.parent as usize]);
                    want.push(world_transform(&bones.local[i], link.inherit, parent.as_ref(), placement));
                }
                assert_eq!(format!("{:?}", bones.world), format!("{want:?}"));
            }
        }
    }
}
