//! MBDyn's incremental update of the 3-node beam, opt-in ([`BeamUpdate::Incremental`];
//! MBDyn 1.7.3 beam.cc, `AfterPredict`, `AssStiffnessVec` and `AfterConvergence`), and of
//! the 2-node beam alike (beam2.cc: one point at the middle, linear interpolation).
//!
//! At each step the nodes' rotation increments are interpolated, not their total rotations:
//! after the predictor, with `R_i,prev` the nodes' converged orientations of the previous
//! step and `P_i` the predicted ones, `R(g_ref,i) = P_i R_i,prevᵀ` gives the section's
//! reference `R_s,ref = R(Σ N_i g_ref,i) R_s,prev` and `κ_ref = R_s,refᵀ G(g_ref) g_ref′ +
//! κ_prev`; Newton's iterates then read `R(g_i) = R_i P_iᵀ`, `R_s = R(Σ N_i g_i) R_s,ref`
//! and `κ = R_sᵀ G(g) g′ + κ_ref` (the strain `R_sᵀ p′ − ε⁰` as in the path-independent
//! beam). What MBDyn stores after convergence (`R_s,prev`, `κ_prev`) is the last
//! iterate's, recomputed here from the accepted state and the step's history.
//!
//! The history is the element's latched data ([`crate::element::Element::latch`]), so
//! residuals and Jacobians hold it fixed, and a state without any (before the first step)
//! reads the initial configuration: `P_i = R_i⁰`, `R_s,ref = R_s⁰`, `κ_ref = 0`. The
//! equilibrium then depends on the load path and the predictor, as MBDyn's does (the book,
//! docs/src/mbdyn/beams.md: "beam.cc is incremental"); the path-independent beam is romdyn's default.

use std::borrow::Cow;
use std::sync::Arc;

use crate::element::contract::{ElementState, Latched};
use crate::kinematics::{Mat3, Vec3};

/// How a beam's (beam3, beam2) section frames and curvatures follow its nodes' rotations.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum BeamUpdate {
    /// Total rotations interpolated relative to the middle node: a function of the state
    /// alone (the default: a static equilibrium, and the operating point a ROM is
    /// linearized about, do not depend on load steps).
    #[default]
    PathIndependent,
    /// MBDyn 1.7.3's update: rotation increments interpolated per step, the section frame
    /// and curvature accumulated over the steps (path dependent).
    Incremental,
}

/// The per-step history of an incremental beam on `N` nodes with `S` evaluation points,
/// latched after each prediction.
#[derive(Clone, Debug)]
pub struct StepHistory<const N: usize, const S: usize> {
    /// `P_i`: the base of Newton's rotation parameters (the predicted orientations).
    pub base: [Mat3; N],
    /// `R_s,ref` per evaluation point.
    pub frames: [Mat3; S],
    /// `κ_ref` per evaluation point [1/m].
    pub curvatures: [Vec3; S],
}

impl<const N: usize, const S: usize> StepHistory<N, S> {
    /// The history a state carries (borrowed, not copied: residuals and Jacobians read it
    /// at every iteration), `initial` where it carries none.
    pub fn of(st: &dyn ElementState, initial: impl FnOnce() -> Self) -> Cow<'_, Self> {
        st.latched().and_then(|l| l.downcast_ref::<Self>()).map_or_else(|| Cow::Owned(initial()), Cow::Borrowed)
    }

    pub fn latched(self) -> Latched {
        Arc::new(self)
    }
}
