//! Checks of [`SolveOptions`] that depend on the chain they are used with.
//!
//! [`SolveOptions::validate`] checks what the options say on their own; this module checks what
//! they say about a particular chain (today: one rate per joint). The edges (the command line,
//! the HTTP API) call it once, when they build options, so that a mismatch is reported before
//! any work or output starts, in the same words as [`Solver::solve`](crate::Solver::solve)
//! would report it.

use crate::chain::Chain;
use crate::solve::{SolveError, SolveOptions};

impl SolveOptions {
    /// Checks the options against `chain`: [`SolveOptions::rates`] is empty or has one value
    /// per joint ([`SolveError::RatesLength`] otherwise, the error a solve would end with).
    pub fn validate_for(&self, chain: &Chain) -> Result<(), SolveError> {
        let n = chain.len();
        if !self.rates.is_empty() && self.rates.len() != n {
            return Err(SolveError::RatesLength { expected: n, got: self.rates.len() });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use crate::{Chain, Link, SolveError, SolveOptions};

    #[test]
    fn rates_are_none_or_one_per_joint() {
        let chain = Chain::new([0.0, 0.0], &[Link::new(1.0, 0.0), Link::new(1.0, 0.0)]).unwrap();
        assert_eq!(SolveOptions::default().validate_for(&chain), Ok(()));
        let two = SolveOptions { rates: vec![1.0, 0.5], ..SolveOptions::default() };
        assert_eq!(two.validate_for(&chain), Ok(()));
        let three = SolveOptions { rates: vec![1.0; 3], ..SolveOptions::default() };
        assert_eq!(three.validate_for(&chain), Err(SolveError::RatesLength { expected: 2, got: 3 }));
    }
}
