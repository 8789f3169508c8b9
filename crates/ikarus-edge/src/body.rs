//! The one body of a command or a request: an arm (a chain, from an arm file) or a rig (a tree of
//! named bones, from a rig file), read by one reader. A job's workflow takes a body and chooses
//! what really differs between the two (the solver's entry point, the JSON's angles by index or
//! by bone name, the picture) by a `match` on it.

use std::path::Path;

use crate::arm::Arm;
use crate::error::CliError;
use crate::rig::Rig;

/// An arm or a rig.
#[derive(Debug, Clone)]
pub enum Body {
    /// A chain: `--arm FILE`, the built-in seed arm without one, or a request's `arm`.
    Chain(Box<Arm>),
    /// A skeleton: `--rig FILE` or a request's `rig` (both boxed: a body is moved, not copied).
    Rig(Box<Rig>),
}

impl Body {
    /// `--rig FILE` when given, else `--arm FILE`, else the built-in seed arm; messages name the
    /// file as each reader does (`rig file r.toml: …`, `arm file a.toml: …`).
    pub fn load(arm: Option<&Path>, rig: Option<&Path>) -> Result<Self, CliError> {
        match rig {
            Some(path) => Ok(Self::Rig(Box::new(Rig::load(path)?))),
            None => Ok(Self::Chain(Box::new(Arm::load(arm)?))),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rig_file_wins_and_no_file_is_the_seed_arm() {
        let rigs = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/rigs/puppet.toml");
        assert!(matches!(Body::load(None, Some(&rigs)), Ok(Body::Rig(r)) if r.name == "puppet"));
        assert!(matches!(Body::load(None, None), Ok(Body::Chain(a)) if a.chain.len() == 3));
        let Err(e) = Body::load(None, Some(Path::new("/nonexistent/r.toml"))) else { panic!("read a missing file") };
        assert!(e.to_string().starts_with("rig file /nonexistent/r.toml: "), "{e}");
    }
}
