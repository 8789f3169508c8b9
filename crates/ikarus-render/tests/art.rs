//! Drawing a character's art: coverage without seams, UV mapping, sampling, tint, blend modes,
//! premultiplied and straight pages, determinism and bounded work. Synthetic art, expectations
//! derived by hand from the rules in `art_raster.rs`.

use ikarus_render::{
    Art, ArtPiece, Blend, Page, Pixmap, RenderError, WorldToPixel, art_pixmap, draw_art, draw_svg_onto, pixmap_png,
};

/// World y up to pixels y down on a picture `height` pixels tall: pixel (x, y) = world (x, height − y).
fn flip(height: u32) -> WorldToPixel {
    WorldToPixel { xx: 1.0, xy: 0.0, yx: 0.0, yy: -1.0, tx: 0.0, ty: f64::from(height) }
}

fn page(width: u32, height: u32, texels: &[[u8; 4]], pma: bool) -> Page {
    assert_eq!(texels.len(), (width * height) as usize);
    Page { width, height, rgba: texels.concat(), pma }
}

fn opaque_white() -> Page {
    page(1, 1, &[[255; 4]], false)
}

/// A quad as two triangles sharing the diagonal 0–2.
fn quad(corners: [[f32; 2]; 4], uvs: [[f32; 2]; 4], color: [f32; 4]) -> ArtPiece {
    ArtPiece {
        page: 0,
        positions: corners.to_vec(),
        uvs: uvs.to_vec(),
        triangles: vec![[0, 1, 2], [0, 2, 3]],
        color,
        dark: None,
        blend: Blend::Normal,
    }
}

const FULL_UV: [[f32; 2]; 4] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];

fn pixel(pixmap: &Pixmap, x: u32, y: u32) -> [u8; 4] {
    let k = 4 * (y * pixmap.width() + x) as usize;
    pixmap.data()[k..k + 4].try_into().unwrap()
}

fn alphas(pixmap: &Pixmap) -> Vec<u8> {
    pixmap.data().chunks_exact(4).map(|p| p[3]).collect()
}

#[test]
fn a_square_of_two_triangles_covers_each_pixel_inside_once() {
    // Corners on pixel centres (2.5 … 12.5): the diagonal and all four sides run through
    // centres. By the top-left rule the left and top sides are in, the right and bottom out:
    // exactly the 10 × 10 pixels 2..12 in both directions.
    let h = 16;
    let to_y = |py: f32| h as f32 - py;
    let corners = [[2.5, to_y(2.5)], [12.5, to_y(2.5)], [12.5, to_y(12.5)], [2.5, to_y(12.5)]];
    for (tint_alpha, want) in [(1.0, 255u8), (0.6, 153)] {
        let art = Art { pages: &[opaque_white()], pieces: vec![quad(corners, FULL_UV, [1.0, 1.0, 1.0, tint_alpha])] };
        let pixmap = art_pixmap(&art, &flip(h), h, h).unwrap();
        for y in 0..h {
            for x in 0..h {
                let inside = (2..12).contains(&x) && (2..12).contains(&y);
                let a = pixel(&pixmap, x, y)[3];
                // Alpha 0.6 drawn twice would be 0.84 (214): every inside pixel is drawn once.
                assert_eq!(a, if inside { want } else { 0 }, "pixel ({x}, {y}) at tint alpha {tint_alpha}");
            }
        }
    }
}

#[test]
fn a_rotated_mesh_has_no_seams_and_no_pixel_drawn_twice() {
    // A 5 × 5 grid of quads with wobbling inner vertices, rotated by 0.3 rad, at alpha 0.6:
    // every pixel whose centre lies clearly inside the outline has alpha 153 (once), none 214.
    let n = 5;
    let (angle, size, centre) = (0.3_f64, 40.0_f64, (32.0_f64, 32.0_f64));
    let mut positions = Vec::new();
    for j in 0..=n {
        for i in 0..=n {
            let inner = i > 0 && i < n && j > 0 && j < n;
            let wobble = if inner { 1.7 * (((i * 7 + j * 3) % 5) as f64 / 5.0 - 0.4) } else { 0.0 };
            let (lx, ly) = (size * (i as f64 / n as f64 - 0.5) + wobble, size * (j as f64 / n as f64 - 0.5) - wobble);
            let (x, y) =
                (centre.0 + angle.cos() * lx - angle.sin() * ly, centre.1 + angle.sin() * lx + angle.cos() * ly);
            positions.push([x as f32, y as f32]);
        }
    }
    let k = |i: u16, j: u16| j * (n as u16 + 1) + i;
    let mut triangles = Vec::new();
    for j in 0..n as u16 {
        for i in 0..n as u16 {
            // Alternate the diagonal, and the winding, from quad to quad.
            if (i + j) % 2 == 0 {
                triangles.extend([[k(i, j), k(i + 1, j), k(i + 1, j + 1)], [k(i, j), k(i + 1, j + 1), k(i, j + 1)]]);
            } else {
                triangles.extend([[k(i, j), k(i, j + 1), k(i + 1, j)], [k(i + 1, j), k(i, j + 1), k(i + 1, j + 1)]]);
            }
        }
    }
    let uvs = vec![[0.5, 0.5]; positions.len()];
    let piece =
        ArtPiece { page: 0, positions, uvs, triangles, color: [1.0, 1.0, 1.0, 0.6], dark: None, blend: Blend::Normal };
    let art = Art { pages: &[opaque_white()], pieces: vec![piece] };
    let side = 64;
    let pixmap = art_pixmap(&art, &flip(side), side, side).unwrap();
    let mut inside = 0;
    for y in 0..side {
        for x in 0..side {
            let a = pixel(&pixmap, x, y)[3];
            assert!(a == 0 || a == 153, "pixel ({x}, {y}) has alpha {a}");
            // The centre in the world, then in the square's own frame.
            let (wx, wy) = (f64::from(x) + 0.5 - centre.0, f64::from(side - y) - 0.5 - centre.1);
            let (lx, ly) = (angle.cos() * wx + angle.sin() * wy, -angle.sin() * wx + angle.cos() * wy);
            if lx.abs().max(ly.abs()) < 0.5 * size - 1e-2 {
                inside += 1;
                assert_eq!(a, 153, "pixel ({x}, {y}) inside the mesh was not drawn");
            }
        }
    }
    // About 40² pixels lie inside.
    assert!((1500..1700).contains(&inside), "{inside}");
}

/// Red, green on the page's top row; blue, white below.
fn four_colours() -> Page {
    page(2, 2, &[[255, 0, 0, 255], [0, 255, 0, 255], [0, 0, 255, 255], [255, 255, 255, 255]], false)
}

const RED: [u8; 4] = [255, 0, 0, 255];
const GREEN: [u8; 4] = [0, 255, 0, 255];
const BLUE: [u8; 4] = [0, 0, 255, 255];
const WHITE: [u8; 4] = [255; 4];

#[test]
fn uvs_put_each_colour_in_its_quarter() {
    // The quad covers the 16 × 16 picture with v = 0 at the top; texel centres are at u, v =
    // ¼ and ¾, so pixels whose centre has u, v < ¼ or > ¾ show one texel unmixed.
    let h = 16;
    let corners = [[0.0, 16.0], [16.0, 16.0], [16.0, 0.0], [0.0, 0.0]];
    let art = Art { pages: &[four_colours()], pieces: vec![quad(corners, FULL_UV, [1.0; 4])] };
    let pixmap = art_pixmap(&art, &flip(h), h, h).unwrap();
    for (x, y, want) in [(1, 1, RED), (3, 0, RED), (14, 1, GREEN), (12, 3, GREEN), (1, 14, BLUE), (15, 15, WHITE)] {
        assert_eq!(pixel(&pixmap, x, y), want, "pixel ({x}, {y})");
    }
    // Between texel centres the colours mix: pixel (5, 5) is mostly red, some of each other.
    let p = pixel(&pixmap, 5, 5);
    assert!(p[0] > p[1] && p[0] > p[2] && p[1] > 0 && p[2] > 0, "{p:?}");
}

#[test]
fn a_rotated_quad_carries_its_colours_with_it() {
    for angle in [std::f64::consts::FRAC_PI_2, 0.5, -2.2] {
        // A 40-unit square about (32, 32) rotated by `angle`; the UV (u, v) sits at the corner
        // mix: world = c0 + u·(c1 − c0) + v·(c3 − c0).
        let rot = |x: f64, y: f64| (32.0 + angle.cos() * x - angle.sin() * y, 32.0 + angle.sin() * x + angle.cos() * y);
        let local = [(-20.0, 20.0), (20.0, 20.0), (20.0, -20.0), (-20.0, -20.0)];
        let world = local.map(|(x, y)| rot(x, y));
        let corners = world.map(|(x, y)| [x as f32, y as f32]);
        let art = Art { pages: &[four_colours()], pieces: vec![quad(corners, FULL_UV, [1.0; 4])] };
        let side = 64;
        let pixmap = art_pixmap(&art, &flip(side), side, side).unwrap();
        for (u, v, want) in [(0.1, 0.1, RED), (0.9, 0.1, GREEN), (0.1, 0.9, BLUE), (0.9, 0.9, WHITE)] {
            let wx = world[0].0 + u * (world[1].0 - world[0].0) + v * (world[3].0 - world[0].0);
            let wy = world[0].1 + u * (world[1].1 - world[0].1) + v * (world[3].1 - world[0].1);
            let (x, y) = (wx.floor() as u32, (f64::from(side) - wy).floor() as u32);
            assert_eq!(pixel(&pixmap, x, y), want, "uv ({u}, {v}) at pixel ({x}, {y}), angle {angle}");
        }
    }
}

/// A 16 × 16 quad filling the picture whose every UV is `(u, v)`: each pixel samples that point.
fn sampled_at(page: Page, u: f32, v: f32, color: [f32; 4], dark: Option<[f32; 3]>) -> [u8; 4] {
    let corners = [[0.0, 16.0], [16.0, 16.0], [16.0, 0.0], [0.0, 0.0]];
    let mut piece = quad(corners, [[u, v]; 4], color);
    piece.dark = dark;
    let art = Art { pages: &[page], pieces: vec![piece] };
    let pixmap = art_pixmap(&art, &flip(16), 16, 16).unwrap();
    let first = pixel(&pixmap, 0, 0);
    assert!(pixmap.data().chunks_exact(4).all(|p| p == first), "every pixel samples the same point");
    first
}

#[test]
fn bilinear_sampling_at_and_between_texels() {
    let black_white = || page(2, 1, &[[0, 0, 0, 255], [255, 255, 255, 255]], false);
    // At a texel's centre (u = ¼) the texel itself; on the boundary (u = ½) the mean, 127.5 →
    // 128; at u = 3/8 (x = 0.25 in texels) a quarter white, 63.75 → 64.
    assert_eq!(sampled_at(black_white(), 0.25, 0.5, [1.0; 4], None), [0, 0, 0, 255]);
    assert_eq!(sampled_at(black_white(), 0.5, 0.5, [1.0; 4], None), [128, 128, 128, 255]);
    assert_eq!(sampled_at(black_white(), 0.375, 0.5, [1.0; 4], None), [64, 64, 64, 255]);
    // Beyond the page's edge the border texel (clamp to edge).
    assert_eq!(sampled_at(black_white(), 1.5, -3.0, [1.0; 4], None), [255; 4]);
    // Filtering is premultiplied: opaque red beside transparent blue gives half-transparent
    // red, never a trace of the invisible blue.
    let red_clear = page(2, 1, &[[255, 0, 0, 255], [0, 0, 255, 0]], false);
    assert_eq!(sampled_at(red_clear, 0.5, 0.5, [1.0; 4], None), [128, 0, 0, 128]);
}

#[test]
fn tint_and_two_colour_tint() {
    // Premultiplied tint: (0.5, 0.25, 1, 0.8) on white → (0.4, 0.2, 0.8, 0.8) → 102, 51, 204, 204.
    let white = opaque_white();
    assert_eq!(sampled_at(white.clone(), 0.5, 0.5, [0.5, 0.25, 1.0, 0.8], None), [102, 51, 204, 204]);
    // Two-colour tint, light L = (1, 0.5, 0), dark D = (0, 0.2, 0.6), alpha 1: white → L,
    // black → D, grey 102/255 = 0.4 → 0.4·L + 0.6·D = (0.4, 0.32, 0.36) → 102, 81.6, 91.8.
    let light = [1.0, 0.5, 0.0, 1.0];
    let dark = Some([0.0, 0.2, 0.6]);
    assert_eq!(sampled_at(white, 0.5, 0.5, light, dark), [255, 128, 0, 255]);
    assert_eq!(sampled_at(page(1, 1, &[[0, 0, 0, 255]], false), 0.5, 0.5, light, dark), [0, 51, 153, 255]);
    let grey = page(1, 1, &[[102, 102, 102, 255]], false);
    assert_eq!(sampled_at(grey, 0.5, 0.5, light, dark), [102, 82, 92, 255]);
    // A transparent texel stays transparent whatever the dark colour.
    assert_eq!(sampled_at(page(1, 1, &[[0, 0, 0, 0]], false), 0.5, 0.5, light, dark), [0; 4]);
}

#[test]
fn each_blend_mode_on_one_pixel() {
    // Source: white tinted (0.5, 0.25, 1, 0.8): premultiplied s = (0.4, 0.2, 0.8), alpha 0.8.
    // Destination: opaque d = (0.2, 0.4, 0.6) = bytes (51, 102, 153).
    let cases = [
        // s + 0.2·d = (0.44, 0.28, 0.92) → 112.2, 71.4, 234.6.
        (Blend::Normal, [112, 71, 235, 255]),
        // min(1, s + d) = (0.6, 0.6, 1).
        (Blend::Additive, [153, 153, 255, 255]),
        // Over opaque: 0.2·d + s·d = (0.04 + 0.08, 0.08 + 0.08, 0.12 + 0.48) → 30.6, 40.8, 153.
        (Blend::Multiply, [31, 41, 153, 255]),
        // s + d − s·d = (0.52, 0.52, 0.92) → 132.6, 132.6, 234.6.
        (Blend::Screen, [133, 133, 235, 255]),
    ];
    for (mode, want) in cases {
        let corners = [[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0]];
        let mut piece = quad(corners, FULL_UV, [0.5, 0.25, 1.0, 0.8]);
        piece.blend = mode;
        let art = Art { pages: &[opaque_white()], pieces: vec![piece] };
        let mut pixmap = Pixmap::new(2, 2).unwrap();
        for p in pixmap.data_mut().chunks_exact_mut(4) {
            p.copy_from_slice(&[51, 102, 153, 255]);
        }
        draw_art(&art, &flip(2), &mut pixmap).unwrap();
        assert_eq!(pixel(&pixmap, 0, 1), want, "{mode:?}");
        assert_eq!(pixel(&pixmap, 1, 1), [51, 102, 153, 255], "{mode:?}: outside the quad");
    }
}

#[test]
fn straight_and_premultiplied_pages_draw_the_same_picture() {
    // Texels whose premultiplication is exact in 8 bits (alpha 255, 0, or colour 255 at 51, 102).
    let straight = [[255, 0, 0, 255], [0, 255, 0, 51], [255, 255, 255, 0], [0, 0, 255, 102]];
    let pma = [[255, 0, 0, 255], [0, 51, 0, 51], [0, 0, 0, 0], [0, 0, 102, 102]];
    let draw = |texels: &[[u8; 4]], pma: bool| {
        let corners = [[3.0, 5.0], [60.0, 12.0], [50.0, 61.0], [8.0, 40.0]];
        let mut piece = quad(corners, [[-0.1, 0.0], [1.2, 0.1], [0.9, 1.0], [0.0, 0.8]], [0.9, 0.7, 1.0, 0.6]);
        piece.blend = Blend::Screen;
        let art = Art { pages: &[page(2, 2, texels, pma)], pieces: vec![piece.clone(), piece] };
        art_pixmap(&art, &flip(64), 64, 64).unwrap().data().to_vec()
    };
    let a = draw(&straight, false);
    assert!(a.chunks_exact(4).filter(|p| p[3] > 0).count() > 1000);
    assert_eq!(a, draw(&pma, true));
    // …and the flag matters: the straight texels read as premultiplied differ.
    assert_ne!(a, draw(&straight, true));
}

fn mesh_art(pages: &[Page]) -> Art<'_> {
    let positions = vec![[1.3, 2.7], [30.1, 4.4], [28.2, 29.9], [3.3, 31.7], [16.0, 16.5]];
    let uvs = vec![[0.0, 1.0], [1.0, 1.0], [1.0, 0.0], [0.0, 0.0], [0.45, 0.55]];
    let triangles = vec![[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]];
    let piece = |blend, color| ArtPiece {
        page: 0,
        positions: positions.clone(),
        uvs: uvs.clone(),
        triangles: triangles.clone(),
        color,
        dark: None,
        blend,
    };
    Art {
        pages,
        pieces: vec![piece(Blend::Normal, [1.0, 0.9, 0.8, 0.7]), piece(Blend::Multiply, [0.3, 1.0, 0.5, 0.9])],
    }
}

#[test]
fn the_same_art_gives_the_same_bytes() {
    let pages = [four_colours()];
    let art = mesh_art(&pages);
    let first = art_pixmap(&art, &flip(32), 32, 32).unwrap();
    let second = art_pixmap(&art.clone(), &flip(32), 32, 32).unwrap();
    assert_eq!(first.data(), second.data());
    assert!(alphas(&first).iter().filter(|&&a| a > 0).count() > 500);
}

#[test]
fn huge_degenerate_and_broken_triangles_are_bounded_and_never_panic() {
    let side = 64;
    let draw = |positions: Vec<[f32; 2]>| {
        let n = positions.len();
        let piece = ArtPiece {
            page: 0,
            positions,
            uvs: vec![[0.5, 0.5]; n],
            triangles: vec![[0, 1, 2]],
            color: [1.0; 4],
            dark: None,
            blend: Blend::Normal,
        };
        let art = Art { pages: &[opaque_white()], pieces: vec![piece] };
        alphas(&art_pixmap(&art, &flip(side), side, side).unwrap()).iter().filter(|&&a| a > 0).count()
    };
    // A triangle a million pixels across covers the whole picture, visiting only its pixels.
    assert_eq!(draw(vec![[-1.0e6, -1.0e6], [1.0e6, -1.0e6], [0.0, 1.0e6]]), 64 * 64);
    // Beyond 2²¹ pixels from the origin a triangle is skipped.
    assert_eq!(draw(vec![[-1.0e9, -1.0e9], [1.0e9, -1.0e9], [0.0, 1.0e9]]), 0);
    // No area: a repeated corner, collinear corners, a point.
    assert_eq!(draw(vec![[1.0, 1.0], [1.0, 1.0], [40.0, 50.0]]), 0);
    assert_eq!(draw(vec![[0.0, 0.0], [10.0, 10.0], [30.0, 30.0]]), 0);
    assert_eq!(draw(vec![[5.0, 5.0]; 3]), 0);
    // Non-finite corners.
    assert_eq!(draw(vec![[f32::NAN, 0.0], [10.0, 10.0], [30.0, 0.0]]), 0);
    assert_eq!(draw(vec![[f32::INFINITY, 0.0], [10.0, 10.0], [30.0, 0.0]]), 0);
    // Entirely off the picture.
    assert_eq!(draw(vec![[-50.0, -50.0], [-10.0, -50.0], [-30.0, -10.0]]), 0);
    // A sliver thinner than a pixel covers at most the centres it contains.
    assert!(draw(vec![[0.0, 10.25], [64.0, 10.25], [64.0, 10.75]]) <= 64);
    // A non-finite view draws nothing rather than panicking.
    let pages = [four_colours()];
    let art = mesh_art(&pages);
    let bad = WorldToPixel { tx: f64::NAN, ..flip(side) };
    assert!(alphas(&art_pixmap(&art, &bad, side, side).unwrap()).iter().all(|&a| a == 0));
}

#[test]
fn bad_art_is_an_error_and_draws_nothing() {
    let pages = [four_colours()];
    let mut art = mesh_art(&pages);
    art.pieces[1].triangles.push([0, 1, 9]);
    let mut pixmap = Pixmap::new(32, 32).unwrap();
    let err = draw_art(&art, &flip(32), &mut pixmap).unwrap_err();
    assert!(matches!(err, RenderError::Art { .. }), "{err:?}");
    assert_eq!(err.to_string(), "pieces[1].triangles[4]: indices [0, 1, 9] must be below the 5 positions");
    assert!(alphas(&pixmap).iter().all(|&a| a == 0));
    assert!(matches!(
        art_pixmap(&mesh_art(&pages), &flip(32), 8, 32),
        Err(RenderError::Size { field: "width", value: 8 })
    ));
    // A page without pixels is an error, not a panic when sampling.
    let empty = Art { pages: &[page(0, 0, &[], false)], ..mesh_art(&pages) };
    assert!(matches!(art_pixmap(&empty, &flip(32), 32, 32), Err(RenderError::Art { .. })));
}

#[test]
fn an_svg_is_drawn_over_the_art_and_the_pair_encodes_as_png() {
    // Art: an opaque red square over the whole 20 × 20 picture; then an SVG with a blue
    // rectangle over its left half.
    let corners = [[0.0, 20.0], [20.0, 20.0], [20.0, 0.0], [0.0, 0.0]];
    let art = Art { pages: &[page(1, 1, &[RED], false)], pieces: vec![quad(corners, FULL_UV, [1.0; 4])] };
    let mut pixmap = art_pixmap(&art, &flip(20), 20, 20).unwrap();
    let svg = "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"20\" height=\"20\">\
               <rect x=\"0\" y=\"0\" width=\"10\" height=\"20\" fill=\"#0000ff\"/></svg>";
    draw_svg_onto(svg, &mut pixmap).unwrap();
    assert_eq!(pixel(&pixmap, 3, 10), BLUE);
    assert_eq!(pixel(&pixmap, 16, 10), RED);
    assert!(matches!(draw_svg_onto("not svg", &mut pixmap), Err(RenderError::Svg(_))));
    let png = pixmap_png(&pixmap).unwrap();
    let back = Page::decode_png(&png, "pair.png", false).unwrap();
    assert_eq!((back.width, back.height), (20, 20));
    assert_eq!(&back.rgba[..4], &BLUE);
}
