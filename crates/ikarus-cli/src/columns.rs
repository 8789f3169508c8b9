//! What the command line's writers ask of a body, an arm or a rig alike: its solver options
//! from the flags, and its pose's CSV columns — an arm's joints by index (`theta1_deg`), a
//! rig's by bone name (`NAME_deg`, then `NAME_ext` for each prismatic bone).

use std::io::Write;

use ikarus::SolveOptions;

use crate::arm::Arm;
use crate::body::Jointed;
use crate::error::CliError;
use crate::rig::Rig;
use crate::settings::SolverSettings;
use crate::solve::write_pose;

/// A body as the command line's workflows and writers see it.
pub trait BodyColumns: Jointed {
    /// The options of a command: `flags` over the file's `[solver]` table over the defaults.
    fn solve_options(&self, flags: &SolverSettings, record_every: Option<u32>) -> Result<SolveOptions, CliError>;
    /// The pose's CSV columns.
    fn pose_columns(&self) -> Vec<String>;
    /// `,value` for every pose column at joint values `q`.
    fn write_pose(&self, w: &mut dyn Write, q: &[f64]) -> std::io::Result<()>;
}

impl BodyColumns for Arm {
    fn solve_options(&self, flags: &SolverSettings, record_every: Option<u32>) -> Result<SolveOptions, CliError> {
        self.options(flags, record_every)
    }
    fn pose_columns(&self) -> Vec<String> {
        (1..=self.chain.len()).map(|i| format!("theta{i}_deg")).collect()
    }
    fn write_pose(&self, w: &mut dyn Write, q: &[f64]) -> std::io::Result<()> {
        q.iter().try_for_each(|a| write!(w, ",{:?}", a.to_degrees()))
    }
}

impl BodyColumns for Rig {
    fn solve_options(&self, flags: &SolverSettings, record_every: Option<u32>) -> Result<SolveOptions, CliError> {
        self.options(flags, record_every)
    }
    fn pose_columns(&self) -> Vec<String> {
        crate::report::pose_columns(&self.skeleton)
    }
    fn write_pose(&self, w: &mut dyn Write, q: &[f64]) -> std::io::Result<()> {
        write_pose(w, self, q)
    }
}
