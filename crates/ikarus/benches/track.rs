//! Time per sample of `track::follow` and `track::plan` with the default options: a figure-8
//! of 100 samples (`Path::figure8`, centre (2, 1), a = 2) on the seed arm (3, 2, 1) with and
//! without its limits (around (4, 1), a = 1.5, with them: inside what the limits reach), and a figure-8 around (3, 2) on the seven-link arm of
//! `examples/arms/seven.toml` with its limits. Groups are named `track/<arm>/<mode>`; one
//! benchmark iteration tracks the whole path, so divide by 100 for the time per sample.
//!
//! `cargo bench -p ikarus --bench track`

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use ikarus::track::{self, Path, TrackMode, TrackOptions};
use ikarus::{Chain, JointLimits, LimitMode, Link, SolveOptions};

fn arm(spec: &[(f64, f64)], start: f64) -> Chain {
    let links: Vec<Link> = spec
        .iter()
        .map(|&(l, m)| {
            let m = m.to_radians();
            Link::new(l, start.to_radians()).with_limits(JointLimits::new(-m, m).expect("valid limits"))
        })
        .collect();
    Chain::new([0.0, 0.0], &links).expect("valid arm")
}

fn bench(c: &mut Criterion) {
    let seed = arm(&[(3.0, 45.0), (2.0, 90.0), (1.0, 170.0)], 5.0);
    let seven =
        arm(&[(2.0, 90.0), (1.7, 120.0), (1.4, 120.0), (1.2, 135.0), (1.0, 135.0), (0.8, 150.0), (0.6, 150.0)], 10.0);
    let cases = [
        ("seed-free", seed.without_limits(), LimitMode::Ignore, Path::figure8([2.0, 1.0], 2.0, 100)),
        ("seed-limits", seed.clone(), LimitMode::Lock, Path::figure8([4.0, 1.0], 1.5, 100)),
        ("seven-limits", seven, LimitMode::Lock, Path::figure8([3.0, 2.0], 2.0, 100)),
    ];
    for (name, chain, limits, path) in cases {
        let path = path.expect("valid path");
        let options =
            TrackOptions { solve: SolveOptions { limits, ..SolveOptions::default() }, ..TrackOptions::default() };
        for mode in [TrackMode::Follow, TrackMode::Plan] {
            let t = track::track(&chain, chain.start_pose().angles(), &path, mode, &options).expect("valid input");
            eprintln!("track/{name}/{mode}: {} of 100 reached, {} flips", t.summary.reached, t.summary.flips.len());
            let mut group = c.benchmark_group(format!("track/{name}"));
            group.sample_size(20).measurement_time(Duration::from_secs(3)).warm_up_time(Duration::from_secs(1));
            group.bench_function(mode.name(), |b| {
                b.iter(|| track::track(&chain, chain.start_pose().angles(), black_box(&path), mode, &options))
            });
            group.finish();
        }
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
