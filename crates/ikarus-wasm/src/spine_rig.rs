//! The `ikarus-spine` add-on's handle (issue 41): [`ikarus::character::SpineRig`] over numbers
//! that JavaScript writes and reads through `Float64Array` views of the module's memory, so that
//! a frame's pose does not cross the boundary as an array.
//!
//! Once: `new SpineRig(parents, lengths, inherits, limits)`. Each frame: write the skeleton's 13
//! numbers per bone at [`frame_ptr`](SpineRig::frame_ptr) (world `a, b, c, d, worldX, worldY`,
//! local `x, y, rotation, scaleX, scaleY, shearX, shearY`, degrees), then `clear()`, `goal(…)`,
//! `pin(…)`, `apply(…)`; read the moved bones ([`moved_ptr`](SpineRig::moved_ptr), `moved`
//! of them, as f64) and every bone's new local rotation ([`rotations_ptr`](SpineRig::rotations_ptr),
//! degrees), and each goal's error ([`errors_ptr`](SpineRig::errors_ptr)).

use ikarus::Goal;
use ikarus::character::{Inherit, Placement, SPINE_BONE_NUMBERS, SpineBone, SpineFrame, TipGoal};
use ikarus::solve::{Bend, Method, Priority, RigGoal, SolveOptions, Solver};
use wasm_bindgen::prelude::*;

use crate::Problem;

fn invalid(message: String) -> Problem {
    Problem { status: 422, message }
}

/// A Spine skeleton's bone tree attached once, solved each frame.
#[wasm_bindgen]
pub struct SpineRig {
    rig: ikarus::character::SpineRig,
    solver: Solver,
    frame: Vec<f64>,
    rotations: Vec<f64>,
    moved: Vec<f64>,
    errors: Vec<f64>,
    goals: Vec<TipGoal>,
    pins: Vec<usize>,
}

#[wasm_bindgen]
impl SpineRig {
    /// Per bone: `parents[i]` (−1 for a root, else lower than `i`), `lengths[i]`, `inherits[i]`
    /// (0 normal, 1 onlyTranslation, 2 noRotationOrReflection, 3 noScale, 4
    /// noScaleOrReflection) and `limits[2i..2i+2]`, the range of its local rotation in degrees
    /// (NaN, NaN: none).
    #[wasm_bindgen(constructor)]
    pub fn new(parents: &[i32], lengths: &[f64], inherits: &[u8], limits: &[f64]) -> Result<SpineRig, Problem> {
        let n = parents.len();
        if lengths.len() != n || inherits.len() != n || limits.len() != 2 * n {
            return Err(invalid(format!(
                "bones: {n} parents, {} lengths, {} inherits, {} limits (must be n, n, n, 2n)",
                lengths.len(),
                inherits.len(),
                limits.len()
            )));
        }
        let mut bones = Vec::with_capacity(n);
        for i in 0..n {
            let inherit = *Inherit::ALL
                .get(usize::from(inherits[i]))
                .ok_or_else(|| invalid(format!("bones[{i}].inherit: must be 0 to 4, got {}", inherits[i])))?;
            let parent = match parents[i] {
                -1 => None,
                p => Some(usize::try_from(p).map_err(|_| invalid(format!("bones[{i}].parent: got {p}")))?),
            };
            let (lo, hi) = (limits[2 * i], limits[2 * i + 1]);
            let limits_deg = (!(lo.is_nan() && hi.is_nan())).then_some([lo, hi]);
            bones.push(SpineBone { parent, length: lengths[i], inherit, limits_deg });
        }
        let rig = ikarus::character::SpineRig::new(bones).map_err(|e| invalid(e.to_string()))?;
        let solver = Solver::new(SolveOptions { method: Method::LevenbergMarquardt, ..SolveOptions::default() })
            .map_err(|e| invalid(e.to_string()))?;
        Ok(SpineRig {
            rig,
            solver,
            frame: vec![0.0; n * SPINE_BONE_NUMBERS],
            rotations: vec![0.0; n],
            moved: vec![0.0; n],
            errors: Vec::with_capacity(n),
            goals: Vec::with_capacity(n),
            pins: Vec::with_capacity(n),
        })
    }

    /// Drops the goals and pins.
    pub fn clear(&mut self) {
        self.goals.clear();
        self.pins.clear();
    }

    /// A goal: `bone`'s tip to `(x, y)`, moving it and `bones − 1` bones above it; `angle`
    /// (degrees, its world direction; NaN: none), `weight` > 0, `priority` (0 primary, 1
    /// secondary), `bend` (0 either, 1 counter-clockwise, −1 clockwise).
    pub fn goal(
        &mut self,
        bone: usize,
        target: &[f64],
        bones: usize,
        angle: f64,
        options: &[f64],
    ) -> Result<(), Problem> {
        let [x, y] = <[f64; 2]>::try_from(target).map_err(|_| invalid("goal: target must be [x, y]".into()))?;
        let [weight, priority, bend] = <[f64; 3]>::try_from(options)
            .map_err(|_| invalid("goal: options must be [weight, priority, bend]".into()))?;
        let goal = if angle.is_nan() { Goal::position(x, y) } else { Goal::with_orientation(x, y, angle.to_radians()) }
            .map_err(|e| invalid(format!("goal on bone {bone}: {e}")))?;
        if !(weight > 0.0 && weight.is_finite()) {
            return Err(invalid(format!("goal on bone {bone}: weight must be > 0, got {weight}")));
        }
        let mut g = RigGoal::new(bone, goal).with_weight(weight);
        if priority == 1.0 {
            g = g.with_priority(Priority::Secondary);
        }
        if bend > 0.0 {
            g = g.with_bend(Bend::Positive);
        } else if bend < 0.0 {
            g = g.with_bend(Bend::Negative);
        }
        self.goals.push(TipGoal { goal: g, bones });
        Ok(())
    }

    /// A pin: `bone`'s tip stays where the frame has it.
    pub fn pin(&mut self, bone: usize) {
        self.pins.push(bone);
    }

    /// Solves the frame at [`frame_ptr`](SpineRig::frame_ptr) for the goals and pins, the
    /// skeleton placed at `placement` (`[x, y, scaleX, scaleY]`); returns how many bones moved.
    pub fn apply(&mut self, placement: &[f64]) -> Result<usize, Problem> {
        let [x, y, sx, sy] =
            <[f64; 4]>::try_from(placement).map_err(|_| invalid("placement: must be [x, y, scaleX, scaleY]".into()))?;
        let frame = SpineFrame {
            numbers: &self.frame,
            placement: Placement { position: [x, y], scale: [sx, sy] },
            goals: &self.goals,
            pins: &self.pins,
        };
        self.rig.solve(&frame, &mut self.solver, &mut self.rotations).map_err(|e| invalid(e.to_string()))?;
        for (m, &b) in self.moved.iter_mut().zip(self.rig.moved()) {
            *m = b as f64;
        }
        self.errors.clear();
        self.errors.extend_from_slice(self.rig.errors());
        Ok(self.rig.moved().len())
    }

    /// Where the frame's numbers go (13 per bone; a byte offset, 8-aligned, fixed for the
    /// rig's life).
    #[wasm_bindgen(getter, js_name = framePtr)]
    pub fn frame_ptr(&self) -> usize {
        self.frame.as_ptr() as usize
    }

    /// Where every bone's local rotation after [`apply`](SpineRig::apply) lies (degrees).
    #[wasm_bindgen(getter, js_name = rotationsPtr)]
    pub fn rotations_ptr(&self) -> usize {
        self.rotations.as_ptr() as usize
    }

    /// Where the moved bones' indices lie (as f64, the first `apply()` of them).
    #[wasm_bindgen(getter, js_name = movedPtr)]
    pub fn moved_ptr(&self) -> usize {
        self.moved.as_ptr() as usize
    }

    /// Where each goal's error after [`apply`](SpineRig::apply) lies, in the goals' order.
    #[wasm_bindgen(getter, js_name = errorsPtr)]
    pub fn errors_ptr(&self) -> usize {
        self.errors.as_ptr() as usize
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ikarus::character::{PoseRequest, Posed};

    #[test]
    fn spineboys_fist_reaches_a_goal_through_the_handle() {
        let file = "spine-spineboy-pro.json";
        let path = format!("{}/../../examples/characters/{file}", env!("CARGO_MANIFEST_DIR"));
        let c = ikarus_edge::character::load(&std::fs::read_to_string(path).unwrap(), file).unwrap().character;
        let parents: Vec<i32> = c.bones().iter().map(|b| b.parent.map_or(-1, |p| p as i32)).collect();
        let lengths: Vec<f64> = c.bones().iter().map(|b| b.length).collect();
        let inherits: Vec<u8> =
            c.bones().iter().map(|b| Inherit::ALL.iter().position(|&i| i == b.inherit).unwrap() as u8).collect();
        let limits = vec![f64::NAN; 2 * parents.len()];
        let mut rig = SpineRig::new(&parents, &lengths, &inherits, &limits).unwrap();
        let mut posed = Posed::default();
        let walk = c.clip_index("walk").unwrap();
        let request = PoseRequest { clip: Some((walk, 0.4)), targets: &[], bends: &[], turns: &[], skin: None };
        c.pose(&request, &mut posed).unwrap();
        for i in 0..posed.len() {
            let (w, l) = (posed.world(i), posed.local(i));
            let v = [w.a, w.b, w.c, w.d, w.x, w.y, l.x, l.y, l.rotation.to_degrees(), l.scale_x, l.scale_y];
            rig.frame[i * SPINE_BONE_NUMBERS..i * SPINE_BONE_NUMBERS + 11].copy_from_slice(&v);
            rig.frame[i * SPINE_BONE_NUMBERS + 11] = l.shear_x.to_degrees();
            rig.frame[i * SPINE_BONE_NUMBERS + 12] = l.shear_y.to_degrees();
        }
        let fist = c.bones().iter().position(|b| b.name == "front-fist").unwrap();
        let tip = posed.tip(fist);
        rig.clear();
        rig.goal(fist, &[tip[0] - 40.0, tip[1] + 30.0], 3, f64::NAN, &[1.0, 0.0, 0.0]).unwrap();
        assert_eq!(rig.apply(&[0.0, 0.0, 1.0, 1.0]).unwrap(), 3);
        assert_eq!(rig.moved[..3], [fist as f64 - 2.0, fist as f64 - 1.0, fist as f64]);
        assert!(rig.errors[0] < 1e-3, "{}", rig.errors[0]);
        let e = rig.goal(fist, &[0.0], 3, f64::NAN, &[1.0, 0.0, 0.0]).unwrap_err();
        assert_eq!(e.message, "goal: target must be [x, y]");
        let e = rig.apply(&[0.0, 0.0]).unwrap_err();
        assert_eq!(e.message, "placement: must be [x, y, scaleX, scaleY]");
    }
}
