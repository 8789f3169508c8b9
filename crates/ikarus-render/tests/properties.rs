//! Any finite, valid arm draws: over random chains (ordinary lengths, lengths from 1e-9 to 1e9
//! mixed in one chain, lengths up to 1e150), poses (huge angles too), goals (near, far, on the
//! base), ghosts, traces, workspaces (sampled grids and exact regions), captions with markup characters and picture sizes, the
//! SVG is made without a panic and parses as SVG, and the PNG decodes at the size asked for;
//! or the picture is refused with a one-line error. The same figure twice gives the same
//! bytes.

use std::f64::consts::PI;

use ikarus::reach::{Region, WorkspaceOptions, sample};
use ikarus::{Chain, JointLimits, Link, Point2};
use ikarus_render::{ArmFigure, Reachable, arm_png, arm_svg};
use proptest::prelude::*;
use proptest::test_runner::{Config, FileFailurePersistence};

/// Lengths `10^e`, `e` in `exponents`, mixed; optional limits.
fn chain(exponents: std::ops::Range<f64>, max_links: usize) -> impl Strategy<Value = Chain> {
    let link = (exponents, -PI..PI, prop::option::of((-3.0f64..3.0, 0.0f64..4.0))).prop_map(|(e, angle, limits)| {
        let length = 10f64.powf(e);
        match limits {
            None => Link::new(length, angle),
            Some((lo, width)) => {
                let lim = JointLimits::new(lo, lo + width).unwrap();
                Link::new(length, lim.clamp(angle)).with_limits(lim)
            }
        }
    });
    (prop::collection::vec(link, 1..=max_links), -1.0f64..1.0, -1.0f64..1.0).prop_map(|(links, x, y)| {
        let reach: f64 = links.iter().map(|l| l.length).sum();
        Chain::new([x * reach, y * reach], &links).unwrap()
    })
}

fn any_chain() -> impl Strategy<Value = Chain> {
    prop_oneof![chain(-2.0..1.0, 12), chain(-9.0..9.0, 12), chain(100.0..150.0, 3)]
}

/// A pose: ordinary angles, or huge ones.
fn pose(n: usize) -> impl Strategy<Value = Vec<f64>> {
    prop_oneof![
        3 => prop::collection::vec(-10.0f64..10.0, n),
        1 => prop::collection::vec(prop_oneof![-1e300f64..1e300, -1e6f64..1e6], n),
    ]
}

#[derive(Debug, Clone)]
struct Picture {
    chain: Chain,
    pose: Vec<f64>,
    ghosts: Vec<Vec<f64>>,
    traces: bool,
    goal: Option<(f64, f64)>,
    /// A grid's resolution (`None`: the exact region), and whether within the limits.
    workspace: Option<(Option<u32>, bool)>,
    show_reach: bool,
    caption: Option<String>,
    size: (u32, u32),
    png: bool,
}

fn picture() -> impl Strategy<Value = Picture> {
    any_chain().prop_flat_map(|chain| {
        let n = chain.len();
        (
            pose(n),
            prop::collection::vec(pose(n), 0..3),
            any::<bool>(),
            // Goal: a radius in reaches (0: on the base) and a direction.
            prop::option::of((prop_oneof![Just(0.0), 0.0f64..1.5, 1.0f64..1e6], -PI..PI)),
            prop::option::of((prop::option::of(8u32..=32), any::<bool>())),
            any::<bool>(),
            prop::option::of("[a-z <>&\"'é°·]{0,30}"),
            (16u32..=400, 16u32..=400),
            prop::bool::weighted(0.2),
        )
            .prop_map(move |(pose, ghosts, traces, goal, workspace, show_reach, caption, size, png)| {
                let b = chain.base();
                let r = chain.max_reach();
                let goal = goal.map(|(k, a)| (b.x + k * r * a.cos(), b.y + k * r * a.sin()));
                Picture { chain: chain.clone(), pose, ghosts, traces, goal, workspace, show_reach, caption, size, png }
            })
    })
}

fn config() -> Config {
    let cases = std::env::var("PROPTEST_CASES").ok().and_then(|v| v.parse().ok()).unwrap_or(96);
    Config { cases, failure_persistence: Some(Box::new(FileFailurePersistence::Off)), ..Config::default() }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn any_valid_arm_draws(p in picture()) {
        let grid = p.workspace.and_then(|(resolution, limits)| resolution.map(|resolution| {
            let options = WorkspaceOptions { resolution, limits, samples: Some(16), parallel: false, ..WorkspaceOptions::default() };
            sample(&p.chain, &options).unwrap()
        }));
        let exact = p.workspace.and_then(|(resolution, limits)| resolution.is_none().then(|| Region::of(&p.chain, limits)));
        let workspace: Option<Reachable> = grid.as_ref().map(Into::into).or(exact.as_ref().map(Into::into));
        let figure = ArmFigure {
            ghosts: p.ghosts.iter().map(Vec::as_slice).collect(),
            traces: p.traces,
            goal: p.goal.map(|(x, y)| Point2::new(x, y)),
            workspace,
            show_reach: p.show_reach,
            caption: p.caption.clone(),
            ..ArmFigure::new(&p.chain, &p.pose)
        };
        let (w, h) = p.size;
        match arm_svg(&figure, w, h) {
            Ok(svg) => {
                let tree = resvg::usvg::Tree::from_str(&svg, &resvg::usvg::Options::default());
                prop_assert!(tree.is_ok(), "the SVG does not parse: {:?}", tree.err());
                prop_assert_eq!(&arm_svg(&figure, w, h).unwrap(), &svg);
            }
            Err(e) => {
                let msg = e.to_string();
                prop_assert!(!msg.is_empty() && !msg.contains('\n'), "{:?}", msg);
            }
        }
        if p.png {
            if let Ok(bytes) = arm_png(&figure, w, h) {
                let decoder = png::Decoder::new(std::io::Cursor::new(&bytes));
                let reader = decoder.read_info();
                prop_assert!(reader.is_ok(), "the PNG does not decode");
                let info = reader.unwrap().info().clone();
                prop_assert_eq!((info.width, info.height), (w, h));
            }
        }
    }
}
