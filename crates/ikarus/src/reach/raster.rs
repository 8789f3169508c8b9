//! The grid while sampling: one bit per cell, painted by any number of threads at once.

use std::sync::atomic::{AtomicU64, Ordering};

use super::region::Slice;

/// Centre of cell `i` along an axis starting at `origin`: `origin + h (i + ½)`. The one formula
/// used when rasterising and when answering queries.
pub(super) fn cell_centre(origin: f64, h: f64, i: u32) -> f64 {
    origin + h * (f64::from(i) + 0.5)
}

/// The index of the cell holding `v` along an axis of `resolution` cells of side `h` from
/// `origin`: `None` outside `[origin, origin + h·resolution]` (or for NaN); the far end belongs
/// to the last cell. The one rule used when marking points and when answering queries.
pub(super) fn cell_index(v: f64, origin: f64, h: f64, resolution: u32) -> Option<u32> {
    let t = (v - origin) / h;
    let n = f64::from(resolution);
    // `t` in [0, n] (NaN fails both comparisons); the cast is exact after the floor.
    (0.0..=n).contains(&t).then(|| (t.floor() as u32).min(resolution - 1))
}

/// The grid while sampling: one bit per cell, rows of whole 64-bit words, set with atomic OR so
/// that any number of threads can paint at once and the result does not depend on order.
pub(super) struct Raster {
    pub(super) origin: [f64; 2],
    pub(super) h: f64,
    pub(super) resolution: u32,
    words_per_row: usize,
    bits: Vec<AtomicU64>,
}

impl Raster {
    pub(super) fn new(origin: [f64; 2], h: f64, resolution: u32) -> Raster {
        let words_per_row = (resolution as usize).div_ceil(64);
        let bits = (0..words_per_row * resolution as usize).map(|_| AtomicU64::new(0)).collect();
        Raster { origin, h, resolution, words_per_row, bits }
    }

    /// Indices of the cells whose centres may lie in `[lo, hi]` along an axis, widened by one
    /// cell against rounding; `None` if none.
    fn index_range(&self, origin: f64, lo: f64, hi: f64) -> Option<(u32, u32)> {
        let last = f64::from(self.resolution - 1);
        let i0 = ((lo - origin) / self.h - 0.5).ceil() - 1.0;
        let i1 = ((hi - origin) / self.h - 0.5).floor() + 1.0;
        if i1 < 0.0 || i0 > last {
            return None;
        }
        Some((i0.max(0.0) as u32, i1.min(last) as u32))
    }

    /// Sets the bit of every cell whose centre lies in `slice`, testing only the cells within
    /// `a + b` of `P` whose bit is not yet set, and writing each word of a row at most once.
    /// (Skipping set bits changes nothing but the time: the result is still the OR of all
    /// slices.)
    pub(super) fn paint(&self, slice: &Slice) {
        self.paint_disk(slice.p, slice.a + slice.b, slice.bounds, |q| slice.contains(q));
    }

    /// Sets the bit of every cell whose centre `q` lies within `reach` of `p`, within the box
    /// `[x_min, x_max, y_min, y_max]`, and has `inside(q)`.
    pub(super) fn paint_disk(&self, p: [f64; 2], reach: f64, bounds: [f64; 4], inside: impl Fn([f64; 2]) -> bool) {
        let [px, py] = p;
        let Some((y0, y1)) = self.index_range(self.origin[1], bounds[2], bounds[3]) else { return };
        for iy in y0..=y1 {
            let cy = cell_centre(self.origin[1], self.h, iy);
            let dy = cy - py;
            let half = reach * reach - dy * dy;
            if half < 0.0 {
                continue;
            }
            let half = half.sqrt();
            let (lo, hi) = ((px - half).max(bounds[0]), (px + half).min(bounds[1]));
            let Some((x0, x1)) = self.index_range(self.origin[0], lo, hi) else { continue };
            let row = &self.bits[iy as usize * self.words_per_row..(iy as usize + 1) * self.words_per_row];
            let mut word = x0 as usize / 64;
            let mut set = row[word].load(Ordering::Relaxed);
            let mut mask = 0u64;
            for ix in x0..=x1 {
                if ix as usize / 64 != word {
                    if mask != 0 {
                        row[word].fetch_or(mask, Ordering::Relaxed);
                    }
                    word = ix as usize / 64;
                    set = row[word].load(Ordering::Relaxed);
                    mask = 0;
                }
                let bit = 1 << (ix % 64);
                if set & bit == 0 && inside([cell_centre(self.origin[0], self.h, ix), cy]) {
                    mask |= bit;
                }
            }
            if mask != 0 {
                row[word].fetch_or(mask, Ordering::Relaxed);
            }
        }
    }

    /// Sets the bit of the cell holding `p` (a point on the grid's right or top edge belongs to
    /// the last column or row); nothing for a point outside the grid.
    pub(super) fn mark(&self, p: [f64; 2]) {
        let index = |v: f64, o: f64| cell_index(v, o, self.h, self.resolution);
        if let (Some(ix), Some(iy)) = (index(p[0], self.origin[0]), index(p[1], self.origin[1])) {
            let word = iy as usize * self.words_per_row + ix as usize / 64;
            self.bits[word].fetch_or(1 << (ix % 64), Ordering::Relaxed);
        }
    }

    /// The cells, row by row from the bottom.
    pub(super) fn into_cells(self) -> Vec<bool> {
        let words: Vec<u64> = self.bits.into_iter().map(AtomicU64::into_inner).collect();
        let res = self.resolution as usize;
        let mut cells = Vec::with_capacity(res * res);
        for row in words.chunks_exact(self.words_per_row) {
            cells.extend((0..res).map(|ix| row[ix / 64] >> (ix % 64) & 1 == 1));
        }
        cells
    }
}
