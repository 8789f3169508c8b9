//! Parsers and checks of the edges' values, shared by the flags, the files and the API: numbers in range, points, angles, and
//! the names of the library's choice enums.

use crate::error::Error;

/// Parses a finite float, naming what was wrong with the text.
pub fn parse_finite(s: &str) -> Result<f64, Error> {
    let v: f64 = s.trim().parse().map_err(|_| Error::input(format!("'{s}' is not a number")))?;
    if v.is_finite() { Ok(v) } else { Err(Error::input(format!("must be a finite number, got {s}"))) }
}

/// `v` if it is finite and greater than 0; otherwise refused, naming the value.
pub fn positive(v: f64) -> Result<f64, Error> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(Error::input(format!("{}: must be a finite number greater than 0", ikarus::number::Num(v))))
    }
}

/// `v` if it is finite and ≥ 0; otherwise refused, naming the value.
pub fn non_negative(v: f64) -> Result<f64, Error> {
    if v.is_finite() && v >= 0.0 {
        Ok(v)
    } else {
        Err(Error::input(format!("{}: must be a finite number ≥ 0", ikarus::number::Num(v))))
    }
}

/// `v` if it is at least 1; otherwise refused, naming the value.
pub fn at_least_one(v: u32) -> Result<u32, Error> {
    if v >= 1 { Ok(v) } else { Err(Error::input(format!("{v}: must be at least 1"))) }
}

/// Parses a finite number greater than 0 ([`parse_finite`], then [`positive`]).
pub fn parse_positive(s: &str) -> Result<f64, Error> {
    positive(parse_finite(s)?)
}

/// Parses a finite number ≥ 0 ([`parse_finite`], then [`non_negative`]).
pub fn parse_non_negative(s: &str) -> Result<f64, Error> {
    non_negative(parse_finite(s)?)
}

/// Parses a whole number of at least 1, refusing text that is not one.
pub fn parse_at_least_one(s: &str) -> Result<u32, Error> {
    let v: u32 = s.trim().parse().map_err(|_| Error::input(format!("'{s}' is not a whole number")))?;
    at_least_one(v)
}

/// Parses `X,Y` into two finite numbers.
pub fn parse_point(s: &str) -> Result<[f64; 2], Error> {
    let parts: Vec<&str> = s.split(',').collect();
    let [x, y] = parts[..] else {
        return Err(Error::input(format!("expected two numbers X,Y, got {} part(s)", parts.len())));
    };
    let x = parse_finite(x).map_err(|m| Error::input(format!("x: {m}")))?;
    let y = parse_finite(y).map_err(|m| Error::input(format!("y: {m}")))?;
    Ok([x, y])
}

/// Parses an angle in degrees (finite).
pub fn parse_angle(s: &str) -> Result<f64, Error> {
    parse_finite(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_parse_and_name_the_bad_part() {
        assert_eq!(parse_point("1.5,-2"), Ok([1.5, -2.0]));
        assert_eq!(parse_point(" 3 , 4 "), Ok([3.0, 4.0]));
        assert_eq!(parse_point("1,nan"), Err(Error::input("y: must be a finite number, got nan")));
        assert_eq!(parse_point("inf,1"), Err(Error::input("x: must be a finite number, got inf")));
        assert_eq!(parse_point("a,1"), Err(Error::input("x: 'a' is not a number")));
        assert_eq!(parse_point("1"), Err(Error::input("expected two numbers X,Y, got 1 part(s)")));
        assert_eq!(parse_point("1,2,3"), Err(Error::input("expected two numbers X,Y, got 3 part(s)")));
    }

    #[test]
    fn ranges() {
        assert!(parse_positive("0").is_err());
        assert!(parse_positive("1e-9").is_ok());
        assert!(parse_non_negative("0").is_ok());
        assert!(parse_non_negative("-0.1").is_err());
        assert!(parse_at_least_one("0").is_err());
        assert!(parse_at_least_one("-3").is_err());
    }
}
