//! FEM node displacements and velocities as ROM outputs (issue 35 point 2, sensors on a
//! flexible body): `--fem-output JOINT:FEM_NODE:x|…|vz`, the ports file's `"fem
//! displacement"`/`"fem velocity"`, the point `x + R (f₀ + Σₖ Φₖ qₖ)` linearized. Checked on
//! the CMS round trip of tests/mbdyn/cms_round_trip.rs (a clamped component: its FEM nodes
//! against the whole beam's nodes at the same points) and on a floating body
//! (tests/mbdyn_files/modal_floating_force.mbd: the rigid motion against a rigid point of
//! the modal node, the modal part against the FEM file's shapes turned by the node's frame).

use crate::common;

use common::mbdyn::test_file;
use faer::{c64, Mat};
use romdyn::analysis::Reference;
use romdyn::cms::{craig_bampton, CmsRequest};
use romdyn::dae::ports::{Direction, Measurement, OutputPort, Point};
use romdyn::dae::{FemOutput, NodeInput, NodeOutput};
use romdyn::kinematics::{Mat3, Vec3};
use romdyn::study::{Application, Ports, Study, StudySource};

fn parse<T: std::str::FromStr>(list: &[&str]) -> Vec<T>
where
    T::Err: std::fmt::Display,
{
    list.iter().map(|s| s.parse().unwrap_or_else(|e| panic!("{s}: {e}"))).collect()
}

fn study(path: &std::path::Path, inputs: &[&str], outputs: &[&str], fem: &[&str]) -> Study {
    let ports = Ports::from_parts(None, &parse::<NodeInput>(inputs), &parse::<NodeOutput>(outputs), &parse::<FemOutput>(fem), &[], None, &[]).unwrap_or_else(|e| panic!("{e}"));
    Study::builder(StudySource::model_file(path)).ports(ports).build().unwrap_or_else(|e| panic!("{e}"))
}

/// The cantilever's outer half reduced with `n` fixed-interface modes and reattached
/// (tests/mbdyn_files/cms_reduced.mbd), with the given FEM node outputs.
fn reduced(dir: &std::path::Path, n: usize, fem: &[&str]) -> Study {
    let sub = common::mbdyn::read_test_file("cms_substructure.mbd");
    let request = CmsRequest { interfaces: vec![9], modes: n, reference: Reference::Initial };
    let cb = craig_bampton(&sub.model, &sub.problem, &request).unwrap_or_else(|e| panic!("{e}"));
    cb.write(&dir.join("cms_substructure.fem"), "cms_substructure.mbd").unwrap_or_else(|e| panic!("{e}"));
    let text = std::fs::read_to_string(test_file("cms_reduced.mbd")).unwrap().replace("set: ifndef integer MODES = 10;", &format!("set: integer MODES = {};", n + 6));
    let path = common::cli::write_file(dir, "cms_reduced.mbd", &text);
    study(std::path::Path::new(&path), &["9:Fy", "9:Fz"], &[], fem)
}

fn largest_relative(a: &Mat<c64>, b: &Mat<c64>) -> f64 {
    let scale = (0..b.nrows()).flat_map(|i| (0..b.ncols()).map(move |j| (i, j))).map(|(i, j)| b[(i, j)].norm()).fold(0.0, f64::max);
    (0..b.nrows()).flat_map(|i| (0..b.ncols()).map(move |j| (i, j))).map(|(i, j)| (a[(i, j)] - b[(i, j)]).norm() / scale).fold(0.0, f64::max)
}

#[test]
fn a_clamped_components_fem_nodes_move_as_the_whole_beams_nodes() {
    let dir = common::cli::temp_dir("fem-node-outputs");
    // The whole cantilever: nodes 17 (tip) and 13 (mid-span of the outer half), forces at
    // node 9 (the interface, a multibody node of both models).
    let full = study(&test_file("cms_cantilever.mbd"), &["9:Fy", "9:Fz"], &["17:y", "17:z", "13:y"], &[]);
    let every = reduced(&dir, 48, &["200:17:y", "200:17:z", "200:13:y"]);
    assert_eq!(every.output_names()[0], "modal 200 FEM node 17 y [m]");
    let freqs = [0.0, 5.0, 17.0, 60.0, 140.0, 400.0];
    let h_full = full.full_frequency_response(&freqs).unwrap_or_else(|e| panic!("{e}"));
    let h_every = every.full_frequency_response(&freqs).unwrap_or_else(|e| panic!("{e}"));
    // Every interior mode kept: the reduction is exact (cms_round_trip.rs: frequencies below
    // 1e-10), so the FEM nodes' responses are the beam nodes' to 1e-8 relative (largest
    // entry's scale), static gain (f = 0) included.
    for (k, f) in freqs.iter().enumerate() {
        let e = largest_relative(&h_every[k], &h_full[k]);
        assert!(e < 1e-8, "every mode, {f} Hz: {e:e}");
    }
    // 12 fixed-interface modes: the static gain of loads at the interface is exact (the
    // constraint modes are the static solution, Craig & Bampton 1968), 1e-8; below the first
    // resonance (17.6 Hz) the dynamic error is the truncation error of the dropped modes
    // (frequencies 1.2e-7 … 9.4e-5 off at N = 12, cms_round_trip.rs): measured 1.2e-7 at 5 Hz (static 4.8e-13),
    // asserted 1e-5.
    let twelve = reduced(&dir, 12, &["200:17:y", "200:17:z", "200:13:y"]);
    let h12 = twelve.full_frequency_response(&freqs[..2]).unwrap_or_else(|e| panic!("{e}"));
    let (e0, e5) = (largest_relative(&h12[0], &h_full[0]), largest_relative(&h12[1], &h_full[1]));
    eprintln!("N = 12: static {e0:.1e}, 5 Hz {e5:.1e}");
    assert!(e0 < 1e-8, "{e0:e}");
    assert!(e5 < 1e-5, "{e5:e}");
    // The lowest resonance of the FEM node's response: the peak of |tip z / Fz| on a fine grid
    // around the first bending frequency of the whole beam (110.64 rad/s = 17.609 Hz), 1 mHz
    // bins: the same bin (the frequencies differ by 1.2e-7 relative).
    let grid: Vec<f64> = (0..400).map(|k| 17.4 + 0.4 * k as f64 / 400.0).collect();
    let peak = |s: &Study| {
        let h = s.full_frequency_response(&grid).unwrap_or_else(|e| panic!("{e}"));
        let k = (0..grid.len()).max_by(|&a, &b| h[a][(1, 1)].norm().total_cmp(&h[b][(1, 1)].norm())).unwrap();
        grid[k]
    };
    let (f_full, f12) = (peak(&full), peak(&twelve));
    assert!((f_full - 110.64 / std::f64::consts::TAU).abs() < 2e-3, "{f_full}");
    assert!((f12 - f_full).abs() < 1e-9, "N = 12 peak {f12} Hz, whole beam {f_full} Hz");
}

/// `R = Rx(a) Ry(b) Rz(c)`, MBDyn's `euler123` (input manual §Orientation matrix).
fn euler123(a: f64, b: f64, c: f64) -> Mat3 {
    let rx = Mat3::new(1.0, 0.0, 0.0, 0.0, a.cos(), -a.sin(), 0.0, a.sin(), a.cos());
    let ry = Mat3::new(b.cos(), 0.0, b.sin(), 0.0, 1.0, 0.0, -b.sin(), 0.0, b.cos());
    let rz = Mat3::new(c.cos(), -c.sin(), 0.0, c.sin(), c.cos(), 0.0, 0.0, 0.0, 1.0);
    rx * ry * rz
}

#[test]
fn a_floating_bodys_fem_node_is_its_rigid_motion_plus_its_modes() {
    // modal_floating_force.mbd: modal node 1 at (0.1, −0.2, 0.3), euler123 (0.2, −0.1, 0.4),
    // origin FEM node A at 0; FEM node C at (0.3, −0.4, 0.2), its shapes (file
    // modal_point_masses.fem) (−0.3, 0.2, 0.4) and (0.2, 0.5, −0.1) per unit q1, q2. At the
    // initial reference (q = 0, at rest) C = x + R f_C: its displacement is the rigid point's
    // (x + R f_C) plus R Φ_C q.
    let r = euler123(0.2, -0.1, 0.4);
    let x = Vec3::new(0.1, -0.2, 0.3);
    let f_c = Vec3::new(0.3, -0.4, 0.2);
    let shapes = [Vec3::new(-0.3, 0.2, 0.4), Vec3::new(0.2, 0.5, -0.1)];
    let axis = |k: usize| Vec3::from_fn(|i, _| if i == k { 1.0 } else { 0.0 });
    let mut outputs: Vec<OutputPort> = Vec::new();
    for k in 0..3 {
        outputs.push(FemOutput { joint: 10, fem_node: "C".into(), component: k }.port());
        outputs.push(OutputPort { name: format!("rigid C {k}"), measurement: Measurement::Displacement { point: Point::at(1, x + r * f_c), direction: Direction::global(axis(k)) } });
        outputs.push(FemOutput { joint: 10, fem_node: "C".into(), component: 3 + k }.port());
    }
    outputs.extend(["10:q1", "10:q2"].map(|s| s.parse::<NodeOutput>().unwrap().port()));
    // FEM node B is the interface of node 2, offset (0.8, 0.1, −0.05) in node 2's frame.
    outputs.push(FemOutput { joint: 10, fem_node: "B".into(), component: 1 }.port());
    outputs.push(OutputPort { name: "node 2 point".into(), measurement: Measurement::Displacement { point: Point::offset(2, Vec3::new(0.8, 0.1, -0.05)), direction: Direction::global(axis(1)) } });
    let inputs = ["2:Fy", "2:Fz", "1:Mx"].map(|s| s.parse::<NodeInput>().unwrap().port()).to_vec();
    let app = Application { inputs, outputs, ..Default::default() };
    let s = Study::builder(StudySource::model_file(test_file("modal_floating_force.mbd"))).application(app).build().unwrap_or_else(|e| panic!("{e}"));
    let freqs = [0.7, 3.0, 11.0, 40.0];
    let h = s.full_frequency_response(&freqs).unwrap_or_else(|e| panic!("{e}"));
    for (hk, f) in h.iter().zip(freqs) {
        let w = std::f64::consts::TAU * f;
        for j in 0..3 {
            let scale = (0..hk.nrows()).map(|i| hk[(i, j)].norm()).fold(0.0, f64::max);
            for k in 0..3 {
                // Closed form: d·R Φ_C,m per unit q_m (R from the Euler angles, Φ from the file).
                let modal: c64 = (0..2).map(|m| hk[(9 + m, j)] * axis(k).dot(&(r * shapes[m]))).sum();
                let (fem, rigid, velocity) = (hk[(3 * k, j)], hk[(3 * k + 1, j)], hk[(3 * k + 2, j)]);
                // 1e-10 of the column's largest response: direct solves of a 30-odd pencil.
                assert!((fem - rigid - modal).norm() <= 1e-10 * scale, "{f} Hz, input {j}, axis {k}: {fem} vs {rigid} + {modal}");
                // At rest the velocity is jω times the displacement.
                assert!((velocity - c64::new(0.0, w) * fem).norm() <= 1e-10 * w * scale, "{f} Hz velocity: {velocity} vs jω {fem}");
            }
            // The interface: FEM node B moves with node 2's point at its offset.
            assert!((hk[(11, j)] - hk[(12, j)]).norm() <= 1e-10 * scale, "{f} Hz, B: {} vs {}", hk[(11, j)], hk[(12, j)]);
        }
    }
}

#[test]
fn fem_node_outputs_that_do_not_exist_are_refused() {
    let refused = |fem: &str| {
        let ports = Ports::from_parts(None, &[], &[], &[fem.parse().unwrap()], &[], None, &[]).unwrap();
        Study::builder(StudySource::model_file(test_file("modal_floating_force.mbd"))).ports(ports).build().err().expect("refused").to_string()
    };
    assert!(refused("10:D:y").contains("modal joint 10 has no FEM node \"D\" (its FEM nodes: A, B, C)"), "{}", refused("10:D:y"));
    assert!(refused("11:A:y").contains("modal joint 11 is not defined"), "{}", refused("11:A:y"));
    let syntax = "10:A:q".parse::<FemOutput>().unwrap_err().to_string();
    assert_eq!(syntax, "'10:A:q': expected JOINT:FEM_NODE:COMPONENT with COMPONENT one of x|y|z|vx|vy|vz|rx|ry|rz (JOINT a modal joint's label, FEM_NODE a node label of its FEM file)");
    let file = |text: &str| romdyn::input::ports_file::parse_ports(text, "p.json".as_ref());
    let p = file(r#"{"outputs": [{"name": "tip", "type": "fem displacement", "joint": 200, "fem_node": "17", "direction": [0, 1, 0]}, {"type": "fem velocity", "joint": 200, "fem_node": "17", "direction": [0, 1, 0]}]}"#).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(p.outputs[0].label(), "tip [m]");
    assert_eq!(p.outputs[1].label(), "output 2 [m/s]");
    assert_eq!(p.outputs[0].measurement, "200:17:y".parse::<FemOutput>().unwrap().port().measurement);
    let e = file(r#"{"outputs": [{"type": "fem displacement", "joint": 200, "direction": [0, 1, 0]}]}"#).unwrap_err().to_string();
    assert!(e.contains("needs \"fem_node\""), "{e}");
    let e = file(r#"{"outputs": [{"type": "displacement", "node": 2, "fem_node": "17", "direction": [0, 1, 0]}]}"#).unwrap_err().to_string();
    assert!(e.contains("\"fem_node\" belongs to 'fem displacement', 'fem velocity' and 'fem rotation' outputs"), "{e}");
}

#[test]
fn a_moving_fem_nodes_velocity_row_is_the_derivative_of_its_velocity() {
    // modal_floating_force.mbd at t = 0.5 s of its run (the body translating, turning and
    // vibrating: ω, q, q̇ not zero): the rows of C̃ and C̃_v of FEM node C's displacement and
    // velocity against central differences of p = x + R (f₀ + Φ q) and
    // ṗ = ẋ + ω × R (f₀ + Φ q) + R Φ q̇ in the unknowns and their rates (the node's kinematics
    // from the state as the linearization reads them).
    let mut outputs = Vec::new();
    for k in 0..3 {
        outputs.push(FemOutput { joint: 10, fem_node: "C".into(), component: k }.port());
        outputs.push(FemOutput { joint: 10, fem_node: "C".into(), component: 3 + k }.port());
    }
    let Moving { study: s, dofs, base, q_first, node } = moving(outputs);
    let f_c = Vec3::new(0.3, -0.4, 0.2);
    let shapes = [Vec3::new(-0.3, 0.2, 0.4), Vec3::new(0.2, 0.5, -0.1)];
    let point = |st: &romdyn::dae::State| {
        let kin = st.node_frame(&dofs, node).kin;
        let local = f_c + shapes[0] * st.y[q_first] + shapes[1] * st.y[q_first + 1];
        let rate = shapes[0] * st.yp[q_first] + shapes[1] * st.yp[q_first + 1];
        (kin.x + kin.r * local, kin.xdot + kin.omega.cross(&(kin.r * local)) + kin.r * rate)
    };
    let kin = base.node_frame(&dofs, node).kin;
    assert!(kin.omega.norm() > 1e-3 && base.yp[q_first].abs() > 1e-6, "the reference moves: ω {}, q̇1 {}", kin.omega, base.yp[q_first]);
    let dae = s.dae();
    let c_rate = dae.c_rate.as_ref().unwrap();
    let h = 1e-6;
    let mut worst: f64 = 0.0;
    for j in 0..dofs.len {
        for rate in [false, true] {
            let shifted = |sign: f64| {
                let mut st = base.clone();
                if rate { st.yp[j] += sign * h } else { st.y[j] += sign * h }
                point(&st)
            };
            let ((p1, v1), (p0, v0)) = (shifted(1.0), shifted(-1.0));
            let (dp, dv) = ((p1 - p0) / (2.0 * h), (v1 - v0) / (2.0 * h));
            for k in 0..3 {
                let (row_p, row_v) = (2 * k, 2 * k + 1);
                let (got_p, got_v) = if rate { (c_rate[(row_p, j)], c_rate[(row_v, j)]) } else { (dae.c[(row_p, j)], dae.c[(row_v, j)]) };
                worst = worst.max((got_p - dp[k]).abs()).max((got_v - dv[k]).abs());
            }
        }
    }
    // Central differences of smooth functions with h = 1e-6 on entries of order 1: 1e-7.
    eprintln!("largest difference of the rows from central differences: {worst:.1e}");
    assert!(worst < 1e-7, "{worst:e}");
}

#[test]
fn a_moving_fem_nodes_rotation_row_is_the_derivative_of_its_orientation() {
    // modal_floating_force.mbd at t = 0.5 s (the body turning and vibrating, q ≠ 0): the rows
    // of C̃ of FEM node C's rotation about x, y, z against central differences of the rotation
    // vector of R_C(y) R_C(y₀)ᵀ, R_C = R exp([ψ×]), ψ = Σₖ Φrₖ qₖ with the rotational shapes
    // of modal_point_masses.fem (node C: (−0.2, 0.4, 0.1) and (0.3, 0.2, −0.4) rad per unit
    // q), R the modal node's frame from the state as the linearization reads it.
    let outputs = (6..9).map(|k| FemOutput { joint: 10, fem_node: "C".into(), component: k }.port()).collect();
    let Moving { study: s, dofs, base, q_first, node } = moving(outputs);
    assert_eq!(s.output_names()[0], "modal 10 FEM node C rx [rad]");
    let shapes = [Vec3::new(-0.2, 0.4, 0.1), Vec3::new(0.3, 0.2, -0.4)];
    let orientation = |st: &romdyn::dae::State| {
        let psi = shapes[0] * st.y[q_first] + shapes[1] * st.y[q_first + 1];
        st.node_frame(&dofs, node).kin.r * nalgebra::Rotation3::new(psi).into_inner()
    };
    let r0 = orientation(&base);
    assert!(base.y[q_first].abs() > 1e-6 && base.node_frame(&dofs, node).kin.omega.norm() > 1e-3, "the reference moves and is deformed");
    let dae = s.dae();
    let h = 1e-6;
    let mut worst: f64 = 0.0;
    for j in 0..dofs.len {
        let turned = |sign: f64| {
            let mut st = base.clone();
            st.y[j] += sign * h;
            romdyn::kinematics::rotation_vector(&(orientation(&st) * r0.transpose()))
        };
        let d = (turned(1.0) - turned(-1.0)) / (2.0 * h);
        for k in 0..3 {
            worst = worst.max((dae.c[(k, j)] - d[k]).abs());
        }
    }
    // Central differences of smooth functions with h = 1e-6 on entries of order 1: 1e-7.
    eprintln!("largest difference of the rotation rows from central differences: {worst:.1e}");
    assert!(worst < 1e-7, "{worst:e}");
}

#[test]
fn a_clamped_components_fem_node_turns_as_the_whole_beams_node() {
    // The CMS round trip with every interior mode kept (exact, as the translations above):
    // FEM node 17's and 13's rotations about y and z against the whole cantilever's nodes 17
    // and 13 (beam node rotations), 1e-8 relative on the largest entry, 0 to 400 Hz.
    let dir = common::cli::temp_dir("fem-node-rotations");
    let full = study(&test_file("cms_cantilever.mbd"), &["9:Fy", "9:Fz"], &["17:ry", "17:rz", "13:rz"], &[]);
    let every = reduced(&dir, 48, &["200:17:ry", "200:17:rz", "200:13:rz"]);
    let freqs = [0.0, 5.0, 17.0, 60.0, 140.0, 400.0];
    let h_full = full.full_frequency_response(&freqs).unwrap_or_else(|e| panic!("{e}"));
    let h_every = every.full_frequency_response(&freqs).unwrap_or_else(|e| panic!("{e}"));
    for (k, f) in freqs.iter().enumerate() {
        let scale = (0..3).flat_map(|i| (0..2).map(move |j| (i, j))).map(|(i, j)| h_full[k][(i, j)].norm()).fold(0.0, f64::max);
        assert!(scale > 0.0, "{f} Hz: the beam does not turn");
        let e = largest_relative(&h_every[k], &h_full[k]);
        assert!(e < 1e-8, "every mode, {f} Hz: {e:e}");
    }
}

/// modal_floating_force.mbd at t = 0.5 s of its run with `outputs`, and what central
/// differences of its FEM nodes read: the unknowns' numbering, the reference in the
/// linearization form, the joint's first modal coordinate (after its 6 interface
/// multipliers) and the modal node's index.
struct Moving {
    study: Study,
    dofs: romdyn::dae::DofMap,
    base: romdyn::dae::State,
    q_first: usize,
    node: usize,
}

fn moving(outputs: Vec<OutputPort>) -> Moving {
    let app = Application { outputs, ..Default::default() };
    let study = Study::builder(StudySource::model_file(test_file("modal_floating_force.mbd"))).reference(Reference::At(0.5)).application(app).build().unwrap_or_else(|e| panic!("{e}"));
    let model = study.model().unwrap();
    let dofs = romdyn::dae::DofMap::new(model);
    let mut base = study.reference_state().unwrap().clone();
    base.linearization_base(&dofs);
    let modal = model.elements.iter().position(|e| e.type_name() == "modal").unwrap();
    let (q_first, node) = (dofs.element_first[modal] + 6, model.node_index(1).unwrap());
    Moving { study, dofs, base, q_first, node }
}
