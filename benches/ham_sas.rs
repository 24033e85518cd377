//! HAM-SAS-like isolator (issue 11, CASES C6): eigenanalysis of its 144-equation linear
//! model, and the whole chain from the file to the free ROM of its modes up to 2 Hz (dummy
//! springs removed), the paper's real-size case. Goal: eigenanalysis + ROM under 20 ms
//! (`eigen_and_rom`; measured 16.1–16.4 ms median, see docs/src/performance/overview.md).
//! `cargo bench --bench ham_sas`.

use romdyn::analysis::{reference_state, Reference};
use romdyn::dae::linearize;
use romdyn::input::mbdyn::read_model;
use romdyn::input::ports_file::read_ports_file;
use romdyn::eigen::{EigenRoute, ModalAnalysis};
use romdyn::rom::ModeSelection;
use romdyn::study::{parse_imposed, Application, RomRequest, Study, StudySource};

const BAND: ModeSelection = ModeSelection::Band { fmin_hz: 0.0, fmax_hz: 2.0 };

fn main() {
    // For instruction counts (callgrind): ROMDYN_BENCH_SEQ=1 keeps faer's products on the
    // calling thread, so that the timed functions' inclusive counts hold all their work.
    if std::env::var_os("ROMDYN_BENCH_SEQ").is_some() {
        faer::set_global_parallelism(faer::Par::Seq);
    }
    divan::main();
}

fn application() -> Application {
    let p = read_ports_file("examples/ham_sas_ports.json".as_ref()).unwrap();
    Application { inputs: p.inputs, outputs: p.outputs, names: p.names, remove_springs: p.remove_springs, imposed: p.imposed.as_deref().map(|s| parse_imposed(s).unwrap()), cuts: Vec::new() }
}

/// Eigenanalysis with right and adjoint vectors of the linearized model as written (dummy
/// springs present: the pencil the ROM is projected from), as `romdyn eig` and `rom` run it:
/// the clamp's zero eigenvalues deflated, QZ on the 132-unknown dynamic part.
#[divan::bench(sample_count = 20)]
fn eigenanalysis(bencher: divan::Bencher) {
    let m = read_model("examples/ham_sas.mbd".as_ref()).unwrap();
    let st = reference_state(&m.model, &m.problem, Reference::Static { load_steps: 1 }).unwrap();
    let dae = linearize(&m.model, &st, &[], &[], None).unwrap();
    let dcoef = m.problem.eigenanalysis.as_ref().and_then(|e| e.dcoef);
    bencher.bench(|| ModalAnalysis::of_dae(&dae, EigenRoute::Lambda, dcoef).unwrap());
}

/// The whole chain from the file: read, static equilibrium, linearization with ports,
/// eigenanalysis, free ROM of the modes up to 2 Hz (dummy springs removed).
#[divan::bench(sample_count = 10)]
fn file_to_free_rom(bencher: divan::Bencher) {
    let app = application();
    bencher.bench(|| {
        let m = read_model("examples/ham_sas.mbd".as_ref()).unwrap();
        let study = Study::builder(StudySource::model(m.model, m.problem)).reference(Reference::Static { load_steps: 1 }).application(app.clone()).build().unwrap();
        study.reduce(&RomRequest::new(BAND)).unwrap()
    });
}

/// Eigenanalysis + ROM as `romdyn rom examples/ham_sas.mbd --static --load-steps 1 --ports
/// examples/ham_sas_ports.json --band 0:2` runs them from the linearized model on: the
/// study's steps (eigenanalysis of the model as written, the dummy springs' ports and
/// feedback, the free model, its warnings) and `reduce` (selection, dominance, projection,
/// springs removed, ordinary form, static gains). The issue 11 goal: under 20 ms.
#[divan::bench(sample_count = 20)]
fn eigen_and_rom(bencher: divan::Bencher) {
    let app = application();
    let m = read_model("examples/ham_sas.mbd".as_ref()).unwrap();
    let st = reference_state(&m.model, &m.problem, Reference::Static { load_steps: 1 }).unwrap();
    let dae = Study::linearize_application(&m.model, &st, &app).unwrap();
    // The model is not Clone: each sample reads its own copy, outside the timed part.
    bencher.with_inputs(|| (StudySource::model(read_model("examples/ham_sas.mbd".as_ref()).unwrap().model, m.problem.clone()), app.clone(), st.clone(), dae.clone())).bench_values(|(source, app, st, dae)| {
        let study = Study::builder(source).application(app).at_state(st).linearized(dae).build().unwrap();
        study.reduce(&RomRequest::new(BAND)).unwrap()
    });
}
