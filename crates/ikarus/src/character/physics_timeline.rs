//! A clip's physics timelines (Spine 4.2's `animations.NAME.physics.CONSTRAINT`): keys of a
//! physics constraint's settings, for one constraint or, under the name `""`, for every
//! constraint whose `…Global` flag for that setting is set; and `reset` keys, which restart the
//! simulation when the clip passes them. Values are sampled as every other timeline
//! ([`super::timeline`]: `f32` keys, Bézier segments read on nine samples).

use super::timeline::{f32ed, key_at, segment};
use super::{Interpolation, PhysicsConstraint, PhysicsSettings};

/// Which setting a physics timeline keys.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum PhysicsProperty {
    /// `inertia`.
    Inertia,
    /// `strength`.
    Strength,
    /// `damping`.
    Damping,
    /// `mass` (keyed as a mass, held inverted).
    Mass,
    /// `wind`.
    Wind,
    /// `gravity`.
    Gravity,
    /// `mix`.
    Mix,
}

impl PhysicsProperty {
    /// Its name in the file's timelines: `inertia`, `strength`, `damping`, `mass`, `wind`,
    /// `gravity`, `mix`.
    pub fn name(self) -> &'static str {
        match self {
            PhysicsProperty::Inertia => "inertia",
            PhysicsProperty::Strength => "strength",
            PhysicsProperty::Damping => "damping",
            PhysicsProperty::Mass => "mass",
            PhysicsProperty::Wind => "wind",
            PhysicsProperty::Gravity => "gravity",
            PhysicsProperty::Mix => "mix",
        }
    }

    /// Sets this setting of `s` to `value` (a mass is held inverted).
    pub fn set(self, s: &mut PhysicsSettings, value: f64) {
        match self {
            PhysicsProperty::Inertia => s.inertia = value,
            PhysicsProperty::Strength => s.strength = value,
            PhysicsProperty::Damping => s.damping = value,
            PhysicsProperty::Mass => s.mass_inverse = 1.0 / value,
            PhysicsProperty::Wind => s.wind = value,
            PhysicsProperty::Gravity => s.gravity = value,
            PhysicsProperty::Mix => s.mix = value,
        }
    }
}

/// One key: its time (seconds), value and the curve toward the next key.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhysicsKey {
    /// Seconds from the clip's start.
    pub time: f64,
    /// The setting's value (a mass for [`PhysicsProperty::Mass`]).
    pub value: f64,
    /// How the value goes to the next key's.
    pub curve: Interpolation,
}

/// A timeline of one setting.
#[derive(Debug, Clone, PartialEq)]
pub struct PhysicsTimeline {
    /// The constraint's index, or `None` for every constraint whose global flag for the
    /// property is set (the file's `""`).
    pub constraint: Option<usize>,
    /// The setting keyed.
    pub property: PhysicsProperty,
    /// Keys in time order (at least one).
    pub keys: Vec<PhysicsKey>,
}

/// A `reset` timeline: the simulation restarts when the clip passes one of its times.
#[derive(Debug, Clone, PartialEq)]
pub struct PhysicsReset {
    /// The constraint's index, or `None` for every constraint.
    pub constraint: Option<usize>,
    /// Key times, seconds, increasing.
    pub times: Vec<f64>,
}

impl PhysicsTimeline {
    /// The value at `time` (`None` before the first key: the setting is left as it is).
    pub fn value_at(&self, time: f64) -> Option<f64> {
        let i = key_at(|i| self.keys[i].time, self.keys.len(), time)?;
        let k = &self.keys[i];
        let Some(next) = self.keys.get(i + 1) else { return Some(f32ed(k.value)) };
        let p0 = (f32ed(k.time), f32ed(k.value));
        let p1 = (f32ed(next.time), f32ed(next.value));
        Some(segment(k.curve, p0, p1, time))
    }

    /// Whether this timeline sets the setting of constraint `k` (which is `c`): its own
    /// timeline, or one for every constraint when `c`'s global flag for the setting is set.
    pub fn keys_constraint(&self, k: usize, c: &PhysicsConstraint) -> bool {
        match self.constraint {
            Some(j) => j == k,
            None => {
                let g = &c.global;
                match self.property {
                    PhysicsProperty::Inertia => g.inertia,
                    PhysicsProperty::Strength => g.strength,
                    PhysicsProperty::Damping => g.damping,
                    PhysicsProperty::Mass => g.mass,
                    PhysicsProperty::Wind => g.wind,
                    PhysicsProperty::Gravity => g.gravity,
                    PhysicsProperty::Mix => g.mix,
                }
            }
        }
    }
}

impl PhysicsReset {
    /// Whether constraint `k` restarts when the clip goes from `from` (exclusive) to `to`
    /// (inclusive) seconds.
    pub fn resets(&self, k: usize, from: f64, to: f64) -> bool {
        self.constraint.is_none_or(|j| j == k) && self.times.iter().any(|&t| from < f32ed(t) && f32ed(t) <= to)
    }
}

/// Sets `settings[k]` (each constraint's, from its setup) from the timelines at `time`, in the
/// timelines' order (a later timeline of the same setting wins).
pub fn physics_settings_at(
    timelines: &[PhysicsTimeline],
    constraints: &[PhysicsConstraint],
    settings: &mut [PhysicsSettings],
    time: f64,
) {
    for t in timelines {
        let Some(v) = t.value_at(time) else { continue };
        for (k, (c, s)) in constraints.iter().zip(settings.iter_mut()).enumerate() {
            if !t.keys_constraint(k, c) {
                continue;
            }
            t.property.set(s, v);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::character::{PhysicsGlobal, PhysicsShares};

    fn constraint(wind_global: bool) -> PhysicsConstraint {
        PhysicsConstraint {
            name: "p".into(),
            order: 0,
            skin: false,
            bone: 0,
            shares: PhysicsShares::default(),
            limit: 5000.0,
            fps: 60.0,
            setup: PhysicsSettings::default(),
            global: PhysicsGlobal { wind: wind_global, ..PhysicsGlobal::default() },
        }
    }

    fn key(time: f64, value: f64) -> PhysicsKey {
        PhysicsKey { time, value, curve: Interpolation::Linear }
    }

    #[test]
    fn a_global_timeline_keys_only_the_constraints_with_the_flag() {
        let cs = [constraint(true), constraint(false)];
        let t = PhysicsTimeline {
            constraint: None,
            property: PhysicsProperty::Wind,
            keys: vec![key(0.0, 0.0), key(1.0, 4.0)],
        };
        let mut s = [PhysicsSettings::default(); 2];
        physics_settings_at(&[t], &cs, &mut s, 0.5);
        assert_eq!((s[0].wind, s[1].wind), (2.0, 0.0));
    }

    #[test]
    fn mass_is_held_inverted_and_a_constraint_s_own_timeline_keys_it() {
        let cs = [constraint(false), constraint(false)];
        let t = PhysicsTimeline { constraint: Some(1), property: PhysicsProperty::Mass, keys: vec![key(0.0, 4.0)] };
        let mut s = [PhysicsSettings::default(); 2];
        physics_settings_at(&[t], &cs, &mut s, 3.0);
        assert_eq!((s[0].mass_inverse, s[1].mass_inverse), (1.0, 0.25));
    }

    #[test]
    fn before_the_first_key_the_setting_is_left() {
        let t = PhysicsTimeline { constraint: Some(0), property: PhysicsProperty::Mix, keys: vec![key(1.0, 0.5)] };
        assert_eq!(t.value_at(0.5), None);
        assert_eq!(t.value_at(1.0), Some(0.5));
    }

    #[test]
    fn reset_keys_fire_once_when_passed() {
        let r = PhysicsReset { constraint: None, times: vec![0.5] };
        assert!(r.resets(3, 0.4, 0.5));
        assert!(!r.resets(3, 0.5, 0.6));
        assert!(!PhysicsReset { constraint: Some(1), times: vec![0.5] }.resets(3, 0.4, 0.5));
    }
}
