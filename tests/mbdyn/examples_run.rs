//! Every MBDyn example in `examples/` reads, runs (its first five steps, with its eigenanalyses
//! moved to the start) and linearizes (issue 4: "each example runs").

use std::path::Path;

use romdyn::analysis::run;
use romdyn::input::mbdyn::read_model;
use romdyn::model::{EigenOutput, EigenRequest};

#[test]
fn every_example_reads_runs_and_has_dynamic_modes() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    let mut files: Vec<_> = std::fs::read_dir(&dir).unwrap().map(|e| e.unwrap().path()).filter(|p| p.extension().is_some_and(|x| x == "mbd")).collect();
    files.sort();
    assert!(files.len() >= 7, "{files:?}");
    for path in files {
        let name = path.display().to_string();
        let m = read_model(&path).unwrap_or_else(|e| panic!("{e}"));
        let mut problem = m.problem.clone();
        problem.final_time = problem.initial_time + 5.0 * problem.time_step;
        let request = problem.eigenanalysis.take().unwrap_or(EigenRequest { times: vec![], dcoef: None, lower_frequency_hz: None, upper_frequency_hz: None, output: EigenOutput::default(), file_suffix: Default::default(), solver: Default::default() });
        problem.eigenanalysis = Some(EigenRequest { times: vec![problem.initial_time], ..request });
        let report = run(&m.model, &problem, &mut ()).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(report.steps, 5, "{name}");
        assert!(report.eigenanalyses[0].dynamic.len() >= 2, "{name}: no dynamic mode");
    }
}
