//! A goal at the edges, from flags or a request ([`make_goal`], degrees).

use ikarus::Goal;

/// A goal at `(x, y)`, with the last link's orientation when `angle_deg` is given (wrapped
/// into (−180°, 180°] exactly before it becomes radians: 1e20° is the direction it names).
pub fn make_goal(x: f64, y: f64, angle_deg: Option<f64>) -> Result<Goal, String> {
    match angle_deg {
        None => Goal::position(x, y),
        Some(a) if !a.is_finite() => Goal::with_orientation(x, y, a),
        Some(a) => Goal::with_orientation(x, y, ikarus::angle::radians_from_degrees(a)),
    }
    .map_err(|e| e.to_string())
}
