//! The multibody solver: every element's Jacobian against finite differences
//! (`multibody_jacobians`, `romdyn check`), springs and a spinning body linearized, the
//! integrator (orientation update, Bathe), beams (`beam2`, `beam3` and its incremental update,
//! internal forces, `beam slider`), joints and their equations, friction (joint, hinge, screw,
//! brake), loads and constitutive laws: each against closed forms, MBDyn 1.7.3's numbers on
//! the same files, or finite differences.

#[path = "../common/mod.rs"]
mod common;

mod beam2;
mod beam_piezo;
mod beam_incremental;
mod beam_output;
mod beam_rotation;
mod beam_slider;
mod brake;
mod electric;
mod fixed_pattern;
mod function_hinge;
mod hinge_friction;
mod hydraulic;
mod hydraulic_elements;
mod hydraulic_output;
mod integrator_bathe;
mod jacobian_check;
mod modal_element;
mod motor_cogging;
mod joint_friction;
mod mbdyn_beam;
mod mbdyn_joint_equations;
mod mbdyn_joints;
mod mbdyn_loads;
mod multibody_jacobians;
mod multibody_springs;
mod newton_reuse;
mod nlsf_laws;
mod nonlinear_laws;
mod rotation_update;
mod scalar_nodes;
mod screw_friction;
mod screw_joint;
mod shell;
mod shell_ans;
mod shell_laws;
mod membrane;
mod spinning_linearization;
