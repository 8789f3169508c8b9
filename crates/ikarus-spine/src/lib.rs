//! The `ikarus-spine` add-on's WebAssembly core (issue 41): [`ikarus::character::SpineRig`]
//! over numbers that JavaScript writes and reads through `Float64Array` views of the module's
//! memory, so that no array crosses the boundary per frame (wasm-bindgen copies arrays, which
//! allocates).
//!
//! Once: `new SpineRig(parents, lengths, inherits, limits)`. Each frame, JavaScript writes
//! - at `framePtr`, [`FRAME_NUMBERS`] numbers per bone: world `a, b, c, d, worldX, worldY`, then
//!   local `x, y, rotation, scaleX, scaleY, shearX, shearY` (degrees), as Spine's `Bone` has them;
//! - at `goalsPtr`, [`GOAL_NUMBERS`] per goal: bone index, x, y, bones (how many bones up from it
//!   move, 1 = the bone alone), angle (degrees, the tip's world direction; NaN: none), weight
//!   (> 0), priority (0 primary, 1 secondary), bend (0 either, 1 positive = counter-clockwise,
//!   −1 negative);
//! - at `pinsPtr`, pinned bones' indices (as f64): their tips stay where the frame has them;
//!
//! then calls `apply(x, y, scaleX, scaleY, goals, pins)` (the skeleton's placement and the
//! counts, each at most `maxGoals`), which returns how many bones moved, and reads
//! - at `rotationsPtr`, every bone's local rotation, degrees (a bone that did not move: the
//!   frame's own number, bit for bit);
//! - at `movedPtr`, the moved bones' indices (as f64, ascending);
//! - at `errorsPtr`, per goal, its bone's tip's distance from its target after the solve.
//!
//! The pointers are byte offsets into the module's `memory`, 8-aligned and fixed for the rig's
//! life; a view must be made again when `memory.buffer` changes (the memory grew). After the
//! first frame with a given set of goals, pins and bones, `apply` does not allocate. A bad
//! input throws an `Error` whose `message` is one line naming the field and the value.

use ikarus::Goal;
use ikarus::character::{Inherit, Placement, SPINE_BONE_NUMBERS, SpineBone, SpineFrame, TipGoal};
use ikarus::solve::{Bend, Method, Priority, RigGoal, SolveOptions, Solver};
use wasm_bindgen::prelude::*;

/// Numbers per bone at `framePtr`.
pub const FRAME_NUMBERS: usize = SPINE_BONE_NUMBERS;

/// Numbers per goal at `goalsPtr`.
pub const GOAL_NUMBERS: usize = 8;

/// A Spine skeleton's bone tree attached once, solved each frame.
#[wasm_bindgen]
pub struct SpineRig {
    rig: ikarus::character::SpineRig,
    solver: Solver,
    /// Per bone, how many bones from it up to its root, itself included.
    chain: Vec<usize>,
    frame: Vec<f64>,
    goal_numbers: Vec<f64>,
    pin_numbers: Vec<f64>,
    rotations: Vec<f64>,
    moved: Vec<f64>,
    errors: Vec<f64>,
    goals: Vec<TipGoal>,
    pins: Vec<usize>,
    /// The message of the last refused [`SpineRig::apply_frame`].
    last_error: String,
}

#[wasm_bindgen]
impl SpineRig {
    /// Per bone: `parents[i]` (−1 for a root, else lower than `i`), `lengths[i]` (≥ 0),
    /// `inherits[i]` (0 normal, 1 onlyTranslation, 2 noRotationOrReflection, 3 noScale,
    /// 4 noScaleOrReflection: Spine's `Inherit` order) and `limits[2i], limits[2i+1]`, the range
    /// of its local rotation in degrees (NaN, NaN: none). Throws an `Error` on bad input.
    #[wasm_bindgen(constructor)]
    pub fn new(parents: &[i32], lengths: &[f64], inherits: &[u8], limits: &[f64]) -> Result<SpineRig, JsError> {
        Self::attach(parents, lengths, inherits, limits).map_err(|m| JsError::new(&m))
    }

    /// Solves the frame at `framePtr` for the first `goals` goals at `goalsPtr` and the first
    /// `pins` pins at `pinsPtr`, the skeleton placed at `(x, y)` scaled by `(scaleX, scaleY)`
    /// (Spine's `Skeleton.x, y, scaleX, scaleY`); returns how many bones moved. Throws an
    /// `Error` on bad input (then the outputs are not written).
    pub fn apply(
        &mut self,
        x: f64,
        y: f64,
        scale_x: f64,
        scale_y: f64,
        goals: f64,
        pins: f64,
    ) -> Result<usize, JsError> {
        let placement = Placement { position: [x, y], scale: [scale_x, scale_y] };
        self.solve(placement, goals, pins).map_err(|m| JsError::new(&m))
    }

    /// [`SpineRig::apply`] for every frame of a game: the same solve, answered as one plain
    /// number, so that the call allocates nothing on the JavaScript side (a `Result` comes back
    /// through wasm-bindgen as a fresh array): how many bones moved, or −1 when the input is
    /// refused, its one-line message then in [`SpineRig::last_error`].
    #[wasm_bindgen(js_name = applyFrame)]
    pub fn apply_frame(&mut self, x: f64, y: f64, scale_x: f64, scale_y: f64, goals: f64, pins: f64) -> f64 {
        let placement = Placement { position: [x, y], scale: [scale_x, scale_y] };
        match self.solve(placement, goals, pins) {
            Ok(moved) => moved as f64,
            Err(message) => {
                self.last_error = message;
                -1.0
            }
        }
    }

    /// The message of the last input [`SpineRig::apply_frame`] refused (empty before any).
    #[wasm_bindgen(getter, js_name = lastError)]
    pub fn last_error(&self) -> String {
        self.last_error.clone()
    }

    /// Byte offset of the frame's numbers ([`FRAME_NUMBERS`] per bone).
    #[wasm_bindgen(getter, js_name = framePtr)]
    pub fn frame_ptr(&self) -> usize {
        self.frame.as_ptr() as usize
    }

    /// Byte offset of the goals ([`GOAL_NUMBERS`] per goal, room for `maxGoals`).
    #[wasm_bindgen(getter, js_name = goalsPtr)]
    pub fn goals_ptr(&self) -> usize {
        self.goal_numbers.as_ptr() as usize
    }

    /// Byte offset of the pins (one bone index per pin, room for `maxGoals`).
    #[wasm_bindgen(getter, js_name = pinsPtr)]
    pub fn pins_ptr(&self) -> usize {
        self.pin_numbers.as_ptr() as usize
    }

    /// How many goals (and how many pins) a frame can have: the bone count.
    #[wasm_bindgen(getter, js_name = maxGoals)]
    pub fn max_goals(&self) -> usize {
        self.rotations.len()
    }

    /// Byte offset of every bone's local rotation after `apply`, degrees.
    #[wasm_bindgen(getter, js_name = rotationsPtr)]
    pub fn rotations_ptr(&self) -> usize {
        self.rotations.as_ptr() as usize
    }

    /// Byte offset of the moved bones' indices after `apply` (as f64, ascending; as many as it
    /// returned).
    #[wasm_bindgen(getter, js_name = movedPtr)]
    pub fn moved_ptr(&self) -> usize {
        self.moved.as_ptr() as usize
    }

    /// Byte offset of each goal's error after `apply`, in the goals' order.
    #[wasm_bindgen(getter, js_name = errorsPtr)]
    pub fn errors_ptr(&self) -> usize {
        self.errors.as_ptr() as usize
    }
}

impl SpineRig {
    /// [`SpineRig::new`] with its error as a string (natively, where `JsError` cannot be made).
    pub fn attach(parents: &[i32], lengths: &[f64], inherits: &[u8], limits: &[f64]) -> Result<SpineRig, String> {
        let n = parents.len();
        if lengths.len() != n {
            return Err(format!("lengths: must be {n} (one per parent), got {}", lengths.len()));
        }
        if inherits.len() != n {
            return Err(format!("inherits: must be {n} (one per parent), got {}", inherits.len()));
        }
        if limits.len() != 2 * n {
            return Err(format!("limits: must be {} (two per parent), got {}", 2 * n, limits.len()));
        }
        let mut bones = Vec::with_capacity(n);
        let mut chain: Vec<usize> = Vec::with_capacity(n);
        for i in 0..n {
            let inherit = *Inherit::ALL
                .get(usize::from(inherits[i]))
                .ok_or_else(|| format!("inherits[{i}]: must be 0 to 4, got {}", inherits[i]))?;
            let parent = match parents[i] {
                -1 => None,
                p => match usize::try_from(p) {
                    Ok(p) if p < i => Some(p),
                    _ => return Err(format!("parents[{i}]: must be −1 or a bone before {i}, got {p}")),
                },
            };
            if !(lengths[i] >= 0.0 && lengths[i].is_finite()) {
                return Err(format!("lengths[{i}]: must be finite and ≥ 0, got {}", lengths[i]));
            }
            let (lo, hi) = (limits[2 * i], limits[2 * i + 1]);
            let limits_deg = if lo.is_nan() && hi.is_nan() {
                None
            } else if lo.is_finite() && hi.is_finite() && lo <= hi {
                Some([lo, hi])
            } else {
                return Err(format!(
                    "limits[{}..{}]: must be NaN, NaN or finite and in order, got {lo}, {hi}",
                    2 * i,
                    2 * i + 2
                ));
            };
            chain.push(parent.map_or(1, |p| chain[p] + 1));
            bones.push(SpineBone { parent, length: lengths[i], inherit, limits_deg });
        }
        let rig = ikarus::character::SpineRig::new(bones).map_err(|e| e.to_string())?;
        let solver = Solver::new(SolveOptions { method: Method::LevenbergMarquardt, ..SolveOptions::default() })
            .map_err(|e| e.to_string())?;
        Ok(SpineRig {
            rig,
            solver,
            chain,
            frame: vec![0.0; n * FRAME_NUMBERS],
            goal_numbers: vec![0.0; n * GOAL_NUMBERS],
            pin_numbers: vec![0.0; n],
            rotations: vec![0.0; n],
            moved: vec![0.0; n],
            errors: vec![0.0; n],
            goals: Vec::with_capacity(n),
            pins: Vec::with_capacity(n),
            last_error: String::new(),
        })
    }

    /// [`SpineRig::apply`] with its error as a string.
    pub fn solve(&mut self, placement: Placement, goals: f64, pins: f64) -> Result<usize, String> {
        let n = self.rotations.len();
        for (field, v) in [("x", placement.position[0]), ("y", placement.position[1])]
            .into_iter()
            .chain([("scaleX", placement.scale[0]), ("scaleY", placement.scale[1])])
        {
            if !v.is_finite() {
                return Err(format!("{field}: must be finite, got {v}"));
            }
        }
        let goals = count("goals", goals, n)?;
        let pins = count("pins", pins, n)?;
        self.read_goals(goals)?;
        self.pins.clear();
        for (k, &p) in self.pin_numbers[..pins].iter().enumerate() {
            self.pins.push(index(&format_args!("pins[{k}]"), p, n)?);
        }
        let frame = SpineFrame { numbers: &self.frame, placement, goals: &self.goals, pins: &self.pins };
        self.rig.solve(&frame, &mut self.solver, &mut self.rotations).map_err(|e| e.to_string())?;
        let moved = self.rig.moved();
        for (m, &b) in self.moved.iter_mut().zip(moved) {
            *m = b as f64;
        }
        self.errors[..goals].copy_from_slice(self.rig.errors());
        Ok(moved.len())
    }

    /// The first `goals` goals at `goalsPtr` into `self.goals`.
    fn read_goals(&mut self, goals: usize) -> Result<(), String> {
        let n = self.rotations.len();
        self.goals.clear();
        for (k, g) in self.goal_numbers.chunks_exact(GOAL_NUMBERS).take(goals).enumerate() {
            let [bone, x, y, bones, angle, weight, priority, bend] =
                <[f64; GOAL_NUMBERS]>::try_from(g).unwrap_or_default();
            let bone = index(&format_args!("goals[{k}].bone"), bone, n)?;
            let most = self.chain[bone];
            if !(bones >= 1.0 && bones <= most as f64 && bones.fract() == 0.0) {
                return Err(format!("goals[{k}].bones: must be 1 to {most} (bone {bone} up to its root), got {bones}"));
            }
            for (field, v) in [("x", x), ("y", y)] {
                if !v.is_finite() {
                    return Err(format!("goals[{k}].{field}: must be finite, got {v}"));
                }
            }
            if angle.is_infinite() {
                return Err(format!("goals[{k}].angle: must be finite or NaN (none), got {angle}"));
            }
            let goal =
                if angle.is_nan() { Goal::position(x, y) } else { Goal::with_orientation(x, y, angle.to_radians()) }
                    .map_err(|e| format!("goals[{k}]: {e}"))?;
            if !(weight > 0.0 && weight.is_finite()) {
                return Err(format!("goals[{k}].weight: must be finite and > 0, got {weight}"));
            }
            let priority = match priority {
                0.0 => Priority::Primary,
                1.0 => Priority::Secondary,
                _ => return Err(format!("goals[{k}].priority: must be 0 (primary) or 1 (secondary), got {priority}")),
            };
            let bend = match bend {
                0.0 => None,
                1.0 => Some(Bend::Positive),
                -1.0 => Some(Bend::Negative),
                _ => return Err(format!("goals[{k}].bend: must be 0, 1 or −1, got {bend}")),
            };
            let mut goal = RigGoal::new(bone, goal).with_weight(weight).with_priority(priority);
            goal.bend = bend;
            self.goals.push(TipGoal { goal, bones: bones as usize });
        }
        Ok(())
    }

    /// The frame's numbers ([`FRAME_NUMBERS`] per bone), to write natively.
    pub fn frame_mut(&mut self) -> &mut [f64] {
        &mut self.frame
    }

    /// The frame's numbers as written.
    pub fn frame(&self) -> &[f64] {
        &self.frame
    }

    /// The goals' numbers ([`GOAL_NUMBERS`] per goal), to write natively.
    pub fn goals_mut(&mut self) -> &mut [f64] {
        &mut self.goal_numbers
    }

    /// The pins' numbers, to write natively.
    pub fn pins_mut(&mut self) -> &mut [f64] {
        &mut self.pin_numbers
    }

    /// Every bone's local rotation after the last solve, degrees.
    pub fn rotations(&self) -> &[f64] {
        &self.rotations
    }

    /// The moved bones' indices after the last solve (the first as many as it returned).
    pub fn moved(&self) -> &[f64] {
        &self.moved
    }

    /// Each goal's error after the last solve (the first as many as it had goals).
    pub fn errors(&self) -> &[f64] {
        &self.errors
    }
}

/// A count from JavaScript: a whole number from 0 to `most`.
fn count(field: &str, v: f64, most: usize) -> Result<usize, String> {
    if v >= 0.0 && v <= most as f64 && v.fract() == 0.0 {
        Ok(v as usize)
    } else {
        Err(format!("{field}: must be a whole number from 0 to {most}, got {v}"))
    }
}

/// A bone index from JavaScript: a whole number below `n`.
fn index(field: &std::fmt::Arguments, v: f64, n: usize) -> Result<usize, String> {
    if v >= 0.0 && v < n as f64 && v.fract() == 0.0 {
        Ok(v as usize)
    } else {
        Err(format!("{field}: must be a bone index from 0 to {}, got {v}", n.saturating_sub(1)))
    }
}
