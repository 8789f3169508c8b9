//! Whole grids: exact cases against brute-force references, soundness, coverage, determinism,
//! options and geometry.

use super::*;
use crate::math;

/// For two joints the grid is exactly the set of cells whose centre is reachable.
#[test]
fn two_links_are_exact() {
    let cases = [
        (vec![2.0, 1.3], Some(((-30.0_f64, 100.0_f64), (-150.0_f64, 20.0_f64)))),
        (vec![1.0, 1.0], Some(((10.0, 300.0), (-170.0, 170.0)))),
        (vec![1.0, 2.5], Some(((-90.0, -89.0), (0.0, 180.0)))),
        (vec![3.0, 1.0], None),
    ];
    for (lengths, limits) in cases {
        let mut links: Vec<Link> = lengths.iter().map(|&l| Link::new(l, 0.0)).collect();
        let (r1, r2) = match limits {
            Some(((a0, a1), (b0, b1))) => {
                links[0] = Link::new(lengths[0], a0.to_radians()).with_limits(lim(a0, a1));
                links[1] = Link::new(lengths[1], b0.to_radians()).with_limits(lim(b0, b1));
                ((a0.to_radians(), a1.to_radians()), (b0.to_radians(), b1.to_radians()))
            }
            None => ((0.0, TAU), (0.0, TAU)),
        };
        let chain = Chain::new([0.25, -0.5], &links).unwrap();
        // Forced through the sampler even when both joints are free.
        let ws = run(&chain, &options(128), &|_, _| {}, true).unwrap();
        assert_eq!(ws.samples(), 1);
        assert!(ws.is_exact());
        let mut decided = 0;
        for iy in 0..128 {
            for ix in 0..128 {
                let c = ws.cell_center(ix, iy);
                let (want, margin) = reference([0.25, -0.5], lengths[0], lengths[1], r1, r2, [c.x, c.y]);
                if margin < 1e-9 {
                    continue;
                }
                decided += 1;
                assert_eq!(ws.is_occupied(ix, iy), want, "{lengths:?} cell ({ix}, {iy}) at {c:?}");
            }
        }
        // No cell centre of these cases lies within 1e-9 of the boundary: every cell is checked.
        assert_eq!(decided, 128 * 128, "{lengths:?}: cells checked");
        assert!(ws.occupied_cells() > 0);
    }
}

/// For three joints the grid is the union of the reference slices at the evenly spaced first
/// joint angles, ends included.
#[test]
fn three_links_match_a_brute_force_reference() {
    let chain = seed_arm();
    let (n, res) = (40u64, 48u32);
    let ws = sample(&chain, &WorkspaceOptions { samples: Some(n), ..options(res) }).unwrap();
    let (lo, hi) = (-PI / 4.0, PI / 4.0);
    let r2 = (-PI / 2.0, PI / 2.0);
    let r3 = (-170f64.to_radians(), 170f64.to_radians());
    let mut decided = 0;
    for iy in 0..res {
        for ix in 0..res {
            let c = ws.cell_center(ix, iy);
            let mut want = false;
            let mut margin = f64::INFINITY;
            for j in 0..n {
                let t1 = lo + (hi - lo) * j as f64 / (n - 1) as f64;
                let p = [3.0 * math::cos(t1), 3.0 * math::sin(t1)];
                let (hit, m) = reference(p, 2.0, 1.0, (t1 + r2.0, t1 + r2.1), r3, [c.x, c.y]);
                want |= hit;
                margin = margin.min(m);
            }
            if margin < 1e-9 {
                continue;
            }
            decided += 1;
            assert_eq!(ws.is_occupied(ix, iy), want, "cell ({ix}, {iy}) at {c:?}");
        }
    }
    assert!(decided > 2000, "{decided}");
}

/// Without limits the region is the annulus. [`sample`] rasterises it directly; the sampler,
/// forced to run anyway, matches its area within 1 % and classifies every cell whose centre
/// is clearly inside or outside accordingly.
#[test]
fn free_area_matches_the_annulus() {
    for (name, chain) in [("seed arm (3, 2, 1)", seed_arm()), ("(5, 1, 1)", free(&[5.0, 1.0, 1.0]))] {
        let opts = WorkspaceOptions { limits: false, ..options(256) };
        let exact = sample(&chain, &opts).unwrap();
        let sampled = run(&chain, &opts, &|_, _| {}, true).unwrap();
        assert!(exact.is_exact() && !sampled.is_exact());
        assert_eq!((exact.samples(), sampled.samples()), (0, WorkspaceOptions::automatic_samples(1)));
        let ann = exact.annulus();
        for ws in [&exact, &sampled] {
            let err = (ws.area() - ann.area()) / ann.area();
            eprintln!(
                "{name}, {}: area {:.5}, annulus {:.5}, error {:+.4} %",
                if ws.is_exact() { "exact" } else { "sampled" },
                ws.area(),
                ann.area(),
                100.0 * err
            );
            assert!(err.abs() < 0.01, "{err}");
        }
        for iy in 0..256 {
            for ix in 0..256 {
                let d = (exact.cell_center(ix, iy) - ann.center).norm();
                assert_eq!(exact.is_occupied(ix, iy), ann.inner <= d && d <= ann.outer);
                if d < ann.outer - 1e-4 && d > ann.inner + 1e-4 {
                    assert!(sampled.is_occupied(ix, iy), "{name} ({ix}, {iy}) at {d}");
                } else if d > ann.outer + 1e-9 || d < ann.inner - 1e-9 {
                    assert!(!sampled.is_occupied(ix, iy), "{name} ({ix}, {iy}) at {d}");
                }
            }
        }
    }
}

#[test]
fn limited_region_lies_in_the_annulus_and_is_smaller() {
    let ws = sample(&seed_arm(), &options(256)).unwrap();
    let ann = ws.annulus();
    let mut occupied = 0;
    for (iy, row) in ws.rows().enumerate() {
        for (ix, &cell) in row.iter().enumerate() {
            if cell {
                occupied += 1;
                let d = (ws.cell_center(ix as u32, iy as u32) - ann.center).norm();
                assert!(d <= ann.outer + 1e-9 && d >= ann.inner - 1e-9, "({ix}, {iy}) at {d}");
            }
        }
    }
    assert_eq!(occupied, ws.occupied_cells());
    eprintln!("seed arm with limits: area {:.4} of the annulus's {:.4}", ws.area(), ann.area());
    assert!(ws.area() > 0.2 * ann.area() && ws.area() < 0.8 * ann.area(), "{}", ws.area());
}

/// Tips of random in-limit poses are marked, except where the tip's cell centre is not
/// reachable (the centre rule: within about half a cell of the boundary), so not quite all.
/// For the seed arm every unmarked tip is checked: its cell centre must be unreachable, or
/// reachable only within the sampling step of the boundary, by a search over the first joint
/// 16 times finer than the sample.
#[test]
fn known_reachable_points_are_marked() {
    let r2 = (-PI / 2.0, PI / 2.0);
    let r3 = (-170f64.to_radians(), 170f64.to_radians());
    let n = WorkspaceOptions::automatic_samples(1);
    // Tip travel between neighbouring samples of the first joint.
    let step = 6.0 * (PI / 2.0) / (n - 1) as f64;
    for (name, chain, min_rate) in [("seed", seed_arm(), 0.995), ("seven", seven(), 0.99)] {
        let ws = sample(&chain, &options(256)).unwrap();
        let mut rng = Rng(11);
        let total = 2000;
        let mut marked = 0;
        for _ in 0..total {
            let tip = end_effector(&chain, &random_pose(&chain, &mut rng)).position;
            if ws.contains(tip) {
                marked += 1;
                continue;
            }
            if name == "seed" {
                let (ix, iy) = ws.cell_of(tip).unwrap();
                let c = ws.cell_center(ix, iy);
                let fine = 16 * n;
                let robust = (0..=fine).any(|j| {
                    let t1 = -PI / 4.0 + (PI / 2.0) * j as f64 / fine as f64;
                    let p = [3.0 * math::cos(t1), 3.0 * math::sin(t1)];
                    let (hit, margin) = reference(p, 2.0, 1.0, (t1 + r2.0, t1 + r2.1), r3, [c.x, c.y]);
                    hit && margin > step
                });
                assert!(!robust, "tip {tip:?}: centre {c:?} of its cell is reachable but not marked");
            }
        }
        let rate = f64::from(marked) / f64::from(total);
        eprintln!("{name}: {marked} of {total} reachable tips marked ({:.2} %)", 100.0 * rate);
        assert!(rate >= min_rate, "{name}: {rate}");
    }
}

/// A denser sample only adds cells near the boundary: the default sample already holds all
/// but a sliver of what sixteen times as many samples find.
#[test]
fn denser_sampling_adds_little() {
    let chain = seed_arm();
    let coarse = sample(&chain, &WorkspaceOptions { samples: Some(513), ..options(128) }).unwrap();
    let dense = sample(&chain, &WorkspaceOptions { samples: Some(8193), ..options(128) }).unwrap();
    // 8192 = 16 · 512 intervals: the coarse angles are among the dense ones.
    for (c, d) in coarse.rows().flatten().zip(dense.rows().flatten()) {
        assert!(!c || *d);
    }
    let extra = dense.occupied_cells() - coarse.occupied_cells();
    eprintln!("16× samples add {extra} of {} cells", dense.occupied_cells());
    assert!((extra as f64) < 0.002 * dense.occupied_cells() as f64, "{extra}");
}

/// The automatic count grows with the sampled joints, and brings the seven-link arm (five
/// sampled joints) within 1 % of the area of 2²⁰ samples, which the old fixed default of 4096
/// misses by 5 %. At resolution 96 to stay quick in debug builds; there 2²⁰ samples are
/// converged (2²¹ and 2²² give the same area). The R_d sample does not depend on the count, so
/// each grid holds the smaller ones; and the densest still lies in the annulus.
#[test]
fn automatic_count_covers_many_joints() {
    let counts: Vec<u64> = [0, 1, 2, 3, 4, 5, 18, usize::MAX].map(WorkspaceOptions::automatic_samples).to_vec();
    assert_eq!(counts, [4096, 4096, 16_384, 65_536, 262_144, 262_144, 262_144, 262_144]);
    assert_eq!(sample(&seed_arm(), &options(64)).unwrap().samples(), 4096);

    let chain = seven();
    let auto = sample(&chain, &options(96)).unwrap();
    let old = sample(&chain, &WorkspaceOptions { samples: Some(4096), ..options(96) }).unwrap();
    let reference = sample(&chain, &WorkspaceOptions { samples: Some(1 << 20), ..options(96) }).unwrap();
    assert_eq!(auto.samples(), 262_144);
    let cells = |ws: &Workspace| ws.rows().flatten().copied().collect::<Vec<bool>>();
    let (old_cells, auto_cells, reference_cells) = (cells(&old), cells(&auto), cells(&reference));
    for ((&o, &a), &r) in old_cells.iter().zip(&auto_cells).zip(&reference_cells) {
        assert!((!o || a) && (!a || r));
    }
    let ann = reference.annulus();
    for iy in 0..96 {
        for ix in 0..96 {
            let d = (reference.cell_center(ix, iy) - ann.center).norm();
            assert!(!reference.is_occupied(ix, iy) || (ann.inner <= d && d <= ann.outer), "({ix}, {iy}) at {d}");
        }
    }
    let shortfall = |ws: &Workspace| (reference.area() - ws.area()) / reference.area();
    eprintln!(
        "seven-link arm at 96: reference {:.4}, automatic {:.4} ({:+.3} %), 4096 samples {:.4} ({:+.3} %)",
        reference.area(),
        auto.area(),
        -100.0 * shortfall(&auto),
        old.area(),
        -100.0 * shortfall(&old)
    );
    assert!(shortfall(&auto) < 0.01, "{}", shortfall(&auto));
    assert!(shortfall(&old) > 0.01, "{}", shortfall(&old));
}

#[test]
fn unreachable_points_are_not_marked() {
    let ws = sample(&seed_arm(), &options(256)).unwrap();
    for p in [(-5.0, 0.0), (-3.0, 0.5), (0.0, -5.5), (6.01, 0.0), (0.0, 6.5), (100.0, 0.0), (f64::NAN, 0.0)] {
        assert!(!ws.contains(Point2::new(p.0, p.1)), "{p:?}");
    }
    assert!(ws.contains(Point2::new(5.0, 0.0)) && ws.contains(Point2::new(3.0, 2.0)));
    let long = sample(&free(&[5.0, 1.0, 1.0]), &options(256)).unwrap();
    for p in [(0.0, 0.0), (2.8, 0.0), (-1.5, 1.5), (0.0, -2.85), (7.02, 0.0)] {
        assert!(!long.contains(Point2::new(p.0, p.1)), "{p:?}");
    }
    assert!(long.contains(Point2::new(0.0, 3.1)) && long.contains(Point2::new(-6.9, 0.0)));
    assert!(!long.is_occupied(256, 0) && !long.is_occupied(0, u32::MAX));
}

#[test]
fn same_options_same_grid_with_or_without_threads() {
    let mut four = seed_arm().links();
    four.push(Link::new(0.5, 0.0).with_limits(lim(-120.0, 120.0)));
    let four = Chain::new([1.0, 2.0], &four).unwrap();
    for chain in [seed_arm(), four, seven()] {
        let opts = WorkspaceOptions { seed: 5, samples: Some(1000), parallel: true, ..options(160) };
        let a = sample(&chain, &opts).unwrap();
        let b = sample(&chain, &opts).unwrap();
        let c = sample(&chain, &WorkspaceOptions { parallel: false, ..opts.clone() }).unwrap();
        assert!(a.occupied_cells() > 1000);
        assert_eq!(a, b);
        assert_eq!(a, c);
    }
    // The seed moves the quasi-random sample of five or more joints.
    let a = sample(&seven(), &WorkspaceOptions { samples: Some(500), ..options(128) }).unwrap();
    let b = sample(&seven(), &WorkspaceOptions { samples: Some(500), seed: 1, ..options(128) }).unwrap();
    assert_ne!(a, b);
}

/// Seven and twenty links, with limits and (forced through the sampler) without: every
/// occupied cell's centre lies in the annulus, so within the exact grid of the free chain.
/// With 4096 samples, to stay quick in debug builds (the automatic count is 262144 for both).
#[test]
fn long_chains_stay_in_the_annulus() {
    let mut rng = Rng(3);
    let twenty: Vec<Link> = (0..20)
        .map(|k| {
            Link::new(rng.range(0.2, 1.0), 0.0).with_limits(JointLimits::new(-1.0 - 0.05 * k as f64, 2.0).unwrap())
        })
        .collect();
    let twenty = Chain::new([-1.0, 3.0], &twenty).unwrap();
    let opts = WorkspaceOptions { samples: Some(4096), ..options(256) };
    for chain in [seven(), twenty] {
        let limited = sample(&chain, &opts).unwrap();
        let exact = sample(&chain, &WorkspaceOptions { limits: false, ..opts.clone() }).unwrap();
        let sampled = run(&chain, &WorkspaceOptions { limits: false, ..opts.clone() }, &|_, _| {}, true).unwrap();
        let ann = exact.annulus();
        assert!(exact.is_exact() && ((exact.area() - ann.area()) / ann.area()).abs() < 0.01);
        for ws in [&limited, &sampled] {
            assert!(ws.occupied_cells() > 1000, "{}", ws.occupied_cells());
            assert!(ws.area() < ann.area());
            for iy in 0..256 {
                for ix in 0..256 {
                    if ws.is_occupied(ix, iy) {
                        let d = (ws.cell_center(ix, iy) - ann.center).norm();
                        assert!(d <= ann.outer + 1e-9 && d >= ann.inner - 1e-9, "({ix}, {iy}) at {d}");
                        assert!(exact.is_occupied(ix, iy));
                    }
                }
            }
        }
    }
}

/// One link reaches a circle, which has no area; a locked last joint leaves a 2D region.
#[test]
fn degenerate_and_locked_chains() {
    let one_limited = Chain::new([0.0, 0.0], &[Link::new(2.0, 0.0).with_limits(lim(-90.0, 90.0))]).unwrap();
    let two_one_locked =
        Chain::new([0.0, 0.0], &[Link::new(2.0, 0.0), Link::new(1.0, 28f64.to_radians()).with_limits(lim(28.0, 28.0))])
            .unwrap();
    for chain in [free(&[2.0]), one_limited, two_one_locked] {
        let ws = sample(&chain, &options(64)).unwrap();
        assert_eq!((ws.occupied_cells(), ws.samples(), ws.area()), (0, 0, 0.0));
        assert!(ws.is_exact());
    }
    let locked = Chain::new(
        [0.0, 0.0],
        &[Link::new(2.0, 0.0), Link::new(1.0, 0.0), Link::new(1.0, 28f64.to_radians()).with_limits(lim(28.0, 28.0))],
    )
    .unwrap();
    let ws = sample(&locked, &options(256)).unwrap();
    // Two free joints with links 2 and |1 + e^{i 28°}|: an annulus.
    let w = math::hypot(1.0 + math::cos(28f64.to_radians()), math::sin(28f64.to_radians()));
    let want = PI * (math::square(2.0 + w) - math::square(2.0 - w));
    assert!(((ws.area() - want) / want).abs() < 0.01, "{} vs {want}", ws.area());
    assert_eq!(ws.samples(), 1);
    assert!(ws.is_exact());
    // A joint narrower than a sixteenth of a cell is locked too, but then the grid is not
    // called exact.
    let mut links = locked.links();
    links[2] = Link::new(1.0, 28f64.to_radians()).with_limits(lim(28.0, 28.0001));
    let nearly = sample(&Chain::new([0.0, 0.0], &links).unwrap(), &options(256)).unwrap();
    assert_eq!(nearly.samples(), 1);
    assert!(!nearly.is_exact());
    assert!(((nearly.area() - want) / want).abs() < 0.01);
}

#[test]
fn bad_options_name_the_field() {
    let chain = seed_arm();
    let cases = [
        (WorkspaceOptions { resolution: 3, ..WorkspaceOptions::default() }, "resolution: must be in 8..=4096, got 3"),
        (
            WorkspaceOptions { resolution: 4097, ..WorkspaceOptions::default() },
            "resolution: must be in 8..=4096, got 4097",
        ),
        (
            WorkspaceOptions { samples: Some(0), ..WorkspaceOptions::default() },
            "samples: must be in 1..=1000000000, got 0",
        ),
        (
            WorkspaceOptions { samples: Some(1_000_000_001), ..WorkspaceOptions::default() },
            "samples: must be in 1..=1000000000, got 1000000001",
        ),
    ];
    for (opts, want) in cases {
        assert_eq!(sample(&chain, &opts).unwrap_err().to_string(), want);
    }
    assert!(WorkspaceOptions { resolution: 8, samples: Some(1), ..WorkspaceOptions::default() }.validate().is_ok());
    assert!(WorkspaceOptions::default().validate().is_ok());
}

#[test]
fn progress_runs_from_zero_to_total() {
    let calls = std::sync::Mutex::new(Vec::new());
    let opts = WorkspaceOptions { samples: Some(3000), parallel: false, ..options(64) };
    let ws = sample_with_progress(&seed_arm(), &opts, &|d, t| calls.lock().unwrap().push((d, t))).unwrap();
    let calls = calls.into_inner().unwrap();
    assert_eq!(calls.first(), Some(&(0, 3000)));
    assert_eq!(calls.last(), Some(&(3000, 3000)));
    assert!(calls.len() > 100 && calls.len() <= 1026, "{}", calls.len());
    assert!(calls.windows(2).all(|w| w[0].0 < w[1].0 && w[1].1 == 3000));
    assert_eq!(ws.samples(), 3000);
}

#[test]
fn grid_geometry_and_rows() {
    let chain = Chain::new([1.0, -1.0], &seed_arm().links()).unwrap();
    let ws = sample(&chain, &options(64)).unwrap();
    assert_eq!(ws.resolution(), 64);
    assert!((ws.cell_size() - 12.0 / 64.0).abs() <= 1e-15);
    assert_eq!(ws.origin(), Point2::new(-5.0, -7.0));
    assert_eq!(ws.rows().len(), 64);
    for (iy, row) in ws.rows().enumerate() {
        assert_eq!(row.len(), 64);
        for (ix, &cell) in row.iter().enumerate() {
            assert_eq!(cell, ws.is_occupied(ix as u32, iy as u32));
            assert_eq!(cell, ws.contains(ws.cell_center(ix as u32, iy as u32)));
        }
    }
    // Bottom row first: the arm reaches up to y = −1 + 5.x but never below y = −1 − 5.
    assert!(ws.rows().next().unwrap().iter().all(|&c| !c));
    assert_eq!(ws.cell_of(Point2::new(7.0, 5.0)), Some((63, 63)));
    assert_eq!(ws.cell_of(Point2::new(-5.0, -7.0)), Some((0, 0)));
    assert_eq!(ws.cell_of(Point2::new(7.0 + 1e-9, 0.0)), None);
    assert!(ws.limits());
}
