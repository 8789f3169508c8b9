//! What a keyed motion (`POST /api/animate` with `keys`) costs: one rig solve per frame, of its
//! tracks and pins together. Read as leniently as the rest of the estimate: a field of the
//! wrong type counts as absent.

use std::fmt;

use serde::Deserialize;
use serde::de::{Deserializer, IgnoredAny, MapAccess, SeqAccess, Visitor};

use super::{Count, Nested, Num};

/// The `keys` of a request: its `fps`, its tracks', bends' and rotations' latest key time, its
/// `duration`, and how many tracks and pins it has.
#[derive(Debug, Default, Deserialize)]
#[serde(default)]
pub(super) struct Keys {
    fps: Num,
    tracks: Tracks,
    bends: Tracks,
    rotations: Tracks,
    pins: Count,
    duration: Num,
}

impl Keys {
    /// Frames of the motion: the duration or the latest key time, whichever is later, × fps (30
    /// when not given), and one.
    pub(super) fn frames(&self) -> f64 {
        let fps = self.fps.value().unwrap_or(30.0).max(0.0);
        let last = self.tracks.last.max(self.bends.last).max(self.rotations.last);
        (last.max(self.duration.value().unwrap_or(0.0)) * fps).max(0.0) + 1.0
    }

    /// Goals of each frame's solve: the tracks and the pins.
    pub(super) fn effectors(&self) -> f64 {
        self.tracks.count + self.pins.0
    }
}

/// An object of key lists: how many lists, and their latest `time`.
#[derive(Debug, Default)]
struct Tracks {
    count: f64,
    last: f64,
}

/// A list of keys: its latest `time`.
#[derive(Debug, Default)]
struct Times(f64);

/// One key: its `time`.
#[derive(Debug, Default, Deserialize)]
#[serde(default)]
struct Key {
    time: Num,
}

impl<'de> Deserialize<'de> for Tracks {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(TracksValue)
    }
}

impl<'de> Deserialize<'de> for Times {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(TimesValue)
    }
}

/// Anything but the shape expected is absent: a visitor's every other method says so.
macro_rules! absent_otherwise {
    ($value:ty) => {
        fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
            f.write_str("any JSON value")
        }
        fn visit_bool<E>(self, _: bool) -> Result<$value, E> {
            Ok(<$value>::default())
        }
        fn visit_i64<E>(self, _: i64) -> Result<$value, E> {
            Ok(<$value>::default())
        }
        fn visit_u64<E>(self, _: u64) -> Result<$value, E> {
            Ok(<$value>::default())
        }
        fn visit_f64<E>(self, _: f64) -> Result<$value, E> {
            Ok(<$value>::default())
        }
        fn visit_str<E>(self, _: &str) -> Result<$value, E> {
            Ok(<$value>::default())
        }
        fn visit_unit<E>(self) -> Result<$value, E> {
            Ok(<$value>::default())
        }
        fn visit_none<E>(self) -> Result<$value, E> {
            Ok(<$value>::default())
        }
    };
}

struct TracksValue;

impl<'de> Visitor<'de> for TracksValue {
    type Value = Tracks;

    absent_otherwise!(Tracks);

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Tracks, A::Error> {
        let mut t = Tracks::default();
        while let Some((_, times)) = map.next_entry::<IgnoredAny, Times>()? {
            t.count += 1.0;
            t.last = t.last.max(times.0);
        }
        Ok(t)
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Tracks, A::Error> {
        while seq.next_element::<IgnoredAny>()?.is_some() {}
        Ok(Tracks::default())
    }
}

struct TimesValue;

impl<'de> Visitor<'de> for TimesValue {
    type Value = Times;

    absent_otherwise!(Times);

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Times, A::Error> {
        let mut last = 0.0f64;
        while let Some(key) = seq.next_element::<Nested<Key>>()? {
            if let Some(t) = key.0.and_then(|k| k.time.value()) {
                last = last.max(t);
            }
        }
        Ok(Times(last))
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Times, A::Error> {
        while map.next_entry::<IgnoredAny, IgnoredAny>()?.is_some() {}
        Ok(Times(0.0))
    }
}

#[cfg(test)]
mod tests {
    use serde_json::json;

    use super::super::estimate;
    use crate::api::Endpoint;

    fn animate(body: serde_json::Value) -> f64 {
        estimate(Endpoint::Animate, body.to_string().as_bytes())
    }

    #[test]
    fn a_keyed_motion_costs_a_solve_of_its_tracks_and_pins_per_frame() {
        let options = json!({"max_iterations": 10, "restarts": 0, "backtrack": 0});
        let rig = json!({"bones": [{}, {}]});
        let keys = json!({"fps": 10, "tracks": {"a": [{"time": 0}, {"time": 2}], "b": [{"time": 0}]},
                          "bends": {"c": [{"time": 0}, {"time": 1.5}]}, "pins": ["d"]});
        // 21 frames × (2 bones × (1 + 2 tracks + 1 pin) × 10 iterations + a pose of 2 bones).
        assert_eq!(animate(json!({"rig": rig, "keys": keys, "options": options})), 21.0 * (80.0 + 2.0));
        // A bend's key later than every track's sets the frames; 30 fps unless told.
        let keys = json!({"tracks": {"a": [{"time": 0}]}, "bends": {"c": [{"time": 0}, {"time": 1}]}});
        assert_eq!(animate(json!({"rig": rig, "keys": keys, "options": options})), 31.0 * (40.0 + 2.0));
        // A duration past the last key sets them too (the tracks hold to it).
        let keys = json!({"tracks": {"a": [{"time": 0}, {"time": 1}]}, "duration": 3});
        assert_eq!(animate(json!({"rig": rig, "keys": keys, "options": options})), 91.0 * (40.0 + 2.0));
        // Leniently read: a field of the wrong type is absent.
        for keys in [json!({"tracks": 5}), json!({"tracks": {"a": 3}}), json!({"tracks": {"a": [1, {"time": "x"}]}})] {
            let one = json!({"rig": rig, "keys": keys, "options": options});
            assert!(animate(one) <= 2.0 * 40.0 + 2.0, "{keys}");
        }
    }

    #[test]
    fn a_keyed_motion_figure_costs_its_motion_and_a_picture_per_frame_of_a_gif() {
        let options = json!({"max_iterations": 10, "restarts": 0, "backtrack": 0});
        let rig = json!({"bones": [{}, {}]});
        let keys = json!({"fps": 10, "tracks": {"a": [{"time": 0}, {"time": 2}]}});
        let render = |format: &str| {
            let body = json!({"figure": "motion", "format": format, "width": 10, "height": 20,
                              "rig": rig, "keys": keys, "options": options});
            estimate(Endpoint::Render, body.to_string().as_bytes())
        };
        // 21 frames × (2 bones × (1 + 1 track) × 10 iterations + a pose of 2 bones), the picture.
        let motion = 21.0 * (40.0 + 2.0);
        assert_eq!(render("png"), 200.0 + motion + 200.0);
        assert_eq!(render("gif"), 200.0 + motion + 21.0 * 200.0);
    }

    #[test]
    fn a_character_s_keyed_gif_costs_a_picture_per_frame_too() {
        // The character's text in `rig` is read as no body: its bones are capped by --max-bones.
        let keys = json!({"fps": 10, "tracks": {"front-leg-target": [{"time": 0}, {"time": 2}]}});
        let render = |format: &str| {
            let body = json!({"figure": "motion", "format": format, "width": 10, "height": 20,
                              "rig": "{\"bones\": []}", "keys": keys, "animation": "walk"});
            estimate(Endpoint::Render, body.to_string().as_bytes())
        };
        assert!(render("gif") >= 200.0 + 21.0 * 200.0, "{}", render("gif"));
        assert_eq!(render("gif") - render("png"), 20.0 * 200.0);
    }
}
