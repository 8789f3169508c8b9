//! The kept eigen-decomposition of [`Dynamic`]: used again only while `A` is unchanged.

use super::*;
use crate::rng::SplitMix64;

/// A `Dynamic` of `m` rows and `n` dense columns with a seeded random `J` and `e`.
fn random(rng: &mut SplitMix64, m: usize, n: usize) -> Dynamic {
    let mut d = Dynamic::default();
    d.shape(n, m, 0);
    d.nz_start = (0..=n).map(|j| j * m).collect();
    d.nz_rows = (0..n).flat_map(|_| 0..m).collect();
    for v in d.jacobian.iter_mut().chain(d.e.iter_mut()) {
        *v = rng.range(-1.0, 1.0);
    }
    d.reset_task();
    d
}

/// The step of the task's rows with column factors `k`, Levenberg–Marquardt with a damping
/// so small that it takes the eigen-decomposition's pseudo-inverse.
fn step(d: &mut Dynamic, k: &[f64]) -> Vec<f64> {
    for (i, &f) in k.iter().enumerate() {
        d.set_weighted(i, f);
    }
    d.gram(Columns::Weighted);
    let mut out = vec![0.0; k.len()];
    d.method_step(Columns::Weighted, Rule::LevenbergMarquardt, &SolveOptions::default(), 1e-30, &mut out);
    out
}

#[test]
fn a_changed_a_is_decomposed_again() {
    let mut rng = SplitMix64(27);
    for (m, n) in [(4, 3), (6, 5), (8, 8)] {
        let mut kept = random(&mut rng, m, n);
        let mut fresh = kept.clone();
        let free = vec![1.0; n];
        let first = step(&mut kept, &free);
        assert!(kept.eigen_of.is_some(), "{m}×{n}: the pseudo-inverse's path was taken");
        // The same A again: the kept decomposition, the same bits.
        assert_eq!(step(&mut kept, &free), first);
        // Joint 1 locked: A changes, and the step is that of a decomposition of the new A.
        let mut locked = free.clone();
        locked[1] = 0.0;
        let again = step(&mut kept, &locked);
        let want = step(&mut fresh, &locked);
        assert_eq!(again[1], 0.0);
        for (a, w) in again.iter().zip(&want) {
            assert!((a - w).abs() <= 1e-9 * (1.0 + w.abs()), "{m}×{n}: {again:?} against {want:?}");
        }
        assert!(again.iter().zip(&first).any(|(a, f)| (a - f).abs() > 1e-6), "{m}×{n}: locking changed the step");
    }
}
