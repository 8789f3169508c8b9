//! Shared by the integration tests and the benchmarks (which include it with `#[path]`).

pub use ikarus::rng::SplitMix64;
