use super::*;
use crate::chain::{JointLimits, Link};
use crate::kinematics::end_effector;

fn seed(limits: bool) -> Chain {
    let d = f64::to_radians;
    let lim = |a: f64, b: f64| JointLimits::new(d(a), d(b)).unwrap();
    let mut links = vec![Link::new(3.0, d(5.0)), Link::new(2.0, d(5.0)), Link::new(1.0, d(5.0))];
    if limits {
        links[0] = links[0].with_limits(lim(-45.0, 45.0));
        links[1] = links[1].with_limits(lim(-90.0, 90.0));
        links[2] = links[2].with_limits(lim(-170.0, 170.0));
    }
    Chain::new([0.0, 0.0], &links).unwrap()
}

fn solve(chain: &Chain, goal: Goal, options: SolveOptions) -> Outcome {
    Solver::new(options).unwrap().solve(chain, chain.start_pose(), &goal).unwrap()
}

#[test]
fn every_method_reaches_an_easy_goal() {
    for method in Method::ALL {
        let o = solve(
            &seed(false),
            Goal::position(2.0, 3.0).unwrap(),
            SolveOptions { method, max_iterations: 10_000, ..Default::default() },
        );
        assert_eq!(o.status, Status::Reached, "{method:?}: {o:?}");
        let tip = end_effector(&seed(false), o.pose.angles()).position;
        assert!((tip - Point2::new(2.0, 3.0)).norm() <= 1e-6);
        println!("{method:?}: {} iterations", o.iterations);
    }
}
