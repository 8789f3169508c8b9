//! A character's motion ([`super::motion`]) played with physics as a game plays it: the
//! motion's frames are consecutive frames of a game's loop, the skeleton's clock at 0 on the
//! first (where the physics restarts, Spine's `Physics.reset`) and advanced by `1 / fps` a
//! frame after it (added up in `f64`, as [`ikarus::character::Character::play`] adds its
//! frame times), the last frame at the motion's end when that is not a whole number of frames.
//! Each frame is posed once with the physics constraints stepping from the frame before
//! ([`ikarus::character::Character::play_frame`]): a motion of n frames is n poses, not the
//! n²/2 of playing every frame from 0. The clip under a keyed course is posed at the clock
//! (looping as the motion loops it), the keys at the frame's time.
//!
//! So frame k of a motion whose frame rate is the pose's `--fps`, starting at 0, is
//! `ikarus pose --animation A --time k/fps` with the same targets, to the bit (while the
//! clock's sum stays within 1e-9 of k/fps, some 20,000 frames at 60 fps: past it a pose at a
//! time adds a last tiny frame that a motion's frame does not).
//!
//! Between frames ([`Motion::play_at`], the bake's checks), the motion at a time is its frame
//! at or before the time and one shorter frame to it, as a pose at a time ends.

use ikarus::character::{PlayFrame, Posed};

use super::motion::{Motion, Physics, Playhead};
use crate::error::Error;
use crate::pose::pose_frame_into;

impl Motion<'_> {
    /// Whether the frames play the character's physics constraints: [`Physics::Played`] and
    /// the character has some.
    #[must_use]
    pub fn plays_physics(&self) -> bool {
        self.physics == Physics::Played && self.loaded.character.constraints().iter().any(|k| k.kind() == "physics")
    }

    /// The clock at frame `k` (> 0) after the clock `before` of frame `k − 1`: one frame time
    /// more, or for a last frame that is not a whole number of frames, the motion's end.
    fn clock_after(&self, k: usize, before: f64) -> f64 {
        let whole = (self.duration * self.fps - (self.duration * self.fps).round()).abs() < 1e-9;
        if k + 1 < self.frame_count() || whole { before + 1.0 / self.fps } else { self.duration }
    }

    /// Frame `k` posed into `out` as the game's frame after the one `out` holds (at clock
    /// `before`), or as the first (`None`: the physics restarts, the clock at 0): its clock.
    pub(crate) fn step(&self, k: usize, before: Option<f64>, out: &mut Posed) -> Result<f64, Error> {
        let clock = before.map_or(0.0, |b| self.clock_after(k, b));
        self.pose_played(
            self.frame_time(k),
            &PlayFrame { clock, before, world: self.loaded.character.physics_world() },
            out,
        )?;
        Ok(clock)
    }

    /// The motion's pose at `time` (its targets, bends and turns) as the game's `frame`: the
    /// clip under the keys at the frame's clock.
    fn pose_played(&self, time: f64, frame: &PlayFrame, out: &mut Posed) -> Result<(), Error> {
        if self.interrupt.as_ref().is_some_and(ikarus::Interrupt::is_interrupted) {
            return Err(Error::input("interrupted"));
        }
        let mut ask = self.ask_at(time);
        if ask.animation.is_some() {
            ask.time = Some(self.clip_time(frame.clock));
        }
        pose_frame_into(self.loaded, &ask, out, (self.interrupt.as_ref(), frame)).map(|_| ())
    }

    /// The index of the last frame at or before `time` (within the motion).
    fn frame_at_or_before(&self, time: f64) -> usize {
        let last = self.frame_count().saturating_sub(1);
        let mut k = ((time * self.fps).floor().max(0.0) as usize).min(last);
        // The floor of the product can be one off the frames' own times (k / fps).
        if k > 0 && self.frame_time(k) > time {
            k -= 1;
        }
        if k < last && self.frame_time(k + 1) <= time {
            k += 1;
        }
        k
    }

    /// The motion at `time` (clamped into it) as a game shows it: with [`Motion::plays_physics`],
    /// the frames played up to the last one at or before `time` and, between frames, one
    /// shorter frame to `time` (as `ikarus pose --time` ends); otherwise
    /// [`Motion::pose_at`]. `head` keeps the game between calls: times asked in increasing
    /// order (or between the last two frames played) cost one pose a frame; an earlier time
    /// plays again from 0.
    pub fn play_at<'h>(&self, time: f64, head: &'h mut Playhead) -> Result<&'h Posed, Error> {
        let time = time.clamp(0.0, self.duration);
        if !self.plays_physics() {
            self.pose_at(time, &mut head.between)?;
            return Ok(&head.between);
        }
        let k = self.frame_at_or_before(time);
        let from_previous = head.previous.is_some_and(|(f, _)| f == k) && head.last.is_some_and(|(f, _)| f == k + 1);
        let clock = if from_previous {
            head.previous.map_or(0.0, |(_, c)| c)
        } else {
            if head.last.is_none_or(|(f, _)| f > k) {
                head.previous = None;
                head.last = Some((0, self.step(0, None, &mut head.last_posed)?));
            }
            while let Some((f, clock)) = head.last.filter(|(f, _)| *f < k) {
                head.previous_posed.clone_from(&head.last_posed);
                head.previous = head.last;
                head.last = Some((f + 1, self.step(f + 1, Some(clock), &mut head.last_posed)?));
            }
            head.last.map_or(0.0, |(_, c)| c)
        };
        let base = if from_previous { &head.previous_posed } else { &head.last_posed };
        let at = self.frame_time(k);
        if time == at {
            return Ok(base);
        }
        head.between.clone_from(base);
        let frame =
            PlayFrame { clock: clock + (time - at), before: Some(clock), world: self.loaded.character.physics_world() };
        self.pose_played(time, &frame, &mut head.between)?;
        Ok(&head.between)
    }
}
