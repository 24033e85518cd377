//! Repeated roots with a single vector (issue 30: "an eigenvalue whose estimate exceeds its
//! own size is never labelled dynamic", and no label may be silently wrong). A critically
//! damped mode (ζ = 1 exactly) is a double root of `m λ² + c λ + k` with one eigenvector:
//! first-order error estimates say nothing there, the computed vectors can be orthogonal
//! through `F_yd` or not finite at all, and a modal ROM cannot represent the mode. Before,
//! the −2 rad/s double root of m = 1 kg, c = 4 N s/m, k = 4 N/m was listed "infinite" with no
//! warning whenever the Λ form's dCoef put it at Λ = 0 exactly (`c = 1/2 s`, eq. 23).

use faer::Mat;
use romdyn::eigen::ModeKind;
use romdyn::linear::{Jacobians, LinearDae};
use romdyn::analysis::Reference;
use romdyn::rom::ModeSelection;
use romdyn::study::{EigenSettings, StudySource, RomRequest, Study, Warning};

/// Every mode near `root` is either labelled dynamic with an honest error (|λ − root| within
/// its estimate, the closed form being `root`), or listed in the study's warning about
/// unresolved eigenvalues; returns how many were listed.
fn assert_honest(study: &Study, root: f64, what: &str) -> usize {
    let listed: Vec<usize> = study
        .warnings()
        .iter()
        .flat_map(|w| match w {
            Warning::UnresolvedEigenvalues { modes } => modes.iter().map(|m| m.0).collect(),
            _ => Vec::new(),
        })
        .collect();
    let mut near = 0;
    for (i, m) in study.modal().modes.iter().enumerate() {
        if !((m.lambda.re - root).abs() < 1e-3 * root.abs() && m.lambda.im.abs() < 1e-3 * root.abs()) {
            continue;
        }
        near += 1;
        if m.kind == ModeKind::Dynamic {
            let off = (m.lambda - faer::c64::new(root, 0.0)).norm();
            assert!(off <= m.error, "{what}: mode {} λ = {} labelled dynamic, {off:.2e} from the closed form {root} with error estimate {:.2e}", i + 1, m.lambda, m.error);
        } else {
            assert!(m.lambda.im < 0.0 || listed.contains(&(i + 1)), "{what}: mode {} λ = {} labelled {} without a warning; warnings {:?}", i + 1, m.lambda, m.kind.name(), study.warnings());
        }
    }
    assert_eq!(near, 2, "{what}: the double root {root} should be found twice");
    listed.len()
}

/// The 2 x 2 first-order form of the oscillator `m ẍ + c ẋ + k x = 0`, unknowns (x, v).
fn oscillator(m: f64, c: f64, k: f64) -> LinearDae {
    let fyd = Mat::from_fn(2, 2, |i, j| match (i, j) {
        (0, 0) => 1.0,
        (1, 1) => m,
        _ => 0.0,
    });
    let fy = Mat::from_fn(2, 2, |i, j| match (i, j) {
        (0, 1) => -1.0,
        (1, 0) => k,
        (1, 1) => c,
        _ => 0.0,
    });
    let names = |p: &str| (0..2).map(|i| format!("{p}{i}")).collect::<Vec<_>>();
    // Input: a force on the mass; output: its displacement.
    let b = Mat::from_fn(2, 1, |i, _| if i == 1 { 1.0 } else { 0.0 });
    let c = Mat::from_fn(1, 2, |_, j| if j == 0 { 1.0 } else { 0.0 });
    LinearDae { jacobians: Jacobians::Derivatives { fyd, fy }, b, c, unknown_names: names("y"), input_names: vec!["f".into()], output_names: vec!["x".into()], constraint_form: None, multipliers: Vec::new(), c_rate: None }
}

/// The critically damped oscillator at several dCoefs, including 1/2 s, which maps the
/// root to Λ = 0 exactly (the computed vectors are then orthogonal through F_yd or not
/// finite), and a Jordan block already in triangular form (its vectors are not finite).
/// Closed form: λ = −c/(2m) = −2 rad/s, twice.
#[test]
fn a_critically_damped_root_is_honest_or_warned() {
    for dcoef in [None, Some(0.5), Some(0.1), Some(3.0)] {
        let settings = EigenSettings { dcoef, ..EigenSettings::default() };
        let study = Study::builder(StudySource::dae(oscillator(1.0, 4.0, 4.0))).eigen(settings).build().unwrap();
        assert_honest(&study, -2.0, &format!("oscillator, dCoef {dcoef:?}"));
    }
    // The Λ form at c = 1/2 s puts the root at Λ = 0 exactly: its value is exact, but its
    // vectors are orthogonal through F_yd, so a ROM keeping it must say it cannot use it.
    let exact = Study::builder(StudySource::dae(oscillator(1.0, 4.0, 4.0))).eigen(EigenSettings { dcoef: Some(0.5), ..EigenSettings::default() }).build().unwrap();
    let unresolved = assert_honest(&exact, -2.0, "dCoef 1/2 s");
    match exact.reduce(&RomRequest::new(ModeSelection::Lowest(2))) {
        Ok(rom) => assert!(unresolved > 0 || rom.warnings.iter().any(|w| matches!(w, Warning::Unscaled { .. })), "a ROM of the exactly defective root warns nothing: {:?}", rom.warnings),
        // Refusing is honest too: the projection of the two parallel modes is singular, and
        // the error says which modes and why.
        Err(e) => assert!(e.to_string().contains("kept mode(s) 1, 2 have left and right vectors orthogonal") && e.to_string().contains("critically damped"), "{e}"),
    }
    // λ I − J with J the Jordan block [[−3, 1], [0, −3]]: triangular already.
    let jordan = LinearDae {
        jacobians: Jacobians::Derivatives { fyd: Mat::identity(2, 2), fy: Mat::from_fn(2, 2, |i, j| if i == j { 3.0 } else if (i, j) == (0, 1) { -1.0 } else { 0.0 }) },
        ..oscillator(1.0, 4.0, 4.0)
    };
    for dcoef in [None, Some(1.0 / 3.0), Some(0.2)] {
        let study = Study::builder(StudySource::dae(jordan.clone())).eigen(EigenSettings { dcoef, ..EigenSettings::default() }).build().unwrap();
        assert_honest(&study, -3.0, &format!("Jordan block, dCoef {dcoef:?}"));
    }
}

/// The same class in an MBDyn model, through the deflated route that picks its own dCoef
/// (`c = 1/ω̄`, the geometric mean of the moduli): a 1 kg body on a viscoelastic
/// displacement joint, critically damped along x (k = 4 N/m, c = 4 N s/m: λ = −2 rad/s
/// twice), lightly damped along y and z, its rotations held by a viscoelastic hinge.
#[test]
fn a_critically_damped_body_is_honest_or_warned() {
    let dir = std::env::temp_dir().join(format!("romdyn-defective-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("critical.mbd");
    std::fs::write(
        &file,
        "begin: data; problem: initial value; end: data;
begin: initial value; initial time: 0.; final time: 1.; time step: 1.e-2; end: initial value;
begin: control data; structural nodes: 2; rigid bodies: 1; joints: 3; end: control data;
begin: nodes;
    structural: 1, static, null, eye, null, null;
    structural: 2, dynamic, null, eye, null, null;
end: nodes;
begin: elements;
    joint: 1, clamp, 1, node, node;
    joint: 2, deformable displacement joint, 1, null, 2, null,
        linear viscoelastic generic, diag, 4., 9., 16., diag, 4., 0.6, 0.8;
    joint: 3, deformable hinge, 1, null, 2, null,
        linear viscoelastic generic, diag, 25., 25., 25., diag, 1., 1., 1.;
    body: 2, 2, 1., null, diag, 1., 1., 1.;
end: elements;
",
    )
    .unwrap();
    for dcoef in [None, Some(0.5)] {
        let study = Study::builder(StudySource::model_file(&file)).reference(Reference::Initial).node_ports(vec!["2:Fx".parse().unwrap()], vec!["2:x".parse().unwrap()]).eigen(EigenSettings { dcoef, ..EigenSettings::default() }).build().unwrap();
        assert_honest(&study, -2.0, &format!("critically damped body, dCoef {dcoef:?}"));
        // The lightly damped y mode is resolved and dynamic: λ = −0.3 ± j √(9 − 0.09) rad/s.
        let y = study.modal().modes.iter().find(|m| m.kind == ModeKind::Dynamic && (m.lambda.im - (9.0f64 - 0.09).sqrt()).abs() < 1e-8).expect("the y mode");
        assert!((y.lambda.re + 0.3).abs() < 1e-8, "{}", y.lambda);
    }
    std::fs::remove_dir_all(&dir).ok();
}
