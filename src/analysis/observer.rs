//! What a run reports while it goes: a start, the initial derivatives, every step (step 0 is
//! the initial state) and every eigenanalysis. Observers (a progress bar, the file writers)
//! implement [`RunObserver`]; an observer's error stops the run.

use super::eigen::Eigenanalysis;
pub use super::error::ObserverError;
use crate::dae::{Assembler, State};
use crate::element::{NodeKinematics, SectionState};
use crate::model::{InitialValueProblem, Label, Model};

/// The run is about to start.
pub struct RunStart<'a> {
    pub model: &'a Model,
    pub problem: &'a InitialValueProblem,
    /// Number of time steps the run will take.
    pub steps: usize,
    /// Number of eigenanalyses requested.
    pub eigenanalyses: usize,
}

/// The consistent initial derivatives converged.
#[derive(Clone, Copy, Debug)]
pub struct Derivatives {
    /// [s]
    pub time: f64,
    pub iterations: usize,
    /// `‖F‖∞` at convergence.
    pub residual_norm: f64,
}

/// A step converged (step 0: the initial state after the derivatives).
pub struct StepDone<'a> {
    pub step: usize,
    /// [s]
    pub time: f64,
    /// [s]
    pub time_step: f64,
    pub iterations: usize,
    /// `‖F‖∞` when Newton stopped.
    pub residual_norm: f64,
    pub model: &'a Model,
    pub assembler: &'a Assembler<'a>,
    pub state: &'a State,
}

impl StepDone<'_> {
    /// Every beam's internal forces and deformation at its evaluation points.
    pub fn beam_sections(&self) -> Vec<(Label, Vec<SectionState>)> {
        self.assembler.section_states(self.state).into_iter().map(|(e, s)| (self.model.elements[e].label(), s)).collect()
    }

    /// Every shell's stress resultants at its Gauss points (MBDyn's `.pla` rows).
    pub fn plate_resultants(&self) -> Vec<(Label, Vec<f64>)> {
        self.assembler.plate_resultants(self.state).into_iter().map(|(e, s)| (self.model.elements[e].label(), s)).collect()
    }

    /// Every written hydraulic element's `.hyd` row (MBDyn's hydraulic elements' output).
    pub fn hydraulic_rows(&self) -> Vec<(Label, Vec<f64>)> {
        self.assembler.hydraulic_rows(self.state).into_iter().map(|(e, r)| (self.model.elements[e].label(), r)).collect()
    }

    /// Every modal joint's modal coordinates and their derivatives
    /// ([`crate::dae::modal_coordinates`]).
    pub fn modal_coordinates(&self) -> Vec<crate::dae::ModalRow> {
        crate::dae::modal_coordinates(self.assembler, self.state)
    }

    /// Every structural node's position, orientation and velocities (global frame).
    pub fn node_kinematics(&self) -> Vec<(Label, NodeKinematics)> {
        self.model.nodes.iter().enumerate().map(|(i, n)| (n.label, self.state.node_frame(&self.assembler.dofs, i).kin)).collect()
    }

    /// The accelerations of the dynamic nodes whose rows (or a written dummy node's rows)
    /// `output` writes with accelerations ([`crate::dae::node_accelerations`]).
    pub fn node_accelerations(&self, output: &crate::model::MotionOutput) -> Vec<(Label, crate::output::motion::Accelerations)> {
        use crate::model::NodeSource;
        // The model nodes under each written entry with accelerations, through its dummy bases.
        let mut wanted = vec![false; self.model.nodes.len()];
        let mut stack: Vec<usize> = (0..output.nodes.len()).filter(|&k| output.nodes[k].written && output.nodes[k].accelerations).collect();
        while let Some(k) = stack.pop() {
            match &output.nodes[k].source {
                NodeSource::Node(l) => {
                    if let Some(i) = self.model.node_index(*l) {
                        wanted[i] = true;
                    }
                }
                NodeSource::Offset { base, .. } => stack.push(*base),
                NodeSource::RelativeFrame { base, reference } => stack.extend([*base, *reference]),
            }
        }
        let acc = crate::dae::node_accelerations(self.assembler, self.state, &wanted);
        self.model.nodes.iter().zip(acc).filter_map(|(n, a)| a.map(|a| (n.label, a))).collect()
    }
}

/// An eigenanalysis was done.
pub struct EigenDone<'a> {
    pub analysis: &'a Eigenanalysis,
}

/// Receives a run's events; every method defaults to doing nothing.
pub trait RunObserver {
    fn started(&mut self, _: &RunStart) -> Result<(), ObserverError> {
        Ok(())
    }
    fn derivatives(&mut self, _: &Derivatives) -> Result<(), ObserverError> {
        Ok(())
    }
    fn step(&mut self, _: &StepDone) -> Result<(), ObserverError> {
        Ok(())
    }
    fn eigenanalysis(&mut self, _: &EigenDone) -> Result<(), ObserverError> {
        Ok(())
    }
}

/// No observer.
impl RunObserver for () {}

/// Two observers, called in order.
impl<A: RunObserver, B: RunObserver> RunObserver for (A, B) {
    fn started(&mut self, e: &RunStart) -> Result<(), ObserverError> {
        self.0.started(e)?;
        self.1.started(e)
    }
    fn derivatives(&mut self, e: &Derivatives) -> Result<(), ObserverError> {
        self.0.derivatives(e)?;
        self.1.derivatives(e)
    }
    fn step(&mut self, e: &StepDone) -> Result<(), ObserverError> {
        self.0.step(e)?;
        self.1.step(e)
    }
    fn eigenanalysis(&mut self, e: &EigenDone) -> Result<(), ObserverError> {
        self.0.eigenanalysis(e)?;
        self.1.eigenanalysis(e)
    }
}
