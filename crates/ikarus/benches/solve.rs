//! Time per solve for each method on three arms: the seed's 3-link arm (3, 2, 1), 7 links of 1.0
//! and 20 links of 0.3, every joint starting at 5°.
//!
//! Each arm gets 64 goals made reachable by construction (the tip of a deterministic
//! pseudo-random pose). One `Solver` and one `Outcome` are reused through `solve_into`; every
//! benchmark iteration solves the next goal in the cycle from the start pose to tolerance 1e-6,
//! so the reported time is the mean time of one solve over the goal set. Groups are named
//! `solve/<arm>/<method>`. Before measuring, each group prints to stderr how many of its goals
//! are reached and the mean number of iterations, to read the times against.
//!
//! `cargo bench -p ikarus --bench solve`

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use ikarus::kinematics::end_effector;
use ikarus::{Chain, Goal, Method, Outcome, SolveOptions, Solver, Status};

#[path = "../tests/common/mod.rs"]
mod common;

use common::SplitMix64;

const GOALS: usize = 64;

use common::fixtures::arm;

/// Tips of `GOALS` pseudo-random poses (every joint uniform in (−π, π)): reachable goals.
fn goals(chain: &Chain, seed: u64) -> Vec<Goal> {
    let mut rng = SplitMix64(seed);
    (0..GOALS)
        .map(|_| {
            let angles: Vec<f64> =
                (0..chain.len()).map(|_| rng.range(-std::f64::consts::PI, std::f64::consts::PI)).collect();
            let p = end_effector(chain, &angles).position;
            Goal::position(p.x, p.y).expect("finite tip")
        })
        .collect()
}

fn bench_solve(c: &mut Criterion) {
    let arms = [("seed", arm(&[3.0, 2.0, 1.0])), ("7x1.0", arm(&[1.0; 7])), ("20x0.3", arm(&[0.3; 20]))];
    for (name, chain) in &arms {
        let goals = goals(chain, 0xBE7C_0000 + chain.len() as u64);
        let start = chain.start_pose().angles();
        // The closed form has its own shapes (none of these position goals); `ikarus bench`
        // times it where it applies.
        for method in Method::ALL.into_iter().filter(|&m| m != Method::Analytic) {
            let opts = SolveOptions { method, tolerance: 1e-6, ..SolveOptions::default() };
            let mut solver = Solver::new(opts).expect("valid options");
            let mut out = Outcome::default();

            let (mut reached, mut iterations) = (0, 0u64);
            for goal in &goals {
                solver.solve_into(chain, start, goal, &mut out).expect("valid input");
                reached += usize::from(out.status == Status::Reached);
                iterations += u64::from(out.iterations);
            }
            eprintln!(
                "solve/{name}/{}: {reached}/{GOALS} reached, {:.1} iterations per solve",
                method.name(),
                iterations as f64 / GOALS as f64
            );

            let mut group = c.benchmark_group(format!("solve/{name}/{}", method.name()));
            group.sample_size(30).measurement_time(Duration::from_secs(3)).warm_up_time(Duration::from_secs(1));
            let mut next = 0;
            group.bench_function("per_solve", |b| {
                b.iter(|| {
                    let goal = &goals[next];
                    next = (next + 1) % GOALS;
                    solver.solve_into(chain, start, black_box(goal), &mut out).expect("valid input");
                    black_box(out.error)
                });
            });
            group.finish();
        }
    }
}

criterion_group!(benches, bench_solve);
criterion_main!(benches);
