//! A ROM as an Octave/MATLAB script (`-o rom.m`): `run('rom.m')` defines `A B C D E Ts`,
//! the names and units, and `sys`, built with `ss(A, B, C, D, Ts)` (`Ts = 0`: continuous
//! time) or `dss(A, B, C, D, E)` for a descriptor ROM, its inputs, outputs and states named;
//! in MATLAB (Control System Toolbox) `InputUnit`, `OutputUnit`, `StateUnit` set too, in
//! Octave (control package, loaded by the script) the units go to `sys.userdata`, which is
//! where its `ss` keeps what it has no property for. Numbers are written with 17 significant
//! digits (a double read back is the same double). The numeric assignments come first
//! (romdyn's own `.m` reader, [`crate::input::octave_m`], reads them).

use faer::Mat;

use super::rom_export::RomExport;

fn number(x: f64) -> String {
    if x.is_nan() {
        "NaN".into()
    } else if x.is_infinite() {
        (if x > 0.0 { "Inf" } else { "-Inf" }).into()
    } else {
        format!("{x:.16e}")
    }
}

fn matrix(name: &str, m: &Mat<f64>) -> String {
    if m.nrows() == 0 || m.ncols() == 0 {
        return format!("{name} = zeros({}, {});\n", m.nrows(), m.ncols());
    }
    let rows: Vec<String> = (0..m.nrows()).map(|i| (0..m.ncols()).map(|j| number(m[(i, j)])).collect::<Vec<_>>().join(" ")).collect();
    format!("{name} = [\n{}\n];\n", rows.join(";\n"))
}

/// `{'a'; 'b'}` with quotes doubled (`{}` when empty).
fn cell(list: &[String]) -> String {
    let items: Vec<String> = list.iter().map(|s| format!("'{}'", s.replace('\'', "''"))).collect();
    format!("{{{}}}", items.join("; "))
}

/// The marker between the numeric assignments and the rest.
pub const NAMES_MARKER: &str = "% --- names, units and the system ---";

/// The script's text.
pub fn script(r: &RomExport) -> String {
    let mut s = String::new();
    s += &format!("% romdyn ROM ({}), {}\n", r.kind, r.time_domain());
    s += "% SI units: inputs, outputs and states in the units listed below; times in s.\n";
    s += "% run('this_file.m') defines A, B, C, D, E, Ts, the names and units, and sys (ss or dss).\n";
    for (name, m) in [("A", &r.a), ("B", &r.b), ("C", &r.c), ("D", &r.d), ("E", &r.e)] {
        s += &matrix(name, m);
    }
    s += &format!("Ts = {};\n", r.sample_time.map_or("0".to_string(), number));
    s += &format!("reference_time = {};\n", number(r.reference_time.unwrap_or(f64::NAN)));
    if !r.hankel_singular_values.is_empty() {
        s += &matrix("hankel_singular_values", &Mat::from_fn(r.hankel_singular_values.len(), 1, |i, _| r.hankel_singular_values[i]));
        s += &format!("error_bound = {};\n", number(r.error_bound.unwrap_or(f64::NAN)));
    }
    s += NAMES_MARKER;
    s += "\n";
    s += &format!("kind = '{}';\ndiscretization = '{}';\n", r.kind, r.discretization);
    for (name, list) in [("inputs", &r.inputs), ("outputs", &r.outputs), ("states", &r.states), ("input_units", &r.input_units), ("output_units", &r.output_units), ("state_units", &r.state_units)] {
        s += &format!("{name} = {};\n", cell(list));
    }
    s += "is_octave = exist('OCTAVE_VERSION', 'builtin') ~= 0;\n";
    s += "if is_octave\n  pkg load control\nend\n";
    s += "if strcmp(kind, 'descriptor')\n  sys = dss(A, B, C, D, E);\nelse\n  sys = ss(A, B, C, D, Ts);\nend\n";
    s += "if is_octave\n";
    s += "  sys = set(sys, 'inname', inputs, 'outname', outputs, 'stname', states);\n";
    s += "  sys = set(sys, 'userdata', struct('input_units', {input_units}, 'output_units', {output_units}, 'state_units', {state_units}));\n";
    s += "else\n";
    s += "  sys.InputName = inputs; sys.OutputName = outputs; sys.StateName = states;\n";
    s += "  sys.InputUnit = input_units; sys.OutputUnit = output_units; sys.StateUnit = state_units;\n";
    s += "end\n";
    s
}
