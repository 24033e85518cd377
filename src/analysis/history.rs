//! Node histories of a run kept in memory (the `.mov` file's content as arrays, for the
//! language bindings): time, positions, orientation matrices, velocities, angular
//! velocities of every structural node at every step, step 0 being the initial state.

use super::observer::{ObserverError, RunObserver, StepDone};
use crate::model::Label;

/// What [`NodeHistories`] gathered; row-major arrays, step index first.
#[derive(Clone, Debug, Default)]
pub struct NodeHistories {
    /// [s], one per step.
    pub time: Vec<f64>,
    pub labels: Vec<Label>,
    /// Positions [m], steps × nodes × 3 (global frame).
    pub position: Vec<f64>,
    /// Orientation matrices (node frame to global), steps × nodes × 3 × 3, row-major.
    pub orientation: Vec<f64>,
    /// Velocities [m/s], steps × nodes × 3.
    pub velocity: Vec<f64>,
    /// Angular velocities [rad/s], steps × nodes × 3 (global frame).
    pub angular_velocity: Vec<f64>,
}

/// Largest number of values kept (8 GB of doubles would end in an allocation failure).
const MAX_VALUES: usize = 1 << 30;

impl RunObserver for NodeHistories {
    fn step(&mut self, e: &StepDone) -> Result<(), ObserverError> {
        let nodes = e.node_kinematics();
        if self.time.is_empty() {
            self.labels = nodes.iter().map(|(l, _)| *l).collect();
        }
        if self.orientation.len() + 9 * nodes.len() > MAX_VALUES {
            return Err(format!("the node histories would hold more than {MAX_VALUES} values: fewer steps or a longer time step").into());
        }
        self.time.push(e.time);
        for (_, k) in &nodes {
            self.position.extend(k.x.iter());
            self.velocity.extend(k.xdot.iter());
            self.angular_velocity.extend(k.omega.iter());
            for i in 0..3 {
                for j in 0..3 {
                    self.orientation.push(k.r[(i, j)]);
                }
            }
        }
        Ok(())
    }
}
