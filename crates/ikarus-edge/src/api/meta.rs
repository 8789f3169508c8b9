//! `GET /api/meta`: the names the page offers in its select lists (methods, limit modes, eases,
//! interpolations)
//! and their defaults, read from the library's enums so that the page cannot drift from them.

use ikarus::motion::Interpolation;
use ikarus::{EaseKind, LimitMode, Method, Named, SolveOptions};
use serde::Serialize;

/// One choice of a select list.
#[derive(Debug, Serialize)]
pub struct Choice {
    /// The name a request gives (`"dls"`, `"sine"`, …).
    pub name: &'static str,
    /// The name the page shows in the list.
    pub label: &'static str,
    /// One line on what it does, shown as the choice's hint.
    pub summary: &'static str,
}

impl Choice {
    fn of<T: Named>(v: T) -> Self {
        Self { name: v.name(), label: v.label(), summary: v.summary() }
    }
}

/// A method, with the limit modes it supports and the one it uses when none is named.
#[derive(Debug, Serialize)]
pub struct MethodChoice {
    /// The method's name, label and summary.
    #[serde(flatten)]
    pub choice: Choice,
    /// The names of the limit modes the method supports.
    pub limit_modes: Vec<&'static str>,
    /// The limit mode it uses when a request names none.
    pub default_limit_mode: &'static str,
    /// Whether it solves rigs (skeletons) too: CCD, FABRIK and the closed form solve chains
    /// only.
    pub solves_rigs: bool,
    /// Whether the λ setting (`lambda`) sets its damping (damped least squares,
    /// Levenberg–Marquardt): the page enables its λ field for these only.
    pub uses_lambda: bool,
    /// The arm shapes the method solves, when it does not solve every arm: `[links, orientation
    /// goal]` pairs (the closed form: two links with a position goal, three with an orientation
    /// goal). Absent: any arm.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shapes: Option<Vec<(usize, bool)>>,
}

/// The settings a solve uses when a request (or `ikarus solve`) names none: the page starts
/// with these, so that its first click gives what the CLI gives for the same goal.
#[derive(Debug, Serialize)]
pub struct Defaults {
    /// `ikarus solve` enforces no joint limits unless `--limits` is given.
    pub limits: bool,
    /// Restarts from other start poses when a solve stalls; 0 solves once.
    pub restarts: u32,
    /// The damping λ of the damped methods.
    pub lambda: f64,
    /// The distance from the goal that counts as reached.
    pub tolerance: f64,
    /// The most iterations of one solve.
    pub max_iterations: u32,
}

/// The answer of `GET /api/meta`.
#[derive(Debug, Serialize)]
pub struct Meta {
    /// The solver methods, in the order the page lists them.
    pub methods: Vec<MethodChoice>,
    /// The method a request uses when it names none.
    pub default_method: &'static str,
    /// Every limit mode.
    pub limit_modes: Vec<Choice>,
    /// The library's default limit mode; a method's own is its entry's `default_limit_mode`.
    pub default_limit_mode: &'static str,
    /// The ease curves of a motion.
    pub eases: Vec<Choice>,
    /// The ease of a motion that names none.
    pub default_ease: &'static str,
    /// The default ease's first shape parameter (`k1`).
    pub default_k1: f64,
    /// The default ease's second shape parameter (`k2`).
    pub default_k2: f64,
    /// How a motion's frames are interpolated between its solves.
    pub interpolations: Vec<Choice>,
    /// The interpolation of a motion that names none.
    pub default_interpolation: &'static str,
    /// The solver settings of a request that names none.
    pub defaults: Defaults,
    /// The colours of the pictures (ikarus-render's palette), which the page draws with too.
    pub palette: ikarus_render::Colours,
}

/// The arm shapes `method` applies to, when not every arm (see [`MethodChoice::shapes`]).
fn shapes(method: Method) -> Option<Vec<(usize, bool)>> {
    // `Method` is non-exhaustive: a new closed form must be added here (the test lists them).
    (method == Method::Analytic).then(|| vec![(2, false), (3, true)])
}

/// The names and defaults, built from the library's tables.
#[must_use]
pub fn meta() -> Meta {
    let d = SolveOptions::default();
    Meta {
        methods: Method::ALL
            .iter()
            .map(|&m| MethodChoice {
                choice: Choice::of(m),
                limit_modes: LimitMode::ALL.iter().filter(|&&l| m.supports(l)).map(|l| l.name()).collect(),
                default_limit_mode: m.default_limit_mode().name(),
                solves_rigs: m.solves_rigs(),
                uses_lambda: m.uses_lambda(),
                shapes: shapes(m),
            })
            .collect(),
        default_method: d.method.name(),
        limit_modes: LimitMode::ALL.iter().map(|&l| Choice::of(l)).collect(),
        default_limit_mode: LimitMode::default().name(),
        eases: EaseKind::ALL.iter().map(|&e| Choice::of(e)).collect(),
        default_ease: EaseKind::Sine.name(),
        default_k1: ikarus::ease::DEFAULT_K1,
        default_k2: ikarus::ease::DEFAULT_K2,
        interpolations: Interpolation::ALL.iter().map(|&i| Choice::of(i)).collect(),
        default_interpolation: Interpolation::default().name(),
        defaults: Defaults {
            limits: !matches!(crate::settings::SolverSettings::default().limit_mode(d.method), Ok(LimitMode::Ignore)),
            restarts: d.restarts.map_or(0, |r| r.attempts),
            lambda: d.lambda,
            tolerance: d.tolerance,
            max_iterations: d.max_iterations,
        },
        palette: ikarus_render::COLOURS,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_variant_is_listed_with_what_it_supports() {
        let m = serde_json::to_value(meta()).unwrap();
        let names = |key: &str| -> Vec<String> {
            m[key].as_array().unwrap().iter().map(|c| c["name"].as_str().unwrap().to_owned()).collect()
        };
        assert_eq!(names("methods"), Method::names());
        assert_eq!(names("limit_modes"), LimitMode::names());
        assert_eq!(names("eases"), EaseKind::names());
        assert_eq!(names("interpolations"), Interpolation::names());
        for (method, listed) in Method::ALL.iter().zip(m["methods"].as_array().unwrap()) {
            let modes: Vec<&str> =
                listed["limit_modes"].as_array().unwrap().iter().map(|v| v.as_str().unwrap()).collect();
            let supported: Vec<&str> =
                LimitMode::ALL.iter().filter(|&&l| method.supports(l)).map(|l| l.name()).collect();
            assert_eq!(modes, supported, "{method}");
            assert_eq!(listed["default_limit_mode"], method.default_limit_mode().name());
            assert_eq!(listed["solves_rigs"], method.solves_rigs(), "{method}");
            assert_eq!(listed["uses_lambda"], method.uses_lambda(), "{method}");
            assert!(!listed["label"].as_str().unwrap().is_empty());
        }
        assert_eq!((m["default_method"].as_str(), m["default_limit_mode"].as_str()), (Some("lm"), Some("lock")));
        // The page starts as `ikarus solve` does: limits off, 16 restarts; only the closed form
        // is limited to some arms.
        assert_eq!(m["defaults"]["limits"], false);
        assert_eq!(m["defaults"]["restarts"], 16);
        let shaped: Vec<&str> = m["methods"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|c| c.get("shapes").is_some())
            .map(|c| c["name"].as_str().unwrap())
            .collect();
        assert_eq!(shaped, ["analytic"]);
        assert_eq!(m["methods"][7]["shapes"], serde_json::json!([[2, false], [3, true]]));
        assert_eq!((m["default_ease"].as_str(), m["default_interpolation"].as_str()), (Some("sine"), Some("spline")));
    }

    /// `uses_lambda` says what λ does: the same solve with λ = 0.05 and λ = 2 ends on another
    /// pose exactly for the methods that say they use it (a closed form's arm of two links, a
    /// reachable goal it answers without falling back; the others a three-link arm).
    #[test]
    fn uses_lambda_is_whether_lambda_changes_the_answer() {
        use ikarus::{Chain, Goal, Link, Solver};
        let goal = Goal::position(1.2, 1.9).unwrap();
        for &method in Method::ALL.iter() {
            let links: &[Link] = if method == Method::Analytic {
                &[Link::new(2.0, 0.3), Link::new(1.5, 0.4)]
            } else {
                &[Link::new(1.5, 0.3), Link::new(1.2, 0.4), Link::new(1.0, 0.5)]
            };
            let chain = Chain::new([0.0, 0.0], links).unwrap();
            let pose = |lambda: f64| {
                let opts =
                    SolveOptions { method, lambda, restarts: None, max_iterations: 50, ..SolveOptions::default() };
                let out = Solver::new(opts).unwrap().solve(&chain, chain.start_pose(), &goal).unwrap();
                out.pose.angles().iter().map(|a| a.to_bits()).collect::<Vec<u64>>()
            };
            assert_eq!(pose(0.05) != pose(2.0), method.uses_lambda(), "{method}");
        }
    }
}
