//! A long fuzz of the solver, outside `cargo test`: random chains (lengths from 1e-9 to 1e9
//! mixed in one chain, single magnitudes, lengths up to 1e151, reaches within MAX_REACH), every method and limit mode, random
//! options within their validated ranges, random goals (near, far away, on the base, with and
//! without an orientation, huge orientations) and start poses (inside the limits, outside,
//! huge), checking on every case the invariants of `tests/properties.rs`:
//!
//! - the solve starts (or, for `analytic`, says plainly that there is no closed form) and
//!   nothing panics;
//! - every number of the outcome and of its frames is finite;
//! - `error`, `angle_error` and the tip are those of a fresh forward-kinematics pass over the
//!   returned angles, bit for bit, and the status agrees with them: `reached` exactly when
//!   both are within their tolerances, `unreachable` only for goals out of reach;
//! - with limits enforced, every returned and recorded angle lies inside its limits;
//! - the iterations stay under the cap of every attempt;
//! - the same solve twice gives the same bits.
//!
//! ```text
//! cargo run --release -p ikarus --example fuzz -- --cases 1000000 --seed 1 [--threads 2]
//! cargo run --release -p ikarus --example fuzz -- --seed 1 --case 4711    # one case, verbose
//! ```
//!
//! Case `k` of seed `S` is drawn from its own generator, so any failure prints the one command
//! line that reproduces it. The exit code is 1 when a case failed.

use std::f64::consts::PI;
use std::process::ExitCode;
use std::time::Instant;

use ikarus::kinematics::{end_effector, joint_positions};
use ikarus::rng::SplitMix64;
use ikarus::solve::wrap_angle;
use ikarus::{
    Chain, Goal, JointLimits, LimitMode, Link, Method, Outcome, Restarts, SolveError, SolveOptions, Solver,
    StallDetection, Status,
};

/// One case: everything a solve takes.
#[derive(Debug, Clone)]
struct Case {
    chain: Chain,
    goal: Goal,
    opts: SolveOptions,
    start: Vec<f64>,
}

fn log_uniform(rng: &mut SplitMix64, lo: f64, hi: f64) -> f64 {
    libm::pow(10.0, rng.range(lo, hi))
}

fn pick<T: Copy>(rng: &mut SplitMix64, items: &[T]) -> T {
    items[(rng.next_u64() % items.len() as u64) as usize]
}

/// The generator of case `k` of `seed`.
fn case_rng(seed: u64, k: u64) -> SplitMix64 {
    let mut rng = SplitMix64(seed ^ k.wrapping_mul(0x9E37_79B9_7F4A_7C15));
    rng.next_u64();
    rng
}

fn random_case(rng: &mut SplitMix64) -> Case {
    let n = if rng.chance(0.7) { 1 + (rng.next_u64() % 8) as usize } else { 1 + (rng.next_u64() % 64) as usize };
    // Lengths: ordinary, mixed magnitudes in one chain, one magnitude, or huge.
    let kind = rng.unit();
    let magnitude = libm::pow(10.0, f64::from(pick(rng, &[-9, -6, -3, 0, 3, 6, 9])));
    let huge = log_uniform(rng, 50.0, 150.0) / n as f64; // reach ≤ MAX_REACH
    let length = |rng: &mut SplitMix64| {
        if kind < 0.3 {
            rng.range(0.01, 10.0)
        } else if kind < 0.7 {
            log_uniform(rng, -9.0, 9.0)
        } else if kind < 0.9 {
            magnitude * rng.range(0.1, 10.0)
        } else {
            huge * rng.range(0.1, 10.0)
        }
    };
    let limited = pick(rng, &[0.0, 0.5, 1.0]);
    let mut links = Vec::with_capacity(n);
    for _ in 0..n {
        let l = length(rng);
        let limits = rng.chance(limited).then(|| {
            let lo = rng.range(-4.0, 4.0);
            let width = if rng.chance(0.1) {
                0.0
            } else if rng.chance(0.1) {
                rng.range(7.0, 20.0)
            } else {
                rng.range(0.0, 4.0)
            };
            JointLimits::new(lo, lo + width).expect("valid limits")
        });
        let angle = rng.range(-PI, PI);
        links.push(match limits {
            Some(lim) => Link::new(l, lim.clamp(angle)).with_limits(lim),
            None => Link::new(l, angle),
        });
    }
    let scale = links.iter().map(|l| l.length).sum::<f64>();
    let base = if rng.chance(0.5) { [0.0, 0.0] } else { [rng.range(-1.0, 1.0) * scale, rng.range(-1.0, 1.0) * scale] };
    let chain = Chain::new(base, &links).expect("valid chain");
    let reach = chain.max_reach();

    // Goals: near or inside the reach, far away, on the base, at a joint-length scale.
    let b = chain.base();
    let dir = rng.range(-PI, PI);
    let (x, y) = match rng.next_u64() % 8 {
        0 => (b.x, b.y),
        1 => {
            let far = log_uniform(rng, 0.5, 99.0);
            (b.x + far * reach * libm::cos(dir), b.y + far * reach * libm::sin(dir))
        }
        2 => {
            let r = chain.lengths()[(rng.next_u64() % n as u64) as usize] * rng.range(0.0, 2.0);
            (b.x + r * libm::cos(dir), b.y + r * libm::sin(dir))
        }
        _ => {
            let r = rng.range(0.0, 1.5) * reach;
            (b.x + r * libm::cos(dir), b.y + r * libm::sin(dir))
        }
    };
    let (x, y) = if x.is_finite() && y.is_finite() { (x, y) } else { (b.x, b.y) };
    let goal = match rng.next_u64() % 4 {
        0 => Goal::with_orientation(x, y, rng.range(-10.0, 10.0)),
        1 if rng.chance(0.2) => Goal::with_orientation(x, y, log_uniform(rng, 3.0, 300.0)),
        _ => Goal::position(x, y),
    }
    .expect("finite goal");

    let method = pick(rng, &Method::ALL);
    let supported: Vec<LimitMode> = LimitMode::ALL.iter().copied().filter(|&m| method.supports(m)).collect();
    let limits = if rng.chance(0.9) { pick(rng, &supported) } else { pick(rng, &LimitMode::ALL) };
    let tolerance_scale = if rng.chance(0.5) { 1.0 } else { reach };
    let opts = SolveOptions {
        method,
        lambda: if rng.chance(0.2) {
            0.0
        } else {
            log_uniform(rng, -4.0, 1.0) * if rng.chance(0.3) { reach } else { 1.0 }
        },
        tolerance: log_uniform(rng, -12.0, -1.0) * tolerance_scale,
        angle_tolerance: log_uniform(rng, -12.0, -1.0),
        orientation_weight: log_uniform(rng, -3.0, 3.0),
        max_iterations: pick(rng, &[0, 1, 2, 10, 50, 100, 200]),
        gain: log_uniform(rng, -3.0, 1.0),
        rates: if rng.chance(0.2) { (0..n).map(|_| rng.range(0.0, 2.0)).collect() } else { Vec::new() },
        max_step: rng.chance(0.7).then(|| log_uniform(rng, -3.0, 1.0)),
        backtrack: if rng.chance(0.3) { 0 } else { (rng.next_u64() % 65) as u32 },
        singular_threshold: if rng.chance(0.2) { 0.0 } else { log_uniform(rng, -12.0, -2.0) },
        stall: rng.chance(0.8).then(|| StallDetection {
            epsilon: if rng.chance(0.2) { 0.0 } else { log_uniform(rng, -12.0, -3.0) },
            window: pick(rng, &[1, 2, 5, 10, 100, 1000, u32::MAX]),
        }),
        record_every: rng.chance(0.3).then(|| 1 + (rng.next_u64() % 20) as u32),
        limits,
        restarts: rng.chance(0.5).then(|| Restarts {
            attempts: 1 + (rng.next_u64() % 3) as u32,
            seed: rng.next_u64(),
            time_budget: None,
        }),
        reach_verdict: rng.chance(0.8),
        closed_form: rng.chance(0.5),
        interrupt: None,
    };
    opts.validate().expect("options within their ranges");

    // Start poses: the chain's, random (maybe outside the limits), or huge.
    let start = match rng.next_u64() % 5 {
        0 => (0..n).map(|_| rng.range(-10.0, 10.0)).collect(),
        1 => {
            (0..n).map(|_| if rng.chance(0.5) { log_uniform(rng, 3.0, 300.0) } else { rng.range(-1.0, 1.0) }).collect()
        }
        _ => chain.start_pose().angles().to_vec(),
    };
    Case { chain, goal, opts, start }
}

/// The library's distance (`attempt.rs`): `√(dx² + dy²)`, by `hypot` where the sum of squares
/// overflows or is subnormal, saturated at `f64::MAX`. `libm`'s `hypot`, as the library's
/// `math` module calls it, so that the two agree bit for bit on every target.
fn distance(d: nalgebra::Vector2<f64>) -> f64 {
    let squared = d.x * d.x + d.y * d.y;
    let r = if squared.is_finite() && squared >= f64::MIN_POSITIVE { squared.sqrt() } else { libm::hypot(d.x, d.y) };
    r.min(f64::MAX)
}

/// Runs one case and checks every invariant; the first broken one, in words.
fn check(case: &Case) -> Result<Option<Outcome>, String> {
    let Case { chain, goal, opts, start } = case;
    let mut solver = Solver::new(opts.clone()).map_err(|e| format!("options rejected: {e}"))?;
    let mut out = Outcome::default();
    match solver.solve_into(chain, start, goal, &mut out) {
        Ok(()) => {}
        Err(SolveError::NoClosedForm { .. }) if opts.method == Method::Analytic => return Ok(None),
        Err(e) => return Err(format!("solve failed: {e}")),
    }
    let n = chain.len();
    let finite = |v: f64| v.is_finite();
    if out.pose.angles().len() != n || !out.pose.angles().iter().copied().all(finite) {
        return Err(format!("angles not finite: {:?}", out.pose.angles()));
    }
    let ee = out.end_effector;
    if ![out.error, out.angle_error, ee.position.x, ee.position.y, ee.orientation].into_iter().all(finite) {
        return Err(format!("numbers not finite: error {} angle_error {} tip {:?}", out.error, out.angle_error, ee));
    }
    // A fresh forward-kinematics pass over the returned angles.
    let fresh = end_effector(chain, out.pose.angles());
    let error = distance(goal.target() - fresh.position);
    let angle_error = goal.orientation().map_or(0.0, |g| wrap_angle(g - fresh.orientation).abs());
    if fresh != ee || error.to_bits() != out.error.to_bits() || angle_error.to_bits() != out.angle_error.to_bits() {
        return Err(format!(
            "reported error {:e} / {:e} at {:?}, forward kinematics gives {error:e} / {angle_error:e} at {fresh:?}",
            out.error, out.angle_error, ee
        ));
    }
    let within = error <= opts.tolerance && angle_error <= opts.angle_tolerance;
    if (out.status == Status::Reached) != within {
        return Err(format!(
            "status {} with error {error:e} (tolerance {:e}), angle error {angle_error:e}",
            out.status, opts.tolerance
        ));
    }
    let outside_region = out.reach_distance.is_some_and(|d| d > opts.tolerance);
    if out.status == Status::Unreachable && !goal.is_out_of_reach(chain, opts.tolerance) && !outside_region {
        return Err("unreachable, but the goal is within reach".to_owned());
    }
    let attempts = 1 + opts.restarts.map_or(0, |r| r.attempts);
    if out.iterations > opts.max_iterations.max(1).saturating_mul(attempts) {
        return Err(format!("{} iterations over a cap of {} × {attempts}", out.iterations, opts.max_iterations));
    }
    let inside = |angles: &[f64]| angles.iter().zip(chain.limits()).all(|(a, lim)| lim.is_none_or(|l| l.contains(*a)));
    if opts.limits != LimitMode::Ignore && !inside(out.pose.angles()) {
        return Err(format!("angles {:?} outside the limits {:?}", out.pose.angles(), chain.limits()));
    }
    for f in out.frames.iter() {
        if !f.angles.iter().copied().all(finite) || !f.joints.iter().all(|p| p.x.is_finite() && p.y.is_finite()) {
            return Err(format!("frame {} not finite", f.iteration));
        }
        if opts.limits != LimitMode::Ignore && !inside(f.angles) {
            return Err(format!("frame {} outside the limits", f.iteration));
        }
        let fk = joint_positions(chain, f.angles);
        if fk.last() != f.joints.last() {
            return Err(format!("frame {}: its joints are not the forward kinematics of its angles", f.iteration));
        }
    }
    // Never worse than where it started (every accepted step of the line search lowers the
    // task error; CCD and FABRIK end on the best pose they visited, the start included), and
    // never worse than its first attempt (restarts end on the best attempt).
    let task_error = |angles: &[f64]| {
        let ee = end_effector(chain, angles);
        let d = distance(goal.target() - ee.position);
        let turn = goal.orientation().map_or(0.0, |g| opts.orientation_weight * wrap_angle(g - ee.orientation));
        d * d + turn * turn
    };
    let final_error = task_error(out.pose.angles());
    let no_worse = |before: f64| final_error <= before * (1.0 + 1e-12) || final_error <= f64::MIN_POSITIVE;
    let descends = opts.backtrack > 0 || matches!(opts.method, Method::CyclicCoordinateDescent | Method::Fabrik);
    if out.status != Status::Reached && descends {
        let mut first = start.clone();
        if opts.limits != LimitMode::Ignore {
            chain.bounds().clamp_into(&mut first);
        }
        let before = task_error(&first);
        if before.is_finite() && !no_worse(before) {
            return Err(format!("ended worse than it started: task error {before:e} -> {final_error:e}"));
        }
    }
    if out.status != Status::Reached && opts.restarts.is_some() {
        let once = SolveOptions { restarts: None, ..opts.clone() };
        let first = Solver::new(once).expect("valid").solve(
            chain,
            &chain.pose_ignoring_limits(start.clone()).expect("finite"),
            goal,
        );
        let before = task_error(first.expect("solved with restarts").pose.angles());
        if !no_worse(before) {
            return Err(format!("ended worse than its first attempt: task error {before:e} -> {final_error:e}"));
        }
    }
    let mut again = Outcome::default();
    Solver::new(opts.clone()).expect("valid").solve_into(chain, start, goal, &mut again).expect("solved once");
    if again != out {
        return Err("the same solve twice differs".to_owned());
    }
    Ok(Some(out))
}

#[derive(Debug, Default, Clone)]
struct Counts {
    cases: [u64; 8],
    reached: [u64; 8],
    failed: [u64; 8],
}

fn method_index(m: Method) -> usize {
    Method::ALL.iter().position(|&x| x == m).expect("every method is in ALL")
}

/// Runs cases `from..to` of `seed` (every `step`-th), printing each failure as a command line.
fn run(seed: u64, from: u64, to: u64, step: u64, verbose: bool) -> Counts {
    let mut counts = Counts::default();
    let mut k = from;
    while k < to {
        let case = random_case(&mut case_rng(seed, k));
        let m = method_index(case.opts.method);
        counts.cases[m] += 1;
        let result = std::panic::catch_unwind(|| check(&case)).unwrap_or_else(|p| {
            let msg = p.downcast_ref::<String>().cloned().or_else(|| p.downcast_ref::<&str>().map(|s| (*s).to_owned()));
            Err(format!("panic: {}", msg.unwrap_or_default()))
        });
        match result {
            Ok(out) => {
                if out.as_ref().is_some_and(|o| o.status == Status::Reached) {
                    counts.reached[m] += 1;
                }
                if verbose {
                    println!("{case:#?}\n{out:#?}");
                }
            }
            Err(why) => {
                counts.failed[m] += 1;
                if verbose {
                    println!("{case:#?}");
                }
                println!(
                    "FAIL {}: {why}\n  reproduce: cargo run --release -p ikarus --example fuzz -- --seed {seed} --case {k}",
                    case.opts.method.name()
                );
            }
        }
        k += step;
    }
    counts
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let flag = |name: &str| args.iter().position(|a| a == name).and_then(|i| args.get(i + 1)).map(|v| v.parse::<u64>());
    let get = |name: &str, default: u64| match flag(name) {
        None => default,
        Some(Ok(v)) => v,
        Some(Err(e)) => {
            eprintln!("{name}: {e}");
            std::process::exit(2);
        }
    };
    let seed = get("--seed", 1);
    if flag("--case").is_some() {
        let k = get("--case", 0);
        let c = run(seed, k, k + 1, 1, true);
        return if c.failed.iter().sum::<u64>() == 0 { ExitCode::SUCCESS } else { ExitCode::FAILURE };
    }
    let cases = get("--cases", 100_000);
    let threads = get("--threads", 1).max(1);
    // Quiet the default panic message: a panic is reported as a failing case.
    std::panic::set_hook(Box::new(|_| {}));
    let began = Instant::now();
    let total = std::thread::scope(|s| {
        let handles: Vec<_> = (0..threads).map(|t| s.spawn(move || run(seed, t, cases, threads, false))).collect();
        handles.into_iter().fold(Counts::default(), |mut acc, h| {
            let c = h.join().expect("a fuzz thread");
            for i in 0..8 {
                acc.cases[i] += c.cases[i];
                acc.reached[i] += c.reached[i];
                acc.failed[i] += c.failed[i];
            }
            acc
        })
    });
    let secs = began.elapsed().as_secs_f64();
    println!("{:<10} {:>9} {:>9} {:>7}", "method", "cases", "reached", "failed");
    for (i, m) in Method::ALL.iter().enumerate() {
        println!("{:<10} {:>9} {:>9} {:>7}", m.name(), total.cases[i], total.reached[i], total.failed[i]);
    }
    let failed: u64 = total.failed.iter().sum();
    println!("{cases} cases of seed {seed} on {threads} thread(s) in {secs:.1} s: {failed} failed");
    if failed == 0 { ExitCode::SUCCESS } else { ExitCode::FAILURE }
}
