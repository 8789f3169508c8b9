//! The chain: a [`Skeleton`] of one branch, built from links; poses and their validation (joint
//! limits are in [`crate::limits`], re-exported here).
//!
//! A [`Chain`] is a planar serial chain of `N ≥ 1` revolute joints, each followed by a rigid
//! link. Joint `i` sits at the end of link `i − 1` (joint 0 sits at the base). Its angle is
//! measured relative to the previous link; the first joint's angle is relative to +x.
//! Counter-clockwise is positive, and every angle inside the library is in radians.
//!
//! The chain holds no data of its own: it is a view of the one body, a skeleton whose bone
//! `i + 1` hangs on bone `i`, every joint revolute at its parent's tip, without a rest-pose
//! preference ([`Chain::skeleton`]; [`Chain::new`] names the bones `link0`, `link1`, ...).
//! Every accessor reads the skeleton, so a chain's forward kinematics and Jacobian are its
//! skeleton's bit for bit.
//!
//! A chain is validated once, when it is built; everything downstream may assume valid data.

use crate::math;
use crate::number::Num;
use crate::skeleton::{Bone, Skeleton};
use nalgebra::Point2;
use thiserror::Error;

use crate::limits::{Bounds, Violation};
pub use crate::limits::{JointLimits, LimitsError};
pub use crate::skeleton::MAX_REACH;

/// One joint and the link that follows it: the link's length, the joint's starting angle
/// (radians, relative to the previous link) and its optional limits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Link {
    /// Length of the link, > 0.
    pub length: f64,
    /// Starting angle of the joint in radians.
    pub angle: f64,
    /// Optional range the joint angle must stay within.
    pub limits: Option<JointLimits>,
}

impl Link {
    /// A link of `length` whose joint starts at `angle` radians, without limits.
    #[must_use]
    pub fn new(length: f64, angle: f64) -> Self {
        Self { length, angle, limits: None }
    }

    /// The same link with its joint limited to `limits`.
    #[must_use]
    pub fn with_limits(mut self, limits: JointLimits) -> Self {
        self.limits = Some(limits);
        self
    }
}

/// A validated planar chain: base position, links, start pose; a view of a one-branch
/// [`Skeleton`] (see the [module docs](self)).
///
/// Build one with [`Chain::new`]; the constructor rejects empty chains, non-finite numbers,
/// non-positive lengths, and start angles outside their limits. A skeleton of the chain's
/// shape becomes one with [`Chain::try_from`] or [`Skeleton::as_chain`], and a chain its
/// skeleton with [`Skeleton::from`]. Two chains are equal when their skeletons are (the bones'
/// names included).
#[derive(Clone, PartialEq)]
pub struct Chain {
    /// The body: one branch, bone `i` is link `i`.
    skeleton: Skeleton,
    /// A cache of the skeleton's start angles as a [`Pose`], so that [`Chain::start_pose`] can
    /// lend one; derived from the skeleton when the chain is made, never changed apart.
    start: Pose,
}

impl std::fmt::Debug for Chain {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        // The chain's own data, not the skeleton's derived tables (its name index is a hash
        // map, whose order would differ from run to run).
        f.debug_struct("Chain")
            .field("base", &self.base())
            .field("names", &self.skeleton.names())
            .field("lengths", &self.lengths())
            .field("limits", &self.limits())
            .field("start", &self.start)
            .finish()
    }
}

/// Which number of a link an error is about.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LinkField {
    /// [`Link::length`].
    Length,
    /// [`Link::angle`].
    Angle,
    /// [`Link::limits`].
    Limits,
}

impl std::fmt::Display for LinkField {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            LinkField::Length => "length",
            LinkField::Angle => "angle",
            LinkField::Limits => "limits",
        })
    }
}

/// Why a [`Chain`] or a [`Pose`] for it is invalid. Every variant names the field and the value.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum ChainError {
    /// The chain has no links.
    #[error("links: a chain needs at least one link, got none")]
    Empty,
    /// A base coordinate is NaN or infinite.
    #[error("base: coordinates must be finite, got ({}, {})", Num(*.x), Num(*.y))]
    NonFiniteBase {
        /// x of the base.
        x: f64,
        /// y of the base.
        y: f64,
    },
    /// A link's number is NaN or infinite.
    #[error("links[{index}].{field}: must be a finite number, got {}", Num(*.value))]
    NonFinite {
        /// Index of the link, from 0.
        index: usize,
        /// Which number.
        field: LinkField,
        /// The offending value.
        value: f64,
    },
    /// A link's length is zero or negative.
    #[error("links[{index}].length: must be greater than 0, got {}", Num(*.value))]
    NonPositiveLength {
        /// Index of the link, from 0.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// A joint's limits are malformed (for callers that build limits from raw numbers and want
    /// the error to name the joint).
    #[error("links[{index}].limits: {source}")]
    Limits {
        /// Index of the link, from 0.
        index: usize,
        /// What is wrong with them.
        source: LimitsError,
    },
    /// A joint angle lies outside that joint's limits.
    #[error("links[{index}].angle: {} rad lies outside the limits [{}, {}] rad", Num(*.value), Num(*.min), Num(*.max))]
    AngleOutsideLimits {
        /// Index of the joint, from 0.
        index: usize,
        /// The offending angle, radians.
        value: f64,
        /// Lower limit, radians.
        min: f64,
        /// Upper limit, radians.
        max: f64,
    },
    /// The chain's reach (the sum of its lengths, plus the base's distance from the origin)
    /// is beyond [`MAX_REACH`] or not a finite number: its squares (areas, `J Jᵀ`) would
    /// overflow, so nothing about it could be computed or drawn.
    #[error(
        "links: the lengths add up to {} from the base, beyond {}, the largest reach ikarus computes with",
        Num(*.reach),
        Num(MAX_REACH)
    )]
    ReachTooLarge {
        /// The sum of the lengths plus the base's distance from the origin.
        reach: f64,
    },
    /// A pose has a different number of angles than the chain has joints.
    #[error("pose: expected {expected} angles (one per joint), got {got}")]
    PoseLength {
        /// Number of joints of the chain.
        expected: usize,
        /// Number of angles given.
        got: usize,
    },
}

impl Chain {
    /// Validates and builds a chain with its base at `base`: a skeleton of one branch whose
    /// bone `i`, named `link{i}`, is link `i` and hangs on bone `i − 1`.
    ///
    /// Checks, in order: at least one link; a finite base; for each link a finite length > 0,
    /// well-formed limits, and a finite start angle within them.
    pub fn new(base: [f64; 2], links: &[Link]) -> Result<Self, ChainError> {
        if links.is_empty() {
            return Err(ChainError::Empty);
        }
        let [x, y] = base;
        if !x.is_finite() || !y.is_finite() {
            return Err(ChainError::NonFiniteBase { x, y });
        }
        for (index, link) in links.iter().enumerate() {
            if !link.length.is_finite() {
                return Err(ChainError::NonFinite { index, field: LinkField::Length, value: link.length });
            }
            if link.length <= 0.0 {
                return Err(ChainError::NonPositiveLength { index, value: link.length });
            }
        }
        let angles: Vec<f64> = links.iter().map(|l| l.angle).collect();
        let limits: Vec<Option<JointLimits>> = links.iter().map(|l| l.limits).collect();
        check_angles(&angles, Bounds::new(&limits))?;
        let reach: f64 = links.iter().map(|l| l.length).sum();
        let extent = math::hypot(x, y) + reach;
        if extent.is_nan() || extent > MAX_REACH {
            return Err(ChainError::ReachTooLarge { reach: extent });
        }
        let bones: Vec<Bone> = links
            .iter()
            .enumerate()
            .map(|(i, link)| Bone {
                parent: i.checked_sub(1).map(|p| format!("link{p}")),
                limits: link.limits,
                ..Bone::new(format!("link{i}"), link.length, link.angle)
            })
            .collect();
        // A valid chain passes every check of a skeleton: the names are distinct, the parents
        // exist and form a path, and the reach is the chain's own sum (the same additions).
        let skeleton = Skeleton::new(base, &bones).expect("ikarus: a valid chain is a valid skeleton");
        Ok(Self { skeleton, start: Pose { angles } })
    }

    /// `skeleton` seen as a chain; it must have a chain's shape ([`Skeleton::is_chain`]).
    fn viewing(skeleton: Skeleton) -> Chain {
        let start = Pose { angles: skeleton.start_angles().to_vec() };
        Chain { skeleton, start }
    }

    /// The chain's body: a skeleton of one branch (see the [module docs](self)).
    #[must_use]
    pub fn skeleton(&self) -> &Skeleton {
        &self.skeleton
    }

    /// Number of joints (equal to the number of links).
    #[must_use]
    pub fn len(&self) -> usize {
        // (The lengths' count, not the names': the hot loops index the lengths and the points
        // by it, and the compiler then knows the two agree.)
        self.lengths().len()
    }

    /// Always `false`: a valid chain has at least one link.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Where the first joint sits.
    #[must_use]
    pub fn base(&self) -> Point2<f64> {
        self.skeleton.base()
    }

    /// Link lengths, base to tip.
    #[must_use]
    pub fn lengths(&self) -> &[f64] {
        self.skeleton.lengths()
    }

    /// Per-joint limits, base to tip.
    #[must_use]
    pub fn limits(&self) -> &[Option<JointLimits>] {
        self.skeleton.limits()
    }

    /// Whether any joint has limits.
    #[must_use]
    pub fn has_limits(&self) -> bool {
        self.skeleton.has_limits()
    }

    /// The pose the chain was built with.
    #[must_use]
    pub fn start_pose(&self) -> &Pose {
        &self.start
    }

    /// The links as given to [`Chain::new`], with the start pose's angles.
    #[must_use]
    pub fn links(&self) -> Vec<Link> {
        self.lengths()
            .iter()
            .zip(self.limits())
            .zip(self.start.angles())
            .map(|((&length, &limits), &angle)| Link { length, angle, limits })
            .collect()
    }

    /// Outer radius of the reachable set ignoring limits: Σ lᵢ.
    #[must_use]
    pub fn max_reach(&self) -> f64 {
        self.skeleton.max_reach()
    }

    /// Inner radius of the reachable set ignoring limits: `max(0, l_max − (Σl − l_max))`.
    ///
    /// Points closer to the base than this cannot be reached because the longest link cannot
    /// be folded back far enough by the others.
    #[must_use]
    pub fn min_reach(&self) -> f64 {
        annulus_inner(self.lengths())
    }

    /// The same chain with every joint free: what a solve with
    /// [`LimitMode::Ignore`](crate::LimitMode::Ignore) sees, for motion and workspaces that must
    /// agree with it (it builds a skeleton: not for a hot loop).
    #[must_use]
    pub fn without_limits(&self) -> Chain {
        Chain { skeleton: self.skeleton.without_limits(), start: self.start.clone() }
    }

    /// The joint limits as a [`Bounds`] view (free if no joint has limits).
    #[must_use]
    pub fn bounds(&self) -> Bounds<'_> {
        self.skeleton.bounds()
    }

    /// Validates `angles` as a pose of this chain: one finite angle per joint, each within its
    /// limits.
    pub fn pose(&self, angles: Vec<f64>) -> Result<Pose, ChainError> {
        self.pose_within(angles, self.bounds())
    }

    /// Validates `angles` as a pose of this chain ignoring its limits: one finite angle per
    /// joint (for a solve with [`LimitMode::Ignore`](crate::LimitMode::Ignore)).
    pub fn pose_ignoring_limits(&self, angles: Vec<f64>) -> Result<Pose, ChainError> {
        self.pose_within(angles, Bounds::free())
    }

    fn pose_within(&self, angles: Vec<f64>, bounds: Bounds<'_>) -> Result<Pose, ChainError> {
        if angles.len() != self.len() {
            return Err(ChainError::PoseLength { expected: self.len(), got: angles.len() });
        }
        check_angles(&angles, bounds)?;
        Ok(Pose { angles })
    }
}

impl From<Chain> for Skeleton {
    /// The chain's body (its bones named as the chain's, `link0`, `link1`, ... for a chain
    /// from [`Chain::new`]).
    fn from(chain: Chain) -> Skeleton {
        chain.skeleton
    }
}

impl TryFrom<Skeleton> for Chain {
    type Error = Skeleton;

    /// The skeleton as a chain, when it has a chain's shape ([`Skeleton::is_chain`]); the
    /// bones keep their names. Otherwise the skeleton back, unchanged.
    fn try_from(skeleton: Skeleton) -> Result<Self, Skeleton> {
        if skeleton.is_chain() { Ok(Chain::viewing(skeleton)) } else { Err(skeleton) }
    }
}

impl Skeleton {
    /// The chain this skeleton is, when its shape allows ([`Skeleton::is_chain`]): a clone of
    /// the skeleton seen as a chain, its bones keeping their names, so its forward kinematics
    /// and Jacobian are the skeleton's bit for bit. `None` for any other shape: a fork, a bone
    /// given before its parent, an offset, a slide, a rest-pose preference.
    #[must_use]
    pub fn as_chain(&self) -> Option<Chain> {
        self.is_chain().then(|| Chain::viewing(self.clone()))
    }
}

/// Inner radius of the annulus reachable by links of `lengths` with free joints.
pub(crate) fn annulus_inner(lengths: &[f64]) -> f64 {
    let total: f64 = lengths.iter().sum();
    let longest = lengths.iter().copied().fold(0.0, f64::max);
    (longest - (total - longest)).max(0.0)
}

fn check_angles(angles: &[f64], bounds: Bounds<'_>) -> Result<(), ChainError> {
    match bounds.first_violation(angles) {
        None => Ok(()),
        Some(Violation::NonFinite { index, value }) => {
            Err(ChainError::NonFinite { index, field: LinkField::Angle, value })
        }
        Some(Violation::Outside { index, value, limits }) => {
            Err(ChainError::AngleOutsideLimits { index, value, min: limits.min(), max: limits.max() })
        }
    }
}

/// Joint angles of a chain, in radians, base to tip.
///
/// A `Pose` from [`Chain::pose`] or [`Chain::start_pose`] is valid for that chain.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Pose {
    angles: Vec<f64>,
}

impl Pose {
    /// The angles, radians.
    #[must_use]
    pub fn angles(&self) -> &[f64] {
        &self.angles
    }

    /// Consumes the pose, giving its angles.
    #[must_use]
    pub fn into_angles(self) -> Vec<f64> {
        self.angles
    }

    pub(crate) fn angles_mut(&mut self) -> &mut Vec<f64> {
        &mut self.angles
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn seed() -> Vec<Link> {
        vec![Link::new(3.0, 0.1), Link::new(2.0, 0.1), Link::new(1.0, 0.1)]
    }

    #[test]
    fn builds_a_valid_chain() {
        let c = Chain::new([1.0, -2.0], &seed()).unwrap();
        assert_eq!(c.len(), 3);
        assert_eq!(c.max_reach(), 6.0);
        assert_eq!(c.min_reach(), 0.0);
        assert_eq!(c.base(), Point2::new(1.0, -2.0));
        assert_eq!(c.start_pose().angles(), &[0.1, 0.1, 0.1]);
        assert_eq!(c.links(), seed());
    }

    #[test]
    fn inner_radius_of_a_long_first_link() {
        let c = Chain::new([0.0, 0.0], &[Link::new(5.0, 0.0), Link::new(1.0, 0.0), Link::new(1.5, 0.0)]).unwrap();
        assert!((c.min_reach() - 2.5).abs() < 1e-15);
    }

    #[test]
    fn rejects_each_kind_of_bad_input_naming_the_field() {
        let cases: Vec<(Vec<Link>, [f64; 2], &str)> = vec![
            (vec![], [0.0, 0.0], "links: a chain needs at least one link"),
            (seed(), [f64::NAN, 0.0], "base: coordinates must be finite, got (NaN, 0)"),
            (
                vec![Link::new(1.0, 0.0), Link::new(0.0, 0.0)],
                [0.0, 0.0],
                "links[1].length: must be greater than 0, got 0",
            ),
            (vec![Link::new(-2.0, 0.0)], [0.0, 0.0], "links[0].length: must be greater than 0, got -2"),
            (vec![Link::new(f64::INFINITY, 0.0)], [0.0, 0.0], "links[0].length: must be a finite number, got inf"),
            (vec![Link::new(1.0, f64::NAN)], [0.0, 0.0], "links[0].angle: must be a finite number, got NaN"),
            (
                vec![Link::new(1.0, 2.0).with_limits(JointLimits::new(-1.0, 1.0).unwrap())],
                [0.0, 0.0],
                "links[0].angle: 2 rad lies outside the limits [-1, 1] rad",
            ),
            // Each length is finite but the reach is not: nothing about it could be drawn.
            (
                vec![Link::new(1e308, 0.0), Link::new(1e308, 0.0)],
                [0.0, 0.0],
                "links: the lengths add up to inf from the base, beyond 1e152, the largest reach ikarus computes with",
            ),
            (vec![Link::new(1.0, 0.0)], [f64::MAX, f64::MAX], "links: the lengths add up to inf from the base"),
            // Finite, but its square (an area, J Jᵀ) would be near the end of the f64 range.
            (
                vec![Link::new(1e152, 0.0), Link::new(1e152, 0.0)],
                [0.0, 0.0],
                "links: the lengths add up to 2e152 from the base, beyond 1e152, the largest reach ikarus computes with",
            ),
        ];
        for (links, base, want) in cases {
            let err = Chain::new(base, &links).unwrap_err().to_string();
            assert!(err.starts_with(want), "got {err:?}, want prefix {want:?}");
        }
    }

    #[test]
    fn without_limits_frees_every_joint_and_keeps_the_rest() {
        let lim = JointLimits::new(-0.5, 0.5).unwrap();
        let c = Chain::new([1.0, 2.0], &[Link::new(1.0, 0.1).with_limits(lim), Link::new(2.0, 0.2)]).unwrap();
        let free = c.without_limits();
        assert!(!free.has_limits());
        assert_eq!((free.base(), free.lengths(), free.start_pose()), (c.base(), c.lengths(), c.start_pose()));
    }

    #[test]
    fn limits_validate() {
        assert_eq!(JointLimits::new(1.0, -1.0), Err(LimitsError::Inverted { min: 1.0, max: -1.0 }));
        assert!(matches!(JointLimits::new(f64::NAN, 1.0), Err(LimitsError::NonFinite { end: "min", .. })));
        assert!(matches!(JointLimits::new(0.0, f64::INFINITY), Err(LimitsError::NonFinite { end: "max", .. })));
        let l = JointLimits::new(-1.0, 1.0).unwrap();
        assert_eq!(l.clamp(3.0), 1.0);
        assert_eq!(l.clamp(-3.0), -1.0);
        assert!(l.contains(1.0) && !l.contains(1.0 + 1e-12));
    }

    #[test]
    fn pose_is_validated_against_the_chain() {
        let c =
            Chain::new([0.0, 0.0], &[Link::new(1.0, 0.0).with_limits(JointLimits::new(-1.0, 1.0).unwrap())]).unwrap();
        assert_eq!(c.pose(vec![0.5]).unwrap().angles(), &[0.5]);
        assert!(matches!(c.pose(vec![0.5, 0.1]), Err(ChainError::PoseLength { expected: 1, got: 2 })));
        assert!(matches!(c.pose(vec![1.5]), Err(ChainError::AngleOutsideLimits { .. })));
        assert!(c.pose_ignoring_limits(vec![1.5]).is_ok());
        assert!(c.pose_ignoring_limits(vec![f64::NAN]).is_err());
    }
}
