//! MBDyn's `total equation` with its `total internal reaction`s (totalequation.cc; input
//! manual, "Elements", §Total equation, §Total internal reaction): the constraint
//! equations of a total joint between nodes A and B, whose multipliers act as reactions
//! on other nodes C and D (the force that moves an end effector applied at the actuator
//! that drives it, as in MBDyn's `tests/joints/total/totaleq`).
//!
//! The equation: the active components of `Q_aᵀ (p_b − p_a) − D(t)` and of the relative
//! rotation of `Q_a` and `Q_b exp(Θ(t))ᵀ`, written by romdyn's [`DrivenJoint`] (its
//! rotation rows are the axial vector of the skew part, `sin φ` where MBDyn's
//! `RotManip::VecRot` gives `φ`: the same zero set, the same motion); the equation adds
//! nothing to A's and B's equilibrium. A reaction reads the equation's multipliers in
//! their order (position components, then rotation components, as `TotalReaction::AssRes`
//! reads them) onto its own active components: a force `Q_c λ_p` (`Q_c = R_c H_p`, the
//! `position orientation` of C) at D's point, and a moment `Q_c' λ_r` (`Q_c' = R_c H_r`,
//! the `rotation orientation`), equal and opposite on C. The Jacobian is not symmetric:
//! the constraint rows hold A's and B's columns, the reactions' rows C's and D's.
//!
//! romdyn writes the pair as one element: its nodes are the union of A, B and the
//! reactions' nodes, each part writing through a slot map.

use super::anchor::{node_labels, Anchor, Pair};
use super::contract::{add_block, Col, Element, ElementState, JacobianSink, Label, NodeKinematics, ResidualSink, Row};
use super::DrivenJoint;
use crate::kinematics::{skew, Mat3, Vec3};

/// A `total internal reaction`: where the equation's multipliers act.
#[derive(Clone, Debug)]
pub struct TotalReaction {
    pub label: Label,
    /// Side C with its `position orientation` (the force's frame).
    pub a_position: Anchor,
    /// Side C with its `rotation orientation` (the moment's frame).
    pub a_rotation: Anchor,
    /// Side D (its point is where the force acts).
    pub b: Anchor,
    pub position_active: [bool; 3],
    pub rotation_active: [bool; 3],
}

impl TotalReaction {
    /// Number of multipliers it reads.
    pub fn count(&self) -> usize {
        self.position_active.iter().chain(&self.rotation_active).filter(|&&x| x).count()
    }

    fn nodes(&self) -> Vec<Label> {
        node_labels(&self.a_position, &self.b)
    }

    /// `(λ_p, λ_r)` in C's frames, and for each multiplier `k` its unit `(force, moment)`
    /// directions in the frames' bases (`e_i` on a position or a rotation component).
    fn lambdas(&self, st: &dyn ElementState) -> (Vec3, Vec3, Vec<(bool, usize)>) {
        let (mut p, mut r, mut which) = (Vec3::zeros(), Vec3::zeros(), Vec::new());
        let active = (0..3).filter(|&i| self.position_active[i]).map(|i| (true, i)).chain((0..3).filter(|&i| self.rotation_active[i]).map(|i| (false, i)));
        for (k, (is_pos, i)) in active.enumerate() {
            if is_pos {
                p[i] = st.multiplier(k);
            } else {
                r[i] = st.multiplier(k);
            }
            which.push((is_pos, i));
        }
        (p, r, which)
    }

    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let (lp, lr, _) = self.lambdas(st);
        let pp = Pair::new(&self.a_position, &self.b, st);
        pp.add_force(out, &(pp.q_a * lp));
        let pr = Pair::new(&self.a_rotation, &self.b, st);
        pr.add_moment(out, &(pr.q_a * lr));
    }

    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let (lp, lr, which) = self.lambdas(st);
        let pp = Pair::new(&self.a_position, &self.b, st);
        let pr = Pair::new(&self.a_rotation, &self.b, st);
        // The force Q_c λ_p at D's point: its geometric terms (arms and frame turning).
        pp.add_force_jacobian(out, &(pp.q_a * lp), &[]);
        // The moment m = R_c H_r λ_r turns with C: δm = −[m×] δθ_c, on D's rows (+m) and C's (−m).
        let moment = pr.q_a * lr;
        if let Some(a) = pr.slot_a {
            add_block(out, Row::moment(pr.slot_b), Col::rotation(a), &(-skew(&moment)));
            add_block(out, Row::moment(a), Col::rotation(a), &skew(&moment));
        }
        for (k, (is_pos, i)) in which.into_iter().enumerate() {
            if is_pos {
                pp.add_reaction_column(out, Col::Multiplier(k), &pp.q_a.column(i).into_owned(), &Vec3::zeros());
            } else {
                pr.add_reaction_column(out, Col::Multiplier(k), &Vec3::zeros(), &pr.q_a.column(i).into_owned());
            }
        }
    }
}

/// A `total equation` and the reactions that apply its multipliers.
pub struct TotalEquation {
    equation: DrivenJoint,
    reactions: Vec<TotalReaction>,
    nodes: Vec<Label>,
    /// For the equation and for each reaction: its own slots in the element's slots.
    equation_slots: Vec<usize>,
    reaction_slots: Vec<Vec<usize>>,
}

impl TotalEquation {
    /// The equation (holonomic constraints only: its multipliers are the reactions') and
    /// its reactions, each reading as many multipliers as the equation has.
    pub fn new(equation: DrivenJoint, reactions: Vec<TotalReaction>) -> Self {
        let mut nodes: Vec<Label> = Vec::new();
        let mut slots_of = |labels: Vec<Label>| -> Vec<usize> {
            labels
                .into_iter()
                .map(|l| match nodes.iter().position(|&n| n == l) {
                    Some(i) => i,
                    None => {
                        nodes.push(l);
                        nodes.len() - 1
                    }
                })
                .collect()
        };
        let equation_slots = slots_of(equation.nodes());
        let reaction_slots = reactions.iter().map(|r| slots_of(r.nodes())).collect();
        TotalEquation { equation, reactions, nodes, equation_slots, reaction_slots }
    }
}

/// An element state seen through a slot map: slot `k` of a part is slot `slots[k]`.
struct Slotted<'a> {
    st: &'a dyn ElementState,
    slots: &'a [usize],
}

impl ElementState for Slotted<'_> {
    fn node(&self, slot: usize) -> &NodeKinematics {
        self.st.node(self.slots[slot])
    }
    fn multiplier(&self, k: usize) -> f64 {
        self.st.multiplier(k)
    }
    fn rate(&self, k: usize) -> f64 {
        self.st.rate(k)
    }
    fn time(&self) -> f64 {
        self.st.time()
    }
    fn gravity(&self) -> Vec3 {
        self.st.gravity()
    }
    fn load_factor(&self) -> f64 {
        self.st.load_factor()
    }
    fn constraint_row_scale(&self) -> f64 {
        self.st.constraint_row_scale()
    }
    fn structural_node(&self, label: Label) -> Option<&NodeKinematics> {
        self.st.structural_node(label)
    }
    fn element_unknown(&self, type_name: &str, label: Label, k: usize) -> Option<(f64, f64)> {
        self.st.element_unknown(type_name, label, k)
    }
    fn scalar_node(&self, id: crate::element::ScalarNodeId) -> Option<(f64, f64)> {
        self.st.scalar_node(id)
    }
}

fn map_row(slots: &[usize], row: Row) -> Row {
    match row {
        Row::Equilibrium { slot, comp } => Row::Equilibrium { slot: slots[slot], comp },
        Row::Momentum { slot, comp } => Row::Momentum { slot: slots[slot], comp },
        Row::Constraint(k) => Row::Constraint(k),
        // A total joint's parts connect structural nodes only.
        r @ Row::Scalar { .. } => r,
    }
}

fn map_col(slots: &[usize], col: Col) -> Col {
    match col {
        Col::Position { slot, comp } => Col::Position { slot: slots[slot], comp },
        Col::Rotation { slot, comp } => Col::Rotation { slot: slots[slot], comp },
        Col::Velocity { slot, comp } => Col::Velocity { slot: slots[slot], comp },
        Col::AngularVelocity { slot, comp } => Col::AngularVelocity { slot: slots[slot], comp },
        c => c,
    }
}

/// Sinks that map a part's slots and keep the constraint rows only, or the others only.
struct ResidualRows<'a> {
    out: &'a mut dyn ResidualSink,
    slots: &'a [usize],
    constraints: bool,
}

struct JacobianRows<'a> {
    out: &'a mut dyn JacobianSink,
    slots: &'a [usize],
    constraints: bool,
}

fn keeps(constraints: bool, row: Row) -> bool {
    matches!(row, Row::Constraint(_)) == constraints
}

impl ResidualSink for ResidualRows<'_> {
    fn add(&mut self, row: Row, value: f64) {
        if keeps(self.constraints, row) {
            self.out.add(map_row(self.slots, row), value);
        }
    }
}

impl JacobianSink for JacobianRows<'_> {
    fn add(&mut self, row: Row, col: Col, value: f64) {
        if keeps(self.constraints, row) {
            self.out.add(map_row(self.slots, row), map_col(self.slots, col), value);
        }
    }
    fn add_block(&mut self, rows: [Row; 3], cols: [Col; 3], m: &Mat3) {
        if rows.iter().all(|&r| keeps(self.constraints, r)) {
            self.out.add_block(rows.map(|r| map_row(self.slots, r)), cols.map(|c| map_col(self.slots, c)), m);
        } else {
            for (i, row) in rows.into_iter().enumerate() {
                for (j, col) in cols.into_iter().enumerate() {
                    self.add(row, col, m[(i, j)]);
                }
            }
        }
    }
}

impl Element for TotalEquation {
    fn label(&self) -> Label {
        self.equation.label()
    }
    fn type_name(&self) -> &'static str {
        "total equation"
    }
    fn nodes(&self) -> Vec<Label> {
        self.nodes.clone()
    }
    fn multipliers(&self) -> Vec<String> {
        self.equation.multipliers()
    }
    fn reads_state(&self) -> bool {
        self.equation.reads_state()
    }
    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let s = Slotted { st, slots: &self.equation_slots };
        self.equation.residual(&s, &mut ResidualRows { out: &mut *out, slots: &self.equation_slots, constraints: true });
        for (r, slots) in self.reactions.iter().zip(&self.reaction_slots) {
            r.residual(&Slotted { st, slots }, &mut ResidualRows { out: &mut *out, slots, constraints: false });
        }
    }
    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let s = Slotted { st, slots: &self.equation_slots };
        self.equation.jacobian(&s, &mut JacobianRows { out: &mut *out, slots: &self.equation_slots, constraints: true });
        for (r, slots) in self.reactions.iter().zip(&self.reaction_slots) {
            r.jacobian(&Slotted { st, slots }, &mut JacobianRows { out: &mut *out, slots, constraints: false });
        }
    }
}
