//! Paper Fig. 7: the mid-span response of the simply supported beam (4 elements,
//! `examples/simply_supported_beam.mbd`) to a co-located force, full model against three
//! ROMs: the first bending mode; the first and third; the first with the third statically
//! residualized. Prints the ROMs' eigenvalues and static gains and writes
//! `out/beam_rom.{csv,svg,png}`.
//!
//!     cargo run --release --example beam_rom

use std::path::Path;

use romdyn::analysis::{reference_state, Reference};
use romdyn::dae::linearize;
use romdyn::input::mbdyn::read_model;
use romdyn::eigen::{EigenRoute, ModalAnalysis, ModeKind};
use romdyn::linear::LinearDae;
use romdyn::linear::{FrequencyResponse, Port};
use romdyn::output::frequency_plot::write_bode_files;
use romdyn::rom::full_frequency_response;
use romdyn::rom::{log_frequencies, DescriptorRom, OrdinaryRom, Selection};

/// The dynamic pairs the output sees (|C v| above 1e-6 of the largest), lowest first, each as
/// its two mode indices: the symmetric bending modes for a mid-span output.
fn observable_pairs(dae: &LinearDae, modal: &ModalAnalysis) -> Vec<Vec<usize>> {
    let seen = |i: usize| modal.modes[i].right.as_ref().map_or(0.0, |v| (0..v.nrows()).map(|k| dae.c[(0, k)] * v[k].norm()).fold(0.0, |m: f64, x| m.max(x.abs())));
    let mut pairs: Vec<usize> = modal.of_kind(ModeKind::Dynamic).filter(|&i| modal.modes[i].lambda.im > 0.0).collect();
    pairs.sort_by(|&a, &b| modal.modes[a].lambda.norm().total_cmp(&modal.modes[b].lambda.norm()));
    let largest = pairs.iter().map(|&i| seen(i)).fold(0.0, f64::max);
    pairs.into_iter().filter(|&i| seen(i) > 1e-6 * largest).map(|i| vec![i, modal.modes[i].partner.unwrap_or(i)]).collect()
}

fn rom(dae: &LinearDae, modal: &ModalAnalysis, kept: &[&Vec<usize>], residualized: &[&Vec<usize>]) -> anyhow::Result<OrdinaryRom> {
    let sel = Selection { kept: kept.iter().flat_map(|p| p.iter().copied()).collect(), dropped: residualized.iter().flat_map(|p| p.iter().copied()).collect() };
    let d = DescriptorRom::project(dae, modal, &sel, !residualized.is_empty())?;
    Ok(d.to_ordinary()?)
}

fn main() -> anyhow::Result<()> {
    let m = read_model(Path::new("examples/simply_supported_beam.mbd"))?;
    let st = reference_state(&m.model, &m.problem, Reference::Static { load_steps: 1 })?;
    let dae = linearize(&m.model, &st, &["5:Fy".parse()?], &["5:y".parse()?], None)?;
    let modal = ModalAnalysis::compute(&dae.jacobians, EigenRoute::Lambda)?;
    let pairs = observable_pairs(&dae, &modal);
    let (first, third) = (&pairs[0], &pairs[1]);
    let exact = 1.0 / 48e3 + 1.0 / 4e6;
    let roms = [
        ("first mode", rom(&dae, &modal, &[first], &[])?),
        ("first and third modes", rom(&dae, &modal, &[first, third], &[])?),
        ("first mode, third residualized", rom(&dae, &modal, &[first], &[third])?),
    ];
    println!("full model: static gain {exact:.6e} m/N (eq. 73); first bending {:.3} rad/s, third {:.3} rad/s", modal.modes[first[0]].lambda.im, modal.modes[third[0]].lambda.im);
    for (name, r) in &roms {
        let g = r.static_gain()?[(0, 0)];
        println!("ROM, {name}: {} states, static gain {g:.6e} m/N ({:+.3} %)", r.a.nrows(), 100.0 * (g / exact - 1.0));
    }
    let hz = |i: usize| romdyn::linear::hz(modal.modes[i].lambda.norm());
    let freq = log_frequencies(hz(first[0]) / 10.0, hz(third[0]) * 3.0, 600);
    let h = full_frequency_response(&dae, &freq);
    let mut responses = FrequencyResponse::new(freq.clone(), Port::from_labels(&dae.input_names), Port::from_labels(&dae.output_names), h);
    for (name, r) in &roms {
        responses = responses.with_reduced(name, r.frequency_response(&freq));
    }
    let [csv, svg, png] = write_bode_files(&responses, Path::new("out/beam_rom"), "Simply supported beam, mid-span force to mid-span displacement (paper Fig. 7)")?;
    println!("wrote {}, {}, {}", csv.display(), svg.display(), png.display());
    Ok(())
}
