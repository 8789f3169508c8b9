//! What a Spine file has that ikarus does not use, listed so that nothing is dropped silently:
//! attachments that are not drawn (point, bounding box, a clipping polygon of more than
//! [`ikarus::character::MAX_CLIP_VERTICES`] vertices), sequences (an attachment's
//! frames shown one after another; only the setup frame is drawn), any
//! top-level field the 4.2 format does not have (Spine 4.3's sliders, a later kind of
//! constraint) and any animation timeline group it does not know.
//!
//! Everything that poses the bones (bones, every constraint kind, skins, the bone and
//! constraint timelines) is read elsewhere, and so are slots, region, mesh, linked mesh, path
//! and clipping attachments (`spine_art`, `spine_slots`), and the attachment, colour, draw
//! order and deform timelines (`spine_slot_clips`); events are not listed. A slot timeline of another name and an
//! attachment's `sequence` timeline (its frames played over time) are listed.

use ikarus::character::Unsupported;
use serde_json::Value;

/// The top-level fields of a Spine 4.2 file.
const FIELDS: [&str; 10] =
    ["skeleton", "bones", "slots", "ik", "transform", "path", "physics", "skins", "events", "animations"];

/// The timeline groups of an animation (`drawOrder` is also written `draworder`).
const TIMELINES: [&str; 11] = [
    "bones",
    "slots",
    "ik",
    "transform",
    "path",
    "physics",
    "attachments",
    "deform",
    "drawOrder",
    "draworder",
    "events",
];

/// The unsupported features of the file `value`, in the file's order.
pub(super) fn features(value: &Value) -> Vec<Unsupported> {
    let mut out = Vec::new();
    let mut push = |kind: &str, name: String| out.push(Unsupported { kind: kind.to_owned(), name });
    let Some(top) = value.as_object() else { return Vec::new() };
    for key in top.keys().filter(|k| !FIELDS.contains(&k.as_str())) {
        push("field", key.clone());
    }
    for (skin, slot, name, attachment) in attachments(value) {
        let at = || format!("{name} (skin {skin}, slot {slot})");
        match attachment.get("type").and_then(Value::as_str) {
            Some("clipping")
                if attachment.get("vertexCount").and_then(Value::as_f64).unwrap_or(0.0)
                    > ikarus::character::MAX_CLIP_VERTICES as f64 =>
            {
                push(
                    "clipping attachment",
                    format!("{} (more than {} vertices)", at(), ikarus::character::MAX_CLIP_VERTICES),
                );
            }
            Some("point") => push("point attachment", at()),
            Some("boundingbox") => push("bounding box attachment", at()),
            _ => {}
        }
        if attachment.get("sequence").is_some() {
            push("sequence", at());
        }
    }
    for (name, animation) in value.get("animations").and_then(Value::as_object).into_iter().flatten() {
        for group in animation.as_object().into_iter().flat_map(|a| a.keys()) {
            if !TIMELINES.contains(&group.as_str()) {
                push("timeline", format!("{group} (animation {name})"));
            }
        }
        for (slot, timelines) in animation.get("slots").and_then(Value::as_object).into_iter().flatten() {
            for kind in timelines.as_object().into_iter().flat_map(|t| t.keys()) {
                if !super::spine_slot_clips::KNOWN.contains(&kind.as_str()) {
                    push("timeline", format!("{kind} (animation {name}, slot {slot})"));
                }
            }
        }
        let skins = animation.get("attachments").and_then(Value::as_object).into_iter().flatten();
        for (skin, slots) in skins {
            for (slot, list) in slots.as_object().into_iter().flatten() {
                for (attachment, timelines) in list.as_object().into_iter().flatten() {
                    for kind in timelines.as_object().into_iter().flat_map(|t| t.keys()).filter(|k| *k != "deform") {
                        push(
                            "timeline",
                            format!("{kind} of {attachment} (animation {name}, skin {skin}, slot {slot})"),
                        );
                    }
                }
            }
        }
    }
    out
}

/// Every attachment of every skin: `(skin, slot, attachment name, attachment)`. Spine 4.x lists
/// skins in an array of `{name, attachments}`; 3.8 writes an object of skins by name.
fn attachments(value: &Value) -> Vec<(String, &str, &str, &Value)> {
    let skins: Vec<(String, &Value)> = match value.get("skins") {
        Some(Value::Array(list)) => list
            .iter()
            .map(|s| {
                (
                    s.get("name").and_then(Value::as_str).unwrap_or("").to_owned(),
                    s.get("attachments").unwrap_or(&Value::Null),
                )
            })
            .collect(),
        Some(Value::Object(by_name)) => by_name.iter().map(|(n, s)| (n.clone(), s)).collect(),
        _ => Vec::new(),
    };
    let mut out = Vec::new();
    for (skin, slots) in skins {
        for (slot, list) in slots.as_object().into_iter().flatten() {
            for (name, attachment) in list.as_object().into_iter().flatten() {
                out.push((skin.clone(), slot.as_str(), name.as_str(), attachment));
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    fn listed(value: &Value) -> Vec<(String, String)> {
        features(value).into_iter().map(|u| (u.kind, u.name)).collect()
    }

    #[test]
    fn clipping_sequences_unknown_fields_and_timelines_are_listed() {
        let file = json!({
            "skeleton": {"spine": "4.2.0"}, "bones": [{"name": "root"}],
            "slider": [{"name": "s"}],
            "skins": [{"name": "default", "attachments": {"hand": {
                "clip": {"type": "clipping", "end": "hand", "vertexCount": 3, "vertices": [0, 0, 1, 0, 0, 1]},
                "big": {"type": "clipping", "end": "hand", "vertexCount": 300},
                "flame": {"sequence": {"count": 3}},
                "bb": {"type": "boundingbox", "vertexCount": 3, "vertices": [0, 0, 1, 0, 0, 1]},
                "tip": {"type": "point", "x": 1},
                "arm": {"type": "mesh"}
            }}}],
            "animations": {"go": {"bones": {}, "sliders": {}, "drawOrder": [],
                "slots": {"hand": {"rgba": [], "flash": []}},
                "attachments": {"default": {"hand": {"flame": {"deform": [], "sequence": []}}}}}}
        });
        assert_eq!(
            listed(&file),
            [
                ("field".to_owned(), "slider".to_owned()),
                ("bounding box attachment".to_owned(), "bb (skin default, slot hand)".to_owned()),
                ("clipping attachment".to_owned(), "big (skin default, slot hand) (more than 256 vertices)".to_owned()),
                ("sequence".to_owned(), "flame (skin default, slot hand)".to_owned()),
                ("point attachment".to_owned(), "tip (skin default, slot hand)".to_owned()),
                ("timeline".to_owned(), "sliders (animation go)".to_owned()),
                ("timeline".to_owned(), "flash (animation go, slot hand)".to_owned()),
                ("timeline".to_owned(), "sequence of flame (animation go, skin default, slot hand)".to_owned()),
            ]
        );
    }

    #[test]
    fn a_file_with_only_what_ikarus_reads_or_does_not_draw_lists_nothing() {
        let file = json!({
            "skeleton": {"spine": "4.2.0"}, "bones": [{"name": "root"}], "slots": [], "ik": [], "transform": [],
            "path": [], "physics": [], "events": {},
            "skins": {"default": {"hand": {"arm": {"type": "mesh"}, "p": {"type": "path"}}}},
            "animations": {"go": {"bones": {}, "slots": {}, "deform": {}, "attachments": {}, "draworder": [], "events": []}}
        });
        assert!(features(&file).is_empty(), "{:?}", listed(&file));
    }
}
