//! Arithmetic on one number or on several side by side (SIMD lanes), written once: the
//! [`Lanes`] trait, implemented for `f64`, for [`Quad`] (four `f64`s in an array, any target)
//! and on x86-64 for `Avx` (four `f64`s in an AVX register, `avx2.rs`), and the sine and cosine
//! of forward kinematics on it ([`sin_cos`]).
//!
//! The batch solver runs the position-only solve on several goals at a time in lanes (eight,
//! a [`Pair`] of `Avx`, on x86-64 with AVX2; four `Quad` lanes elsewhere); the scalar solver
//! runs the same code on an `f64`. Every operation used here is one
//! IEEE 754 operation per lane (`+ − × ÷`, comparisons, selects), never a fused multiply-add
//! nor an approximation, so a lane computes exactly what the scalar code computes, bit for bit,
//! on every target: x86-64 with SSE2 or AVX2, wasm32, aarch64.
//!
//! Why not a SIMD crate. `wide` (the first one tried) picks its instructions when the program
//! is compiled: on the default x86-64 target that is SSE2, two lanes per instruction, and its
//! AVX code needs the whole program built for AVX; `Quad`'s plain arrays, compiled inside one
//! function built for AVX2 and chosen at run time, measured 1.2–1.3× faster than `wide::f64x4`
//! in the batch solver (CPU time of 300 000 seed-arm solves, 0.14 against 0.17–0.18 s), and
//! ran no slower than eight lanes for AVX-512. And `wide`'s `f64x4::sin_cos` uses fused
//! multiply-adds where the target has them (aarch64 always, x86-64 built with `fma`), so its
//! results would depend on the machine and differ from any scalar function's: the sine and
//! cosine are computed here, with the same operations in every lane type.
//!
//! Why `Avx` beside `Quad`. Compiled for AVX2, `Quad`'s arrays are turned into vector code by
//! LLVM's vectoriser, which put two thirds of the batch loop's multiplications on 128-bit
//! halves and chose differently after edits that did not touch the arithmetic (5–13 % more
//! instructions from reordering one function's parameters). `Avx` names each 256-bit
//! instruction: the batch of 3000 goals on the 3-link arm of `cgbatch` ran in 9.5 million
//! instructions instead of 12.1 (callgrind), whatever the code around it. Generic code the
//! lanes run through must not call lane operations from closures: a closure is compiled on its
//! own, outside the AVX2 function, and would call each instruction as a function.
//!
//! Why two groups of `Avx` (`Pair<Avx>`, `pair.rs`) and not one. A step of one group is a
//! chain of dependent operations (the joints' sines, the 2×2 solve, the trial pose's sines);
//! a second, independent group lets the processor run one chain while the other waits. On
//! this machine (AMD EPYC, AVX2, no AVX-512), passes of 100,000 seed-arm goals alternated in
//! one process took 0.94–1.02 of one group's CPU time (median of seven runs' ratios 1.02), the
//! seven-link arm 0.95–1.00, the 20-link arm 0.89–0.94, with 130 fewer instructions per
//! seed-arm solve (callgrind): within noise on the 3-link arm, a little faster on long chains. The loop is bound by its instruction count (per-lane
//! bookkeeping and selects as much as arithmetic) more than by latency, so the second group
//! has little to hide.

use std::ops::{Add, Div, Mul, Neg, Sub};

#[cfg(target_arch = "x86_64")]
mod avx2;
#[cfg(target_arch = "x86_64")]
mod pair;
#[cfg(target_arch = "x86_64")]
pub(crate) use avx2::Avx;
#[cfg(target_arch = "x86_64")]
pub(crate) use pair::Pair;

/// Numbers side by side: `f64` (one lane) or `f64x4` (four). Every operation is lane-wise and
/// exactly rounded, so lane `k` of a result depends only on lane `k` of the operands.
pub(crate) trait Lanes:
    Copy + Add<Output = Self> + Sub<Output = Self> + Mul<Output = Self> + Div<Output = Self> + Neg<Output = Self>
{
    /// A lane-wise truth value.
    type Mask: Copy;
    /// The number of lanes.
    const LANES: usize;
    /// Every lane `x`.
    fn splat(x: f64) -> Self;
    /// Lane `k`.
    fn lane(self, k: usize) -> f64;
    /// A copy with lane `k` set to `x`.
    fn with_lane(self, k: usize, x: f64) -> Self;
    /// `|x|`.
    fn abs(self) -> Self;
    /// `self < other`.
    fn lt(self, other: Self) -> Self::Mask;
    /// `self <= other`.
    fn le(self, other: Self) -> Self::Mask;
    /// `self > other`.
    fn gt(self, other: Self) -> Self::Mask;
    /// `self == other`.
    fn eq(self, other: Self) -> Self::Mask;
    /// Lane-wise `mask ? a : b`.
    fn select(mask: Self::Mask, a: Self, b: Self) -> Self;
    /// Lane-wise `mask ? a : b` of masks.
    fn select_mask(mask: Self::Mask, a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// A mask true in every lane.
    fn yes() -> Self::Mask;
    /// A mask false in every lane.
    fn no() -> Self::Mask;
    /// Lane-wise and.
    fn and(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// Lane-wise or.
    fn or(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// Whether every lane of `mask` holds.
    fn all(mask: Self::Mask) -> bool;
    /// Lane `k` of `mask`.
    fn mask_lane(mask: Self::Mask, k: usize) -> bool;
    /// The mask whose lane `k` is `f(k)`.
    fn mask_from(f: impl Fn(usize) -> bool) -> Self::Mask;

    /// `(sin x, cos x)` from `s = sin r`, `c = cos r` and the quadrant `q` of `x = r + qπ/2`
    /// (an integer-valued number): a choice among `±s` and `±c`, no arithmetic, so any way
    /// of choosing gives the same bits. This one works on every lane type with masks.
    #[inline(always)]
    fn place(s: Self, c: Self, q: Self) -> (Self, Self) {
        // The quadrant q mod 4, as a number 0, 1, 2 or 3: q − 4·⌊q/4⌋.
        let quarter = q * Self::splat(0.25);
        let mut floor = round(quarter);
        floor = Self::select(floor.gt(quarter), floor - Self::splat(1.0), floor);
        let k = q - Self::splat(4.0) * floor;
        // sin(r + kπ/2), cos(r + kπ/2): k = 1 → (c, −s), 2 → (−s, −c), 3 → (−c, s).
        let (one, two, three) = (Self::splat(1.0), Self::splat(2.0), Self::splat(3.0));
        let odd = Self::or(k.eq(one), k.eq(three));
        let (sin, cos) = (Self::select(odd, c, s), Self::select(odd, s, c));
        let sin = Self::select(Self::or(k.eq(two), k.eq(three)), -sin, sin);
        let cos = Self::select(Self::or(k.eq(one), k.eq(two)), -cos, cos);
        (sin, cos)
    }
}

impl Lanes for f64 {
    type Mask = bool;
    const LANES: usize = 1;
    #[inline(always)]
    fn splat(x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn lane(self, _: usize) -> f64 {
        self
    }
    #[inline(always)]
    fn with_lane(self, _: usize, x: f64) -> Self {
        x
    }
    #[inline(always)]
    fn abs(self) -> Self {
        f64::abs(self)
    }
    #[inline(always)]
    fn lt(self, other: Self) -> bool {
        self < other
    }
    #[inline(always)]
    fn le(self, other: Self) -> bool {
        self <= other
    }
    #[inline(always)]
    fn gt(self, other: Self) -> bool {
        self > other
    }
    #[inline(always)]
    fn eq(self, other: Self) -> bool {
        self == other
    }
    #[inline(always)]
    fn select(mask: bool, a: Self, b: Self) -> Self {
        // Without a branch: the quadrant of a sine is as good as random.
        let m = bits(mask);
        f64::from_bits((a.to_bits() & m) | (b.to_bits() & !m))
    }
    #[inline(always)]
    fn select_mask(mask: bool, a: bool, b: bool) -> bool {
        if mask { a } else { b }
    }
    #[inline(always)]
    fn yes() -> bool {
        true
    }
    #[inline(always)]
    fn no() -> bool {
        false
    }
    #[inline(always)]
    fn and(a: bool, b: bool) -> bool {
        a & b
    }
    #[inline(always)]
    fn or(a: bool, b: bool) -> bool {
        a | b
    }
    #[inline(always)]
    fn all(mask: bool) -> bool {
        mask
    }
    #[inline(always)]
    fn mask_lane(mask: bool, _: usize) -> bool {
        mask
    }
    #[inline(always)]
    fn mask_from(f: impl Fn(usize) -> bool) -> bool {
        f(0)
    }
    #[inline(always)]
    #[allow(clippy::cast_possible_truncation)]
    fn place(s: f64, c: f64, q: f64) -> (f64, f64) {
        // |q| < 2²⁰ here: exact as an integer.
        match (q as i64) & 3 {
            0 => (s, c),
            1 => (c, -s),
            2 => (-s, -c),
            _ => (-c, s),
        }
    }
}

/// Four lanes as a plain array, every operation written out lane by lane: compiled inside a
/// function built for AVX2 (see `solve::fast::run_lanes`) the compiler turns each into one
/// 256-bit instruction; elsewhere into what the target has (SSE2 pairs, NEON, simd128, or
/// scalar code). Only IEEE operations, so every lane computes what `f64` computes.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Quad(pub(crate) [f64; 4]);

/// A lane-wise truth value of a [`Quad`]: all ones or all zeros per lane.
#[derive(Debug, Clone, Copy)]
pub(crate) struct QuadMask([u64; 4]);

/// `f(a[k], b[k])` for the four lanes.
macro_rules! quad {
    ($a:expr, $b:expr, |$x:ident, $y:ident| $e:expr) => {{
        let (a, b) = ($a, $b);
        let f = |$x, $y| $e;
        [f(a[0], b[0]), f(a[1], b[1]), f(a[2], b[2]), f(a[3], b[3])]
    }};
}

macro_rules! quad_op {
    ($tr:ident, $f:ident, $op:tt) => {
        impl $tr for Quad {
            type Output = Quad;
            #[inline(always)]
            fn $f(self, o: Quad) -> Quad {
                Quad(quad!(self.0, o.0, |x, y| x $op y))
            }
        }
    };
}
quad_op!(Add, add, +);
quad_op!(Sub, sub, -);
quad_op!(Mul, mul, *);
quad_op!(Div, div, /);

impl Neg for Quad {
    type Output = Quad;
    #[inline(always)]
    fn neg(self) -> Quad {
        let a = self.0;
        Quad([-a[0], -a[1], -a[2], -a[3]])
    }
}

/// All ones for true, all zeros for false.
#[inline(always)]
fn bits(b: bool) -> u64 {
    if b { u64::MAX } else { 0 }
}

macro_rules! quad_cmp {
    ($f:ident, $op:tt) => {
        #[inline(always)]
        fn $f(self, o: Quad) -> QuadMask {
            QuadMask(quad!(self.0, o.0, |x, y| bits(x $op y)))
        }
    };
}

impl Lanes for Quad {
    type Mask = QuadMask;
    const LANES: usize = 4;
    #[inline(always)]
    fn splat(x: f64) -> Self {
        Quad([x; 4])
    }
    #[inline(always)]
    fn lane(self, k: usize) -> f64 {
        self.0[k]
    }
    #[inline(always)]
    fn with_lane(mut self, k: usize, x: f64) -> Self {
        self.0[k] = x;
        self
    }
    #[inline(always)]
    fn abs(self) -> Self {
        let a = self.0;
        Quad([a[0].abs(), a[1].abs(), a[2].abs(), a[3].abs()])
    }
    quad_cmp!(lt, <);
    quad_cmp!(le, <=);
    quad_cmp!(gt, >);
    quad_cmp!(eq, ==);
    #[inline(always)]
    fn select(m: QuadMask, a: Self, b: Self) -> Self {
        let m = m.0;
        let pick = |k: usize| f64::from_bits((a.0[k].to_bits() & m[k]) | (b.0[k].to_bits() & !m[k]));
        Quad([pick(0), pick(1), pick(2), pick(3)])
    }
    #[inline(always)]
    fn select_mask(m: QuadMask, a: QuadMask, b: QuadMask) -> QuadMask {
        let m = m.0;
        let pick = |k: usize| (a.0[k] & m[k]) | (b.0[k] & !m[k]);
        QuadMask([pick(0), pick(1), pick(2), pick(3)])
    }
    #[inline(always)]
    fn yes() -> QuadMask {
        QuadMask([u64::MAX; 4])
    }
    #[inline(always)]
    fn no() -> QuadMask {
        QuadMask([0; 4])
    }
    #[inline(always)]
    fn and(a: QuadMask, b: QuadMask) -> QuadMask {
        QuadMask(quad!(a.0, b.0, |x, y| x & y))
    }
    #[inline(always)]
    fn or(a: QuadMask, b: QuadMask) -> QuadMask {
        QuadMask(quad!(a.0, b.0, |x, y| x | y))
    }
    #[inline(always)]
    fn all(m: QuadMask) -> bool {
        let m = m.0;
        (m[0] & m[1] & m[2] & m[3]) != 0
    }
    #[inline(always)]
    fn mask_from(f: impl Fn(usize) -> bool) -> QuadMask {
        QuadMask([bits(f(0)), bits(f(1)), bits(f(2)), bits(f(3))])
    }
    #[inline(always)]
    fn mask_lane(m: QuadMask, k: usize) -> bool {
        m.0[k] != 0
    }
}

/// Arguments up to this size are reduced by the three-part Cody–Waite subtraction below, which
/// is exact there (`y · P1` is exact for `|y| < 2²⁷`); larger ones, and non-finite ones, go to
/// [`crate::math::sin_cos`] (Payne–Hanek reduction). Joint angles and their sums are far below.
const POLYNOMIAL_LIMIT: f64 = 1_048_576.0;

/// `1.5 · 2⁵²`: `(x + R) − R` is `x` rounded to the nearest integer, ties to even, for
/// `|x| < 2⁵¹` (in the default rounding mode, the same on every target).
const ROUND: f64 = 6_755_399_441_055_744.0;

/// `π/2` in three parts (Cody & Waite): `P1` and `P2` have few enough significant bits that
/// their products with the quadrant are exact.
#[allow(clippy::excessive_precision)] // the published digits; each rounds to the double meant
const P1: f64 = 1.570_796_310_901_641_845_703_125;
#[allow(clippy::excessive_precision)] // the published digits; each rounds to the double meant
const P2: f64 = 1.589_325_471_229_585_673_428e-8;
#[allow(clippy::excessive_precision)] // the published digits; each rounds to the double meant
const P3: f64 = 6.123_233_995_736_765_886_14e-17;

/// Minimax coefficients of `(sin r − r) / r³` and `(cos r − 1 + r²/2) / r⁴` in `z = r²` on
/// `|r| ≤ π/4` (S. L. Moshier's Cephes `sin.c`; peak relative error about 2e-16).
#[allow(clippy::excessive_precision)] // the published digits; each rounds to the double meant
const SIN: [f64; 6] = [
    1.589_623_015_765_465_680_60e-10,
    -2.505_074_776_285_780_728_66e-8,
    2.755_731_362_138_572_452_13e-6,
    -1.984_126_982_958_953_859_96e-4,
    8.333_333_333_322_118_588_78e-3,
    -1.666_666_666_666_663_072_95e-1,
];
#[allow(clippy::excessive_precision)] // the published digits; each rounds to the double meant
const COS: [f64; 6] = [
    -1.135_853_652_138_768_173_00e-11,
    2.087_570_084_197_473_167_78e-9,
    -2.755_731_417_929_673_881_12e-7,
    2.480_158_728_885_170_453_48e-5,
    -1.388_888_888_887_305_641_16e-3,
    4.166_666_666_666_659_292_18e-2,
];

/// `x` rounded to the nearest integer (ties to even), for `|x| < 2⁵¹`.
#[inline(always)]
fn round<L: Lanes>(x: L) -> L {
    (x + L::splat(ROUND)) - L::splat(ROUND)
}

/// Sine and cosine of every lane, `(sin x, cos x)`: the same bits for the same argument in any
/// lane of any [`Lanes`] type on any target (see the [module docs](self)).
///
/// The argument is reduced to `r = x − qπ/2` with `|r| ≤ π/4`, `q` the nearest integer, and
/// the Cephes polynomials of `r` give sine and cosine to within about 1 ulp of the correctly
/// rounded values (the tests compare with `libm` on a million arguments). Lanes beyond
/// ±2²⁰ rad, or not finite, are computed by [`crate::math::sin_cos`].
#[inline(always)]
pub(crate) fn sin_cos<L: Lanes>(x: L) -> (L, L) {
    let small = x.abs().le(L::splat(POLYNOMIAL_LIMIT));
    if !L::all(small) {
        return sin_cos_lane_by_lane(x);
    }
    let q = round(x * L::splat(std::f64::consts::FRAC_2_PI));
    let r = ((x - q * L::splat(P1)) - q * L::splat(P2)) - q * L::splat(P3);
    let z = r * r;
    // The degree-5 polynomials by Estrin's scheme, (k₅ + k₄z) + z²(k₃ + k₂z) + z⁴(k₁ + k₀z):
    // half the dependent operations of Horner's, which matters in a solve, where each
    // iteration waits for its sines.
    let z2 = z * z;
    let z4 = z2 * z2;
    let (ps, pc) = (estrin(&SIN, z, z2, z4), estrin(&COS, z, z2, z4));
    let s = r + r * z * ps;
    let c = (L::splat(1.0) - L::splat(0.5) * z) + z2 * pc;
    L::place(s, c, q)
}

/// `k₅ + k₄z + k₃z² + k₂z³ + k₁z⁴ + k₀z⁵` by Estrin's scheme, `(k₅ + k₄z) + z²(k₃ + k₂z) +
/// z⁴(k₁ + k₀z)`, given `z²` and `z⁴`. (A function, not a closure: a closure would be compiled
/// on its own, outside the AVX2 function the lanes run in.)
#[inline(always)]
fn estrin<L: Lanes>(k: &[f64; 6], z: L, z2: L, z4: L) -> L {
    let lo = L::splat(k[5]) + L::splat(k[4]) * z;
    let mid = L::splat(k[3]) + L::splat(k[2]) * z;
    let hi = L::splat(k[1]) + L::splat(k[0]) * z;
    (lo + z2 * mid) + z4 * hi
}

/// [`sin_cos`] one lane at a time: the polynomial for the lanes within its range, the
/// Payne–Hanek reduction of [`crate::math::sin_cos`] for the others.
#[cold]
#[inline(never)]
fn sin_cos_lane_by_lane<L: Lanes>(x: L) -> (L, L) {
    let (mut s, mut c) = (x, x);
    for k in 0..L::LANES {
        let v = x.lane(k);
        let (sv, cv) = if v.abs() <= POLYNOMIAL_LIMIT { sin_cos(v) } else { crate::math::sin_cos(v) };
        s = s.with_lane(k, sv);
        c = c.with_lane(k, cv);
    }
    (s, c)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::SplitMix64;

    /// The distance in units in the last place between two finite doubles of the same sign,
    /// or the absolute difference in units of 2⁻⁵³ near zero.
    fn ulps(a: f64, b: f64) -> f64 {
        let scale = a.abs().max(b.abs()).max(0.5);
        (a - b).abs() / (scale * f64::EPSILON)
    }

    #[test]
    fn sine_and_cosine_are_within_an_ulp_or_two_of_libm() {
        let mut rng = SplitMix64(7);
        let mut worst: f64 = 0.0;
        for i in 0..1_000_000 {
            let x = match i % 4 {
                0 => (rng.unit() - 0.5) * 8.0,
                1 => (rng.unit() - 0.5) * 200.0,
                2 => (rng.unit() - 0.5) * 2.0 * POLYNOMIAL_LIMIT,
                _ => (rng.unit() - 0.5) * 1e-3,
            };
            let (s, c) = sin_cos(x);
            let (ls, lc) = crate::math::sin_cos(x);
            worst = worst.max(ulps(s, ls)).max(ulps(c, lc));
        }
        assert!(worst <= 2.0, "{worst} ulps");
    }

    #[test]
    fn special_arguments() {
        assert_eq!(sin_cos(0.0), (0.0, 1.0));
        assert_eq!(sin_cos(-0.0).1, 1.0);
        let (s, c) = sin_cos(f64::INFINITY);
        assert!(s.is_nan() && c.is_nan());
        let (s, c) = sin_cos(f64::NAN);
        assert!(s.is_nan() && c.is_nan());
        // Beyond the polynomial's range: the exact reduction.
        assert_eq!(sin_cos(1e22), crate::math::sin_cos(1e22));
        assert_eq!(sin_cos(-3e6), crate::math::sin_cos(-3e6));
        // Quadrant boundaries and their neighbours.
        for k in -8..=8 {
            for d in [-1e-9, 0.0, 1e-9] {
                let x = f64::from(k) * std::f64::consts::FRAC_PI_4 + d;
                let (s, c) = sin_cos(x);
                let (ls, lc) = crate::math::sin_cos(x);
                assert!(ulps(s, ls) <= 2.0 && ulps(c, lc) <= 2.0, "{x}: {s} {ls} {c} {lc}");
            }
        }
    }

    /// The explicit AVX lanes compute what `f64` does, operation by operation (every lane
    /// operation the solver uses, on ordinary, signed-zero, infinite and NaN operands).
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn avx_lanes_give_the_scalar_bits() {
        if !std::arch::is_x86_feature_detected!("avx2") {
            return;
        }
        let mut rng = SplitMix64(13);
        let special = [0.0, -0.0, 1.0, -1.0, f64::INFINITY, f64::NEG_INFINITY, f64::NAN, f64::MIN_POSITIVE, 1e-310];
        let pick = |rng: &mut SplitMix64| {
            if rng.unit() < 0.2 {
                special[(rng.unit() * special.len() as f64) as usize % special.len()]
            } else {
                (rng.unit() - 0.5) * 40.0
            }
        };
        let avx = |x: [f64; 4]| (0..4).fold(Avx::splat(0.0), |v, k| v.with_lane(k, x[k]));
        let mask_bits = |m: <Avx as Lanes>::Mask| [0, 1, 2, 3].map(|k| Avx::mask_lane(m, k));
        for _ in 0..20_000 {
            let (a, b): ([f64; 4], [f64; 4]) = ([0; 4].map(|_| pick(&mut rng)), [0; 4].map(|_| pick(&mut rng)));
            let (va, vb) = (avx(a), avx(b));
            let same = |v: Avx, f: &dyn Fn(f64, f64) -> f64| {
                for k in 0..4 {
                    assert_eq!(v.lane(k).to_bits(), f(a[k], b[k]).to_bits(), "{} {}", a[k], b[k]);
                }
            };
            same(va + vb, &|x, y| x + y);
            same(va - vb, &|x, y| x - y);
            same(va * vb, &|x, y| x * y);
            same(va / vb, &|x, y| x / y);
            same(-va, &|x, _| -x);
            same(va.abs(), &|x, _| x.abs());
            let lt = va.lt(vb);
            same(Avx::select(lt, va, vb), &|x, y| if x < y { x } else { y });
            assert_eq!(mask_bits(lt), [0, 1, 2, 3].map(|k| a[k] < b[k]));
            assert_eq!(mask_bits(va.le(vb)), [0, 1, 2, 3].map(|k| a[k] <= b[k]));
            assert_eq!(mask_bits(va.gt(vb)), [0, 1, 2, 3].map(|k| a[k] > b[k]));
            assert_eq!(mask_bits(va.eq(vb)), [0, 1, 2, 3].map(|k| a[k] == b[k]));
            let (gt, eq) = (va.gt(vb), va.eq(vb));
            assert_eq!(mask_bits(Avx::and(lt, eq)), [false; 4]);
            assert_eq!(mask_bits(Avx::or(gt, eq)), [0, 1, 2, 3].map(|k| a[k] >= b[k]));
            assert_eq!(
                mask_bits(Avx::select_mask(lt, Avx::yes(), gt)),
                [0, 1, 2, 3].map(|k| {
                    // (Not `!=`: NaN is neither.)
                    let (below, above) = (a[k] < b[k], a[k] > b[k]);
                    below | above
                })
            );
            assert_eq!(Avx::all(lt), (0..4).all(|k| a[k] < b[k]));
            assert_eq!(mask_bits(Avx::mask_from(|k| k % 2 == 1)), [false, true, false, true]);
            assert_eq!(mask_bits(Avx::no()), [false; 4]);
            let x = a.map(|v| v * 1e3);
            let (s, c) = sin_cos(avx(x));
            for (k, &v) in x.iter().enumerate() {
                let (es, ec) = sin_cos(v);
                assert_eq!((s.lane(k).to_bits(), c.lane(k).to_bits()), (es.to_bits(), ec.to_bits()), "{v}");
            }
        }
    }

    #[test]
    fn four_lanes_give_the_scalar_bits() {
        let mut rng = SplitMix64(11);
        for i in 0..100_000 {
            let mut xs = [0.0; 4];
            for x in &mut xs {
                *x = (rng.unit() - 0.5) * if i % 2 == 0 { 20.0 } else { 2.0 * POLYNOMIAL_LIMIT };
            }
            if i % 1000 == 0 {
                xs[i / 1000 % 4] = 1e7 * (rng.unit() + 1.0);
            }
            let (s, c) = sin_cos(Quad(xs));
            for (k, &x) in xs.iter().enumerate() {
                let (es, ec) = sin_cos(x);
                assert_eq!((s.lane(k).to_bits(), c.lane(k).to_bits()), (es.to_bits(), ec.to_bits()), "{x}");
            }
        }
    }
}
