//! What the command line's writers ask of a body, an arm or a rig alike: its solver options
//! from the flags, and its pose's CSV columns — an arm's joints by index (`theta1_deg`), a
//! rig's by bone name (`NAME_deg`, then `NAME_ext` for each prismatic bone).

use std::io::Write;

use ikarus::SolveOptions;

use crate::arm::Arm;
use crate::body::Jointed;
use crate::error::Error;
use crate::rig::Rig;
use crate::settings::SolverSettings;
use crate::solve::write_pose;

/// A body as the command line's workflows and writers see it.
pub trait BodyColumns: Jointed {
    /// The options of a command: `flags` over the file's `[solver]` table over the defaults.
    fn solve_options(&self, flags: &SolverSettings, record_every: Option<u32>) -> Result<SolveOptions, Error>;
    /// The pose's CSV columns.
    fn pose_columns(&self) -> Vec<String>;
    /// `,value` for every pose column at joint values `q`.
    fn write_pose(&self, w: &mut dyn Write, q: &[f64]) -> std::io::Result<()>;
}

impl BodyColumns for Arm {
    fn solve_options(&self, flags: &SolverSettings, record_every: Option<u32>) -> Result<SolveOptions, Error> {
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
    fn solve_options(&self, flags: &SolverSettings, record_every: Option<u32>) -> Result<SolveOptions, Error> {
        self.options(flags, record_every)
    }
    fn pose_columns(&self) -> Vec<String> {
        crate::report::pose_columns(&self.skeleton)
    }
    fn write_pose(&self, w: &mut dyn Write, q: &[f64]) -> std::io::Result<()> {
        write_pose(w, self, q)
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;

    fn row(body: &dyn Fn(&mut Vec<u8>) -> std::io::Result<()>) -> String {
        let mut out = Vec::new();
        body(&mut out).unwrap();
        String::from_utf8(out).unwrap()
    }

    #[test]
    fn an_arms_joints_by_index_a_rigs_by_bone_name() {
        let arm = Arm::load(None).unwrap();
        assert_eq!(arm.pose_columns(), ["theta1_deg", "theta2_deg", "theta3_deg"]);
        let q = [std::f64::consts::FRAC_PI_2, 0.0, -std::f64::consts::PI];
        assert_eq!(row(&|w| BodyColumns::write_pose(&arm, w, &q)), ",90.0,0.0,-180.0");

        let rig = Rig::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/rigs/puppet.toml")).unwrap();
        let columns = rig.pose_columns();
        let names = rig.skeleton.names();
        assert_eq!(columns.len(), names.len());
        for (c, n) in columns.iter().zip(names) {
            assert_eq!(c, &format!("{n}_deg"));
        }
        let values = row(&|w| BodyColumns::write_pose(&rig, w, rig.start()));
        assert_eq!(values.matches(',').count(), names.len(), "{values}");
    }
}
