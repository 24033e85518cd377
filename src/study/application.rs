//! The paper's application (§8) on a [`Study`]: ports at points of bodies, node names and
//! mode labels, dummy springs removed from the ROM (eqs. 92–95), imposed motion and
//! transmissibility (eqs. 96–100).

use std::collections::BTreeMap;

use faer::{c64, Mat};

use crate::dae::ports::{InputPort, OutputPort};
use crate::dae::{cut_parts, element_part, linearize_ports, Cut, ElementPart, NodeInput, NodeOutput, State};
use crate::eigen::{cluster_label, degenerate_clusters, mode_label, real_mode_label, ModalEnergy};
use crate::eigen::ModalAnalysis;
use crate::linear::{FrequencyResponse, LinearDae, Port};
use crate::model::{InitialValueProblem, Label, Model};
use crate::rom::{full_frequency_response, transmissibility, with_spring_ports, without_elements, ImposedModel, SpringFeedback};

use super::checks::{equilibrium_warning, port_warnings};
use super::linear::LinearModel;
use super::{EigenSettings, ReducedModel, Solver, Study, StudyError};

/// What the application adds to a linearization.
#[derive(Clone, Debug, Default)]
pub struct Application {
    pub inputs: Vec<InputPort>,
    pub outputs: Vec<OutputPort>,
    /// Names of nodes (bodies) for mode labels.
    pub names: BTreeMap<Label, String>,
    /// Labels of deformable elements (dummy springs) removed from the ROM and the full model.
    pub remove_springs: Vec<Label>,
    /// Imposed motion: node and components (0..6: x, y, z, rx, ry, rz).
    pub imposed: Option<(Label, Vec<usize>)>,
    /// Control loops cut open at genels or abstract forces ([`Cut`]): their ports come after
    /// the other inputs and outputs (and before the imposed components).
    pub cuts: Vec<Cut>,
}

/// `NODE` (all six components) or `NODE:x,y,rz`.
pub fn parse_imposed(s: &str) -> Result<(Label, Vec<usize>), String> {
    const NAMES: [&str; 6] = ["x", "y", "z", "rx", "ry", "rz"];
    let bad = || format!("'{s}': expected NODE or NODE:COMPONENTS with components among x,y,z,rx,ry,rz");
    let (node, comps) = s.split_once(':').map_or((s, None), |(n, c)| (n, Some(c)));
    let node: Label = node.trim().parse().map_err(|_| bad())?;
    let mut list = match comps {
        None => (0..6).collect(),
        Some(c) => c.split(',').map(|x| NAMES.iter().position(|n| n.eq_ignore_ascii_case(x.trim())).ok_or_else(bad)).collect::<Result<Vec<_>, _>>()?,
    };
    list.sort_unstable();
    list.dedup();
    if list.is_empty() {
        return Err(bad());
    }
    Ok((node, list))
}

/// The application's ports with the imposed node's components appended (forces as inputs,
/// displacements as outputs).
fn application_ports(app: &Application) -> (Vec<InputPort>, Vec<OutputPort>) {
    let mut inputs = app.inputs.clone();
    let mut outputs = app.outputs.clone();
    if let Some((node, comps)) = &app.imposed {
        for &k in comps {
            inputs.push(NodeInput { node: *node, component: k }.port());
            outputs.push(NodeOutput { node: *node, component: k }.port());
        }
    }
    (inputs, outputs)
}

fn applied(app: &Application, parts: Vec<ElementPart>, projected: Option<LinearDae>, feedback: Option<SpringFeedback>) -> Applied {
    let imposed = app.imposed.as_ref().map_or(0, |(_, c)| c.len());
    Applied { projected, feedback, parts, imposed, names: app.names.clone() }
}

/// What a study keeps of its application.
pub(super) struct Applied {
    /// The DAE the ROM is projected from: the springs present, their coordinates as the last
    /// inputs and outputs (`None` without springs to remove).
    pub projected: Option<LinearDae>,
    pub feedback: Option<SpringFeedback>,
    pub parts: Vec<ElementPart>,
    /// Number of imposed components (the last inputs and outputs of the study's DAE).
    pub imposed: usize,
    pub names: BTreeMap<Label, String>,
}

impl Study {
    /// The study of an application at a given reference solution, with the sparse solver's
    /// progress reports. Springs to remove and imposed motion take the dense route (their
    /// corrections are dense).
    pub(super) fn application_state(model: Model, problem: &InitialValueProblem, state: State, app: &Application, eigen: EigenSettings, progress: &dyn Fn(&str)) -> Result<Self, StudyError> {
        let (inputs, outputs) = application_ports(app);
        if app.remove_springs.is_empty() && app.imposed.is_none() {
            let mut study = Self::from_model_ports(model, problem, state, &inputs, &outputs, &app.cuts, eigen, progress)?;
            study.application = Some(applied(app, Vec::new(), None, None));
            // The labels need the application's names: the warnings stay, the study is the same.
            return Ok(study);
        }
        if eigen.solver == Solver::Sparse {
            return Err(StudyError::Option { option: super::Setting::Solver, message: "sparse: removing dummy springs and imposing motion are done on the dense linear model only (use --solver dense or auto)".into() });
        }
        let dae = Self::linearize_application(&model, &state, app)?;
        Self::from_application_dae(model, problem, state, dae, app, eigen)
    }

    /// The dense linearization with the application's ports (imposed components last), the
    /// DAE a study of springs to remove or imposed motion starts from (given to the builder
    /// with [`super::StudyBuilder::linearized`]).
    pub fn linearize_application(model: &Model, state: &State, app: &Application) -> Result<LinearDae, StudyError> {
        let (inputs, outputs) = application_ports(app);
        let mut dae = linearize_ports(model, state, &inputs, &outputs, None)?;
        for part in cut_parts(model, state, &app.cuts)? {
            part.cut_dense(&mut dae, app.imposed.as_ref().map_or(0, |(_, c)| c.len()));
        }
        Ok(dae)
    }

    /// The study of an application with springs to remove or imposed motion, from its
    /// linearization `dae` ([`Study::linearize_application`]): the eigenanalysis of the model
    /// as written, the springs' ports and feedback, the free model and its warnings (the
    /// steps `romdyn rom` runs after linearizing, timed by `benches/ham_sas.rs`).
    pub(super) fn from_application_dae(model: Model, problem: &InitialValueProblem, state: State, dae: LinearDae, app: &Application, eigen: EigenSettings) -> Result<Self, StudyError> {
        let parts = app.remove_springs.iter().map(|&l| element_part(&model, &state, l)).collect::<Result<Vec<_>, _>>()?;
        let file_dcoef = problem.eigenanalysis.as_ref().and_then(|e| e.dcoef);
        // The eigenanalysis of the model as written and the free model (springs removed, its
        // static gain) do not depend on each other: both cores when one is free.
        let (modal, (projected, feedback, free)) = rayon::join(
            || ModalAnalysis::of_dae(&dae, eigen.route, eigen.dcoef.or(file_dcoef)),
            || {
                let (projected, feedback) = if parts.is_empty() {
                    (None, None)
                } else {
                    let (p, f) = with_spring_ports(&dae, &parts);
                    (Some(p), Some(f))
                };
                let free = LinearModel::from_dense(without_elements(&dae, &parts), false);
                // Filled now, read by the port warnings and every ROM's static gain.
                let _ = free.dense_static_gain();
                (projected, feedback, free)
            },
        );
        let mut modal = modal.map_err(|e| e.with_unknown_names(&dae.unknown_names))?;
        super::checks::refine_errors(&mut modal, &free, Some(&model));
        let mut warnings: Vec<_> = equilibrium_warning(&model, &state, problem.tolerance).into_iter().collect();
        let classes = crate::eigen::ModalEnergy::non_mechanical_mask(&model);
        warnings.extend(port_warnings(&free, &modal, (classes.len() == free.dim()).then_some(&classes[..])));
        let applied = applied(app, parts, projected, feedback);
        Ok(Study { linear: free, modal, sparse: None, model: Some(model), warnings, reference_time: Some(state.t), reference_state: None, problem: None, application: Some(applied) })
    }

    /// One label per mode ("table pitch (ry) 93 %") from the kinetic-energy shares and the
    /// node names; `None` for modes without shares. A member of a cluster of degenerate
    /// modes gets the cluster's label ([`cluster_label`]: "little pendulums yaw (rz) 88 %, 1
    /// of 4 modes at 15.91 Hz"), the same for every member and for any basis of the cluster.
    pub fn mode_labels(&self) -> Vec<Option<String>> {
        let mut names = self.model.as_ref().map(|m| m.node_names.clone()).unwrap_or_default();
        if let Some(a) = &self.application {
            names.extend(a.names.iter().map(|(k, v)| (*k, v.clone())));
        }
        let names = &names;
        let gravity = self.model.as_ref().map(|m| m.gravity).unwrap_or_default();
        let energy = self.energy();
        let mut labels: Vec<_> = energy.iter().map(|s| mode_label(s, names, &gravity)).collect();
        for cluster in degenerate_clusters(&self.modal.modes) {
            for &i in &cluster {
                labels[i] = cluster_label(&energy[i], names, &gravity, cluster.len(), self.modal.modes[i].freq_hz());
            }
        }
        labels
    }

    /// A label for a real eigenvalue `lambda` [rad/s] of the free model (the study's full
    /// model, dummy springs removed: e.g. a free ROM's unstable pair): the kinetic-energy
    /// shares of the free model's real mode nearest it ([`LinearDae::real_mode_near`]),
    /// worded by [`real_mode_label`] ("tipping (ry): base ry 48 %, …, unstable"). `None`
    /// without a model or when the free model has no real eigenvalue near `lambda`.
    pub fn free_real_mode_label(&self, lambda: f64) -> Option<String> {
        let model = self.model.as_ref()?;
        let (lambda, v) = self.linear.dense().real_mode_near(lambda)?;
        let right = faer::Col::from_fn(v.nrows(), |i| c64::new(v[i], 0.0));
        let mode = crate::eigen::Mode { lambda: c64::new(lambda, 0.0), right: Some(right), left: None, partner: None, ..self.modal.modes.first()?.clone() };
        let mut names = model.node_names.clone();
        if let Some(a) = &self.application {
            names.extend(a.names.iter().map(|(k, v)| (*k, v.clone())));
        }
        real_mode_label(&ModalEnergy::new(model, self.linear.dense()).shares(&mode), &names, &model.gravity, lambda)
    }

    /// The elements removed from the full model and the ROMs ("deformable hinge 902").
    pub fn removed_springs(&self) -> Vec<String> {
        self.application.as_ref().map_or(Vec::new(), |a| a.parts.iter().map(|p| p.element.clone()).collect())
    }

    /// Number of imposed components (the last inputs and outputs of [`Study::dae`]).
    pub fn imposed_len(&self) -> usize {
        self.application.as_ref().map_or(0, |a| a.imposed)
    }

    fn imposed_count(&self) -> Result<usize, StudyError> {
        match self.application.as_ref().map_or(0, |a| a.imposed) {
            0 => Err(StudyError::NoImposedMotion),
            n => Ok(n),
        }
    }

    /// Eq. 100 on the full model (springs removed: the result does not depend on them) and on
    /// the ROM, at `freq_hz`: a response from the imposed components (its inputs) to the
    /// regular outputs, the ROM its reduced model "ROM".
    pub fn transmissibility(&self, rom: &ReducedModel, freq_hz: &[f64]) -> Result<FrequencyResponse, StudyError> {
        let n = self.imposed_count()?;
        let eq100 = |h: Vec<Mat<c64>>| h.iter().zip(freq_hz).map(|(m, f)| transmissibility(m, n).ok_or(StudyError::SingularImposedMotion(*f))).collect::<Result<Vec<_>, _>>();
        let dae = self.linear.dense();
        let full = eq100(full_frequency_response(dae, freq_hz))?;
        let rom_t = eq100(rom.ordinary.frequency_response(freq_hz))?;
        let no = dae.num_outputs() - n;
        let ports = |names: &[String]| Port::from_labels(names);
        Ok(FrequencyResponse::new(freq_hz.to_vec(), ports(&dae.output_names[no..]), ports(&dae.output_names[..no]), full).with_reduced("ROM", rom_t))
    }

    /// The proper state-space model from the imposed displacements to the other outputs.
    pub fn imposed_model(&self, rom: &ReducedModel) -> Result<ImposedModel, StudyError> {
        let n = self.imposed_count()?;
        Ok(rom.ordinary.imposed_motion(n)?)
    }
}

impl Study {
    /// The imposed-motion model in discrete time at the sampling of `rom`'s discrete form
    /// (`None` when `rom` is continuous).
    pub fn imposed_discrete(&self, m: &ImposedModel, rom: &ReducedModel) -> Result<Option<crate::rom::DiscreteRom>, StudyError> {
        Ok(rom.discrete.as_ref().map(|d| m.rom.discretize(&d.sampling)).transpose()?)
    }

    /// The imposed-motion model in exportable form (inputs: the imposed displacements), its
    /// discrete-time form `discrete` when given ([`Study::imposed_discrete`]).
    pub fn imposed_export(&self, m: &ImposedModel, discrete: Option<&crate::rom::DiscreteRom>) -> crate::output::rom_file::RomExport {
        use crate::output::rom_file::unit_of_name;
        let r = discrete.map_or(&m.rom, |d| &d.rom);
        let n = r.a.nrows();
        crate::output::rom_file::RomExport {
            kind: "ordinary",
            e: Mat::identity(n, n),
            a: r.a.clone(),
            b: r.b.clone(),
            c: r.c.clone(),
            d: r.d.clone(),
            eigenvalues: r.eigenvalues.clone(),
            full_eigenvalues: Vec::new(),
            inputs: r.input_names.clone(),
            outputs: r.output_names.clone(),
            states: discrete.and_then(|d| d.state_names.clone()).unwrap_or_else(|| (1..=n).map(|k| format!("imposed-motion state {k}")).collect()),
            input_units: r.input_names.iter().map(|s| unit_of_name(s)).collect(),
            output_units: r.output_names.iter().map(|s| unit_of_name(s)).collect(),
            state_units: vec!["state of the ROM minus the imposed motion's part (see rom::imposed)".to_string(); n],
            state_modes: vec![0; n],
            state_freq_hz: vec![f64::NAN; n],
            reference_time: self.reference_time,
            dcoef: self.modal.dcoef,
            full_static_gain: None,
            rom_static_gain: None,
            sample_time: discrete.map(|d| d.sample_time()),
            discretization: discrete.map_or("continuous".into(), |d| d.sampling.method.name()),
            hankel_singular_values: Vec::new(),
            error_bound: None,
        }
    }
}
