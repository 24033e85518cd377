//! One design point: the model text with `set:` overrides, reference solution,
//! linearization, modes and ROM through the same [`Study`] workflow as `romdyn rom`.

use std::path::Path;

use faer::c64;

use crate::analysis::Reference;
use crate::dae::State;
use crate::input::mbdyn::{read_model_text, ReadOptions, SetOverrides};
use crate::eigen::ModalAnalysis;
use crate::dae::DofMap;
use crate::model::Model;
use crate::rom::mode_units;

use super::track::{sketch, PointMode};
use crate::output::rom_file::RomExport;
use crate::study::{EigenSettings, Ports, RomForm, RomRequest, Setting, Study, StudyError, StudySource};

/// What every design point computes (the options of `romdyn rom`).
#[derive(Clone, Debug)]
pub struct SweepOptions {
    pub reference: Reference,
    pub ports: Ports,
    pub eigen: EigenSettings,
    pub rom: RomRequest,
    pub form: RomForm,
    /// Number of lowest dynamic modes in the table and the plot (a pair counts once): the
    /// lowest at the first point, followed through the others ([`super::track`]).
    pub modes: usize,
    /// Each static equilibrium starts from the previous design point's (the points then run
    /// one after the other).
    pub continuation: bool,
    /// The rotation update of the model's beams (beam3, beam2): `Auto` is MBDyn's incremental
    /// update at a reference reached by a time integration (`--at T`), as `romdyn eig` on
    /// the same file, and path independent at a static or initial one
    /// ([`crate::input::mbdyn::BeamUpdateChoice`]).
    pub beam_update: crate::input::mbdyn::BeamUpdateChoice,
}

impl SweepOptions {
    /// Refuses the ROM options whose states are not the modal coordinates the sweep tracks:
    /// balanced reduction and the minimal realization change the state basis point by point
    /// (each point's own Hankel or Kalman basis), so the stacked `A[:,:,k]` would neither be
    /// in one basis nor interpolate. A discrete-time ROM keeps the modal states (`Ad` is a
    /// function of `A` on the same coordinates) and is taken.
    pub fn check(&self) -> Result<(), StudyError> {
        let refuse = |option, what: &str| Err(StudyError::Option { option, message: format!("{what} is not available in a sweep: its states are each point's own basis, not the modal coordinates the sweep stacks in one basis and interpolates; reduce one design point on its own (its values given with --set) instead") });
        if self.rom.balanced.is_some() {
            return refuse(Setting::Balanced, "balanced reduction");
        }
        if self.rom.minimal.is_some() {
            return refuse(Setting::Minimal, "the minimal realization");
        }
        Ok(())
    }
}

/// What a design point gives.
#[derive(Clone, Debug)]
pub struct PointResult {
    /// The ROM (same form and ports at every point).
    pub rom: RomExport,
    /// The lowest dynamic modes of the full model (a pair once, by its member with
    /// `Im λ ≥ 0`), by increasing |λ|, with their shapes and labels: the tabulated modes and
    /// [`candidates`] more, among which tracking finds the modes of the previous point.
    pub modes: Vec<PointMode>,
    /// The study's and the ROM's warnings.
    pub warnings: Vec<String>,
    /// The reference solution (continuation starts the next point from it; `None` for a
    /// result sent back from another process).
    pub state: Option<State>,
}

/// The overrides of one design point: parameter `names[k]` = `values[k]`.
pub fn overrides(names: &[String], values: &[f64]) -> SetOverrides {
    names.iter().cloned().zip(values.iter().copied()).collect()
}

/// Runs one design point on the text of the MBDyn file `name` (the name only labels messages
/// and resolves includes). `start`: the previous point's reference solution (continuation).
pub fn run_point(text: &str, name: &Path, names: &[String], values: &[f64], options: &SweepOptions, start: Option<&State>) -> Result<PointResult, StudyError> {
    options.check()?;
    let overrides = overrides(names, values);
    let m = read_model_text(text, name, ReadOptions::new(&overrides, options.beam_update, options.reference.integrates()))?;
    let builder = Study::builder(StudySource::read(m, name)).reference(options.reference).ports(options.ports.clone()).eigen(options.eigen).for_request(&options.rom);
    let study = match start {
        Some(start) => builder.start(start.clone()),
        None => builder,
    }
    .build()?;
    let state = study.reference_state().cloned();
    let rom = study.reduce(&options.rom)?;
    rom.check_form(options.form)?;
    let modes = point_modes(&study, candidates(options.modes));
    let mut warnings: Vec<String> = study.warnings().iter().map(|w| w.to_string()).collect();
    warnings.extend(rom.warnings.iter().map(|w| w.to_string()));
    Ok(PointResult { rom: rom.export(&study, options.form), modes, warnings, state })
}

/// The modes a point reports when `n` are tabulated: `n` and half as many more (at least 2),
/// so a mode that fell below another still has a candidate.
pub fn candidates(n: usize) -> usize {
    n + (n / 2).max(2)
}

/// The `n` lowest dynamic modes of a study ([`lowest_modes`]' units) with their labels (the
/// modal table's label column, [`Study::mode_labels`]: the node component with the largest
/// share of kinetic energy, "node 5 vertical (y) 25 %") and shapes: right vectors on the
/// model's motion unknowns, adjoint vectors on their equations ([`motion_indices`]).
pub fn point_modes(study: &Study, n: usize) -> Vec<PointMode> {
    let modal = study.modal();
    let labels = study.mode_labels();
    let (unknowns, equations) = study.model().map(motion_indices).unwrap_or_default();
    let restrict = |v: Option<&faer::Col<c64>>, at: &[usize]| v.map_or(Vec::new(), |v| sketch(at.iter().map(|&i| v[i]).collect()));
    lowest_units(modal, n)
        .into_iter()
        .map(|unit| {
            let first = &modal.modes[unit[0]];
            PointMode {
                lambda: first.lambda,
                label: labels[unit[0]].clone().unwrap_or_default(),
                members: unit.iter().map(|i| i + 1).collect(),
                shapes: unit.iter().map(|&i| restrict(modal.modes[i].right.as_ref(), &unknowns)).collect(),
                adjoint: restrict(first.left.as_ref(), &equations),
            }
        })
        .collect()
}

/// The unknowns that say how a model moves (structural nodes' positions and rotations,
/// scalar nodes, element coordinates and differential states: not momenta, not Lagrange
/// multipliers) and the equations of the same unknowns (a dynamic node's equilibrium rows,
/// after its momentum definitions).
pub fn motion_indices(model: &Model) -> (Vec<usize>, Vec<usize>) {
    let dofs = DofMap::new(model);
    let (mut unknowns, mut equations) = (Vec::new(), Vec::new());
    for n in 0..model.nodes.len() {
        unknowns.extend(dofs.node_first[n]..dofs.node_first[n] + 6);
        equations.extend(dofs.equilibrium_row(n)..dofs.equilibrium_row(n) + 6);
    }
    let scalars = dofs.scalar_first..dofs.scalar_first + model.scalar_nodes.len();
    let others = (dofs.scalar_first..dofs.len).filter(|&i| scalars.contains(&i) || dofs.is_coordinate(i) || dofs.is_state(i));
    for i in others {
        unknowns.push(i);
        equations.push(i);
    }
    (unknowns, equations)
}

/// The `n` lowest dynamic units, each with the member [`lowest_modes`] reports first.
fn lowest_units(modal: &ModalAnalysis, n: usize) -> Vec<Vec<usize>> {
    let key = |i: &usize| (modal.modes[*i].lambda.im, modal.modes[*i].lambda.re);
    mode_units(modal)
        .into_iter()
        .take(n)
        .map(|mut unit| {
            unit.sort_by(|a, b| key(b).partial_cmp(&key(a)).unwrap_or(std::cmp::Ordering::Equal));
            unit
        })
        .collect()
}

/// The `n` lowest dynamic modes, one eigenvalue per mode (unit of [`mode_units`]): a complex
/// pair by its member with `Im λ > 0`, a `±a` real pair (an unstable equilibrium) by `+a`.
pub fn lowest_modes(modal: &ModalAnalysis, n: usize) -> Vec<c64> {
    let key = |l: c64| (l.im, l.re);
    mode_units(modal)
        .iter()
        .take(n)
        .filter_map(|unit| unit.iter().map(|&i| modal.modes[i].lambda).max_by(|a, b| key(*a).partial_cmp(&key(*b)).unwrap_or(std::cmp::Ordering::Equal)))
        .collect()
}
