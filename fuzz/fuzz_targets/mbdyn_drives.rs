//! Drive callers and scalar functions (issue 32's grammar: `string` drives calling
//! `model::drive`, `model::sf`, nested callers, scalar function cards built from others):
//! the fuzzed text is the drive of a couple on a pendulum, after scalar function cards made
//! from the text's first line. Reading and three time steps must end in a result or an
//! error, never a panic, an abort or a hang.
#![no_main]

use libfuzzer_sys::fuzz_target;

const MODEL: &str = "begin: data; problem: initial value; end: data;
begin: initial value; initial time: 0.; final time: 3.e-3; time step: 1.e-3; method: ms, .6; tolerance: 1.e-9; max iterations: 10; end: initial value;
begin: control data; structural nodes: 2; rigid bodies: 1; joints: 2; forces: 1; end: control data;
SCALAR_FUNCTIONS
begin: nodes; structural: 1, static, null, eye, null, null; structural: 2, dynamic, 0., -1., 0., eye, null, null; end: nodes;
begin: elements;
joint: 1, clamp, 1, node, node;
joint: 2, revolute hinge, 1, position, null, 2, position, 0., 1., 0.;
body: 3, 2, 1., null, diag, 1.e-3, 1.e-3, 1.e-3;
couple: 4, absolute, 2, single, 0., 0., 1., DRIVE;
end: elements;
";

fuzz_target!(|data: &[u8]| {
    let text = String::from_utf8_lossy(data);
    let (functions, drive) = text.split_once('\n').unwrap_or(("", &text));
    let file = MODEL.replace("SCALAR_FUNCTIONS", functions).replace("DRIVE", drive);
    let path = std::path::Path::new("fuzz.mbd");
    let Ok(m) = romdyn::input::mbdyn::parse_text(&file, path).and_then(|d| romdyn::input::mbdyn::build(&d)) else { return };
    let _ = romdyn::analysis::run(&m.model, &m.problem, &mut ());
});
