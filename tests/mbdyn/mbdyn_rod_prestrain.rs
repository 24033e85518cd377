//! Rods whose prestrain is a drive (MBDyn's 1-D template drive caller after `prestrain`;
//! issue 12, point 3): `tests/mbdyn_files/rod_prestrain.mbd` against closed forms and MBDyn
//! 1.7.3, the rods' Jacobians against finite differences, and the 1-D syntax as MBDyn's
//! reader takes it.

use crate::common;

use common::mbdyn::{assert_jacobians_after_run, read_test_file, test_file as path};
use romdyn::analysis::run;
use romdyn::dae::Assembler;
use romdyn::input::mbdyn::{build, parse_text, read_model};

#[test]
fn driven_prestrain_gives_the_closed_forms_and_mbdyns_motion() {
    let m = read_model(&path("rod_prestrain.mbd")).unwrap_or_else(|e| panic!("{e}"));
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let kin = |k: usize| report.final_state.node_frame(&asm.dofs, k).kin;
    // Node 2 (file header): z = 1 − a + a r cos(W t) + a (1 − r) cos(w t), r = w²/(w² − W²),
    // a = 0.25, W = 2 rad/s, w = 20 rad/s, at t = 1 s; node 3 at rest at 3.1 m; node 4 held
    // at 5 m by a prestrain that cancels the pull 2 t N.
    let (a, big_w, w, t): (f64, f64, f64, f64) = (0.25, 2.0, 20.0, 1.0);
    let r = w * w / (w * w - big_w * big_w);
    let z2 = 1.0 - a + a * r * (big_w * t).cos() + a * (1.0 - r) * (w * t).cos();
    let v2 = -a * r * big_w * (big_w * t).sin() - a * (1.0 - r) * w * (w * t).sin();
    // MBDyn 1.7.3 (built from github:alex-marinov/mbdyn, 1727489e) on this file, `output
    // precision: 16`, last row of its .mov.
    let cases = [
        ("node 2 z", kin(1).x[2], z2, 6.4388007928160751e-01),
        ("node 2 vz", kin(1).xdot[2], v2, -4.1314928383778948e-01),
        ("node 3 z", kin(2).x[2], 3.1, 3.1000000000000001e+00),
        ("node 4 z", kin(3).x[2], 5.0, 5.0),
    ];
    for (what, x, exact, mbdyn) in cases {
        eprintln!("{what}: {x:.15e}, closed form {exact:.15e}, MBDyn {mbdyn:.15e}");
        // ms with ρ∞ = 0.6, h = 1 ms on a 20 rad/s oscillation: measured 1.8e-6 m off in z,
        // 1.7e-5 m/s in velocity (w times it); 1e-5 of the amplitude 0.25 m, 5 m/s.
        let scale = if what.contains('v') { 5.0 } else { 0.25 };
        assert!((x - exact).abs() < 1e-5 * scale, "{what}: {x} against the closed form {exact}");
        // Same method and steps, the same Newton iterations (1000 in all) as MBDyn: measured
        // to 1e-13; 1e-10 of the amplitude.
        assert!((x - mbdyn).abs() < 1e-10 * scale, "{what}: {x} against MBDyn {mbdyn}");
    }
    // MBDyn 1.7.3's .out: 1000 iterations over its 1001 "Step" rows, step by step as romdyn's.
    assert_eq!(report.newton_iterations + report.derivatives_iterations, 1000);
}

#[test]
fn prestrained_rod_jacobians_match_finite_differences() {
    let checks = assert_jacobians_after_run(&mut read_test_file("rod_prestrain.mbd"), Some(0.3), 1e-3);
    let rods: Vec<_> = checks.iter().filter(|c| c.element.starts_with("rod")).collect();
    assert_eq!(rods.len(), 3, "{checks:?}");
    // The state-reading prestrain of rod 4 is held (as MBDyn's Jacobian holds it).
    assert!(rods.iter().any(|c| c.drive_held) && rods.iter().any(|c| !c.drive_held), "{rods:?}");
}

#[test]
fn one_dimensional_prestrain_is_read_as_mbdyns_reader_reads_it() {
    let base = std::fs::read_to_string(path("rod_prestrain.mbd")).unwrap();
    let read = |t: &str| parse_text(t, &path("rod_prestrain.mbd")).and_then(|d| build(&d)).map_err(|e| e.to_string());
    // MBDyn 1.7.3's 1-D template drive takes no value before the drive (SingleTDCR<doublereal>):
    // `single, .1, const, 1.` reads `.1` as the drive and stops on the rest, as romdyn.
    let e = read(&base.replace("prestrain, single, const, .1;", "prestrain, single, .1, const, 1.;")).err().unwrap();
    let line = base.lines().position(|l| l.contains("prestrain, single, const, .1;")).unwrap() + 1;
    assert!(e.contains(&format!("rod_prestrain.mbd:{line}:")) && e.contains("unexpected extra argument 'const'"), "{e}");
    // `component`, a plain drive, `null` and `array` are the other forms.
    for form in ["component, const, .1", "const, .1", ".1", "array, 2, const, .05, const, .05"] {
        let m = read(&base.replace("single, const, .1", form)).unwrap_or_else(|e| panic!("{form}: {e}"));
        assert_eq!(m.model.elements.len(), 8, "{form}");
    }
    // An `array`'s items are drive callers, not template drive callers (tpldrive_impl.cc
    // `ArrayTDCR::Read`: `GetT`, which reads nothing in 1-D, then `GetDriveCaller`): MBDyn
    // 1.7.3 stops on `single` there ("var \"single\" not found"), and so does romdyn.
    let e = read(&base.replace("single, const, .1", "array, 2, const, .05, single, const, .05")).err().unwrap();
    assert!(e.contains(&format!("rod_prestrain.mbd:{line}:")) && e.contains("found 'single'"), "{e}");
    // A time-varying prestrain elsewhere is refused by name.
    let e = read(&base.replace("joint: 1, clamp, 1, node, node;", "joint: 1, deformable axial joint, 1, null, 2, null, linear elastic, 1., prestrain, cosine, 0., 2., -.25, forever, 0.;")).err().unwrap();
    assert!(e.contains("time-varying prestrain is supported by romdyn on rods only"), "{e}");
}

#[test]
fn a_one_dimensional_reference_names_a_template_card_not_a_drive_caller() {
    // mbpar.cc `GetTplDriveCaller`: `reference, LABEL` in a template drive caller copies the
    // `template drive caller:` card of that dimension. Here label 5 names both a dimension-1
    // card (0.1) and a drive caller card (0.7): MBDyn 1.7.3 on this text keeps node 3 at rest
    // at z = 3.1000000000000001 (the closed form of the file's header, prestrain 0.1); romdyn
    // took the drive caller before, and node 3 ended at 3.4547 m with no message.
    let base = std::fs::read_to_string(path("rod_prestrain.mbd")).unwrap();
    let text = base
        .replacen("begin: elements;\n", "template drive caller: 5, 1, const, .1;\ndrive caller: 5, const, .7;\n\nbegin: elements;\n", 1)
        .replace("prestrain, single, const, .1;", "prestrain, reference, 5;");
    assert!(text.contains("reference, 5;") && text.contains("template drive caller: 5"));
    let m = romdyn::input::mbdyn::read_model_text(&text, &path("rod_prestrain.mbd"), &Default::default()).unwrap_or_else(|e| panic!("{e}"));
    let report = run(&m.model, &m.problem, &mut ()).unwrap();
    let asm = Assembler::new(&m.model);
    let z3 = report.final_state.node_frame(&asm.dofs, 2).kin.x[2];
    // At rest where it starts, as in the first test (1e-10 of the 0.25 m scale there).
    assert!((z3 - 3.1).abs() < 2.5e-11, "node 3 z = {z3}, closed form and MBDyn 1.7.3: 3.1");
    // A missing card is an error at the label.
    let e = parse_text(&text.replace("prestrain, reference, 5;", "prestrain, reference, 6;"), &path("rod_prestrain.mbd")).and_then(|d| build(&d)).err().unwrap().to_string();
    assert!(e.contains("template drive caller 6 of dimension 1 is not defined"), "{e}");
}
