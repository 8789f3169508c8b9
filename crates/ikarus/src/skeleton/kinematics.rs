//! Forward kinematics of a skeleton and the stacked Jacobian of its effectors.
//!
//! With angles θ (one per bone, each relative to its parent's direction; a root's to +x), the
//! absolute direction of bone i is its parent's plus its own angle, and its tip follows from
//! its start (its parent's tip, or the base for a root):
//!
//! ```text
//! φ_i = φ_parent(i) + θ_i   (φ of a root's parent = 0),
//! start_i = tip_parent(i)   (the base for a root),
//! tip_i = start_i + l_i (cos φ_i, sin φ_i).
//! ```
//!
//! These are the operations of [`crate::kinematics::joint_positions_into`], in the same order
//! (`0 + θ` for a root, then `x += l cos φ`, `y += l sin φ`), so a one-branch skeleton's
//! positions equal its chain's bit for bit.
//!
//! A bone with an offset `o` (its origin in the parent's frame) or a prismatic joint (value
//! `d`, unit slide `s` in the parent's frame, fixed angle `α`) starts elsewhere:
//!
//! ```text
//! start_i = tip_parent(i) + R(φ_parent(i)) ((o − (l_parent, 0)) + d s)   (o = (l_parent, 0) by default),
//! φ_i = φ_parent(i) + α                                                  (prismatic),
//! ```
//!
//! the same point as `start_parent + R(φ_parent) (o + d s)`, written from the parent's tip so
//! that no start need be kept (a root's "tip" is the base and `φ = 0`).
//!
//! Turning bone j by dθ rotates everything below it about `start_j`: an effector at the tip of
//! bone e moves when j lies on e's path from the root (an ancestor of e, or e itself), and
//! then
//!
//! ```text
//! ∂tip_e/∂θ_j = (−(y_e − y_j), x_e − x_j)   with (x_j, y_j) = start_j,   ∂φ_e/∂θ_j = 1,
//! ```
//!
//! and both are 0 otherwise. Sliding a prismatic bone j by dd moves everything below it along
//! the slide's world direction: `∂tip_e/∂d_j = R(φ_parent(j)) s_j`, `∂φ_e/∂d_j = 0`. The stacked Jacobian puts each effector's rows (x, y, and φ when
//! it has an orientation) below the previous effector's, one column per bone.
//!
//! The functions panic if a slice or the Jacobian's shape does not fit the skeleton: that is a
//! programming error, not bad input ([`Skeleton::check_angles`] checks angles).

use nalgebra::{DMatrix, Point2};

use super::{Joint, Skeleton};

/// One effector of the stacked Jacobian: the tip of a bone, its position and optionally its
/// direction.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Effector {
    /// Index of the bone whose tip it is.
    pub bone: usize,
    /// Whether it has an orientation row too.
    pub orientation: bool,
}

impl Effector {
    /// The position of bone `bone`'s tip: two rows, x and y.
    #[must_use]
    pub fn position(bone: usize) -> Self {
        Self { bone, orientation: false }
    }

    /// The position and direction of bone `bone`'s tip: three rows, x, y and φ.
    #[must_use]
    pub fn with_orientation(bone: usize) -> Self {
        Self { bone, orientation: true }
    }

    /// How many rows of the stacked Jacobian it takes: 2, or 3 with an orientation.
    #[must_use]
    pub fn rows(self) -> usize {
        if self.orientation { 3 } else { 2 }
    }
}

/// The number of rows of the stacked Jacobian of `effectors`.
#[must_use]
pub fn task_rows(effectors: &[Effector]) -> usize {
    effectors.iter().map(|e| e.rows()).sum()
}

impl Skeleton {
    /// Writes every bone's start, tip and absolute direction (radians from +x, not wrapped)
    /// for `angles` into the caller's buffers, one entry per bone in the order given.
    /// Allocates nothing. See the [module docs](self) for the formulas.
    ///
    /// # Panics
    /// If any slice's length differs from [`Skeleton::len`].
    pub fn forward_into(
        &self,
        angles: &[f64],
        starts: &mut [Point2<f64>],
        tips: &mut [Point2<f64>],
        directions: &mut [f64],
    ) {
        let n = self.len();
        assert!(
            angles.len() == n && starts.len() == n && tips.len() == n && directions.len() == n,
            "ikarus: forward kinematics of {n} bones given {} angles and buffers of {}, {}, {}",
            angles.len(),
            starts.len(),
            tips.len(),
            directions.len()
        );
        for &i in &self.order {
            let (from, turn) = match self.parents[i] {
                Some(q) => (tips[q], directions[q]),
                None => (self.base, 0.0),
            };
            let (mut p, phi) = self.origin(i, angles[i], from, turn);
            starts[i] = p;
            let (s, c) = crate::lanes::sin_cos(phi);
            let l = self.lengths[i];
            p.x += l * c;
            p.y += l * s;
            tips[i] = p;
            directions[i] = phi;
        }
    }

    /// Bone `i`'s origin and absolute direction for its joint value `q`, from its parent's
    /// tip `from` and direction `turn` (the base and 0 for a root): see the module docs. A
    /// revolute bone at its parent's tip is `(from, turn + q)`, the chain's operations.
    #[inline]
    fn origin(&self, i: usize, q: f64, from: Point2<f64>, turn: f64) -> (Point2<f64>, f64) {
        if self.plain {
            return (from, turn + q);
        }
        let (local, phi) = match self.joints[i] {
            Joint::Revolute => (self.shifts[i], turn + q),
            Joint::Prismatic { slide, .. } => {
                let [sx, sy] = slide.expect("ikarus: a skeleton's slides are resolved");
                let [ox, oy] = self.shifts[i].unwrap_or([0.0, 0.0]);
                (Some([ox + q * sx, oy + q * sy]), turn + self.fixed[i])
            }
        };
        let Some([x, y]) = local else { return (from, phi) };
        let (s, c) = crate::lanes::sin_cos(turn);
        (Point2::new(from.x + c * x - s * y, from.y + s * x + c * y), phi)
    }

    /// Forward kinematics into one buffer of `len() + 1` points — the base, then every bone's
    /// tip in the skeleton's order (bone `i`'s tip at `points[i + 1]`; its start is its
    /// parent's tip, or the base) — and every bone's absolute direction. The same operations
    /// as [`Skeleton::forward_into`], so the same bits. Allocates nothing.
    ///
    /// # Panics
    /// If `angles` or `directions` does not hold one entry per bone or `points` not `len() + 1`.
    pub fn points_into(&self, angles: &[f64], points: &mut [Point2<f64>], directions: &mut [f64]) {
        let n = self.len();
        assert!(
            angles.len() == n && points.len() == n + 1 && directions.len() == n,
            "ikarus: forward kinematics of {n} bones given {} angles, {} points and {} directions",
            angles.len(),
            points.len(),
            directions.len()
        );
        points[0] = self.base;
        for &i in &self.order {
            let (from, turn) = match self.parents[i] {
                Some(q) => (points[q + 1], directions[q]),
                None => (self.base, 0.0),
            };
            let (mut p, phi) = self.origin(i, angles[i], from, turn);
            let (s, c) = crate::lanes::sin_cos(phi);
            let l = self.lengths[i];
            p.x += l * c;
            p.y += l * s;
            points[i + 1] = p;
            directions[i] = phi;
        }
    }

    /// The absolute direction of bone `bone` for `angles`: the sum of the angles from its root
    /// down to it, in that order (a prismatic bone adds its fixed angle; the same bits as
    /// [`Skeleton::forward_into`]'s). Allocates the path (as long as the bone's depth).
    #[must_use]
    pub fn direction(&self, angles: &[f64], bone: usize) -> f64 {
        self.path(bone).iter().fold(0.0, |phi, &j| phi + self.relative_angle(j, angles[j]))
    }

    /// Bone `j`'s angle from its parent's direction (a root's from +x) at joint value `q`:
    /// `q` itself for a revolute joint, the fixed [`Bone::angle`](super::Bone::angle) of a
    /// prismatic one.
    #[inline]
    #[must_use]
    pub fn relative_angle(&self, j: usize, q: f64) -> f64 {
        match self.joints[j] {
            Joint::Revolute => q,
            Joint::Prismatic { .. } => self.fixed[j],
        }
    }

    /// Bone `j`'s column of the Jacobian for an effector at `tip`, with `starts` and
    /// `directions` of forward kinematics: `(∂x, ∂y, ∂φ)` (see the module docs).
    #[inline]
    #[must_use]
    pub fn column(&self, j: usize, tip: Point2<f64>, starts_j: Point2<f64>, directions: &[f64]) -> [f64; 3] {
        match self.joints[j] {
            Joint::Revolute => [-(tip.y - starts_j.y), tip.x - starts_j.x, 1.0],
            Joint::Prismatic { slide, .. } => {
                let [sx, sy] = slide.expect("ikarus: a skeleton's slides are resolved");
                let turn = self.parents[j].map_or(0.0, |p| directions[p]);
                let (s, c) = crate::lanes::sin_cos(turn);
                [c * sx - s * sy, s * sx + c * sy, 0.0]
            }
        }
    }

    /// Fills the stacked Jacobian of `effectors` from the starts and tips computed by
    /// [`Skeleton::forward_into`] (and its directions): [`task_rows`] rows (each effector's x, y and, with an
    /// orientation, φ, in the order of `effectors`) and one column per bone. Allocates nothing
    /// if `out` already has that shape; otherwise it is resized first.
    ///
    /// # Panics
    /// If `starts` or `tips` does not hold one point per bone, or an effector's bone is not a
    /// bone of this skeleton.
    pub fn jacobian_into(
        &self,
        starts: &[Point2<f64>],
        tips: &[Point2<f64>],
        directions: &[f64],
        effectors: &[Effector],
        out: &mut DMatrix<f64>,
    ) {
        let n = self.len();
        assert!(
            starts.len() == n && tips.len() == n && directions.len() == n,
            "ikarus: the Jacobian of {n} bones needs {n} starts, tips and directions"
        );
        let rows = task_rows(effectors);
        if out.shape() != (rows, n) {
            *out = DMatrix::zeros(rows, n);
        } else {
            out.fill(0.0);
        }
        let mut row = 0;
        for e in effectors {
            let tip = tips[e.bone];
            for j in self.path_to_root(e.bone) {
                let [dx, dy, dphi] = self.column(j, tip, starts[j], directions);
                out[(row, j)] = dx;
                out[(row + 1, j)] = dy;
                if e.orientation {
                    out[(row + 2, j)] = dphi;
                }
            }
            row += e.rows();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::kinematics::{jacobian_from_joints, joint_positions_into};
    use crate::skeleton::{Bone, Joint};
    use crate::{Chain, JointLimits, Link};
    use nalgebra::Matrix3xX;
    use proptest::prelude::*;
    use std::f64::consts::PI;

    fn forward(s: &Skeleton, angles: &[f64]) -> (Vec<Point2<f64>>, Vec<Point2<f64>>, Vec<f64>) {
        let n = s.len();
        let (mut starts, mut tips, mut dirs) = (vec![Point2::origin(); n], vec![Point2::origin(); n], vec![0.0; n]);
        s.forward_into(angles, &mut starts, &mut tips, &mut dirs);
        (starts, tips, dirs)
    }

    #[test]
    fn a_fork_by_hand() {
        // A trunk up from (1, 0), two branches: one straight on, one turned right by 90°.
        let s = Skeleton::new(
            [1.0, 0.0],
            &[
                Bone::new("left", 1.0, PI / 2.0).with_parent("trunk"),
                Bone::new("trunk", 2.0, PI / 2.0),
                Bone::new("right", 0.5, -PI / 2.0).with_parent("trunk"),
            ],
        )
        .unwrap();
        let (starts, tips, dirs) = forward(&s, s.start_angles());
        let near = |p: Point2<f64>, x: f64, y: f64| (p.x - x).abs() < 1e-12 && (p.y - y).abs() < 1e-12;
        assert!(near(starts[1], 1.0, 0.0) && near(tips[1], 1.0, 2.0));
        assert!(near(starts[0], 1.0, 2.0) && near(tips[0], 0.0, 2.0), "{tips:?}");
        assert!(near(starts[2], 1.0, 2.0) && near(tips[2], 1.5, 2.0), "{tips:?}");
        assert!((dirs[0] - PI).abs() < 1e-15 && dirs[2].abs() < 1e-15);
        let mut j = DMatrix::zeros(0, 0);
        s.jacobian_into(&starts, &tips, &dirs, &[Effector::with_orientation(0), Effector::position(2)], &mut j);
        // Left tip (0, 2): trunk from (1, 0) → (−2, −1); left from (1, 2) → (0, −1); right: 0.
        #[rustfmt::skip]
        let want = DMatrix::from_row_slice(5, 3, &[
            0.0, -2.0, 0.0,
            -1.0, -1.0, 0.0,
            1.0, 1.0, 0.0,
            // Right tip (1.5, 2): trunk → (−2, 0.5); right from (1, 2) → (0, 0.5).
            0.0, -2.0, 0.0,
            0.0, 0.5, 0.5,
        ]);
        assert!((&j - &want).abs().max() < 1e-12, "{j}");
    }

    #[test]
    fn forward_kinematics_do_not_depend_on_the_order_given() {
        let bones = [
            Bone::new("a", 1.0, 0.3),
            Bone::new("b", 0.7, -0.4).with_parent("a"),
            Bone::new("c", 0.5, 1.1).with_parent("b"),
            Bone::new("d", 0.9, 0.2).with_parent("a"),
            Bone::new("e", 0.4, 2.0),
        ];
        let s = Skeleton::new([0.5, -0.5], &bones).unwrap();
        let (_, tips, _) = forward(&s, s.start_angles());
        let reversed: Vec<Bone> = bones.iter().rev().cloned().collect();
        let r = Skeleton::new([0.5, -0.5], &reversed).unwrap();
        let (_, rtips, _) = forward(&r, r.start_angles());
        for (i, b) in bones.iter().enumerate() {
            assert_eq!(tips[i], rtips[r.index_of(&b.name).unwrap()]);
        }
    }

    /// Random chains: base, lengths, angles (some limited).
    fn chains() -> impl Strategy<Value = (Chain, Vec<f64>)> {
        (1usize..=12).prop_flat_map(|n| {
            (
                (-10.0f64..10.0, -10.0f64..10.0),
                prop::collection::vec((0.01f64..5.0, -2.0 * PI..2.0 * PI, any::<bool>()), n),
                prop::collection::vec(-7.0f64..7.0, n),
            )
                .prop_map(|((x, y), links, angles)| {
                    let links: Vec<Link> = links
                        .iter()
                        .map(|&(l, a, limited)| {
                            let link = Link::new(l, a);
                            if limited { link.with_limits(JointLimits::new(a - 1.0, a + 1.0).unwrap()) } else { link }
                        })
                        .collect();
                    (Chain::new([x, y], &links).unwrap(), angles)
                })
        })
    }

    /// Random trees: each bone hangs on an earlier one or starts at the base, then the order
    /// is shuffled (so the order given is not topological).
    fn trees() -> impl Strategy<Value = (Skeleton, Vec<f64>)> {
        (1usize..=14).prop_flat_map(|n| {
            (
                prop::collection::vec((0.05f64..3.0, any::<u32>(), any::<u64>()), n),
                prop::collection::vec(-2.0 * PI..2.0 * PI, n),
            )
                .prop_map(|(raw, angles)| {
                    let mut bones: Vec<(u64, Bone)> = raw
                        .iter()
                        .enumerate()
                        .map(|(i, &(l, p, key))| {
                            // About one bone in four is a root.
                            let parent = (i > 0 && p % 4 != 0).then(|| format!("b{}", p as usize % i));
                            (key, Bone { parent, ..Bone::new(format!("b{i}"), l, 0.0) })
                        })
                        .collect();
                    bones.sort_by_key(|(key, _)| *key);
                    let bones: Vec<Bone> = bones.into_iter().map(|(_, b)| b).collect();
                    (Skeleton::new([0.3, -0.2], &bones).unwrap(), angles)
                })
        })
    }

    /// The stacked Jacobian of `effectors` by central differences of forward kinematics (step
    /// 1e-6 on each joint value), in the layout of `jacobian_into`.
    fn central_differences(s: &Skeleton, angles: &[f64], effectors: &[Effector]) -> DMatrix<f64> {
        let rows: usize = effectors.iter().map(|e| e.rows()).sum();
        let mut fd = DMatrix::zeros(rows, s.len());
        let h = 1e-6;
        for c in 0..s.len() {
            let (mut plus, mut minus) = (angles.to_vec(), angles.to_vec());
            plus[c] += h;
            minus[c] -= h;
            let (_, tp, dp) = forward(s, &plus);
            let (_, tm, dm) = forward(s, &minus);
            let mut row = 0;
            for e in effectors {
                fd[(row, c)] = (tp[e.bone].x - tm[e.bone].x) / (2.0 * h);
                fd[(row + 1, c)] = (tp[e.bone].y - tm[e.bone].y) / (2.0 * h);
                if e.orientation {
                    fd[(row + 2, c)] = (dp[e.bone] - dm[e.bone]) / (2.0 * h);
                }
                row += e.rows();
            }
        }
        fd
    }

    /// Whether `j` matches the differences `fd` entry by entry, relative to the column's scale
    /// (the lever arm, at least 1): central differences are O(h²), rounding ~ε·reach/h.
    fn close(j: &DMatrix<f64>, fd: &DMatrix<f64>) -> Result<(), String> {
        if j.shape() != fd.shape() {
            return Err(format!("shape {:?} vs {:?}", j.shape(), fd.shape()));
        }
        for r in 0..j.nrows() {
            for c in 0..j.ncols() {
                let (a, d) = (j[(r, c)], fd[(r, c)]);
                if (a - d).abs() > 1e-6 * a.abs().max(1.0) {
                    return Err(format!("row {r} col {c}: {a} vs {d}"));
                }
            }
        }
        Ok(())
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 300, ..ProptestConfig::default() })]

        /// A chain as a skeleton: the same positions, direction and Jacobian, bit for bit.
        #[test]
        fn a_chain_is_a_skeleton_of_one_branch_bit_for_bit((chain, angles) in chains()) {
            let s = crate::fixtures::chain_written_as_rig(&chain);
            prop_assert_eq!(s.max_reach().to_bits(), chain.max_reach().to_bits());
            prop_assert_eq!(s.start_angles(), chain.start_pose().angles());
            prop_assert_eq!(s.limits(), chain.limits());
            let n = chain.len();
            let mut joints = vec![Point2::origin(); n + 1];
            let phi = joint_positions_into(&chain, &angles, &mut joints);
            let (starts, tips, dirs) = forward(&s, &angles);
            for i in 0..n {
                prop_assert_eq!(starts[i].x.to_bits(), joints[i].x.to_bits());
                prop_assert_eq!(starts[i].y.to_bits(), joints[i].y.to_bits());
                prop_assert_eq!(tips[i].x.to_bits(), joints[i + 1].x.to_bits());
                prop_assert_eq!(tips[i].y.to_bits(), joints[i + 1].y.to_bits());
            }
            prop_assert_eq!(dirs[n - 1].to_bits(), phi.to_bits());
            let mut want = Matrix3xX::zeros(n);
            jacobian_from_joints(&joints, &mut want);
            let mut got = DMatrix::zeros(0, 0);
            s.jacobian_into(&starts, &tips, &dirs, &[Effector::with_orientation(n - 1)], &mut got);
            prop_assert_eq!(got.shape(), (3, n));
            for r in 0..3 {
                for c in 0..n {
                    prop_assert_eq!(got[(r, c)].to_bits(), want[(r, c)].to_bits(), "({}, {})", r, c);
                }
            }
        }

        /// The stacked Jacobian of every tip (orientation on every other one) matches central
        /// finite differences of forward kinematics.
        #[test]
        fn the_jacobian_matches_central_differences((s, angles) in trees()) {
            let n = s.len();
            let effectors: Vec<Effector> =
                (0..n).map(|b| if b % 2 == 0 { Effector::with_orientation(b) } else { Effector::position(b) }).collect();
            let (starts, tips, dirs) = forward(&s, &angles);
            let mut j = DMatrix::zeros(0, 0);
            s.jacobian_into(&starts, &tips, &dirs, &effectors, &mut j);
            // Built again into the same buffer: the same matrix (the buffer is cleared first).
            let first = j.clone();
            s.jacobian_into(&starts, &tips, &dirs, &effectors, &mut j);
            prop_assert_eq!(&first, &j);
            let fd = central_differences(&s, &angles, &effectors);
            prop_assert!(close(&j, &fd).is_ok(), "{}", close(&j, &fd).unwrap_err());
            for c in 0..n {
                let mut row = 0;
                for e in &effectors {
                    // Zero exactly off the path.
                    if !s.path(e.bone).contains(&c) {
                        for k in 0..e.rows() {
                            prop_assert_eq!(fd[(row + k, c)], 0.0);
                            prop_assert_eq!(j[(row + k, c)], 0.0);
                        }
                    }
                    row += e.rows();
                }
            }
        }

        /// Offsets and prismatic joints: the Jacobian matches central differences too (a
        /// prismatic column is the slide's world direction, its orientation row 0).
        #[test]
        fn the_jacobian_of_offsets_and_slides_matches_central_differences((s, angles) in bodies()) {
            let n = s.len();
            let effectors: Vec<Effector> =
                (0..n).map(|b| if b % 2 == 0 { Effector::with_orientation(b) } else { Effector::position(b) }).collect();
            let (starts, tips, dirs) = forward(&s, &angles);
            let mut j = DMatrix::zeros(0, 0);
            s.jacobian_into(&starts, &tips, &dirs, &effectors, &mut j);
            let fd = central_differences(&s, &angles, &effectors);
            prop_assert!(close(&j, &fd).is_ok(), "{}", close(&j, &fd).unwrap_err());
            for c in 0..n {
                let mut row = 0;
                for e in &effectors {
                    if let Joint::Prismatic { .. } = s.joint(c) {
                        if e.orientation {
                            prop_assert_eq!(j[(row + 2, c)], 0.0);
                        }
                    }
                    row += e.rows();
                }
            }
        }

        /// Forward kinematics of offsets and slides against an independent implementation:
        /// each origin from its parent's origin, `start_p + R(φ_p) (offset + d slide)`, by
        /// recursion (not the library's walk from the parent's tip).
        #[test]
        fn offsets_and_slides_match_an_independent_forward_kinematics((s, angles) in bodies()) {
            let bones = s.bones();
            let (starts, tips, dirs) = forward(&s, &angles);
            for i in 0..s.len() {
                let (origin, phi) = by_definition(&s, &bones, &angles, i);
                let tip = origin + bones[i].length * nalgebra::Vector2::new(crate::math::cos(phi), crate::math::sin(phi));
                let near = |a: Point2<f64>, b: Point2<f64>| (a - b).norm() <= 1e-9 * (1.0 + b.coords.norm());
                prop_assert!(near(starts[i], origin), "start {}: {} vs {}", i, starts[i], origin);
                prop_assert!(near(tips[i], tip), "tip {}: {} vs {}", i, tips[i], tip);
                prop_assert!((dirs[i] - phi).abs() <= 1e-12 * (1.0 + phi.abs()));
                prop_assert_eq!(s.direction(&angles, i).to_bits(), dirs[i].to_bits());
            }
        }
    }

    /// Bone `i`'s origin and direction by the definition of [`crate::skeleton::Bone::offset`]
    /// and [`Joint::Prismatic`], recursively from the base.
    fn by_definition(s: &Skeleton, bones: &[Bone], q: &[f64], i: usize) -> (Point2<f64>, f64) {
        let (p_origin, p_phi, p_len) = match s.parent(i) {
            Some(p) => {
                let (o, phi) = by_definition(s, bones, q, p);
                (o, phi, bones[p].length)
            }
            None => (s.base(), 0.0, 0.0),
        };
        let [ox, oy] = bones[i].offset.unwrap_or([p_len, 0.0]);
        let (mut lx, mut ly) = (ox, oy);
        let phi = match bones[i].joint {
            Joint::Revolute => p_phi + q[i],
            Joint::Prismatic { slide, .. } => {
                let [sx, sy] = slide.unwrap();
                let norm = (sx * sx + sy * sy).sqrt();
                lx += q[i] * sx / norm;
                ly += q[i] * sy / norm;
                p_phi + bones[i].angle
            }
        };
        let (sn, cs) = (crate::math::sin(p_phi), crate::math::cos(p_phi));
        (Point2::new(p_origin.x + cs * lx - sn * ly, p_origin.y + sn * lx + cs * ly), phi)
    }

    /// Random trees with offsets (about half the bones) and prismatic joints (about a third;
    /// slides in any direction, some limited), and joint values for them.
    fn bodies() -> impl Strategy<Value = (Skeleton, Vec<f64>)> {
        (1usize..=10).prop_flat_map(|n| {
            prop::collection::vec(
                (
                    0.05f64..3.0,
                    any::<u32>(),
                    prop::option::of((-2.0f64..2.0, -2.0f64..2.0)),
                    prop::option::of((-PI..PI, 0.5f64..2.0, -1.0f64..1.0)),
                    -2.0 * PI..2.0 * PI,
                ),
                n,
            )
            .prop_map(|raw| {
                let mut values = Vec::new();
                let bones: Vec<Bone> = raw
                    .iter()
                    .enumerate()
                    .map(|(i, &(l, p, offset, slide, q))| {
                        let mut b = Bone::new(format!("b{i}"), l, 0.3 * q);
                        if i > 0 && p % 4 != 0 {
                            b = b.with_parent(format!("b{}", p as usize % i));
                        }
                        if let Some((x, y)) = offset {
                            b = b.with_offset([x, y]);
                        }
                        if p % 3 == 0 {
                            if let Some((a, r, d)) = slide {
                                b = b.prismatic(d).with_slide([r * crate::math::cos(a), r * crate::math::sin(a)]);
                                values.push(d + 0.2 * crate::math::sin(q));
                                return b;
                            }
                        }
                        values.push(q);
                        b
                    })
                    .collect();
                (Skeleton::new([0.3, -0.2], &bones).unwrap(), values)
            })
        })
    }

    #[test]
    fn a_slider_and_an_offset_by_hand() {
        // A root up from the base, a bone at (0.5, 0.25) in its frame sliding along its own
        // x by 0.5 at a fixed right angle.
        let s = Skeleton::new(
            [1.0, 0.0],
            &[
                Bone::new("root", 2.0, PI / 2.0),
                Bone::new("slider", 1.0, PI / 2.0).with_parent("root").with_offset([0.5, 0.25]).with_slide([2.0, 0.0]),
            ],
        )
        .unwrap();
        let q = [PI / 2.0, 0.5];
        let (starts, tips, dirs) = forward(&s, &q);
        // Origin: (1, 0) + R(90°)(0.5 + 0.5, 0.25) = (1 − 0.25, 1.0); direction 180°.
        assert!((starts[1] - Point2::new(0.75, 1.0)).norm() < 1e-12, "{}", starts[1]);
        assert!((tips[1] - Point2::new(-0.25, 1.0)).norm() < 1e-12, "{}", tips[1]);
        assert!((dirs[1] - PI).abs() < 1e-15);
        let mut j = DMatrix::zeros(0, 0);
        s.jacobian_into(&starts, &tips, &dirs, &[Effector::with_orientation(1)], &mut j);
        // Root turning about (1, 0): tip (−0.25, 1) → (−1, −1.25); the slide along world +y.
        #[rustfmt::skip]
        let want = DMatrix::from_row_slice(3, 2, &[
            -1.0, 0.0,
            -1.25, 1.0,
            1.0, 0.0,
        ]);
        assert!((&j - &want).abs().max() < 1e-12, "{j}");
    }
}
