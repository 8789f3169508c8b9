//! [`Num`]: how a number a user gave is written back in a message.
//!
//! Rust's `{}` of an `f64` writes every digit in positional notation: `1e300` becomes a
//! 301-character line, and `5e-324` one of 327. Messages print numbers through [`Num`]
//! instead: the shortest form that reads back to the same `f64` (as `{}` and `{:e}` both give),
//! in positional notation for ordinary magnitudes and in exponent notation for
//! `|x| ≥ 1e16` and for nonzero `|x| < 1e-6`.

use std::fmt;

/// An `f64` as a message shows it: `1.5`, `-0.001`, `1e300`, `5e-324`, `1.2345678e-7`, `NaN`,
/// `inf`. A precision (`{:.3}`) is honoured in the same notation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Num(pub f64);

impl Num {
    /// Whether the number is written in exponent notation.
    fn exponent(self) -> bool {
        let a = self.0.abs();
        a.is_finite() && (a >= 1e16 || (a != 0.0 && a < 1e-6))
    }
}

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match (self.exponent(), f.precision()) {
            (true, Some(p)) => write!(f, "{:.p$e}", self.0),
            (true, None) => write!(f, "{:e}", self.0),
            (false, Some(p)) => write!(f, "{:.p$}", self.0),
            (false, None) => write!(f, "{}", self.0),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Num;

    #[test]
    fn numbers_are_short_and_read_back() {
        for (x, want) in [
            (0.0, "0"),
            (-0.0, "-0"),
            (1.5, "1.5"),
            (-0.001, "-0.001"),
            (1e-6, "0.000001"),
            (9.99e15, "9990000000000000"),
            (1e16, "1e16"),
            (1e300, "1e300"),
            (-1e300, "-1e300"),
            (5e-324, "5e-324"),
            (1.2345678e-7, "1.2345678e-7"),
            (f64::MAX, "1.7976931348623157e308"),
            (f64::NAN, "NaN"),
            (f64::INFINITY, "inf"),
            (f64::NEG_INFINITY, "-inf"),
        ] {
            let s = Num(x).to_string();
            assert_eq!(s, want, "{x:e}");
            assert!(s.len() <= 23, "{s}");
            if x.is_finite() {
                assert_eq!(s.parse::<f64>().unwrap().to_bits(), x.to_bits(), "{s}");
            }
        }
        assert_eq!(format!("{:.2}", Num(1.23456)), "1.23");
        assert_eq!(format!("{:.2}", Num(1e300)), "1.00e300");
    }

    /// Issue 11: error lines printed 1e300 with all its 301 digits. Every library error that
    /// shows a user's number goes through [`Num`].
    #[test]
    fn error_messages_write_numbers_short() {
        use crate::{Chain, Goal, JointLimits, Link, SolveOptions};
        let messages = [
            Chain::new([0.0, 0.0], &[Link::new(-1e300, 0.0)]).unwrap_err().to_string(),
            Chain::new([1e300, 5e-324], &[Link::new(1.0, f64::NAN)]).unwrap_err().to_string(),
            Chain::new([0.0, 0.0], &[Link::new(1.0, 1e300).with_limits(JointLimits::new(5e-324, 1.0).unwrap())])
                .unwrap_err()
                .to_string(),
            JointLimits::new(1e300, 5e-324).unwrap_err().to_string(),
            Goal::with_orientation(1e300, 5e-324, f64::NAN).unwrap_err().to_string(),
            SolveOptions { tolerance: -5e-324, ..SolveOptions::default() }.validate().unwrap_err().to_string(),
            SolveOptions { rates: vec![-1e300], ..SolveOptions::default() }.validate().unwrap_err().to_string(),
        ];
        let want = [
            "links[0].length: must be greater than 0, got -1e300",
            "links[0].angle: must be a finite number, got NaN",
            "links[0].angle: 1e300 rad lies outside the limits [5e-324, 1] rad",
            "min must not exceed max, got [1e300, 5e-324]",
            "goal.angle: must be a finite number, got NaN",
            "tolerance: must be a finite number > 0, got -5e-324",
            "rates[0]: must be a finite number ≥ 0, got -1e300",
        ];
        for (got, want) in messages.iter().zip(want) {
            assert_eq!(got, want);
        }
    }
}
