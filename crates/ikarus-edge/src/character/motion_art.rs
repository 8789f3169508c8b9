//! A character's motion ([`super::motion`]) drawn with its art, for `ikarus animate|track --rig
//! FILE.json --atlas FILE.atlas --out x.gif|png|svg` (and `POST /api/render`'s figure `motion`
//! with an atlas): every frame posed as the motion poses it, and its art drawn as `ikarus pose
//! --atlas` draws a pose's ([`AtlasArt::art`]): the motion's skin, the slot keys (attachment,
//! colour, draw order, deform) of the clip under a keyed course at the frame's clip time (with
//! physics played, the game's clock, as the bones are posed), one [`DrawList`] reused and the
//! atlas's decoded pages borrowed by every frame.

use ikarus::character::{DrawList, Posed};
use ikarus_render::{Art, ArtPlacement, CharacterArtMotion, CharacterMotionFigure};

use super::art_draw::AtlasArt;
use super::motion::Motion;
use crate::error::Error;
use crate::picture::Drawing;
use crate::pose::{PoseReport, skin_index};

/// Most art vertices a picture of a character's motion holds, over every frame: each frame's
/// art is kept until the picture is drawn (the GIF draws every frame, the one picture fits
/// them all). Four million is some 100 MB held, some 6,000 frames of spineboy.
pub const MAX_DRAWN_VERTICES: usize = 4_000_000;

/// One frame of a motion, posed ([`Motion::each_posed`]).
pub struct PosedFrame<'a> {
    /// Its index.
    pub index: usize,
    /// Its time, seconds.
    pub time: f64,
    /// Its pose.
    pub posed: &'a Posed,
    /// The clip whose slot keys draw it and the clip's time then: the clip under a keyed
    /// course at the game's clock with physics played, else at the frame's time, looped as the
    /// bones' clip is; `None` without one.
    pub clip: Option<(usize, f64)>,
}

impl Motion<'_> {
    /// Every frame posed in order into one `Posed`, handed to `sink`. Stops at the first frame
    /// that cannot be posed, or at `sink`'s first error.
    pub fn each_posed(&self, sink: &mut dyn FnMut(&PosedFrame) -> Result<(), Error>) -> Result<(), Error> {
        let c = &self.loaded.character;
        let clip = self.clip().and_then(|name| c.clip_index(name));
        let mut posed = Posed::default();
        let mut clock = None;
        for k in 0..self.frame_count() {
            let time = self.frame_time(k);
            self.frame_into(k, &mut clock, &mut posed)?;
            // The clip's time as the frame's bones were posed at it (`ask_at`, `pose_played`).
            let at = clock.unwrap_or(time);
            sink(&PosedFrame { index: k, time, posed: &posed, clip: clip.map(|i| (i, self.clip_time(at))) })?;
        }
        Ok(())
    }
}

/// Every frame of a motion with its art: its time and report (the bones), and its art.
pub struct MotionArt<'p> {
    /// Each frame's time and pose, as [`Motion::poses`] gives them.
    pub poses: Vec<(f64, PoseReport)>,
    /// Each frame's art.
    pub arts: Vec<Art<'p>>,
}

/// Why a motion's art could not be drawn, each a one-line message without a label.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum MotionArtError {
    /// The character's: a frame that cannot be posed, a skin the file does not have.
    Pose(Error),
    /// The atlas's: a region the motion draws that it lacks (naming the region and its slot).
    Art(Error),
    /// The picture's: more art vertices over the frames than [`MAX_DRAWN_VERTICES`].
    Cap(String),
}

/// Every frame of `motion` posed and drawn with `atlas`'s art (see the module's rules).
///
/// # Errors
/// [`MotionArtError`], one line: a frame that cannot be posed or a skin the file does not have
/// (`skin "x": no such skin …`), a region the atlas lacks, the vertex cap.
pub fn posed_with_art<'p>(motion: &Motion<'_>, atlas: &'p AtlasArt) -> Result<MotionArt<'p>, MotionArtError> {
    let c = &motion.loaded.character;
    let skin = skin_index(c, motion.skin.as_deref()).map_err(MotionArtError::Pose)?;
    let mut list = DrawList::default();
    let (mut poses, mut arts) = (Vec::new(), Vec::new());
    let mut vertices = 0usize;
    let mut failed = None;
    let posed = motion.each_posed(&mut |frame| {
        let art = match atlas.art(c, frame.posed, (skin, frame.clip), &mut list) {
            Ok(art) => art,
            Err(m) => {
                failed = Some(MotionArtError::Art(m));
                return Err(Error::input(""));
            }
        };
        vertices = vertices.saturating_add(art.pieces.iter().map(|p| p.positions.len()).sum());
        if vertices > MAX_DRAWN_VERTICES {
            failed = Some(MotionArtError::Cap(format!(
                "the art of the first {} frames has more than the cap of {MAX_DRAWN_VERTICES} vertices to draw",
                frame.index + 1
            )));
            return Err(Error::input(""));
        }
        poses.push((frame.time, PoseReport::of(c, frame.posed)));
        arts.push(art);
        Ok(())
    });
    match (posed, failed) {
        (_, Some(e)) => Err(e),
        (Err(m), None) => Err(MotionArtError::Pose(m)),
        (Ok(()), None) => Ok(MotionArt { poses, arts }),
    }
}

/// The motion's picture with its art: every frame's bones (`drawn.poses`) and art
/// (`drawn.arts`, moved in), `placement` under the bones or alone, captioned with
/// [`Motion::caption`], drawn at the motion's fps.
#[must_use]
pub fn art_drawing<'a>(
    motion: &Motion<'_>,
    poses: &'a [(f64, PoseReport)],
    arts: Vec<Art<'a>>,
    placement: ArtPlacement,
) -> Drawing<'a> {
    let figure = CharacterArtMotion {
        motion: CharacterMotionFigure {
            frames: poses.iter().map(|(_, r)| r.figure(None)).collect(),
            times: poses.iter().map(|(t, _)| *t).collect(),
            caption: Some(motion.caption()),
        },
        arts,
        placement,
    };
    Drawing::CharacterArtMotion { figure, fps: motion.fps }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::character::motion::{Physics, keyed};
    use crate::keys::KeysFile;

    /// Celestial circus's root held still for 1.2 s over its clip `stars` (0.7333 s, whose
    /// slots show star attachments from 0.0667 s on): the frames' art is each frame's pose drawn
    /// with the clip's slot keys at the clip's time, looped past its end as the bones' clip is.
    #[test]
    fn each_frame_draws_the_slot_keys_at_its_looped_clip_time() {
        let text = include_str!("../../../../examples/characters/spine-celestial-circus-pro.json");
        let loaded = crate::character::load(text, "circus").unwrap();
        let c = &loaded.character;
        let keys = KeysFile::parse(
            r#"{"fps": 10, "tracks": {"root": [{"time": 0, "x": 0, "y": 0}, {"time": 1.2, "x": 0, "y": 0}]}}"#,
        )
        .unwrap();
        let (course, fps) = keyed(&loaded, &keys, Some("stars".into()), 100, "cap").unwrap();
        let mut motion = Motion::new(&loaded, course, fps).unwrap();
        motion.physics = Physics::Off;
        let atlas = AtlasArt::read_file(
            &std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/characters/celestial-circus.atlas"),
        )
        .unwrap();
        let drawn = posed_with_art(&motion, &atlas).unwrap();
        assert_eq!(drawn.arts.len(), 13);
        let stars = c.clip_index("stars").unwrap();
        let length = c.clips()[stars].duration;
        assert!(length > 0.7 && length < 1.0, "{length}");
        let mut posed = Posed::default();
        let mut list = DrawList::default();
        for (k, art) in drawn.arts.iter().enumerate() {
            let time = motion.frame_time(k);
            let clip_time = if time > length { time % length } else { time };
            motion.pose_at(time, &mut posed).unwrap();
            let expected = atlas.art(c, &posed, (c.default_skin(), Some((stars, clip_time))), &mut list).unwrap();
            assert_eq!(art, &expected, "frame {k} at {time} s");
        }
        // The keys matter: at 0 s no star shows, at 0.2 s the first three do; near the clip's
        // end (0.7 s) fewer show than after it, where the clip starts again.
        let count = |k: usize| drawn.arts[k].pieces.len();
        assert!(count(2) > count(0), "{} {}", count(2), count(0));
        for k in 8..13 {
            assert!(count(k) > count(7), "frame {k}: {} pieces, {} at 0.7 s", count(k), count(7));
        }
    }
}
