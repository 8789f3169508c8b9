//! [`Dynamic`]: a skeleton's task space — `m` stacked rows of any number of effectors, in two
//! priority levels — with the step rules of the chain's `Fixed3` on `m × m` matrices
//! factorised in place ([`super::kernels`]), so that a skeleton's iterations allocate nothing.
//!
//! Rows `0..primary` are the first level (pins and primary goals), rows `primary..m` the
//! second. With one level the rules are the chain's: `Δθ = Wᵀ y` with `y` from `A = W Wᵀ`
//! (`W` the Jacobian, columns weighted by the limit mode). With two, the step is the classic
//! task-priority one (Nakamura, Hanafusa & Yoshikawa 1987; Siciliano & Slotine 1991):
//!
//! ```text
//! Δθ₁ = rule(W₁, e₁),   P₁ = I − W₁ᵀ A₁⁺ W₁,   r₂ = e₂ − W₂ Δθ₁,
//! Δθ  = Δθ₁ + P₁ W₂ᵀ (W₂ P₁ W₂ᵀ + λ² I)⁻¹ r₂,
//! ```
//!
//! so the secondary goals move only in the null space of the first level (to first order they
//! never pull a pin or a primary goal), damped like the rule (λ² = μ for Levenberg–Marquardt,
//! the rule's λ for DLS and SDLS, none for the pseudoinverse; the transpose rule takes its
//! error-minimising length on `W₂ P₁`).

use nalgebra::{DMatrix, DVector};

use super::kernels::{cholesky_solve, dot, pinv_apply, symmetric_eigen, transpose_apply};
use super::{Algebra, Columns};
use crate::math;
use crate::solve::SolveOptions;
use crate::solve::step::Rule;

/// SDLS's bound on any joint change in one step, radians (Buss & Kim's γ_max).
const GAMMA_MAX: f64 = std::f64::consts::FRAC_PI_4;

/// A skeleton's task-space state (see the [module docs](self)).
#[derive(Debug, Clone, Default)]
pub(in crate::solve) struct Dynamic {
    /// The task error, `m` rows.
    pub(in crate::solve) e: DVector<f64>,
    /// `J`, `m × n`, rows scaled as `e`'s.
    pub(in crate::solve) jacobian: DMatrix<f64>,
    /// Rows of the first priority level (the rest are the second).
    pub(in crate::solve) primary: usize,
    /// Each effector's row count (2, or 3 with an orientation), in row order: SDLS's blocks.
    pub(in crate::solve) blocks: Vec<usize>,
    weighted: DMatrix<f64>,
    task: DVector<f64>,
    predicted: DVector<f64>,
    /// `A = W Wᵀ`, `m × m` column-major.
    a: Vec<f64>,
    /// Work: a copy of a diagonal block, factors, eigenvectors (`m × m` each).
    block: Vec<f64>,
    factor: Vec<f64>,
    vectors: Vec<f64>,
    values: Vec<f64>,
    /// Work vectors of `m`.
    y: Vec<f64>,
    first: Vec<usize>,
    t: Vec<f64>,
    r: Vec<f64>,
    /// `P₁ W₂ᵀ`, `n × (m − primary)` column-major.
    k: Vec<f64>,
    /// The longest secondary error one step works on (see `secondary_step`).
    pub(in crate::solve) secondary_reach: f64,
    /// The first level's weight in the merit ([`primary_merit`]).
    pub(in crate::solve) primary_merit: f64,
    /// The rows where column `j` of `J` may be nonzero (the rows of the effectors whose path
    /// holds bone `j`), ascending: `nz_rows[nz_start[j]..nz_start[j + 1]]`.
    pub(in crate::solve) nz_start: Vec<usize>,
    pub(in crate::solve) nz_rows: Vec<usize>,
    /// Whether `a` holds `Σ gram_kᵢ² Jᵢ Jᵢᵀ` for the current `J` (cleared with each new `J`).
    pub(in crate::solve) gram_valid: bool,
    gram_k: Vec<f64>,
    pending_k: Vec<f64>,
    /// The eigen-decomposition of `A`'s leading `k × k` block (`eigen_of == Some(k)`), kept
    /// while `A` is unchanged: Levenberg–Marquardt's retries, a step tried again without the
    /// rest pose's pull and the second level's `A₁⁺` ask for it again on the same `A`.
    eigen_of: Option<usize>,
    eigen_values: Vec<f64>,
    eigen_vectors: Vec<f64>,
}

/// The weight of the first level's squared error in the line search's merit when a task has
/// two levels: `1 / tolerance²`, at least 10⁶. A step may then trade a secondary goal's unit of
/// squared error for no more than a tolerance of primary error, so the first level ends within
/// its tolerance whatever the second asks (the projected step costs it nothing to first order;
/// this guards the second-order rest).
pub(in crate::solve) fn primary_merit(tolerance: f64) -> f64 {
    (1.0 / (tolerance * tolerance)).max(1e6)
}

/// The merit of squared errors `first` (first level) and `second`: their sum, the first
/// weighted by `weight` when there are two `levels`.
pub(in crate::solve) fn merit_of(first: f64, second: f64, levels: bool, weight: f64) -> f64 {
    if levels { weight * first + second } else { first + second }
}

impl Dynamic {
    /// Sizes every buffer for `n` joints and `m` rows, the first `primary` of the first level,
    /// and zeroes `J` and the weighted `J` (only the rows of [`Dynamic::nz_rows`] are written
    /// after that).
    pub(in crate::solve) fn shape(&mut self, n: usize, m: usize, primary: usize) {
        if self.jacobian.shape() != (m, n) {
            self.jacobian = DMatrix::zeros(m, n);
            self.weighted = DMatrix::zeros(m, n);
        } else {
            self.jacobian.fill(0.0);
            self.weighted.fill(0.0);
        }
        for v in [&mut self.e, &mut self.task, &mut self.predicted] {
            if v.len() != m {
                *v = DVector::zeros(m);
            }
        }
        for v in [&mut self.a, &mut self.block, &mut self.factor, &mut self.vectors, &mut self.eigen_vectors] {
            v.resize(m * m, 0.0);
        }
        for v in [&mut self.values, &mut self.eigen_values, &mut self.y, &mut self.t, &mut self.r] {
            v.resize(m, 0.0);
        }
        self.first.resize(m, 0);
        self.gram_k.resize(n, 1.0);
        self.pending_k.resize(n, 1.0);
        self.gram_valid = false;
        self.eigen_of = None;
        self.k.resize(n * m, 0.0);
        self.primary = if primary == 0 { m } else { primary };
    }

    /// `Σ v²`, the first level's rows weighted by `primary_merit` when there are two levels
    /// (the model's trial error weighs its rows the same way: [`merit_of`]).
    fn merit(&self, v: &[f64]) -> f64 {
        let (first, second) = v.split_at(self.primary);
        let f: f64 = first.iter().map(|x| x * x).sum();
        let s: f64 = second.iter().map(|x| x * x).sum();
        merit_of(f, s, !second.is_empty(), self.primary_merit)
    }

    /// Fills `eigen_values` and `eigen_vectors` with the eigen-decomposition of `A`'s leading
    /// `k × k` block, unless they already hold it for this `A`.
    fn leading_eigen(&mut self, k: usize) {
        if self.eigen_of == Some(k) {
            return;
        }
        let m = self.e.len();
        for c in 0..k {
            for r in 0..k {
                self.block[r + c * k] = self.a[r + c * m];
            }
        }
        symmetric_eigen(k, &self.block[..k * k], &mut self.factor, &mut self.eigen_values, &mut self.eigen_vectors);
        self.eigen_of = Some(k);
    }

    /// `y = rule(A_sub, v)` on the leading `k × k` block of `A` (copied to `self.block`), into
    /// `self.y`. SDLS is handled by the caller (it works in joint space).
    fn task_step(&mut self, k: usize, rule: Rule, opts: &SolveOptions, mu: f64, v_from_task: bool) {
        let m = self.e.len();
        for c in 0..k {
            for r in 0..k {
                self.block[r + c * k] = self.a[r + c * m];
            }
        }
        let v: &[f64] = if v_from_task { &self.task.as_slice()[..k] } else { &self.r[..k] };
        let (block, y) = (&self.block[..k * k], &mut self.y[..k]);
        let shift = match rule {
            Rule::Transpose => {
                transpose_apply(k, block, v, &mut self.t, y);
                return;
            }
            Rule::PseudoInverse => None,
            Rule::DampedLeastSquares | Rule::SelectivelyDamped => Some(opts.lambda * opts.lambda),
            Rule::LevenbergMarquardt => Some(mu),
        };
        let trace: f64 = (0..k).map(|i| block[i + i * k]).sum();
        if let Some(shift) = shift {
            if shift > 1e-12 * trace && cholesky_solve(k, block, shift, v, &mut self.factor, &mut self.first, y) {
                return;
            }
        }
        self.leading_eigen(k);
        let floor = opts.singular_threshold * opts.singular_threshold;
        let v: &[f64] = if v_from_task { &self.task.as_slice()[..k] } else { &self.r[..k] };
        pinv_apply(k, &self.eigen_values, &self.eigen_vectors, floor, v, &mut self.y[..k]);
    }

    /// Buss & Kim's selectively damped step of the leading `k` rows into `out` (see `sdls.rs`:
    /// the same rule, with the norms taken per effector block).
    fn sdls_step(&mut self, columns: Columns, k: usize, threshold: f64, out: &mut [f64]) {
        self.leading_eigen(k);
        out.fill(0.0);
        let floor = threshold * threshold;
        let blocks = &self.blocks;
        let block_norm = |v: &dyn Fn(usize) -> f64| {
            let mut row = 0;
            let mut sum = 0.0;
            for &b in blocks {
                if row + 2 > k {
                    break;
                }
                sum += math::hypot(v(row), v(row + 1));
                if b == 3 && row + 2 < k {
                    sum += v(row + 2).abs();
                }
                row += b;
            }
            sum
        };
        let w = columns.pick(&self.jacobian, &self.weighted);
        for i in 0..k {
            let mu = self.eigen_values[i];
            if mu <= floor {
                continue;
            }
            let u = &self.eigen_vectors[i * k..(i + 1) * k];
            let alpha = dot(u, &self.task.as_slice()[..k]);
            if alpha == 0.0 {
                continue;
            }
            let sigma = mu.sqrt();
            let (mut mm, mut largest) = (0.0, 0.0f64);
            for col in w.column_iter() {
                let v = dot(&col.as_slice()[..k], u) / sigma;
                mm += v.abs() * block_norm(&|r| col[r]);
                largest = largest.max((alpha * v / sigma).abs());
            }
            mm /= sigma;
            let nn = block_norm(&|r| u[r]);
            let gamma = if mm > nn { GAMMA_MAX * nn / mm } else { GAMMA_MAX };
            let shrink = if largest > gamma { gamma / largest } else { 1.0 };
            for (o, col) in out.iter_mut().zip(w.column_iter()) {
                *o += shrink * alpha * dot(&col.as_slice()[..k], u) / mu;
            }
        }
        let largest = out.iter().fold(0.0f64, |m, x| m.max(x.abs()));
        if largest > GAMMA_MAX {
            let shrink = GAMMA_MAX / largest;
            out.iter_mut().for_each(|x| *x *= shrink);
        }
    }

    /// The second level: `out += P₁ W₂ᵀ y₂` with `y₂` the damped solve of `W₂ P₁ W₂ᵀ` against
    /// `r₂ = task₂ − W₂ out` (see the [module docs](self)).
    fn secondary_step(&mut self, columns: Columns, rule: Rule, opts: &SolveOptions, mu: f64, out: &mut [f64]) {
        let m = self.e.len();
        let p = self.primary;
        let m2 = m - p;
        let n = out.len();
        // A₁⁺ by eigen-decomposition of the leading block.
        self.leading_eigen(p);
        let floor = opts.singular_threshold * opts.singular_threshold;
        let w = columns.pick(&self.jacobian, &self.weighted);
        // K = P₁ W₂ᵀ, one column per secondary row.
        for s in 0..m2 {
            let col = &mut self.k[s * n..(s + 1) * n];
            for (j, c) in col.iter_mut().enumerate() {
                *c = w[(p + s, j)];
            }
            for r in 0..p {
                self.t[r] = (0..n).map(|j| w[(r, j)] * col[j]).sum();
            }
            pinv_apply(p, &self.eigen_values, &self.eigen_vectors, floor, &self.t, &mut self.y);
            for (j, c) in col.iter_mut().enumerate() {
                *c -= (0..p).map(|r| w[(r, j)] * self.y[r]).sum::<f64>();
            }
        }
        // r₂ = task₂ − W₂ Δθ₁; G = W₂ K.
        for s in 0..m2 {
            let moved: f64 = (0..n).map(|j| w[(p + s, j)] * out[j]).sum();
            self.r[s] = self.task[p + s] - moved;
        }
        // A far secondary goal (one out of reach, say) asks for a long step that the cap on
        // the whole step would then cut, primary part and all: its error is clamped to
        // `secondary_reach`, as Buss & Kim clamp a task error far from the goal.
        let norm = dot(&self.r[..m2], &self.r[..m2]).sqrt();
        if norm > self.secondary_reach && norm.is_finite() {
            let f = self.secondary_reach / norm;
            self.r[..m2].iter_mut().for_each(|x| *x *= f);
        }
        for c in 0..m2 {
            for r in 0..m2 {
                self.block[r + c * m2] = (0..n).map(|j| w[(p + r, j)] * self.k[c * n + j]).sum();
            }
        }
        let g = &self.block[..m2 * m2];
        let y = &mut self.y[..m2];
        let shift = match rule {
            Rule::Transpose => {
                transpose_apply(m2, g, &self.r, &mut self.t, y);
                None
            }
            Rule::PseudoInverse => Some(0.0),
            Rule::DampedLeastSquares | Rule::SelectivelyDamped => Some(opts.lambda * opts.lambda),
            Rule::LevenbergMarquardt => Some(mu),
        };
        if let Some(shift) = shift {
            let trace: f64 = (0..m2).map(|i| g[i + i * m2]).sum();
            if !(shift > 1e-12 * trace && cholesky_solve(m2, g, shift, &self.r, &mut self.factor, &mut self.first, y)) {
                symmetric_eigen(m2, g, &mut self.factor, &mut self.values, &mut self.vectors);
                pinv_apply(m2, &self.values, &self.vectors, floor, &self.r, y);
            }
        }
        for s in 0..m2 {
            let ys = self.y[s];
            for (o, kj) in out.iter_mut().zip(&self.k[s * n..(s + 1) * n]) {
                *o += kj * ys;
            }
        }
    }
}

impl Algebra for Dynamic {
    fn fit(&mut self, _n: usize) {
        // Sized by `shape`, which knows the rows.
    }

    #[inline]
    fn e_norm_squared(&self) -> f64 {
        self.merit(self.e.as_slice())
    }

    #[inline]
    fn e_norm(&self) -> f64 {
        self.e.norm()
    }

    #[inline]
    fn column_dot_e(&self, i: usize) -> f64 {
        self.jacobian.column(i).dot(&self.e)
    }

    #[inline]
    fn reset_task(&mut self) {
        self.task.copy_from(&self.e);
    }

    #[inline]
    fn set_weighted(&mut self, i: usize, k: f64) {
        let m = self.e.len();
        let (w, j) =
            (&mut self.weighted.as_mut_slice()[i * m..(i + 1) * m], &self.jacobian.as_slice()[i * m..(i + 1) * m]);
        for &r in &self.nz_rows[self.nz_start[i]..self.nz_start[i + 1]] {
            w[r] = j[r] * k;
        }
        self.pending_k[i] = k;
    }

    /// `A = Σ kᵢ² Jᵢ Jᵢᵀ` for the column factors `kᵢ` (1 for [`Columns::Plain`], else those of
    /// [`Algebra::set_weighted`]). `A` is kept between calls for the same `J`: a call whose
    /// factors differ from the last ones in a few columns (a limit mode's next round, which
    /// locks a joint or two) only adds those columns' change, and one with the same factors
    /// (Levenberg–Marquardt's retry) costs nothing.
    fn gram(&mut self, columns: Columns) {
        let m = self.e.len();
        if columns == Columns::Plain {
            self.pending_k.fill(1.0);
        }
        if self.gram_valid {
            for i in 0..self.pending_k.len() {
                let (new, old) = (self.pending_k[i], self.gram_k[i]);
                if new != old {
                    self.eigen_of = None;
                    let f = new * new - old * old;
                    let col = &self.jacobian.as_slice()[i * m..(i + 1) * m];
                    let rows = &self.nz_rows[self.nz_start[i]..self.nz_start[i + 1]];
                    for (k, &c) in rows.iter().enumerate() {
                        let x = f * col[c];
                        for &r in &rows[k..] {
                            self.a[r + c * m] += col[r] * x;
                            if r != c {
                                self.a[c + r * m] = self.a[r + c * m];
                            }
                        }
                    }
                    self.gram_k[i] = new;
                }
            }
            return;
        }
        self.eigen_of = None;
        let a = &mut self.a;
        a.fill(0.0);
        let w = columns.pick(&self.jacobian, &self.weighted);
        for (i, col) in w.column_iter().enumerate() {
            let col = col.as_slice();
            let rows = &self.nz_rows[self.nz_start[i]..self.nz_start[i + 1]];
            for (k, &c) in rows.iter().enumerate() {
                let x = col[c];
                for &r in &rows[k..] {
                    a[r + c * m] += col[r] * x;
                }
            }
        }
        for c in 0..m {
            for r in c + 1..m {
                a[c + r * m] = a[r + c * m];
            }
        }
        self.gram_k.copy_from_slice(&self.pending_k);
        self.gram_valid = true;
    }

    fn method_step(&mut self, columns: Columns, rule: Rule, opts: &SolveOptions, mu: f64, out: &mut [f64]) {
        let p = self.primary;
        if rule == Rule::SelectivelyDamped {
            self.sdls_step(columns, p, opts.singular_threshold, out);
        } else {
            self.task_step(p, rule, opts, mu, true);
            let w = columns.pick(&self.jacobian, &self.weighted);
            for (i, (o, col)) in out.iter_mut().zip(w.column_iter()).enumerate() {
                let col = col.as_slice();
                *o = self.nz_rows[self.nz_start[i]..self.nz_start[i + 1]]
                    .iter()
                    .take_while(|&&r| r < p)
                    .map(|&r| col[r] * self.y[r])
                    .sum();
            }
        }
        if p < self.e.len() {
            self.secondary_step(columns, rule, opts, mu, out);
        }
    }

    /// `y = A⁺ W z` by a Cholesky factorisation of `A + t² I` (`t` the singular threshold: the
    /// pseudoinverse's own cut, as a damping, which leaves the directions well above it exact),
    /// or where that fails by the eigen-decomposition; then `delta += z − Wᵀ y`. (The
    /// factorisation is several times cheaper than the decomposition, and the rest pose's pull
    /// projects every step.)
    fn project_push(&mut self, columns: Columns, threshold: f64, z: &[f64], locked: &[bool], delta: &mut [f64]) {
        let m = self.e.len();
        {
            let w = columns.pick(&self.jacobian, &self.weighted);
            for r in 0..m {
                self.r[r] = (0..z.len()).map(|j| w[(r, j)] * z[j]).sum();
            }
        }
        let trace: f64 = (0..m).map(|i| self.a[i + i * m]).sum();
        let shift = (threshold * threshold).max(1e-15 * trace);
        if !cholesky_solve(m, &self.a, shift, &self.r, &mut self.factor, &mut self.first, &mut self.y) {
            self.leading_eigen(m);
            pinv_apply(m, &self.eigen_values, &self.eigen_vectors, threshold * threshold, &self.r, &mut self.y);
        }
        let w = columns.pick(&self.jacobian, &self.weighted);
        for (i, d) in delta.iter_mut().enumerate() {
            if !locked[i] {
                *d += z[i] - dot(w.column(i).as_slice(), &self.y[..m]);
            }
        }
    }

    #[inline]
    fn task_sub_column(&mut self, i: usize, d: f64) {
        self.task.axpy(-d, &self.jacobian.column(i), 1.0);
    }

    #[inline]
    fn predict_from_e(&mut self) {
        self.predicted.copy_from(&self.e);
    }

    #[inline]
    fn predict_sub_column(&mut self, i: usize, d: f64) {
        self.predicted.axpy(-d, &self.jacobian.column(i), 1.0);
    }

    #[inline]
    fn predicted_norm_squared(&self) -> f64 {
        self.merit(self.predicted.as_slice())
    }
}

#[cfg(test)]
#[path = "dynamic_tests.rs"]
mod tests;
