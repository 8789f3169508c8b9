//! A character's motion ([`super::motion`]) written as frames CSV and drawn as pictures, for
//! `ikarus animate|track --rig FILE.json --format csv | --out x.gif|svg|png`, `POST
//! /api/animate|track` with `"format": "csv"` and `POST /api/render` (figure `motion`) with a
//! character: the same bytes through each.

use std::io::Write;

use serde::Serialize;

use super::motion::{Motion, StreamError};
use crate::error::Error;
use crate::picture::Drawing;
use crate::pose::{PoseReport, PosedBoneJson};

/// Most bones a picture of a character's motion draws, frames × bones: a picture holds every
/// frame's bones (the SVG and PNG draw each frame, the GIF animates them), so unlike the frames'
/// JSON and CSV it cannot be written as it is posed. A million is some 100 MB held, and 15,000
/// frames of a 67-bone spineboy.
pub const MAX_DRAWN_BONES: usize = 1_000_000;

/// The CSV's header: one row per bone per frame, the fields of a posed bone.
pub const CSV_HEADER: &str = "frame,time,bone,x,y,rotation_deg,tip_x,tip_y";

/// The motion's frames as CSV into `w`, each frame written as it is posed
/// ([`Motion::each_frame`]): [`CSV_HEADER`], then for every frame (`time` in seconds) every bone
/// in the file's order. Numbers are printed as the rig's CSV prints them (Rust's shortest form
/// that reads back to the same bits), a bone's name quoted as RFC 4180 asks when it holds a
/// comma, a quote or a line break.
pub fn write_csv(motion: &Motion<'_>, w: &mut dyn Write) -> Result<(), StreamError> {
    writeln!(w, "{CSV_HEADER}").map_err(StreamError::Io)?;
    motion.each_frame(&mut |k, time, report| {
        for b in &report.bones {
            writeln!(
                w,
                "{k},{time:?},{},{:?},{:?},{:?},{:?},{:?}",
                csv_field(&b.name),
                b.x,
                b.y,
                b.rotation_deg,
                b.tip[0],
                b.tip[1]
            )?;
        }
        Ok(())
    })
}

/// The motion's frames as CSV bytes ([`write_csv`]).
pub fn csv(motion: &Motion<'_>) -> Result<Vec<u8>, Error> {
    let mut bytes = Vec::new();
    write_csv(motion, &mut bytes).map_err(message)?;
    Ok(bytes)
}

/// One frame of [`write_json`], borrowed: the bytes of [`super::motion::FrameJson`].
#[derive(Serialize)]
struct FrameRef<'a> {
    time: f64,
    bones: &'a [PosedBoneJson],
}

/// The motion's frames as JSON into `w`, each frame written as it is posed
/// ([`Motion::each_frame`]): the bytes `serde_json` makes of [`Motion::frames`],
/// `{"frames":[{"time":…,"bones":[…]},…],"unsupported":[…]}`, without a line break.
pub fn write_json(motion: &Motion<'_>, w: &mut dyn Write) -> Result<(), StreamError> {
    w.write_all(b"{\"frames\":[").map_err(StreamError::Io)?;
    let mut unsupported = Vec::new();
    motion.each_frame(&mut |k, time, report| {
        if k > 0 {
            w.write_all(b",")?;
        }
        serde_json::to_writer(&mut *w, &FrameRef { time, bones: &report.bones })?;
        if k + 1 == motion.frame_count() {
            unsupported = serde_json::to_vec(&report.unsupported)?;
        }
        Ok(())
    })?;
    w.write_all(b"],\"unsupported\":")
        .and_then(|()| w.write_all(&unsupported))
        .and_then(|()| w.write_all(b"}"))
        .map_err(StreamError::Io)
}

/// The motion's frames as JSON bytes ([`write_json`]).
pub fn json(motion: &Motion<'_>) -> Result<Vec<u8>, Error> {
    let mut bytes = Vec::new();
    write_json(motion, &mut bytes).map_err(message)?;
    Ok(bytes)
}

/// A [`StreamError`] into memory as one line: a frame's refusal (writing to memory does not
/// fail otherwise).
fn message(e: StreamError) -> Error {
    match e {
        StreamError::Motion(m) => m,
        StreamError::Io(e) => Error::input(format!("cannot write: {e}")),
    }
}

/// `field` as one CSV field: as it is, or in double quotes with its quotes doubled when it holds
/// a comma, a quote or a line break (RFC 4180).
fn csv_field(field: &str) -> std::borrow::Cow<'_, str> {
    if field.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", field.replace('"', "\"\"")).into()
    } else {
        field.into()
    }
}

/// The motion's picture of `poses` (its frames, from [`Motion::poses`]): every frame's bones and
/// IK targets, captioned with [`Motion::caption`], drawn at the motion's fps.
#[must_use]
pub fn drawing<'a>(motion: &Motion<'_>, poses: &'a [(f64, PoseReport)]) -> Drawing<'a> {
    let figure = ikarus_render::CharacterMotionFigure {
        frames: poses.iter().map(|(_, r)| r.figure(None)).collect(),
        times: poses.iter().map(|(t, _)| *t).collect(),
        caption: Some(motion.caption()),
    };
    Drawing::CharacterMotion { figure, fps: motion.fps }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_with_commas_quotes_and_line_breaks_are_quoted() {
        assert_eq!(csv_field("front-foot"), "front-foot");
        assert_eq!(csv_field("a,b"), "\"a,b\"");
        assert_eq!(csv_field("say \"hi\""), "\"say \"\"hi\"\"\"");
        assert_eq!(csv_field("two\nlines"), "\"two\nlines\"");
    }

    #[test]
    fn the_streamed_json_is_the_bytes_of_the_frames_and_a_refused_frame_stops_the_writer() {
        use crate::character::motion::{Course, Motion};
        let text = include_str!("../../../../examples/characters/spine-raptor-pro.json");
        let loaded = crate::character::load(text, "raptor").unwrap();
        let course = Course::Path { bone: "root".into(), points: vec![[0.0, 0.0], [1.0, 2.0], [3.0, 1.0]] };
        let motion = Motion::new(&loaded, course, 30.0).unwrap();
        assert_eq!(json(&motion).unwrap(), serde_json::to_vec(&motion.frames().unwrap()).unwrap());
        // The writer sees each frame as it is posed: one that fails at the second frame stops
        // the motion there.
        let mut frames = 0;
        let stopped = motion.each_frame(&mut |k, _, _| {
            frames += 1;
            if k == 1 { Err(std::io::Error::other("full")) } else { Ok(()) }
        });
        assert!(matches!(stopped, Err(StreamError::Io(_))));
        assert_eq!(frames, 2);
    }
}
