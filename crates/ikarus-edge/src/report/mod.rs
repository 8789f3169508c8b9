//! The JSON objects that `ikarus solve`, `ikarus animate`, `ikarus track`, `ikarus workspace`
//! and `ikarus reach` print, shared by the command line and `ikarus serve` so that both answer
//! with the same shapes (degrees at the edge, names matching the arm and rig files). Shapes
//! only: the work is done elsewhere. One file per concern: [`solve`] (a solve of an arm or a
//! rig), [`motion`] (a motion of either), [`workspace`] (reachable areas and verdicts),
//! [`rig`] (a rig file as JSON), [`character`] (a character file as JSON); the pieces they share (a rig's values keyed by bone name in
//! its file's order, degrees for people) are here.

use ikarus::Point2;
use serde::Serialize;
use serde::ser::{SerializeMap, Serializer};

use crate::rig::Rig;

pub mod character;
pub mod motion;
pub mod rig;
pub mod solve;
pub mod workspace;

pub use motion::*;
pub use rig::*;
pub use solve::*;
pub use workspace::*;

/// Angles in radians as degrees, in the same order.
pub fn degrees(angles: &[f64]) -> Vec<f64> {
    angles.iter().map(|a| a.to_degrees()).collect()
}

/// Points as `[x, y]` pairs, in the same order.
pub fn points(joints: &[ikarus::Point2<f64>]) -> Vec<[f64; 2]> {
    joints.iter().map(|p| [p.x, p.y]).collect()
}

/// An angle in radians as degrees for people: normalised into (−180°, 180°], with `decimals`
/// decimals and the `°` sign, and never `-0.000°` (a value that rounds to zero, or to −180°,
/// prints as 0 or 180).
pub fn deg_text(radians: f64, decimals: usize) -> String {
    let deg = ikarus::angle::wrap_angle(radians).to_degrees();
    let deg = if deg <= -180.0 { deg + 360.0 } else { deg };
    let text = format!("{deg:.decimals$}");
    match text.strip_prefix('-') {
        Some(abs) if abs.parse::<f64>().is_ok_and(|v| v == 0.0 || v == 180.0) => format!("{abs}°"),
        _ => format!("{text}°"),
    }
}

/// Values keyed by bone name, written as a JSON object in the rig's order (a map type would
/// sort the names).
pub struct ByName<'a, T> {
    /// The rig's bone names, in its file's order.
    pub names: &'a [String],
    /// One value per bone, in the same order.
    pub values: Vec<T>,
}

impl<T: Serialize> Serialize for ByName<'_, T> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.values.len()))?;
        for (name, value) in self.names.iter().zip(&self.values) {
            map.serialize_entry(name, value)?;
        }
        map.end()
    }
}

/// Every bone's angle from its parent's direction at joint values `q`, degrees: the joint
/// value of a revolute bone, the fixed angle of a prismatic one (the same bits as
/// `degrees` for a rig without prismatic joints).
pub fn relative_degrees(s: &ikarus::Skeleton, q: &[f64]) -> Vec<f64> {
    q.iter().enumerate().map(|(j, &v)| s.relative_angle(j, v).to_degrees()).collect()
}

/// The displacements of a rig's prismatic bones, keyed by name in the rig's order.
pub struct Extensions<'a> {
    /// The skeleton whose prismatic bones are written, and whose names key them.
    pub skeleton: &'a ikarus::Skeleton,
    /// Every bone's joint value.
    pub values: Vec<f64>,
}

impl<'a> Extensions<'a> {
    /// The displacements at joint values `q`: `None` for a skeleton without prismatic joints,
    /// so that its answers carry no `extensions` (and stay what they were before joint kinds).
    pub fn of(skeleton: &'a ikarus::Skeleton, q: &[f64]) -> Option<Self> {
        skeleton.has_prismatic().then(|| Self { skeleton, values: q.to_vec() })
    }
}

/// The CSV columns of a rig's pose: `NAME_deg` for every bone (its angle from its parent's
/// direction), then `NAME_ext` for every prismatic bone (its displacement), in the rig's order.
pub fn pose_columns(s: &ikarus::Skeleton) -> Vec<String> {
    let angles = s.names().iter().map(|n| format!("{n}_deg"));
    let prismatic = |(j, n): (usize, &String)| match s.joint(j) {
        ikarus::Joint::Revolute => None,
        ikarus::Joint::Prismatic { .. } => Some(format!("{n}_ext")),
    };
    angles.chain(s.names().iter().enumerate().filter_map(prismatic)).collect()
}

/// The values under [`pose_columns`] at joint values `q`.
pub fn pose_values(s: &ikarus::Skeleton, q: &[f64]) -> Vec<f64> {
    let prismatic = |(j, &v): (usize, &f64)| match s.joint(j) {
        ikarus::Joint::Revolute => None,
        ikarus::Joint::Prismatic { .. } => Some(v),
    };
    relative_degrees(s, q).into_iter().chain(q.iter().enumerate().filter_map(prismatic)).collect()
}

impl Serialize for Extensions<'_> {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(None)?;
        for (j, joint) in self.skeleton.joints().iter().enumerate() {
            match joint {
                ikarus::Joint::Revolute => {}
                ikarus::Joint::Prismatic { .. } => map.serialize_entry(self.skeleton.name(j), &self.values[j])?,
            }
        }
        map.end()
    }
}

/// Every bone's tip at `angles`, in the rig's order.
pub fn tips(rig: &Rig, angles: &[f64]) -> Vec<Point2<f64>> {
    let s = &rig.skeleton;
    let mut points = vec![Point2::origin(); s.len() + 1];
    let mut directions = vec![0.0; s.len()];
    s.points_into(angles, &mut points, &mut directions);
    points.remove(0);
    points
}

#[cfg(test)]
mod tests {
    use super::deg_text;

    #[test]
    fn angles_for_people_are_in_the_half_open_circle_without_negative_zero() {
        let cases = [
            (0.0, "0.000°"),
            (-0.0, "0.000°"),
            (-1e-9, "0.000°"),
            (-214.371, "145.629°"),
            (180.0, "180.000°"),
            (-180.0, "180.000°"),
            (-179.99999, "180.000°"),
            (540.0, "180.000°"),
            (-90.0, "-90.000°"),
            (359.9996, "0.000°"),
            (1e20, "-" /* any value, but one in range */),
        ];
        for (deg, want) in cases {
            let got = deg_text(f64::to_radians(deg), 3);
            if want == "-" {
                let v: f64 = got.trim_end_matches('°').parse().unwrap();
                assert!(v > -180.0 && v <= 180.0, "{deg} -> {got}");
            } else {
                assert_eq!(got, want, "{deg}");
            }
        }
    }
}
