//! The blocks of an input file that set up the analysis: `control data` (with rigid body kinematics) and `data`/`initial value`.

pub(super) mod control;
pub(super) mod problem;
pub(super) mod rbk;
