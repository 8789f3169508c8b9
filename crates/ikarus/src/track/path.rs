//! [`Path`]: the goals a tip should pass through, in order, with constructors for lines,
//! circles and figure-8s.

use crate::math;
use crate::number::Num;
use std::f64::consts::TAU;

use thiserror::Error;

use crate::goal::{Goal, GoalError};

/// A path for the tip: one [`Goal`] per sample, in order, at least one, every number finite.
///
/// Build one from goals ([`Path::new`]), points ([`Path::from_points`]), or a shape sampled at
/// `samples` points: [`Path::line`], [`Path::circle`], [`Path::figure8`]. A shape's samples
/// include both ends, so a closed shape (circle, figure-8) ends where it began.
#[derive(Debug, Clone, PartialEq)]
pub struct Path {
    goals: Vec<Goal>,
}

/// Why a [`Path`] could not be built. Every variant names the field and the value.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum PathError {
    /// No samples.
    #[error("path: needs at least one sample, got none")]
    Empty,
    /// A shape needs at least two samples (its two ends).
    #[error("samples: must be at least 2, got {value}")]
    Samples {
        /// The offending count.
        value: usize,
    },
    /// A shape's parameter is out of range.
    #[error("{field}: must be {expected}, got {}", Num(*.value))]
    Parameter {
        /// The parameter's name (`x0`, `radius`, `a`, …).
        field: &'static str,
        /// The allowed range, in words.
        expected: &'static str,
        /// The offending value.
        value: f64,
    },
    /// A point of [`Path::from_points`] is not finite.
    #[error("path[{index}].{source}")]
    Point {
        /// Index of the sample, from 0.
        index: usize,
        /// What is wrong with it (`x: must be a finite number, got NaN`).
        source: PointError,
    },
}

/// Which coordinate of a point is not finite (see [`PathError::Point`]).
#[derive(Debug, Clone, PartialEq, Error)]
#[error("{field}: must be a finite number, got {}", Num(*.value))]
pub struct PointError {
    /// `"x"`, `"y"` or `"angle"`.
    pub field: &'static str,
    /// The offending value.
    pub value: f64,
}

impl Path {
    /// A path through `goals`, in order; [`PathError::Empty`] if there are none.
    pub fn new(goals: Vec<Goal>) -> Result<Self, PathError> {
        if goals.is_empty() { Err(PathError::Empty) } else { Ok(Self { goals }) }
    }

    /// A path of position goals through `points`, in order.
    pub fn from_points(points: &[[f64; 2]]) -> Result<Self, PathError> {
        let goals = points
            .iter()
            .enumerate()
            .map(|(index, &[x, y])| Goal::position(x, y).map_err(|e| point_error(index, e)))
            .collect::<Result<Vec<_>, _>>()?;
        Self::new(goals)
    }

    /// `samples` points evenly spaced on the segment from `from` to `to`, both ends included.
    pub fn line(from: [f64; 2], to: [f64; 2], samples: usize) -> Result<Self, PathError> {
        for (field, value) in [("x0", from[0]), ("y0", from[1]), ("x1", to[0]), ("y1", to[1])] {
            finite(field, value)?;
        }
        Self::sampled(samples, |t| [from[0] + t * (to[0] - from[0]), from[1] + t * (to[1] - from[1])])
    }

    /// `samples` points evenly spaced in angle on the circle of `radius` around `centre`,
    /// counter-clockwise from `centre + (radius, 0)`, ending where it began:
    /// `(cx + r cos 2πt, cy + r sin 2πt)` for `t = k / (samples − 1)`.
    pub fn circle(centre: [f64; 2], radius: f64, samples: usize) -> Result<Self, PathError> {
        finite("cx", centre[0])?;
        finite("cy", centre[1])?;
        positive("radius", radius)?;
        Self::sampled(samples, |t| {
            let (s, c) = math::sin_cos(TAU * t);
            [centre[0] + radius * c, centre[1] + radius * s]
        })
    }

    /// `samples` points evenly spaced in the parameter on the lemniscate of Gerono around
    /// `centre`: `(cx + a sin 2πt, cy + a sin 2πt · cos 2πt)` for `t = k / (samples − 1)`.
    ///
    /// A figure-8 lying on its side, `2a` wide and `a` high: it starts at the centre, runs
    /// counter-clockwise round the right lobe, crosses the centre and runs clockwise round the
    /// left lobe back to the centre.
    pub fn figure8(centre: [f64; 2], a: f64, samples: usize) -> Result<Self, PathError> {
        finite("cx", centre[0])?;
        finite("cy", centre[1])?;
        positive("a", a)?;
        Self::sampled(samples, |t| {
            let (s, c) = math::sin_cos(TAU * t);
            [centre[0] + a * s, centre[1] + a * s * c]
        })
    }

    /// The goals, in order.
    #[must_use]
    pub fn goals(&self) -> &[Goal] {
        &self.goals
    }

    /// The number of samples, at least 1.
    #[must_use]
    pub fn len(&self) -> usize {
        self.goals.len()
    }

    /// Always `false`: a path has at least one sample.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.goals.is_empty()
    }

    /// `samples ≥ 2` points `at(t)` for `t = k / (samples − 1)`; the shapes' parameters are
    /// finite, so every point is (a point that overflows is reported as not finite).
    fn sampled(samples: usize, at: impl Fn(f64) -> [f64; 2]) -> Result<Self, PathError> {
        if samples < 2 {
            return Err(PathError::Samples { value: samples });
        }
        let last = (samples - 1) as f64;
        let points: Vec<[f64; 2]> = (0..samples).map(|k| at(k as f64 / last)).collect();
        Self::from_points(&points)
    }
}

fn point_error(index: usize, e: GoalError) -> PathError {
    let GoalError::NonFinite { field, value } = e;
    PathError::Point { index, source: PointError { field, value } }
}

fn finite(field: &'static str, value: f64) -> Result<(), PathError> {
    if value.is_finite() { Ok(()) } else { Err(PathError::Parameter { field, expected: "a finite number", value }) }
}

fn positive(field: &'static str, value: f64) -> Result<(), PathError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(PathError::Parameter { field, expected: "a finite number > 0", value })
    }
}
