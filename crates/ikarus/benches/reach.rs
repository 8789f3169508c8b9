//! Time of one `reach::sample` on the seed arm (lengths 3, 2, 1; limits ±45°, ±90°, ±170°) with
//! the default options at resolutions 256 and 512: with limits (the default: 4096 exact slices
//! of the last two joints, sampled over the first) and without (the annulus, rasterised
//! directly), on rayon's global pool (`parallel`) and on the calling thread (`serial`). The
//! seven-link arm of `examples/arms/seven.toml` is measured at 256 with limits, to show the cost
//! of the quasi-random sample of five joints: with the automatic count (262144 samples, `seven`)
//! and with 4096 (`seven-4096`, the fixed default before the count adapted to the joints).
//! Groups are named `reach/<arm>/<resolution>/<limits|free>/<parallel|serial>`; before
//! measuring, each prints to stderr the number of samples and the area, to read the times
//! against.
//!
//! The exact region ([`Region`]) of the same two arms with their limits: its build
//! (`region/<arm>/build`, one `Region::of`) and its verdict (`region/<arm>/verdict`: one pass of
//! `Region::verdict` within 1e-6 over 1024 fixed points spread uniformly over the square of side
//! 2·reach about the base, inside and outside the region alike; criterion reports the pass and
//! its throughput in points per second, so one verdict takes the pass's time / 1024). `ikarus
//! bench --reach` reports the same figures as medians over a million points, with the 8-link
//! build.
//!
//! `cargo bench -p ikarus --bench reach`

use std::hint::black_box;
use std::time::Duration;

use criterion::{Criterion, criterion_group, criterion_main};
use ikarus::reach::{Region, WorkspaceOptions, sample};
use ikarus::rng::SplitMix64;
use ikarus::{Chain, JointLimits, Link, Point2};

fn arm(spec: &[(f64, f64)]) -> Chain {
    let links: Vec<Link> = spec
        .iter()
        .map(|&(l, m)| {
            let m = m.to_radians();
            Link::new(l, 0.0).with_limits(JointLimits::new(-m, m).expect("valid limits"))
        })
        .collect();
    Chain::new([0.0, 0.0], &links).expect("valid arm")
}

fn bench(c: &mut Criterion) {
    let seed = arm(&[(3.0, 45.0), (2.0, 90.0), (1.0, 170.0)]);
    let seven = arm(&[(2.0, 90.0), (1.7, 120.0), (1.4, 120.0), (1.2, 135.0), (1.0, 135.0), (0.8, 150.0), (0.6, 150.0)]);
    let mut cases = Vec::new();
    for resolution in [256, 512] {
        for limits in [true, false] {
            for parallel in [true, false] {
                cases.push(("seed", &seed, None, resolution, limits, parallel));
            }
        }
    }
    cases.push(("seven", &seven, None, 256, true, true));
    cases.push(("seven-4096", &seven, Some(4096), 256, true, true));
    for (name, chain, samples, resolution, limits, parallel) in cases {
        let options = WorkspaceOptions { resolution, limits, samples, parallel, ..WorkspaceOptions::default() };
        let ws = sample(chain, &options).expect("valid options");
        eprintln!(
            "{name} {resolution} limits={limits}: {} samples, area {:.4} (annulus {:.4})",
            ws.samples(),
            ws.area(),
            ws.annulus().area()
        );
        let id = format!(
            "reach/{name}/{resolution}/{}/{}",
            if limits { "limits" } else { "free" },
            if parallel { "parallel" } else { "serial" }
        );
        c.bench_function(&id, |b| b.iter(|| sample(black_box(chain), black_box(&options)).expect("valid options")));
    }
    for (name, chain) in [("seed", &seed), ("seven", &seven)] {
        region(c, name, chain);
    }
}

/// Points of the verdict benchmark.
const POINTS: usize = 1024;

/// `region/<name>/build` and `region/<name>/verdict` (per point, over [`POINTS`] points).
fn region(c: &mut Criterion, name: &str, chain: &Chain) {
    let region = Region::of(chain, true);
    let reach = chain.max_reach();
    let mut rng = SplitMix64(7);
    let points: Vec<Point2<f64>> =
        (0..POINTS).map(|_| Point2::new(rng.range(-reach, reach), rng.range(-reach, reach))).collect();
    let inside = points.iter().filter(|&&p| region.verdict(p, 1e-6).reachable).count();
    eprintln!(
        "{name} region: {} boundary pieces, area {:.4}; {inside} of {POINTS} verdict points reachable",
        region.pieces(),
        region.area()
    );
    c.bench_function(&format!("region/{name}/build"), |b| b.iter(|| Region::of(black_box(chain), true)));
    let mut group = c.benchmark_group(format!("region/{name}"));
    group.throughput(criterion::Throughput::Elements(POINTS as u64));
    group.bench_function("verdict", |b| {
        b.iter(|| {
            for &p in &points {
                black_box(region.verdict(black_box(p), 1e-6));
            }
        })
    });
    group.finish();
}

criterion_group! {
    name = benches;
    config = Criterion::default().sample_size(10).measurement_time(Duration::from_secs(5));
    targets = bench
}
criterion_main!(benches);
