//! Assembly of the residual `F(y, ẏ, t)` and of `a F_/ẏ + b F_/y` from the nodes and the
//! elements' contributions (`a = 1, b = c` gives `J(c)`, eq. 5).

use super::jacobian_sink::{global_row, Entries, Jacobian, Shape, Values};
use super::prefetch;
use super::state::NodeFrame;
use super::{DofMap, State, Triplets};
use crate::element::{ElementState, NodeKinematics, ResidualSink, Row, SectionState};
use crate::kinematics::{skew, Vec3};
use crate::model::ConstraintForm;
use crate::model::{Model, NodeKind};

/// Which combination of the two Jacobians to assemble: `a F_/ẏ + b F_/y`, in a given
/// constraint form. `dcoef` scales the constraint rows of the form of eq. 30 (`Φ/c`).
#[derive(Clone, Copy, Debug)]
pub struct Coefficients {
    pub a: f64,
    pub b: f64,
    pub form: ConstraintForm,
    pub dcoef: f64,
}

impl Coefficients {
    /// `J(c) = F_/ẏ + c F_/y` (Newton in time integration).
    pub fn newton(dcoef: f64, form: ConstraintForm) -> Self {
        Coefficients { a: 1.0, b: dcoef, form, dcoef }
    }
    /// `F_/y` in the plain form (static analysis).
    pub fn static_analysis() -> Self {
        Coefficients { a: 0.0, b: 1.0, form: ConstraintForm::Plain, dcoef: 1.0 }
    }
}

/// The node frames of one state ([`Assembler::frames_into`]), kept by a Newton iteration
/// for its residual and its Jacobian.
#[derive(Clone, Debug, Default)]
pub struct Frames(Vec<NodeFrame>);

impl std::ops::Deref for Frames {
    type Target = [NodeFrame];
    fn deref(&self) -> &[NodeFrame] {
        &self.0
    }
}

/// Assembles a model's DAE. Borrows the model; owns only its numbering.
pub struct Assembler<'m> {
    pub model: &'m Model,
    pub dofs: DofMap,
}

/// What one element reads; its nodes are looked up through its slots (no allocation).
struct Context<'a> {
    model: &'a Model,
    frames: &'a [NodeFrame],
    /// The frames drives reading the model's state see (`frames` but in a
    /// finite-difference check of the Jacobian, which holds those drives fixed).
    read_frames: &'a [NodeFrame],
    slots: &'a [usize],
    /// Scalar node index of each of the element's scalar slots.
    scalar_slots: &'a [usize],
    /// The whole state's `y`, `ẏ` (scalar nodes' values and derivatives).
    y: &'a [f64],
    yp: &'a [f64],
    /// The unknown of the first scalar node.
    scalar_first: usize,
    /// The first own unknown of every element ([`DofMap::element_first`]).
    element_first: &'a [usize],
    multipliers: &'a [f64],
    /// Time derivatives of the element's own unknowns.
    rates: &'a [f64],
    t: f64,
    load: f64,
    gravity: Vec3,
    constraint_scale: f64,
    latched: Option<&'a (dyn std::any::Any + Send + Sync)>,
}

impl ElementState for Context<'_> {
    fn node(&self, slot: usize) -> &NodeKinematics {
        &self.frames[self.slots[slot]].kin
    }
    fn multiplier(&self, k: usize) -> f64 {
        self.multipliers[k]
    }
    fn rate(&self, k: usize) -> f64 {
        self.rates[k]
    }
    fn time(&self) -> f64 {
        self.t
    }
    fn scalar_value(&self, slot: usize) -> f64 {
        self.y[self.scalar_first + self.scalar_slots[slot]]
    }
    fn scalar_rate(&self, slot: usize) -> f64 {
        self.yp[self.scalar_first + self.scalar_slots[slot]]
    }
    fn scalar_node(&self, id: crate::element::ScalarNodeId) -> Option<(f64, f64)> {
        self.model.scalar_index(id).map(|i| (self.y[self.scalar_first + i], self.yp[self.scalar_first + i]))
    }
    fn gravity(&self) -> Vec3 {
        self.gravity * self.load
    }
    fn load_factor(&self) -> f64 {
        self.load
    }
    fn constraint_row_scale(&self) -> f64 {
        self.constraint_scale
    }
    fn structural_node(&self, label: crate::element::Label) -> Option<&NodeKinematics> {
        self.model.node_index(label).map(|i| &self.read_frames[i].kin)
    }
    fn element_unknown(&self, type_name: &str, label: crate::element::Label, k: usize) -> Option<(f64, f64)> {
        let e = self.model.elements.iter().position(|e| e.type_name() == type_name && e.label() == label)?;
        // The elements' unknowns follow each other to the end of `y`: the element's own end
        // is the next one's start (an initial assembly's twin has fewer unknowns).
        let end = self.element_first.get(e + 1).copied().unwrap_or(self.y.len());
        let i = self.element_first.get(e)? + k;
        (i < end).then(|| (self.y[i], self.yp[i]))
    }
    fn latched(&self) -> Option<&(dyn std::any::Any + Send + Sync)> {
        self.latched
    }
}

/// Maps an element's residual rows to equations and hands `(equation, value)` to `put`.
struct Residual<'a, P: FnMut(usize, f64)> {
    dofs: &'a DofMap,
    element: usize,
    slots: &'a [usize],
    first: usize,
    constraint_scale: f64,
    put: P,
}

impl<P: FnMut(usize, f64)> ResidualSink for Residual<'_, P> {
    fn add(&mut self, row: Row, value: f64) {
        let scale = match row {
            Row::Constraint(k) if self.dofs.is_multiplier(self.first + k) => self.constraint_scale,
            _ => 1.0,
        };
        if let Some(i) = global_row(self.dofs, self.element, self.slots, self.first, row) {
            (self.put)(i, value * scale);
        }
    }
}

impl<'m> Assembler<'m> {
    pub fn new(model: &'m Model) -> Self {
        Assembler { model, dofs: DofMap::new(model) }
    }

    pub(crate) fn frames(&self, st: &State) -> Vec<NodeFrame> {
        (0..self.model.nodes.len()).map(|i| st.node_frame(&self.dofs, i)).collect()
    }

    /// Asks the caches for element `e`'s data ahead of its evaluation, when there is such
    /// an element ([`prefetch`]).
    #[inline(always)]
    fn prefetch(&self, st: &State, e: usize) {
        if let Some(el) = self.model.elements.get(e) {
            let slots = self.dofs.element_nodes.get(e).map_or(&[][..], Vec::as_slice);
            prefetch::element(el.as_ref(), slots, st.latched.get(e).and_then(Option::as_ref));
        }
    }

    fn context<'a>(&'a self, frames: &'a [NodeFrame], st: &'a State, e: usize, constraint_scale: f64) -> Context<'a> {
        let first = self.dofs.element_first[e];
        Context {
            model: self.model,
            frames,
            read_frames: frames,
            slots: &self.dofs.element_nodes[e],
            scalar_slots: &self.dofs.element_scalars[e],
            y: &st.y,
            yp: &st.yp,
            scalar_first: self.dofs.scalar_first,
            element_first: &self.dofs.element_first,
            multipliers: &st.y[first..first + self.dofs.element_len[e]],
            rates: &st.yp[first..first + self.dofs.element_len[e]],
            t: st.t,
            load: st.load,
            gravity: self.model.gravity,
            constraint_scale,
            latched: st.latched.get(e).and_then(|l| l.as_deref()),
        }
    }

    /// Whether an element of the model has events ([`crate::element::Element::latch`]).
    pub fn has_events(&self) -> bool {
        self.model.elements.iter().any(|e| e.events().is_some())
    }

    /// The elements' events of a step: each element with events latches its data from
    /// `now` (the predicted state at the step's time) and `before` (the accepted state of
    /// the previous step) into `now`.
    pub fn latch_events(&self, now: &mut State, before: &State) {
        let (frames, before_frames) = (self.frames(now), self.frames(before));
        let mut changed = Vec::new();
        for (e, events) in self.model.elements.iter().enumerate().filter_map(|(e, el)| Some((e, el.events()?))) {
            let ctx = self.context(&frames, now, e, 1.0);
            let prev = self.context(&before_frames, before, e, 1.0);
            if let Some(l) = events.latch(&ctx, &prev) {
                changed.push((e, l));
            }
        }
        for (e, l) in changed {
            now.latched[e] = Some(l);
        }
    }

    /// Advances the memory of the model's step drives ([`crate::element::drive::StepDrive`]) at
    /// the start of step `step` (1 for the first), whose time is `t_new`, from the accepted
    /// state `st` (MBDyn's `DriveHandler::SetTime` with a new step number). The drives read
    /// the model's nodes as in a residual; node slot `i` is the model's node `i`.
    pub fn begin_step(&self, st: &State, step: usize, t_new: f64) {
        if self.model.step_drives.is_empty() {
            return;
        }
        self.with_all_nodes(st, st.t, |ctx| {
            for d in &self.model.step_drives {
                d.begin_step(step, t_new, ctx);
            }
        });
    }

    /// `f` of a state that reads every node of the model at `st` at time `t` (node slot `i`
    /// is the model's node `i`): what a drive outside every element reads.
    fn with_all_nodes<R>(&self, st: &State, t: f64, f: impl FnOnce(&Context) -> R) -> R {
        let frames = self.frames(st);
        let slots: Vec<usize> = (0..frames.len()).collect();
        f(&Context { model: self.model, frames: &frames, read_frames: &frames, slots: &slots, scalar_slots: &[], y: &st.y, yp: &st.yp, scalar_first: self.dofs.scalar_first, element_first: &self.dofs.element_first, multipliers: &[], rates: &[], t, load: st.load, gravity: self.model.gravity, constraint_scale: 1.0, latched: None })
    }

    /// A drive's value at time `t` reading the model's nodes at `st`, as a drive outside
    /// every element reads it ([`Self::with_all_nodes`]): the integration
    /// method's spectral radius before a step (MBDyn's `MultistepSolver::SetCoef`).
    pub fn drive_value(&self, drive: &crate::element::drive::Drive, st: &State, t: f64) -> f64 {
        self.with_all_nodes(st, t, |ctx| drive.value_in(ctx))
    }

    /// `F(y, ẏ, t)`; constraint rows are divided by `dcoef` in the form of eq. 30.
    pub fn residual(&self, st: &State, form: ConstraintForm, dcoef: f64) -> Vec<f64> {
        self.residual_with(st, &self.frames(st), form, dcoef)
    }

    /// The node frames of `st` into `out`, for [`Assembler::residual_at`] and
    /// [`Assembler::jacobian_at`] (a Newton iteration computes them once for both).
    pub fn frames_into(&self, st: &State, out: &mut Frames) {
        out.0.clear();
        out.0.extend((0..self.model.nodes.len()).map(|i| st.node_frame(&self.dofs, i)));
    }

    /// [`Assembler::residual`] with the node frames of `st` given ([`Assembler::frames_into`]).
    pub fn residual_at(&self, st: &State, frames: &Frames, form: ConstraintForm, dcoef: f64) -> Vec<f64> {
        self.residual_with(st, frames, form, dcoef)
    }

    fn residual_with(&self, st: &State, frames: &[NodeFrame], form: ConstraintForm, dcoef: f64) -> Vec<f64> {
        let mut f = vec![0.0; self.dofs.len];
        for (i, fr) in frames.iter().enumerate() {
            self.node_residual(st, i, fr, &mut f);
        }
        let scale = if form == ConstraintForm::Scaled { 1.0 / dcoef } else { 1.0 };
        for (e, el) in self.model.elements.iter().enumerate() {
            self.prefetch(st, e + prefetch::AHEAD);
            let ctx = self.context(frames, st, e, scale);
            let mut sink = Residual { dofs: &self.dofs, element: e, slots: &self.dofs.element_nodes[e], first: self.dofs.element_first[e], constraint_scale: scale, put: |i, v| f[i] += v };
            el.residual(&ctx, &mut sink);
        }
        f
    }

    /// `a F_/ẏ + b F_/y` as triplets in a fixed order.
    pub fn jacobian(&self, st: &State, c: Coefficients) -> Triplets {
        let mut out = Triplets::new(self.dofs.len);
        self.jacobian_into(st, c, &mut out);
        out
    }

    /// [`Assembler::jacobian`] into `out`, reusing its storage (Newton iterations).
    pub fn jacobian_into(&self, st: &State, c: Coefficients, out: &mut Triplets) {
        out.clear(self.dofs.len);
        out.shape = Some(self.assemble_jacobian(st, &self.frames(st), c, out));
    }

    /// [`Assembler::jacobian_into`] with the node frames of `st` given; `out.shape` is the
    /// fingerprint of the positions ([`Shape`]).
    pub fn jacobian_at(&self, st: &State, frames: &Frames, c: Coefficients, out: &mut Triplets) {
        out.clear(self.dofs.len);
        out.shape = Some(self.assemble_jacobian(st, frames, c, out));
    }

    /// The values of [`Assembler::jacobian_at`]'s triplets alone, in their order, into
    /// `values`, and the fingerprint of their positions: where it equals that of earlier
    /// triplets, the values sit at those triplets' positions (Newton's iterations on a known
    /// pattern map no row or column and push no index).
    pub fn jacobian_values_at(&self, st: &State, frames: &Frames, c: Coefficients, values: &mut Vec<f64>) -> Shape {
        values.clear();
        self.assemble_jacobian(st, frames, c, &mut Values(values))
    }

    fn assemble_jacobian<O: Entries>(&self, st: &State, frames: &[NodeFrame], c: Coefficients, out: &mut O) -> Shape {
        for (i, fr) in frames.iter().enumerate() {
            self.node_jacobian(st, i, fr, c, out);
        }
        let scale = if c.form == ConstraintForm::Scaled { 1.0 / c.dcoef } else { 1.0 };
        let mut shape = Shape::of_model(self.dofs.len, self.model.elements.len());
        for (e, el) in self.model.elements.iter().enumerate() {
            self.prefetch(st, e + prefetch::AHEAD);
            let ctx = self.context(frames, st, e, scale);
            let mut sink = Jacobian { dofs: &self.dofs, element: e, frames, slots: &self.dofs.element_nodes[e], first: self.dofs.element_first[e], c, out: &mut *out, shape: shape.element(e) };
            el.jacobian(&ctx, &mut sink);
            shape = sink.shape;
        }
        shape
    }

    /// A dynamic node's own terms: `β`, `γ` in the momentum definitions; `β̇` and
    /// `γ̇ + ẋ × β` in the equilibrium.
    ///
    /// A displacement-only node ([`Model::displacement_nodes`]) holds its orientation: a
    /// static one has `g` as moment equation, a dynamic one `γ̇ + g` as angular equilibrium
    /// (its angular momentum definition reads `γ = 0`, no element puts inertia there).
    fn node_residual(&self, st: &State, i: usize, fr: &NodeFrame, f: &mut [f64]) {
        let first = self.dofs.node_first[i];
        let displacement = self.dofs.node_displacement[i];
        if self.dofs.node_kind[i] != NodeKind::Dynamic {
            if displacement {
                (0..3).for_each(|k| f[first + 3 + k] += st.y[first + 3 + k]);
            }
            return;
        }
        let (beta, gamma) = st.momenta(&self.dofs, i);
        let gyro = if displacement { Vec3::new(st.y[first + 3], st.y[first + 4], st.y[first + 5]) } else { fr.kin.xdot.cross(&beta) };
        // A moving frame (`rigid body kinematics`): 2 W × β and W × γ (autostr.cc).
        let (lin, ang) = match &self.model.frame_motion {
            Some(m) => {
                let w = m.at(st.t).w;
                (2.0 * w.cross(&beta), w.cross(&gamma))
            }
            None => (Vec3::zeros(), Vec3::zeros()),
        };
        for k in 0..3 {
            f[first + k] += st.y[first + 6 + k];
            f[first + 3 + k] += st.y[first + 9 + k];
            f[first + 6 + k] += st.yp[first + 6 + k] + lin[k];
            f[first + 9 + k] += st.yp[first + 9 + k] + gyro[k] + ang[k];
        }
    }

    fn node_jacobian<O: Entries>(&self, st: &State, i: usize, fr: &NodeFrame, c: Coefficients, out: &mut O) {
        let first = self.dofs.node_first[i];
        if let (Some(m), NodeKind::Dynamic) = (&self.model.frame_motion, self.dofs.node_kind[i]) {
            let wx = skew(&m.at(st.t).w);
            for k in 0..3 {
                for j in 0..3 {
                    out.put(first + 6 + k, first + 6 + j, 2.0 * c.b * wx[(k, j)]);
                    out.put(first + 9 + k, first + 9 + j, c.b * wx[(k, j)]);
                }
            }
        }
        if self.dofs.node_displacement[i] {
            let row = if self.dofs.node_kind[i] == NodeKind::Dynamic { first + 9 } else { first + 3 };
            (0..3).for_each(|k| out.put(row + k, first + 3 + k, c.b));
            if self.dofs.node_kind[i] == NodeKind::Dynamic {
                for k in 0..3 {
                    out.put(first + k, first + 6 + k, c.b);
                    out.put(first + 3 + k, first + 9 + k, c.b);
                    out.put(first + 6 + k, first + 6 + k, c.a);
                    out.put(first + 9 + k, first + 9 + k, c.a);
                }
            }
            return;
        }
        if self.dofs.node_kind[i] != NodeKind::Dynamic {
            return;
        }
        let (beta, _) = st.momenta(&self.dofs, i);
        let (bx, vx) = (skew(&beta), skew(&fr.kin.xdot));
        for k in 0..3 {
            out.put(first + k, first + 6 + k, c.b);
            out.put(first + 3 + k, first + 9 + k, c.b);
            out.put(first + 6 + k, first + 6 + k, c.a);
            out.put(first + 9 + k, first + 9 + k, c.a);
            for j in 0..3 {
                // ∂(ẋ × β)/∂ẋ = −[β×], ∂(ẋ × β)/∂β = [ẋ×].
                out.put(first + 9 + k, first + j, -c.a * bx[(k, j)]);
                out.put(first + 9 + k, first + 6 + j, c.b * vx[(k, j)]);
            }
        }
    }

    /// Every element whose residual is not differentiable at `st` ([`Element::non_smooth`]),
    /// as "in line 3: …".
    ///
    /// [`Element::non_smooth`]: crate::element::Element::non_smooth
    pub fn non_smooth_elements(&self, st: &State) -> Vec<String> {
        let frames = self.frames(st);
        let named = |(e, el): (usize, &Box<dyn crate::element::Element>)| el.non_smoothness().and_then(|n| n.non_smooth(&self.context(&frames, st, e, 1.0))).map(|why| format!("{} {}: {why}", el.type_name(), el.label()));
        self.model.elements.iter().enumerate().filter_map(named).collect()
    }

    /// Every element whose residual is not differentiable somewhere between `from` and `to`
    /// ([`Element::kink_crossed`]), as "in line 3: …".
    ///
    /// [`Element::kink_crossed`]: crate::element::Element::kink_crossed
    pub fn kinks_crossed(&self, from: &State, to: &State) -> Vec<String> {
        let (frames_from, frames_to) = (self.frames(from), self.frames(to));
        let named = |(e, el): (usize, &Box<dyn crate::element::Element>)| {
            el.non_smoothness().and_then(|n| n.kink_crossed(&self.context(&frames_from, from, e, 1.0), &self.context(&frames_to, to, e, 1.0))).map(|why| format!("{} {}: {why}", el.type_name(), el.label()))
        };
        self.model.elements.iter().enumerate().filter_map(named).collect()
    }

    /// Every element's energy stores at `st` ([`crate::element::Outputs::energy_stores`]):
    /// `(element index, global unknown, store)`.
    pub fn energy_stores(&self, st: &State) -> Vec<(usize, usize, crate::element::EnergyStore)> {
        let frames = self.frames(st);
        let stores = |(e, el): (usize, &Box<dyn crate::element::Element>)| el.outputs().map(|o| o.energy_stores(&self.context(&frames, st, e, 1.0)).into_iter().map(move |s| (e, self.dofs.element_first[e] + s.unknown, s)).collect::<Vec<_>>()).unwrap_or_default();
        self.model.elements.iter().enumerate().flat_map(stores).collect()
    }

    /// Every element whose Jacobian at `st` depends on reaction multipliers' values
    /// ([`Element::reaction_dependence`]), as "in line 3: …".
    ///
    /// [`Element::reaction_dependence`]: crate::element::Element::reaction_dependence
    pub fn reaction_dependent_elements(&self, st: &State) -> Vec<String> {
        let frames = self.frames(st);
        let named = |(e, el): (usize, &Box<dyn crate::element::Element>)| el.non_smoothness().and_then(|n| n.reaction_dependence(&self.context(&frames, st, e, 1.0))).map(|why| format!("{} {}: {why}", el.type_name(), el.label()));
        self.model.elements.iter().enumerate().filter_map(named).collect()
    }

    /// Why each element that cannot evaluate its residual at `st` cannot
    /// ([`Element::failure`]), each naming its element.
    ///
    /// [`Element::failure`]: crate::element::Element::failure
    /// An element whose residual holds a value that is not finite without a reason of its
    /// own is named with the first such equation (a constitutive law's scalar function out
    /// of its domain, a drive gone NaN inside it).
    pub fn element_failures(&self, st: &State) -> Vec<String> {
        let frames = self.frames(st);
        let mut out = Vec::new();
        for (e, el) in self.model.elements.iter().enumerate() {
            let ctx = self.context(&frames, st, e, 1.0);
            if let Some(why) = el.failure(&ctx) {
                out.push(why);
                continue;
            }
            let mut bad: Option<(usize, f64)> = None;
            let mut sink = Residual { dofs: &self.dofs, element: e, slots: &self.dofs.element_nodes[e], first: self.dofs.element_first[e], constraint_scale: 1.0, put: |i, v: f64| {
                if !v.is_finite() && bad.is_none() {
                    bad = Some((i, v));
                }
            } };
            el.residual(&ctx, &mut sink);
            if let Some((i, v)) = bad {
                out.push(format!("{}: its contribution to {} is {v}{}", self.model.element_name(e), self.dofs.equation_name(self.model, i), self.model.element_functions_note(e)));
            }
        }
        out
    }

    /// Internal forces and deformation of every element that has evaluation points (beams),
    /// as `(element index, sections)`.
    pub fn section_states(&self, st: &State) -> Vec<(usize, Vec<SectionState>)> {
        self.element_outputs(st, |o, s| o.sections(s))
    }

    /// Every shell's stress resultants at its Gauss points, by element index.
    pub fn plate_resultants(&self, st: &State) -> Vec<(usize, Vec<f64>)> {
        self.element_outputs(st, |o, s| o.plate_resultants(s))
    }

    /// Every written hydraulic element's row of MBDyn's `.hyd` file, by element index.
    pub fn hydraulic_rows(&self, st: &State) -> Vec<(usize, Vec<f64>)> {
        self.element_outputs(st, |o, s| if o.writes_hydraulic_row() { o.hydraulic_row(s) } else { Vec::new() })
    }

    /// What `read` gives of each element's outputs at `st`, for the elements that give any.
    fn element_outputs<T>(&self, st: &State, read: impl Fn(&dyn crate::element::Outputs, &dyn crate::element::ElementState) -> Vec<T>) -> Vec<(usize, Vec<T>)> {
        let frames = self.frames(st);
        let mut out = Vec::new();
        for (e, el) in self.model.elements.iter().enumerate() {
            let values = el.outputs().map(|o| read(o, &self.context(&frames, st, e, 1.0))).unwrap_or_default();
            if !values.is_empty() {
                out.push((e, values));
            }
        }
        out
    }

    /// The contribution of one element alone, as `(equation, value)` entries (for the
    /// finite-difference check), with the nodes' frames at `st` given.
    /// Drives reading the model's state read `read_frames` (the unperturbed state in a
    /// finite-difference check: their derivatives are in no Jacobian, as in MBDyn).
    pub(crate) fn element_residual(&self, st: &State, frames: &[NodeFrame], read_frames: &[NodeFrame], e: usize, form: ConstraintForm, dcoef: f64) -> Vec<(usize, f64)> {
        let mut entries = Vec::new();
        let scale = if form == ConstraintForm::Scaled { 1.0 / dcoef } else { 1.0 };
        let ctx = Context { read_frames, ..self.context(frames, st, e, scale) };
        let mut sink = Residual { dofs: &self.dofs, element: e, slots: &self.dofs.element_nodes[e], first: self.dofs.element_first[e], constraint_scale: scale, put: |i, v| entries.push((i, v)) };
        self.model.elements[e].residual(&ctx, &mut sink);
        entries
    }

    /// The Jacobian entries of one element alone, with the nodes' frames at `st` given.
    pub(crate) fn element_jacobian(&self, st: &State, frames: &[NodeFrame], e: usize, c: Coefficients) -> Triplets {
        let mut out = Triplets::new(self.dofs.len);
        let ctx = self.context(frames, st, e, if c.form == ConstraintForm::Scaled { 1.0 / c.dcoef } else { 1.0 });
        let mut sink = Jacobian { dofs: &self.dofs, element: e, frames, slots: &self.dofs.element_nodes[e], first: self.dofs.element_first[e], c, out: &mut out, shape: Shape::default() };
        self.model.elements[e].jacobian(&ctx, &mut sink);
        out
    }
}
