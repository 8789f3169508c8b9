//! Two lane groups side by side: [`Pair`], twice the lanes of its half, each operation done on
//! both halves. The halves are independent, so the processor interleaves their dependency
//! chains: where one group's step waits for a result (a sine, a division), the other's runs.
//!
//! Every operation is the half's operation on each half, so every lane computes what the half
//! (and so what `f64`) computes, bit for bit.

use std::ops::{Add, Div, Mul, Neg, Sub};

use super::Lanes;

/// Two groups of lanes, `L::LANES` each: lanes `0..L::LANES` are the first half's, the rest
/// the second's.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Pair<L>(pub(crate) L, pub(crate) L);

/// A lane-wise truth value of a [`Pair`]: one mask per half.
#[derive(Debug, Clone, Copy)]
pub(crate) struct PairMask<M>(M, M);

/// `Pair(op(a.0, b.0), op(a.1, b.1))` for an operator.
macro_rules! pair_op {
    ($tr:ident, $f:ident) => {
        impl<L: Lanes> $tr for Pair<L> {
            type Output = Pair<L>;
            #[inline(always)]
            fn $f(self, o: Pair<L>) -> Pair<L> {
                Pair($tr::$f(self.0, o.0), $tr::$f(self.1, o.1))
            }
        }
    };
}
pair_op!(Add, add);
pair_op!(Sub, sub);
pair_op!(Mul, mul);
pair_op!(Div, div);

impl<L: Lanes> Neg for Pair<L> {
    type Output = Pair<L>;
    #[inline(always)]
    fn neg(self) -> Pair<L> {
        Pair(-self.0, -self.1)
    }
}

/// A comparison of both halves.
macro_rules! pair_cmp {
    ($f:ident) => {
        #[inline(always)]
        fn $f(self, o: Self) -> Self::Mask {
            PairMask(self.0.$f(o.0), self.1.$f(o.1))
        }
    };
}

impl<L: Lanes> Lanes for Pair<L> {
    type Mask = PairMask<L::Mask>;
    const LANES: usize = 2 * L::LANES;
    #[inline(always)]
    fn splat(x: f64) -> Self {
        Pair(L::splat(x), L::splat(x))
    }
    #[inline(always)]
    fn lane(self, k: usize) -> f64 {
        if k < L::LANES { self.0.lane(k) } else { self.1.lane(k - L::LANES) }
    }
    #[inline(always)]
    fn with_lane(self, k: usize, x: f64) -> Self {
        if k < L::LANES {
            Pair(self.0.with_lane(k, x), self.1)
        } else {
            Pair(self.0, self.1.with_lane(k - L::LANES, x))
        }
    }
    #[inline(always)]
    fn abs(self) -> Self {
        Pair(self.0.abs(), self.1.abs())
    }
    pair_cmp!(lt);
    pair_cmp!(le);
    pair_cmp!(gt);
    pair_cmp!(eq);
    #[inline(always)]
    fn select(m: Self::Mask, a: Self, b: Self) -> Self {
        Pair(L::select(m.0, a.0, b.0), L::select(m.1, a.1, b.1))
    }
    #[inline(always)]
    fn select_mask(m: Self::Mask, a: Self::Mask, b: Self::Mask) -> Self::Mask {
        PairMask(L::select_mask(m.0, a.0, b.0), L::select_mask(m.1, a.1, b.1))
    }
    #[inline(always)]
    fn yes() -> Self::Mask {
        PairMask(L::yes(), L::yes())
    }
    #[inline(always)]
    fn no() -> Self::Mask {
        PairMask(L::no(), L::no())
    }
    #[inline(always)]
    fn and(a: Self::Mask, b: Self::Mask) -> Self::Mask {
        PairMask(L::and(a.0, b.0), L::and(a.1, b.1))
    }
    #[inline(always)]
    fn or(a: Self::Mask, b: Self::Mask) -> Self::Mask {
        PairMask(L::or(a.0, b.0), L::or(a.1, b.1))
    }
    #[inline(always)]
    fn all(m: Self::Mask) -> bool {
        L::all(m.0) & L::all(m.1)
    }
    #[inline(always)]
    fn mask_lane(m: Self::Mask, k: usize) -> bool {
        if k < L::LANES { L::mask_lane(m.0, k) } else { L::mask_lane(m.1, k - L::LANES) }
    }
    #[inline(always)]
    fn mask_from(f: impl Fn(usize) -> bool) -> Self::Mask {
        PairMask(L::mask_from(&f), L::mask_from(|k| f(k + L::LANES)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lanes::Quad;

    /// Lane `k` of a pair is lane `k` of its first half below the half's width and lane
    /// `k − width` of its second half above, for reading, writing and masks alike.
    #[test]
    fn lanes_are_numbered_first_half_then_second() {
        let mut p = Pair::<Quad>::splat(0.0);
        for (k, v) in [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0].into_iter().enumerate() {
            p = p.with_lane(k, v);
        }
        assert_eq!(p, Pair(Quad([0.0, 1.0, 2.0, 3.0]), Quad([4.0, 5.0, 6.0, 7.0])));
        assert_eq!((0..8).map(|k| p.lane(k)).collect::<Vec<_>>(), [0.0, 1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0]);
        let odd = Pair::<Quad>::mask_from(|k| k % 2 == 1 || k == 6);
        let picked = Pair::<Quad>::select(odd, p, -p);
        assert_eq!((0..8).map(|k| picked.lane(k)).collect::<Vec<_>>(), [-0.0, 1.0, -2.0, 3.0, -4.0, 5.0, 6.0, 7.0]);
        let above = p.gt(Pair::splat(4.5));
        assert_eq!(
            (0..8).map(|k| Pair::<Quad>::mask_lane(above, k)).collect::<Vec<_>>(),
            [false, false, false, false, false, true, true, true]
        );
        assert!(!Pair::<Quad>::all(above));
        assert!(Pair::<Quad>::all(Pair::<Quad>::or(p.gt(Pair::splat(0.0)), p.eq(Pair::splat(0.0)))));
        assert!(!Pair::<Quad>::all(Pair::<Quad>::and(above, p.lt(Pair::splat(7.0)))));
    }
}
