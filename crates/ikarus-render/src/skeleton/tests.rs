//! Skeleton figures: wedges, names, the base marker, goal directions, bad input.

use super::*;
use ikarus::{Bone, JointLimits};

fn fork() -> Skeleton {
    let lim = JointLimits::new(-0.5, 0.5).unwrap();
    Skeleton::new(
        [0.0, 0.0],
        &[
            Bone::new("trunk", 1.0, 1.5),
            Bone::new("left", 0.8, 0.4).with_parent("trunk").with_limits(lim),
            Bone::new("right", 0.8, -0.4).with_parent("trunk"),
        ],
    )
    .unwrap()
}

#[test]
fn wedges_only_at_limited_bones_and_only_when_asked() {
    let s = fork();
    let plain = skeleton_svg(&SkeletonFigure::new(&s, s.start_angles()), 300, 300).unwrap();
    assert!(!plain.contains("joint ranges"));
    let with =
        skeleton_svg(&SkeletonFigure { ranges: true, ..SkeletonFigure::new(&s, s.start_angles()) }, 300, 300).unwrap();
    let wedges = with.split("joint ranges").nth(1).unwrap().split("/>").next().unwrap();
    assert_eq!(wedges.matches('A').count(), 1, "{wedges}");
}

#[test]
fn a_wedge_turns_from_the_parents_direction() {
    let s = fork();
    let b = Bones::at(&s, s.start_angles());
    let w = wedges(&s, &b);
    assert_eq!(w.len(), 1);
    assert!((w[0].heading - 1.5).abs() < 1e-15);
    assert_eq!(w[0].at, b.tips[0]);
}

#[test]
fn labels_are_off_by_default_and_every_name_is_written_when_on() {
    let s = fork();
    let plain = skeleton_svg(&SkeletonFigure::new(&s, s.start_angles()), 300, 300).unwrap();
    assert!(!plain.contains(">trunk<"));
    let with =
        skeleton_svg(&SkeletonFigure { labels: true, ..SkeletonFigure::new(&s, s.start_angles()) }, 300, 300).unwrap();
    for name in ["trunk", "left", "right"] {
        // Halo and text.
        assert_eq!(with.matches(&format!(">{name}</text>")).count(), 2, "{name}");
    }
}

#[test]
fn the_base_is_a_mount_unless_a_root_points_down() {
    let up = fork();
    let svg = skeleton_svg(&SkeletonFigure::new(&up, up.start_angles()), 300, 300).unwrap();
    assert!(!svg.contains("class=\"socket\""));
    assert_eq!(svg.matches(&format!("fill=\"{}\"", style::MOUNT)).count(), 1, "the mount");
    let legs = Skeleton::new([0.0, 0.0], &[Bone::new("body", 1.0, 1.5), Bone::new("leg", 1.0, -1.6)]).unwrap();
    let svg = skeleton_svg(&SkeletonFigure::new(&legs, legs.start_angles()), 300, 300).unwrap();
    assert_eq!(svg.matches("class=\"socket\"").count(), 1);
    // The socket replaces the mount: one shape in the mount's colour, the socket.
    assert_eq!(svg.matches(&format!("fill=\"{}\"", style::MOUNT)).count(), 1);
}

#[test]
fn a_goal_direction_points_the_way_of_its_angle() {
    let s = fork();
    let goal = Point2::new(0.5, 1.0);
    for angle in [0.0, std::f64::consts::FRAC_PI_2, 3.0, -2.0] {
        let figure = SkeletonFigure {
            goals: vec![BoneGoal::at(1, goal).with_angle(angle)],
            ..SkeletonFigure::new(&s, s.start_angles())
        };
        let svg = skeleton_svg(&figure, 400, 400).unwrap();
        let (gx, gy) = figure.view(400, 400).world_to_pixel(goal);
        let head = svg.split("class=\"goal-direction\"").next().unwrap().rsplit("d=\"M").next().unwrap();
        let mut xy = head.split([' ', 'L']).map(|v| v.parse::<f64>().unwrap());
        let (x, y) = (xy.next().unwrap() - gx, xy.next().unwrap() - gy);
        // The head's point is 34 px × unit (0.5 here) from the goal along the direction,
        // y pointing down; the SVG's numbers are rounded to 1/100 px.
        let (ex, ey) = (17.0 * angle.cos(), -17.0 * angle.sin());
        assert!((x - ex).abs() <= 0.006 && (y - ey).abs() <= 0.006, "{angle}: ({x}, {y}) vs ({ex}, {ey})");
    }
}

#[test]
fn bad_input_names_the_field() {
    let s = fork();
    let pose = [0.0, 0.0, 0.0];
    let err = |f: SkeletonFigure| skeleton_svg(&f, 200, 200).unwrap_err().to_string();
    assert_eq!(err(SkeletonFigure::new(&s, &pose[..2])), "pose: expected 3 values for this arm or skeleton, got 2");
    assert_eq!(
        err(SkeletonFigure { pins: vec![0, 3], ..SkeletonFigure::new(&s, &pose) }),
        "pins[1]: no bone 3 in a skeleton of 3 bones"
    );
    let g = BoneGoal::at(1, Point2::new(0.0, f64::NAN));
    assert_eq!(
        err(SkeletonFigure { goals: vec![g], ..SkeletonFigure::new(&s, &pose) }),
        "goals[0].position.y: must be a finite number, got NaN"
    );
    let g = BoneGoal::at(1, Point2::new(0.0, 1.0)).with_angle(f64::INFINITY);
    assert!(err(SkeletonFigure { goals: vec![g], ..SkeletonFigure::new(&s, &pose) }).starts_with("goals[0].angle"));
    let g = BoneGoal::at(9, Point2::new(0.0, 1.0));
    assert_eq!(
        err(SkeletonFigure { goals: vec![g], ..SkeletonFigure::new(&s, &pose) }),
        "goals[0].bone: no bone 9 in a skeleton of 3 bones"
    );
}

/// The box a figure fits holds the base, every bone at every pose given and every goal (a far
/// one pulled in to three reaches): an animation's frames share the box of all their poses.
#[test]
fn the_extent_holds_every_pose_and_goal() {
    let s = fork();
    let (a, b) = (s.start_angles().to_vec(), vec![-1.0, 2.0, -2.5]);
    let far = Point2::new(1e9, 0.0);
    let figure = SkeletonFigure { goals: vec![BoneGoal::at(1, far)], ..SkeletonFigure::new(&s, &a) };
    let (min, max) = figure.extent([a.as_slice(), b.as_slice()]);
    let inside = |p: Point2<f64>| min.x <= p.x && p.x <= max.x && min.y <= p.y && p.y <= max.y;
    for pose in [&a, &b] {
        let (mut starts, mut tips, mut dirs) = (vec![Point2::origin(); 3], vec![Point2::origin(); 3], vec![0.0; 3]);
        s.forward_into(pose, &mut starts, &mut tips, &mut dirs);
        assert!(starts.iter().chain(&tips).all(|&p| inside(p)), "{pose:?}: {min} {max}");
    }
    // The far goal counts three reaches out, in its direction.
    assert!((max.x - 3.0 * s.max_reach()).abs() < 1e-12, "{max}");
    // A pose that does not fit the skeleton is left out, not a panic.
    assert_eq!(figure.extent([&[0.0][..], a.as_slice()]), figure.extent([a.as_slice()]));
    // A figure given a box is drawn in that box's view, whatever its pose.
    let fit = Some(figure.extent([a.as_slice(), b.as_slice()]));
    let still = |pose: &[f64]| SkeletonFigure { fit, pose, ..figure.clone() }.view(300, 300);
    assert_eq!(still(&a), still(&b));
}

#[test]
fn a_prismatic_bone_has_a_sleeve_along_its_slide_and_no_wedge() {
    let limits = |lo, hi| JointLimits::new(lo, hi).unwrap();
    let s = Skeleton::new(
        [0.0, 0.0],
        &[
            Bone::new("arm", 1.0, 0.5).with_limits(limits(-1.0, 1.0)),
            Bone::new("ram", 0.5, 0.0).with_parent("arm").prismatic(0.2).with_limits(limits(0.0, 0.6)),
        ],
    )
    .unwrap();
    let b = Bones::at(&s, s.start_angles());
    // Only the revolute bone's limits are an angle's range.
    assert_eq!(wedges(&s, &b).len(), 1);
    let sl = sleeves(&s, s.start_angles(), &b);
    assert_eq!(sl.len(), 1);
    // The slide starts at the arm's tip and runs along the arm; the ram starts 0.2 along it.
    let (sin, cos) = 0.5f64.sin_cos();
    assert!((sl[0].joint - b.tips[0]).norm() < 1e-15, "{:?}", sl[0]);
    assert!((sl[0].slide[0] - cos).abs() < 1e-15 && (sl[0].slide[1] - sin).abs() < 1e-15, "{:?}", sl[0]);
    assert_eq!(sl[0].start, b.starts[1]);
    let along = Point2::new(b.tips[0].x + 0.2 * cos, b.tips[0].y + 0.2 * sin);
    assert!((b.starts[1] - along).norm() < 1e-15, "{:?} vs {along:?}", b.starts[1]);
    assert_eq!(sl[0].limits, Some(limits(0.0, 0.6)));
    // The sleeve is drawn; its bar only with the ranges.
    let plain = skeleton_svg(&SkeletonFigure::new(&s, s.start_angles()), 300, 300).unwrap();
    assert_eq!((plain.matches("class=\"sleeve\"").count(), plain.matches("slide-limits").count()), (1, 0));
    let with =
        skeleton_svg(&SkeletonFigure { ranges: true, ..SkeletonFigure::new(&s, s.start_angles()) }, 300, 300).unwrap();
    assert_eq!((with.matches("class=\"sleeve\"").count(), with.matches("slide-limits").count()), (1, 1));
    // A revolute skeleton has neither.
    let f = fork();
    let svg =
        skeleton_svg(&SkeletonFigure { ranges: true, ..SkeletonFigure::new(&f, f.start_angles()) }, 300, 300).unwrap();
    assert!(!svg.contains("sleeve") && !svg.contains("slide-limits") && !svg.contains("prismatic joints"));
}
