//! The skeleton model: a tree of named bones, validated once (errors in [`error`]; forward
//! kinematics and the stacked effector Jacobian in [`kinematics`]).
//!
//! A [`Skeleton`] is a planar tree of `N ≥ 1` bones. Each bone is a joint at its origin
//! followed by a rigid segment of its length. A bone with a parent starts at its parent's tip
//! (or at its [`Bone::offset`] in the parent's frame), and its angle is measured from the
//! parent's direction; a bone without a parent (a root; there may be several) starts at the
//! base (plus its offset, in world axes) and its angle is measured from +x. Counter-clockwise
//! is positive, and every angle inside the library is in radians.
//!
//! The joint is a [`Joint`]: a revolute joint's value is the bone's angle; a prismatic joint
//! keeps the bone at its fixed angle ([`Bone::angle`]) and its value is a displacement of the
//! bone's origin along a fixed direction of the parent's frame, in length units. Everything
//! called "angles" per bone (poses, start and rest values, limits) holds these joint values.
//!
//! A chain is a skeleton with one branch: a [`Chain`](crate::Chain) is a view of one
//! ([`Chain::skeleton`](crate::Chain::skeleton), [`Skeleton::is_chain`]), and its forward
//! kinematics and Jacobian equal the chain's bit for bit.
//!
//! # Orders
//!
//! Everything a caller passes or receives per bone — angles, limits, lengths, names, the
//! positions of forward kinematics, the Jacobian's columns — is in the order the bones were
//! given to [`Skeleton::new`] (a rig file's order), and a bone's index is its place in that
//! order. Callers never permute anything: they keep the order they wrote, and an error, an
//! output or a column `i` means the `i`-th bone they gave. Internally the skeleton also keeps a
//! topological order ([`Skeleton::topological_order`]: every parent before its children, a
//! depth-first walk from the roots, siblings in the order given), which forward kinematics
//! walks; it is a list of indices, not a second layout of the data, so nothing is copied or
//! translated between the two. A chain's order is already topological, so its walk is the
//! chain's own.

use std::collections::HashMap;

use nalgebra::Point2;

use crate::limits::{Bounds, JointLimits, Violation};
use crate::math;
use tree::{children_of, cycle_error, depth_first, roots_of, subtrees_of};

pub mod error;
pub mod kinematics;
mod refit;
mod tree;

pub use error::{BoneField, SkeletonError};
pub use kinematics::Effector;
pub(crate) use refit::Refit;

/// The largest reach (sum of the lengths plus the base's distance from the origin) a body may
/// have: its square, and so the areas of workspaces and the entries of `J Jᵀ`, stay far inside
/// the f64 range (a workspace's area overflowed from a reach of about 1.3e154).
pub const MAX_REACH: f64 = 1e152;

/// A bone's joint: what its joint value moves. A new kind is added here, and the compiler then
/// names every place that must handle it (forward kinematics, the Jacobian, restarts, the
/// methods that refuse it).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Joint {
    /// The bone turns about its origin; the joint value is its angle (radians, from the
    /// parent's direction), its limits in radians.
    Revolute,
    /// The bone slides: its angle stays [`Bone::angle`], and its origin moves by the joint
    /// value `d` (length units; its limits too) along `slide`, a direction in the parent's
    /// frame (world axes for a root).
    Prismatic {
        /// The direction of the slide (normalised when the skeleton is built; `None`: along
        /// the bone's own rest direction, `(cos angle, sin angle)`).
        slide: Option<[f64; 2]>,
        /// The start value of the displacement.
        extension: f64,
    },
}

/// One bone: its name, its parent's name (`None` for a root, which starts at the base), its
/// length, its starting angle (radians, relative to the parent's direction; a root's relative
/// to +x), its optional limits, and its rest-pose preference (a stiffness and a rest angle; see
/// [`Bone::stiffness`]).
#[derive(Debug, Clone, PartialEq)]
pub struct Bone {
    /// Name, unique within the skeleton and not empty.
    pub name: String,
    /// The parent's name, or `None` for a bone that starts at the base.
    pub parent: Option<String>,
    /// Length, > 0.
    pub length: f64,
    /// Starting angle in radians, relative to the parent's direction (a root's to +x).
    pub angle: f64,
    /// Optional range the angle must stay within.
    pub limits: Option<JointLimits>,
    /// How much the bone resists turning away from its rest angle, ≥ 0 (0 by default: no
    /// preference). In a rig solve a bone of stiffness `s` turns `1 + s` times less readily
    /// than a bone of stiffness 0 for the same effect on the goals, and between the goals'
    /// steps it is pulled back toward its rest angle, in what the goals and pins leave free
    /// (see [`crate::solve`]'s rest pose): a stiff spine and a supple arm make a reach move
    /// the arm first and the body only as needed.
    pub stiffness: f64,
    /// The angle the bone is pulled back to, radians (`None`: its starting angle, the bind
    /// pose); within its limits. It matters only with a stiffness > 0. For a prismatic joint:
    /// the rest displacement (`None`: its start extension).
    pub rest: Option<f64>,
    /// The bone's origin in its parent's frame (the parent's origin, x along its direction);
    /// for a root, relative to the base in world axes. `None`: the parent's tip
    /// `(parent length, 0)`, or the base itself for a root.
    pub offset: Option<[f64; 2]>,
    /// What the joint at the bone's origin does ([`Joint::Revolute`] by default).
    pub joint: Joint,
}

impl Bone {
    /// A root bone called `name` of `length` starting at `angle` radians from +x, without
    /// limits; [`Bone::with_parent`] hangs it on another bone.
    #[must_use]
    pub fn new(name: impl Into<String>, length: f64, angle: f64) -> Self {
        Self {
            name: name.into(),
            parent: None,
            length,
            angle,
            limits: None,
            stiffness: 0.0,
            rest: None,
            offset: None,
            joint: Joint::Revolute,
        }
    }

    /// The same bone starting at `offset` in its parent's frame (see [`Bone::offset`]).
    #[must_use]
    pub fn with_offset(mut self, offset: [f64; 2]) -> Self {
        self.offset = Some(offset);
        self
    }

    /// The same bone on a prismatic joint that starts at `extension` (length units), sliding
    /// along the bone's own rest direction; [`Bone::with_slide`] turns the slide.
    #[must_use]
    pub fn prismatic(mut self, extension: f64) -> Self {
        self.joint = Joint::Prismatic { slide: None, extension };
        self
    }

    /// The same bone with its prismatic joint sliding along `slide` (in the parent's frame).
    /// A revolute bone becomes prismatic, starting at 0.
    #[must_use]
    pub fn with_slide(mut self, slide: [f64; 2]) -> Self {
        let extension = match self.joint {
            Joint::Revolute => 0.0,
            Joint::Prismatic { extension, .. } => extension,
        };
        self.joint = Joint::Prismatic { slide: Some(slide), extension };
        self
    }

    /// The same bone starting at the tip of the bone called `parent`, its angle measured from
    /// that bone's direction.
    #[must_use]
    pub fn with_parent(mut self, parent: impl Into<String>) -> Self {
        self.parent = Some(parent.into());
        self
    }

    /// The same bone with its angle limited to `limits`.
    #[must_use]
    pub fn with_limits(mut self, limits: JointLimits) -> Self {
        self.limits = Some(limits);
        self
    }

    /// The same bone with stiffness `stiffness` (see [`Bone::stiffness`]).
    #[must_use]
    pub fn with_stiffness(mut self, stiffness: f64) -> Self {
        self.stiffness = stiffness;
        self
    }

    /// The same bone pulled back to `rest` radians rather than to its starting angle.
    #[must_use]
    pub fn with_rest(mut self, rest: f64) -> Self {
        self.rest = Some(rest);
        self
    }
}

/// A validated planar tree of bones: base, bones, start angles, and the tree's structure
/// (parents, children, a depth-first order with each subtree's span in it, roots) computed
/// once. Its memory is linear in the bones: a bone's path from the root is walked along the
/// parents ([`Skeleton::path_to_root`]) or tested in constant time ([`Skeleton::is_on_path`]),
/// never stored.
///
/// Build one with [`Skeleton::new`]. Per-bone data is in the order the bones were given (see
/// the [module docs](self)).
#[derive(Debug, Clone, PartialEq)]
pub struct Skeleton {
    base: Point2<f64>,
    names: Vec<String>,
    index: HashMap<String, usize>,
    parents: Vec<Option<usize>>,
    lengths: Vec<f64>,
    limits: Vec<Option<JointLimits>>,
    start: Vec<f64>,
    /// Each bone's stiffness and rest angle ([`Bone::stiffness`], [`Bone::rest`] resolved).
    stiffness: Vec<f64>,
    rest: Vec<f64>,
    /// Each bone's offset as given, and where its origin lies from its parent's tip in the
    /// parent's frame (`offset − (parent length, 0)`; a root's from the base), `None` at the tip.
    offsets: Vec<Option<[f64; 2]>>,
    shifts: Vec<Option<[f64; 2]>>,
    /// Each bone's joint, a prismatic slide normalised; and its fixed angle (a prismatic
    /// bone's [`Bone::angle`]; 0 for a revolute one, whose angle is its joint value).
    joints: Vec<Joint>,
    fixed: Vec<f64>,
    /// Whether every bone is revolute and starts at its parent's tip (or the base).
    plain: bool,
    /// Every bone once, every parent before its children.
    order: Vec<usize>,
    /// The children of bone `i` are `children[child_start[i]..child_start[i + 1]]`, in the
    /// order given.
    children: Vec<usize>,
    child_start: Vec<usize>,
    /// Bone `i` is `order[enter[i]]`; its descendants follow it, up to `order[leave[i]]`.
    enter: Vec<usize>,
    leave: Vec<usize>,
    /// The root above each bone (a root's is itself).
    root: Vec<usize>,
    /// The length of the path to each bone's tip (what `reach` is the largest of), kept so that
    /// [`Skeleton::refit`] computes it again in place.
    to_tip: Vec<f64>,
    reach: f64,
}

impl Skeleton {
    /// Validates and builds a skeleton with its base at `base`.
    ///
    /// Checks, in order: at least one bone; a finite base; for each bone a non-empty name not
    /// used before and a finite length > 0; every parent names a bone; no bone is its own
    /// ancestor; each start angle finite and within its limits; each stiffness finite and ≥ 0,
    /// each rest angle finite and within its limits; the reach (the longest
    /// root-to-tip path plus the base's distance from the origin) at most [`MAX_REACH`].
    pub fn new(base: [f64; 2], bones: &[Bone]) -> Result<Self, SkeletonError> {
        if bones.is_empty() {
            return Err(SkeletonError::Empty);
        }
        let [x, y] = base;
        if !x.is_finite() || !y.is_finite() {
            return Err(SkeletonError::NonFiniteBase { x, y });
        }
        let n = bones.len();
        let mut index = HashMap::with_capacity(n);
        for (i, bone) in bones.iter().enumerate() {
            if bone.name.is_empty() {
                return Err(SkeletonError::EmptyName { index: i });
            }
            if let Some(&first) = index.get(&bone.name) {
                return Err(SkeletonError::DuplicateName { index: i, name: bone.name.clone(), first });
            }
            index.insert(bone.name.clone(), i);
            if !bone.length.is_finite() {
                let (name, field, value) = (bone.name.clone(), BoneField::Length, bone.length);
                return Err(SkeletonError::NonFinite { index: i, name, field, value });
            }
            if bone.length <= 0.0 {
                return Err(SkeletonError::NonPositiveLength { index: i, name: bone.name.clone(), value: bone.length });
            }
        }
        let mut parents = Vec::with_capacity(n);
        for (i, bone) in bones.iter().enumerate() {
            parents.push(match &bone.parent {
                None => None,
                Some(p) => Some(*index.get(p).ok_or_else(|| SkeletonError::UnknownParent {
                    index: i,
                    name: bone.name.clone(),
                    parent: p.clone(),
                })?),
            });
        }
        let (children, child_start) = children_of(&parents);
        let order = depth_first(&parents, &children, &child_start);
        if order.len() < n {
            return Err(cycle_error(bones, &parents, &order));
        }
        let limits: Vec<Option<JointLimits>> = bones.iter().map(|b| b.limits).collect();
        let lengths: Vec<f64> = bones.iter().map(|b| b.length).collect();
        let names: Vec<String> = bones.iter().map(|b| b.name.clone()).collect();
        let (joints, fixed, offsets) = joints_of(bones)?;
        let start: Vec<f64> = bones.iter().zip(&joints).map(|(b, j)| joint_value(b.angle, *j)).collect();
        check_angles(&names, &joints, &start, Bounds::new(&limits))?;
        let (stiffness, rest) = rest_pose(bones, &joints, &limits)?;
        let shifts: Vec<Option<[f64; 2]>> =
            offsets.iter().zip(&parents).map(|(o, p)| o.map(|[x, y]| [x - p.map_or(0.0, |p| lengths[p]), y])).collect();
        let plain = offsets.iter().all(Option::is_none) && joints.iter().all(|j| *j == Joint::Revolute);
        let (enter, leave) = subtrees_of(&parents, &order);
        let root = roots_of(&parents, &order);
        Self {
            base: Point2::new(x, y),
            names,
            index,
            parents,
            lengths,
            limits,
            start,
            stiffness,
            rest,
            offsets,
            shifts,
            joints,
            fixed,
            plain,
            order,
            children,
            child_start,
            enter,
            leave,
            root,
            to_tip: vec![0.0; n],
            reach: 0.0,
        }
        .with_reach()
    }

    /// Whether the skeleton has a chain's shape, so that it can be seen as a
    /// [`Chain`](crate::Chain) ([`Skeleton::as_chain`]): one branch in the order given (bone
    /// `i + 1` hangs on bone `i`), every bone revolute at its parent's tip, no stiffness.
    #[must_use]
    pub fn is_chain(&self) -> bool {
        let one_branch = self.parents.iter().enumerate().all(|(i, &p)| p == i.checked_sub(1));
        one_branch && self.plain && !self.has_rest_pose()
    }

    /// The same skeleton with every bone free: what a solve with
    /// [`LimitMode::Ignore`](crate::LimitMode::Ignore) sees, for motion and workspaces that must
    /// agree with it (it builds a skeleton: not for a hot loop).
    #[must_use]
    pub fn without_limits(&self) -> Skeleton {
        let mut bones = self.bones();
        for bone in &mut bones {
            bone.limits = None;
        }
        // The bones passed every check with their limits; without them there is one check
        // fewer (a slide's reach is then its nominal range, as for any unlimited slide).
        Skeleton::new([self.base.x, self.base.y], &bones).expect("ikarus: a valid skeleton stays valid without limits")
    }

    /// Number of bones.
    #[must_use]
    pub fn len(&self) -> usize {
        self.names.len()
    }

    /// Always `false`: a valid skeleton has at least one bone.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Where every root bone starts.
    #[must_use]
    pub fn base(&self) -> Point2<f64> {
        self.base
    }

    /// The bones' names.
    #[must_use]
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// The name of bone `i`.
    ///
    /// # Panics
    /// If `i >= self.len()`.
    #[must_use]
    pub fn name(&self, i: usize) -> &str {
        &self.names[i]
    }

    /// The index of the bone called `name`.
    #[must_use]
    pub fn index_of(&self, name: &str) -> Option<usize> {
        self.index.get(name).copied()
    }

    /// The parent of bone `i`, `None` for a root.
    ///
    /// # Panics
    /// If `i >= self.len()`.
    #[must_use]
    pub fn parent(&self, i: usize) -> Option<usize> {
        self.parents[i]
    }

    /// The parents of every bone.
    #[must_use]
    pub fn parents(&self) -> &[Option<usize>] {
        &self.parents
    }

    /// The children of bone `i`, in the order given.
    ///
    /// # Panics
    /// If `i >= self.len()`.
    pub fn children(&self, i: usize) -> impl ExactSizeIterator<Item = usize> + '_ {
        self.children[self.child_start[i]..self.child_start[i + 1]].iter().copied()
    }

    /// The roots (bones that start at the base), in the order given.
    pub fn roots(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.len()).filter(|&i| self.parents[i].is_none())
    }

    /// The bones from a root down to bone `i`: its ancestors, root first, then `i` itself.
    /// These are the bones whose turning moves bone `i`'s tip. Built on each call (its
    /// length is `i`'s depth): a loop that only visits them walks [`Skeleton::path_to_root`],
    /// a test of one bone asks [`Skeleton::is_on_path`].
    ///
    /// # Panics
    /// If `i >= self.len()`.
    #[must_use]
    pub fn path(&self, i: usize) -> Vec<usize> {
        let mut path: Vec<usize> = self.path_to_root(i).collect();
        path.reverse();
        path
    }

    /// The bones of [`Skeleton::path`] the other way round, without allocating: bone `i`, its
    /// parent, and so on up to its root.
    ///
    /// # Panics
    /// If `i >= self.len()`.
    pub fn path_to_root(&self, i: usize) -> impl Iterator<Item = usize> + '_ {
        assert!(i < self.len(), "ikarus: bone {i} of a skeleton of {} bones", self.len());
        std::iter::successors(Some(i), |&j| self.parents[j])
    }

    /// Whether bone `j` lies on bone `i`'s path from its root (`j` is `i` or one of its
    /// ancestors), that is whether turning bone `j` moves bone `i`'s tip. Constant time: `j`'s
    /// descendants follow it in the depth-first order, so `i` is among them exactly when its
    /// place there falls within `j`'s subtree.
    ///
    /// # Panics
    /// If `i` or `j` is not below [`Skeleton::len`].
    #[must_use]
    pub fn is_on_path(&self, j: usize, i: usize) -> bool {
        let at = self.enter[i];
        self.enter[j] <= at && at < self.leave[j]
    }

    /// The root above bone `i` (the first bone of its [`Skeleton::path`]; a root's is itself).
    ///
    /// # Panics
    /// If `i >= self.len()`.
    #[must_use]
    pub fn root_of(&self, i: usize) -> usize {
        self.root[i]
    }

    /// Every bone once, every parent before its children: a depth-first walk from the roots,
    /// roots and siblings in the order given.
    #[must_use]
    pub fn topological_order(&self) -> &[usize] {
        &self.order
    }

    /// Bone lengths.
    #[must_use]
    pub fn lengths(&self) -> &[f64] {
        &self.lengths
    }

    /// Per-bone limits.
    #[must_use]
    pub fn limits(&self) -> &[Option<JointLimits>] {
        &self.limits
    }

    /// Whether any bone has limits.
    #[must_use]
    pub fn has_limits(&self) -> bool {
        self.limits.iter().any(Option::is_some)
    }

    /// The limits as a [`Bounds`] view, bone `i` bounded by its limits (free if no bone has
    /// limits).
    #[must_use]
    pub fn bounds(&self) -> Bounds<'_> {
        if self.has_limits() { Bounds::new(&self.limits) } else { Bounds::free() }
    }

    /// The joint values the skeleton was built with (its start pose): radians for a revolute
    /// joint, the [`Joint::Prismatic`] extension for a prismatic one.
    #[must_use]
    pub fn start_angles(&self) -> &[f64] {
        &self.start
    }

    /// Each bone's stiffness ([`Bone::stiffness`]; 0 for a bone without a preference).
    #[must_use]
    pub fn stiffness(&self) -> &[f64] {
        &self.stiffness
    }

    /// Each bone's rest angle, radians ([`Bone::rest`], or its start angle).
    #[must_use]
    pub fn rest_angles(&self) -> &[f64] {
        &self.rest
    }

    /// Whether some bone has a stiffness > 0: a rig solve then prefers the rest pose.
    #[must_use]
    pub fn has_rest_pose(&self) -> bool {
        self.stiffness.iter().any(|&s| s > 0.0)
    }

    /// The joint of bone `i` (a prismatic slide normalised).
    ///
    /// # Panics
    /// If `i >= self.len()`.
    #[must_use]
    pub fn joint(&self, i: usize) -> Joint {
        self.joints[i]
    }

    /// Every bone's joint.
    #[must_use]
    pub fn joints(&self) -> &[Joint] {
        &self.joints
    }

    /// Whether some bone has a prismatic joint.
    #[must_use]
    pub fn has_prismatic(&self) -> bool {
        self.joints.iter().any(|j| matches!(j, Joint::Prismatic { .. }))
    }

    /// Every bone's offset as given ([`Bone::offset`]).
    #[must_use]
    pub fn offsets(&self) -> &[Option<[f64; 2]>] {
        &self.offsets
    }

    /// Whether every bone is revolute and starts at its parent's tip (a root at the base): the
    /// shape of today's rigs, whose geometry (annuli of lengths, two-bone triangles) the
    /// solver's reach tests and soft goals use.
    #[must_use]
    pub fn is_plain(&self) -> bool {
        self.plain
    }

    /// The bones as given to [`Skeleton::new`], with the start angles.
    #[must_use]
    pub fn bones(&self) -> Vec<Bone> {
        (0..self.len())
            .map(|i| Bone {
                name: self.names[i].clone(),
                parent: self.parents[i].map(|p| self.names[p].clone()),
                length: self.lengths[i],
                angle: match self.joints[i] {
                    Joint::Revolute => self.start[i],
                    Joint::Prismatic { .. } => self.fixed[i],
                },
                limits: self.limits[i],
                stiffness: self.stiffness[i],
                rest: (self.rest[i] != self.start[i]).then_some(self.rest[i]),
                offset: self.offsets[i],
                joint: self.joints[i],
            })
            .collect()
    }

    /// The longest path of lengths from the base to a tip: no tip is ever farther from the
    /// base. For a one-branch skeleton, its chain's [`Chain::max_reach`](crate::Chain::max_reach).
    #[must_use]
    pub fn max_reach(&self) -> f64 {
        self.reach
    }

    /// Checks `angles` as a pose of this skeleton: one finite angle per bone, each within its
    /// limits.
    pub fn check_angles(&self, angles: &[f64]) -> Result<(), SkeletonError> {
        self.check_angles_within(angles, self.bounds())
    }

    /// Checks `angles` as a pose of this skeleton ignoring its limits: one finite angle per
    /// bone.
    pub fn check_angles_ignoring_limits(&self, angles: &[f64]) -> Result<(), SkeletonError> {
        self.check_angles_within(angles, Bounds::free())
    }

    fn check_angles_within(&self, angles: &[f64], bounds: Bounds<'_>) -> Result<(), SkeletonError> {
        if angles.len() != self.len() {
            return Err(SkeletonError::AnglesLength { expected: self.len(), got: angles.len() });
        }
        check_angles(&self.names, &self.joints, angles, bounds)
    }
}

/// Each bone's stiffness and rest angle (its start angle unless given), checked: a stiffness
/// finite and ≥ 0, a rest angle finite and within the bone's limits.
fn rest_pose(
    bones: &[Bone],
    joints: &[Joint],
    limits: &[Option<JointLimits>],
) -> Result<(Vec<f64>, Vec<f64>), SkeletonError> {
    let mut stiffness = Vec::with_capacity(bones.len());
    let mut rest = Vec::with_capacity(bones.len());
    for (index, ((bone, lim), &joint)) in bones.iter().zip(limits).zip(joints).enumerate() {
        let name = || bone.name.clone();
        let s = bone.stiffness;
        if !s.is_finite() {
            return Err(SkeletonError::NonFinite { index, name: name(), field: BoneField::Stiffness, value: s });
        }
        if s < 0.0 {
            return Err(SkeletonError::NegativeStiffness { index, name: name(), value: s });
        }
        let r = bone.rest.unwrap_or(joint_value(bone.angle, joint));
        if !r.is_finite() {
            return Err(SkeletonError::NonFinite { index, name: name(), field: BoneField::Rest, value: r });
        }
        if let Some(l) = lim {
            if !l.contains(r) {
                let (min, max) = (l.min(), l.max());
                return Err(match joint {
                    Joint::Revolute => SkeletonError::RestOutsideLimits { index, name: name(), value: r, min, max },
                    Joint::Prismatic { .. } => {
                        let field = BoneField::Rest;
                        SkeletonError::ExtensionOutsideLimits { index, name: name(), field, value: r, min, max }
                    }
                });
            }
        }
        stiffness.push(s);
        rest.push(r);
    }
    Ok((stiffness, rest))
}

fn check_angles(names: &[String], joints: &[Joint], angles: &[f64], bounds: Bounds<'_>) -> Result<(), SkeletonError> {
    let Some(violation) = bounds.first_violation(angles) else { return Ok(()) };
    let (Violation::NonFinite { index, .. } | Violation::Outside { index, .. }) = violation;
    let (name, joint) = (names[index].clone(), joints[index]);
    let field = match joint {
        Joint::Revolute => BoneField::Angle,
        Joint::Prismatic { .. } => BoneField::Extension,
    };
    Err(match (violation, joint) {
        (Violation::NonFinite { value, .. }, _) => SkeletonError::NonFinite { index, name, field, value },
        (Violation::Outside { value, limits, .. }, Joint::Revolute) => {
            SkeletonError::AngleOutsideLimits { index, name, value, min: limits.min(), max: limits.max() }
        }
        (Violation::Outside { value, limits, .. }, Joint::Prismatic { .. }) => {
            let (min, max) = (limits.min(), limits.max());
            SkeletonError::ExtensionOutsideLimits { index, name, field, value, min, max }
        }
    })
}

/// A bone's start joint value: its angle (revolute) or its extension (prismatic).
fn joint_value(angle: f64, joint: Joint) -> f64 {
    match joint {
        Joint::Revolute => angle,
        Joint::Prismatic { extension, .. } => extension,
    }
}

/// Each bone's joint (a slide checked finite and not zero, then normalised; by default along
/// the bone's rest direction), its fixed angle, and its offset checked finite.
type JointsOf = (Vec<Joint>, Vec<f64>, Vec<Option<[f64; 2]>>);
fn joints_of(bones: &[Bone]) -> Result<JointsOf, SkeletonError> {
    let (mut joints, mut fixed, mut offsets) = (Vec::new(), Vec::new(), Vec::new());
    for (index, bone) in bones.iter().enumerate() {
        let name = || bone.name.clone();
        if let Some([x, y]) = bone.offset {
            if !x.is_finite() || !y.is_finite() {
                return Err(SkeletonError::NonFinitePair { index, name: name(), field: BoneField::Offset, x, y });
            }
        }
        offsets.push(bone.offset);
        match bone.joint {
            Joint::Revolute => {
                joints.push(Joint::Revolute);
                fixed.push(0.0);
            }
            Joint::Prismatic { slide, extension } => {
                if !bone.angle.is_finite() {
                    let (field, value) = (BoneField::Angle, bone.angle);
                    return Err(SkeletonError::NonFinite { index, name: name(), field, value });
                }
                let [x, y] = slide.unwrap_or([math::cos(bone.angle), math::sin(bone.angle)]);
                if !x.is_finite() || !y.is_finite() {
                    return Err(SkeletonError::NonFinitePair { index, name: name(), field: BoneField::Slide, x, y });
                }
                let norm = math::hypot(x, y);
                if norm == 0.0 {
                    return Err(SkeletonError::ZeroSlide { index, name: name(), x, y });
                }
                joints.push(Joint::Prismatic { slide: Some([x / norm, y / norm]), extension });
                fixed.push(bone.angle);
            }
        }
    }
    Ok((joints, fixed, offsets))
}

#[cfg(test)]
mod tests;
