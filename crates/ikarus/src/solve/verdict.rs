//! The certified-reach verdict before a solve: with limits enforced, a goal the exact region
//! ([`Region`]) does not hold cannot be reached by any pose, so the solve ends at once as
//! [`Status::Unreachable`](super::Status::Unreachable) with the pose that reaches the nearest
//! reachable point, instead of searching with every restart first.
//!
//! A position goal is judged against the chain's region, within the tolerance. An orientation
//! goal is judged by its wrist point (the goal moved back along the last link) against the
//! region of the chain without its last link ([`Region::wrist`]), within the tolerance plus the
//! last link's length times the angle tolerance (how far the wrist moves over the orientations
//! that count as reached). That region is exact when the last joint turns freely and holds the
//! true one otherwise, so the verdict `unreachable` is always right; a goal it lets through may
//! still be out of reach, and is then searched for as before.
//!
//! The regions are built on the first solve of a chain with limits (0.2 ms for the seed arm,
//! about 1 ms for eight links, several for the 20-link tentacle) and kept by the
//! [`Solver`](super::Solver) until it solves for a chain with other lengths, limits or base.
//! They are also kept for the process, for the last [`SHARED_REGIONS`] chains: a new solver on a
//! chain seen before (each [`track::plan`](crate::track::plan) and each server request makes
//! one) takes them instead of building them again. A region is a function of the chain's
//! lengths, limits and base alone, so a shared one is the one the solver would build, bit for
//! bit. They are built with [`Region::try_of`]: within its
//! work cap (a chain whose region needs more is solved by searching, without a verdict, and the
//! solver remembers not to try again for it) and watching the solve's interrupt (an interrupted
//! build leaves nothing behind, and the solve ends `interrupted` at its first check).

use std::sync::{Arc, Mutex};

use nalgebra::{Point2, Vector2};

use crate::chain::Chain;
use crate::goal::Goal;
use crate::math;
use crate::reach::{Region, RegionError, RegionOptions};

/// The regions of the last chain checked, and what identifies that chain.
#[derive(Debug, Clone, Default)]
pub(super) struct ReachCache {
    key: Vec<f64>,
    /// `Some(None)`: tried, and over the work cap.
    position: Option<Option<Arc<Region>>>,
    /// `Some(None)`: tried, and the chain has one link (no wrist region) or it was over the
    /// work cap.
    wrist: Option<Option<Arc<Region>>>,
}

/// Which of a chain's two regions.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Position,
    Wrist,
}

/// A region built in this process: the chain's key (as [`ReachCache`] keeps it), which region,
/// and what the build gave (`None`: none, or over the work cap).
struct Shared {
    key: Vec<f64>,
    kind: Kind,
    region: Option<Arc<Region>>,
}

/// How many built regions the process keeps (the most recently built).
pub(crate) const SHARED_REGIONS: usize = 8;

/// The regions built in this process, oldest first.
static SHARED: Mutex<Vec<Shared>> = Mutex::new(Vec::new());

/// The region of `kind` for the chain with `key`, if this process built it before.
fn shared(key: &[f64], kind: Kind) -> Option<Option<Arc<Region>>> {
    let list = SHARED.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    list.iter().find(|s| s.kind == kind && s.key == key).map(|s| s.region.clone())
}

/// Keeps what a build gave for the chain with `key`, dropping the oldest beyond
/// [`SHARED_REGIONS`].
fn share(key: &[f64], kind: Kind, region: Option<Arc<Region>>) {
    let mut list = SHARED.lock().unwrap_or_else(std::sync::PoisonError::into_inner);
    if list.iter().any(|s| s.kind == kind && s.key == key) {
        return;
    }
    if list.len() == SHARED_REGIONS {
        list.remove(0);
    }
    list.push(Shared { key: key.to_vec(), kind, region });
}

/// The region in `slot`: taken from the process's built regions, or built by `build` if it was
/// not tried yet: `None` when there is none (`build` gave none or ran over its cap, remembered)
/// or the build was interrupted (not remembered: the next solve tries again).
fn built<'s>(
    slot: &'s mut Option<Option<Arc<Region>>>,
    (key, kind): (&[f64], Kind),
    build: impl FnOnce() -> Result<Option<Region>, RegionError>,
) -> Option<&'s Region> {
    if slot.is_none() {
        *slot = match shared(key, kind) {
            Some(region) => Some(region),
            None => {
                let region = match build() {
                    Ok(region) => region.map(Arc::new),
                    Err(RegionError::TooComplex { .. }) => None,
                    Err(_) => return None,
                };
                share(key, kind, region.clone());
                Some(region)
            }
        };
    }
    slot.as_ref().and_then(Option::as_deref)
}

/// What the verdict found: the distance from the goal to the region (0 inside), and whether it
/// is farther than the tolerance (the pose reaching the nearest point is then in `pose`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Found {
    pub(super) distance: f64,
    pub(super) unreachable: bool,
}

impl ReachCache {
    /// Forgets the regions if `chain` is not the chain they were built for.
    fn fit(&mut self, chain: &Chain) {
        let base = chain.base();
        let mut same = self.key.len() == 2 + 3 * chain.len() && self.key[0] == base.x && self.key[1] == base.y;
        let entries = chain.lengths().iter().zip(chain.limits()).map(|(&l, lim)| {
            let (lo, hi) = lim.map_or((f64::NEG_INFINITY, f64::INFINITY), |lim| (lim.min(), lim.max()));
            [l, lo, hi]
        });
        if same {
            same = entries.clone().enumerate().all(|(k, e)| self.key[2 + 3 * k..5 + 3 * k] == e);
        }
        if !same {
            self.key.clear();
            self.key.extend([base.x, base.y]);
            self.key.extend(entries.flatten());
            self.position = None;
            self.wrist = None;
        }
    }

    /// Judges `goal` for `chain` with its limits; writes the pose reaching the nearest
    /// reachable point into `pose` when the goal is out of reach. `None` when there is nothing
    /// to judge by (an orientation goal on a one-link chain, a region over its work cap, or a
    /// build stopped by `interrupt`).
    pub(super) fn judge(
        &mut self,
        chain: &Chain,
        goal: &Goal,
        tolerances: (f64, f64),
        interrupt: Option<&crate::Interrupt>,
        pose: &mut Vec<f64>,
    ) -> Option<Found> {
        let (tolerance, angle_tolerance) = tolerances;
        self.fit(chain);
        let target = goal.target();
        let options = RegionOptions { limits: true, interrupt: interrupt.cloned(), ..RegionOptions::default() };
        match goal.orientation() {
            None => {
                let region = built(&mut self.position, (&self.key, Kind::Position), || {
                    Region::try_of(chain, &options).map(Some)
                })?;
                if !region.is_checked() {
                    return None;
                }
                let v = region.verdict(target, tolerance);
                if !v.reachable {
                    region.pose_reaching_into(target, pose);
                }
                Some(Found { distance: v.distance, unreachable: !v.reachable })
            }
            Some(direction) => {
                let region = built(&mut self.wrist, (&self.key, Kind::Wrist), || Region::try_wrist(chain, &options))?;
                if !region.is_checked() {
                    return None;
                }
                let n = chain.len();
                let last = chain.lengths()[n - 1];
                let wrist: Point2<f64> = target - last * Vector2::new(math::cos(direction), math::sin(direction));
                let v = region.verdict(wrist, tolerance + last * angle_tolerance);
                if !v.reachable {
                    wrist_pose(chain, region, wrist, direction, pose);
                }
                Some(Found { distance: v.distance, unreachable: !v.reachable })
            }
        }
    }

    /// A start pose for the first restart of a solve that [`ReachCache::judge`] let through
    /// (so the regions are built, for this chain): the pose the region reads off for the
    /// boundary point nearest the goal (for an orientation goal, nearest its wrist, with the
    /// last link pointed as asked), moved a share [`SEED_INSET`] of the way toward the middle
    /// of every limited joint's range. `false` (and `pose` untouched) when there is no region
    /// to read it from.
    ///
    /// Why: a lock-mode solve that stalls against a limit from the arm's start pose stalls
    /// there again from the first restarts, which start near the start pose: on the bench's
    /// seed arm (`limits-position`) the 42 goals of 1000 that restarted stalled in the same
    /// corner from their first two (20 goals) or nine (22) attempts. The boundary pose lies on
    /// the branch of poses that reaches the goal's side of the region: from it, every goal of
    /// every `limits-*` bench set (seed, seven, tentacle) that restarts is reached by restart 1,
    /// where they took up to 10 restarts before. It is only a start: a boundary pose is often
    /// singular (links in line, or joints at their limits: on the tentacle about a third of
    /// those starts stalled within two iterations), so the inset moves it inside.
    pub(super) fn seed_pose(&self, chain: &Chain, goal: &Goal, pose: &mut Vec<f64>) -> bool {
        let target = goal.target();
        match goal.orientation() {
            None => match &self.position {
                Some(Some(region)) if region.is_checked() => {
                    region.pose_reaching_into(target, pose);
                }
                _ => return false,
            },
            Some(direction) => match &self.wrist {
                Some(Some(region)) if region.is_checked() => {
                    let last = chain.lengths()[chain.len() - 1];
                    let wrist = target - last * Vector2::new(math::cos(direction), math::sin(direction));
                    wrist_pose(chain, region, wrist, direction, pose);
                }
                _ => return false,
            },
        }
        for (a, lim) in pose.iter_mut().zip(chain.limits()) {
            if let Some(l) = lim {
                *a = l.clamp(*a + SEED_INSET * (0.5 * (l.min() + l.max()) - *a));
            }
        }
        true
    }
}

/// How far [`ReachCache::seed_pose`] moves each limited joint toward the middle of its range,
/// as a share of the way.
const SEED_INSET: f64 = 0.05;

/// The pose putting the wrist (the chain without its last link) on the point of `region`
/// nearest `wrist`, and the last link pointing along `direction` (the nearest it can within
/// its range), into `pose`.
fn wrist_pose(chain: &Chain, region: &Region, wrist: Point2<f64>, direction: f64, pose: &mut Vec<f64>) {
    let n = chain.len();
    region.pose_reaching_into(wrist, pose);
    // The last joint points the last link as the goal asks, within its range.
    let before: f64 = pose.iter().sum();
    let wanted = direction - before;
    let angle = match chain.limits()[n - 1] {
        Some(l) => l.nearest_equivalent(wanted, 0.5 * (l.min() + l.max())).unwrap_or_else(|| l.nearer_end(wanted)),
        None => crate::angle::wrap_angle(wanted),
    };
    pose.push(angle);
}

#[cfg(test)]
mod tests {
    use std::f64::consts::PI;

    use nalgebra::Point2;

    use crate::chain::{Chain, Link};
    use crate::fixtures::{limited_arm as limited, seed_arm_limited as seed, seven_link_arm as seven};
    use crate::goal::Goal;
    use crate::kinematics::end_effector;
    use crate::limits::JointLimits;
    use crate::math;
    use crate::reach::Region;
    use crate::rng::SplitMix64;
    use crate::solve::{LimitMode, Method, SolveOptions, Solver, Status};

    #[test]
    fn a_goal_outside_the_region_is_answered_at_once_with_the_nearest_pose() {
        let chain = seed();
        let region = Region::of(&chain, true);
        let goal = Goal::position(-3.0, -1.0).unwrap();
        let out = Solver::new(SolveOptions::default()).unwrap().solve(&chain, chain.start_pose(), &goal).unwrap();
        assert_eq!(out.status, Status::Unreachable);
        assert_eq!((out.iterations, out.restarts), (1, 0));
        let d = region.distance(goal.target());
        assert_eq!(out.reach_distance, Some(d));
        assert!((out.error - d).abs() < 1e-9, "{} vs {d}", out.error);
        assert!((out.end_effector.position - region.nearest(goal.target())).norm() < 1e-9);
        for (a, l) in out.pose.angles().iter().zip(chain.limits()) {
            assert!(l.unwrap().contains(*a));
        }
        // Without the verdict the search runs every restart and ends no closer.
        let searched = SolveOptions { reach_verdict: false, ..SolveOptions::default() };
        let slow = Solver::new(searched).unwrap().solve(&chain, chain.start_pose(), &goal).unwrap();
        assert_ne!(slow.status, Status::Reached);
        assert!(slow.iterations > 1 && slow.reach_distance.is_none());
        assert!(slow.error >= d - 1e-9, "{} < {d}", slow.error);
    }

    /// The region's nearest pose recovers its angles from points, and can round an ulp or two
    /// past the limit it lies on (here the elbow's upper limit: 1.0779494873184452 against
    /// 1.077949487318445, found by `rig_motion_properties` tracking this arm): the answer is
    /// clamped back, so a pose outside the limits is never handed out.
    #[test]
    fn the_nearest_pose_keeps_within_the_limits_it_lies_on() {
        let elbow = JointLimits::new(-0.9742445137674658, 1.077949487318445).unwrap();
        let chain =
            Chain::new([0.0, 0.0], &[Link::new(0.3, 0.0), Link::new(0.3, 0.8333026795398881).with_limits(elbow)])
                .unwrap();
        let start = chain.pose(vec![-0.040009201910397196, 1.008558209291579]).unwrap();
        let goal = Goal::position(0.46555014001115286, 0.21029116721282393).unwrap();
        let opts = SolveOptions { limits: LimitMode::Lock, ..SolveOptions::default() };
        let out = Solver::new(opts).unwrap().solve(&chain, &start, &goal).unwrap();
        assert_eq!(out.status, Status::Unreachable);
        assert_eq!(out.pose.angles()[1], elbow.max());
        assert!(chain.pose(out.pose.angles().to_vec()).is_ok(), "{:?}", out.pose.angles());
    }

    /// The closest poses the searches found behind the seed arm (`solve::limit_tests`,
    /// measured there by the search with restarts) are the verdict's distances.
    #[test]
    fn the_verdict_finds_the_closest_poses_the_searches_found() {
        let chain = seed();
        let mut solver = Solver::new(SolveOptions::default()).unwrap();
        for ((x, y), closest) in [((-3.0, -1.0), 3.4913), ((-4.0, 0.5), 4.6010), ((-4.0, 2.0), 3.9512)] {
            let out = solver.solve(&chain, chain.start_pose(), &Goal::position(x, y).unwrap()).unwrap();
            assert_eq!(out.status, Status::Unreachable);
            assert!((out.error - closest).abs() < 1e-4, "({x}, {y}): {} vs {closest}", out.error);
        }
    }

    /// A second solver on a chain the process has built the regions of takes them (the same
    /// region, not a copy) and answers as the first; a chain with other limits gets its own.
    #[test]
    fn a_new_solver_takes_the_regions_this_process_built() {
        // Lengths no other test uses, so that this chain's regions are built here.
        let arm = |hi: f64| {
            let lim = JointLimits::new(-1.0, hi).unwrap();
            let links = [Link::new(1.37, 0.2), Link::new(0.91, 0.3).with_limits(lim), Link::new(0.53, 0.1)];
            Chain::new([0.0, 0.0], &links).unwrap()
        };
        let (chain, other) = (arm(1.5), arm(1.25));
        // Inside the inner hole the elbow's range leaves (about 1.17 from the base), and an oriented one.
        let goals = [Goal::position(0.3, 0.2).unwrap(), Goal::with_orientation(0.5, 1.9, 2.0).unwrap()];
        let solve = |chain: &Chain| {
            let mut solver = Solver::new(SolveOptions::default()).unwrap();
            let outs: Vec<_> = goals.iter().map(|g| solver.solve(chain, chain.start_pose(), g).unwrap()).collect();
            (solver, outs)
        };
        let regions = |s: &Solver| match (&s.reach.position, &s.reach.wrist) {
            (Some(Some(p)), Some(Some(w))) => (p.clone(), w.clone()),
            other => panic!("both regions built: {other:?}"),
        };
        let (first, a) = solve(&chain);
        let (second, b) = solve(&chain);
        let (p1, w1) = regions(&first);
        let (p2, w2) = regions(&second);
        assert!(std::sync::Arc::ptr_eq(&p1, &p2) && std::sync::Arc::ptr_eq(&w1, &w2));
        assert_eq!(a, b);
        assert_eq!(a[0].status, Status::Unreachable, "the verdict judged the first goal");
        let (third, _) = solve(&other);
        let (p3, _) = regions(&third);
        assert!(!std::sync::Arc::ptr_eq(&p1, &p3));
        assert_ne!(p1.area(), p3.area());
    }

    #[test]
    fn no_verdict_without_limits() {
        let chain = seed();
        let goal = Goal::position(-3.0, -1.0).unwrap();
        for opts in [
            SolveOptions { limits: LimitMode::Ignore, ..SolveOptions::default() },
            SolveOptions { reach_verdict: false, ..SolveOptions::default() },
        ] {
            let out = Solver::new(opts).unwrap().solve(&chain, chain.start_pose(), &goal).unwrap();
            assert_eq!(out.reach_distance, None);
        }
        let free = chain.without_limits();
        let out = Solver::new(SolveOptions::default()).unwrap().solve(&free, free.start_pose(), &goal).unwrap();
        assert_eq!((out.status, out.reach_distance), (Status::Reached, None));
    }

    /// Random goals: every one the verdict passes (away from the boundary) is reached by the
    /// default solver; for every one it stops, no method, searching with restarts, gets closer
    /// than the verdict's distance.
    #[test]
    fn the_verdict_agrees_with_solving() {
        for (name, chain, n) in [("seed", seed(), 1500), ("seven", seven(), 600)] {
            let region = Region::of(&chain, true);
            let reach = chain.max_reach();
            let mut rng = SplitMix64(21);
            let mut solver = Solver::new(SolveOptions::default()).unwrap();
            let mut searchers: Vec<Solver> = Method::ALL
                .iter()
                .filter(|m| m.solves_rigs() || **m == Method::LevenbergMarquardt)
                .map(|&method| {
                    Solver::new(SolveOptions { method, reach_verdict: false, ..SolveOptions::default() }).unwrap()
                })
                .collect();
            let (mut inside, mut outside) = (0, 0);
            for i in 0..n {
                let p = Point2::new(rng.range(-reach, reach), rng.range(-reach, reach));
                let goal = Goal::position(p.x, p.y).unwrap();
                let out = solver.solve(&chain, chain.start_pose(), &goal).unwrap();
                let d = region.distance(p);
                assert_eq!(out.reach_distance, Some(d), "{name} {p}");
                if d == 0.0 {
                    inside += 1;
                    assert_eq!(out.status, Status::Reached, "{name}: {p} inside, {out:?}");
                } else {
                    outside += 1;
                    assert_eq!(out.status, Status::Unreachable, "{name} {p}");
                    let k = i % searchers.len();
                    let searcher = &mut searchers[k];
                    let method = searcher.options().method;
                    let s = searcher.solve(&chain, chain.start_pose(), &goal).unwrap();
                    assert_ne!(s.status, Status::Reached, "{name}: {p} reached by {method:?}");
                    assert!(s.error >= d - 1e-9, "{name}: {p} {method:?} got within {} < {d}", s.error);
                }
            }
            assert!(inside > n / 8 && outside > n / 8, "{name}: {inside} inside, {outside} outside");
        }
    }

    #[test]
    fn orientation_goals_are_judged_by_their_wrist() {
        // The last joint turns freely, so the wrist region is exact.
        let c = limited(&[(3.0, -45.0, 45.0), (2.0, -90.0, 90.0)]);
        let links: Vec<Link> = c.links().into_iter().chain(std::iter::once(Link::new(1.0, 0.0))).collect();
        let chain = Chain::new([0.0, 0.0], &links).unwrap();
        let wrist = Region::wrist(&chain, true).unwrap();
        let mut rng = SplitMix64(5);
        let mut solver = Solver::new(SolveOptions::default()).unwrap();
        let mut searcher = Solver::new(SolveOptions { reach_verdict: false, ..SolveOptions::default() }).unwrap();
        let mut stopped = 0;
        for _ in 0..400 {
            let (x, y, a) = (rng.range(-6.0, 6.0), rng.range(-6.0, 6.0), rng.range(-PI, PI));
            let goal = Goal::with_orientation(x, y, a).unwrap();
            let out = solver.solve(&chain, chain.start_pose(), &goal).unwrap();
            let w = Point2::new(x - math::cos(a), y - math::sin(a));
            assert_eq!(out.reach_distance, Some(wrist.distance(w)));
            if out.status == Status::Unreachable && out.reach_distance > Some(0.0) {
                stopped += 1;
                // The last link points as asked; the wrist is at its region's nearest point.
                assert!(out.angle_error < 1e-9, "{out:?}");
                let tip = end_effector(&chain, out.pose.angles()).position;
                assert!((tip - (wrist.nearest(w) + nalgebra::Vector2::new(math::cos(a), math::sin(a)))).norm() < 1e-9);
                let s = searcher.solve(&chain, chain.start_pose(), &goal).unwrap();
                assert_ne!(s.status, Status::Reached, "({x}, {y}, {a}) reached by searching");
            } else {
                assert_eq!(out.status, Status::Reached, "({x}, {y}, {a}): {out:?}");
            }
        }
        assert!(stopped > 50, "{stopped}");
    }

    /// Issue 24: on the 64-link arm whose lengths spread from 1e-9 to 1e9 the verdict built
    /// its region for minutes before the first iteration, deaf to the interrupt (the server
    /// answered 503 and the work went on). A token set from another thread now ends the solve
    /// `interrupted` (the only wall-clock bound: it ends at all).
    #[test]
    fn the_verdict_stops_building_when_interrupted() {
        use crate::{Interrupt, Restarts};
        // A chain no other test solves: the process keeps what building a chain's region gave,
        // and a region found over the cap elsewhere would not be built (nor interrupted) here.
        let chain = crate::fixtures::spread_arm_at([0.5, 0.0]);
        let token = Interrupt::new();
        let options = SolveOptions {
            method: Method::DampedLeastSquares,
            limits: LimitMode::Clamp,
            restarts: Some(Restarts { attempts: 2, ..Restarts::default() }),
            interrupt: Some(token.clone()),
            ..SolveOptions::default()
        };
        let setter = std::thread::spawn(move || {
            std::thread::sleep(std::time::Duration::from_millis(50));
            token.interrupt();
        });
        let goal = Goal::position(0.0, 0.0).unwrap();
        let out = Solver::new(options).unwrap().solve(&chain, chain.start_pose(), &goal).unwrap();
        setter.join().unwrap();
        assert_eq!(out.status, Status::Interrupted, "{out:?}");
        assert_eq!((out.iterations, out.reach_distance), (0, None));
    }

    /// A region over the work cap is tried once per chain: the cache remembers it has none,
    /// and the solve searches without a verdict.
    #[test]
    fn a_region_over_the_cap_is_remembered_and_the_solve_searches() {
        use super::ReachCache;
        let chain = crate::fixtures::spread_arm();
        let goal = Goal::position(0.0, 0.0).unwrap();
        let mut cache = ReachCache::default();
        let mut pose = Vec::new();
        assert_eq!(cache.judge(&chain, &goal, (1e-6, 1e-6), None, &mut pose), None);
        assert!(matches!(cache.position, Some(None)), "{:?}", cache.position.as_ref().map(Option::is_some));
        assert_eq!(cache.judge(&chain, &goal, (1e-6, 1e-6), None, &mut pose), None);
        assert!(!cache.seed_pose(&chain, &goal, &mut pose));
    }
}
