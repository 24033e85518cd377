//! The element contract: local addressing of rows and columns, and the two sinks.

use crate::kinematics::{Mat3, Vec3};

/// Label of a node or an element, as in MBDyn input files.
pub type Label = u32;

/// The kinds of MBDyn's scalar nodes that carry an unknown (input manual, §Nodes): each kind
/// has its own label space, as in MBDyn.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum ScalarNodeKind {
    /// `abstract`: algebraic or differential, no unit.
    Abstract,
    /// `electric`: a voltage [V], differential.
    Electric,
    /// `hydraulic`: a pressure [Pa], algebraic.
    Hydraulic,
}

impl ScalarNodeKind {
    /// MBDyn's keyword of the node type: "abstract", "electric", "hydraulic".
    pub fn keyword(self) -> &'static str {
        match self {
            ScalarNodeKind::Abstract => "abstract",
            ScalarNodeKind::Electric => "electric",
            ScalarNodeKind::Hydraulic => "hydraulic",
        }
    }
}

/// A scalar node: its kind and its label within that kind.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct ScalarNodeId {
    pub kind: ScalarNodeKind,
    pub label: Label,
}

impl std::fmt::Display for ScalarNodeId {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} node {}", self.kind.keyword(), self.label)
    }
}

/// Kinematics of one node, as an element sees it.
#[derive(Clone, Debug)]
pub struct NodeKinematics {
    pub x: Vec3,
    pub r: Mat3,
    pub xdot: Vec3,
    pub omega: Vec3,
}

/// An equation, addressed locally. `slot` indexes the element's own node list.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Row {
    /// Force (0..3) or moment (3..6) equilibrium of a node: residual `… − f`.
    Equilibrium { slot: usize, comp: usize },
    /// Linear (0..3) or angular (3..6) momentum definition of a dynamic node.
    Momentum { slot: usize, comp: usize },
    /// The element's own constraint equation `k`.
    Constraint(usize),
    /// The equation of the element's scalar node `slot` (its index in
    /// [`Element::scalar_nodes`]): an abstract node's "force" row, MBDyn's
    /// `iGetFirstRowIndex` of a `ScalarNode`; residual `… − f`.
    Scalar { slot: usize },
}

/// A perturbation an entry is a derivative with respect to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Col {
    Position { slot: usize, comp: usize },
    /// Virtual rotation δθ (`δR Rᵀ = [δθ×]`).
    Rotation { slot: usize, comp: usize },
    Velocity { slot: usize, comp: usize },
    AngularVelocity { slot: usize, comp: usize },
    /// The element's own unknown `k` (a multiplier, a coordinate or a state).
    Multiplier(usize),
    /// The time derivative of the element's own unknown `k`, a differential state
    /// ([`UnknownKind::State`]): its entries go to `F_/ẏ`.
    Rate(usize),
    /// The value `x` of the element's scalar node `slot` (a `y` unknown).
    ScalarValue { slot: usize },
    /// The time derivative `ẋ` of the element's scalar node `slot` (a differential node
    /// only): its entries go to `F_/ẏ`.
    ScalarRate { slot: usize },
}

/// One private datum of an element ([`super::private_data`]): its value at a state, `None`
/// where the state lacks a node it reads, and the memory it keeps across steps, if any (a
/// rotation counted across turns), which the run advances with the model's step drives.
#[derive(Clone)]
pub struct PrivateDatum {
    read: std::sync::Arc<dyn Fn(&dyn ElementState) -> Option<f64> + Send + Sync>,
    memory: Option<super::drive::StepDrive>,
}

impl PrivateDatum {
    /// A datum that is a function of the state alone.
    pub fn new(read: impl Fn(&dyn ElementState) -> Option<f64> + Send + Sync + 'static) -> Self {
        PrivateDatum { read: std::sync::Arc::new(read), memory: None }
    }

    /// A datum that is the value of `memory` (a drive with a memory of the accepted steps).
    pub fn remembering(memory: super::drive::StepDrive) -> Self {
        let m = memory.clone();
        PrivateDatum { read: std::sync::Arc::new(move |st: &dyn ElementState| Some(m.value_at(st.time(), Some(st))).filter(|v| !v.is_nan())), memory: Some(memory) }
    }

    pub fn value(&self, st: &dyn ElementState) -> Option<f64> {
        (self.read)(st)
    }

    /// The memory the run must advance at every step (the model's step drives).
    pub fn memory(&self) -> Option<&super::drive::StepDrive> {
        self.memory.as_ref()
    }
}

/// Data an element re-sets at an event and holds until the next one (a driven element's
/// drives re-set by its hints when it switches on, a bistop law's status and reference
/// strain): kept in the state ([`crate::dae::State::latched`]), set by
/// [`Events::latch`] once per step, never inside Newton's iterations.
pub type Latched = std::sync::Arc<dyn std::any::Any + Send + Sync>;

/// What an element reads: its nodes' kinematics, its multipliers, the time and gravity.
pub trait ElementState {
    fn node(&self, slot: usize) -> &NodeKinematics;
    fn multiplier(&self, k: usize) -> f64;
    /// The time derivative of the element's own unknown `k`; read only for a differential
    /// state ([`UnknownKind::State`]), zero where the caller integrates none (the initial
    /// assembly).
    fn rate(&self, _k: usize) -> f64 {
        0.0
    }
    fn time(&self) -> f64;
    /// The value of the element's scalar node `slot` ([`Element::scalar_nodes`]).
    fn scalar_value(&self, _slot: usize) -> f64 {
        0.0
    }
    /// The time derivative of the element's scalar node `slot` (zero where the caller
    /// integrates none).
    fn scalar_rate(&self, _slot: usize) -> f64 {
        0.0
    }
    /// Any scalar node of the model, `(value, derivative)`, at the state being assembled
    /// (what a `dof` or `node` drive caller on a scalar node reads); `None` where the caller
    /// has no model or no such node.
    fn scalar_node(&self, _id: ScalarNodeId) -> Option<(f64, f64)> {
        None
    }
    /// Gravity [m/s²], already multiplied by the load factor.
    fn gravity(&self) -> Vec3;
    /// Factor on applied loads (ramped from 0 to 1 by static analysis; 1 otherwise).
    fn load_factor(&self) -> f64;
    /// The factor the assembler multiplies holonomic constraint rows by: `1/c` in the form
    /// of eq. 30, 1 otherwise. Constraint rows depend on positions, whose scaling the
    /// assembler applies; an equation in the element's own multiplier alone (a switched-off
    /// driven element's `λ = 0`) needs it to write a Jacobian consistent with its residual.
    fn constraint_row_scale(&self) -> f64 {
        1.0
    }
    /// Any structural node of the model by label, at the state being assembled (what a
    /// drive reading the model's state sees, MBDyn's `model::position(N)`, …); `None` where
    /// the caller has no model (a unit test of one element).
    fn structural_node(&self, _label: Label) -> Option<&NodeKinematics> {
        None
    }
    /// Own unknown `k` of the element `type_name` `label` and its rate, at the state being
    /// assembled (a drive reading a modal joint's `q[N]`); `None` where the state has no
    /// such unknown (the initial assembly, a unit test of one element).
    fn element_unknown(&self, _type_name: &str, _label: Label, _k: usize) -> Option<(f64, f64)> {
        None
    }
    /// The element's data of its last event ([`Events::latch`]), `None` before any (the
    /// element's data as read).
    fn latched(&self) -> Option<&(dyn std::any::Any + Send + Sync)> {
        None
    }
}

/// Where an element adds its residual.
pub trait ResidualSink {
    fn add(&mut self, row: Row, value: f64);
}

/// Where an element adds `∂F/∂(perturbation)` entries; the assembler turns them into `J(c)`.
pub trait JacobianSink {
    fn add(&mut self, row: Row, col: Col, value: f64);
    /// A 3x3 block (the assembler maps a block of one node's columns at once).
    fn add_block(&mut self, rows: [Row; 3], cols: [Col; 3], m: &Mat3) {
        for (i, row) in rows.into_iter().enumerate() {
            for (j, col) in cols.into_iter().enumerate() {
                self.add(row, col, m[(i, j)]);
            }
        }
    }
    /// Blocks `m[k]` in the same three rows at columns `cols[k]`, in order: the same entries
    /// as one [`JacobianSink::add_block`] per block (the assembler maps the rows once; an
    /// element with many blocks in a row of three equations, a beam, hands them at once).
    fn add_blocks(&mut self, rows: [Row; 3], cols: &[[Col; 3]], m: &[Mat3]) {
        debug_assert_eq!(cols.len(), m.len());
        for (c, m) in cols.iter().zip(m) {
            self.add_block(rows, *c, m);
        }
    }
}

/// Rows of a 3-vector quantity.
impl Row {
    pub fn force(slot: usize) -> [Row; 3] {
        [0, 1, 2].map(|comp| Row::Equilibrium { slot, comp })
    }
    pub fn moment(slot: usize) -> [Row; 3] {
        [3, 4, 5].map(|comp| Row::Equilibrium { slot, comp })
    }
    pub fn linear_momentum(slot: usize) -> [Row; 3] {
        [0, 1, 2].map(|comp| Row::Momentum { slot, comp })
    }
    pub fn angular_momentum(slot: usize) -> [Row; 3] {
        [3, 4, 5].map(|comp| Row::Momentum { slot, comp })
    }
}

impl Col {
    pub fn position(slot: usize) -> [Col; 3] {
        [0, 1, 2].map(|comp| Col::Position { slot, comp })
    }
    pub fn rotation(slot: usize) -> [Col; 3] {
        [0, 1, 2].map(|comp| Col::Rotation { slot, comp })
    }
    pub fn velocity(slot: usize) -> [Col; 3] {
        [0, 1, 2].map(|comp| Col::Velocity { slot, comp })
    }
    pub fn angular_velocity(slot: usize) -> [Col; 3] {
        [0, 1, 2].map(|comp| Col::AngularVelocity { slot, comp })
    }
}

/// Adds a 3-vector to three rows.
pub fn add_vec(sink: &mut dyn ResidualSink, rows: [Row; 3], v: &Vec3) {
    for (k, row) in rows.into_iter().enumerate() {
        sink.add(row, v[k]);
    }
}

/// Adds a 3x3 block.
pub fn add_block(sink: &mut dyn JacobianSink, rows: [Row; 3], cols: [Col; 3], m: &Mat3) {
    sink.add_block(rows, cols, m);
}

/// What an element's own unknown `k` is, with its equation `k`: it decides how the
/// integrator updates the unknown, which coefficient its Jacobian column takes and whether
/// the equation is divided by dCoef in the form of eq. 30 (paper §6.1). Algebraic kinds
/// (multipliers) carry no time derivative of their own; differential kinds (coordinates,
/// states) are integrated like a node's position.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum UnknownKind {
    /// Algebraic: the Lagrange multiplier of a holonomic constraint `Φ(q, t) = 0`, updated
    /// and scaled as the constraint form says (eqs. 29–30).
    Multiplier,
    /// Algebraic: the unknown of a velocity-level constraint `ψ(q, q̇, t) = 0` (MBDyn's
    /// "differential" constraint equations, e.g. the imposed angular velocity of `axial
    /// rotation`): its equation is never divided by dCoef, and the unknown is an ordinary
    /// algebraic unknown (Jacobian coefficient `c`, updated as `y += c δ`) in both
    /// constraint forms.
    VelocityConstraint,
    /// Differential: a coordinate rather than a multiplier (the abscissa of a beam slider
    /// along its beams): a configuration unknown like a node's, updated as `y += c δ` with
    /// Jacobian coefficient `c`, and set by the initial assembly; its equation is not
    /// divided by dCoef. The element's holonomic rows may depend on it: in the form of
    /// eq. 30 the assembler gives those entries the coefficient of the row's position
    /// entries, so the element writes the plain derivative `Φ_/s`.
    Coordinate,
    /// Differential: a state of the element with its own first-order equation
    /// `ψ(z, ż, q, q̇, λ) = 0` (a LuGre friction model's bristle deflection, MBDyn's
    /// `DofOrder::DIFFERENTIAL` dof of friction.cc): integrated like a node's position
    /// (`ż += δ`, `z += c δ`, Jacobian entries on `ż` ([`Col::Rate`]) with coefficient 1 and
    /// on `z` ([`Col::Multiplier`]) with `c`), its equation not divided by dCoef, and left
    /// out of the initial assembly ([`Element::assembly_form`]). It starts at zero.
    State,
}

/// The events of an element that has them ([`Element::events`]: beams with MBDyn's
/// incremental update, driven elements and joints, bistop laws).
pub trait Events {
    /// Once per step, after the predictor and before Newton (where MBDyn's `AfterPredict`
    /// switches a driven element on, and a bistop law's first `Update` of the step
    /// activates it): `now` is the predicted state at the step's time, `before` the accepted
    /// state of the previous step (what MBDyn's `model::…_prev` functions read); both carry
    /// the data of the element's last event. Returns the data that replace them, `None` to
    /// keep them. Residuals and Jacobians (Newton's and a linearization's) hold the latched
    /// data fixed: they are constants of the state, as MBDyn's element members are.
    fn latch(&self, now: &dyn ElementState, before: &dyn ElementState) -> Option<Latched>;
}

/// The irregularities of an element's residual ([`Element::non_smoothness`]): friction
/// models (joint, hinge and screw friction) and the driven elements that wrap them.
pub trait NonSmooth {
    /// Why its residual is not differentiable at this state, if it is not (a friction state
    /// at zero sliding velocity past its breakaway deflection): a linearization there takes
    /// a one-sided derivative, and an eigenanalysis reports it.
    fn non_smooth(&self, s: &dyn ElementState) -> Option<String>;
    /// Why its residual is not differentiable somewhere between the states `from` and `to`
    /// (a friction coefficient's kink that the sliding speed crosses), if it is not: when
    /// Newton fails with its last iterates on the two sides of such a point, its failure
    /// names it, since Newton's iterates can cycle across a kink instead of converging.
    fn kink_crossed(&self, from: &dyn ElementState, to: &dyn ElementState) -> Option<String>;
    /// Why its Jacobian at this state depends on the values of joint reaction multipliers,
    /// if it does (a friction force proportional to the normal reaction `|λ|`): those are
    /// the integrator's, which steps accepted within the tolerance without a Newton
    /// iteration leave noisy, and an eigenanalysis warns that its eigenvalues carry it.
    fn reaction_dependence(&self, s: &dyn ElementState) -> Option<String>;
}

/// A point of a flexible body: `p = x + R (f₀ + Σₖ Φₖ qₖ)`, `x`, `R` the floating frame
/// (the modal node's, or a fixed frame).
#[derive(Clone, Debug)]
pub struct FlexiblePoint {
    /// `f₀`, the undeformed position in the floating frame [m].
    pub position: Vec3,
    /// `(own unknown of qₖ, Φₖ)`: the point's translation per unit modal coordinate [m].
    pub shapes: Vec<(usize, Vec3)>,
    /// `(own unknown of qₖ, Φrₖ)`: its rotation per unit modal coordinate [rad], in the
    /// floating frame (zero where the FEM file has translations only).
    pub rotation_shapes: Vec<(usize, Vec3)>,
    /// The fixed frame (position [m], orientation) of a clamped body; `None`: the frame is
    /// the element's first node's.
    pub clamped: Option<(Vec3, Mat3)>,
}

/// Energy one of an element's own unknowns stores, for the modal table's shares
/// ([`crate::eigen::ModalEnergy`]): `½ weight |y|²` of the unknown's value (`rate: false`:
/// a motor's magnetic energy `½ L i²` [J], a fluid volume's compression energy `½ (V/β) p²`)
/// or `½ weight |ẏ|²` of its rate (`rate: true`: a flexible body's mode, `½ Mₖₖ q̇ₖ²`).
#[derive(Clone, Debug, PartialEq)]
pub struct EnergyStore {
    /// The own unknown `k`.
    pub unknown: usize,
    /// The coefficient of `½ |y|²` (or `½ |ẏ|²`) in the energy [J per unit squared].
    pub weight: f64,
    pub rate: bool,
    /// What the unknown is, in words: "current", "chamber 1 pressure", "mode 3".
    pub name: String,
    /// The mode's number in a FEM file (a modal joint's modes).
    pub mode: Option<usize>,
}

/// What an element reports beyond its equations ([`Element::outputs`]); each part has a
/// default, so an element states only what it has.
pub trait Outputs {
    /// Its private datum `name` (MBDyn's `iGetPrivDataIdx`/`dGetPrivData`), which the
    /// `element` and `dof` drive callers read, if romdyn computes it (see
    /// [`super::private_data`]).
    fn private_data(&self, _name: &str) -> Option<PrivateDatum> {
        None
    }
    /// Its modal coordinates (a modal body's): `(own unknown k of q, the mode's number in
    /// the FEM file)` each, for MBDyn's `.mod` file ([`crate::dae::modal_coordinates`]).
    fn modal_coordinates(&self) -> Vec<(usize, usize)> {
        Vec::new()
    }
    /// A point of the element's flexible body (a modal joint's FEM node `fem_node`), for
    /// outputs at points (sensors); an error in words when there is none.
    fn flexible_point(&self, _fem_node: &str) -> Result<FlexiblePoint, String> {
        Err("the element has no FEM nodes".into())
    }
    /// The energy its own unknowns store at `s` ([`EnergyStore`]: a motor's current, an
    /// actuator's chamber pressures, a modal joint's modes); none for most elements.
    fn energy_stores(&self, _s: &dyn ElementState) -> Vec<EnergyStore> {
        Vec::new()
    }
    /// Internal forces and deformation at the element's evaluation points (beams), for
    /// output; none for other elements.
    fn sections(&self, _s: &dyn ElementState) -> Vec<SectionState> {
        Vec::new()
    }
    /// Stress resultants at the element's Gauss points, MBDyn's `.pla` row after the label
    /// (shells: the 12 force and moment fluxes n₁₁ … m₂₃ [N/m, N] of each point; membranes:
    /// n₁₁, n₂₂, n₁₂ [N/m] of each point); none for other elements.
    fn plate_resultants(&self, _s: &dyn ElementState) -> Vec<f64> {
        Vec::new()
    }
    /// Its row of MBDyn's `.hyd` file (a hydraulic element's own output: flows, volumes,
    /// densities, … in the columns of its `Output` in MBDyn 1.7.3, SI units) at this state;
    /// read only where [`Outputs::writes_hydraulic_row`] says so.
    fn hydraulic_row(&self, _s: &dyn ElementState) -> Vec<f64> {
        Vec::new()
    }
    /// Whether it writes a `.hyd` row ([`Outputs::hydraulic_row`]) at every output instant.
    fn writes_hydraulic_row(&self) -> bool {
        false
    }
}

/// One element of the model.
pub trait Element: Send + Sync {
    fn label(&self) -> Label;
    /// The element type in MBDyn's words, e.g. "revolute hinge".
    fn type_name(&self) -> &'static str;
    /// What the reader noticed in the element's own input files and let pass (a modal
    /// joint's FEM file: zeros skipped, unequal lumped masses), each with its place.
    fn input_warnings(&self) -> Vec<String> {
        Vec::new()
    }
    /// Labels of the structural nodes it connects, in slot order (none for an element on
    /// scalar nodes only).
    fn nodes(&self) -> Vec<Label> {
        Vec::new()
    }
    /// The scalar nodes it connects (abstract, electric, hydraulic), in slot order
    /// ([`Row::Scalar`], [`Col::ScalarValue`], [`Col::ScalarRate`]); none for most elements.
    fn scalar_nodes(&self) -> Vec<ScalarNodeId> {
        Vec::new()
    }
    /// Names of its own unknowns (Lagrange multipliers), one per constraint equation.
    fn multipliers(&self) -> Vec<String> {
        Vec::new()
    }
    /// What its own unknown `k` is ([`UnknownKind`]): a multiplier of a holonomic
    /// constraint unless the element says otherwise.
    fn unknown_kind(&self, _k: usize) -> UnknownKind {
        UnknownKind::Multiplier
    }
    /// Its own unknowns that are generalized momenta (a modal body's `p = ∂T/∂q̇`), each
    /// with its own equation the definition `p − p(…) = 0` (unit coefficient on `p`): they
    /// are set from their definitions wherever dynamic nodes' momenta are
    /// (`solve::newton::momenta_from_definitions`). None by default.
    fn momentum_unknowns(&self) -> std::ops::Range<usize> {
        0..0
    }
    /// Initial values of its own differential unknowns that do not start at zero: `(k, y,
    /// ẏ)` (a modal body's initial modal coordinates and rates). None by default.
    fn initial_unknowns(&self) -> Vec<(usize, f64, f64)> {
        Vec::new()
    }
    /// Whether a drive of the element reads the model's state (MBDyn's `model::` functions
    /// in a `string` drive): its residual then depends on nodes through the drive, and its
    /// Jacobian, as MBDyn's, holds the drive's value fixed (see
    /// [`crate::element::drive::TimeFunction`]).
    fn reads_state(&self) -> bool {
        false
    }
    /// The element the initial assembly uses in this one's place, when they differ (a joint
    /// with friction: the joint alone, as MBDyn's `InitialAssRes` of a joint with friction
    /// leaves the friction out). Its unknowns must be this element's first ones.
    fn assembly_form(&self) -> Option<&dyn Element> {
        None
    }
    /// What makes its residual or Jacobian less regular than a smooth function of the
    /// state, when something does ([`NonSmooth`]: friction's kinks and its dependence on
    /// reaction values); `None` for most elements.
    fn non_smoothness(&self) -> Option<&dyn NonSmooth> {
        None
    }
    /// Its events, when it has any in this configuration ([`Events`]: data re-set once per
    /// step and held); `None` for most elements.
    fn events(&self) -> Option<&dyn Events> {
        None
    }
    /// The element with a hint's drive in place of its own (MBDyn's `SetValue` with hints,
    /// when a driven element switches on), `None` where the hint does not apply to it.
    fn hinted(&self, _hint: &super::HintValue) -> Option<Box<dyn Element>> {
        None
    }
    /// Whether its constraint rows depend on its own multipliers (a joint regularization:
    /// `Φ − C λ`). Their multiplier entries in `J(c)` then go as `1/c` in the form of eq. 30,
    /// which no pencil `λ F_/ẏ + F_/y` holds: [`crate::dae::linearize`] linearizes such a
    /// model in the form of eq. 29.
    fn constraint_rows_read_multipliers(&self) -> bool {
        false
    }
    /// Why its residual cannot be evaluated at this state, if it cannot (a driven element
    /// whose hints could not be built when it switched on: its residual is NaN there), so
    /// that Newton's failure names the reason instead of a bare "not finite".
    fn failure(&self, _s: &dyn ElementState) -> Option<String> {
        None
    }
    /// Adds its contribution to `F(y, ẏ, t)`.
    fn residual(&self, s: &dyn ElementState, out: &mut dyn ResidualSink);
    /// Adds its derivatives; the assembler forms `J(c)` from them.
    fn jacobian(&self, s: &dyn ElementState, out: &mut dyn JacobianSink);
    /// What it reports beyond its equations, when it reports anything ([`Outputs`]: private
    /// data that drive callers read, a beam's sections); `None` for most elements.
    fn outputs(&self) -> Option<&dyn Outputs> {
        None
    }
}

/// Internal forces and deformation at one evaluation point of a beam, in the section frame.
#[derive(Clone, Debug, PartialEq)]
pub struct SectionState {
    /// Position of the evaluation point [m].
    pub position: Vec3,
    /// Section frame (axis 1 along the beam).
    pub orientation: Mat3,
    /// Axial strain and shear strains [-].
    pub strain: Vec3,
    /// Torsional and bending curvatures [1/m].
    pub curvature: Vec3,
    /// Axial and shear forces [N].
    pub force: Vec3,
    /// Torsional and bending moments [N m].
    pub moment: Vec3,
}
