//! The edge of a sampled workspace as smooth closed curves, instead of the cells' staircase:
//! marching squares over the cell centres (each crossing half-way between an occupied and an
//! empty centre), the pieces joined into loops with the occupied side on their left (outer edges
//! counter-clockwise, holes clockwise: fill them with the even-odd rule), then neighbour
//! averaging and Chaikin's corner cutting. The playground's `areaOutline` (view.js) is the same
//! algorithm, step for step, so that the page and the pictures draw the same edge.

use std::collections::HashMap;

use nalgebra::Point2;

use super::Workspace;

/// Rounds of averaging each point with its two neighbours (¼, ½, ¼) before the corner cutting:
/// they iron out the ripple of the cells.
pub const OUTLINE_AVERAGING: u32 = 3;

/// Rounds of Chaikin's corner cutting of [`Workspace::outline`]'s default smoothing.
pub const OUTLINE_SMOOTHING: u32 = 2;

/// An edge between two cell centres: horizontal `(0, i, j)` between cells (i, j) and (i + 1, j),
/// vertical `(1, i, j)` between (i, j) and (i, j + 1). Indices start at −1 (the ring of empty
/// cells around the grid).
type Edge = (u8, i64, i64);

/// Which edges a square of four cell centres crosses, per case (occupied corners: bottom-left 1,
/// bottom-right 2, top-right 4, top-left 8), each walked with the occupied side on the left.
/// Edges: b(ottom), r(ight), t(op), l(eft).
const CROSSINGS: [&[(char, char)]; 16] = [
    &[],
    &[('b', 'l')],
    &[('r', 'b')],
    &[('r', 'l')],
    &[('t', 'r')],
    &[('b', 'l'), ('t', 'r')],
    &[('t', 'b')],
    &[('t', 'l')],
    &[('l', 't')],
    &[('b', 't')],
    &[('r', 'b'), ('l', 't')],
    &[('r', 't')],
    &[('l', 'r')],
    &[('b', 'r')],
    &[('l', 'b')],
    &[],
];

impl Workspace {
    /// The edge of the occupied cells as closed loops of world points, smoothed by
    /// [`OUTLINE_AVERAGING`] rounds of averaging and `smoothing` rounds of corner cutting
    /// (0: the raw marching-squares edge, no averaging either). Loops come in scan order (the
    /// lowest row first), so the result is deterministic. No occupied cell: no loop.
    #[must_use]
    pub fn outline(&self, smoothing: u32) -> Vec<Vec<Point2<f64>>> {
        let n = i64::from(self.resolution());
        let occupied =
            |i: i64, j: i64| (0..n).contains(&i) && (0..n).contains(&j) && self.is_occupied(i as u32, j as u32);
        let edge = |e: char, i: i64, j: i64| -> Edge {
            match e {
                'b' => (0, i, j),
                't' => (0, i, j + 1),
                'l' => (1, i, j),
                _ => (1, i + 1, j),
            }
        };
        let mut next: HashMap<Edge, Edge> = HashMap::new();
        let mut order: Vec<Edge> = Vec::new();
        for j in -1..n {
            for i in -1..n {
                let case = usize::from(occupied(i, j))
                    | usize::from(occupied(i + 1, j)) << 1
                    | usize::from(occupied(i + 1, j + 1)) << 2
                    | usize::from(occupied(i, j + 1)) << 3;
                for &(a, b) in CROSSINGS[case] {
                    let from = edge(a, i, j);
                    next.insert(from, edge(b, i, j));
                    order.push(from);
                }
            }
        }
        let cell = self.cell_size();
        let origin = self.origin();
        let point = |(kind, i, j): Edge| {
            // Half-way between the two cell centres the edge joins.
            let (cx, cy) = if kind == 0 { (i as f64 + 1.0, j as f64 + 0.5) } else { (i as f64 + 0.5, j as f64 + 1.0) };
            Point2::new(origin.x + cx * cell, origin.y + cy * cell)
        };
        let mut seen: HashMap<Edge, ()> = HashMap::with_capacity(order.len());
        let mut loops = Vec::new();
        for start in order {
            if seen.contains_key(&start) {
                continue;
            }
            let mut ring = Vec::new();
            let mut at = Some(start);
            // Each edge is visited once, so the walk ends within `next.len()` steps.
            while let Some(e) = at {
                if seen.insert(e, ()).is_some() {
                    break;
                }
                ring.push(point(e));
                at = next.get(&e).copied();
            }
            if smoothing > 0 {
                for _ in 0..OUTLINE_AVERAGING {
                    if ring.len() > 2 {
                        ring = average(&ring);
                    }
                }
            }
            for _ in 0..smoothing {
                if ring.len() > 2 {
                    ring = chaikin(&ring);
                }
            }
            if ring.len() > 2 {
                loops.push(ring);
            }
        }
        loops
    }
}

/// Each point of a closed loop averaged with its two neighbours (¼, ½, ¼).
fn average(ring: &[Point2<f64>]) -> Vec<Point2<f64>> {
    let m = ring.len();
    (0..m)
        .map(|k| {
            let (a, p, b) = (ring[(k + m - 1) % m], ring[k], ring[(k + 1) % m]);
            Point2::new(0.25 * a.x + 0.5 * p.x + 0.25 * b.x, 0.25 * a.y + 0.5 * p.y + 0.25 * b.y)
        })
        .collect()
}

/// One round of Chaikin's corner cutting on a closed loop: each side replaced by its points at
/// ¼ and ¾.
fn chaikin(ring: &[Point2<f64>]) -> Vec<Point2<f64>> {
    let m = ring.len();
    let mut out = Vec::with_capacity(2 * m);
    for k in 0..m {
        let (p, q) = (ring[k], ring[(k + 1) % m]);
        out.push(Point2::new(0.75 * p.x + 0.25 * q.x, 0.75 * p.y + 0.25 * q.y));
        out.push(Point2::new(0.25 * p.x + 0.75 * q.x, 0.25 * p.y + 0.75 * q.y));
    }
    out
}

#[cfg(test)]
mod tests {
    use crate::math;
    use crate::reach::WorkspaceOptions;
    use crate::{Chain, JointLimits, Link};

    /// Twice the signed area of a closed loop (shoelace), positive counter-clockwise.
    fn area(ring: &[nalgebra::Point2<f64>]) -> f64 {
        (0..ring.len())
            .map(|k| {
                let (p, q) = (ring[k], ring[(k + 1) % ring.len()]);
                p.x * q.y - q.x * p.y
            })
            .sum::<f64>()
            / 2.0
    }

    fn sharpest_turn_deg(ring: &[nalgebra::Point2<f64>]) -> f64 {
        let m = ring.len();
        (0..m)
            .map(|k| {
                let (a, b, c) = (ring[k], ring[(k + 1) % m], ring[(k + 2) % m]);
                let (u, v) = (b - a, c - b);
                math::atan2(u.x * v.y - u.y * v.x, u.dot(&v)).abs().to_degrees()
            })
            .fold(0.0, f64::max)
    }

    #[test]
    fn an_annulus_has_a_smooth_outer_edge_and_a_hole_on_its_radii() {
        // Links 3 and 1, free: the annulus between radii 2 and 4.
        let chain = Chain::new([0.0, 0.0], &[Link::new(3.0, 0.0), Link::new(1.0, 0.0)]).unwrap();
        let opts = WorkspaceOptions { resolution: 128, limits: false, parallel: false, ..WorkspaceOptions::default() };
        let ws = crate::reach::sample(&chain, &opts).unwrap();
        let loops = ws.outline(super::OUTLINE_SMOOTHING);
        assert_eq!(loops.len(), 2);
        let (outer, hole) = if area(&loops[0]) > 0.0 { (&loops[0], &loops[1]) } else { (&loops[1], &loops[0]) };
        assert!(area(outer) > 0.0 && area(hole) < 0.0, "outer counter-clockwise, the hole clockwise");
        let cell = ws.cell_size();
        for p in outer {
            assert!((p.coords.norm() - 4.0).abs() < cell, "outer edge at r = {}", p.coords.norm());
        }
        for p in hole {
            assert!((p.coords.norm() - 2.0).abs() < cell, "hole at r = {}", p.coords.norm());
        }
        let cells = ws.occupied_cells() as f64 * cell * cell;
        let filled = area(outer) + area(hole);
        assert!((filled - cells).abs() / cells < 0.02, "{filled} vs {cells}");
        // The raw edge turns 45° at cell corners; the smoothed one far less.
        let raw = ws.outline(0);
        assert!(raw.iter().map(|r| sharpest_turn_deg(r)).fold(0.0, f64::max) >= 45.0 - 1e-9);
        assert!(sharpest_turn_deg(outer) < 25.0, "{}", sharpest_turn_deg(outer));
        // The same workspace, the same loops, bit for bit.
        assert_eq!(ws.outline(2), loops);
    }

    /// The page draws the same edge: e2e/view.test.mjs asserts these very points for the same
    /// grid (a plus of five cells), so the two implementations cannot drift apart.
    #[test]
    fn the_same_points_as_the_playground() {
        use crate::reach::{Annulus, Workspace};
        use nalgebra::Point2;
        // Rows bottom first: "010", "111", "010"; cells of 0.5 from (1, -1).
        let cells: Vec<bool> = "010111010".chars().map(|c| c == '1').collect();
        let ws = Workspace {
            annulus: Annulus { center: Point2::origin(), inner: 0.0, outer: 1.0 },
            resolution: 3,
            origin: Point2::new(1.0, -1.0),
            cell_size: 0.5,
            limits: false,
            samples: 0,
            exact: false,
            occupied: 5,
            cells,
        };
        let raw = ws.outline(0);
        let want = [
            (1.5, -0.75),
            (1.75, -1.0),
            (2.0, -0.75),
            (2.25, -0.5),
            (2.5, -0.25),
            (2.25, 0.0),
            (2.0, 0.25),
            (1.75, 0.5),
            (1.5, 0.25),
            (1.25, 0.0),
            (1.0, -0.25),
            (1.25, -0.5),
        ];
        assert_eq!(raw.len(), 1);
        assert_eq!(raw[0].iter().map(|p| (p.x, p.y)).collect::<Vec<_>>(), want);
        let smooth = ws.outline(2);
        assert_eq!(smooth[0].len(), 48);
        let head: Vec<(f64, f64)> = smooth[0][..3].iter().map(|p| (p.x, p.y)).collect();
        assert_eq!(head, [(1.5986328125, -0.716796875), (1.6591796875, -0.736328125), (1.7197265625, -0.74609375)]);
    }

    #[test]
    fn a_limited_arm_gives_one_counter_clockwise_loop() {
        let chain = Chain::new(
            [0.0, 0.0],
            &[
                Link::new(2.0, 0.0).with_limits(JointLimits::new(-0.5, 0.5).unwrap()),
                Link::new(1.0, 0.0).with_limits(JointLimits::new(-1.0, 1.0).unwrap()),
            ],
        )
        .unwrap();
        let opts = WorkspaceOptions { resolution: 64, parallel: false, ..WorkspaceOptions::default() };
        let ws = crate::reach::sample(&chain, &opts).unwrap();
        let loops = ws.outline(2);
        assert_eq!(loops.len(), 1);
        assert!(area(&loops[0]) > 0.0);
    }
}
