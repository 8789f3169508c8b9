//! A skeleton with its effectors as a [`Model`] of the solver core: forward kinematics into
//! the base and every bone's tip, the stacked task error and Jacobian of every effector (pins
//! and primary goals first, secondary goals after), and per-effector measurement and status.

use nalgebra::Point2;

use super::algebra::dynamic::{Dynamic, merit_of, primary_merit};
use super::model::Problem;
use super::model::{Model, Posture, ScratchOf};
use super::task::{EffectorOutcome, Priority, RigTask, RigTaskError};
use super::{Outcome, SolveOptions, Status};
use crate::angle::wrap_angle;
use crate::chain::{JointLimits, annulus_inner};
use crate::kinematics::EndEffector;
use crate::limits::Bounds;
use crate::math;
use crate::math::distance;
use crate::rng::SplitMix64;
use crate::skeleton::{Joint, Skeleton};
use std::f64::consts::PI;

/// A rig's step that lowers the merit by less than this share of it counts toward the stall
/// window: against its limits a rig creeps for many iterations with steps that change nothing
/// (each accepted by the line search for a decrease in the fifteenth digit) before its pose
/// stands still, where a restart does better.
const PROGRESS_FLOOR: f64 = 1e-6;

/// The longest secondary error one step works on, as a share of the skeleton's reach.
const SECONDARY_REACH: f64 = 0.1;

/// What a skeleton's forward kinematics writes: the base and every bone's tip (bone `i`'s at
/// `points[i + 1]`), and every bone's absolute direction.
#[derive(Debug, Clone, Default)]
pub(super) struct RigPoints {
    pub(super) points: Vec<Point2<f64>>,
    pub(super) directions: Vec<f64>,
    /// Every bone's origin, for a skeleton that is not [plain](Skeleton::is_plain) (a plain
    /// one's origins are its parents' tips; then empty).
    pub(super) starts: Vec<Point2<f64>>,
}

impl RigPoints {
    /// Sizes the buffers for `skeleton`.
    fn fit(&mut self, skeleton: &Skeleton) {
        let n = skeleton.len();
        self.points.resize(n + 1, Point2::origin());
        self.directions.resize(n, 0.0);
        self.starts.resize(if skeleton.is_plain() { 0 } else { n }, Point2::origin());
    }

    /// Forward kinematics of `angles` on `skeleton` into these buffers (sized by `fit`).
    #[inline]
    pub(super) fn compute(&mut self, skeleton: &Skeleton, angles: &[f64]) {
        if self.starts.is_empty() {
            skeleton.points_into(angles, &mut self.points, &mut self.directions);
        } else {
            self.points[0] = skeleton.base();
            skeleton.forward_into(angles, &mut self.starts, &mut self.points[1..], &mut self.directions);
        }
    }
}

/// One effector as the core sees it.
#[derive(Debug, Clone, Copy)]
pub(super) struct Eff {
    bone: usize,
    target: Point2<f64>,
    orientation: Option<f64>,
    /// `√weight`: the scale of its rows.
    root_weight: f64,
    /// Whether its target is out of the reach of the bones from the base to it, limits ignored.
    out_of_reach: bool,
    /// Whether it is in the first priority level (a pin or a primary goal).
    pub(super) primary: bool,
    /// Its place in [`Outcome::effectors`].
    pub(super) slot: usize,
}

impl Eff {
    fn rows(&self) -> usize {
        if self.orientation.is_some() { 3 } else { 2 }
    }
}

/// A skeleton solve's data, rebuilt per solve in buffers reused across solves.
#[derive(Debug, Clone, Default)]
pub(super) struct RigWork {
    /// The effectors in row order: pins and primary goals, then secondary goals.
    pub(super) effs: Vec<Eff>,
    /// The limits the solve enforces: the skeleton's (unless ignored), narrowed by bends.
    pub(super) limits: Vec<Option<JointLimits>>,
    /// The start pose, with bent joints turned to their side.
    pub(super) start: Vec<f64>,
    /// Rows of the first priority level.
    pub(super) primary_rows: usize,
    /// Where the first level, solved again alone, starts from (the pose the whole solve
    /// ended on): its own buffer, since that solve's restarts draw into its scratch's.
    pub(super) resume: Vec<f64>,
    /// The rest pose's column weights and pull shares (see [`Posture`]); empty when no bone
    /// of the skeleton has a stiffness.
    pub(super) rest_scale: Vec<f64>,
    pub(super) rest_pull: Vec<f64>,
    pub(super) fk: RigPoints,
    lengths: Vec<f64>,
}

impl RigWork {
    /// Builds the solve's effectors, limits and start from `task` (already validated) and the
    /// start pose `start`; writes the effectors' identities into `out.effectors`.
    pub(super) fn setup(
        &mut self,
        skeleton: &Skeleton,
        start: &[f64],
        task: &RigTask,
        opts: &SolveOptions,
        out: &mut Outcome,
    ) -> Result<(), RigTaskError> {
        self.fk.fit(skeleton);
        self.fk.compute(skeleton, start);
        let ignore = opts.limits == super::LimitMode::Ignore;
        self.limits.clear();
        self.limits.extend(skeleton.limits().iter().map(|l| if ignore { None } else { *l }));
        self.start.clear();
        self.start.extend_from_slice(start);
        self.rest_scale.clear();
        self.rest_pull.clear();
        if skeleton.has_rest_pose() {
            let stiffness = skeleton.stiffness();
            self.rest_scale.extend(stiffness.iter().map(|s| 1.0 / (1.0 + s).sqrt()));
            self.rest_pull.extend(stiffness.iter().map(|s| s / (1.0 + s)));
        }
        self.apply_bends(skeleton, start, task)?;
        if self.limits.iter().all(Option::is_none) {
            self.limits.clear();
        }

        out.effectors.clear();
        self.effs.clear();
        for (slot, g) in task.goals.iter().enumerate() {
            // (Softening assumes the two bones' triangle: plain skeletons only.)
            let target = match skeleton.parent(g.bone) {
                Some(parent) if g.softness > 0.0 && skeleton.is_plain() => {
                    let root = match skeleton.parent(parent) {
                        Some(q) => self.fk.points[q + 1],
                        None => skeleton.base(),
                    };
                    let reach = skeleton.lengths()[g.bone] + skeleton.lengths()[parent];
                    g.softened_target(root, reach)
                }
                _ => g.goal.target(),
            };
            out.effectors.push(placeholder(g.bone, false, target));
            let eff = Eff {
                bone: g.bone,
                target,
                orientation: g.goal.orientation(),
                root_weight: g.weight.sqrt(),
                slot,
                out_of_reach: false,
                primary: g.priority == Priority::Primary,
            };
            let out_of_reach = self.out_of_reach(skeleton, &eff, opts.tolerance);
            self.effs.push(Eff { out_of_reach, ..eff });
        }
        for (k, pin) in task.pins.iter().enumerate() {
            let target = self.fk.points[pin.bone + 1];
            let orientation = pin.orientation.then_some(self.fk.directions[pin.bone]);
            out.effectors.push(placeholder(pin.bone, true, target));
            let slot = task.goals.len() + k;
            let eff =
                Eff { bone: pin.bone, target, orientation, root_weight: 1.0, slot, out_of_reach: false, primary: true };
            self.effs.push(eff);
        }
        // Row order: the first level (pins, primary goals), then the secondary goals; stable.
        // Within a level, limbs of one root together: effectors on different roots share no
        // bone, so the task's matrices are then block-diagonal in row order, which the
        // factorisations skip over.
        self.effs.sort_by_key(|e| (!e.primary, skeleton.root_of(e.bone)));
        self.primary_rows = self.effs.iter().filter(|e| e.primary).map(Eff::rows).sum();
        Ok(())
    }

    /// Whether `eff`'s target is beyond the reach of the bones from the base to it (by more
    /// than `tolerance`), limits ignored (never, for a skeleton that is not plain): the annulus of their lengths, or with an orientation
    /// the wrist's annulus of all but the last.
    fn out_of_reach(&mut self, skeleton: &Skeleton, eff: &Eff, tolerance: f64) -> bool {
        if !skeleton.is_plain() {
            // Offsets and slides leave the annulus of lengths: no claim is made.
            return false;
        }
        // Root first, as a chain of these bones would sum them.
        self.lengths.clear();
        self.lengths.extend(skeleton.path_to_root(eff.bone).map(|j| skeleton.lengths()[j]));
        self.lengths.reverse();
        let base = skeleton.base();
        let (point, lengths) = match eff.orientation {
            None => (eff.target, &self.lengths[..]),
            Some(phi) => {
                let (last, rest) = self.lengths.split_last().expect("a path holds its bone");
                (eff.target - *last * nalgebra::Vector2::new(math::cos(phi), math::sin(phi)), rest)
            }
        };
        let d = distance(point.x - base.x, point.y - base.y);
        if lengths.is_empty() {
            return d > tolerance;
        }
        let outer: f64 = lengths.iter().sum();
        d > outer + tolerance || d < annulus_inner(lengths) - tolerance
    }
}

/// An effector's outcome before the solve measures it.
fn placeholder(bone: usize, pinned: bool, target: Point2<f64>) -> EffectorOutcome {
    EffectorOutcome {
        bone,
        pinned,
        status: Status::IterationLimit,
        error: f64::INFINITY,
        angle_error: 0.0,
        tip: Point2::origin(),
        orientation: 0.0,
        target,
    }
}

/// A skeleton and its effectors, borrowed for one solve.
#[derive(Debug, Clone, Copy)]
pub(super) struct Rig<'a> {
    pub(super) skeleton: &'a Skeleton,
    pub(super) effs: &'a [Eff],
    pub(super) limits: &'a [Option<JointLimits>],
    pub(super) primary_rows: usize,
    /// The solve's tolerance (the merit's weight of the first level comes from it).
    pub(super) tolerance: f64,
    /// The skeleton's rest-pose preference, if it has one.
    pub(super) posture: Option<Posture<'a>>,
}

impl Rig<'_> {
    /// Whether the task has two priority levels.
    pub(super) fn levels(&self) -> bool {
        self.primary_rows > 0 && self.primary_rows < self.effs.iter().map(Eff::rows).sum()
    }

    /// The merit of the effectors' weighted squared errors `sq(eff)`: summed per priority level
    /// (the first `primary_rows` rows, then the rest), in the effectors' order.
    #[inline]
    fn merit(&self, opts: &SolveOptions, sq: impl Fn(&Eff) -> f64) -> f64 {
        let (mut first, mut second, mut row) = (0.0, 0.0, 0);
        for eff in self.effs {
            if row < self.primary_rows {
                first += sq(eff);
            } else {
                second += sq(eff);
            }
            row += eff.rows();
        }
        merit_of(first, second, self.levels(), primary_merit(opts.tolerance))
    }

    /// Where bone `j` starts, from the points of forward kinematics.
    #[inline]
    fn start_of(&self, points: &RigPoints, j: usize) -> Point2<f64> {
        if !points.starts.is_empty() {
            return points.starts[j];
        }
        match self.skeleton.parent(j) {
            Some(q) => points.points[q + 1],
            None => points.points[0],
        }
    }
}

impl Model for Rig<'_> {
    type Goal = ();
    type Points = RigPoints;
    type Alg = Dynamic;
    const PROGRESS_FLOOR: Option<f64> = Some(PROGRESS_FLOOR);

    #[inline]
    fn len(&self) -> usize {
        self.skeleton.len()
    }

    fn fit(&self, s: &mut ScratchOf<Self>) {
        let n = self.skeleton.len();
        for p in [&mut s.joints, &mut s.trial_joints] {
            p.fit(self.skeleton);
        }
        s.fit_joints(n);
        let rows = self.effs.iter().map(Eff::rows).sum();
        s.alg.shape(n, rows, self.primary_rows);
        s.alg.secondary_reach = SECONDARY_REACH * self.skeleton.max_reach();
        s.alg.primary_merit = primary_merit(self.tolerance);
        s.alg.blocks.clear();
        s.alg.blocks.extend(self.effs.iter().map(Eff::rows));
        // Column j's nonzero rows: those of the effectors below bone j.
        let (start, rows) = (&mut s.alg.nz_start, &mut s.alg.nz_rows);
        start.clear();
        rows.clear();
        for j in 0..n {
            start.push(rows.len());
            let mut row = 0;
            for eff in self.effs {
                if self.skeleton.is_on_path(j, eff.bone) {
                    rows.extend(row..row + eff.rows());
                }
                row += eff.rows();
            }
        }
        start.push(rows.len());
    }

    fn max_reach(&self) -> f64 {
        self.skeleton.max_reach()
    }

    fn limits(&self) -> &[Option<JointLimits>] {
        self.limits
    }

    fn bounds(&self) -> Bounds<'_> {
        if self.limits.is_empty() { Bounds::free() } else { Bounds::new(self.limits) }
    }

    #[inline]
    fn posture(&self) -> Option<Posture<'_>> {
        self.posture
    }

    #[inline]
    fn forward_into(&self, angles: &[f64], points: &mut RigPoints) -> f64 {
        points.compute(self.skeleton, angles);
        angles.iter().sum()
    }

    #[inline]
    fn frame_points(points: &RigPoints) -> &[Point2<f64>] {
        &points.points
    }

    fn measure(
        &self,
        _: &(),
        opts: &SolveOptions,
        points: &RigPoints,
        _phi: f64,
        out: &mut Outcome,
        alg: &mut Dynamic,
    ) {
        let w_o = opts.orientation_weight;
        let (mut error, mut angle_error) = (0.0f64, 0.0f64);
        let mut row = 0;
        for eff in self.effs {
            let tip = points.points[eff.bone + 1];
            let phi = points.directions[eff.bone];
            let (dx, dy) = (eff.target.x - tip.x, eff.target.y - tip.y);
            let turn = eff.orientation.map(|g| wrap_angle(g - phi));
            let o = &mut out.effectors[eff.slot];
            o.error = distance(dx, dy);
            o.angle_error = turn.map_or(0.0, f64::abs);
            o.tip = tip;
            o.orientation = phi;
            error = error.max(o.error);
            angle_error = angle_error.max(o.angle_error);
            let rw = eff.root_weight;
            alg.e[row] = rw * dx;
            alg.e[row + 1] = rw * dy;
            if let Some(t) = turn {
                alg.e[row + 2] = rw * w_o * t;
            }
            row += eff.rows();
        }
        out.error = error;
        out.angle_error = angle_error;
        let first = &out.effectors[0];
        out.end_effector = EndEffector { position: first.tip, orientation: first.orientation };
    }

    fn jacobian(&self, _: &(), opts: &SolveOptions, points: &RigPoints, alg: &mut Dynamic) {
        // Only the entries of each effector's path are written; the rest stay the zeros of
        // `Dynamic::shape`.
        let w_o = opts.orientation_weight;
        alg.gram_valid = false;
        let mut row = 0;
        for eff in self.effs {
            let tip = points.points[eff.bone + 1];
            let rw = eff.root_weight;
            for j in self.skeleton.path_to_root(eff.bone) {
                let [dx, dy, dphi] = self.skeleton.column(j, tip, self.start_of(points, j), &points.directions);
                alg.jacobian[(row, j)] = rw * dx;
                alg.jacobian[(row + 1, j)] = rw * dy;
                if eff.orientation.is_some() {
                    alg.jacobian[(row + 2, j)] = rw * w_o * dphi;
                }
            }
            row += eff.rows();
        }
    }

    fn trial_error(&self, _: &(), opts: &SolveOptions, points: &RigPoints, _phi: f64) -> f64 {
        let w_o = opts.orientation_weight;
        self.merit(opts, |eff| {
            let tip = points.points[eff.bone + 1];
            let rw = eff.root_weight;
            let turn = eff.orientation.map_or(0.0, |g| rw * w_o * wrap_angle(g - points.directions[eff.bone]));
            math::square(rw * (eff.target.x - tip.x)) + math::square(rw * (eff.target.y - tip.y)) + turn * turn
        })
    }

    fn best_key(&self, opts: &SolveOptions, out: &Outcome, _alg: &Dynamic) -> f64 {
        self.merit(opts, |eff| {
            let o = &out.effectors[eff.slot];
            let w = eff.root_weight * eff.root_weight;
            w * (o.error * o.error + math::square(opts.orientation_weight * o.angle_error))
        })
    }

    fn is_out_of_reach(&self, _: &(), _tolerance: f64) -> bool {
        self.effs.iter().any(|e| e.out_of_reach)
    }

    fn judge(&self, _: &(), opts: &SolveOptions, out: &mut Outcome) {
        let overall = out.status;
        for eff in self.effs {
            let o = &mut out.effectors[eff.slot];
            let within = o.error <= opts.tolerance && o.angle_error <= opts.angle_tolerance;
            o.status = if within {
                Status::Reached
            } else if eff.out_of_reach {
                Status::Unreachable
            } else {
                match overall {
                    Status::Reached | Status::Unreachable => Status::Stalled,
                    other @ (Status::Stalled | Status::IterationLimit | Status::Interrupted) => other,
                }
            };
        }
    }

    /// The joints on the path of an effector the attempt missed are drawn anew, uniformly
    /// inside their bounds (for a free joint: ±π around the start of a revolute one, ±its
    /// bone's length around the start of a prismatic one); the others keep the
    /// attempt's angles, so that a restart does not undo the limbs that were reached. (Drawing
    /// every joint, a rig of four limbs would need every limb to succeed in the same attempt;
    /// and a chain's restarts begin near the start pose, which suits one limb but leaves every
    /// limb of a rig in the basin it failed in for most of its attempts.)
    fn settle_restart(&self, p: &Problem<'_, Self>, k: u32, out: &Outcome, restart: &mut [f64], free: &mut [bool]) {
        let opts = p.opts;
        free.fill(false);
        for eff in self.effs {
            let o = &out.effectors[eff.slot];
            if !(o.error <= opts.tolerance && o.angle_error <= opts.angle_tolerance) {
                for j in self.skeleton.path_to_root(eff.bone) {
                    free[j] = true;
                }
            }
        }
        let seed = opts.restarts.map_or(0, |r| r.seed);
        let mut rng = SplitMix64(seed ^ 0x005E_ED0F_B0E5 ^ u64::from(k).wrapping_mul(0x9E37_79B9_7F4A_7C15));
        let start = self.skeleton.start_angles();
        for (i, ((r, &f), &a)) in restart.iter_mut().zip(free.iter()).zip(out.pose.angles()).enumerate() {
            let u = rng.unit();
            *r = if f {
                let free = match self.skeleton.joint(i) {
                    Joint::Revolute => PI,
                    Joint::Prismatic { .. } => self.skeleton.lengths()[i],
                };
                let (lo, hi) = p.bounds.get(i).map_or((start[i] - free, start[i] + free), |l| (l.min(), l.max()));
                lo + u * (hi - lo)
            } else {
                a
            };
        }
    }

    fn ccd_sweep(_: &Problem<'_, Self>, _: &[f64], _: &RigPoints, _: &mut [f64], _: &mut RigPoints) -> f64 {
        // Refused before the solve starts (`Method::solves_rigs`); a NaN would stall it.
        f64::NAN
    }

    fn fabrik_iterate(_: &Problem<'_, Self>, _: &[f64], _: &RigPoints, _: &mut [f64], _: &mut RigPoints) -> f64 {
        f64::NAN
    }
}
