//! The step rules ([`Method`]) and the ways of enforcing joint limits ([`LimitMode`]), with
//! their names at the edges and which rule supports which mode.

use crate::listed_enum;
use crate::names::by_name;
use crate::skeleton::Joint;

listed_enum! {
    /// The step rule of a solve. See the [module docs](super) for the formulas.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
    pub enum Method {
        /// Jacobian transpose with the step length that minimises the linearised error.
        Transpose,
        /// Jacobian pseudoinverse `Jᵀ (J Jᵀ)⁺`, via the eigen-decomposition of `J Jᵀ`.
        PseudoInverse,
        /// Damped least squares `Jᵀ (J Jᵀ + λ² I)⁻¹`, λ = [`SolveOptions::lambda`](super::SolveOptions::lambda).
        DampedLeastSquares,
        /// Selectively damped least squares (Buss & Kim 2005): each singular direction's joint
        /// change is clamped by how far it can move the tip.
        SelectivelyDamped,
        /// Levenberg–Marquardt: damped least squares whose damping adapts to how well the
        /// linearisation predicted the last step (Nielsen's update), starting from
        /// [`SolveOptions::lambda`](super::SolveOptions::lambda). The default: as fast as DLS on reachable goals, and it does
        /// not crawl near singular poses (goals at or beyond the reach).
        #[default]
        LevenbergMarquardt,
        /// Cyclic coordinate descent: one joint at a time, from the tip to the base, each turned to
        /// the angle that best brings the tip to the goal.
        CyclicCoordinateDescent,
        /// FABRIK (Aristidou & Lasenby 2011): backward and forward reaching on the joint positions,
        /// with angular limits applied in the forward pass.
        Fabrik,
        /// Closed form, for two links with a position goal or three links with an orientation goal;
        /// other shapes are a [`SolveError::NoClosedForm`](super::SolveError::NoClosedForm).
        Analytic,
    }
}

impl Method {
    /// The short name used at the edges: `transpose`, `pinv`, `dls`, `sdls`, `lm`, `ccd`,
    /// `fabrik`, `analytic`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            Method::Transpose => "transpose",
            Method::PseudoInverse => "pinv",
            Method::DampedLeastSquares => "dls",
            Method::SelectivelyDamped => "sdls",
            Method::LevenbergMarquardt => "lm",
            Method::CyclicCoordinateDescent => "ccd",
            Method::Fabrik => "fabrik",
            Method::Analytic => "analytic",
        }
    }

    /// Whether it solves skeletons (rigs): the Jacobian methods do; CCD, FABRIK and the
    /// closed form solve chains only.
    #[must_use]
    pub fn solves_rigs(self) -> bool {
        match self {
            Method::Transpose
            | Method::PseudoInverse
            | Method::DampedLeastSquares
            | Method::SelectivelyDamped
            | Method::LevenbergMarquardt => true,
            Method::CyclicCoordinateDescent | Method::Fabrik | Method::Analytic => false,
        }
    }

    /// Whether [`SolveOptions::lambda`](super::SolveOptions::lambda) sets the method's damping:
    /// damped least squares' damping, and Levenberg–Marquardt's damping at the start. The
    /// others take their steps without it (SDLS damps each singular direction by its own
    /// bound).
    #[must_use]
    pub fn uses_lambda(self) -> bool {
        match self {
            Method::DampedLeastSquares | Method::LevenbergMarquardt => true,
            Method::Transpose
            | Method::PseudoInverse
            | Method::SelectivelyDamped
            | Method::CyclicCoordinateDescent
            | Method::Fabrik
            | Method::Analytic => false,
        }
    }

    /// Whether it can move a joint of kind `joint`: every method turns revolute joints; the
    /// Jacobian methods slide prismatic ones too (a column is the slide's direction), CCD,
    /// FABRIK and the closed forms do not. A new joint kind or method makes the compiler
    /// name this match.
    #[must_use]
    pub fn moves(self, joint: Joint) -> bool {
        match joint {
            Joint::Revolute => true,
            Joint::Prismatic { .. } => match self {
                Method::Transpose
                | Method::PseudoInverse
                | Method::DampedLeastSquares
                | Method::SelectivelyDamped
                | Method::LevenbergMarquardt => true,
                Method::CyclicCoordinateDescent | Method::Fabrik | Method::Analytic => false,
            },
        }
    }

    /// A label for people: `Levenberg–Marquardt`, …
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            Method::Transpose => "Jacobian transpose",
            Method::PseudoInverse => "Pseudoinverse",
            Method::DampedLeastSquares => "Damped least squares",
            Method::SelectivelyDamped => "Selectively damped LS",
            Method::LevenbergMarquardt => "Levenberg–Marquardt",
            Method::CyclicCoordinateDescent => "Cyclic coordinate descent",
            Method::Fabrik => "FABRIK",
            Method::Analytic => "Closed form (2 links)",
        }
    }

    /// One line saying what the method does.
    #[must_use]
    pub fn summary(self) -> &'static str {
        match self {
            Method::Transpose => "Jacobian transpose with the error-minimising step length",
            Method::PseudoInverse => "Jacobian pseudoinverse (truncated at singular values below 1e-6)",
            Method::DampedLeastSquares => "Damped least squares with the damping λ",
            Method::SelectivelyDamped => "Selectively damped least squares (Buss & Kim)",
            Method::LevenbergMarquardt => {
                "Levenberg–Marquardt: damped least squares with adaptive damping, starting at the damping λ"
            }
            Method::CyclicCoordinateDescent => "Cyclic coordinate descent, one joint at a time from the tip",
            Method::Fabrik => "FABRIK, forward and backward reaching on the joint positions",
            Method::Analytic => "Closed form: 2 links with a position goal, 3 links with an orientation goal",
        }
    }

    /// Whether the method enforces limits the way `mode` says. Every mode is supported by the
    /// Jacobian methods, and by [`Method::Analytic`] (its closed form respects the limits
    /// exactly; where it has no answer it falls back on damped least squares under `mode`).
    /// CCD and FABRIK turn or place one joint at a time and can only clamp: they support
    /// [`LimitMode::Ignore`] and [`LimitMode::Clamp`].
    #[must_use]
    pub fn supports(self, mode: LimitMode) -> bool {
        match self {
            Method::Transpose
            | Method::PseudoInverse
            | Method::DampedLeastSquares
            | Method::SelectivelyDamped
            | Method::LevenbergMarquardt
            | Method::Analytic => true,
            Method::CyclicCoordinateDescent | Method::Fabrik => matches!(mode, LimitMode::Ignore | LimitMode::Clamp),
        }
    }

    /// The limit mode used when limits are enforced and no mode is named: [`LimitMode::Lock`]
    /// where it is supported, else [`LimitMode::Clamp`].
    #[must_use]
    pub fn default_limit_mode(self) -> LimitMode {
        if self.supports(LimitMode::default()) { LimitMode::default() } else { LimitMode::Clamp }
    }

    /// Whether the method steps along the Jacobian (and so supports every [`LimitMode`]).
    #[must_use]
    pub fn uses_jacobian(self) -> bool {
        match self {
            Method::Transpose
            | Method::PseudoInverse
            | Method::DampedLeastSquares
            | Method::SelectivelyDamped
            | Method::LevenbergMarquardt => true,
            Method::CyclicCoordinateDescent | Method::Fabrik | Method::Analytic => false,
        }
    }
}

listed_enum! {
    /// How joint limits are enforced. Every mode except [`LimitMode::Ignore`] also clamps each
    /// step into the limits, so no pose of a solve ever leaves them.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
    pub enum LimitMode {
        /// Limits are not enforced.
        Ignore,
        /// After every step, each limited joint is clamped into its range (the seed program's
        /// method). Simple, but a joint pinned at a limit can hold the chain in a dead end.
        Clamp,
        /// Clamp and lock: a joint whose step would cross its limit moves only to the limit, its
        /// Jacobian column is removed, and the step is solved again for the other joints (the way
        /// Blender's IK treats limits). Each iteration starts with every joint free, so a locked
        /// joint is released as soon as the task pulls it back inside.
        #[default]
        Lock,
        /// [`LimitMode::Lock`] plus a secondary task pushing every limited joint toward the middle
        /// of its range, projected into the null space of the Jacobian so that it does not disturb
        /// the tip (Parent, "adding more control"). It matters only for redundant chains.
        NullSpace,
        /// Weighted least norm (Chan & Lawrence 1995): a joint moving toward a limit is slowed by a
        /// weight `1 / (1 + |∂H/∂θ|)` of the barrier `H = Σ (max − min)² / 4(max − θ)(θ − min)`;
        /// joints moving away keep weight 1. Steps are clamped as well.
        Weighted,
    }
}

impl LimitMode {
    /// The short name used at the edges: `ignore`, `clamp`, `lock`, `nullspace`, `weighted`.
    #[must_use]
    pub fn name(self) -> &'static str {
        match self {
            LimitMode::Ignore => "ignore",
            LimitMode::Clamp => "clamp",
            LimitMode::Lock => "lock",
            LimitMode::NullSpace => "nullspace",
            LimitMode::Weighted => "weighted",
        }
    }

    /// A label for people: `Clamp and lock`, …
    #[must_use]
    pub fn label(self) -> &'static str {
        match self {
            LimitMode::Ignore => "Ignore limits",
            LimitMode::Clamp => "Clamp (seed)",
            LimitMode::Lock => "Clamp and lock",
            LimitMode::NullSpace => "Lock + null space",
            LimitMode::Weighted => "Weighted least norm",
        }
    }

    /// One line saying what the mode does.
    #[must_use]
    pub fn summary(self) -> &'static str {
        match self {
            LimitMode::Ignore => "Do not enforce the joint ranges",
            LimitMode::Clamp => "Clamp every step into the ranges (the seed's method; can get stuck)",
            LimitMode::Lock => "Clamp and lock: a joint at its limit is held and the step re-solved for the others",
            LimitMode::NullSpace => "Lock, plus a push toward the middle of the ranges in the null space of the task",
            LimitMode::Weighted => "Weighted least norm: joints slow down as they near a limit",
        }
    }
}

by_name!(Method, "method");
by_name!(LimitMode, "limit mode");

#[cfg(test)]
mod tests {
    use super::*;
    use crate::names::Named;

    #[test]
    fn names_round_trip_and_are_unique() {
        for &m in Method::ALL.iter() {
            assert_eq!(Method::from_name(m.name()), Some(m));
            assert_eq!(m.to_string().parse::<Method>(), Ok(m));
            assert_eq!(Method::ALL.iter().filter(|o| o.name() == m.name()).count(), 1);
        }
        for &m in LimitMode::ALL.iter() {
            assert_eq!(LimitMode::from_name(m.name()), Some(m));
            assert_eq!(m.to_string().parse::<LimitMode>(), Ok(m));
        }
        let err = "newton".parse::<Method>().unwrap_err().to_string();
        assert_eq!(
            err,
            "unknown method 'newton' (expected one of: transpose, pinv, dls, sdls, lm, ccd, fabrik, analytic)"
        );
    }

    #[test]
    fn every_method_supports_ignore_clamp_and_its_default_mode() {
        for &m in Method::ALL.iter() {
            assert!(m.supports(LimitMode::Ignore) && m.supports(LimitMode::Clamp), "{m}");
            assert!(m.supports(m.default_limit_mode()), "{m}");
            // A method that steps along J supports every mode.
            if m.uses_jacobian() {
                assert!(LimitMode::ALL.iter().all(|&l| m.supports(l)), "{m}");
            }
        }
        assert_eq!(Method::LevenbergMarquardt.default_limit_mode(), LimitMode::Lock);
        assert_eq!(Method::CyclicCoordinateDescent.default_limit_mode(), LimitMode::Clamp);
        assert!(!Method::Fabrik.supports(LimitMode::Weighted));
    }
}
