//! The reachable workspace of a chain.
