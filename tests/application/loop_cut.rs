//! Closed and open loops from one file (issue 34 point 4): `--cut genel:L` takes a link of a
//! control loop out of the linearization and makes the signal across it an input (injected)
//! and an output (returned). Checked on examples/pid_mass.mbd against the closed forms of
//! its plant `P = 1/(m s² + c s + k)`, controller `C = (B0 s² + B1 s + B2)/(s² + A1 s)`,
//! loop `L = P C` and closed loop, and on the worked example examples/pid_two_mass.mbd (a
//! flexible drive, plant `K12/((M1 s² + C1 s + K1 + K12)(M2 s² + C2 s + K12) − K12²)`).

use std::path::{Path, PathBuf};

use faer::{c64, Mat};
use romdyn::dae::{Cut, NodeInput, NodeOutput};
use romdyn::eigen::ModeKind;
use romdyn::rom::{full_frequency_response, ModeSelection};
use romdyn::study::{Ports, RomRequest, Setting, Study, StudyError, StudySource};

fn example(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples").join(name)
}

fn study(file: &str, inputs: &[&str], outputs: &[&str], cuts: &[&str]) -> Result<Study, StudyError> {
    let inputs: Vec<NodeInput> = inputs.iter().map(|s| s.parse().unwrap()).collect();
    let outputs: Vec<NodeOutput> = outputs.iter().map(|s| s.parse().unwrap()).collect();
    let cuts: Vec<Cut> = cuts.iter().map(|s| s.parse().unwrap()).collect();
    let ports = Ports::from_parts(None, &inputs, &outputs, &[], &[], None, &cuts)?;
    Study::builder(StudySource::model_file(example(file))).ports(ports).build()
}

/// `p[0] sⁿ + … + p[n]` at `s`.
fn poly(p: &[f64], s: c64) -> c64 {
    p.iter().fold(c64::new(0.0, 0.0), |acc, &x| acc * s + x)
}

fn product(a: &[f64], b: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; a.len() + b.len() - 1];
    for (i, x) in a.iter().enumerate() {
        for (j, y) in b.iter().enumerate() {
            out[i + j] += x * y;
        }
    }
    out
}

/// The roots of a polynomial as the eigenvalues of its companion matrix (nalgebra: independent
/// of romdyn's QZ).
fn roots(p: &[f64]) -> Vec<c64> {
    let n = p.len() - 1;
    let companion = nalgebra::DMatrix::from_fn(n, n, |i, j| if i == 0 { -p[j + 1] / p[0] } else if i == j + 1 { 1.0 } else { 0.0 });
    companion.complex_eigenvalues().iter().map(|z| c64::new(z.re, z.im)).collect()
}

fn dynamic_eigenvalues(study: &Study) -> Vec<c64> {
    study.modal().modes.iter().filter(|m| m.kind == ModeKind::Dynamic).map(|m| m.lambda).collect()
}

fn assert_same_roots(got: &[c64], want: &[c64], tol: f64) {
    assert_eq!(got.len(), want.len(), "got {got:?}, want {want:?}");
    for w in want {
        let d = got.iter().map(|g| (g - w).norm()).fold(f64::INFINITY, f64::min);
        assert!(d <= tol * w.norm(), "{w} not among {got:?} (closest {d:e})");
    }
}

fn assert_close(got: c64, want: c64, tol: f64, what: &str) {
    assert!((got - want).norm() <= tol * want.norm(), "{what}: {got} vs {want} (relative {:e})", (got - want).norm() / want.norm());
}

/// 0.05 to 50 Hz, 25 points per decade.
fn grid() -> Vec<f64> {
    (0..=75).map(|k| 0.05 * 10f64.powf(k as f64 / 25.0)).collect()
}

fn s_of(f: f64) -> c64 {
    c64::new(0.0, 2.0 * std::f64::consts::PI * f)
}

/// examples/pid_mass.mbd: m, c, k, the controller's numerator and denominator.
struct PidMass {
    plant: [f64; 3],
    num: [f64; 3],
    den: [f64; 3],
}

const PID_MASS: PidMass = {
    let (m, k, c, kp, ki, kd, tau) = (2.0, 50.0, 0.4, 100.0, 200.0, 10.0, 0.01);
    PidMass { plant: [m, c, k], num: [(kp * tau + kd) / tau, (kp + ki * tau) / tau, ki / tau], den: [1.0, 1.0 / tau, 0.0] }
};

impl PidMass {
    fn p(&self, s: c64) -> c64 {
        c64::new(1.0, 0.0) / poly(&self.plant, s)
    }
    fn c(&self, s: c64) -> c64 {
        poly(&self.num, s) / poly(&self.den, s)
    }
}

#[test]
fn cutting_the_pid_link_gives_the_plant_the_controller_and_the_loop_of_the_closed_forms() {
    // Inputs: the disturbance f on node 1, then the cut's injected force; outputs: x (node 1),
    // u (node 2), then the cut's returned force.
    let cut = study("pid_mass.mbd", &["1:abstract"], &["1:abstract", "2:abstract"], &["genel:4"]).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(cut.input_names(), ["abstract node 1 [-]", "cut genel cross spring support 4 at abstract node 1 (injected) [-]"]);
    assert_eq!(cut.output_names()[2], "cut genel cross spring support 4 at abstract node 1 (returned) [-]");
    // Poles of the cut model: the plant's, roots of m s² + c s + k (closed form, 1e-8), and
    // the controller's −1/τ (its integrator is the zero eigenvalue).
    let mut want = roots(&PID_MASS.plant);
    want.push(c64::new(-100.0, 0.0));
    assert_same_roots(&dynamic_eigenvalues(&cut), &want, 1e-8);
    assert_eq!(cut.modal().modes.iter().filter(|m| m.kind == ModeKind::Zero).count(), 1);
    let freqs = grid();
    for (h, &f) in full_frequency_response(cut.dae(), &freqs).iter().zip(&freqs) {
        let s = s_of(f);
        let (p, c) = (PID_MASS.p(s), PID_MASS.c(s));
        // Closed forms on 0.05–50 Hz, 1e-8 relative: x/f = P, u/f = C P, the returned force
        // (the link's −u) per injected force −P C, so L = −returned/injected = P C.
        assert_close(h[(0, 0)], p, 1e-8, &format!("P at {f} Hz"));
        assert_close(h[(1, 0)], c * p, 1e-8, &format!("C P at {f} Hz"));
        assert_close(h[(0, 1)], p, 1e-8, &format!("x per injected force at {f} Hz"));
        assert_close(-h[(2, 1)], p * c, 1e-8, &format!("L at {f} Hz"));
    }
}

/// The closed loop from the open-loop pieces of the cut model: closing `w = r` in
/// `[x; r] = H [f; w]` gives `x/f = H_xf + H_xw (1 − H_rw)⁻¹ H_rf`.
fn closed_from_cut(h: &Mat<c64>, row: usize) -> c64 {
    let n = h.ncols() - 1;
    h[(row, 0)] + h[(row, n)] * h[(h.nrows() - 1, 0)] / (c64::new(1.0, 0.0) - h[(h.nrows() - 1, n)])
}

#[test]
fn the_closed_loop_equals_the_open_loop_pieces_closed_again() {
    let closed = study("pid_mass.mbd", &["1:abstract"], &["1:abstract", "2:abstract"], &[]).unwrap_or_else(|e| panic!("{e}"));
    let freqs = grid();
    let full = full_frequency_response(closed.dae(), &freqs);
    // The closed-loop ROM keeps every dynamic mode (the quartic's four roots).
    let rom = closed.reduce(&RomRequest::new(ModeSelection::band(0.0, 1000.0).unwrap())).unwrap_or_else(|e| panic!("{e}"));
    let reduced = rom.ordinary.frequency_response(&freqs);
    // Cut at the link (genel 4, at its output) and at the controller (the scalar filter,
    // genel 3, at its input): both give the same loop.
    let at_link = study("pid_mass.mbd", &["1:abstract"], &["1:abstract", "2:abstract"], &["genel:4"]).unwrap();
    let at_controller = study("pid_mass.mbd", &["1:abstract"], &["1:abstract", "2:abstract"], &["genel:3"]).unwrap();
    assert_eq!(at_controller.input_names()[1], "cut genel scalar filter 3 at abstract node 1 (injected) [-]");
    let link = full_frequency_response(at_link.dae(), &freqs);
    let controller = full_frequency_response(at_controller.dae(), &freqs);
    for k in 0..freqs.len() {
        let s = s_of(freqs[k]);
        let (p, c) = (PID_MASS.p(s), PID_MASS.c(s));
        let one = c64::new(1.0, 0.0);
        // Source: the closed forms, x/f = P/(1 + P C), u/f = T = P C/(1 + P C); 1e-8.
        let (sensitivity, t) = (p / (one + p * c), p * c / (one + p * c));
        for (h, what) in [(&full[k], "full"), (&reduced[k], "ROM")] {
            assert_close(h[(0, 0)], sensitivity, 1e-8, &format!("{what} x/f at {} Hz", freqs[k]));
            assert_close(h[(1, 0)], t, 1e-8, &format!("{what} T at {} Hz", freqs[k]));
        }
        // The cut models' pieces closed again (P, C and L from the same file): 1e-8.
        let (pp, pc) = (link[k][(0, 0)], link[k][(1, 0)]);
        assert_close(reduced[k][(1, 0)], pc / (one + pc), 1e-8, &format!("T from the cut's P C at {} Hz", freqs[k]));
        assert_close(reduced[k][(0, 0)], pp / (one + pc), 1e-8, &format!("S P from the cut's pieces at {} Hz", freqs[k]));
        for (h, what) in [(&link[k], "link"), (&controller[k], "controller")] {
            assert_close(closed_from_cut(h, 0), full[k][(0, 0)], 1e-8, &format!("x/f closed at the {what} at {} Hz", freqs[k]));
            assert_close(closed_from_cut(h, 1), full[k][(1, 0)], 1e-8, &format!("u/f closed at the {what} at {} Hz", freqs[k]));
        }
        // Cut at the controller's input the returned signal is the measured x, and the loop is the same.
        assert_close(-controller[k][(2, 1)], p * c, 1e-8, &format!("L at the controller at {} Hz", freqs[k]));
    }
}

/// examples/pid_two_mass.mbd's plant and controller.
fn two_mass() -> ([f64; 5], f64, [f64; 3], [f64; 3]) {
    let (m1, m2, k1, c1, k12, c2) = (1.0, 0.5, 20.0, 2.0, 200.0, 0.1);
    let (kp, ki, kd, tau) = (10.0, 10.0, 1.0, 0.005);
    let d = product(&[m1, c1, k1 + k12], &[m2, c2, k12]);
    let den = [d[0], d[1], d[2], d[3], d[4] - k12 * k12];
    (den, k12, [(kp * tau + kd) / tau, (kp + ki * tau) / tau, ki / tau], [1.0, 1.0 / tau, 0.0])
}

#[test]
fn worked_example_flexible_drive_closed_loop_from_its_plant_and_controller() {
    let (den, k12, num_c, den_c) = two_mass();
    let ports = (&["1:abstract"][..], &["2:abstract", "3:abstract"][..]);
    let plant = study("pid_two_mass.mbd", ports.0, ports.1, &["genel:5"]).unwrap_or_else(|e| panic!("{e}"));
    // Plant poles: the roots of its quartic (closed form, nalgebra), and the controller's −1/τ.
    let mut want = roots(&den);
    want.push(c64::new(-200.0, 0.0));
    assert_same_roots(&dynamic_eigenvalues(&plant), &want, 1e-8);
    // Closed-loop poles: the roots of den·den_C + K12·num_C (closed form), 1e-8.
    let closed = study("pid_two_mass.mbd", ports.0, ports.1, &[]).unwrap_or_else(|e| panic!("{e}"));
    let characteristic: Vec<f64> = {
        let a = product(&den, &den_c);
        let b = product(&[k12], &num_c);
        let mut c = a.clone();
        let shift = a.len() - b.len();
        b.iter().enumerate().for_each(|(i, x)| c[shift + i] += x);
        c
    };
    assert_same_roots(&dynamic_eigenvalues(&closed), &roots(&characteristic), 1e-8);
    let freqs = grid();
    let rom = closed.reduce(&RomRequest::new(ModeSelection::band(0.0, 1000.0).unwrap())).unwrap_or_else(|e| panic!("{e}"));
    let reduced = rom.ordinary.frequency_response(&freqs);
    let open = full_frequency_response(plant.dae(), &freqs);
    let one = c64::new(1.0, 0.0);
    for k in 0..freqs.len() {
        let s = s_of(freqs[k]);
        let (p, c) = (c64::new(k12, 0.0) / poly(&den, s), poly(&num_c, s) / poly(&den_c, s));
        // The cut gives P (x2 per motor force) and L = P C (closed forms), 1e-8.
        assert_close(open[k][(0, 0)], p, 1e-8, &format!("P at {} Hz", freqs[k]));
        assert_close(-open[k][(2, 1)], p * c, 1e-8, &format!("L at {} Hz", freqs[k]));
        // The closed loop's ROM: u/d = T = P C/(1 + P C) from the cut's P and C, 1e-8.
        let (pp, pc) = (open[k][(0, 0)], open[k][(1, 0)]);
        assert_close(reduced[k][(1, 0)], pc / (one + pc), 1e-8, &format!("T at {} Hz", freqs[k]));
        assert_close(reduced[k][(0, 0)], pp / (one + pc), 1e-8, &format!("x2/d at {} Hz", freqs[k]));
    }
}

#[test]
fn cuts_that_cannot_be_made_are_refused_with_the_option() {
    let refused = |cuts: &[&str]| match study("pid_mass.mbd", &["1:abstract"], &["1:abstract"], cuts) {
        Err(StudyError::Option { option: Setting::Cut, message }) => message,
        Err(e) => panic!("{cuts:?}: refused for another reason: {e}"),
        Ok(_) => panic!("{cuts:?} was not refused"),
    };
    assert_eq!(refused(&["genel:9"]), "genel:9: the model has no genel 9 (a cut names a genel or an abstract force by its label)");
    assert_eq!(refused(&["force:1"]), "force:1: abstract force 1 does not depend on the state at the reference (its value is a function of time): no loop passes through it");
    assert_eq!(refused(&["genel:1"]), "genel:1: genel mass 1 reads no scalar node other than those whose equations it writes: it is part of a node's dynamics, not a link to cut");
    assert_eq!(refused(&["genel:4", "genel:4"]), "genel:4: named twice");
    // A structural force is not a cut: the cantilever's tip force (force 301).
    let cantilever = romdyn::input::mbdyn::read_model(&example("cantilever.mbd")).unwrap();
    let ports = Ports::from_parts(None, &[], &[], &[], &[], None, &["force:301".parse().unwrap()]).unwrap();
    match Study::builder(StudySource::model(cantilever.model, cantilever.problem)).ports(ports).build() {
        Err(StudyError::Option { option: Setting::Cut, message }) => assert!(message.starts_with("force:301: force 301 is an absolute force: a cut takes a genel or an abstract force"), "{message}"),
        other => panic!("a structural force was cut: {:?}", other.err().map(|e| e.to_string())),
    }
    // Syntax: the family and the label.
    assert_eq!("joint:3".parse::<Cut>().unwrap_err(), "'joint:3': expected genel:LABEL or force:LABEL (a genel or an abstract force of the model)");
    assert_eq!("genel:x".parse::<Cut>().unwrap_err(), "'genel:x': expected genel:LABEL or force:LABEL (a genel or an abstract force of the model)");
}

#[test]
fn the_dense_and_sparse_cuts_are_the_same_and_ports_go_before_the_last() {
    // The dense route (a study with springs removed or imposed motion) cuts the dense
    // linearization: the same matrices as the sparse cut, entry for entry, and the cut's ports
    // inserted before the last `last` ports (an imposed motion's, which stay last).
    let m = romdyn::input::mbdyn::read_model(&example("pid_mass.mbd")).unwrap();
    let asm = romdyn::dae::Assembler::new(&m.model);
    let state = romdyn::dae::State::initial(&m.model, &asm.dofs);
    let inputs: Vec<_> = ["1:abstract", "2:abstract"].map(|s| s.parse::<NodeInput>().unwrap().port()).to_vec();
    let outputs: Vec<_> = ["1:abstract", "2:abstract_rate"].map(|s| s.parse::<NodeOutput>().unwrap().port()).to_vec();
    let parts = romdyn::dae::cut_parts(&m.model, &state, &["genel:4".parse().unwrap(), "genel:3".parse().unwrap()]).unwrap();
    let mut dense = romdyn::dae::linearize_ports(&m.model, &state, &inputs, &outputs, None).unwrap();
    let mut sparse = romdyn::dae::linearize_sparse(&m.model, &state, &inputs, &outputs).unwrap();
    for p in &parts {
        p.cut_dense(&mut dense, 1);
        p.cut_sparse(&mut sparse);
    }
    assert_eq!(dense.input_names, ["abstract node 1 [-]", "cut genel cross spring support 4 at abstract node 1 (injected) [-]", "cut genel scalar filter 3 at abstract node 1 (injected) [-]", "abstract node 2 [-]"]);
    assert_eq!(dense.output_names[3], "abstract node 2 rate [1/s]");
    assert_eq!(sparse.input_names[3], "cut genel scalar filter 3 at abstract node 1 (injected) [-]");
    let (fyd, fy) = dense.jacobians.derivatives();
    let same = |a: &Mat<f64>, b: &Mat<f64>| a.nrows() == b.nrows() && a.ncols() == b.ncols() && (0..a.nrows()).all(|i| (0..a.ncols()).all(|j| a[(i, j)] == b[(i, j)]));
    assert!(same(&fyd, &sparse.fyd.to_dense()) && same(&fy, &sparse.fy.to_dense()));
    // Columns and rows moved by the insertion: dense's [0, 2, 3, 1] are sparse's [0, 1, 2, 3].
    let order = [0, 2, 3, 1];
    for (d, s) in order.iter().enumerate() {
        assert!((0..dense.b.nrows()).all(|i| dense.b[(i, d)] == sparse.b[(i, *s)]), "input {d}");
        assert!((0..dense.c.ncols()).all(|j| dense.c[(d, j)] == sparse.c[(*s, j)]), "output {d}");
        let (rd, rs) = (dense.c_rate.as_ref().unwrap(), sparse.c_rate.as_ref().unwrap());
        assert!((0..rd.ncols()).all(|j| rd[(d, j)] == rs[(*s, j)]), "rate output {d}");
    }
}
