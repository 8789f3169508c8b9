//! The sections of a `.skel` before the skins: the header (`skeleton`), the strings table, the
//! bones, slots and the IK, transform, path and physics constraints, each written as Spine's
//! JSON export writes it (names for indices, degrees, colours as hex, the enums' names).

use serde_json::{Map, Value, json};

use super::Names;
use super::reader::Reader;
use crate::error::Error;

/// Bones' inherit modes, by their number in the file.
const INHERIT: [&str; 5] = ["normal", "onlyTranslation", "noRotationOrReflection", "noScale", "noScaleOrReflection"];
/// Slots' blend modes.
const BLEND: [&str; 4] = ["normal", "additive", "multiply", "screen"];
/// Path constraints' position, spacing and rotate modes.
const POSITION_MODE: [&str; 2] = ["fixed", "percent"];
const SPACING_MODE: [&str; 4] = ["length", "fixed", "percent", "proportional"];
const ROTATE_MODE: [&str; 3] = ["tangent", "chain", "chainScale"];

/// An enum's name from its number in the file, refused out of range.
pub(super) fn pick(
    r: &Reader<'_>,
    start: usize,
    field: &str,
    names: &[&'static str],
    i: usize,
) -> Result<Value, Error> {
    names
        .get(i)
        .map(|s| Value::from(*s))
        .ok_or_else(|| r.fail_at(start, field, &format!("an unknown {field} (got {i})")))
}

fn enum_varint(r: &mut Reader<'_>, field: &str, names: &[&'static str]) -> Result<Value, Error> {
    let start = r.pos();
    let i = r.unsigned(field)?;
    pick(r, start, field, names, i)
}

/// The header: hash, version, bounds, reference scale, and the nonessential fps, images and
/// audio; returns the `skeleton` object and whether nonessential data follows in the file.
pub(super) fn header(r: &mut Reader<'_>) -> Result<(Value, bool), Error> {
    r.at = "skeleton".to_owned();
    let hash = r.take_bytes(8, "hash")?;
    let mut o = Map::new();
    o.insert("hash".into(), Value::from(base64(hash)));
    let start = r.pos();
    let version = r.string("spine")?.unwrap_or_default();
    if !version.starts_with("4.2") {
        return Err(r.fail_at(
            start,
            "spine",
            &format!("this reader reads Spine 4.2's binary format (got {version:?})"),
        ));
    }
    o.insert("spine".into(), Value::from(version));
    for f in ["x", "y", "width", "height", "referenceScale"] {
        o.insert(f.into(), r.number(f)?);
    }
    let nonessential = r.bool("nonessential")?;
    if nonessential {
        o.insert("fps".into(), r.number("fps")?);
        o.insert("images".into(), Value::from(r.string("images")?.unwrap_or_default()));
        o.insert("audio".into(), Value::from(r.string("audio")?.unwrap_or_default()));
    }
    Ok((Value::Object(o), nonessential))
}

/// Standard base64 without padding, as JSON writes the 8 bytes of the hash.
fn base64(bytes: &[u8]) -> String {
    const ABC: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::new();
    for chunk in bytes.chunks(3) {
        let n = chunk.iter().enumerate().fold(0u32, |n, (i, b)| n | u32::from(*b) << (16 - 8 * i));
        for i in 0..=chunk.len() {
            out.push(char::from(ABC[(n >> (18 - 6 * i) & 63) as usize]));
        }
    }
    out
}

/// The strings table that attachment names, paths and keys refer to.
pub(super) fn strings(r: &mut Reader<'_>) -> Result<(), Error> {
    r.at = "strings".to_owned();
    let n = r.count("count", 1)?;
    let mut table = Vec::with_capacity(n);
    for i in 0..n {
        r.at = format!("strings[{i}]");
        table.push(r.string("")?.unwrap_or_default());
    }
    r.strings = table;
    Ok(())
}

/// The bones, parent first.
pub(super) fn bones(r: &mut Reader<'_>, names: &mut Names, nonessential: bool) -> Result<Value, Error> {
    r.at = "bones".to_owned();
    let n = r.count("count", 35)?;
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        r.at = format!("bones[{i}]");
        let mut o = Map::new();
        let name = r.name("name")?;
        o.insert("name".into(), Value::from(name.clone()));
        if i > 0 {
            let p = r.index("parent", "bone", i)?;
            o.insert("parent".into(), Value::from(names.bones[p].clone()));
        }
        for f in ["rotation", "x", "y", "scaleX", "scaleY", "shearX", "shearY", "length"] {
            o.insert(f.into(), r.number(f)?);
        }
        o.insert("inherit".into(), enum_varint(r, "inherit", &INHERIT)?);
        o.insert("skin".into(), Value::from(r.bool("skin")?));
        if nonessential {
            o.insert("color".into(), Value::from(r.rgba("color")?));
            if let Some(icon) = r.string("icon")? {
                o.insert("icon".into(), Value::from(icon));
            }
            o.insert("visible".into(), Value::from(r.bool("visible")?));
        }
        names.bones.push(name);
        out.push(Value::Object(o));
    }
    Ok(Value::Array(out))
}

/// The slots, in setup draw order.
pub(super) fn slots(r: &mut Reader<'_>, names: &mut Names, nonessential: bool) -> Result<Value, Error> {
    r.at = "slots".to_owned();
    let n = r.count("count", 11)?;
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        r.at = format!("slots[{i}]");
        let mut o = Map::new();
        let name = r.name("name")?;
        o.insert("name".into(), Value::from(name.clone()));
        let b = r.index("bone", "bone", names.bones.len())?;
        o.insert("bone".into(), Value::from(names.bones[b].clone()));
        o.insert("color".into(), Value::from(r.rgba("color")?));
        let dark = r.int("dark")?;
        if dark != -1 {
            o.insert("dark".into(), Value::from(format!("{:06x}", dark as u32 & 0x00ff_ffff)));
        }
        if let Some(a) = r.string_ref("attachment")? {
            o.insert("attachment".into(), Value::from(a));
        }
        o.insert("blend".into(), enum_varint(r, "blend", &BLEND)?);
        if nonessential {
            o.insert("visible".into(), Value::from(r.bool("visible")?));
        }
        names.slots.push(name);
        out.push(Value::Object(o));
    }
    Ok(Value::Array(out))
}

/// A constraint's `order` and constrained bones.
fn order_and_bones(r: &mut Reader<'_>, names: &Names, o: &mut Map<String, Value>) -> Result<(), Error> {
    o.insert("order".into(), Value::from(r.unsigned("order")?));
    let n = r.count("bones", 1)?;
    let mut bones = Vec::with_capacity(n);
    for _ in 0..n {
        let b = r.index("bones", "bone", names.bones.len())?;
        bones.push(Value::from(names.bones[b].clone()));
    }
    o.insert("bones".into(), Value::Array(bones));
    Ok(())
}

fn target_bone(r: &mut Reader<'_>, names: &Names, o: &mut Map<String, Value>) -> Result<(), Error> {
    let t = r.index("target", "bone", names.bones.len())?;
    o.insert("target".into(), Value::from(names.bones[t].clone()));
    Ok(())
}

/// The IK constraints.
pub(super) fn ik(r: &mut Reader<'_>, names: &mut Names) -> Result<Value, Error> {
    r.at = "ik".to_owned();
    let n = r.count("count", 5)?;
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        r.at = format!("ik[{i}]");
        let mut o = Map::new();
        let name = r.name("name")?;
        o.insert("name".into(), Value::from(name.clone()));
        order_and_bones(r, names, &mut o)?;
        target_bone(r, names, &mut o)?;
        let flags = r.byte("flags")?;
        o.insert("skin".into(), Value::from(flags & 1 != 0));
        o.insert("bendPositive".into(), Value::from(flags & 2 != 0));
        o.insert("compress".into(), Value::from(flags & 4 != 0));
        o.insert("stretch".into(), Value::from(flags & 8 != 0));
        o.insert("uniform".into(), Value::from(flags & 16 != 0));
        let mix = match (flags & 32 != 0, flags & 64 != 0) {
            (false, _) => json!(0.0),
            (true, false) => json!(1.0),
            (true, true) => r.number("mix")?,
        };
        o.insert("mix".into(), mix);
        if flags & 128 != 0 {
            o.insert("softness".into(), r.number("softness")?);
        }
        names.ik.push(name);
        out.push(Value::Object(o));
    }
    Ok(Value::Array(out))
}

/// The transform constraints.
pub(super) fn transform(r: &mut Reader<'_>, names: &mut Names) -> Result<Value, Error> {
    r.at = "transform".to_owned();
    let n = r.count("count", 6)?;
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        r.at = format!("transform[{i}]");
        let mut o = Map::new();
        let name = r.name("name")?;
        o.insert("name".into(), Value::from(name.clone()));
        order_and_bones(r, names, &mut o)?;
        target_bone(r, names, &mut o)?;
        let flags = r.byte("flags")?;
        o.insert("skin".into(), Value::from(flags & 1 != 0));
        o.insert("local".into(), Value::from(flags & 2 != 0));
        o.insert("relative".into(), Value::from(flags & 4 != 0));
        // Each offset and mix is there when its bit is set, else 0.
        for (bit, f) in [(8, "rotation"), (16, "x"), (32, "y"), (64, "scaleX"), (128, "scaleY")] {
            o.insert(f.into(), if flags & bit != 0 { r.number(f)? } else { Value::from(0.0) });
        }
        let flags = r.byte("flags")?;
        let fields = [
            (1, "shearY"),
            (2, "mixRotate"),
            (4, "mixX"),
            (8, "mixY"),
            (16, "mixScaleX"),
            (32, "mixScaleY"),
            (64, "mixShearY"),
        ];
        for (bit, f) in fields {
            o.insert(f.into(), if flags & bit != 0 { r.number(f)? } else { Value::from(0.0) });
        }
        names.transform.push(name);
        out.push(Value::Object(o));
    }
    Ok(Value::Array(out))
}

/// The path constraints.
pub(super) fn path(r: &mut Reader<'_>, names: &mut Names) -> Result<Value, Error> {
    r.at = "path".to_owned();
    let n = r.count("count", 26)?;
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        r.at = format!("path[{i}]");
        let mut o = Map::new();
        let name = r.name("name")?;
        o.insert("name".into(), Value::from(name.clone()));
        o.insert("order".into(), Value::from(r.unsigned("order")?));
        o.insert("skin".into(), Value::from(r.bool("skin")?));
        let nb = r.count("bones", 1)?;
        let mut bones = Vec::with_capacity(nb);
        for _ in 0..nb {
            let b = r.index("bones", "bone", names.bones.len())?;
            bones.push(Value::from(names.bones[b].clone()));
        }
        o.insert("bones".into(), Value::Array(bones));
        let t = r.index("target", "slot", names.slots.len())?;
        o.insert("target".into(), Value::from(names.slots[t].clone()));
        let start = r.pos();
        let flags = r.byte("flags")?;
        o.insert("positionMode".into(), pick(r, start, "positionMode", &POSITION_MODE, usize::from(flags & 1))?);
        o.insert("spacingMode".into(), pick(r, start, "spacingMode", &SPACING_MODE, usize::from(flags >> 1 & 3))?);
        o.insert("rotateMode".into(), pick(r, start, "rotateMode", &ROTATE_MODE, usize::from(flags >> 3 & 3))?);
        if flags & 128 != 0 {
            o.insert("rotation".into(), r.number("rotation")?);
        }
        for f in ["position", "spacing", "mixRotate", "mixX", "mixY"] {
            o.insert(f.into(), r.number(f)?);
        }
        names.path.push(name);
        out.push(Value::Object(o));
    }
    Ok(Value::Array(out))
}

/// The physics constraints.
pub(super) fn physics(r: &mut Reader<'_>, names: &mut Names) -> Result<Value, Error> {
    r.at = "physics".to_owned();
    let n = r.count("count", 30)?;
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        r.at = format!("physics[{i}]");
        let mut o = Map::new();
        let name = r.name("name")?;
        o.insert("name".into(), Value::from(name.clone()));
        o.insert("order".into(), Value::from(r.unsigned("order")?));
        let b = r.index("bone", "bone", names.bones.len())?;
        o.insert("bone".into(), Value::from(names.bones[b].clone()));
        let flags = r.byte("flags")?;
        o.insert("skin".into(), Value::from(flags & 1 != 0));
        for (bit, f) in [(2, "x"), (4, "y"), (8, "rotate"), (16, "scaleX"), (32, "shearX")] {
            if flags & bit != 0 {
                o.insert(f.into(), r.number(f)?);
            }
        }
        if flags & 64 != 0 {
            o.insert("limit".into(), r.number("limit")?);
        }
        o.insert("fps".into(), Value::from(r.byte("fps")?));
        for f in ["inertia", "strength", "damping"] {
            o.insert(f.into(), r.number(f)?);
        }
        if flags & 128 != 0 {
            let start = r.pos();
            let inverse = r.float("mass")?;
            if inverse == 0.0 {
                return Err(r.fail_at(start, "mass", "the inverse of a mass is 0 (got 0)"));
            }
            o.insert("mass".into(), Value::from(f64::from(1.0 / inverse as f32)));
        }
        for f in ["wind", "gravity"] {
            o.insert(f.into(), r.number(f)?);
        }
        let flags = r.byte("flags")?;
        let globals = [
            "inertiaGlobal",
            "strengthGlobal",
            "dampingGlobal",
            "massGlobal",
            "windGlobal",
            "gravityGlobal",
            "mixGlobal",
        ];
        for (bit, f) in globals.iter().enumerate() {
            o.insert((*f).into(), Value::from(flags & 1 << bit != 0));
        }
        if flags & 128 != 0 {
            o.insert("mix".into(), r.number("mix")?);
        }
        names.physics.push(name);
        out.push(Value::Object(o));
    }
    Ok(Value::Array(out))
}
