//! [`sample_skeleton`] against shapes known without it: the PRR arm of `examples/joints/prr.toml`
//! with free elbows reaches a stadium (a segment swept by an annulus), and with its limits on,
//! Monte-Carlo poses drawn inside the ranges land in occupied cells.

use super::super::sample_skeleton;
use super::*;
use crate::skeleton::{Bone, Skeleton};

/// `examples/joints/prr.toml`: a carriage sliding on `[-1, 1.5]` along +x, a shoulder on it at
/// `(0.15, 0.05)`, links 1.0 (`[0°, 170°]`) and 0.7 (`±150°`).
fn prr() -> Skeleton {
    let deg = |d: f64| d.to_radians();
    let limits = |lo: f64, hi: f64| JointLimits::new(lo, hi).unwrap();
    let bones = [
        Bone::new("carriage", 0.3, 0.0).prismatic(0.0).with_slide([1.0, 0.0]).with_limits(limits(-1.0, 1.5)),
        Bone::new("upper", 1.0, deg(70.0))
            .with_parent("carriage")
            .with_offset([0.15, 0.05])
            .with_limits(limits(0.0, deg(170.0))),
        Bone::new("lower", 0.7, deg(-40.0)).with_parent("upper").with_limits(limits(deg(-150.0), deg(150.0))),
    ];
    Skeleton::new([0.0, 0.0], &bones).unwrap()
}

/// Distance from `p` to the segment the shoulder runs along, and to its far end.
fn to_rail(p: Point2<f64>) -> (f64, f64) {
    let (a, b) = ([-0.85, 0.05], [1.65, 0.05]);
    let x = p.x.clamp(a[0], b[0]);
    let near = math::hypot(p.x - x, p.y - a[1]);
    let far = math::hypot(p.x - a[0], p.y - a[1]).max(math::hypot(p.x - b[0], p.y - b[1]));
    (near, far)
}

/// With the elbows free, the tip reaches every point whose distances to the rail's points
/// include one in `[0.3, 1.7]` (the two links' annulus about a shoulder on the rail): the
/// stadium of radius 1.7 about the rail, the hole of radius 0.3 about each shoulder filled by
/// the next ones (the rail is longer than 0.6). Area `π 1.7² + 2 · 1.7 · 2.5`.
#[test]
fn the_prr_arms_free_region_is_a_stadium() {
    let s = prr();
    let options = WorkspaceOptions { limits: false, ..WorkspaceOptions::default() };
    let ws = sample_skeleton(&s, 2, &options).unwrap();
    assert!(!ws.is_exact());
    let h = ws.cell_size();
    let (r1, r2) = (0.3, 1.7);
    let exact = PI * r2 * r2 + 2.0 * r2 * 2.5;
    let perimeter = TAU * r2 + 2.0 * 2.5;
    // Occupied by a touched cell: up to about 0.64 h per unit of perimeter more; missed cells
    // would make it less.
    let area = ws.area();
    assert!(area >= exact - 0.05 * h * perimeter && area <= exact + h * perimeter, "{area} vs {exact}, h {h}");
    let half_diagonal = h * std::f64::consts::FRAC_1_SQRT_2;
    for iy in 0..ws.resolution() {
        for ix in 0..ws.resolution() {
            let c = ws.cell_center(ix, iy);
            let (near, far) = to_rail(c);
            if ws.is_occupied(ix, iy) {
                // Sound: the cell holds a reachable point, so its centre is within half a
                // diagonal of the region.
                assert!(near <= r2 + half_diagonal && far >= r1 - half_diagonal, "cell {ix},{iy} at {c:?}");
            } else {
                // Complete: a centre two cells inside the region is never missed.
                assert!(!(near <= r2 - 2.0 * h && far >= r1 + 2.0 * h), "missed cell {ix},{iy} at {c:?}");
            }
        }
    }
    // Every occupied cell lies within the body's reach.
    let reach = s.max_reach();
    for iy in 0..ws.resolution() {
        for ix in 0..ws.resolution() {
            if ws.is_occupied(ix, iy) {
                assert!(math::distance_between(ws.cell_center(ix, iy), s.base()) <= reach + half_diagonal);
            }
        }
    }
}

/// With the limits on, tips of poses drawn uniformly inside the ranges (an independent
/// Monte-Carlo sample) land in occupied cells, all but a sliver along the boundary; and the same
/// bits whatever the threads.
#[test]
fn monte_carlo_tips_within_the_limits_land_in_occupied_cells() {
    let s = prr();
    let ws = sample_skeleton(&s, 2, &WorkspaceOptions::default()).unwrap();
    let threaded = sample_skeleton(&s, 2, &WorkspaceOptions { parallel: true, ..WorkspaceOptions::default() });
    assert_eq!(threaded.unwrap(), ws);
    let mut rng = Rng(7);
    let (mut points, mut dirs) = (vec![Point2::origin(); 4], vec![0.0; 3]);
    let draws = 200_000;
    let mut missed = 0;
    for _ in 0..draws {
        let q = [
            rng.range(-1.0, 1.5),
            rng.range(0.0, 170f64.to_radians()),
            rng.range(-150f64.to_radians(), 150f64.to_radians()),
        ];
        s.points_into(&q, &mut points, &mut dirs);
        missed += usize::from(!ws.contains(points[3]));
    }
    assert!(missed * 1000 <= draws, "{missed} of {draws} Monte-Carlo tips in empty cells");
    // The limits cut the free stadium down.
    let free = sample_skeleton(&s, 2, &WorkspaceOptions { limits: false, ..WorkspaceOptions::default() }).unwrap();
    assert!(ws.area() < 0.9 * free.area(), "{} vs {}", ws.area(), free.area());
}

/// A bone's tip inside the tree: the carriage's own tip runs along the rail only (a segment,
/// cells along one row), whatever the joints after it.
#[test]
fn the_region_of_an_inner_bone_ignores_the_bones_after_it() {
    let ws = sample_skeleton(&prr(), 0, &WorkspaceOptions::default()).unwrap();
    let rows: Vec<usize> = ws.rows().enumerate().filter(|(_, r)| r.iter().any(|&c| c)).map(|(i, _)| i).collect();
    assert_eq!(rows.len(), 1, "{rows:?}");
    let h = ws.cell_size();
    let cells = ws.occupied_cells() as f64;
    assert!((cells * h - 2.5).abs() <= 2.0 * h, "{cells} cells of {h}");
}
