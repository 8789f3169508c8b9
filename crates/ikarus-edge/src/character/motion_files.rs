//! A character's motion ([`super::motion`]) written as frames CSV and drawn as pictures, for
//! `ikarus animate|track --rig FILE.json --format csv | --out x.gif|svg|png`, `POST
//! /api/animate|track` with `"format": "csv"` and `POST /api/render` (figure `motion`) with a
//! character: the same bytes through each.

use std::io::Write;

use super::motion::Motion;
use crate::picture::Drawing;
use crate::pose::PoseReport;

/// The CSV's header: one row per bone per frame, the fields of a posed bone.
pub const CSV_HEADER: &str = "frame,time,bone,x,y,rotation_deg,tip_x,tip_y";

/// The frames as CSV into `w`: [`CSV_HEADER`], then for every frame (`time` in seconds) every
/// bone in the file's order. Numbers are printed as the rig's CSV prints them (Rust's shortest
/// form that reads back to the same bits), a bone's name quoted as RFC 4180 asks when it holds a
/// comma, a quote or a line break.
pub fn write_csv(w: &mut dyn Write, poses: &[(f64, PoseReport)]) -> std::io::Result<()> {
    writeln!(w, "{CSV_HEADER}")?;
    for (k, (time, report)) in poses.iter().enumerate() {
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
    }
    Ok(())
}

/// The motion's frames as CSV bytes ([`write_csv`]).
pub fn csv(motion: &Motion<'_>) -> Result<Vec<u8>, String> {
    let mut bytes = Vec::new();
    write_csv(&mut bytes, &motion.poses()?).map_err(|e| format!("cannot write CSV: {e}"))?;
    Ok(bytes)
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
}
