//! `GET /api/meta`: the names the page offers in its select lists (methods, limit modes, eases)
//! and their defaults, read from the library's enums so that the page cannot drift from them.

use axum::Json;
use ikarus::{EaseKind, LimitMode, Method, Named, SolveOptions};
use serde::Serialize;

/// One choice of a select list.
#[derive(Debug, Serialize)]
pub struct Choice {
    pub name: &'static str,
    pub label: &'static str,
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
    #[serde(flatten)]
    pub choice: Choice,
    pub limit_modes: Vec<&'static str>,
    pub default_limit_mode: &'static str,
}

/// The answer of `GET /api/meta`.
#[derive(Debug, Serialize)]
pub struct Meta {
    pub methods: Vec<MethodChoice>,
    pub default_method: &'static str,
    pub limit_modes: Vec<Choice>,
    pub default_limit_mode: &'static str,
    pub eases: Vec<Choice>,
    pub default_ease: &'static str,
    pub default_k1: f64,
    pub default_k2: f64,
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
            })
            .collect(),
        default_method: d.method.name(),
        limit_modes: LimitMode::ALL.iter().map(|&l| Choice::of(l)).collect(),
        default_limit_mode: LimitMode::default().name(),
        eases: EaseKind::ALL.iter().map(|&e| Choice::of(e)).collect(),
        default_ease: EaseKind::Sine.name(),
        default_k1: ikarus::ease::DEFAULT_K1,
        default_k2: ikarus::ease::DEFAULT_K2,
    }
}

pub async fn handler() -> Json<Meta> {
    Json(meta())
}
