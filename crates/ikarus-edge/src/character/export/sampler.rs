//! The motion posed at the times a fit asks for, each time posed once while it is remembered:
//! every timeline of an export reads the same times (the key times and the checks between
//! them), so posing once per time and not once per timeline keeps an export's poses about
//! (key times × checks) rather than (timelines × key times × checks).
//!
//! The editable form is fitted to the motion without physics ([`Motion::pose_at`]): under the
//! runtime's rules its physics constraints stay on, and play on top of the keys in a game as
//! they play on top of the motion's frames ([`Motion::play_at`]).

use std::collections::HashMap;
use std::rc::Rc;

use ikarus::character::{Affine, IkSettings, LocalTransform, Posed};

use crate::character::motion::Motion;
use crate::error::Error;
use crate::pose::pose_into;

/// How many bone poses (times × bones) are remembered at most; past it the memory is cleared
/// (posing again what is asked again).
const MAX_REMEMBERED: usize = 1 << 20;

/// The motion at one time.
pub(super) struct Snapshot {
    /// Every bone's local transform as the pose left it.
    pub local: Vec<LocalTransform>,
    /// Every bone's world transform.
    pub world: Vec<Affine>,
    /// Every IK constraint's settings as the clip and the bend keys left them (by constraint
    /// index; the default for a constraint of another kind).
    pub settings: Vec<IkSettings>,
}

/// Poses of a motion by time.
pub(super) struct Sampler<'m, 'a> {
    motion: &'m Motion<'a>,
    posed: Posed,
    remembered: HashMap<u64, Rc<Snapshot>>,
    gains: HashMap<u64, f64>,
    moved: Posed,
    /// How many times were posed (for the tests' counts).
    pub posed_count: usize,
}

impl<'m, 'a> Sampler<'m, 'a> {
    pub(super) fn new(motion: &'m Motion<'a>) -> Self {
        Sampler {
            motion,
            posed: Posed::default(),
            remembered: HashMap::new(),
            gains: HashMap::new(),
            moved: Posed::default(),
            posed_count: 0,
        }
    }

    /// How far any bone's origin or tip moves, per unit, when the motion's targets are all
    /// moved by `step` (along x, then y; the larger) at `time`: what an error of a target's key
    /// costs once the IK constraints have carried it (about 1, more near a limb's full reach).
    /// All targets at once (two poses a time, whatever their number): a bone moved by two
    /// targets counts both, which errs on the close side.
    pub(super) fn gain(&mut self, time: f64, step: f64) -> Result<f64, Error> {
        if let Some(g) = self.gains.get(&time.to_bits()) {
            return Ok(*g);
        }
        let base = self.at(time)?;
        let mut gain: f64 = 1.0;
        for d in [[step, 0.0], [0.0, step]] {
            let mut ask = self.motion.ask_at(time);
            for (_, p) in &mut ask.targets {
                p[0] += d[0];
                p[1] += d[1];
            }
            pose_into(self.motion.loaded, &ask, &mut self.moved)?;
            self.posed_count += 1;
            let m = &self.moved;
            let bones = self.motion.loaded.character.bones();
            for (i, bone) in bones.iter().enumerate().take(m.len()) {
                let w = &base.world[i];
                let (o, t) = (m.origin(i), m.tip(i));
                let l = bone.length;
                gain = gain.max((o[0] - w.x).hypot(o[1] - w.y) / step);
                gain = gain.max((t[0] - (w.x + w.a * l)).hypot(t[1] - (w.y + w.c * l)) / step);
            }
        }
        if self.gains.len() > MAX_REMEMBERED {
            self.gains.clear();
        }
        self.gains.insert(time.to_bits(), gain);
        Ok(gain)
    }

    /// The motion at `time`.
    pub(super) fn at(&mut self, time: f64) -> Result<Rc<Snapshot>, Error> {
        if let Some(s) = self.remembered.get(&time.to_bits()) {
            return Ok(Rc::clone(s));
        }
        self.motion.pose_at(time, &mut self.posed)?;
        self.posed_count += 1;
        let p = &self.posed;
        let bones = p.len();
        let constraints = self.motion.loaded.character.constraints().len();
        let s = Rc::new(Snapshot {
            local: (0..bones).map(|i| p.local(i)).collect(),
            world: (0..bones).map(|i| p.world(i)).collect(),
            settings: (0..constraints).map(|k| p.ik_settings(k).unwrap_or_default()).collect(),
        });
        if (self.remembered.len() + 1) * bones.max(1) > MAX_REMEMBERED {
            self.remembered.clear();
        }
        self.remembered.insert(time.to_bits(), Rc::clone(&s));
        Ok(s)
    }
}
