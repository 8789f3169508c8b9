//! Pictures of skeletons: the SVG parses and holds what the figure asks for (one path per bone,
//! one marker per goal and per pin), the PNG decodes at its size, a one-branch skeleton draws
//! the arm's links, every tip lies in the view, and the shipped rigs draw.

use ikarus::{Bone, Chain, JointLimits, Link, Point2, Skeleton};
use ikarus_render::{ArmFigure, BoneGoal, SkeletonFigure, arm_svg, skeleton_png, skeleton_svg};
use resvg::usvg;

/// A rig file of `examples/rigs/` as a skeleton, read with the toml crate the way the CLI's
/// reader does (the render crate cannot use the CLI): `base`, then `[[bones]]` with `name`,
/// `parent`, `length`, `angle_deg` and `limits_deg`.
fn rig(name: &str) -> Skeleton {
    let path = format!("{}/../../examples/rigs/{name}.toml", env!("CARGO_MANIFEST_DIR"));
    let text = std::fs::read_to_string(&path).expect("the shipped rig");
    let table: toml::Table = text.parse().expect("TOML");
    let float = |v: &toml::Value| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)).expect("a number");
    let base = table.get("base").and_then(|b| b.as_array()).map_or([0.0, 0.0], |b| [float(&b[0]), float(&b[1])]);
    let bones: Vec<Bone> = table["bones"]
        .as_array()
        .expect("[[bones]]")
        .iter()
        .map(|b| {
            let mut bone = Bone::new(
                b["name"].as_str().expect("a name"),
                float(&b["length"]),
                float(&b["angle_deg"]).to_radians(),
            );
            if let Some(p) = b.get("parent") {
                bone = bone.with_parent(p.as_str().expect("a parent's name"));
            }
            if let Some(l) = b.get("limits_deg").and_then(|l| l.as_array()) {
                bone =
                    bone.with_limits(JointLimits::new(float(&l[0]).to_radians(), float(&l[1]).to_radians()).unwrap());
            }
            bone
        })
        .collect();
    Skeleton::new(base, &bones).expect("a valid rig")
}

fn parse(svg: &str) -> usvg::Tree {
    usvg::Tree::from_str(svg, &usvg::Options::default()).expect("the SVG parses")
}

/// Ids of every node below `group`.
fn ids(group: &usvg::Group, out: &mut Vec<String>) {
    for node in group.children() {
        if !node.id().is_empty() {
            out.push(node.id().to_string());
        }
        if let usvg::Node::Group(g) = node {
            ids(g, out);
        }
    }
}

fn decode_png(bytes: &[u8]) -> (u32, u32) {
    let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    let reader = decoder.read_info().expect("a PNG header");
    let info = reader.info();
    (info.width, info.height)
}

#[test]
fn the_svg_has_one_path_per_bone_and_one_marker_per_goal_and_pin() {
    let puppet = rig("puppet");
    let hand_of = |n: &str| puppet.index_of(n).unwrap();
    let figure = SkeletonFigure {
        goals: vec![
            BoneGoal::at(hand_of("left_hand"), Point2::new(0.6, 0.9)),
            BoneGoal::at(hand_of("right_hand"), Point2::new(0.5, 0.2)).with_angle(-0.3),
            BoneGoal::at(hand_of("head"), Point2::new(0.1, 1.0)),
        ],
        pins: vec![hand_of("left_foot"), hand_of("right_foot")],
        ranges: true,
        labels: true,
        caption: Some("puppet".into()),
        ..SkeletonFigure::new(&puppet, puppet.start_angles())
    };
    let svg = skeleton_svg(&figure, 640, 480).unwrap();
    let tree = parse(&svg);
    assert_eq!((tree.size().width(), tree.size().height()), (640.0, 480.0));
    let mut found = Vec::new();
    ids(tree.root(), &mut found);
    let mut bones: Vec<&str> = found.iter().map(String::as_str).filter(|id| id.starts_with("bone")).collect();
    bones.sort_unstable();
    let mut want: Vec<String> = (0..puppet.len()).map(|i| format!("bone{i}")).collect();
    want.sort_unstable();
    assert_eq!(bones, want);
    // Goals: the red centre dot (r = 4.2 px at this size's unit), one per goal inside the plot.
    let goal_dots = svg.matches("fill=\"#d62728\"/>").count();
    assert_eq!(goal_dots, 3 + 1, "three goals and the legend's dot");
    // Pins: one blue square per pin, and one in the legend.
    assert_eq!(svg.matches("class=\"pin\"").count(), 2 + 1);
    // One direction arrow, for the one goal with an angle.
    assert_eq!(svg.matches("class=\"goal-direction\"").count(), 1);
}

#[test]
fn the_png_decodes_at_its_size() {
    let hand = rig("hand");
    let figure = SkeletonFigure { ranges: true, labels: true, ..SkeletonFigure::new(&hand, hand.start_angles()) };
    let png = skeleton_png(&figure, 333, 517).unwrap();
    assert_eq!(decode_png(&png), (333, 517));
}

/// The `M x y L x y` segments of a path's `d`, as pairs of points (strings as written).
fn segments(d: &str) -> Vec<[(String, String); 2]> {
    let nums: Vec<&str> = d.split(['M', 'L', ' ']).filter(|s| !s.is_empty()).collect();
    let points: Vec<(String, String)> = nums.chunks(2).map(|c| (c[0].to_string(), c[1].to_string())).collect();
    points.windows(2).map(|w| [w[0].clone(), w[1].clone()]).collect()
}

#[test]
fn a_one_branch_skeleton_draws_the_arms_links() {
    let lim = |d: f64| JointLimits::new(-d.to_radians(), d.to_radians()).unwrap();
    let chain = Chain::new(
        [0.5, -1.0],
        &[Link::new(3.0, 0.3).with_limits(lim(60.0)), Link::new(2.0, 0.5), Link::new(1.5, -0.7)],
    )
    .unwrap();
    let skeleton = chain.skeleton().clone();
    let pose = [0.4, 1.1, -0.6];
    let arm = arm_svg(&ArmFigure { show_reach: false, ..ArmFigure::new(&chain, &pose) }, 500, 400).unwrap();
    let figure = SkeletonFigure::new(&skeleton, &pose);
    let skel = skeleton_svg(&figure, 500, 400).unwrap();
    // The arm's links: the ink polyline (round-joined, in ink) after the comment "arm", in the
    // arm's view (centred on the base, fitting its reach), back in world coordinates.
    let arm_part = arm.split("<!-- arm -->").nth(1).unwrap();
    let ink = arm_part.lines().find(|l| l.contains("stroke-linejoin=\"round\" stroke=\"#26324a\"")).unwrap();
    let d = ink.split("d=\"").nth(1).unwrap().split('"').next().unwrap();
    let world = |view: &ikarus_render::View, [(x, y), _]: &[(String, String); 2]| {
        view.pixel_to_world(x.parse().unwrap(), y.parse().unwrap())
    };
    let arm_view = ArmFigure::new(&chain, &pose).view(500, 400);
    let arm_starts: Vec<Point2<f64>> = segments(d).iter().map(|s| world(&arm_view, s)).collect();
    assert_eq!(arm_starts.len(), 3);
    // The skeleton's bones, one path each, in its own view (fitted to the bones).
    let view = figure.view(500, 400);
    let bone_starts: Vec<Point2<f64>> = (0..3)
        .map(|i| {
            let line = skel.lines().find(|l| l.contains(&format!("id=\"bone{i}\""))).unwrap();
            let d = line.split("d=\"").nth(1).unwrap().split('"').next().unwrap();
            let s = segments(d);
            assert_eq!(s.len(), 1);
            world(&view, &s[0])
        })
        .collect();
    // The same links: the same joints, to the SVG's 1/100 px.
    let px = 0.006 / view.scale().min(arm_view.scale());
    for (a, b) in arm_starts.iter().zip(&bone_starts) {
        assert!((a - b).norm() < px, "{a} vs {b}");
    }
}

/// Where the bones are drawn, in pixels: the box of every point of the `bone{i}` paths.
fn drawn_box(svg: &str) -> (f64, f64, f64, f64) {
    let (mut x0, mut y0, mut x1, mut y1) = (f64::INFINITY, f64::INFINITY, f64::NEG_INFINITY, f64::NEG_INFINITY);
    for line in svg.lines().filter(|l| l.contains("id=\"bone")) {
        let d = line.split("d=\"").nth(1).unwrap().split('"').next().unwrap();
        for [a, b] in segments(d) {
            for (x, y) in [a, b] {
                let (x, y) = (x.parse::<f64>().unwrap(), y.parse::<f64>().unwrap());
                (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
            }
        }
    }
    (x0, y0, x1, y1)
}

/// Issue 24: the hand filled the top sixth of its picture (drawn in the circle of its reach
/// around the wrist). Now a rig's picture is fitted to its bones: at any size and pose, the
/// drawing is centred in the plot and fills it along one side, with room to spare.
#[test]
fn a_rig_fills_its_picture() {
    for name in ["hand", "puppet"] {
        let s = rig(name);
        let curled: Vec<f64> = s.start_angles().iter().map(|a| a - 0.3).collect();
        for pose in [s.start_angles().to_vec(), curled] {
            for (w, h) in [(800, 800), (600, 400), (300, 700)] {
                let figure = SkeletonFigure::new(&s, &pose);
                let svg = skeleton_svg(&figure, w, h).unwrap();
                let plot = figure.view(w, h).plot_area();
                let (x0, y0, x1, y1) = drawn_box(&svg);
                let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
                let at = format!("{name} {w}×{h}: bones in x {x0:.0}..{x1:.0}, y {y0:.0}..{y1:.0} of {plot:?}");
                // The base is in the box too, so the bones' own box may sit off centre a little.
                assert!((cx - 0.5 * (plot.left + plot.right)).abs() < 0.1 * plot.width(), "{at}");
                assert!((cy - 0.5 * (plot.top + plot.bottom)).abs() < 0.1 * plot.height(), "{at}");
                // The box with its margin (12 % of its larger side each side) fills the plot
                // along one side: the bones alone fill 1/1.24 of it, less the base's share.
                let filled = ((x1 - x0) / plot.width()).max((y1 - y0) / plot.height());
                assert!((0.6..=0.81).contains(&filled), "{at}: fills {filled:.2}");
                assert!(plot.contains(x0, y0) && plot.contains(x1, y1), "{at}");
            }
        }
    }
}

#[test]
fn every_tip_lies_inside_the_view() {
    for name in ["puppet", "hand"] {
        let s = rig(name);
        // The start pose, and every bone stretched straight out from its parent.
        let straight = vec![0.0; s.len()];
        for pose in [s.start_angles().to_vec(), straight] {
            for (w, h) in [(800, 800), (300, 700), (900, 200)] {
                let figure = SkeletonFigure::new(&s, &pose);
                let view = figure.view(w, h);
                let plot = view.plot_area();
                let n = s.len();
                let (mut starts, mut tips, mut dirs) =
                    (vec![Point2::origin(); n], vec![Point2::origin(); n], vec![0.0; n]);
                s.forward_into(&pose, &mut starts, &mut tips, &mut dirs);
                for (i, t) in tips.iter().enumerate() {
                    let (x, y) = view.world_to_pixel(*t);
                    assert!(plot.contains(x, y), "{name} {w}×{h}: {} at ({x}, {y}) outside {plot:?}", s.name(i));
                }
            }
        }
    }
}

#[test]
fn the_shipped_rigs_draw() {
    for name in ["puppet", "hand"] {
        let s = rig(name);
        for (ranges, labels) in [(false, false), (true, true)] {
            let figure = SkeletonFigure { ranges, labels, ..SkeletonFigure::new(&s, s.start_angles()) };
            let svg = skeleton_svg(&figure, 400, 400).unwrap();
            parse(&svg);
            skeleton_png(&figure, 64, 64).unwrap();
        }
    }
}

/// The boxes of the texts that are bone names, one per name, as laid out by usvg in the
/// embedded font.
fn name_boxes(svg: &str, skeleton: &Skeleton) -> Vec<(String, usvg::Rect)> {
    let mut options = usvg::Options { font_family: "DejaVu Sans".into(), ..usvg::Options::default() };
    options.fontdb_mut().load_font_data(dejavu::sans::regular().to_vec());
    let tree = usvg::Tree::from_str(svg, &options).expect("the SVG parses");
    fn walk(group: &usvg::Group, names: &[String], out: &mut Vec<(String, usvg::Rect)>) {
        for node in group.children() {
            match node {
                usvg::Node::Group(g) => walk(g, names, out),
                usvg::Node::Text(t) => {
                    let text: String = t.chunks().iter().map(|c| c.text()).collect();
                    if names.contains(&text) && !out.iter().any(|(n, _)| *n == text) {
                        out.push((text, t.abs_bounding_box()));
                    }
                }
                _ => {}
            }
        }
    }
    let mut out = Vec::new();
    walk(tree.root(), skeleton.names(), &mut out);
    out
}

#[test]
fn bone_names_do_not_cover_each_other() {
    let puppet = rig("puppet");
    let i = |n: &str| puppet.index_of(n).unwrap();
    let mut reaching = puppet.start_angles().to_vec();
    for (bone, deg) in
        [("spine", -20.0), ("left_upper_arm", -80.0), ("right_upper_arm", -110.0), ("right_forearm", 40.0)]
    {
        reaching[i(bone)] = f64::to_radians(deg);
    }
    let hand = rig("hand");
    for (s, pose) in [(&puppet, puppet.start_angles()), (&puppet, &reaching[..]), (&hand, hand.start_angles())] {
        let figure = SkeletonFigure { labels: true, ranges: true, ..SkeletonFigure::new(s, pose) };
        let boxes = name_boxes(&skeleton_svg(&figure, 800, 800).unwrap(), s);
        assert_eq!(boxes.len(), s.len(), "every bone is named");
        for (k, (a, ra)) in boxes.iter().enumerate() {
            for (b, rb) in &boxes[k + 1..] {
                let apart = ra.right() <= rb.left()
                    || rb.right() <= ra.left()
                    || ra.bottom() <= rb.top()
                    || rb.bottom() <= ra.top();
                assert!(apart, "{a} {ra:?} and {b} {rb:?} overlap");
            }
        }
    }
}
