//! Spine's animations into clips: the bone timelines (`rotate`, `translate`, `translatex`,
//! `translatey`, `scale`, `scalex`, `scaley`, `shear`, `shearx`, `sheary`) and the IK
//! constraints' (`ik`); every other timeline (slots, deform, draw order, events, attachments,
//! `inherit`, transform, path and physics constraints') is skipped.
//!
//! Transform constraints' timelines (`transform`) key the six mixes (`mixRotate`, `mixX`,
//! `mixY`, `mixScaleX`, `mixScaleY`, `mixShearY`; 3.8: `rotateMix`, `translateMix`, `scaleMix`,
//! `shearMix`) with the defaults of [`super::spine_transform`], a curve per mix.
//!
//! A key's `time` defaults to 0; its value is `value` (3.8: `angle` for a rotation) or `x`, `y`,
//! defaulting to 1 for a scale and to 0 otherwise; an IK key's `mix` to 1, `softness` to 0,
//! `bendPositive` to true, `compress` and `stretch` to false. `curve` is absent (linear),
//! `"stepped"`, or Spine 4's Bezier: four numbers `[cx1, cy1, cx2, cy2]` per channel, the
//! control points in the keys' own time and value (degrees for angles). Spine 3.8 writes
//! `"curve": cx1, "c2": cy1, "c3": cx2, "c4": cy2`, normalised to the segment (defaults 0, 1,
//! 1), one curve for every channel; it is turned into Spine 4's form here.

use std::collections::HashMap;
use std::fmt;
use std::marker::PhantomData;

use ikarus::character::{
    BoneKey, BoneProperty, BoneTimeline, ChannelKey, Clip, ConstraintKeys, ConstraintTimeline, IkKey, IkSettings,
    Interpolation, MAX_CHANNELS,
};
use serde::Deserialize;
use serde::de::{self, Deserializer, MapAccess, SeqAccess, Visitor};

use crate::error::Error;
use crate::names::cell;

/// A JSON object's entries in the file's order (`serde_json` keeps no order of its own here).
/// A name listed twice is refused (`"walk" is listed twice in this object`): a JSON reader
/// keeps one of them, which one differs between readers, and keeping both made every later
/// lookup by name (an animation's duration, a clip by name) see the wrong one, and cost a scan
/// each (quadratic in a file of 73,000 entries named alike).
pub(super) struct Ordered<T>(pub Vec<(String, T)>);

impl<T> Default for Ordered<T> {
    fn default() -> Self {
        Ordered(Vec::new())
    }
}

impl<'de, T: Deserialize<'de>> Deserialize<'de> for Ordered<T> {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Entries<T>(PhantomData<T>);
        impl<'de, T: Deserialize<'de>> Visitor<'de> for Entries<T> {
            type Value = Ordered<T>;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("an object")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
                let mut out = Vec::new();
                let mut seen = std::collections::HashSet::new();
                while let Some(key) = map.next_key::<String>()? {
                    if !seen.insert(key.clone()) {
                        return Err(de::Error::custom(format_args!(
                            "{key:?} is listed twice in this object (names must be unique)"
                        )));
                    }
                    let value = map.next_value::<T>()?;
                    out.push((key, value));
                }
                Ok(Ordered(out))
            }
        }
        d.deserialize_map(Entries(PhantomData))
    }
}

/// One animation: its bones' timelines by bone and kind, its IK constraints' by name.
#[derive(Deserialize)]
pub(super) struct Animation {
    #[serde(default)]
    bones: Ordered<Ordered<Vec<Key>>>,
    #[serde(default)]
    ik: Ordered<Vec<Key>>,
    #[serde(default)]
    transform: Ordered<Vec<Key>>,
}

/// A key of any timeline ikarus reads (the fields of the others are ignored).
#[derive(Deserialize)]
#[serde(rename_all = "camelCase")]
struct Key {
    #[serde(default)]
    time: f64,
    value: Option<f64>,
    /// 3.8's rotation value.
    angle: Option<f64>,
    x: Option<f64>,
    y: Option<f64>,
    curve: Option<Curve>,
    c2: Option<f64>,
    c3: Option<f64>,
    c4: Option<f64>,
    mix: Option<f64>,
    softness: Option<f64>,
    bend_positive: Option<bool>,
    compress: Option<bool>,
    stretch: Option<bool>,
    /// A transform constraint key's mixes.
    #[serde(flatten)]
    mixes: super::spine_transform::MixesJson,
}

/// A key's `curve` as written.
enum Curve {
    Stepped,
    /// Spine 4: four numbers per channel.
    Numbers(Vec<f64>),
    /// Spine 3.8: `cx1`, with `c2`, `c3`, `c4` beside it.
    Number(f64),
}

impl<'de> Deserialize<'de> for Curve {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct CurveVisitor;
        impl<'de> Visitor<'de> for CurveVisitor {
            type Value = Curve;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("\"stepped\" or Bezier numbers")
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Curve, E> {
                match v {
                    "stepped" => Ok(Curve::Stepped),
                    _ => Err(E::invalid_value(de::Unexpected::Str(v), &self)),
                }
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Curve, E> {
                Ok(Curve::Number(v))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Curve, E> {
                Ok(Curve::Number(v as f64))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Curve, E> {
                Ok(Curve::Number(v as f64))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Curve, A::Error> {
                let mut numbers = Vec::new();
                while let Some(n) = seq.next_element::<f64>()? {
                    numbers.push(n);
                }
                Ok(Curve::Numbers(numbers))
            }
        }
        d.deserialize_any(CurveVisitor)
    }
}

/// What the timelines' names resolve to.
pub(super) struct Names<'a> {
    /// Bone names to indices.
    pub bones: &'a HashMap<String, usize>,
    /// The IK constraints' names to indices (the first of a name listed twice, [`super::first_index`]).
    pub constraints: &'a HashMap<&'a str, usize>,
    /// The transform constraints' names to their indices in the whole list of constraints (the
    /// first of a name listed twice).
    pub transforms: &'a HashMap<&'a str, usize>,
}

/// What a bone timeline's kind keys: the property, whether its values are angles (degrees in
/// the file), and a value's default.
fn property(kind: &str) -> Option<(BoneProperty, bool, f64)> {
    Some(match kind {
        "rotate" => (BoneProperty::Rotate, true, 0.0),
        "translate" => (BoneProperty::Translate, false, 0.0),
        "translatex" => (BoneProperty::TranslateX, false, 0.0),
        "translatey" => (BoneProperty::TranslateY, false, 0.0),
        "scale" => (BoneProperty::Scale, false, 1.0),
        "scalex" => (BoneProperty::ScaleX, false, 1.0),
        "scaley" => (BoneProperty::ScaleY, false, 1.0),
        "shear" => (BoneProperty::Shear, true, 0.0),
        "shearx" => (BoneProperty::ShearX, true, 0.0),
        "sheary" => (BoneProperty::ShearY, true, 0.0),
        _ => return None,
    })
}

/// The clip of animation `name`, `duration` long; `legacy` for a 3.8 file.
pub(super) fn clip(name: &str, a: &Animation, duration: f64, names: &Names<'_>, legacy: bool) -> Result<Clip, Error> {
    let at = format!("animations.{}", cell(name));
    let mut bones = Vec::new();
    for (bone_name, timelines) in &a.bones.0 {
        let bone = names
            .bones
            .get(bone_name)
            .copied()
            .ok_or_else(|| Error::input(format!("{at}.bones.{}: no bone of that name", cell(bone_name))))?;
        for (kind, keys) in &timelines.0 {
            let Some((property, angle, default)) = property(kind) else { continue };
            let unit = if angle { 1f64.to_radians() } else { 1.0 };
            let channels = property.channels();
            let value = |k: &Key| match channels {
                1 => [k.value.or(k.angle).unwrap_or(default) * unit, 0.0],
                _ => [k.x.unwrap_or(default) * unit, k.y.unwrap_or(default) * unit],
            };
            let series = Series { path: format!("{at}.bones.{}.{kind}", cell(bone_name)), channels, unit, legacy };
            let keys = series
                .read(keys, value)?
                .into_iter()
                .map(|Read { time, values, curves, .. }| BoneKey { time, values, curves })
                .collect();
            bones.push(BoneTimeline { bone, property, keys });
        }
    }
    let mut constraints = Vec::new();
    for (ik_name, keys) in &a.ik.0 {
        let constraint = names
            .constraints
            .get(ik_name.as_str())
            .copied()
            .ok_or_else(|| Error::input(format!("{at}.ik.{}: no IK constraint of that name", cell(ik_name))))?;
        let series = Series { path: format!("{at}.ik.{}", cell(ik_name)), channels: 2, unit: 1.0, legacy };
        let value = |k: &Key| [k.mix.unwrap_or(1.0), k.softness.unwrap_or(0.0)];
        let keys = series
            .read(keys, value)?
            .into_iter()
            .map(|Read { time, values: [mix, softness], curves, key: k }| {
                let settings = IkSettings {
                    mix,
                    softness,
                    bend_positive: k.bend_positive.unwrap_or(true),
                    compress: k.compress.unwrap_or(false),
                    stretch: k.stretch.unwrap_or(false),
                };
                IkKey { time, settings, curves }
            })
            .collect::<Vec<_>>();
        if let Some((i, k)) = keys.iter().enumerate().find(|(_, k)| !(0.0..=1.0).contains(&k.settings.mix)) {
            return Err(Error::input(format!("{}[{i}].mix = {}: must be within 0 and 1", series.path, k.settings.mix)));
        }
        if let Some((i, k)) = keys.iter().enumerate().find(|(_, k)| k.settings.softness < 0.0) {
            return Err(Error::input(format!(
                "{}[{i}].softness = {}: must not be negative",
                series.path, k.settings.softness
            )));
        }
        constraints.push(ConstraintTimeline { constraint, keys: ConstraintKeys::Ik(keys) });
    }
    constraints.extend(transform_timelines(a, names, &at, legacy)?);
    Ok(Clip { name: name.to_owned(), duration, bones, constraints })
}

/// The transform constraints' timelines of animation `a` (at `at`).
fn transform_timelines(
    a: &Animation,
    names: &Names<'_>,
    at: &str,
    legacy: bool,
) -> Result<Vec<ConstraintTimeline>, Error> {
    let mut out = Vec::new();
    for (name, keys) in &a.transform.0 {
        let constraint = names.transforms.get(name.as_str()).copied().ok_or_else(|| {
            Error::input(format!("{at}.transform.{}: no transform constraint of that name", cell(name)))
        })?;
        let path = format!("{at}.transform.{}", cell(name));
        for (i, k) in keys.iter().enumerate() {
            k.mixes.settings(&format!("{path}[{i}]"))?;
        }
        // Every key's mixes were checked above.
        let mixes = |k: &Key| {
            let mut values = [0.0; MAX_CHANNELS];
            values[..6].copy_from_slice(&k.mixes.settings("").map_or([0.0; 6], |m| m.to_array()));
            values
        };
        let series = Series { path, channels: 6, unit: 1.0, legacy };
        let keys = series
            .read(keys, mixes)?
            .into_iter()
            .map(|Read { time, values, curves, .. }| ChannelKey { time, values, curves })
            .collect();
        out.push(ConstraintTimeline { constraint, keys: ConstraintKeys::Transform(keys) });
    }
    Ok(out)
}

/// A key as read: its time, values in the model's units, curves toward the next key, and the
/// key as written.
struct Read<'k, const N: usize> {
    time: f64,
    values: [f64; N],
    curves: [Interpolation; N],
    key: &'k Key,
}

/// How one timeline's keys are read: its path in the file, its channels, the factor from the
/// file's values to the model's (degrees to radians for angles), and the curves' form.
struct Series {
    path: String,
    channels: usize,
    unit: f64,
    legacy: bool,
}

impl Series {
    /// Each key's time, values (by `value`, in the model's units), curves toward the next key,
    /// and the key itself; times must be at least 0 and increasing.
    fn read<'k, const N: usize>(
        &self,
        keys: &'k [Key],
        value: impl Fn(&Key) -> [f64; N],
    ) -> Result<Vec<Read<'k, N>>, Error> {
        let mut out = Vec::with_capacity(keys.len());
        for (i, k) in keys.iter().enumerate() {
            if k.time < 0.0 {
                return Err(Error::input(format!("{}[{i}].time = {}: must not be negative", self.path, k.time)));
            }
            if let Some(prev) = keys.get(i.wrapping_sub(1)).filter(|p| p.time >= k.time) {
                return Err(Error::input(format!(
                    "{}[{i}].time = {}: must be after the previous key's, {}",
                    self.path, k.time, prev.time
                )));
            }
            let next = keys.get(i + 1).map(|n| (n.time, value(n)));
            let curves = self.curves(i, k, value(k), next)?;
            out.push(Read { time: k.time, values: value(k), curves, key: k });
        }
        Ok(out)
    }

    /// Key `i`'s curves toward `next` (its time and values), per channel.
    fn curves<const N: usize>(
        &self,
        i: usize,
        k: &Key,
        here: [f64; N],
        next: Option<(f64, [f64; N])>,
    ) -> Result<[Interpolation; N], Error> {
        // Spine 3.8's curve, normalised to the segment from this key to the next.
        let normalised = |p: [f64; 4]| match next {
            None => [Interpolation::Linear; N],
            Some((t1, there)) => std::array::from_fn(|c| unit_bezier([k.time, here[c]], [t1, there[c]], p)),
        };
        Ok(match &k.curve {
            None => [Interpolation::Linear; N],
            Some(Curve::Stepped) => [Interpolation::Stepped; N],
            Some(Curve::Number(cx1)) => {
                normalised([*cx1, k.c2.unwrap_or(0.0), k.c3.unwrap_or(1.0), k.c4.unwrap_or(1.0)])
            }
            Some(Curve::Numbers(n)) if self.legacy && n.len() == 4 => normalised([n[0], n[1], n[2], n[3]]),
            Some(Curve::Numbers(n)) => {
                let want = 4 * self.channels;
                if n.len() != want {
                    return Err(Error::input(format!(
                        "{}[{i}].curve: {} numbers, expected {want} ([cx1, cy1, cx2, cy2] per channel)",
                        self.path,
                        n.len()
                    )));
                }
                let mut curves = [Interpolation::Linear; N];
                for (c, p) in n.chunks(4).enumerate().take(N) {
                    curves[c] = Interpolation::Bezier { c1: [p[0], p[1] * self.unit], c2: [p[2], p[3] * self.unit] };
                }
                curves
            }
        })
    }
}

/// The Bezier from `from` to `to` (each `[time, value]`) whose control points are
/// `[cx1, cy1, cx2, cy2]` in the segment scaled to the unit square (Spine 3.8's and DragonBones'
/// form), as the model's absolute control points.
pub(super) fn unit_bezier(from: [f64; 2], to: [f64; 2], [cx1, cy1, cx2, cy2]: [f64; 4]) -> Interpolation {
    let (dt, dv) = (to[0] - from[0], to[1] - from[1]);
    Interpolation::Bezier { c1: [from[0] + cx1 * dt, from[1] + cy1 * dv], c2: [from[0] + cx2 * dt, from[1] + cy2 * dv] }
}
