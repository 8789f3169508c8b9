//! The work meter of a region's construction: every loop of the sweep and the union spends
//! units of work as it goes (one per pair of boundary pieces tested for crossings, per piece
//! a side test looks at, per segment a winding number walks), and stops when the caller's
//! [`Interrupt`] is set or the units run out.
//!
//! A unit is a few hundred nanoseconds at most (an intersection of two arcs, one step of a
//! winding number), and the meter is asked at the end of each inner loop, so an interrupt is
//! seen within a few milliseconds. Counting instead of timing keeps the answer deterministic:
//! the same chain runs out of units at the same step on every machine.

use crate::Interrupt;

/// Why a construction stopped before its end.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Stop {
    /// The caller's interrupt was set.
    Interrupted,
    /// The work cap was spent.
    OverBudget,
}

/// Units of work left, and the interrupt to watch.
#[derive(Debug)]
pub(crate) struct Work<'a> {
    interrupt: Option<&'a Interrupt>,
    left: u64,
    /// Units spent so far.
    pub(crate) spent: u64,
}

impl<'a> Work<'a> {
    /// `cap` units (`u64::MAX`: no cap, never spent), stopping early when `interrupt` is set.
    pub(crate) fn new(cap: u64, interrupt: Option<&'a Interrupt>) -> Work<'a> {
        Work { interrupt, left: cap, spent: 0 }
    }

    /// No cap and nothing to watch.
    pub(crate) fn unbounded() -> Work<'static> {
        Work::new(u64::MAX, None)
    }

    /// Spends `units`; `Err` once the cap is passed or the interrupt is set.
    #[inline]
    pub(crate) fn spend(&mut self, units: u64) -> Result<(), Stop> {
        self.spent = self.spent.saturating_add(units);
        if self.left != u64::MAX {
            self.left = self.left.checked_sub(units).ok_or(Stop::OverBudget)?;
        }
        if crate::interrupt::is_set(self.interrupt) { Err(Stop::Interrupted) } else { Ok(()) }
    }

    /// [`Work::spend`] of a count given as `usize`.
    #[inline]
    pub(crate) fn spend_n(&mut self, units: usize) -> Result<(), Stop> {
        self.spend(u64::try_from(units).unwrap_or(u64::MAX))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_meter_stops_at_its_cap_and_at_the_interrupt() {
        let mut w = Work::new(10, None);
        assert_eq!(w.spend(6), Ok(()));
        assert_eq!(w.spend(4), Ok(()));
        assert_eq!(w.spend(1), Err(Stop::OverBudget));
        let token = Interrupt::new();
        let mut w = Work::new(u64::MAX, Some(&token));
        assert_eq!(w.spend_n(1000), Ok(()));
        token.interrupt();
        assert_eq!(w.spend(0), Err(Stop::Interrupted));
        let mut unbounded = Work::unbounded();
        assert_eq!((unbounded.spend(u64::MAX), unbounded.spend(u64::MAX)), (Ok(()), Ok(())));
    }
}
