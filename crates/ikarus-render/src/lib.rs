//! Pictures of planar arms.
