//! MBDyn's `beam slider` (input manual, §Beam slider; beamslider.cc, `BeamSliderJoint`): a
//! point of a node slides without friction along the reference line of a chain of
//! three-node beams.
//!
//! The chain is parametrized by one abscissa `S` (beam `k` covers `S ∈ [2k − 1, 2k + 1]`,
//! its local `s = S − 2k` is the beams' `ξ`), the line by each beam's interpolated offset
//! points `p_j = x_j + R_j o_j`: `x(s) = Σ N_j(s) p_j`, tangent `l = Σ N_j′ p_j`. The
//! slider's point is `x_c = x_b + R_b f`, its frame `R_b R` with axes `e₁ e₂ e₃`. Unknowns:
//! the abscissa (a coordinate, [`UnknownKind::Coordinate`]), the force `F` on the slider and,
//! for `classic`, the moments `m₂ m₃`. Equations, as beamslider.cc:
//!
//! ```text
//! l · F = 0              no force along the line (frictionless)
//! x_c − x(s) = 0         the point on the line
//! e₂ · l = e₃ · l = 0    classic: the slider's axis 1 along the line
//! ```
//!
//! Reactions: `F` and `M + (R_b f) × F` on the slider node, `M = (e₂ m₂ + e₃ m₃) × l`; their
//! opposites, about each beam node, on the node whose finite volume holds `s` (node 1 for
//! `s < −1/√3`, node 2 up to `1/√3`, node 3 beyond), shared linearly between two nodes
//! within `±smearing` of the volume boundary (MBDyn's `dW`). MBDyn keeps the current beam
//! as element state, moved by one beam when `s` leaves `[−1, 1]`; romdyn takes the beam
//! whose interval holds `S` (clamped to the chain), the same except when one Newton
//! iteration crosses more than one beam.
//!
//! The stored unknown is `S − S₀`, `S₀` the abscissa of the line's point nearest the
//! slider as written ([`BeamSlider::nearest_abscissa`], from `initial beam` and `initial
//! node` on), where MBDyn's derivatives phase, which solves for its algebraic abscissa,
//! puts it. MBDyn's beam slider takes no part in its initial assembly (empty
//! `InitialAssRes`): nor does romdyn's when the slider is written on the line
//! ([`BeamSlider::start_rate`]), so that velocities written inconsistent with it reach the
//! first step as MBDyn's do; written off the line (where MBDyn's derivatives phase fails),
//! romdyn's assembly moves it onto the line.
//!
//! The contract has no element history, so the current beam is a function of the state, and
//! the abscissa is a coordinate ([`UnknownKind::Coordinate`]), not a multiplier: in the form
//! of eq. 30 an algebraic abscissa (MBDyn's) would enter the scaled constraint rows as
//! `Φ_/s / c`, which no pair `F_/ẏ`, `F_/y` expresses, so the linearization needs it as a
//! configuration unknown. Its equation, `l · F = 0`, is not divided by dCoef (MBDyn's is):
//! the converged solutions are the same.

use super::beam::shape;
use super::contract::{Col, Element, ElementState, JacobianSink, Label, NodeKinematics, ResidualSink, Row};
use crate::kinematics::{skew, Mat3, Vec3};
use super::UnknownKind;

/// Which rotation the slider constrains.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SliderKind {
    /// Free rotation.
    Spherical,
    /// Rotation only about the line: the slider's axis 1 along the tangent.
    Classic,
}

/// One beam of the chain: its three nodes and the line's offsets from them (node frames).
#[derive(Clone, Debug)]
pub struct SliderBeam {
    pub nodes: [Label; 3],
    pub offsets: [Vec3; 3],
}

/// A beam slider: `node`'s point `offset` (frame `orientation`, both in the node frame)
/// on the line of `beams`.
#[derive(Clone, Debug)]
pub struct BeamSlider {
    pub label: Label,
    pub node: Label,
    pub offset: Vec3,
    pub orientation: Mat3,
    pub kind: SliderKind,
    pub beams: Vec<SliderBeam>,
    /// Initial abscissa `S₀ = 2 (initial beam − 1) + initial node − 2`.
    pub initial: f64,
    /// Half-width of the zone where the reaction passes from one beam node to the next.
    pub smearing: f64,
    /// `Some(Ṡ₀)` for a slider written on the line: as MBDyn's, it takes no part in the
    /// initial assembly (whose velocities then need not satisfy it), and its abscissa starts
    /// moving at `Ṡ₀`, the written velocities' rate along the line ([`BeamSlider::start`]).
    /// `None`: the initial assembly moves the slider onto the line and its velocity along it
    /// (where MBDyn's derivatives phase fails).
    pub start_rate: Option<f64>,
}

/// `s` of the finite-volume boundaries, `1/√3`.
const BOUNDARY: f64 = 0.577_350_269_189_625_8;

/// Everything the residual and Jacobian read, at one state.
struct Geometry {
    /// Slots of the current beam's three nodes.
    slots: [usize; 3],
    n: [f64; 3],
    np: [f64; 3],
    x_nodes: [Vec3; 3],
    /// `R_j o_j`.
    f: [Vec3; 3],
    x: Vec3,
    l: Vec3,
    /// `∂l/∂s`.
    lp: Vec3,
    fb: Vec3,
    xc: Vec3,
    e2: Vec3,
    e3: Vec3,
    force: Vec3,
    /// `e₂ m₂ + e₃ m₃` (zero for a spherical slider).
    mm: Vec3,
    /// Reaction sharing: (local node, weight, ∂weight/∂s).
    weights: Vec<(usize, f64, f64)>,
}

impl BeamSlider {
    fn rotations(&self) -> usize {
        match self.kind {
            SliderKind::Spherical => 0,
            SliderKind::Classic => 2,
        }
    }

    /// The current beam and its local `s` for the abscissa `S`.
    fn beam_at(&self, abscissa: f64) -> (usize, f64) {
        let last = self.beams.len() - 1;
        let k = ((abscissa + 1.0) / 2.0).floor().clamp(0.0, last as f64) as usize;
        (k, abscissa - 2.0 * k as f64)
    }

    /// MBDyn's `dW`: which node (or two) of the beam carries the reaction at `s`.
    fn weights(&self, s: f64) -> Vec<(usize, f64, f64)> {
        let d_l = self.smearing;
        if s < -BOUNDARY - d_l {
            vec![(0, 1.0, 0.0)]
        } else if s < -BOUNDARY + d_l {
            let d = 0.5 * (BOUNDARY + s) / d_l;
            vec![(0, 0.5 - d, -0.5 / d_l), (1, 0.5 + d, 0.5 / d_l)]
        } else if s > BOUNDARY + d_l {
            vec![(2, 1.0, 0.0)]
        } else if s > BOUNDARY - d_l {
            let d = 0.5 * (BOUNDARY - s) / d_l;
            vec![(1, 0.5 + d, -0.5 / d_l), (2, 0.5 - d, 0.5 / d_l)]
        } else {
            vec![(1, 1.0, 0.0)]
        }
    }

    fn geometry(&self, st: &dyn ElementState) -> Geometry {
        let (k, s) = self.beam_at(self.initial + st.multiplier(0));
        let beam = &self.beams[k];
        let slots = [1 + 2 * k, 2 + 2 * k, 3 + 2 * k];
        let (n, np) = (shape::values(s), shape::derivatives(s));
        let npp = [1.0, -2.0, 1.0];
        let (mut x_nodes, mut f) = ([Vec3::zeros(); 3], [Vec3::zeros(); 3]);
        let (mut x, mut l, mut lp) = (Vec3::zeros(), Vec3::zeros(), Vec3::zeros());
        for j in 0..3 {
            let node = st.node(slots[j]);
            x_nodes[j] = node.x;
            f[j] = node.r * beam.offsets[j];
            let p = node.x + f[j];
            x += n[j] * p;
            l += np[j] * p;
            lp += npp[j] * p;
        }
        let b = st.node(0);
        let fb = b.r * self.offset;
        let frame = b.r * self.orientation;
        let (e2, e3) = (frame.column(1).into_owned(), frame.column(2).into_owned());
        let force = Vec3::new(st.multiplier(1), st.multiplier(2), st.multiplier(3));
        let mm = match self.kind {
            SliderKind::Spherical => Vec3::zeros(),
            SliderKind::Classic => e2 * st.multiplier(4) + e3 * st.multiplier(5),
        };
        Geometry { slots, n, np, x_nodes, f, x, l, lp, fb, xc: b.x + fb, e2, e3, force, mm, weights: self.weights(s) }
    }
}

/// The nodes' kinematics as a slider sees them, with a trial abscissa.
struct Trial<'a> {
    kin: &'a [NodeKinematics],
    sigma: f64,
}

impl ElementState for Trial<'_> {
    fn node(&self, slot: usize) -> &NodeKinematics {
        &self.kin[slot]
    }
    fn multiplier(&self, k: usize) -> f64 {
        if k == 0 { self.sigma } else { 0.0 }
    }
    fn time(&self) -> f64 {
        0.0
    }
    fn gravity(&self) -> Vec3 {
        Vec3::zeros()
    }
    fn load_factor(&self) -> f64 {
        1.0
    }
}

impl BeamSlider {
    /// The abscissa of the line's point nearest the slider's, by Newton on `l · (x_c −
    /// x(S)) = 0` from `initial` (moving from beam to beam), with the nodes at `kin` (in slot
    /// order): where MBDyn's derivatives phase, which solves for the abscissa with the
    /// positions held, takes a slider that starts on the line but not at its initial
    /// node. `None` when Newton does not converge in 50 iterations.
    pub fn nearest_abscissa(&self, kin: &[NodeKinematics]) -> Option<f64> {
        self.nearest(kin).map(|(abscissa, _)| abscissa)
    }

    /// The slider as written at `kin` (the nodes' kinematics in slot order): the nearest
    /// abscissa `S₀`, and, when the slider's point is on the line there (within 1e-9 of the
    /// line's length per unit abscissa), the rate `Ṡ₀ = l · (v_c − ẋ(S₀))/(l · l)` of the
    /// written velocities along it (`v_c` the slider point's velocity, `ẋ(S₀)` the line
    /// point's, `l = ∂x/∂S`).
    pub fn start(&self, kin: &[NodeKinematics]) -> Option<(f64, Option<f64>)> {
        let (abscissa, sigma) = self.nearest(kin)?;
        let g = self.geometry(&Trial { kin, sigma });
        if (g.xc - g.x).norm() > 1e-9 * g.l.norm().max(f64::MIN_POSITIVE) {
            return Some((abscissa, None));
        }
        let b = &kin[0];
        let vc = b.xdot + b.omega.cross(&g.fb);
        let vx: Vec3 = (0..3).map(|j| g.n[j] * (kin[g.slots[j]].xdot + kin[g.slots[j]].omega.cross(&g.f[j]))).sum();
        Some((abscissa, Some(g.l.dot(&(vc - vx)) / g.l.dot(&g.l))))
    }

    /// `(S, S − initial)` of the nearest point.
    fn nearest(&self, kin: &[NodeKinematics]) -> Option<(f64, f64)> {
        let mut sigma = 0.0;
        for _ in 0..50 {
            let g = self.geometry(&Trial { kin, sigma });
            let gap = g.xc - g.x;
            let (value, slope) = (g.l.dot(&gap), g.lp.dot(&gap) - g.l.dot(&g.l));
            if !(slope.abs() > 0.0) {
                return None;
            }
            let step = -value / slope;
            sigma += step;
            if step.abs() <= 1e-14 * (1.0 + (self.initial + sigma).abs()) {
                return Some((self.initial + sigma, sigma));
            }
        }
        None
    }
}

/// A linear map from the element's perturbations to a 3-vector: node blocks and single
/// columns.
#[derive(Default)]
struct Lin {
    blocks: Vec<([Col; 3], Mat3)>,
    cols: Vec<(Col, Vec3)>,
}

impl Lin {
    fn block(mut self, cols: [Col; 3], m: Mat3) -> Self {
        self.blocks.push((cols, m));
        self
    }
    fn col(mut self, col: Col, v: Vec3) -> Self {
        self.cols.push((col, v));
        self
    }
    /// `m δ`.
    fn times(&self, m: &Mat3) -> Lin {
        Lin { blocks: self.blocks.iter().map(|(c, b)| (*c, m * b)).collect(), cols: self.cols.iter().map(|(c, v)| (*c, m * v)).collect() }
    }
    fn plus(mut self, other: Lin) -> Lin {
        self.blocks.extend(other.blocks);
        self.cols.extend(other.cols);
        self
    }
    /// Adds `δ` to three rows.
    fn write(&self, out: &mut dyn JacobianSink, rows: [Row; 3]) {
        for (cols, m) in &self.blocks {
            out.add_block(rows, *cols, m);
        }
        for (col, v) in &self.cols {
            for (i, row) in rows.into_iter().enumerate() {
                out.add(row, *col, v[i]);
            }
        }
    }
    /// Adds `vᵀ δ` to one row.
    fn write_dot(&self, out: &mut dyn JacobianSink, row: Row, v: &Vec3) {
        for (cols, m) in &self.blocks {
            let r = v.transpose() * m;
            for j in 0..3 {
                out.add(row, cols[j], r[j]);
            }
        }
        for (col, w) in &self.cols {
            out.add(row, *col, v.dot(w));
        }
    }
}

const ABSCISSA: Col = Col::Multiplier(0);

fn force_cols() -> [Col; 3] {
    [1, 2, 3].map(Col::Multiplier)
}

impl Geometry {
    /// `δ(Σ w_j p_j)` of the beam's points at fixed `s`, for the given weights.
    fn points(&self, w: &[f64; 3]) -> Lin {
        let mut lin = Lin::default();
        for j in 0..3 {
            lin = lin.block(Col::position(self.slots[j]), w[j] * Mat3::identity()).block(Col::rotation(self.slots[j]), -w[j] * skew(&self.f[j]));
        }
        lin
    }
    fn d_x(&self) -> Lin {
        self.points(&self.n).col(ABSCISSA, self.l)
    }
    fn d_l(&self) -> Lin {
        self.points(&self.np).col(ABSCISSA, self.lp)
    }
    fn d_xc(&self) -> Lin {
        Lin::default().block(Col::position(0), Mat3::identity()).block(Col::rotation(0), -skew(&self.fb))
    }
    fn d_force(&self) -> Lin {
        Lin::default().block(force_cols(), Mat3::identity())
    }
    /// `δM`, `M = mm × l`, `δmm = e₂ δm₂ + e₃ δm₃ − [mm×] δθ_b`.
    fn d_moment(&self, classic: bool) -> Lin {
        if !classic {
            return Lin::default();
        }
        let lx = skew(&self.l);
        let d_mm = Lin::default().block(Col::rotation(0), -skew(&self.mm)).col(Col::Multiplier(4), self.e2).col(Col::Multiplier(5), self.e3);
        d_mm.times(&(-lx)).plus(self.d_l().times(&skew(&self.mm)))
    }
}

/// What the initial assembly sees of a beam slider written on the line: nothing.
struct NotAssembled;

static NOT_ASSEMBLED: NotAssembled = NotAssembled;

impl Element for NotAssembled {
    fn label(&self) -> Label {
        0
    }
    fn type_name(&self) -> &'static str {
        "beam slider"
    }
    fn residual(&self, _st: &dyn ElementState, _out: &mut dyn ResidualSink) {}
    fn jacobian(&self, _st: &dyn ElementState, _out: &mut dyn JacobianSink) {}
}

impl Element for BeamSlider {
    fn label(&self) -> Label {
        self.label
    }
    fn type_name(&self) -> &'static str {
        "beam slider"
    }
    fn nodes(&self) -> Vec<Label> {
        let mut v = vec![self.node];
        for (k, b) in self.beams.iter().enumerate() {
            v.extend_from_slice(if k == 0 { &b.nodes[..] } else { &b.nodes[1..] });
        }
        v
    }
    fn multipliers(&self) -> Vec<String> {
        let mut v: Vec<String> = ["s", "f x", "f y", "f z"].map(String::from).to_vec();
        v.extend(["m 2", "m 3"].iter().take(self.rotations()).map(|s| s.to_string()));
        v
    }
    fn unknown_kind(&self, k: usize) -> UnknownKind {
        if k == 0 { UnknownKind::Coordinate } else { UnknownKind::Multiplier }
    }
    fn initial_unknowns(&self) -> Vec<(usize, f64, f64)> {
        self.start_rate.map(|rate| vec![(0, 0.0, rate)]).unwrap_or_default()
    }
    /// Nothing, for a slider written on the line: MBDyn 1.7.3's beam slider takes no part
    /// in its initial assembly (empty `InitialAssRes`, `InitialAssJac`), so the velocities
    /// the assembly sets need not satisfy it and the first step changes them.
    fn assembly_form(&self) -> Option<&dyn Element> {
        self.start_rate.map(|_| &NOT_ASSEMBLED as &dyn Element)
    }

    fn residual(&self, st: &dyn ElementState, out: &mut dyn ResidualSink) {
        let g = self.geometry(st);
        out.add(Row::Constraint(0), g.l.dot(&g.force));
        let c = g.xc - g.x;
        for i in 0..3 {
            out.add(Row::Constraint(1 + i), c[i]);
        }
        if self.kind == SliderKind::Classic {
            out.add(Row::Constraint(4), g.e2.dot(&g.l));
            out.add(Row::Constraint(5), g.e3.dot(&g.l));
        }
        let moment = g.mm.cross(&g.l);
        let on_slider = moment + g.fb.cross(&g.force);
        for i in 0..3 {
            out.add(Row::Equilibrium { slot: 0, comp: i }, -g.force[i]);
            out.add(Row::Equilibrium { slot: 0, comp: 3 + i }, -on_slider[i]);
        }
        for &(j, w, _) in &g.weights {
            let m = moment + (g.xc - g.x_nodes[j]).cross(&g.force);
            for i in 0..3 {
                out.add(Row::Equilibrium { slot: g.slots[j], comp: i }, w * g.force[i]);
                out.add(Row::Equilibrium { slot: g.slots[j], comp: 3 + i }, w * m[i]);
            }
        }
    }

    fn jacobian(&self, st: &dyn ElementState, out: &mut dyn JacobianSink) {
        let g = self.geometry(st);
        let classic = self.kind == SliderKind::Classic;
        let (d_l, d_force, d_xc) = (g.d_l(), g.d_force(), g.d_xc());
        // l · F = 0.
        d_l.write_dot(out, Row::Constraint(0), &g.force);
        d_force.write_dot(out, Row::Constraint(0), &g.l);
        // x_c − x(s) = 0.
        g.d_xc().plus(g.d_x().times(&-Mat3::identity())).write(out, [1, 2, 3].map(Row::Constraint));
        if classic {
            // δ(e · l) = (e × l) · δθ_b + e · δl.
            for (row, e) in [(4, g.e2), (5, g.e3)] {
                d_l.write_dot(out, Row::Constraint(row), &e);
                let el = e.cross(&g.l);
                for i in 0..3 {
                    out.add(Row::Constraint(row), Col::Rotation { slot: 0, comp: i }, el[i]);
                }
            }
        }
        // The slider: −F, −(M + f_b × F).
        let d_moment = g.d_moment(classic);
        let fx = skew(&g.force);
        d_force.times(&-Mat3::identity()).write(out, Row::force(0));
        let d_fb_cross_f = Lin::default().block(Col::rotation(0), fx * skew(&g.fb)).plus(d_force.times(&skew(&g.fb)));
        d_moment.times(&-Mat3::identity()).plus(d_fb_cross_f.times(&-Mat3::identity())).write(out, Row::moment(0));
        // The beam nodes: w F, w (M + (x_c − x_j) × F), w depending on s.
        let moment = g.mm.cross(&g.l);
        for &(j, w, dw) in &g.weights {
            let slot = g.slots[j];
            let arm = g.xc - g.x_nodes[j];
            let mut d_f = d_force.times(&(w * Mat3::identity()));
            if dw != 0.0 {
                d_f = d_f.col(ABSCISSA, dw * g.force);
            }
            d_f.write(out, Row::force(slot));
            let d_arm = Lin { blocks: d_xc.blocks.clone(), cols: Vec::new() }.block(Col::position(slot), -Mat3::identity());
            let mut d_m = d_moment.times(&(w * Mat3::identity())).plus(d_arm.times(&(-w * fx))).plus(d_force.times(&(w * skew(&arm))));
            if dw != 0.0 {
                d_m = d_m.col(ABSCISSA, dw * (moment + arm.cross(&g.force)));
            }
            d_m.write(out, Row::moment(slot));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn abscissa_picks_the_beam_and_its_finite_volume() {
        let beam = SliderBeam { nodes: [1, 2, 3], offsets: [Vec3::zeros(); 3] };
        let slider = BeamSlider { label: 1, node: 9, offset: Vec3::zeros(), orientation: Mat3::identity(), kind: SliderKind::Spherical, beams: vec![beam.clone(), SliderBeam { nodes: [3, 4, 5], ..beam }], initial: -1.0, smearing: 0.1, start_rate: None };
        assert_eq!(slider.beam_at(-1.5), (0, -1.5));
        assert_eq!(slider.beam_at(0.9), (0, 0.9));
        assert_eq!(slider.beam_at(1.5), (1, -0.5));
        assert_eq!(slider.beam_at(3.5), (1, 1.5));
        assert_eq!(slider.nodes(), vec![9, 1, 2, 3, 4, 5]);
        // Smearing: at the boundary the reaction is shared half and half; the weights are
        // continuous at the zone's ends.
        let w = slider.weights(-BOUNDARY);
        assert!((w[0].1 - 0.5).abs() < 1e-15 && (w[1].1 - 0.5).abs() < 1e-15);
        let inside = slider.weights(BOUNDARY - 0.1 + 1e-12);
        assert!((inside[0].1 - 1.0).abs() < 1e-10 && inside[1].1.abs() < 1e-10);
    }
}
