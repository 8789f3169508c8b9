//! Four lanes in one AVX register: [`Avx`], the batch solver's lane type on x86-64 processors
//! with AVX2, every operation one named 256-bit instruction.
//!
//! [`Quad`](super::Quad) leaves the choice of instructions to LLVM's vectoriser, which splits
//! some of its operations into two 128-bit halves and does so differently each time the code
//! around them changes (measured: 82 of the batch loop's 123 multiplications on 128-bit halves,
//! and a 5–13 % swing in instructions from edits that do not touch the arithmetic). Here the
//! instructions are written out, so the loop's speed does not hang on the optimiser's mood.
//!
//! The operations are the IEEE ones `f64` and `Quad` perform (`vaddpd`, `vsubpd`, `vmulpd`,
//! `vdivpd` round exactly as their scalar forms; no fused multiply-add is used; comparisons are
//! the ordered, quiet ones, false on NaN like Rust's; selects and sign changes move bits), so
//! every lane computes what the scalar solver computes, bit for bit.
//!
//! # Safety
//!
//! Every method runs AVX instructions. An `Avx` value is made only inside
//! `solve::fast::run_lanes`'s AVX2 branch, which runs after `is_x86_feature_detected!("avx2")`
//! said the processor has it; nothing else in the crate names the type. The methods are
//! `#[inline(always)]` so that they are compiled into that `#[target_feature(enable = "avx2")]`
//! function.
#![allow(unsafe_code)]

use std::arch::x86_64::{
    __m256d, _CMP_EQ_OQ, _CMP_GT_OQ, _CMP_LE_OQ, _CMP_LT_OQ, _mm256_add_pd, _mm256_and_pd, _mm256_andnot_pd,
    _mm256_blendv_pd, _mm256_castsi256_pd, _mm256_cmp_pd, _mm256_div_pd, _mm256_movemask_pd, _mm256_mul_pd,
    _mm256_or_pd, _mm256_set_epi64x, _mm256_set1_pd, _mm256_sub_pd, _mm256_xor_pd,
};
use std::ops::{Add, Div, Mul, Neg, Sub};

use super::Lanes;

/// Four `f64` lanes in one 256-bit register.
#[derive(Clone, Copy)]
pub(crate) struct Avx(__m256d);

/// A lane-wise truth value of an [`Avx`]: all ones or all zeros per lane.
#[derive(Clone, Copy)]
pub(crate) struct AvxMask(__m256d);

impl std::fmt::Debug for Avx {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_tuple("Avx").field(&self.to_array()).finish()
    }
}

impl Avx {
    #[inline(always)]
    fn to_array(self) -> [f64; 4] {
        // SAFETY: `__m256d` and `[f64; 4]` have the same size, and every bit pattern is valid
        // for both.
        unsafe { std::mem::transmute::<__m256d, [f64; 4]>(self.0) }
    }

    #[inline(always)]
    fn from_array(a: [f64; 4]) -> Self {
        // SAFETY: as in `to_array`.
        Avx(unsafe { std::mem::transmute::<[f64; 4], __m256d>(a) })
    }
}

/// `Avx(op(a, b))` for an AVX intrinsic `op`.
macro_rules! avx_op {
    ($tr:ident, $f:ident, $op:ident) => {
        impl $tr for Avx {
            type Output = Avx;
            #[inline(always)]
            fn $f(self, o: Avx) -> Avx {
                // SAFETY: see the module's doc.
                Avx(unsafe { $op(self.0, o.0) })
            }
        }
    };
}
avx_op!(Add, add, _mm256_add_pd);
avx_op!(Sub, sub, _mm256_sub_pd);
avx_op!(Mul, mul, _mm256_mul_pd);
avx_op!(Div, div, _mm256_div_pd);

impl Neg for Avx {
    type Output = Avx;
    #[inline(always)]
    fn neg(self) -> Avx {
        // The sign bit flipped, as `-x` does.
        // SAFETY: see the module's doc.
        Avx(unsafe { _mm256_xor_pd(self.0, _mm256_set1_pd(-0.0)) })
    }
}

/// A comparison `self OP other` with the ordered, quiet predicate `$p` (false when a lane is NaN).
macro_rules! avx_cmp {
    ($f:ident, $p:ident) => {
        #[inline(always)]
        fn $f(self, o: Avx) -> AvxMask {
            // SAFETY: see the module's doc.
            AvxMask(unsafe { _mm256_cmp_pd::<$p>(self.0, o.0) })
        }
    };
}

impl Lanes for Avx {
    type Mask = AvxMask;
    const LANES: usize = 4;
    #[inline(always)]
    fn splat(x: f64) -> Self {
        // SAFETY: see the module's doc.
        Avx(unsafe { _mm256_set1_pd(x) })
    }
    #[inline(always)]
    fn lane(self, k: usize) -> f64 {
        self.to_array()[k]
    }
    #[inline(always)]
    fn with_lane(self, k: usize, x: f64) -> Self {
        let mut a = self.to_array();
        a[k] = x;
        Avx::from_array(a)
    }
    #[inline(always)]
    fn abs(self) -> Self {
        // The sign bit cleared, as `f64::abs` does.
        // SAFETY: see the module's doc.
        Avx(unsafe { _mm256_andnot_pd(_mm256_set1_pd(-0.0), self.0) })
    }
    avx_cmp!(lt, _CMP_LT_OQ);
    avx_cmp!(le, _CMP_LE_OQ);
    avx_cmp!(gt, _CMP_GT_OQ);
    avx_cmp!(eq, _CMP_EQ_OQ);
    #[inline(always)]
    fn select(m: AvxMask, a: Self, b: Self) -> Self {
        // `vblendvpd` takes `a`'s lane where the mask's sign bit is set: the mask's lanes are
        // all ones or all zeros.
        // SAFETY: see the module's doc.
        Avx(unsafe { _mm256_blendv_pd(b.0, a.0, m.0) })
    }
    #[inline(always)]
    fn select_mask(m: AvxMask, a: AvxMask, b: AvxMask) -> AvxMask {
        // SAFETY: see the module's doc.
        AvxMask(unsafe { _mm256_blendv_pd(b.0, a.0, m.0) })
    }
    #[inline(always)]
    fn yes() -> AvxMask {
        AvxMask(Self::splat(f64::from_bits(u64::MAX)).0)
    }
    #[inline(always)]
    fn no() -> AvxMask {
        AvxMask(Self::splat(0.0).0)
    }
    #[inline(always)]
    fn and(a: AvxMask, b: AvxMask) -> AvxMask {
        // SAFETY: see the module's doc.
        AvxMask(unsafe { _mm256_and_pd(a.0, b.0) })
    }
    #[inline(always)]
    fn or(a: AvxMask, b: AvxMask) -> AvxMask {
        // SAFETY: see the module's doc.
        AvxMask(unsafe { _mm256_or_pd(a.0, b.0) })
    }
    #[inline(always)]
    fn all(m: AvxMask) -> bool {
        // SAFETY: see the module's doc.
        unsafe { _mm256_movemask_pd(m.0) == 0b1111 }
    }
    #[inline(always)]
    fn mask_lane(m: AvxMask, k: usize) -> bool {
        // SAFETY: see the module's doc.
        unsafe { (_mm256_movemask_pd(m.0) >> k) & 1 != 0 }
    }
    #[inline(always)]
    fn mask_from(f: impl Fn(usize) -> bool) -> AvxMask {
        let lane = |k: usize| -i64::from(f(k));
        // SAFETY: see the module's doc.
        AvxMask(unsafe { _mm256_castsi256_pd(_mm256_set_epi64x(lane(3), lane(2), lane(1), lane(0))) })
    }
}
