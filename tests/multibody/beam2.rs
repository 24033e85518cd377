//! MBDyn's two-node beam `beam2` (docs/src/mbdyn/beams.md): closed forms of the linear cantilever
//! (bending with shear, axial, torsion) and of pure bending at large rotation, MBDyn 1.7.3's
//! numbers on the same files, and the `.act` rows MBDyn writes for it (label and the one
//! evaluation point's force and moment). Its Jacobian is checked against finite
//! differences with every other element in `tests/multibody/multibody_jacobians.rs`.
//!
//! MBDyn 1.7.3 (built by shared/tools/build-mbdyn.sh): `mbdyn -f tests/mbdyn_files/FILE.mbd
//! -o out`, rows of `out.mov` and `out.act` at t = 1 s (the files ask for 16 digits).

use crate::common;
use common::mbdyn::test_file as file;

use common::cli::{listing, romdyn_at, temp_dir};
use romdyn::analysis::run;
use romdyn::dae::Assembler;
use romdyn::input::mbdyn::{read_model_text, SetOverrides};
use romdyn::kinematics::{rotation_vector, Vec3};

/// Final positions and rotation vectors of the nodes `labels` of a file, with `H` set.
fn final_nodes(name: &str, h: Option<f64>, labels: &[u32]) -> Vec<(Vec3, Vec3)> {
    let path = file(name);
    let text = std::fs::read_to_string(&path).unwrap();
    let overrides = h.map(|h| SetOverrides::from([("H".to_string(), h)])).unwrap_or_default();
    let m = read_model_text(&text, &path, &overrides).unwrap_or_else(|e| panic!("{e}"));
    let report = run(&m.model, &m.problem, &mut ()).unwrap_or_else(|e| panic!("{e}"));
    let asm = Assembler::new(&m.model);
    labels
        .iter()
        .map(|l| {
            let slot = m.model.nodes.iter().position(|n| n.label == *l).unwrap();
            let k = report.final_state.node_frame(&asm.dofs, slot).kin;
            (k.x, rotation_vector(&k.r))
        })
        .collect()
}

#[test]
fn a_cantilever_of_beam2_has_the_closed_form_tip_deflections_and_mbdyn_s_numbers() {
    // tests/mbdyn_files/beam2_cantilever.mbd: L = 1.5 m in 3 elements, EA = 1e6 N, GA = 4e5 N,
    // GJ = 2e3 N m², EJ = 5e3 N m², shear stiffness corrected for locking as the input manual
    // says; tip loads P = 1 N, N = 100 N, T = 1 N m.
    let tips = final_nodes("beam2_cantilever.mbd", None, &[4, 14, 24]);
    let (l, ea, ga, gj, ej) = (1.5_f64, 1e6, 4e5, 2e3, 5e3);
    // Timoshenko, P L³/(3 EJ) + P L/GA = 2.2875e-4 m and P L²/(2 EJ) = 2.25e-4 rad: the
    // corrected two-node beam is exact for a linear moment; the load's geometric
    // nonlinearity, (2e-4)² relative, stays below 1e-7 relative.
    let (x, phi) = tips[0];
    let deflection = l.powi(3) / (3.0 * ej) + l / ga;
    assert!((x.y - deflection).abs() < 1e-7 * deflection, "tip y {} against {deflection}", x.y);
    assert!((phi.z - l * l / (2.0 * ej)).abs() < 1e-7 * phi.z, "tip rotation {}", phi.z);
    // Axial N L/EA = 1.5e-4 m and torsion T L/GJ = 7.5e-4 rad: exact (1e-12 relative).
    assert!((tips[1].0.x - l - 100.0 * l / ea).abs() < 1e-12, "tip x {}", tips[1].0.x);
    assert!((tips[2].1.x - l / gj).abs() < 1e-12 * 7.5e-4 + 1e-16, "tip twist {}", tips[2].1.x);
    // MBDyn 1.7.3 on the same file: node 4 y 2.2874999486775902e-04 m, rotation
    // 1.2891550153263667e-02 deg; node 14 x 1.5001500000000001 m; node 24 4.2971834578858850e-02
    // deg. Agreement to 1e-12 m (romdyn measured 2.287499948621e-4, 1e-12 apart: Newton's
    // tolerance 1e-8 N on EA = 1e6 N).
    assert!((x.y - 2.2874999486775902e-04).abs() < 1e-11, "tip y {} against MBDyn's", x.y);
    assert!((phi.z.to_degrees() - 1.2891550153263667e-02).abs() < 1e-9, "tip rotation {} deg against MBDyn's", phi.z.to_degrees());
    assert!((tips[1].0.x - 1.5001500000000001).abs() < 1e-12);
    assert!((tips[2].1.x.to_degrees() - 4.2971834578858850e-02).abs() < 1e-9);
}

#[test]
fn a_tip_couple_bends_four_beam2_into_the_exact_polygon_at_any_load_step() {
    // tests/mbdyn_files/beam2_tip_couple.mbd: M = 1.5 N m, EJ = 1 N m², 4 elements of 0.25 m.
    // Pure bending: no axial or shear force, so each element keeps its chord 0.25 m, its
    // curvature is M/EJ and its two nodes turn by φ = 0.375 rad apart; the chords turn by
    // (k + ½) φ: tip at Σ 0.25 (cos, sin)((k + ½) φ) = (0.6689091635784031,
    // 0.6231534088137909) m, turned by 1.5 rad. romdyn's curvature is exact for any angle
    // per element (below π), measured to 1e-15 m; 1e-10 bounds Newton's stop.
    let phi = 0.375_f64;
    let polygon = (0..4).map(|k| 0.25 * Vec3::new(((k as f64 + 0.5) * phi).cos(), ((k as f64 + 0.5) * phi).sin(), 0.0)).sum::<Vec3>();
    for h in [1.0, 0.1] {
        let (x, r) = final_nodes("beam2_tip_couple.mbd", Some(h), &[5])[0];
        assert!((x - polygon).norm() < 1e-10, "H = {h}: tip {x:?} against {polygon:?}");
        assert!((r.z - 1.5).abs() < 1e-10, "H = {h}: tip rotation {}", r.z);
    }
    // MBDyn 1.7.3, tip x, y [m]: 0.66408072228358794, 0.62595307543082024 (H = 1),
    // 0.66879666471425070, 0.62322796243159206 (H = 0.1), 0.66890873831301589,
    // 0.62315368821288930 (H = 0.01), 0.66890916004225776, 0.62315341113685918 (H = 0.001):
    // beam2.cc accumulates the curvature of each step's rotation increments, so its
    // equilibrium depends on the load steps and tends to the polygon as they get small
    // (4.2e-9 m from it in 1000 steps, against 5.6e-3 m in one).
    let mbdyn_fine = Vec3::new(0.66890916004225776, 0.62315341113685918, 0.0);
    assert!((mbdyn_fine - polygon).norm() < 5e-9, "MBDyn's 1000 steps {mbdyn_fine:?}");
}

#[test]
fn run_writes_mbdyn_s_act_row_for_beam2() {
    // MBDyn's output manual: beam2's `.act` row is the label and the evaluation point's force
    // and moment in the section frame (7 columns). Torsion cantilever C of
    // beam2_cantilever.mbd, MBDyn 1.7.3: `23 0 0 0 1 0 0` (T = 1 N m through every section).
    let dir = temp_dir("beam2-act");
    let (ok, _, err) = romdyn_at(&dir, &["run", file("beam2_cantilever.mbd").to_str().unwrap(), "-o", "c"]);
    assert!(ok, "{err}");
    assert!(listing(&dir).contains(&"c.act".to_string()));
    let body = std::fs::read_to_string(dir.join("c.act")).unwrap();
    let last: Vec<Vec<f64>> = body.lines().rev().take(9).map(|l| l.split_whitespace().map(|c| c.parse().unwrap()).collect()).collect();
    for row in &last {
        assert_eq!(row.len(), 7, "label and 6 values: {row:?}");
    }
    let c = last.iter().find(|r| r[0] == 23.0).unwrap();
    let expected = [23.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0];
    for (a, b) in c.iter().zip(expected) {
        assert!((a - b).abs() < 1e-9, "row {c:?} against MBDyn's {expected:?}");
    }
    // Cantilever A's first element (MBDyn 1.7.3): shear force 1 N, bending moment at x =
    // 0.25 m, P (L − 0.25) = 1.25 N m.
    let a = last.iter().find(|r| r[0] == 1.0).unwrap();
    assert!((a[2] - 1.0).abs() < 1e-6 && (a[6] - 1.25).abs() < 1e-6, "row {a:?}");
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_viscous_law_on_beam2_and_hbeam_are_refused_by_name() {
    let dir = temp_dir("beam2-refused");
    let text = std::fs::read_to_string(file("beam2_tip_couple.mbd")).unwrap();
    let viscous = text.replace("linear elastic generic, diag, EA, EA, EA, EJ, EJ, EJ;", "linear viscoelastic generic, diag, EA, EA, EA, EJ, EJ, EJ, proportional, 0.01;");
    assert_ne!(viscous, text);
    std::fs::write(dir.join("v.mbd"), viscous).unwrap();
    let (ok, _, err) = romdyn_at(&dir, &["run", "v.mbd"]);
    assert!(!ok && err.contains("v.mbd:44:") && err.contains("viscous or viscoelastic section law on a beam2"), "{err}");
    let hbeam = text.replace("beam2: 1, 1, null, 2, null, eye, reference, 1;", "hbeam: 1, 1, null, 2, null, reference, 1;");
    std::fs::write(dir.join("h.mbd"), hbeam).unwrap();
    let (ok, _, err) = romdyn_at(&dir, &["run", "h.mbd"]);
    assert!(!ok && err.contains("h.mbd:44:") && err.contains("'hbeam'") && err.contains("experimental"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}
