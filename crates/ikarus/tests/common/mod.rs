//! Shared by the integration tests and the benchmarks (which include it with `#[path]`).
#![allow(dead_code)]

pub mod fixtures;

pub use ikarus::rng::SplitMix64;
