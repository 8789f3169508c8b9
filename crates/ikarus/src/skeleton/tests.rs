use super::*;
use crate::{Chain, Link};

fn lim(a: f64, b: f64) -> JointLimits {
    JointLimits::new(a, b).unwrap()
}

/// A small figure: a pelvis with a spine and head above, two legs from the base.
fn figure() -> Vec<Bone> {
    vec![
        Bone::new("pelvis", 0.2, 1.5),
        Bone::new("head", 0.3, 0.0).with_parent("spine"),
        Bone::new("spine", 0.5, 0.1).with_parent("pelvis").with_limits(lim(-0.5, 0.5)),
        Bone::new("left", 0.9, -1.5),
        Bone::new("right", 0.9, -1.6),
        Bone::new("left_foot", 0.2, 1.5).with_parent("left"),
    ]
}

#[test]
fn builds_a_tree_and_answers_questions_about_it() {
    let s = Skeleton::new([1.0, 2.0], &figure()).unwrap();
    assert_eq!(s.len(), 6);
    assert!(!s.is_empty());
    assert_eq!(s.base(), Point2::new(1.0, 2.0));
    assert_eq!(s.names()[1], "head");
    assert_eq!((s.index_of("spine"), s.index_of("tail")), (Some(2), None));
    assert_eq!(s.parents(), &[None, Some(2), Some(0), None, None, Some(3)]);
    assert_eq!(s.parent(5), Some(3));
    assert_eq!(s.children(0).collect::<Vec<_>>(), [2]);
    assert_eq!(s.children(1).len(), 0);
    assert_eq!(s.roots().collect::<Vec<_>>(), [0, 3, 4]);
    // Depth first from the roots in the order given.
    assert_eq!(s.topological_order(), &[0, 2, 1, 3, 5, 4]);
    assert_eq!((s.path(1), s.path(5), s.path(4)), (vec![0, 2, 1], vec![3, 5], vec![4]));
    assert_eq!(s.start_angles(), &[1.5, 0.0, 0.1, -1.5, -1.6, 1.5]);
    assert_eq!(s.lengths(), &[0.2, 0.3, 0.5, 0.9, 0.9, 0.2]);
    assert!(s.has_limits() && s.bounds().get(2) == Some(lim(-0.5, 0.5)) && s.bounds().get(0).is_none());
    // The longest path: left + left_foot = 1.1 (pelvis + spine + head = 1.0).
    assert!((s.max_reach() - 1.1).abs() < 1e-15);
    assert_eq!(s.bones(), figure());
    assert_eq!(s.name(4), "right");
}

#[test]
fn every_parent_comes_before_its_children() {
    let s = Skeleton::new([0.0, 0.0], &figure()).unwrap();
    let order = s.topological_order();
    let mut seen = vec![false; s.len()];
    for &i in order {
        assert!(s.parent(i).is_none_or(|p| seen[p]), "{order:?}");
        seen[i] = true;
    }
    assert!(seen.iter().all(|&b| b));
}

#[test]
fn a_chain_is_a_skeleton_of_one_branch() {
    let chain =
        Chain::new([0.5, 0.0], &[Link::new(3.0, 0.1), Link::new(2.0, 0.2).with_limits(lim(-1.0, 1.0))]).unwrap();
    let s = chain.skeleton();
    assert_eq!(s.names(), &["link0", "link1"]);
    assert_eq!(s.parents(), &[None, Some(0)]);
    assert_eq!(s.topological_order(), &[0, 1]);
    assert!(s.is_chain() && s.is_plain() && !s.has_rest_pose());
    assert_eq!(
        (s.base(), s.lengths(), s.limits(), s.start_angles()),
        (chain.base(), chain.lengths(), chain.limits(), chain.start_pose().angles())
    );
    assert_eq!(s.max_reach(), chain.max_reach());
    // The same as the rig written by hand, names aside.
    let by_hand = crate::fixtures::chain_written_as_rig(&chain);
    assert_eq!(by_hand.bones().iter().map(|b| (b.length, b.angle, b.limits)).collect::<Vec<_>>(), {
        s.bones().iter().map(|b| (b.length, b.angle, b.limits)).collect::<Vec<_>>()
    });
    // A chain at the largest reach is a skeleton too (the same sum, the same check).
    let widest = Chain::new([0.0, 0.0], &[Link::new(5e151, 0.0), Link::new(5e151, 0.0)]).unwrap();
    assert_eq!(widest.skeleton().max_reach(), MAX_REACH);
    // And back: the chain view of a one-branch skeleton is the chain, its bones keeping their
    // names (so the hand-written rig's view is another chain, equal but for the names).
    assert_eq!(s.as_chain(), Some(chain.clone()));
    assert_eq!(Chain::try_from(Skeleton::from(widest.clone())), Ok(widest));
    let view = by_hand.as_chain().unwrap();
    assert_eq!(view.skeleton().names(), &["upper0", "upper1"]);
    assert_eq!((view.links(), view.base()), (chain.links(), chain.base()));
    assert_ne!(view, chain);
}

#[test]
fn only_a_plain_branch_in_order_has_a_chain_view() {
    let a = Bone::new("a", 1.0, 0.2);
    let b = Bone::new("b", 1.0, 0.3).with_parent("a");
    let view = |bones: &[Bone]| Skeleton::new([0.0, 0.0], bones).unwrap().as_chain();
    let chain = view(&[a.clone(), b.clone()]).unwrap();
    assert_eq!((chain.lengths(), chain.start_pose().angles()), (&[1.0, 1.0][..], &[0.2, 0.3][..]));
    // Given child first, forked, offset, sliding, stiff: no chain (and the skeleton back).
    let child_first = Skeleton::new([0.0, 0.0], &[b.clone(), a.clone()]).unwrap();
    assert_eq!(Chain::try_from(child_first.clone()), Err(child_first));
    assert_eq!(view(&[b.clone(), a.clone()]), None);
    assert_eq!(view(&[a.clone(), b.clone(), Bone::new("c", 1.0, 0.0).with_parent("a")]), None);
    assert_eq!(view(&[a.clone(), b.clone().with_offset([0.5, 0.0])]), None);
    assert_eq!(view(&[a.clone(), b.clone().prismatic(0.0)]), None);
    assert_eq!(view(&[a.clone().with_stiffness(1.0), b]), None);
}

#[test]
fn rejects_each_kind_of_bad_input_naming_the_bone_and_the_value() {
    let b = |name: &str, parent: Option<&str>| {
        let bone = Bone::new(name, 1.0, 0.0);
        match parent {
            Some(p) => bone.with_parent(p),
            None => bone,
        }
    };
    let cases: Vec<(Vec<Bone>, [f64; 2], &str)> = vec![
        (vec![], [0.0, 0.0], "bones: a skeleton needs at least one bone, got none"),
        (vec![b("a", None)], [f64::NAN, 1.0], "base: coordinates must be finite, got (NaN, 1)"),
        (vec![b("a", None), b("", None)], [0.0, 0.0], "bones[1].name: must not be empty"),
        (
            vec![b("a", None), b("b", Some("a")), b("a", Some("b"))],
            [0.0, 0.0],
            "bones[2] (\"a\").name: the name of bones[0] already; names must be unique",
        ),
        (
            vec![b("a", None), Bone::new("b", 0.0, 0.0)],
            [0.0, 0.0],
            "bones[1] (\"b\").length: must be greater than 0, got 0",
        ),
        (vec![Bone::new("a", -1e300, 0.0)], [0.0, 0.0], "bones[0] (\"a\").length: must be greater than 0, got -1e300"),
        (
            vec![Bone::new("a", f64::INFINITY, 0.0)],
            [0.0, 0.0],
            "bones[0] (\"a\").length: must be a finite number, got inf",
        ),
        (
            vec![b("pelvis", None), b("spine", Some("pelvs"))],
            [0.0, 0.0],
            "bones[1] (\"spine\").parent = \"pelvs\": no bone of that name",
        ),
        (
            vec![b("a", Some("a"))],
            [0.0, 0.0],
            "bones[0] (\"a\").parent = \"a\": a cycle (a → a); a bone cannot be its own ancestor",
        ),
        // The root is fine; c → d → e → c is a cycle, and f hangs below it.
        (
            vec![b("r", None), b("f", Some("d")), b("c", Some("e")), b("d", Some("c")), b("e", Some("d"))],
            [0.0, 0.0],
            "bones[2] (\"c\").parent = \"e\": a cycle (c → e → d → c); a bone cannot be its own ancestor",
        ),
        (
            vec![b("a", None), Bone::new("b", 1.0, f64::NAN).with_parent("a")],
            [0.0, 0.0],
            "bones[1] (\"b\").angle: must be a finite number, got NaN",
        ),
        (
            vec![b("a", None), Bone::new("b", 1.0, 2.0).with_parent("a").with_limits(lim(-1.0, 1.0))],
            [0.0, 0.0],
            "bones[1] (\"b\").angle: 2 rad lies outside the limits [-1, 1] rad",
        ),
        // Issue 25: offsets and prismatic joints.
        (
            vec![b("a", None), b("b", Some("a")).with_offset([f64::NAN, 0.0])],
            [0.0, 0.0],
            "bones[1] (\"b\").offset: must be finite numbers, got [NaN, 0]",
        ),
        (
            vec![b("a", None), b("s", Some("a")).with_slide([0.0, 0.0])],
            [0.0, 0.0],
            "bones[1] (\"s\").slide: must not be zero, got [0, 0]",
        ),
        (
            vec![b("s", None).with_slide([1.0, f64::INFINITY])],
            [0.0, 0.0],
            "bones[0] (\"s\").slide: must be finite numbers, got [1, inf]",
        ),
        (
            vec![b("a", None), b("s", Some("a")).prismatic(0.5).with_limits(lim(-0.2, 0.3))],
            [0.0, 0.0],
            "bones[1] (\"s\").extension: 0.5 lies outside the limits [-0.2, 0.3]",
        ),
        (
            vec![b("s", None).prismatic(f64::NAN)],
            [0.0, 0.0],
            "bones[0] (\"s\").extension: must be a finite number, got NaN",
        ),
        // Each path is within the reach, but the longest is not.
        (
            vec![Bone::new("a", 1e152, 0.0), Bone::new("b", 1e152, 0.0), Bone::new("c", 1e140, 0.0).with_parent("a")],
            [0.0, 0.0],
            "bones: the longest path of lengths reaches 1.0000000000010001e152 from the origin, beyond 1e152",
        ),
        (
            vec![Bone::new("a", 1e152, 0.0), Bone::new("b", 1e152, 0.0).with_parent("a")],
            [0.0, 0.0],
            "bones: the longest path of lengths reaches 2e152 from the origin, beyond 1e152, the largest reach",
        ),
        (vec![b("a", None)], [f64::MAX, f64::MAX], "bones: the longest path of lengths reaches inf"),
    ];
    for (bones, base, want) in cases {
        let err = Skeleton::new(base, &bones).unwrap_err().to_string();
        assert!(err.starts_with(want), "got {err:?}, want prefix {want:?}");
    }
}

#[test]
fn siblings_share_the_reach_of_the_longest() {
    // Two branches of 1e152 each from the base: each path is 1e152, within the cap.
    let s = Skeleton::new([0.0, 0.0], &[Bone::new("a", 1e152, 0.0), Bone::new("b", 1e152, 0.0)]).unwrap();
    assert_eq!(s.max_reach(), 1e152);
}

#[test]
fn angles_are_checked_against_the_skeleton() {
    let s = Skeleton::new([0.0, 0.0], &figure()).unwrap();
    assert!(s.check_angles(&[0.0; 6]).is_ok());
    assert_eq!(s.check_angles(&[0.0; 5]), Err(SkeletonError::AnglesLength { expected: 6, got: 5 }));
    let mut bad = [0.0; 6];
    bad[2] = 0.6;
    assert_eq!(
        s.check_angles(&bad).unwrap_err().to_string(),
        "bones[2] (\"spine\").angle: 0.6 rad lies outside the limits [-0.5, 0.5] rad"
    );
    assert!(s.check_angles_ignoring_limits(&bad).is_ok());
    bad[3] = f64::INFINITY;
    assert!(s.check_angles_ignoring_limits(&bad).is_err());
}

/// A chain of `n` bones, each hanging on the one before, written last bone first (so that the
/// order given is not topological).
fn long_chain(n: usize) -> Vec<Bone> {
    (0..n)
        .rev()
        .map(|i| {
            let bone = Bone::new(format!("b{i}"), 1e-3, 0.01);
            if i == 0 { bone } else { bone.with_parent(format!("b{}", i - 1)) }
        })
        .collect()
}

/// Issue 24: a skeleton kept every bone's path from the root, n²/2 entries: a chain of 100 000
/// bones asked for 40 GB and aborted. Its structure is linear in the bones now, and answers
/// the same questions.
#[test]
fn a_long_chain_is_built_in_memory_linear_in_its_bones() {
    let n = 100_000;
    let s = Skeleton::new([0.0, 0.0], &long_chain(n)).unwrap();
    let (first, last) = (s.index_of("b0").unwrap(), s.index_of(&format!("b{}", n - 1)).unwrap());
    assert_eq!((first, last), (n - 1, 0));
    assert_eq!(s.root_of(last), first);
    assert!(s.is_on_path(first, last) && !s.is_on_path(last, first) && s.is_on_path(last, last));
    let path = s.path(last);
    assert_eq!((path.len(), path[0], path[n - 1]), (n, first, last));
    assert!(path.windows(2).all(|w| s.parent(w[1]) == Some(w[0])));
    assert!((s.max_reach() - n as f64 * 1e-3).abs() < 1e-9);
    // Forward kinematics walks it: the tip of a slowly curling chain.
    let mut tips = vec![Point2::origin(); n];
    let (mut starts, mut dirs) = (tips.clone(), vec![0.0; n]);
    s.forward_into(s.start_angles(), &mut starts, &mut tips, &mut dirs);
    assert!((dirs[last] - s.direction(s.start_angles(), last)).abs() < 1e-9);
}

/// A long tail hanging below a cycle, tail first: found in one walk per bone, not one per
/// bone per bone, and named as before (the first bone on the cycle in the order given).
#[test]
fn a_cycle_below_a_long_tail_is_named() {
    let n = 50_000;
    let mut bones: Vec<Bone> =
        (0..n).map(|i| Bone::new(format!("t{i}"), 1.0, 0.0).with_parent(format!("t{}", i + 1))).collect();
    bones.push(Bone::new(format!("t{n}"), 1.0, 0.0).with_parent("x"));
    bones.push(Bone::new("x", 1.0, 0.0).with_parent(format!("t{n}")));
    bones.push(Bone::new("root", 1.0, 0.0));
    let e = Skeleton::new([0.0, 0.0], &bones).unwrap_err().to_string();
    assert_eq!(
        e,
        format!("bones[{n}] (\"t{n}\").parent = \"x\": a cycle (t{n} → x → t{n}); a bone cannot be its own ancestor")
    );
}

/// Random forests, in a shuffled order.
fn forests() -> impl proptest::strategy::Strategy<Value = Skeleton> {
    use proptest::prelude::*;
    (1usize..=30, any::<u64>()).prop_map(|(n, seed)| {
        let mut rng = crate::rng::SplitMix64(seed);
        let mut bones: Vec<(f64, Bone)> = (0..n)
            .map(|i| {
                let bone = Bone::new(format!("b{i}"), 1.0, 0.0);
                // About one bone in five is a root.
                let parent = (i > 0 && rng.unit() > 0.2).then(|| format!("b{}", (rng.unit() * i as f64) as usize % i));
                (rng.unit(), Bone { parent, ..bone })
            })
            .collect();
        bones.sort_by(|a, b| a.0.total_cmp(&b.0));
        Skeleton::new([0.0, 0.0], &bones.into_iter().map(|(_, b)| b).collect::<Vec<_>>()).unwrap()
    })
}

proptest::proptest! {
    /// The constant-time answers agree with the path walked along the parents.
    #[test]
    fn paths_roots_and_ancestry_agree(s in forests()) {
        for i in 0..s.len() {
            let path = s.path(i);
            let mut up: Vec<usize> = s.path_to_root(i).collect();
            up.reverse();
            proptest::prop_assert_eq!(&path, &up);
            proptest::prop_assert_eq!(*path.last().unwrap(), i);
            proptest::prop_assert!(s.parent(path[0]).is_none());
            proptest::prop_assert_eq!(s.root_of(i), path[0]);
            for j in 0..s.len() {
                proptest::prop_assert_eq!(s.is_on_path(j, i), path.contains(&j), "bone {} on the path of {}", j, i);
            }
        }
    }
}
