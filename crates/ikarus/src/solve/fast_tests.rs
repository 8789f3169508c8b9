//! The fast path's own tests: every way out of it, and every lane type ending every goal alike
//! (the comparison with the general loop and with `solve_into` is in `chain_model.rs`).

use super::*;

/// The goals the bit-for-bit tests (in `model.rs`) use exercise every way out of the fast
/// path: reached, at the iteration cap, and handed to the general loop mid-attempt.
#[test]
fn every_way_out_is_taken() {
    let mut rng = crate::rng::SplitMix64(5);
    let chain = crate::fixtures::random_chain(&mut rng, 20, false);
    let reach = chain.max_reach();
    let opts = SolveOptions { limits: LimitMode::Ignore, ..SolveOptions::default() };
    let goals: Vec<(usize, f64, f64)> = (0..400)
        .map(|i| match i % 4 {
            0 => (i, 3.0 * reach * (rng.unit() - 0.5), 3.0 * reach * (rng.unit() - 0.5)),
            _ => {
                let g = crate::fixtures::random_goal(&mut rng, &chain, false);
                (i, g.target().x, g.target().y)
            }
        })
        .collect();
    let mut seen = std::collections::BTreeMap::new();
    let mut buffers = Buffers::<Quad>::default();
    let mut emitted = vec![0; goals.len()];
    let start = chain.start_pose().angles().to_vec();
    run(&chain, &opts, opts.max_iterations, &start, &mut buffers, goals.iter().copied(), |i, end| {
        emitted[i] += 1;
        *seen.entry(end.status.map_or("resume", Status::as_str)).or_insert(0) += 1;
    });
    assert!(emitted.iter().all(|&e| e == 1), "every goal once");
    assert!(seen.get("reached").copied().unwrap_or(0) >= 290, "{seen:?}");
    assert!(seen.contains_key("resume"), "{seen:?}");
    let capped = SolveOptions { max_iterations: 3, ..opts };
    seen.clear();
    run(&chain, &capped, capped.max_iterations, &start, &mut buffers, goals.iter().copied(), |_, end| {
        *seen.entry(end.status.map_or("resume", Status::as_str)).or_insert(0) += 1;
    });
    assert!(seen.contains_key("iteration_limit"), "{seen:?}");
}

/// Everything a goal's end hands out, as bits.
fn ends<L: Lanes>(chain: &Chain, opts: &SolveOptions, goals: &[(usize, f64, f64)]) -> Vec<Vec<u64>> {
    let mut buffers = Buffers::<L>::default();
    let mut out = vec![Vec::new(); goals.len()];
    let start = chain.start_pose().angles().to_vec();
    run(chain, opts, opts.max_iterations, &start, &mut buffers, goals.iter().copied(), |i, end| {
        let status = end.status.map_or(u64::MAX, |s| s as u64);
        let numbers = [end.error, end.tip.0, end.tip.1, end.phi].into_iter().chain(end.angles.iter().copied());
        out[i] = [status, u64::from(end.iterations)].into_iter().chain(numbers.map(f64::to_bits)).collect();
    });
    out
}

/// The explicit AVX lanes in two groups (what `solve_batch` runs on an AVX2 processor), one
/// group of them, the portable `Quad` lanes (what it runs elsewhere) and two groups of those
/// end every goal alike, bit for bit: one goal per lane or many through the same lane (lanes
/// that finish early take the next goal), goals out of reach among them, batches shorter than
/// one group and tails that do not fill the lanes (300 and 7 goals).
#[cfg(target_arch = "x86_64")]
#[test]
fn avx_and_portable_lanes_end_every_goal_alike() {
    if !std::arch::is_x86_feature_detected!("avx2") {
        return;
    }
    let mut rng = crate::rng::SplitMix64(17);
    for links in [3, 7, 20] {
        let chain = crate::fixtures::random_chain(&mut rng, links, false);
        let reach = chain.max_reach();
        let all: Vec<(usize, f64, f64)> =
            (0..300).map(|i| (i, 2.2 * reach * (rng.unit() - 0.5), 2.2 * reach * (rng.unit() - 0.5))).collect();
        let outside = all.iter().filter(|&&(_, x, y)| crate::math::distance(x, y) > reach).count();
        assert!(outside > 30, "{outside} goals out of reach");
        for opts in [
            SolveOptions { limits: LimitMode::Ignore, ..SolveOptions::default() },
            SolveOptions {
                limits: LimitMode::Ignore,
                max_iterations: 5,
                max_step: Some(0.1),
                ..SolveOptions::default()
            },
        ] {
            for goals in [&all[..], &all[..7]] {
                let quad = ends::<Quad>(&chain, &opts, goals);
                assert!(quad.iter().all(|e| !e.is_empty()), "every goal ends once");
                assert_eq!(ends::<Pair<Avx>>(&chain, &opts, goals), quad, "{links} links, two groups");
                assert_eq!(ends::<Avx>(&chain, &opts, goals), quad, "{links} links");
                assert_eq!(ends::<Pair<Quad>>(&chain, &opts, goals), quad, "{links} links, two quads");
            }
        }
    }
}
