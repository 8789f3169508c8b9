//! One 256-colour palette for a whole GIF: the style's solid colours exactly, the rest learnt by
//! NeuQuant from sample frames, and one index kept for "unchanged since the last frame".

use std::collections::HashMap;

/// NeuQuant's sampling factor: 1 is best and slowest, 30 fastest; 10 is the gif crate's
/// suggestion for a good balance. It runs once per GIF, on a few frames.
const QUANTISER_SPEED: i32 = 10;

/// The palette index never given to a colour: frames after the first mark pixels that did not
/// change with it and declare it transparent.
pub(crate) const UNCHANGED: u8 = 255;

/// A global GIF palette and a memo of which entry each colour maps to.
pub(crate) struct Palette {
    /// Entries 0..255 as RGB; entry 255 ([`UNCHANGED`]) is a placeholder.
    colours: Vec<[u8; 3]>,
    /// Colours seen so far and their entries.
    memo: HashMap<[u8; 3], u8>,
}

impl Palette {
    /// `keys` exactly (at most 64 of them), then `255 − keys.len()` colours NeuQuant learns from
    /// `sample` (opaque RGBA pixels).
    pub(crate) fn learn(sample: &[u8], keys: &[[u8; 3]]) -> Self {
        debug_assert!(keys.len() <= 64, "NeuQuant needs room to learn");
        let learnt = 255 - keys.len();
        let nq = color_quant::NeuQuant::new(QUANTISER_SPEED, learnt, sample);
        let mut colours: Vec<[u8; 3]> = keys.to_vec();
        colours.extend(nq.color_map_rgb().chunks_exact(3).map(|c| [c[0], c[1], c[2]]));
        colours.resize(255, [0, 0, 0]);
        let memo = keys.iter().enumerate().map(|(i, &k)| (k, i as u8)).collect();
        colours.push([0, 0, 0]);
        Self { colours, memo }
    }

    /// The palette as `r, g, b, …` for the GIF's global colour table (256 entries).
    pub(crate) fn rgb_table(&self) -> Vec<u8> {
        self.colours.iter().flatten().copied().collect()
    }

    /// The entry nearest `colour` (squared RGB distance; the first of equals), never
    /// [`UNCHANGED`]. Key colours map to themselves.
    fn nearest(&self, colour: [u8; 3]) -> u8 {
        let dist =
            |c: &[u8; 3]| -> i32 { c.iter().zip(colour).map(|(&a, b)| (i32::from(a) - i32::from(b)).pow(2)).sum() };
        let mut best = (i32::MAX, 0u8);
        for (i, c) in self.colours[..usize::from(UNCHANGED)].iter().enumerate() {
            let d = dist(c);
            if d < best.0 {
                best = (d, i as u8);
            }
        }
        best.1
    }

    /// Palette indices of opaque RGBA pixels, written into `out` (cleared first).
    pub(crate) fn map_into(&mut self, rgba: &[u8], out: &mut Vec<u8>) {
        out.clear();
        out.reserve(rgba.len() / 4);
        // Neighbouring pixels mostly share a colour: remember the last one.
        let mut last: Option<([u8; 3], u8)> = None;
        for p in rgba.chunks_exact(4) {
            let colour = [p[0], p[1], p[2]];
            let index = match last {
                Some((c, i)) if c == colour => i,
                _ => {
                    let i = match self.memo.get(&colour) {
                        Some(&i) => i,
                        None => {
                            let i = self.nearest(colour);
                            self.memo.insert(colour, i);
                            i
                        }
                    };
                    last = Some((colour, i));
                    i
                }
            };
            out.push(index);
        }
    }

    /// The RGB colour of entry `index`.
    #[cfg(test)]
    pub(crate) fn colour(&self, index: u8) -> [u8; 3] {
        self.colours[usize::from(index)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_stay_exact_and_the_unchanged_index_is_never_used() {
        let keys = [[0xd6, 0x27, 0x28], [255, 255, 255], [0x26, 0x32, 0x4a]];
        // A sample dominated by greys, with a few red pixels.
        let mut sample = Vec::new();
        for i in 0..10_000u32 {
            let g = (i % 256) as u8;
            sample.extend([g, g, g, 255]);
        }
        sample.extend([0xd6, 0x27, 0x28, 255].repeat(5));
        let mut palette = Palette::learn(&sample, &keys);
        assert_eq!(palette.rgb_table().len(), 256 * 3);
        let mut out = Vec::new();
        palette.map_into(&[0xd6, 0x27, 0x28, 255, 255, 255, 255, 255, 0, 0, 0, 255], &mut out);
        assert_eq!(palette.colour(out[0]), keys[0]);
        assert_eq!(palette.colour(out[1]), keys[1]);
        assert!(out.iter().all(|&i| i != UNCHANGED));
        // A colour near a key but not equal maps to something close.
        palette.map_into(&[0xd0, 0x2a, 0x2a, 255], &mut out);
        let c = palette.colour(out[0]);
        assert!(c.iter().zip([0xd0, 0x2a, 0x2a]).all(|(&a, b): (&u8, u8)| a.abs_diff(b) < 12), "{c:?}");
    }
}
