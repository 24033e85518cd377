//! The `elements` block: the element types romdyn reads, by family (bodies, joints, beams, forces, genels, electric, hydraulic, plates, modal), their constitutive laws, and the table of element types from which the refusals are written.

pub(super) mod beam_piezo;
pub(super) mod beam_slider;
pub(super) mod beams;
pub(super) mod block;
pub(super) mod context;
pub(super) mod driven;
pub(super) mod electric;
pub(super) mod forces;
pub(super) mod friction;
pub(super) mod genels;
pub(super) mod hints;
pub(super) mod hydraulic;
pub(super) mod hydraulic_args;
pub(super) mod hydraulic_elements;
pub(super) mod joints;
pub(super) mod laws;
pub(super) mod plate_laws;
pub(super) mod modal;
pub(super) mod plates;
pub(super) mod screw;
pub(super) mod total_equation;
pub(super) mod total_joint;
pub(super) mod variable_body;
