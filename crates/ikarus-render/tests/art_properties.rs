//! Properties of the art's rasteriser over random meshes: a fan of triangles around a centre
//! (a star-shaped polygon) is drawn without seams and without any pixel drawn twice, even when
//! corners and edges run through pixel centres.

use ikarus_render::{Art, ArtPiece, Blend, Page, WorldToPixel, art_pixmap};
use proptest::prelude::*;

const SIDE: u32 = 64;

/// `(b − a) × (p − a)`, exact for the quarter-pixel coordinates used here.
fn cross(a: Px, b: Px, p: Px) -> f64 {
    (b.0 - a.0) * (p.1 - a.1) - (b.1 - a.1) * (p.0 - a.0)
}

/// A point in pixels (y down).
type Px = (f64, f64);

/// The fan's corners in pixels, on a quarter-pixel grid: the centre, then the rim in order of
/// angle.
fn fan(centre: (i32, i32), spokes: &[(u32, u32)]) -> Option<(Px, Vec<Px>)> {
    let total: u32 = spokes.iter().map(|s| s.0).sum();
    // Each step must turn by less than half a turn for the fan to be a star.
    if spokes.iter().any(|s| 2 * s.0 >= total) {
        return None;
    }
    let c = (f64::from(centre.0) / 4.0, f64::from(centre.1) / 4.0);
    let mut turned = 0;
    let rim: Vec<Px> = spokes
        .iter()
        .map(|&(step, radius)| {
            turned += step;
            let angle = std::f64::consts::TAU * f64::from(turned) / f64::from(total);
            let r = f64::from(radius) / 4.0;
            ((4.0 * (c.0 + r * angle.cos())).round() / 4.0, (4.0 * (c.1 + r * angle.sin())).round() / 4.0)
        })
        .collect();
    // After snapping every triangle must keep its turn (no fold-over), or overlaps are real.
    let positive = (0..rim.len()).all(|i| cross(c, rim[i], rim[(i + 1) % rim.len()]) > 0.0);
    positive.then_some((c, rim))
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    #[test]
    fn a_fan_has_no_seams_and_no_pixel_drawn_twice(
        centre in (80i32..176, 80i32..176),
        spokes in prop::collection::vec((1u32..8, 8u32..120), 3..12),
        reversed in any::<bool>(),
    ) {
        let Some((c, rim)) = fan(centre, &spokes) else { return Ok(()) };
        let n = rim.len();
        // World = pixels with y flipped; the corners stay on the quarter grid.
        let h = f64::from(SIDE);
        let mut positions = vec![[c.0 as f32, (h - c.1) as f32]];
        positions.extend(rim.iter().map(|p| [p.0 as f32, (h - p.1) as f32]));
        let triangles: Vec<[u16; 3]> = (0..n as u16)
            .map(|i| {
                let (a, b) = (1 + i, 1 + (i + 1) % n as u16);
                if reversed { [0, b, a] } else { [0, a, b] }
            })
            .collect();
        let piece = ArtPiece {
            page: 0,
            uvs: vec![[0.5, 0.5]; positions.len()],
            positions,
            triangles,
            color: [1.0, 1.0, 1.0, 0.6],
            dark: None,
            blend: Blend::Normal,
        };
        let art = Art { pages: &[Page { width: 1, height: 1, rgba: vec![255; 4], pma: false }], pieces: vec![piece] };
        let to_pixel = WorldToPixel { xx: 1.0, xy: 0.0, yx: 0.0, yy: -1.0, tx: 0.0, ty: h };
        let pixmap = art_pixmap(&art, &to_pixel, SIDE, SIDE).unwrap();
        for y in 0..SIDE {
            for x in 0..SIDE {
                let a = pixmap.data()[4 * (y * SIDE + x) as usize + 3];
                // Alpha 0.6 once is 153; twice would be 214.
                prop_assert!(a == 0 || a == 153, "pixel ({}, {}) has alpha {}", x, y, a);
                let p = (f64::from(x) + 0.5, f64::from(y) + 0.5);
                // Must be drawn: strictly inside a triangle, on a spoke strictly inside the
                // fan, or the centre itself.
                let must = p == c
                    || (0..n).any(|i| {
                        let (v, w) = (rim[i], rim[(i + 1) % n]);
                        let (e0, e1, e2) = (cross(c, v, p), cross(v, w, p), cross(w, c, p));
                        // Inside, or on the spoke c–v between c and v (e0 = 0).
                        e0 >= 0.0 && e1 > 0.0 && e2 > 0.0
                    });
                prop_assert!(!must || a == 153, "pixel ({}, {}) inside the fan is not drawn", x, y);
            }
        }
    }
}
