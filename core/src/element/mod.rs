//! The element library and the one contract every element follows.
//!
//! An element contributes to the DAE residual `F(y, ẏ, t)` (eq. 1) and to its Jacobian
//! `J(c) = F_/ẏ + c F_/y` (eq. 5). It sees its nodes only through their kinematics
//! (position `x`, orientation `R`, velocity `ẋ`, angular velocity `ω`) and writes to rows
//! and columns named locally (`Row`, `Col`): the assembler maps them to global equations,
//! applies the chain rule of the orientation parameters (`δθ = G δg`,
//! `δω = G δġ + ∂(Gġ)/∂g δg`) and the constraint form (eq. 29 or eq. 30). The integrator,
//! the static solver and the linearization use nothing else.

mod anchor;
mod angular_acceleration;
mod axial_rotation;
mod beam;
mod beam_slider;
mod bistop_rod;
mod body;
mod variable_body;
mod cardano;
mod central_gravity;
mod contract;
mod deformable;
mod deformable_joint;
mod distance;
mod electric;
mod electric_cogging;
pub mod drive;
mod driven_element;
mod driven_gravity;
mod driven_joint;
mod force;
pub mod frame_motion;
mod friction;
mod hinge_friction;
mod hydraulic;
mod hydraulic_pipe_dynamic;
mod hydraulic_storage;
mod function_hinge;
mod genel;
mod state_space;
mod gimbal;
mod imposed_velocity;
mod internal_force;
mod invariant_hinge;
mod joint;
mod law_functions;
pub mod modal;
mod nlsf_rod;
mod prestrained_rod;
pub mod private_data;
mod screw;
mod tikhonov;
mod time_variant_law;
mod time_variant_rod;
mod total_equation;
mod viscous_body;
mod wrapper;
mod screw_friction;
mod shell;

pub use beam::{shape as beam_shape, Beam2, Beam3, BeamError, BeamUpdate, BeamNode, PiezoActuator, PiezoError, SectionLaw, SectionOrientation};
pub use beam_slider::{BeamSlider, SliderBeam, SliderKind};
pub use bistop_rod::{BistopRod, BistopStatus};
pub use body::RigidBody;
pub use shell::membrane::{Membrane4, MembraneLaw};
pub use shell::{Shell4, ShellError, ShellLaw, ShellVariant};
pub use modal::{FemNode, Interface as ModalInterface, ModalBody, ModalFrame};
pub use variable_body::VariableBody;
pub use frame_motion::{FrameMotion, FrameState};
pub use cardano::CardanoHinge;
pub use central_gravity::CentralGravity;
pub use wrapper::ElementWrapper;
pub use contract::{Col, Element, ElementState, EnergyStore, Events, FlexiblePoint, JacobianSink, Label, Latched, NodeKinematics, NonSmooth, Outputs, ResidualSink, Row, ScalarNodeId, ScalarNodeKind, SectionState, UnknownKind};
pub use deformable::{DeformableDisplacement, DeformableHinge, LinearViscoelastic, Rod, RodViscosity};
pub use distance::Distance;
pub use electric::{Accelerometer, AccelerometerKind, Cogging, DisplacementSensor, Motor};
pub use hydraulic::{Actuator, ControlValve, HydraulicFluid, MinorLoss, Pipe};
pub use hydraulic_pipe_dynamic::DynamicPipe;
pub use hydraulic_storage::{Accumulator, Orifice, Tank};
pub use genel::{AbstractForce, ScalarClamp, ScalarDistance, ScalarDof, ScalarLaw, ScalarMass, ScalarSpring, ScalarSpringPair};
pub use state_space::{controllable_form, observable_form, ScalarInput, StateSpace};
pub use deformable_joint::DeformableJoint;
pub use invariant_hinge::InvariantDeformableHinge;
pub use driven_element::{DrivenElement, Hint, HintValue};
pub use driven_gravity::DrivenGravity;
pub use driven_joint::{DrivenJoint, VectorDrive, RotationRemnant};
pub use force::{Couple, Force, ForceFrame};
pub use friction::{InLineFriction, ModLugre};
pub use hinge_friction::{HingeNormalForce, RevoluteHingeFriction};
pub use screw_friction::ScrewFriction;
pub use function_hinge::FunctionHinge;
pub use gimbal::GimbalRotation;
pub use imposed_velocity::{ImposedVelocity, VelocityKind};
pub use internal_force::{InternalCouple, InternalForce, TotalInternalForce};
pub use anchor::Anchor;
pub use angular_acceleration::AngularAcceleration;
pub use axial_rotation::AxialRotation;
pub use joint::{Joint, JointKind};
pub use law_functions::LawFunctions;
pub use nlsf_rod::NlsfRod;
pub use prestrained_rod::PrestrainedRod;
pub use screw::Screw;
pub use tikhonov::Tikhonov;
pub use time_variant_law::TimeVariance;
pub use time_variant_rod::TimeVariantRod;
pub use total_equation::{TotalEquation, TotalReaction};
pub use viscous_body::ViscousBody;
