//! Forward kinematics and the analytic Jacobian of a planar chain.
//!
//! With joint angles θ₁…θ_N (each relative to the previous link) the absolute direction of
//! link k is the partial sum φ_k = θ₁ + … + θ_k, and joint positions follow by accumulation:
//!
//! ```text
//! p₀ = base,   p_k = p_{k−1} + l_k (cos φ_k, sin φ_k),   tip = p_N,   orientation = φ_N.
//! ```
//!
//! Turning joint i by dθ rotates every point beyond it about p_{i−1}, so the Jacobian column
//! of joint i is the tip's lever arm turned by 90°, and the orientation row is all ones:
//!
//! ```text
//! ∂tip/∂θ_i = (−(y_N − y_{i−1}),  x_N − x_{i−1}),     ∂φ_N/∂θ_i = 1.
//! ```
//!
//! Every function here takes angles as a slice with one entry per joint and panics if the
//! length differs: that is a programming error, not bad input ([`Chain::pose`] validates
//! input).

use nalgebra::{Matrix2xX, Matrix3xX, Point2};

use crate::chain::Chain;

/// Where the tip of a chain is and which way its last link points.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EndEffector {
    /// Tip position.
    pub position: Point2<f64>,
    /// Absolute direction of the last link, radians from +x (the sum of all joint angles,
    /// not wrapped).
    pub orientation: f64,
}

fn check_len(chain: &Chain, angles: &[f64]) {
    assert_eq!(
        angles.len(),
        chain.len(),
        "ikarus: {} angles given for a chain of {} joints",
        angles.len(),
        chain.len()
    );
}

/// Position and orientation of the tip for `angles`.
///
/// # Panics
/// If `angles.len() != chain.len()`.
#[must_use]
pub fn end_effector(chain: &Chain, angles: &[f64]) -> EndEffector {
    check_len(chain, angles);
    let mut p = chain.base();
    let mut phi = 0.0;
    for (&l, &a) in chain.lengths().iter().zip(angles) {
        phi += a;
        let (s, c) = crate::lanes::sin_cos(phi);
        p.x += l * c;
        p.y += l * s;
    }
    EndEffector { position: p, orientation: phi }
}

/// Writes the positions of every joint into `out`: base first, tip last (`N + 1` points).
/// Returns the tip's orientation. Allocates nothing.
///
/// # Panics
/// If `angles.len() != chain.len()` or `out.len() != chain.len() + 1`.
pub fn joint_positions_into(chain: &Chain, angles: &[f64], out: &mut [Point2<f64>]) -> f64 {
    check_len(chain, angles);
    assert_eq!(out.len(), chain.len() + 1, "ikarus: joint buffer must hold {} points", chain.len() + 1);
    let mut p = chain.base();
    let mut phi = 0.0;
    out[0] = p;
    for ((&l, &a), slot) in chain.lengths().iter().zip(angles).zip(&mut out[1..]) {
        phi += a;
        let (s, c) = crate::lanes::sin_cos(phi);
        p.x += l * c;
        p.y += l * s;
        *slot = p;
    }
    phi
}

/// Positions of every joint: base first, tip last (`N + 1` points).
///
/// # Panics
/// If `angles.len() != chain.len()`.
#[must_use]
pub fn joint_positions(chain: &Chain, angles: &[f64]) -> Vec<Point2<f64>> {
    let mut out = vec![Point2::origin(); chain.len() + 1];
    joint_positions_into(chain, angles, &mut out);
    out
}

/// Fills the 3×N Jacobian (rows x, y, orientation) from joint positions computed by
/// [`joint_positions_into`]. Allocates nothing if `out` already has N columns.
///
/// # Panics
/// If `joints` is empty.
pub fn jacobian_from_joints(joints: &[Point2<f64>], out: &mut Matrix3xX<f64>) {
    let n = joints.len() - 1;
    if out.ncols() != n {
        *out = Matrix3xX::zeros(n);
    }
    let tip = joints[n];
    for (i, p) in joints[..n].iter().enumerate() {
        let mut col = out.column_mut(i);
        col[0] = -(tip.y - p.y);
        col[1] = tip.x - p.x;
        col[2] = 1.0;
    }
}

/// The 2×N positional Jacobian ∂(x, y)/∂θ at `angles`.
///
/// # Panics
/// If `angles.len() != chain.len()`.
#[must_use]
pub fn jacobian(chain: &Chain, angles: &[f64]) -> Matrix2xX<f64> {
    let full = jacobian_with_orientation(chain, angles);
    full.fixed_rows::<2>(0).into_owned()
}

/// The 3×N Jacobian ∂(x, y, φ)/∂θ at `angles`: position rows, then the orientation row.
///
/// # Panics
/// If `angles.len() != chain.len()`.
#[must_use]
pub fn jacobian_with_orientation(chain: &Chain, angles: &[f64]) -> Matrix3xX<f64> {
    let joints = joint_positions(chain, angles);
    let mut out = Matrix3xX::zeros(chain.len());
    jacobian_from_joints(&joints, &mut out);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::chain::Link;
    use proptest::prelude::*;

    fn chain(lengths: &[f64]) -> Chain {
        let links: Vec<Link> = lengths.iter().map(|&l| Link::new(l, 0.0)).collect();
        Chain::new([0.0, 0.0], &links).unwrap()
    }

    fn near(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol
    }

    #[test]
    fn hand_values_for_the_seed_arm() {
        let c = chain(&[3.0, 2.0, 1.0]);
        let d = std::f64::consts::FRAC_PI_2;
        let ee = end_effector(&c, &[0.0, d, -d]);
        assert!(near(ee.position.x, 4.0, 1e-12) && near(ee.position.y, 2.0, 1e-12), "{ee:?}");
        assert!(near(ee.orientation, 0.0, 1e-15));
        let joints = joint_positions(&c, &[0.0, d, -d]);
        let want = [(0.0, 0.0), (3.0, 0.0), (3.0, 2.0), (4.0, 2.0)];
        for (p, (x, y)) in joints.iter().zip(want) {
            assert!(near(p.x, x, 1e-12) && near(p.y, y, 1e-12), "{joints:?}");
        }
    }

    #[test]
    fn base_offsets_every_point() {
        let c = Chain::new([1.5, -2.0], &[Link::new(2.0, std::f64::consts::PI)]).unwrap();
        let ee = end_effector(&c, c.start_pose().angles());
        assert!(near(ee.position.x, -0.5, 1e-12) && near(ee.position.y, -2.0, 1e-12));
    }

    #[test]
    fn straight_arm_jacobian_by_hand() {
        // All angles 0 along +x: column i is (0, reach − distance of joint i from base, 1).
        let c = chain(&[3.0, 2.0, 1.0]);
        let j = jacobian_with_orientation(&c, &[0.0, 0.0, 0.0]);
        let want = [[0.0, 6.0, 1.0], [0.0, 3.0, 1.0], [0.0, 1.0, 1.0]];
        for (i, col) in want.iter().enumerate() {
            for r in 0..3 {
                assert!(near(j[(r, i)], col[r], 1e-12), "{j}");
            }
        }
        assert_eq!(jacobian(&c, &[0.0, 0.0, 0.0]), j.fixed_rows::<2>(0).into_owned());
    }

    #[test]
    #[should_panic(expected = "2 angles given for a chain of 3 joints")]
    fn wrong_length_is_a_programming_error() {
        let _ = end_effector(&chain(&[1.0, 1.0, 1.0]), &[0.0, 0.0]);
    }

    fn chain_and_angles() -> impl Strategy<Value = (Vec<f64>, Vec<f64>)> {
        (1usize..=12).prop_flat_map(|n| {
            (
                prop::collection::vec(0.05f64..5.0, n),
                prop::collection::vec(-2.0 * std::f64::consts::PI..2.0 * std::f64::consts::PI, n),
            )
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

        /// Both Jacobians match central finite differences of forward kinematics.
        #[test]
        fn jacobian_matches_central_differences((lengths, angles) in chain_and_angles()) {
            let c = chain(&lengths);
            let j3 = jacobian_with_orientation(&c, &angles);
            let j2 = jacobian(&c, &angles);
            let h = 1e-6;
            let scale = c.max_reach();
            for i in 0..angles.len() {
                let mut plus = angles.clone();
                let mut minus = angles.clone();
                plus[i] += h;
                minus[i] -= h;
                let (ep, em) = (end_effector(&c, &plus), end_effector(&c, &minus));
                let fd = [
                    (ep.position.x - em.position.x) / (2.0 * h),
                    (ep.position.y - em.position.y) / (2.0 * h),
                    (ep.orientation - em.orientation) / (2.0 * h),
                ];
                // Central differences are O(h²) accurate; rounding adds ~ε·reach/h.
                let tol = 1e-7 * scale.max(1.0);
                for r in 0..3 {
                    prop_assert!((j3[(r, i)] - fd[r]).abs() <= tol, "row {} col {}: {} vs {}", r, i, j3[(r, i)], fd[r]);
                }
                for r in 0..2 {
                    prop_assert!((j2[(r, i)] - fd[r]).abs() <= tol);
                }
            }
        }

        /// Every link keeps its length and the into-variant agrees with the tip function.
        #[test]
        fn joint_positions_keep_link_lengths((lengths, angles) in chain_and_angles()) {
            let c = chain(&lengths);
            let joints = joint_positions(&c, &angles);
            for (k, l) in lengths.iter().enumerate() {
                let d = (joints[k + 1] - joints[k]).norm();
                prop_assert!((d - l).abs() <= 1e-12 * l.max(1.0));
            }
            let ee = end_effector(&c, &angles);
            prop_assert_eq!(joints[lengths.len()], ee.position);
        }
    }
}
