//! The shared facade of the edges, in one place: arm files, settings, requests, messages and the
//! API's JSON answers. Every other module names it as `crate::edge`.

pub(crate) use ikarus_edge::edge::*;
