//! Playing a clip with physics as a game does: the skeleton's clock starts at 0, the physics
//! restarts there, and every frame the clock and the clip advance by `1 / fps` and the
//! character is posed with its physics constraints stepping (Spine's `Physics.reset` at 0,
//! then `update(dt)`, apply, `updateWorldTransform(Physics.update)`), up to the time asked.

use super::pose::Frame;
use super::{
    Character, CharacterError, PhysicsMode, PhysicsWorld, PoseError, PoseRequest, Posed, Together, TogetherError,
    TogetherReport,
};
use crate::{Interrupt, Solver};

/// How a clip is played with physics.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Play {
    /// The game's frames a second (default 60): how often the clock advances and the clip and
    /// the physics are applied (each physics constraint steps at its own `fps` within).
    pub fps: f64,
    /// The skeleton's wind, gravity and reference scale (the default's is 100: a character's
    /// own is [`Character::physics_world`]).
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
        self.play_until(request, play, out, None)
    }

    /// [`Character::play`], stopped with [`PoseError::Interrupted`] once `interrupt` is set
    /// (checked in every frame's pose).
    pub fn play_watched(
        &self,
        request: &PoseRequest,
        play: &Play,
        out: &mut Posed,
        interrupt: &Interrupt,
    ) -> Result<(), PoseError> {
        self.play_until(request, play, out, Some(interrupt))
    }

    fn play_until(
        &self,
        request: &PoseRequest,
        play: &Play,
        out: &mut Posed,
        interrupt: Option<&Interrupt>,
    ) -> Result<(), PoseError> {
        if !(play.fps.is_finite() && play.fps > 0.0) {
            return Err(PoseError::Fps(play.fps));
        }
        let Some((clip, end)) = request.clip else {
            let frame = Frame::Play { mode: PhysicsMode::Reset, clock: 0.0, from: 0.0, world: play.world };
            return self.pose_frame(request, out, interrupt, (frame, &[]));
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
        self.pose_frame(&at(0.0), out, interrupt, (start, &[]))?;
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
            self.pose_frame(&at(clock), out, interrupt, (frame, &[]))?;
        }
        Ok(())
    }
}

/// One frame of a game's loop with physics ([`Character::play_frame`]): the skeleton's clock
/// now and at the frame before (`None`: the first frame, where the physics restarts).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlayFrame {
    /// The skeleton's clock now, seconds (it only grows in a game; the clip's time is the
    /// request's, which a looping game wraps).
    pub clock: f64,
    /// The clock at the frame before, or `None` for the first frame (physics restarts).
    pub before: Option<f64>,
    /// The skeleton's wind, gravity and reference scale.
    pub world: PhysicsWorld,
}

impl Character {
    /// Poses one frame of a game's loop as Spine's runtime does it with physics: the clip at
    /// the request's time, then every constraint, the physics constraints stepping from the
    /// state `out` kept from the frame before up to `frame.clock` (restarting on the first
    /// frame, or where a clip's `reset` key lies between the two clip times). What a game
    /// calls every frame; [`Character::play`] is these frames from 0.
    pub fn play_frame(&self, request: &PoseRequest, frame: &PlayFrame, out: &mut Posed) -> Result<(), PoseError> {
        self.pose_frame(request, out, None, (frame.of(request)?, &[]))
    }

    /// [`Character::play_frame`], stopped with [`PoseError::Interrupted`] once `interrupt` is
    /// set (checked before each constraint, as [`Character::pose_watched`] does).
    pub fn play_frame_watched(
        &self,
        request: &PoseRequest,
        frame: &PlayFrame,
        out: &mut Posed,
        interrupt: &Interrupt,
    ) -> Result<(), PoseError> {
        self.pose_frame(request, out, Some(interrupt), (frame.of(request)?, &[]))
    }
}

impl Character {
    /// [`Character::pose_together`] as one frame of a game's loop with physics, as
    /// [`Character::play_frame`] poses one: the physics constraints step (or restart on the
    /// first frame) in every pose the solve makes, each round from the state `out` kept from
    /// the frame before, so the goals are met on the pose the constraints produce, physics
    /// included, at this frame; `out` keeps the last round's state for the next frame.
    pub fn pose_together_frame(
        &self,
        request: &PoseRequest,
        rules: &Together,
        solver: &mut Solver,
        frame: &PlayFrame,
        out: &mut Posed,
    ) -> Result<TogetherReport, TogetherError> {
        let frame = frame.of(request)?;
        self.together(request, (rules, solver), out, frame)
    }
}

impl PlayFrame {
    /// The pose's physics frame for `request` at this game frame: a restart on the first
    /// frame, else a step from the frame before, the clip's time before being the request's
    /// less the clock's advance. A clock that is not finite or goes back is refused.
    pub(crate) fn of(&self, request: &PoseRequest) -> Result<Frame, PoseError> {
        if !self.clock.is_finite() || self.before.is_some_and(|b| !(b.is_finite() && b <= self.clock)) {
            return Err(PoseError::Time(self.clock));
        }
        let (mode, from) = match self.before {
            None => (PhysicsMode::Reset, self.clock),
            Some(before) => (PhysicsMode::Update, before),
        };
        let from = request.clip.map_or(from, |(_, t)| t - (self.clock - from));
        Ok(Frame::Play { mode, clock: self.clock, from, world: self.world })
    }
}

impl Character {
    /// The skeleton's reference scale for physics (Spine's `referenceScale` in the skeleton
    /// object, default 100): the distance physics forces are given in ("baseline scale factor
    /// for applying physics and other effects based on distance to non-scalable properties,
    /// such as angle or scale", the runtime API reference).
    pub fn reference_scale(&self) -> f64 {
        self.reference_scale
    }

    /// The character with the skeleton's reference scale `r`; refused unless positive and
    /// finite.
    pub fn with_reference_scale(mut self, r: f64) -> Result<Self, CharacterError> {
        if !(r.is_finite() && r > 0.0) {
            return Err(CharacterError::ReferenceScale { value: r });
        }
        self.reference_scale = r;
        Ok(self)
    }

    /// The physics world a game plays this character in: the default wind and gravity
    /// directions and the character's own [`Character::reference_scale`] (what [`Play::world`]
    /// and [`PlayFrame::world`] should be for a file whose `referenceScale` is not 100).
    pub fn physics_world(&self) -> PhysicsWorld {
        PhysicsWorld { reference_scale: self.reference_scale, ..PhysicsWorld::default() }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::character::{
        BoneKey, BoneProperty, BoneTimeline, CharacterBone, CharacterParts, Clip, Constraint, Inherit, Interpolation,
        LocalTransform, PhysicsConstraint, PhysicsGlobal, PhysicsSettings, PhysicsShares,
    };

    /// A root that slides 100 units along x in 1 s and a child the physics constraint moves.
    fn slider(physics: bool) -> Character {
        let bone = |name: &str, parent| CharacterBone {
            name: name.into(),
            parent,
            length: 10.0,
            setup: LocalTransform::default(),
            inherit: Inherit::Normal,
        };
        let key = |time, x| BoneKey { time, values: [x, 0.0], curves: [Interpolation::Linear; 2] };
        let clip = Clip {
            name: "slide".into(),
            duration: 1.0,
            bones: vec![BoneTimeline {
                bone: 0,
                property: BoneProperty::Translate,
                keys: vec![key(0.0, 0.0), key(1.0, 100.0)],
            }],
            constraints: vec![],
        };
        let constraints = if physics {
            vec![Constraint::Physics(PhysicsConstraint {
                name: "p".into(),
                order: 0,
                skin: false,
                bone: 1,
                shares: PhysicsShares { x: 1.0, y: 1.0, ..PhysicsShares::default() },
                limit: 5000.0,
                fps: 60.0,
                setup: PhysicsSettings { inertia: 0.5, damping: 0.9, ..PhysicsSettings::default() },
                global: PhysicsGlobal::default(),
            })]
        } else {
            vec![]
        };
        let parts = CharacterParts {
            bones: vec![bone("root", None), bone("tail", Some(0))],
            constraints,
            clips: vec![clip],
            ..CharacterParts::default()
        };
        Character::new(parts).unwrap()
    }

    fn request(time: f64) -> PoseRequest<'static> {
        PoseRequest { clip: Some((0, time)), ..PoseRequest::default() }
    }

    #[test]
    fn a_played_tail_lags_behind_its_posed_place_and_pose_leaves_it() {
        let c = slider(true);
        let (mut posed, mut played) = (Posed::default(), Posed::default());
        c.pose(&request(0.5), &mut posed).unwrap();
        assert_eq!(posed.origin(1), [50.0, 0.0]);
        c.play(&request(0.5), &Play::default(), &mut played).unwrap();
        let lag = posed.origin(1)[0] - played.origin(1)[0];
        assert!(lag > 0.1 && lag < 50.0, "{lag}");
        // The root is where the clip has it at the play's clock (30 sixtieths added up).
        assert!((played.origin(0)[0] - 50.0).abs() < 1e-9, "{:?}", played.origin(0));
    }

    #[test]
    fn a_games_frames_one_by_one_are_the_play_to_the_bit() {
        let c = slider(true);
        let (mut played, mut framed) = (Posed::default(), Posed::default());
        c.play(&request(0.5), &Play::default(), &mut played).unwrap();
        let mut before = None;
        let mut clock = 0.0;
        for f in 0..=30 {
            if f > 0 {
                clock += 1.0 / 60.0;
            }
            let frame = PlayFrame { clock, before, world: PhysicsWorld::default() };
            c.play_frame(&request(clock), &frame, &mut framed).unwrap();
            before = Some(clock);
        }
        assert_eq!(played.origin(1).map(f64::to_bits), framed.origin(1).map(f64::to_bits));
        assert_eq!(played.matrix(1).map(f64::to_bits), framed.matrix(1).map(f64::to_bits));
        // A clock that goes back, or is not finite, is refused.
        let back = PlayFrame { clock: 0.1, before: Some(0.2), world: PhysicsWorld::default() };
        assert_eq!(c.play_frame(&request(0.1), &back, &mut framed), Err(PoseError::Time(0.1)));
    }

    #[test]
    fn a_solve_together_as_a_games_frames_steps_the_physics_as_play_frame_does() {
        let c = slider(true);
        let (mut framed, mut together) = (Posed::default(), Posed::default());
        let mut solver = Solver::new(crate::SolveOptions::default()).unwrap();
        let mut before = None;
        for f in 0..=10 {
            let clock = f as f64 / 60.0;
            let frame = PlayFrame { clock, before, world: PhysicsWorld::default() };
            c.play_frame(&request(clock), &frame, &mut framed).unwrap();
            c.pose_together_frame(&request(clock), &Together::default(), &mut solver, &frame, &mut together).unwrap();
            assert_eq!(framed.origin(1).map(f64::to_bits), together.origin(1).map(f64::to_bits), "frame {f}");
            before = Some(clock);
        }
        // The tail lags: the physics stepped.
        let mut posed = Posed::default();
        c.pose(&request(10.0 / 60.0), &mut posed).unwrap();
        assert!((posed.origin(1)[0] - together.origin(1)[0]).abs() > 0.1);
        // A frame whose interrupt is set stops.
        let stop = Interrupt::new();
        stop.interrupt();
        let frame = PlayFrame { clock: 0.0, before: None, world: PhysicsWorld::default() };
        assert_eq!(c.play_frame_watched(&request(0.0), &frame, &mut framed, &stop), Err(PoseError::Interrupted));
    }

    #[test]
    fn without_physics_a_play_is_the_pose() {
        let c = slider(false);
        let (mut posed, mut played) = (Posed::default(), Posed::default());
        for t in [0.0, 0.25, 0.2333, 1.0] {
            c.pose(&request(t), &mut posed).unwrap();
            c.play(&request(t), &Play::default(), &mut played).unwrap();
            // The same but for the clock's sum of frame times.
            assert!((posed.origin(1)[0] - played.origin(1)[0]).abs() < 1e-9, "{t}");
        }
    }

    #[test]
    fn a_time_off_the_frames_ends_with_a_shorter_frame_and_the_same_play_the_same_bits() {
        let c = slider(true);
        let (mut a, mut b) = (Posed::default(), Posed::default());
        c.play(&request(0.2333), &Play::default(), &mut a).unwrap();
        c.play(&request(0.2333), &Play::default(), &mut b).unwrap();
        // The root is where the clip has it at 0.2333 s, not at the 14th frame (0.2333…).
        assert!((a.origin(0)[0] - 23.33).abs() < 1e-4, "{:?}", a.origin(0));
        assert_eq!(a.origin(1).map(f64::to_bits), b.origin(1).map(f64::to_bits));
    }

    #[test]
    fn bad_plays_are_refused() {
        let c = slider(true);
        let mut p = Posed::default();
        assert_eq!(c.play(&request(1.0), &Play { fps: 0.0, ..Play::default() }, &mut p), Err(PoseError::Fps(0.0)));
        assert_eq!(c.play(&request(1e9), &Play::default(), &mut p), Err(PoseError::TooLong { time: 1e9, fps: 60.0 }));
        assert_eq!(c.play(&request(-1.0), &Play::default(), &mut p), Err(PoseError::Time(-1.0)));
    }
}
