//! Pictures of the joint examples (`examples/joints/`): every bone is drawn from its own origin
//! (an offset, a slide), found here by a forward kinematics written from the bones' fields (not
//! the library's), and every prismatic joint has a sleeve from where its slide starts to the
//! bone's origin, and a limit bar when the figure shows ranges.

use std::path::Path;

use ikarus::{Joint, RigTask};
use ikarus_edge::picture::rig_figure;
use ikarus_edge::rig::Rig;

fn rig(name: &str) -> Rig {
    Rig::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/joints").join(format!("{name}.toml")))
        .unwrap()
}

/// Every bone's origin at its start pose, from its parent's origin and direction: the offset
/// (default the parent's tip) plus, for a prismatic bone, its extension along its unit slide
/// (default along its own angle), both in the parent's frame.
fn origins(rig: &Rig) -> Vec<[f64; 2]> {
    let bones = rig.skeleton.bones();
    let base = rig.skeleton.base();
    let index = |name: &str| bones.iter().position(|b| b.name == name).unwrap();
    fn place(bones: &[ikarus::Bone], base: [f64; 2], index: &dyn Fn(&str) -> usize, i: usize) -> ([f64; 2], f64) {
        let b = &bones[i];
        let (o, phi, len) = match &b.parent {
            Some(p) => {
                let j = index(p);
                let (o, phi) = place(bones, base, index, j);
                (o, phi, bones[j].length)
            }
            None => (base, 0.0, 0.0),
        };
        let [mut x, mut y] = b.offset.unwrap_or([len, 0.0]);
        if let Joint::Prismatic { slide, extension } = b.joint {
            let [sx, sy] = slide.unwrap_or([b.angle.cos(), b.angle.sin()]);
            x += extension * sx / sx.hypot(sy);
            y += extension * sy / sx.hypot(sy);
        }
        let (s, c) = phi.sin_cos();
        ([o[0] + c * x - s * y, o[1] + s * x + c * y], phi + b.angle)
    }
    (0..bones.len()).map(|i| place(&bones, [base.x, base.y], &index, i).0).collect()
}

/// The first point of the `<path … id="ID"/>` or `<path … class="ID"/>` elements, in order.
fn starts(svg: &str, id: &str) -> Vec<(f64, f64)> {
    svg.lines()
        .filter(|l| l.starts_with("<path") && l.contains(id))
        .map(|l| {
            let d = l.split("d=\"M").nth(1).unwrap();
            let mut n = d.split([' ', 'L', 'Z', '"']).filter(|s| !s.is_empty()).map(|s| s.parse::<f64>().unwrap());
            (n.next().unwrap(), n.next().unwrap())
        })
        .collect()
}

#[test]
fn bones_start_at_their_origins_and_prismatic_joints_have_sleeves() {
    for (name, prismatic) in [("palm", 0), ("rrp", 1), ("prr", 1)] {
        let rig = rig(name);
        let pose = rig.skeleton.start_angles();
        for ranges in [false, true] {
            let figure = rig_figure(&rig, pose, &RigTask::default(), ranges, None);
            let view = figure.view(640, 480);
            let svg = ikarus_render::skeleton_svg(&figure, 640, 480).unwrap();
            for (i, o) in origins(&rig).into_iter().enumerate() {
                let (x, y) = view.world_to_pixel(ikarus::Point2::new(o[0], o[1]));
                let got = starts(&svg, &format!("id=\"bone{i}\""));
                assert_eq!(got.len(), 1, "{name} bone {i}");
                // The SVG writes pixels to 0.01.
                assert!(
                    (got[0].0 - x).abs() <= 0.006 && (got[0].1 - y).abs() <= 0.006,
                    "{name} bone {i}: {got:?} vs ({x}, {y})"
                );
            }
            assert_eq!(svg.matches("class=\"sleeve\"").count(), prismatic, "{name}");
            assert_eq!(svg.matches("class=\"slide-limits\"").count(), if ranges { prismatic } else { 0 }, "{name}");
        }
    }
}

#[test]
fn a_sleeve_runs_from_where_the_slide_starts_to_the_bones_origin() {
    let rig = rig("rrp");
    let pose = rig.skeleton.start_angles();
    let figure = rig_figure(&rig, pose, &RigTask::default(), false, None);
    let view = figure.view(640, 480);
    let svg = ikarus_render::skeleton_svg(&figure, 640, 480).unwrap();
    let line = svg.lines().find(|l| l.contains("class=\"sleeve\"")).unwrap();
    let d = line.split("d=\"M").nth(1).unwrap().split('"').next().unwrap();
    let corners: Vec<(f64, f64)> = d
        .trim_end_matches('Z')
        .split(" L")
        .map(|p| {
            let mut n = p.split(' ').filter(|s| !s.is_empty()).map(|s| s.parse::<f64>().unwrap());
            (n.next().unwrap(), n.next().unwrap())
        })
        .collect();
    assert_eq!(corners.len(), 4, "{d}");
    // The ram's extension (0.1) starts at the elbow's tip along the forearm: its ends' middles.
    let o = origins(&rig);
    let ram = rig.skeleton.index_of("ram").unwrap();
    let elbow = rig.skeleton.index_of("elbow").unwrap();
    let tip = |i: usize| {
        let phi: f64 = rig.skeleton.bones()[..=i].iter().map(|b| b.angle).sum();
        [o[i][0] + rig.skeleton.lengths()[i] * phi.cos(), o[i][1] + rig.skeleton.lengths()[i] * phi.sin()]
    };
    let mid = |a: (f64, f64), b: (f64, f64)| ((a.0 + b.0) / 2.0, (a.1 + b.1) / 2.0);
    for (end, world) in [(mid(corners[0], corners[3]), tip(elbow)), (mid(corners[1], corners[2]), o[ram])] {
        let (x, y) = view.world_to_pixel(ikarus::Point2::new(world[0], world[1]));
        assert!((end.0 - x).hypot(end.1 - y) < 0.02, "{end:?} vs ({x}, {y})");
    }
}

/// A slide's range wider than the view (the PRR carriage's −1 to 1.5 on a view of the arm) is
/// drawn only inside the plot, without end ticks where it is cut; it used to run past the plot's
/// frame to the picture's edge.
#[test]
fn a_slide_range_wider_than_the_view_stays_in_the_plot() {
    let rig = rig("prr");
    let figure = rig_figure(&rig, rig.skeleton.start_angles(), &RigTask::default(), true, None);
    let svg = ikarus_render::skeleton_svg(&figure, 640, 480).unwrap();
    // The plot: the white rectangle inside the page's background.
    let attr = |tag: &str, name: &str| -> f64 {
        let at = tag.find(&format!(" {name}=\"")).unwrap() + name.len() + 3;
        tag[at..at + tag[at..].find('"').unwrap()].parse().unwrap()
    };
    let tag = svg.split("<rect").nth(2).expect("the plot's rectangle");
    let (left, top) = (attr(tag, "x"), attr(tag, "y"));
    let (right, bottom) = (left + attr(tag, "width"), top + attr(tag, "height"));
    let path = svg.lines().find(|l| l.contains("class=\"slide-limits\"")).expect("a limits bar");
    let d = &path[path.find("d=\"").unwrap() + 3..];
    let d = &d[..d.find('"').unwrap()];
    let numbers: Vec<f64> = d
        .split(|c: char| c == ' ' || c.is_ascii_alphabetic())
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().unwrap())
        .collect();
    for p in numbers.chunks(2) {
        assert!(
            p[0] >= left - 0.01 && p[0] <= right + 0.01 && p[1] >= top - 0.01 && p[1] <= bottom + 0.01,
            "({}, {}) outside the plot [{left}, {right}] × [{top}, {bottom}]: {d}",
            p[0],
            p[1]
        );
    }
    // The bar first, then a tick at each end that is not cut by the plot's edge; this range
    // is cut on at least one side.
    let on_edge = |p: &[f64]| (p[0] - left).abs() < 0.01 || (p[0] - right).abs() < 0.01;
    let cut = numbers.chunks(2).take(2).filter(|p| on_edge(p)).count();
    assert!(cut >= 1, "the range is wider than the view: {d}");
    assert_eq!(d.matches('M').count(), 1 + (2 - cut), "{d}");
}
