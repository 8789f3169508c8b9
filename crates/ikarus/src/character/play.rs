//! Playing a clip with physics as a game does: the skeleton's clock starts at 0, the physics
//! restarts there, and every frame the clock and the clip advance by `1 / fps` and the
//! character is posed with its physics constraints stepping (Spine's `Physics.reset` at 0,
//! then `update(dt)`, apply, `updateWorldTransform(Physics.update)`), up to the time asked.

use super::pose::Frame;
use super::{Character, PhysicsMode, PhysicsWorld, PoseError, PoseRequest, Posed};

/// How a clip is played with physics.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Play {
    /// The game's frames a second (default 60): how often the clock advances and the clip and
    /// the physics are applied (each physics constraint steps at its own `fps` within).
    pub fps: f64,
    /// The skeleton's wind, gravity and reference scale.
    pub world: PhysicsWorld,
}

impl Default for Play {
    fn default() -> Self {
        Play { fps: 60.0, world: PhysicsWorld::default() }
    }
}

/// The most frames one play takes (an hour at 60 frames a second): a longer play is refused.
pub const MAX_FRAMES: u64 = 216_000;

impl Character {
    /// Poses the character as a game shows it at the request's clip time `T` after playing the
    /// clip from 0: frame 0 at clock 0 restarts the physics; each next frame adds `1 / fps` to
    /// the clock (in `f64`, as the runtime adds its frame times) and poses the clip at the
    /// clock with the physics stepping; a last, shorter frame reaches `T` when it is not a
    /// whole number of frames (within 1e-9 of one counts as one). Without a clip, the setup
    /// pose is played for no time (the physics restarts and nothing moves). Targets, bends and
    /// turns apply at every frame. Same request, same bits.
    pub fn play(&self, request: &PoseRequest, play: &Play, out: &mut Posed) -> Result<(), PoseError> {
        if !(play.fps.is_finite() && play.fps > 0.0) {
            return Err(PoseError::Fps(play.fps));
        }
        let Some((clip, end)) = request.clip else {
            let frame = Frame::Play { mode: PhysicsMode::Reset, clock: 0.0, from: 0.0, world: play.world };
            return self.pose_frame(request, out, None, (frame, &[]));
        };
        if !(end.is_finite() && end >= 0.0) {
            return Err(PoseError::Time(end));
        }
        let exact = (end * play.fps).round();
        let whole = if (end * play.fps - exact).abs() < 1e-9 { exact } else { (end * play.fps).floor() };
        if whole > MAX_FRAMES as f64 {
            return Err(PoseError::TooLong { time: end, fps: play.fps });
        }
        let frames = whole as u64;
        let dt = 1.0 / play.fps;
        let at = |clock: f64| PoseRequest { clip: Some((clip, clock)), ..*request };
        let start = Frame::Play { mode: PhysicsMode::Reset, clock: 0.0, from: 0.0, world: play.world };
        self.pose_frame(&at(0.0), out, None, (start, &[]))?;
        let mut clock = 0.0;
        for f in 0..=frames {
            let from = clock;
            if f < frames {
                clock += dt;
            } else if whole != exact || end - clock > 1e-9 {
                clock = end;
            } else {
                break;
            }
            let frame = Frame::Play { mode: PhysicsMode::Update, clock, from, world: play.world };
            self.pose_frame(&at(clock), out, None, (frame, &[]))?;
        }
        Ok(())
    }
}
