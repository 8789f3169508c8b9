//! How every rig solve is judged: from its final angles alone, by the skeleton's forward
//! kinematics, with the same function for ikarus, the sequential baseline and KDL, so that no
//! solver is taken at its word.

use ikarus::solve::wrap_angle;
use ikarus::{Point2, SolveOptions};

use super::set::{RigCase, RigSet};
use crate::judge::within;

/// Rounding slack added to the tolerances, as for chains.
const ROUNDING_SLACK: f64 = 1e-12;

/// How one rig solve is judged.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigVerdict {
    /// Every effector within the tolerance (pins: their direction too) and every bone inside
    /// its limits.
    pub reached: bool,
    /// The largest distance of an effector's tip from its target (a pin's: from where it
    /// started); infinite for angles that are not a pose.
    pub error: f64,
    /// The largest direction error of a pin, radians (0 without pins).
    pub angle_error: f64,
    /// Whether every limited bone is inside its limits (modulo 2π, with a nanoradian of slack).
    pub inside_limits: bool,
}

/// Reusable buffers for forward kinematics.
#[derive(Debug, Clone, Default)]
pub struct Judge {
    points: Vec<Point2<f64>>,
    directions: Vec<f64>,
}

impl Judge {
    /// Judges the final `angles` of a solve of `case` from `set`.
    ///
    /// Reached means: every goal bone's tip within the solver tolerance of its target, every
    /// pinned bone's tip within it of where it started and its direction within the angle
    /// tolerance of its start direction, and every limited bone's angle inside its limits
    /// modulo 2π (`angle + 2πk ∈ [min − 1e-9, max + 1e-9]`: unwrapped angles are not
    /// penalised). The tolerances get 1e-12 of slack for rounding. Angles of the wrong count or
    /// not finite are not reached.
    pub fn judge(&mut self, set: &RigSet, case: &RigCase, angles: &[f64]) -> RigVerdict {
        let n = set.skeleton.len();
        if angles.len() != n || angles.iter().any(|a| !a.is_finite()) {
            return RigVerdict {
                reached: false,
                error: f64::INFINITY,
                angle_error: f64::INFINITY,
                inside_limits: false,
            };
        }
        self.points.resize(n + 1, Point2::origin());
        self.directions.resize(n, 0.0);
        set.skeleton.points_into(angles, &mut self.points, &mut self.directions);
        let opts = SolveOptions::default();
        let mut error: f64 = 0.0;
        for (&g, t) in set.goals.iter().zip(&case.targets) {
            error = error.max((self.points[g + 1] - t).norm());
        }
        let mut angle_error: f64 = 0.0;
        for (&p, (tip, phi)) in set.pins.iter().zip(&set.pin_targets) {
            error = error.max((self.points[p + 1] - tip).norm());
            angle_error = angle_error.max(wrap_angle(self.directions[p] - phi).abs());
        }
        let inside_limits =
            angles.iter().zip(set.skeleton.limits()).all(|(&a, lim)| lim.is_none_or(|l| within(a, l.min(), l.max())));
        let reached = error <= opts.tolerance + ROUNDING_SLACK
            && angle_error <= opts.angle_tolerance + ROUNDING_SLACK
            && inside_limits;
        RigVerdict { reached, error, angle_error, inside_limits }
    }
}

#[cfg(test)]
mod tests {
    use std::f64::consts::TAU;

    use super::*;
    use crate::rigs::set::{RigSetName, generate};

    #[test]
    fn the_generating_configuration_reaches_and_the_start_does_not() {
        let mut j = Judge::default();
        for kind in RigSetName::ALL {
            let s = generate(kind, 50, 1).unwrap();
            for c in &s.cases {
                let v = j.judge(&s, c, &c.config);
                assert!(v.reached && v.error == 0.0 && v.angle_error == 0.0, "{}: {v:?}", s.name());
            }
            let v = j.judge(&s, &s.cases[0], &s.start);
            assert!(!v.reached && v.error > 1e-3 && v.inside_limits, "{}: {v:?}", s.name());
        }
    }

    #[test]
    fn a_wrong_answer_is_judged_failed() {
        let mut j = Judge::default();
        let s = generate(RigSetName::Puppet, 5, 3).unwrap();
        let c = &s.cases[0];
        // Another case's configuration: inside the limits, every effector elsewhere.
        let v = j.judge(&s, c, &s.cases[1].config);
        assert!(!v.reached && v.error > 1e-3 && v.inside_limits, "{v:?}");
        // One effector off by 2e-6, the others exact: not reached.
        let hand = s.goals[0];
        let mut off = c.config.clone();
        off[hand] += 2e-6 / s.skeleton.lengths()[hand];
        let v = j.judge(&s, c, &off);
        assert!(!v.reached && v.error > 1e-6 && v.error < 3e-6, "{v:?}");
        // Every tip exact but a bone outside its limits: not reached. A whole turn is fine.
        let mut turned = c.config.clone();
        turned[0] += TAU;
        assert!(j.judge(&s, c, &turned).reached);
        let spine = s.skeleton.index_of("spine").unwrap();
        let lim = s.skeleton.limits()[spine].unwrap();
        let mut beyond = c.config.clone();
        beyond[spine] = lim.max() + 1e-6;
        let v = j.judge(&s, c, &beyond);
        assert!(!v.reached && !v.inside_limits, "{v:?}");
        // Not a pose.
        assert!(!j.judge(&s, c, &c.config[1..]).reached);
        let mut nan = c.config.clone();
        nan[3] = f64::NAN;
        assert_eq!(j.judge(&s, c, &nan).error, f64::INFINITY);
    }

    #[test]
    fn a_pin_must_keep_its_place_and_direction() {
        let mut j = Judge::default();
        let s = generate(RigSetName::PuppetPins, 3, 1).unwrap();
        let c = &s.cases[0];
        assert!(j.judge(&s, c, &c.config).reached);
        // Turn the foot about the ankle: the tip moves, and so does the direction.
        let foot = s.pins[0];
        let mut moved = c.config.clone();
        moved[foot] += 1e-3;
        let v = j.judge(&s, c, &moved);
        assert!(!v.reached && v.angle_error > 9e-4, "{v:?}");
        // The hands reaching but the legs moved away from the start: not reached.
        let thigh = s.skeleton.root_of(foot);
        let mut walked = c.config.clone();
        walked[thigh] += 0.1;
        assert!(!j.judge(&s, c, &walked).reached);
    }
}
