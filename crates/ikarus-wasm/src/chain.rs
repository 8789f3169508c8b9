//! The typed chain: an arm read once, solved many times without JSON. [`Chain`] holds the
//! validated arm (read by the edge's reader, so its refusals are the server's lines), the
//! options of `/api/solve` for it, and one [`Solver`] and [`Outcome`] whose buffers every solve
//! reuses. Each solve writes one [record](Chain::record_len) into a `Float64Array` the caller
//! owns; its numbers are bit for bit those of `call("solve", …)` for the same arm, options and
//! goal (the same library call from the same start pose).

use ikarus::{Follower, Goal, Outcome, SampleStatus, SolveOptions, Solver, Status};
use ikarus_edge::edge::{self, Arm, Limits};
use wasm_bindgen::prelude::*;

use crate::Problem;

/// Numbers of a record after the angles: the tip's x and y, the error, the iterations, the
/// restarts, the status code.
const TAIL: usize = 6;

/// Numbers of a follow record after the angles and the joints: the error, the step, the status code.
const FOLLOW_TAIL: usize = 3;

/// The code of `status` in a record: its index in [`Status::ALL`], the order of
/// [`ikarus::Status`]. (A follow record's code is the index of its status in
/// [`SampleStatus::ALL`]; `off_path` never: it is the plan's.)
fn status_code(status: Status) -> u32 {
    Status::ALL.iter().position(|&s| s == status).map_or(u32::MAX, |i| i as u32)
}

/// A chain to solve from JavaScript without JSON: `new Chain(armJson, optionsJson)`, then
/// `solve(x, y, out)` / `solveBatch(goals, out)`. A record is `n + 6` numbers (`n` joints):
/// the angles in degrees (`angles_deg`), the tip's x and y (`end_effector`), `error`,
/// `iterations`, `restarts`, and the status code ([`status_name`] names it: 0 `reached`,
/// 1 `unreachable`, 2 `stalled`, 3 `iteration_limit`, 4 `interrupted`).
#[wasm_bindgen]
pub struct Chain {
    arm: Arm,
    solver: Solver,
    outcome: Outcome,
    goals: Vec<Goal>,
    outcomes: Vec<Outcome>,
    /// The record of the last [`solve_here`](Chain::solve_here), read by JavaScript through a
    /// view over the module's memory at [`record_ptr`](Chain::record_ptr).
    record: Vec<f64>,
    /// The options as `/api/track` reads them, for the follower.
    track: SolveOptions,
    /// The follower of [`follow_here`](Chain::follow_here) and its bound (degrees), made on the
    /// first follow and again when the bound changes.
    follower: Option<(f64, Follower)>,
    /// The record of the last follow, read at [`follow_ptr`](Chain::follow_ptr).
    follow_record: Vec<f64>,
}

/// A [`Problem`] of the edge's.
fn problem(p: edge::Problem) -> Problem {
    Problem { status: p.status, message: p.message }
}

#[wasm_bindgen]
impl Chain {
    /// The arm `arm` (the API's `arm` object as JSON text; `""` for the built-in seed arm) with
    /// the options `options` (the API's `options` object as JSON text, `""` for none), as
    /// `/api/solve` reads them; frames are not recorded. Throws the server's [`Problem`]
    /// (`arm: links[0].length = -1: …`, `options.tolerance = 0: …`); for a value of the wrong
    /// kind, the server's line less `request body: ` and the position in the JSON text
    /// (`options.method: unknown variant …`). An arm with offsets or slides (a one-branch rig,
    /// which `/api/solve` solves as a rig) is refused with the command line's line.
    #[wasm_bindgen(constructor)]
    pub fn new(arm: &str, options: &str) -> Result<Chain, Problem> {
        let arm = if arm.trim().is_empty() {
            seed_arm()
        } else {
            edge::arm_from_json(arm).map_err(|p| Problem { status: p.status, message: unplaced(&p.message) })?
        };
        let options = if options.trim().is_empty() { "{}" } else { options };
        let track = edge::solve_options(&arm, options, &Limits::default())
            .map_err(|p| Problem { status: p.status, message: under("options", &p.message) })?;
        let options = SolveOptions { record_every: None, ..track.clone() };
        let solver = Solver::new(options).map_err(|e| Problem { status: 422, message: format!("options: {e}") })?;
        let n = arm.chain().len();
        Ok(Chain {
            arm,
            solver,
            outcome: Outcome::default(),
            goals: Vec::new(),
            outcomes: Vec::new(),
            record: vec![0.0; n + TAIL],
            track,
            follower: None,
            follow_record: vec![0.0; n + 2 * (n + 1) + FOLLOW_TAIL],
        })
    }

    /// The number of joints (`n`).
    #[wasm_bindgen(getter)]
    pub fn joints(&self) -> usize {
        self.arm.chain().len()
    }

    /// The numbers of one record: `n + 6`.
    #[wasm_bindgen(getter, js_name = recordLen)]
    pub fn record_len(&self) -> usize {
        self.joints() + TAIL
    }

    /// Solves the goal (`x`, `y`) from the arm's start pose into `out` (at least one record
    /// long) and returns the status code. Throws a [`Problem`] for a goal that is not finite
    /// (`goal.x = NaN: …`) or an `out` too short.
    pub fn solve(&mut self, x: f64, y: f64, out: &mut [f64]) -> Result<u32, Problem> {
        let len = self.record_len();
        let record = out.get_mut(..len).ok_or_else(|| short("out", len, 1))?;
        let code = self.solve_here(x, y)?;
        record.copy_from_slice(&self.record);
        Ok(code)
    }

    /// [`solve`](Chain::solve) into the chain's own record, which JavaScript reads through a
    /// `Float64Array` view over the module's memory at [`record_ptr`](Chain::record_ptr): no
    /// array crosses the boundary (wasm-bindgen copies a `Float64Array` argument in and out).
    #[wasm_bindgen(js_name = solveHere)]
    pub fn solve_here(&mut self, x: f64, y: f64) -> Result<u32, Problem> {
        let goal = edge::goal(x, y, None).map_err(problem)?;
        let chain = self.arm.chain();
        self.solver
            .solve_into(chain, chain.start_pose().angles(), &goal, &mut self.outcome)
            .map_err(|e| Problem { status: 422, message: e.to_string() })?;
        Ok(write(&self.outcome, &mut self.record))
    }

    /// Where the chain's own record lies in the module's memory (a byte offset, 8-aligned;
    /// fixed for the chain's life, though the memory's buffer changes when it grows).
    #[wasm_bindgen(getter, js_name = recordPtr)]
    pub fn record_ptr(&self) -> usize {
        self.record.as_ptr() as usize
    }

    /// The numbers of a follow record: `3n + 5` (`n` joints).
    #[wasm_bindgen(getter, js_name = followLen)]
    pub fn follow_len(&self) -> usize {
        self.follow_record.len()
    }

    /// Where the chain's follow record lies in the module's memory (as [`record_ptr`](Chain::record_ptr)).
    #[wasm_bindgen(getter, js_name = followPtr)]
    pub fn follow_ptr(&self) -> usize {
        self.follow_record.as_ptr() as usize
    }

    /// One step of following the pointer: from the pose `start_deg` (degrees, one per joint)
    /// toward the goal (`x`, `y`), no joint moving more than `max_step_deg` — what `/api/track`
    /// answers for `{arm, options, start_deg, max_step_deg, path: [[x, y]], mode: "follow",
    /// bound_first: true}`, bit for bit. Writes the follow record (read at
    /// [`follow_ptr`](Chain::follow_ptr)): the angles in degrees (`angles_deg`), the joints'
    /// x, y pairs from the base to the tip (`joints`), `error`, `step_deg`, and the sample's
    /// status code ([`follow_status_name`]); returns the code. Throws a [`Problem`] for a goal,
    /// pose or bound the server refuses (`goal.x = NaN: …`, `start_deg: expected 3 angles …`,
    /// `max_step_deg = 0: …`).
    #[wasm_bindgen(js_name = followHere)]
    pub fn follow_here(&mut self, start_deg: &[f64], x: f64, y: f64, max_step_deg: f64) -> Result<u32, Problem> {
        let goal = edge::goal(x, y, None).map_err(problem)?;
        let start = edge::start_pose(&self.arm, start_deg).map_err(problem)?;
        let refused = |e: ikarus::TrackError| Problem { status: 422, message: e.to_string() };
        let follower = match &mut self.follower {
            Some((bound, f)) if bound.to_bits() == max_step_deg.to_bits() => {
                f.reset(&start).map_err(refused)?;
                f
            }
            slot => {
                let options = edge::follow_options(self.track.clone(), max_step_deg).map_err(problem)?;
                let f = Follower::new(self.arm.chain(), &start, &options).map_err(refused)?;
                &mut slot.insert((max_step_deg, f)).1
            }
        };
        let step = follower.step(&goal);
        let n = start.len();
        let (angles, rest) = self.follow_record.split_at_mut(n);
        let (joints, tail) = rest.split_at_mut(2 * (n + 1));
        for (dst, a) in angles.iter_mut().zip(follower.pose()) {
            *dst = a.to_degrees();
        }
        for (dst, p) in
            joints.chunks_exact_mut(2).zip(ikarus::kinematics::joint_positions(self.arm.chain(), follower.pose()))
        {
            dst.copy_from_slice(&[p.x, p.y]);
        }
        let code = SampleStatus::ALL.iter().position(|&s| s == step.status).map_or(u32::MAX, |i| i as u32);
        tail.copy_from_slice(&[step.error, step.step.to_degrees(), f64::from(code)]);
        Ok(code)
    }

    /// Solves the goals `goals` (`x, y` pairs, flat) through the library's batch path, each from
    /// the start pose, writing one record per goal into `out` in order (what `solve` would write
    /// for each, bit for bit). Throws a [`Problem`] naming the first goal that is not finite
    /// (`goals[3]: …`), or for an odd `goals` or an `out` too short.
    #[wasm_bindgen(js_name = solveBatch)]
    pub fn solve_batch(&mut self, goals: &[f64], out: &mut [f64]) -> Result<(), Problem> {
        if goals.len() % 2 != 0 {
            return Err(Problem { status: 422, message: format!("goals: {} numbers, not x, y pairs", goals.len()) });
        }
        let count = goals.len() / 2;
        let len = self.record_len();
        let out = out.get_mut(..count * len).ok_or_else(|| short("out", len, count))?;
        self.goals.clear();
        for (i, xy) in goals.chunks_exact(2).enumerate() {
            let goal = edge::goal(xy[0], xy[1], None)
                .map_err(|p| Problem { status: p.status, message: format!("goals[{i}]: {}", p.message) })?;
            self.goals.push(goal);
        }
        let chain = self.arm.chain();
        self.solver
            .solve_batch(chain, chain.start_pose().angles(), &self.goals, &mut self.outcomes)
            .map_err(|e| Problem { status: 422, message: e.to_string() })?;
        for (o, record) in self.outcomes.iter().zip(out.chunks_exact_mut(len)) {
            write(o, record);
        }
        Ok(())
    }
}

/// The seed arm (`examples/arms/seed.toml`, the edge's [`edge::default_arm`]). The small module
/// (without the `json` feature) has no TOML reader, so it reads the same arm from JSON; a test
/// checks that the two are one arm.
#[cfg(feature = "json")]
fn seed_arm() -> Arm {
    edge::default_arm()
}

/// The seed arm, read from [`SEED_ARM_JSON`] (the small module has no TOML reader).
#[cfg(not(feature = "json"))]
fn seed_arm() -> Arm {
    edge::arm_from_json(SEED_ARM_JSON).expect("the seed arm's JSON is valid (a test reads it)")
}

/// `examples/arms/seed.toml` as the API's `arm` object (`call("arm/default")`'s answer).
#[cfg_attr(feature = "json", allow(dead_code, reason = "read by the small module and the tests"))]
const SEED_ARM_JSON: &str = r#"{"name":"seed","base":[0.0,0.0],"links":[{"length":3.0,"angle_deg":5.0,"limits_deg":[-45.0,45.0]},{"length":2.0,"angle_deg":5.0,"limits_deg":[-90.0,90.0]},{"length":1.0,"angle_deg":5.0,"limits_deg":[-170.0,170.0]}]}"#;

/// The name of a record's status code (`reached`, …; `undefined` for another number).
#[wasm_bindgen(js_name = statusName)]
pub fn status_name(code: u32) -> Option<String> {
    Status::ALL.get(code as usize).map(|&s| edge::status_name(s).to_owned())
}

/// The name of a follow record's status code (`reached`, `limited`, …; `undefined` for another number).
#[wasm_bindgen(js_name = followStatusName)]
pub fn follow_status_name(code: u32) -> Option<String> {
    SampleStatus::ALL.get(code as usize).map(|&s| s.as_str().to_owned())
}

/// The message of a refused `arm` as `/api/solve` words it for `{"arm": …}`, less the position
/// in a JSON text the caller did not write: the edge's `arm: links[0].length: invalid type: …
/// at line 1 column 23` (a value of the wrong kind) is `arm.links[0].length: invalid type: …`;
/// a refused value (`arm: links[0].length = 0: …`) is the server's line as it is.
fn unplaced(message: &str) -> String {
    let Some(at) = message.rfind(" at line ") else { return message.to_owned() };
    let message = &message[..at];
    message.strip_prefix("arm: ").map_or_else(|| message.to_owned(), |rest| under("arm", rest))
}

/// `message` (a refusal inside the object `object`) as the server words it: `object.path: …`
/// when it starts with a field's path or a refused value (`links[0].length: …`, `tolerance =
/// 0: …`), `object: …` when it names no field (`invalid type: …`, as the small module, without
/// serde_path_to_error, words a value of the wrong kind).
fn under(object: &str, message: &str) -> String {
    let head = message.split(": ").next().unwrap_or(message);
    if head.contains(' ') && !head.contains(" = ") {
        format!("{object}: {message}")
    } else {
        format!("{object}.{message}")
    }
}

/// The refusal of an output array shorter than `count` records of `len` numbers.
fn short(name: &str, len: usize, count: usize) -> Problem {
    Problem { status: 422, message: format!("{name}: shorter than {count} record(s) of {len} numbers") }
}

/// Writes `o` as a record into `record` (exactly one record long); returns the status code.
fn write(o: &Outcome, record: &mut [f64]) -> u32 {
    let (angles, tail) = record.split_at_mut(record.len() - TAIL);
    for (dst, a) in angles.iter_mut().zip(o.pose.angles()) {
        *dst = a.to_degrees();
    }
    let code = status_code(o.status);
    let p = o.end_effector.position;
    tail.copy_from_slice(&[p.x, p.y, o.error, f64::from(o.iterations), f64::from(o.restarts), f64::from(code)]);
    code
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_record_is_the_json_answers_numbers() {
        let mut chain = Chain::new("", "").unwrap();
        let mut out = vec![0.0; chain.record_len()];
        let code = chain.solve(2.0, 3.0, &mut out).unwrap();
        let json: serde_json::Value =
            serde_json::from_str(&crate::answer("solve", r#"{"goal":{"x":2,"y":3}}"#).unwrap()).unwrap();
        let n = chain.joints();
        for i in 0..n {
            assert_eq!(out[i].to_bits(), json["angles_deg"][i].as_f64().unwrap().to_bits());
        }
        assert_eq!(out[n], json["end_effector"]["x"].as_f64().unwrap());
        assert_eq!(out[n + 2], json["error"].as_f64().unwrap());
        assert_eq!(out[n + 3], json["iterations"].as_f64().unwrap());
        assert_eq!(status_name(code).as_deref(), json["status"].as_str());
        assert_eq!(out[n + 5], f64::from(code));

        let mut batch = vec![0.0; 2 * chain.record_len()];
        chain.solve_batch(&[9.0, 9.0, 2.0, 3.0], &mut batch).unwrap();
        assert_eq!(batch[chain.record_len()..], out[..]);
        assert_eq!(status_name(batch[n + 5] as u32).as_deref(), Some("unreachable"));
    }

    #[test]
    fn a_refusal_without_a_path_is_not_joined_to_its_object() {
        assert_eq!(under("arm", "links[0].length: invalid type: x"), "arm.links[0].length: invalid type: x");
        assert_eq!(under("options", "tolerance = 0: must be …"), "options.tolerance = 0: must be …");
        assert_eq!(
            under("arm", "invalid type: string \"x\", expected f64"),
            "arm: invalid type: string \"x\", expected f64"
        );
        assert_eq!(
            unplaced("arm: invalid type: string \"x\", expected f64 at line 1 column 23"),
            "arm: invalid type: string \"x\", expected f64"
        );
    }

    #[test]
    fn the_seed_arms_json_is_the_built_in_arm() {
        assert_eq!(SEED_ARM_JSON, crate::answer("arm/default", "").unwrap());
    }

    #[test]
    fn the_chains_own_record_is_solves_record() {
        let mut chain = Chain::new("", "").unwrap();
        let mut out = vec![0.0; chain.record_len()];
        for (x, y) in [(2.0, 3.0), (9.0, 9.0), (-1.0, 0.5)] {
            let code = chain.solve(x, y, &mut out).unwrap();
            out.iter_mut().for_each(|v| *v = f64::NAN);
            assert_eq!(chain.solve_here(x, y).unwrap(), code);
            assert_eq!(chain.record_ptr(), chain.record.as_ptr() as usize);
            chain.solve(x, y, &mut out).unwrap();
            assert_eq!(chain.record, out);
        }
    }

    /// The follow record is the numbers of `/api/track`'s one-sample follow answer, bit for bit,
    /// step after step from the pose each step left (as the page follows the pointer: one
    /// follower reset to each pose), with the
    /// limits off and on, the bound changed on the way, goals reached, cut by the bound and
    /// out of reach.
    #[test]
    fn a_follow_record_is_the_track_answers_numbers() {
        let goals = [(2.0, 3.0), (-4.0, 1.0), (-4.1, 1.2), (9.0, 9.0), (0.5, -5.5), (1.0, 1.0), (-6.0, 0.0)];
        let mut seen = std::collections::BTreeSet::new();
        for options in ["", r#"{"limits": true}"#, r#"{"method": "dls", "limits": true, "limit_mode": "clamp"}"#] {
            let mut chain = Chain::new("", options).unwrap();
            let n = chain.joints();
            let mut pose: Vec<f64> = chain.arm.start().iter().map(|a| a.to_degrees()).collect();
            // Each goal asked 6 times, as the page chases a goal the bound cut short.
            for (k, &(x, y)) in goals.iter().flat_map(|g| [g; 6]).enumerate() {
                let bound = if k < 20 { 10.0 } else { 25.0 };
                let code = chain.follow_here(&pose, x, y, bound).unwrap();
                let body = serde_json::json!({
                    "options": serde_json::from_str::<serde_json::Value>(if options.is_empty() { "{}" } else { options }).unwrap(),
                    "start_deg": pose, "max_step_deg": bound, "path": [[x, y]], "mode": "follow", "bound_first": true,
                });
                let json: serde_json::Value =
                    serde_json::from_str(&crate::answer("track", &body.to_string()).unwrap()).unwrap();
                let s = &json["samples"][0];
                let r = &chain.follow_record;
                let bits = |v: &serde_json::Value| v.as_f64().unwrap().to_bits();
                for i in 0..n {
                    assert_eq!(r[i].to_bits(), bits(&s["angles_deg"][i]), "{options} goal {k}");
                }
                for j in 0..=n {
                    assert_eq!(r[n + 2 * j].to_bits(), bits(&s["joints"][j][0]));
                    assert_eq!(r[n + 2 * j + 1].to_bits(), bits(&s["joints"][j][1]));
                }
                let tail = &r[3 * n + 2..];
                assert_eq!((tail[0].to_bits(), tail[1].to_bits()), (bits(&s["error"]), bits(&s["step_deg"])));
                assert_eq!(follow_status_name(code).as_deref(), s["status"].as_str());
                assert_eq!(tail[2], f64::from(code));
                seen.insert(s["status"].as_str().unwrap().to_owned());
                pose = r[..n].to_vec();
            }
        }
        assert!(["reached", "limited", "unreachable"].iter().all(|s| seen.contains(*s)), "{seen:?}");
        assert_eq!(Chain::new("", "").unwrap().follow_len(), 3 * 3 + 5);
        for (code, status) in SampleStatus::ALL.iter().enumerate() {
            assert_eq!(follow_status_name(code as u32).as_deref(), Some(status.as_str()));
        }
        assert_eq!(follow_status_name(7), None);
    }

    #[test]
    fn a_refused_follow_is_the_servers_line() {
        let mut chain = Chain::new("", "").unwrap();
        let track = |fields: &str| {
            crate::answer("track", &format!(r#"{{"mode": "follow", "bound_first": true, {fields}}}"#)).unwrap_err()
        };
        let e = chain.follow_here(&[0.0, 0.0], 1.0, 1.0, 10.0).unwrap_err();
        assert_eq!(e, track(r#""start_deg": [0, 0], "path": [[1, 1]]"#));
        let e = chain.follow_here(&[0.0, 0.0, 0.0], 1.0, 1.0, 0.0).unwrap_err();
        assert_eq!(e, track(r#""start_deg": [0, 0, 0], "max_step_deg": 0, "path": [[1, 1]]"#));
        let e = chain.follow_here(&[0.0, f64::NAN, 0.0], 1.0, 1.0, 5.0).unwrap_err();
        assert!(e.message.contains("NaN"), "{e:?}");
        assert!(chain.follow_here(&[0.0; 3], f64::INFINITY, 1.0, 5.0).unwrap_err().message.starts_with("goal.x"));
    }

    #[test]
    fn refusals_are_the_servers_lines() {
        let e = Chain::new("", r#"{"tolerance": 0}"#).err().unwrap();
        let server = crate::answer("solve", r#"{"goal":{"x":2,"y":3},"options":{"tolerance":0}}"#).unwrap_err();
        assert_eq!(e, server);
        let e = Chain::new(r#"{"links": [{"length": "x"}]}"#, "").err().unwrap();
        assert_eq!(e.message, "arm.links[0].length: invalid type: string \"x\", expected f64");
        let e = Chain::new("", r#"{"method": "newton"}"#).err().unwrap();
        assert!(e.message.starts_with("options.method: unknown variant `newton`"), "{e:?}");
        assert!(!e.message.contains(" at line "), "{e:?}");
        let e = Chain::new(r#"{"links": [{"length": -1}]}"#, "").err().unwrap();
        let server = crate::answer("solve", r#"{"goal":{"x":2,"y":3},"arm":{"links":[{"length":-1}]}}"#).unwrap_err();
        assert_eq!(e, server);
        let mut chain = Chain::new("", "").unwrap();
        let e = chain.solve(f64::NAN, 1.0, &mut [0.0; 9]).unwrap_err();
        assert!(e.message.starts_with("goal.x"), "{e:?}");
        let e = chain.solve(1.0, 1.0, &mut [0.0; 8]).unwrap_err();
        assert_eq!(e.message, "out: shorter than 1 record(s) of 9 numbers");
        let e = chain.solve_batch(&[1.0, 1.0, 1.0, f64::INFINITY], &mut [0.0; 18]).unwrap_err();
        assert!(e.message.starts_with("goals[1]: goal.y"), "{e:?}");
        assert!(chain.solve_batch(&[1.0], &mut []).is_err());
        assert_eq!(status_name(5), None);
    }
}
