//! `romdyn validate` (issue 33): the whole validation from the file, whose cost is the
//! nonlinear time integration. The README's beam (`--static --input 5:Fy --output 5:y
//! --count 1 --residualize-modes 7`, 20480 steps of 1.27e-4 s by default) and the HAM-SAS
//! example (`--static --load-steps 1 --input 3:Fz --output 3:z --count 6`, 163840 steps of
//! 0.132 s). `cargo bench --bench validate` (or `--profile dev`); figures in the book's
//! Performance chapter.

use std::path::Path;

use romdyn::analysis::Reference;
use romdyn::input::mbdyn::read_model;
use romdyn::rom::ModeSelection;
use romdyn::study::{Ports, Residualization, RomRequest, Study, StudySource};
use romdyn::validate::{validate, ValidateOptions};

fn main() {
    divan::main();
}

fn validate_file(file: &str, load_steps: usize, input: &str, output: &str, request: &RomRequest) -> bool {
    let m = read_model(Path::new(file)).unwrap();
    let ports = Ports::Nodes { inputs: vec![input.parse().unwrap()], outputs: vec![output.parse().unwrap()] };
    let mut study = Study::builder(StudySource::model(m.model, m.problem)).reference(Reference::Static { load_steps }).ports(ports.clone()).for_request(request).build().unwrap();
    let (state, problem) = study.reference_and_problem().unwrap();
    let rom = study.reduce(request).unwrap();
    validate(&mut study, &problem, &state, &ports, &rom, &ValidateOptions::default(), &mut |_, _| {}).unwrap().represents
}

#[divan::bench(sample_count = 3, sample_size = 1)]
fn readme_beam() -> bool {
    let request = RomRequest::new(ModeSelection::Lowest(1)).residualize(Residualization::Modes(vec![7]));
    validate_file("examples/simply_supported_beam.mbd", 10, "5:Fy", "5:y", &request)
}

#[divan::bench(sample_count = 1, sample_size = 1)]
fn ham_sas() -> bool {
    validate_file("examples/ham_sas.mbd", 1, "3:Fz", "3:z", &RomRequest::new(ModeSelection::Lowest(6)))
}
