//! In-place kernels on small dense symmetric matrices (column-major `k × k` in a slice), for
//! the [`Dynamic`](super::dynamic::Dynamic) task space: nalgebra's decompositions of dynamic
//! size allocate their results, and these run every iteration of a skeleton solve.

use crate::math;

/// Solves `(A + shift·I) y = v` for symmetric `A` by a Cholesky factorisation into `l`
/// (`k × k`, overwritten; the factor is stored by rows). Returns `false`, leaving `y`
/// unspecified, if `A + shift·I` is not positive definite (to rounding).
///
/// The factorisation works on `A`'s envelope: row `r` of the factor is zero left of row `r`'s
/// first nonzero entry of `A` (`first`, work space of `k`), so a block-diagonal `A` — a rig's
/// limbs that share no bone — costs only its blocks.
pub(super) fn cholesky_solve(
    k: usize,
    a: &[f64],
    shift: f64,
    v: &[f64],
    l: &mut [f64],
    first: &mut [usize],
    y: &mut [f64],
) -> bool {
    let (a, l, v, y, first) = (&a[..k * k], &mut l[..k * k], &v[..k], &mut y[..k], &mut first[..k]);
    for (r, f) in first.iter_mut().enumerate() {
        *f = (0..r).find(|&c| a[r + c * k] != 0.0).unwrap_or(r);
    }
    // L Lᵀ = A + shift I: row r of L in l[r k .. r k + r + 1], zero before first[r].
    for r in 0..k {
        let fr = first[r];
        for c in fr..=r {
            let mut s = a[r + c * k];
            for p in fr.max(first[c])..c {
                s -= l[r * k + p] * l[c * k + p];
            }
            if c < r {
                l[r * k + c] = s / l[c * k + c];
            } else {
                let d = s + shift;
                if !(d > 0.0 && d.is_finite()) {
                    return false;
                }
                l[r * k + r] = d.sqrt();
            }
        }
    }
    // L z = v, then Lᵀ y = z.
    for r in 0..k {
        let mut s = v[r];
        for p in first[r]..r {
            s -= l[r * k + p] * y[p];
        }
        y[r] = s / l[r * k + r];
    }
    for r in (0..k).rev() {
        y[r] /= l[r * k + r];
        let yr = y[r];
        for p in first[r]..r {
            y[p] -= l[r * k + p] * yr;
        }
    }
    true
}

/// The most Jacobi sweeps [`symmetric_eigen`] runs; each sweep cuts the off-diagonal mass by a
/// large factor (quadratically once small), so a few suffice for any size used here.
const MAX_SWEEPS: usize = 60;

/// Eigen-decomposition of symmetric `A` by cyclic Jacobi rotations: `values[i]` and column `i`
/// of `vectors` (`k × k`), with `w` (`k × k`) as work space. Bounded by [`MAX_SWEEPS`] sweeps.
pub(super) fn symmetric_eigen(k: usize, a: &[f64], w: &mut [f64], values: &mut [f64], vectors: &mut [f64]) {
    w[..k * k].copy_from_slice(&a[..k * k]);
    for c in 0..k {
        for r in 0..k {
            vectors[r + c * k] = if r == c { 1.0 } else { 0.0 };
        }
    }
    let scale: f64 = w[..k * k].iter().fold(0.0, |m, x| m.max(x.abs()));
    if scale > 0.0 && scale.is_finite() {
        for _ in 0..MAX_SWEEPS {
            let mut off = 0.0;
            for c in 0..k {
                for r in 0..c {
                    off += w[r + c * k] * w[r + c * k];
                }
            }
            if off.sqrt() <= 1e-15 * scale || !off.is_finite() {
                break;
            }
            for p in 0..k {
                for q in p + 1..k {
                    let apq = w[p + q * k];
                    if apq == 0.0 {
                        continue;
                    }
                    let (app, aqq) = (w[p + p * k], w[q + q * k]);
                    let theta = (aqq - app) / (2.0 * apq);
                    let t = theta.signum() / (theta.abs() + math::hypot(theta, 1.0));
                    let t = if theta == 0.0 { 1.0 } else { t };
                    let c = 1.0 / math::hypot(t, 1.0);
                    let s = t * c;
                    // W ← Jᵀ W J on columns p and q, then rows p and q; V ← V J.
                    rotate_columns(&mut w[..k * k], k, p, q, c, s);
                    for col in w[..k * k].chunks_exact_mut(k) {
                        let (wpi, wqi) = (col[p], col[q]);
                        col[p] = c * wpi - s * wqi;
                        col[q] = s * wpi + c * wqi;
                    }
                    rotate_columns(&mut vectors[..k * k], k, p, q, c, s);
                }
            }
        }
    }
    for i in 0..k {
        values[i] = w[i + i * k];
    }
}

/// Columns `p < q` of the column-major `m` (`k` rows) turned by the rotation `(c, s)`: column
/// `p` becomes `c·p − s·q`, column `q` becomes `s·p + c·q`. (On the two columns as slices, so
/// that the loop runs without index checks; the same operations as element by element.)
#[inline]
fn rotate_columns(m: &mut [f64], k: usize, p: usize, q: usize, c: f64, s: f64) {
    let (left, right) = m.split_at_mut(q * k);
    for (a, b) in left[p * k..(p + 1) * k].iter_mut().zip(&mut right[..k]) {
        let (u, v) = (*a, *b);
        *a = c * u - s * v;
        *b = s * u + c * v;
    }
}

/// `y = A⁺ v` from `A`'s eigen-decomposition, dropping eigenvalues at or below `floor`.
pub(super) fn pinv_apply(k: usize, values: &[f64], vectors: &[f64], floor: f64, v: &[f64], y: &mut [f64]) {
    y[..k].fill(0.0);
    for (i, &mu) in values[..k].iter().enumerate() {
        if mu > floor {
            let u = &vectors[i * k..(i + 1) * k];
            let f = dot(u, &v[..k]) / mu;
            for (yr, ur) in y[..k].iter_mut().zip(u) {
                *yr += f * ur;
            }
        }
    }
}

/// `y = α v` with `α = ⟨v, A v⟩ / ⟨A v, A v⟩` (the Jacobian transpose's error-minimising
/// length), computed on `A` and `v` scaled to order one so that nothing overflows; `y = 0` when
/// `A v = 0` or nothing is finite. `av` is work space of `k`.
pub(super) fn transpose_apply(k: usize, a: &[f64], v: &[f64], av: &mut [f64], y: &mut [f64]) {
    let s = a[..k * k].iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let m = v[..k].iter().fold(0.0f64, |m, x| m.max(x.abs()));
    y[..k].fill(0.0);
    if !(s > 0.0 && s.is_finite() && m > 0.0 && m.is_finite()) {
        return;
    }
    for r in 0..k {
        av[r] = (0..k).map(|c| (a[r + c * k] / s) * (v[c] / m)).sum();
    }
    let denom = dot(&av[..k], &av[..k]);
    if denom > 0.0 {
        let num: f64 = (0..k).map(|r| (v[r] / m) * av[r]).sum();
        let alpha = num / denom / s;
        for r in 0..k {
            y[r] = alpha * v[r];
        }
    }
}

/// `a · b`.
#[inline]
pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;
    use nalgebra::DMatrix;

    fn random_spd(rng: &mut SplitMix64, k: usize, rank: usize) -> DMatrix<f64> {
        let b = DMatrix::from_fn(k, rank, |_, _| rng.range(-1.0, 1.0));
        &b * b.transpose()
    }

    #[test]
    fn cholesky_solves_shifted_systems() {
        let mut rng = SplitMix64(3);
        for k in 1..12 {
            let a = random_spd(&mut rng, k, k);
            let v: Vec<f64> = (0..k).map(|_| rng.range(-1.0, 1.0)).collect();
            let (mut l, mut y) = (vec![0.0; k * k], vec![0.0; k]);
            let mut first = vec![0; k];
            assert!(cholesky_solve(k, a.as_slice(), 0.1, &v, &mut l, &mut first, &mut y));
            let shifted = &a + DMatrix::identity(k, k) * 0.1;
            let r = shifted * nalgebra::DVector::from_column_slice(&y) - nalgebra::DVector::from_column_slice(&v);
            assert!(r.norm() < 1e-12, "k {k}: {}", r.norm());
        }
        // Not positive definite: refused.
        let a = [-1.0];
        assert!(!cholesky_solve(1, &a, 0.0, &[1.0], &mut [0.0], &mut [0], &mut [0.0]));
    }

    /// A block-diagonal matrix (its blocks interleaved with zeros) is solved as exactly as a
    /// dense one.
    #[test]
    fn cholesky_on_an_envelope() {
        let mut rng = SplitMix64(4);
        let k = 9;
        let mut a = random_spd(&mut rng, k, k);
        for r in 0..k {
            for c in 0..k {
                if (r < 4) != (c < 4) || (r >= 4 && c >= 4 && (r < 6) != (c < 6)) {
                    a[(r, c)] = 0.0;
                }
            }
        }
        let v: Vec<f64> = (0..k).map(|_| rng.range(-1.0, 1.0)).collect();
        let (mut l, mut y, mut first) = (vec![f64::NAN; k * k], vec![0.0; k], vec![0; k]);
        assert!(cholesky_solve(k, a.as_slice(), 0.01, &v, &mut l, &mut first, &mut y));
        assert_eq!(&first[..], &[0, 0, 0, 0, 4, 4, 6, 6, 6]);
        let shifted = &a + DMatrix::identity(k, k) * 0.01;
        let r = shifted * nalgebra::DVector::from_column_slice(&y) - nalgebra::DVector::from_column_slice(&v);
        assert!(r.norm() < 1e-12, "{}", r.norm());
    }

    #[test]
    fn jacobi_matches_nalgebra_and_pinv_drops_null_directions() {
        let mut rng = SplitMix64(5);
        for k in 1..14 {
            let rank = 1 + (k / 2);
            let a = random_spd(&mut rng, k, rank);
            let (mut w, mut vals, mut vecs) = (vec![0.0; k * k], vec![0.0; k], vec![0.0; k * k]);
            symmetric_eigen(k, a.as_slice(), &mut w, &mut vals, &mut vecs);
            let v = DMatrix::from_column_slice(k, k, &vecs);
            let rebuilt = &v * DMatrix::from_diagonal(&nalgebra::DVector::from_column_slice(&vals)) * v.transpose();
            assert!((rebuilt - &a).norm() < 1e-12, "k {k}");
            // A⁺ v against nalgebra's pseudo-inverse.
            let rhs: Vec<f64> = (0..k).map(|_| rng.range(-1.0, 1.0)).collect();
            let mut y = vec![0.0; k];
            pinv_apply(k, &vals, &vecs, 1e-9, &rhs, &mut y);
            let want = a.clone().pseudo_inverse(1e-9).unwrap() * nalgebra::DVector::from_column_slice(&rhs);
            let got = nalgebra::DVector::from_column_slice(&y);
            assert!((got - want).norm() < 1e-8, "k {k}");
        }
    }

    #[test]
    fn transpose_length_minimises_the_linear_error() {
        let mut rng = SplitMix64(9);
        let k = 5;
        let a = random_spd(&mut rng, k, k);
        let v: Vec<f64> = (0..k).map(|_| rng.range(-1.0, 1.0)).collect();
        let (mut av, mut y) = (vec![0.0; k], vec![0.0; k]);
        transpose_apply(k, a.as_slice(), &v, &mut av, &mut y);
        let vv = nalgebra::DVector::from_column_slice(&v);
        let alpha = y[0] / v[0];
        let res = |t: f64| (&vv - t * (&a * &vv)).norm_squared();
        assert!(res(alpha) <= res(alpha * 1.01) && res(alpha) <= res(alpha * 0.99));
    }
}
