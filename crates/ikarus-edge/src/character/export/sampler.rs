//! The motion posed at the times a fit asks for, each time posed once while it is remembered:
//! every timeline of an export reads the same times (the key times and the checks between
//! them), so posing once per time and not once per timeline keeps an export's poses about
//! (key times × checks) rather than (timelines × key times × checks).

use std::collections::HashMap;
use std::rc::Rc;

use ikarus::character::{Affine, IkSettings, LocalTransform, Posed};

use crate::character::motion::Motion;

/// How many bone poses (times × bones) are remembered at most; past it the memory is cleared
/// (posing again what is asked again).
const MAX_REMEMBERED: usize = 1 << 20;

/// The motion at one time.
pub(super) struct Snapshot {
    /// Every bone's local transform as the pose left it.
    pub local: Vec<LocalTransform>,
    /// Every bone's world transform.
    pub world: Vec<Affine>,
    /// Every constraint's settings as the clip and the bend keys left them.
    pub settings: Vec<IkSettings>,
}

/// Poses of a motion by time.
pub(super) struct Sampler<'m, 'a> {
    motion: &'m Motion<'a>,
    posed: Posed,
    remembered: HashMap<u64, Rc<Snapshot>>,
    /// How many times were posed (for the tests' counts).
    pub posed_count: usize,
}

impl<'m, 'a> Sampler<'m, 'a> {
    pub(super) fn new(motion: &'m Motion<'a>) -> Self {
        Sampler { motion, posed: Posed::default(), remembered: HashMap::new(), posed_count: 0 }
    }

    /// The motion at `time`.
    pub(super) fn at(&mut self, time: f64) -> Result<Rc<Snapshot>, String> {
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
            settings: (0..constraints).map(|k| p.settings(k)).collect(),
        });
        if (self.remembered.len() + 1) * bones.max(1) > MAX_REMEMBERED {
            self.remembered.clear();
        }
        self.remembered.insert(time.to_bits(), Rc::clone(&s));
        Ok(s)
    }
}
