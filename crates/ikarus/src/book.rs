#[doc = include_str!("../../../README.md")] pub struct Readme; #[doc = include_str!("../../../docs/src/guide/library.md")] pub struct GuideLibrary; #[doc = include_str!("../../../docs/src/guide/motion.md")] pub struct GuideMotion; #[doc = include_str!("../../../docs/src/guide/rigs.md")] pub struct GuideRigs; #[doc = include_str!("../../../docs/src/solving/rigs.md")] pub struct SolvingRigs;
// Only the first line counts: rustdoc numbers a block's lines from its item's line, so every
// item stands on line 1, and a failing block is named by its page and its line there
// (`docs/src/guide/motion.md - book::GuideMotion (line 169)`). One item per page
// with ```rust blocks; crates/ikarus-cli/tests/readme.rs checks that none is missing.
