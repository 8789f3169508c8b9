//! The typed character: a character file read once, posed many times without JSON.
//! [`Character`] holds the file as `/api/pose` reads it (the same refusals), the animation
//! chosen, and the library's [`Posed`] buffers every pose reuses. Each pose writes five numbers
//! per bone into a `Float64Array` the caller owns, bit for bit those of `call("pose", …)` for
//! the same file, animation, time and targets (the same library call).

use ikarus::character::{Play, PoseRequest, Posed};
use ikarus_edge::character::Loaded;
use ikarus_edge::edge::Limits;
use ikarus_edge::pose::{clip_at, finite_time, target_point};
use wasm_bindgen::prelude::*;

use crate::Problem;

/// Numbers per bone in a pose: x, y, rotation_deg, tip x, tip y.
const PER_BONE: usize = 5;

/// A character to pose from JavaScript without JSON: `new Character(text)`, then
/// `setAnimation(name)` and `pose(time, targets, out)`. The pose is `5 × bones` numbers, bone
/// after bone in the file's order (the names of [`Character::bones`]): the world origin's x and
/// y, the rotation in degrees, and the tip's x and y (`/api/pose`'s `x`, `y`, `rotation_deg`,
/// `tip`).
#[wasm_bindgen]
pub struct Character {
    loaded: Loaded,
    clip: Option<usize>,
    targets: Vec<(usize, [f64; 2])>,
    posed: Posed,
    /// The numbers of the last [`pose_here`](Character::pose_here), read by JavaScript through
    /// a view over the module's memory at [`numbers_ptr`](Character::numbers_ptr).
    numbers: Vec<f64>,
    /// The stand-in's buffers ([`given`]).
    given: given::Given,
    /// The pose the stand-in's calls sample into and pose into.
    given_posed: Posed,
}

#[path = "character_given.rs"]
mod given;

/// A refusal of `/api/pose`'s job (a 422 with its line).
fn invalid(message: impl std::fmt::Display) -> Problem {
    Problem { status: 422, message: message.to_string() }
}

#[wasm_bindgen]
impl Character {
    /// The character file `text` (Spine or DragonBones JSON), read as `/api/pose` reads its
    /// `rig`; throws the server's [`Problem`] for a file it refuses.
    #[wasm_bindgen(constructor)]
    pub fn new(text: &str) -> Result<Character, Problem> {
        let loaded = ikarus_edge::api::pose::character(text, &Limits::default())
            .map_err(|p| Problem { status: p.status, message: p.message })?;
        let numbers = vec![0.0; PER_BONE * loaded.character.bones().len()];
        Ok(Character {
            loaded,
            clip: None,
            targets: Vec::new(),
            posed: Posed::default(),
            numbers,
            given: given::Given::default(),
            given_posed: Posed::default(),
        })
    }

    /// The bones' names in the file's order (the pose's order).
    #[must_use]
    pub fn bones(&self) -> Vec<String> {
        self.loaded.character.bones().iter().map(|b| b.name.clone()).collect()
    }

    /// The animations' names.
    #[must_use]
    pub fn animations(&self) -> Vec<String> {
        self.loaded.character.clips().iter().map(|c| c.name.clone()).collect()
    }

    /// The constraints the file has that are left inactive, flat `kind, name` pairs (`/api/pose`'s
    /// `unsupported`, `[{kind, name}, …]`).
    #[must_use]
    pub fn unsupported(&self) -> Vec<String> {
        self.loaded.character.unsupported().iter().flat_map(|u| [u.kind.clone(), u.name.clone()]).collect()
    }

    /// The numbers of one pose: `5 × bones`.
    #[wasm_bindgen(getter, js_name = poseLen)]
    pub fn pose_len(&self) -> usize {
        PER_BONE * self.loaded.character.bones().len()
    }

    /// Samples the animation `name` in the poses that follow (`undefined`: the setup pose).
    /// Throws the server's line for a name the file does not have.
    #[wasm_bindgen(js_name = setAnimation)]
    pub fn set_animation(&mut self, name: Option<String>) -> Result<(), Problem> {
        self.clip = clip_at(&self.loaded.character, name.as_deref(), None).map_err(invalid)?.map(|(i, _)| i);
        Ok(())
    }

    /// Poses the character into `out` (at least [`pose_len`](Character::pose_len) numbers): the
    /// setup pose, the animation at `time` seconds (ignored in the setup pose), then each target
    /// in order, `targets` being flat `bone index, x, y` triples (the bone's world origin put at
    /// (x, y)), then the IK constraints by the runtime's rules. Throws a [`Problem`] for a time or
    /// a point that is not finite (the server's line), a bone index that is not one, or a short
    /// `out`.
    pub fn pose(&mut self, time: f64, targets: &[f64], out: &mut [f64]) -> Result<(), Problem> {
        let len = self.pose_len();
        let out = out
            .get_mut(..len)
            .ok_or_else(|| invalid(format!("out: shorter than the pose's {len} numbers ({PER_BONE} per bone)")))?;
        self.pose_here(time, targets)?;
        out.copy_from_slice(&self.numbers);
        Ok(())
    }

    /// [`pose`](Character::pose) into the character's own numbers, which JavaScript reads
    /// through a `Float64Array` view over the module's memory at
    /// [`numbers_ptr`](Character::numbers_ptr): the pose does not cross the boundary as an array.
    #[wasm_bindgen(js_name = poseHere)]
    pub fn pose_here(&mut self, time: f64, targets: &[f64]) -> Result<(), Problem> {
        let c = &self.loaded.character;
        if targets.len() % 3 != 0 {
            return Err(invalid(format!("targets: {} numbers, not bone, x, y triples", targets.len())));
        }
        let clip = match self.clip {
            Some(i) => Some((i, finite_time(time).map_err(invalid)?)),
            None => None,
        };
        self.targets.clear();
        for (k, t) in targets.chunks_exact(3).enumerate() {
            let bone =
                c.bones().get(t[0] as usize).filter(|_| t[0].fract() == 0.0 && t[0] >= 0.0).ok_or_else(|| {
                    invalid(format!("targets[{k}]: bone {} is not a bone's index (0 to {})", t[0], c.bones().len() - 1))
                })?;
            self.targets.push((t[0] as usize, target_point(&bone.name, [t[1], t[2]]).map_err(invalid)?));
        }
        // The default skin, and physics played from 0 at 60 frames a second, as the edge's pose
        // takes them unless told otherwise.
        let request = PoseRequest { clip, targets: &self.targets, bends: &[], turns: &[], skin: c.default_skin() };
        let physics = c.constraints().iter().any(|k| k.kind() == "physics");
        let posed = if physics {
            c.play(&request, &Play { world: c.physics_world(), ..Play::default() }, &mut self.posed)
        } else {
            c.pose(&request, &mut self.posed)
        };
        posed.map_err(invalid)?;
        for (i, bone) in self.numbers.chunks_exact_mut(PER_BONE).enumerate() {
            let ([x, y], [tx, ty]) = (self.posed.origin(i), self.posed.tip(i));
            bone.copy_from_slice(&[x, y, self.posed.rotation(i).to_degrees(), tx, ty]);
        }
        Ok(())
    }

    /// Where the character's own numbers lie in the module's memory (a byte offset, 8-aligned;
    /// fixed for the character's life, though the memory's buffer changes when it grows).
    #[wasm_bindgen(getter, js_name = numbersPtr)]
    pub fn numbers_ptr(&self) -> usize {
        self.numbers.as_ptr() as usize
    }
}

#[cfg(test)]
mod tests_support {
    /// The shipped spineboy's file.
    pub(super) fn spineboy() -> String {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/characters/spine-spineboy-pro.json");
        std::fs::read_to_string(path).unwrap()
    }
}

#[cfg(test)]
mod tests {
    use super::tests_support::spineboy;
    use super::*;

    #[test]
    fn a_character_with_physics_is_played_as_the_json_answer_plays_it() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../examples/characters/spine-celestial-circus-pro.json");
        let text = std::fs::read_to_string(path).unwrap();
        let mut c = Character::new(&text).unwrap();
        c.set_animation(Some("swing".to_owned())).unwrap();
        let mut out = vec![0.0; c.pose_len()];
        c.pose(1.0, &[], &mut out).unwrap();
        let request = serde_json::json!({"rig": text, "animation": "swing", "time": 1.0});
        let json: serde_json::Value =
            serde_json::from_str(&crate::answer("pose", &request.to_string()).unwrap()).unwrap();
        for (i, b) in json["bones"].as_array().unwrap().iter().enumerate() {
            assert_eq!(out[PER_BONE * i].to_bits(), b["x"].as_f64().unwrap().to_bits(), "bone {i}");
            assert_eq!(out[PER_BONE * i + 1].to_bits(), b["y"].as_f64().unwrap().to_bits(), "bone {i}");
        }
    }

    #[test]
    fn a_pose_is_the_json_answers_numbers() {
        let text = spineboy();
        let mut c = Character::new(&text).unwrap();
        let bones = c.bones();
        let hand = bones.iter().position(|b| b == "crosshair").unwrap();
        c.set_animation(Some("walk".to_owned())).unwrap();
        let mut out = vec![0.0; c.pose_len()];
        c.pose(0.4, &[hand as f64, 50.0, 200.0], &mut out).unwrap();
        let request = serde_json::json!({"rig": text, "animation": "walk", "time": 0.4,
            "targets": [{"bone": "crosshair", "x": 50.0, "y": 200.0}]});
        let json: serde_json::Value =
            serde_json::from_str(&crate::answer("pose", &request.to_string()).unwrap()).unwrap();
        for (i, b) in json["bones"].as_array().unwrap().iter().enumerate() {
            assert_eq!(b["name"].as_str(), Some(bones[i].as_str()));
            let want = [&b["x"], &b["y"], &b["rotation_deg"], &b["tip"][0], &b["tip"][1]];
            for (k, w) in want.iter().enumerate() {
                assert_eq!(out[PER_BONE * i + k].to_bits(), w.as_f64().unwrap().to_bits(), "bone {i} number {k}");
            }
        }
    }

    #[test]
    fn the_characters_own_numbers_are_poses_and_unsupported_is_the_answers() {
        let text = spineboy();
        let mut c = Character::new(&text).unwrap();
        c.set_animation(Some("walk".to_owned())).unwrap();
        let mut out = vec![0.0; c.pose_len()];
        c.pose(0.3, &[3.0, 10.0, 20.0], &mut out).unwrap();
        c.pose(0.0, &[], &mut vec![0.0; c.pose_len()]).unwrap();
        c.pose_here(0.3, &[3.0, 10.0, 20.0]).unwrap();
        assert_eq!(c.numbers, out);
        assert_eq!(c.numbers_ptr(), c.numbers.as_ptr() as usize);
        let request = serde_json::json!({ "rig": text });
        let json: serde_json::Value =
            serde_json::from_str(&crate::answer("pose", &request.to_string()).unwrap()).unwrap();
        let want: Vec<String> = json["unsupported"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(|u| [u["kind"].as_str().unwrap().to_owned(), u["name"].as_str().unwrap().to_owned()])
            .collect();
        assert_eq!(c.unsupported(), want);
    }

    #[test]
    fn refusals_name_the_field() {
        let server = crate::answer("pose", r#"{"rig": "[[bones]]"}"#).unwrap_err();
        assert_eq!(Character::new("[[bones]]").err(), Some(server));
        let text = spineboy();
        let mut c = Character::new(&text).unwrap();
        let e = c.set_animation(Some("wlk".to_owned())).unwrap_err();
        assert!(e.message.starts_with("animation \"wlk\": no such animation (the file has: "), "{e:?}");
        let mut out = vec![0.0; c.pose_len()];
        assert!(c.pose(0.0, &[9999.0, 0.0, 0.0], &mut out).unwrap_err().message.starts_with("targets[0]: bone 9999"));
        assert!(c.pose(0.0, &[1.5, 0.0, 0.0], &mut out).is_err());
        let e = c.pose(0.0, &[1.0, f64::NAN, 0.0], &mut out).unwrap_err();
        assert!(e.message.contains("the point must be finite"), "{e:?}");
        c.set_animation(Some("walk".to_owned())).unwrap();
        assert!(c.pose(f64::INFINITY, &[], &mut out).unwrap_err().message.starts_with("time: must be a finite"));
        assert!(c.pose(0.0, &[], &mut out[..4]).unwrap_err().message.starts_with("out: shorter"));
    }
}
