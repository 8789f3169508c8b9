use ikarus::Solver;
use ikarus::character::{PoseRequest, Posed, Together};
use std::time::Instant;
fn main() {
    for f in ["spine-spineboy-pro.json", "spine-raptor-pro.json"] {
        let text = std::fs::read_to_string(format!("examples/characters/{f}")).unwrap();
        let loaded = ikarus_edge::character::load(&text, f).unwrap();
        let c = &loaded.character;
        let walk = c.clip_index("walk").unwrap();
        let dur = c.clips()[walk].duration;
        let mut out = Posed::default();
        let n = 20000;
        for (label, ikarus) in [("runtime", false), ("ikarus", true)] {
            let mut solver = Solver::new(ikarus_edge::pose::character_options()).unwrap();
            let rules = Together::default();
            let count = if ikarus { 2000 } else { n };
            let mut times = Vec::with_capacity(count);
            for i in 0..count {
                let t = dur * (i as f64 / count as f64);
                let req = PoseRequest { clip: Some((walk, t)), targets: &[] };
                let s = Instant::now();
                if ikarus {
                    c.pose_together(&req, &rules, &mut solver, &mut out).unwrap();
                } else {
                    c.pose(&req, &mut out).unwrap();
                }
                times.push(s.elapsed().as_secs_f64() * 1e6);
            }
            times.sort_by(f64::total_cmp);
            println!(
                "{f} {label}: {} poses, median {:.2} µs, p99 {:.2} µs",
                count,
                times[count / 2],
                times[count * 99 / 100]
            );
        }
    }
}
